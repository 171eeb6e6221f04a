/*
 * colour.h - colour of ch. 2 and app. J, K: the sRGB transfer curve, CIE XYZ
 * and xyY, RGB spaces built from their primaries and white point (sRGB /
 * Rec. 709, Rec. 2020, Adobe RGB (1998), CIE RGB), chromatic adaptation
 * (von Kries, Bradford) and lights given in watts, lumens or candela.
 * Spectra, the CIE 1931 observer and Planck's law live in spectrum.h.
 * Tests: tests/test_colour.c; vectors: tests/vectors/colour_*.csv
 */
#ifndef SVET_COLOUR_H
#define SVET_COLOUR_H

#include <stdint.h>
#include "real.h"
#include "radiance.h"

/* --- the sRGB transfer curve (IEC 61966-2-1:1999, sec. 5.2) --------------- */

/* Encode one linear value v (1 = display white) with the sRGB curve:
 *   12.92 v                    for v <= 0.0031308,
 *   1.055 v^(1/2.4) - 0.055    otherwise.
 * Values outside [0, 1] are not clamped: negative v gives -encode(-v), so
 * out-of-gamut colours survive a round trip. NaN stays NaN.
 * This function can't fail. */
real colour_srgb_encode(real v);

/* The inverse curve: e / 12.92 for e <= 0.04045, ((e + 0.055) / 1.055)^2.4
 * otherwise; odd-symmetric like colour_srgb_encode. This function can't fail. */
real colour_srgb_decode(real e);

/* Linear value -> 8-bit sRGB code 0..255: clamp to [0, 1], encode, round to
 * nearest. NaN gives 0. This function can't fail. */
uint8_t colour_srgb_encode_byte(real v);

/* 8-bit sRGB code -> linear value, exact to the rounding of real.
 * This function can't fail. */
real colour_srgb_decode_byte(uint8_t code);

#endif
