/*
 * sphere.c - the sphere of app. D: intersection after Haines, Guenther,
 * Akenine-Moller, "Precision Improvements for Ray/Sphere Intersection" (Ray
 * Tracing Gems, 2019, ch. 7), re-projected hit points and their error
 * bound after pbrt-v3 sec. 3.9.4, uniform area sampling (Archimedes).
 * Tests: tests/geometry/test_sphere.c; vectors: tests/vectors/sphere.csv
 */
#include "geometry/sphere.h"
#include "geometry/quadric.h"
#include "geometry/shape.h"

typedef struct {
    VECTOR3 c;  /* centre */
    real r;     /* radius */
    real area;  /* 4 pi r^2 */
} sphere_t;

static bool sphere_intersect(const COBJECT *obj, int prim, const ray_t *r,
                             real tmin, real tmax, hit_t *hit)
{
    const sphere_t *sp = obj->shape;
    (void)prim;
    /* app. D: |o + t d - c|^2 = r^2, i.e. a t^2 + 2 bh t + c = 0 with
     * f = o - c, a = d.d, bh = f.d, c = f.f - r^2. d is first scaled by a
     * power of two so that a is of order one whatever |d| is. */
    VECTOR3 d, f, l;
    int k = quadric_scale_dir(d, r->d);
    vec_sub(f, r->o, sp->c);
    real a = SVECTOR3(d, d);
    if (!(a > 0))
        return false;
    real bh = SVECTOR3(f, d);
    real c = SVECTOR3(f, f) - sp->r * sp->r;
    /* The textbook discriminant bh^2 - a c subtracts two numbers of the
     * order of |f|^2 and loses every digit when the origin is far from a
     * small sphere. Haines et al. (ch. 7) use the point of the ray nearest
     * the centre instead: l = f - (f.d / d.d) d, and
     * bh^2 - a c = a (r^2 - |l|^2). */
    vec_add_scaled(l, f, -bh / a, d);
    real disc = a * (sp->r * sp->r - SVECTOR3(l, l));
    real t[2];
    int n = quadric_roots(a, bh, c, disc, t);
    for (int i = 0; i < n; i++) {
        real ti = quadric_unscale_t(t[i], k);
        if (ti > tmin && ti < tmax) {
            hit->t = ti;
            hit->prim = 0;
            return true;
        }
    }
    return false;
}

/* The point c + q of the sphere for a vector q from the centre (of any
 * length, from a ray or a sample), re-projected onto the surface as pbrt-v3
 * (sec. 3.9.4) does: q <- q r / |q|. Error bound, u the unit roundoff:
 * |q| (two hypot() calls of <= 1 ulp each) is within gamma(4) of the exact
 * length; r / |q| adds one rounding, the product q_i (r/|q|) another, so the
 * computed q_i is within gamma(6) |q*_i| <= gamma(7) |q_i| of
 * q*_i = q_i r / |q|, which lies exactly on the sphere (quadric_project).
 * Adding the centre rounds once more: |fl(c_i + q_i) - (c_i + q_i)| <=
 * u |c_i + q_i| <= gamma(2) |p_i|. Hence
 *     p_error_i = gamma(7) |q_i| + gamma(2) |p_i|.
 * (pbrt-v3 has gamma(5) |p| with the centre at the object-space origin.)
 * q is replaced by its projection; n is the outward unit normal q / r. */
static void sphere_point(const sphere_t *sp, VECTOR3 q, VECTOR3 p,
                         VECTOR3 p_error, VECTOR3 n)
{
    if (!quadric_project(q, sp->r))
        vec_set(q, 0, 0, sp->r); /* no direction: the north pole */
    vec_add(p, sp->c, q);
    real g7 = ray_gamma(7), g2 = ray_gamma(2);
    for (int i = 0; i < 3; i++)
        p_error[i] = g7 * fabs(q[i]) + g2 * fabs(p[i]);
    vec_normalize(n, q);
}

static void sphere_surface(const COBJECT *obj, const ray_t *r,
                           const hit_t *hit, PATHPOINT *pp)
{
    const sphere_t *sp = obj->shape;
    VECTOR3 q;
    ray_at(q, r, hit->t);
    vec_sub(q, q, sp->c);
    sphere_point(sp, q, pp->cross_point, pp->p_error, pp->ng);
    vec_copy(pp->n, pp->ng);
    /* s = phi / 2 pi, t = theta / pi (sphere.h); theta by atan2 rather
     * than acos(z / r), which is ill-conditioned near the poles. */
    real rho = hypot(q[X], q[Y]);
    real phi = quadric_phi(q[X], q[Y]);
    real theta = atan2(rho, q[Z]);
    pp->st[0] = fmin(phi / (2 * REAL_PI), REAL_C(1.0));
    pp->st[1] = fmin(theta / REAL_PI, REAL_C(1.0));
    real cos_phi = rho > 0 ? q[X] / rho : 1;
    real sin_phi = rho > 0 ? q[Y] / rho : 0;
    vec_set(pp->dpds, -2 * REAL_PI * q[Y], 2 * REAL_PI * q[X], 0);
    vec_set(pp->dpdt, REAL_PI * q[Z] * cos_phi, REAL_PI * q[Z] * sin_phi,
            -REAL_PI * rho);
    shape_frame(pp->u, pp->v, pp->n, pp->dpds);
}

static void sphere_bounds(const COBJECT *obj, int prim, bbox_t *b)
{
    const sphere_t *sp = obj->shape;
    (void)prim;
    VECTOR3 lo, hi;
    for (int i = 0; i < 3; i++) {
        lo[i] = sp->c[i] - sp->r;
        hi[i] = sp->c[i] + sp->r;
    }
    bbox_empty(b);
    quadric_bounds_add(b, lo, hi);
}

static real sphere_area(const COBJECT *obj)
{
    return ((const sphere_t *)obj->shape)->area;
}

static void sphere_sample(const COBJECT *obj, const real u[2],
                          cobject_sample_t *s)
{
    const sphere_t *sp = obj->shape;
    /* Archimedes: z is uniform in [-r, r] for a uniform point of the
     * sphere, so z = 1 - 2 u0; sin(theta) = sqrt(1 - z^2) is written
     * 2 sqrt(u0 (1 - u0)), which does not cancel near the poles. */
    real z = 1 - 2 * u[0];
    real sin_theta = 2 * sqrt(u[0] * (1 - u[0]));
    real phi = 2 * REAL_PI * u[1];
    VECTOR3 q = { sp->r * sin_theta * cos(phi), sp->r * sin_theta * sin(phi),
                  sp->r * z };
    sphere_point(sp, q, s->p, s->p_error, s->n);
    s->pdf = 1 / sp->area;
}

/* F = |p - c|^2 - r^2: half gradient p - c, half Hessian the identity, so
 * dn = dp / r along the surface. */
static void sphere_normal_change(const COBJECT *obj, const PATHPOINT *pp,
                                 const VECTOR3 dp, VECTOR3 dn)
{
    const sphere_t *sp = obj->shape;
    VECTOR3 g;
    vec_sub(g, pp->cross_point, sp->c);
    shape_normal_change(g, dp, pp->n, dn);
}

static const cobject_ops sphere_ops = {
    "sphere", sphere_intersect, sphere_surface, sphere_bounds,
    sphere_area, sphere_sample, NULL, sphere_normal_change
};

COBJECT *sphere_new(const VECTOR3 centre, real radius, svet_error *err)
{
    if (shape_check_finite("sphere", "centre", centre, err) ||
        quadric_check_radius("sphere", radius, err))
        return NULL;
    COBJECT *obj = shape_alloc(&sphere_ops, sizeof(sphere_t), err);
    if (!obj)
        return NULL;
    sphere_t *sp = obj->shape;
    vec_copy(sp->c, centre);
    sp->r = radius;
    sp->area = 4 * REAL_PI * radius * radius;
    return quadric_object_done(obj, err);
}
