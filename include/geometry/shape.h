/*
 * shape.h - what the primitives of app. D share: one allocation for a
 * COBJECT and its shape data, input checks with an svet_error message, a
 * unit cross product and a surface frame that neither overflow nor
 * underflow at any scale.
 * Tests: tests/geometry/test_shape.c
 */
#ifndef SVET_SHAPE_H
#define SVET_SHAPE_H

#include <stdbool.h>
#include <stddef.h>
#include "materials/cobject.h"
#include "core/error.h"

/* A COBJECT and `size` bytes of shape data (obj->shape, aligned for any
 * type, zeroed) in one block, initialised with cobject_init(obj, ops,
 * shape): cobject_free() releases both, so ops->destroy is needed only for
 * what the shape owns besides. Returns NULL with SVET_ERR_NOMEM in err when
 * memory runs out. */
COBJECT *shape_alloc(const cobject_ops *ops, size_t size, svet_error *err);

/* SVET_OK when every component of p is finite; otherwise SVET_ERR_RANGE
 * with the message "<shape>: <what> (x, y, z) is not finite". */
svet_status shape_check_finite(const char *shape, const char *what,
                               const VECTOR3 p, svet_error *err);

/* s = a 2^-e, exactly (a power of two changes only the exponent), with e
 * chosen so that the largest component of s lies in [1, 2); returns e.
 * The zero vector and a non-finite one are copied (e = 0). The exponent
 * is read from the bits and the scaling is one product per component: no
 * libm call. This function can't fail. */
int shape_scale_exponent(VECTOR3 s, const VECTOR3 a);

/* n = (a x b) / |a x b|, computed after scaling a and b by powers of two
 * (exact) so that no product overflows or underflows. Returns false and
 * n = (0, 0, 0) when a x b computes to zero (parallel or zero edges) or an
 * input is not finite. This function can't fail. */
bool shape_unit_cross(VECTOR3 n, const VECTOR3 a, const VECTOR3 b);

/* |a x b|, the area of the parallelogram on a and b, with the same
 * scaling: INFINITY only when the area itself exceeds REAL_MAX. */
real shape_cross_length(const VECTOR3 a, const VECTOR3 b);

/* The frame (u, v, n) of PATHPOINT for a unit normal n and the tangent
 * dpds (dP/ds): u is dpds made perpendicular to n and normalised, v = n x u,
 * so u x v = n (right-handed) and u points along dP/ds as closely as n
 * allows. When dpds is zero, not finite or parallel to n, u and v come from
 * frame_from_normal(n) instead. This function can't fail. */
void shape_frame(VECTOR3 u, VECTOR3 v, const VECTOR3 n, const VECTOR3 dpds);

/* The change dn of a unit normal n = +-g / |g| (either way round) for a
 * change dg of the vector g it is the direction of: the derivative of
 * g / |g|, dn = (dg - (dg . n) n) / (g . n). For a surface F = 0, g its
 * half gradient and dg its half Hessian times a step dp along it (pbrt-v3
 * sec. 3.2.3 reaches the sphere's by the Weingarten equations); for a
 * mesh's interpolated normal, g the interpolation. dn = 0 where g . n is
 * 0 or the result is not finite. This function can't fail. */
void shape_normal_change(const VECTOR3 g, const VECTOR3 dg, const VECTOR3 n,
                         VECTOR3 dn);

/* max(|a_x|, |a_y|, |a_z|) */
static inline real shape_max_abs(const VECTOR3 a)
{
    return fmax(fabs(a[X]), fmax(fabs(a[Y]), fabs(a[Z])));
}

#endif
