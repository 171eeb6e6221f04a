/*
 * xform_shape.h - the transformed object as xform.c and its speed layer
 * (fast/xform_cull.c) share it; internal to the two, not installed.
 * Tests: tests/geometry/test_xform.c
 */
#ifndef SVET_XFORM_SHAPE_H
#define SVET_XFORM_SHAPE_H

#include "geometry/xform.h"

/* Matrices [M | t] travel as pointers to their 12 entries, row by row
 * (C11 will not pass a real[3][4] where a const one is expected). */
#define AT(m, i, j) ((m)[4 * (i) + (j)])
#define MAT(a) (&(a)[0][0])

typedef struct {
    COBJECT *inner;
    xform_t x;
    real absdet; /* |det M| */
    real area;
    /* world_point()'s constants, each the very product it would compute:
     * |m_ij|, gamma(4) |m_i3| and gamma(4) |inv_ij| */
    real abs_m[3][3], g_m3[3], g_inv[3][4];
#ifdef SVET_SIMD
    /* the speed layer's (xform_cull_init()) */
    /* A sphere in the world around a transformed box, padded so that a ray
     * that passes outside it cannot be reported as a hit (sphere_pad()):
     * most rays are turned away by it before they are mapped to object
     * space. cull is false for other primitives and extreme transforms. */
    bool cull;
    xform_sphere_t sphere;
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
#endif
} xf_shape;

/* The inner primitive's intersect() on the object-space ray ro (d scaled
 * by 2^-k), its t mapped back to the world's. Inline: every test of a
 * transformed object that gets past its culling makes it. */
static inline bool xform_intersect_object(const xf_shape *sh, int prim,
                                          const ray_t *ro, int k, real tmin,
                                          real tmax, hit_t *hit)
{
    /* an affine map keeps t; only the power-of-two scaling of d moves it.
     * h zeroed: the inner primitive may leave part of its scratch b unset,
     * and the same ray must give the same bytes */
    hit_t h = { 0, 0, { 0, 0, 0 } };
    real lo = k ? ldexp(tmin, k) : tmin, hi = k ? ldexp(tmax, k) : tmax;
    if (!sh->inner->ops->intersect(sh->inner, prim, ro, lo, hi, &h))
        return false;
    real t = k ? ldexp(h.t, -k) : h.t;
    if (!(t > tmin && t < tmax))
        return false;
    *hit = h;
    hit->t = t;
    return true;
}

/* xform.c, for both: the ray in object space (false when its direction
 * there is zero or not finite), with d scaled by 2^-k; the inner
 * surface() of a hit, in object space; the world point of an object
 * point and its error bound; a PATHPOINT's normals, derivatives and
 * frame mapped to the world. */
bool xform_object_ray(const xf_shape *sh, const ray_t *r, ray_t *ro, int *k);
void xform_surface_object(const xf_shape *sh, const ray_t *r,
                          const hit_t *hit, PATHPOINT *pp);
void xform_world_point(const xf_shape *sh, const VECTOR3 p, const VECTOR3 e,
                       VECTOR3 out, VECTOR3 out_e);
void xform_surface_frame(const xf_shape *sh, PATHPOINT *pp);

#ifdef SVET_SIMD
/* fast/xform_cull.c: its constants, set once by xform_new(); intersect()
 * and surface() with the culling sphere, the box's slabs, the face table
 * and SSE lanes, the same answers bit for bit as xform_intersect_plain()
 * and xform_surface_generic(). */
void xform_cull_init(xf_shape *sh);
bool xform_cull_intersect(const COBJECT *obj, int prim, const ray_t *r,
                          real tmin, real tmax, hit_t *hit);
void xform_cull_surface(const COBJECT *obj, const ray_t *r, const hit_t *hit,
                        PATHPOINT *pp);
#endif

#endif
