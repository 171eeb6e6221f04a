/*
 * test_cobject.c - what every COBJECT shares: the sub-primitive loop keeps
 * the nearest hit, and cobject_fill sets the book's ray-dependent PATHPOINT
 * fields (r_dist, out, bout, IntersectObj). Uses a toy primitive: planes
 * z = k for k = 0..nprims-1 facing +z, so the answers are exact.
 */
#include "testutil.h"
#include "cobject.h"
#include "frame.h"

#include <stdlib.h>

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
                                     toy_bounds, toy_area, NULL, NULL };

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

Suite *test_suite(void)
{
    Suite *s = suite_create("cobject (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, nearest_of_many_sub_primitives_is_kept);
    tcase_add_test(tc, fill_sets_the_books_ray_fields);
    suite_add_tcase(s, tc);
    return s;
}
