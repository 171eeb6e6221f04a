/*
 * xform.c - affine transforms and primitives under them (app. D): rotation
 * by Rodrigues' formula (app. C), rays to object space, hit points back to
 * the world with the error bounds of pbrt-v3 sec. 3.9.4, normals by the
 * inverse transpose, areas by Nanson's formula or quadrature. Its speed
 * layer, a culling sphere around a transformed box, the box's slabs
 * tested before its own test, a table of its faces' frames and SSE lanes
 * for the matrix rows, is fast/xform_cull.c (SIMD=on builds).
 * Tests: tests/geometry/test_xform.c; vectors: tests/vectors/xform.csv
 */
#include "geometry/xform.h"
#include "geometry/shape.h"
#include "xform_shape.h"

#include <stddef.h>
#include <string.h>

typedef long double ld;

/* --- the matrices ----------------------------------------------------------- */

static xform_t invalid(void)
{
    xform_t x;
    memset(&x, 0, sizeof x);
    x.valid = false;
    return x;
}

static bool all_finite(const real *m)
{
    for (int i = 0; i < 12; i++)
        if (!isfinite(m[i]))
            return false;
    return true;
}

xform_t xform_identity(void)
{
    xform_t x;
    memset(&x, 0, sizeof x);
    for (int i = 0; i < 3; i++)
        x.m[i][i] = x.inv[i][i] = 1;
    x.valid = true;
    return x;
}

xform_t xform_translate(const VECTOR3 t)
{
    if (!vec_is_finite(t))
        return invalid();
    xform_t x = xform_identity();
    for (int i = 0; i < 3; i++) {
        x.m[i][3] = t[i];
        x.inv[i][3] = -t[i];
    }
    return x;
}

xform_t xform_scale(const VECTOR3 s)
{
    xform_t x = xform_identity();
    for (int i = 0; i < 3; i++) {
        real r = 1 / s[i];
        if (!isfinite(s[i]) || s[i] == 0 || !isfinite(r))
            return invalid();
        x.m[i][i] = s[i];
        x.inv[i][i] = r;
    }
    return x;
}

xform_t xform_rotate(const VECTOR3 axis, real degrees)
{
    VECTOR3 k;
    if (!isfinite(degrees) || vec_normalize(k, axis) == 0)
        return invalid();
    /* exact cosines and sines at multiples of 90 degrees, so that quarter
     * turns permute axes without rounding */
    real c, s;
    real r = fmod(degrees, REAL_C(360.0));
    if (r < 0)
        r += 360;
    if (r == 0 || r == 90 || r == 180 || r == 270) {
        const real cs[4][2] = { { 1, 0 }, { 0, 1 }, { -1, 0 }, { 0, -1 } };
        c = cs[(int)r / 90][0];
        s = cs[(int)r / 90][1];
    } else {
        double a = (double)degrees * (3.14159265358979323846 / 180.0);
        c = (real)cos(a);
        s = (real)sin(a);
    }
    /* app. C in matrix form: R = c I + s [k]x + (1 - c) k k^T, the matrix
     * whose columns are Rodrigues' rotations of the axes */
    const real kx[3][3] = { { 0, -k[Z], k[Y] }, { k[Z], 0, -k[X] },
                            { -k[Y], k[X], 0 } };
    xform_t x = xform_identity();
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            real v = (i == j ? c : 0) + s * kx[i][j] + (1 - c) * k[i] * k[j];
            x.m[i][j] = v;
            x.inv[j][i] = v; /* R^-1 = R^T */
        }
    return x;
}

/* out = a o b (b applied first), accumulated in long double */
static void affine_mul(real *out, const real *a, const real *b)
{
    real r[3][4];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++) {
            ld sum = j == 3 ? (ld)AT(a, i, 3) : 0;
            for (int k = 0; k < 3; k++)
                sum += (ld)AT(a, i, k) * (ld)AT(b, k, j);
            r[i][j] = (real)sum;
        }
    memcpy(out, r, sizeof r);
}

xform_t xform_compose(xform_t first, xform_t then)
{
    if (!first.valid || !then.valid)
        return invalid();
    xform_t x;
    affine_mul(MAT(x.m), MAT(then.m), MAT(first.m));
    affine_mul(MAT(x.inv), MAT(first.inv), MAT(then.inv));
    x.valid = all_finite(MAT(x.m)) && all_finite(MAT(x.inv));
    return x.valid ? x : invalid();
}

/* det of the linear part, in long double, and whether it is far enough
 * from 0: |det| > 64 epsilon |c0| |c1| |c2| (Hadamard's bound is the
 * product of the column lengths; the ratio is scale-free). */
static ld det3(const real *m, bool *regular)
{
    ld a[3][3]; /* the entries, widened (exactly) */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            a[i][j] = (ld)AT(m, i, j);
    ld d = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
           a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    ld h = 1;
    for (int j = 0; j < 3; j++)
        h *= sqrtl(a[0][j] * a[0][j] + a[1][j] * a[1][j] +
                   a[2][j] * a[2][j]);
    *regular = isfinite(d) && fabsl(d) > 64 * (ld)REAL_EPSILON * h;
    return d;
}

/* The inverse of [M | t] by cofactors in long double. */
static svet_status inverse_of(const real *m, real *out,
                              svet_error *err)
{
    bool regular;
    if (!all_finite(m))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "xform: the matrix is not finite");
    ld d = det3(m, &regular);
    if (!regular)
        return svet_error_set(err, SVET_ERR_RANGE, "xform: the matrix is "
                              "singular to working precision (det %Lg)", d);
    ld a[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            /* cofactor of AT(m, j, i), the adjugate's (i, j) entry */
            int r0 = (j + 1) % 3, r1 = (j + 2) % 3;
            int c0 = (i + 1) % 3, c1 = (i + 2) % 3;
            a[i][j] = ((ld)AT(m, r0, c0) * (ld)AT(m, r1, c1) -
                       (ld)AT(m, r0, c1) * (ld)AT(m, r1, c0)) / d;
        }
    real r[3][4];
    for (int i = 0; i < 3; i++) {
        ld t = 0;
        for (int k = 0; k < 3; k++) {
            r[i][k] = (real)a[i][k];
            t -= a[i][k] * (ld)AT(m, k, 3);
        }
        r[i][3] = (real)t;
    }
    if (!all_finite(MAT(r)))
        return svet_error_set(err, SVET_ERR_RANGE, "xform: the inverse "
                              "exceeds the range of %s", REAL_NAME);
    memcpy(out, r, sizeof r);
    return SVET_OK;
}

svet_status xform_invert(const xform_t *a, xform_t *out, svet_error *err)
{
    if (!a->valid)
        return svet_error_set(err, SVET_ERR_RANGE, "xform: not invertible "
                              "(a zero scale, a zero axis or a NaN made it)");
    real r[3][4];
    svet_status st = inverse_of(MAT(a->m), MAT(r), err);
    if (st != SVET_OK)
        return st;
    real keep[3][4];
    memcpy(keep, a->m, sizeof keep); /* out may alias a */
    memcpy(out->m, r, sizeof r);
    memcpy(out->inv, keep, sizeof keep);
    out->valid = true;
    return SVET_OK;
}

svet_status xform_from_matrix(const real m[12], xform_t *out,
                              svet_error *err)
{
    xform_t x;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++)
            x.m[i][j] = m[4 * i + j];
    x.valid = true;
    svet_status st = xform_invert(&x, &x, err);
    if (st != SVET_OK)
        return st;
    /* x now maps world to object: swap back */
    out->valid = true;
    memcpy(out->m, x.inv, sizeof out->m);
    memcpy(out->inv, x.m, sizeof out->inv);
    return SVET_OK;
}

/* One row of apply(): m_i0 p_x + m_i1 p_y + m_i2 p_z + (m_i3 or 0). */
static inline real row(const real *m, int i, const VECTOR3 p, bool point)
{
    return AT(m, i, 0) * p[X] + AT(m, i, 1) * p[Y] + AT(m, i, 2) * p[Z] +
           (point ? AT(m, i, 3) : 0);
}

/* m p for a point, or its linear part for a vector; the rows written
 * out, which every ray that meets a transformed object makes twice */
static inline void apply(const real *m, VECTOR3 out, const VECTOR3 p,
                         bool point)
{
    real r0 = row(m, 0, p, point), r1 = row(m, 1, p, point),
         r2 = row(m, 2, p, point);
    vec_set(out, r0, r1, r2);
}

void xform_point(const xform_t *x, VECTOR3 out, const VECTOR3 p)
{
    apply(MAT(x->m), out, p, true);
}

void xform_vector(const xform_t *x, VECTOR3 out, const VECTOR3 v)
{
    apply(MAT(x->m), out, v, false);
}

void xform_normal(const xform_t *x, VECTOR3 out, const VECTOR3 n)
{
    /* M^-T n: the columns of inv dotted with n */
    real r[3];
    for (int i = 0; i < 3; i++)
        r[i] = x->inv[0][i] * n[X] + x->inv[1][i] * n[Y] +
               x->inv[2][i] * n[Z];
    vec_set(out, r[0], r[1], r[2]);
}

/* out = m p with a bound on its error: pbrt-v3 sec. 3.9.4. Each
 * coordinate sum_j m_ij p_j + m_i3 costs three products and three sums; a
 * term sees at most four roundings, so the result is within gamma(4)
 * (sum_j |m_ij p_j| + |m_i3|) of the exact image of the float point
 * (pbrt-v3 writes gamma(3), counting one addition fewer). A point already
 * uncertain by e carries (1 + gamma(4)) sum_j |m_ij| e_j more. */
static void point_with_error(const real *m, const VECTOR3 p,
                             const VECTOR3 e, VECTOR3 out, VECTOR3 out_e)
{
    real g = ray_gamma(4);
    apply(m, out, p, true);
    for (int i = 0; i < 3; i++) {
        real a = fabs(AT(m, i, 0) * p[X]), b = fabs(AT(m, i, 1) * p[Y]),
             c = fabs(AT(m, i, 2) * p[Z]), d = fabs(AT(m, i, 3));
        real prop = fabs(AT(m, i, 0)) * e[X] + fabs(AT(m, i, 1)) * e[Y] +
                    fabs(AT(m, i, 2)) * e[Z];
        out_e[i] = (1 + g) * prop + g * a + g * b + g * c + g * d;
    }
}

/* --- the transformed COBJECT ------------------------------------------------ */

static const cobject_ops xform_ops;

/* The ray in object space. Its direction is first scaled by 2^-k (exact)
 * when its largest component m lies outside [2^-16, 2^17), so that
 * M^-1 d neither underflows nor overflows; then t_object = t_world 2^k.
 * Inside that range k is 0, whatever ilogb(m) (a NaN component makes ro's
 * direction NaN below). */
bool xform_object_ray(const xf_shape *sh, const ray_t *r, ray_t *ro, int *k)
{
    real m = real_max(fabs(r->d[X]), real_max(fabs(r->d[Y]), fabs(r->d[Z])));
    *k = 0;
    if (!(m >= REAL_C(0x1p-16) && m < REAL_C(0x1p17)) && m > 0 &&
        isfinite(m))
        *k = real_ilogb(m);
    VECTOR3 d;
    for (int i = 0; i < 3; i++)
        d[i] = *k ? real_ldexp(r->d[i], -*k) : r->d[i];
    apply(MAT(sh->x.inv), ro->o, r->o, true);
    apply(MAT(sh->x.inv), ro->d, d, false);
    return vec_is_finite(ro->o) && vec_is_finite(ro->d) &&
           (ro->d[X] != 0 || ro->d[Y] != 0 || ro->d[Z] != 0);
}

bool xform_intersect_plain(const COBJECT *obj, int prim, const ray_t *r,
                           real tmin, real tmax, hit_t *hit)
{
    const xf_shape *sh = obj->shape;
    ray_t ro;
    int k;
    if (!xform_object_ray(sh, r, &ro, &k))
        return false;
    return xform_intersect_object(sh, prim, &ro, k, tmin, tmax, hit);
}

static bool xf_intersect(const COBJECT *obj, int prim, const ray_t *r,
                         real tmin, real tmax, hit_t *hit)
{
#ifdef SVET_SIMD
    return xform_cull_intersect(obj, prim, r, tmin, tmax, hit);
#else
    return xform_intersect_plain(obj, prim, r, tmin, tmax, hit);
#endif
}

/* The world point of an object point p (error e), with its error bound,
 * grown by what mapping a point next to it back to object space may
 * round away: a ray spawned from the world point will have its origin
 * mapped back, gamma(4) (sum_l |inv_jl| |q_l| + |inv_j3|) per object
 * axis j, and sum_j |m_ij| times that in the world. Offsetting by the
 * whole bound keeps the spawned origin on its side of the surface after
 * the round trip. */
/* Row i of point_with_error()'s bound, from the shape's constants (the
 * same operations in the same order, so the same bits). */
static inline real point_error_row(const xf_shape *sh, int i, const VECTOR3 p,
                                   const VECTOR3 e)
{
    const real g = ray_gamma(4);
    real a = fabs(sh->x.m[i][0] * p[X]), b = fabs(sh->x.m[i][1] * p[Y]),
         c = fabs(sh->x.m[i][2] * p[Z]);
    real prop = sh->abs_m[i][0] * e[X] + sh->abs_m[i][1] * e[Y] +
                sh->abs_m[i][2] * e[Z];
    return (1 + g) * prop + g * a + g * b + g * c + sh->g_m3[i];
}

/* Row j of world_point()'s bound on the error of mapping back. */
static inline real back_row(const xf_shape *sh, int j, const VECTOR3 w)
{
    return sh->g_inv[j][3] + sh->g_inv[j][0] * w[0] + sh->g_inv[j][1] * w[1] +
           sh->g_inv[j][2] * w[2];
}

static inline real widen_row(const xf_shape *sh, int i, real e,
                             const VECTOR3 back)
{
    return e + sh->abs_m[i][0] * back[0] + sh->abs_m[i][1] * back[1] +
           sh->abs_m[i][2] * back[2];
}

/* The world point of object point p (error e) and its bound: what
 * point_with_error() gives, widened by the error of the inverse map
 * (|M| times the bound back of M^-1's rounding), with the constants
 * taken from the shape and the rows written out (every hit on a
 * transformed object completes one). */
void xform_world_point(const xf_shape *sh, const VECTOR3 p, const VECTOR3 e,
                       VECTOR3 out, VECTOR3 out_e)
{
    apply(MAT(sh->x.m), out, p, true);
    real e0 = point_error_row(sh, 0, p, e), e1 = point_error_row(sh, 1, p, e),
         e2 = point_error_row(sh, 2, p, e);
    VECTOR3 w = { fabs(out[X]) + e0, fabs(out[Y]) + e1, fabs(out[Z]) + e2 };
    VECTOR3 back = { back_row(sh, 0, w), back_row(sh, 1, w),
                     back_row(sh, 2, w) };
    vec_set(out_e, widen_row(sh, 0, e0, back), widen_row(sh, 1, e1, back),
            widen_row(sh, 2, e2, back));
}

/* unit M^-T n, with a fallback that cannot happen for a valid transform */
static real world_normal(const xf_shape *sh, VECTOR3 out, const VECTOR3 n)
{
    VECTOR3 w;
    xform_normal(&sh->x, w, n);
    real len = vec_normalize(out, w);
    if (len == 0)
        vec_copy(out, n);
    return len;
}

/* The normals, derivatives and frame of pp, in object space, mapped to
 * the world. */
void xform_surface_frame(const xf_shape *sh, PATHPOINT *pp)
{
    /* the shading normal is the geometric one for most primitives: map it
     * once */
    bool same = memcmp(pp->n, pp->ng, sizeof pp->n) == 0;
    world_normal(sh, pp->ng, pp->ng);
    if (same)
        vec_copy(pp->n, pp->ng);
    else
        world_normal(sh, pp->n, pp->n);
    xform_vector(&sh->x, pp->dpds, pp->dpds);
    xform_vector(&sh->x, pp->dpdt, pp->dpdt);
    shape_frame(pp->u, pp->v, pp->n, pp->dpds);
}

void xform_surface_object(const xf_shape *sh, const ray_t *r,
                          const hit_t *hit, PATHPOINT *pp)
{
    ray_t ro;
    int k;
    xform_object_ray(sh, r, &ro, &k);
    hit_t h = *hit;
    if (k != 0)
        h.t = ldexp(hit->t, k);
    sh->inner->ops->surface(sh->inner, &ro, &h, pp);
}

void xform_surface_generic(const COBJECT *obj, const ray_t *r,
                           const hit_t *hit, PATHPOINT *pp)
{
    const xf_shape *sh = obj->shape;
    xform_surface_object(sh, r, hit, pp);
    VECTOR3 p, e;
    xform_world_point(sh, pp->cross_point, pp->p_error, p, e);
    vec_copy(pp->cross_point, p);
    vec_copy(pp->p_error, e);
    xform_surface_frame(sh, pp);
}

static void xf_surface(const COBJECT *obj, const ray_t *r, const hit_t *hit,
                       PATHPOINT *pp)
{
#ifdef SVET_SIMD
    xform_cull_surface(obj, r, hit, pp);
#else
    xform_surface_generic(obj, r, hit, pp);
#endif
}

static void xf_bounds(const COBJECT *obj, int prim, bbox_t *b)
{
    const xf_shape *sh = obj->shape;
    bbox_t in;
    sh->inner->ops->bounds(sh->inner, prim, &in);
    bbox_empty(b);
    if (bbox_is_empty(&in))
        return;
    bool unbounded = shape_max_abs(in.min) >= REAL_MAX ||
                     shape_max_abs(in.max) >= REAL_MAX;
    for (int c = 0; c < 8 && !unbounded; c++) {
        VECTOR3 q, p, e, zero = { 0, 0, 0 };
        for (int i = 0; i < 3; i++)
            q[i] = (c >> i) & 1 ? in.max[i] : in.min[i];
        point_with_error(MAT(sh->x.m), q, zero, p, e);
        VECTOR3 lo, hi;
        vec_sub(lo, p, e);
        vec_add(hi, p, e);
        if (!vec_is_finite(lo) || !vec_is_finite(hi))
            unbounded = true;
        bbox_add_point(b, lo);
        bbox_add_point(b, hi);
    }
    if (unbounded)
        for (int i = 0; i < 3; i++) {
            b->min[i] = -REAL_MAX;
            b->max[i] = REAL_MAX;
        }
}

static real xf_area(const COBJECT *obj)
{
    return ((const xf_shape *)obj->shape)->area;
}

static void xf_sample(const COBJECT *obj, const real u[2],
                      cobject_sample_t *s)
{
    const xf_shape *sh = obj->shape;
    cobject_sample_t so;
    sh->inner->ops->sample(sh->inner, u, &so);
    xform_world_point(sh, so.p, so.p_error, s->p, s->p_error);
    /* Nanson: dA_world = |det M| |M^-T n| dA_object, so the density per
     * world area is the object density over that factor. */
    real len = world_normal(sh, s->n, so.n);
    real pdf = so.pdf / (sh->absdet * len);
    s->pdf = (so.pdf > 0 && isfinite(pdf)) ? pdf : 0;
}

static void xf_destroy(COBJECT *obj)
{
    xf_shape *sh = obj->shape;
    cobject_free(sh->inner);
}

/* The inner object's normal change at the hit mapped back to object
 * space (point by M^-1, normal by M^T, step by M^-1's linear part), and
 * the world normal's M^-T dn_o through shape_normal_change(), which
 * accounts for the renormalisation. */
static void xf_normal_change(const COBJECT *obj, const PATHPOINT *pp,
                             const VECTOR3 dp, VECTOR3 dn)
{
    const xf_shape *sh = obj->shape;
    vec_set(dn, 0, 0, 0);
    if (!sh->inner->ops->normal_change)
        return;
    PATHPOINT po = *pp;
    VECTOR3 dpo, no, g, dg, dno;
    apply(MAT(sh->x.inv), po.cross_point, pp->cross_point, true);
    apply(MAT(sh->x.inv), dpo, dp, false);
    for (int j = 0; j < 3; j++)
        no[j] = sh->x.m[0][j] * pp->n[X] + sh->x.m[1][j] * pp->n[Y] +
                sh->x.m[2][j] * pp->n[Z];
    if (vec_normalize(po.n, no) == 0)
        return;
    sh->inner->ops->normal_change(sh->inner, &po, dpo, dno);
    xform_normal(&sh->x, g, po.n);
    xform_normal(&sh->x, dg, dno);
    shape_normal_change(g, dg, pp->n, dn);
}

static const cobject_ops xform_ops = {
    "xform", xf_intersect, xf_surface, xf_bounds, xf_area, xf_sample,
    xf_destroy, xf_normal_change
};

const xform_t *xform_of(const COBJECT *obj)
{
    if (!obj || obj->ops != &xform_ops)
        return NULL;
    return &((const xf_shape *)obj->shape)->x;
}

#ifndef SVET_SIMD
/* Without the speed layer there is no culling sphere and no shortcut for
 * a box's slabs: brute force (accel.c) tests each object through its
 * intersect(). */
bool xform_culling_sphere(const COBJECT *obj, xform_sphere_t *s)
{
    (void)obj;
    (void)s;
    return false;
}

bool xform_intersect_unculled(const COBJECT *obj, int prim, const ray_t *r,
                              real tmin, real tmax, hit_t *hit)
{
    return xform_intersect_plain(obj, prim, r, tmin, tmax, hit);
}

bool xform_intersect_unseparated(const COBJECT *obj, int prim,
                                 const ray_t *r, real tmin, real tmax,
                                 hit_t *hit)
{
    return xform_intersect_plain(obj, prim, r, tmin, tmax, hit);
}
#endif

/* --- the area under the map ------------------------------------------------ */

/* J(n) = |det M| |M^-T n| for a unit object normal n (Nanson's formula) */
static ld area_scale(const xf_shape *sh, const VECTOR3 n)
{
    VECTOR3 w;
    xform_normal(&sh->x, w, n);
    return (ld)sh->absdet * (ld)vec_length(w);
}

/* M^T M = s^2 I to rounding: then J(n) = s^2 for every n */
static bool is_similarity(const real *m)
{
    ld g[3][3], tr = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            g[i][j] = 0;
            for (int k = 0; k < 3; k++)
                g[i][j] += (ld)AT(m, k, i) * (ld)AT(m, k, j);
        }
    tr = (g[0][0] + g[1][1] + g[2][2]) / 3;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (fabsl(g[i][j] - (i == j ? tr : 0)) > 64 * (ld)REAL_EPSILON * tr)
                return false;
    return true;
}

/* Nodes x and weights w of the n-point Gauss-Legendre rule on [-1, 1]:
 * the roots of P_n by Newton's iteration from Tricomi's initial guesses
 * cos(pi (i - 1/4) / (n + 1/2)) (Numerical Recipes, 3rd ed., sec. 4.6). */
static void gauss_legendre(int n, double *x, double *w)
{
    const double pi = 3.14159265358979323846;
    for (int i = 0; i < n; i++) {
        double z = cos(pi * (i + 0.75) / (n + 0.5)), dp = 1;
        for (int it = 0; it < 100; it++) {
            double p0 = 1, p1 = z;
            for (int k = 2; k <= n; k++) {
                double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (z * p1 - p0) / (z * z - 1);
            double dz = p1 / dp;
            z -= dz;
            if (fabs(dz) < 1e-15)
                break;
        }
        x[i] = z;
        w[i] = 2 / ((1 - z * z) * dp * dp);
    }
}

/* The world area as the integral over u in [0,1)^2 of J(n(u)) / pdf(u):
 * pdf(u) du is the object's area element. Composite Gauss-Legendre, 16
 * panels of 16 points per axis (65536 samples of inner): for a sphere
 * under axis ratios up to 6 this is exact to double rounding, 4e-8 at a
 * ratio of 20, where J's nearest singularity crowds the poles. */
#define QUAD_PANELS 16
#define QUAD_POINTS 16
static real quadrature_area(const xf_shape *sh)
{
    double xi[QUAD_POINTS], wi[QUAD_POINTS];
    gauss_legendre(QUAD_POINTS, xi, wi);
    const double h = 1.0 / QUAD_PANELS;
    ld sum = 0;
    for (int a = 0; a < QUAD_PANELS; a++)
        for (int i = 0; i < QUAD_POINTS; i++)
            for (int b = 0; b < QUAD_PANELS; b++)
                for (int j = 0; j < QUAD_POINTS; j++) {
                    real u[2] = { (real)(h * (a + 0.5 * (1 + xi[i]))),
                                  (real)(h * (b + 0.5 * (1 + xi[j]))) };
                    cobject_sample_t s;
                    sh->inner->ops->sample(sh->inner, u, &s);
                    if (!(s.pdf > 0))
                        continue;
                    sum += (ld)(wi[i] * wi[j] * 0.25 * h * h) *
                           area_scale(sh, s.n) / (ld)s.pdf;
                }
    return (real)sum;
}

static real transformed_area(const xf_shape *sh)
{
    const COBJECT *in = sh->inner;
    real a = in->ops->area(in);
    if (!isfinite(a))
        return (real)INFINITY;
    if (a == 0)
        return 0;
    const char *name = in->ops->name;
    VECTOR3 z = { 0, 0, 1 };
    if (is_similarity(MAT(sh->x.m)))
        return (real)(area_scale(sh, z) * (ld)a);
    if (!strcmp(name, "triangle") || !strcmp(name, "parallelogram") ||
        !strcmp(name, "disk")) {
        real u[2] = { REAL_C(0.5), REAL_C(0.5) };
        cobject_sample_t s;
        in->ops->sample(in, u, &s);
        return (real)(area_scale(sh, s.n) * (ld)a);
    }
    if (!strcmp(name, "box")) {
        bbox_t b;
        in->ops->bounds(in, -1, &b);
        ld sum = 0;
        for (int k = 0; k < 3; k++) {
            VECTOR3 n = { 0, 0, 0 };
            n[k] = 1;
            ld fa = ((ld)b.max[(k + 1) % 3] - (ld)b.min[(k + 1) % 3]) *
                    ((ld)b.max[(k + 2) % 3] - (ld)b.min[(k + 2) % 3]);
            sum += 2 * fa * area_scale(sh, n);
        }
        return (real)sum;
    }
    return quadrature_area(sh);
}

/* --- construction ------------------------------------------------------------ */

static svet_status check(const xform_t *x, svet_error *err)
{
    if (!x->valid)
        return svet_error_set(err, SVET_ERR_RANGE, "xform: the transform "
                              "has no inverse (a zero scale, a zero axis or "
                              "a NaN made it)");
    if (!all_finite(MAT(x->m)) || !all_finite(MAT(x->inv)))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "xform: the transform is not finite");
    bool regular;
    ld d = det3(MAT(x->m), &regular);
    if (!regular)
        return svet_error_set(err, SVET_ERR_RANGE, "xform: the matrix is "
                              "singular to working precision (det %Lg)", d);
    /* inv must be m's inverse to within the rounding of both: each entry
     * of M inv - I below 64 epsilon |row i of M|_1 |column j of inv|_1
     * (the rounded factors of a composition are inverse to one another
     * only to that order) */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++) {
            ld s = j == 3 ? (ld)x->m[i][3] : 0, row = 0, col = 0;
            for (int k = 0; k < 3; k++) {
                s += (ld)x->m[i][k] * (ld)x->inv[k][j];
                row += fabsl((ld)x->m[i][k]);
                col += fabsl((ld)x->inv[k][j]);
            }
            if (j == i)
                s -= 1;
            ld mag = row * col + (j == 3 ? fabsl((ld)x->m[i][3]) : 0);
            if (fabsl(s) > 64 * (ld)REAL_EPSILON * mag)
                return svet_error_set(err, SVET_ERR_RANGE, "xform: inv is "
                                      "not the inverse of m (entry %d,%d of "
                                      "m inv - I is %Lg)", i, j, s);
        }
    return SVET_OK;
}

COBJECT *xform_new(COBJECT *inner, const xform_t *to_world, svet_error *err)
{
    if (!inner) {
        if (!err || err->status == SVET_OK)
            svet_error_set(err, SVET_ERR_RANGE, "xform: no object to place");
        return NULL;
    }
    if (check(to_world, err) != SVET_OK) {
        cobject_free(inner);
        return NULL;
    }
    xform_t x = *to_world;
    if (inner->ops == &xform_ops) {
        /* merge: one matrix, one object */
        xf_shape *ish = inner->shape;
        x = xform_compose(ish->x, x);
        COBJECT *core = ish->inner;
        ish->inner = NULL;
        cobject_free(inner);
        inner = core;
        if (check(&x, err) != SVET_OK) {
            cobject_free(inner);
            return NULL;
        }
    }
    COBJECT *obj = shape_alloc(&xform_ops, sizeof(xf_shape), err);
    if (!obj) {
        cobject_free(inner);
        return NULL;
    }
    xf_shape *sh = obj->shape;
    sh->inner = inner;
    sh->x = x;
    bool regular;
    sh->absdet = (real)fabsl(det3(MAT(x.m), &regular));
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            sh->abs_m[i][j] = fabs(x.m[i][j]);
        sh->g_m3[i] = ray_gamma(4) * fabs(x.m[i][3]);
        for (int j = 0; j < 4; j++)
            sh->g_inv[i][j] = ray_gamma(4) * fabs(x.inv[i][j]);
    }
    sh->area = transformed_area(sh);
#ifdef SVET_SIMD
    xform_cull_init(sh);
#endif
    obj->nprims = inner->nprims;
    /* the world point and frame are written from the inner surface()'s
     * (surface_point(), then surface_frame() or the face table) */
    obj->surface_fills = inner->surface_fills;
    return obj;
}
