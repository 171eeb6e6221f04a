/*
 * sphere.h - the sphere of app. D as a COBJECT: ray intersection without
 * catastrophic cancellation (Haines et al., Ray Tracing Gems 2019, ch. 7),
 * hit points re-projected onto the surface with a bound on their error
 * (pbrt-v3 sec. 3.9), and uniform sampling by area.
 * Tests: tests/geometry/test_sphere.c; vectors: tests/vectors/sphere.csv
 */
#ifndef SVET_SPHERE_H
#define SVET_SPHERE_H

#include "materials/cobject.h"
#include "core/error.h"

/* A sphere of the given centre and radius, one sub-primitive (prim 0).
 * Its normal ng points out of the ball. Surface parameters, as pbrt-v3's
 * Sphere with the polar angle measured from +z: s = phi / (2 pi), phi the
 * azimuth of p - centre from +x toward +y in [0, 2 pi); t = theta / pi,
 * theta the angle from +z, so t = 0 at the north pole centre + (0,0,r) and
 * t = 1 at the south pole. dP/ds = 2 pi (-y, x, 0) and
 * dP/dt = pi (z cos phi, z sin phi, -r sin theta) with (x, y, z) = p - centre;
 * the frame's u runs along dP/ds (east), v = n x u (north), and at the poles,
 * where dP/ds vanishes, comes from frame_from_normal.
 * Returns NULL with SVET_ERR_RANGE in err when a coordinate of centre or
 * the radius is NaN or infinite, the radius is <= 0, or the area 4 pi r^2
 * or its reciprocal would overflow; NULL with SVET_ERR_NOMEM when memory
 * runs out. Free with cobject_free(). */
COBJECT *sphere_new(const VECTOR3 centre, real radius, svet_error *err);

#endif
