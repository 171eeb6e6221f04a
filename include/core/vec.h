/*
 * vec.h - VECTOR3 and the vector algebra of ch. 1 and app. B: the book's
 * VVECTOR3 (cross product) and SVECTOR3 (dot product), plus what a renderer
 * needs besides: sums, scaling, length, normalisation, reflection (1.4),
 * refraction (1.11-1.12) and rotation about an axis (app. C).
 * Tests: tests/core/test_vec.c; vectors: tests/vectors/vec_*.csv
 */
#ifndef SVET_VEC_H
#define SVET_VEC_H

#include <stdbool.h>
#include "core/real.h"

/* The book writes `#define X 0` etc.; an enum keeps the spelling without
 * turning every later identifier called X into a constant. */
enum { X = 0, Y = 1, Z = 2 };

/* ch. 1: "typedef float VECTOR3[3];" - a vector in Cartesian coordinates. */
typedef real VECTOR3[3];

/* c = a x b (app. B). c may alias a or b. This function can't fail. */
static inline void VVECTOR3(VECTOR3 c, const VECTOR3 a, const VECTOR3 b)
{
    real cx = a[Y] * b[Z] - a[Z] * b[Y];
    real cy = a[Z] * b[X] - a[X] * b[Z];
    real cz = a[X] * b[Y] - a[Y] * b[X];
    c[X] = cx; c[Y] = cy; c[Z] = cz;
}

/* a . b (app. B). */
static inline real SVECTOR3(const VECTOR3 a, const VECTOR3 b)
{
    return a[X] * b[X] + a[Y] * b[Y] + a[Z] * b[Z];
}

static inline void vec_set(VECTOR3 c, real x, real y, real z)
{
    c[X] = x; c[Y] = y; c[Z] = z;
}

static inline void vec_copy(VECTOR3 c, const VECTOR3 a)
{
    c[X] = a[X]; c[Y] = a[Y]; c[Z] = a[Z];
}

/* c = a + b */
static inline void vec_add(VECTOR3 c, const VECTOR3 a, const VECTOR3 b)
{
    c[X] = a[X] + b[X]; c[Y] = a[Y] + b[Y]; c[Z] = a[Z] + b[Z];
}

/* c = a - b */
static inline void vec_sub(VECTOR3 c, const VECTOR3 a, const VECTOR3 b)
{
    c[X] = a[X] - b[X]; c[Y] = a[Y] - b[Y]; c[Z] = a[Z] - b[Z];
}

/* c = s a */
static inline void vec_scale(VECTOR3 c, const VECTOR3 a, real s)
{
    c[X] = s * a[X]; c[Y] = s * a[Y]; c[Z] = s * a[Z];
}

/* c = a + s b: a point moved along a ray, p = o + t d. */
static inline void vec_add_scaled(VECTOR3 c, const VECTOR3 a, real s,
                                  const VECTOR3 b)
{
    c[X] = a[X] + s * b[X]; c[Y] = a[Y] + s * b[Y]; c[Z] = a[Z] + s * b[Z];
}

/* c = -a */
static inline void vec_neg(VECTOR3 c, const VECTOR3 a)
{
    c[X] = -a[X]; c[Y] = -a[Y]; c[Z] = -a[Z];
}

/* c = a * b component by component */
static inline void vec_mul(VECTOR3 c, const VECTOR3 a, const VECTOR3 b)
{
    c[X] = a[X] * b[X]; c[Y] = a[Y] * b[Y]; c[Z] = a[Z] * b[Z];
}

/* c = |a| component by component */
static inline void vec_abs(VECTOR3 c, const VECTOR3 a)
{
    c[X] = fabs(a[X]); c[Y] = fabs(a[Y]); c[Z] = fabs(a[Z]);
}

/* Component-wise min and max; a NaN component of a yields b's. */
static inline void vec_min(VECTOR3 c, const VECTOR3 a, const VECTOR3 b)
{
    c[X] = real_min(a[X], b[X]); c[Y] = real_min(a[Y], b[Y]);
    c[Z] = real_min(a[Z], b[Z]);
}

static inline void vec_max(VECTOR3 c, const VECTOR3 a, const VECTOR3 b)
{
    c[X] = real_max(a[X], b[X]); c[Y] = real_max(a[Y], b[Y]);
    c[Z] = real_max(a[Z], b[Z]);
}

static inline real vec_max_component(const VECTOR3 a)
{
    return real_max(a[X], real_max(a[Y], a[Z]));
}

/* Index (X, Y or Z) of the component largest in magnitude. */
static inline int vec_max_axis(const VECTOR3 a)
{
    real x = fabs(a[X]), y = fabs(a[Y]), z = fabs(a[Z]);
    return x > y ? (x > z ? X : Z) : (y > z ? Y : Z);
}

static inline real vec_length2(const VECTOR3 a)
{
    return SVECTOR3(a, a);
}

/* Euclidean length. sqrt of the sum of squares where that is exact to
 * rounding; hypot, slower but safe, only when the squares would overflow
 * (components near sqrt(REAL_MAX)) or lose digits to underflow (below
 * sqrt(REAL_MIN)). */
static inline real vec_length(const VECTOR3 a)
{
    real l2 = a[X] * a[X] + a[Y] * a[Y] + a[Z] * a[Z];
    if (l2 > REAL_MIN * REAL_C(0x1p24) && l2 < REAL_MAX * REAL_C(0x1p-2))
        return sqrt(l2);
    if (l2 == 0 && a[X] == 0 && a[Y] == 0 && a[Z] == 0)
        return 0;
    return hypot(hypot(a[X], a[Y]), a[Z]);
}

static inline real vec_distance(const VECTOR3 a, const VECTOR3 b)
{
    VECTOR3 d;
    vec_sub(d, a, b);
    return vec_length(d);
}

static inline bool vec_is_finite(const VECTOR3 a)
{
    return isfinite(a[X]) && isfinite(a[Y]) && isfinite(a[Z]);
}

/* c = a / |a|; c may alias a. Returns |a|. The zero vector (and a vector
 * with a NaN or infinite component) has no direction: c is set to (0,0,0)
 * and 0 is returned, so callers test the result instead of dividing by 0. */
static inline real vec_normalize(VECTOR3 c, const VECTOR3 a)
{
    real len = vec_length(a);
    if (!(len > 0) || !isfinite(len)) {
        vec_set(c, 0, 0, 0);
        return 0;
    }
    /* Divide rather than multiply by 1/len: the result is then correctly
     * rounded per component, and a vector along an axis stays exactly unit. */
    c[X] = a[X] / len; c[Y] = a[Y] / len; c[Z] = a[Z] / len;
    return len;
}

/* Mirror direction, eq. (1.4): r = 2 (in . n) n - in, for a unit normal n
 * and `in` pointing away from the surface (the book's Psi_i). r may alias
 * in. This function can't fail. */
void vec_reflect(VECTOR3 r, const VECTOR3 in, const VECTOR3 n);

/* Refracted direction, eq. (1.11) and eq. (1.12): `in` (unit, pointing away from
 * the surface, the book's Psi_i) arrives from the medium of index n1 and
 * leaves into index n2; n is the unit normal (either side). Returns true and
 * the unit transmitted direction t (pointing away from the surface on the
 * other side), or false on total internal reflection, when the book's
 * c2 = (n1/n2) sin(theta_i) exceeds 1 (t is then set to the mirror
 * direction). t may alias in. */
bool vec_refract(VECTOR3 t, const VECTOR3 in, const VECTOR3 n, real n1,
                 real n2);

/* Rotate a by `angle` radians about the unit axis k, counter-clockwise when
 * seen from the tip of k: Rodrigues' formula (app. C). r may alias a. */
void vec_rotate(VECTOR3 r, const VECTOR3 a, const VECTOR3 k, real angle);

#endif
