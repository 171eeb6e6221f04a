/*
 * grid.h - the grids of ch. 7 ("Hierarchical grids"): the uniform grid
 * walked by the 3D-DDA of Amanatides & Woo ("A fast voxel traversal
 * algorithm for ray tracing", Eurographics 1987), and the hierarchical
 * grid of Jevans & Wyvill ("Adaptive voxel subdivision for ray tracing",
 * Graphics Interface 1989), in which a cell holding too many primitives
 * holds a grid of its own. Both index a primset_t; the renderer reaches
 * them through accel.h, in the programs that offer them (grid_accels).
 * Coherent camera rays can also walk the grid together, in packets
 * (grid_intersect_packet: the coherent grid traversal of Wald, Ize,
 * Kensler, Knoll & Parker, SIGGRAPH 2006), with the same answers.
 * Built in src/accel/grid_build.c, walked in src/accel/grid.c (the plain
 * walk), src/accel/fast/grid_walk.c (the fast walk) and
 * src/accel/fast/grid_packet.c (packets).
 * Tests: tests/accel/test_grid.c (agreement with brute force: tests/accel/test_accel.c)
 */
#ifndef SVET_GRID_H
#define SVET_GRID_H

#include <stddef.h>
#include <stdint.h>
#include "core/error.h"
#include "accel/accel.h"
#include "accel/primset.h"

/* Cells per axis = about k N^(1/3) over the box's aspect (N primitives):
 * k^3 N cells in all (Cleary & Wyvill 1988). With eight triangles to one
 * sign test (the quads), a coarser grid walks fewer cells for little more
 * testing: 1.5 runs about as fast as 2 on every size and kind of ray,
 * faster on camera rays at 1e6, with less memory (`make bench-grid
 * BENCH_ARGS=--tune`; the tables are in bench/results/grid.md, "Why the
 * defaults"). */
#define GRID_K_DEFAULT 1.5
/* Hierarchical grid (Jevans & Wyvill 1989): the top level is the uniform
 * grid (k = HGRID_K_DEFAULT); a cell with more than HGRID_LEAF_DEFAULT
 * primitives gets a child grid of HGRID_CHILD_K_DEFAULT n^(1/3) cells per
 * axis for its n primitives, at most HGRID_DEPTH_DEFAULT levels below the
 * top. A coarser top level takes fewer steps through empty space but
 * leaves more to the children; what the sweep showed for each setting is
 * in bench/results/grid.md ("Why the defaults"). */
#define HGRID_K_DEFAULT 2.0
#define HGRID_CHILD_K_DEFAULT 1.5
#define HGRID_LEAF_DEFAULT 32
#define HGRID_DEPTH_DEFAULT 2
/* No grid has more cells than this, at any level. */
#define GRID_MAX_CELLS (1L << 25)
/* The most cell entries the bounds of n primitives may span in the top
 * level: a finer grid over large primitives is coarsened (k times 0.7)
 * until they fit, so that no input makes the build run for long. */
#define GRID_SPAN_MAX(n) \
    ((double)(n) * 32 > 0x1p27 ? 0x1p27 : fmax(0x1p22, (double)(n) * 32))

/* Quads (below) only for scenes of at least this many mesh triangles.
 * They copy every triangle's corners into each of its cells (about 4.7
 * times the corners' memory): where the corners come from main memory
 * anyway that costs little and saves the gathers, but where the corners
 * and the grid fit the caches and the quads do not, incoherent rays wait
 * on memory instead. The threshold lies between the sizes where each
 * was measured (bench/results/grid.md, "Why the defaults"). */
#define GRID_QUAD_MIN_DEFAULT 500000

typedef struct {
    double k;       /* top level: cells per axis = k N^(1/3) */
    long quad_min;  /* quads where at least this many mesh triangles */
    int max_depth;  /* 0: uniform grid; > 0: levels of child grids */
    int leaf_max;   /* a cell with more primitives gets a child grid */
    double child_k; /* child grid: cells per axis = child_k n^(1/3) */
} grid_params_t;

/* The uniform grid's defaults (max_depth 0) and the hierarchical grid's. */
void grid_params_uniform(grid_params_t *p);
void grid_params_hierarchical(grid_params_t *p);

/* One grid: the top level, or a child of a cell. Coordinates in double,
 * whatever real is, so that the walk decides cells far more finely than
 * the primitives' own rounding (grid.c's opening comment). */
typedef struct {
    double min[3];      /* lower corner */
    double w[3];        /* cell size per axis */
    double inv_w[3];    /* 1 / w */
    double max[3];      /* upper corner: min + res w */
    int res[3];         /* cells per axis */
    int nb[3];          /* blocks of GRID_BLOCK^3 cells per axis: ceil(res /
                           GRID_BLOCK); the last may reach past res */
    uint32_t first;     /* cells of the nodes before it */
    uint32_t bfirst;    /* its blocks are blocks[bfirst ..) */
    int depth;          /* 0 for the top level */
} grid_node_t;

/* Cells per axis of a block (macro-cell): a block's 4 x 4 x 4 cells have
 * one bit each in a 64-bit word, so the walk tests a cell without touching
 * memory and crosses a block with no cell in it in one step
 * (fast/grid_walk.c). */
#define GRID_BLOCK 4

/* An item with this bit set is a child grid's node number; otherwise the
 * number of a primitive in the primset. */
#define GRID_CHILD ((uint32_t)1 << 31)

/* A block of GRID_BLOCK^3 cells: bit x + 4 y + 16 z of its word in
 * bmask is set when the cell at (x, y, z) within the block holds
 * something; the non-empty cells of all blocks are numbered in block
 * order, then bit order: the k-th set bit of block b is cell bbase[b] + k.
 * Two arrays, so that the walk's words (8 bytes a block) share the cache
 * with nothing it reads less often. */

/* Where the vectors hold MESH_BATCH reals (float with SSE2), and the
 * scene has at least grid_params_t.quad_min mesh triangles, every
 * non-empty cell also keeps its mesh triangles' corners, MESH_BATCH
 * triangles side by side as mesh_lanes_reject_soa() reads them (and
 * mesh_wide_reject_soa2(), two quads at once, with AVX): the walk
 * tests a cell's triangles without gathering their corners from the
 * primset (one cache line each, scattered) or transposing them. Without
 * quads it gathers MESH_BATCH triangles the mailbox lets through and
 * tests them with mesh_ray_reject(). */
#if defined(SIMD_REAL) && VLANES == MESH_BATCH && defined(SVET_SIMD)
#define GRID_QUADS 1
#else
#define GRID_QUADS 0
#endif

/* A triangle in more cells than this stays out of the quads (grid.c). */
#define GRID_QUAD_SPAN 8

/* A lane of a grid_quad_t holding no triangle (the last quad of a cell
 * is padded with copies of its first lane). */
#define GRID_QUAD_PAD UINT32_MAX
/* Set in qstart[s] when cell s holds items other than its quads' mesh
 * triangles (large triangles, other primitives, a child grid): the walk
 * then reads its items too. */
#define GRID_MORE ((uint32_t)1 << 31)

/* MESH_BATCH mesh triangles of one cell: coordinate k (x0 y0 z0 x1 ... z2)
 * of lane j is c[k MESH_BATCH + j]. 160 bytes in float. */
typedef struct {
    real c[9 * MESH_BATCH];
    uint32_t ref[MESH_BATCH]; /* primitive numbers, or GRID_QUAD_PAD */
} grid_quad_t;

/* The grid: flat arrays. An empty cell costs a bit, an empty block 12
 * bytes (3/16 byte a cell); a non-empty cell 4 bytes plus 4 per item,
 * and where GRID_QUADS 4 more and 160 per quad of its triangles. */
typedef struct {
    const primset_t *ps;  /* the primitives (borrowed) */
    grid_node_t *nodes;   /* nodes[0] is the top level */
    uint32_t nnodes;
    uint64_t *bmask;      /* every node's blocks: which cells are full */
    uint32_t *bbase;      /*   and the number of the first full one */
    uint32_t nblocks;
    uint32_t *cstart;     /* non-empty cell s holds items[cstart[s] ..
                             cstart[s + 1]) */
    uint32_t nfull;       /* non-empty cells */
    uint32_t *items;      /* primitive numbers, child markers last */
    uint32_t nitems;
    grid_quad_t *quads;   /* with quads: non-empty cell s's mesh
                             triangles are quads[qstart[s] & ~GRID_MORE ..
                             qstart[s + 1] & ~GRID_MORE); else NULL */
    uint32_t *qstart;
    uint32_t nquads;
    uint64_t *qout;       /* bit t % 64 of word t / 64: mesh triangle t is
                             in more than GRID_QUAD_SPAN cells and in no
                             quad (tested from the items) */
    uint32_t ncells;      /* cells of every node, empty or not (a cell's
                             items: grid_cell_items()) */
    double diag;          /* diagonal of the top level */
    /* statistics of the build */
    int depth;            /* deepest level */
    uint32_t max_items;   /* most primitives in one cell */
    uint32_t empty_cells;
} grid_t;

/* The items of cell c of node n (c = x + res_x (y + res_y z)):
 * items[*begin .. *end), empty when the cell is. This function can't
 * fail. */
void grid_cell_items(const grid_t *g, uint32_t n, long c, uint32_t *begin,
                     uint32_t *end);

/* Build a grid over ps (whose bounds must still be there). Fails with
 * SVET_ERR_NOMEM, or SVET_ERR_UNSUPPORTED when the scene's extent does not
 * fit a double (then use brute force). ps must outlive the grid. */
svet_status grid_build(grid_t **out, const primset_t *ps,
                       const grid_params_t *p, svet_error *err);

/* Nearest hit: q (primset_query_init) ends with the nearest hit of the
 * primitives in the grid; the primset's unbounded primitives are the
 * caller's. Returns q->found. This function can't fail. */
bool grid_intersect(const grid_t *g, primset_query_t *q);

/* Any hit in (q->tmin, q->tmax); stops at the first. This function can't
 * fail. */
bool grid_occluded(const grid_t *g, primset_query_t *q);

/* grid_intersect() and grid_occluded() by the plain walk of grid.c, the
 * 3D-DDA of Amanatides & Woo cell by cell, in every build: the same
 * answers (found, ref, t and bits of the hit), which the default build
 * gets faster from the walk by blocks (fast/grid_walk.c). q->cells counts
 * the cells it visits, every level's. These functions can't fail. */
bool grid_intersect_plain(const grid_t *g, primset_query_t *q);
bool grid_occluded_plain(const grid_t *g, primset_query_t *q);

/* The most rays grid_intersect_packet() takes at once. */
#define GRID_PACKET_MAX 64

/* Nearest hits of n rays (q[0 .. n), each from primset_query_init()) at
 * once, for coherent rays with one origin (a pinhole camera's: a tile of
 * 8 x 8 pixels, say, the fastest size at 1e6 triangles here; the rays in
 * any order, which only the speed sees): each q[i] ends exactly as
 * grid_intersect(g, &q[i]) leaves it (found, ref, t and bits of the
 * hit), bit for bit. The coherent grid traversal of Wald, Ize, Kensler,
 * Knoll & Parker ("Ray tracing animated scenes using coherent grid
 * traversal", SIGGRAPH 2006): one walk, slice by slice of cells along the
 * packet's major axis, over the cells the rays' frustum may cross; each
 * non-empty cell tested, with the single walk's own per-ray test, only
 * for the rays that may pass through it. Only the top level walks by
 * packets: a cell holding a child grid (hierarchical grid) is walked ray
 * by ray with each ray's best hit so far. Rays that do not share the
 * first ray's origin (its bytes: -0 for +0 goes alone too), or whose
 * largest direction component is not on the packet's major axis
 * with its sign (or is not finite, or ties with another axis that the
 * triangle test takes for the largest, or lies outside the triangle
 * test's fast range, 2^-16 to 2^17: mesh_ray_prepare), are traced alone by
 * grid_intersect(); so are all the rays left when the frustum grows
 * wider than 64 blocks of a slab (a very wide packet).
 * n may be anything: n <= 0 does nothing, more than GRID_PACKET_MAX goes
 * GRID_PACKET_MAX at a time. This function can't fail. */
void grid_intersect_packet(const grid_t *g, primset_query_t *q, int n);

/* Bytes the grid holds. */
size_t grid_bytes(const grid_t *g);

/* NULL is allowed. */
void grid_free(grid_t *g);

/* --- the grids as acceleration structures (accel.h) ---------------------- */

/* The uniform grid (ACCEL_GRID) and the hierarchical grid (ACCEL_HGRID)
 * as accel.h's tables: accel_params_t's grid_k, hgrid_* numbers over the
 * defaults above. A program that offers the grids passes grid_accels (or
 * allparts.h's list, which holds it) as accel_params_t.structures. */
extern const accel_ops_t grid_uniform_accel;
extern const accel_ops_t grid_hierarchical_accel;
/* Both, NULL-terminated. */
extern const accel_ops_t *const grid_accels[];

#endif
