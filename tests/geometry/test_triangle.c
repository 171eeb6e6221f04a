/*
 * test_triangle.c - the triangle of app. D and the watertight test of Woop,
 * Benthin, Wald 2013: exact hits and misses, the open interval (tmin, tmax),
 * parallel and degenerate cases, no ray slipping through closed meshes
 * (octahedron, subdivided icosahedron) at every scale, the geomcheck
 * harness, shading normals, tests/vectors/triangle.csv, and a NaN sweep.
 */
#include "testutil.h"
#include "geomcheck.h"
#include "primcheck.h"
#include "geometry/triangle.h"

#include <stdlib.h>
#include <string.h>

static COBJECT *tri(real x0, real y0, real z0, real x1, real y1, real z1,
                    real x2, real y2, real z2)
{
    VECTOR3 p0 = { x0, y0, z0 }, p1 = { x1, y1, z1 }, p2 = { x2, y2, z2 };
    svet_error err;
    COBJECT *o = triangle_new(p0, p1, p2, &err);
    ck_assert_msg(o != NULL, "%s", err.msg);
    return o;
}

static bool shoot(const COBJECT *o, real ox, real oy, real oz, real dx,
                  real dy, real dz, real tmin, real tmax)
{
    ray_t r = { { ox, oy, oz }, { dx, dy, dz } };
    hit_t h;
    return cobject_intersect(o, &r, tmin, tmax, &h);
}

START_TEST(triangle_hit_has_exact_t_point_barycentrics_and_frame)
{
    COBJECT *o = tri(0, 0, 0, 1, 0, 0, 0, 1, 0);
    ray_t r = { { REAL_C(0.25), REAL_C(0.25), 1 }, { 0, 0, -2 } };
    hit_t h;
    ck_assert(cobject_intersect(o, &r, 0, (real)INFINITY, &h));
    ck_assert(h.t == REAL_C(0.5));
    ck_assert(h.b[0] == REAL_C(0.5) && h.b[1] == REAL_C(0.25) &&
              h.b[2] == REAL_C(0.25));
    PATHPOINT pp;
    cobject_fill(o, &r, &h, &pp);
    ck_assert(pp.cross_point[X] == REAL_C(0.25) &&
              pp.cross_point[Y] == REAL_C(0.25) && pp.cross_point[Z] == 0);
    /* ng along (p1 - p0) x (p2 - p0) = +z; u along dP/ds = p1 - p0 */
    ck_assert(pp.ng[X] == 0 && pp.ng[Y] == 0 && pp.ng[Z] == 1);
    ck_assert(pp.n[Z] == 1 && pp.u[X] == 1 && pp.v[Y] == 1);
    ck_assert(pp.st[0] == REAL_C(0.25) && pp.st[1] == REAL_C(0.25));
    ck_assert(pp.dpds[X] == 1 && pp.dpdt[Y] == 1);
    ck_assert(pp.r_dist == 1 && pp.bout);
    ck_assert(o->ops->area(o) == REAL_C(0.5));
    bbox_t b;
    o->ops->bounds(o, -1, &b);
    ck_assert(b.min[X] == 0 && b.max[X] == 1 && b.max[Y] == 1 &&
              b.min[Z] == 0 && b.max[Z] == 0);
    cobject_free(o);
}
END_TEST

START_TEST(triangle_is_hit_from_behind_and_keeps_its_geometric_normal)
{
    COBJECT *o = tri(0, 0, 0, 1, 0, 0, 0, 1, 0);
    ray_t r = { { REAL_C(0.5), REAL_C(0.25), -3 }, { 0, 0, 1 } };
    hit_t h;
    ck_assert(cobject_intersect(o, &r, 0, (real)INFINITY, &h));
    ck_assert(h.t == 3);
    PATHPOINT pp;
    cobject_fill(o, &r, &h, &pp);
    ck_assert(pp.ng[Z] == 1 && !pp.bout);
    cobject_free(o);
}
END_TEST

START_TEST(triangle_respects_the_open_interval_tmin_tmax)
{
    COBJECT *o = tri(0, 0, 0, 1, 0, 0, 0, 1, 0);
    real h = REAL_C(0.5), inf = (real)INFINITY;
    /* the hit is at t = 0.5 exactly */
    ck_assert(!shoot(o, REAL_C(0.25), REAL_C(0.25), 1, 0, 0, -2, 0, h));
    ck_assert(shoot(o, REAL_C(0.25), REAL_C(0.25), 1, 0, 0, -2, 0,
                    nextafter(h, inf)));
    ck_assert(!shoot(o, REAL_C(0.25), REAL_C(0.25), 1, 0, 0, -2, h, inf));
    ck_assert(shoot(o, REAL_C(0.25), REAL_C(0.25), 1, 0, 0, -2,
                    nextafter(h, REAL_C(0.0)), inf));
    /* behind the origin */
    ck_assert(!shoot(o, REAL_C(0.25), REAL_C(0.25), 1, 0, 0, 2, 0, inf));
    /* a negative tmin asks for hits behind the origin too */
    ck_assert(shoot(o, REAL_C(0.25), REAL_C(0.25), 1, 0, 0, 2, -1, inf));
    cobject_free(o);
}
END_TEST

START_TEST(triangle_misses_outside_its_edges_and_hits_on_them)
{
    COBJECT *o = tri(0, 0, 0, 1, 0, 0, 0, 1, 0);
    real inf = (real)INFINITY;
    /* just outside each edge, by one ulp of the coordinate */
    ck_assert(!shoot(o, REAL_C(0.5), -REAL_MIN * 64, 1, 0, 0, -1, 0, inf));
    ck_assert(!shoot(o, -REAL_MIN * 64, REAL_C(0.5), 1, 0, 0, -1, 0, inf));
    real ob = nextafter(REAL_C(0.5), REAL_C(1.0));
    ck_assert(!shoot(o, REAL_C(0.5), ob, 1, 0, 0, -1, 0, inf));
    /* exactly on the edges and through the corners: edges are inclusive */
    ck_assert(shoot(o, REAL_C(0.5), 0, 1, 0, 0, -1, 0, inf));
    ck_assert(shoot(o, 0, REAL_C(0.5), 1, 0, 0, -1, 0, inf));
    ck_assert(shoot(o, REAL_C(0.5), REAL_C(0.5), 1, 0, 0, -1, 0, inf));
    ck_assert(shoot(o, 0, 0, 1, 0, 0, -1, 0, inf));
    ck_assert(shoot(o, 1, 0, 1, 0, 0, -1, 0, inf));
    ck_assert(shoot(o, 0, 1, 1, 0, 0, -1, 0, inf));
    /* far away */
    ck_assert(!shoot(o, 5, 5, 1, 0, 0, -1, 0, inf));
    cobject_free(o);
}
END_TEST

START_TEST(rays_parallel_to_the_triangle_never_hit)
{
    COBJECT *o = tri(0, 0, 0, 1, 0, 0, 0, 1, 0);
    real inf = (real)INFINITY;
    /* above the plane */
    ck_assert(!shoot(o, -1, REAL_C(0.2), 1, 1, 0, 0, 0, inf));
    /* in the plane, across the triangle, along each axis and diagonally */
    ck_assert(!shoot(o, -1, REAL_C(0.2), 0, 1, 0, 0, 0, inf));
    ck_assert(!shoot(o, REAL_C(0.2), -1, 0, 0, 1, 0, 0, inf));
    ck_assert(!shoot(o, -1, -1, 0, 1, 1, 0, 0, inf));
    /* in the plane, along an edge */
    ck_assert(!shoot(o, -1, 0, 0, 1, 0, 0, 0, inf));
    /* a tilted triangle and random rays lying in its plane */
    VECTOR3 p0 = { 1, 2, 3 }, p1 = { 4, -1, 2 }, p2 = { 0, 5, -1 };
    svet_error err;
    COBJECT *t = triangle_new(p0, p1, p2, &err);
    pcg32_t g;
    pcg32_seed(&g, 3, 4);
    long n = 0;
    for (int i = 0; i < 20000; i++, n++) {
        /* origin and a target in the plane: affine combinations with
         * exactly representable weights k/8 */
        real a = (real)(int)pcg32_bounded(&g, 17) / 8 - 1;
        real b = (real)(int)pcg32_bounded(&g, 17) / 8 - 1;
        real c = (real)(int)pcg32_bounded(&g, 9) / 8;
        ray_t r;
        for (int k = 0; k < 3; k++) {
            r.o[k] = p0[k] + a * (p1[k] - p0[k]) + b * (p2[k] - p0[k]);
            r.d[k] = c * (p1[k] - p0[k]) + (1 - c) * (p2[k] - p0[k]);
        }
        hit_t h;
        ck_assert_msg(!cobject_intersect(t, &r, 0, inf, &h),
                      "in-plane ray %d hits at t = %g", i, (double)h.t);
    }
    test_report_cases("rays_parallel_to_the_triangle_never_hit", n);
    cobject_free(t);
    cobject_free(o);
}
END_TEST

/* Rays at a triangle through each of its points and edges and from all
 * directions; none may hit, none may produce a NaN. */
static long never_hit(const VECTOR3 p0, const VECTOR3 p1, const VECTOR3 p2,
                      pcg32_t *g)
{
    svet_error err;
    COBJECT *o = triangle_new(p0, p1, p2, &err);
    ck_assert_msg(o != NULL, "%s", err.msg);
    ck_assert(o->ops->area(o) == 0);
    const real *pts[3] = { p0, p1, p2 };
    long n = 0;
    for (int i = 0; i < 3000; i++, n++) {
        ray_t r;
        VECTOR3 target, w;
        const real *a = pts[i % 3], *b = pts[(i + 1) % 3];
        real s = pcg32_real(g);
        for (int k = 0; k < 3; k++)
            target[k] = a[k] + s * (b[k] - a[k]);
        if (i % 5 == 0)
            vec_copy(target, a);
        geomcheck_random_dir(w, g);
        vec_add_scaled(r.o, target, 1 + 10 * pcg32_real(g), w);
        vec_sub(r.d, target, r.o);
        hit_t h;
        real t;
        real bb[3] = { 0, 0, 0 };
        ck_assert(!cobject_intersect(o, &r, 0, (real)INFINITY, &h));
        ck_assert(!triangle_intersect_watertight(p0, p1, p2, &r, 0,
                                                 (real)INFINITY, &t, bb));
        ck_assert(!triangle_intersect_watertight(p0, p1, p2, &r,
                                                 -(real)INFINITY,
                                                 (real)INFINITY, &t, bb));
    }
    /* sampling a shape of no area: pdf 0, finite point */
    real u[2] = { REAL_C(0.3), REAL_C(0.7) };
    cobject_sample_t smp;
    o->ops->sample(o, u, &smp);
    ck_assert(smp.pdf == 0 && vec_is_finite(smp.p) && vec_is_finite(smp.n));
    cobject_free(o);
    return n;
}

START_TEST(degenerate_triangles_never_hit_and_never_give_nan)
{
    pcg32_t g;
    pcg32_seed(&g, 5, 6);
    long n = 0;
    VECTOR3 a = { 1, 2, 3 }, b = { 3, 5, 7 }, c = { 5, 8, 11 }; /* collinear */
    VECTOR3 d = { REAL_C(0.1), REAL_C(0.2), REAL_C(0.3) };
    VECTOR3 big = { REAL_C(1e6), -REAL_C(1e6), REAL_C(3e6) };
    VECTOR3 big2 = { REAL_C(2e6), -REAL_C(2e6), REAL_C(6e6) };
    n += never_hit(a, b, c, &g);     /* collinear, exactly */
    n += never_hit(a, c, b, &g);     /* collinear, middle vertex last */
    n += never_hit(a, a, b, &g);     /* repeated vertex */
    n += never_hit(a, b, b, &g);
    n += never_hit(d, d, d, &g);     /* a point */
    n += never_hit(big, big2, big, &g);
    VECTOR3 z = { 0, 0, 0 };
    n += never_hit(z, big, big2, &g); /* collinear through the origin */
    ck_assert(triangle_is_degenerate(a, b, c));
    VECTOR3 nan = { (real)NAN, 0, 0 };
    ck_assert(triangle_is_degenerate(a, b, nan));
    VECTOR3 p = { 0, 0, 0 }, q = { 1, 0, 0 }, s = { 1, REAL_C(1e-6), 0 };
    ck_assert(!triangle_is_degenerate(p, q, s)); /* a needle is not */
    test_report_cases("degenerate_triangles_never_hit_and_never_give_nan", n);
}
END_TEST

START_TEST(a_prepared_ray_gives_the_same_answers_bit_for_bit)
{
    /* one prepared ray against many triangles, as a mesh uses it; the
     * directions span huge and tiny lengths (the power-of-two rescaling) */
    pcg32_t g;
    pcg32_seed(&g, 16, 17);
    long n = 0;
    for (int i = 0; i < 2000; i++) {
        ray_t r;
        vec_set(r.o, 4 * pcg32_real(&g) - 2, 4 * pcg32_real(&g) - 2,
                4 * pcg32_real(&g) - 2);
        geomcheck_random_dir(r.d, &g);
        vec_scale(r.d, r.d, ldexp(REAL_C(1.0), (int)pcg32_bounded(&g, 80) - 40));
        triangle_ray_t pr;
        triangle_ray_prepare(&pr, &r);
        for (int j = 0; j < 20; j++, n++) {
            VECTOR3 p[3];
            for (int k = 0; k < 9; k++)
                p[k / 3][k % 3] = 2 * pcg32_real(&g) - 1;
            real t1 = -1, t2 = -1, b1[3] = { 0, 0, 0 }, b2[3] = { 0, 0, 0 };
            bool h1 = triangle_intersect_watertight(p[0], p[1], p[2], &r, 0,
                                                    (real)INFINITY, &t1, b1);
            bool h2 = triangle_intersect_prepared(p[0], p[1], p[2], &pr, 0,
                                                  (real)INFINITY, &t2, b2);
            ck_assert(h1 == h2);
            ck_assert(memcmp(&t1, &t2, sizeof t1) == 0 &&
                      memcmp(b1, b2, sizeof b1) == 0);
        }
    }
    ray_t zero = { { 0, 0, 0 }, { 0, 0, 0 } };
    triangle_ray_t pr;
    triangle_ray_prepare(&pr, &zero);
    VECTOR3 a = { -1, -1, 0 }, b = { 1, -1, 0 }, c = { 0, 1, 0 };
    real t, bb[3];
    ck_assert(!pr.ok);
    ck_assert(!triangle_intersect_prepared(a, b, c, &pr, -1, 1, &t, bb));
    test_report_cases("a_prepared_ray_gives_the_same_answers_bit_for_bit", n);
}
END_TEST

START_TEST(reported_t_is_a_mean_of_the_vertex_z)
{
    /* triangle.h promises that t 2^scale lies within gamma(8) max|z_i| of
     * the range of the vertices' z_i = sz (p_i - o)_kz, whatever the
     * angle: the parallelogram relies on it to skip a test early. Grazing
     * rays (direction 2^-k off the plane) are where t is least certain. */
    pcg32_t g;
    pcg32_seed(&g, 18, 19);
    long n = 0, hits = 0;
    for (int i = 0; i < 200000; i++) {
        VECTOR3 p[3], e1, e2, nrm, q, dir;
        for (int k = 0; k < 9; k++)
            p[k / 3][k % 3] = 2 * pcg32_real(&g) - 1;
        vec_sub(e1, p[1], p[0]);
        vec_sub(e2, p[2], p[0]);
        VVECTOR3(nrm, e1, e2);
        if (vec_normalize(nrm, nrm) == 0)
            continue;
        /* aim at a point of (or near) the triangle along a direction in
         * its plane, tilted by 2^-k */
        real b1 = pcg32_real(&g), b2 = pcg32_real(&g) * (1 - b1);
        for (int k = 0; k < 3; k++)
            q[k] = p[0][k] + b1 * e1[k] + b2 * e2[k];
        if (i % 3 == 0) /* at a vertex: t at an end of the range */
            vec_copy(q, p[i % 9 / 3]);
        geomcheck_random_dir(dir, &g);
        vec_add_scaled(dir, dir, -SVECTOR3(dir, nrm), nrm);
        vec_add_scaled(dir, dir,
                       ldexp(REAL_C(1.0), -(int)pcg32_bounded(&g, 30)), nrm);
        ray_t r;
        vec_add_scaled(r.o, q, -(2 * pcg32_real(&g)), dir);
        vec_scale(r.d, dir, ldexp(REAL_C(1.0), (int)pcg32_bounded(&g, 60) - 30));
        triangle_ray_t pr;
        triangle_ray_prepare(&pr, &r);
        real t, b[3];
        n++;
        if (!triangle_intersect_prepared(p[0], p[1], p[2], &pr, 0,
                                         (real)INFINITY, &t, b))
            continue;
        hits++;
        real z[3], lo = (real)INFINITY, hi = -(real)INFINITY, m = 0;
        for (int k = 0; k < 3; k++) {
            z[k] = pr.sz * (p[k][pr.kz] - pr.o[pr.kz]);
            lo = fmin(lo, z[k]);
            hi = fmax(hi, z[k]);
            m = fmax(m, fabs(z[k]));
        }
        real ts = ldexp(t, pr.scale);
        ck_assert_msg(ts >= lo - ray_gamma(8) * m &&
                          ts <= hi + ray_gamma(8) * m,
                      "t %a outside [%a, %a]", (double)ts, (double)lo,
                      (double)hi);
    }
    ck_assert(hits > n / 4);
    test_report_cases("reported_t_is_a_mean_of_the_vertex_z", n);
}
END_TEST

/* --- closed meshes -------------------------------------------------------- */

typedef struct {
    int n, cap;
    VECTOR3 (*v)[3];
} mesh_t;

static void mesh_add(mesh_t *m, const VECTOR3 a, const VECTOR3 b,
                     const VECTOR3 c)
{
    if (m->n == m->cap) {
        m->cap = m->cap ? 2 * m->cap : 64;
        m->v = realloc(m->v, (size_t)m->cap * sizeof *m->v);
        ck_assert_ptr_nonnull(m->v);
    }
    vec_copy(m->v[m->n][0], a);
    vec_copy(m->v[m->n][1], b);
    vec_copy(m->v[m->n][2], c);
    m->n++;
}

static void octahedron(mesh_t *m)
{
    for (int sx = -1; sx <= 1; sx += 2)
        for (int sy = -1; sy <= 1; sy += 2)
            for (int sz = -1; sz <= 1; sz += 2) {
                VECTOR3 a = { (real)sx, 0, 0 }, b = { 0, (real)sy, 0 },
                        c = { 0, 0, (real)sz };
                mesh_add(m, a, b, c);
            }
}

/* The icosahedron subdivided `level` times, midpoints pushed to the unit
 * sphere. mid(a, b) = unit(a + b) is the same float for both triangles of
 * an edge (a + b = b + a exactly), so the mesh is closed. */
static void subdivide(mesh_t *m, const VECTOR3 a, const VECTOR3 b,
                      const VECTOR3 c, int level)
{
    if (level == 0) {
        mesh_add(m, a, b, c);
        return;
    }
    VECTOR3 ab, bc, ca;
    vec_add(ab, a, b);
    vec_add(bc, b, c);
    vec_add(ca, c, a);
    vec_normalize(ab, ab);
    vec_normalize(bc, bc);
    vec_normalize(ca, ca);
    subdivide(m, a, ab, ca, level - 1);
    subdivide(m, ab, b, bc, level - 1);
    subdivide(m, ca, bc, c, level - 1);
    subdivide(m, ab, bc, ca, level - 1);
}

static void icosphere(mesh_t *m, int level)
{
    const real f = REAL_C(1.6180339887498949);
    const real v[12][3] = { { -1, f, 0 }, { 1, f, 0 }, { -1, -f, 0 },
                            { 1, -f, 0 }, { 0, -1, f }, { 0, 1, f },
                            { 0, -1, -f }, { 0, 1, -f }, { f, 0, -1 },
                            { f, 0, 1 }, { -f, 0, -1 }, { -f, 0, 1 } };
    static const int face[20][3] = {
        { 0, 11, 5 }, { 0, 5, 1 }, { 0, 1, 7 }, { 0, 7, 10 }, { 0, 10, 11 },
        { 1, 5, 9 }, { 5, 11, 4 }, { 11, 10, 2 }, { 10, 7, 6 }, { 7, 1, 8 },
        { 3, 9, 4 }, { 3, 4, 2 }, { 3, 2, 6 }, { 3, 6, 8 }, { 3, 8, 9 },
        { 4, 9, 5 }, { 2, 4, 11 }, { 6, 2, 10 }, { 8, 6, 7 }, { 9, 8, 1 } };
    VECTOR3 u[12];
    for (int i = 0; i < 12; i++)
        vec_normalize(u[i], v[i]);
    for (int i = 0; i < 20; i++)
        subdivide(m, u[face[i][0]], u[face[i][1]], u[face[i][2]], level);
}

/* The mesh scaled by s and moved to c, each vertex transformed once per
 * use by the same arithmetic, so shared vertices stay shared. */
static COBJECT **place(const mesh_t *m, real s, const VECTOR3 c,
                       VECTOR3 (*out)[3])
{
    COBJECT **objs = malloc((size_t)m->n * sizeof *objs);
    ck_assert_ptr_nonnull(objs);
    for (int i = 0; i < m->n; i++) {
        for (int j = 0; j < 3; j++)
            vec_add_scaled(out[i][j], c, s, m->v[i][j]);
        svet_error err;
        objs[i] = triangle_new(out[i][0], out[i][1], out[i][2], &err);
        ck_assert_msg(objs[i] != NULL, "%s", err.msg);
    }
    return objs;
}

static bool any_hit(COBJECT **objs, int n, const ray_t *r)
{
    for (int i = 0; i < n; i++) {
        hit_t h;
        if (cobject_intersect(objs[i], r, 0, (real)INFINITY, &h))
            return true;
    }
    return false;
}

/* Rays from two interior points through every vertex, the midpoint of
 * every edge, random points of the edges and random directions; and from
 * outside, straight at edge points. Every one must hit. */
static long mesh_is_watertight(const mesh_t *m, pcg32_t *g)
{
    int ns;
    const real *sc = primcheck_scales(&ns);
    VECTOR3 (*v)[3] = malloc((size_t)m->n * sizeof *v);
    ck_assert_ptr_nonnull(v);
    long n = 0;
    for (int i = 0; i < ns; i++) {
        for (int away = 0; away < 2; away++) {
            VECTOR3 c = { 0, 0, 0 };
            if (away)
                vec_set(c, 7 * sc[i], -3 * sc[i], 5 * sc[i]);
            COBJECT **objs = place(m, sc[i], c, v);
            VECTOR3 inner[2];
            vec_copy(inner[0], c);
            VECTOR3 off = { REAL_C(0.11), REAL_C(-0.23), REAL_C(0.17) };
            vec_add_scaled(inner[1], c, sc[i], off);
            for (int f = 0; f < m->n; f++) {
                for (int e = 0; e < 3; e++) {
                    const real *a = v[f][e], *b = v[f][(e + 1) % 3];
                    VECTOR3 targets[3];
                    vec_copy(targets[0], a);
                    for (int k = 0; k < 3; k++) {
                        targets[1][k] = REAL_C(0.5) * (a[k] + b[k]);
                        real s = pcg32_real(g);
                        targets[2][k] = a[k] + s * (b[k] - a[k]);
                    }
                    for (int o = 0; o < 2; o++)
                        for (int k = 0; k < 3; k++) {
                            ray_t r;
                            vec_copy(r.o, inner[o]);
                            vec_sub(r.d, targets[k], r.o);
                            ck_assert_msg(any_hit(objs, m->n, &r),
                                          "ray from inside through (%.9g "
                                          "%.9g %.9g) at scale %g slips "
                                          "through", (double)targets[k][X],
                                          (double)targets[k][Y],
                                          (double)targets[k][Z], (double)sc[i]);
                            n++;
                        }
                    /* from outside, aimed at the edge point through the
                     * centre, so that the edge faces the ray */
                    for (int k = 1; k < 3; k++) {
                        ray_t r;
                        VECTOR3 out;
                        vec_sub(out, targets[k], c);
                        vec_add_scaled(r.o, targets[k], 2, out);
                        vec_sub(r.d, targets[k], r.o);
                        ck_assert_msg(any_hit(objs, m->n, &r),
                                      "ray from outside at edge point (%.9g "
                                      "%.9g %.9g) at scale %g misses",
                                      (double)targets[k][X],
                                      (double)targets[k][Y],
                                      (double)targets[k][Z], (double)sc[i]);
                        n++;
                    }
                }
                ray_t r;
                vec_copy(r.o, inner[f % 2]);
                geomcheck_random_dir(r.d, g);
                ck_assert(any_hit(objs, m->n, &r));
                n++;
            }
            for (int f = 0; f < m->n; f++)
                cobject_free(objs[f]);
            free(objs);
        }
    }
    free(v);
    return n;
}

START_TEST(no_ray_slips_through_a_closed_octahedron)
{
    mesh_t m = { 0, 0, NULL };
    octahedron(&m);
    pcg32_t g;
    pcg32_seed(&g, 8, 9);
    long n = mesh_is_watertight(&m, &g);
    free(m.v);
    test_report_cases("no_ray_slips_through_a_closed_octahedron", n);
}
END_TEST

START_TEST(no_ray_slips_through_a_subdivided_icosahedron)
{
    mesh_t m = { 0, 0, NULL };
    icosphere(&m, 2); /* 320 triangles */
    ck_assert_int_eq(m.n, 320);
    pcg32_t g;
    pcg32_seed(&g, 10, 11);
    long n = mesh_is_watertight(&m, &g);
    free(m.v);
    test_report_cases("no_ray_slips_through_a_subdivided_icosahedron", n);
}
END_TEST

/* --- the geomcheck harness -------------------------------------------------- */

static COBJECT *make_triangle(real s, const VECTOR3 c, void *ctx)
{
    (void)ctx;
    VECTOR3 p[3];
    const real shape[3][3] = { { REAL_C(0.3), REAL_C(-0.5), REAL_C(0.1) },
                               { REAL_C(0.9), REAL_C(0.4), REAL_C(-0.2) },
                               { REAL_C(-0.6), REAL_C(0.7), REAL_C(0.5) } };
    for (int i = 0; i < 3; i++)
        vec_add_scaled(p[i], c, s, shape[i]);
    svet_error err;
    COBJECT *o = triangle_new(p[0], p[1], p[2], &err);
    ck_assert_msg(o != NULL, "%s", err.msg);
    return o;
}

START_TEST(triangle_spawned_rays_never_rehit_at_any_scale)
{
    test_report_cases("triangle_spawned_rays_never_rehit_at_any_scale",
                      primcheck_over_scales(make_triangle, NULL,
                                            PRIMCHECK_SPAWN, GEOMCHECK_FLAT,
                                            true, 100));
}
END_TEST

START_TEST(triangle_sampled_points_are_hit_at_any_scale)
{
    test_report_cases("triangle_sampled_points_are_hit_at_any_scale",
                      primcheck_over_scales(make_triangle, NULL,
                                            PRIMCHECK_SAMPLED, GEOMCHECK_FLAT,
                                            true, 200));
}
END_TEST

START_TEST(triangle_hits_are_finite_at_any_scale)
{
    test_report_cases("triangle_hits_are_finite_at_any_scale",
                      primcheck_over_scales(make_triangle, NULL,
                                            PRIMCHECK_FINITE, GEOMCHECK_FLAT,
                                            true, 300));
}
END_TEST

START_TEST(triangle_sampling_is_uniform_with_pdf_one_over_area)
{
    test_report_cases("triangle_sampling_is_uniform_with_pdf_one_over_area",
                      primcheck_over_scales(make_triangle, NULL,
                                            PRIMCHECK_AREA, GEOMCHECK_FLAT,
                                            true, 400));
}
END_TEST

START_TEST(triangle_samples_are_uniform_by_area)
{
    /* The fraction of N uniform samples that falls into the sub-triangle
     * cut off by the midpoints of two edges must be 1/4: a binomial with
     * sd sqrt(p (1 - p) / N) = 0.0019 for N = 50000; 5 sd = 0.0097. */
    COBJECT *o = tri(0, 0, 0, 4, 0, 0, 1, 3, 0);
    pcg32_t g;
    pcg32_seed(&g, 12, 13);
    const int N = 50000;
    int in = 0;
    for (int i = 0; i < N; i++) {
        real u[2] = { pcg32_real(&g), pcg32_real(&g) };
        cobject_sample_t s;
        o->ops->sample(o, u, &s);
        ck_assert(s.p[Z] == 0 && s.n[Z] == 1);
        /* the corner triangle at p0: s + t <= 1/2 in the (s, t) of
         * p = p0 + s e1 + t e2; with e1 = (4,0), e2 = (1,3):
         * t = y/3, s = (x - t)/4 */
        real t = s.p[Y] / 3, ss = (s.p[X] - t) / 4;
        if (ss + t <= REAL_C(0.5))
            in++;
    }
    ck_assert_near((double)in / N, 0.25, 0.0097);
    test_report_cases("triangle_samples_are_uniform_by_area", N);
    cobject_free(o);
}
END_TEST

/* --- shading normals ------------------------------------------------------- */

START_TEST(shading_normals_are_interpolated_and_ng_stays_geometric)
{
    COBJECT *o = tri(0, 0, 0, 1, 0, 0, 0, 1, 0);
    VECTOR3 n0 = { 0, 0, 2 }, n1 = { 1, 0, 1 }, n2 = { 0, 1, 1 };
    svet_error err;
    ck_assert_int_eq(triangle_set_normals(o, n0, n1, n2, &err), SVET_OK);
    ray_t r = { { REAL_C(0.25), REAL_C(0.25), 1 }, { 0, 0, -1 } };
    hit_t h;
    ck_assert(cobject_intersect(o, &r, 0, (real)INFINITY, &h));
    PATHPOINT pp;
    cobject_fill(o, &r, &h, &pp);
    ck_assert(pp.ng[Z] == 1);
    /* 0.5 (0,0,1) + 0.25 (1,0,1)/sqrt2 + 0.25 (0,1,1)/sqrt2, normalised */
    double a = 0.25 / sqrt(2.0), z = 0.5 + 2 * a;
    double len = sqrt(2 * a * a + z * z);
    ck_assert_near(pp.n[X], a / len, 4 * REAL_EPSILON);
    ck_assert_near(pp.n[Y], a / len, 4 * REAL_EPSILON);
    ck_assert_near(pp.n[Z], z / len, 4 * REAL_EPSILON);
    ck_assert_near(SVECTOR3(pp.u, pp.n), 0, 4 * REAL_EPSILON);
    ck_assert_near(SVECTOR3(pp.v, pp.n), 0, 4 * REAL_EPSILON);
    VECTOR3 c;
    VVECTOR3(c, pp.u, pp.v);
    for (int k = 0; k < 3; k++)
        ck_assert_near(c[k], pp.n[k], 8 * REAL_EPSILON);
    /* errors: a zero normal, a NaN, not a triangle */
    VECTOR3 zero = { 0, 0, 0 }, nan = { (real)NAN, 0, 1 };
    ck_assert_int_eq(triangle_set_normals(o, zero, n1, n2, &err),
                     SVET_ERR_RANGE);
    ck_assert_int_eq(triangle_set_normals(o, n0, nan, n2, &err),
                     SVET_ERR_RANGE);
    COBJECT not_tri;
    static const cobject_ops other = { "other", NULL, NULL, NULL, NULL, NULL,
                                       NULL, NULL };
    cobject_init(&not_tri, &other, NULL);
    ck_assert_int_eq(triangle_set_normals(&not_tri, n0, n1, n2, &err),
                     SVET_ERR_RANGE);
    ck_assert_int_eq(triangle_set_normals(NULL, n0, n1, n2, NULL),
                     SVET_ERR_RANGE);
    cobject_free(o);
}
END_TEST

START_TEST(triangle_rejects_non_finite_and_unrepresentable_input)
{
    VECTOR3 a = { 0, 0, 0 }, b = { 1, 0, 0 }, nan = { 0, (real)NAN, 0 };
    VECTOR3 inf = { (real)INFINITY, 0, 0 };
    svet_error err;
    ck_assert_ptr_null(triangle_new(a, b, nan, &err));
    ck_assert_int_eq(err.status, SVET_ERR_RANGE);
    ck_assert_msg(strstr(err.msg, "p2") != NULL, "%s", err.msg);
    ck_assert_ptr_null(triangle_new(inf, a, b, &err));
    ck_assert_int_eq(err.status, SVET_ERR_RANGE);
    /* finite corners whose edges overflow */
    VECTOR3 hi = { REAL_MAX, 0, 0 }, lo = { -REAL_MAX, 0, 0 },
            up = { 0, REAL_MAX, 0 };
    ck_assert_ptr_null(triangle_new(hi, lo, up, &err));
    ck_assert_int_eq(err.status, SVET_ERR_RANGE);
    ck_assert_ptr_null(triangle_new(a, b, nan, NULL)); /* err may be NULL */
}
END_TEST

/* --- reference vectors --------------------------------------------------- */

START_TEST(triangle_matches_the_reference_vectors)
{
    testcsv_t c;
    testcsv_open(&c, "triangle.csv");
    long n = 0;
    for (; testcsv_next(&c); n++) {
        VECTOR3 p0, p1, p2;
        primcheck_csv_vec(&c, "p0", p0);
        primcheck_csv_vec(&c, "p1", p1);
        primcheck_csv_vec(&c, "p2", p2);
        svet_error err;
        COBJECT *o = triangle_new(p0, p1, p2, &err);
        ck_assert_msg(o != NULL, "%s", err.msg);
        PATHPOINT pp;
        primcheck_csv_hit(&c, o, "p", "n", &pp);
        cobject_free(o);
    }
    testcsv_close(&c);
    ck_assert_int_gt(n, 0);
    test_report_cases("triangle_matches_the_reference_vectors", n);
}
END_TEST

START_TEST(triangle_sweep_never_returns_nan_or_inf)
{
    pcg32_t g;
    pcg32_seed(&g, 14, 15);
    long n = 0;
    for (int i = 0; i < 200; i++) {
        /* random triangles over many scales, some degenerate */
        VECTOR3 p[3];
        real s = ldexp(REAL_C(1.0), (int)pcg32_bounded(&g, 100) - 50);
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++)
                p[j][k] = s * (2 * pcg32_real(&g) - 1);
        if (i % 4 == 1)
            vec_copy(p[2], p[0]);
        if (i % 4 == 2)
            for (int k = 0; k < 3; k++)
                p[2][k] = p[0][k] + 2 * (p[1][k] - p[0][k]);
        svet_error err;
        COBJECT *o = triangle_new(p[0], p[1], p[2], &err);
        ck_assert_msg(o != NULL, "%s", err.msg);
        n += primcheck_sweep_finite(o, 2000, (uint64_t)i);
        cobject_free(o);
    }
    test_report_cases("triangle_sweep_never_returns_nan_or_inf", n);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("triangle");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, triangle_hit_has_exact_t_point_barycentrics_and_frame);
    tcase_add_test(tc, triangle_is_hit_from_behind_and_keeps_its_geometric_normal);
    tcase_add_test(tc, triangle_respects_the_open_interval_tmin_tmax);
    tcase_add_test(tc, triangle_misses_outside_its_edges_and_hits_on_them);
    tcase_add_test(tc, rays_parallel_to_the_triangle_never_hit);
    tcase_add_test(tc, degenerate_triangles_never_hit_and_never_give_nan);
    tcase_add_test(tc, a_prepared_ray_gives_the_same_answers_bit_for_bit);
    tcase_add_test(tc, reported_t_is_a_mean_of_the_vertex_z);
    tcase_add_test(tc, no_ray_slips_through_a_closed_octahedron);
    tcase_add_test(tc, no_ray_slips_through_a_subdivided_icosahedron);
    tcase_add_test(tc, triangle_spawned_rays_never_rehit_at_any_scale);
    tcase_add_test(tc, triangle_sampled_points_are_hit_at_any_scale);
    tcase_add_test(tc, triangle_hits_are_finite_at_any_scale);
    tcase_add_test(tc, triangle_sampling_is_uniform_with_pdf_one_over_area);
    tcase_add_test(tc, triangle_samples_are_uniform_by_area);
    tcase_add_test(tc, shading_normals_are_interpolated_and_ng_stays_geometric);
    tcase_add_test(tc, triangle_rejects_non_finite_and_unrepresentable_input);
    tcase_add_test(tc, triangle_matches_the_reference_vectors);
    tcase_add_test(tc, triangle_sweep_never_returns_nan_or_inf);
    suite_add_tcase(s, tc);
    return s;
}
