/*
 * grid_walk.h - what the files of the grids (ch. 7) share and nothing else
 * reads: the ray in double with the walk's margins, the cell lookup, the
 * slab test, the stopping rule of the 3D-DDA (Amanatides & Woo 1987), and
 * the fast walk's entry points that the packets reuse. grid.c's opening
 * comment argues the margins; grid.h describes the data.
 * Tests: tests/accel/test_grid.c
 */
#ifndef SVET_GRID_WALK_H
#define SVET_GRID_WALK_H

#include "accel/grid.h"
#include "core/bits.h"

#include <math.h>

/* Cell coordinate of x on axis a, clamped into the grid. */
static inline int cell_of(const grid_node_t *nd, int a, double x)
{
    /* floor(c) by the conversion, which truncates: the same for c >= 0
     * (plain x86-64 has no floor instruction; libm's is a call) */
    double c = (x - nd->min[a]) * nd->inv_w[a];
    if (!(c >= 0))
        return 0;
    if (c >= nd->res[a] - 1)
        return nd->res[a] - 1;
    return (int)c;
}

/* The non-empty cell of bit `bit` (set) of a block: base its bbase, mask
 * its bmask. */
static inline uint32_t full_cell(uint32_t base, uint64_t mask, int bit)
{
    return base + (uint32_t)bits_count(mask & ((UINT64_C(1) << bit) - 1));
}

/* The items of cell (x, y, z) of node nd: items[*begin ..
 * *end), empty when the cell is. The cell's bit in its block's word says
 * whether it holds anything; the set bits before it count the non-empty
 * cells before it in the block (grid.h). This function can't fail. */
static inline void grid_cell_at(const grid_t *g, const grid_node_t *nd,
                                int x, int y, int z, uint32_t *begin,
                                uint32_t *end)
{
    int bit = x % GRID_BLOCK + GRID_BLOCK * (y % GRID_BLOCK) +
              GRID_BLOCK * GRID_BLOCK * (z % GRID_BLOCK);
    long b = nd->bfirst + x / GRID_BLOCK +
             nd->nb[0] * (y / GRID_BLOCK + (long)nd->nb[1] * (z / GRID_BLOCK));
    *begin = *end = 0;
    if (g->bmask[b] >> bit & 1) {
        uint32_t s = full_cell(g->bbase[b], g->bmask[b], bit);
        *begin = g->cstart[s];
        *end = g->cstart[s + 1];
    }
}

/* The per-axis loops of the walks' set-up unrolled where the compiler
 * takes the hint (gcc's -O2 keeps them as loops). */
#if defined(__GNUC__) || defined(__clang__)
#define GRID_UNROLL3 _Pragma("GCC unroll 3")
#else
#define GRID_UNROLL3
#endif

/* The walk's slack, 256 u (grid.c's opening comment). */
#define WALK_SLACK (256 * (double)REAL_UNIT_ROUNDOFF)

/* The ray in double, and the walk's margins (grid.c's opening comment). */
typedef struct {
    double o[3], d[3], inv_d[3];
    double t0, t1;  /* the query interval widened by the slack */
    double bias;    /* WALK_SLACK diag / |d| */
#if GRID_QUADS && MESH_WIDE
    mesh_wide_ray_t wr; /* for two quads at once (where there are quads) */
#endif
} walk_t;

/* The part [*t0, *t1] of [lo, hi] (ray interval) inside the box. */
static inline bool slab(const walk_t *w, const double min[3],
                        const double max[3], double lo, double hi,
                        double *t0, double *t1)
{
    GRID_UNROLL3
    for (int a = 0; a < 3; a++) {
        double tn = (min[a] - w->o[a]) * w->inv_d[a];
        double tf = (max[a] - w->o[a]) * w->inv_d[a];
        if (tn > tf) {
            double s = tn;
            tn = tf;
            tf = s;
        }
        /* 0 * inf: the ray runs in the plane of a face, inside the slab
         * (the comparisons below treat NaN as "no limit"). */
        if (tn > lo)
            lo = tn;
        if (tf < hi)
            hi = tf;
    }
    *t0 = lo;
    *t1 = hi;
    return lo <= hi;
}

/* The ray's walk_t (the wide ray only where wide) as at the start of a
 * query whose tmax was tmax_q. Always inlined where compilers allow: with
 * the packets as a second caller gcc would make it a call, on every ray. */
#if defined(__GNUC__) || defined(__clang__)
__attribute__((always_inline))
#endif
static inline void walk_init_at(walk_t *w, const grid_t *g,
                                const primset_query_t *q, real tmax_q,
                                bool wide)
{
    const ray_t *r = q->r;
    double len2 = 0;
    GRID_UNROLL3
    for (int a = 0; a < 3; a++) {
        w->o[a] = (double)r->o[a];
        w->d[a] = (double)r->d[a];
        w->inv_d[a] = 1 / w->d[a];
        len2 += w->d[a] * w->d[a];
    }
    w->bias = WALK_SLACK * g->diag / sqrt(len2);
    double tmin = (double)q->tmin, tmax = (double)tmax_q;
    w->t0 = tmin - WALK_SLACK * fabs(tmin) - w->bias;
    w->t1 = tmax + WALK_SLACK * fabs(tmax) + w->bias;
#if GRID_QUADS && MESH_WIDE
    if (wide && g->quads)
        mesh_wide_ray_prepare(&w->wr, &q->mr);
#else
    (void)wide;
#endif
}

/* Where the walk may stop once the nearest hit so far is at tmax: a cell
 * whose exit t_exit lies beyond it has t_exit (1 - WALK_SLACK) - bias >
 * tmax, the stopping rule of grid.c's opening comment (x + 2 s |x| >=
 * x / (1 - s) for either sign of x = tmax + bias; the double rounding of
 * this line is far below s). Never beyond t1. */
static inline double walk_end_at(double bias, const primset_query_t *q,
                                 double t1)
{
    if (!q->found)
        return t1;
    double x = (double)q->tmax + bias;
    x += 2 * WALK_SLACK * fabs(x);
    return x < t1 ? x : t1;
}

/* walk_end_at() with the walk's own bias. */
static inline double walk_end(const walk_t *w, const primset_query_t *q,
                              double t1)
{
    return walk_end_at(w->bias, q, t1);
}

/* The t at which the ray crosses plane p (x_a = min_a + p w_a) of nd:
 * every crossing the walk compares comes from this one formula, the
 * planes between cells and those between blocks alike. */
static inline double plane_t(const grid_node_t *nd, const walk_t *w, int a,
                             long p)
{
    return (nd->min[a] + (double)p * nd->w[a] - w->o[a]) * w->inv_d[a];
}

/* A walk of node ni over [t0, t1]: the plain one (grid.c) or the fast one
 * (fast/grid_walk.c). Returns true when a shadow query found a hit. */
typedef bool (*grid_walk_fn)(const grid_t *g, uint32_t ni, const walk_t *w,
                             primset_query_t *q, double t0, double t1,
                             bool shadow);

/* A query of the whole grid: the ray's part of the top level's box, then
 * its walk by `walk` (a constant at each caller, so the call is direct
 * once inlined); `wide` as for walk_init_at(). Returns q->found, or for a
 * shadow query whether it found a hit. */
#if defined(__GNUC__) || defined(__clang__)
__attribute__((always_inline))
#endif
static inline bool grid_query(const grid_t *g, primset_query_t *q,
                              bool shadow, bool wide, grid_walk_fn walk)
{
    if (g->ncells == 0 || g->ps->nbounded == 0)
        return q->found;
    walk_t w;
    walk_init_at(&w, g, q, q->tmax, wide);
    const grid_node_t *top = &g->nodes[0];
    double t0, t1;
    if (!(w.t0 <= w.t1) ||
        !slab(&w, top->min, top->max, w.t0, w.t1, &t0, &t1))
        return q->found;
    bool hit = walk(g, 0, &w, q, t0, t1, shadow);
    return shadow ? hit : q->found;
}

/* The axis of the nearest of the crossings tx, ty, tz (ties to the
 * later axis), and that crossing's t in *t. Branches, not selects: a
 * predicted branch lets the next step start before the compare is done. */
static inline int nearest_axis(double tx, double ty, double tz, double *t)
{
    if (tx < ty && tx < tz) {
        *t = tx;
        return 0;
    }
    if (ty < tz) {
        *t = ty;
        return 1;
    }
    *t = tz;
    return 2;
}

/* Kept out of the fast walk's loop, where compilers allow: inlined, its
 * registers would push the walk's state onto the stack. */
#if defined(__GNUC__) || defined(__clang__)
#define GRID_NOINLINE __attribute__((noinline))
#else
#define GRID_NOINLINE
#endif

#if GRID_QUADS
/* The full test of the lanes `left` of the quads qd (lane j in quad
 * j / MESH_BATCH), which the sign test could not reject, through the
 * mailbox. The corners come from the quad, which the sign test has just
 * brought into the cache, not from ps->tri (a copy of the same bits, so
 * the same answer), which is often a miss to memory. Returns true when a
 * shadow query found a hit. */
static inline bool test_lanes(const primset_t *ps, primset_query_t *q,
                              const grid_quad_t *qd, unsigned left,
                              bool shadow)
{
    /* one turn per lane kept (usually one or two of eight), not per lane */
    for (; left; left &= left - 1) {
        int j = bits_lowest(left);
        const grid_quad_t *qj = &qd[j / MESH_BATCH];
        uint32_t ref = qj->ref[j % MESH_BATCH];
        if (ref == GRID_QUAD_PAD) /* padding is last */
            break;
        if (primset_seen(q, ref))
            continue;
        real c[9];
        for (int k = 0; k < 9; k++)
            c[k] = qj->c[k * MESH_BATCH + j % MESH_BATCH];
        if (primset_test_corners(ps, q, ref, c) && shadow)
            return true;
    }
    return false;
}
#endif
/* --- between the build and the fast walk (grid_build.c, fast/grid_walk.c) */

/* One of the grid's arrays that the walks read, of `bytes`, aligned for
 * the vectors (grid_build.c). NULL when out of memory; free() frees it. */
void *grid_alloc(size_t bytes);

#if GRID_QUADS
/* The quads of every non-empty cell (grid.h), from g's items
 * (fast/grid_walk.c). Fails with SVET_ERR_NOMEM. */
svet_status grid_make_quads(grid_t *g, svet_error *err);
#endif

/* --- the fast walk, which the packets reuse (fast/grid_walk.c) ----------- */

/* Walk node ni over [t0, t1] (inside its box), by blocks and cells.
 * Returns true when a shadow query found a hit. This function can't fail. */
bool grid_walk_node(const grid_t *g, uint32_t ni, const walk_t *w,
                    primset_query_t *q, double t0, double t1, bool shadow);

/* Test the n items of a cell (those in the grid's quads left out), child
 * grids walked. Returns true when a shadow query found a hit. */
bool grid_test_items(const grid_t *g, const walk_t *w, primset_query_t *q,
                     const uint32_t *items, uint32_t n, bool shadow);

/* Test non-empty cell f: its quads, then its other items. Returns true
 * when a shadow query found a hit. */
bool grid_test_full(const grid_t *g, const walk_t *w, primset_query_t *q,
                    uint32_t f, bool shadow);

#endif
