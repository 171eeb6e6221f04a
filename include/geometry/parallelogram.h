/*
 * parallelogram.h - the parallelogram of app. D (the book's rectangle, the
 * walls and light of the Cornell box) as a COBJECT: two triangles tested
 * with the watertight test of Woop, Benthin, Wald 2013 (triangle.h), so no
 * ray slips through its diagonal or an edge it shares with a neighbour.
 * Tests: tests/geometry/test_parallelogram.c; vectors: tests/vectors/parallelogram.csv
 */
#ifndef SVET_PARALLELOGRAM_H
#define SVET_PARALLELOGRAM_H

#include <stdint.h>
#include "materials/cobject.h"
#include "core/error.h"
#include "geometry/triangle.h"

/* The parallelogram with corners c0, c1, c2 = c1 + c3 - c0, c3 in order
 * around it: p(s, t) = c0 + s (c1 - c0) + t (c3 - c0) for (s, t) in
 * [0,1]^2, which are PATHPOINT.st; dP/ds = c1 - c0, dP/dt = c3 - c0; the
 * geometric normal ng = unit((c1 - c0) x (c3 - c0)) (the convention of the
 * Cornell box scene), and u runs along c1 - c0. The surface is the two
 * triangles (c0, c1, c2) and (c0, c2, c3) sharing the diagonal c0-c2.
 * Returns NULL with SVET_ERR_RANGE when a coordinate is NaN or infinite,
 * the edges are parallel or zero (no area at working precision), or the
 * area exceeds the largest real; NULL with SVET_ERR_NOMEM when memory
 * runs out. */
COBJECT *parallelogram_new(const VECTOR3 c0, const VECTOR3 c1,
                           const VECTOR3 c3, svet_error *err);

/* The same from all four corners, as a scene file lists them: c2 must
 * equal c1 + c3 - c0 up to the rounding of the inputs, 16 units of
 * roundoff of |c0| + |c1| + |c2| + |c3| per axis (corners written in
 * decimal from an exact parallelogram, like the Cornell box's, pass).
 * The given c2 is used as the corner, so that two parallelograms sharing
 * a corner share it bit for bit and stay watertight. Fails as
 * parallelogram_new does, and with SVET_ERR_RANGE naming the size of the
 * mismatch, and how much of it leaves the plane, when c2 is farther off. */
COBJECT *parallelogram_new4(const VECTOR3 c0, const VECTOR3 c1,
                            const VECTOR3 c2, const VECTOR3 c3,
                            svet_error *err);

/* --- brute force over many parallelograms (accel.c) ---------------------- */

/* True when obj was made by parallelogram_new or parallelogram_new4.
 * This function can't fail. */
bool parallelogram_is(const COBJECT *obj);

/* Up to this many parallelograms in one batch (the bits of a uint64_t). */
#define PARALLELOGRAM_BATCH_MAX 64

typedef struct parallelogram_batch parallelogram_batch_t;

/* A batch over objs[0 .. n): what the early rejections of each read,
 * copied side by side. Returns NULL when n is outside
 * [0, PARALLELOGRAM_BATCH_MAX], an object is not a parallelogram, or
 * memory runs out. The objects must outlive the batch. */
parallelogram_batch_t *parallelogram_batch_new(const COBJECT *const *objs,
                                               int n);

/* NULL is allowed. */
void parallelogram_batch_free(parallelogram_batch_t *b);

/* The early rejections that a parallelogram's intersect() makes before
 * its watertight test, for the objects of the batch whose bit is set in
 * want and the ray r over (tmin, tmax): bit i of the result is 0 when
 * objs[i] rejects r there (it cannot report a hit: fast/parallelogram_cull.c proves
 * it) or bit i of want is 0, 1 when it may hit. Leaving out the objects a
 * ray cannot meet (accel.c's skip) spares their tests. This function
 * can't fail. */
uint64_t parallelogram_batch_cull(const parallelogram_batch_t *b,
                                  const ray_t *r, real tmin, real tmax,
                                  uint64_t want);

/* The same answer, bit for bit, by a plain loop over the parallelograms:
 * what parallelogram_batch_cull runs where SSE2 is missing (it runs
 * several at once with SSE2 or AVX where they are there). Test hook:
 * tests/geometry/test_parallelogram.c compares the two. This function can't
 * fail.
 *   The batch is the speed layer's (src/geometry/fast/
 * parallelogram_cull.c): without it (SIMD=off) parallelogram_batch_new
 * returns NULL, and brute force tests each parallelogram through its
 * intersect(). */
uint64_t parallelogram_batch_cull_plain(const parallelogram_batch_t *b,
                                        const ray_t *r, real tmin, real tmax,
                                        uint64_t want);

/* A parallelogram's intersect() without those early rejections, on a ray
 * prepared once by triangle_ray_prepare(pr, r) for any number of them:
 * the same answer and hit, bit for bit, as
 * obj->ops->intersect(obj, prim, r, tmin, tmax, hit) whenever the
 * rejections let the ray through (and, by their proofs, no hit where they
 * do not). obj must be a parallelogram. This function can't fail. */
bool parallelogram_intersect_prepared(const COBJECT *obj, int prim,
                                      const triangle_ray_t *pr, real tmin,
                                      real tmax, hit_t *hit);

/* The plain algorithm, what SIMD=off builds run: the two triangles'
 * watertight tests one after the other (on a ray prepared by
 * triangle_ray_prepare(pr, r) for the second), with no early rejection.
 * Test hooks: with the speed layer, intersect() and
 * parallelogram_intersect_prepared() give the same answers and hits, bit
 * for bit (tests/geometry/test_parallelogram.c). obj must be a
 * parallelogram. These functions can't fail. */
bool parallelogram_intersect_plain(const COBJECT *obj, int prim,
                                   const ray_t *r, real tmin, real tmax,
                                   hit_t *hit);
bool parallelogram_prepared_plain(const COBJECT *obj, int prim,
                                  const triangle_ray_t *pr, real tmin,
                                  real tmax, hit_t *hit);

#endif
