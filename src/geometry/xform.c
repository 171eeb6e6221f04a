/*
 * xform.c - affine transforms and primitives under them (app. D): rotation
 * by Rodrigues' formula (app. C), rays to object space, hit points back to
 * the world with the error bounds of pbrt-v3 sec. 3.9.4, normals by the
 * inverse transpose, areas by Nanson's formula or quadrature.
 * Tests: tests/geometry/test_xform.c; vectors: tests/vectors/xform.csv
 */
#include "geometry/xform.h"
#include "geometry/shape.h"
#include "core/simd.h"

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

/* Matrices [M | t] travel as pointers to their 12 entries, row by row
 * (C11 will not pass a real[3][4] where a const one is expected). */
#define AT(m, i, j) ((m)[4 * (i) + (j)])
#define MAT(a) (&(a)[0][0])

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

typedef struct {
    COBJECT *inner;
    xform_t x;
    real absdet; /* |det M| */
    real area;
    /* A sphere in the world around a transformed box, padded so that a ray
     * that passes outside it cannot be reported as a hit (sphere_pad()):
     * most rays are turned away by it before they are mapped to object
     * space. cull is false for other primitives and extreme transforms. */
    bool cull;
    xform_sphere_t sphere;
    /* world_point()'s constants, each the very product it would compute:
     * |m_ij|, gamma(4) |m_i3| and gamma(4) |inv_ij| */
    real abs_m[3][3], g_m3[3], g_inv[3][4];
    /* For a box, what xf_surface() computes from the fields of a hit that
     * depend on its face alone (pp->prim), computed once per face by the
     * very same calls (set_faces()); nfaces is 0 for other primitives. */
    int nfaces;
    struct {
        VECTOR3 ng, n, u, v, dpds, dpdt;
    } face[6];
    /* the box's own bounds (its bounds(), the min and max its intersect()
     * tests against), for leaves_box(); set with the face table */
    VECTOR3 box_min, box_max;
    /* the same for vectors of four lanes (x, y, z and one that never
     * answers: -inf, +inf), and the columns of inv, col[j][i] = inv[i][j]
     * with a zero fourth lane (object_ray() with SSE) */
    real box_lo4[4], box_hi4[4];
    real inv_col[4][4];
    /* world_point()'s numbers by column, lane i for row i (zero in lane
     * 3): m's columns, |m_ij|'s, gamma(4) |m_i3| and gamma(4) |inv_ij|'s
     * (world_point_v()) */
    real m_col[4][4], abs_col[3][4], g_m3_4[4], g_inv_col[4][4];
} xf_shape;

static const cobject_ops xform_ops;

/* The ray in object space. Its direction is first scaled by 2^-k (exact)
 * when its largest component is far from 1, so that M^-1 d neither
 * underflows nor overflows; then t_object = t_world 2^k. Returns false
 * when the object-space direction is zero or not finite. */
/* object_ray() for a direction whose largest component m lies outside
 * [2^-16, 2^17): the rare case, a function of its own, so that the
 * usual one (inline) saves no registers. */
static bool
object_ray_scaled(const xf_shape *sh, const ray_t *r, real m, ray_t *ro,
                  int *k)
{
    VECTOR3 d;
    *k = 0;
    if (m > 0 && isfinite(m))
        *k = real_ilogb(m);
    if (*k)
        for (int i = 0; i < 3; i++)
            d[i] = real_ldexp(r->d[i], -*k);
    else
        vec_copy(d, r->d);
    apply(MAT(sh->x.inv), ro->o, r->o, true);
    apply(MAT(sh->x.inv), ro->d, d, false);
    return vec_is_finite(ro->o) && vec_is_finite(ro->d) &&
           (ro->d[X] != 0 || ro->d[Y] != 0 || ro->d[Z] != 0);
}

/* An object-space ray in eight reals (o, d and two spare), so that
 * object_ray() may store vectors of four into it. */
typedef union {
    ray_t r;
    real v[8];
} ray_slots;
_Static_assert(sizeof(ray_t) == 6 * sizeof(real) &&
               offsetof(ray_t, d) == 3 * sizeof(real),
               "ray_t: o and d without padding");

static inline bool object_ray(const xf_shape *sh, const ray_t *r,
                              ray_slots *rs, int *k)
{
    /* no libm in this inner loop: plain comparisons for the max (a NaN
     * component makes ro->d NaN below whatever m is), and ilogb only for
     * m outside [2^-16, 2^17), where ilogb(m) leaves [-16, 16] */
    real m = real_max(fabs(r->d[X]), real_max(fabs(r->d[Y]), fabs(r->d[Z])));
    if (!(m >= REAL_C(0x1p-16) && m < REAL_C(0x1p17))) {
        rs->v[6] = rs->v[7] = 0; /* leaves_box()'s fourth lane reads v[6] */
        return object_ray_scaled(sh, r, m, &rs->r, k);
    }
    *k = 0;
#if defined(SIMD_REAL) && !defined(SVET_DOUBLE)
    /* apply() with SSE, lane i for row i: the columns of inv times the
     * coordinates, summed in row()'s order, the vector's + 0 kept (it
     * makes a -0 +0), so every lane has row()'s bits; lane 3 is 0. Then
     * the tests below on the lanes: all of o and d finite (each lane of
     * (o - o) + (d - d) is 0 exactly when both are), d not zero. */
    const __m128 c0 = _mm_loadu_ps(sh->inv_col[0]),
                 c1 = _mm_loadu_ps(sh->inv_col[1]),
                 c2 = _mm_loadu_ps(sh->inv_col[2]);
    const __m128 zero = _mm_setzero_ps();
    __m128 o = _mm_add_ps(
        _mm_add_ps(_mm_add_ps(_mm_mul_ps(c0, _mm_set1_ps(r->o[X])),
                              _mm_mul_ps(c1, _mm_set1_ps(r->o[Y]))),
                   _mm_mul_ps(c2, _mm_set1_ps(r->o[Z]))),
        _mm_loadu_ps(sh->inv_col[3]));
    __m128 d = _mm_add_ps(
        _mm_add_ps(_mm_add_ps(_mm_mul_ps(c0, _mm_set1_ps(r->d[X])),
                              _mm_mul_ps(c1, _mm_set1_ps(r->d[Y]))),
                   _mm_mul_ps(c2, _mm_set1_ps(r->d[Z]))),
        zero);
    _mm_storeu_ps(rs->v, o);
    _mm_storeu_ps(rs->v + 3, d); /* over o's lane 3 */
    __m128 f = _mm_add_ps(_mm_sub_ps(o, o), _mm_sub_ps(d, d));
    return _mm_movemask_ps(_mm_cmpeq_ps(f, zero)) == 15 &&
           (_mm_movemask_ps(_mm_cmpneq_ps(d, zero)) & 7) != 0;
#else
    ray_t *ro = &rs->r;
    apply(MAT(sh->x.inv), ro->o, r->o, true);
    apply(MAT(sh->x.inv), ro->d, r->d, false);
    /* finite: x - x is 0 for a finite x, NaN otherwise (vec_is_finite's
     * answer without a branch per coordinate) */
    real f = ((ro->o[X] - ro->o[X]) + (ro->o[Y] - ro->o[Y])) +
             ((ro->o[Z] - ro->o[Z]) + (ro->d[X] - ro->d[X])) +
             ((ro->d[Y] - ro->d[Y]) + (ro->d[Z] - ro->d[Z]));
    return f == 0 && (ro->d[X] != 0 || ro->d[Y] != 0 || ro->d[Z] != 0);
#endif
}

/* True when the object-space ray ro of a transformed box (sh->nfaces = 6)
 * starts beyond one of the box's slabs and does not move back toward it:
 * then box.c's intersect() on this very ray reports no hit for tmin >= 0.
 * The argument needs no rounding bound, for it looks at the numbers that
 * intersect() sees: with o_k > max_k and d_k > 0, its slab's exit
 * t1 = (max_k - o_k) / d_k is a negative number (a difference of two
 * distinct floats is not 0) over a positive one, so <= 0, and its push
 * t1 + 2 gamma(3) |t1| stays <= 0 (2 gamma(3) < 1; a -0 becomes +0): the
 * exit hi <= 0, and a hit needs the entry lo <= hi or hi itself in
 * (tmin, tmax) with tmin >= 0. With d_k = 0 its slab() answers "never"
 * (o_k outside the slab). The same with o_k < min_k and d_k <= 0. This
 * turns away a ray that leaves the box from its surface (the origin
 * spawned outside the face, the direction outward), which always passes
 * the culling sphere, and many that pass beside it, for the price of six
 * comparisons instead of the six divisions of the slab test.
 * tests/geometry/test_xform.c compares with xform_intersect_unseparated(). */
static inline bool leaves_box(const xf_shape *sh, const ray_slots *rs)
{
#if defined(SIMD_REAL) && !defined(SVET_DOUBLE)
    /* the six comparisons as four lanes: o (and d_x, which the fourth
     * lane's infinite bounds turn away) against the bounds, d's sign */
    const __m128 o = _mm_loadu_ps(rs->v), d = _mm_loadu_ps(rs->v + 3);
    const __m128 zero = _mm_setzero_ps();
    __m128 beyond = _mm_or_ps(
        _mm_and_ps(_mm_cmpgt_ps(o, _mm_loadu_ps(sh->box_hi4)),
                   _mm_cmpge_ps(d, zero)),
        _mm_and_ps(_mm_cmplt_ps(o, _mm_loadu_ps(sh->box_lo4)),
                   _mm_cmple_ps(d, zero)));
    return _mm_movemask_ps(beyond) != 0;
#else
    const ray_t *ro = &rs->r;
    return (ro->o[X] > sh->box_max[X] && ro->d[X] >= 0) ||
           (ro->o[X] < sh->box_min[X] && ro->d[X] <= 0) ||
           (ro->o[Y] > sh->box_max[Y] && ro->d[Y] >= 0) ||
           (ro->o[Y] < sh->box_min[Y] && ro->d[Y] <= 0) ||
           (ro->o[Z] > sh->box_max[Z] && ro->d[Z] >= 0) ||
           (ro->o[Z] < sh->box_min[Z] && ro->d[Z] <= 0);
#endif
}

static inline bool intersect_unculled(const COBJECT *obj, int prim,
                                      const ray_t *r, real tmin, real tmax,
                                      hit_t *hit, bool separate)
{
    const xf_shape *sh = obj->shape;
    ray_slots ro;
    int k;
    if (!object_ray(sh, r, &ro, &k))
        return false;
    if (separate && sh->nfaces && tmin >= 0 && leaves_box(sh, &ro))
        return false;
    /* an affine map keeps t; only the power-of-two scaling of d moves it.
     * h zeroed: the inner primitive may leave part of its scratch b unset,
     * and the same ray must give the same bytes */
    hit_t h = { 0, 0, { 0, 0, 0 } };
    real lo = k ? ldexp(tmin, k) : tmin, hi = k ? ldexp(tmax, k) : tmax;
    if (!sh->inner->ops->intersect(sh->inner, prim, &ro.r, lo, hi, &h))
        return false;
    real t = k ? ldexp(h.t, -k) : h.t;
    if (!(t > tmin && t < tmax))
        return false;
    *hit = h;
    hit->t = t;
    return true;
}

bool xform_intersect_unculled(const COBJECT *obj, int prim, const ray_t *r,
                              real tmin, real tmax, hit_t *hit)
{
    return intersect_unculled(obj, prim, r, tmin, tmax, hit, true);
}

bool xform_intersect_unseparated(const COBJECT *obj, int prim,
                                 const ray_t *r, real tmin, real tmax,
                                 hit_t *hit)
{
    return intersect_unculled(obj, prim, r, tmin, tmax, hit, false);
}

static bool xf_intersect(const COBJECT *obj, int prim, const ray_t *r,
                         real tmin, real tmax, hit_t *hit)
{
    const xf_shape *sh = obj->shape;
    if (sh->cull && tmin >= 0 && xform_sphere_misses(&sh->sphere, r))
        return false;
    return xform_intersect_unculled(obj, prim, r, tmin, tmax, hit);
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
static void world_point(const xf_shape *sh, const VECTOR3 p, const VECTOR3 e,
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

#if defined(SIMD_REAL) && !defined(SVET_DOUBLE)
/* world_point() with SSE, lane i for row i: every lane the operations of
 * apply(), point_error_row(), back_row() and widen_row() for its row,
 * in their order (a product's factors in either order give the same
 * bits; fabs as the sign bit cleared), on the shape's columns, so the
 * same bits (tests/geometry/test_xform.c compares xf_surface(), which uses this,
 * with xform_surface_generic(), which uses world_point()). */
static inline void world_point_v(const xf_shape *sh, const VECTOR3 p,
                                 const VECTOR3 e, VECTOR3 out, VECTOR3 out_e)
{
    const real g = ray_gamma(4);
    const __m128 sign = _mm_set1_ps(-0.0f);
    const __m128 px = _mm_set1_ps(p[X]), py = _mm_set1_ps(p[Y]),
                 pz = _mm_set1_ps(p[Z]);
    const __m128 mx = _mm_mul_ps(_mm_loadu_ps(sh->m_col[0]), px),
                 my = _mm_mul_ps(_mm_loadu_ps(sh->m_col[1]), py),
                 mz = _mm_mul_ps(_mm_loadu_ps(sh->m_col[2]), pz);
    const __m128 o = _mm_add_ps(_mm_add_ps(_mm_add_ps(mx, my), mz),
                                _mm_loadu_ps(sh->m_col[3]));
    const __m128 a0 = _mm_loadu_ps(sh->abs_col[0]),
                 a1 = _mm_loadu_ps(sh->abs_col[1]),
                 a2 = _mm_loadu_ps(sh->abs_col[2]);
    const __m128 prop = _mm_add_ps(
        _mm_add_ps(_mm_mul_ps(a0, _mm_set1_ps(e[X])),
                   _mm_mul_ps(a1, _mm_set1_ps(e[Y]))),
        _mm_mul_ps(a2, _mm_set1_ps(e[Z])));
    const __m128 G = _mm_set1_ps(g);
    const __m128 err = _mm_add_ps(
        _mm_add_ps(
            _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_set1_ps(1 + g), prop),
                                  _mm_mul_ps(G, _mm_andnot_ps(sign, mx))),
                       _mm_mul_ps(G, _mm_andnot_ps(sign, my))),
            _mm_mul_ps(G, _mm_andnot_ps(sign, mz))),
        _mm_loadu_ps(sh->g_m3_4));
    const __m128 w = _mm_add_ps(_mm_andnot_ps(sign, o), err);
    const __m128 back = _mm_add_ps(
        _mm_add_ps(_mm_add_ps(_mm_loadu_ps(sh->g_inv_col[3]),
                              _mm_mul_ps(_mm_loadu_ps(sh->g_inv_col[0]),
                                         _mm_shuffle_ps(w, w, 0x00))),
                   _mm_mul_ps(_mm_loadu_ps(sh->g_inv_col[1]),
                              _mm_shuffle_ps(w, w, 0x55))),
        _mm_mul_ps(_mm_loadu_ps(sh->g_inv_col[2]),
                   _mm_shuffle_ps(w, w, 0xaa)));
    const __m128 oe = _mm_add_ps(
        _mm_add_ps(_mm_add_ps(err, _mm_mul_ps(a0, _mm_shuffle_ps(back, back,
                                                                 0x00))),
                   _mm_mul_ps(a1, _mm_shuffle_ps(back, back, 0x55))),
        _mm_mul_ps(a2, _mm_shuffle_ps(back, back, 0xaa)));
    real ro[4], re[4];
    _mm_storeu_ps(ro, o);
    _mm_storeu_ps(re, oe);
    vec_set(out, ro[0], ro[1], ro[2]);
    vec_set(out_e, re[0], re[1], re[2]);
}
#else
static inline void world_point_v(const xf_shape *sh, const VECTOR3 p,
                                 const VECTOR3 e, VECTOR3 out, VECTOR3 out_e)
{
    world_point(sh, p, e, out, out_e);
}
#endif

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

/* The inner primitive's surface() on the ray in object space, and the
 * point mapped back to the world. */
static inline void surface_point(const xf_shape *sh, const ray_t *r,
                                 const hit_t *hit, PATHPOINT *pp, bool vec)
{
    ray_slots ro;
    int k;
    object_ray(sh, r, &ro, &k);
    hit_t h = *hit;
    if (k != 0)
        h.t = ldexp(hit->t, k);
    sh->inner->ops->surface(sh->inner, &ro.r, &h, pp);
    VECTOR3 p, e;
    if (vec)
        world_point_v(sh, pp->cross_point, pp->p_error, p, e);
    else
        world_point(sh, pp->cross_point, pp->p_error, p, e);
    vec_copy(pp->cross_point, p);
    vec_copy(pp->p_error, e);
}

/* The normals, derivatives and frame of pp, in object space, mapped to
 * the world. */
static void surface_frame(const xf_shape *sh, PATHPOINT *pp)
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

void xform_surface_generic(const COBJECT *obj, const ray_t *r,
                           const hit_t *hit, PATHPOINT *pp)
{
    const xf_shape *sh = obj->shape;
    surface_point(sh, r, hit, pp, false);
    surface_frame(sh, pp);
}

static void xf_surface(const COBJECT *obj, const ray_t *r, const hit_t *hit,
                       PATHPOINT *pp)
{
    const xf_shape *sh = obj->shape;
    surface_point(sh, r, hit, pp, true);
    if (pp->prim >= 0 && pp->prim < sh->nfaces) {
        /* a box's face: its world frame as surface_frame() made it */
        int f = pp->prim;
        vec_copy(pp->ng, sh->face[f].ng);
        vec_copy(pp->n, sh->face[f].n);
        vec_copy(pp->u, sh->face[f].u);
        vec_copy(pp->v, sh->face[f].v);
        vec_copy(pp->dpds, sh->face[f].dpds);
        vec_copy(pp->dpdt, sh->face[f].dpdt);
        return;
    }
    surface_frame(sh, pp);
}

/* The face table of a transformed box (xf_shape.face): box.c's surface()
 * sets ng, n, u, v, dpds and dpdt from the face alone (the one in
 * hit->b[0], returned in pp->prim), so surface_frame() maps them to the
 * same bits at every hit on that face; here it runs once per face, on a
 * hit of that face from a ray at the origin. */
static void set_faces(xf_shape *sh)
{
    sh->nfaces = 0;
    if (strcmp(sh->inner->ops->name, "box") != 0)
        return;
    for (int f = 0; f < 6; f++) {
        ray_t r = { { 0, 0, 0 }, { 0, 0, 0 } };
        hit_t h = { 0, 0, { (real)f, 0, 0 } };
        PATHPOINT pp;
        memset(&pp, 0, sizeof pp);
        pp.prim = 0;
        sh->inner->ops->surface(sh->inner, &r, &h, &pp);
        if (pp.prim != f)
            return;
        surface_frame(sh, &pp);
        vec_copy(sh->face[f].ng, pp.ng);
        vec_copy(sh->face[f].n, pp.n);
        vec_copy(sh->face[f].u, pp.u);
        vec_copy(sh->face[f].v, pp.v);
        vec_copy(sh->face[f].dpds, pp.dpds);
        vec_copy(sh->face[f].dpdt, pp.dpdt);
    }
    bbox_t bb;
    sh->inner->ops->bounds(sh->inner, -1, &bb);
    vec_copy(sh->box_min, bb.min);
    vec_copy(sh->box_max, bb.max);
    for (int k = 0; k < 3; k++) {
        sh->box_lo4[k] = bb.min[k];
        sh->box_hi4[k] = bb.max[k];
    }
    sh->box_lo4[3] = -(real)INFINITY;
    sh->box_hi4[3] = (real)INFINITY;
    sh->nfaces = 6;
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
    world_point(sh, so.p, so.p_error, s->p, s->p_error);
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

static const cobject_ops xform_ops = {
    "xform", xf_intersect, xf_surface, xf_bounds, xf_area, xf_sample,
    xf_destroy
};

const xform_t *xform_of(const COBJECT *obj)
{
    if (!obj || obj->ops != &xform_ops)
        return NULL;
    return &((const xf_shape *)obj->shape)->x;
}

bool xform_culling_sphere(const COBJECT *obj, xform_sphere_t *s)
{
    if (!xform_of(obj))
        return false;
    const xf_shape *sh = obj->shape;
    if (!sh->cull)
        return false;
    *s = sh->sphere;
    return true;
}

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

/* --- the culling sphere ---------------------------------------------------- */

/* max row sum of |A| for the linear part of a 3x4 matrix, in long double */
static ld norm_inf(const real *a)
{
    ld n = 0;
    for (int i = 0; i < 3; i++) {
        ld row = fabsl((ld)AT(a, i, 0)) + fabsl((ld)AT(a, i, 1)) +
                 fabsl((ld)AT(a, i, 2));
        n = row > n ? row : n;
    }
    return n;
}

/* The sphere and its pad for a transformed box (sh->inner a "box").
 *   Why a ray that passes outside cannot be reported as a hit. Write W for
 * the exact map p -> M p + m, kappa = |M| |M^-1| (infinity norms).
 * xf_intersect maps the ray to o' = M^-1 o + t_inv and d' = M^-1 d 2^-k,
 * each rounded within gamma(4) (|M^-1| |.| + |t_inv|); the box reports t
 * only where the exact o' + t d' lies within gamma(9) (|o'| + |box|) of
 * the box on every axis (box.c: two roundings of each slab distance, the
 * exit pushed by 2 gamma(3) and rounded twice more). And M inv differs from I by what check()
 * allows, 64 epsilon |row|_1 |col|_1 per entry: at most 384 u kappa. Going
 * back through W, the world point o + t d then lies within
 *   E = K kappa (|o| + |m| + t |d|) + gamma(9) |M| |box|,  K = 512 u
 * (the sum of those terms, 400 u kappa, rounded up) of W(box), which lies
 * in the sphere of radius R about c (the transformed corners, in long
 * double, rounded up). A hit is near the sphere, so t |d| <= |c - o| + R
 * + sqrt(3) E; with K kappa <= 1/64 that gives the Euclidean pad
 *   sqrt(3) E <= 4 (K kappa (|m| + R + |c|) + gamma(9) |M| |box|)
 *                + 2 K kappa |o| + 2 K kappa |c - o|_1,
 * with factor 4 for the rounding of c, of R and of the pad itself. */
static void set_culling(xf_shape *sh)
{
    sh->cull = false;
    if (strcmp(sh->inner->ops->name, "box") != 0)
        return;
    bbox_t b;
    sh->inner->ops->bounds(sh->inner, -1, &b);
    const real *m = MAT(sh->x.m);
    ld kappa = norm_inf(m) * norm_inf(MAT(sh->x.inv));
    ld K = 512 * (ld)REAL_UNIT_ROUNDOFF;
    if (!(K * kappa <= 1.0L / 64) || !isfinite(kappa))
        return;
    ld c[3], r2 = 0, box = 0, mt = 0, cmax = 0;
    for (int i = 0; i < 3; i++) {
        c[i] = (ld)AT(m, i, 3);
        for (int j = 0; j < 3; j++)
            c[i] += (ld)AT(m, i, j) *
                    (0.5L * (ld)b.min[j] + 0.5L * (ld)b.max[j]);
        mt = fmaxl(mt, fabsl((ld)AT(m, i, 3)));
        box = fmaxl(box, fmaxl(fabsl((ld)b.min[i]), fabsl((ld)b.max[i])));
        cmax = fmaxl(cmax, fabsl(c[i]));
    }
    for (int corner = 0; corner < 8; corner++) {
        ld d2 = 0;
        for (int i = 0; i < 3; i++) {
            ld p = (ld)AT(m, i, 3);
            for (int j = 0; j < 3; j++)
                p += (ld)AT(m, i, j) *
                     ((corner >> j) & 1 ? (ld)b.max[j] : (ld)b.min[j]);
            d2 += (p - c[i]) * (p - c[i]);
        }
        r2 = fmaxl(r2, d2);
    }
    ld R = sqrtl(r2);
    ld pad0 = 4 * (K * kappa * (mt + R + cmax) +
                   (ld)ray_gamma(9) * norm_inf(m) * box);
    xform_sphere_t *s = &sh->sphere;
    for (int i = 0; i < 3; i++)
        s->centre[i] = (real)c[i];
    s->radius = real_next_up((real)R);
    s->pad0 = real_next_up((real)pad0);
    s->pad_o = s->pad_oc = real_next_up((real)(2 * K * kappa));
    sh->cull = vec_is_finite(s->centre) && isfinite(s->radius) &&
               isfinite(s->pad0) && isfinite(s->pad_o);
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
        for (int j = 0; j < 4; j++) {
            sh->g_inv[i][j] = ray_gamma(4) * fabs(x.inv[i][j]);
            sh->inv_col[j][i] = x.inv[i][j];
        }
    }
    for (int j = 0; j < 4; j++)
        sh->inv_col[j][3] = 0;
    for (int i = 0; i < 4; i++) {
        for (int j = 0; j < 4; j++) {
            sh->m_col[j][i] = i < 3 ? x.m[i][j] : 0;
            sh->g_inv_col[j][i] = i < 3 ? sh->g_inv[i][j] : 0;
        }
        for (int j = 0; j < 3; j++)
            sh->abs_col[j][i] = i < 3 ? sh->abs_m[i][j] : 0;
        sh->g_m3_4[i] = i < 3 ? sh->g_m3[i] : 0;
    }
    sh->area = transformed_area(sh);
    set_culling(sh);
    set_faces(sh);
    obj->nprims = inner->nprims;
    /* the world point and frame are written from the inner surface()'s
     * (surface_point(), then surface_frame() or the face table) */
    obj->surface_fills = inner->surface_fills;
    return obj;
}
