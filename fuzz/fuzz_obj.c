/*
 * fuzz_obj.c - libFuzzer target for the OBJ reader (obj.h): any bytes must
 * give SVET_OK or an error message naming the file, never a crash, a hang,
 * a leak or undefined behaviour. A file that reads is then used: every
 * triangle's surface, area sampling, the split by material, and brute
 * force, the uniform and the hierarchical grid (accel.h), which must agree
 * exactly on a handful of rays (abort() otherwise, so the fuzzer keeps the
 * input). `make fuzz-obj`; fuzz/README.md has the runs.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "accel/accel.h"
#include "accel/grid.h"
#include "mesh/mesh.h"
#include "mesh/obj.h"
#include "core/rng.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void use_mesh(const obj_t *o)
{
    COBJECT *m = o->mesh;
    const mesh_t *mm = mesh_get(m);
    pcg32_t g;
    pcg32_seed(&g, 1, 2);
    for (int i = 0; i < 8; i++) {
        real u[2] = { pcg32_real(&g), pcg32_real(&g) };
        cobject_sample_t s;
        m->ops->sample(m, u, &s);
    }
    if (mm->slot && o->nmaterials > 0) {
        COBJECT *part;
        svet_error e;
        if (mesh_new_subset(&part, m, mm->slot[0], &e) == SVET_OK)
            cobject_free(part);
    }
    accel_t *a[3] = { NULL, NULL, NULL };
    COBJECT *objs[1] = { m };
    for (int k = 0; k < 3; k++) {
        accel_params_t p;
        accel_params_default(&p);
        p.structures = grid_accels;
        p.kind = (accel_kind)(ACCEL_BRUTE + k);
        svet_error e;
        if (accel_build(&a[k], objs, 1, &p, &e) != SVET_OK)
            abort(); /* only memory could fail here */
    }
    bbox_t b;
    m->ops->bounds(m, -1, &b);
    for (int i = 0; i < 16; i++) {
        ray_t r;
        for (int k = 0; k < 3; k++) {
            real lo = b.min[k], hi = b.max[k];
            r.o[k] = lo + (hi - lo) * (2 * pcg32_real(&g) - REAL_C(0.5));
            real target = lo + (hi - lo) * pcg32_real(&g);
            r.d[k] = target - r.o[k];
        }
        if (i % 4 == 0)
            r.d[i % 3] = 0;
        accel_hit_t h[3];
        bool hit[3];
        for (int k = 0; k < 3; k++) {
            hit[k] = accel_intersect(a[k], &r, 0, (real)INFINITY, &h[k]);
            if (accel_occluded(a[k], &r, 0, (real)INFINITY) != hit[k])
                abort();
        }
        for (int k = 1; k < 3; k++)
            if (hit[k] != hit[0] ||
                (hit[0] && (h[k].hit.t != h[0].hit.t ||
                            h[k].hit.prim != h[0].hit.prim)))
                abort();
        if (hit[0]) {
            PATHPOINT pp;
            cobject_fill(h[0].obj, &r, &h[0].hit, &pp);
        }
    }
    for (int k = 0; k < 3; k++)
        accel_free(a[k]);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* Small limits keep each run short; the code paths are the same. */
    obj_limits_t lim = { 1 << 13, 1 << 13, 1 << 15 };
    obj_t o;
    svet_error e;
    svet_status st = obj_parse("fuzz.obj", (const char *)data, size, &lim, &o,
                               &e);
    if (st == SVET_OK)
        use_mesh(&o);
    else if (strncmp(e.msg, "fuzz.obj", 8) != 0)
        abort(); /* every message names the file */
    obj_free(&o);
    return 0;
}
