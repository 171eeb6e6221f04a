/*
 * real.h - the one scalar type of svet's geometry, materials and radiance.
 * The book computes in float (ch. 1: typedef float VECTOR3[3]); `make
 * REAL=double` defines SVET_DOUBLE and everything switches to double.
 * Tests: every suite runs in both builds (make test, make REAL=double test).
 */
#ifndef SVET_REAL_H
#define SVET_REAL_H

#include <float.h>
/* Type-generic maths: sqrt(x) is sqrtf for float x and sqrt for double,
 * so one source serves both builds. */
#include <tgmath.h>
/* <tgmath.h> includes <complex.h>, whose macros `I` and `complex` would
 * take the book's symbol for intensity (I = Phi / (4 pi)); svet uses no
 * complex numbers. */
#undef I
#undef complex

#ifdef SVET_DOUBLE
typedef double real;
#define REAL_EPSILON DBL_EPSILON /* 2^-52: spacing of reals just above 1 */
#define REAL_MAX DBL_MAX
#define REAL_MIN DBL_MIN
#define REAL_NAME "double"
#else
typedef float real;
#define REAL_EPSILON FLT_EPSILON /* 2^-23 */
#define REAL_MAX FLT_MAX
#define REAL_MIN FLT_MIN
#define REAL_NAME "float"
#endif

/* A literal of type real: REAL_C(0.5). Without it `x * 0.5` silently
 * computes in double when real is float (-Wdouble-promotion catches it). */
#define REAL_C(x) ((real)(x))

/* Unit roundoff u = epsilon / 2: |fl(a op b) - (a op b)| <= u |a op b|. */
#define REAL_UNIT_ROUNDOFF (REAL_EPSILON * REAL_C(0.5))

/* max and min for hot paths. fmax()/fmin() are library calls unless NaN
 * and signed-zero semantics are relaxed (-ffast-math, which svet does not
 * use); these compile to one instruction. With a NaN argument they return
 * b, so use them only where NaN cannot arrive or b is the safe answer. */
static inline real real_max(real a, real b)
{
    return a > b ? a : b;
}

static inline real real_min(real a, real b)
{
    return a < b ? a : b;
}

#define REAL_PI REAL_C(3.14159265358979323846)
#define REAL_INV_PI REAL_C(0.31830988618379067154)

#endif
