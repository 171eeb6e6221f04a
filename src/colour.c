/*
 * colour.c - colour of ch. 2 and app. J, K: the sRGB transfer curve, XYZ,
 * xyY, RGB spaces from primaries, chromatic adaptation, photometric lights.
 * Tests: tests/test_colour.c
 */
#include "colour.h"

/* --- the sRGB transfer curve (IEC 61966-2-1:1999) --------------------------- */

real colour_srgb_encode(real v)
{
    if (v < 0)
        return -colour_srgb_encode(-v);
    /* The linear toe below 0.0031308 avoids the infinite slope of a pure
     * power law at 0 (IEC 61966-2-1, sec. 5.2). */
    if (v <= REAL_C(0.0031308))
        return REAL_C(12.92) * v;
    return REAL_C(1.055) * pow(v, REAL_C(1.0) / REAL_C(2.4)) - REAL_C(0.055);
}

real colour_srgb_decode(real e)
{
    if (e < 0)
        return -colour_srgb_decode(-e);
    if (e <= REAL_C(0.04045))
        return e / REAL_C(12.92);
    return pow((e + REAL_C(0.055)) / REAL_C(1.055), REAL_C(2.4));
}

uint8_t colour_srgb_encode_byte(real v)
{
    if (!(v > 0)) /* also NaN */
        return 0;
    if (v >= 1)
        return 255;
    return (uint8_t)(colour_srgb_encode(v) * 255 + REAL_C(0.5));
}

real colour_srgb_decode_byte(uint8_t code)
{
    return colour_srgb_decode((real)code / 255);
}
