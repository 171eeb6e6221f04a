/*
 * xform.h - affine transforms (scale, Rodrigues rotation of app. C,
 * translation) and any primitive of app. D under one, as a COBJECT: an
 * oriented box or an ellipsoid is one line. Rays go to object space (t is
 * unchanged by an affine map), hits come back with their error bounds
 * grown as pbrt-v3 sec. 3.9.4 derives, normals by the inverse transpose.
 * Tests: tests/geometry/test_xform.c; vectors: tests/vectors/xform.csv
 */
#ifndef SVET_XFORM_H
#define SVET_XFORM_H

#include <stdbool.h>
#include "materials/cobject.h"
#include "core/error.h"

/* p_world = M p + m[.][3] for m = [M | translation], and inv the same for
 * the inverse map. Every constructor below fills both, the inverse from
 * the inverse of each factor, so no matrix is ever inverted numerically
 * except by xform_invert and xform_from_matrix. */
typedef struct {
    real m[3][4];   /* object to world: rows of [M | t] */
    real inv[3][4]; /* world to object */
    bool valid;     /* false for a transform that has no inverse (a zero
                       scale factor, a zero rotation axis, a NaN or
                       infinite input, or a composition with one): inv is
                       then all zeros, and xform_new and xform_invert
                       refuse it */
} xform_t;

/* The identity. */
xform_t xform_identity(void);

/* p + t. valid only when t is finite. */
xform_t xform_translate(const VECTOR3 t);

/* (s_x p_x, s_y p_y, s_z p_z): non-uniform scaling; a negative factor
 * mirrors. valid only when every factor is finite and nonzero. */
xform_t xform_scale(const VECTOR3 s);

/* Rotation by `degrees` about `axis` (any nonzero length), counter-
 * clockwise seen from the tip of the axis, by Rodrigues' formula (app. C)
 * in matrix form R = cos(a) I + sin(a) [k]x + (1 - cos(a)) k k^T. Angles
 * that are multiples of 90 degrees use exact cosines and sines, so such a
 * rotation permutes axes exactly. The inverse is R's transpose. valid only
 * for a finite angle and a nonzero finite axis. */
xform_t xform_rotate(const VECTOR3 axis, real degrees);

/* The transform that applies `first`, then `then`: matrices
 * M = M_then M_first, so a chain reads in the order it acts:
 *     xform_compose(xform_compose(xform_scale(s), xform_rotate(y, -17)),
 *                   xform_translate(t))
 * scales, then rotates, then translates (the Cornell box's small block).
 * Products are accumulated in long double and rounded once. */
xform_t xform_compose(xform_t first, xform_t then);

/* The inverse of a: its matrix is inverted afresh (cofactors in long
 * double), and a's matrix becomes the inverse's inverse. Returns SVET_OK,
 * or SVET_ERR_RANGE when a is not valid, not finite, or singular to
 * working precision (|det M| below 64 epsilon times the product of the
 * lengths of M's columns, Hadamard's bound); *out is then unchanged. */
svet_status xform_invert(const xform_t *a, xform_t *out, svet_error *err);

/* A transform from the matrix [M | t] given as its three rows of four,
 * m[4 i + j] = row i, column j; its inverse computed as xform_invert does.
 * Fails as xform_invert does. */
svet_status xform_from_matrix(const real m[12], xform_t *out,
                              svet_error *err);

/* Apply x: out = M p + t (a point), M v (a vector), or M^-T n (a normal,
 * not normalised: normals stay perpendicular to transformed tangents
 * under non-uniform scaling). out may alias the input. These functions
 * can't fail. */
void xform_point(const xform_t *x, VECTOR3 out, const VECTOR3 p);
void xform_vector(const xform_t *x, VECTOR3 out, const VECTOR3 v);
void xform_normal(const xform_t *x, VECTOR3 out, const VECTOR3 n);

/* The primitive `inner` placed in the world by to_world. Takes ownership
 * of inner: cobject_free() of the result frees it, and so does a failing
 * xform_new. inner may be NULL, so that a failed constructor can be
 * passed straight in, xform_new(box_new(lo, hi, &err), &x, &err): the
 * result is then NULL and err keeps the inner constructor's message. An
 * inner xform is merged into this one (one matrix, one object).
 *
 * The object keeps inner's sub-primitives (nprims) and its surface
 * parameters st and prim; ng and n are inner's normals mapped by M^-T,
 * dP/ds and dP/dt by M, and u, v are rebuilt from them. Attach materials
 * and lights to the returned object.
 *
 * area(): the local area scale of an affine map at a point of normal n is
 * J(n) = |det M| |M^-T n| (Nanson's formula). It is constant for a
 * similarity (rotation and uniform scale), and constant per face of a
 * flat shape, so the area is exact (to rounding) for every shape under a
 * similarity, for shapes with one normal ("triangle", "parallelogram",
 * "disk") and for a "box" (six faces from its bounds) under any map, and
 * infinite for a "plane". A curved shape under a non-uniform map (an
 * ellipsoid) has no closed form: the area is computed once here by
 * quadrature over inner's sampler, the integral over u in [0,1)^2 of
 * J(n(u)) / pdf(u), by composite Gauss-Legendre with 16 panels of 16
 * points per axis (65536 samples): exact to double rounding for a sphere
 * under axis ratios up to 6 (4e-8 relative at 20), to O(1/16) of a seam's
 * share where the sampler jumps between parts (a capped cylinder's rim).
 *
 * sample(): a sample of inner carried to the world, with the exact pdf
 * inner_pdf / J(n_inner). That is 1/area, uniform, exactly when J is the
 * same over the surface (the exact cases above, the box only if its three
 * face orientations scale alike); otherwise it is the correct density of a
 * non-uniform sampler.
 *
 * Returns NULL with SVET_ERR_RANGE when to_world is not valid, not finite,
 * singular, or its inv is not its inverse; NULL with SVET_ERR_NOMEM when
 * memory runs out. */
COBJECT *xform_new(COBJECT *inner, const xform_t *to_world, svet_error *err);

/* The transform of an object made by xform_new, or NULL for any other. */
const xform_t *xform_of(const COBJECT *obj);

/* --- the culling sphere, for brute force (accel.c) ----------------------- */

/* A sphere around a transformed box, padded for rounding (fast/xform_cull.c
 * proves the pad): a ray that stays outside it over t >= 0 cannot be
 * reported as a hit. pad = pad0 + pad_o max|o| + pad_oc |c - o|_1. */
typedef struct {
    VECTOR3 centre;
    real radius;
    real pad0, pad_o, pad_oc;
} xform_sphere_t;

/* True, with the sphere in *s, when obj comes from xform_new and its
 * intersect() starts with that sphere (transformed boxes, unless the
 * transform is extreme); false otherwise, and always without the speed
 * layer (SIMD=off), whose sphere it is (src/geometry/fast/xform_cull.c).
 * This function can't fail. */
bool xform_culling_sphere(const COBJECT *obj, xform_sphere_t *s);

/* What xform_sphere_misses() reads of the ray alone, the same for every
 * sphere: max|o|, d . d and max|d|, made by xform_sphere_ray(), which
 * can't fail. */
typedef struct {
    real o_max, dd, d_max;
} xform_sphere_ray_t;

static inline void xform_sphere_ray(const ray_t *r, xform_sphere_ray_t *rs)
{
    rs->o_max = real_max(fabs(r->o[X]),
                         real_max(fabs(r->o[Y]), fabs(r->o[Z])));
    rs->dd = SVECTOR3(r->d, r->d);
    rs->d_max = real_max(fabs(r->d[X]),
                         real_max(fabs(r->d[Y]), fabs(r->d[Z])));
}

/* xform_sphere_misses() with rs = xform_sphere_ray(r) made once for
 * many spheres: the same answer. This function can't fail. */
static inline bool xform_sphere_misses_ray(const xform_sphere_t *sh,
                                           const ray_t *r,
                                           const xform_sphere_ray_t *rs)
{
    VECTOR3 oc;
    vec_sub(oc, sh->centre, r->o);
    real oc1 = fabs(oc[X]) + fabs(oc[Y]) + fabs(oc[Z]);
    real rho = sh->radius +
               (sh->pad0 + sh->pad_o * rs->o_max + sh->pad_oc * oc1);
    real rho2 = rho * rho;
    real c2 = SVECTOR3(oc, oc), b = SVECTOR3(oc, r->d);
    real dd = rs->dd;
    const real u = REAL_UNIT_ROUNDOFF;
    /* the distance of the line from the centre, squared, times dd */
    if (c2 * dd - b * b > (rho2 + 32 * u * c2) * dd)
        return true;
    return b + 4 * u * oc1 * rs->d_max <= 0 && c2 > rho2 * (1 + 8 * u);
}

/* The test that intersect() makes first, for tmin >= 0: true when the
 * ray (over t >= 0) stays outside the culling sphere: its
 * line passes the centre farther than the radius, or it starts outside
 * the sphere and moves away from the centre. Evaluated with margins for
 * its own rounding (the squares carry gamma(3), the difference of
 * c2 dd and b^2 cancels down to what 32 u c2 dd covers, b carries
 * gamma(3) |c - o|_1 max|d|). A NaN makes every comparison false: no
 * early answer. Inline: brute force makes it for every ray. This function
 * can't fail. */
static inline bool xform_sphere_misses(const xform_sphere_t *sh,
                                       const ray_t *r)
{
    xform_sphere_ray_t rs;
    xform_sphere_ray(r, &rs);
    return xform_sphere_misses_ray(sh, r, &rs);
}

/* The intersect() of an object from xform_new without the sphere test:
 * the same answer and hit, bit for bit, whenever the test lets the ray
 * through (without the speed layer, xform_intersect_plain). This function
 * can't fail. */
bool xform_intersect_unculled(const COBJECT *obj, int prim, const ray_t *r,
                              real tmin, real tmax, hit_t *hit);

/* xform_intersect_unculled() without its shortcut for a box's slab that
 * the ray starts beyond and moves away from (leaves_box() in
 * fast/xform_cull.c):
 * the same answers, bit for bit. Test hook: tests/geometry/test_xform.c compares
 * the two. This function can't fail. */
bool xform_intersect_unseparated(const COBJECT *obj, int prim,
                                 const ray_t *r, real tmin, real tmax,
                                 hit_t *hit);

/* The surface() of an object from xform_new the general way, the plain
 * algorithm: the inner primitive's normals, derivatives and frame mapped
 * to the world at every hit. surface() gives the same bits; with the
 * speed layer, for a box it takes them from a table made once per face. Test hook: tests/geometry/test_xform.c compares the
 * two. This function can't fail. */
void xform_surface_generic(const COBJECT *obj, const ray_t *r,
                           const hit_t *hit, PATHPOINT *pp);

/* The plain algorithm, what SIMD=off builds run: the ray mapped to
 * object space by the inverse's rows and the inner primitive's own test,
 * with no culling sphere and no shortcut. Test hook: intersect() gives
 * the same answer and hit bytes (tests/geometry/test_xform.c). This
 * function can't fail. */
bool xform_intersect_plain(const COBJECT *obj, int prim, const ray_t *r,
                           real tmin, real tmax, hit_t *hit);

#endif
