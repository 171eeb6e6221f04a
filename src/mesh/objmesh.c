/*
 * objmesh.c - an OBJ file as the objects of a `mesh` statement (ch. 7; see
 * objmesh.h): read, moved, split by usemtl slot.
 * Tests: tests/mesh/test_objmesh.c
 */
#include "mesh/objmesh.h"

#include <stdlib.h>
#include <string.h>
#include "mesh/mesh.h"
#include "mesh/obj.h"

/* Does x mirror (det M < 0)? */
static bool mirrors(const xform_t *x)
{
    const real (*m)[4] = x->m;
    double det = (double)m[0][0] * ((double)m[1][1] * (double)m[2][2] -
                                    (double)m[1][2] * (double)m[2][1]) -
                 (double)m[0][1] * ((double)m[1][0] * (double)m[2][2] -
                                    (double)m[1][2] * (double)m[2][0]) +
                 (double)m[0][2] * ((double)m[1][0] * (double)m[2][1] -
                                    (double)m[1][1] * (double)m[2][0]);
    return det < 0;
}

/* A copy of the mesh src moved by x: positions by x, normals by its
 * inverse transpose; a mirroring transform (det < 0) also reverses each
 * triangle's winding, so that ng, which follows the winding, keeps
 * pointing out of a closed mesh. */
static svet_status mesh_transformed(COBJECT **out, const COBJECT *src,
                                    const xform_t *x, svet_error *err)
{
    const mesh_t *s = mesh_get(src);
    mesh_t m;
    memset(&m, 0, sizeof m);
    m.nverts = s->nverts;
    m.ntris = s->ntris;
    size_t nv = (size_t)s->nverts, nt = (size_t)s->ntris;
    m.p = malloc(nv * sizeof *m.p);
    m.tri = malloc(nt * sizeof *m.tri);
    if (s->n)
        m.n = malloc(nv * sizeof *m.n);
    if (s->st)
        m.st = malloc(nv * sizeof *m.st);
    if (s->slot)
        m.slot = malloc(nt * sizeof *m.slot);
    if (!m.p || !m.tri || (s->n && !m.n) || (s->st && !m.st) ||
        (s->slot && !m.slot)) {
        free(m.p); free(m.tri); free(m.n); free(m.st); free(m.slot);
        return svet_error_set(err, SVET_ERR_NOMEM, "out of memory");
    }
    bool mirror = mirrors(x);
    for (size_t i = 0; i < nv; i++) {
        xform_point(x, m.p[i], s->p[i]);
        if (m.n) {
            /* A zero normal means "none here" (mesh.h) and stays zero. */
            xform_normal(x, m.n[i], s->n[i]);
            vec_normalize(m.n[i], m.n[i]);
        }
        if (m.st) {
            m.st[i][0] = s->st[i][0];
            m.st[i][1] = s->st[i][1];
        }
    }
    for (size_t i = 0; i < nt; i++) {
        m.tri[i][0] = s->tri[i][0];
        m.tri[i][1] = s->tri[i][mirror ? 2 : 1];
        m.tri[i][2] = s->tri[i][mirror ? 1 : 2];
        if (m.slot)
            m.slot[i] = s->slot[i];
    }
    return mesh_new(out, &m, err);
}

/* A copy of the usemtl name of slot k (0: none, NULL), in *name; false
 * when memory runs out. */
static bool slot_name(const obj_t *o, int k, char **name)
{
    *name = NULL;
    if (k == 0)
        return true;
    size_t n = strlen(o->materials[k - 1]) + 1;
    *name = malloc(n);
    if (*name)
        memcpy(*name, o->materials[k - 1], n);
    return *name != NULL;
}

/* Split mesh (taken: freed or handed on) by the slots of o into parts:
 * one per used slot in slot order (slot -1 first), the whole mesh when
 * only one is used. */
static svet_status split(const obj_t *o, COBJECT *mesh,
                         scene_mesh_part_t **parts, int *nparts,
                         svet_error *err)
{
    const mesh_t *mm = mesh_get(mesh);
    int nslots = o->nmaterials + 1; /* slot -1 is index 0 */
    char *used = calloc((size_t)nslots, 1);
    scene_mesh_part_t *p = calloc((size_t)nslots, sizeof *p);
    int n = 0, nused = 0;
    svet_status st = SVET_OK;
    if (!used || !p) {
        st = svet_error_set(err, SVET_ERR_NOMEM, "out of memory");
        nslots = 0;
    } else if (!mm->slot) {
        used[0] = 1;
    } else {
        for (int i = 0; i < mm->ntris; i++)
            used[mm->slot[i] + 1] = 1;
    }
    for (int k = 0; k < nslots; k++)
        nused += used[k];
    for (int k = 0; k < nslots && !st; k++) {
        if (!used[k])
            continue;
        if (!slot_name(o, k, &p[n].material)) {
            st = svet_error_set(err, SVET_ERR_NOMEM, "out of memory");
        } else if (nused == 1) {
            p[n++].obj = mesh;
            mesh = NULL; /* the part has it now */
        } else {
            st = mesh_new_subset(&p[n].obj, mesh, (int32_t)(k - 1), err);
            n++;
        }
    }
    free(used);
    cobject_free(mesh);
    if (st) {
        scene_mesh_parts_free(p, n);
        return st;
    }
    *parts = p;
    *nparts = n;
    return SVET_OK;
}

/* o's warnings into w: the kept ones, and the count of the rest. */
static void hand_on_warnings(const obj_t *o, scene_warnings_t *w)
{
    if (!w)
        return;
    long kept = o->nwarnings < OBJ_MAX_WARNINGS ? o->nwarnings
                                                : OBJ_MAX_WARNINGS;
    for (long i = 0; i < kept; i++)
        scene_warn(w, "%s", o->warnings[i]);
    w->n += o->nwarnings - kept;
}

svet_status objmesh_load(const char *path, const xform_t *x,
                         scene_mesh_part_t **parts, int *nparts,
                         scene_warnings_t *warnings, svet_error *err)
{
    *parts = NULL;
    *nparts = 0;
    obj_t o;
    svet_status st = obj_read(path, NULL, &o, err);
    if (st)
        return st;
    hand_on_warnings(&o, warnings);
    COBJECT *mesh = o.mesh;
    o.mesh = NULL;
    if (x) {
        COBJECT *moved = NULL;
        svet_error e;
        st = mesh_transformed(&moved, mesh, x, &e);
        cobject_free(mesh);
        mesh = moved;
        if (st)
            st = svet_error_set(err, st, "%s: %s", path, e.msg);
    }
    if (!st)
        st = split(&o, mesh, parts, nparts, err);
    obj_free(&o);
    return st;
}
