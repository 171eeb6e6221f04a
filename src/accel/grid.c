/*
 * grid.c - ch. 7: the uniform grid and the hierarchical grid.
 *   build: primitives go into every cell their padded bounds overlap,
 *          triangles only into the cells they truly overlap (the
 *          separating-axis test of Akenine-Moller, "Fast 3D triangle-box
 *          overlap testing", JGT 6(1), 2001); one pass lists the
 *          (cell, primitive) pairs, a counting sort lays them out; then
 *          flat arrays: blocks of 4^3 cells with a 64-bit word of which
 *          cells hold something, and only the non-empty cells numbered;
 *          where the vectors have 4 lanes, each non-empty cell's mesh
 *          triangles copied four side by side (quads, grid.h);
 *   hierarchy (Jevans & Wyvill 1989): a cell with more than leaf_max
 *          primitives gets a child grid over the part of the cell its
 *          primitives occupy, recursively, bounded by depth and size;
 *   walk:  the 3D-DDA of Amanatides & Woo 1987, in double, crossing
 *          an empty block in one step (macro-regions, Devillers 1989);
 *          a cell's quads through the sign test four triangles at a
 *          time (mesh_lanes_reject_soa; with AVX two quads, eight
 *          triangles, at a time: mesh_wide_reject_soa2), the survivors
 *          through the full test; elsewhere (double, no SSE2) one
 *          triangle at a time;
 *   packets: camera rays with one origin walked together, slice by slice
 *          along their major axis (the coherent grid traversal of Wald,
 *          Ize, Kensler, Knoll & Parker, SIGGRAPH 2006), each ray tested
 *          with the single walk's own code: grid_intersect_packet(), the
 *          same answers as grid_intersect() (the argument is above
 *          packet());
 *   tables: both grids as accel.h's accel_ops_t (grid_accels, at the
 *          end), which accel.c calls without naming this file.
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
 * simply goes on until a cell's exit passes it.
 */
/* madvise()'s MADV_HUGEPAGE (Linux) is outside POSIX: grid_alloc() */
#define _DEFAULT_SOURCE
#include "accel/grid.h"
#include "core/bits.h"

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

/* Cell coordinate of x on axis a, clamped into the grid. */
static int cell_of(const grid_node_t *nd, int a, double x)
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

/* The non-empty cell of bit `bit` (set) of a block: base its bbase, mask
 * its bmask. */
static inline uint32_t full_cell(uint32_t base, uint64_t mask, int bit)
{
    return base + (uint32_t)bits_count(mask & ((UINT64_C(1) << bit) - 1));
}

/* Is item it a mesh triangle kept in the grid's quads? */
static inline bool in_quads(const grid_t *g, uint32_t it)
{
    return g->quads && it < g->ps->ntri &&
           !(g->qout[it / 64] >> (it % 64) & 1);
}

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

/* One of the grid's arrays that the walks read, of `bytes`: 64-byte
 * aligned, so that a quad's vectors never straddle more cache lines than
 * they must; where Linux offers transparent huge pages and the array spans
 * several, aligned to 2 MiB and advised to use them, so that the walks'
 * loads miss the TLB less (the 1e6 spheres' quads are 100 MB, their other
 * arrays 30 MB; chapters/ch07/README.md measures it). The advice changes
 * no byte and may be ignored. NULL when out of memory; free() frees it. */
static void *grid_alloc(size_t bytes)
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

static svet_status make_quads(grid_t *g, svet_error *err)
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
    return GRID_QUADS && g->ps->ntri >= quad_min ? make_quads(g, err)
                                                 : SVET_OK;
}

void grid_cell_items(const grid_t *g, uint32_t n, long c, uint32_t *begin,
                     uint32_t *end)
{
    const grid_node_t *nd = &g->nodes[n];
    int x = (int)(c % nd->res[0]), y = (int)(c / nd->res[0] % nd->res[1]);
    int z = (int)(c / ((long)nd->res[0] * nd->res[1]));
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

/* --- the walk (Amanatides & Woo 1987) ------------------------------------- */

/* The per-axis loops of the walk's set-up unrolled where the compiler
 * takes the hint (gcc's -O2 kept them as loops): callgrind, camera rays
 * at 1e6, 1,733 -> 1,634 instructions a ray (chapters/ch07/README.md). */
#if defined(__GNUC__) || defined(__clang__)
#define GRID_UNROLL3 _Pragma("GCC unroll 3")
#else
#define GRID_UNROLL3
#endif

/* The walk's slack, 256 u (see the top of the file). */
#define WALK_SLACK (256 * (double)REAL_UNIT_ROUNDOFF)

/* The ray in double, and the walk's margins (see the top of the file). */
typedef struct {
    double o[3], d[3], inv_d[3];
    double t0, t1;  /* the query interval widened by the slack */
    double bias;    /* WALK_SLACK diag / |d| */
#if GRID_QUADS && MESH_WIDE
    mesh_wide_ray_t wr; /* for two quads at once (where there are quads) */
#endif
} walk_t;

/* The part [*t0, *t1] of [lo, hi] (ray interval) inside the box. */
static bool slab(const walk_t *w, const double min[3], const double max[3],
                 double lo, double hi, double *t0, double *t1)
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
 * query whose tmax was tmax_q. Inlined where compilers allow: with the
 * packets as its second caller gcc made it a call, which cost single rays
 * 1.2% more instructions (callgrind, incoherent rays at 1e6). */
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

/* The walk of q from its start, (tmin, tmax). */
#if defined(__GNUC__) || defined(__clang__)
__attribute__((always_inline))
#endif
static inline void walk_init(walk_t *w, const grid_t *g,
                             const primset_query_t *q)
{
    walk_init_at(w, g, q, q->tmax, true);
}

/* Where the walk may stop once the nearest hit so far is at tmax: a cell
 * whose exit t_exit lies beyond it has t_exit (1 - WALK_SLACK) - bias >
 * tmax, the stopping rule at the top of the file (x + 2 s |x| >=
 * x / (1 - s) for either sign of x = tmax + bias; the double rounding of
 * this line is far below s). Never beyond t1. */
static double walk_end_at(double bias, const primset_query_t *q, double t1)
{
    if (!q->found)
        return t1;
    double x = (double)q->tmax + bias;
    x += 2 * WALK_SLACK * fabs(x);
    return x < t1 ? x : t1;
}

/* walk_end_at() with the walk's own bias. */
static double walk_end(const walk_t *w, const primset_query_t *q, double t1)
{
    return walk_end_at(w->bias, q, t1);
}

/* The t at which the ray crosses plane p (x_a = min_a + p w_a) of nd:
 * every crossing the walk compares comes from this one formula, the
 * planes between cells and those between blocks alike. */
static double plane_t(const grid_node_t *nd, const walk_t *w, int a, long p)
{
    return (nd->min[a] + (double)p * nd->w[a] - w->o[a]) * w->inv_d[a];
}

/* The state of a walk through one node (see walk()): per axis, t the t
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

/* The axis of the nearest of the crossings tx, ty, tz (ties to the
 * later axis), and that crossing's t in *t. Branches, not selects: see
 * walk(). */
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

/* Cross empty blocks (the current one is empty) until one holds
 * something, and set the walk on the cell of that block it enters first;
 * returns that block's word, or 0 when the walk is over (past tend, or out
 * of the grid). The block DDA runs on tb, kept by walk() along with the
 * cells' t (no set-up here); the axis is picked by branches, as in walk().
 * See walk() for why the cell entered is right. */
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

static bool walk(const grid_t *g, uint32_t ni, const walk_t *w,
                 primset_query_t *q, double t0, double t1, bool shadow);

#if GRID_QUADS
/* The full test of the lanes `left` of the quads qd (lane j in quad
 * j / MESH_BATCH), which the sign test could not reject, through the
 * mailbox. The corners come from the quad, which the sign test has just
 * brought into the cache, not from ps->tri (a copy of the same bits, so
 * the same answer): for incoherent rays at 1e6 triangles ps->tri[ref] was
 * a miss to memory about once a ray, and reading the quad traced them
 * about 17% faster (x 1.13 to 1.21 in alternating runs; camera rays about
 * 10%, packets of 8 x 8 2 to 5%). Returns
 * true when a shadow query found a hit. */
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

/* Batches pay with 4 lanes a vector (float with SSE2): with 2 (double)
 * camera rays ran 5% slower than one triangle at a time, measured on the
 * 1e6 spheres, and the plain lanes could only add work to the scalar
 * test. Elsewhere every triangle goes through primset_test(). */
#if defined(SIMD_REAL) && VLANES >= 4
#define GRID_BATCHES 1
#else
#define GRID_BATCHES 0
#endif

/* Test the n items of a cell: mesh triangles MESH_BATCH at a time (where
 * GRID_BATCHES; those in the grid's quads are left to test_quads()),
 * other primitives one by one, child grids (listed last) walked. Returns
 * true when a shadow query found a hit. */
static bool test_cell(const grid_t *g, const walk_t *w, primset_query_t *q,
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
                walk(g, it & ~GRID_CHILD, w, q, c0, c1, shadow))
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

/* Kept out of walk()'s loop, where compilers allow: inlined, its
 * registers pushed the walk's state (lc, bit, steps) onto the stack. */
#if defined(__GNUC__) || defined(__clang__)
#define GRID_NOINLINE __attribute__((noinline))
#else
#define GRID_NOINLINE
#endif

/* Test non-empty cell f: its quads, then its other items. */
static GRID_NOINLINE bool test_full(const grid_t *g, const walk_t *w,
                                    primset_query_t *q, uint32_t f,
                                    bool shadow)
{
    if (GRID_QUADS && g->quads) {
        uint32_t a = g->qstart[f], b = g->qstart[f + 1] & ~GRID_MORE;
        if (test_quads(g->ps, w, q, g->quads + (a & ~GRID_MORE),
                       b - (a & ~GRID_MORE), shadow))
            return true;
        if (!(a & GRID_MORE))
            return false;
    }
    return test_cell(g, w, q, g->items + g->cstart[f],
                     g->cstart[f + 1] - g->cstart[f], shadow);
}

/* Walk node ni over [t0, t1] (inside its box). Returns true when a
 * shadow query found a hit.
 *
 * The 3D-DDA of Amanatides & Woo 1987 over the cells, with the empty
 * space skipped block by block (the macro-regions of Devillers, "The
 * macro-regions: an efficient space subdivision structure for ray
 * tracing", Eurographics 1989, here fixed blocks of 4^3 cells). Inside a
 * block that holds something, each step goes to the nearest cell
 * crossing and a cell is tested against the block's 64-bit word in a
 * register; t grows by adding dt, in double: after n steps its rounding
 * error is below n 2^-53 of t, far inside the cells' padding (2^-20 of
 * the scene). The step picks its axis with plain branches: selects
 * without branches ran slower, measured on this machine, for incoherent
 * rays as for camera rays. At 1e6 triangles, with the same comparisons
 * and sums as masks (SSE2 on the t, integer masks on the counters and
 * bits): 22% fewer mispredicts under callgrind's simulator, 20% more
 * instructions, and incoherent rays 2% slower, camera rays 5% (each
 * step then waits for its compare and select, where a predicted branch
 * lets the next one start); with the t in an array indexed by the axis
 * (Amanatides & Woo's table) incoherent rays ran 3.5% slower. Incoherent
 * rays wait on memory more than on the predictor, and a ray's steps are
 * regular enough for it. Stepping out of the last cell of a block loads
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
 * a primitive it hits there lies within its padding (2^-20 of the scene,
 * grid.c's top) of the blocks on both sides, so it is in a cell the walk
 * visits. The cell entered, at the entry t tin through the face on axis
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
static bool walk(const grid_t *g, uint32_t ni, const walk_t *w,
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
                if (test_full(g, w, q, f, shadow)) {
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

/* --- packets of coherent rays (Wald et al. 2006) -------------------------- */

/* Rays a packet's arrays hold: GRID_PACKET_MAX, a multiple of 4 (the
 * vector loops of pk_slice_boxes() and pk_cell_rays()). */
#define PK_N GRID_PACKET_MAX
/* the live rays are the bits of a uint64_t, and the groups of four rays'
 * boxes come in fours (pk_slice_boxes) */
_Static_assert(GRID_PACKET_MAX <= 64 && GRID_PACKET_MAX % 16 == 0,
               "GRID_PACKET_MAX: at most 64, a multiple of 16");

/* A packet on its walk. Distances along the major axis k are measured
 * from the common origin in the rays' direction: s = (x_k - o_k) sg, so
 * ray i is at s = t |d_k| and there at o_u + s mu[i] on axis u (the same
 * for v). Every per-ray array is padded to a multiple of 4 with rays that
 * are nowhere (s0 = +inf, s1 = -inf). */
typedef struct {
    int k, u, v;           /* the major axis and the other two */
    double sg;             /* +1 or -1: the rays' direction on k */
    double o[3];           /* the common origin */
    double margin;         /* how far every test is widened (ps->pad) */
    int n;                 /* rays, rounded up to a multiple of 4 (of 16
                              above 16: the groups' boxes) */
    uint64_t live;         /* rays still walking */
    double S0, S1;         /* the union of the live rays' [s0, s1] */
    double mlo[2], mhi[2]; /* the live rays' extreme mu (0) and mv (1) */
    double s0[PK_N], s1[PK_N];   /* ray i's part of the grid (widened):
                                    from its entry to its exit or, once
                                    it has a hit, to its walk_end() */
    double mu[PK_N], mv[PK_N];   /* d_u / |d_k|, d_v / |d_k| */
    double iad[PK_N], adk[PK_N]; /* 1 / |d_k|, |d_k| */
    double tol[PK_N];            /* margin (|mu| + |mv|): pk_slice() */
    double tend[PK_N], t1[PK_N]; /* walk_end(), and the walk's t1 */
    double bias[PK_N];           /* the walk's bias (walk_end_at()) */
    real tmax0[PK_N];            /* tmax when the packet began */
    uint64_t wset;               /* the rays whose walk_t is made: only
                                    those the single walk's code needs
                                    (pk_walk()), so that the packet's
                                    state stays within the first-level
                                    cache */
#if GRID_QUADS && MESH_WIDE
    vwreal wo[3];                /* the origin, permuted (o_u, o_v, o_k),
                                    in every lane: the wide rays' o */
#endif
    /* ray i's box on (u, v) within the current slice, relative to o,
     * widened; empty (+inf, -inf) where the ray is not in the slice */
    double ul[PK_N], uh[PK_N], vl[PK_N], vh[PK_N];
    double box[4];         /* their union: least ul, greatest uh, vl, vh */
#ifdef __AVX__
    /* with more than 16 rays: the union of each group of four's boxes
     * (least ul, greatest uh, vl, vh), so that a cell tests the groups
     * first (pk_cell_rays) */
    double gb[4][PK_N / 4];
#endif
} packet_t;

#ifdef __AVX__
/* The least (mx false) or greatest lane of each of a0 .. a3, as the lanes
 * of one vector: two 4 x 4 half-transposes and three mins or maxes. */
static inline __m256d pk_reduce4(__m256d a0, __m256d a1, __m256d a2,
                                 __m256d a3, bool mx)
{
#define PK_OP(x, y) (mx ? _mm256_max_pd(x, y) : _mm256_min_pd(x, y))
    __m256d m01 = PK_OP(_mm256_unpacklo_pd(a0, a1), _mm256_unpackhi_pd(a0, a1));
    __m256d m23 = PK_OP(_mm256_unpacklo_pd(a2, a3), _mm256_unpackhi_pd(a2, a3));
    return PK_OP(_mm256_permute2f128_pd(m01, m23, 0x20),
                 _mm256_permute2f128_pd(m01, m23, 0x31));
#undef PK_OP
}
#endif

#ifdef __AVX__
/* The lanes whose bit is set in b (0 to 15), as a mask. */
static inline __m256d pk_mask4(unsigned b)
{
#define PK_M_(b)                                                              \
    { -((b) & 1), -((b) >> 1 & 1), -((b) >> 2 & 1), -((b) >> 3 & 1) }
    static const long long lanes[16][4] = {
        PK_M_(0),  PK_M_(1),  PK_M_(2),  PK_M_(3),  PK_M_(4),  PK_M_(5),
        PK_M_(6),  PK_M_(7),  PK_M_(8),  PK_M_(9),  PK_M_(10), PK_M_(11),
        PK_M_(12), PK_M_(13), PK_M_(14), PK_M_(15)
    };
#undef PK_M_
    return _mm256_castsi256_pd(
        _mm256_loadu_si256((const __m256i *)(const void *)lanes[b]));
}

/* x where m is set, else y (m from a comparison or pk_mask4()). */
static inline __m256d pk_sel4(__m256d m, __m256d x, __m256d y)
{
    return _mm256_blendv_pd(y, x, m);
}
#endif

static inline double pk_min(double a, double b)
{
    return a < b ? a : b;
}

static inline double pk_max(double a, double b)
{
    return a > b ? a : b;
}

/* The s of plane pl (x_k = min_k + pl w_k) of nd: times iad[i], the t at
 * which ray i crosses it, the bits plane_t() gives (sg |1/d| = 1/d). */
static inline double pk_plane_s(const grid_node_t *nd, const packet_t *p,
                                long pl)
{
    return (nd->min[p->k] + (double)pl * nd->w[p->k] - p->o[p->k]) * p->sg;
}

/* S0, S1 and the extreme slopes over the live rays. */
static void pk_bounds(packet_t *p)
{
#ifdef __AVX__
    /* four rays at a time, the others' lanes at +-inf: the least and the
     * greatest of the same numbers (no rounding), so the same bounds up
     * to the sign of a zero, which no comparison with them sees */
    const __m256d pinf = _mm256_set1_pd((double)INFINITY);
    const __m256d ninf = _mm256_set1_pd(-(double)INFINITY);
    __m256d lo0 = pinf, lo1 = pinf, lo2 = pinf, hi0 = ninf, hi1 = ninf,
            hi2 = ninf;
    for (int i = 0; i < p->n; i += 4) {
        unsigned b = (unsigned)(p->live >> i & 15);
        if (!b)
            continue;
        const __m256d m = pk_mask4(b);
        __m256d mu = _mm256_loadu_pd(p->mu + i);
        __m256d mv = _mm256_loadu_pd(p->mv + i);
        lo0 = _mm256_min_pd(lo0, pk_sel4(m, _mm256_loadu_pd(p->s0 + i), pinf));
        hi0 = _mm256_max_pd(hi0, pk_sel4(m, _mm256_loadu_pd(p->s1 + i), ninf));
        lo1 = _mm256_min_pd(lo1, pk_sel4(m, mu, pinf));
        hi1 = _mm256_max_pd(hi1, pk_sel4(m, mu, ninf));
        lo2 = _mm256_min_pd(lo2, pk_sel4(m, mv, pinf));
        hi2 = _mm256_max_pd(hi2, pk_sel4(m, mv, ninf));
    }
    double lo[4], hi[4];
    _mm256_storeu_pd(lo, pk_reduce4(lo0, lo1, lo2, pinf, false));
    _mm256_storeu_pd(hi, pk_reduce4(hi0, hi1, hi2, ninf, true));
    p->S0 = lo[0];
    p->S1 = hi[0];
    p->mlo[0] = lo[1];
    p->mhi[0] = hi[1];
    p->mlo[1] = lo[2];
    p->mhi[1] = hi[2];
#else
    p->S0 = (double)INFINITY;
    p->S1 = -(double)INFINITY;
    p->mlo[0] = p->mlo[1] = (double)INFINITY;
    p->mhi[0] = p->mhi[1] = -(double)INFINITY;
    for (uint64_t m = p->live; m; m &= m - 1) {
        int i = bits_lowest(m);
        p->S0 = pk_min(p->S0, p->s0[i]);
        p->S1 = pk_max(p->S1, p->s1[i]);
        p->mlo[0] = pk_min(p->mlo[0], p->mu[i]);
        p->mhi[0] = pk_max(p->mhi[0], p->mu[i]);
        p->mlo[1] = pk_min(p->mlo[1], p->mv[i]);
        p->mhi[1] = pk_max(p->mhi[1], p->mv[i]);
    }
#endif
}

/* The cells [*c0, *c1] on axis u (j = 0) or v (j = 1) that the live
 * rays' points with s in [a, b] may lie in: {s m} for s in [a, b] and m
 * in [mlo, mhi] lies between the least and the greatest of the four
 * corner products (rounding is monotone, so every ray's own product
 * lies between them too), widened by twice the margin. */
static void pk_range(const grid_node_t *nd, const packet_t *p, int j,
                     double a, double b, int *c0, int *c1)
{
    int ax = j ? p->v : p->u;
    double aa = a * p->mlo[j], ab = a * p->mhi[j];
    double ba = b * p->mlo[j], bb = b * p->mhi[j];
    double lo = pk_min(pk_min(aa, ab), pk_min(ba, bb));
    double hi = pk_max(pk_max(aa, ab), pk_max(ba, bb));
    *c0 = cell_of(nd, ax, p->o[ax] + lo - 2 * p->margin);
    *c1 = cell_of(nd, ax, p->o[ax] + hi + 2 * p->margin);
}

/* Ray i's box on (u, v) within the slice [a, b] of s: its segment
 * there runs from s = max(a, s0) to min(b, s1), and u = s mu is linear
 * in s, so the ends bound it. */
static void pk_box(packet_t *p, int i, double a, double b)
{
    const double inf = (double)INFINITY, mg = p->margin;
    double sa = pk_max(a, p->s0[i]), sb = pk_min(b, p->s1[i]);
    double ua = sa * p->mu[i], ub = sb * p->mu[i];
    double va = sa * p->mv[i], vb = sb * p->mv[i];
    bool in = sa <= sb;
    p->ul[i] = in ? pk_min(ua, ub) - mg : inf;
    p->uh[i] = in ? pk_max(ua, ub) + mg : -inf;
    p->vl[i] = in ? pk_min(va, vb) - mg : inf;
    p->vh[i] = in ? pk_max(va, vb) + mg : -inf;
}

/* pk_box() of every ray, and the union of their boxes (with AVX four
 * rays at a time: the same operations in the same order, and the vector
 * min and max answer as pk_min and pk_max, NaN included). */
static void pk_slice_boxes(packet_t *p, double a, double b)
{
#ifdef __AVX__
    const double inf = (double)INFINITY, mg = p->margin;
    const __m256d va = _mm256_set1_pd(a), vb = _mm256_set1_pd(b);
    const __m256d vmg = _mm256_set1_pd(mg), pinf = _mm256_set1_pd(inf);
    const __m256d ninf = _mm256_set1_pd(-inf);
    __m256d lo_u = pinf, hi_u = ninf, lo_v = pinf, hi_v = ninf;
    for (int i = 0; i < p->n; i += 4) {
        if (!(p->live >> i & 15))
            continue; /* their boxes stay empty (pk_drop()) */
        __m256d sa = _mm256_max_pd(va, _mm256_loadu_pd(p->s0 + i));
        __m256d sb = _mm256_min_pd(vb, _mm256_loadu_pd(p->s1 + i));
        __m256d in = _mm256_cmp_pd(sa, sb, _CMP_LE_OQ);
        __m256d mu = _mm256_loadu_pd(p->mu + i);
        __m256d mv = _mm256_loadu_pd(p->mv + i);
        __m256d ua = _mm256_mul_pd(sa, mu), ub = _mm256_mul_pd(sb, mu);
        __m256d xa = _mm256_mul_pd(sa, mv), xb = _mm256_mul_pd(sb, mv);
        __m256d ul = _mm256_blendv_pd(pinf,
            _mm256_sub_pd(_mm256_min_pd(ua, ub), vmg), in);
        __m256d uh = _mm256_blendv_pd(ninf,
            _mm256_add_pd(_mm256_max_pd(ua, ub), vmg), in);
        __m256d vl = _mm256_blendv_pd(pinf,
            _mm256_sub_pd(_mm256_min_pd(xa, xb), vmg), in);
        _mm256_storeu_pd(p->ul + i, ul);
        _mm256_storeu_pd(p->uh + i, uh);
        _mm256_storeu_pd(p->vl + i, vl);
        __m256d vh = _mm256_blendv_pd(ninf,
            _mm256_add_pd(_mm256_max_pd(xa, xb), vmg), in);
        _mm256_storeu_pd(p->vh + i, vh);
        lo_u = _mm256_min_pd(lo_u, ul);
        hi_u = _mm256_max_pd(hi_u, uh);
        lo_v = _mm256_min_pd(lo_v, vl);
        hi_v = _mm256_max_pd(hi_v, vh);
    }
    if (p->n > 16) { /* the groups' boxes, four groups at a time */
        double *const src[4] = { p->ul, p->uh, p->vl, p->vh };
        for (int g = 0; g < p->n; g += 16)
            for (int c = 0; c < 4; c++) {
                const double *x = src[c] + g;
                _mm256_storeu_pd(p->gb[c] + g / 4,
                                 pk_reduce4(_mm256_loadu_pd(x),
                                            _mm256_loadu_pd(x + 4),
                                            _mm256_loadu_pd(x + 8),
                                            _mm256_loadu_pd(x + 12), c & 1));
            }
    }
    double x[4][4];
    _mm256_storeu_pd(x[0], lo_u);
    _mm256_storeu_pd(x[1], hi_u);
    _mm256_storeu_pd(x[2], lo_v);
    _mm256_storeu_pd(x[3], hi_v);
    for (int c = 0; c < 4; c += 2) {
        p->box[c] = pk_min(pk_min(x[c][0], x[c][1]), pk_min(x[c][2], x[c][3]));
        p->box[c + 1] = pk_max(pk_max(x[c + 1][0], x[c + 1][1]),
                               pk_max(x[c + 1][2], x[c + 1][3]));
    }
#else
    p->box[0] = p->box[2] = (double)INFINITY;
    p->box[1] = p->box[3] = -(double)INFINITY;
    for (int i = 0; i < p->n; i++) {
        pk_box(p, i, a, b);
        p->box[0] = pk_min(p->box[0], p->ul[i]);
        p->box[1] = pk_max(p->box[1], p->uh[i]);
        p->box[2] = pk_min(p->box[2], p->vl[i]);
        p->box[3] = pk_max(p->box[3], p->vh[i]);
    }
#endif
}

#ifndef __AVX__
/* Whether ray i's line on (u, v) may meet the cell [u0, u1] x [v0, v1]
 * (relative to o): see pk_slice(). With AVX, pk_line4() below asks it of
 * four rays at once by the same operations. */
static inline bool pk_line(const packet_t *p, int i, double u0, double u1,
                           double v0, double v1)
{
    double mu = p->mu[i], mv = p->mv[i];
    double fa = mv * u0, fb = mv * u1;
    double ga = mu * v0, gb = mu * v1;
    double tol = p->tol[i];
    return !(pk_min(fa, fb) - pk_max(ga, gb) > tol ||
             pk_max(fa, fb) - pk_min(ga, gb) < -tol);
}
#endif

#ifdef __AVX__
/* pk_line() of rays i .. i + 3 at once, as the bits of a mask: the same
 * operations (the vector min and max answer as pk_min and pk_max, NaN
 * included; the ordered comparisons are false on NaN, as C's). */
static inline int pk_line4(const packet_t *p, int i, __m256d u0, __m256d u1,
                           __m256d v0, __m256d v1)
{
    __m256d mu = _mm256_loadu_pd(p->mu + i), mv = _mm256_loadu_pd(p->mv + i);
    __m256d tol = _mm256_loadu_pd(p->tol + i);
    __m256d fa = _mm256_mul_pd(mv, u0), fb = _mm256_mul_pd(mv, u1);
    __m256d ga = _mm256_mul_pd(mu, v0), gb = _mm256_mul_pd(mu, v1);
    __m256d x = _mm256_sub_pd(_mm256_min_pd(fa, fb), _mm256_max_pd(ga, gb));
    __m256d y = _mm256_sub_pd(_mm256_max_pd(fa, fb), _mm256_min_pd(ga, gb));
    __m256d out = _mm256_or_pd(
        _mm256_cmp_pd(x, tol, _CMP_GT_OQ),
        _mm256_cmp_pd(y, _mm256_sub_pd(_mm256_setzero_pd(), tol), _CMP_LT_OQ));
    return ~_mm256_movemask_pd(out) & 15;
}
#endif

/* The rays whose slice box overlaps the cell [u0, u1] x [v0, v1]
 * (relative to o) and whose line on (u, v) may meet it (pk_line): a
 * superset of the rays whose segment in the slice meets the cell, the
 * cell's own extent along k being the slice's. */
static inline uint64_t pk_cell_rays(const packet_t *p, double u0, double u1,
                                    double v0, double v1)
{
    uint64_t m = 0;
#ifdef __AVX__
    const __m256d a = _mm256_set1_pd(u0), b = _mm256_set1_pd(u1);
    const __m256d c = _mm256_set1_pd(v0), d = _mm256_set1_pd(v1);
    int box;
#define PK_OVERLAP(L0, H0, L1, H1)                                           \
    _mm256_movemask_pd(_mm256_and_pd(                                         \
        _mm256_and_pd(_mm256_cmp_pd(_mm256_loadu_pd(L0), b, _CMP_LE_OQ),      \
                      _mm256_cmp_pd(_mm256_loadu_pd(H0), a, _CMP_GE_OQ)),     \
        _mm256_and_pd(_mm256_cmp_pd(_mm256_loadu_pd(L1), d, _CMP_LE_OQ),      \
                      _mm256_cmp_pd(_mm256_loadu_pd(H1), c, _CMP_GE_OQ))))
    if (p->n <= 16) {
        for (int i = 0; i < p->n; i += 4)
            if ((box = PK_OVERLAP(p->ul + i, p->uh + i, p->vl + i,
                                  p->vh + i)) != 0)
                m |= (uint64_t)(box & pk_line4(p, i, a, b, c, d)) << i;
        return m;
    }
    /* the groups whose union box meets the cell, then their rays */
    uint32_t gm = 0;
    for (int g = 0; g < p->n / 4; g += 4)
        gm |= (uint32_t)PK_OVERLAP(p->gb[0] + g, p->gb[1] + g, p->gb[2] + g,
                                   p->gb[3] + g)
              << g;
    for (; gm; gm &= gm - 1) {
        int i = 4 * bits_lowest(gm);
        if ((box = PK_OVERLAP(p->ul + i, p->uh + i, p->vl + i,
                              p->vh + i)) != 0)
            m |= (uint64_t)(box & pk_line4(p, i, a, b, c, d)) << i;
    }
#undef PK_OVERLAP
#else
    for (int i = 0; i < p->n; i++)
        m |= (uint64_t)(p->ul[i] <= u1 && p->uh[i] >= u0 &&
                        p->vl[i] <= v1 && p->vh[i] >= v0 &&
                        pk_line(p, i, u0, u1, v0, v1))
             << i;
#endif
    return m;
}

/* Ray i's walk_t, made on first use: the one walk_init() made when the
 * packet began (the same tmax), for the single walk's code (child grids,
 * a cell's other items, cells without quads). */
static const walk_t *pk_walk(const grid_t *g, packet_t *p, walk_t *w,
                             const primset_query_t *q, int i)
{
    if (!(p->wset >> i & 1)) {
        walk_init_at(&w[i], g, &q[i], p->tmax0[i], true);
        p->wset |= UINT64_C(1) << i;
    }
    return &w[i];
}

#if GRID_QUADS
/* t = the nine corner vectors c0 .. c8 (permuted by MESH_PERMUTED) less
 * the origin o (in the same order), for pk_test_cell(): written out, so
 * that every load has a constant offset. */
#define PK_DEFINE_LESS_ORIGIN(NAME, T, P)                                     \
    static inline void NAME(T c0, T c1, T c2, T c3, T c4, T c5, T c6, T c7,  \
                            T c8, T t[9], const T o[3])                       \
    {                                                                         \
        t[0] = P##_SUB(c0, o[0]), t[1] = P##_SUB(c1, o[1]);                   \
        t[2] = P##_SUB(c2, o[2]), t[3] = P##_SUB(c3, o[0]);                   \
        t[4] = P##_SUB(c4, o[1]), t[5] = P##_SUB(c5, o[2]);                   \
        t[6] = P##_SUB(c6, o[0]), t[7] = P##_SUB(c7, o[1]);                   \
        t[8] = P##_SUB(c8, o[2]);                                             \
    }
PK_DEFINE_LESS_ORIGIN(pk_less_origin, vreal, V)
#if MESH_WIDE
PK_DEFINE_LESS_ORIGIN(pk_less_origin_w, vwreal, VW)
#endif
#endif

/* Where compilers allow, an empty statement that may read x and write any
 * memory: the corner vectors t of pk_test_cell() are then read from
 * memory for each ray, as operands of its arithmetic, instead of being
 * held in nine of the sixteen vector registers while the sign test's
 * temporaries spill around them (gcc 12, AVX2: 72 -> 48 instructions a
 * ray and pair of quads, 53 -> 45 a ray and quad; the same operations). */
#if defined(__GNUC__) || defined(__clang__)
#define GRID_FROM_MEMORY(x) __asm__("" : : "r"(x) : "memory")
#else
#define GRID_FROM_MEMORY(x) ((void)0)
#endif

/* Test non-empty cell f for the packet's rays `rays`: test_full() of
 * each, with the loops turned inside out where the cell has quads: each
 * pair of quads (or quad) taken once and the rays run through it, so that
 * the cell's quads are found and a call made once a cell, not once a ray.
 * The same per-ray tests (mesh_wide_reject_soa2, mesh_lanes_reject_soa,
 * test_lanes, test_cell: the same bits and the same mailbox), in another
 * order, which the nearest-hit rule does not see. */
static void pk_test_cell(const grid_t *g, packet_t *p, walk_t *w,
                         primset_query_t *q, uint32_t f, uint64_t rays)
{
#if GRID_QUADS
    if (g->quads) {
        const primset_t *ps = g->ps;
        uint32_t a = g->qstart[f], e = g->qstart[f + 1] & ~GRID_MORE;
        const grid_quad_t *qd = g->quads + (a & ~GRID_MORE);
        uint32_t nq = e - (a & ~GRID_MORE), i = 0;
        /* The sign test's first step, the corners less the origin, is the
         * same for every ray of the packet (one origin, one kz: packet()):
         * done once a pair of quads (or a quad), then
         * mesh_wide_reject_perm() (mesh_lanes_reject_perm()) from there
         * with a zero origin (x - 0 is x, bit for bit), the same
         * operations as mesh_wide_reject_soa2() (mesh_lanes_reject_soa())
         * and so the same mask. */
        const int r0 = bits_lowest(rays), kz = p->k; /* = every q.mr.kz */
#if MESH_WIDE
        const vwreal zo[3] = { VW_SET1(0), VW_SET1(0), VW_SET1(0) };
        for (; i + 1 < nq; i += 2) {
            vwreal t[9];
#define PK_PAIR_(j)                                                           \
    VW_LOAD2(qd[i].c + (j) * VLANES, qd[i + 1].c + (j) * VLANES)
            MESH_PERMUTED(kz, pk_less_origin_w, PK_PAIR_, t, p->wo);
#undef PK_PAIR_
            for (uint64_t m = rays; m; m &= m - 1) {
                int r = bits_lowest(m);
                GRID_FROM_MEMORY(t);
                /* every ray of a packet is fast (packet()) */
                unsigned left = ~mesh_wide_reject_perm(t[0], t[1], t[2], t[3],
                                                       t[4], t[5], t[6], t[7],
                                                       t[8], zo,
                                                       VW_SET1(q[r].mr.sx),
                                                       VW_SET1(q[r].mr.sy)) &
                                ((1u << (2 * MESH_BATCH)) - 1);
                if (left)
                    test_lanes(ps, &q[r], qd + i, left, false);
            }
        }
#endif
        const vreal zo4[3] = { V_SET1(0), V_SET1(0), V_SET1(0) };
        for (; i < nq; i++) {
            vreal t[9];
#define PK_QUAD_(j) V_LOAD(qd[i].c + (j) * VLANES)
            MESH_PERMUTED(kz, pk_less_origin, PK_QUAD_, t, q[r0].mr.vo);
#undef PK_QUAD_
            for (uint64_t m = rays; m; m &= m - 1) {
                int r = bits_lowest(m);
                GRID_FROM_MEMORY(t);
                unsigned left = ~mesh_lanes_reject_perm(t[0], t[1], t[2], t[3],
                                                        t[4], t[5], t[6], t[7],
                                                        t[8], zo4,
                                                        q[r].mr.vsx,
                                                        q[r].mr.vsy) &
                                ((1u << MESH_BATCH) - 1);
                if (left)
                    test_lanes(ps, &q[r], qd + i, left, false);
            }
        }
        if (!(a & GRID_MORE))
            return;
        for (uint64_t m = rays; m; m &= m - 1) {
            int r = bits_lowest(m);
            test_cell(g, pk_walk(g, p, w, q, r), &q[r],
                      g->items + g->cstart[f],
                      g->cstart[f + 1] - g->cstart[f], false);
        }
        return;
    }
#endif
    for (uint64_t m = rays; m; m &= m - 1) {
        int r = bits_lowest(m);
        test_full(g, pk_walk(g, p, w, q, r), &q[r], f, false);
    }
}

/* Take ray i out of the walk. */
static void pk_drop(packet_t *p, int i)
{
    p->live &= ~(UINT64_C(1) << i);
    p->s0[i] = p->ul[i] = p->vl[i] = (double)INFINITY;
    p->s1[i] = p->uh[i] = p->vh[i] = -(double)INFINITY;
}

/* After the slices up to far plane s = b are done: every live ray whose
 * crossing of that plane lies past its walk_end() is finished -- the
 * single walk's stopping rule, with the slice's far plane for the cell's
 * exit. Returns true when a ray was dropped. */
static bool pk_stop(packet_t *p, double b)
{
    uint64_t drop = 0;
#ifdef __AVX__
    const __m256d vb = _mm256_set1_pd(b);
    for (int i = 0; i < p->n; i += 4)
        drop |= (uint64_t)_mm256_movemask_pd(_mm256_cmp_pd(
                    _mm256_mul_pd(vb, _mm256_loadu_pd(p->iad + i)),
                    _mm256_loadu_pd(p->tend + i), _CMP_NLE_UQ))
                << i;
#else
    for (int i = 0; i < p->n; i++)
        drop |= (uint64_t)!(b * p->iad[i] <= p->tend[i]) << i;
#endif
    drop &= p->live;
    for (uint64_t m = drop; m; m &= m - 1)
        pk_drop(p, bits_lowest(m));
    if (drop)
        pk_bounds(p);
    return drop != 0;
}

/* The bits of a block's word whose cell has coordinate lo .. hi (within
 * the block, 0 to GRID_BLOCK - 1) on axis a. */
static inline uint64_t pk_axis_bits(int a, int lo, int hi)
{
    const uint64_t layers = UINT64_C(0x0001000100010001);
    if (a == 0) /* bit x + 4 y + 16 z */
        return layers * (0x1111u * ((2u << hi) - (1u << lo)));
    if (a == 1)
        return layers * ((UINT64_C(1) << 4 * (hi + 1)) -
                         (UINT64_C(1) << 4 * lo));
    return (~UINT64_C(0) >> (48 - 16 * hi)) & (~UINT64_C(0) << 16 * lo);
}

/* A block the frustum may cross in a block slab, and the bits of its
 * cells in the frustum's range on u and v that hold something. */
typedef struct {
    long blk;
    int bu, bv;
    uint64_t cells;
} pk_block_t;

/* At most this many blocks a slab: a wider frustum is walked ray by ray. */
#define PK_BLOCKS 64

/* A block slab's blocks that the frustum may cross and that hold
 * something in its range (blk[0 .. n)), and the planes between the cells
 * of that range on u (j = 0) and v (j = 1), relative to the origin:
 * e[j][c - c0[j]] is plane c (made once a slab, not once a cell: the
 * same formula, so the same bits). At most 4 PK_BLOCKS cells an axis. */
typedef struct {
    pk_block_t blk[PK_BLOCKS];
    int n, c0[2];
    double e[2][GRID_BLOCK * PK_BLOCKS + 1];
} pk_slab_t;

/* The blocks of block slab bj (s from a to b) that the frustum may cross
 * and that hold something in its range, into sl (and, when there are
 * any, the planes between the range's cells); returns how many, or -1
 * when the range spans more than PK_BLOCKS blocks. */
static int pk_slab_blocks(const grid_t *g, const packet_t *p, int bj,
                          double a, double b, pk_slab_t *sl)
{
    pk_block_t *out = sl->blk;
    const grid_node_t *nd = &g->nodes[0];
    const int u = p->u, v = p->v;
    int u0, u1, v0, v1;
    pk_range(nd, p, 0, a, b, &u0, &u1);
    pk_range(nd, p, 1, a, b, &v0, &v1);
    const long stride[3] = { 1, nd->nb[0], (long)nd->nb[0] * nd->nb[1] };
    const int bu0 = u0 / GRID_BLOCK, bu1 = u1 / GRID_BLOCK;
    const int bv0 = v0 / GRID_BLOCK, bv1 = v1 / GRID_BLOCK;
    if ((bu1 - bu0 + 1) * (bv1 - bv0 + 1) > PK_BLOCKS)
        return -1;
    const uint64_t *bm = g->bmask + nd->bfirst;
    long bk = (long)bj * stride[p->k];
    int n = 0;
    for (int bv = bv0; bv <= bv1; bv++) {
        uint64_t vbits = pk_axis_bits(
            v, bv == bv0 ? v0 % GRID_BLOCK : 0,
            bv == bv1 ? v1 % GRID_BLOCK : GRID_BLOCK - 1);
        for (int bu = bu0; bu <= bu1; bu++) {
            long blk = bk + bv * stride[v] + bu * stride[u];
            uint64_t c = bm[blk] & vbits &
                         pk_axis_bits(u, bu == bu0 ? u0 % GRID_BLOCK : 0,
                                      bu == bu1 ? u1 % GRID_BLOCK
                                                : GRID_BLOCK - 1);
            if (c) {
                out[n].blk = blk;
                out[n].bu = bu;
                out[n].bv = bv;
                out[n++].cells = c;
            }
        }
    }
    if (n > 0) {
        const int ax[2] = { u, v }, lo[2] = { u0, v0 }, hi[2] = { u1, v1 };
        for (int j = 0; j < 2; j++) {
            sl->c0[j] = lo[j];
            for (int c = lo[j]; c <= hi[j] + 1; c++)
                sl->e[j][c - lo[j]] =
                    nd->min[ax[j]] + c * nd->w[ax[j]] - p->o[ax[j]];
        }
    }
    return sl->n = n;
}

/* Walk slice j (s from a to b) over the slab's blocks blks[0 .. nb): each
 * non-empty cell of the slice in the frustum's range, tested for the rays
 * that may pass through it: those whose box in the slice overlaps the
 * cell (pk_cell_rays) and whose line on (u, v) meets it. Every ray's line
 * on (u, v) runs through the origin (the common origin is at u = v = 0),
 * along (mu, mv): f(P) = mv P_u - mu P_v is zero on it, and the line
 * meets a rectangle when f takes both signs over its corners; the
 * rectangle widened by the margin moves f by at most margin (|mu| +
 * |mv|). With the box, the segment test of 2D separating axes: exact,
 * but for the margins. The rays' boxes are made only for a slice with
 * something in it. */
static void pk_slice(const grid_t *g, packet_t *p, walk_t *w,
                     primset_query_t *q, int j, double a, double b,
                     const pk_slab_t *sl)
{
    const pk_block_t *blks = sl->blk;
    const int nb = sl->n;
    const grid_node_t *nd = &g->nodes[0];
    const int u = p->u, v = p->v;
    const uint64_t *bm = g->bmask + nd->bfirst;
    const uint32_t *bb = g->bbase + nd->bfirst;
    uint64_t kbits = pk_axis_bits(p->k, j % GRID_BLOCK, j % GRID_BLOCK);
    bool boxes = false;
    for (int x = 0; x < nb; x++) {
        uint64_t cells = blks[x].cells & kbits;
        if (!cells)
            continue;
        if (!boxes) {
            pk_slice_boxes(p, a, b);
            boxes = true;
        }
        long blk = blks[x].blk;
        for (; cells; cells &= cells - 1) {
            int bit = bits_lowest(cells);
            /* bit x + 4 y + 16 z: axis a's coordinate is 2 a bits up */
            int cu = blks[x].bu * GRID_BLOCK + (bit >> 2 * u & 3);
            int cv = blks[x].bv * GRID_BLOCK + (bit >> 2 * v & 3);
            const double *eu = sl->e[0] + (cu - sl->c0[0]);
            const double *ev = sl->e[1] + (cv - sl->c0[1]);
            double lu = eu[0], hu = eu[1], lv = ev[0], hv = ev[1];
            if (p->box[0] > hu || p->box[1] < lu || p->box[2] > hv ||
                p->box[3] < lv)
                continue; /* no ray's box meets it */
            uint64_t in = pk_cell_rays(p, lu, hu, lv, hv) & p->live;
            if (!in)
                continue;
            pk_test_cell(g, p, w, q, full_cell(bb[blk], bm[blk], bit), in);
            for (; in; in &= in - 1) {
                int i = bits_lowest(in);
                q[i].cells++;
                if (q[i].found) {
                    /* the ray's segment now ends at its walk_end():
                     * beyond it no cell can hold a better hit */
                    p->tend[i] = walk_end_at(p->bias[i], &q[i], p->t1[i]);
                    p->s1[i] = p->tend[i] * p->adk[i] + p->margin;
                    pk_box(p, i, a, b);
                }
            }
        }
    }
}

/* Whether the packet takes query qi: its ray starts at the common origin
 * o (finite), moves along the packet's major axis k in its direction,
 * with |d_k| its largest component, and is fast for the triangle test
 * (mesh_ray_prepare()); the others are traced alone. */
static inline bool pk_admits(const packet_t *p, const primset_query_t *qi,
                             const real *o, bool o_ok)
{
    const ray_t *r = qi->r;
    double dk = (double)r->d[p->k] * p->sg;
    /* & rather than &&: one branch, not ten. The origin's bytes: -0 for
     * +0 sends a ray alone, which only costs time. |d_k| is finite where
     * the ray is fast and k is its kz; the slopes' tests catch a NaN in
     * d_u or d_v, which vec_max_axis() passes over. */
    return (int)o_ok & (memcmp(r->o, o, sizeof r->o) == 0) & (dk > 0) &
           (dk >= fabs((double)r->d[p->u])) &
           (dk >= fabs((double)r->d[p->v])) & (qi->mr.kz == p->k) &
           (int)qi->mr.fast;
}

#ifndef __AVX__
/* Ray i's values once it is set up: its part [t0, t1] of the grid (from
 * slab()), the walk's bias (the caller makes it live). With AVX,
 * pk_setup4() computes them four at a time. */
static inline void pk_enter(packet_t *p, const primset_query_t *q, int i,
                            double t0, double t1, double bias)
{
    p->bias[i] = bias;
    p->tmax0[i] = q[i].tmax;
    p->s0[i] = t0 * p->adk[i] - p->margin;
    p->s1[i] = t1 * p->adk[i] + p->margin;
    p->t1[i] = t1;
    p->tend[i] = walk_end_at(bias, &q[i], t1);
}
#endif

#ifdef __AVX__
/* |x|, as fabs: the sign bit cleared. */
static inline __m256d pk_abs4(__m256d x)
{
    return _mm256_andnot_pd(_mm256_set1_pd(-0.0), x);
}
#endif

/* Set up rays i .. i + 3 of the packet (the lanes of `ok`; the others
 * are nowhere): walk_init_at()'s bias, t0 and t1, slab() against the
 * grid's box, the slopes and the segment along k. Returns the lanes
 * whose ray meets the grid (made live by the caller). With AVX four rays
 * at a time, each lane by the scalar operations in their order (the
 * vector operations are IEEE's, and the comparisons and selections answer
 * as C's, NaN included), so the same bits. */
static int pk_setup4(const grid_t *g, packet_t *p, const primset_query_t *q,
                     int i, int n, const real *o, bool o_ok, uint64_t *alone)
{
    const grid_node_t *nd = &g->nodes[0];
    const int k = p->k, u = p->u, v = p->v;
    int ok = 0, in = 0;
#ifdef __AVX__
    double d[3][4], tn[4], tx[4];
    for (int l = 0; l < 4; l++) {
        bool y = i + l < n && pk_admits(p, &q[i + l], o, o_ok);
        if (i + l < n && !y)
            *alone |= UINT64_C(1) << (i + l);
        ok |= y << l;
        if (!y) { /* harmless values; `ok` keeps the lane out */
            d[0][l] = d[1][l] = d[2][l] = 1;
            tn[l] = 0;
            tx[l] = 0;
            continue; /* q[i + l] may lie past the caller's n queries */
        }
        const ray_t *r = q[i + l].r;
        for (int a = 0; a < 3; a++)
            d[a][l] = (double)r->d[a];
        tn[l] = (double)q[i + l].tmin;
        tx[l] = (double)q[i + l].tmax;
    }
    const __m256d one = _mm256_set1_pd(1);
    const __m256d sl = _mm256_set1_pd(WALK_SLACK);
    __m256d D[3], len2 = _mm256_setzero_pd(), inv[3];
    for (int a = 0; a < 3; a++) { /* walk_init_at() */
        D[a] = _mm256_loadu_pd(d[a]);
        inv[a] = _mm256_div_pd(one, D[a]);
        len2 = _mm256_add_pd(len2, _mm256_mul_pd(D[a], D[a]));
    }
    __m256d bias = _mm256_div_pd(_mm256_set1_pd(WALK_SLACK * g->diag),
                                 _mm256_sqrt_pd(len2));
    __m256d tmin = _mm256_loadu_pd(tn), tmax = _mm256_loadu_pd(tx);
    __m256d t0 = _mm256_sub_pd(
        _mm256_sub_pd(tmin, _mm256_mul_pd(sl, pk_abs4(tmin))), bias);
    __m256d t1 = _mm256_add_pd(
        _mm256_add_pd(tmax, _mm256_mul_pd(sl, pk_abs4(tmax))), bias);
    __m256d lo = t0, hi = t1;
    for (int a = 0; a < 3; a++) { /* slab() */
        __m256d n0 = _mm256_mul_pd(_mm256_set1_pd(nd->min[a] - p->o[a]),
                                   inv[a]);
        __m256d f0 = _mm256_mul_pd(_mm256_set1_pd(nd->max[a] - p->o[a]),
                                   inv[a]);
        __m256d sw = _mm256_cmp_pd(n0, f0, _CMP_GT_OQ);
        __m256d n1 = pk_sel4(sw, f0, n0), f1 = pk_sel4(sw, n0, f0);
        lo = pk_sel4(_mm256_cmp_pd(n1, lo, _CMP_GT_OQ), n1, lo);
        hi = pk_sel4(_mm256_cmp_pd(f1, hi, _CMP_LT_OQ), f1, hi);
    }
    in = ok & _mm256_movemask_pd(
                  _mm256_and_pd(_mm256_cmp_pd(t0, t1, _CMP_LE_OQ),
                                _mm256_cmp_pd(lo, hi, _CMP_LE_OQ)));
    const __m256d live = pk_mask4((unsigned)in);
    const __m256d zero = _mm256_setzero_pd();
    __m256d dk = _mm256_mul_pd(D[k], _mm256_set1_pd(p->sg));
    __m256d mu = _mm256_div_pd(D[u], dk), mv = _mm256_div_pd(D[v], dk);
    _mm256_storeu_pd(p->iad + i, pk_sel4(live, _mm256_div_pd(one, dk), zero));
    _mm256_storeu_pd(p->adk + i, pk_sel4(live, dk, zero));
    _mm256_storeu_pd(p->mu + i, pk_sel4(live, mu, zero));
    _mm256_storeu_pd(p->mv + i, pk_sel4(live, mv, zero));
    _mm256_storeu_pd(p->tol + i,
                     pk_sel4(live,
                             _mm256_mul_pd(_mm256_set1_pd(p->margin),
                                           _mm256_add_pd(pk_abs4(mu),
                                                         pk_abs4(mv))),
                             zero));
    const __m256d pinf = _mm256_set1_pd((double)INFINITY);
    const __m256d ninf = _mm256_set1_pd(-(double)INFINITY);
    const __m256d mg = _mm256_set1_pd(p->margin);
    /* pk_enter()'s values, the same operations */
    _mm256_storeu_pd(p->bias + i, bias);
    _mm256_storeu_pd(p->t1 + i, pk_sel4(live, hi, zero));
    _mm256_storeu_pd(p->tend + i, pk_sel4(live, hi, zero)); /* no hit yet */
    _mm256_storeu_pd(p->s0 + i,
                     pk_sel4(live, _mm256_sub_pd(_mm256_mul_pd(lo, dk), mg),
                             pinf));
    _mm256_storeu_pd(p->s1 + i,
                     pk_sel4(live, _mm256_add_pd(_mm256_mul_pd(hi, dk), mg),
                             ninf));
    _mm256_storeu_pd(p->ul + i, pinf); /* empty until its first slice */
    _mm256_storeu_pd(p->vl + i, pinf);
    _mm256_storeu_pd(p->uh + i, ninf);
    _mm256_storeu_pd(p->vh + i, ninf);
    for (int m = in; m; m &= m - 1) {
        int j = i + bits_lowest((uint64_t)m);
        p->tmax0[j] = q[j].tmax;
        /* a query that came with a hit: walk_end(), as the scalar path
         * makes it (where tmax >= 0 that is t1 already: it never ends
         * before the walk's own t1 there) */
        if (q[j].found)
            p->tend[j] = walk_end_at(p->bias[j], &q[j], p->t1[j]);
    }
#else
    for (int l = 0; l < 4 && i + l < n; l++) {
        if (pk_admits(p, &q[i + l], o, o_ok))
            ok |= 1 << l;
        else
            *alone |= UINT64_C(1) << (i + l);
    }
    for (int l = 0; l < 4; l++) {
        int j = i + l;
        p->s0[j] = (double)INFINITY;
        p->s1[j] = -(double)INFINITY;
        p->mu[j] = p->mv[j] = p->iad[j] = p->adk[j] = p->tol[j] =
            p->tend[j] = p->t1[j] = 0;
        if (!(ok >> l & 1))
            continue;
        walk_t wl; /* walk_init()'s values, but for the wide ray */
        walk_init_at(&wl, g, &q[j], q[j].tmax, false);
        double t0, t1;
        if (!(wl.t0 <= wl.t1) ||
            !slab(&wl, nd->min, nd->max, wl.t0, wl.t1, &t0, &t1))
            continue; /* misses the grid: q[j] as query() leaves it */
        const ray_t *r = q[j].r;
        double dk = (double)r->d[k] * p->sg;
        p->iad[j] = 1 / dk;
        p->adk[j] = dk;
        p->mu[j] = (double)r->d[u] / dk;
        p->mv[j] = (double)r->d[v] / dk;
        p->tol[j] = p->margin * (fabs(p->mu[j]) + fabs(p->mv[j]));
        pk_enter(p, q, j, t0, t1, wl.bias);
        in |= 1 << l;
    }
#endif
    return in;
}

/* One packet of n <= GRID_PACKET_MAX rays (grid_intersect_packet()).
 *
 * Why each ray gets grid_intersect()'s answer. Both answers are the
 * nearest hit of the primitives tested (the rule of primset_keep(), which
 * does not depend on the order of the tests), and both test with the same
 * per-ray code (pk_test_cell() runs test_full()'s own steps: the quads'
 * sign test, the full test, the mailbox, the other items, child grids
 * walked by walk()), so a primitive gives the same t and bits in both.
 * The single walk's answer is brute force's because it tests every
 * primitive whose hit could beat the best (grid.c's top): such a hit
 * point lies in a cell that holds the primitive (the padding) and that
 * the ray enters before walk_end(). Here each ray tests a superset of
 * those cells: (1) the slices are walked in the rays' order along k, and
 * a ray is dropped only after a block slab whose far plane it crosses
 * past its walk_end() (the single walk's rule, with the slab's far plane,
 * whose t has plane_t()'s bits, for a cell's exit); (2) a ray's segment
 * runs over its part of the grid's box within the walk's widened (t0,
 * t1), widened by the margin along k, and once it has a hit ends at
 * walk_end() (plus the margin): no better hit lies beyond; (3) within a
 * slice, every cell the segment meets is in the frustum's range
 * (pk_range(): the corner products bound every ray's own, and the range
 * is widened by twice the margin), is found from the blocks' words when
 * it holds something, and passes both the box test (pk_cell_rays(), the
 * segment's box widened by the margin) and the line test (pk_line(),
 * also in pk_cell_rays(), four rays at a time with AVX); the union of
 * the boxes only bounds them. The margin is ps->pad, the
 * padding of every primitive's cells (2^-20 of the scene), far above the
 * double rounding of these few operations, so rounding only ever adds
 * cells. A packet's rays all move one way on k (packet() sends the others
 * alone), so no ray needs a slice before one the walk has passed. */
static void packet(const grid_t *g, primset_query_t *q, int n)
{
    const grid_node_t *nd = &g->nodes[0];
    /* the major axis: that of the first and the last ray's directions
     * summed (a tile's corners), by vec_max_axis()'s rule, which the
     * rays' own kz follow */
    double sum[3];
    for (int a = 0; a < 3; a++)
        sum[a] = (double)q[0].r->d[a] + (double)q[n - 1].r->d[a];
    packet_t p;
    double ax = fabs(sum[0]), ay = fabs(sum[1]), az = fabs(sum[2]);
    p.k = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    p.u = p.k == 2 ? 0 : p.k + 1;
    p.v = p.u == 2 ? 0 : p.u + 1;
    p.sg = sum[p.k] < 0 ? -1 : 1;
    const real *o = q[0].r->o;
    const bool o_ok = isfinite(o[0]) && isfinite(o[1]) && isfinite(o[2]);
    for (int a = 0; a < 3; a++)
        p.o[a] = (double)o[a];
    p.margin = g->ps->pad;
    p.n = n > 16 ? (n + 15) / 16 * 16 : (n + 3) / 4 * 4;
    p.live = 0;
    p.wset = 0;
    walk_t w[PK_N]; /* made by pk_walk() where needed */
    const int k = p.k;
#if GRID_QUADS && MESH_WIDE
    p.wo[0] = VW_SET1(o[p.u]);
    p.wo[1] = VW_SET1(o[p.v]);
    p.wo[2] = VW_SET1(o[k]);
#endif
    uint64_t alone = 0;
    for (int i = 0; i < p.n; i += 4)
        p.live |= (uint64_t)pk_setup4(g, &p, q, i, n, o, o_ok, &alone) << i;
    for (; alone; alone &= alone - 1)
        grid_intersect(g, &q[bits_lowest(alone)]);
    if (!p.live)
        return;
    pk_bounds(&p);
    const int res = nd->res[k], step = p.sg > 0 ? 1 : -1;
    int j = cell_of(nd, k, p.o[k] + p.sg * p.S0);
    pk_slab_t sl;
    while (p.live && j >= 0 && j < res) {
        /* the block slab of j: its slices from j on, in the rays' order */
        int bj = j / GRID_BLOCK;
        int jend = step > 0 ? bj * GRID_BLOCK + GRID_BLOCK - 1 : bj * GRID_BLOCK;
        if (jend >= res)
            jend = res - 1;
        double a = pk_plane_s(nd, &p, step > 0 ? j : j + 1);
        double b = pk_plane_s(nd, &p, step > 0 ? jend + 1 : jend);
        if (a > p.S1)
            break;
        int nb = pk_slab_blocks(g, &p, bj, pk_max(a, p.S0), pk_min(b, p.S1),
                                &sl);
        if (nb < 0) {
            /* too wide: the rays left go alone, from the start (with the
             * hits found so far, which can only be kept or beaten) */
            for (uint64_t m = p.live; m; m &= m - 1)
                grid_intersect(g, &q[bits_lowest(m)]);
            return;
        }
        for (; nb > 0; j += step) {
            double sa = pk_plane_s(nd, &p, step > 0 ? j : j + 1);
            double sb = pk_plane_s(nd, &p, step > 0 ? j + 1 : j);
            pk_slice(g, &p, w, q, j, sa, sb, &sl);
            if (j == jend)
                break;
        }
        /* the rays whose walk_end() lies before the slab's far plane are
         * done (dropping them later than the single walk would only
         * costs time: their segments end there) */
        pk_stop(&p, b);
        j = jend + step;
    }
}

void grid_intersect_packet(const grid_t *g, primset_query_t *q, int n)
{
    if (g->ncells == 0 || g->ps->nbounded == 0)
        return;
    for (int i = 0; i < n; i += GRID_PACKET_MAX) {
        int m = n - i < GRID_PACKET_MAX ? n - i : GRID_PACKET_MAX;
        if (m == 1)
            grid_intersect(g, &q[i]);
        else
            packet(g, q + i, m);
    }
}

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
