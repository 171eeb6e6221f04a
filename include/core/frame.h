/*
 * frame.h - local coordinate systems (app. A): the orthonormal frame
 * (u, v, n) that PATHPOINT carries, built from a unit normal, and the change
 * of coordinates between world and local.
 * Tests: tests/core/test_frame.c; vectors: tests/vectors/frame.csv
 */
#ifndef SVET_FRAME_H
#define SVET_FRAME_H

#include "core/vec.h"

/* Complete a unit normal n to a right-handed orthonormal frame (u, v, n),
 * u x v = n. Duff, Burgess, Christensen, Hery, Kensler, Liani, Villemin,
 * "Building an Orthonormal Basis, Revisited", JCGT 6(1), 2017, listing 3:
 * no division by a small number anywhere, so it is exact to rounding for
 * every n, (0,0,-1) included. No frame field on the sphere can be
 * continuous everywhere (the hairy-ball theorem); this one is continuous
 * except across the plane n.z = 0, where copysign switches hemisphere.
 * This function can't fail. */
void frame_from_normal(VECTOR3 u, VECTOR3 v, const VECTOR3 n);

/* Local coordinates of the world vector a: (a . u, a . v, a . n).
 * l may alias a. */
static inline void frame_to_local(VECTOR3 l, const VECTOR3 a,
                                  const VECTOR3 u, const VECTOR3 v,
                                  const VECTOR3 n)
{
    real x = SVECTOR3(a, u), y = SVECTOR3(a, v), z = SVECTOR3(a, n);
    vec_set(l, x, y, z);
}

/* World vector of the local coordinates l: l.x u + l.y v + l.z n.
 * w may alias l. */
static inline void frame_to_world(VECTOR3 w, const VECTOR3 l,
                                  const VECTOR3 u, const VECTOR3 v,
                                  const VECTOR3 n)
{
    real x = l[X] * u[X] + l[Y] * v[X] + l[Z] * n[X];
    real y = l[X] * u[Y] + l[Y] * v[Y] + l[Z] * n[Y];
    real z = l[X] * u[Z] + l[Y] * v[Z] + l[Z] * n[Z];
    vec_set(w, x, y, z);
}

#endif
