/*
 * vectors_vec.c - writes the test vectors of the vector algebra (app. B),
 * reflection (1.4), refraction (1.11-1.12), rotation (app. C) and the local
 * frame (app. A) into DIR/vec_*.csv and DIR/frame.csv.
 * Inputs are floats (exact in both builds, printed with 17 digits, the
 * float's exact value); expected values are computed in long double by
 * formulas independent of src/core/vec.c where one exists: refraction by
 * Snell's law in the form t = -eta w + (eta cos_i - cos_t) n, rotation by
 * the axis-angle rotation matrix. Usage: vectors_vec DIR
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "core/rng.h"
#include "vectors.h"

typedef long double ld;

static FILE *open_csv(const char *dir, const char *name, const char *what,
                      const char *header)
{
    FILE *f = vectors_open(dir, name);
    fprintf(f, "# %s\n# Written by tools/vectors_vec.c (make vectors). Inputs "
               "are floats (exact decimal); expected values long double.\n%s\n", what, header);
    return f;
}

static float rnd(pcg32_t *g, float lo, float hi)
{
    /* 24 random bits: the same inputs in the float and double builds */
    float u = (float)(pcg32_next(g) >> 8) * 0x1p-24f;
    return lo + (hi - lo) * u;
}

static void unit(float w[3], pcg32_t *g)
{
    ld v[3], len;
    do {
        for (int k = 0; k < 3; k++)
            v[k] = rnd(g, -1, 1);
        len = sqrtl(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    } while (len < 0.1L || len > 1);
    for (int k = 0; k < 3; k++)
        w[k] = (float)(v[k] / len);
}

static ld dotl(const float a[3], const float b[3])
{
    return (ld)a[0] * b[0] + (ld)a[1] * b[1] + (ld)a[2] * b[2];
}

static void ops(const char *dir, pcg32_t *g)
{
    FILE *f = open_csv(dir, "vec_ops.csv",
                       "VECTOR3 operations of app. B: cross (VVECTOR3), dot "
                       "(SVECTOR3), length, normalize.\n# e = expected result "
                       "(dot and length in ex); tolerances absolute.",
                       "case,op,ax,ay,az,bx,by,bz,ex,ey,ez,tol_float,"
                       "tol_double,source");
    int c = 0;
    for (int i = 0; i < 40; i++) {
        float a[3], b[3];
        for (int k = 0; k < 3; k++) {
            a[k] = rnd(g, -10, 10);
            b[k] = rnd(g, -10, 10);
        }
        ld cx = (ld)a[1] * b[2] - (ld)a[2] * b[1];
        ld cy = (ld)a[2] * b[0] - (ld)a[0] * b[2];
        ld cz = (ld)a[0] * b[1] - (ld)a[1] * b[0];
        ld d = dotl(a, b), len = sqrtl(dotl(a, a));
        const char *op[4] = { "cross", "dot", "length", "normalize" };
        for (int o = 0; o < 4; o++) {
            ld e[3] = { 0, 0, 0 };
            if (o == 0) { e[0] = cx; e[1] = cy; e[2] = cz; }
            if (o == 1) e[0] = d;
            if (o == 2) e[0] = len;
            if (o == 3) for (int k = 0; k < 3; k++) e[k] = a[k] / len;
            /* cross/dot of |x| <= 10: 2 products and 1-2 sums of size
             * <= 300: error <= 3 * 300 * eps/2 */
            double tf = o == 3 ? 4 * 0x1p-23 : 600 * 0x1p-23;
            double td = o == 3 ? 4 * 0x1p-52 : 600 * 0x1p-52;
            fprintf(f, "%d,%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17Lg,%.17Lg,"
                       "%.17Lg,%.3g,%.3g,long double\n", c++, op[o],
                    (double)a[0], (double)a[1], (double)a[2], (double)b[0],
                    (double)b[1], (double)b[2], e[0], e[1], e[2], tf, td);
        }
    }
    /* the zero vector normalises to zero by contract */
    fprintf(f, "%d,normalize,0,0,0,0,0,0,0,0,0,0,0,contract of vec_normalize\n",
            c++);
    vectors_close(f, dir, "vec_ops.csv");
}

static void reflect_refract(const char *dir, pcg32_t *g)
{
    FILE *fr = open_csv(dir, "vec_reflect.csv",
                        "Mirror direction, eq. (1.4): r = 2 (w.n) n - w, w and "
                        "n unit.", "case,wx,wy,wz,nx,ny,nz,rx,ry,rz,tol_float,"
                        "tol_double,source");
    FILE *ft = open_csv(dir, "vec_refract.csv",
                        "Refraction, eqs. (1.11)-(1.12): w (unit, away from "
                        "the surface) from index n1 into n2; tir = 1 when "
                        "(n1/n2) sin(theta_i) > 1 (t is then the mirror "
                        "direction).\n# Expected by Snell: t = -eta w + (eta "
                        "cos_i - cos_t) n' with n' = n on the side of w.",
                        "case,wx,wy,wz,nx,ny,nz,n1,n2,tir,tx,ty,tz,tol_float,"
                        "tol_double,source");
    const float etas[][2] = { { 1, 1.5f }, { 1.5f, 1 }, { 1, 1 }, { 1, 2.42f },
                              { 1.33f, 1 } };
    int c = 0;
    for (int i = 0; i < 60; i++) {
        float w[3], n[3];
        unit(w, g);
        unit(n, g);
        ld d = dotl(w, n);
        fprintf(fr, "%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17Lg,%.17Lg,%.17Lg,"
                    "%.3g,%.3g,long double\n", i, (double)w[0], (double)w[1],
                (double)w[2], (double)n[0], (double)n[1], (double)n[2],
                2 * d * n[0] - w[0], 2 * d * n[1] - w[1], 2 * d * n[2] - w[2],
                8 * 0x1p-23, 8 * 0x1p-52);
        for (int e = 0; e < 5; e++, c++) {
            ld n1 = etas[e][0], n2 = etas[e][1], eta = n1 / n2;
            ld s = d > 0 ? 1 : -1; /* n' = s n faces w */
            ld ci = fabsl(d), si2 = fmaxl(0, 1 - ci * ci);
            ld st2 = eta * eta * si2;
            ld t[3];
            int tir = st2 >= 1;
            if (tir)
                for (int k = 0; k < 3; k++)
                    t[k] = 2 * d * n[k] - w[k];
            else {
                ld ct = sqrtl(1 - st2);
                for (int k = 0; k < 3; k++)
                    t[k] = -eta * w[k] + (eta * ci - ct) * s * n[k];
            }
            /* near the critical angle cos_t = sqrt(1 - st2) amplifies the
             * input's rounding: tolerance ~ eps / cos_t */
            double ct = tir ? 1 : (double)sqrtl(1 - st2);
            double tf = 32 * 0x1p-23 / fmax(ct, 1e-3);
            double td = 32 * 0x1p-52 / fmax(ct, 1e-3);
            if (!tir && ct < 1e-3) /* skip cases too close to decide */
                continue;
            if (tir && st2 < 1.001L)
                continue;
            fprintf(ft, "%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%.17Lg,"
                        "%.17Lg,%.17Lg,%.3g,%.3g,Snell long double\n", c,
                    (double)w[0], (double)w[1], (double)w[2], (double)n[0],
                    (double)n[1], (double)n[2], (double)etas[e][0],
                    (double)etas[e][1], tir, t[0], t[1], t[2], tf, td);
        }
    }
    vectors_close(fr, dir, "vec_reflect.csv");
    vectors_close(ft, dir, "vec_refract.csv");
}

static void rotate(const char *dir, pcg32_t *g)
{
    FILE *f = open_csv(dir, "vec_rotate.csv",
                       "Rotation of a by angle (radians) about the unit axis "
                       "k, counter-clockwise seen from the tip of k (app. C).\n"
                       "# Expected: the axis-angle rotation matrix R = c I + "
                       "s [k]x + (1-c) k k^T applied in long double.",
                       "case,ax,ay,az,kx,ky,kz,angle,rx,ry,rz,tol_float,"
                       "tol_double,source");
    for (int i = 0; i < 60; i++) {
        float a[3], k[3];
        for (int j = 0; j < 3; j++)
            a[j] = rnd(g, -2, 2);
        unit(k, g);
        float ang = rnd(g, -7, 7);
        ld c = cosl(ang), s = sinl(ang), C = 1 - c;
        ld x = k[0], y = k[1], z = k[2];
        ld R[3][3] = { { c + x * x * C, x * y * C - z * s, x * z * C + y * s },
                       { y * x * C + z * s, c + y * y * C, y * z * C - x * s },
                       { z * x * C - y * s, z * y * C + x * s, c + z * z * C } };
        ld r[3];
        for (int j = 0; j < 3; j++)
            r[j] = R[j][0] * a[0] + R[j][1] * a[1] + R[j][2] * a[2];
        fprintf(f, "%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17Lg,%.17Lg,%.17Lg,"
                   "%.3g,%.3g,rotation matrix long double\n", i, (double)a[0],
                (double)a[1], (double)a[2], (double)k[0], (double)k[1],
                (double)k[2], (double)ang, r[0], r[1], r[2], 64 * 0x1p-23,
                64 * 0x1p-52);
    }
    vectors_close(f, dir, "vec_rotate.csv");
}

static void frames(const char *dir, pcg32_t *g)
{
    FILE *f = open_csv(dir, "frame.csv",
                       "Orthonormal frame (u, v) completing the unit normal n "
                       "(app. A), Duff et al. 2017 listing 3, in long double.\n"
                       "# A port must reproduce this particular frame (any "
                       "rotation of u, v about n is also orthonormal, but "
                       "shading and sampling depend on which one).",
                       "case,nx,ny,nz,ux,uy,uz,vx,vy,vz,tol_float,tol_double,"
                       "source");
    const float special[][3] = { { 0, 0, 1 }, { 0, 0, -1 }, { 1, 0, 0 },
                                 { 0, 1, 0 }, { -1, 0, 0 }, { 0, -1, 0 } };
    for (int i = 0; i < 66; i++) {
        float n[3];
        if (i < 6)
            for (int k = 0; k < 3; k++)
                n[k] = special[i][k];
        else
            unit(n, g);
        ld sign = copysignl(1, n[2]);
        ld a = -1 / (sign + n[2]);
        ld b = (ld)n[0] * n[1] * a;
        ld u[3] = { 1 + sign * n[0] * n[0] * a, sign * b, -sign * n[0] };
        ld v[3] = { b, sign + (ld)n[1] * n[1] * a, -n[1] };
        fprintf(f, "%d,%.17g,%.17g,%.17g,%.17Lg,%.17Lg,%.17Lg,%.17Lg,%.17Lg,"
                   "%.17Lg,%.3g,%.3g,Duff 2017 long double\n", i, (double)n[0],
                (double)n[1], (double)n[2], u[0], u[1], u[2], v[0], v[1],
                v[2], 8 * 0x1p-23, 8 * 0x1p-52);
    }
    vectors_close(f, dir, "frame.csv");
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s DIR\n", argv[0]);
        return 2;
    }
    pcg32_t g;
    pcg32_seed(&g, 2026, 1);
    ops(argv[1], &g);
    reflect_refract(argv[1], &g);
    rotate(argv[1], &g);
    frames(argv[1], &g);
    return 0;
}
