/*
 * fast/grid_walk.c - ch. 7: the grids' fast walk, grid_intersect() and
 * grid_occluded(): the same answers as grid.c's plain walk, bit for bit
 * (tests/accel/test_grid.c checks both on the same rays), with four speed
 * layers over the plain 3D-DDA of Amanatides & Woo 1987, each in its own
 * section below:
 *   block masks: inside a block of 4^3 cells that holds something, a cell
 *          is tested against the block's 64-bit word in a register, not
 *          looked up in memory;
 *   macro-regions (Devillers, "The macro-regions: an efficient space
 *          subdivision structure for ray tracing", Eurographics 1989, here
 *          fixed blocks of 4^3 cells): a block with nothing in it is
 *          crossed in one step;
 *   batches: MESH_BATCH mesh triangles that the mailbox lets through go
 *          through the sign test of mesh_ray_reject() at once, the
 *          survivors through the full test (float with SSE2);
 *   quads: where the vectors hold MESH_BATCH reals and the scene is large
 *          (grid.h), every cell keeps its triangles' corners side by side,
 *          MESH_BATCH to a quad, for mesh_lanes_reject_soa() (with AVX
 *          two quads, eight triangles, at a time: mesh_wide_reject_soa2).
 * Left out of the build by `make SIMD=off`, where grid.c's plain walk
 * answers every query.
 * Tests: tests/accel/test_grid.c, tests/accel/test_accel.c
 */
#include "../grid_walk.h"

#include <stdlib.h>
#include <string.h>

/* --- block masks and macro-regions: the walk by blocks ------------------- */

/* The state of a walk through one node (grid_walk_node()): per axis, t the t
 * of the next cell plane crossed, dt the t between two cell planes, lc
 * the cells left ahead in the current block; tb the t of the next plane
 * between blocks, db = GRID_BLOCK dt, lb the blocks left ahead in the
 * grid; sg the direction (+1, -1, or 0 for an axis the ray does not move
 * along: d = 0, or 1/d not finite), ix the cell of an axis with sg 0;
 * blk and bit the current block and the cell's bit in its word, dblk and
 * dbit their steps; steps the cells and empty blocks visited. */
typedef struct {
    struct {
        double t, dt, tb, db; /* per axis, not four arrays: the compiler
                                 then keeps tx, ty, tz apart in registers
                                 (adjacent, it packed two in a vector and
                                 unpacked them at every step) */
    } ax[3];
    int lc[3], lb[3], sg[3], ix[3], dbit[3];
    long dblk[3];
    long blk;
    int bit;
    long steps;
} dda_t;

static const int bit_stride[3] = { 1, GRID_BLOCK, GRID_BLOCK * GRID_BLOCK };

/* The cells ahead on axis a (lc) in the block the walk has just entered
 * on that axis: all but one, except in the grid's last block going up,
 * which may reach past res (the walk never steps into a cell that is not
 * there). */
static inline int entry_lc(const grid_node_t *nd, const dda_t *s, int a)
{
    return s->sg[a] > 0 && s->lb[a] == 0
               ? nd->res[a] - 1 - GRID_BLOCK * (nd->nb[a] - 1)
               : GRID_BLOCK - 1;
}

/* The cell's coordinate within its block on axis a. */
static inline int local_cell(const grid_node_t *nd, const dda_t *s, int a)
{
    return s->sg[a] > 0   ? entry_lc(nd, s, a) - s->lc[a]
           : s->sg[a] < 0 ? s->lc[a]
                          : s->ix[a] % GRID_BLOCK;
}

/* Cross empty blocks (the current one is empty) until one holds
 * something, and set the walk on the cell of that block it enters first;
 * returns that block's word, or 0 when the walk is over (past tend, or out
 * of the grid). The block DDA runs on tb, kept by grid_walk_node() along
 * with the cells' t (no set-up here); the axis is picked by branches, as
 * in grid_walk_node(), which argues why the cell entered is right. */
static uint64_t skip_empty(const grid_node_t *nd, const walk_t *w,
                           const uint64_t *bmask, dda_t *s, double tend)
{
    double tx = s->ax[0].tb, ty = s->ax[1].tb, tz = s->ax[2].tb;
    const double dx = s->ax[0].db, dy = s->ax[1].db, dz = s->ax[2].db;
    const long bx = s->dblk[0], by = s->dblk[1], bz = s->dblk[2];
    int lx = s->lb[0], ly = s->lb[1], lz = s->lb[2];
    int a = 0;      /* the axis of the last step */
    double tin = 0; /* and its t */
    long blk = s->blk;
    uint64_t mask = 0; /* the current block's: empty */
    /* every branch does its axis's whole step, with its own registers:
     * no array indexed by the axis in the loop */
    for (;;) {
        if (tx < ty && tx < tz) {
            if (!(tx <= tend) || lx == 0)
                break;
            a = 0;
            tin = tx;
            lx--;
            tx += dx;
            blk += bx;
        } else if (ty < tz) {
            if (!(ty <= tend) || ly == 0)
                break;
            a = 1;
            tin = ty;
            ly--;
            ty += dy;
            blk += by;
        } else {
            if (!(tz <= tend) || lz == 0)
                break;
            a = 2;
            tin = tz;
            lz--;
            tz += dz;
            blk += bz;
        }
        if ((mask = bmask[blk]) != 0)
            break;
    }
    /* one step per block crossed */
    int moved = (lx != s->lb[0]) | (ly != s->lb[1]) << 1 |
                (lz != s->lb[2]) << 2;
    s->steps += (s->lb[0] - lx) + (s->lb[1] - ly) + (s->lb[2] - lz);
    if (mask == 0) /* past tend, or out of the grid */
        return 0;
    s->blk = blk;
    s->lb[0] = lx;
    s->lb[1] = ly;
    s->lb[2] = lz;
    s->ax[0].tb = tx;
    s->ax[1].tb = ty;
    s->ax[2].tb = tz;
    /* Enter the block at tin through its face on axis a: on a and on the
     * other axes whose block changed, the block's first cell, t from
     * plane_t(); then, on every axis but a, on past the cell planes the
     * ray crossed before tin, as the cell DDA would have. */
    s->bit = 0;
    GRID_UNROLL3
    for (int b = 0; b < 3; b++) {
        int sg = s->sg[b];
        if (sg != 0 && (b == a || (moved >> b & 1))) {
            long bc = sg > 0 ? nd->nb[b] - 1 - s->lb[b] : s->lb[b];
            s->lc[b] = entry_lc(nd, s, b);
            s->ax[b].t = plane_t(
                nd, w, b, GRID_BLOCK * bc + (sg > 0 ? 1 : GRID_BLOCK - 1));
        }
        if (b != a)
            while (s->lc[b] > 0 && s->ax[b].t < tin) {
                s->ax[b].t += s->ax[b].dt;
                s->lc[b]--;
            }
        s->bit += local_cell(nd, s, b) * bit_stride[b];
    }
    return mask;
}

/* The 3D-DDA of grid.c's walk_plain() over the cells, with the empty
 * space skipped block by block (the macro-regions). Inside a
 * block that holds something, each step goes to the nearest cell
 * crossing and a cell is tested against the block's 64-bit word in a
 * register; t grows by adding dt, in double: after n steps its rounding
 * error is below n 2^-53 of t, far inside the cells' padding (2^-20 of
 * the scene). The step picks its axis with plain branches, and the t of
 * the three axes live in three scalars, not in the paper's table indexed
 * by the axis: a ray's steps are regular enough for the predictor, and a
 * predicted branch lets the next step start before its compare is done,
 * where a select waits for it. Stepping out of the last cell of a block loads
 * the next block's word; when it is 0, skip_empty() goes block by block
 * (the same DDA over the planes between blocks, whose t, tb, the walk
 * keeps all along: no set-up per empty run) until a block holds
 * something.
 *
 * Why skipping never jumps past a cell it should visit. The planes between
 * blocks are cell planes; their t (tb) comes from plane_t() and then grows
 * by GRID_BLOCK dt (exact: a power of two times dt), as the cells' t grow
 * by dt, so the block DDA crosses a block plane at the t the cell DDA
 * would (to a few ulps), and so enters the blocks the cell DDA would
 * enter, save where two crossings lie within a few ulps of each other:
 * there the ray passes within a few ulps of a block edge or corner, and
 * a primitive it hits there lies within its padding (2^-20 of the scene:
 * grid.c's opening comment) of the blocks on both sides, so it is in a
 * cell the walk visits. The cell entered, at the entry t tin through the face on axis
 * a: on a, the block's first; on an axis whose block changed during the
 * skip, the block's first, with t from plane_t(); then, on every axis but
 * a, the walk moves on past the cell planes whose t lies before tin (at
 * most GRID_BLOCK - 1, never out of the block) -- the cell DDA's own rule
 * on its own t, so the cell is the one the cell DDA would be in at tin, to
 * the same few ulps. Every step moves one axis forward and none back (a
 * cell or block step on its axis; the catching up on the others only
 * forward, within the block): counting 4 per block left and 1 per cell
 * left in the block on every axis, each step lowers the count, so the
 * walk ends after at most about res_x + res_y + res_z steps, whatever
 * rounding does. An axis the ray does not move along has lc = lb = 0 and
 * t = tb = inf: it is never chosen before another, and choosing it ends
 * the walk. */
bool grid_walk_node(const grid_t *g, uint32_t ni, const walk_t *w,
                    primset_query_t *q, double t0, double t1, bool shadow)
{
    const grid_node_t *nd = &g->nodes[ni];
    const uint64_t *bmask = g->bmask + nd->bfirst;
    const uint32_t *bbase = g->bbase + nd->bfirst;
    const long bstride[3] = { 1, nd->nb[0], (long)nd->nb[0] * nd->nb[1] };
    dda_t s;
    s.blk = 0;
    s.bit = 0;
    s.steps = 1;
    GRID_UNROLL3
    for (int a = 0; a < 3; a++) {
        int ix = cell_of(nd, a, w->o[a] + t0 * w->d[a]);
        int sg = !isfinite(w->inv_d[a]) ? 0 : w->d[a] > 0 ? 1
                                           : w->d[a] < 0 ? -1 : 0;
        /* ix >= 0: unsigned, so that % and / are a mask and a shift */
        int loc = (int)((unsigned)ix % GRID_BLOCK);
        int bl = (int)((unsigned)ix / GRID_BLOCK);
        s.ix[a] = ix;
        s.sg[a] = sg;
        if (sg > 0) {
            s.lb[a] = nd->nb[a] - 1 - bl;
            s.lc[a] = entry_lc(nd, &s, a) - loc;
            s.ax[a].t = plane_t(nd, w, a, ix + 1);
            s.ax[a].dt = nd->w[a] * w->inv_d[a];
            s.ax[a].tb = plane_t(nd, w, a, (long)GRID_BLOCK * (bl + 1));
        } else if (sg < 0) {
            s.lc[a] = loc;
            s.lb[a] = bl;
            s.ax[a].t = plane_t(nd, w, a, ix);
            s.ax[a].dt = -nd->w[a] * w->inv_d[a];
            s.ax[a].tb = plane_t(nd, w, a, (long)GRID_BLOCK * bl);
        } else {
            s.lc[a] = s.lb[a] = 0;
            s.ax[a].t = s.ax[a].tb = (double)INFINITY;
            s.ax[a].dt = 0;
        }
        s.ax[a].db = GRID_BLOCK * s.ax[a].dt;
        s.dbit[a] = sg * bit_stride[a];
        s.dblk[a] = sg * bstride[a];
        s.blk += bl * bstride[a];
        s.bit += loc * bit_stride[a];
    }
    const double dtx = s.ax[0].dt, dty = s.ax[1].dt, dtz = s.ax[2].dt;
    const int dbx = s.dbit[0], dby = s.dbit[1], dbz = s.dbit[2];
    double tend = walk_end(w, q, t1);
    bool hit = false;
    uint64_t mask = bmask[s.blk];
    if (mask == 0 && !(mask = skip_empty(nd, w, bmask, &s, tend)))
        goto done;
    for (;;) {
        /* the hot state in scalars, which the compiler keeps in registers */
        double tx = s.ax[0].t, ty = s.ax[1].t, tz = s.ax[2].t;
        int lx = s.lc[0], ly = s.lc[1], lz = s.lc[2];
        long steps = s.steps;
        int bit = s.bit;
        int a; /* the axis of the step */
        for (;;) {
            if (mask >> bit & 1) {
                uint32_t f = full_cell(bbase[s.blk], mask, bit);
                if (grid_test_full(g, w, q, f, shadow)) {
                    s.steps = steps;
                    hit = true;
                    goto done;
                }
                tend = walk_end(w, q, t1);
            }
            /* the axis of the nearest crossing; past tend (the query's end
             * or the stopping rule) the walk is over */
            double texit;
            a = nearest_axis(tx, ty, tz, &texit);
            if (!(texit <= tend)) {
                s.steps = steps;
                goto done;
            }
            if (a == 0) {
                if (lx == 0)
                    break; /* out of the block */
                lx--;
                bit += dbx;
                tx += dtx;
            } else if (a == 1) {
                if (ly == 0)
                    break;
                ly--;
                bit += dby;
                ty += dty;
            } else {
                if (lz == 0)
                    break;
                lz--;
                bit += dbz;
                tz += dtz;
            }
            steps++;
        }
        /* out of the block, into the next one or out of the grid */
        s.ax[0].t = tx;
        s.ax[1].t = ty;
        s.ax[2].t = tz;
        s.lc[0] = lx;
        s.lc[1] = ly;
        s.lc[2] = lz;
        s.steps = steps;
        if (s.lb[a] == 0)
            goto done;
        s.steps++;
        s.lb[a]--;
        /* the first cell of the next block */
        s.lc[a] = entry_lc(nd, &s, a);
        s.bit = bit - (GRID_BLOCK - 1) * s.dbit[a];
        s.blk += s.dblk[a];
        s.ax[a].t += s.ax[a].dt;
        s.ax[a].tb += s.ax[a].db;
        mask = bmask[s.blk];
        if (mask == 0 && !(mask = skip_empty(nd, w, bmask, &s, tend)))
            goto done;
    }
done:
    q->cells += s.steps;
    return hit;
}

bool grid_intersect(const grid_t *g, primset_query_t *q)
{
    return grid_query(g, q, false, true, grid_walk_node);
}

bool grid_occluded(const grid_t *g, primset_query_t *q)
{
    return grid_query(g, q, true, true, grid_walk_node);
}

/* --- quads: a cell's triangles side by side ------------------------------ */

#if GRID_QUADS
/* The cells' mesh triangles as quads (grid.h, GRID_QUADS): each
 * non-empty cell's triangles in the order of its items, MESH_BATCH a
 * quad, the last quad padded with its first lane (GRID_QUAD_PAD). A
 * triangle listed in more than GRID_QUAD_SPAN cells (a stadium's ground)
 * stays out of the quads: copying its corners into every cell would cost
 * far more memory than its one shared copy, which stays in cache; the walk
 * tests it from the items (g->qout marks it). */
static bool quad_candidate(const grid_t *g, uint32_t it)
{
    return it < g->ps->ntri && !(g->qout[it / 64] >> (it % 64) & 1);
}

svet_status grid_make_quads(grid_t *g, svet_error *err)
{
    const primset_t *ps = g->ps;
    uint8_t *span = calloc((size_t)ps->ntri + 1, 1);
    g->qout = calloc((size_t)ps->ntri / 64 + 1, sizeof *g->qout);
    if (!span || !g->qout) {
        free(span);
        return svet_error_set(err, SVET_ERR_NOMEM, "grid: out of memory");
    }
    for (uint32_t k = 0; k < g->nitems; k++)
        if (g->items[k] < ps->ntri && span[g->items[k]] <= GRID_QUAD_SPAN)
            span[g->items[k]]++;
    for (uint32_t t = 0; t < ps->ntri; t++)
        if (span[t] > GRID_QUAD_SPAN)
            g->qout[t / 64] |= UINT64_C(1) << (t % 64);
    free(span);
    uint64_t nq = 0;
    for (uint32_t f = 0; f < g->nfull; f++) {
        uint32_t nt = 0;
        for (uint32_t k = g->cstart[f]; k < g->cstart[f + 1]; k++)
            nt += quad_candidate(g, g->items[k]);
        nq += (nt + MESH_BATCH - 1) / MESH_BATCH;
    }
    if (nq >= GRID_MORE)
        return svet_error_set(err, SVET_ERR_NOMEM,
                              "grid: %llu quads: too many",
                              (unsigned long long)nq);
    g->quads = grid_alloc((size_t)(nq ? nq : 1) * sizeof *g->quads);
    g->qstart = grid_alloc(((size_t)g->nfull + 1) * sizeof *g->qstart);
    if (!g->quads || !g->qstart)
        return svet_error_set(err, SVET_ERR_NOMEM, "grid: out of memory");
    uint32_t q = 0;
    for (uint32_t f = 0; f < g->nfull; f++) {
        bool more = false;
        int lane = MESH_BATCH;
        g->qstart[f] = q;
        for (uint32_t k = g->cstart[f]; k < g->cstart[f + 1]; k++) {
            uint32_t it = g->items[k];
            if (!quad_candidate(g, it)) {
                more = true;
                continue;
            }
            if (lane == MESH_BATCH) {
                lane = 0;
                q++;
            }
            grid_quad_t *qd = &g->quads[q - 1];
            for (int c = 0; c < 9; c++)
                qd->c[c * MESH_BATCH + lane] = ps->tri[it][c];
            qd->ref[lane++] = it;
        }
        for (; q > g->qstart[f] && lane < MESH_BATCH; lane++) {
            grid_quad_t *qd = &g->quads[q - 1];
            for (int c = 0; c < 9; c++)
                qd->c[c * MESH_BATCH + lane] = qd->c[c * MESH_BATCH];
            qd->ref[lane] = GRID_QUAD_PAD;
        }
        if (more)
            g->qstart[f] |= GRID_MORE;
    }
    g->qstart[g->nfull] = q;
    g->nquads = q;
    return SVET_OK;
}

#endif

/* Is item it a mesh triangle kept in the grid's quads? */
static inline bool in_quads(const grid_t *g, uint32_t it)
{
    return g->quads && it < g->ps->ntri &&
           !(g->qout[it / 64] >> (it % 64) & 1);
}

/* Test the nq quads qd of a cell (GRID_QUADS): the sign test of each
 * quad's triangles at once (mesh_lanes_reject_soa; where the widest
 * vectors hold two quads, AVX, two quads at once with
 * mesh_wide_reject_soa2), then, for each lane it cannot reject, the
 * mailbox and the full test. The same answers as primset_test() on each
 * triangle: a lane is rejected only where mesh_ray_intersect() returns
 * false at that very test, with the same bits (mesh.h), the mailbox only
 * keeps a triangle from being tested twice, and the nearest-hit rule does
 * not depend on the order. A triangle the sign test rejects is not
 * entered in the mailbox (nor counted in q->tests): in the next cell it
 * is rejected again, as cheaply. Returns true when a shadow query found a
 * hit. */
static bool test_quads(const primset_t *ps, const walk_t *w,
                       primset_query_t *q, const grid_quad_t *qd, uint32_t nq,
                       bool shadow)
{
    (void)w;
#if GRID_QUADS
    uint32_t i = 0;
#if MESH_WIDE
    for (; i + 1 < nq; i += 2) {
        unsigned left = ~mesh_wide_reject_soa2(qd[i].c, qd[i + 1].c, &q->mr,
                                               &w->wr) &
                        ((1u << (2 * MESH_BATCH)) - 1);
        if (left && test_lanes(ps, q, qd + i, left, shadow))
            return true;
    }
#endif
    for (; i < nq; i++) {
        unsigned left = ~mesh_lanes_reject_soa(qd[i].c, &q->mr) &
                        ((1u << MESH_BATCH) - 1);
        if (left && test_lanes(ps, q, qd + i, left, shadow))
            return true;
    }
#else
    (void)ps;
    (void)q;
    (void)qd;
    (void)nq;
    (void)shadow;
#endif
    return false;
}

/* --- batches: a cell's items, MESH_BATCH triangles at a time ------------- */

/* Test the nb (1 to MESH_BATCH) mesh triangles rb[] (corners qb[]), which
 * the mailbox has passed: the sign test of all of them at once
 * (mesh_ray_reject), then the full test of those it cannot reject. The
 * same answers as primset_test() one by one: a lane is rejected only
 * where mesh_ray_intersect() returns false at that very test, with the
 * same bits (mesh.h), and the nearest-hit rule does not depend on the
 * order. Returns true when a shadow query found a hit. */
static bool test_batch(const primset_t *ps, primset_query_t *q,
                       const real *qb[MESH_BATCH], const uint32_t *rb,
                       int nb, bool shadow)
{
    if (nb == 1)
        return primset_test_tri(ps, q, rb[0]) && shadow;
    for (int j = nb; j < MESH_BATCH; j++)
        qb[j] = qb[0]; /* padding: its answer is not read */
    unsigned left = ~mesh_ray_reject(qb, &q->mr) & ((1u << nb) - 1);
    for (int j = 0; left; j++, left >>= 1)
        if ((left & 1) && primset_test_tri(ps, q, rb[j]) && shadow)
            return true;
    return false;
}

/* Batches pay with 4 lanes a vector (float with SSE2); with 2 (double)
 * they cost more than one triangle at a time, and plain lanes could only
 * add work to the scalar test. Elsewhere every triangle goes through
 * primset_test(). */
#if defined(SIMD_REAL) && VLANES >= 4
#define GRID_BATCHES 1
#else
#define GRID_BATCHES 0
#endif

/* Test the n items of a cell: mesh triangles MESH_BATCH at a time (where
 * GRID_BATCHES; those in the grid's quads are left to test_quads()),
 * other primitives one by one, child grids (listed last) walked. Returns
 * true when a shadow query found a hit. */
bool grid_test_items(const grid_t *g, const walk_t *w, primset_query_t *q,
                     const uint32_t *items, uint32_t n, bool shadow)
{
    const primset_t *ps = g->ps;
    const real *qb[MESH_BATCH];
    uint32_t rb[MESH_BATCH];
    int nb = 0;
    for (uint32_t k = 0; k < n; k++) {
        uint32_t it = items[k];
        if (it & GRID_CHILD) {
            if (nb && test_batch(ps, q, qb, rb, nb, shadow))
                return true;
            nb = 0;
            const grid_node_t *ch = &g->nodes[it & ~GRID_CHILD];
            double c0, c1;
            if (slab(w, ch->min, ch->max, w->t0, w->t1, &c0, &c1) &&
                grid_walk_node(g, it & ~GRID_CHILD, w, q, c0, c1, shadow))
                return true;
        } else if (GRID_BATCHES && it < ps->ntri) {
            if (in_quads(g, it) || primset_seen(q, it))
                continue;
            qb[nb] = ps->tri[it];
            rb[nb++] = it;
            if (nb == MESH_BATCH) {
                if (test_batch(ps, q, qb, rb, nb, shadow))
                    return true;
                nb = 0;
            }
        } else if (primset_test(ps, q, it) && shadow) {
            return true;
        }
    }
    return nb && test_batch(ps, q, qb, rb, nb, shadow);
}

GRID_NOINLINE bool grid_test_full(const grid_t *g, const walk_t *w,
                                  primset_query_t *q, uint32_t f, bool shadow)
{
    if (GRID_QUADS && g->quads) {
        uint32_t a = g->qstart[f], b = g->qstart[f + 1] & ~GRID_MORE;
        if (test_quads(g->ps, w, q, g->quads + (a & ~GRID_MORE),
                       b - (a & ~GRID_MORE), shadow))
            return true;
        if (!(a & GRID_MORE))
            return false;
    }
    return grid_test_items(g, w, q, g->items + g->cstart[f],
                     g->cstart[f + 1] - g->cstart[f], shadow);
}
