/*
 * vectors_sample.c - writes the test vectors of the samplers of ch. 4
 * (include/core/sample.h) into DIR/sample_directions.csv, sample_points.csv and
 * sample_sphere.csv: each sampler's output for a table of u (0 and the
 * largest float below 1 included), with expected values computed here in
 * long double from the closed forms of the sources (angles by atan2/acos
 * where the code avoids them), not by calling src/core/sample.c. Inputs are
 * floats, exact in both builds. Usage: vectors_sample DIR
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "vectors.h"

typedef long double ld;

#define PI_L 3.141592653589793238462643383279502884L
#define U_FLOAT 0x1p-24L  /* unit roundoff of float */
#define U_DOUBLE 0x1p-53L /* unit roundoff of double */

/* The u table: extremes, their neighbours, and a few interior values. */
static const float us[][2] = {
    { 0.0f, 0.0f }, { 0.0f, 0.25f }, { 0.25f, 0.0f }, { 0.5f, 0.5f },
    { 0.125f, 0.875f }, { 0.75f, 0.3f }, { 0x1p-24f, 0.6f },
    { 0.999f, 0.1f }, { 1.0f - 0x1p-24f, 0.4f }, { 0.3f, 1.0f - 0x1p-24f },
    { 1.0f - 0x1p-24f, 1.0f - 0x1p-24f }, { 0.9f, 0.55f },
};
#define NU ((int)(sizeof us / sizeof us[0]))

/* A tolerance, rounded up to 3 significant digits. */
static double tol(ld t)
{
    char buf[64];
    snprintf(buf, sizeof buf, "%.2e", (double)t * 1.01);
    return strtod(buf, NULL);
}

/* --- directions ---------------------------------------------------------- */

typedef struct {
    ld w[3], pdf;
    ld k;      /* condition: direction tolerance is 32 u k */
    ld kpdf;   /* pdf relative tolerance is 32 u kpdf */
    const char *source;
} dres;

static void polar(ld w[3], ld theta, ld phi)
{
    w[0] = sinl(theta) * cosl(phi);
    w[1] = sinl(theta) * sinl(phi);
    w[2] = cosl(theta);
}

/* The same from 1 - cos(theta) = omc: theta = 2 asin(sqrt(omc / 2)), with
 * no acos of a rounded argument near 1 (which would lose the small
 * angles of narrow lobes). */
static void polar_omc(ld w[3], ld omc, ld phi)
{
    polar(w, 2 * asinl(sqrtl(omc / 2)), phi);
}

/* Shirley & Chiu 1997, in polar form: the point at radius r, angle phi of
 * the concentric map of (a, b) in [-1,1]^2. */
static void concentric(ld d[2], ld u0, ld u1)
{
    ld a = 2 * u0 - 1, b = 2 * u1 - 1, r, phi;
    if (a == 0 && b == 0) {
        d[0] = d[1] = 0;
        return;
    }
    if (fabsl(a) > fabsl(b)) {
        r = a;
        phi = PI_L / 4 * (b / a);
    } else {
        r = b;
        phi = PI_L / 2 - PI_L / 4 * (a / b);
    }
    d[0] = r * cosl(phi);
    d[1] = r * sinl(phi);
}

static dres ref_direction(const char *s, ld a, ld b, ld u0, ld u1)
{
    dres r;
    memset(&r, 0, sizeof r);
    r.k = 1;
    r.kpdf = 1;
    ld phi = 2 * PI_L * u1;
    if (strcmp(s, "uniform_sphere") == 0) {
        polar_omc(r.w, 2 * u0, phi); /* Archimedes: z uniform */
        r.pdf = 1 / (4 * PI_L);
        r.source = "z = 1 - 2 u0 (pbrt-v3 13.6.1) long double";
    } else if (strcmp(s, "uniform_hemisphere") == 0) {
        polar(r.w, acosl(u0), phi);
        r.pdf = 1 / (2 * PI_L);
        r.source = "z = u0 (pbrt-v3 13.6.1) long double";
    } else if (strcmp(s, "cosine_hemisphere") == 0) {
        ld d[2];
        concentric(d, u0, u1);
        /* the disk radius is max(|2u0 - 1|, |2u1 - 1|), exact here */
        ld rad = fmaxl(fabsl(2 * u0 - 1), fabsl(2 * u1 - 1));
        ld z2 = (1 - rad) * (1 + rad);
        ld zmin = 0x1p-12L;
        if (z2 < zmin * zmin) { /* the contract: lifted to z = 2^-12 */
            ld len = sqrtl(d[0] * d[0] + d[1] * d[1]);
            ld sc = sqrtl(1 - zmin * zmin) / len;
            r.w[0] = d[0] * sc;
            r.w[1] = d[1] * sc;
            r.w[2] = zmin;
        } else {
            r.w[0] = d[0];
            r.w[1] = d[1];
            r.w[2] = sqrtl(z2);
        }
        r.pdf = r.w[2] / PI_L;
        /* sample.c takes z from the exact 1 - r, so z (hence the pdf) is
         * good to a few ulps even at the rim; x, y carry cos/sin of the
         * angle. */
        r.source = "Malley + Shirley-Chiu 1997 long double";
    } else if (strcmp(s, "uniform_cone") == 0) {
        polar_omc(r.w, u0 * (1 - a), phi);
        r.pdf = 1 / (2 * PI_L * (1 - a));
        r.source = "cos = 1 - u0 (1 - cos_max) (pbrt-v3 13.6.4) long double";
    } else if (strcmp(s, "phong_lobe") == 0) {
        /* cos = (1 - u0)^(1/(e+1)); 1 - cos = -expm1(log1p(-u0)/(e+1)) */
        ld omc = -expm1l(log1pl(-u0) / (a + 1)), c = 1 - omc;
        polar_omc(r.w, omc, phi);
        r.pdf = (a + 1) / (2 * PI_L) * powl(c, a);
        /* the pdf is evaluated at the rounded cos: relative error e du */
        r.kpdf = 2 + a;
        r.source = "cos = (1 - u0)^(1/(e+1)) long double";
    } else if (strcmp(s, "ward_half") == 0) {
        /* Walter 2005 eqs. (6)-(7) with angles: phi = atan(ay/ax tan(psi))
         * in psi's quadrant, delta = atan(sqrt(-log(1-u0) / A(phi))). The
         * pdf exp(-tan^2 A) / (pi ax ay cos^3) has exp(...) = 1 - u0. */
        ld ph = atan2l(b * sinl(phi), a * cosl(phi));
        ld A = cosl(ph) * cosl(ph) / (a * a) + sinl(ph) * sinl(ph) / (b * b);
        ld e = -logl(1 - u0);
        ld delta = atanl(sqrtl(e / A));
        polar(r.w, delta, ph);
        r.pdf = (1 - u0) / (PI_L * a * b * powl(cosl(delta), 3));
        /* dphi/dpsi = 1 / (ax ay A) amplifies the rounding of 2 pi u1 */
        r.k = 1 + 1 / (a * b * A);
        r.kpdf = 2 + e;
        r.source = "Walter 2005 eqs. 6-7 long double";
    } else {
        fprintf(stderr, "unknown sampler %s\n", s);
        exit(1);
    }
    return r;
}

static void directions_file(const char *dir)
{
    static const struct {
        const char *s;
        float a, b;
    } samplers[] = {
        { "uniform_sphere", 0, 0 },   { "uniform_hemisphere", 0, 0 },
        { "cosine_hemisphere", 0, 0 }, { "uniform_cone", 0.5f, 0 },
        { "uniform_cone", -0.3f, 0 }, { "uniform_cone", 0.999f, 0 },
        { "phong_lobe", 0, 0 },       { "phong_lobe", 1, 0 },
        { "phong_lobe", 10, 0 },      { "phong_lobe", 1000, 0 },
        { "phong_lobe", 1e5f, 0 },    { "ward_half", 1, 1 },
        { "ward_half", 0.1f, 0.1f },  { "ward_half", 1e-4f, 1e-4f },
        { "ward_half", 1, 0.01f },    { "ward_half", 0.01f, 1 },
    };
    FILE *f = vectors_open(dir, "sample_directions.csv");
    fprintf(f,
            "# Direction samplers of ch. 4 (include/core/sample.h) at a table of "
            "u: w = (wx, wy, wz) and the pdf per solid angle (sampler's pdf "
            "function at w).\n"
            "# a, b = parameters: cone a = cos_theta_max; phong a = e; ward "
            "a = alpha_x, b = alpha_y. Expected: long double closed forms "
            "(source), written by tools/vectors_sample.c.\n"
            "# tol_*: absolute on each component of w, 32 u k with u the "
            "unit roundoff and k the condition (1; 1 + dphi/dpsi for "
            "anisotropic Ward).\n"
            "# pdf_rel_*: relative on the pdf, 32 u kpdf (kpdf = 2 + e for "
            "Phong, 2 - log(1 - u0) for Ward: the pdf at a rounded w).\n"
            "case,sampler,a,b,u0,u1,wx,wy,wz,pdf,tol_float,tol_double,"
            "pdf_rel_float,pdf_rel_double,source\n");
    int n = 0;
    for (size_t s = 0; s < sizeof samplers / sizeof samplers[0]; s++)
        for (int i = 0; i < NU; i++) {
            dres r = ref_direction(samplers[s].s, (ld)samplers[s].a,
                                   (ld)samplers[s].b, (ld)us[i][0],
                                   (ld)us[i][1]);
            fprintf(f,
                    "%d,%s,%.17g,%.17g,%.17g,%.17g,%.17Lg,%.17Lg,%.17Lg,%.17Lg,"
                    "%.3g,%.3g,%.3g,%.3g,%s\n",
                    n++, samplers[s].s, (double)samplers[s].a,
                    (double)samplers[s].b, (double)us[i][0], (double)us[i][1],
                    r.w[0], r.w[1], r.w[2], r.pdf, tol(32 * U_FLOAT * r.k),
                    tol(32 * U_DOUBLE * r.k), tol(32 * U_FLOAT * r.kpdf),
                    tol(32 * U_DOUBLE * r.kpdf), r.source);
        }
    vectors_close(f, dir, "sample_directions.csv");
}

/* --- points -------------------------------------------------------------- */

static void points_file(const char *dir)
{
    FILE *f = vectors_open(dir, "sample_points.csv");
    fprintf(f,
            "# Point samplers of ch. 4 at a table of u: concentric_disk "
            "(p0, p1) = the disk point (Shirley & Chiu 1997); triangle "
            "(p0, p1) = barycentrics (b0, b1) = (1 - sqrt(u0), u1 sqrt(u0)) "
            "(pbrt-v3 13.6.5).\n"
            "# Expected in long double by tools/vectors_sample.c; tol_* "
            "absolute, 16 u (u = unit roundoff).\n"
            "case,sampler,u0,u1,p0,p1,tol_float,tol_double,source\n");
    int n = 0;
    for (int i = 0; i < NU; i++) {
        ld d[2];
        concentric(d, (ld)us[i][0], (ld)us[i][1]);
        fprintf(f, "%d,concentric_disk,%.17g,%.17g,%.17Lg,%.17Lg,%.3g,%.3g,"
                   "Shirley-Chiu 1997 long double\n",
                n++, (double)us[i][0], (double)us[i][1], d[0], d[1],
                tol(16 * U_FLOAT), tol(16 * U_DOUBLE));
    }
    for (int i = 0; i < NU; i++) {
        ld su = sqrtl((ld)us[i][0]);
        fprintf(f, "%d,triangle,%.17g,%.17g,%.17Lg,%.17Lg,%.3g,%.3g,"
                   "pbrt-v3 13.6.5 long double\n",
                n++, (double)us[i][0], (double)us[i][1], 1 - su,
                (ld)us[i][1] * su, tol(16 * U_FLOAT), tol(16 * U_DOUBLE));
    }
    vectors_close(f, dir, "sample_points.csv");
}

/* --- the sphere by solid angle ------------------------------------------- */

/* Duff et al. 2017 listing 3 in long double: the frame a port must use. */
static void duff(ld u[3], ld v[3], const ld n[3])
{
    ld sign = copysignl(1, n[2]);
    ld a = -1 / (sign + n[2]);
    ld b = n[0] * n[1] * a;
    u[0] = 1 + sign * n[0] * n[0] * a;
    u[1] = sign * b;
    u[2] = -sign * n[0];
    v[0] = b;
    v[1] = sign + n[1] * n[1] * a;
    v[2] = -n[1];
}

static void sphere_file(const char *dir)
{
    static const float cfg[][7] = {
        /* x (3), c (3), r */
        { 0, 0, 0, 0, 0, 3, 2 },            /* 1.5 radii, on the axis */
        { 1, -2, 0.5f, 4, 1, -1, 0.75f },   /* 4.9 radii */
        { 0, 0, 0, 30, 40, 0, 0.5f },       /* 100 radii */
        { 5, 5, 5, 5, 5, -9995, 1 },        /* 1e4 radii, along -z */
        { 0.25f, 0.5f, 0, 0, 0, 0, 1 },     /* inside, 0.56 r */
        { 0, 0, 0, 0, 0, 0, 1 },            /* at the centre */
        { 0.9f, 0, 0, 0, 0, 0, 1 },         /* inside, 0.9 r */
    };
    FILE *f = vectors_open(dir, "sample_sphere.csv");
    fprintf(f,
            "# sample_sphere_solid_angle(w, x, c, r, u): the direction w "
            "from x toward the sphere (c, r) and its pdf per solid angle.\n"
            "# Outside: uniform in the cone (Shirley, Wang, Zimmerman 1996; "
            "pbrt-v3 14.2.2) about axis = (c - x)/|c - x|, 1 - cos(theta) = "
            "u0 (1 - cos_max), phi = 2 pi u1, in the frame (s, t, axis) of "
            "Duff et al. 2017 listing 3 (w = sin cos(phi) s + sin sin(phi) t "
            "+ cos axis); pdf 1/(2 pi (1 - cos_max)).\n"
            "# Inside: the point p = c + r n, n = uniform_sphere(u), w = "
            "(p - x)/|p - x|, pdf = |p - x|^2 / (4 pi r^2 |n.w|).\n"
            "# Expected in long double by tools/vectors_sample.c; tol_* "
            "absolute on w (64 u), pdf_rel_* relative (64 u).\n"
            "case,xx,xy,xz,cx,cy,cz,r,u0,u1,wx,wy,wz,pdf,tol_float,tol_double,"
            "pdf_rel_float,pdf_rel_double,source\n");
    int n = 0;
    for (size_t s = 0; s < sizeof cfg / sizeof cfg[0]; s++)
        for (int i = 0; i < NU; i++) {
            ld x[3], c[3];
            for (int k = 0; k < 3; k++) {
                x[k] = (ld)cfg[s][k];
                c[k] = (ld)cfg[s][3 + k];
            }
            ld r = (ld)cfg[s][6], u0 = (ld)us[i][0], u1 = (ld)us[i][1];
            ld xc[3] = { c[0] - x[0], c[1] - x[1], c[2] - x[2] };
            ld d = sqrtl(xc[0] * xc[0] + xc[1] * xc[1] + xc[2] * xc[2]);
            ld w[3], pdf;
            const char *src;
            if (d >= r) {
                ld axis[3] = { xc[0] / d, xc[1] / d, xc[2] / d }, e1[3], e2[3];
                duff(e1, e2, axis);
                /* h = 1 - cos_max = 1 - sqrt(1 - s^2) = -expm1(log1p(-s^2)/2),
                 * accurate for far spheres (s = r/d tiny) */
                ld h = -expm1l(0.5L * log1pl(-(r * r) / (d * d)));
                ld omc = u0 * h, th = 2 * asinl(sqrtl(omc / 2)), cth = 1 - omc;
                ld phi = 2 * PI_L * u1;
                for (int k = 0; k < 3; k++)
                    w[k] = sinl(th) * cosl(phi) * e1[k] +
                           sinl(th) * sinl(phi) * e2[k] + cth * axis[k];
                pdf = 1 / (2 * PI_L * h);
                src = "cone long double";
            } else {
                ld z = 1 - 2 * u0, st = sqrtl(1 - z * z), phi = 2 * PI_L * u1;
                ld nn[3] = { st * cosl(phi), st * sinl(phi), z };
                ld p[3], len = 0;
                for (int k = 0; k < 3; k++) {
                    p[k] = c[k] + r * nn[k];
                    w[k] = p[k] - x[k];
                    len += w[k] * w[k];
                }
                len = sqrtl(len);
                ld cosn = 0;
                for (int k = 0; k < 3; k++) {
                    w[k] /= len;
                    cosn += nn[k] * w[k];
                }
                pdf = len * len / (4 * PI_L * r * r * fabsl(cosn));
                src = "area to solid angle long double";
            }
            fprintf(f,
                    "%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17Lg,"
                    "%.17Lg,%.17Lg,%.17Lg,%.3g,%.3g,%.3g,%.3g,%s\n",
                    n++, (double)cfg[s][0], (double)cfg[s][1],
                    (double)cfg[s][2], (double)cfg[s][3], (double)cfg[s][4],
                    (double)cfg[s][5], (double)cfg[s][6], (double)us[i][0],
                    (double)us[i][1], w[0], w[1], w[2], pdf,
                    tol(64 * U_FLOAT), tol(64 * U_DOUBLE), tol(64 * U_FLOAT),
                    tol(64 * U_DOUBLE), src);
        }
    vectors_close(f, dir, "sample_sphere.csv");
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s DIR\n", argv[0]);
        return 2;
    }
    directions_file(argv[1]);
    points_file(argv[1]);
    sphere_file(argv[1]);
    return 0;
}
