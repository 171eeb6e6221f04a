/*
 * parallelogram.h - the parallelogram of app. D (the book's rectangle, the
 * walls and light of the Cornell box) as a COBJECT: two triangles tested
 * with the watertight test of Woop, Benthin, Wald 2013 (triangle.h), so no
 * ray slips through its diagonal or an edge it shares with a neighbour.
 * Tests: tests/test_parallelogram.c; vectors: tests/vectors/parallelogram.csv
 */
#ifndef SVET_PARALLELOGRAM_H
#define SVET_PARALLELOGRAM_H

#include "cobject.h"
#include "error.h"

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

#endif
