/*
 * cone.h - the finite right circular cone of app. D as a COBJECT, open or
 * closed by its base disk: the lateral quadratic solved in the frame of the
 * axis with a discriminant that does not cancel and stable roots, hit
 * points re-projected onto the surface with an error bound (pbrt-v3
 * sec. 3.9).
 * Tests: tests/geometry/test_cone.c; vectors: tests/vectors/cone.csv
 */
#ifndef SVET_CONE_H
#define SVET_CONE_H

#include <stdbool.h>
#include "materials/cobject.h"
#include "core/error.h"

/* Faces, as PATHPOINT.prim reports them after cobject_fill (the object has
 * one sub-primitive, prim 0, for intersect and bounds). */
enum { CONE_LATERAL = 0, CONE_BASE = 1 };

/* The cone with apex `apex` over the disk of the given radius centred at
 * `base` perpendicular to the axis, closed by that disk when `capped`.
 * ng points out of the solid (on the open cone too): on the base disk it is
 * -w, w = (apex - base) / H, H = |apex - base|; on the lateral face
 * (cos phi e1 + sin phi e2 + (radius/H) w) normalised; at the apex itself,
 * where the cone has no normal, it is w. With (e1, e2) = frame_from_normal(w)
 * and a lateral point base + rho (cos phi e1 + sin phi e2) + h w,
 * rho = radius (1 - h/H), the surface parameters are s = phi / (2 pi) and
 * t = h / H (0 on the base rim, 1 at the apex); dP/ds = 2 pi rho
 * (-sin phi e1 + cos phi e2), dP/dt = -radius (cos phi e1 + sin phi e2) + H w.
 * The frame's u runs along dP/ds, v = n x u; at the apex, where dP/ds
 * vanishes, the frame comes from frame_from_normal(w). The base disk is
 * parameterised as a disk (disk.h). Returns NULL with SVET_ERR_RANGE in
 * err when an input is NaN or infinite, the radius is <= 0, base == apex,
 * or the area or the bounds would overflow; NULL with SVET_ERR_NOMEM when
 * memory runs out. Free with cobject_free(). */
COBJECT *cone_new(const VECTOR3 base, const VECTOR3 apex, real radius,
                  bool capped, svet_error *err);

#endif
