/*
 * box.h - the axis-aligned box of app. D as a COBJECT: the slab test of
 * Kay & Kajiya 1986 made conservative as in pbrt-v3 sec. 3.9.2, with hit
 * points placed exactly on the face they hit. An oriented box is a box
 * under an affine transform (xform.h).
 * Tests: tests/geometry/test_box.c; vectors: tests/vectors/box.csv
 */
#ifndef SVET_BOX_H
#define SVET_BOX_H

#include "materials/cobject.h"
#include "core/error.h"

/* Faces, as PATHPOINT.prim numbers them after a hit: 2 axis + (1 on the
 * max side). The normal ng points out of the box. */
enum {
    BOX_XMIN = 0, BOX_XMAX = 1, /* x = min.x, normal -x; x = max.x, +x */
    BOX_YMIN = 2, BOX_YMAX = 3,
    BOX_ZMIN = 4, BOX_ZMAX = 5
};

/* The box [min, max]. On face f of axis k = f / 2, with the two other axes
 * a = (k + 1) % 3 and b = (k + 2) % 3: the frame u, v is (e_a, e_b) on a
 * max face and (e_b, e_a) on a min face, so u x v = ng; st are the
 * coordinates of the hit along u's and v's axes scaled to [0, 1] over the
 * box (min -> 0); dP/ds and dP/dt are the box's extents along u and v.
 * The hit point has the face's coordinate exactly and its other two
 * clamped into the face, so it lies on the box; p_error is 0 across the
 * face and bounds the distance along it from the exact hit.
 * A ray from inside hits the face where it leaves. A ray in the plane of
 * a face, inside the box's extent, hits the box (the slab test counts the
 * boundary as inside); sample() picks a face by area, then a uniform
 * point on it: pdf = 1/area.
 * min == max on one axis is allowed (a double-sided rectangle). Returns
 * NULL with SVET_ERR_RANGE when a coordinate is NaN or infinite, min > max
 * on some axis, the box has no area, or its extents or area exceed the
 * largest real; NULL with SVET_ERR_NOMEM when memory runs out. */
COBJECT *box_new(const VECTOR3 min, const VECTOR3 max, svet_error *err);

#endif
