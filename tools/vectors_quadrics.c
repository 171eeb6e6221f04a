/*
 * vectors_quadrics.c - writes tests/vectors/sphere.csv, disk.csv,
 * cylinder.csv and cone.csv: rays against the quadrics of app. D with the
 * expected hit computed in long double by the textbook formulas, in world
 * coordinates, independent of src/'s robust path (no local frame, no
 * shifted discriminant, no re-projection). Inputs are floats, so the float
 * and the double build read the same rays. Checked by tests/test_<m>.c.
 * Usage: vectors_quadrics OUTDIR (run by `make vectors`)
 */
#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "vectors.h"

typedef long double ld;

enum { SPHERE, DISK, CYLINDER, CONE };
static const char *const kind_name[] = { "sphere", "disk", "cylinder",
                                         "cone" };

/* A shape as the CSV gives it: floats. a is the centre (sphere, disk) or
 * the base (cylinder, cone); b the disk's normal, the cylinder's top or the
 * cone's apex. */
typedef struct {
    int kind;
    float a[3], b[3];
    float radius;
    int capped;
} shape_t;

/* The expected hit in long double. */
typedef struct {
    bool hit;
    ld t, p[3], n[3];
    ld cosine;     /* |d . n| / |d| at the hit */
    ld curvature;  /* radius of curvature of the face hit; 0 if flat */
    int face;      /* 0 lateral (or the sphere, the disk), 1 base, 2 top */
} expect_t;

static ld dot(const ld a[3], const ld b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static ld norm(const ld a[3])
{
    return sqrtl(dot(a, a));
}

static void to_ld(ld out[3], const float in[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = (ld)in[i];
}

static void unit(ld a[3])
{
    ld l = norm(a);
    for (int i = 0; i < 3; i++)
        a[i] /= l;
}

/* Keep root t of the ray if it is the nearest positive one so far. */
static void offer(expect_t *e, ld t, int face, const ld o[3], const ld d[3],
                  const ld n[3], ld curvature)
{
    if (!(t > 0) || (e->hit && t >= e->t))
        return;
    e->hit = true;
    e->t = t;
    e->face = face;
    e->curvature = curvature;
    for (int i = 0; i < 3; i++) {
        e->p[i] = o[i] + t * d[i];
        e->n[i] = n[i];
    }
    e->cosine = fabsl(dot(d, n)) / norm(d);
}

/* The textbook roots (-B -+ sqrt(B^2 - 4AC)) / 2A, or -C/B when A = 0. */
static int textbook_roots(ld A, ld B, ld C, ld t[2])
{
    if (A == 0) {
        if (B == 0)
            return 0;
        t[0] = -C / B;
        return 1;
    }
    ld disc = B * B - 4 * A * C;
    /* A discriminant that is zero in exact arithmetic (a tangent ray, a ray
     * through the cone's apex) can come out a few ulps below zero; within
     * 64 ulps of its terms it counts as a double root. */
    if (disc < 0 && -disc <= 64 * LDBL_EPSILON * (B * B + fabsl(4 * A * C)))
        disc = 0;
    if (disc < 0)
        return 0;
    t[0] = (-B - sqrtl(disc)) / (2 * A);
    t[1] = (-B + sqrtl(disc)) / (2 * A);
    return 2;
}

/* A flat disk of centre c, unit normal w (the outward normal is sign w)
 * and radius R: the plane equation t = (c - o) . w / (d . w). */
static void flat(expect_t *e, const ld o[3], const ld d[3], const ld c[3],
                 const ld w[3], ld R, ld sign, int face)
{
    ld dw = dot(d, w);
    if (dw == 0)
        return;
    ld co[3] = { c[0] - o[0], c[1] - o[1], c[2] - o[2] };
    ld t = dot(co, w) / dw;
    ld q[3];
    for (int i = 0; i < 3; i++)
        q[i] = o[i] + t * d[i] - c[i];
    if (dot(q, q) > R * R)
        return;
    ld n[3] = { sign * w[0], sign * w[1], sign * w[2] };
    offer(e, t, face, o, d, n, 0);
}

static expect_t trace(const shape_t *s, const float fo[3], const float fd[3])
{
    expect_t e;
    memset(&e, 0, sizeof e);
    ld o[3], d[3], a[3], b[3], R = (ld)s->radius;
    to_ld(o, fo);
    to_ld(d, fd);
    to_ld(a, s->a);
    to_ld(b, s->b);
    if (s->kind == SPHERE) {
        /* |o + t d - c|^2 = R^2 */
        ld f[3] = { o[0] - a[0], o[1] - a[1], o[2] - a[2] };
        ld t[2];
        int n = textbook_roots(dot(d, d), 2 * dot(f, d), dot(f, f) - R * R, t);
        for (int i = 0; i < n; i++) {
            ld q[3];
            for (int k = 0; k < 3; k++)
                q[k] = (o[k] + t[i] * d[k] - a[k]) / R;
            offer(&e, t[i], 0, o, d, q, R);
        }
    } else if (s->kind == DISK) {
        unit(b);
        flat(&e, o, d, a, b, R, 1, 0);
    } else if (s->kind == CYLINDER) {
        /* |(p - base) - ((p - base).w) w|^2 = R^2, 0 <= (p - base).w <= H */
        ld w[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
        ld H = norm(w);
        unit(w);
        ld f[3] = { o[0] - a[0], o[1] - a[1], o[2] - a[2] }, dp[3], fp[3];
        for (int k = 0; k < 3; k++) {
            dp[k] = d[k] - dot(d, w) * w[k];
            fp[k] = f[k] - dot(f, w) * w[k];
        }
        ld t[2];
        int n = textbook_roots(dot(dp, dp), 2 * dot(dp, fp),
                               dot(fp, fp) - R * R, t);
        for (int i = 0; i < n; i++) {
            ld q[3], h;
            for (int k = 0; k < 3; k++)
                q[k] = f[k] + t[i] * d[k];
            h = dot(q, w);
            if (h < 0 || h > H)
                continue;
            for (int k = 0; k < 3; k++)
                q[k] = (q[k] - h * w[k]) / R;
            offer(&e, t[i], 0, o, d, q, R);
        }
        if (s->capped) {
            flat(&e, o, d, a, w, R, -1, 1);
            flat(&e, o, d, b, w, R, 1, 2);
        }
    } else {
        /* ((p - apex) . v)^2 = cos^2(alpha) |p - apex|^2 with v the unit
         * axis from the apex to the base, cos^2(alpha) = H^2 / (H^2 + R^2),
         * 0 <= (p - apex) . v <= H. */
        ld v[3] = { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
        ld H = norm(v);
        unit(v);
        ld c2 = H * H / (H * H + R * R);
        ld f[3] = { o[0] - b[0], o[1] - b[1], o[2] - b[2] };
        ld dv = dot(d, v), fv = dot(f, v), t[2];
        int n = textbook_roots(dv * dv - c2 * dot(d, d),
                               2 * (dv * fv - c2 * dot(d, f)),
                               fv * fv - c2 * dot(f, f), t);
        for (int i = 0; i < n; i++) {
            ld q[3], g[3], h;
            for (int k = 0; k < 3; k++)
                q[k] = f[k] + t[i] * d[k];
            h = dot(q, v);
            /* the apex is an end of the range: a few ulps of slack */
            if (h < -64 * LDBL_EPSILON * norm(f) || h > H)
                continue;
            /* outward normal: minus the gradient of
             * (q . v)^2 - cos^2 |q|^2 */
            for (int k = 0; k < 3; k++)
                g[k] = c2 * q[k] - h * v[k];
            ld rho = h * R / H; /* radius of the cone at the hit */
            if (norm(q) <= 64 * LDBL_EPSILON * norm(f))
                for (int k = 0; k < 3; k++)
                    g[k] = -v[k]; /* the apex: the axis, by convention */
            unit(g);
            offer(&e, t[i], 0, o, d, g, rho);
        }
        if (s->capped) {
            ld vv[3] = { -v[0], -v[1], -v[2] };
            flat(&e, o, d, a, vv, R, -1, 1);
        }
    }
    return e;
}

/* The same shape grown (f > 1) or shrunk about its middle. */
static shape_t scaled(const shape_t *s, float f)
{
    shape_t r = *s;
    r.radius = s->radius * f;
    if (s->kind == CYLINDER || s->kind == CONE)
        for (int i = 0; i < 3; i++) {
            float m = 0.5f * (s->a[i] + s->b[i]);
            r.a[i] = m + (s->a[i] - m) * f;
            r.b[i] = m + (s->b[i] - m) * f;
        }
    return r;
}

static double uniform(pcg32_t *g)
{
    return (double)pcg32_next(g) * 0x1p-32;
}

static void random_dir(double w[3], pcg32_t *g)
{
    double z = 1 - 2 * uniform(g);
    double phi = 2 * 3.14159265358979323846 * uniform(g);
    double r = sqrt(fmax(0.0, 1 - z * z));
    w[0] = r * cos(phi);
    w[1] = r * sin(phi);
    w[2] = z;
}

typedef struct {
    FILE *f;
    const char *dir;
    char name[32];
    int kind, rows;
} out_t;

static void open_out(out_t *o, const char *dir, int kind)
{
    o->kind = kind;
    o->rows = 0;
    o->dir = dir;
    snprintf(o->name, sizeof o->name, "%s.csv", kind_name[kind]);
    o->f = vectors_open(dir, o->name);
    static const char *const params[] = {
        "cx,cy,cz,radius", "cx,cy,cz,ax,ay,az,radius",
        "bx,by,bz,ex,ey,ez,radius,capped", "bx,by,bz,ax,ay,az,radius,capped"
    };
    static const char *const what[] = {
        "sphere of centre c and radius; the textbook quadratic "
        "|o + t d - c|^2 = radius^2",
        "disk of centre c, normal a (not unit) and radius; the plane "
        "equation t = (c - o).a / (d.a), then |p - c| <= radius",
        "cylinder about the segment from b (base) to e (top), capped if "
        "capped = 1; the textbook quadratic of the distance from the axis "
        "line, 0 <= (p - b).w <= H, and the plane equations of the caps",
        "cone with apex a over the disk of the given radius at b, closed by "
        "that disk if capped = 1; the textbook quadratic "
        "((p - a).v)^2 = cos^2(alpha) |p - a|^2, 0 <= (p - a).v <= H, and "
        "the base plane"
    };
    fprintf(o->f,
            "# %s.csv - rays against the %s of app. D (svet).\n"
            "# Written by tools/vectors_quadrics.c; checked by "
            "tests/test_%s.c. Shape: %s.\n"
            "# Inputs are floats, printed with 17 digits so that float and "
            "double read the same value. The ray is o + t d, t > 0,\n"
            "# d not unit.\n"
            "# Expected values: the nearest hit in long double by the "
            "textbook formula (source column), rounded to 17 digits;\n"
            "# hit = 0 leaves t, p and n empty. n is the unit normal out of "
            "the solid (the disk: along a).\n"
            "# tol_float / tol_double: absolute tolerance on each coordinate "
            "of p and on the distance t |d|; ntol_*: on each\n"
            "# component of n. tol = 64 eps S / cos, S the largest "
            "coordinate or size in the row, cos = |d.n|/|d| (rays are\n"
            "# kept only with cos >= 0.05 and a hit or miss that survives "
            "growing and shrinking the shape by 0.1%%);\n"
            "# ntol = 64 eps (1 + S / (cos rho)), rho the radius of "
            "curvature of the face hit (0 for flat faces: ntol = 64 eps).\n"
            "# Rows with source 'exact' have values exact in binary (cos may "
            "be 0: tol = 64 eps S).\n",
            kind_name[kind], kind_name[kind], kind_name[kind], what[kind]);
    fprintf(o->f, "case,ox,oy,oz,dx,dy,dz,%s,hit,t,px,py,pz,nx,ny,nz,"
                  "tol_float,ntol_float,tol_double,ntol_double,source\n",
            params[kind]);
}

static void close_out(out_t *o)
{
    vectors_close(o->f, o->dir, o->name);
    printf("%s/%s: %d rows\n", o->dir, o->name, o->rows);
}

static double maxabs3(const float a[3])
{
    return fmax(fabs((double)a[0]),
                fmax(fabs((double)a[1]), fabs((double)a[2])));
}

static void print3(FILE *f, const float a[3])
{
    fprintf(f, ",%.17g,%.17g,%.17g", (double)a[0], (double)a[1], (double)a[2]);
}

/* Write one row; exact rows get the cos-free tolerance. */
static void row(out_t *out, const char *name, const shape_t *s,
                const float o[3], const float d[3], const char *source,
                bool exact)
{
    expect_t e = trace(s, o, d);
    FILE *f = out->f;
    fprintf(f, "%s", name);
    print3(f, o);
    print3(f, d);
    print3(f, s->a);
    if (s->kind != SPHERE)
        print3(f, s->b);
    fprintf(f, ",%.17g", (double)s->radius);
    if (s->kind == CYLINDER || s->kind == CONE)
        fprintf(f, ",%d", s->capped);
    if (!e.hit) {
        fprintf(f, ",0,,,,,,,,,,,,%s\n", source);
        out->rows++;
        return;
    }
    double S = fmax(maxabs3(o), fmax(maxabs3(s->a), (double)s->radius));
    if (s->kind != SPHERE && s->kind != DISK)
        S = fmax(S, maxabs3(s->b));
    for (int k = 0; k < 3; k++)
        S = fmax(S, fabs((double)e.p[k]));
    double cosine = exact ? 1 : (double)e.cosine;
    double curv = e.curvature > 0 ? S / (cosine * (double)e.curvature) : 0;
    const double eps[2] = { (double)FLT_EPSILON, DBL_EPSILON };
    fprintf(f, ",1,%.17Lg,%.17Lg,%.17Lg,%.17Lg,%.17Lg,%.17Lg,%.17Lg", e.t,
            e.p[0], e.p[1], e.p[2], e.n[0], e.n[1], e.n[2]);
    for (int b = 0; b < 2; b++)
        fprintf(f, ",%.3g,%.3g", 64 * eps[b] * S / cosine,
                64 * eps[b] * (1 + curv));
    fprintf(f, ",%s\n", source);
    out->rows++;
}

/* A random ray that hits or misses the shape robustly: the outcome and
 * the face survive growing and shrinking the shape by 0.1%, and a hit is
 * not grazing. Returns false to ask for another. */
static bool robust(const shape_t *s, const float o[3], const float d[3])
{
    expect_t e = trace(s, o, d);
    shape_t big = scaled(s, 1.001f), small = scaled(s, 0.999f);
    expect_t eb = trace(&big, o, d), es = trace(&small, o, d);
    if (e.hit != eb.hit || e.hit != es.hit)
        return false;
    if (!e.hit)
        return true;
    if (e.face != eb.face || e.face != es.face || e.cosine < 0.05L)
        return false;
    /* keep away from the cone's apex, where the normal turns fast */
    return !(s->kind == CONE && e.face == 0 &&
             e.curvature < 0.05L * (ld)s->radius);
}

static void random_rows(out_t *out, pcg32_t *g, int n)
{
    int made = 0, hits = 0;
    while (made < n) {
        shape_t s;
        memset(&s, 0, sizeof s);
        s.kind = out->kind;
        double scale = pow(10.0, 2 * uniform(g) - 1); /* 0.1 .. 10 */
        double c[3], w[3], u[3];
        random_dir(w, g);
        for (int i = 0; i < 3; i++)
            c[i] = scale * 20 * (uniform(g) - 0.5);
        s.radius = (float)(scale * (0.3 + uniform(g)));
        double H = scale * (0.5 + 2 * uniform(g));
        for (int i = 0; i < 3; i++) {
            s.a[i] = (float)c[i];
            s.b[i] = (float)(s.kind == DISK ? w[i] : c[i] + H * w[i]);
        }
        if (s.kind == SPHERE || s.kind == DISK)
            H = 0;
        s.capped = (int)(pcg32_next(g) & 1);
        /* origin 1.5 .. 6 sizes away (inside, one time in eight), aimed
         * at a random point near the shape, with a direction length
         * 1/4 .. 4 */
        double size = fmax((double)s.radius, H), mid[3], o[3], t[3];
        for (int i = 0; i < 3; i++)
            mid[i] = s.kind == SPHERE || s.kind == DISK
                         ? c[i]
                         : 0.5 * (c[i] + (double)s.b[i]);
        random_dir(u, g);
        double dist = size * (1.5 + 4.5 * uniform(g));
        if ((pcg32_next(g) & 7) == 0 && s.kind != DISK)
            dist = 0.3 * size * uniform(g);
        double len = pow(2.0, 4 * uniform(g) - 2);
        float fo[3], fd[3];
        random_dir(t, g);
        double reach = 1.3 * size * uniform(g);
        for (int i = 0; i < 3; i++) {
            o[i] = mid[i] + dist * u[i];
            fo[i] = (float)o[i];
            fd[i] = (float)(len * (mid[i] + reach * t[i] - o[i]));
        }
        if (!robust(&s, fo, fd))
            continue;
        expect_t e = trace(&s, fo, fd);
        /* about two hits in three */
        if (!e.hit && 3 * (made - hits) >= n)
            continue;
        char name[32];
        snprintf(name, sizeof name, "random%d", made);
        row(out, name, &s, fo, fd,
            s.kind == DISK ? "long double plane equation"
                           : "long double textbook quadratic",
            false);
        made++;
        hits += e.hit;
    }
}

static shape_t shape(int kind, float ax, float ay, float az, float bx,
                     float by, float bz, float radius, int capped)
{
    shape_t s = { kind, { ax, ay, az }, { bx, by, bz }, radius, capped };
    return s;
}

#define V(x, y, z) ((const float[3]){ (x), (y), (z) })

static void sphere_rows(out_t *o)
{
    shape_t s = shape(SPHERE, 1, 2, 3, 0, 0, 0, 2, 0);
    row(o, "along_x", &s, V(-9, 2, 3), V(1, 0, 0), "exact", true);
    row(o, "direction_length_1024", &s, V(-9, 2, 3), V(1024, 0, 0), "exact",
        true);
    row(o, "down_onto_north_pole", &s, V(1, 2, 10), V(0, 0, -1), "exact",
        true);
    row(o, "from_centre", &s, V(1, 2, 3), V(0, 1, 0), "exact", true);
    row(o, "from_inside_backwards", &s, V(2, 2, 3), V(-1, 0, 0), "exact",
        true);
    row(o, "beside", &s, V(-9, 4.5f, 3), V(1, 0, 0), "exact", true);
    row(o, "pointing_away", &s, V(-9, 2, 3), V(-1, 0, 0), "exact", true);
    shape_t u = shape(SPHERE, 0, 0, 0, 0, 0, 0, 1, 0);
    /* r^2 - |l|^2 = 0 exactly: the double root t = 2 */
    row(o, "tangent", &u, V(-2, 1, 0), V(1, 0, 0), "exact", true);
}

static void disk_rows(out_t *o)
{
    shape_t s = shape(DISK, 0, 0, 1, 0, 0, 3, 2, 0);
    row(o, "down_the_normal", &s, V(0.5f, 0.5f, 5), V(0, 0, -1), "exact",
        true);
    row(o, "up_from_below", &s, V(0.5f, 0.5f, -3), V(0, 0, 2), "exact", true);
    row(o, "parallel_in_plane", &s, V(-5, 0, 1), V(1, 0, 0), "exact", true);
    row(o, "parallel_above", &s, V(-5, 0, 1.5f), V(1, 0, 0), "exact", true);
    row(o, "outside_radius", &s, V(2.5f, 0, 5), V(0, 0, -1), "exact", true);
    shape_t t = shape(DISK, 1, -1, 2, 1, 1, 0, 1.5f, 0);
    row(o, "tilted", &t, V(4, 2, 2), V(-1, -1, 0), "exact", true);
}

static void cylinder_rows(out_t *o)
{
    shape_t c = shape(CYLINDER, 0, 0, 0, 0, 0, 4, 1, 1);
    shape_t u = shape(CYLINDER, 0, 0, 0, 0, 0, 4, 1, 0);
    row(o, "along_axis_capped", &c, V(0.5f, 0, -2), V(0, 0, 1), "exact", true);
    row(o, "along_axis_open", &u, V(0.5f, 0, -2), V(0, 0, 1), "exact", true);
    row(o, "across", &c, V(-5, 0, 2), V(1, 0, 0), "exact", true);
    row(o, "from_inside_open", &u, V(0, 0, 2), V(0, 1, 0), "exact", true);
    row(o, "top_cap_from_above", &c, V(0, 0.5f, 10), V(0, 0, -1), "exact",
        true);
    row(o, "over_the_top", &c, V(-5, 0, 4.5f), V(1, 0, 0), "exact", true);
    shape_t t = shape(CYLINDER, 1, 1, 1, 3, 3, 1, 1, 1);
    row(o, "tilted_axis_across", &t, V(2, 2, -4), V(0, 0, 1), "exact", true);
}

static void cone_rows(out_t *o)
{
    shape_t c = shape(CONE, 0, 0, 0, 0, 0, 2, 1, 1);
    shape_t u = shape(CONE, 0, 0, 0, 0, 0, 2, 1, 0);
    row(o, "down_the_axis_onto_the_apex", &c, V(0, 0, 5), V(0, 0, -1),
        "exact", true);
    row(o, "across_at_half_height", &c, V(-5, 0, 1), V(1, 0, 0),
        "long double textbook quadratic", false);
    row(o, "base_from_below", &c, V(0.25f, 0, -3), V(0, 0, 1), "exact", true);
    row(o, "up_inside_the_open_cone", &u, V(0.25f, 0, -3), V(0, 0, 1),
        "long double textbook quadratic", false);
    row(o, "above_the_apex_misses_the_upper_nappe", &c, V(-5, 0, 2.5f),
        V(1, 0, 0), "exact", true);
    row(o, "parallel_to_a_generator", &u, V(0.5f, 0, -1), V(-1, 0, 2),
        "long double; linear case a = 0", false);
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s OUTDIR\n", argv[0]);
        return 2;
    }
    void (*special[])(out_t *) = { sphere_rows, disk_rows, cylinder_rows,
                                   cone_rows };
    for (int kind = SPHERE; kind <= CONE; kind++) {
        out_t out;
        pcg32_t g;
        pcg32_seed(&g, 20240 + (uint64_t)kind, 7);
        open_out(&out, argv[1], kind);
        special[kind](&out);
        random_rows(&out, &g, 60);
        close_out(&out);
    }
    return 0;
}
