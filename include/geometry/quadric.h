/*
 * quadric.h - what the quadric primitives of app. D (sphere, disk, cylinder,
 * cone) share: a quadratic solved without cancellation, rays rescaled by a
 * power of two, the local frame of an axis with the error bound of its
 * points, and the flat disk that is a disk primitive and every cap.
 * Tests: tests/geometry/test_quadric.c
 */
#ifndef SVET_QUADRIC_H
#define SVET_QUADRIC_H

#include "materials/cobject.h"
#include "core/error.h"
#include "core/frame.h"

/* --- the quadratic ------------------------------------------------------ */

/* The real roots of a t^2 + 2 bh t + c = 0 (bh is half the usual b), given
 * its discriminant disc = bh^2 - a c computed by the caller in the most
 * accurate way its geometry allows (see below). The book's textbook formula
 * (-b +- sqrt(b^2 - 4ac)) / 2a subtracts nearly equal numbers for one root;
 * instead q = -(bh + sign(bh) sqrt(disc)), t0 = c / q, t1 = q / a
 * (Press et al., "Numerical Recipes", 3rd ed., sec. 5.6; Haines, Guenther,
 * Akenine-Moller, "Precision Improvements for Ray/Sphere Intersection", Ray
 * Tracing Gems, 2019, ch. 7).
 *
 * The discriminant is invariant under a shift of the ray origin along the
 * ray, so callers compute it at the point of the ray nearest the shape,
 * where its terms are small, and the roots with bh and c of the real origin,
 * so that a root near 0 (a ray leaving the surface) keeps its sign.
 *
 * Writes the roots in ascending order to t and returns how many there are:
 * 0 when disc < 0 or is NaN, or the equation is degenerate (a = bh = 0);
 * 1 when a == 0 (the equation is linear); 2 otherwise (a double root
 * twice). The roots may be +-infinity when a is tiny, never NaN. */
int quadric_roots(real a, real bh, real c, real disc, real t[2]);

/* a b - c d to within 1.5 ulp by Kahan's algorithm with fma (Jeannerod,
 * Louvet, Muller, "Further analysis of Kahan's algorithm for the accurate
 * computation of 2x2 determinants", Math. Comp. 82, 2013). This function
 * can't fail. */
real quadric_diff_of_products(real a, real b, real c, real d);

/* Scale d by a power of two so that its largest component lies in [1, 2):
 * ds = d 2^-k, exactly (a power of two changes only the exponent), and
 * return k. The ray o + t d is then o + t' ds with t' = t 2^k, so the
 * quadratic of any finite direction, 1e-30 or 1e30 long, has coefficients
 * that neither overflow nor underflow; quadric_unscale_t(t', k) gives t
 * back exactly. A direction whose largest component lies in
 * [2^-32, 2^32] needs no scaling and is copied (k = 0), as are the zero
 * vector and a non-finite one. */
int quadric_scale_dir(VECTOR3 ds, const VECTOR3 d);

static inline real quadric_unscale_t(real ts, int k)
{
    return k ? scalbn(ts, -k) : ts;
}

/* Scale q in place to length len (> 0): the re-projection of a point onto
 * a sphere or circle (pbrt-v3 sec. 3.9.4). A q of extreme length is first
 * scaled by a power of two (quadric_scale_dir, exact), so that len / |q|
 * cannot overflow when q is tiny; then each component is rounded three
 * times (|q| by hypot to 1 ulp twice, the quotient, the product): the
 * result is within gamma(6) |q_i| of a vector exactly len long. Returns false, leaving q
 * unchanged, when q is zero or not finite. This function can't fail. */
bool quadric_project(VECTOR3 q, real len);

/* Azimuth atan2(y, x) in [0, 2 pi]; 0 for x = y = 0. */
real quadric_phi(real x, real y);

/* --- the local frame of an axis ------------------------------------------ */

/* A right-handed orthonormal frame (e1, e2, w), e1 x e2 = w, placed at o:
 * the local coordinates in which the cylinder, cone and disk are solved
 * (app. A). w is the axis (the normal of a disk). */
typedef struct {
    VECTOR3 o;          /* origin of the local coordinates */
    VECTOR3 e1, e2, w;  /* local x, y, z axes in world coordinates */
} quadric_frame_t;

/* How far (e1, e2, w) may be from the exactly orthonormal frame of the exact
 * axis, per unit of local coordinate: w = a/|a| is off by at most gamma(3)
 * < 2 eps (two hypot() roundings and a division), and frame_from_normal
 * (Duff et al. 2017) is orthonormal to a few ulps (tests/geometry/test_quadric.c
 * checks a quarter of this bound on 1e5 random axes). A point
 * o + x e1 + y e2 + z w is thus within QUADRIC_FRAME_DELTA (|x|+|y|+|z|) of
 * the point that the exact frame would give; the margin also covers the
 * rounding of the local coordinates of a ray (a dot product, gamma(4)),
 * which is what keeps a spawned ray from finding its own surface again. */
#define QUADRIC_FRAME_DELTA (16 * REAL_EPSILON)

/* Frame at o with axis w (unit; callers normalise it). This function can't
 * fail. */
void quadric_frame_init(quadric_frame_t *f, const VECTOR3 o, const VECTOR3 w);

/* The ray r in local coordinates: ol = origin, dl = direction scaled by
 * 2^-k as quadric_scale_dir does (returned k): a local root t' is the
 * world t = quadric_unscale_t(t', k). This function can't fail. */
int quadric_frame_ray(const quadric_frame_t *f, const ray_t *r, VECTOR3 ol,
                      VECTOR3 dl);

/* The world point p = at + x e1 + y e2 + z w of local coordinates (x, y, z)
 * about the point `at` (f->o, or the centre of a cap), and its error bound
 * per axis: the sum rounds each of its four terms at most four times,
 * gamma(4) (|at_i| + |x e1_i| + |y e2_i| + |z w_i|); the frame's defect
 * adds QUADRIC_FRAME_DELTA (|x|+|y|+|z|) on every axis; `extra` is what the
 * caller knows of the error of (x, y, z) themselves (after a reprojection).
 * This function can't fail. */
void quadric_frame_point(const quadric_frame_t *f, const VECTOR3 at, real x,
                         real y, real z, real extra, VECTOR3 p,
                         VECTOR3 p_error);

/* The nearest of the n local roots ts[] (ascending, scaled by 2^-k as
 * quadric_frame_ray returns them) whose world t lies in (tmin, *tmax) and
 * whose local point ol + t' dl is finite with z in [zlo, zhi]: the part of
 * a lateral surface between its ends. On success sets hit->t, hit->prim = 0,
 * hit->b = the local (x, y, z) of the point, lowers *tmax to t and returns
 * true. */
bool quadric_lateral_hit(const real ts[], int n, int k, const VECTOR3 ol,
                         const VECTOR3 dl, real zlo, real zhi, real tmin,
                         real *tmax, hit_t *hit);

/* --- flat disks: the disk primitive and every cap ------------------------ */

/* Hit of the local ray (ol, dl) with the disk z = zc, x^2 + y^2 <= R^2 of
 * the local frame: returns true, the local parameter ts (unscaled by the
 * caller) and the local (x, y) of the hit. A ray parallel to the plane
 * (dl.z = 0), in it or not, misses: a disk has no thickness. */
bool quadric_disk_hit(const VECTOR3 ol, const VECTOR3 dl, real zc, real R,
                      real *ts, real *x, real *y);

/* A hit of the local ray with the cap z = zc of radius R (quadric_disk_hit)
 * at a world t in (tmin, *tmax): sets hit->t, hit->prim = 0,
 * hit->b = (x, y, code), lowers *tmax to t and returns true. `code` tells
 * surface() which cap it was, as each primitive documents. */
bool quadric_cap_hit(const VECTOR3 ol, const VECTOR3 dl, int k, real zc,
                     real R, real code, real tmin, real *tmax, hit_t *hit);

/* Complete pp for the local point (x, y) of the disk of radius R centred
 * at `centre` = f->o + zc w in the plane spanned by f->e1, f->e2, with
 * normal sign * w (sign = +1 or -1). The point is rebuilt from its plane
 * coordinates, centre + x e1 + y e2, not taken from the ray, so its error
 * off the plane is that of quadric_frame_point, plus
 * QUADRIC_FRAME_DELTA |zc| because the intersection sees the cap through
 * local coordinates measured from f->o. Parameters (app. D):
 * s = phi / (2 pi), phi the azimuth from e1 toward e2; t = rho / R, from 0
 * at the centre to 1 on the rim; dP/ds = 2 pi (-y e1 + x e2),
 * dP/dt = R (cos phi e1 + sin phi e2); the frame is shape_frame's from n
 * and dP/ds (frame_from_normal(n) at the centre). This function can't
 * fail. */
void quadric_disk_surface(const quadric_frame_t *f, const VECTOR3 centre,
                          real zc, real R, real sign, real x, real y,
                          PATHPOINT *pp);

/* --- the normal's change ----------------------------------------------- */

/* The change dn of the unit normal pp->n of the lateral face
 * F = x^2 + y^2 + a_z z^2 + ... in frame f (a_z = 0: a cylinder about f's
 * axis; -k^2: a cone of apex f->o and slope k), for a world step dp along
 * it: shape_normal_change() of the half gradient (x, y, a_z z) and the
 * half Hessian diag(1, 1, a_z). This function can't fail. */
void quadric_lateral_normal_change(const quadric_frame_t *f, real a_z,
                                   const PATHPOINT *pp, const VECTOR3 dp,
                                   VECTOR3 dn);

/* A point of that disk, uniform by area: rho = R sqrt(u0), phi = 2 pi u1
 * (the inverse of the radial CDF rho^2 / R^2), rho kept within
 * quadric_sample_margin of the rim. Sets s->p, s->n, s->p_error;
 * the caller sets s->pdf. This function can't fail. */
void quadric_disk_sample(const quadric_frame_t *f, const VECTOR3 centre,
                         real zc, real R, real sign, const real u[2],
                         cobject_sample_t *s);

/* Grow b by the disk of radius R centred at `centre` with unit normal w:
 * on axis i it extends R sqrt(1 - w_i^2) = R hypot(w_j, w_k) either side
 * (padded by 4 eps R for the rounding of w and of the product, then
 * rounded outward), so the box is tight. This function can't fail. */
void quadric_disk_bounds(bbox_t *b, const VECTOR3 centre, const VECTOR3 w,
                         real R);

/* Grow b by the box [lo, hi], rounded one ulp outward on every side: lo
 * and hi were computed with one rounding, and a bound must contain the
 * exact surface. This function can't fail. */
void quadric_bounds_add(bbox_t *b, const VECTOR3 lo, const VECTOR3 hi);

/* How far inside a rim (or an end of a lateral face) of size `size` near
 * the point `at` a sampled point is kept. A point drawn on the exact rim
 * rounds to either side of it, by up to its error bound, and a ray aimed
 * at it from outside then misses by rounding; kept this far inside, the
 * sample, the aimed ray (rounded at |at| too) and the local coordinates of
 * its hit stay on the surface:
 *     margin = 4 (gamma(4) (max_i |at_i| + 2 size) + 2 delta size),
 * delta = QUADRIC_FRAME_DELTA: twice the in-plane error of a rim point
 * (sqrt(3) times its per-axis bound), to cover the ray's own rounding.
 * Samples in that band move onto its inner edge: a band of relative width
 * ~1e-5 (float, a shape at the origin), which no test of the distribution
 * can see, while the pdf stays 1/area. This function can't fail. */
real quadric_sample_margin(const VECTOR3 at, real size);

/* Choose face i of n with probability area[i] / (sum of the areas) by u0,
 * and stretch the part of [0, 1) that chose it back to [0, 1] in *u0, so
 * that one uniform number both picks the face and samples it. This
 * function can't fail. */
int quadric_pick_face(real *u0, const real area[], int n);

/* --- construction -------------------------------------------------------- */

/* SVET_OK when radius is finite and > 0; otherwise SVET_ERR_RANGE with
 * the message "<shape>: radius <r> is not a positive finite number". */
svet_status quadric_check_radius(const char *shape, real radius,
                                 svet_error *err);

/* The axis of a cylinder or cone from `from` to `to`: SVET_OK with w the
 * unit axis and *H = |to - from| > 0; otherwise SVET_ERR_RANGE with the
 * message of shape_check_finite (an end is not finite),
 * quadric_check_radius, or "<shape>: the axis from <from_name> to
 * <to_name> has zero (or infinite) length". */
svet_status quadric_check_axis(const char *shape, const char *from_name,
                               const VECTOR3 from, const char *to_name,
                               const VECTOR3 to, real radius, VECTOR3 w,
                               real *H, svet_error *err);

/* How far inside the ends a lateral sample of a cylinder or cone of
 * radius `radius` and height H between `from` and `to` is kept: the
 * larger quadric_sample_margin of the two ends, at most H / 2. This
 * function can't fail. */
real quadric_lateral_margin(const VECTOR3 from, const VECTOR3 to, real radius,
                            real H);

/* The last step of every quadric constructor: check that the object's
 * area is representable with its reciprocal (the pdf of uniform sampling:
 * finite, > 0, 1/area finite) and that its bounds are finite. Returns obj,
 * or frees it and returns NULL with SVET_ERR_RANGE in err. */
COBJECT *quadric_object_done(COBJECT *obj, svet_error *err);

#endif
