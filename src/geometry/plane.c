/*
 * plane.c - the infinite plane of app. D: t = (p0 - o) . n / (d . n), with
 * a bound on the rounding error of the numerator so that a ray starting on
 * the plane (to within that bound) never hits it (after pbrt-v3 sec.
 * 3.9.6), and hit points rebuilt from their plane coordinates.
 * Tests: tests/geometry/test_plane.c; vectors: tests/vectors/plane.csv
 */
#include "geometry/plane.h"
#include "core/frame.h"
#include "geometry/shape.h"

typedef struct {
    VECTOR3 p0;   /* the point given */
    VECTOR3 n;    /* unit normal */
    VECTOR3 u, v; /* frame_from_normal(n) */
    real perp;    /* bound on |u . n| and |v . n|, exactly evaluated */
} plane_shape;

static bool plane_intersect(const COBJECT *obj, int prim, const ray_t *r,
                            real tmin, real tmax, hit_t *hit)
{
    const plane_shape *s = obj->shape;
    /* app. D: (o + t d - p0) . n = 0, so t = (p0 - o) . n / (d . n) */
    real den = SVECTOR3(r->d, s->n);
    if (den == 0 || !isfinite(den))
        return false; /* parallel to the plane, or lying in it */
    VECTOR3 w;
    vec_sub(w, s->p0, r->o);
    real num = SVECTOR3(w, s->n);
    /* Which side is the origin on? Each w_k carries one rounding and the
     * three-term dot product gamma(3) sum|w_k n_k| (Higham 2002, sec. 3.1):
     * |num - exact| <= gamma(4) sum|w_k n_k|, and gamma(5) leaves room for
     * |w_k| being itself rounded. Within that bound the origin may lie on
     * either side and t = 0 is possible: no hit, as pbrt-v3's t-error test
     * does for triangles (sec. 3.9.6). Only for tmin >= 0. */
    if (tmin >= 0) {
        real bound = ray_gamma(5) * (fabs(w[X] * s->n[X]) +
                                     fabs(w[Y] * s->n[Y]) +
                                     fabs(w[Z] * s->n[Z]));
        if (!(fabs(num) > bound))
            return false;
    }
    real t = num / den;
    if (!(t > tmin && t < tmax))
        return false;
    hit->t = t;
    hit->prim = prim;
    return true;
}

static void plane_surface(const COBJECT *obj, const ray_t *r,
                          const hit_t *hit, PATHPOINT *pp)
{
    const plane_shape *s = obj->shape;
    /* Plane coordinates of o + t d, then the point rebuilt from them,
     * p = p0 + s u + t v: on the plane up to the rounding below, however
     * far o + t d was off it (pbrt-v3 sec. 3.9.4's re-projection). */
    VECTOR3 q, w;
    ray_at(q, r, hit->t);
    vec_sub(w, q, s->p0);
    real a = SVECTOR3(w, s->u), b = SVECTOR3(w, s->v);
    if (!isfinite(a) || !isfinite(b)) {
        a = 0;
        b = 0;
    }
    /* Error: each p_k = p0_k + a u_k + b v_k costs two products and two
     * sums, gamma(3) (|p0_k| + |a u_k| + |b v_k|); and the exact point
     * p0 + a u + b v lies (|a| + |b|) perp off the plane since u, v are
     * perpendicular to n only to rounding. */
    real g3 = ray_gamma(3);
    real off = fabs(a) * s->perp + fabs(b) * s->perp;
    for (int k = 0; k < 3; k++) {
        real au = a * s->u[k], bv = b * s->v[k];
        pp->cross_point[k] = s->p0[k] + au + bv;
        /* summed term by term, scaled first: no overflow near REAL_MAX */
        pp->p_error[k] = g3 * fabs(s->p0[k]) + g3 * fabs(au) +
                         g3 * fabs(bv) + off;
    }
    vec_copy(pp->ng, s->n);
    vec_copy(pp->n, s->n);
    vec_copy(pp->u, s->u);
    vec_copy(pp->v, s->v);
    vec_copy(pp->dpds, s->u);
    vec_copy(pp->dpdt, s->v);
    pp->st[0] = a - floor(a);
    pp->st[1] = b - floor(b);
}

static void plane_bounds(const COBJECT *obj, int prim, bbox_t *b)
{
    (void)prim;
    const plane_shape *s = obj->shape;
    for (int k = 0; k < 3; k++) {
        /* the plane is k = p0_k exactly when n is the k axis */
        bool flat = fabs(s->n[k]) == 1;
        b->min[k] = flat ? s->p0[k] : -REAL_MAX;
        b->max[k] = flat ? s->p0[k] : REAL_MAX;
    }
}

static real plane_area(const COBJECT *obj)
{
    (void)obj;
    return (real)INFINITY;
}

static void plane_sample(const COBJECT *obj, const real u[2],
                         cobject_sample_t *smp)
{
    (void)u;
    const plane_shape *s = obj->shape;
    vec_copy(smp->p, s->p0);
    vec_copy(smp->n, s->n);
    vec_set(smp->p_error, 0, 0, 0);
    smp->pdf = 0; /* no uniform density on an infinite plane */
}

static const cobject_ops plane_ops = {
    "plane", plane_intersect, plane_surface, plane_bounds, plane_area,
    plane_sample, NULL, NULL
};

COBJECT *plane_new(const VECTOR3 point, const VECTOR3 normal,
                   svet_error *err)
{
    if (shape_check_finite("plane", "point", point, err) ||
        shape_check_finite("plane", "normal", normal, err))
        return NULL;
    VECTOR3 n;
    if (vec_normalize(n, normal) == 0) {
        svet_error_set(err, SVET_ERR_RANGE, "plane: the normal is zero");
        return NULL;
    }
    COBJECT *obj = shape_alloc(&plane_ops, sizeof(plane_shape), err);
    if (!obj)
        return NULL;
    plane_shape *s = obj->shape;
    vec_copy(s->p0, point);
    vec_copy(s->n, n);
    frame_from_normal(s->u, s->v, n);
    /* |exact u . n| <= |computed| + gamma(3) sum|u_k n_k| */
    real pu = fabs(SVECTOR3(s->u, n)) +
              ray_gamma(3) * (fabs(s->u[X] * n[X]) + fabs(s->u[Y] * n[Y]) +
                              fabs(s->u[Z] * n[Z]));
    real pv = fabs(SVECTOR3(s->v, n)) +
              ray_gamma(3) * (fabs(s->v[X] * n[X]) + fabs(s->v[Y] * n[Y]) +
                              fabs(s->v[Z] * n[Z]));
    s->perp = fmax(pu, pv);
    return obj;
}
