/*
 * disk.h - the flat disk of app. D as a COBJECT: a circle of given centre,
 * normal and radius; hit points rebuilt from the plane's own coordinates
 * so that their error off the plane is tiny (pbrt-v3 sec. 3.9.4).
 * Tests: tests/geometry/test_disk.c; vectors: tests/vectors/disk.csv
 */
#ifndef SVET_DISK_H
#define SVET_DISK_H

#include "materials/cobject.h"
#include "core/error.h"

/* A disk of the given centre and radius in the plane through centre
 * perpendicular to `normal` (any nonzero length; it is normalised). One
 * sub-primitive (prim 0); ng is the unit normal n = normal / |normal|,
 * whichever side the ray comes from. With (e1, e2) = frame_from_normal(n)
 * and a point centre + rho (cos phi e1 + sin phi e2), the surface
 * parameters are s = phi / (2 pi) and t = rho / radius (0 at the centre,
 * 1 on the rim); dP/ds = 2 pi rho (-sin phi e1 + cos phi e2),
 * dP/dt = radius (cos phi e1 + sin phi e2); u runs along dP/ds, v = n x u,
 * and at the centre u, v = e1, e2.
 * Returns NULL with SVET_ERR_RANGE in err when an input is NaN or
 * infinite, the radius is <= 0, the normal is zero, or the area pi r^2 or
 * its reciprocal would overflow; NULL with SVET_ERR_NOMEM when memory runs
 * out. Free with cobject_free(). */
COBJECT *disk_new(const VECTOR3 centre, const VECTOR3 normal, real radius,
                  svet_error *err);

#endif
