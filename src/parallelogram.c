/*
 * parallelogram.c - the parallelogram of app. D as two triangles under the
 * watertight test of Woop, Benthin, Wald 2013 (a departure from the book's
 * plane-then-inside test, which leaks along shared edges), with points
 * rebuilt from barycentrics (pbrt-v3 sec. 3.9.5).
 * Tests: tests/test_parallelogram.c; vectors: tests/vectors/parallelogram.csv
 */
#include "parallelogram.h"
#include "shape.h"
#include "triangle.h"

typedef struct {
    VECTOR3 c[4];   /* corners c0 c1 c2 c3 */
    VECTOR3 e1, e2; /* c1 - c0, c3 - c0 */
    VECTOR3 n;      /* unit e1 x e2 */
    real area;
} para_shape;

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

static real clamp01(real x)
{
    return fmin(fmax(x, REAL_C(0.0)), REAL_C(1.0));
}

static bool para_intersect(const COBJECT *obj, int prim, const ray_t *r,
                           real tmin, real tmax, hit_t *hit)
{
    const para_shape *sh = obj->shape;
    real t, b[3], st[2];
    bool any = false;
    triangle_ray_t pr;
    triangle_ray_prepare(&pr, r);
    /* triangle A: p = c0 + (b1 + b2) e1 + b2 e2 */
    if (triangle_intersect_prepared(sh->c[0], sh->c[1], sh->c[2], &pr, tmin,
                                    tmax, &t, b)) {
        any = true;
        tmax = t;
        st[0] = b[1] + b[2];
        st[1] = b[2];
    }
    /* triangle B: p = c0 + b1 e1 + (b1 + b2) e2; only if nearer */
    if (triangle_intersect_prepared(sh->c[0], sh->c[2], sh->c[3], &pr, tmin,
                                    tmax, &t, b)) {
        any = true;
        st[0] = b[1];
        st[1] = b[1] + b[2];
    }
    if (!any)
        return false;
    hit->t = t;
    hit->prim = prim;
    hit->b[0] = clamp01(st[0]);
    hit->b[1] = clamp01(st[1]);
    hit->b[2] = 0;
    return true;
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
    shape_frame(pp->u, pp->v, pp->n, sh->e1);
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
    para_sample, NULL
};

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
    if (triangle_is_degenerate(c0, c1, c3) || !shape_unit_cross(n, e1, e2)) {
        svet_error_set(err, SVET_ERR_RANGE, "parallelogram: degenerate, the "
                       "edges c1 - c0 = (%g, %g, %g) and c3 - c0 = (%g, %g, "
                       "%g) are parallel or zero", (double)e1[X],
                       (double)e1[Y], (double)e1[Z], (double)e2[X],
                       (double)e2[Y], (double)e2[Z]);
        return NULL;
    }
    real area = shape_cross_length(e1, e2);
    if (!isfinite(area) || !isfinite(1 / area)) {
        svet_error_set(err, SVET_ERR_RANGE, "parallelogram: area %g is out "
                       "of the range of %s", (double)area, REAL_NAME);
        return NULL;
    }
    COBJECT *obj = shape_alloc(&parallelogram_ops, sizeof(para_shape), err);
    if (!obj)
        return NULL;
    para_shape *sh = obj->shape;
    vec_copy(sh->c[0], c0);
    vec_copy(sh->c[1], c1);
    vec_copy(sh->c[2], c2);
    vec_copy(sh->c[3], c3);
    vec_copy(sh->e1, e1);
    vec_copy(sh->e2, e2);
    vec_copy(sh->n, n);
    sh->area = area;
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
