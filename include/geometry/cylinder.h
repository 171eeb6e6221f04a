/*
 * cylinder.h - the finite circular cylinder of app. D as a COBJECT, open or
 * capped: the lateral quadratic solved in the frame of its axis (app. A)
 * without cancellation (after Haines et al., Ray Tracing Gems 2019, ch. 7),
 * re-projected hit points with an error bound (pbrt-v3 sec. 3.9).
 * Tests: tests/geometry/test_cylinder.c; vectors: tests/vectors/cylinder.csv
 */
#ifndef SVET_CYLINDER_H
#define SVET_CYLINDER_H

#include <stdbool.h>
#include "materials/cobject.h"
#include "core/error.h"

/* Faces, as PATHPOINT.prim reports them after cobject_fill (the object has
 * one sub-primitive, prim 0, for intersect and bounds). */
enum { CYLINDER_LATERAL = 0, CYLINDER_BASE = 1, CYLINDER_TOP = 2 };

/* The cylinder of the given radius about the segment from base to top,
 * closed by the two disks at its ends when `capped`. ng points out of the
 * solid (on the open cylinder too, whichever side the ray comes from): on
 * the base cap it is -w, on the top cap +w, w = (top - base) / |top - base|.
 * With (e1, e2) = frame_from_normal(w), H = |top - base| and a lateral point
 * base + radius (cos phi e1 + sin phi e2) + z w, the surface parameters of
 * the lateral face are s = phi / (2 pi), t = z / H (0 at the base, 1 at the
 * top); dP/ds = 2 pi radius (-sin phi e1 + cos phi e2), dP/dt = H w; the
 * frame's u runs along dP/ds, v = n x u = w. The caps are parameterised as
 * disks (disk.h) about their centres, phi measured from e1 toward e2 on
 * both. Returns NULL with SVET_ERR_RANGE in err when an input is NaN or
 * infinite, the radius is <= 0, base == top, or the area or the bounds
 * would overflow; NULL with SVET_ERR_NOMEM when memory runs out. Free with
 * cobject_free(). */
COBJECT *cylinder_new(const VECTOR3 base, const VECTOR3 top, real radius,
                      bool capped, svet_error *err);

#endif
