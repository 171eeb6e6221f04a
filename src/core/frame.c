/*
 * frame.c - orthonormal frame from a unit normal (app. A), after Duff et al.
 * 2017 (JCGT 6(1)), listing 3.
 * Tests: tests/core/test_frame.c
 */
#include "core/frame.h"

void frame_from_normal(VECTOR3 u, VECTOR3 v, const VECTOR3 n)
{
    /* copysign, not (n.z >= 0): -0.0 then picks the lower hemisphere's
     * branch, where 1/(sign + n.z) = -1 stays finite. */
    real sign = copysign(REAL_C(1.0), n[Z]);
    real a = -1 / (sign + n[Z]);
    real b = n[X] * n[Y] * a;
    vec_set(u, 1 + sign * n[X] * n[X] * a, sign * b, -sign * n[X]);
    vec_set(v, b, sign + n[Y] * n[Y] * a, -n[Y]);
}
