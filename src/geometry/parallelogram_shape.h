/*
 * parallelogram_shape.h - the parallelogram's shape as parallelogram.c
 * and its speed layer (fast/parallelogram_cull.c) share it; internal to
 * the two, not installed.
 * Tests: tests/geometry/test_parallelogram.c
 */
#ifndef SVET_PARALLELOGRAM_SHAPE_H
#define SVET_PARALLELOGRAM_SHAPE_H

#include "geometry/parallelogram.h"

#ifdef SVET_SIMD
/* What the early rejections below read of a parallelogram, side by side:
 * in the shape, and copied into a batch for brute force. */
typedef struct {
    VECTOR3 n;       /* unit e1 x e2, as in the shape */
    VECTOR3 c0;      /* corner c0 */
    real h_lo, h_hi; /* min and max of the computed n . c_i: the slab
                        h_lo <= n . p <= h_hi holds the parallelogram */
    real h_mid, h_half; /* its middle plane n . p = h_mid, half-width */
    real c_max;      /* max |c_i| over corners and axes */
    VECTOR3 a, b;    /* dual to e1, e2 in the plane: (p - c0) . a = s,
                        (p - c0) . b = t for p = c0 + s e1 + t e2 */
    real a1, b1;     /* |a|_1, |b|_1, rounded up */
    real k_area;     /* 2 / (the smaller of the two triangles' areas),
                        rounded up; infinite when that is not positive or
                        the quotient overflows (stays_before()) */
} para_cull_t;

#endif

typedef struct {
    VECTOR3 c[4];   /* corners c0 c1 c2 c3 */
    VECTOR3 e1, e2; /* c1 - c0, c3 - c0 */
    VECTOR3 n;      /* unit e1 x e2 */
    VECTOR3 u, v;   /* the frame of every point: shape_frame(n, e1) */
    real area;
#ifdef SVET_SIMD
    /* the speed layer's (parallelogram_cull_init()) */
    bool degenerate[2]; /* triangle_is_degenerate of A and B: never hit */
    real cs[3][4];  /* the corners by axis, cs[k][i] = c[i][k]: a vector
                       of the four along each axis (shear_corners()) */
    para_cull_t k;  /* what the early rejections read */
#endif
} para_shape;

/* (s, t) of a hit of triangle A or B from its barycentrics:
 * A: p = c0 + (b1 + b2) e1 + b2 e2; B: p = c0 + b1 e1 + (b1 + b2) e2. */
static inline void parallelogram_st_of(int tri, const real b[3], real st[2])
{
    st[0] = tri == 0 ? b[1] + b[2] : b[1];
    st[1] = tri == 0 ? b[2] : b[1] + b[2];
}

/* The hit at t, (s, t) = st clamped to [0, 1]^2. */
static inline void parallelogram_set_hit(hit_t *hit, int prim, real t,
                                         const real st[2])
{
    hit->t = t;
    hit->prim = prim;
    hit->b[0] = real_min(real_max(st[0], REAL_C(0.0)), REAL_C(1.0));
    hit->b[1] = real_min(real_max(st[1], REAL_C(0.0)), REAL_C(1.0));
    hit->b[2] = 0;
}

/* The two triangles A = (c0, c1, c2) and B = (c0, c2, c3) one after the
 * other under the watertight test, on a ray prepared by
 * triangle_ray_prepare(): true with the nearer hit's t and (s, t) (B
 * only if nearer). parallelogram.c. */
bool parallelogram_two_triangles(const para_shape *sh,
                                 const triangle_ray_t *pr, real tmin,
                                 real tmax, real *t, real st[2]);

#ifdef SVET_SIMD
/* fast/parallelogram_cull.c: the constants the early rejections read,
 * set once by the constructor; intersect() with the early rejections; the
 * watertight test of both triangles with their shared corners sheared
 * once, on a prepared ray. The answers are parallelogram_intersect_plain's
 * and parallelogram_prepared_plain's, bit for bit. */
void parallelogram_cull_init(para_shape *sh);
bool parallelogram_cull_intersect(const para_shape *sh, int prim,
                                  const ray_t *r, real tmin, real tmax,
                                  hit_t *hit);
bool parallelogram_cull_prepared(const para_shape *sh, int prim,
                                 const triangle_ray_t *pr, real tmin,
                                 real tmax, hit_t *hit);
#endif

#endif
