/*
 * parallelogram.c - the parallelogram of app. D as two triangles under the
 * watertight test of Woop, Benthin, Wald 2013 (a departure from the book's
 * plane-then-inside test, which leaks along shared edges), with points
 * rebuilt from barycentrics (pbrt-v3 sec. 3.9.5). Its speed layer, early
 * rejections before the test and the two triangles' shared corners
 * sheared once (SSE), is fast/parallelogram_cull.c (SIMD=on builds).
 * Tests: tests/geometry/test_parallelogram.c; vectors: tests/vectors/parallelogram.csv
 */
#include "geometry/parallelogram.h"

#include <stdlib.h>

#include "geometry/shape.h"
#include "parallelogram_shape.h"

/* The surface point at (s, t): in triangle A = (c0, c1, c2) where s >= t,
 * with barycentrics (1 - s, s - t, t), else in B = (c0, c2, c3) with
 * (1 - t, s, t - s). Rebuilt on the triangle, so that it lies on the very
 * surface the intersection test sees, with triangle_point's bound. */
static void point_at(const para_shape *sh, real s, real t, VECTOR3 p,
                     VECTOR3 p_error)
{
    if (s >= t) {
        real b[3] = { 1 - s, s - t, t };
        triangle_point(p, p_error, sh->c[0], sh->c[1], sh->c[2], b);
    } else {
        real b[3] = { 1 - t, s, t - s };
        triangle_point(p, p_error, sh->c[0], sh->c[2], sh->c[3], b);
    }
}

/* The intersection test: triangle A, then triangle B if nearer, each by
 * the watertight test (triangle.c) on the ray prepared once. */
bool parallelogram_two_triangles(const para_shape *sh,
                                 const triangle_ray_t *pr, real tmin,
                                 real tmax, real *t, real st[2])
{
    real b[3];
    bool any = false;
    if (triangle_intersect_prepared(sh->c[0], sh->c[1], sh->c[2], pr, tmin,
                                    tmax, t, b)) {
        any = true;
        tmax = *t; /* B only if nearer */
        parallelogram_st_of(0, b, st);
    }
    if (triangle_intersect_prepared(sh->c[0], sh->c[2], sh->c[3], pr, tmin,
                                    tmax, t, b)) {
        any = true;
        parallelogram_st_of(1, b, st);
    }
    return any;
}

bool parallelogram_prepared_plain(const COBJECT *obj, int prim,
                                  const triangle_ray_t *pr, real tmin,
                                  real tmax, hit_t *hit)
{
    real t, st[2];
    if (!parallelogram_two_triangles(obj->shape, pr, tmin, tmax, &t, st))
        return false;
    parallelogram_set_hit(hit, prim, t, st);
    return true;
}

bool parallelogram_intersect_plain(const COBJECT *obj, int prim,
                                   const ray_t *r, real tmin, real tmax,
                                   hit_t *hit)
{
    triangle_ray_t pr;
    triangle_ray_prepare(&pr, r);
    return parallelogram_prepared_plain(obj, prim, &pr, tmin, tmax, hit);
}

static bool para_intersect(const COBJECT *obj, int prim, const ray_t *r,
                           real tmin, real tmax, hit_t *hit)
{
#ifdef SVET_SIMD
    return parallelogram_cull_intersect(obj->shape, prim, r, tmin, tmax, hit);
#else
    return parallelogram_intersect_plain(obj, prim, r, tmin, tmax, hit);
#endif
}

bool parallelogram_intersect_prepared(const COBJECT *obj, int prim,
                                      const triangle_ray_t *pr, real tmin,
                                      real tmax, hit_t *hit)
{
#ifdef SVET_SIMD
    return parallelogram_cull_prepared(obj->shape, prim, pr, tmin, tmax, hit);
#else
    return parallelogram_prepared_plain(obj, prim, pr, tmin, tmax, hit);
#endif
}

static void para_surface(const COBJECT *obj, const ray_t *r, const hit_t *hit,
                         PATHPOINT *pp)
{
    (void)r;
    const para_shape *sh = obj->shape;
    point_at(sh, hit->b[0], hit->b[1], pp->cross_point, pp->p_error);
    pp->st[0] = hit->b[0];
    pp->st[1] = hit->b[1];
    vec_copy(pp->dpds, sh->e1);
    vec_copy(pp->dpdt, sh->e2);
    vec_copy(pp->ng, sh->n);
    vec_copy(pp->n, sh->n);
    vec_copy(pp->u, sh->u);
    vec_copy(pp->v, sh->v);
}

static void para_bounds(const COBJECT *obj, int prim, bbox_t *b)
{
    (void)prim;
    const para_shape *sh = obj->shape;
    bbox_empty(b);
    for (int i = 0; i < 4; i++)
        bbox_add_point(b, sh->c[i]);
}

static real para_area(const COBJECT *obj)
{
    return ((const para_shape *)obj->shape)->area;
}

static void para_sample(const COBJECT *obj, const real u[2],
                        cobject_sample_t *smp)
{
    /* (s, t) = u is uniform by area: the map is affine */
    const para_shape *sh = obj->shape;
    point_at(sh, u[0], u[1], smp->p, smp->p_error);
    vec_copy(smp->n, sh->n);
    smp->pdf = 1 / sh->area;
}

static const cobject_ops parallelogram_ops = {
    "parallelogram", para_intersect, para_surface, para_bounds, para_area,
    para_sample, NULL, NULL
};

bool parallelogram_is(const COBJECT *obj)
{
    return obj && obj->ops == &parallelogram_ops;
}

#ifndef SVET_SIMD
/* Without the speed layer there is no batch: brute force (accel.c) then
 * tests each parallelogram through its intersect(). */
parallelogram_batch_t *parallelogram_batch_new(const COBJECT *const *objs,
                                               int n)
{
    (void)objs;
    (void)n;
    return NULL;
}

void parallelogram_batch_free(parallelogram_batch_t *b)
{
    (void)b;
}

uint64_t parallelogram_batch_cull(const parallelogram_batch_t *b,
                                  const ray_t *r, real tmin, real tmax,
                                  uint64_t want)
{
    (void)b, (void)r, (void)tmin, (void)tmax;
    return want;
}

uint64_t parallelogram_batch_cull_plain(const parallelogram_batch_t *b,
                                        const ray_t *r, real tmin, real tmax,
                                        uint64_t want)
{
    return parallelogram_batch_cull(b, r, tmin, tmax, want);
}
#endif

/* The checks both constructors share, and the object. */
static COBJECT *make(const VECTOR3 c0, const VECTOR3 c1, const VECTOR3 c2,
                     const VECTOR3 c3, svet_error *err)
{
    VECTOR3 e1, e2, n;
    vec_sub(e1, c1, c0);
    vec_sub(e2, c3, c0);
    if (!vec_is_finite(e1) || !vec_is_finite(e2) || !vec_is_finite(c2)) {
        svet_error_set(err, SVET_ERR_RANGE, "parallelogram: edges exceed "
                       "the largest %s", REAL_NAME);
        return NULL;
    }
    /* The test of (c0, c1, c3) on the edges scaled to near 1 by powers
     * of 2 (exact, shape.h): the same answer where the edges' products
     * are normal numbers, and no "parallel" for perpendicular edges
     * whose products overflow (beyond sqrt(REAL_MAX)) or underflow. */
    VECTOR3 origin = { 0, 0, 0 }, s1, s2;
    int x1 = shape_scale_exponent(s1, e1), x2 = shape_scale_exponent(s2, e2);
    if (triangle_is_degenerate(origin, s1, s2) ||
        !shape_unit_cross(n, e1, e2)) {
        svet_error_set(err, SVET_ERR_RANGE, "parallelogram: degenerate, the "
                       "edges c1 - c0 = (%g, %g, %g) and c3 - c0 = (%g, %g, "
                       "%g) are parallel or zero", (double)e1[X],
                       (double)e1[Y], (double)e1[Z], (double)e2[X],
                       (double)e2[Y], (double)e2[Z]);
        return NULL;
    }
    real area = shape_cross_length(e1, e2);
    if (!isfinite(area) || !isfinite(1 / area)) {
        /* told in double, where it is a number */
        double a = ldexp((double)shape_cross_length(s1, s2), x1 + x2);
        svet_error_set(err, SVET_ERR_RANGE, "parallelogram: area %g is out "
                       "of the range of %s", a, REAL_NAME);
        return NULL;
    }
    COBJECT *obj = shape_alloc(&parallelogram_ops, sizeof(para_shape), err);
    if (!obj)
        return NULL;
    obj->surface_fills = true; /* para_surface() writes every field */
    para_shape *sh = obj->shape;
    vec_copy(sh->c[0], c0);
    vec_copy(sh->c[1], c1);
    vec_copy(sh->c[2], c2);
    vec_copy(sh->c[3], c3);
    vec_copy(sh->e1, e1);
    vec_copy(sh->e2, e2);
    vec_copy(sh->n, n);
    shape_frame(sh->u, sh->v, sh->n, sh->e1);
    sh->area = area;
#ifdef SVET_SIMD
    parallelogram_cull_init(sh);
#endif
    return obj;
}

static bool check_corners(const VECTOR3 c0, const VECTOR3 c1,
                          const VECTOR3 c3, svet_error *err)
{
    return shape_check_finite("parallelogram", "c0", c0, err) == SVET_OK &&
           shape_check_finite("parallelogram", "c1", c1, err) == SVET_OK &&
           shape_check_finite("parallelogram", "c3", c3, err) == SVET_OK;
}

COBJECT *parallelogram_new(const VECTOR3 c0, const VECTOR3 c1,
                           const VECTOR3 c3, svet_error *err)
{
    if (!check_corners(c0, c1, c3, err))
        return NULL;
    VECTOR3 e2, c2;
    vec_sub(e2, c3, c0);
    vec_add(c2, c1, e2);
    return make(c0, c1, c2, c3, err);
}

COBJECT *parallelogram_new4(const VECTOR3 c0, const VECTOR3 c1,
                            const VECTOR3 c2, const VECTOR3 c3,
                            svet_error *err)
{
    if (!check_corners(c0, c1, c3, err) ||
        shape_check_finite("parallelogram", "c2", c2, err))
        return NULL;
    /* Each corner given in decimal is its exact value rounded once, u
     * relative; c1 + c3 - c0 costs two roundings more and the difference
     * one: an exact parallelogram leaves a mismatch below about
     * 4u (|c0| + |c1| + |c2| + |c3|) per axis; 16u allows for corners
     * computed by a few operations before they were written. */
    VECTOR3 want, miss, e1, e2, n;
    real worst = 0, worst_tol = 0;
    bool bad = false;
    for (int k = 0; k < 3; k++) {
        want[k] = c1[k] + c3[k] - c0[k];
        miss[k] = c2[k] - want[k];
        real tol = 16 * REAL_UNIT_ROUNDOFF *
                   (fabs(c0[k]) + fabs(c1[k]) + fabs(c2[k]) + fabs(c3[k]));
        if (!(fabs(miss[k]) <= tol))
            bad = true;
        if (fabs(miss[k]) > worst) {
            worst = fabs(miss[k]);
            worst_tol = tol;
        }
    }
    if (bad) {
        vec_sub(e1, c1, c0);
        vec_sub(e2, c3, c0);
        real out = shape_unit_cross(n, e1, e2) ? fabs(SVECTOR3(miss, n)) : 0;
        svet_error_set(err, SVET_ERR_RANGE, "parallelogram: c2 (%g, %g, %g) "
                       "is not c1 + c3 - c0 = (%g, %g, %g): off by (%g, %g, "
                       "%g), %g of it out of the plane (tolerance %g)",
                       (double)c2[X], (double)c2[Y], (double)c2[Z],
                       (double)want[X], (double)want[Y], (double)want[Z],
                       (double)miss[X], (double)miss[Y], (double)miss[Z],
                       (double)out, (double)worst_tol);
        return NULL;
    }
    return make(c0, c1, c2, c3, err);
}
