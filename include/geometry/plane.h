/*
 * plane.h - the infinite plane of app. D as a COBJECT: the plane equation
 * (x - p0) . n = 0, with a conservative test of which side the ray starts
 * on (after pbrt-v3 sec. 3.9.6) and hit points rebuilt from their plane
 * coordinates with an error bound (pbrt-v3 sec. 3.9.4).
 * Tests: tests/geometry/test_plane.c; vectors: tests/vectors/plane.csv
 */
#ifndef SVET_PLANE_H
#define SVET_PLANE_H

#include "materials/cobject.h"
#include "core/error.h"

/* The plane through `point` with normal `normal` (any nonzero length; it
 * is normalised and becomes PATHPOINT.ng, so the plane has a front). The
 * frame (u, v) of every hit is frame_from_normal(n), the same everywhere;
 * dP/ds = u and dP/dt = v (unit length), and st are the plane coordinates
 * (s, t) = ((p - point) . u, (p - point) . v) reduced modulo 1, so a
 * texture repeats every unit of length.
 *
 * Being infinite, the plane has area INFINITY, and sample() cannot draw a
 * uniform point: it returns `point` itself with pdf 0 (an integrator must
 * not divide by it; a plane is not an area light). bounds() is +-REAL_MAX
 * on every axis, except that an axis along which the normal points
 * exactly is bounded to the plane's coordinate there.
 *
 * A ray that lies in the plane, or runs parallel to it, never hits it.
 * Returns NULL with SVET_ERR_RANGE when a coordinate is NaN or infinite or
 * the normal is zero; NULL with SVET_ERR_NOMEM when memory runs out. */
COBJECT *plane_new(const VECTOR3 point, const VECTOR3 normal,
                   svet_error *err);

#endif
