/*
 * grid_build.c - ch. 7: building the uniform grid and the hierarchical
 * grid (grid.h describes the data; grid.c walks it).
 *   cells: about k^3 N cells over the scene's box, as cubic as its aspect
 *          allows; every primitive goes into each cell its padded bounds
 *          overlap, a triangle only into the cells it truly overlaps (the
 *          separating-axis test of Akenine-Moller, "Fast 3D triangle-box
 *          overlap testing", JGT 6(1), 2001); one pass lists the (cell,
 *          primitive) pairs, a counting sort lays them out;
 *   hierarchy (Jevans & Wyvill, "Adaptive voxel subdivision for ray
 *          tracing", Graphics Interface 1989): a cell with more than
 *          leaf_max primitives gets a child grid over the part of the
 *          cell its primitives occupy, recursively, bounded by depth and
 *          by a memory budget;
 *   storage: every level's cells in flat arrays, in blocks of 4^3 cells
 *          with a 64-bit word of which cells hold something, only the
 *          non-empty cells numbered (grid.h); where the fast walk has
 *          quads, grid_make_quads() (fast/grid_walk.c) adds them.
 * Tests: tests/accel/test_grid.c
 */
/* madvise()'s MADV_HUGEPAGE (Linux) is outside POSIX: grid_alloc() */
#define _DEFAULT_SOURCE
#include "grid_walk.h"

#include <stdlib.h>
#include <string.h>
#ifdef __linux__
#include <sys/mman.h>
#endif

void grid_params_uniform(grid_params_t *p)
{
    p->k = GRID_K_DEFAULT;
    p->quad_min = GRID_QUAD_MIN_DEFAULT;
    p->max_depth = 0;
    p->leaf_max = HGRID_LEAF_DEFAULT;
    p->child_k = HGRID_CHILD_K_DEFAULT;
}

void grid_params_hierarchical(grid_params_t *p)
{
    p->k = HGRID_K_DEFAULT;
    p->quad_min = GRID_QUAD_MIN_DEFAULT;
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
        nd->nb[a] = (res[a] + GRID_BLOCK - 1) / GRID_BLOCK;
    }
    nd->first = 0;
    nd->bfirst = 0;
    nd->depth = depth;
}

static long node_cells(const grid_node_t *nd)
{
    return (long)nd->res[0] * nd->res[1] * nd->res[2];
}

/* --- triangle / box overlap -------------------------------------------- */

/* min and max of finite doubles, without libm's NaN-aware calls */
static double dmin(double a, double b)
{
    return a < b ? a : b;
}

static double dmax(double a, double b)
{
    return a > b ? a : b;
}

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
    /* the normal first: it separates most cells from a triangle that
     * crosses their bounds' corner */
    s->axis[0][0] = e[0][1] * e[1][2] - e[0][2] * e[1][1];
    s->axis[0][1] = e[0][2] * e[1][0] - e[0][0] * e[1][2];
    s->axis[0][2] = e[0][0] * e[1][1] - e[0][1] * e[1][0];
    int k = 1;
    for (int i = 0; i < 3; i++) {
        const double *f = e[i];
        double ax[3][3] = { { 0, f[2], -f[1] },   /* f x (1,0,0) */
                            { -f[2], 0, f[0] },   /* f x (0,1,0) */
                            { f[1], -f[0], 0 } }; /* f x (0,0,1) */
        for (int j = 0; j < 3; j++, k++)
            memcpy(s->axis[k], ax[j], sizeof ax[j]);
    }
    for (k = 0; k < 10; k++) {
        const double *n = s->axis[k];
        double p[3];
        for (int i = 0; i < 3; i++)
            p[i] = n[0] * v[i][0] + n[1] * v[i][1] + n[2] * v[i][2];
        s->lo[k] = dmin(p[0], dmin(p[1], p[2]));
        s->hi[k] = dmax(p[0], dmax(p[1], p[2]));
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
    uint64_t max_cells, max_items; /* the hierarchy's budget */
} build_t;

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

/* The (cell, primitive) pairs of a level being filled. */
typedef struct {
    uint32_t (*pair)[2];
    size_t n, cap;
} pairs_t;

static bool add_pair(pairs_t *p, uint32_t cell, uint32_t ref)
{
    if (p->n == p->cap) {
        size_t cap = p->cap ? 2 * p->cap : 1024;
        uint32_t(*q)[2] = realloc(p->pair, cap * sizeof *q);
        if (!q)
            return false;
        p->pair = q;
        p->cap = cap;
    }
    p->pair[p->n][0] = cell;
    p->pair[p->n][1] = ref;
    p->n++;
    return true;
}

/* Append the cells of nd that primitive ref goes into. */
static bool ref_cells(const build_t *B, const grid_node_t *nd, uint32_t ref,
                      pairs_t *out)
{
    int lo[3], hi[3];
    ref_range(B, nd, ref, lo, hi);
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
                long cell = x + nd->res[0] * (y + (long)nd->res[1] * z);
                if (!add_pair(out, (uint32_t)cell, ref))
                    return false;
            }
    return true;
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

/* Fill bn (node set up) with the n primitives refs[] (NULL: 0 .. n-1):
 * one pass lists the (cell, primitive) pairs, a counting sort by cell
 * lays them out (keeping each cell's primitives in list order). Returns
 * false when memory runs out. */
static bool fill_node(const build_t *B, bnode_t *bn, const uint32_t *refs,
                      uint32_t n)
{
    long nc = node_cells(&bn->node);
    bn->start = calloc((size_t)nc + 1, sizeof *bn->start);
    bn->items = NULL;
    pairs_t pr = { NULL, 0, 0 };
    bool ok = bn->start != NULL;
    for (uint32_t i = 0; i < n && ok; i++)
        ok = ref_cells(B, &bn->node, refs ? refs[i] : i, &pr);
    if (ok)
        bn->items = malloc((pr.n ? pr.n : 1) * sizeof *bn->items);
    if (!ok || !bn->items) {
        free(pr.pair);
        return false;
    }
    /* start[c + 1] counts cell c, then becomes its end by prefix sum */
    for (size_t k = 0; k < pr.n; k++)
        bn->start[pr.pair[k][0] + 1]++;
    for (long c = 0; c < nc; c++)
        bn->start[c + 1] += bn->start[c];
    for (size_t k = 0; k < pr.n; k++)
        bn->items[bn->start[pr.pair[k][0]]++] = pr.pair[k][1];
    /* each start[c] now ends cell c: shift back by one cell */
    memmove(bn->start + 1, bn->start, (size_t)nc * sizeof *bn->start);
    bn->start[0] = 0;
    free(pr.pair);
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

/* Try to give cell c of node ni a child grid; parent_n is the number of
 * primitives of the cell that node ni itself refines (none for the top).
 * On success *new_items is the cell's new item list (the primitives kept
 * in it, then the child, whose node is *child and which holds *child_n
 * primitives) or NULL when no child was made: one would not help, or the
 * budget is spent. Returns false only when memory runs out. */
static bool refine_cell(build_t *B, uint32_t ni, long c, uint32_t parent_n,
                        uint32_t **new_items, uint32_t *nnew,
                        uint32_t *child_i, uint32_t *child_n)
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
    int ix[3] = { (int)(c % nd.res[0]), (int)((c / nd.res[0]) % nd.res[1]),
                  (int)(c / ((long)nd.res[0] * nd.res[1])) };
    double lo[3], hi[3], ulo[3], uhi[3];
    for (int a = 0; a < 3; a++) {
        lo[a] = nd.min[a] + ix[a] * nd.w[a] - B->pad;
        hi[a] = nd.min[a] + (ix[a] + 1) * nd.w[a] + B->pad;
        ulo[a] = (double)INFINITY;
        uhi[a] = -(double)INFINITY;
    }
    uint32_t *keep = malloc(((size_t)n + 1) * sizeof *keep);
    uint32_t *down = malloc(((size_t)n + 1) * sizeof *down);
    if (!keep || !down) {
        free(keep);
        free(down);
        return false;
    }
    /* A primitive as large as the cell across two axes (the ground under
     * the teapot, a wall) stays in this cell: it would go into most of
     * the child's cells, and it must not stretch the child over the whole
     * cell. The child spans the part of the cell that the others occupy:
     * a teapot in one corner of a stadium's cell gets all its cells. */
    uint32_t nkeep = 0, ndown = 0;
    for (uint32_t i = 0; i < n; i++) {
        const bbox_t *b = &B->ps->bounds[its[i]];
        int across = 0;
        for (int a = 0; a < 3; a++)
            across += (double)b->min[a] - B->pad <= lo[a] &&
                      (double)b->max[a] + B->pad >= hi[a];
        if (across >= 2) {
            keep[nkeep++] = its[i];
            continue;
        }
        down[ndown++] = its[i];
        for (int a = 0; a < 3; a++) {
            ulo[a] = dmin(ulo[a], (double)b->min[a] - B->pad);
            uhi[a] = dmax(uhi[a], (double)b->max[a] + B->pad);
        }
    }
    double ext[3];
    for (int a = 0; a < 3; a++) {
        lo[a] = dmax(lo[a], ulo[a]);
        hi[a] = dmin(hi[a], uhi[a]);
        ext[a] = hi[a] - lo[a];
    }
    /* Budget: the child's cells and items must fit what is left; a
     * coarser child fits where a fine one does not, and a coarse child
     * is far better than none (a cell of hundreds of primitives). */
    int res[3] = { 1, 1, 1 };
    bnode_t child;
    long nc = 1;
    bool fits = false;
    bool thick = ext[0] > 0 && ext[1] > 0 && ext[2] > 0;
    for (double k = B->p->child_k; thick && ndown > (uint32_t)B->p->leaf_max;
         k *= 0.7) {
        choose_res(ext, k, ndown, res);
        node_init(&child.node, lo, hi, res, nd.depth + 1);
        nc = node_cells(&child.node);
        if (nc <= 1)
            break;
        double work = span_sum(B, &child.node, down, ndown);
        if (B->total_cells + (uint64_t)nc <= B->max_cells &&
            (double)B->total_items + work <= (double)B->max_items) {
            fits = true;
            break;
        }
    }
    if (!fits) {
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
    long nonempty = 0;
    for (long k = 0; k < nc; k++)
        nonempty += child.start[k + 1] > child.start[k];
    double avg = nonempty ? (double)child.start[nc] / nonempty : 0;
    uint32_t ci;
    if (avg > 0.75 * ndown) {
        free(keep);
        free_bnode(&child);
        return true;
    }
    if (!push_node(B, &child, &ci)) {
        free(keep);
        free_bnode(&child);
        return false;
    }
    keep[nkeep++] = GRID_CHILD | ci;
    *new_items = keep;
    *nnew = nkeep;
    *child_i = ci;
    *child_n = ndown;
    return true;
}

/* Keys (~count << 32 | cell) sort the most crowded cells first. */
static int by_key(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

/* Refine the crowded cells of node ni, the most crowded first (so that a
 * budget running short leaves the least crowded unrefined), rewrite its
 * items with the refined cells' new lists, and only then refine the new
 * children: every level is made before the next, so no cell's
 * grandchildren take the budget its siblings need. */
static bool refine(build_t *B, uint32_t ni, uint32_t parent_n)
{
    long nc = node_cells(&B->nodes[ni].node);
    uint32_t **repl = calloc((size_t)nc, sizeof *repl);
    uint32_t *nrepl = calloc((size_t)nc, sizeof *nrepl);
    uint64_t *order = malloc((size_t)nc * sizeof *order);
    uint32_t *kids = malloc((size_t)nc * 2 * sizeof *kids);
    if (!repl || !nrepl || !order || !kids) {
        free(repl);
        free(nrepl);
        free(order);
        free(kids);
        return false;
    }
    long ncand = 0, nkids = 0;
    const uint32_t *st = B->nodes[ni].start;
    for (long c = 0; c < nc; c++) {
        uint32_t n = st[c + 1] - st[c];
        if (n > (uint32_t)B->p->leaf_max)
            order[ncand++] = (uint64_t)(UINT32_MAX - n) << 32 | (uint64_t)c;
    }
    qsort(order, (size_t)ncand, sizeof *order, by_key);
    bool ok = true, any = false;
    for (long i = 0; i < ncand && ok; i++) {
        uint32_t c = (uint32_t)(order[i] & UINT32_MAX);
        ok = refine_cell(B, ni, c, parent_n, &repl[c], &nrepl[c],
                         &kids[2 * nkids], &kids[2 * nkids + 1]);
        if (ok && repl[c]) {
            any = true;
            nkids++;
        }
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
    free(order);
    for (long i = 0; i < nkids && ok; i++)
        ok = refine(B, kids[2 * i], kids[2 * i + 1]);
    free(kids);
    return ok;
}

/* --- flattening and statistics -------------------------------------------- */

static long node_blocks(const grid_node_t *nd)
{
    return (long)nd->nb[0] * nd->nb[1] * nd->nb[2];
}

/* 64-byte aligned, so that a quad's vectors never straddle more cache
 * lines than they must; where Linux offers transparent huge pages and the
 * array spans several, aligned to 2 MiB and advised to use them, so that
 * the walks' loads miss the TLB less on large scenes. The advice changes
 * no byte and may be ignored. */
void *grid_alloc(size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    const size_t huge = (size_t)2 << 20;
    if (bytes >= 4 * huge) {
        size_t n = (bytes + huge - 1) / huge * huge;
        void *p = aligned_alloc(huge, n);
        if (p)
            (void)madvise(p, n, MADV_HUGEPAGE);
        return p;
    }
#endif
    return aligned_alloc(64, (bytes + 63) / 64 * 64);
}

static svet_status flatten(build_t *B, grid_t *g, long quad_min,
                           svet_error *err)
{
    uint64_t cells = 0, items = 0, blocks = 0, full = 0;
    for (uint32_t i = 0; i < B->nnodes; i++) {
        const bnode_t *bn = &B->nodes[i];
        long nc = node_cells(&bn->node);
        cells += (uint64_t)nc;
        items += bn->start[nc];
        blocks += (uint64_t)node_blocks(&bn->node);
        for (long c = 0; c < nc; c++)
            full += bn->start[c + 1] > bn->start[c];
    }
    if (cells + 1 > UINT32_MAX || items > GRID_CHILD - 1 ||
        blocks > UINT32_MAX)
        return svet_error_set(err, SVET_ERR_NOMEM,
                              "grid: %llu cells, %llu items: too many",
                              (unsigned long long)cells,
                              (unsigned long long)items);
    g->nodes = malloc(B->nnodes * sizeof *g->nodes);
    const size_t nb = (size_t)(blocks ? blocks : 1);
    g->bmask = grid_alloc(nb * sizeof *g->bmask);
    g->bbase = grid_alloc(nb * sizeof *g->bbase);
    g->cstart = grid_alloc((size_t)(full + 1) * sizeof *g->cstart);
    g->items = grid_alloc((size_t)(items ? items : 1) * sizeof *g->items);
    if (!g->nodes || !g->bmask || !g->bbase || !g->cstart || !g->items)
        return svet_error_set(err, SVET_ERR_NOMEM, "grid: out of memory");
    memset(g->bmask, 0, nb * sizeof *g->bmask);
    memset(g->bbase, 0, nb * sizeof *g->bbase);
    uint32_t c0 = 0, i0 = 0, b0 = 0, s0 = 0;
    g->depth = 0;
    g->max_items = 0;
    g->empty_cells = 0;
    for (uint32_t i = 0; i < B->nnodes; i++) {
        const bnode_t *bn = &B->nodes[i];
        const grid_node_t *nd = &bn->node;
        g->nodes[i] = *nd;
        g->nodes[i].first = c0;
        g->nodes[i].bfirst = b0;
        /* block by block, bit by bit: the order of bbase */
        long nbk = node_blocks(nd);
        for (long k = 0; k < nbk; k++) {
            int bxyz[3] = { (int)(k % nd->nb[0]),
                            (int)(k / nd->nb[0] % nd->nb[1]),
                            (int)(k / ((long)nd->nb[0] * nd->nb[1])) };
            g->bbase[b0 + k] = s0;
            for (int bit = 0; bit < GRID_BLOCK * GRID_BLOCK * GRID_BLOCK;
                 bit++) {
                int x = bxyz[0] * GRID_BLOCK + bit % GRID_BLOCK;
                int y = bxyz[1] * GRID_BLOCK + bit / GRID_BLOCK % GRID_BLOCK;
                int z = bxyz[2] * GRID_BLOCK +
                        bit / (GRID_BLOCK * GRID_BLOCK);
                if (x >= nd->res[0] || y >= nd->res[1] || z >= nd->res[2])
                    continue;
                long c = x + nd->res[0] * (y + (long)nd->res[1] * z);
                uint32_t b = bn->start[c], e = bn->start[c + 1];
                g->empty_cells += b == e;
                if (b == e)
                    continue;
                uint32_t prims = 0;
                for (uint32_t m = b; m < e; m++)
                    prims += !(bn->items[m] & GRID_CHILD);
                g->max_items = prims > g->max_items ? prims : g->max_items;
                g->bmask[b0 + k] |= UINT64_C(1) << bit;
                g->cstart[s0++] = i0;
                memcpy(g->items + i0, bn->items + b, (e - b) * sizeof *g->items);
                i0 += e - b;
            }
        }
        c0 += (uint32_t)node_cells(nd);
        b0 += (uint32_t)nbk;
        if (nd->depth > g->depth)
            g->depth = nd->depth;
    }
    g->cstart[s0] = i0;
    g->nnodes = B->nnodes;
    g->ncells = c0;
    g->nitems = i0;
    g->nblocks = b0;
    g->nfull = s0;
#if GRID_QUADS
    if (g->ps->ntri >= quad_min)
        return grid_make_quads(g, err);
#else
    (void)quad_min;
#endif
    return SVET_OK;
}

void grid_cell_items(const grid_t *g, uint32_t n, long c, uint32_t *begin,
                     uint32_t *end)
{
    const grid_node_t *nd = &g->nodes[n];
    grid_cell_at(g, nd, (int)(c % nd->res[0]),
                 (int)(c / nd->res[0] % nd->res[1]),
                 (int)(c / ((long)nd->res[0] * nd->res[1])), begin, end);
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
    /* The child grids may add four times the cells and entries of the top
     * level, plus 16 per primitive: whatever the scene, a hierarchy costs
     * a bounded multiple of a uniform grid's memory. Past that children
     * get coarser, then none are made (a budget, not an error). */
    B.max_cells = 4 * B.total_cells + 16 * (uint64_t)ps->nbounded + 4096;
    B.max_items = 4 * B.total_items + 16 * (uint64_t)ps->nbounded + 4096;
    if (st == SVET_OK && p->max_depth > 0 && !refine(&B, 0, UINT32_MAX))
        st = svet_error_set(err, SVET_ERR_NOMEM, "grid: out of memory");
    if (st == SVET_OK)
        st = flatten(&B, g, p->quad_min, err);
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
    if (!g || !g->nodes)
        return g ? sizeof *g : 0;
    return sizeof *g + g->nnodes * sizeof *g->nodes +
           (size_t)g->nblocks * (sizeof *g->bmask + sizeof *g->bbase) +
           ((size_t)g->nfull + 1) * sizeof *g->cstart +
           (size_t)g->nitems * sizeof *g->items +
           (g->quads ? (size_t)g->nquads * sizeof *g->quads +
                           ((size_t)g->nfull + 1) * sizeof *g->qstart +
                           ((size_t)g->ps->ntri / 64 + 1) * sizeof *g->qout
                     : 0);
}

void grid_free(grid_t *g)
{
    if (!g)
        return;
    free(g->nodes);
    free(g->items);
    free(g->bmask);
    free(g->bbase);
    free(g->cstart);
    free(g->quads);
    free(g->qstart);
    free(g->qout);
    free(g);
}
