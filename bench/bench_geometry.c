/*
 * bench_geometry.c - `make bench-geometry`: the first table of svet's
 * speed/accuracy trade (app. D primitives).
 *  1. Intersections per second for every primitive (nearest hit, the ray
 *     aimed at the object's bounds so most rays hit).
 *  2. The error of the hit point against a long double reference at scales
 *     1 to 1e6: the reference refines the primitive's own t by Newton's
 *     method on the surface's implicit equation (sphere |x-c|^2 = r^2, a
 *     plane n.(x - p0) = 0, a cylinder |(x-b) x w|^2 = r^2, a cone
 *     (v.w)^2 = cos^2(a) |v|^2), in long double from the same rounded ray
 *     and shape: independent of the code's formulas. Also reported: how
 *     often the hit's error bound p_error (ray.h) covers the true error.
 * The binary measures its own build (float or double); `make
 * bench-geometry` runs both and prints them side by side:
 *   bench_geometry --csv FILE        measure, write rows to FILE
 *   bench_geometry --report F D      the Markdown tables from two CSVs
 */
#include "bench.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "geometry/box.h"
#include "geometry/cone.h"
#include "geometry/cylinder.h"
#include "geometry/disk.h"
#include "geometry/parallelogram.h"
#include "geometry/plane.h"
#include "core/rng.h"
#include "core/sample.h"
#include "geometry/sphere.h"
#include "geometry/triangle.h"
#include "geometry/xform.h"

typedef long double ld;

enum { SPHERE, PLANE, DISK, PARALLELOGRAM, TRIANGLE, BOX, CYLINDER, CONE,
       ELLIPSOID, NKINDS };
static const char *kind_name[NKINDS] = {
    "sphere", "plane", "disk", "parallelogram", "triangle", "box",
    "cylinder (capped)", "cone (capped)", "ellipsoid (xform sphere)" };

/* The shape at scale s, centred near s (0.3, -0.2, 0.5): what the object
 * was built from, kept for the reference. */
typedef struct {
    int kind;
    real s;
    VECTOR3 c, a, b, n; /* centre / corner, axis ends, normal */
    real r;
    VECTOR3 p[3];
    VECTOR3 bmin, bmax;
} shape_t;

static COBJECT *build(int kind, real s, shape_t *sh)
{
    memset(sh, 0, sizeof *sh);
    sh->kind = kind;
    sh->s = s;
    vec_set(sh->c, REAL_C(0.3) * s, REAL_C(-0.2) * s, REAL_C(0.5) * s);
    sh->r = REAL_C(0.8) * s;
    vec_set(sh->n, REAL_C(0.2), REAL_C(0.9), REAL_C(0.1));
    vec_normalize(sh->n, sh->n);
    switch (kind) {
    case SPHERE:
        return sphere_new(sh->c, sh->r, NULL);
    case PLANE:
        return plane_new(sh->c, sh->n, NULL);
    case DISK:
        return disk_new(sh->c, sh->n, sh->r, NULL);
    case PARALLELOGRAM:
    case TRIANGLE:
        vec_copy(sh->p[0], sh->c);
        vec_set(sh->p[1], sh->c[X] + s, sh->c[Y] + REAL_C(0.1) * s, sh->c[Z]);
        vec_set(sh->p[2], sh->c[X] + REAL_C(0.2) * s, sh->c[Y] + REAL_C(0.3) * s,
                sh->c[Z] - s);
        return kind == TRIANGLE ? triangle_new(sh->p[0], sh->p[1], sh->p[2], NULL)
                                : parallelogram_new(sh->p[0], sh->p[1], sh->p[2], NULL);
    case BOX:
        vec_add_scaled(sh->bmin, sh->c, -REAL_C(0.5) * s, (VECTOR3){ 1, 1, 1 });
        vec_add_scaled(sh->bmax, sh->c, REAL_C(0.7) * s, (VECTOR3){ 1, 1, 1 });
        return box_new(sh->bmin, sh->bmax, NULL);
    case CYLINDER:
    case CONE:
        vec_copy(sh->a, sh->c);
        vec_set(sh->b, sh->c[X] + REAL_C(0.3) * s, sh->c[Y] + s, sh->c[Z] - REAL_C(0.2) * s);
        return kind == CYLINDER ? cylinder_new(sh->a, sh->b, sh->r, true, NULL)
                                : cone_new(sh->a, sh->b, sh->r, true, NULL);
    case ELLIPSOID: {
        VECTOR3 o = { 0, 0, 0 }, sc = { s, REAL_C(0.5) * s, REAL_C(0.7) * s };
        xform_t m = xform_compose(xform_scale(sc), xform_translate(sh->c));
        return xform_new(sphere_new(o, 1, NULL), &m, NULL);
    }
    }
    return NULL;
}

/* --- the reference: implicit equations in long double ------------------ */

static void ldv(ld out[3], const VECTOR3 v)
{
    for (int i = 0; i < 3; i++)
        out[i] = v[i];
}

static ld dotl(const ld a[3], const ld b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void crossl(ld c[3], const ld a[3], const ld b[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* Plane through q with normal m: residual at x. */
static ld f_plane(const ld x[3], const ld q[3], const ld m[3])
{
    ld d[3] = { x[0] - q[0], x[1] - q[1], x[2] - q[2] };
    return dotl(d, m);
}

/* The implicit functions of the faces of sh, evaluated at x; the face the
 * hit lies on is the one with the smallest |f| / |grad f| (distance). */
static int nfaces(int kind)
{
    switch (kind) {
    case BOX: return 6;
    case CYLINDER: case CONE: return 3;
    default: return 1;
    }
}

static ld face_f(const shape_t *sh, int face, const ld x[3])
{
    ld c[3], m[3];
    ldv(c, sh->c);
    switch (sh->kind) {
    case SPHERE: {
        ld d[3] = { x[0] - c[0], x[1] - c[1], x[2] - c[2] };
        return (dotl(d, d) - (ld)sh->r * sh->r) / (2 * (ld)sh->r);
    }
    case ELLIPSOID: {
        ld sx = sh->s, sy = 0.5L * (ld)sh->s, sz = 0.7L * (ld)sh->s;
        ld d[3] = { (x[0] - c[0]) / sx, (x[1] - c[1]) / sy, (x[2] - c[2]) / sz };
        return (dotl(d, d) - 1) * 0.5L * sy; /* ~ distance near the surface */
    }
    case PLANE:
    case DISK:
        ldv(m, sh->n);
        return f_plane(x, c, m);
    case PARALLELOGRAM:
    case TRIANGLE: {
        ld p0[3], p1[3], p2[3], e1[3], e2[3];
        ldv(p0, sh->p[0]);
        ldv(p1, sh->p[1]);
        ldv(p2, sh->p[2]);
        for (int i = 0; i < 3; i++) {
            e1[i] = p1[i] - p0[i];
            e2[i] = p2[i] - p0[i];
        }
        crossl(m, e1, e2);
        ld len = sqrtl(dotl(m, m));
        for (int i = 0; i < 3; i++)
            m[i] /= len;
        return f_plane(x, p0, m);
    }
    case BOX: {
        int axis = face / 2;
        ld bound = face % 2 ? (ld)sh->bmax[axis] : (ld)sh->bmin[axis];
        return x[axis] - bound;
    }
    case CYLINDER:
    case CONE: {
        ld a[3], b[3], w[3];
        ldv(a, sh->a);
        ldv(b, sh->b);
        for (int i = 0; i < 3; i++)
            w[i] = b[i] - a[i];
        ld H = sqrtl(dotl(w, w));
        for (int i = 0; i < 3; i++)
            w[i] /= H;
        if (face == 1)
            return f_plane(x, a, w);
        if (face == 2) {
            if (sh->kind == CONE)
                return 1e300L; /* a cone has no top cap */
            return f_plane(x, b, w);
        }
        ld v[3] = { x[0] - a[0], x[1] - a[1], x[2] - a[2] };
        if (sh->kind == CYLINDER) {
            ld q[3];
            crossl(q, v, w);
            return (dotl(q, q) - (ld)sh->r * sh->r) / (2 * (ld)sh->r);
        }
        /* cone with apex b: v from the apex, axis toward the base */
        ld va[3] = { x[0] - b[0], x[1] - b[1], x[2] - b[2] };
        ld axis[3] = { -w[0], -w[1], -w[2] };
        ld c2 = H * H / (H * H + (ld)sh->r * sh->r);
        ld t = dotl(va, axis);
        return (t * t - c2 * dotl(va, va)) / (2 * sqrtl(dotl(va, va)) + 1e-300L);
    }
    }
    return 0;
}

static int nearest_face(const shape_t *sh, const ld x[3])
{
    int face = 0;
    ld best = 1e300L;
    for (int f = 0; f < nfaces(sh->kind); f++) {
        ld v = fabsl(face_f(sh, f, x));
        if (v < best) {
            best = v;
            face = f;
        }
    }
    return face;
}

/* Distance from x to the surface (|f| / |grad f| on the nearest face) and
 * the unit gradient there. */
static ld surface_distance(const shape_t *sh, const ld x[3], ld m[3])
{
    int face = nearest_face(sh, x);
    ld f = face_f(sh, face, x), g2 = 0;
    ld h = fmaxl(1e-7L * (ld)sh->s, 1e-30L);
    for (int i = 0; i < 3; i++) {
        ld xp[3] = { x[0], x[1], x[2] }, xm[3] = { x[0], x[1], x[2] };
        xp[i] += h;
        xm[i] -= h;
        m[i] = (face_f(sh, face, xp) - face_f(sh, face, xm)) / (2 * h);
        g2 += m[i] * m[i];
    }
    ld g = sqrtl(g2);
    for (int i = 0; i < 3; i++)
        m[i] /= g;
    return fabsl(f) / g;
}

/* The exact hit: Newton on f(o + t d) from the code's t, on the face the
 * code's point is nearest to. Returns false if it does not converge. */
static bool exact_hit(const shape_t *sh, const ray_t *r, real t0, ld p[3])
{
    ld o[3], d[3], x[3];
    ldv(o, r->o);
    ldv(d, r->d);
    ld t = t0;
    for (int i = 0; i < 3; i++)
        x[i] = o[i] + t * d[i];
    int face = nearest_face(sh, x);
    for (int it = 0; it < 50; it++) {
        for (int i = 0; i < 3; i++)
            x[i] = o[i] + t * d[i];
        ld f = face_f(sh, face, x);
        ld h = fmaxl(fabsl(t), 1) * 1e-9L;
        ld x2[3];
        for (int i = 0; i < 3; i++)
            x2[i] = o[i] + (t + h) * d[i];
        ld df = (face_f(sh, face, x2) - f) / h;
        if (df == 0)
            return false;
        ld step = f / df;
        t -= step;
        if (fabsl(step) <= fabsl(t) * 1e-18L)
            break;
    }
    for (int i = 0; i < 3; i++)
        p[i] = o[i] + t * d[i];
    return true;
}

/* --- measuring ---------------------------------------------------------- */

static void make_rays(ray_t *rays, int n, const COBJECT *o,
                      const shape_t *sh, pcg32_t *g)
{
    bbox_t b;
    o->ops->bounds(o, -1, &b);
    VECTOR3 c, ext;
    /* an infinite plane has unbounded bounds: aim near its point */
    for (int k = 0; k < 3; k++) {
        if (!(fabs(b.min[k]) < REAL_C(1e30)) || !(fabs(b.max[k]) < REAL_C(1e30))) {
            b.min[k] = sh->c[k] - 2 * sh->s;
            b.max[k] = sh->c[k] + 2 * sh->s;
        }
    }
    bbox_centroid(c, &b);
    vec_sub(ext, b.max, b.min);
    real R = REAL_C(0.5) * vec_length(ext);
    if (!(R > 0))
        R = 1;
    for (int i = 0; i < n; i++) {
        real u[2] = { pcg32_real(g), pcg32_real(g) };
        VECTOR3 w, target;
        sample_uniform_sphere(w, u);
        vec_add_scaled(rays[i].o, c, 3 * R, w);
        for (int k = 0; k < 3; k++)
            target[k] = b.min[k] + pcg32_real(g) * (b.max[k] - b.min[k]);
        vec_sub(rays[i].d, target, rays[i].o);
        vec_normalize(rays[i].d, rays[i].d);
    }
}

static int run_csv(const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f) {
        perror(path);
        return 1;
    }
    const int nspeed = 1 << 20;
    ray_t *rays = malloc((size_t)nspeed * sizeof *rays);
    if (!rays)
        return 1;
    pcg32_t g;
    for (int k = 0; k < NKINDS; k++) {
        shape_t sh;
        COBJECT *o = build(k, 1, &sh);
        if (!o) {
            fprintf(stderr, "bench_geometry: cannot build %s\n", kind_name[k]);
            return 1;
        }
        pcg32_seed(&g, 1, (uint64_t)k);
        make_rays(rays, nspeed, o, &sh, &g);
        /* speed: best of 3 runs of the whole batch */
        double best = 1e300;
        long hits = 0;
        for (int rep = 0; rep < 3; rep++) {
            hits = 0;
            double t0 = bench_now();
            for (int i = 0; i < nspeed; i++) {
                hit_t h;
                hits += o->ops->intersect(o, 0, &rays[i], 0, (real)INFINITY, &h);
            }
            double dt = bench_now() - t0;
            if (dt < best)
                best = dt;
        }
        fprintf(f, "speed,%s,%.6g,%.4f\n", kind_name[k], nspeed / best / 1e6,
                (double)hits / nspeed);
        cobject_free(o);
        /* accuracy at scales 1 .. 1e6 */
        for (int e = 0; e <= 6; e += 2) {
            real s = (real)pow(10.0, e);
            o = build(k, s, &sh);
            pcg32_seed(&g, 2, (uint64_t)(k * 10 + e));
            const int nacc = 20000;
            make_rays(rays, nacc, o, &sh, &g);
            double maxrel = 0, sumsq = 0;
            long n = 0, covered = 0;
            for (int i = 0; i < nacc; i++) {
                hit_t h;
                if (!cobject_intersect(o, &rays[i], 0, (real)INFINITY, &h))
                    continue;
                PATHPOINT pp;
                cobject_fill(o, &rays[i], &h, &pp);
                ld p[3];
                if (!exact_hit(&sh, &rays[i], h.t, p))
                    continue;
                double err = 0;
                for (int c = 0; c < 3; c++) {
                    ld dc = fabsl((ld)pp.cross_point[c] - p[c]);
                    if ((double)dc > err)
                        err = (double)dc;
                }
                /* the bound's promise (pbrt-v3 sec. 3.9): the surface
                 * passes within the box p +- p_error, i.e. the distance
                 * to the surface is at most the box's support along the
                 * normal */
                ld x[3], m[3];
                ldv(x, pp.cross_point);
                ld dist = surface_distance(&sh, x, m);
                ld support = fabsl(m[0]) * pp.p_error[0] +
                             fabsl(m[1]) * pp.p_error[1] +
                             fabsl(m[2]) * pp.p_error[2];
                bool inside = dist <= support * (1 + 1e-6L);
                /* relative to the scale, or to the distance travelled when
                 * that is larger (far grazing hits of the plane) */
                double rel = err / fmax((double)s, (double)pp.r_dist);
                if (rel > maxrel)
                    maxrel = rel;
                sumsq += rel * rel;
                covered += inside;
                n++;
            }
            fprintf(f, "error,%s,%g,%.3g,%.3g,%.6f,%ld\n", kind_name[k],
                    (double)s, maxrel, n ? sqrt(sumsq / (double)n) : 0.0,
                    n ? (double)covered / (double)n : 0.0, n);
            cobject_free(o);
        }
    }
    free(rays);
    fclose(f);
    return 0;
}

/* --- the report ------------------------------------------------------- */

#define MAXROWS 256
typedef struct {
    char kind[16], name[64];
    double a, b, c, d;
    long n;
} row_t;

static int load(const char *path, row_t *rows)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        perror(path);
        return -1;
    }
    int n = 0;
    char line[512];
    while (n < MAXROWS && fgets(line, sizeof line, f)) {
        row_t *r = &rows[n];
        memset(r, 0, sizeof *r);
        char *tok = strtok(line, ",\n");
        if (!tok)
            continue;
        snprintf(r->kind, sizeof r->kind, "%s", tok);
        tok = strtok(NULL, ",\n");
        snprintf(r->name, sizeof r->name, "%s", tok ? tok : "");
        double *v[4] = { &r->a, &r->b, &r->c, &r->d };
        for (int i = 0; i < 4 && (tok = strtok(NULL, ",\n")); i++)
            *v[i] = atof(tok);
        if ((tok = strtok(NULL, ",\n")))
            r->n = atol(tok);
        n++;
    }
    fclose(f);
    return n;
}

static int report(const char *fpath, const char *dpath)
{
    static row_t fr[MAXROWS], dr[MAXROWS];
    int nf = load(fpath, fr), nd = load(dpath, dr);
    if (nf < 0 || nd < 0 || nf != nd)
        return 1;
    char cpu[256], date[64];
    bench_cpu_model(cpu, sizeof cpu);
    printf("## Primitives (app. D): speed and accuracy, float against double\n\n"
           "Machine: %s, %ld cores; gcc %s; one thread; command `make "
           "bench-geometry`; date %s. Load average when the report was made: "
           "%.1f (above the core count the machine was shared and the rates "
           "are low and noisy; the errors do not depend on it).\n\n", cpu,
           sysconf(_SC_NPROCESSORS_ONLN), __VERSION__,
           bench_date(date, sizeof date), bench_loadavg());
    printf("Nearest-hit tests of 2^20 rays aimed at the object's bounds "
           "(best of 3):\n\n| primitive | float Mrays/s | double Mrays/s | "
           "hit fraction |\n|---|---:|---:|---:|\n");
    for (int i = 0; i < nf; i++)
        if (!strcmp(fr[i].kind, "speed"))
            printf("| %s | %.1f | %.1f | %.2f |\n", fr[i].name, fr[i].a,
                   dr[i].a, fr[i].b);
    printf("\nError of the hit point, max over 20000 rays, relative to the "
           "scale s (object size and distance from the origin ~ s) or to "
           "the distance the ray travelled if larger, "
           "against the exact intersection of the same rounded ray and shape "
           "in long double; and the fraction of hits whose error box "
           "p_error reaches the surface (the distance from the computed "
           "point to the surface is at most the box's extent along the "
           "normal: what ray_spawn relies on):\n\n| primitive | s | float max err/s | float rms err/s | "
           "float bound holds | double max err/s | double rms err/s | "
           "double bound holds |\n|---|---:|---:|---:|---:|---:|---:|---:|\n");
    for (int i = 0; i < nf; i++)
        if (!strcmp(fr[i].kind, "error"))
            printf("| %s | %g | %.2g | %.2g | %.4f | %.2g | %.2g | %.4f |\n",
                   fr[i].name, fr[i].a, fr[i].b, fr[i].c, fr[i].d, dr[i].b,
                   dr[i].c, dr[i].d);
    printf("\nThe unit roundoff is %.2g in float and %.2g in double. The "
           "error along the ray is a few hundred units of it at every scale "
           "(hit points are computed relative to the object, not to the "
           "origin), except where the problem itself is ill-conditioned: a "
           "ray grazing a plane moves its hit point by 1/cos(theta) times "
           "any rounding, which the plane's maximum shows. That error lies "
           "along the surface; what matters for spawning rays is the "
           "distance to the surface, which the error box covers for every "
           "hit.\n", 0x1p-24, 0x1p-53);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 3 && !strcmp(argv[1], "--csv"))
        return run_csv(argv[2]);
    if (argc == 4 && !strcmp(argv[1], "--report"))
        return report(argv[2], argv[3]);
    fprintf(stderr, "usage: bench_geometry --csv FILE | --report FLOAT.csv "
                    "DOUBLE.csv (make bench-geometry runs both)\n");
    return 2;
}
