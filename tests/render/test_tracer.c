/*
 * test_tracer.c - ch. 5's list of objects (tracer.h) answers every query
 * as the acceleration structures of ch. 7 answer it, field by field and
 * bit for bit: the batched brute force, brute force through
 * primset_test() and the uniform grid, on random scenes of every
 * primitive with duplicated objects (ties at the same t), a mesh, planes
 * without bounds, and rays spawned and aimed as the integrator spawns
 * them; and every shipped scene renders to the same bits with the list
 * as with every part the svet command offers.
 */
#include "testutil.h"
#include "accel/accel.h"
#include "render/allparts.h"
#include "geomcheck.h"
#include "geometry/box.h"
#include "geometry/cone.h"
#include "geometry/cylinder.h"
#include "geometry/disk.h"
#include "geometry/parallelogram.h"
#include "geometry/plane.h"
#include "geometry/sphere.h"
#include "geometry/triangle.h"
#include "geometry/xform.h"
#include "materials/material.h"
#include "mesh/meshgen.h"
#include "render/render.h"
#include "render/scenefile.h"
#include "render/tracer.h"

#include <glob.h>
#include <string.h>

static real uni(pcg32_t *g, real lo, real hi)
{
    return lo + (hi - lo) * pcg32_real(g);
}

static void rand_point(VECTOR3 p, pcg32_t *g, real lo, real hi)
{
    vec_set(p, uni(g, lo, hi), uni(g, lo, hi), uni(g, lo, hi));
}

/* Append o (not NULL) to s with the scene's one material. */
static void add(scene_t *s, COBJECT *o)
{
    ck_assert_ptr_nonnull(o);
    ck_assert_int_eq(scene_add_object(s, o, s->anon_materials[0], NULL),
                     SVET_OK);
}

/* One random object of each kind in turn (k), in [-4, 4]^3. */
static COBJECT *random_object(pcg32_t *g, int k)
{
    svet_error e;
    VECTOR3 a, b, c;
    rand_point(a, g, -4, 4);
    rand_point(b, g, -1, 1);
    rand_point(c, g, -1, 1);
    switch (k % 9) {
    case 0: return sphere_new(a, uni(g, REAL_C(0.2), REAL_C(1.5)), &e);
    case 1: {
        VECTOR3 hi = { a[X] + uni(g, REAL_C(0.1), 2), a[Y] + uni(g, REAL_C(0.1), 2),
                       a[Z] + uni(g, REAL_C(0.1), 2) };
        return box_new(a, hi, &e);
    }
    case 2: vec_add(b, b, a); vec_add(c, c, a); return parallelogram_new(a, b, c, &e);
    case 3: return disk_new(a, b, uni(g, REAL_C(0.2), 2), &e);
    case 4: vec_add(b, b, a); vec_add(c, c, a); return triangle_new(a, b, c, &e);
    case 5: vec_add(b, b, a); return cylinder_new(a, b, uni(g, REAL_C(0.1), 1), true, &e);
    case 6: vec_add(b, b, a); return cone_new(a, b, uni(g, REAL_C(0.1), 1), k % 2 == 0, &e);
    case 7: { /* a transformed box: the batch's culling spheres */
        VECTOR3 lo = { -1, -1, -1 }, hi = { 1, REAL_C(0.5), 2 };
        xform_t x = xform_compose(xform_rotate(b, uni(g, -180, 180)),
                                  xform_translate(a));
        return xform_new(box_new(lo, hi, &e), &x, &e);
    }
    default: { /* a transformed sphere */
        VECTOR3 o = { 0, 0, 0 }, sc = { 1, REAL_C(0.4), REAL_C(1.3) };
        xform_t x = xform_compose(xform_scale(sc), xform_translate(a));
        return xform_new(sphere_new(o, 1, &e), &x, &e);
    }
    }
}

/* A scene of n random objects, a few of them twice (a copy of the same
 * shape: every hit of one is a tie with the other), an unbounded plane
 * unless `bounded`, and a mesh when `mesh`. */
static void random_scene(scene_t *s, pcg32_t *g, int n, bool bounded,
                         bool mesh)
{
    scene_init(s);
    material_params mp;
    material_params_default(&mp);
    material_t *m;
    ck_assert_int_eq(material_new(&mp, &m, NULL), SVET_OK);
    ck_assert_int_eq(scene_add_anon_material(s, m, NULL), SVET_OK);
    if (!bounded) {
        VECTOR3 p = { 0, -5, 0 }, up = { 0, 1, 0 };
        add(s, plane_new(p, up, NULL));
    }
    for (int i = 0; i < n; i++) {
        uint64_t state = g->state, inc = g->inc;
        add(s, random_object(g, i));
        if (i % 4 == 1) { /* the same object again, from the same numbers */
            pcg32_t again = *g;
            again.state = state;
            again.inc = inc;
            add(s, random_object(&again, i));
        }
    }
    if (mesh) {
        COBJECT *o;
        VECTOR3 c = { 1, 0, -1 };
        ck_assert_int_eq(meshgen_uv_sphere(&o, c, REAL_C(1.7), 24, 12, NULL),
                         SVET_OK);
        add(s, o);
    }
}

/* The two tracers answer r over (tmin, tmax) alike, skip given to both
 * (the list ignores it): found, the object, and every field of the hit
 * to the last bit; the shadow query agrees with the nearest hit. */
static bool same_answer(const tracer_t *a, const tracer_t *b, const ray_t *r,
                        real tmin, real tmax, const COBJECT *const skip[2],
                        hit_t *hit, const COBJECT **obj)
{
    hit_t ha, hb;
    const COBJECT *oa = NULL, *ob = NULL;
    memset(&ha, 0x5a, sizeof ha);
    memset(&hb, 0x5a, sizeof hb);
    bool fa = a->intersect(a->ctx, r, tmin, tmax, skip, &ha, &oa);
    bool fb = b->intersect(b->ctx, r, tmin, tmax, skip, &hb, &ob);
    ck_assert_int_eq(fa, fb);
    if (fa) {
        ck_assert_ptr_eq(oa, ob);
        ck_assert_int_eq(ha.prim, hb.prim);
        ck_assert(memcmp(&ha.t, &hb.t, sizeof ha.t) == 0);
        ck_assert(memcmp(ha.b, hb.b, sizeof ha.b) == 0);
        *hit = ha;
        *obj = oa;
    }
    ck_assert_int_eq(a->occluded(a->ctx, r, tmin, tmax, skip), fa);
    ck_assert_int_eq(b->occluded(b->ctx, r, tmin, tmax, skip), fb);
    return fa;
}

/* The structure of kind k over s's objects, as the svet command builds
 * it (generic: brute force through primset_test() alone). */
static accel_t *build(const scene_t *s, accel_kind k, bool generic)
{
    accel_params_t p;
    accel_params_default(&p);
    p.kind = k;
    p.structures = scene_features_all()->accels;
    p.brute_generic = generic;
    accel_t *a = NULL;
    svet_error e;
    ck_assert_msg(accel_build(&a, s->objects, s->nobjects, &p, &e) == SVET_OK,
                  "%s", e.msg);
    return a;
}

/* Compare the list with each structure on n random rays and on the rays
 * spawned from their hits (bounce rays leaving the surface, shadow rays
 * to a point on another object); returns the queries made. */
static long compare_on(const scene_t *s, pcg32_t *g, int n, long *ties)
{
    const tracer_t plain = tracer_brute(s);
    accel_t *acc[3] = { build(s, ACCEL_BRUTE, false),
                        build(s, ACCEL_BRUTE, true),
                        build(s, ACCEL_GRID, false) };
    tracer_t t[3];
    for (int k = 0; k < 3; k++)
        t[k] = accel_tracer(acc[k]);
    long queries = 0;
    for (int i = 0; i < n; i++) {
        ray_t r;
        rand_point(r.o, g, -7, 7);
        VECTOR3 aim;
        rand_point(aim, g, -4, 4);
        VVECTOR3(r.d, aim, r.o);
        if (i % 5 == 0)
            geomcheck_random_dir(r.d, g);
        real tmax = i % 7 == 0 ? uni(g, 0, 2) : (real)INFINITY;
        if (i % 50 == 49) /* a bad ray: every tracer misses */
            r.d[i % 3] = i % 100 == 99 ? (real)NAN : (real)INFINITY;
        for (int k = 0; k < 3; k++) {
            hit_t h;
            const COBJECT *o;
            queries++;
            if (!same_answer(&plain, &t[k], &r, 0, tmax, NULL, &h, &o) ||
                k != 0)
                continue;
            /* the first object has the tie when a copy of it follows */
            for (int j = o->id + 1; j < s->nobjects; j++) {
                const COBJECT *c = s->objects[j];
                hit_t hc = { 0, 0, { 0, 0, 0 } };
                if (c->ops == o->ops && c->nprims == o->nprims &&
                    c->ops->intersect(c, h.prim, &r, 0, tmax, &hc) &&
                    hc.t == h.t)
                    (*ties)++;
            }
            /* rays as the integrator spawns them from the hit */
            PATHPOINT pp;
            cobject_fill(o, &r, &h, &pp);
            VECTOR3 w;
            geomcheck_random_dir(w, g);
            ray_t sr;
            ray_spawn(&sr, pp.cross_point, pp.p_error, pp.ng, w);
            const COBJECT *skip[2] = { o, NULL };
            for (int q = 0; q < 3; q++, queries++)
                same_answer(&plain, &t[q], &sr, 0, (real)INFINITY, skip, &h,
                            &o);
            const COBJECT *l = s->objects[pcg32_bounded(g, (uint32_t)s->nobjects)];
            if (!l->ops->sample || l == pp.IntersectObj)
                continue;
            real u[2] = { pcg32_real(g), pcg32_real(g) };
            cobject_sample_t ls;
            l->ops->sample(l, u, &ls);
            real st = ray_spawn_to(&sr, pp.cross_point, pp.p_error, pp.ng, ls.p,
                                   ls.p_error, ls.n);
            const COBJECT *skip2[2] = { pp.IntersectObj, l };
            for (int q = 0; q < 3; q++, queries++)
                same_answer(&plain, &t[q], &sr, 0, st, skip2, &h, &o);
        }
    }
    for (int k = 0; k < 3; k++)
        accel_free(acc[k]);
    return queries;
}

START_TEST(the_list_answers_as_every_structure_bit_for_bit)
{
    pcg32_t g;
    pcg32_seed(&g, 2024, 15);
    long queries = 0, ties = 0;
    for (int sc = 0; sc < 12; sc++) {
        scene_t s;
        random_scene(&s, &g, 6 + (int)pcg32_bounded(&g, 30), sc % 2 == 0,
                     sc % 4 == 3);
        /* the batch is what the svet command's brute force is, except
         * over a mesh, which it leaves to primset_test() */
        accel_t *a = build(&s, ACCEL_BRUTE, false);
#ifdef SVET_SIMD
        ck_assert((accel_tracer(a).intersect == accel_tracer_intersect) ==
                  (sc % 4 == 3));
#else
        /* no batch in the plain build: primset_test() is brute force */
        ck_assert(accel_tracer(a).intersect == accel_tracer_intersect);
#endif
        accel_free(a);
        queries += compare_on(&s, &g, 1500, &ties);
        scene_free(&s);
    }
    ck_assert_msg(ties > 100, "%ld ties", ties);
    test_report_cases("the_list_answers_as_every_structure_bit_for_bit "
                      "(queries)", queries);
}
END_TEST

START_TEST(ties_go_to_the_first_object)
{
    scene_t s;
    pcg32_t g;
    pcg32_seed(&g, 5, 1);
    random_scene(&s, &g, 0, true, false);
    VECTOR3 c = { 0, 0, 0 }, c1 = { 1, 0, 0 }, c3 = { 0, 1, 0 };
    add(&s, parallelogram_new(c, c1, c3, NULL));
    add(&s, parallelogram_new(c, c1, c3, NULL));
    add(&s, sphere_new(c, 1, NULL));
    add(&s, sphere_new(c, 1, NULL));
    tracer_t t = tracer_brute(&s);
    ray_t r = { { REAL_C(0.25), REAL_C(0.5), 3 }, { 0, 0, -1 } };
    hit_t h;
    const COBJECT *o;
    ck_assert(t.intersect(t.ctx, &r, 0, (real)INFINITY, NULL, &h, &o));
    ck_assert_ptr_eq(o, s.objects[2]); /* the first sphere, at t = 2 */
    ck_assert(t.intersect(t.ctx, &r, REAL_C(2.5), (real)INFINITY, NULL, &h,
                          &o));
    ck_assert_ptr_eq(o, s.objects[0]); /* the first parallelogram */
    ck_assert(memcmp(&h.t, &(real){ 3 }, sizeof h.t) == 0);
    scene_free(&s);
}
END_TEST

START_TEST(bad_rays_and_empty_intervals_are_misses)
{
    scene_t s;
    pcg32_t g;
    pcg32_seed(&g, 6, 1);
    random_scene(&s, &g, 8, false, false);
    tracer_t t = tracer_brute(&s);
    hit_t h;
    const COBJECT *o = NULL;
    ray_t r = { { 0, 0, 0 }, { 0, 0, 0 } };
    ck_assert(!t.intersect(t.ctx, &r, 0, (real)INFINITY, NULL, &h, &o));
    r.d[Y] = (real)NAN;
    ck_assert(!t.occluded(t.ctx, &r, 0, (real)INFINITY, NULL));
    r.d[Y] = -1;
    ck_assert(t.intersect(t.ctx, &r, 0, (real)INFINITY, NULL, &h, &o));
    ck_assert(!t.intersect(t.ctx, &r, 1, 1, NULL, &h, &o));
    ck_assert(!t.occluded(t.ctx, &r, 0, (real)NAN, NULL));
    ck_assert(tracer_ray_ok(&r, 0, 1) && !tracer_ray_ok(&r, 1, 0));
    scene_free(&s);
}
END_TEST

/* Every shipped scene, read as ch. 5 reads it (no parts: the list) and as
 * the svet command does (every part: the batched brute force), renders
 * to the same bits, at one thread and at two. */
START_TEST(every_shipped_scene_renders_the_same_with_the_list)
{
    glob_t gl;
    ck_assert_int_eq(glob("scenes/*.scn", 0, NULL, &gl), 0);
    ck_assert(gl.gl_pathc >= 8);
    long pixels = 0;
    for (size_t i = 0; i < gl.gl_pathc; i++) {
        scene_t s[2];
        render_t r[2];
        svet_error e;
        /* a scene rendered by a part's method (caustic.scn's photon
         * maps, textures.scn's textures) is read with the parts but without the acceleration layer
         * in place of nothing */
        scene_features_t parts = { 0 };
        parts.parts = scene_features_all()->parts;
        for (int k = 0; k < 2; k++) {
            const scene_features_t *f = k ? scene_features_all() : NULL;
            svet_status st = scenefile_read_with(&s[k], gl.gl_pathv[i], f, &e);
            if (k == 0 && st == SVET_ERR_UNSUPPORTED)
                st = scenefile_read_with(&s[k], gl.gl_pathv[i], &parts, &e);
            ck_assert_msg(st == SVET_OK, "%s", e.msg);
            ck_assert_int_eq(scenefile_override(&s[k], "resolution=20x14", &e),
                             SVET_OK);
            ck_assert_int_eq(render_init(&r[k], &s[k], &e), SVET_OK);
            render_pass(&r[k], 3, k + 1, NULL, NULL);
        }
        ck_assert_msg(strncmp(r[0].accel_choice, "brute (the list", 15) == 0,
                      "%s", r[0].accel_choice);
        ck_assert_msg(strncmp(r[1].accel_choice, "brute (auto", 11) == 0,
                      "%s", r[1].accel_choice);
        size_t n = (size_t)r[0].camera.width * (size_t)r[0].camera.height;
        ck_assert_msg(memcmp(r[0].acc.sum, r[1].acc.sum, 3 * n * sizeof(image_fixed_t)) ==
                              0 &&
                          memcmp(r[0].sum2, r[1].sum2, 3 * n * sizeof(image_fixed_t)) == 0 &&
                          memcmp(r[0].acc.count, r[1].acc.count,
                                 n * sizeof(uint64_t)) == 0,
                      "%s: the images differ", gl.gl_pathv[i]);
        ck_assert(r[0].stats.rays == r[1].stats.rays && r[0].stats.rays > 0);
        pixels += (long)n;
        for (int k = 0; k < 2; k++) {
            render_free(&r[k]);
            scene_free(&s[k]);
        }
    }
    globfree(&gl);
    test_report_cases("every_shipped_scene_renders_the_same_with_the_list "
                      "(pixels)", pixels);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("tracer");
    TCase *tc = tcase_create("tracer");
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, the_list_answers_as_every_structure_bit_for_bit);
    tcase_add_test(tc, ties_go_to_the_first_object);
    tcase_add_test(tc, bad_rays_and_empty_intervals_are_misses);
    tcase_add_test(tc, every_shipped_scene_renders_the_same_with_the_list);
    suite_add_tcase(s, tc);
    return s;
}
