/*
 * fast/grid_packet.c - ch. 7: packets of coherent camera rays walked
 * through the grid together, grid_intersect_packet(): the coherent grid
 * traversal of Wald, Ize, Kensler, Knoll & Parker ("Ray tracing animated
 * scenes using coherent grid traversal", SIGGRAPH 2006). What it adds to
 * the single walk (fast/grid_walk.c): one walk for up to GRID_PACKET_MAX
 * rays with one origin, slice by slice of cells along their major axis,
 * over the cells the rays' frustum may cross; each non-empty cell found
 * once and tested, with the single walk's own per-ray code, only for the
 * rays that may pass through it; with AVX four rays' set-up and tests at
 * a time. The same answers as grid_intersect(), bit for bit (the argument
 * is above packet()). Left out of the build by `make SIMD=off`, where
 * grid.c traces a packet's rays one by one.
 * Tests: tests/accel/test_grid.c
 */
#include "../grid_walk.h"

#include <string.h>

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

/* Ray i's walk_t, made on first use: the one grid_query() would make as
 * the packet began (the same tmax), for the single walk's code (child
 * grids, a cell's other items, cells without quads). */
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
 * temporaries spill around them (the same arithmetic, fewer moves). */
#if defined(__GNUC__) || defined(__clang__)
#define GRID_FROM_MEMORY(x) __asm__("" : : "r"(x) : "memory")
#else
#define GRID_FROM_MEMORY(x) ((void)0)
#endif

/* Test non-empty cell f for the packet's rays `rays`: grid_test_full() of
 * each, with the loops turned inside out where the cell has quads: each
 * pair of quads (or quad) taken once and the rays run through it, so that
 * the cell's quads are found and a call made once a cell, not once a ray.
 * The same per-ray tests (mesh_wide_reject_soa2, mesh_lanes_reject_soa,
 * test_lanes, grid_test_items: the same bits and the same mailbox), in
 * another
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
            grid_test_items(g, pk_walk(g, p, w, q, r), &q[r],
                      g->items + g->cstart[f],
                      g->cstart[f + 1] - g->cstart[f], false);
        }
        return;
    }
#endif
    for (uint64_t m = rays; m; m &= m - 1) {
        int r = bits_lowest(m);
        grid_test_full(g, pk_walk(g, p, w, q, r), &q[r], f, false);
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
        walk_t wl; /* grid_query()'s values, but for the wide ray */
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
 * per-ray code (pk_test_cell() runs grid_test_full()'s own steps: the quads'
 * sign test, the full test, the mailbox, the other items, child grids
 * walked by grid_walk_node()), so a primitive gives the same t and bits in both.
 * The single walk's answer is brute force's because it tests every
 * primitive whose hit could beat the best (grid.c's opening comment): such a hit
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
