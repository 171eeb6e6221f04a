/*
 * grid.c - ch. 7: walking the uniform grid and the hierarchical grid
 * (grid_build.c builds them; grid.h describes the data).
 *   the uniform grid: the 3D-DDA of Amanatides & Woo ("A fast voxel
 *          traversal algorithm for ray tracing", Eurographics 1987), cell
 *          by cell along the ray, with mailboxing (sec. 4 of the paper;
 *          primset_seen()): walk_plain();
 *   the hierarchical grid (Jevans & Wyvill 1989): a cell that holds a
 *          child grid walks it with the same 3D-DDA, recursively;
 *   the tables: both grids as accel.h's accel_ops_t (grid_accels, at the
 *          end), which accel.c calls without naming this file.
 * This is the walk of the book, and what `make SIMD=off` and the chapter
 * programs' cc lines build; the default build answers grid_intersect()
 * with the fast walk of fast/grid_walk.c (block masks, macro-regions,
 * batches, quads) and packets with fast/grid_packet.c, the same answers
 * bit for bit.
 * Tests: tests/accel/test_grid.c, tests/accel/test_accel.c
 *
 * Why the answers are exactly brute force's. A walk may stop in a cell
 * once its nearest hit lies before the cell's exit: every primitive with a
 * nearer hit lies in a cell already visited. With rounding that needs two
 * margins. (1) Every primitive is inserted with its bounds padded by
 * ps->pad (2^-20 of the scene's diagonal), far more than the double
 * rounding of the cell arithmetic, so a hit point lies well inside the
 * cells its primitive is in. (2) The walk stops only when the best t lies
 * below the exit t by slack = 256 u (t_exit + diag/|d|), u the unit
 * roundoff of real: a bound on the rounding error of the primitives' own
 * t (for a triangle, pbrt-v3 sec. 3.9.6 bounds it by a few u of the
 * distances to its vertices), so a primitive whose computed t beats the
 * best cannot lie beyond the cell. The same slack widens (tmin, tmax) for
 * the walk. A primitive is tested once per ray (the mailbox of primset.h)
 * and a hit beyond the current cell is kept, not discarded: the walk
 * simply goes on until a cell's exit passes it. Since the nearest-hit rule
 * does not depend on the order of the tests (primset_test()), every walk
 * that tests at least these primitives gives the same hit, bit for bit:
 * the plain walk here, the fast walk and the packets.
 */
#include "grid_walk.h"

/* --- the uniform grid: the 3D-DDA of Amanatides & Woo 1987 --------------- */

/* Walk node ni (the top level, or a child grid) over [t0, t1], the part
 * of the ray inside its box. Returns true when a shadow query found a hit.
 *
 * Initialisation (sec. 3 of the paper): the cell the ray is in at t0; per
 * axis the direction of the step, the t at which the ray crosses the
 * next cell plane (the paper's tMax) and the t between two planes
 * (tDelta). Then each step tests the cell's primitives, and moves to the
 * neighbour across the nearest plane, adding tDelta to that axis's t; t
 * grows in double, so after n steps its rounding error is below n 2^-53
 * of t, far inside the cells' padding. The walk ends past the last cell,
 * or at a cell whose exit lies beyond walk_end(): past the query's end,
 * or past the nearest hit by the slack (the opening comment). An axis the
 * ray does not move along (d = 0, or 1/d not finite) has t = inf: it is
 * never chosen before another, and choosing it ends the walk. */
static bool walk_plain(const grid_t *g, uint32_t ni, const walk_t *w,
                       primset_query_t *q, double t0, double t1, bool shadow)
{
    const grid_node_t *nd = &g->nodes[ni];
    int cell[3], step[3];
    double t_max[3], t_delta[3];
    for (int a = 0; a < 3; a++) {
        cell[a] = cell_of(nd, a, w->o[a] + t0 * w->d[a]);
        if (!isfinite(w->inv_d[a])) {
            step[a] = 0;
            t_max[a] = (double)INFINITY;
            t_delta[a] = 0;
        } else if (w->d[a] > 0) {
            step[a] = 1;
            t_max[a] = plane_t(nd, w, a, cell[a] + 1);
            t_delta[a] = nd->w[a] * w->inv_d[a];
        } else {
            step[a] = -1;
            t_max[a] = plane_t(nd, w, a, cell[a]);
            t_delta[a] = -nd->w[a] * w->inv_d[a];
        }
    }
    for (;;) {
        q->cells++;
        uint32_t begin, end;
        grid_cell_at(g, nd, cell[0], cell[1], cell[2], &begin, &end);
        for (uint32_t k = begin; k < end; k++) {
            uint32_t it = g->items[k];
            if (!(it & GRID_CHILD)) {
                /* the mailbox inside primset_test(): once per ray */
                if (primset_test(g->ps, q, it) && shadow)
                    return true;
                continue;
            }
            /* the hierarchical grid: a child grid, listed after the
             * cell's own primitives, walked over the ray's part of its
             * box */
            uint32_t ci = it & ~GRID_CHILD;
            const grid_node_t *ch = &g->nodes[ci];
            double c0, c1;
            if (slab(w, ch->min, ch->max, w->t0, w->t1, &c0, &c1) &&
                walk_plain(g, ci, w, q, c0, c1, shadow))
                return true;
        }
        double t_exit;
        int a = nearest_axis(t_max[0], t_max[1], t_max[2], &t_exit);
        if (!(t_exit <= walk_end(w, q, t1)) || step[a] == 0)
            return false;
        cell[a] += step[a];
        if (cell[a] < 0 || cell[a] >= nd->res[a])
            return false;
        t_max[a] += t_delta[a];
    }
}

bool grid_intersect_plain(const grid_t *g, primset_query_t *q)
{
    return grid_query(g, q, false, false, walk_plain);
}

bool grid_occluded_plain(const grid_t *g, primset_query_t *q)
{
    return grid_query(g, q, true, false, walk_plain);
}

#ifndef SVET_SIMD
/* Without the speed layers (`make SIMD=off`: no fast/grid_walk.c, no
 * fast/grid_packet.c) the plain walk answers every query, and a packet's
 * rays one by one: the answers grid.h promises. */
bool grid_intersect(const grid_t *g, primset_query_t *q)
{
    return grid_intersect_plain(g, q);
}

bool grid_occluded(const grid_t *g, primset_query_t *q)
{
    return grid_occluded_plain(g, q);
}

void grid_intersect_packet(const grid_t *g, primset_query_t *q, int n)
{
    for (int i = 0; i < n; i++)
        grid_intersect_plain(g, &q[i]);
}
#endif

/* --- the grids as acceleration structures (accel.h) ---------------------- */

/* accel_params_t's numbers over the defaults: the uniform grid's when
 * hierarchical is false, else the hierarchical grid's. */
static void params_of(const accel_params_t *p, bool hierarchical,
                      grid_params_t *g)
{
    if (hierarchical)
        grid_params_hierarchical(g);
    else
        grid_params_uniform(g);
    if (!hierarchical && p->grid_k > 0)
        g->k = p->grid_k;
    if (hierarchical && p->hgrid_k > 0)
        g->k = p->hgrid_k;
    if (p->hgrid_leaf > 0)
        g->leaf_max = p->hgrid_leaf;
    if (hierarchical && p->hgrid_depth > 0)
        g->max_depth = p->hgrid_depth;
    if (hierarchical && p->hgrid_child_k > 0)
        g->child_k = p->hgrid_child_k;
}

static svet_status build_uniform(void **out, const primset_t *ps,
                                 const accel_params_t *p, svet_error *err)
{
    grid_params_t g;
    params_of(p, false, &g);
    return grid_build((grid_t **)out, ps, &g, err);
}

static svet_status build_hierarchical(void **out, const primset_t *ps,
                                      const accel_params_t *p,
                                      svet_error *err)
{
    grid_params_t g;
    params_of(p, true, &g);
    return grid_build((grid_t **)out, ps, &g, err);
}

static bool ops_intersect(const void *g, primset_query_t *q)
{
    return grid_intersect(g, q);
}

static bool ops_occluded(const void *g, primset_query_t *q)
{
    return grid_occluded(g, q);
}

static void ops_intersect_packet(const void *g, primset_query_t *q, int n)
{
    grid_intersect_packet(g, q, n);
}

static void ops_free(void *g)
{
    grid_free(g);
}

static void ops_stats(const void *v, accel_stats_t *s)
{
    const grid_t *g = v;
    s->bytes = grid_bytes(g);
    s->nodes = (long)g->nnodes;
    s->cells = (long)g->ncells;
    s->items = (long)g->nitems;
    s->empty_cells = (long)g->empty_cells;
    s->max_cell = (long)g->max_items;
    s->depth = g->depth;
    for (int k = 0; k < 3; k++) {
        s->res[k] = g->nodes[0].res[k];
        s->box_min[k] = g->nodes[0].min[k];
        s->box_max[k] = g->nodes[0].max[k];
    }
}

/* AUTO's measure (accel.h): the fraction of the top level's references
 * that sit in cells of more than `crowd` primitives. */
static double ops_crowded(const void *v, long crowd)
{
    const grid_t *g = v;
    const grid_node_t *top = &g->nodes[0];
    long nc = (long)top->res[0] * top->res[1] * top->res[2];
    double crowded = 0, all = 0;
    for (long c = 0; c < nc; c++) {
        uint32_t begin, end;
        grid_cell_items(g, 0, c, &begin, &end);
        double n = end - begin;
        all += n;
        if (n > crowd)
            crowded += n;
    }
    return all > 0 ? crowded / all : 0;
}

const accel_ops_t grid_uniform_accel = {
    .kind = ACCEL_GRID, .build = build_uniform, .intersect = ops_intersect,
    .occluded = ops_occluded, .free = ops_free, .stats = ops_stats,
    .crowded = ops_crowded, .intersect_packet = ops_intersect_packet
};

const accel_ops_t grid_hierarchical_accel = {
    .kind = ACCEL_HGRID, .build = build_hierarchical,
    .intersect = ops_intersect, .occluded = ops_occluded, .free = ops_free,
    .stats = ops_stats, .crowded = ops_crowded,
    .intersect_packet = ops_intersect_packet
};

const accel_ops_t *const grid_accels[] = {
    &grid_uniform_accel, &grid_hierarchical_accel, NULL
};
