/*
 * cone.c - the finite cone of app. D: the lateral quadratic in the frame of
 * the axis, its discriminant taken where the ray passes nearest the apex
 * (the shift Haines et al. use for the sphere, Ray Tracing Gems 2019,
 * ch. 7) with Kahan's 2x2 determinant, stable roots, the base disk,
 * re-projected hit points and their error (pbrt-v3 sec. 3.9.4).
 * Tests: tests/geometry/test_cone.c; vectors: tests/vectors/cone.csv
 */
#include "geometry/cone.h"
#include "geometry/quadric.h"
#include "geometry/shape.h"

typedef struct {
    quadric_frame_t f; /* at the apex; w = (apex - base) / H */
    VECTOR3 base;
    real H, R;         /* height |apex - base| and base radius */
    real k, k2;        /* slope R / H of the radius, and its square */
    bool capped;
    real area[2];      /* of the faces: lateral, base */
    real total;        /* area of the surface */
    real margin;       /* of lateral samples from the ends (quadric.h) */
} cone_t;

/* The cone x^2 + y^2 = k^2 z^2 at the local point o: its value, and half
 * its derivative along d. */
static real cone_f(const cone_t *cn, const VECTOR3 o)
{
    return o[X] * o[X] + o[Y] * o[Y] - cn->k2 * o[Z] * o[Z];
}

static real cone_half_df(const cone_t *cn, const VECTOR3 o, const VECTOR3 d)
{
    return o[X] * d[X] + o[Y] * d[Y] - cn->k2 * o[Z] * d[Z];
}

/* A ray aimed through the apex may pass it on either side by rounding, and
 * then both crossings of the double cone near the apex can come out above
 * it (z > 0): the ray would enter the solid without a hit. So a ray whose
 * direction lies strictly inside the solid's cone of directions
 * (a = dx^2 + dy^2 - k^2 dz^2 < 0, dz < 0) and whose line passes within
 * its own rounding of the apex hits the apex, at the line's nearest
 * approach. The rounding: the local coordinates of the ray carry gamma(4)
 * and the frame's defect (QUADRIC_FRAME_DELTA) times their size. A ray
 * leaving the cone outward never qualifies: on the lateral face d . n <=
 * sin(beta - alpha) <= 0 for every direction d within alpha of the axis. */
static bool apex_hit(const cone_t *cn, const VECTOR3 ol, const VECTOR3 dl,
                     int k, real tmin, real *tmax, hit_t *hit)
{
    if (!(dl[Z] < 0 && cone_f(cn, dl) < 0))
        return false;
    real ts = -SVECTOR3(ol, dl) / SVECTOR3(dl, dl);
    VECTOR3 near;
    vec_add_scaled(near, ol, ts, dl);
    real eps = (QUADRIC_FRAME_DELTA + ray_gamma(8)) *
               (fabs(ol[X]) + fabs(ol[Y]) + fabs(ol[Z]));
    real t = quadric_unscale_t(ts, k);
    if (!(vec_length(near) <= eps && t > tmin && t < *tmax))
        return false;
    hit->t = *tmax = t;
    hit->prim = 0;
    vec_set(hit->b, 0, 0, 0);
    return true;
}

/* hit->b: the local (x, y, z) of a lateral hit, z in [-H, 0] (the apex is
 * the local origin), or the local (x, y) of a base hit and b[2] = CONE_BASE,
 * which no lateral z can be. */
static bool cone_intersect(const COBJECT *obj, int prim, const ray_t *r,
                           real tmin, real tmax, hit_t *hit)
{
    const cone_t *cn = obj->shape;
    (void)prim;
    VECTOR3 ol, dl, oc;
    int k = quadric_frame_ray(&cn->f, r, ol, dl);
    /* app. D: with the apex at the local origin the lateral surface is
     * x^2 + y^2 = k^2 z^2, -H <= z <= 0: a t^2 + 2 bh t + c = 0 with
     * a = dx^2 + dy^2 - k^2 dz^2, bh = ox dx + oy dy - k^2 oz dz,
     * c = ox^2 + oy^2 - k^2 oz^2. */
    real a = cone_f(cn, dl);
    real bh = cone_half_df(cn, ol, dl);
    real c = cone_f(cn, ol);
    /* bh^2 - a c does not change when the origin slides along the ray.
     * Evaluated at the ray's point nearest the apex, oc = o - (o.d/d.d) d,
     * its terms are of the size of the cone rather than of |o|^2, which
     * avoids the cancellation the textbook formula suffers for a distant
     * origin (for the sphere this is exactly Haines et al.'s
     * a (r^2 - |l|^2)); the remaining difference of two products is taken
     * with Kahan's fma algorithm. The roots use bh and c of the true
     * origin, so that a root near 0 keeps its sign. */
    vec_add_scaled(oc, ol, -SVECTOR3(ol, dl) / SVECTOR3(dl, dl), dl);
    real bhc = cone_half_df(cn, oc, dl);
    real disc = quadric_diff_of_products(bhc, bhc, a, cone_f(cn, oc));
    real t[2];
    int n = quadric_roots(a, bh, c, disc, t);
    /* One refinement step per root: near the apex the cone's value at the
     * hit is far smaller than the rounding of c and bh taken at a distant
     * origin (a chord from the base rim to a point near the apex lies
     * nearly on the surface, and its far root came out before the end of
     * the chord). At the estimate o + t d the coefficients are small and
     * accurate, and the root of the shifted quadratic nearest 0 corrects
     * t: c'/q' with q' = -(bh' + sign(bh') sqrt(disc)), disc unchanged by
     * the shift. */
    for (int i = 0; i < n; i++) {
        VECTOR3 oi;
        vec_add_scaled(oi, ol, t[i], dl);
        real bhi = cone_half_df(cn, oi, dl);
        real qi = -(bhi + copysign(sqrt(disc), bhi));
        real dt = cone_f(cn, oi) / qi;
        if (isfinite(dt))
            t[i] += dt;
    }
    if (n == 2 && t[0] > t[1]) {
        real s = t[0]; t[0] = t[1]; t[1] = s;
    }
    bool found = quadric_lateral_hit(t, n, k, ol, dl, -cn->H, 0, tmin, &tmax,
                                     hit);
    found |= apex_hit(cn, ol, dl, k, tmin, &tmax, hit);
    if (cn->capped)
        found |= quadric_cap_hit(ol, dl, k, -cn->H, cn->R, CONE_BASE, tmin,
                                 &tmax, hit);
    return found;
}

/* A lateral point of local (x, y, z), from a ray or a sample: z clamped to
 * [-H, 0] and (x, y) re-projected to the radius rho = -k z of the cone at
 * that height. rho carries gamma(2) (k and the product), the projection
 * gamma(6) more (quadric_project), so each re-projected x_i is within
 * gamma(8) |x_i| of a point exactly on the cone: the `extra` error handed
 * to quadric_frame_point. Sets p, p_error and the outward normal n,
 * and returns the projected local coordinates in xyz. */
static void lateral_point(const cone_t *cn, VECTOR3 xyz, VECTOR3 p,
                          VECTOR3 p_error, VECTOR3 n)
{
    real z = fmin(fmax(xyz[Z], -cn->H), REAL_C(0.0));
    real rho_cone = -cn->k * z;
    VECTOR3 q = { xyz[X], xyz[Y], 0 };
    if (rho_cone == 0 || !quadric_project(q, rho_cone))
        vec_set(q, rho_cone, 0, 0); /* the apex, or on the axis: phi = 0 */
    real x = q[X], y = q[Y];
    quadric_frame_point(&cn->f, cn->f.o, x, y, z,
                        ray_gamma(8) * (fabs(x) + fabs(y)), p, p_error);
    /* The gradient direction (cos phi, sin phi, k), scaled by rho. */
    VECTOR3 nl = { x, y, cn->k * rho_cone };
    frame_to_world(n, nl, cn->f.e1, cn->f.e2, cn->f.w);
    if (vec_normalize(n, n) == 0)
        vec_copy(n, cn->f.w); /* the apex */
    vec_set(xyz, x, y, z);
}

static void cone_surface(const COBJECT *obj, const ray_t *r, const hit_t *hit,
                         PATHPOINT *pp)
{
    const cone_t *cn = obj->shape;
    (void)r;
    if (hit->b[2] == CONE_BASE) {
        pp->prim = CONE_BASE;
        quadric_disk_surface(&cn->f, cn->base, -cn->H, cn->R, -1, hit->b[0],
                             hit->b[1], pp);
        return;
    }
    pp->prim = CONE_LATERAL;
    VECTOR3 q;
    vec_copy(q, hit->b);
    lateral_point(cn, q, pp->cross_point, pp->p_error, pp->ng);
    vec_copy(pp->n, pp->ng);
    /* s = phi / 2 pi, t = h / H = 1 + z / H (cone.h) */
    real phi = quadric_phi(q[X], q[Y]);
    pp->st[0] = fmin(phi / (2 * REAL_PI), REAL_C(1.0));
    pp->st[1] = fmin(fmax(1 + q[Z] / cn->H, REAL_C(0.0)), REAL_C(1.0));
    VECTOR3 ds = { -2 * REAL_PI * q[Y], 2 * REAL_PI * q[X], 0 };
    VECTOR3 dt = { -cn->R * cos(phi), -cn->R * sin(phi), cn->H };
    frame_to_world(pp->dpds, ds, cn->f.e1, cn->f.e2, cn->f.w);
    frame_to_world(pp->dpdt, dt, cn->f.e1, cn->f.e2, cn->f.w);
    shape_frame(pp->u, pp->v, pp->n, pp->dpds);
}

static void cone_bounds(const COBJECT *obj, int prim, bbox_t *b)
{
    const cone_t *cn = obj->shape;
    (void)prim;
    /* The convex hull of the base circle and the apex: tight. */
    bbox_empty(b);
    quadric_disk_bounds(b, cn->base, cn->f.w, cn->R);
    quadric_bounds_add(b, cn->f.o, cn->f.o);
}

static real cone_area(const COBJECT *obj)
{
    return ((const cone_t *)obj->shape)->total;
}

static void cone_sample(const COBJECT *obj, const real u[2],
                        cobject_sample_t *s)
{
    const cone_t *cn = obj->shape;
    real v[2] = { u[0], u[1] };
    int face = quadric_pick_face(&v[0], cn->area, cn->capped ? 2 : 1);
    if (face == CONE_LATERAL) {
        /* Unrolled, the lateral face is a circular sector about the apex:
         * the area within distance h' of the apex grows as h'^2, so
         * h' / H = sqrt(u0) (inverse CDF), and phi is uniform; h' is kept
         * the sample margin from the apex and the base. */
        real h = fmin(fmax(cn->H * sqrt(v[0]), cn->margin),
                      cn->H - cn->margin);
        real rho = cn->k * h, phi = 2 * REAL_PI * v[1];
        VECTOR3 q = { rho * cos(phi), rho * sin(phi), -h };
        lateral_point(cn, q, s->p, s->p_error, s->n);
    } else {
        quadric_disk_sample(&cn->f, cn->base, -cn->H, cn->R, -1, v, s);
    }
    s->pdf = 1 / cn->total;
}

/* The lateral face, F = x^2 + y^2 - k^2 z^2 about the apex; the base is
 * flat. */
static void cone_normal_change(const COBJECT *obj, const PATHPOINT *pp,
                               const VECTOR3 dp, VECTOR3 dn)
{
    const cone_t *cn = obj->shape;
    if (pp->prim == CONE_LATERAL)
        quadric_lateral_normal_change(&cn->f, -cn->k2, pp, dp, dn);
    else
        vec_set(dn, 0, 0, 0);
}

static const cobject_ops cone_ops = {
    "cone", cone_intersect, cone_surface, cone_bounds,
    cone_area, cone_sample, NULL, cone_normal_change
};

COBJECT *cone_new(const VECTOR3 base, const VECTOR3 apex, real radius,
                  bool capped, svet_error *err)
{
    VECTOR3 w;
    real H;
    if (quadric_check_axis("cone", "base", base, "apex", apex, radius, w, &H,
                           err) != SVET_OK)
        return NULL;
    COBJECT *obj = shape_alloc(&cone_ops, sizeof(cone_t), err);
    if (!obj)
        return NULL;
    cone_t *cn = obj->shape;
    quadric_frame_init(&cn->f, apex, w);
    vec_copy(cn->base, base);
    cn->H = H;
    cn->R = radius;
    cn->k = radius / H;
    cn->k2 = cn->k * cn->k;
    cn->capped = capped;
    cn->margin = quadric_lateral_margin(base, apex, radius, H);
    cn->area[CONE_LATERAL] = REAL_PI * radius * hypot(radius, H);
    cn->area[CONE_BASE] = REAL_PI * radius * radius;
    cn->total = cn->area[CONE_LATERAL] + (capped ? cn->area[CONE_BASE] : 0);
    return quadric_object_done(obj, err);
}
