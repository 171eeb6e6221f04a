/*
 * real.h - the one scalar type of svet's geometry, materials and radiance.
 * The book computes in float (ch. 1: typedef float VECTOR3[3]); `make
 * REAL=double` defines SVET_DOUBLE and everything switches to double.
 * Tests: every suite runs in both builds (make test, make REAL=double test).
 */
#ifndef SVET_REAL_H
#define SVET_REAL_H

#include <float.h>
#include <stdint.h>
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

/* The bits of a real, for the helpers below (C11 allows reading a union
 * member other than the one last written: the bytes are reinterpreted). */
#ifdef SVET_DOUBLE
typedef uint64_t real_bits_t;
#define REAL_MANT_BITS 52
#define REAL_EXP_BIAS 1023
#define REAL_TRUE_MIN DBL_TRUE_MIN
#else
typedef uint32_t real_bits_t;
#define REAL_MANT_BITS 23
#define REAL_EXP_BIAS 127
#define REAL_TRUE_MIN FLT_TRUE_MIN
#endif
typedef union {
    real x;
    real_bits_t u;
} real_union_t;

/* nextafter(x, +INFINITY) and nextafter(x, -INFINITY) without a libm call
 * (C's nextafter may not be inlined: it must also set errno): the next
 * representable real above (below) x. NaN gives NaN, +-0 the smallest
 * subnormal of the direction's sign, and an infinity toward its own sign
 * stays. */
static inline real real_next_up(real x)
{
    if (!(x < (real)INFINITY))
        return x; /* NaN, +inf */
    if (x == 0)
        return REAL_TRUE_MIN;
    real_union_t v;
    v.x = x;
    /* the magnitude's bits are ordered as the magnitudes are */
    v.u = x > 0 ? v.u + 1 : v.u - 1;
    return v.x;
}

static inline real real_next_down(real x)
{
    return -real_next_up(-x);
}

/* 2^e for REAL_MIN_EXP - 1 <= e <= REAL_MAX_EXP - 1 (the normal range),
 * built from its bits. This function can't fail. */
#ifdef SVET_DOUBLE
#define REAL_MIN_EXP DBL_MIN_EXP
#define REAL_MAX_EXP DBL_MAX_EXP
#else
#define REAL_MIN_EXP FLT_MIN_EXP
#define REAL_MAX_EXP FLT_MAX_EXP
#endif
static inline real real_pow2(int e)
{
    real_union_t v;
    v.u = (real_bits_t)(e + REAL_EXP_BIAS) << REAL_MANT_BITS;
    return v.x;
}

/* ldexp(x, e) = x 2^e, without a libm call when 2^e is a normal number:
 * then x * 2^e is one correctly rounded product, the very number ldexp
 * returns (both round the exact x 2^e once, overflow and underflow
 * included). Other e go to ldexp. This function can't fail. */
static inline real real_ldexp(real x, int e)
{
    if (e >= REAL_MIN_EXP - 1 && e <= REAL_MAX_EXP - 1)
        return x * real_pow2(e);
    return ldexp(x, e);
}

/* ilogb(x), the unbiased exponent of x, read from the bits when x is a
 * normal number; zero, subnormals, infinities and NaN go to ilogb. This
 * function can't fail. */
static inline int real_ilogb(real x)
{
    real_union_t v;
    v.x = x;
    int biased = (int)((v.u >> REAL_MANT_BITS) &
                       ((real_bits_t)2 * REAL_EXP_BIAS + 1));
    if (biased == 0 || biased == 2 * REAL_EXP_BIAS + 1)
        return ilogb(x);
    return biased - REAL_EXP_BIAS;
}

#define REAL_PI REAL_C(3.14159265358979323846)
#define REAL_INV_PI REAL_C(0.31830988618379067154)

#endif
