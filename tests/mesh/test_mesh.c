/*
 * test_mesh.c - triangle meshes (ch. 7): the per-ray watertight test is
 * triangle.h's bit for bit, and the batch sign test's mask the plain
 * lanes'; surface() interpolates normals and texture coordinates and
 * keeps n on ng's side; area and alias-table sampling;
 * the geometric robustness harness on a closed mesh; input checks.
 */
#include "testutil.h"
#include "geomcheck.h"
#include "mesh/mesh.h"
#include "mesh/meshgen.h"
#include "core/rng.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A mesh from literal arrays (copied into malloc'd ones). */
static COBJECT *make_mesh(int nv, const real (*p)[3], const real (*n)[3],
                          const real (*st)[2], int nt, const int32_t (*tri)[3])
{
    mesh_t m = { 0 };
    m.nverts = nv;
    m.ntris = nt;
    m.p = malloc((size_t)nv * sizeof *m.p);
    m.tri = malloc((size_t)nt * sizeof *m.tri);
    memcpy(m.p, p, (size_t)nv * sizeof *m.p);
    memcpy(m.tri, tri, (size_t)nt * sizeof *m.tri);
    if (n) {
        m.n = malloc((size_t)nv * sizeof *m.n);
        memcpy(m.n, n, (size_t)nv * sizeof *m.n);
    }
    if (st) {
        m.st = malloc((size_t)nv * sizeof *m.st);
        memcpy(m.st, st, (size_t)nv * sizeof *m.st);
    }
    COBJECT *o;
    svet_error e;
    ck_assert_msg(mesh_new(&o, &m, &e) == SVET_OK, "%s", e.msg);
    return o;
}

static void random_point(VECTOR3 p, pcg32_t *g, real scale)
{
    for (int k = 0; k < 3; k++)
        p[k] = scale * (2 * pcg32_real(g) - 1);
}

/* The fast path must give the bits of triangle_intersect_watertight: the
 * grids rely on it (brute force and grids agree exactly). Rays aimed at
 * vertices and edge midpoints make edge functions round to zero (the
 * fallback path); tiny and huge directions take the rescaling path. */
START_TEST(per_ray_test_matches_the_triangle_test_bit_for_bit)
{
    pcg32_t g;
    pcg32_seed(&g, 61, 1);
    long cases = 0, hits = 0, edge = 0;
    for (int i = 0; i < 200000; i++) {
        real q[9];
        for (int k = 0; k < 9; k++)
            q[k] = 2 * pcg32_real(&g) - 1;
        if (i % 7 == 0) /* axis-aligned triangles: many exact zeros */
            for (int k = 0; k < 9; k++)
                q[k] = (real)(int)(4 * q[k]) / 4;
        ray_t r;
        random_point(r.o, &g, 3);
        VECTOR3 target;
        int mode = i % 4;
        real b0 = pcg32_real(&g), b1 = (1 - b0) * pcg32_real(&g);
        if (mode == 1) { /* a vertex */
            int v = (int)pcg32_bounded(&g, 3);
            vec_copy(target, q + 3 * v);
        } else if (mode == 2) { /* an edge midpoint */
            int v = (int)pcg32_bounded(&g, 3), w = (v + 1) % 3;
            for (int k = 0; k < 3; k++)
                target[k] = REAL_C(0.5) * (q[3 * v + k] + q[3 * w + k]);
        } else {
            for (int k = 0; k < 3; k++)
                target[k] = b0 * q[k] + b1 * q[3 + k] +
                            (1 - b0 - b1) * q[6 + k];
        }
        vec_sub(r.d, target, r.o);
        if (i % 11 == 0)
            vec_scale(r.d, r.d, REAL_C(1e-9));
        if (i % 13 == 0)
            vec_scale(r.d, r.d, REAL_C(1e9));
        if (i % 17 == 0)
            r.d[i % 3] = 0;
        real tmin = i % 5 == 0 ? -1 : 0;
        real tmax = i % 3 == 0 ? (real)INFINITY : 1 + pcg32_real(&g);
        mesh_ray_t mr;
        mesh_ray_prepare(&mr, &r);
        real t1 = -7, t2 = -7, b_1[3] = { 0 }, b_2[3] = { 0 };
        bool h1 = triangle_intersect_watertight(q, q + 3, q + 6, &r, tmin,
                                                tmax, &t1, b_1);
        bool h2 = triangle_is_degenerate(q, q + 3, q + 6)
                      ? false
                      : mesh_ray_intersect(q, &mr, tmin, tmax, &t2, b_2);
        ck_assert_msg(h1 == h2, "case %d: hit %d vs %d", i, h1, h2);
        if (h1) {
            ck_assert_msg(memcmp(&t1, &t2, sizeof t1) == 0 &&
                              memcmp(b_1, b_2, sizeof b_1) == 0,
                          "case %d: t %.9g vs %.9g", i, (double)t1,
                          (double)t2);
            hits++;
            edge += mode == 1 || mode == 2;
        }
        cases++;
    }
    ck_assert(hits > 10000 && edge > 1000);
    test_report_cases("per_ray_test_matches_the_triangle_test_bit_for_bit",
                      cases);
}
END_TEST

/* A corner for the batch test's adversarial cases: kind 0 random in
 * [-1, 1]^3, 1 on a quarter grid (exact zeros in the edge functions),
 * 2 huge, 3 tiny, 4 NaN or infinite in one coordinate. */
static void batch_corner(real *p, pcg32_t *g, int kind)
{
    random_point(p, g, 1);
    if (kind == 1)
        for (int k = 0; k < 3; k++)
            p[k] = (real)(int)(4 * p[k]) / 4;
    else if (kind == 2)
        vec_scale(p, p, REAL_C(1e30));
    else if (kind == 3)
        vec_scale(p, p, REAL_C(1e-30));
    else if (kind == 4)
        p[pcg32_bounded(g, 3)] = pcg32_bounded(g, 2) ? (real)NAN
                                                      : (real)INFINITY;
}

/* The batch sign test (SSE2 where there is SSE2; two blocks of lanes at
 * once where there is AVX) gives the plain lane
 * loop's mask bit for bit, and rejects a lane only where the watertight
 * test misses it: random triangles, triangles on a quarter grid, edge-on
 * ones (the ray lies in their plane), degenerate ones (a repeated corner,
 * collinear corners), huge, tiny, NaN and infinite corners; rays aimed at
 * a vertex, an edge midpoint or inside of lane 0's triangle, parallel to
 * an axis, and with tiny or huge directions (not fast: nothing rejected). */
START_TEST(batch_sign_test_matches_the_plain_lanes_and_never_rejects_a_hit)
{
    pcg32_t g;
    pcg32_seed(&g, 62, 3);
    long cases = 0, rejected = 0, kept = 0, hits = 0, soa_cases = 0;
    long wide_cases = 0;
    for (int i = 0; i < 50000; i++) {
        real q[MESH_BATCH][9];
        for (int j = 0; j < MESH_BATCH; j++) {
            int kind = (int)pcg32_bounded(&g, 10);
            kind = kind < 5 ? 0 : kind - 4; /* half of them random */
            for (int v = 0; v < 3; v++)
                batch_corner(q[j] + 3 * v, &g, kind == 5 ? 0 : kind);
            if (kind == 5) { /* degenerate: a repeated or collinear corner */
                if (pcg32_bounded(&g, 2))
                    vec_copy(q[j] + 6, q[j]);
                else
                    for (int k = 0; k < 3; k++)
                        q[j][6 + k] = REAL_C(0.5) * (q[j][k] + q[j][3 + k]);
            }
        }
        ray_t r;
        random_point(r.o, &g, 3);
        VECTOR3 target;
        const real *q0 = q[0];
        int mode = i % 5;
        if (mode == 1) {
            vec_copy(target, q0 + 3 * pcg32_bounded(&g, 3));
        } else if (mode == 2) {
            int v = (int)pcg32_bounded(&g, 3), w = (v + 1) % 3;
            for (int k = 0; k < 3; k++)
                target[k] = REAL_C(0.5) * (q0[3 * v + k] + q0[3 * w + k]);
        } else {
            real b0 = pcg32_real(&g), b1 = (1 - b0) * pcg32_real(&g);
            for (int k = 0; k < 3; k++)
                target[k] = b0 * q0[k] + b1 * q0[3 + k] +
                            (1 - b0 - b1) * q0[6 + k];
        }
        vec_sub(r.d, target, r.o);
        if (mode == 3) { /* lane 1 edge-on: its plane holds the ray */
            real s = pcg32_real(&g), u = pcg32_real(&g);
            for (int k = 0; k < 3; k++) {
                q[1][k] = r.o[k] + s * r.d[k];
                q[1][3 + k] = r.o[k] + (s + 1) * r.d[k];
                q[1][6 + k] = q[1][k] + u * q[2][k];
            }
        }
        if (mode == 4)
            r.d[pcg32_bounded(&g, 3)] = 0;
        if (i % 23 == 0)
            vec_scale(r.d, r.d, REAL_C(1e-9));
        if (i % 29 == 0)
            vec_scale(r.d, r.d, REAL_C(1e9));
        mesh_ray_t mr;
        mesh_ray_prepare(&mr, &r);
#if MESH_WIDE
        mesh_wide_ray_t wr;
        mesh_wide_ray_prepare(&wr, &mr);
#endif
        const real *qp[MESH_BATCH];
        for (int j = 0; j < MESH_BATCH; j++)
            qp[j] = q[j];
        unsigned m = mesh_ray_reject(qp, &mr);
        unsigned mp = mesh_ray_reject_plain(qp, &mr);
        ck_assert_msg(m == mp, "case %d: mask %x, plain lanes %x", i, m, mp);
#if defined(SIMD_REAL) && VLANES == MESH_BATCH
        /* the same triangles side by side, as a grid cell keeps them */
        real soa[9 * MESH_BATCH];
        for (int j = 0; j < MESH_BATCH; j++)
            for (int k = 0; k < 9; k++)
                soa[k * MESH_BATCH + j] = q[j][k];
        unsigned ms = mesh_lanes_reject_soa(soa, &mr);
        ck_assert_msg(ms == mp, "case %d: side by side %x, plain lanes %x", i,
                      ms, mp);
        soa_cases++;
#if MESH_WIDE
        /* two such blocks at once (AVX): the second holds the lanes in
         * reverse order, so its mask is the plain mask reversed */
        real rev[9 * MESH_BATCH];
        unsigned mrev = 0;
        for (int j = 0; j < MESH_BATCH; j++) {
            for (int k = 0; k < 9; k++)
                rev[k * MESH_BATCH + j] = q[MESH_BATCH - 1 - j][k];
            mrev |= (mp >> (MESH_BATCH - 1 - j) & 1) << j;
        }
        unsigned mw = mesh_wide_reject_soa2(soa, rev, &mr, &wr);
        ck_assert_msg(mw == (mp | mrev << MESH_BATCH),
                      "case %d: two blocks %x, plain lanes %x and %x", i, mw,
                      mp, mrev);
        wide_cases++;
#endif
#endif
        for (int j = 0; j < MESH_BATCH; j++) {
            real t, b[3];
            bool h = triangle_intersect_watertight(
                q[j], q[j] + 3, q[j] + 6, &r, -(real)INFINITY,
                (real)INFINITY, &t, b);
            if (m >> j & 1) {
                ck_assert_msg(!h, "case %d lane %d: rejected, but hit at %g",
                              i, j, (double)t);
                rejected++;
            } else {
                kept++;
                hits += h;
            }
            cases++;
        }
    }
    ck_assert(rejected > 50000 && kept > 20000 && hits > 10000);
    test_report_cases(
        "batch_sign_test_matches_the_plain_lanes_and_never_rejects_a_hit",
        cases);
    test_report_cases("batch_sign_test_matches_the_plain_lanes_and_never_"
                      "rejects_a_hit (corners side by side)",
                      soa_cases);
    test_report_cases("batch_sign_test_matches_the_plain_lanes_and_never_"
                      "rejects_a_hit (two blocks side by side, AVX)",
                      wide_cases);
}
END_TEST

/* One triangle with normals and st given; a ray through the point with
 * barycentrics (0.2, 0.3, 0.5): every field against its formula. */
START_TEST(surface_interpolates_normals_and_texture_coordinates)
{
    const real p[3][3] = { { 0, 0, 0 }, { 2, 0, 0 }, { 0, 3, 0 } };
    const real n[3][3] = { { 0, 0, 1 }, { 1, 0, 1 }, { 0, 1, 1 } };
    const real st[3][2] = { { REAL_C(0.1), REAL_C(0.2) },
                            { REAL_C(0.9), REAL_C(0.2) },
                            { REAL_C(0.1), REAL_C(0.8) } };
    const int32_t tri[1][3] = { { 0, 1, 2 } };
    COBJECT *o = make_mesh(3, p, n, st, 1, tri);
    const real b[3] = { REAL_C(0.2), REAL_C(0.3), REAL_C(0.5) };
    VECTOR3 x = { b[1] * 2, b[2] * 3, 0 };
    ray_t r = { { x[X], x[Y], 5 }, { 0, 0, -1 } };
    hit_t h;
    ck_assert(cobject_intersect(o, &r, 0, (real)INFINITY, &h));
    ck_assert_near(h.t, 5, 1e-6);
    PATHPOINT pp;
    cobject_fill(o, &r, &h, &pp);
    for (int k = 0; k < 3; k++)
        ck_assert_near(pp.cross_point[k], x[k], 4e-7);
    /* n = unit(b0 n0 + b1 n1' + b2 n2'), the normals unit first */
    real s2 = sqrt(REAL_C(0.5));
    VECTOR3 ns = { b[1] * s2, b[2] * s2, b[0] + (b[1] + b[2]) * s2 };
    vec_normalize(ns, ns);
    for (int k = 0; k < 3; k++)
        ck_assert_near(pp.n[k], ns[k], 1e-6);
    ck_assert_near(pp.ng[Z], 1, 0);
    /* st = sum b_i st_i */
    ck_assert_near(pp.st[0], 0.2 * 0.1 + 0.3 * 0.9 + 0.5 * 0.1, 1e-6);
    ck_assert_near(pp.st[1], 0.2 * 0.2 + 0.3 * 0.2 + 0.5 * 0.8, 1e-6);
    /* s runs along x: 0.8 of s over 2 of x; t along y: 0.6 over 3 */
    ck_assert_near(pp.dpds[X], 2 / 0.8, 1e-5);
    ck_assert_near(pp.dpds[Y], 0, 1e-5);
    ck_assert_near(pp.dpdt[X], 0, 1e-5);
    ck_assert_near(pp.dpdt[Y], 3 / 0.6, 1e-5);
    /* a right-handed orthonormal frame around n */
    VECTOR3 c;
    VVECTOR3(c, pp.u, pp.v);
    for (int k = 0; k < 3; k++)
        ck_assert_near(c[k], pp.n[k], 1e-6);
    ck_assert_near(SVECTOR3(pp.u, pp.n), 0, 1e-6);
    /* p_error = gamma(7) sum |b_i p_i| (pbrt-v3 sec. 3.9.6) */
    ck_assert_near(pp.p_error[X], ray_gamma(7) * (b[1] * 2),
                   1e-3 * (double)ray_gamma(7));
    cobject_free(o);
}
END_TEST

/* Normals against the winding are turned to ng's side; without st the
 * barycentrics give it (triangle.h: st = (b1, b2)). */
START_TEST(shading_normal_is_turned_to_the_side_of_ng)
{
    const real p[3][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } };
    const real n[3][3] = { { 0, 0, -1 }, { REAL_C(0.1), 0, -1 },
                           { 0, REAL_C(0.1), -1 } };
    const int32_t tri[1][3] = { { 0, 1, 2 } };
    COBJECT *o = make_mesh(3, p, n, NULL, 1, tri);
    ray_t r = { { REAL_C(0.25), REAL_C(0.25), -1 }, { 0, 0, 1 } };
    hit_t h;
    ck_assert(cobject_intersect(o, &r, 0, (real)INFINITY, &h));
    PATHPOINT pp;
    cobject_fill(o, &r, &h, &pp);
    ck_assert(SVECTOR3(pp.n, pp.ng) > 0);
    ck_assert_near(pp.ng[Z], 1, 0);
    ck_assert_near(pp.st[0], 0.25, 1e-6);
    ck_assert_near(pp.st[1], 0.25, 1e-6);
    VECTOR3 c;
    VVECTOR3(c, pp.u, pp.v);
    for (int k = 0; k < 3; k++)
        ck_assert_near(c[k], pp.n[k], 1e-6);
    cobject_free(o);
}
END_TEST

/* A vertex without a normal (zero) or without st (NaN) makes its
 * triangles fall back to ng and to barycentric st. */
START_TEST(missing_normals_and_st_fall_back_per_triangle)
{
    const real p[4][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 } };
    const real n[4][3] = { { 0, 0, 0 }, { 0, 1, 1 }, { 0, 1, 1 }, { 0, 1, 1 } };
    const real st[4][2] = { { (real)NAN, 0 }, { 1, 0 }, { 0, 1 }, { 1, 1 } };
    const int32_t tri[2][3] = { { 0, 1, 2 }, { 1, 3, 2 } };
    COBJECT *o = make_mesh(4, p, n, st, 2, tri);
    ray_t r = { { REAL_C(0.2), REAL_C(0.2), 1 }, { 0, 0, -1 } };
    hit_t h;
    PATHPOINT pp;
    ck_assert(cobject_intersect(o, &r, 0, (real)INFINITY, &h));
    ck_assert_int_eq(h.prim, 0);
    cobject_fill(o, &r, &h, &pp);
    ck_assert_near(pp.n[Z], 1, 0);          /* vertex 0 has no normal */
    ck_assert_near(pp.st[0], 0.2, 1e-6);    /* nor st: (b1, b2) */
    vec_set(r.o, REAL_C(0.8), REAL_C(0.8), 1);
    ck_assert(cobject_intersect(o, &r, 0, (real)INFINITY, &h));
    ck_assert_int_eq(h.prim, 1);
    cobject_fill(o, &r, &h, &pp);
    ck_assert_near(pp.n[Y], sqrt(0.5), 1e-6); /* interpolated */
    ck_assert_near(pp.st[0], 0.8, 1e-6);      /* from the vertices' st */
    ck_assert_near(pp.st[1], 0.8, 1e-6);
    cobject_free(o);
}
END_TEST

/* Area: a unit cube of 12 triangles, plus a degenerate triangle, has area
 * 6; the degenerate one is never hit nor sampled. */
START_TEST(area_sums_triangles_and_degenerate_ones_add_nothing)
{
    const real p[9][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 },
                           { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 },
                           { 2, 2, 2 } };
    const int32_t tri[13][3] = {
        { 0, 2, 1 }, { 0, 3, 2 }, { 4, 5, 6 }, { 4, 6, 7 }, { 0, 1, 5 },
        { 0, 5, 4 }, { 1, 2, 6 }, { 1, 6, 5 }, { 2, 3, 7 }, { 2, 7, 6 },
        { 3, 0, 4 }, { 3, 4, 7 }, { 8, 8, 6 } };
    COBJECT *o = make_mesh(9, p, NULL, NULL, 13, tri);
    ck_assert_near(o->ops->area(o), 6, 1e-6);
    ck_assert_int_eq(o->nprims, 13);
    ck_assert(mesh_triangle_is_degenerate(mesh_get(o), 12));
    pcg32_t g;
    pcg32_seed(&g, 3, 4);
    for (int i = 0; i < 20000; i++) {
        real u[2] = { pcg32_real(&g), pcg32_real(&g) };
        cobject_sample_t s;
        o->ops->sample(o, u, &s);
        ck_assert(s.p[X] <= 1 && s.p[Y] <= 1 && s.p[Z] <= 1);
        ck_assert_near(s.pdf, 1.0 / 6, 1e-6);
    }
    /* the cube is closed and convex: the harness's convex checks apply */
    long n = geomcheck_spawn_never_rehits(o, GEOMCHECK_CONVEX, 300, 8, 5);
    n += geomcheck_shadow_rays_between_points_miss(o, 2000, 6);
    n += geomcheck_sampled_points_are_hit(o, GEOMCHECK_CONVEX, 2000, 4, 7);
    test_report_cases("area_sums_triangles_and_degenerate_ones_add_nothing",
                      20000 + n);
    cobject_free(o);
}
END_TEST

/* The alias table picks triangle i with probability A_i / A. Four
 * separate triangles of areas 1, 2, 3, 4 (in units of 1/2): counts of N
 * samples against N A_i / A by Pearson's chi-square, 3 degrees of
 * freedom. With a fixed seed the statistic is one number; the threshold
 * 21.1 is the 1 - 1e-4 quantile of chi^2(3), so a correct sampler fails
 * with probability 1e-4 over seeds, and an error of 1% in one
 * probability (N = 4e5: a shift of ~40 sigma^2 in the statistic) fails. */
START_TEST(sampling_picks_triangles_in_proportion_to_area)
{
    real p[12][3];
    int32_t tri[4][3];
    for (int i = 0; i < 4; i++) {
        real x = (real)(10 * i);
        vec_set(p[3 * i], x, 0, 0);
        vec_set(p[3 * i + 1], x + (real)(i + 1), 0, 0);
        vec_set(p[3 * i + 2], x, 1, 0);
        tri[i][0] = 3 * i;
        tri[i][1] = 3 * i + 1;
        tri[i][2] = 3 * i + 2;
    }
    COBJECT *o = make_mesh(12, (const real(*)[3])p, NULL, NULL, 4,
                           (const int32_t(*)[3])tri);
    ck_assert_near(o->ops->area(o), 5, 1e-6);
    pcg32_t g;
    pcg32_seed(&g, 8, 9);
    const long N = 400000;
    long count[4] = { 0 };
    for (long i = 0; i < N; i++) {
        real u[2] = { pcg32_real(&g), pcg32_real(&g) };
        cobject_sample_t s;
        o->ops->sample(o, u, &s);
        int k = (int)(s.p[X] / 10);
        ck_assert(k >= 0 && k < 4);
        /* inside triangle k */
        ck_assert(s.p[X] >= (real)(10 * k) && s.p[Y] >= 0 &&
                  (s.p[X] - (real)(10 * k)) / (real)(k + 1) + s.p[Y] <=
                      1 + REAL_C(1e-6));
        count[k]++;
    }
    double chi2 = 0;
    for (int k = 0; k < 4; k++) {
        double e = N * (k + 1) / 10.0;
        chi2 += (count[k] - e) * (count[k] - e) / e;
    }
    ck_assert_msg(chi2 < 21.1, "chi2 = %g", chi2);
    test_report_cases("sampling_picks_triangles_in_proportion_to_area", N);
    cobject_free(o);
}
END_TEST

static COBJECT *sphere_mesh(int nu, int nv)
{
    COBJECT *o;
    svet_error e;
    VECTOR3 c = { REAL_C(0.5), -1, 2 };
    ck_assert_msg(meshgen_uv_sphere(&o, c, REAL_C(1.5), nu, nv, &e) == SVET_OK,
                  "%s", e.msg);
    return o;
}

/* The UV sphere is a convex polyhedron: the harness's checks for convex
 * solids apply to it as a whole. */
START_TEST(closed_sphere_mesh_passes_the_robustness_harness)
{
    COBJECT *o = sphere_mesh(24, 12);
    long n = geomcheck_spawn_never_rehits(o, GEOMCHECK_CONVEX, 400, 8, 11);
    n += geomcheck_sampled_points_are_hit(o, GEOMCHECK_CONVEX, 2000, 4, 12);
    n += geomcheck_shadow_rays_between_points_miss(o, 2000, 13);
    n += geomcheck_hits_are_finite(o, 4000, 3, 14);
    n += geomcheck_sampling_matches_area(o, 4000, true, 15);
    test_report_cases("closed_sphere_mesh_passes_the_robustness_harness", n);
    cobject_free(o);
}
END_TEST

static void expect_range_error(mesh_t *m, const char *what)
{
    COBJECT *o = (COBJECT *)1;
    svet_error e;
    ck_assert_int_eq(mesh_new(&o, m, &e), SVET_ERR_RANGE);
    ck_assert_ptr_null(o);
    ck_assert_msg(strstr(e.msg, what) != NULL, "'%s' lacks '%s'", e.msg,
                  what);
    ck_assert_ptr_null(m->p); /* freed and zeroed */
}

static void one_triangle(mesh_t *m)
{
    memset(m, 0, sizeof *m);
    m->nverts = 3;
    m->ntris = 1;
    m->p = calloc(3, sizeof *m->p);
    m->tri = calloc(1, sizeof *m->tri);
    m->p[1][X] = 1;
    m->p[2][Y] = 1;
    m->tri[0][1] = 1;
    m->tri[0][2] = 2;
}

START_TEST(mesh_new_rejects_bad_input_with_a_reason)
{
    mesh_t m;
    one_triangle(&m);
    m.tri[0][2] = 3;
    expect_range_error(&m, "refers to vertex 3 of 3");
    one_triangle(&m);
    m.tri[0][0] = -1;
    expect_range_error(&m, "refers to vertex -1");
    one_triangle(&m);
    m.p[1][Y] = (real)NAN;
    expect_range_error(&m, "vertex 1 is not finite");
    one_triangle(&m);
    m.p[2][Z] = (real)INFINITY;
    expect_range_error(&m, "vertex 2 is not finite");
    one_triangle(&m);
    m.n = calloc(3, sizeof *m.n);
    m.n[0][X] = (real)NAN;
    expect_range_error(&m, "normal of vertex 0");
    one_triangle(&m);
    m.st = calloc(3, sizeof *m.st);
    m.st[2][1] = (real)INFINITY;
    expect_range_error(&m, "st of vertex 2");
    one_triangle(&m);
    m.ntris = 0;
    expect_range_error(&m, "0 triangles");
    one_triangle(&m);
    m.nverts = -5;
    expect_range_error(&m, "-5 vertices");
}
END_TEST

START_TEST(subset_keeps_the_triangles_of_one_slot)
{
    const real p[5][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 },
                           { 5, 0, 0 }, { 5, 1, 0 } };
    const int32_t tri[3][3] = { { 0, 1, 2 }, { 1, 3, 4 }, { 2, 1, 4 } };
    mesh_t m = { 0 };
    m.nverts = 5;
    m.ntris = 3;
    m.p = malloc(sizeof p);
    m.tri = malloc(sizeof tri);
    m.slot = malloc(3 * sizeof *m.slot);
    memcpy(m.p, p, sizeof p);
    memcpy(m.tri, tri, sizeof tri);
    m.slot[0] = 0;
    m.slot[1] = 1;
    m.slot[2] = 0;
    COBJECT *o, *s;
    svet_error e;
    ck_assert(mesh_new(&o, &m, &e) == SVET_OK);
    ck_assert(mesh_new_subset(&s, o, 0, &e) == SVET_OK);
    const mesh_t *q = mesh_get(s);
    ck_assert_int_eq(q->ntris, 2);
    ck_assert_int_eq(q->nverts, 4); /* vertices 0 1 2 4, renumbered */
    ck_assert_near(q->p[q->tri[1][2]][X], 5, 0);
    ck_assert_int_eq(q->slot[1], 0);
    COBJECT *none;
    ck_assert_int_eq(mesh_new_subset(&none, o, 7, &e), SVET_ERR_RANGE);
    ck_assert(strstr(e.msg, "slot 7") != NULL);
    ck_assert_ptr_null(mesh_get(NULL));
    /* bytes: the documented layout (mesh.h) */
    size_t expect = sizeof(COBJECT) + sizeof(mesh_t) + 5 * sizeof(VECTOR3) +
                    3 * (sizeof(int32_t[3]) + sizeof(real) + sizeof(int32_t)) +
                    3 * sizeof(int32_t);
    ck_assert_uint_eq(mesh_bytes(o), expect);
    cobject_free(s);
    cobject_free(o);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("mesh");
    TCase *tc = tcase_create("mesh");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, per_ray_test_matches_the_triangle_test_bit_for_bit);
    tcase_add_test(
        tc, batch_sign_test_matches_the_plain_lanes_and_never_rejects_a_hit);
    tcase_add_test(tc, surface_interpolates_normals_and_texture_coordinates);
    tcase_add_test(tc, shading_normal_is_turned_to_the_side_of_ng);
    tcase_add_test(tc, missing_normals_and_st_fall_back_per_triangle);
    tcase_add_test(tc, area_sums_triangles_and_degenerate_ones_add_nothing);
    tcase_add_test(tc, sampling_picks_triangles_in_proportion_to_area);
    tcase_add_test(tc, closed_sphere_mesh_passes_the_robustness_harness);
    tcase_add_test(tc, mesh_new_rejects_bad_input_with_a_reason);
    tcase_add_test(tc, subset_keeps_the_triangles_of_one_slot);
    suite_add_tcase(s, tc);
    return s;
}
