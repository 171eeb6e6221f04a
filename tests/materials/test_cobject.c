/*
 * test_cobject.c - what every COBJECT shares: the sub-primitive loop keeps
 * the nearest hit, and cobject_fill sets the book's ray-dependent PATHPOINT
 * fields (r_dist, out, bout, IntersectObj). Uses a toy primitive: planes
 * z = k for k = 0..nprims-1 facing +z, so the answers are exact. And the
 * objects that skip the clear before surface() (COBJECT.surface_fills)
 * fill the same PATHPOINT whatever it held before.
 */
#include "testutil.h"
#include "geometry/box.h"
#include "materials/cobject.h"
#include "core/frame.h"
#include "geomcheck.h"
#include "geometry/parallelogram.h"
#include "core/rng.h"
#include "geometry/xform.h"

#include <stdlib.h>
#include <string.h>

static bool toy_intersect(const COBJECT *obj, int prim, const ray_t *r,
                          real tmin, real tmax, hit_t *hit)
{
    (void)obj;
    if (r->d[Z] == 0)
        return false;
    real t = ((real)prim - r->o[Z]) / r->d[Z];
    if (!(t > tmin && t < tmax))
        return false;
    hit->t = t;
    hit->prim = prim;
    return true;
}

static void toy_surface(const COBJECT *obj, const ray_t *r, const hit_t *hit,
                        PATHPOINT *pp)
{
    (void)obj;
    ray_at(pp->cross_point, r, hit->t);
    pp->cross_point[Z] = (real)hit->prim;
    vec_set(pp->ng, 0, 0, 1);
    vec_copy(pp->n, pp->ng);
    frame_from_normal(pp->u, pp->v, pp->n);
}

static void toy_bounds(const COBJECT *obj, int prim, bbox_t *b)
{
    (void)obj; (void)prim;
    bbox_empty(b);
}

static real toy_area(const COBJECT *obj)
{
    (void)obj;
    return (real)INFINITY;
}

static const cobject_ops toy_ops = { "toy", toy_intersect, toy_surface,
                                     toy_bounds, toy_area, NULL, NULL,
                                     NULL };

START_TEST(nearest_of_many_sub_primitives_is_kept)
{
    COBJECT *o = malloc(sizeof *o);
    cobject_init(o, &toy_ops, NULL);
    o->nprims = 5;
    ray_t r = { { 0, 0, REAL_C(10.0) }, { 0, 0, -2 } }; /* non-unit d */
    hit_t h;
    ck_assert(cobject_intersect(o, &r, 0, (real)INFINITY, &h));
    ck_assert_int_eq(h.prim, 4);
    ck_assert_near(h.t, 3, 0);
    /* the interval is open: nothing in (0, 3); from t = 3 on, plane 3 at
     * t = 3.5 is the nearest; past t = 5 (plane 0) there is none */
    ck_assert(!cobject_intersect(o, &r, 0, 3, &h));
    ck_assert(cobject_intersect(o, &r, 3, 100, &h));
    ck_assert_int_eq(h.prim, 3);
    ck_assert(!cobject_intersect(o, &r, 6, 100, &h));
    cobject_free(o);
    cobject_free(NULL);
}
END_TEST

START_TEST(fill_sets_the_books_ray_fields)
{
    COBJECT *o = malloc(sizeof *o);
    cobject_init(o, &toy_ops, NULL);
    o->nprims = 1;
    ck_assert_int_eq(o->id, -1);
    ck_assert(o->material == NULL && o->light == NULL);
    ray_t r = { { 0, 0, REAL_C(4.0) }, { 0, REAL_C(3.0), REAL_C(-4.0) } };
    hit_t h;
    ck_assert(cobject_intersect(o, &r, 0, (real)INFINITY, &h));
    PATHPOINT pp;
    cobject_fill(o, &r, &h, &pp);
    ck_assert_near(pp.r_dist, 5, 4 * REAL_EPSILON); /* t = 1, |d| = 5 */
    ck_assert_near(pp.out[Y], -0.6, 2 * REAL_EPSILON);
    ck_assert_near(pp.out[Z], 0.8, 2 * REAL_EPSILON);
    ck_assert(pp.bout);
    ck_assert(pp.IntersectObj == o);
    ck_assert(pp.nextpoint == NULL);
    VECTOR3 w = { 0, 0, -1 };
    pathpoint_set_in(&pp, w);
    ck_assert(!pp.bin);
    /* from below the plane, out points down: bout false */
    ray_t r2 = { { 0, 0, -1 }, { 0, 0, 1 } };
    ck_assert(cobject_intersect(o, &r2, 0, (real)INFINITY, &h));
    cobject_fill(o, &r2, &h, &pp);
    ck_assert(!pp.bout);
    cobject_free(o);
}
END_TEST

/* A PATHPOINT filled by cobject_fill() from pp_before, field by field
 * (padding bytes are no field's). */
static bool same_fields(const PATHPOINT *a, const PATHPOINT *b)
{
#define SAME(f) (memcmp(&a->f, &b->f, sizeof a->f) == 0)
    return SAME(u) && SAME(v) && SAME(n) && SAME(cross_point) && SAME(in) &&
           SAME(out) && SAME(bin) && SAME(bout) && SAME(r_dist) &&
           SAME(intensity) && SAME(IntersectObj) && SAME(nextpoint) &&
           SAME(ng) && SAME(p_error) && SAME(st) && SAME(dpds) &&
           SAME(dpdt) && SAME(prim);
#undef SAME
}

static real random_scale(pcg32_t *g)
{
    return ldexp(REAL_C(1.0), (int)pcg32_bounded(g, 17) - 8); /* 2^-8..2^8 */
}

/* One of the objects that promise surface_fills, at a random place and
 * scale: a parallelogram, a box, or either transformed (rotated, scaled
 * unevenly or mirrored, moved). */
static COBJECT *random_filling_object(pcg32_t *g, int kind)
{
    svet_error err;
    real s = random_scale(g);
    VECTOR3 c0, e1, e3, c1, c3;
    geomcheck_random_dir(c0, g);
    geomcheck_random_dir(e1, g);
    geomcheck_random_dir(e3, g);
    vec_scale(c0, c0, s);
    vec_scale(e1, e1, s * (REAL_C(0.1) + pcg32_real(g)));
    vec_scale(e3, e3, s * (REAL_C(0.1) + pcg32_real(g)));
    vec_add(c1, c0, e1);
    vec_add(c3, c0, e3);
    COBJECT *o;
    if (kind % 2 == 0) {
        o = parallelogram_new(c0, c1, c3, &err);
    } else {
        VECTOR3 lo, hi;
        for (int k = 0; k < 3; k++) {
            real a = c0[k], b = c0[k] + s * (REAL_C(0.05) + pcg32_real(g));
            lo[k] = a;
            hi[k] = b;
        }
        o = box_new(lo, hi, &err);
    }
    if (o && kind >= 2) {
        VECTOR3 axis, sc, tr;
        geomcheck_random_dir(axis, g);
        geomcheck_random_dir(tr, g);
        vec_scale(tr, tr, s);
        for (int k = 0; k < 3; k++)
            sc[k] = (REAL_C(0.25) + 2 * pcg32_real(g)) *
                    (pcg32_next(g) % 4 == 0 ? -1 : 1);
        xform_t x = xform_compose(
            xform_compose(xform_scale(sc),
                          xform_rotate(axis, (real)(360 * pcg32_real(g)))),
            xform_translate(tr));
        o = xform_new(o, &x, &err);
    }
    return o;
}

START_TEST(objects_that_skip_the_clear_fill_the_same_pathpoint_whatever_it_held)
{
    /* cobject_fill() clears only in, bin, intensity and nextpoint for an
     * object with surface_fills: its surface() must write every other
     * field and read none before writing it. Filled once into a zeroed
     * PATHPOINT (what the memset before surface() gave) and once into one
     * of random bytes (NaNs, infinities, the previous vertex's values),
     * the fields must agree bit for bit; a surface() that leaves a field
     * (or reads it) differs. */
    pcg32_t g;
    pcg32_seed(&g, 0x5eed, 77);
    long cases = 0;
    for (int obj_i = 0; obj_i < 400; obj_i++) {
        COBJECT *o = random_filling_object(&g, obj_i % 4);
        if (!o)
            continue; /* a degenerate draw */
        ck_assert(o->surface_fills);
        for (int i = 0; i < 500; i++) {
            /* a ray at a sampled point of the surface, from anywhere */
            cobject_sample_t smp;
            real u[2] = { pcg32_real(&g), pcg32_real(&g) };
            o->ops->sample(o, u, &smp);
            ray_t r;
            geomcheck_random_dir(r.o, &g);
            vec_scale(r.o, r.o, random_scale(&g) * 4);
            vec_add(r.o, r.o, smp.p);
            vec_sub(r.d, smp.p, r.o);
            hit_t h;
            if (!cobject_intersect(o, &r, 0, (real)INFINITY, &h))
                continue;
            PATHPOINT zero, junk;
            memset(&zero, 0, sizeof zero);
            unsigned char *bytes = (unsigned char *)&junk;
            uint32_t fill = pcg32_next(&g) % 3;
            for (size_t k = 0; k < sizeof junk; k++)
                bytes[k] = fill == 0   ? 0xff
                           : fill == 1 ? 0x7f
                                       : (unsigned char)pcg32_next(&g);
            cobject_fill(o, &r, &h, &zero);
            cobject_fill(o, &r, &h, &junk);
            ck_assert(same_fields(&zero, &junk));
            cases++;
        }
        cobject_free(o);
    }
    ck_assert(cases > 100000);
    test_report_cases(
        "objects_that_skip_the_clear_fill_the_same_pathpoint_whatever_it_held",
        cases);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("cobject (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, nearest_of_many_sub_primitives_is_kept);
    tcase_add_test(tc, fill_sets_the_books_ray_fields);
    tcase_add_test(tc,
                   objects_that_skip_the_clear_fill_the_same_pathpoint_whatever_it_held);
    suite_add_tcase(s, tc);
    return s;
}
