/*
 * grid.c - ch. 7: the uniform grid and the hierarchical grid.
 *   build: primitives go into every cell their padded bounds overlap,
 *          triangles only into the cells they truly overlap (the
 *          separating-axis test of Akenine-Moller, "Fast 3D triangle-box
 *          overlap testing", JGT 6(1), 2001); two passes (count, fill)
 *          into flat arrays;
 *   hierarchy (Jevans & Wyvill 1989): a cell with more than leaf_max
 *          primitives gets a child grid over the part of the cell its
 *          primitives occupy, recursively, bounded by depth and size;
 *   walk:  the 3D-DDA of Amanatides & Woo 1987, in double.
 * Tests: tests/test_grid.c, tests/test_accel.c
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
 * simply goes on until a cell's exit passes it.
 */
#include "grid.h"

#include <stdlib.h>
#include <string.h>

void grid_params_uniform(grid_params_t *p)
{
    p->k = GRID_K_DEFAULT;
    p->max_depth = 0;
    p->leaf_max = HGRID_LEAF_DEFAULT;
    p->child_k = HGRID_CHILD_K_DEFAULT;
}

void grid_params_hierarchical(grid_params_t *p)
{
    p->k = HGRID_K_DEFAULT;
    p->max_depth = HGRID_DEPTH_DEFAULT;
    p->leaf_max = HGRID_LEAF_DEFAULT;
    p->child_k = HGRID_CHILD_K_DEFAULT;
}

/* --- resolution ---------------------------------------------------------- */

/* About k^3 n cells over a box of extents ext, as cubic as the aspect
 * allows: s cells per unit length on every axis, with s^na prod(ext) =
 * k^3 n over the na axes that get more than one cell (an axis shorter than
 * 1/s gets one cell and drops out). In logarithms, so no extent overflows. */
static void choose_res(const double ext[3], double k, double n, int res[3])
{
    double target = k * k * k * (n > 1 ? n : 1);
    if (!(target >= 1))
        target = 1;
    if (target > GRID_MAX_CELLS)
        target = GRID_MAX_CELLS;
    bool active[3];
    for (int a = 0; a < 3; a++) {
        res[a] = 1;
        active[a] = ext[a] > 0;
    }
    for (int iter = 0; iter < 3; iter++) {
        double lsum = 0;
        int na = 0;
        for (int a = 0; a < 3; a++)
            if (active[a]) {
                lsum += log(ext[a]);
                na++;
            }
        if (na == 0)
            return;
        double ls = (log(target) - lsum) / na; /* log of s */
        bool dropped = false;
        for (int a = 0; a < 3; a++)
            if (active[a] && log(ext[a]) + ls < 0) {
                active[a] = false;
                dropped = true;
            }
        if (dropped)
            continue;
        for (int a = 0; a < 3; a++)
            if (active[a]) {
                double r = exp(log(ext[a]) + ls);
                res[a] = r > 65536 ? 65536 : (int)fmax(1.0, round(r));
            }
        break;
    }
    /* rounding up may overshoot the cap: trim the longest axis */
    while ((double)res[0] * res[1] * res[2] > GRID_MAX_CELLS) {
        int a = res[0] >= res[1] ? (res[0] >= res[2] ? 0 : 2)
                                 : (res[1] >= res[2] ? 1 : 2);
        res[a] = res[a] * 3 / 4;
    }
}

static void node_init(grid_node_t *nd, const double min[3],
                      const double max[3], const int res[3], int depth)
{
    for (int a = 0; a < 3; a++) {
        nd->min[a] = min[a];
        nd->res[a] = res[a];
        nd->w[a] = (max[a] - min[a]) / res[a];
        if (!(nd->w[a] > 0))
            nd->w[a] = 1; /* cannot happen with pad > 0; no division by 0 */
        nd->inv_w[a] = 1 / nd->w[a];
        nd->max[a] = max[a];
    }
    nd->first = 0;
    nd->depth = depth;
}

static long node_cells(const grid_node_t *nd)
{
    return (long)nd->res[0] * nd->res[1] * nd->res[2];
}

/* Cell coordinate of x on axis a, clamped into the grid. */
static int cell_of(const grid_node_t *nd, int a, double x)
{
    double c = floor((x - nd->min[a]) * nd->inv_w[a]);
    if (!(c >= 0))
        return 0;
    if (c >= nd->res[a] - 1)
        return nd->res[a] - 1;
    return (int)c;
}

/* --- triangle / box overlap -------------------------------------------- */

/* The separating-axis test of Akenine-Moller 2001 for one triangle
 * against many cells of one size: the triangle's normal and the nine
 * edge x axis directions, each with the interval the triangle projects to
 * and the radius h . |axis| a cell of half-size h projects to, computed
 * once per triangle; a cell is then 10 dot products. (The three box axes
 * need no test: the cells come from the triangle's bounds.) Every vertex
 * is projected, where the paper projects two, so that rounding never
 * separates what touches: the criterion holds for any axis, exact or not,
 * and the cells are padded. */
typedef struct {
    double axis[10][3];
    double lo[10], hi[10], r[10];
} tri_sat_t;

static void tri_sat_init(tri_sat_t *s, const real *q, const double h[3])
{
    double v[3][3], e[3][3];
    for (int i = 0; i < 3; i++)
        for (int a = 0; a < 3; a++)
            v[i][a] = (double)q[3 * i + a];
    for (int a = 0; a < 3; a++) {
        e[0][a] = v[1][a] - v[0][a];
        e[1][a] = v[2][a] - v[1][a];
        e[2][a] = v[0][a] - v[2][a];
    }
    int k = 0;
    for (int i = 0; i < 3; i++) {
        const double *f = e[i];
        double ax[3][3] = { { 0, f[2], -f[1] },   /* f x (1,0,0) */
                            { -f[2], 0, f[0] },   /* f x (0,1,0) */
                            { f[1], -f[0], 0 } }; /* f x (0,0,1) */
        for (int j = 0; j < 3; j++, k++)
            memcpy(s->axis[k], ax[j], sizeof ax[j]);
    }
    s->axis[9][0] = e[0][1] * e[1][2] - e[0][2] * e[1][1];
    s->axis[9][1] = e[0][2] * e[1][0] - e[0][0] * e[1][2];
    s->axis[9][2] = e[0][0] * e[1][1] - e[0][1] * e[1][0];
    for (k = 0; k < 10; k++) {
        const double *n = s->axis[k];
        double p[3];
        for (int i = 0; i < 3; i++)
            p[i] = n[0] * v[i][0] + n[1] * v[i][1] + n[2] * v[i][2];
        s->lo[k] = fmin(p[0], fmin(p[1], p[2]));
        s->hi[k] = fmax(p[0], fmax(p[1], p[2]));
        s->r[k] = h[0] * fabs(n[0]) + h[1] * fabs(n[1]) + h[2] * fabs(n[2]);
    }
}

/* Does the triangle overlap the cell of centre c? */
static bool tri_sat_overlap(const tri_sat_t *s, const double c[3])
{
    for (int k = 0; k < 10; k++) {
        const double *n = s->axis[k];
        double pc = n[0] * c[0] + n[1] * c[1] + n[2] * c[2];
        if (s->lo[k] - pc > s->r[k] || s->hi[k] - pc < -s->r[k])
            return false;
    }
    return true;
}

/* --- building one level --------------------------------------------------- */

/* A grid being built: its node, and its cells' items in its own arrays
 * until flatten() lays every level end to end. */
typedef struct {
    grid_node_t node;
    uint32_t *start; /* ncells + 1 */
    uint32_t *items;
} bnode_t;

typedef struct {
    const primset_t *ps;
    const grid_params_t *p;
    double pad;
    bnode_t *nodes;
    uint32_t nnodes, cap;
    uint64_t total_cells, total_items;
} build_t;

/* Past these the hierarchy stops refining (a budget, not an error). */
#define BUILD_MAX_ITEMS (UINT64_C(1) << 28)
#define BUILD_MAX_TOTAL_CELLS (UINT64_C(1) << 26)

/* The cell range [lo, hi] of primitive ref's padded bounds in nd. */
static void ref_range(const build_t *B, const grid_node_t *nd, uint32_t ref,
                      int lo[3], int hi[3])
{
    const bbox_t *b = &B->ps->bounds[ref];
    for (int a = 0; a < 3; a++) {
        lo[a] = cell_of(nd, a, (double)b->min[a] - B->pad);
        hi[a] = cell_of(nd, a, (double)b->max[a] + B->pad);
    }
}

/* The triangle of ref when it is a mesh triangle, else NULL. */
static const real *ref_triangle(const primset_t *ps, uint32_t ref)
{
    return ref < ps->ntri ? ps->tri[ref] : NULL;
}

/* Visit the cells of nd that primitive ref goes into: fn(ctx, cell). */
typedef void (*cell_fn)(void *ctx, uint32_t cell, uint32_t ref);

static void for_cells(const build_t *B, const grid_node_t *nd, uint32_t ref,
                      const int lo[3], const int hi[3], cell_fn fn,
                      void *ctx)
{
    const real *tri = ref_triangle(B->ps, ref);
    /* A triangle within one row of cells overlaps each of them: only
     * when its bounds span two axes can a cell miss it. */
    int thick = (lo[0] < hi[0]) + (lo[1] < hi[1]) + (lo[2] < hi[2]);
    bool sat = tri && thick >= 2;
    tri_sat_t ts;
    if (sat) {
        double h[3];
        for (int a = 0; a < 3; a++)
            h[a] = 0.5 * nd->w[a] + B->pad;
        tri_sat_init(&ts, tri, h);
    }
    for (int z = lo[2]; z <= hi[2]; z++)
        for (int y = lo[1]; y <= hi[1]; y++)
            for (int x = lo[0]; x <= hi[0]; x++) {
                if (sat) {
                    double c[3] = { nd->min[0] + (x + 0.5) * nd->w[0],
                                    nd->min[1] + (y + 0.5) * nd->w[1],
                                    nd->min[2] + (z + 0.5) * nd->w[2] };
                    if (!tri_sat_overlap(&ts, c))
                        continue;
                }
                uint32_t cell = (uint32_t)(x + nd->res[0] *
                                           (y + (long)nd->res[1] * z));
                fn(ctx, cell, ref);
            }
}

static void count_fn(void *ctx, uint32_t cell, uint32_t ref)
{
    (void)ref;
    ((uint32_t *)ctx)[cell]++;
}

typedef struct {
    uint32_t *fill; /* next free slot per cell */
    uint32_t *items;
} fill_ctx;

static void fill_fn(void *ctx, uint32_t cell, uint32_t ref)
{
    fill_ctx *f = ctx;
    f->items[f->fill[cell]++] = ref;
}

/* Sum over refs of the cells their bounds span: the work (and the most
 * items) of filling nd with them. */
static double span_sum(const build_t *B, const grid_node_t *nd,
                       const uint32_t *refs, uint32_t n)
{
    double s = 0;
    for (uint32_t i = 0; i < n; i++) {
        int lo[3], hi[3];
        ref_range(B, nd, refs ? refs[i] : i, lo, hi);
        s += (double)(hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) *
             (hi[2] - lo[2] + 1);
    }
    return s;
}

/* Fill bn (node set up) with the n primitives refs[] (NULL: 0 .. n-1).
 * Returns false when memory runs out. */
static bool fill_node(const build_t *B, bnode_t *bn, const uint32_t *refs,
                      uint32_t n)
{
    long nc = node_cells(&bn->node);
    bn->start = calloc((size_t)nc + 1, sizeof *bn->start);
    bn->items = NULL;
    uint32_t *count = calloc((size_t)nc + 1, sizeof *count);
    if (!bn->start || !count) {
        free(count);
        return false;
    }
    for (uint32_t i = 0; i < n; i++) {
        uint32_t ref = refs ? refs[i] : i;
        int lo[3], hi[3];
        ref_range(B, &bn->node, ref, lo, hi);
        for_cells(B, &bn->node, ref, lo, hi, count_fn, count);
    }
    uint64_t total = 0;
    for (long c = 0; c < nc; c++) {
        bn->start[c] = (uint32_t)total;
        total += count[c];
    }
    bn->start[nc] = (uint32_t)total;
    bn->items = malloc((size_t)(total ? total : 1) * sizeof *bn->items);
    if (!bn->items) {
        free(count);
        return false;
    }
    fill_ctx f = { count, bn->items };
    memcpy(count, bn->start, (size_t)nc * sizeof *count);
    for (uint32_t i = 0; i < n; i++) {
        uint32_t ref = refs ? refs[i] : i;
        int lo[3], hi[3];
        ref_range(B, &bn->node, ref, lo, hi);
        for_cells(B, &bn->node, ref, lo, hi, fill_fn, &f);
    }
    free(count);
    return true;
}

static bool push_node(build_t *B, const bnode_t *bn, uint32_t *index)
{
    if (B->nnodes == B->cap) {
        uint32_t cap = B->cap ? 2 * B->cap : 16;
        bnode_t *p = realloc(B->nodes, cap * sizeof *p);
        if (!p)
            return false;
        B->nodes = p;
        B->cap = cap;
    }
    *index = B->nnodes;
    B->nodes[B->nnodes++] = *bn;
    B->total_cells += (uint64_t)node_cells(&bn->node);
    B->total_items += bn->start[node_cells(&bn->node)];
    return true;
}

static void free_bnode(bnode_t *bn)
{
    free(bn->start);
    free(bn->items);
    bn->start = bn->items = NULL;
}

/* --- the hierarchy (Jevans & Wyvill 1989) --------------------------------- */

static bool refine(build_t *B, uint32_t ni, uint32_t parent_n);

/* Try to give cell c of node ni a child grid; parent_n is the number of
 * primitives of the cell that node ni itself refines (none for the top).
 * On success *new_items is the cell's new item list (the primitives kept
 * in it, then the child) or NULL when no child was made: one would not
 * help, or the budget is spent. Returns false only when memory runs out. */
static bool refine_cell(build_t *B, uint32_t ni, long c, uint32_t parent_n,
                        uint32_t **new_items, uint32_t *nnew)
{
    grid_node_t nd = B->nodes[ni].node; /* copy: B->nodes may move */
    const uint32_t *its = B->nodes[ni].items + B->nodes[ni].start[c];
    uint32_t n = B->nodes[ni].start[c + 1] - B->nodes[ni].start[c];
    *new_items = NULL;
    *nnew = 0;
    /* A cell holding the whole set its parent cell held would only repeat
     * it (primitives all meeting at one point, like a UV sphere's pole). */
    if (n <= (uint32_t)B->p->leaf_max || n >= parent_n ||
        nd.depth >= B->p->max_depth)
        return true;
    /* The child spans the part of the (padded) cell that its primitives'
     * padded bounds occupy: a teapot in one corner of a stadium's cell
     * gets all the child's cells. */
    int x = (int)(c % nd.res[0]), y = (int)((c / nd.res[0]) % nd.res[1]);
    int z = (int)(c / ((long)nd.res[0] * nd.res[1]));
    int ix[3] = { x, y, z };
    double lo[3], hi[3], ulo[3], uhi[3];
    for (int a = 0; a < 3; a++) {
        lo[a] = nd.min[a] + ix[a] * nd.w[a] - B->pad;
        hi[a] = nd.min[a] + (ix[a] + 1) * nd.w[a] + B->pad;
        ulo[a] = (double)INFINITY;
        uhi[a] = -(double)INFINITY;
    }
    for (uint32_t i = 0; i < n; i++) {
        const bbox_t *b = &B->ps->bounds[its[i]];
        for (int a = 0; a < 3; a++) {
            ulo[a] = fmin(ulo[a], (double)b->min[a] - B->pad);
            uhi[a] = fmax(uhi[a], (double)b->max[a] + B->pad);
        }
    }
    double ext[3];
    for (int a = 0; a < 3; a++) {
        lo[a] = fmax(lo[a], ulo[a]);
        hi[a] = fmin(hi[a], uhi[a]);
        ext[a] = hi[a] - lo[a];
        if (!(ext[a] > 0))
            return true;
    }
    int res[3];
    choose_res(ext, B->p->child_k, n, res);
    if ((long)res[0] * res[1] * res[2] <= 1)
        return true;
    bnode_t child;
    node_init(&child.node, lo, hi, res, nd.depth + 1);
    uint32_t *keep = malloc((size_t)n * sizeof *keep);
    uint32_t *down = malloc((size_t)n * sizeof *down);
    if (!keep || !down) {
        free(keep);
        free(down);
        return false;
    }
    /* A primitive spanning every cell of the child stays in the parent's
     * cell: copying it into all of them would only cost memory. */
    uint32_t nkeep = 0, ndown = 0;
    double work = 0;
    for (uint32_t i = 0; i < n; i++) {
        int l[3], h[3];
        ref_range(B, &child.node, its[i], l, h);
        double cells = (double)(h[0] - l[0] + 1) * (h[1] - l[1] + 1) *
                       (h[2] - l[2] + 1);
        if (cells >= (double)node_cells(&child.node) && n > 1) {
            keep[nkeep++] = its[i];
        } else {
            down[ndown++] = its[i];
            work += cells;
        }
    }
    /* Budget: the child's cells and items must fit what is left. */
    if (ndown <= 1 ||
        B->total_cells + (uint64_t)node_cells(&child.node) >
            BUILD_MAX_TOTAL_CELLS ||
        (double)B->total_items + work > (double)BUILD_MAX_ITEMS) {
        free(keep);
        free(down);
        return true;
    }
    if (!fill_node(B, &child, down, ndown)) {
        free(keep);
        free(down);
        free_bnode(&child);
        return false;
    }
    free(down);
    /* Does it separate anything? If the average non-empty child cell
     * still holds most of the primitives, the child is wasted. */
    long nc = node_cells(&child.node), nonempty = 0;
    for (long k = 0; k < nc; k++)
        nonempty += child.start[k + 1] > child.start[k];
    double avg = nonempty ? (double)child.start[nc] / nonempty : 0;
    if (avg > 0.75 * ndown) {
        free(keep);
        free_bnode(&child);
        return true;
    }
    uint32_t ci;
    if (!push_node(B, &child, &ci)) {
        free(keep);
        free_bnode(&child);
        return false;
    }
    keep[nkeep++] = GRID_CHILD | ci;
    *new_items = keep;
    *nnew = nkeep;
    return refine(B, ci, ndown);
}

/* Refine every cell of node ni, depth first, then rewrite its items with
 * the refined cells' new lists. */
static bool refine(build_t *B, uint32_t ni, uint32_t parent_n)
{
    long nc = node_cells(&B->nodes[ni].node);
    uint32_t **repl = calloc((size_t)nc, sizeof *repl);
    uint32_t *nrepl = calloc((size_t)nc, sizeof *nrepl);
    if (!repl || !nrepl) {
        free(repl);
        free(nrepl);
        return false;
    }
    bool ok = true, any = false;
    for (long c = 0; c < nc && ok; c++) {
        ok = refine_cell(B, ni, c, parent_n, &repl[c], &nrepl[c]);
        any |= repl[c] != NULL;
    }
    if (ok && any) {
        /* Rewrite the node's items with the refined cells replaced. */
        bnode_t *bn = &B->nodes[ni];
        uint64_t total = 0;
        for (long c = 0; c < nc; c++)
            total += repl[c] ? nrepl[c] : bn->start[c + 1] - bn->start[c];
        uint32_t *items = malloc((size_t)(total ? total : 1) * sizeof *items);
        uint32_t *start = malloc((size_t)(nc + 1) * sizeof *start);
        if (!items || !start) {
            free(items);
            free(start);
            ok = false;
        } else {
            uint32_t k = 0;
            for (long c = 0; c < nc; c++) {
                start[c] = k;
                if (repl[c]) {
                    memcpy(items + k, repl[c], nrepl[c] * sizeof *items);
                    k += nrepl[c];
                } else {
                    uint32_t m = bn->start[c + 1] - bn->start[c];
                    memcpy(items + k, bn->items + bn->start[c],
                           m * sizeof *items);
                    k += m;
                }
            }
            start[nc] = k;
            B->total_items -= bn->start[nc];
            B->total_items += k;
            free(bn->items);
            free(bn->start);
            bn->items = items;
            bn->start = start;
        }
    }
    for (long c = 0; c < nc; c++)
        free(repl[c]);
    free(repl);
    free(nrepl);
    return ok;
}

/* --- flattening and statistics -------------------------------------------- */

static svet_status flatten(build_t *B, grid_t *g, svet_error *err)
{
    uint64_t cells = 0, items = 0;
    for (uint32_t i = 0; i < B->nnodes; i++) {
        long nc = node_cells(&B->nodes[i].node);
        cells += (uint64_t)nc;
        items += B->nodes[i].start[nc];
    }
    if (cells + 1 > UINT32_MAX || items > GRID_CHILD - 1)
        return svet_error_set(err, SVET_ERR_NOMEM,
                              "grid: %llu cells, %llu items: too many",
                              (unsigned long long)cells,
                              (unsigned long long)items);
    g->nodes = malloc(B->nnodes * sizeof *g->nodes);
    g->cells = malloc((size_t)(cells + 1) * sizeof *g->cells);
    g->items = malloc((size_t)(items ? items : 1) * sizeof *g->items);
    g->occupied = calloc((size_t)(cells / 64 + 1), sizeof *g->occupied);
    if (!g->nodes || !g->cells || !g->items || !g->occupied)
        return svet_error_set(err, SVET_ERR_NOMEM, "grid: out of memory");
    uint32_t c0 = 0, i0 = 0;
    g->depth = 0;
    g->max_items = 0;
    g->empty_cells = 0;
    for (uint32_t i = 0; i < B->nnodes; i++) {
        bnode_t *bn = &B->nodes[i];
        long nc = node_cells(&bn->node);
        g->nodes[i] = bn->node;
        g->nodes[i].first = c0;
        for (long c = 0; c < nc; c++) {
            uint32_t b = bn->start[c], e = bn->start[c + 1];
            g->cells[c0 + c] = i0 + b;
            uint32_t prims = 0;
            for (uint32_t k = b; k < e; k++)
                prims += !(bn->items[k] & GRID_CHILD);
            g->max_items = prims > g->max_items ? prims : g->max_items;
            g->empty_cells += b == e;
            if (b != e)
                g->occupied[(c0 + c) >> 6] |= UINT64_C(1) << ((c0 + c) & 63);
        }
        memcpy(g->items + i0, bn->items,
               bn->start[nc] * sizeof *g->items);
        c0 += (uint32_t)nc;
        i0 += bn->start[nc];
        if (bn->node.depth > g->depth)
            g->depth = bn->node.depth;
    }
    g->cells[c0] = i0;
    g->nnodes = B->nnodes;
    g->ncells = c0;
    g->nitems = i0;
    return SVET_OK;
}

svet_status grid_build(grid_t **out, const primset_t *ps,
                       const grid_params_t *p, svet_error *err)
{
    *out = NULL;
    grid_t *g = calloc(1, sizeof *g);
    if (!g)
        return svet_error_set(err, SVET_ERR_NOMEM, "grid: out of memory");
    g->ps = ps;
    build_t B;
    memset(&B, 0, sizeof B);
    B.ps = ps;
    B.p = p;
    B.pad = ps->pad;
    double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 }, ext[3];
    if (ps->nbounded > 0)
        for (int a = 0; a < 3; a++) {
            lo[a] = (double)ps->box.min[a] - B.pad;
            hi[a] = (double)ps->box.max[a] + B.pad;
        }
    for (int a = 0; a < 3; a++)
        ext[a] = hi[a] - lo[a];
    g->diag = sqrt(ext[0] * ext[0] + ext[1] * ext[1] + ext[2] * ext[2]);
    if (!isfinite(g->diag) || !isfinite(B.pad)) {
        free(g);
        return svet_error_set(err, SVET_ERR_UNSUPPORTED,
                              "grid: the scene's extent overflows a double");
    }
    svet_status st = SVET_OK;
    bnode_t top;
    memset(&top, 0, sizeof top);
    int res[3];
    double k = p->k > 0 ? p->k : GRID_K_DEFAULT;
    /* A primitive larger than the cells goes into many of them: when the
     * bounds span more than GRID_SPAN_MAX cell slots in all, coarsen (the
     * build could otherwise take without end). */
    for (;;) {
        choose_res(ext, k, ps->nbounded, res);
        node_init(&top.node, lo, hi, res, 0);
        if (span_sum(&B, &top.node, NULL, ps->nbounded) <=
                GRID_SPAN_MAX(ps->nbounded) ||
            node_cells(&top.node) <= 1)
            break;
        k *= 0.7;
    }
    uint32_t ti;
    if (!fill_node(&B, &top, NULL, ps->nbounded) || !push_node(&B, &top, &ti))
        st = svet_error_set(err, SVET_ERR_NOMEM, "grid: out of memory");
    if (st == SVET_OK && p->max_depth > 0 && !refine(&B, 0, UINT32_MAX))
        st = svet_error_set(err, SVET_ERR_NOMEM, "grid: out of memory");
    if (st == SVET_OK)
        st = flatten(&B, g, err);
    if (B.nnodes == 0)
        free_bnode(&top);
    for (uint32_t i = 0; i < B.nnodes; i++)
        free_bnode(&B.nodes[i]);
    free(B.nodes);
    if (st != SVET_OK) {
        grid_free(g);
        return st;
    }
    *out = g;
    return SVET_OK;
}

size_t grid_bytes(const grid_t *g)
{
    if (!g)
        return 0;
    return sizeof *g + g->nnodes * sizeof *g->nodes +
           ((size_t)g->ncells + 1) * sizeof *g->cells +
           (size_t)g->nitems * sizeof *g->items +
           ((size_t)g->ncells / 64 + 1) * sizeof *g->occupied;
}

void grid_free(grid_t *g)
{
    if (!g)
        return;
    free(g->nodes);
    free(g->cells);
    free(g->items);
    free(g->occupied);
    free(g);
}

/* --- the walk (Amanatides & Woo 1987) ------------------------------------- */

/* The ray in double, and the walk's margins (see the top of the file). */
typedef struct {
    double o[3], d[3], inv_d[3];
    double t0, t1;           /* the query interval widened by the slack */
    double stop_scale;       /* stop when best t < t_exit stop_scale - */
    double stop_bias;        /* stop_bias */
} walk_t;

/* The part [*t0, *t1] of [lo, hi] (ray interval) inside the box. */
static bool slab(const walk_t *w, const double min[3], const double max[3],
                 double lo, double hi, double *t0, double *t1)
{
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

static void walk_init(walk_t *w, const grid_t *g, const primset_query_t *q)
{
    const ray_t *r = q->r;
    double len2 = 0;
    for (int a = 0; a < 3; a++) {
        w->o[a] = (double)r->o[a];
        w->d[a] = (double)r->d[a];
        w->inv_d[a] = 1 / w->d[a];
        len2 += w->d[a] * w->d[a];
    }
    const double s = 256 * (double)REAL_UNIT_ROUNDOFF;
    double bias = s * g->diag / sqrt(len2);
    w->stop_scale = 1 - s;
    w->stop_bias = bias;
    double tmin = (double)q->tmin, tmax = (double)q->tmax;
    w->t0 = tmin - s * fabs(tmin) - bias;
    w->t1 = tmax + s * fabs(tmax) + bias;
}

/* Walk node ni over [t0, t1] (inside its box). Returns true when a
 * shadow query found a hit.
 *
 * The 3D-DDA of Amanatides & Woo 1987: tn[a] is the t at which the ray
 * crosses the next cell boundary on axis a, dt[a] the t between two
 * boundaries; each step goes to the nearest crossing. tn grows by adding
 * dt, in double: after n steps its rounding error is below n 2^-53 of t,
 * far inside the cells' padding (2^-20 of the scene) for any grid of at
 * most 2^16 cells a side. The axis of the nearest crossing comes from the
 * three comparisons through a table (their paper's trick: no branches to
 * mispredict on random directions). */
static bool walk(const grid_t *g, uint32_t ni, const walk_t *w,
                 primset_query_t *q, double t0, double t1, bool shadow)
{
    /* cmp bits (tn0 < tn1, tn0 < tn2, tn1 < tn2) -> the smallest tn;
     * 2 and 5 cannot happen */
    static const int8_t axis_of[8] = { 2, 1, 2, 1, 2, 2, 0, 0 };
    const grid_node_t *nd = &g->nodes[ni];
    const primset_t *ps = g->ps;
    const uint32_t *cells = g->cells, *items = g->items;
    const uint64_t *occ = g->occupied;
    int ix[3], stop[3];
    long delta[3];
    long stride[3] = { 1, nd->res[0], (long)nd->res[0] * nd->res[1] };
    double tn[3], dt[3];
    long cell = nd->first;
    for (int a = 0; a < 3; a++) {
        ix[a] = cell_of(nd, a, w->o[a] + t0 * w->d[a]);
        cell += ix[a] * stride[a];
        if (w->d[a] > 0) {
            stop[a] = nd->res[a];
            delta[a] = stride[a];
            tn[a] = (nd->min[a] + (ix[a] + 1) * nd->w[a] - w->o[a]) *
                    w->inv_d[a];
            dt[a] = nd->w[a] * w->inv_d[a];
        } else if (w->d[a] < 0) {
            stop[a] = -1;
            delta[a] = -stride[a];
            tn[a] = (nd->min[a] + ix[a] * nd->w[a] - w->o[a]) * w->inv_d[a];
            dt[a] = -nd->w[a] * w->inv_d[a];
        } else {
            stop[a] = -2; /* never reached: this axis never steps */
            delta[a] = 0;
            tn[a] = (double)INFINITY;
            dt[a] = 0;
        }
    }
    for (;;) {
        q->cells++;
        if (occ[cell >> 6] >> (cell & 63) & 1) {
            for (uint32_t k = cells[cell], e = cells[cell + 1]; k < e; k++) {
                uint32_t it = items[k];
                if (it & GRID_CHILD) {
                    const grid_node_t *ch = &g->nodes[it & ~GRID_CHILD];
                    double c0, c1;
                    if (slab(w, ch->min, ch->max, w->t0, w->t1, &c0, &c1) &&
                        walk(g, it & ~GRID_CHILD, w, q, c0, c1, shadow))
                        return true;
                } else if (primset_test(ps, q, it) && shadow) {
                    return true;
                }
            }
        }
        int a = axis_of[((tn[0] < tn[1]) << 2) | ((tn[0] < tn[2]) << 1) |
                        (tn[1] < tn[2])];
        double texit = tn[a];
        /* the nearest hit lies before this cell's exit, with margin */
        if (q->found && (double)q->tmax < texit * w->stop_scale - w->stop_bias)
            return false;
        if (!(texit <= t1) || isinf(texit))
            return false;
        ix[a] += delta[a] > 0 ? 1 : -1;
        if (ix[a] == stop[a])
            return false;
        cell += delta[a];
        tn[a] += dt[a];
    }
}

static bool query(const grid_t *g, primset_query_t *q, bool shadow)
{
    if (g->ncells == 0 || g->ps->nbounded == 0)
        return q->found;
    walk_t w;
    walk_init(&w, g, q);
    const grid_node_t *top = &g->nodes[0];
    double t0, t1;
    if (!(w.t0 <= w.t1) ||
        !slab(&w, top->min, top->max, w.t0, w.t1, &t0, &t1))
        return q->found;
    bool hit = walk(g, 0, &w, q, t0, t1, shadow);
    return shadow ? hit : q->found;
}

bool grid_intersect(const grid_t *g, primset_query_t *q)
{
    return query(g, q, false);
}

bool grid_occluded(const grid_t *g, primset_query_t *q)
{
    return query(g, q, true);
}
