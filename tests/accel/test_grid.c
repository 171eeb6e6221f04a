/*
 * test_grid.c - the grids of ch. 7 as structures: the resolution rule
 * (about k^3 N cells over the box's aspect), every triangle listed in
 * every cell it overlaps (checked against clipping the triangle to the
 * cell, an independent method), the 3D-DDA's cell counts on rays whose
 * path is known, the hierarchy's refinement and its limits, the plain
 * walk (grid.c) against the fast walk (fast/grid_walk.c) and brute force
 * on the same rays, and the packets of camera rays (Wald et al. 2006)
 * against single rays and brute force, bad rays included. Agreement with
 * brute force through accel.h: tests/accel/test_accel.c.
 */
#include "testutil.h"
#include "accel/grid.h"
#include "mesh/mesh.h"
#include "mesh/meshgen.h"
#include "accel/primset.h"
#include "core/rng.h"
#include "geometry/sphere.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static grid_t *build(const primset_t *ps, double k, int depth)
{
    grid_params_t p;
    if (depth > 0)
        grid_params_hierarchical(&p);
    else
        grid_params_uniform(&p);
    p.k = k;
    p.max_depth = depth;
    grid_t *g;
    svet_error e;
    ck_assert_msg(grid_build(&g, ps, &p, &e) == SVET_OK, "%s", e.msg);
    return g;
}

static long cells_of(const grid_node_t *nd)
{
    return (long)nd->res[0] * nd->res[1] * nd->res[2];
}

START_TEST(resolution_follows_k_cubed_n_over_the_aspect)
{
    meshgen_scene_t s;
    svet_error e;
    /* 4 x 4 x 4 spheres: a cubic box */
    ck_assert(meshgen_sphere_grid(&s, 4, 20000, &e) == SVET_OK);
    primset_t ps;
    ck_assert(primset_build(&ps, s.objs, s.nobjs, &e) == SVET_OK);
    for (double k = 0.5; k <= 3; k += 1.25) {
        grid_t *g = build(&ps, k, 0);
        const grid_node_t *top = &g->nodes[0];
        double want = k * k * k * ps.nbounded, got = (double)cells_of(top);
        /* each axis is rounded: within (1 +- 1/res)^3 of the target */
        double slack = 3.0 / top->res[0] + 3.0 / (top->res[0] * top->res[0]);
        ck_assert_msg(fabs(got / want - 1) <= slack, "k %g: %g cells, want %g",
                      k, got, want);
        ck_assert_int_eq(top->res[0], top->res[1]);
        ck_assert_int_eq(top->res[1], top->res[2]);
        ck_assert_int_eq(g->nnodes, 1);
        grid_free(g);
    }
    primset_free(&ps);
    meshgen_free_objects(&s);
    /* a flat terrain: one cell across its thickness, the rest in x, y */
    COBJECT *t;
    VECTOR3 c = { 0, 0, 0 };
    ck_assert(meshgen_terrain(&t, c, 100, REAL_C(0.01), 60, 1, &e) ==
              SVET_OK);
    ck_assert(primset_build(&ps, &t, 1, &e) == SVET_OK);
    grid_t *g = build(&ps, 2, 0);
    const grid_node_t *top = &g->nodes[0];
    ck_assert_int_eq(top->res[Z], 1);
    ck_assert_int_eq(top->res[X], top->res[Y]);
    double want = 8.0 * ps.nbounded;
    ck_assert(fabs((double)cells_of(top) / want - 1) < 0.05);
    grid_free(g);
    primset_free(&ps);
    cobject_free(t);
}
END_TEST

/* Sutherland-Hodgman: clip the polygon v[0..n) to x_a >= lo (sign +1) or
 * x_a <= hi (sign -1); returns the new count (in double, on exact
 * corners of floats). */
static int clip(double (*v)[3], int n, int a, double bound, int sign,
                double (*out)[3])
{
    int m = 0;
    for (int i = 0; i < n; i++) {
        const double *p = v[i], *q = v[(i + 1) % n];
        double dp = sign * (p[a] - bound), dq = sign * (q[a] - bound);
        if (dp >= 0)
            memcpy(out[m++], p, sizeof(double[3]));
        if ((dp >= 0) != (dq >= 0)) {
            double t = dp / (dp - dq);
            for (int k = 0; k < 3; k++)
                out[m][k] = p[k] + t * (q[k] - p[k]);
            m++;
        }
    }
    return m;
}

/* Does the triangle q meet the box, shrunk by `inset` on every side? */
static bool clipped_nonempty(const real *q, const double lo[3],
                             const double hi[3], double inset)
{
    double a[12][3], b[12][3];
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++)
            a[i][k] = (double)q[3 * i + k];
    int n = 3;
    for (int ax = 0; ax < 3 && n > 0; ax++) {
        n = clip(a, n, ax, lo[ax] + inset, 1, b);
        n = clip(b, n, ax, hi[ax] - inset, -1, a);
    }
    return n > 0;
}

/* Every triangle is in every cell it truly meets; a triangle listed in a
 * cell comes within the padding of it. Tori tilted every way and a
 * terrain, on grids coarse and fine. */
START_TEST(every_triangle_is_in_every_cell_it_overlaps)
{
    svet_error e;
    COBJECT *objs[3];
    VECTOR3 c0 = { 0, 0, 0 }, c1 = { 3, 1, -2 }, c2 = { -2, 2, 1 };
    ck_assert(meshgen_torus(&objs[0], c0, 2, REAL_C(0.7), 16, 7, &e) == 0);
    ck_assert(meshgen_uv_sphere(&objs[1], c1, REAL_C(1.3), 12, 7, &e) == 0);
    ck_assert(meshgen_terrain(&objs[2], c2, 5, 1, 7, 4, &e) == 0);
    primset_t ps;
    ck_assert(primset_build(&ps, objs, 3, &e) == SVET_OK);
    long checked = 0;
    for (double k = 0.7; k < 3; k *= 3) {
        grid_t *g = build(&ps, k, 0);
        const grid_node_t *nd = &g->nodes[0];
        char *in = malloc(ps.ntri);
        for (int z = 0; z < nd->res[2]; z++)
            for (int y = 0; y < nd->res[1]; y++)
                for (int x = 0; x < nd->res[0]; x++) {
                    long c = x + nd->res[0] * (y + (long)nd->res[1] * z);
                    memset(in, 0, ps.ntri);
                    uint32_t cb, ce;
                    grid_cell_items(g, 0, c, &cb, &ce);
                    /* ascending: the walk relies on mesh triangles
                     * coming first in a cell (and child grids last) */
                    for (uint32_t i = cb + 1; i < ce; i++)
                        ck_assert_uint_lt(g->items[i - 1], g->items[i]);
                    for (uint32_t i = cb; i < ce; i++)
                        in[g->items[i]] = 1;
                    int ix[3] = { x, y, z };
                    double lo[3], hi[3];
                    for (int a = 0; a < 3; a++) {
                        lo[a] = nd->min[a] + ix[a] * nd->w[a];
                        hi[a] = lo[a] + nd->w[a];
                    }
                    for (uint32_t t = 0; t < ps.ntri; t++) {
                        /* meets the cell shrunk by a hair: must be in */
                        if (!in[t])
                            ck_assert_msg(!clipped_nonempty(ps.tri[t], lo, hi,
                                                            1e-9),
                                          "triangle %u missing from cell "
                                          "(%d %d %d)", t, x, y, z);
                        /* listed: meets the cell grown by the padding */
                        else
                            ck_assert(clipped_nonempty(ps.tri[t], lo, hi,
                                                       -2 * ps.pad));
                        checked++;
                    }
                }
        free(in);
        grid_free(g);
    }
    test_report_cases("every_triangle_is_in_every_cell_it_overlaps", checked);
    primset_free(&ps);
    for (int i = 0; i < 3; i++)
        cobject_free(objs[i]);
}
END_TEST

/* Rays whose steps are known. The grid is 5^3 cells, so 2^3 blocks of
 * 4^3 (the last ones one cell thick); tiny meshes sit in the corner cells
 * (0,0,0) and (4,4,4), so only blocks (0,0,0) and (1,1,1) hold anything.
 * The walk counts every cell of a block that holds something and every
 * empty block once. Each row below crosses 4 cells of block (0,0,0) and
 * one empty block: 5. The diagonal slightly off the corners crosses 10
 * cells of block (0,0,0) (3 * 4 - 2: each step crosses one plane), then
 * the empty blocks (0,1,0) and (0,1,1) (y, z and x cross in that order),
 * then cell (4,4,4) of block (1,1,1): 13. Nothing is hit, so the walk goes
 * to the end. */
START_TEST(the_walk_visits_the_cells_a_ray_crosses)
{
    /* two tiny triangles at opposite corners of [0, 10]^3 */
    mesh_t m = { 0 };
    m.nverts = 6;
    m.ntris = 2;
    m.p = calloc(6, sizeof *m.p);
    m.tri = calloc(2, sizeof *m.tri);
    vec_set(m.p[1], REAL_C(0.01), 0, 0);
    vec_set(m.p[2], 0, REAL_C(0.01), 0);
    vec_set(m.p[3], 10, 10, 10);
    vec_set(m.p[4], REAL_C(9.99), 10, 10);
    vec_set(m.p[5], 10, REAL_C(9.99), 10);
    for (int k = 0; k < 6; k++)
        m.tri[k / 3][k % 3] = k;
    COBJECT *o;
    svet_error e;
    ck_assert(mesh_new(&o, &m, &e) == SVET_OK);
    primset_t ps;
    ck_assert(primset_build(&ps, &o, 1, &e) == SVET_OK);
    ck_assert_uint_eq(ps.ntri, 2);
    grid_params_t p;
    grid_params_uniform(&p);
    p.k = 4; /* 4^3 * 2 = 128 cells: 5 per axis */
    grid_t *g;
    ck_assert(grid_build(&g, &ps, &p, &e) == SVET_OK);
    int n = g->nodes[0].res[0];
    ck_assert_int_eq(n, 5);
    ray_t rows[3] = { { { -1, 5, 5 }, { 1, 0, 0 } },
                      { { 5, REAL_C(5.5), -3 }, { 0, 0, 2 } },
                      { { REAL_C(4.1), 20, REAL_C(6.3) }, { 0, -1, 0 } } };
    for (int i = 0; i < 3; i++) {
        primset_query_t q;
        primset_query_init(&q, &rows[i], 0, (real)INFINITY);
        ck_assert(!grid_intersect(g, &q));
        ck_assert_int_eq(q.cells, n);
        primset_query_init(&q, &rows[i], 0, (real)INFINITY);
        ck_assert(!grid_intersect_plain(g, &q));
        ck_assert_int_eq(q.cells, n);
    }
    ray_t diag = { { REAL_C(-0.5), REAL_C(-0.4), REAL_C(-0.45) },
                   { 1, 1, 1 } };
    primset_query_t q;
    primset_query_init(&q, &diag, 0, (real)INFINITY);
    ck_assert(!grid_intersect(g, &q));
    ck_assert_int_eq(q.cells, 3 * n - 2);
    primset_query_init(&q, &diag, 0, (real)INFINITY);
    ck_assert(!grid_intersect_plain(g, &q));
    ck_assert_int_eq(q.cells, 3 * n - 2);
    /* a short tmax stops the walk: from x = -1 to x = 3.9 covers cells
     * 0..1 (cell width 2.0...) */
    primset_query_init(&q, &rows[0], 0, REAL_C(3.5));
    grid_intersect(g, &q);
    ck_assert_int_le(q.cells, 2);
    primset_query_init(&q, &rows[0], 0, REAL_C(3.5));
    grid_intersect_plain(g, &q);
    ck_assert_int_le(q.cells, 2);
    grid_free(g);
    primset_free(&ps);
    cobject_free(o);
}
END_TEST

/* Brute force over (0, tmax): every primitive, in number order. */
static void brute_to(const primset_t *ps, const ray_t *r, real tmax,
                     primset_query_t *q)
{
    primset_query_init(q, r, 0, tmax);
    for (uint32_t i = 0; i < ps->nrefs; i++)
        primset_test(ps, q, i);
}

static void brute(const primset_t *ps, const ray_t *r, primset_query_t *q)
{
    brute_to(ps, r, (real)INFINITY, q);
}

/* Do two queries end with the same answer: found, and then the same
 * primitive, t and barycentrics, bit for bit? */
static bool same_answer(const primset_query_t *a, const primset_query_t *b)
{
    return a->found == b->found &&
           (!a->found ||
            (a->ref == b->ref &&
             memcmp(&a->hit.t, &b->hit.t, sizeof a->hit.t) == 0 &&
             memcmp(a->hit.b, b->hit.b, sizeof a->hit.b) == 0));
}

/* The plain walk's answers (nearest hit, and any hit) for the query
 * `from` (as it came, hit or not) are the fast walk's, bit for bit. */
static void check_plain(const grid_t *g, const primset_query_t *from)
{
    primset_query_t fast = *from, plain = *from;
    grid_intersect(g, &fast);
    grid_intersect_plain(g, &plain);
    const ray_t *r = from->r;
    ck_assert_msg(same_answer(&plain, &fast),
                  "ray (%g %g %g) (%g %g %g): plain walk %d (primitive %u), "
                  "fast walk %d (primitive %u)",
                  (double)r->o[0], (double)r->o[1], (double)r->o[2],
                  (double)r->d[0], (double)r->d[1], (double)r->d[2],
                  plain.found, plain.ref, fast.found, fast.ref);
    fast = *from;
    plain = *from;
    ck_assert(grid_occluded_plain(g, &plain) == grid_occluded(g, &fast));
}

/* The grid's answers (nearest hit, and any hit) for r are brute force's,
 * bit for bit, by the fast walk and by the plain walk. */
static void check_ray(const grid_t *g, const primset_t *ps, const ray_t *r)
{
    primset_query_t want, got, shadow;
    brute(ps, r, &want);
    primset_query_init(&got, r, 0, (real)INFINITY);
    check_plain(g, &got);
    grid_intersect(g, &got);
    ck_assert_msg(got.found == want.found,
                  "ray (%g %g %g) (%g %g %g): grid %d, brute force %d",
                  (double)r->o[0], (double)r->o[1], (double)r->o[2],
                  (double)r->d[0], (double)r->d[1], (double)r->d[2],
                  got.found, want.found);
    if (want.found) {
        ck_assert_uint_eq(got.ref, want.ref);
        ck_assert(memcmp(&got.hit.t, &want.hit.t, sizeof got.hit.t) == 0);
        ck_assert(memcmp(got.hit.b, want.hit.b, sizeof got.hit.b) == 0);
    }
    primset_query_init(&shadow, r, 0, (real)INFINITY);
    ck_assert(grid_occluded(g, &shadow) == want.found);
}

/* A point of the grid in cell coordinates u (cell (i, j, k) spans
 * [i, i + 1] x ...), rounded to real. */
static void grid_point(const grid_node_t *nd, const double u[3], VECTOR3 p)
{
    for (int a = 0; a < 3; a++)
        p[a] = (real)(nd->min[a] + u[a] * nd->w[a]);
}

/* Empty-space skipping (grid.c: blocks of 4^3 cells) never skips a cell it
 * should visit. A sparse scene on a 32^3 grid (8^3 blocks, half of them
 * empty): tiny triangles around block corners, thin ones lying in block
 * faces and along block edges, a few large ones across many blocks. Rays
 * through block corners in every direction, along block edges and faces
 * (parallel to one or two axes), crossing a block only at an edge or a
 * corner, starting inside empty blocks, on block planes and outside the
 * grid; each answered as brute force answers, nearest and any hit, by the
 * uniform grid and by a hierarchy whose children have blocks too. */
START_TEST(skipping_empty_blocks_never_misses_a_cell)
{
    pcg32_t rng;
    pcg32_seed(&rng, 2024, 6);
    int ntri = 0, cap = 400;
    mesh_t m = { 0 };
    m.p = calloc(3 * (size_t)cap, sizeof *m.p);
    m.tri = calloc((size_t)cap, sizeof *m.tri);
    /* one triangle: corners c + s (random offsets), or given */
#define TRI(P0, P1, P2)                                                      \
    do {                                                                     \
        vec_copy(m.p[3 * ntri], P0);                                         \
        vec_copy(m.p[3 * ntri + 1], P1);                                     \
        vec_copy(m.p[3 * ntri + 2], P2);                                     \
        for (int k_ = 0; k_ < 3; k_++)                                       \
            m.tri[ntri][k_] = 3 * ntri + k_;                                 \
        ntri++;                                                              \
    } while (0)
    /* the box [0, 32]^3: tiny triangles at its corners fix it */
    for (int c = 0; c < 8; c++) {
        VECTOR3 p0 = { 32 * (real)(c & 1), 32 * (real)(c >> 1 & 1),
                       32 * (real)(c >> 2) };
        VECTOR3 p1, p2;
        vec_copy(p1, p0);
        vec_copy(p2, p0);
        p1[0] += p0[0] > 0 ? REAL_C(-0.2) : REAL_C(0.2);
        p2[1] += p0[1] > 0 ? REAL_C(-0.2) : REAL_C(0.2);
        TRI(p0, p1, p2);
    }
    /* small triangles around 40 block corners (multiples of 4) */
    for (int i = 0; i < 40; i++) {
        VECTOR3 c = { 4 * (real)(1 + pcg32_bounded(&rng, 7)),
                      4 * (real)(1 + pcg32_bounded(&rng, 7)),
                      4 * (real)(1 + pcg32_bounded(&rng, 7)) };
        VECTOR3 q[3];
        for (int k = 0; k < 3; k++)
            for (int a = 0; a < 3; a++)
                q[k][a] = c[a] + REAL_C(0.6) * (pcg32_real(&rng) - REAL_C(0.5));
        TRI(q[0], q[1], q[2]);
    }
    /* thin triangles lying in block faces (x, y or z = 4 i), and along
     * block edges */
    for (int i = 0; i < 40; i++) {
        int a = (int)pcg32_bounded(&rng, 3), b = (a + 1) % 3, c = (a + 2) % 3;
        real plane = 4 * (real)(1 + pcg32_bounded(&rng, 7));
        real ob = 24 * pcg32_real(&rng), oc = 24 * pcg32_real(&rng);
        real edge = 4 * (real)(1 + pcg32_bounded(&rng, 7));
        VECTOR3 q[3];
        for (int k = 0; k < 3; k++) {
            q[k][a] = plane;
            q[k][b] = ob + 6 * pcg32_real(&rng);
            q[k][c] = i % 2 ? edge : oc + 6 * pcg32_real(&rng);
        }
        q[1][c] += REAL_C(0.3); /* thin, not degenerate */
        TRI(q[0], q[1], q[2]);
    }
    /* a few large ones */
    for (int i = 0; i < 3; i++) {
        VECTOR3 q[3];
        for (int k = 0; k < 3; k++)
            for (int a = 0; a < 3; a++)
                q[k][a] = 8 + 16 * pcg32_real(&rng);
        TRI(q[0], q[1], q[2]);
    }
#undef TRI
    m.nverts = 3 * ntri;
    m.ntris = ntri;
    COBJECT *o;
    svet_error e;
    ck_assert(mesh_new(&o, &m, &e) == SVET_OK);
    primset_t ps;
    ck_assert(primset_build(&ps, &o, 1, &e) == SVET_OK);
    long cases = 0;
    for (int variant = 0; variant < 4; variant++) {
        /* uniform and hierarchical, with quads (where the build has
         * them) and without */
        int depth = 2 * (variant & 1);
        grid_params_t p;
        grid_params_uniform(&p);
        p.k = 32 / cbrt((double)ps.nbounded); /* 32 cells per axis */
        p.quad_min = variant >> 1 ? LONG_MAX : 0;
        p.max_depth = depth;
        p.leaf_max = 1; /* the hierarchy refines every shared cell */
        grid_t *g;
        ck_assert(grid_build(&g, &ps, &p, &e) == SVET_OK);
        const grid_node_t *nd = &g->nodes[0];
        ck_assert_int_eq(nd->res[0], 32);
        ck_assert_int_eq(nd->res[1], 32);
        ck_assert_int_eq(nd->res[2], 32);
        if (depth > 0)
            ck_assert_uint_gt(g->nnodes, 1);
        /* many blocks are empty (some 250 of the 512) */
        uint32_t empty = 0;
        for (uint32_t b = 0; b < 512; b++)
            empty += g->bmask[b] == 0;
        ck_assert_uint_gt(empty, 200);
        for (int i = 0; i < 3000; i++) {
            double u[3], v[3];
            for (int a = 0; a < 3; a++) {
                /* a block corner, a block plane, or anywhere (and a
                 * little outside) */
                int kind = (int)pcg32_bounded(&rng, 3);
                u[a] = kind == 0   ? 4.0 * pcg32_bounded(&rng, 9)
                       : kind == 1 ? 4.0 * pcg32_bounded(&rng, 9) +
                                         (pcg32_real(&rng) < REAL_C(0.5) ? 0 : 1e-7)
                                   : -2 + 36 * (double)pcg32_real(&rng);
                /* directions: along an axis, in a face's plane, through
                 * block corners (multiples of 4 apart), or any */
                int dk = (int)pcg32_bounded(&rng, 4);
                v[a] = dk == 0   ? 0
                       : dk == 1 ? (pcg32_real(&rng) < REAL_C(0.5) ? -1 : 1)
                       : dk == 2 ? 4.0 * ((int)pcg32_bounded(&rng, 5) - 2)
                                 : 2 * (double)pcg32_real(&rng) - 1;
            }
            if (v[0] == 0 && v[1] == 0 && v[2] == 0)
                v[i % 3] = 1;
            ray_t r;
            grid_point(nd, u, r.o);
            for (int a = 0; a < 3; a++)
                r.d[a] = (real)v[a];
            check_ray(g, &ps, &r);
            /* the same line from well outside the grid, backwards */
            ray_t back;
            for (int a = 0; a < 3; a++) {
                back.o[a] = r.o[a] + 40 * r.d[a];
                back.d[a] = -r.d[a];
            }
            check_ray(g, &ps, &back);
            cases += 2;
        }
        grid_free(g);
    }
    test_report_cases("skipping_empty_blocks_never_misses_a_cell", cases);
    primset_free(&ps);
    cobject_free(o);
}
END_TEST

/* The teapot's cell gets a child grid; the child lies inside its parent
 * cell (padded); budgets hold; a uniform grid of the same scene holds
 * the teapot in a handful of crowded cells. */
START_TEST(a_crowded_cell_gets_a_child_grid)
{
    meshgen_scene_t s;
    svet_error e;
    ck_assert(meshgen_teapot_stadium(&s, 30000, &e) == SVET_OK);
    primset_t ps;
    ck_assert(primset_build(&ps, s.objs, s.nobjs, &e) == SVET_OK);
    grid_t *u = build(&ps, GRID_K_DEFAULT, 0);
    ck_assert_uint_ge(u->max_items, 5000);
    grid_t *h = build(&ps, HGRID_K_DEFAULT, HGRID_DEPTH_DEFAULT);
    ck_assert_uint_gt(h->nnodes, 1);
    ck_assert_int_ge(h->depth, 1);
    ck_assert_int_le(h->depth, HGRID_DEPTH_DEFAULT);
    ck_assert_uint_lt(h->max_items, u->max_items / 10);
    for (uint32_t i = 1; i < h->nnodes; i++) {
        const grid_node_t *c = &h->nodes[i];
        ck_assert(c->depth >= 1);
        for (int a = 0; a < 3; a++)
            ck_assert(c->max[a] > c->min[a] && c->res[a] >= 1);
    }
    /* every child is referenced exactly once, from a shallower node */
    int *refd = calloc(h->nnodes, sizeof *refd);
    for (uint32_t n = 0; n < h->nnodes; n++) {
        const grid_node_t *nd = &h->nodes[n];
        for (long c = 0; c < cells_of(nd); c++) {
            uint32_t cb, ce;
            grid_cell_items(h, n, c, &cb, &ce);
            for (uint32_t k = cb; k < ce; k++)
                if (h->items[k] & GRID_CHILD) {
                    uint32_t ch = h->items[k] & ~GRID_CHILD;
                    ck_assert_uint_lt(ch, h->nnodes);
                    ck_assert_int_eq(h->nodes[ch].depth, nd->depth + 1);
                    refd[ch]++;
                }
        }
    }
    for (uint32_t n = 1; n < h->nnodes; n++)
        ck_assert_int_eq(refd[n], 1);
    free(refd);
    ck_assert_uint_le(h->ncells, (uint32_t)1 << 26);
    grid_free(u);
    grid_free(h);
    primset_free(&ps);
    meshgen_free_objects(&s);
}
END_TEST

/* Thousands of huge overlapping triangles would put millions of entries
 * in a fine grid: the build coarsens instead of taking forever. */
START_TEST(huge_primitives_coarsen_the_grid_instead_of_exploding)
{
    int n = 3000;
    mesh_t m = { 0 };
    m.nverts = 3 * n;
    m.ntris = n;
    m.p = malloc((size_t)m.nverts * sizeof *m.p);
    m.tri = malloc((size_t)n * sizeof *m.tri);
    pcg32_t g;
    pcg32_seed(&g, 4, 4);
    for (int i = 0; i < n; i++) {
        for (int k = 0; k < 3; k++) {
            for (int a = 0; a < 3; a++)
                m.p[3 * i + k][a] = 100 * (2 * pcg32_real(&g) - 1);
            m.tri[i][k] = 3 * i + k;
        }
    }
    COBJECT *o;
    svet_error e;
    ck_assert(mesh_new(&o, &m, &e) == SVET_OK);
    primset_t ps;
    ck_assert(primset_build(&ps, &o, 1, &e) == SVET_OK);
    grid_t *u = build(&ps, 4, 0), *h = build(&ps, 4, 3);
    /* k^3 N = 192000 cells would hold ~1e8 entries: the budget (grid.c,
     * GRID_SPAN_MAX) coarsens the grid until they fit */
    ck_assert_uint_le(u->nitems, GRID_SPAN_MAX(n));
    ck_assert_uint_lt(u->ncells, 64u * 3000);
    ck_assert_uint_le(h->nitems, 2 * GRID_SPAN_MAX(n));
    grid_free(u);
    grid_free(h);
    primset_free(&ps);
    cobject_free(o);
}
END_TEST

/* Variant 0 to 3 of a grid over ps with k cells per cube root: uniform
 * (even) or hierarchical (odd: two levels, leaves of leaf_max), with
 * quads (0, 1: forced, as the defaults keep them for large scenes; where
 * the build has them) or without (2, 3). */
static grid_t *variant_grid(const primset_t *ps, int variant, double k,
                            int leaf_max)
{
    grid_params_t p;
    grid_params_uniform(&p);
    p.k = k;
    p.quad_min = variant >> 1 ? LONG_MAX : 0;
    p.max_depth = 2 * (variant & 1);
    p.leaf_max = leaf_max;
    grid_t *g;
    svet_error e;
    ck_assert_msg(grid_build(&g, ps, &p, &e) == SVET_OK, "%s", e.msg);
    return g;
}

/* Cells that hold mesh triangles, other primitives and child grids
 * together: with quads (GRID_QUADS), a cell's triangles are its quads
 * (checked here against its items and the primset's corners, padding
 * last) and the rest its items; both grids, with quads and without,
 * answer as brute force, nearest and any hit.
 * Two UV spheres (meshes) crossed by analytic spheres, rays from inside
 * and outside, some along the axes. */
START_TEST(cells_of_triangles_and_other_primitives_answer_as_brute_force)
{
    svet_error e;
    COBJECT *objs[8];
    VECTOR3 c0 = { 0, 0, 0 }, c1 = { REAL_C(1.5), REAL_C(0.3), 0 };
    ck_assert(meshgen_uv_sphere(&objs[0], c0, 1, 24, 12, &e) == SVET_OK);
    ck_assert(meshgen_uv_sphere(&objs[1], c1, REAL_C(0.8), 16, 9, &e) ==
              SVET_OK);
    pcg32_t rng;
    pcg32_seed(&rng, 77, 7);
    for (int i = 2; i < 8; i++) {
        VECTOR3 c = { 3 * pcg32_real(&rng) - 1, 2 * pcg32_real(&rng) - 1,
                      2 * pcg32_real(&rng) - 1 };
        objs[i] = sphere_new(c, REAL_C(0.1) + REAL_C(0.4) * pcg32_real(&rng),
                             &e);
        ck_assert(objs[i] != NULL);
    }
    primset_t ps;
    ck_assert(primset_build(&ps, objs, 8, &e) == SVET_OK);
    long cases = 0, quads = 0, mixed = 0;
    for (int variant = 0; variant < 4; variant++) {
        int depth = 2 * (variant & 1), with = !(variant >> 1);
        grid_t *g = variant_grid(&ps, variant, 1, 4);
        if (depth > 0)
            ck_assert_uint_gt(g->nnodes, 1);
        ck_assert(GRID_QUADS && with ? g->quads != NULL : g->quads == NULL);
        for (uint32_t f = 0; g->quads && f < g->nfull; f++) {
            uint32_t qa = g->qstart[f] & ~GRID_MORE;
            uint32_t qb = g->qstart[f + 1] & ~GRID_MORE;
            uint32_t lane = 0, more = 0;
            for (uint32_t k = g->cstart[f]; k < g->cstart[f + 1]; k++) {
                uint32_t it = g->items[k];
                /* other primitives, child grids and triangles in many
                 * cells are left to the items */
                if (it >= ps.ntri || (g->qout[it / 64] >> (it % 64) & 1)) {
                    more = 1;
                    continue;
                }
                const grid_quad_t *qd = &g->quads[qa + lane / MESH_BATCH];
                ck_assert_uint_eq(qd->ref[lane % MESH_BATCH], it);
                for (int c = 0; c < 9; c++)
                    ck_assert(qd->c[c * MESH_BATCH + lane % MESH_BATCH] ==
                              ps.tri[it][c]);
                lane++;
            }
            ck_assert_uint_eq(qb - qa, (lane + MESH_BATCH - 1) / MESH_BATCH);
            for (; lane % MESH_BATCH; lane++)
                ck_assert_uint_eq(
                    g->quads[qa + lane / MESH_BATCH].ref[lane % MESH_BATCH],
                    GRID_QUAD_PAD);
            ck_assert_uint_eq(!!(g->qstart[f] & GRID_MORE), more);
            quads += qb - qa;
            mixed += more && lane > 0;
        }
        for (int i = 0; i < 4000; i++) {
            ray_t r;
            for (int a = 0; a < 3; a++) {
                r.o[a] = 5 * pcg32_real(&rng) - 2;
                r.d[a] = 2 * pcg32_real(&rng) - 1;
            }
            if (i % 4 == 0) { /* along an axis */
                int a = (int)pcg32_bounded(&rng, 3);
                vec_set(r.d, 0, 0, 0);
                r.d[a] = i % 8 ? 1 : -1;
            }
            check_ray(g, &ps, &r);
            cases++;
        }
        grid_free(g);
    }
    /* the case this test is for: cells with both (where there are quads) */
    ck_assert(!GRID_QUADS || mixed > 10);
    test_report_cases(
        "cells_of_triangles_and_other_primitives_answer_as_brute_force",
        cases);
    if (GRID_QUADS)
        test_report_cases("cells_of_triangles_and_other_primitives_answer_"
                          "as_brute_force (quads checked)",
                          quads);
    primset_free(&ps);
    for (int i = 0; i < 8; i++)
        cobject_free(objs[i]);
}
END_TEST

/* A pinhole camera's rays through the w x h pixels of the tile at (x0,
 * y0) of an nx x ny image: origin o, looking along f, the image's axes
 * along r and up (pixel (i, j) at f + (2 (i + 1/2) / nx - 1) r + (1 - 2
 * (j + 1/2) / ny) up). */
static int tile_rays(ray_t *out, const VECTOR3 o, const VECTOR3 f,
                     const VECTOR3 r, const VECTOR3 up, int nx, int ny,
                     int x0, int y0, int w, int h)
{
    int n = 0;
    for (int j = y0; j < y0 + h && j < ny; j++)
        for (int i = x0; i < x0 + w && i < nx; i++) {
            real x = 2 * ((real)i + REAL_C(0.5)) / (real)nx - 1;
            real y = 1 - 2 * ((real)j + REAL_C(0.5)) / (real)ny;
            vec_copy(out[n].o, o);
            for (int a = 0; a < 3; a++)
                out[n].d[a] = f[a] + x * r[a] + y * up[a];
            n++;
        }
    return n;
}

/* Every ray of a packet answered by grid_intersect_packet() as
 * grid_intersect() answers it alone, and as brute force: found, the
 * primitive, t and the barycentrics bit for bit. With `pre`, every other
 * query comes with a hit already, as a caller's query may: the ray's next
 * hit beyond its nearest (brute force from there; primset_test() of its
 * primitive before the walk: found, a lower tmax, the primitive in the
 * mailbox), which the walk must beat. Returns the hits. */
static long check_packet(const grid_t *g, const primset_t *ps,
                         const ray_t *r, const real *tmax, int n, bool pre,
                         long *pres)
{
    /* exactly n queries each, so that a read past the caller's n shows
     * under the sanitizers (make sanitize) */
    primset_query_t *got = malloc((size_t)n * sizeof *got);
    primset_query_t *one = malloc((size_t)n * sizeof *one);
    primset_query_t *want = malloc((size_t)n * sizeof *want);
    ck_assert(got && one && want);
    long hits = 0;
    for (int i = 0; i < n; i++) {
        primset_query_init(&got[i], &r[i], 0, tmax[i]);
        primset_query_init(&one[i], &r[i], 0, tmax[i]);
        brute_to(ps, &r[i], tmax[i], &want[i]);
        if (pre && i % 2 && want[i].found) {
            primset_query_t next;
            primset_query_init(&next, &r[i], want[i].hit.t, tmax[i]);
            for (uint32_t k = 0; k < ps->nrefs; k++)
                primset_test(ps, &next, k);
            if (next.found && next.ref != want[i].ref) {
                ck_assert(primset_test(ps, &got[i], next.ref));
                ck_assert(primset_test(ps, &one[i], next.ref));
                (*pres)++;
            }
        }
    }
    for (int i = 0; i < n; i++)
        check_plain(g, &one[i]);
    grid_intersect_packet(g, got, n);
    for (int i = 0; i < n; i++) {
        grid_intersect(g, &one[i]);
        const primset_query_t *o1 = &one[i], *w = &want[i];
        ck_assert_msg(got[i].found == o1->found && o1->found == w->found,
                      "ray %d of %d (%g %g %g) (%g %g %g): packet %d, "
                      "alone %d, brute force %d",
                      i, n, (double)r[i].o[0], (double)r[i].o[1],
                      (double)r[i].o[2], (double)r[i].d[0],
                      (double)r[i].d[1], (double)r[i].d[2], got[i].found,
                      o1->found, w->found);
        if (!w->found)
            continue;
        hits++;
        ck_assert_msg(got[i].ref == o1->ref && o1->ref == w->ref,
                      "ray %d: primitive %u, alone %u, brute force %u", i,
                      got[i].ref, o1->ref, w->ref);
        ck_assert(memcmp(&got[i].hit.t, &o1->hit.t, sizeof w->hit.t) == 0);
        ck_assert(memcmp(&got[i].hit.t, &w->hit.t, sizeof w->hit.t) == 0);
        ck_assert(memcmp(got[i].hit.b, o1->hit.b, sizeof w->hit.b) == 0);
        ck_assert(memcmp(got[i].hit.b, w->hit.b, sizeof w->hit.b) == 0);
    }
    free(got);
    free(one);
    free(want);
    return hits;
}

/* Packets of camera rays answer as single rays and brute force. Scenes:
 * 3^3 UV spheres crossed by analytic spheres, a terrain under them; the
 * uniform grid and the hierarchy, with quads and without. Cameras outside
 * the grid and inside it, in random directions and along the axes (so
 * that whole rows of a packet run parallel to an axis plane, and the
 * centre ray along an axis), with tiles of 4 x 4, 8 x 2, 8 x 8, 16 x 4,
 * 3 x 5, 12 x 10 (more than GRID_PACKET_MAX: two packets), 6 x 3 (18
 * rays: groups of four wholly past the caller's n) and 1 x 1 (a packet of
 * one) over the whole image, the border tiles included (rays that
 * miss everything, part-filled tiles); wide fields of view, whose tiles
 * straddle the change of major axis (those rays go alone); for a third
 * of the cameras rays of random lengths (tmax); three rays in 64 that
 * go alone (another origin, the other way, or a direction 2^-20 as long:
 * outside the triangle test's fast range, mesh_ray_prepare); and in a
 * third of the packets, queries that come with their hit (check_packet). */
START_TEST(packets_answer_as_single_rays_and_brute_force)
{
    svet_error e;
    meshgen_scene_t s;
    ck_assert(meshgen_sphere_grid(&s, 3, 6000, &e) == SVET_OK);
    COBJECT *objs[40];
    int nobjs = 0;
    for (int i = 0; i < s.nobjs; i++)
        objs[nobjs++] = s.objs[i];
    pcg32_t rng;
    pcg32_seed(&rng, 4242, 11);
    for (int i = 0; i < 6; i++) {
        VECTOR3 c = { 8 * pcg32_real(&rng) - 1, 8 * pcg32_real(&rng) - 1,
                      8 * pcg32_real(&rng) - 1 };
        objs[nobjs] = sphere_new(c, REAL_C(0.2) + REAL_C(0.6) *
                                                     pcg32_real(&rng), &e);
        ck_assert(objs[nobjs++] != NULL);
    }
    VECTOR3 tc = { 3, 3, -REAL_C(1.5) };
    ck_assert(meshgen_terrain(&objs[nobjs++], tc, 9, REAL_C(0.5), 24, 3,
                              &e) == SVET_OK);
    primset_t ps;
    ck_assert(primset_build(&ps, objs, nobjs, &e) == SVET_OK);
    long cases = 0, hits = 0, packets = 0, pres = 0;
    const int shapes[][2] = { { 4, 4 }, { 8, 2 }, { 8, 8 }, { 3, 5 },
                              { 16, 4 }, { 12, 10 }, { 6, 3 }, { 1, 1 } };
    for (int variant = 0; variant < 4; variant++) {
        grid_t *g = variant_grid(&ps, variant, 2, 8);
        for (int cam = 0; cam < 14; cam++) {
            VECTOR3 o, f, r, up, target;
            if (cam < 6) { /* outside, looking along an axis */
                int a = cam % 3;
                real sg = cam < 3 ? 1 : -1;
                vec_set(o, 3, 3, 3);
                o[a] -= sg * 12;
                vec_set(f, 0, 0, 0);
                f[a] = sg;
                vec_set(r, 0, 0, 0);
                vec_set(up, 0, 0, 0);
                r[(a + 1) % 3] = REAL_C(0.6);
                up[(a + 2) % 3] = REAL_C(0.6);
            } else { /* anywhere, inside the grid for the later ones */
                real span = cam < 10 ? 30 : 7;
                for (int a = 0; a < 3; a++) {
                    o[a] = span * pcg32_real(&rng) - (span - 7) / 2 - 1;
                    target[a] = 6 * pcg32_real(&rng);
                }
                vec_sub(f, target, o);
                vec_normalize(f, f);
                VECTOR3 z = { 0, 0, 1 };
                VVECTOR3(r, f, z);
                vec_normalize(r, r);
                VVECTOR3(up, r, f);
                /* wide views straddle the change of major axis */
                real fov = cam % 2 ? REAL_C(1.5) : REAL_C(0.4);
                vec_scale(r, r, fov);
                vec_scale(up, up, fov);
            }
            const int *sh =
                shapes[cam % (int)(sizeof shapes / sizeof shapes[0])];
            int nx = 36, ny = 28;
            for (int y0 = 0; y0 < ny; y0 += sh[1])
                for (int x0 = 0; x0 < nx; x0 += sh[0]) {
                    ray_t rays[2 * GRID_PACKET_MAX];
                    real tmax[2 * GRID_PACKET_MAX];
                    int n = tile_rays(rays, o, f, r, up, nx, ny, x0, y0,
                                      sh[0], sh[1]);
                    for (int i = 0; i < n; i++) {
                        /* a third of the packets: rays that end anywhere */
                        tmax[i] = cam % 3 == 1 ? 20 * pcg32_real(&rng)
                                               : (real)INFINITY;
                        /* now and then a ray that goes alone: another
                         * origin, or the other way */
                        uint32_t odd = pcg32_bounded(&rng, 64);
                        if (odd == 0)
                            rays[i].o[i % 3] += REAL_C(0.25);
                        else if (odd == 1)
                            vec_neg(rays[i].d, rays[i].d);
                        else if (odd == 2) /* outside the triangle
                                              test's fast range */
                            vec_scale(rays[i].d, rays[i].d, REAL_C(0x1p-20));
                    }
                    hits += check_packet(g, &ps, rays, tmax, n,
                                         packets % 3 == 0, &pres);
                    cases += n;
                    packets++;
                }
        }
        grid_free(g);
    }
    /* many rays hit, many miss */
    ck_assert(hits > cases / 4 && hits < cases * 3 / 4 && pres > 1000);
    test_report_cases("packets_answer_as_single_rays_and_brute_force (rays)",
                      cases);
    test_report_cases("packets_answer_as_single_rays_and_brute_force "
                      "(packets)", packets);
    test_report_cases("packets_answer_as_single_rays_and_brute_force "
                      "(queries that came with a farther hit)", pres);
    primset_free(&ps);
    for (int i = 0; i < nobjs; i++)
        cobject_free(objs[i]);
    free(s.objs);
}
END_TEST

/* Rays a caller should not send, in packets: a NaN or infinite direction,
 * a NaN origin (on the packet's first ray, whose origin the others are
 * compared with), tmax below tmin or NaN; each answers as it does alone
 * and as brute force does (no hit), and spoils nothing for the rays
 * beside it. n = 0 and n < 0 leave the queries as they were. */
START_TEST(packets_with_bad_rays_answer_as_single_rays)
{
    svet_error e;
    meshgen_scene_t s;
    ck_assert(meshgen_sphere_grid(&s, 2, 2000, &e) == SVET_OK);
    primset_t ps;
    ck_assert(primset_build(&ps, s.objs, s.nobjs, &e) == SVET_OK);
    const real nan = (real)NAN, inf = (real)INFINITY;
    long cases = 0, hits = 0;
    for (int variant = 0; variant < 4; variant++) {
        grid_t *g = variant_grid(&ps, variant, 2, 8);
        VECTOR3 o = { -9, 2, 2 }, f = { 1, 0, 0 };
        VECTOR3 r = { 0, REAL_C(0.4), 0 }, up = { 0, 0, REAL_C(0.4) };
        for (int bad = 0; bad < 7; bad++) {
            ray_t rays[GRID_PACKET_MAX];
            real tmax[GRID_PACKET_MAX];
            int n = tile_rays(rays, o, f, r, up, 8, 8, 0, 0, 8, 8);
            for (int i = 0; i < n; i++)
                tmax[i] = inf;
            for (int i = bad % 2; i < n; i += 5) {
                switch (bad) {
                case 0: rays[i].d[i % 3] = nan; break;
                case 1: rays[i].d[i % 3] = inf; break;
                case 2: tmax[i] = -1; break;
                case 3: tmax[i] = nan; break;
                case 4: rays[i].o[i % 3] = nan; break;
                case 5: vec_set(rays[i].d, 0, 0, 0); break;
                default: rays[i].d[0] = -inf; break;
                }
            }
            if (bad == 6) /* the first ray's origin spoilt */
                rays[0].o[0] = -inf;
            hits += check_packet(g, &ps, rays, tmax, n, false, NULL);
            cases += n;
        }
        /* n = 0 and n < 0: nothing read, nothing written */
        primset_query_t q[2], before[2];
        ray_t ray = { { 0, 2, 2 }, { 1, 0, 0 } };
        primset_query_init(&q[0], &ray, 0, inf);
        primset_query_init(&q[1], &ray, 0, inf);
        memcpy(before, q, sizeof q);
        grid_intersect_packet(g, q, 0);
        grid_intersect_packet(g, q, -3);
        ck_assert(memcmp(before, q, sizeof q) == 0);
        grid_free(g);
    }
    ck_assert(hits > cases / 8); /* the good rays beside them hit */
    test_report_cases("packets_with_bad_rays_answer_as_single_rays", cases);
    primset_free(&ps);
    for (int i = 0; i < s.nobjs; i++)
        cobject_free(s.objs[i]);
    free(s.objs);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("grid");
    TCase *tc = tcase_create("grid");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, resolution_follows_k_cubed_n_over_the_aspect);
    tcase_add_test(tc, every_triangle_is_in_every_cell_it_overlaps);
    tcase_add_test(tc, the_walk_visits_the_cells_a_ray_crosses);
    tcase_add_test(tc, skipping_empty_blocks_never_misses_a_cell);
    tcase_add_test(tc, a_crowded_cell_gets_a_child_grid);
    tcase_add_test(tc, huge_primitives_coarsen_the_grid_instead_of_exploding);
    tcase_add_test(tc,
                   cells_of_triangles_and_other_primitives_answer_as_brute_force);
    tcase_add_test(tc, packets_answer_as_single_rays_and_brute_force);
    tcase_add_test(tc, packets_with_bad_rays_answer_as_single_rays);
    suite_add_tcase(s, tc);
    return s;
}
