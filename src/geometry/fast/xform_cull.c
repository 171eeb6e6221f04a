/*
 * xform_cull.c - speed layer of xform.c (SIMD=on). It adds, with the same
 * answers bit for bit: a padded sphere around a transformed box that
 * turns most rays away before they are mapped to object space (with its
 * proof); for a box, the slabs its object-space ray starts beyond and
 * leaves, answered by six comparisons before the box's own test; a table
 * of the world frames of a box's six faces, made once; and the matrix
 * rows of a ray's and a hit's mapping in four SSE lanes (float).
 * Tests: tests/geometry/test_xform.c (against xform_intersect_plain and
 * xform_surface_generic, and the box hit by hand in object space)
 */
#include "geometry/xform.h"
#include "geometry/shape.h"
#include "../xform_shape.h"
#include "core/simd.h"

#include <stddef.h>
#include <string.h>

typedef long double ld;

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
        return xform_object_ray(sh, r, &rs->r, k);
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
    return xform_object_ray(sh, r, &rs->r, k);
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
    return xform_intersect_object(sh, prim, &ro.r, k, tmin, tmax, hit);
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

bool xform_cull_intersect(const COBJECT *obj, int prim, const ray_t *r,
                          real tmin, real tmax, hit_t *hit)
{
    const xf_shape *sh = obj->shape;
    if (sh->cull && tmin >= 0 && xform_sphere_misses(&sh->sphere, r))
        return false;
    return xform_intersect_unculled(obj, prim, r, tmin, tmax, hit);
}

#if defined(SIMD_REAL) && !defined(SVET_DOUBLE)
/* world_point() with SSE, lane i for row i: every lane the operations of
 * apply(), point_error_row(), back_row() and widen_row() for its row,
 * in their order (a product's factors in either order give the same
 * bits; fabs as the sign bit cleared), on the shape's columns, so the
 * same bits (tests/geometry/test_xform.c compares surface(), which uses this,
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
    xform_world_point(sh, p, e, out, out_e);
}
#endif

void xform_cull_surface(const COBJECT *obj, const ray_t *r, const hit_t *hit,
                        PATHPOINT *pp)
{
    const xf_shape *sh = obj->shape;
    xform_surface_object(sh, r, hit, pp);
    VECTOR3 p, e;
    world_point_v(sh, pp->cross_point, pp->p_error, p, e);
    vec_copy(pp->cross_point, p);
    vec_copy(pp->p_error, e);
    if (pp->prim >= 0 && pp->prim < sh->nfaces) {
        /* a box's face: its world frame as xform_surface_frame() made it */
        int f = pp->prim;
        vec_copy(pp->ng, sh->face[f].ng);
        vec_copy(pp->n, sh->face[f].n);
        vec_copy(pp->u, sh->face[f].u);
        vec_copy(pp->v, sh->face[f].v);
        vec_copy(pp->dpds, sh->face[f].dpds);
        vec_copy(pp->dpdt, sh->face[f].dpdt);
        return;
    }
    xform_surface_frame(sh, pp);
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
        xform_surface_frame(sh, &pp);
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

/* The constants above, once per object (xform.c's xform_new() calls this
 * last): the matrices by column for the SSE lanes, the culling sphere and
 * the face table. */
void xform_cull_init(xf_shape *sh)
{
    const xform_t *x = &sh->x;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++)
            sh->inv_col[j][i] = x->inv[i][j];
    for (int j = 0; j < 4; j++)
        sh->inv_col[j][3] = 0;
    for (int i = 0; i < 4; i++) {
        for (int j = 0; j < 4; j++) {
            sh->m_col[j][i] = i < 3 ? x->m[i][j] : 0;
            sh->g_inv_col[j][i] = i < 3 ? sh->g_inv[i][j] : 0;
        }
        for (int j = 0; j < 3; j++)
            sh->abs_col[j][i] = i < 3 ? sh->abs_m[i][j] : 0;
        sh->g_m3_4[i] = i < 3 ? sh->g_m3[i] : 0;
    }
    set_culling(sh);
    set_faces(sh);
}
