/*
 * vectors_flat.c - writes the test vectors of the flat primitives of app. D
 * and of affine transforms: DIR/triangle.csv, plane.csv, parallelogram.csv,
 * box.csv, xform.csv (make vectors; usage: vectors_flat DIR).
 * Inputs are floats (printed with 17 digits: exact in float and double).
 * Expected values are computed in long double by the textbook formula of
 * each shape, independent of the robust code under test: Moller-Trumbore
 * for the triangle, the plane equation and Cramer's rule for planes and
 * parallelograms, the Kay-Kajiya slab test for the box, and for transforms
 * the 4x4 matrix of scale, Rodrigues rotation and translation with the
 * inverse built from the inverse factors, applied to the same formulas.
 * Cases stay clear of edges (barycentric or (s, t) margins of at least
 * 0.05), so that a float and a double port agree on hit or miss.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "core/rng.h"
#include "vectors.h"

typedef long double ld;

#define U_FLOAT 0x1p-24 /* unit roundoff of float */
#define U_DOUBLE 0x1p-53

static FILE *open_csv(const char *dir, const char *name, const char *what,
                      const char *header)
{
    FILE *f = vectors_open(dir, name);
    fprintf(f, "# %s\n# Written by tools/vectors_flat.c (make vectors). "
               "Inputs are floats (exact decimal); expected values long "
               "double.\n%s\n", what, header);
    return f;
}

/* A float uniform in [lo, hi): 24 random bits, the same in every build. */
static float rnd(pcg32_t *g, float lo, float hi)
{
    float u = (float)(pcg32_next(g) >> 8) * 0x1p-24f;
    return lo + (hi - lo) * u;
}

static ld dotl(const ld a[3], const ld b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void crossl(ld c[3], const ld a[3], const ld b[3])
{
    ld x = a[1] * b[2] - a[2] * b[1];
    ld y = a[2] * b[0] - a[0] * b[2];
    ld z = a[0] * b[1] - a[1] * b[0];
    c[0] = x; c[1] = y; c[2] = z;
}

static ld lenl(const ld a[3])
{
    return sqrtl(dotl(a, a));
}

static void subl(ld c[3], const ld a[3], const ld b[3])
{
    for (int k = 0; k < 3; k++)
        c[k] = a[k] - b[k];
}

/* a random unit vector, long double */
static void unitl(ld w[3], pcg32_t *g)
{
    ld len;
    do {
        for (int k = 0; k < 3; k++)
            w[k] = rnd(g, -1, 1);
        len = lenl(w);
    } while (len < 0.1L || len > 1);
    for (int k = 0; k < 3; k++)
        w[k] /= len;
}

/* round a long double vector to floats, and read it back exactly */
static void tofloat(ld a[3])
{
    for (int k = 0; k < 3; k++)
        a[k] = (float)a[k];
}

static void put3(FILE *f, const ld a[3])
{
    fprintf(f, "%.17g,%.17g,%.17g,", (double)a[0], (double)a[1],
            (double)a[2]);
}

static void put3e(FILE *f, const ld a[3])
{
    fprintf(f, "%.17Lg,%.17Lg,%.17Lg,", a[0], a[1], a[2]);
}

static ld max_abs3(const ld a[3])
{
    return fmaxl(fabsl(a[0]), fmaxl(fabsl(a[1]), fabsl(a[2])));
}

/* The tolerances of a row: 32 u kappa, where kappa is the condition of
 * the hit: the size of the coordinates against the distance travelled
 * across the surface's normal (a grazing hit or one far from the origin
 * amplifies rounding), or the shape's thinness |e1||e2| / |e1 x e2| for
 * its normal; plus one. */
static void put_tol(FILE *f, ld kappa)
{
    fprintf(f, "%.3Lg,%.3Lg,", 32 * (kappa + 1) * U_FLOAT,
            32 * (kappa + 1) * U_DOUBLE);
}

/* The ray, the hit flag and t of a row. */
static void put_ray_hit(FILE *f, const ld o[3], const ld d[3], int hit, ld t)
{
    put3(f, o);
    put3(f, d);
    fprintf(f, "%d,%.17Lg,", hit, t);
}

/* The end of every row: the point, the normal, scale, the tolerances and
 * where the expected values come from. */
static void put_tail(FILE *f, const ld p[3], const ld n[3], ld scale,
                     ld kappa, const char *source)
{
    put3e(f, p);
    put3e(f, n);
    fprintf(f, "%.17Lg,", scale);
    put_tol(f, kappa);
    fprintf(f, "%s\n", source);
}

/* A ray from a random point at distance [0.5, 3) s of `target`, at least
 * 0.3 away from the plane of unit normal n in cosine (on the side n points
 * to when `front`), aimed at target, with a direction of random length in
 * [0.1, 10) times the distance. o and d are rounded to floats. Returns
 * |cos| of the ray to n. */
static ld aim_side(ld o[3], ld d[3], const ld target[3], const ld n[3],
                   ld s, int front, pcg32_t *g)
{
    ld w[3];
    do
        unitl(w, g);
    while (fabsl(dotl(w, n)) < 0.3L);
    if (front && dotl(w, n) < 0)
        for (int k = 0; k < 3; k++)
            w[k] = -w[k];
    ld dist = s * rnd(g, 0.5f, 3);
    for (int k = 0; k < 3; k++)
        o[k] = target[k] + dist * w[k];
    tofloat(o);
    ld len = rnd(g, 0.1f, 10);
    for (int k = 0; k < 3; k++)
        d[k] = (target[k] - o[k]) * len;
    tofloat(d);
    return fabsl(dotl(w, n));
}

static ld aim(ld o[3], ld d[3], const ld target[3], const ld n[3], ld s,
              pcg32_t *g)
{
    return aim_side(o, d, target, n, s, 0, g);
}

/* --- triangle --------------------------------------------------------------- */

/* Moller & Trumbore, "Fast, Minimum Storage Ray/Triangle Intersection",
 * JGT 2(1), 1997, in long double: t and barycentrics by Cramer's rule. */
static int moller_trumbore(ld p[3][3], const ld o[3], const ld d[3],
                           ld *t, ld b[2])
{
    ld e1[3], e2[3], P[3], T[3], Q[3];
    subl(e1, p[1], p[0]);
    subl(e2, p[2], p[0]);
    crossl(P, d, e2);
    ld det = dotl(e1, P);
    if (fabsl(det) < 1e-30L * lenl(e1) * lenl(e2) * lenl(d))
        return 0;
    subl(T, o, p[0]);
    b[0] = dotl(T, P) / det;
    crossl(Q, T, e1);
    b[1] = dotl(d, Q) / det;
    *t = dotl(e2, Q) / det;
    return b[0] >= 0 && b[1] >= 0 && b[0] + b[1] <= 1 && *t > 0;
}

static void triangles(const char *dir, pcg32_t *g)
{
    FILE *f = open_csv(dir, "triangle.csv",
                       "Ray/triangle hits (app. D) over t in (0, inf): "
                       "corners p0 p1 p2, ray o + t d (d not unit).\n# "
                       "hit = 1 or 0; t, the point p = o + t d and the unit "
                       "normal n along (p1 - p0) x (p2 - p0) by Moller-"
                       "Trumbore (1997) in long double.\n# Tolerances: t "
                       "relative, p relative to `scale` (the largest input "
                       "coordinate), n absolute.",
                       "case,p0x,p0y,p0z,p1x,p1y,p1z,p2x,p2y,p2z,ox,oy,oz,"
                       "dx,dy,dz,hit,t,px,py,pz,nx,ny,nz,scale,tol_float,"
                       "tol_double,source");
    const float scales[] = { 1e-3f, 1, 1e3f };
    for (int i = 0; i < 90; i++) {
        ld s = scales[i % 3], p[3][3], c[3], e1[3], e2[3], N[3], n[3];
        for (int k = 0; k < 3; k++)
            c[k] = s * rnd(g, -3, 3);
        do {
            for (int j = 0; j < 3; j++) {
                for (int k = 0; k < 3; k++)
                    p[j][k] = c[k] + s * rnd(g, -1, 1);
                tofloat(p[j]);
            }
            subl(e1, p[1], p[0]);
            subl(e2, p[2], p[0]);
            crossl(N, e1, e2);
        } while (lenl(N) < 0.3L * lenl(e1) * lenl(e2));
        for (int k = 0; k < 3; k++)
            n[k] = N[k] / lenl(N);
        /* aim: inside with margin 0.1 (kind 0, 1), outside beyond an edge
         * by 0.2 or more (2), or along the plane from 0.5 s off it (3) */
        int kind = i % 4;
        ld b1 = rnd(g, 0.1f, 0.8f), b2 = rnd(g, 0.1f, 0.9f - (float)b1);
        if (kind == 2)
            b1 = -rnd(g, 0.2f, 0.7f);
        ld target[3], o[3], d[3], cosv = 1;
        for (int k = 0; k < 3; k++)
            target[k] = p[0][k] + b1 * e1[k] + b2 * e2[k];
        if (kind < 3) {
            cosv = aim(o, d, target, n, s, g);
        } else {
            ld w[3], side[3];
            unitl(w, g);
            crossl(side, n, w); /* in the plane */
            for (int k = 0; k < 3; k++) {
                o[k] = target[k] + 0.5L * s * n[k] - s * side[k];
                d[k] = side[k];
            }
            tofloat(o);
            tofloat(d);
        }
        ld t = 0, b[2], pt[3] = { 0, 0, 0 };
        int hit = moller_trumbore(p, o, d, &t, b);
        if (!hit)
            t = 0;
        else
            for (int k = 0; k < 3; k++)
                pt[k] = o[k] + t * d[k];
        ld scale = fmaxl(max_abs3(o), fmaxl(max_abs3(p[0]),
                         fmaxl(max_abs3(p[1]), max_abs3(p[2]))));
        ld kappa = fmaxl(scale / (lenl(e1) * cosv),
                         lenl(e1) * lenl(e2) / lenl(N));
        fprintf(f, "%d,", i);
        for (int j = 0; j < 3; j++)
            put3(f, p[j]);
        put_ray_hit(f, o, d, hit, t);
        put_tail(f, pt, n, scale, kappa, "Moller-Trumbore 1997 in long double");
    }
    vectors_close(f, dir, "triangle.csv");
}

/* --- plane ------------------------------------------------------------------ */

static void planes(const char *dir, pcg32_t *g)
{
    FILE *f = open_csv(dir, "plane.csv",
                       "Ray/plane hits (app. D) over t in (0, inf): the plane "
                       "through p with normal n (not unit), ray o + t d.\n# "
                       "hit = 1 or 0; t = (p - o) . n / (d . n), the point q "
                       "= o + t d and the unit normal e = n / |n|, in long "
                       "double.\n# A ray parallel to the plane (d . n = 0 "
                       "exactly) misses. Tolerances: t relative, q relative "
                       "to `scale`, e absolute.",
                       "case,px,py,pz,nx,ny,nz,ox,oy,oz,dx,dy,dz,hit,t,qx,qy,"
                       "qz,ex,ey,ez,scale,tol_float,tol_double,source");
    const float scales[] = { 1e-3f, 1, 1e3f };
    for (int i = 0; i < 60; i++) {
        ld s = scales[i % 3], p[3], n[3], e[3], o[3], d[3], target[3];
        int kind = i % 4; /* 0, 1 hit; 2 pointing away; 3 parallel */
        for (int k = 0; k < 3; k++)
            p[k] = s * rnd(g, -3, 3);
        tofloat(p);
        unitl(n, g);
        ld len = rnd(g, 0.5f, 4);
        for (int k = 0; k < 3; k++)
            n[k] *= len;
        if (kind == 3) { /* an axis normal, so the ray is exactly parallel */
            for (int k = 0; k < 3; k++)
                n[k] = 0;
            n[i % 3] = len;
        }
        tofloat(n);
        for (int k = 0; k < 3; k++)
            e[k] = n[k] / lenl(n);
        /* a target in the plane, within 2 s of p */
        ld w[3], side[3];
        unitl(w, g);
        crossl(side, e, w);
        ld r = s * rnd(g, 0, 2) / fmaxl(lenl(side), 1e-3L);
        for (int k = 0; k < 3; k++)
            target[k] = p[k] + r * side[k];
        ld cosv = 1;
        if (kind < 3) {
            cosv = aim(o, d, target, e, s, g);
            if (kind == 2)
                for (int k = 0; k < 3; k++)
                    d[k] = -d[k];
        } else {
            for (int k = 0; k < 3; k++) {
                o[k] = target[k] + s * e[k];
                d[k] = side[k];
            }
            tofloat(o);
            d[i % 3] = 0;
            tofloat(d);
        }
        ld den = dotl(d, e), t = 0, q[3] = { 0, 0, 0 }, po[3];
        subl(po, p, o);
        int hit = 0;
        if (den != 0) {
            t = dotl(po, e) / den;
            hit = t > 0;
        }
        if (!hit)
            t = 0;
        else
            for (int k = 0; k < 3; k++)
                q[k] = o[k] + t * d[k];
        ld scale = fmaxl(max_abs3(p), fmaxl(max_abs3(o), max_abs3(target)));
        fprintf(f, "%d,", i);
        put3(f, p);
        put3(f, n);
        put_ray_hit(f, o, d, hit, t);
        put_tail(f, q, e, scale, scale / (s * cosv),
                 "plane equation in long double");
    }
    vectors_close(f, dir, "plane.csv");
}

/* --- parallelogram --------------------------------------------------------- */

static void parallelograms(const char *dir, pcg32_t *g)
{
    FILE *f = open_csv(dir, "parallelogram.csv",
                       "Ray/parallelogram hits (app. D) over t in (0, inf): "
                       "corners c0, c1, c2 = c1 + c3 - c0, c3; ray o + t d."
                       "\n# hit = 1 or 0; t from the plane of N = (c1 - c0) "
                       "x (c3 - c0), then (s, t_param) of q - c0 = s (c1 - "
                       "c0) + t_param (c3 - c0) by Cramer's rule, in long "
                       "double; the point p = o + t d, the unit normal n = "
                       "N / |N|.\n# Tolerances: t relative, p relative to "
                       "`scale`, n, s and t_param absolute.",
                       "case,c0x,c0y,c0z,c1x,c1y,c1z,c3x,c3y,c3z,ox,oy,oz,"
                       "dx,dy,dz,hit,t,s,t_param,px,py,pz,nx,ny,nz,scale,"
                       "tol_float,tol_double,source");
    const float scales[] = { 1e-3f, 1, 1e3f };
    for (int i = 0; i < 60; i++) {
        ld s = scales[i % 3], c[3], c0[3], c1[3], c3[3], e1[3], e2[3], N[3];
        for (int k = 0; k < 3; k++)
            c[k] = s * rnd(g, -3, 3);
        do {
            for (int k = 0; k < 3; k++) {
                c0[k] = c[k] + s * rnd(g, -1, 1);
                c1[k] = c[k] + s * rnd(g, -1, 1);
                c3[k] = c[k] + s * rnd(g, -1, 1);
            }
            tofloat(c0);
            tofloat(c1);
            tofloat(c3);
            subl(e1, c1, c0);
            subl(e2, c3, c0);
            crossl(N, e1, e2);
        } while (lenl(N) < 0.3L * lenl(e1) * lenl(e2));
        ld n[3];
        for (int k = 0; k < 3; k++)
            n[k] = N[k] / lenl(N);
        /* inside with margin 0.05 (kinds 0, 1) or outside by 0.1 (2, 3) */
        int kind = i % 4;
        ld a = rnd(g, 0.05f, 0.95f), b = rnd(g, 0.05f, 0.95f);
        if (kind == 2)
            a = rnd(g, 1.1f, 1.6f);
        if (kind == 3)
            b = -rnd(g, 0.1f, 0.6f);
        ld target[3], o[3], d[3];
        for (int k = 0; k < 3; k++)
            target[k] = c0[k] + a * e1[k] + b * e2[k];
        ld cosv = aim(o, d, target, n, s, g);
        /* the textbook test: the plane, then (s, t) inside [0, 1]^2 */
        ld oc[3], q[3], w[3], wx[3], xw[3];
        subl(oc, c0, o);
        ld t = dotl(oc, N) / dotl(d, N);
        for (int k = 0; k < 3; k++)
            q[k] = o[k] + t * d[k];
        subl(w, q, c0);
        crossl(wx, w, e2);
        crossl(xw, e1, w);
        ld ss = dotl(wx, N) / dotl(N, N), tt = dotl(xw, N) / dotl(N, N);
        int hit = t > 0 && ss >= 0 && ss <= 1 && tt >= 0 && tt <= 1;
        if (!hit) {
            t = ss = tt = 0;
            q[0] = q[1] = q[2] = 0;
        }
        ld scale = fmaxl(max_abs3(o), fmaxl(max_abs3(c0),
                         fmaxl(max_abs3(c1), max_abs3(c3))));
        fprintf(f, "%d,", i);
        put3(f, c0);
        put3(f, c1);
        put3(f, c3);
        put_ray_hit(f, o, d, hit, t);
        fprintf(f, "%.17Lg,%.17Lg,", ss, tt);
        put_tail(f, q, n, scale,
                 fmaxl(scale / (lenl(e1) * cosv),
                       lenl(e1) * lenl(e2) / lenl(N)),
                 "plane and Cramer's rule in long double");
    }
    vectors_close(f, dir, "parallelogram.csv");
}

/* --- box ------------------------------------------------------------------------ */

/* Kay & Kajiya's slab test, "Ray Tracing Complex Scenes", SIGGRAPH 1986,
 * in long double: the nearest of entry and exit with t > 0, and its face
 * 2 axis + (1 on the max side). */
static int slab(const ld lo[3], const ld hi[3], const ld o[3], const ld d[3],
                ld *t, int *face)
{
    ld tn = -INFINITY, tf = INFINITY;
    int fn = -1, ff = -1;
    for (int k = 0; k < 3; k++) {
        if (d[k] == 0) {
            if (o[k] < lo[k] || o[k] > hi[k])
                return 0;
            continue;
        }
        ld t0 = (lo[k] - o[k]) / d[k], t1 = (hi[k] - o[k]) / d[k];
        int f0 = 2 * k, f1 = 2 * k + 1;
        if (t0 > t1) {
            ld x = t0; t0 = t1; t1 = x;
            int y = f0; f0 = f1; f1 = y;
        }
        if (t0 > tn) { tn = t0; fn = f0; }
        if (t1 < tf) { tf = t1; ff = f1; }
    }
    if (tn > tf)
        return 0;
    if (tn > 0) { *t = tn; *face = fn; return 1; }
    if (tf > 0) { *t = tf; *face = ff; return 1; }
    return 0;
}

static void boxes(const char *dir, pcg32_t *g)
{
    FILE *f = open_csv(dir, "box.csv",
                       "Ray/box hits (app. D) over t in (0, inf): the "
                       "axis-aligned box [min, max], ray o + t d.\n# hit = 1 "
                       "or 0; t and face (0..5 = -x +x -y +y -z +z) by the "
                       "slab test of Kay & Kajiya (1986) in long double; "
                       "the point p = o + t d with its face coordinate "
                       "exact; n the outward axis normal (exact).\n# "
                       "Tolerances: t relative, p relative to `scale`.",
                       "case,minx,miny,minz,maxx,maxy,maxz,ox,oy,oz,dx,dy,"
                       "dz,hit,t,face,px,py,pz,nx,ny,nz,scale,tol_float,"
                       "tol_double,source");
    const float scales[] = { 1e-3f, 1, 1e3f };
    for (int i = 0; i < 60; i++) {
        ld s = scales[i % 3], lo[3], hi[3], ext[3], c[3];
        for (int k = 0; k < 3; k++) {
            c[k] = s * rnd(g, -3, 3);
            lo[k] = c[k] - s * rnd(g, 0.2f, 1);
            hi[k] = c[k] + s * rnd(g, 0.2f, 1);
        }
        tofloat(lo);
        tofloat(hi);
        subl(ext, hi, lo);
        /* kinds: 0, 1 from outside at a face point (margin 0.05 of the
         * extent); 2 from inside (exit, margin 0.05); 3 pointing away */
        int kind = i % 4, fc = (int)pcg32_bounded(g, 6), ka = fc / 2;
        ld o[3], d[3], target[3], n[3] = { 0, 0, 0 }, cosv = 1;
        n[ka] = (fc & 1) ? 1 : -1;
        if (kind == 2) {
            ld t, p[3];
            int face;
            do {
                for (int k = 0; k < 3; k++)
                    o[k] = lo[k] + ext[k] * rnd(g, 0.1f, 0.9f);
                tofloat(o);
                unitl(d, g);
                tofloat(d);
                slab(lo, hi, o, d, &t, &face);
                for (int k = 0; k < 3; k++)
                    p[k] = (o[k] + t * d[k] - lo[k]) / ext[k];
            } while (fminl(p[0], fminl(p[1], p[2])) < -1e-9L ||
                     fmaxl(p[0], fmaxl(p[1], p[2])) > 1 + 1e-9L ||
                     /* away from the edges of the exit face */
                     (p[(face / 2 + 1) % 3] < 0.05L ||
                      p[(face / 2 + 1) % 3] > 0.95L ||
                      p[(face / 2 + 2) % 3] < 0.05L ||
                      p[(face / 2 + 2) % 3] > 0.95L));
        } else {
            for (int k = 0; k < 3; k++)
                target[k] = lo[k] + ext[k] * rnd(g, 0.05f, 0.95f);
            target[ka] = (fc & 1) ? hi[ka] : lo[ka];
            cosv = aim_side(o, d, target, n, s, 1, g);
            if (kind == 3) {
                /* from a point outside, away from the box's centre */
                for (int k = 0; k < 3; k++)
                    d[k] = o[k] - c[k];
                tofloat(d);
            }
        }
        ld t = 0, p[3] = { 0, 0, 0 };
        int face = -1, hit = slab(lo, hi, o, d, &t, &face);
        if (hit) {
            for (int k = 0; k < 3; k++)
                p[k] = o[k] + t * d[k];
            p[face / 2] = (face & 1) ? hi[face / 2] : lo[face / 2];
            for (int k = 0; k < 3; k++)
                n[k] = k == face / 2 ? ((face & 1) ? 1 : -1) : 0;
        } else {
            t = 0;
            n[0] = n[1] = n[2] = 0;
        }
        ld scale = fmaxl(max_abs3(o), fmaxl(max_abs3(lo), max_abs3(hi)));
        fprintf(f, "%d,", i);
        put3(f, lo);
        put3(f, hi);
        put_ray_hit(f, o, d, hit, t);
        fprintf(f, "%d,", face);
        put_tail(f, p, n, scale, scale / (s * 0.2L * cosv),
                 "Kay-Kajiya slab test in long double");
    }
    vectors_close(f, dir, "box.csv");
}

/* --- xform ---------------------------------------------------------------------- */

/* [R S | t] and its inverse [S^-1 R^T | -S^-1 R^T t] in long double, R
 * the axis-angle rotation matrix, from the factors. */
typedef struct {
    ld m[3][3], t[3], inv[3][3];
} affine_l;

static void make_affine(affine_l *a, const ld s[3], const ld axis[3], ld deg,
                        const ld t[3])
{
    ld k[3], len = lenl(axis);
    for (int i = 0; i < 3; i++)
        k[i] = axis[i] / len;
    ld th = deg * 3.14159265358979323846264338327950288L / 180;
    ld c = cosl(th), sn = sinl(th);
    const ld kx[3][3] = { { 0, -k[2], k[1] }, { k[2], 0, -k[0] },
                          { -k[1], k[0], 0 } };
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            ld r = (i == j ? c : 0) + sn * kx[i][j] + (1 - c) * k[i] * k[j];
            a->m[i][j] = r * s[j];      /* R S */
            a->inv[j][i] = r / s[j];    /* S^-1 R^T */
        }
    for (int i = 0; i < 3; i++)
        a->t[i] = t[i];
}

static void lin(ld out[3], ld m[3][3], const ld v[3])
{
    ld r[3];
    for (int i = 0; i < 3; i++)
        r[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
    for (int i = 0; i < 3; i++)
        out[i] = r[i];
}

/* M^-T n, unit */
static void normal_l(ld out[3], const affine_l *a, const ld n[3])
{
    ld r[3];
    for (int i = 0; i < 3; i++)
        r[i] = a->inv[0][i] * n[0] + a->inv[1][i] * n[1] + a->inv[2][i] * n[2];
    ld len = lenl(r);
    for (int i = 0; i < 3; i++)
        out[i] = r[i] / len;
}

static void xforms(const char *dir, pcg32_t *g)
{
    FILE *f = open_csv(dir, "xform.csv",
                       "A box (a = min, b = max) or a parallelogram (c0 = 0, "
                       "c1 = a, c3 = b) under the transform: scale (sx, sy, "
                       "sz), then rotate deg degrees about (kx, ky, kz), "
                       "then translate (tx, ty, tz); ray o + t d in the "
                       "world.\n# Expected by the matrix M = R S with the "
                       "axis-angle R and its inverse S^-1 R^T in long "
                       "double: the ray taken to object space, the slab "
                       "test or plane + Cramer there, the world point p = o "
                       "+ t d, the normal n = unit(M^-T n_object), and the "
                       "area as the sum of |M a x M b| over the faces.\n# "
                       "Tolerances: t and area relative, p relative to "
                       "`scale`, n absolute.",
                       "case,inner,ax,ay,az,bx,by,bz,sx,sy,sz,kx,ky,kz,deg,"
                       "tx,ty,tz,ox,oy,oz,dx,dy,dz,hit,t,area,px,py,pz,nx,ny,"
                       "nz,scale,tol_float,tol_double,source");
    for (int i = 0; i < 60; i++) {
        int box = i % 2 == 0, kind = (i / 2) % 4;
        ld a[3], b[3], s[3], ax[3], t[3], deg = rnd(g, -180, 180);
        for (int k = 0; k < 3; k++) {
            s[k] = rnd(g, 0.3f, 3);
            t[k] = rnd(g, -5, 5);
        }
        unitl(ax, g);
        tofloat(s);
        tofloat(ax);
        tofloat(t);
        deg = (float)deg;
        ld N[3];
        if (box) {
            for (int k = 0; k < 3; k++) {
                a[k] = rnd(g, -1, -0.2f);
                b[k] = rnd(g, 0.2f, 1);
            }
        } else {
            do {
                for (int k = 0; k < 3; k++) {
                    a[k] = rnd(g, -1, 1);
                    b[k] = rnd(g, -1, 1);
                }
                crossl(N, a, b);
            } while (lenl(N) < 0.3L * lenl(a) * lenl(b));
        }
        tofloat(a);
        tofloat(b);
        affine_l M;
        make_affine(&M, s, ax, deg, t);
        /* an object-space target with margins, its normal, then a world
         * ray at it */
        ld target_o[3], n_o[3] = { 0, 0, 0 }, target[3], n_w[3], o[3], d[3];
        int fc = (int)pcg32_bounded(g, 6), ka = fc / 2;
        if (box) {
            for (int k = 0; k < 3; k++)
                target_o[k] = a[k] + (b[k] - a[k]) * rnd(g, 0.05f, 0.95f);
            target_o[ka] = (fc & 1) ? b[ka] : a[ka];
            n_o[ka] = (fc & 1) ? 1 : -1;
        } else {
            ld u = rnd(g, 0.05f, 0.95f), v = rnd(g, 0.05f, 0.95f);
            if (kind == 2)
                u = rnd(g, 1.1f, 1.6f);
            for (int k = 0; k < 3; k++)
                target_o[k] = u * a[k] + v * b[k];
            crossl(n_o, a, b);
        }
        lin(target, M.m, target_o);
        for (int k = 0; k < 3; k++)
            target[k] += t[k];
        normal_l(n_w, &M, n_o);
        ld cosv = aim_side(o, d, target, n_w, 1, box, g);
        if (kind == 2 && box) { /* from inside the box */
            ld c_o[3], c_w[3];
            for (int k = 0; k < 3; k++)
                c_o[k] = 0.5L * (a[k] + b[k]);
            lin(c_w, M.m, c_o);
            for (int k = 0; k < 3; k++) {
                o[k] = c_w[k] + t[k];
                d[k] = target[k] - o[k];
            }
            tofloat(o);
            tofloat(d);
        }
        if (kind == 3)
            for (int k = 0; k < 3; k++)
                d[k] = -d[k];
        /* the reference: object-space ray, textbook test */
        ld oo[3], dd[3], ot[3];
        subl(ot, o, t);
        lin(oo, M.inv, ot);
        lin(dd, M.inv, d);
        ld th = 0, p[3] = { 0, 0, 0 }, n[3] = { 0, 0, 0 };
        int hit, face = -1;
        if (box) {
            hit = slab(a, b, oo, dd, &th, &face);
            if (hit) {
                ld nf[3] = { 0, 0, 0 };
                nf[face / 2] = (face & 1) ? 1 : -1;
                normal_l(n, &M, nf);
            }
        } else {
            ld zero[3] = { 0, 0, 0 }, oc[3], q[3], wx[3], xw[3];
            crossl(N, a, b);
            subl(oc, zero, oo);
            th = dotl(oc, N) / dotl(dd, N);
            for (int k = 0; k < 3; k++)
                q[k] = oo[k] + th * dd[k];
            crossl(wx, q, b);
            crossl(xw, a, q);
            ld ss = dotl(wx, N) / dotl(N, N), tt = dotl(xw, N) / dotl(N, N);
            hit = th > 0 && ss >= 0 && ss <= 1 && tt >= 0 && tt <= 1;
            if (hit)
                normal_l(n, &M, N);
        }
        if (hit)
            for (int k = 0; k < 3; k++)
                p[k] = o[k] + th * d[k];
        else
            th = 0;
        /* area: |M a x M b| over the faces */
        ld area = 0;
        if (box) {
            for (int k = 0; k < 3; k++) {
                ld u[3] = { 0, 0, 0 }, v[3] = { 0, 0, 0 }, mu[3], mv[3], c[3];
                u[(k + 1) % 3] = b[(k + 1) % 3] - a[(k + 1) % 3];
                v[(k + 2) % 3] = b[(k + 2) % 3] - a[(k + 2) % 3];
                lin(mu, M.m, u);
                lin(mv, M.m, v);
                crossl(c, mu, mv);
                area += 2 * lenl(c);
            }
        } else {
            ld mu[3], mv[3], c[3];
            lin(mu, M.m, a);
            lin(mv, M.m, b);
            crossl(c, mu, mv);
            area = lenl(c);
        }
        ld smax = fmaxl(s[0], fmaxl(s[1], s[2]));
        ld smin = fminl(s[0], fminl(s[1], s[2]));
        ld scale = fmaxl(max_abs3(o), fmaxl(max_abs3(target), max_abs3(t)));
        ld kappa = (smax / smin) * (1 + scale / (smin * cosv)) *
                   (box ? 1 : lenl(a) * lenl(b) / lenl(N));
        fprintf(f, "%d,%s,", i, box ? "box" : "parallelogram");
        put3(f, a);
        put3(f, b);
        put3(f, s);
        put3(f, ax);
        fprintf(f, "%.17g,", (double)deg);
        put3(f, t);
        put_ray_hit(f, o, d, hit, th);
        fprintf(f, "%.17Lg,", area);
        put_tail(f, p, n, scale, kappa,
                 box ? "Kay-Kajiya slabs under M = R S in long double"
                     : "plane and Cramer's rule under M = R S in long double");
    }
    vectors_close(f, dir, "xform.csv");
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s DIR\n", argv[0]);
        return 2;
    }
    pcg32_t g;
    pcg32_seed(&g, 2024, 2);
    triangles(argv[1], &g);
    planes(argv[1], &g);
    parallelograms(argv[1], &g);
    boxes(argv[1], &g);
    xforms(argv[1], &g);
    return 0;
}
