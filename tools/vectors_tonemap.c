/*
 * vectors_tonemap.c - writes the test vectors of the tone-mapping curves of
 * ch. 6 into DIR/tonemap.csv (make vectors; usage: vectors_tonemap DIR):
 * the exponential map, Reinhard et al. 2002 (eqs. 2-4) and Drago et al.
 * 2003, one luminance at a time. Expected values are the papers' formulas
 * written plainly in long double here (not src/colour/tonemap.c, which rearranges
 * Reinhard's against overflow). Inputs are floats printed with 17 digits.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "vectors.h"

typedef long double ld;

/* The kernels compute in double in both builds (tonemap.h): a few
 * roundings of 2^-53 each, and log/pow/exp within an ulp or two; 1e-14
 * relative (absolute below 1) bounds them with room. */
static double tol_of(ld e)
{
    return 1e-14 * fmax(1.0, fabs((double)e));
}

static double f(double x) /* the float nearest x, as an input */
{
    return (double)(float)x;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: vectors_tonemap DIR\n");
        return 1;
    }
    FILE *out = vectors_open(argv[1], "tonemap.csv");
    fprintf(out,
            "# tone-mapping curves of ch. 6 (include/colour/tonemap.h), one "
            "luminance at a time\n"
            "# op exponential: 1 - exp(-lw / lav)\n"
            "# op reinhard: L = key lw / lav; L (1 + L / white^2) / (1 + L) "
            "(Reinhard et al. 2002 eqs. 2, 4; white inf is eq. 3)\n"
            "# op drago: (ld_max / 100) / log10(lw_max + 1) ln(lw + 1) / "
            "ln(2 + 8 (lw / lw_max)^(ln bias / ln 0.5)) (Drago et al. "
            "2003; lw, lw_max already divided by the adaptation "
            "luminance)\n"
            "# expected: those formulas in long double; tol absolute\n"
            "# columns unused by an op are 0\n"
            "op,lw,lav,key,white,bias,lw_max,ld_max,expected,tol,source\n");
    const double lws[] = { 0, 1e-6, 1e-3, 0.18, 1, 3.7, 100, 1e5, 1e30 };
    const int nl = (int)(sizeof lws / sizeof lws[0]);
    long rows = 0;
    /* exponential */
    const double lavs[] = { 0.01, 1, 50 };
    for (int i = 0; i < nl; i++)
        for (int k = 0; k < 3; k++) {
            double lw = f(lws[i]), lav = f(lavs[k]);
            ld e = 1 - expl(-(ld)lw / lav);
            fprintf(out, "exponential,%.17g,%.17g,0,0,0,0,0,%.21Lg,%.3g,%s\n",
                    lw, lav, e, tol_of(e), "formula in long double");
            rows++;
        }
    /* Reinhard */
    const double keys[] = { 0.09, 0.18, 0.72 };
    const double whites[] = { 0.5, 2, 1e6, INFINITY };
    for (int i = 0; i < nl; i++)
        for (int k = 0; k < 3; k++)
            for (int w = 0; w < 4; w++) {
                double lw = f(lws[i]), lav = f(lavs[k]), key = f(keys[k]);
                double white = isinf(whites[w]) ? whites[w] : f(whites[w]);
                ld L = (ld)key * lw / lav;
                if (isinf(white) && L > 1e300L)
                    continue; /* inf/inf in the plain formula */
                ld e = isinf(white) ? L / (1 + L)
                                    : L * (1 + L / ((ld)white * white)) /
                                          (1 + L);
                if (e > 1e12L)
                    continue; /* far past white: nothing to pin down */
                fprintf(out, "reinhard,%.17g,%.17g,%.17g,%.17g,0,0,0,"
                             "%.21Lg,%.3g,%s\n",
                        lw, lav, key, white, e, tol_of(e),
                        "Reinhard 2002 eqs. 2-4 in long double");
                rows++;
            }
    /* Drago */
    const double biases[] = { 0.7, 0.85, 1.0 };
    const double lmaxs[] = { 10, 1e4, 1e30 };
    for (int i = 0; i < nl; i++)
        for (int b = 0; b < 3; b++)
            for (int m = 0; m < 3; m++) {
                double lw = f(lws[i]), bias = f(biases[b]), lmax = f(lmaxs[m]);
                if (lw > lmax || lw == 0)
                    continue;
                double ldmax = b == 1 ? 80 : 100;
                ld p = logl(bias) / logl(0.5L);
                ld e = ((ld)ldmax / 100 / log10l((ld)lmax + 1)) *
                       log1pl((ld)lw) /
                       logl(2 + 8 * powl((ld)lw / lmax, p));
                fprintf(out, "drago,%.17g,0,0,0,%.17g,%.17g,%.17g,%.21Lg,"
                             "%.3g,%s\n",
                        lw, bias, lmax, ldmax, e, tol_of(e),
                        "Drago 2003 in long double");
                rows++;
            }
    vectors_close(out, argv[1], "tonemap.csv");
    printf("%s/tonemap.csv: %ld rows\n", argv[1], rows);
    return 0;
}
