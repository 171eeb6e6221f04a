/*
 * triangle.c - the triangle of app. D. Departs from the book's "hit the
 * plane, then test inside" with the watertight test of Woop, Benthin, Wald,
 * JCGT 2(1) 2013, and pbrt-v3 sec. 3.9 for the error bounds.
 * Tests: tests/geometry/test_triangle.c; vectors: tests/vectors/triangle.csv
 */
#include "geometry/triangle.h"
#include "geometry/shape.h"

#include <stdlib.h>

/* The exact sign of a*b - c*d. In float the two products are exact in
 * double (24 + 24 bits < 53) and the one rounding of their difference
 * keeps its sign: this is Woop et al.'s fallback. In double there is no
 * wider type that is exact, so Kahan's fma algorithm is used instead: its
 * relative error is below 2u (Jeannerod, Louvet, Muller, "Further analysis
 * of Kahan's algorithm for the accurate computation of 2x2 determinants",
 * Math. Comp. 82, 2013), so its result is zero exactly when a*b = c*d and
 * has the right sign otherwise. */
static real diff_of_products_exact(real a, real b, real c, real d)
{
#ifdef SVET_DOUBLE
    double w = c * d;
    double e = fma(-c, d, w); /* w - c*d, exactly */
    double f = fma(a, b, -w);
    return f + e;
#else
    return (real)((double)a * (double)b - (double)c * (double)d);
#endif
}

/* max |a|, |b|, |c| of finite reals without fmax's libm call */
static inline real max3a(real a, real b, real c)
{
    return real_max(fabs(a), real_max(fabs(b), fabs(c)));
}

void triangle_ray_prepare_scaled(triangle_ray_t *pr, const ray_t *r)
{
    const int kz = pr->kz;
    real dz = r->d[kz];
    pr->ok = dz != 0 && isfinite(dz);
    pr->scale = 0;
    if (!pr->ok) {
        pr->sx = pr->sy = pr->sz = 0;
        return;
    }
    /* Scale d by a power of two (exact) when its largest component is far
     * from 1, so that 1/d_z and the sheared z's cannot overflow; the ray
     * parameter then scales back by the same power (o + t d = o + t' d'). */
    VECTOR3 d;
    pr->scale = ilogb(dz);
    for (int i = 0; i < 3; i++)
        d[i] = ldexp(r->d[i], -pr->scale);
    /* as triangle_ray_prepare: one division, sx and sy two roundings */
    real inv = 1 / d[kz];
    pr->sx = -d[pr->kx] * inv;
    pr->sy = -d[pr->ky] * inv;
    pr->sz = inv;
}

bool triangle_hit_sheared(const triangle_sheared_t *v0,
                          const triangle_sheared_t *v1,
                          const triangle_sheared_t *v2, real e0, real e1,
                          real e2, const triangle_ray_t *pr, real tmin,
                          real tmax, real *t, real b[3])
{
    /* Inside when all three have one sign; zero counts for both sides, so
     * a ray through an edge is inside both triangles that share it. */
    if ((e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0))
        return false;
    real det = e0 + e1 + e2;
    /* det = 0: the ray lies in the triangle's plane (or the projection is
     * degenerate). A non-finite det means an overflow: no reliable hit. */
    if (det == 0 || !isfinite(det))
        return false;

    /* t = sum e_i z_i / det with the sheared z's (Woop et al. eq. 8). */
    const real sz = pr->sz;
    real z0 = sz * v0->az, z1 = sz * v1->az, z2 = sz * v2->az;
    real tt = (e0 * z0 + e1 * z1 + e2 * z2) / det;
    if (!isfinite(tt))
        return false;
    /* The cheap rejections first: the order of the tests below does not
     * change which hits pass. With tmin >= 0 a tt <= 0 fails either the
     * error bound (dt >= 0) or the interval. */
    if (tmin >= 0 && !(tt > 0))
        return false;
    real tw = pr->scale != 0 ? ldexp(tt, -pr->scale) : tt;
    if (!(tw > tmin && tw < tmax))
        return false;

    /* pbrt-v3 sec. 3.9.6: a conservative bound dt on the error of tt.
     * The sheared x, y carry gamma(5) (max|x| + max|a_z|) (the translated
     * coordinate one rounding, the shear factor two, its product and the
     * sum one each), the edge functions de, the scaled z's gamma(3) max|z|,
     * and t = sum e_i z_i / det carries dt. One departure: pbrt-v3 uses the
     * scaled z's (in units of t) in the x and y terms (in units of length),
     * which is right only for |d| near 1; here the unscaled a_z keep the
     * units apart, so the bound holds for any length of d. A hit that may
     * truly lie at t <= 0 is rejected, so a ray leaving the triangle never
     * finds it again at t ~ 0. Applied when tmin >= 0 only, so a caller
     * asking for t < 0 still gets it. */
    if (tmin >= 0) {
        real max_z = max3a(z0, z1, z2);
        real max_az = max3a(v0->az, v1->az, v2->az);
        real max_x = max3a(v0->x, v1->x, v2->x);
        real max_y = max3a(v0->y, v1->y, v2->y);
        real dz = ray_gamma(3) * max_z;
        real dx = ray_gamma(5) * (max_x + max_az);
        real dy = ray_gamma(5) * (max_y + max_az);
        real de = 2 * (ray_gamma(2) * max_x * max_y + dy * max_x +
                       dx * max_y);
        real max_e = max3a(e0, e1, e2);
        real dt = 3 * (ray_gamma(3) * max_e * max_z + de * max_z +
                       dz * max_e) / fabs(det);
        if (tt <= dt)
            return false;
    }
    *t = tw;
    /* All e_i have det's sign and sum to it: each b_i lies in [0, 1]. */
    b[0] = e0 / det;
    b[1] = e1 / det;
    b[2] = e2 / det;
    return true;
}

bool triangle_intersect_prepared(const VECTOR3 p0, const VECTOR3 p1,
                                 const VECTOR3 p2, const triangle_ray_t *pr,
                                 real tmin, real tmax, real *t, real b[3])
{
    if (!pr->ok)
        return false;
    triangle_sheared_t v0, v1, v2;
    triangle_shear(&v0, p0, pr);
    triangle_shear(&v1, p1, pr);
    triangle_shear(&v2, p2, pr);

    /* Edge functions (2D cross products) of the projected vertices: e_i is
     * the signed double area opposite vertex i, i.e. its unnormalised
     * barycentric. The shared edge of two triangles gives x1*y2 - y1*x2 in
     * one and x2*y1 - y2*x1 = -(x1*y2 - y1*x2) in the other, exactly. */
    real e0 = triangle_edge(&v1, &v2);
    real e1 = triangle_edge(&v2, &v0);
    real e2 = triangle_edge(&v0, &v1);
    /* A zero may be rounding: recompute exactly (Woop et al. sec. 3.3). */
    if (e0 == 0 || e1 == 0 || e2 == 0) {
        e0 = diff_of_products_exact(v1.x, v2.y, v1.y, v2.x);
        e1 = diff_of_products_exact(v2.x, v0.y, v2.y, v0.x);
        e2 = diff_of_products_exact(v0.x, v1.y, v0.y, v1.x);
    }
    real tt, bb[3];
    if (!triangle_hit_sheared(&v0, &v1, &v2, e0, e1, e2, pr, tmin, tmax, &tt,
                              bb))
        return false;
    /* Only now, on the rare path of a hit: a triangle of no area has no
     * normal, so it is never hit (it would give NaN normals downstream). */
    if (triangle_is_degenerate(p0, p1, p2))
        return false;
    *t = tt;
    vec_copy(b, bb);
    return true;
}

bool triangle_intersect_watertight(const VECTOR3 p0, const VECTOR3 p1,
                                   const VECTOR3 p2, const ray_t *r,
                                   real tmin, real tmax, real *t, real b[3])
{
    triangle_ray_t pr;
    triangle_ray_prepare(&pr, r);
    return triangle_intersect_prepared(p0, p1, p2, &pr, tmin, tmax, t, b);
}

bool triangle_is_degenerate(const VECTOR3 p0, const VECTOR3 p1,
                            const VECTOR3 p2)
{
    VECTOR3 a, b;
    vec_sub(a, p1, p0);
    vec_sub(b, p2, p0);
    if (!vec_is_finite(a) || !vec_is_finite(b))
        return true;
    /* Component k of a x b is a_j b_l - a_l b_j. The edges carry one
     * rounding each, the products one more, the difference one: the
     * computed component is within gamma(4) (|a_j b_l| + |a_l b_j|) of the
     * exact cross product of the exact edges (Higham 2002, sec. 3.1). When
     * every component lies within its bound, the exact area may be 0. */
    for (int k = 0; k < 3; k++) {
        int j = (k + 1) % 3, l = (k + 2) % 3;
        real c = a[j] * b[l] - a[l] * b[j];
        real bound = ray_gamma(4) * (fabs(a[j] * b[l]) + fabs(a[l] * b[j]));
        if (fabs(c) > bound)
            return false;
    }
    return true;
}

void triangle_fill_surface(const VECTOR3 p0, const VECTOR3 p1,
                           const VECTOR3 p2, const VECTOR3 normals[3],
                           const real b[3], PATHPOINT *pp)
{
    triangle_point(pp->cross_point, pp->p_error, p0, p1, p2, b);
    /* app. D: the parameterisation p = p0 + s (p1 - p0) + t (p2 - p0),
     * s = b1, t = b2 */
    vec_sub(pp->dpds, p1, p0);
    vec_sub(pp->dpdt, p2, p0);
    pp->st[0] = fmin(fmax(b[1], REAL_C(0.0)), REAL_C(1.0));
    pp->st[1] = fmin(fmax(b[2], REAL_C(0.0)), REAL_C(1.0));
    if (!shape_unit_cross(pp->ng, pp->dpds, pp->dpdt))
        vec_set(pp->ng, 0, 0, 1);
    vec_copy(pp->n, pp->ng);
    if (normals) {
        /* Phong's interpolated shading normal */
        VECTOR3 ns;
        for (int k = 0; k < 3; k++)
            ns[k] = b[0] * normals[0][k] + b[1] * normals[1][k] +
                    b[2] * normals[2][k];
        if (vec_normalize(ns, ns) > 0)
            vec_copy(pp->n, ns);
    }
    shape_frame(pp->u, pp->v, pp->n, pp->dpds);
}

/* (b1, b2) with q = b1 e1 + b2 e2 in the least-squares sense (the 2 x 2
 * normal equations of the plane of e1, e2); false where they are
 * singular. */
static bool plane_coords(const VECTOR3 e1, const VECTOR3 e2, const VECTOR3 q,
                         real b[2])
{
    real a = SVECTOR3(e1, e1), c = SVECTOR3(e1, e2), d = SVECTOR3(e2, e2);
    real det = a * d - c * c;
    if (!(det > 0))
        return false;
    real p1 = SVECTOR3(e1, q), p2 = SVECTOR3(e2, q);
    b[0] = (d * p1 - c * p2) / det;
    b[1] = (a * p2 - c * p1) / det;
    return true;
}

void triangle_normal_change(const VECTOR3 p0, const VECTOR3 p1,
                            const VECTOR3 p2, const VECTOR3 normals[3],
                            const PATHPOINT *pp, const VECTOR3 dp,
                            VECTOR3 dn)
{
    vec_set(dn, 0, 0, 0);
    if (!normals)
        return;
    VECTOR3 e1, e2, q, g, dg;
    vec_sub(e1, p1, p0);
    vec_sub(e2, p2, p0);
    vec_sub(q, pp->cross_point, p0);
    real b[2], db[2];
    if (!plane_coords(e1, e2, q, b) || !plane_coords(e1, e2, dp, db))
        return;
    for (int k = 0; k < 3; k++) {
        g[k] = (1 - b[0] - b[1]) * normals[0][k] + b[0] * normals[1][k] +
               b[1] * normals[2][k];
        dg[k] = db[0] * (normals[1][k] - normals[0][k]) +
                db[1] * (normals[2][k] - normals[0][k]);
    }
    shape_normal_change(g, dg, pp->n, dn);
}

void triangle_sample_point(const VECTOR3 p0, const VECTOR3 p1,
                           const VECTOR3 p2, const real u[2],
                           cobject_sample_t *s)
{
    VECTOR3 e1, e2;
    vec_sub(e1, p1, p0);
    vec_sub(e2, p2, p0);
    real area = REAL_C(0.5) * shape_cross_length(e1, e2);
    if (triangle_is_degenerate(p0, p1, p2) || !isfinite(area)) {
        vec_copy(s->p, p0);
        vec_set(s->n, 0, 0, 1);
        vec_set(s->p_error, 0, 0, 0);
        s->pdf = 0;
        return;
    }
    /* Uniform barycentrics by the square-root map, b0 = 1 - sqrt(u0),
     * b1 = u1 sqrt(u0) (Shirley & Chiu; pbrt-v3 sec. 13.6.5). */
    real su = sqrt(u[0]);
    real b[3] = { 1 - su, u[1] * su, 0 };
    b[2] = fmax(1 - b[0] - b[1], REAL_C(0.0));
    triangle_point(s->p, s->p_error, p0, p1, p2, b);
    shape_unit_cross(s->n, e1, e2);
    s->pdf = 1 / area;
}

/* --- the triangle COBJECT ------------------------------------------------ */

typedef struct {
    VECTOR3 p[3];       /* corners */
    VECTOR3 normals[3]; /* unit vertex normals when has_normals */
    bool has_normals;
    bool degenerate;    /* triangle_is_degenerate(): never hit */
    real area;
} triangle_shape;

static bool tri_intersect(const COBJECT *obj, int prim, const ray_t *r,
                          real tmin, real tmax, hit_t *hit)
{
    const triangle_shape *s = obj->shape;
    if (s->degenerate)
        return false;
    if (!triangle_intersect_watertight(s->p[0], s->p[1], s->p[2], r, tmin,
                                       tmax, &hit->t, hit->b))
        return false;
    hit->prim = prim;
    return true;
}

static void tri_surface(const COBJECT *obj, const ray_t *r, const hit_t *hit,
                        PATHPOINT *pp)
{
    (void)r;
    const triangle_shape *s = obj->shape;
    triangle_fill_surface(s->p[0], s->p[1], s->p[2],
                          s->has_normals ? s->normals : NULL, hit->b, pp);
}

static void tri_bounds(const COBJECT *obj, int prim, bbox_t *b)
{
    (void)prim;
    const triangle_shape *s = obj->shape;
    bbox_empty(b);
    for (int i = 0; i < 3; i++)
        bbox_add_point(b, s->p[i]);
}

static real tri_area(const COBJECT *obj)
{
    return ((const triangle_shape *)obj->shape)->area;
}

static void tri_sample(const COBJECT *obj, const real u[2],
                       cobject_sample_t *smp)
{
    const triangle_shape *s = obj->shape;
    triangle_sample_point(s->p[0], s->p[1], s->p[2], u, smp);
}

static void tri_normal_change(const COBJECT *obj, const PATHPOINT *pp,
                              const VECTOR3 dp, VECTOR3 dn)
{
    const triangle_shape *s = obj->shape;
    triangle_normal_change(s->p[0], s->p[1], s->p[2],
                           s->has_normals ? s->normals : NULL, pp, dp, dn);
}

static const cobject_ops triangle_ops = {
    "triangle", tri_intersect, tri_surface, tri_bounds, tri_area, tri_sample,
    NULL, tri_normal_change
};

COBJECT *triangle_new(const VECTOR3 p0, const VECTOR3 p1, const VECTOR3 p2,
                      svet_error *err)
{
    if (shape_check_finite("triangle", "p0", p0, err) ||
        shape_check_finite("triangle", "p1", p1, err) ||
        shape_check_finite("triangle", "p2", p2, err))
        return NULL;
    VECTOR3 e1, e2;
    vec_sub(e1, p1, p0);
    vec_sub(e2, p2, p0);
    real area = REAL_C(0.5) * shape_cross_length(e1, e2);
    if (!vec_is_finite(e1) || !vec_is_finite(e2) || !isfinite(area)) {
        svet_error_set(err, SVET_ERR_RANGE, "triangle: edges or area exceed "
                       "the largest %s", REAL_NAME);
        return NULL;
    }
    COBJECT *obj = shape_alloc(&triangle_ops, sizeof(triangle_shape), err);
    if (!obj)
        return NULL;
    triangle_shape *s = obj->shape;
    vec_copy(s->p[0], p0);
    vec_copy(s->p[1], p1);
    vec_copy(s->p[2], p2);
    s->degenerate = triangle_is_degenerate(p0, p1, p2);
    s->area = s->degenerate ? 0 : area;
    return obj;
}

svet_status triangle_set_normals(COBJECT *obj, const VECTOR3 n0,
                                 const VECTOR3 n1, const VECTOR3 n2,
                                 svet_error *err)
{
    if (!obj || obj->ops != &triangle_ops)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "triangle_set_normals: not a triangle");
    const real *n[3] = { n0, n1, n2 };
    VECTOR3 unit[3];
    for (int i = 0; i < 3; i++)
        if (vec_normalize(unit[i], n[i]) == 0)
            return svet_error_set(err, SVET_ERR_RANGE,
                                  "triangle: vertex normal %d (%g, %g, %g) is "
                                  "zero or not finite", i, (double)n[i][X],
                                  (double)n[i][Y], (double)n[i][Z]);
    triangle_shape *s = obj->shape;
    for (int i = 0; i < 3; i++)
        vec_copy(s->normals[i], unit[i]);
    s->has_normals = true;
    return SVET_OK;
}
