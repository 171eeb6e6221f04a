/*
 * mesh.h - the triangle mesh of ch. 7: one COBJECT holding many triangles
 * (nprims = the triangle count) over shared vertex arrays, as Wavefront OBJ
 * files (obj.h) and the procedural generators (meshgen.h) produce them.
 * Each triangle is the watertight triangle of triangle.h; the mesh adds
 * interpolated shading normals and texture coordinates, area sampling, and
 * a per-ray form of the watertight test for the grids' inner loop, with
 * its sign test for several triangles at once (SSE2, include/core/simd.h).
 * Tests: tests/mesh/test_mesh.c
 */
#ifndef SVET_MESH_H
#define SVET_MESH_H

#include <stdbool.h>
#include <stdint.h>
#include "materials/cobject.h"
#include "core/error.h"
#include "core/simd.h"
#include "geometry/triangle.h"

/* Largest mesh accepted: indices are int32, and the grids use 31 bits for
 * a primitive's number. */
#define MESH_MAX_VERTICES (1L << 28)
#define MESH_MAX_TRIANGLES (1L << 28)

/* The mesh. The first group of fields is what a loader or generator fills
 * (malloc'd arrays; mesh_new() takes them over); the second is derived by
 * mesh_new().
 *
 * Memory per triangle (float build; double doubles every real):
 *   tri 12 B + alias table 8 B = 20 B per triangle, plus 12 B (p) + 12 B
 *   (n, if any) + 8 B (st, if any) per vertex, and 4 B per triangle for
 *   slot when present. A closed mesh has about half as many vertices as
 *   triangles, so a mesh with normals and texture coordinates costs about
 *   20 + 16 = 36 B per triangle (56 B in double). An acceleration structure
 *   adds its own compact copy of the corners (primset.h, 36 B per triangle)
 *   and its cells (grid.h). mesh_bytes() gives the exact figure;
 *   bench/results/grid.md gives the figure at 1e6 triangles.
 */
typedef struct {
    /* -- given -- */
    int nverts;
    VECTOR3 *p;          /* vertex positions [nverts], finite */
    VECTOR3 *n;          /* unit vertex normals [nverts], or NULL; a zero
                            vector means "none at this vertex": triangles
                            using it are shaded with ng */
    real (*st)[2];       /* texture coordinates [nverts], or NULL; a NaN
                            means "none at this vertex": triangles using it
                            take st from their barycentrics */
    int ntris;
    int32_t (*tri)[3];   /* vertex indices of each triangle, counter-
                            clockwise seen from the front: ng is along
                            (p1 - p0) x (p2 - p0) */
    int32_t *slot;       /* material slot of each triangle (OBJ usemtl:
                            obj.h), or NULL */
    /* -- derived by mesh_new() -- */
    real *alias_prob;    /* Walker's alias table over the triangles, by */
    int32_t *alias;      /* area: pick slot i, keep it with probability
                            alias_prob[i], else take alias[i] */
    double area;         /* total area, summed in double */
    bbox_t bounds;
} mesh_t;

/* Make a mesh COBJECT from m, taking over its arrays (p, n, st, tri, slot:
 * from malloc; on success they belong to the object, and *m is zeroed; on
 * failure they are freed too). The derived fields are computed here.
 * Fails with SVET_ERR_RANGE when a count is negative or above the limits,
 * there is no vertex or no triangle, an index is out of range, a position
 * is NaN or infinite, or a normal is not finite; SVET_ERR_NOMEM when memory
 * runs out. Degenerate (zero-area) triangles are allowed: they have no
 * area, are never hit and never sampled. */
svet_status mesh_new(COBJECT **out, mesh_t *m, svet_error *err);

/* A new mesh of the triangles of src whose slot equals `slot` (all of them
 * when src has no slots and slot is 0), with only the vertices they use, in
 * the same order. For a scene that maps each OBJ material to its own
 * COBJECT. Fails with SVET_ERR_RANGE when src is not a mesh or no triangle
 * has that slot, SVET_ERR_NOMEM. */
svet_status mesh_new_subset(COBJECT **out, const COBJECT *src, int32_t slot,
                            svet_error *err);

/* The mesh data of obj, or NULL when obj is not a mesh. */
const mesh_t *mesh_get(const COBJECT *obj);

/* Bytes the mesh occupies (arrays and the structures around them). */
size_t mesh_bytes(const COBJECT *obj);

/* True when triangle i cannot be hit (triangle_is_degenerate). */
bool mesh_triangle_is_degenerate(const mesh_t *m, int i);

/* --- the per-ray watertight test ---------------------------------------- */

/* What triangle_intersect_watertight() computes from the ray alone, once
 * per ray rather than once per triangle: the axis permutation and the
 * shear of Woop, Benthin, Wald 2013 (their sec. 3, precomputed per ray as
 * the paper suggests). */
typedef struct {
    const ray_t *r;  /* the ray itself, for the fallback */
    int kx, ky, kz;  /* permutation: the ray's largest component is kz */
    real sx, sy, sz; /* shear: x += sx z, y += sy z, z *= sz */
    bool fast;       /* false: d needed rescaling (or is zero or not
                        finite): use triangle_intersect_watertight */
#ifdef SIMD_REAL
    vreal vo[3];     /* o[kx], o[ky], o[kz] in every lane */
    vreal vsx, vsy;  /* sx, sy in every lane (mesh_ray_reject) */
#endif
} mesh_ray_t;

/* Prepare r for mesh_ray_intersect(). This function can't fail. */
static inline void mesh_ray_prepare(mesh_ray_t *mr, const ray_t *r)
{
    mr->r = r;
    int kz = vec_max_axis(r->d);
    real dz = r->d[kz];
    /* triangle.c rescales d when ilogb(d_z) is outside [-16, 16], i.e.
     * |d_z| outside [2^-16, 2^17) (or zero, or not finite); such rays go
     * the slow way, so that both give bit-identical answers. */
    real adz = fabs(dz);
    mr->fast = adz >= REAL_C(0x1p-16) && adz < REAL_C(0x1p17);
    mr->kz = kz;
    mr->kx = kz == 2 ? 0 : kz + 1;
    mr->ky = mr->kx == 2 ? 0 : mr->kx + 1;
    if (mr->fast) {
        /* as triangle_ray_prepare computes them: one division */
        real inv = 1 / dz;
        mr->sx = -r->d[mr->kx] * inv;
        mr->sy = -r->d[mr->ky] * inv;
        mr->sz = inv;
    } else {
        mr->sx = mr->sy = mr->sz = 0;
    }
#ifdef SIMD_REAL
    mr->vo[0] = V_SET1(r->o[mr->kx]);
    mr->vo[1] = V_SET1(r->o[mr->ky]);
    mr->vo[2] = V_SET1(r->o[kz]);
    mr->vsx = V_SET1(mr->sx);
    mr->vsy = V_SET1(mr->sy);
#endif
}

/* The corners of triangle i side by side in q: the layout that
 * mesh_ray_intersect() reads. This function can't fail. */
void mesh_triangle_corners(const mesh_t *m, int i, real q[9]);

/* max for the error bound below: the same value as fmax for the finite,
 * non-negative numbers it gets, without fmax's call (C's fmax must honour
 * NaN, so compilers do not inline it). */
static inline real mesh_max3(real a, real b, real c)
{
    real m = a > b ? a : b;
    return m > c ? m : c;
}

/* The first steps of mesh_ray_intersect() for a fast ray (Woop et al.
 * sec. 3): the corners translated to the ray's origin and sheared (x, y,
 * and az, z before the scaling by sz), and the edge functions e. Shared
 * by the batch's plain lanes (mesh_lane_rejects). */
typedef struct {
    real x[3], y[3], az[3], e[3];
} mesh_edges_t;

static inline void mesh_edges(const real q[9], const mesh_ray_t *mr,
                              mesh_edges_t *v)
{
    const ray_t *r = mr->r;
    const int kx = mr->kx, ky = mr->ky, kz = mr->kz;
    const real sx = mr->sx, sy = mr->sy;
    real a0x = q[kx] - r->o[kx], a0y = q[ky] - r->o[ky];
    real a1x = q[3 + kx] - r->o[kx], a1y = q[3 + ky] - r->o[ky];
    real a2x = q[6 + kx] - r->o[kx], a2y = q[6 + ky] - r->o[ky];
    v->az[0] = q[kz] - r->o[kz];
    v->az[1] = q[3 + kz] - r->o[kz];
    v->az[2] = q[6 + kz] - r->o[kz];
    v->x[0] = a0x + sx * v->az[0], v->y[0] = a0y + sy * v->az[0];
    v->x[1] = a1x + sx * v->az[1], v->y[1] = a1y + sy * v->az[1];
    v->x[2] = a2x + sx * v->az[2], v->y[2] = a2y + sy * v->az[2];
    v->e[0] = v->x[1] * v->y[2] - v->y[1] * v->x[2];
    v->e[1] = v->x[2] * v->y[0] - v->y[2] * v->x[0];
    v->e[2] = v->x[0] * v->y[1] - v->y[0] * v->x[1];
}

/* Exactly triangle_intersect_watertight(q[0..2], q[3..5], q[6..8], r, ...)
 * (the same operations in the same order, so the same bits), for a
 * triangle that is not degenerate: the caller guarantees that, which saves
 * the degeneracy test of every hit. The rare cases that need more work (an
 * edge function rounding to zero; a rescaled ray) call the full test. This
 * function can't fail. */
static inline bool mesh_ray_intersect(const real q[9], const mesh_ray_t *mr,
                                      real tmin, real tmax, real *t,
                                      real b[3])
{
    const ray_t *r = mr->r;
    if (!mr->fast)
        return triangle_intersect_watertight(q, q + 3, q + 6, r, tmin, tmax,
                                             t, b);
    /* Translate to the origin and shear (Woop et al. sec. 3), then the
     * edge functions. A zero may be rounding, and the exact recomputation
     * of all three may change any sign: the full test does it. The
     * product is zero when one of them is (one test, not three), and
     * also when it underflows: then the full test gives the same answer,
     * only slower. */
    mesh_edges_t v;
    mesh_edges(q, mr, &v);
    const real x0 = v.x[0], x1 = v.x[1], x2 = v.x[2];
    const real y0 = v.y[0], y1 = v.y[1], y2 = v.y[2];
    const real a0z = v.az[0], a1z = v.az[1], a2z = v.az[2];
    const real e0 = v.e[0], e1 = v.e[1], e2 = v.e[2];
    if (e0 * e1 * e2 == 0)
        return triangle_intersect_watertight(q, q + 3, q + 6, r, tmin, tmax,
                                             t, b);
    /* | and & rather than || and &&: one branch, not six (the signs are
     * as good as random, so each branch would be mispredicted often) */
    if (((e0 < 0) | (e1 < 0) | (e2 < 0)) & ((e0 > 0) | (e1 > 0) | (e2 > 0)))
        return false;
    real det = e0 + e1 + e2;
    if (det == 0 || !isfinite(det))
        return false;
    const real sz = mr->sz;
    real z0 = sz * a0z, z1 = sz * a1z, z2 = sz * a2z;
    real tt = (e0 * z0 + e1 * z1 + e2 * z2) / det;
    if (!isfinite(tt))
        return false;
    /* Reject early what is outside (tmin, tmax) before the error bound:
     * the bound only ever rejects more, so the answer is unchanged. */
    if (!(tt > tmin && tt < tmax))
        return false;
    if (tmin >= 0) {
        /* pbrt-v3 sec. 3.9.6 with triangle.c's change of units: keep the
         * two in step (tests/mesh/test_mesh.c checks that they agree). */
        real max_z = mesh_max3(fabs(z0), fabs(z1), fabs(z2));
        real max_az = mesh_max3(fabs(a0z), fabs(a1z), fabs(a2z));
        real max_x = mesh_max3(fabs(x0), fabs(x1), fabs(x2));
        real max_y = mesh_max3(fabs(y0), fabs(y1), fabs(y2));
        real dz = ray_gamma(3) * max_z;
        real dx = ray_gamma(5) * (max_x + max_az);
        real dy = ray_gamma(5) * (max_y + max_az);
        real de = 2 * (ray_gamma(2) * max_x * max_y + dy * max_x +
                       dx * max_y);
        real max_e = mesh_max3(fabs(e0), fabs(e1), fabs(e2));
        real dt = 3 * (ray_gamma(3) * max_e * max_z + de * max_z +
                       dz * max_e) / fabs(det);
        if (tt <= dt)
            return false;
    }
    *t = tt;
    b[0] = e0 / det;
    b[1] = e1 / det;
    b[2] = e2 / det;
    return true;
}

/* --- several triangles at once ------------------------------------------- */

/* Triangles mesh_ray_reject() takes at once. */
#define MESH_BATCH 4

/* The edge functions of mesh_ray_intersect() for lane j of a batch and
 * whether its sign test rejects: exactly the scalar operations, in the
 * scalar order (the translation, the shear, the three 2D cross products,
 * the product p of the three), then the signs, read from the sign bits: a
 * lane is rejected when p is less or greater than zero (neither zero nor
 * NaN) and two of the three sign bits differ. That is
 * mesh_ray_intersect()'s rule, one negative and one positive where p is
 * not zero, on every lane but those whose p is NaN (an edge function is
 * NaN, or one is zero and another infinite), which are kept here and go
 * on to mesh_ray_intersect(), where they find no hit either; where p is
 * neither, none of the three is zero (a zero factor makes p zero or NaN),
 * so the sign bits are the signs, infinite ones included. In vectors the
 * sign bits cost two XORs and an OR instead of six comparisons and four
 * ORs (3 to 4 sign tests a camera ray at 1e6 triangles). */
static inline bool mesh_lane_rejects(const real q[9], const mesh_ray_t *mr)
{
    mesh_edges_t v;
    mesh_edges(q, mr, &v);
    const real e0 = v.e[0], e1 = v.e[1], e2 = v.e[2];
    real p = e0 * e1 * e2;
    return ((p < 0) | (p > 0)) &&
           ((signbit(e0) != signbit(e1)) | (signbit(e0) != signbit(e2)));
}

/* mesh_ray_reject() in plain C, lane by lane: kept for machines without
 * SSE2, and as the reference the tests compare the vector code with. */
static inline unsigned mesh_ray_reject_plain(const real *const q[MESH_BATCH],
                                             const mesh_ray_t *mr)
{
    if (!mr->fast)
        return 0;
    unsigned m = 0;
    for (int j = 0; j < MESH_BATCH; j++)
        m |= (unsigned)mesh_lane_rejects(q[j], mr) << j;
    return m;
}

#ifdef SIMD_REAL
/* The 9 corner coordinates (x0 y0 z0 x1 ... z2) of the VLANES triangles
 * q[0 ..) as 9 vectors, lane j from q[j]. */
static inline void mesh_lanes_load(const real *const *q, vreal c[9])
{
#ifdef SVET_DOUBLE
    for (int k = 0; k < 9; k++)
        c[k] = _mm_loadh_pd(_mm_load_sd(q[0] + k), q[1] + k);
#else
    /* two unaligned loads per triangle (q[0..3], q[4..7]) and two 4 x 4
     * transposes; q[8] lane by lane */
    __m128 r0 = _mm_loadu_ps(q[0]), r1 = _mm_loadu_ps(q[1]);
    __m128 r2 = _mm_loadu_ps(q[2]), r3 = _mm_loadu_ps(q[3]);
    __m128 s0 = _mm_loadu_ps(q[0] + 4), s1 = _mm_loadu_ps(q[1] + 4);
    __m128 s2 = _mm_loadu_ps(q[2] + 4), s3 = _mm_loadu_ps(q[3] + 4);
    _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
    _MM_TRANSPOSE4_PS(s0, s1, s2, s3);
    __m128 u01 = _mm_unpacklo_ps(_mm_load_ss(q[0] + 8), _mm_load_ss(q[1] + 8));
    __m128 u23 = _mm_unpacklo_ps(_mm_load_ss(q[2] + 8), _mm_load_ss(q[3] + 8));
    c[0] = r0, c[1] = r1, c[2] = r2, c[3] = r3;
    c[4] = s0, c[5] = s1, c[6] = s2, c[7] = s3;
    c[8] = _mm_movelh_ps(u01, u23);
#endif
}

/* The sign test of mesh_lane_rejects() on corners already permuted (p0 =
 * (x, y, z) of corner 0 in the ray's kx, ky, kz order, ...), o the ray's
 * origin in that order and sx, sy its shear, in every lane: written once
 * for vectors of type T and the macros P_ADD, P_SUB, ... of simd.h (P is
 * V or VW), and made for SSE2's vectors and, where they are wider, for
 * the widest (MESH_WIDE). */
#define MESH_DEFINE_LANES_REJECT(NAME, T, P)                                  \
    static inline unsigned NAME(T p0x, T p0y, T p0z, T p1x, T p1y, T p1z,     \
                                T p2x, T p2y, T p2z, const T o[3], T sx,      \
                                T sy)                                         \
    {                                                                         \
        T a0z = P##_SUB(p0z, o[2]), a1z = P##_SUB(p1z, o[2]);                 \
        T a2z = P##_SUB(p2z, o[2]);                                           \
        T x0 = P##_ADD(P##_SUB(p0x, o[0]), P##_MUL(sx, a0z));                 \
        T y0 = P##_ADD(P##_SUB(p0y, o[1]), P##_MUL(sy, a0z));                 \
        T x1 = P##_ADD(P##_SUB(p1x, o[0]), P##_MUL(sx, a1z));                 \
        T y1 = P##_ADD(P##_SUB(p1y, o[1]), P##_MUL(sy, a1z));                 \
        T x2 = P##_ADD(P##_SUB(p2x, o[0]), P##_MUL(sx, a2z));                 \
        T y2 = P##_ADD(P##_SUB(p2y, o[1]), P##_MUL(sy, a2z));                 \
        T e0 = P##_SUB(P##_MUL(x1, y2), P##_MUL(y1, x2));                     \
        T e1 = P##_SUB(P##_MUL(x2, y0), P##_MUL(y2, x0));                     \
        T e2 = P##_SUB(P##_MUL(x0, y1), P##_MUL(y0, x1));                     \
        T nz = P##_NEQ(P##_MUL(P##_MUL(e0, e1), e2), P##_SET1(0));            \
        T mixed = P##_OR(P##_XOR(e0, e1), P##_XOR(e0, e2));                   \
        return (unsigned)P##_MASK(P##_AND(nz, mixed));                        \
    }

/* F called with the 9 corner vectors L(0) ... L(8) (x0 y0 z0 x1 ... z2)
 * permuted for the ray (kz its largest axis, kx = kz + 1, ky = kx + 1,
 * mod 3), then the other arguments. The three permutations are spelled
 * out so that the vectors stay in registers (no array, no copy). */
#define MESH_PERMUTED(kz, F, L, ...)                                          \
    ((kz) == 0   ? F(L(1), L(2), L(0), L(4), L(5), L(3), L(7), L(8), L(6),    \
                     __VA_ARGS__)                                             \
     : (kz) == 1 ? F(L(2), L(0), L(1), L(5), L(3), L(4), L(8), L(6), L(7),    \
                     __VA_ARGS__)                                             \
                 : F(L(0), L(1), L(2), L(3), L(4), L(5), L(6), L(7), L(8),    \
                     __VA_ARGS__))

MESH_DEFINE_LANES_REJECT(mesh_lanes_reject_perm, vreal, V)

/* mesh_lanes_reject_perm() on the 9 corner vectors c (x0 y0 z0 x1 ...
 * z2, as mesh_lanes_load() gives them). */
static inline unsigned mesh_lanes_reject_vec(const vreal c[9],
                                             const mesh_ray_t *mr)
{
#define MESH_C_(k) c[k]
    return MESH_PERMUTED(mr->kz, mesh_lanes_reject_perm, MESH_C_, mr->vo,
                         mr->vsx, mr->vsy);
#undef MESH_C_
}

/* mesh_lane_rejects() for VLANES triangles at once, each V_ macro one
 * IEEE operation of the scalar code (simd.h), in its order. */
static inline unsigned mesh_lanes_reject(const real *const *q,
                                         const mesh_ray_t *mr)
{
    vreal c[9];
    mesh_lanes_load(q, c);
    return mesh_lanes_reject_vec(c, mr);
}

/* The same for VLANES triangles stored side by side, as a grid cell keeps
 * them (grid.h): coordinate k (x0 y0 z0 x1 ... z2) of lane j is
 * soa[k VLANES + j]. No gather, no transpose: 9 loads. For a ray that is
 * not fast, no lane is rejected. This function can't fail. */
static inline unsigned mesh_lanes_reject_soa(const real *soa,
                                             const mesh_ray_t *mr)
{
    if (!mr->fast)
        return 0;
#define MESH_SOA_(k) V_LOAD(soa + (k) * VLANES)
    return MESH_PERMUTED(mr->kz, mesh_lanes_reject_perm, MESH_SOA_, mr->vo,
                         mr->vsx, mr->vsy);
#undef MESH_SOA_
}

/* The widest vectors, where they hold twice SSE2's (AVX: 8 floats, 4
 * doubles): the same sign test on two blocks of VLANES triangles side by
 * side at once, lanes 0 .. VLANES-1 from the first block, the others
 * from the second. */
#if VWLANES == 2 * VLANES
#define MESH_WIDE 1

/* The ray's origin (permuted) and shear in every lane of the widest
 * vectors: made once per ray by the caller, which keeps it on its stack
 * (mesh_ray_t does not hold it: a struct on the heap need not be aligned
 * for these vectors). */
typedef struct {
    vwreal o[3], sx, sy;
} mesh_wide_ray_t;

/* This function can't fail. */
static inline void mesh_wide_ray_prepare(mesh_wide_ray_t *w,
                                         const mesh_ray_t *mr)
{
    w->o[0] = VW_SET1(mr->r->o[mr->kx]);
    w->o[1] = VW_SET1(mr->r->o[mr->ky]);
    w->o[2] = VW_SET1(mr->r->o[mr->kz]);
    w->sx = VW_SET1(mr->sx);
    w->sy = VW_SET1(mr->sy);
}

MESH_DEFINE_LANES_REJECT(mesh_wide_reject_perm, vwreal, VW)

/* mesh_lanes_reject_soa() of the blocks lo and hi (each as
 * mesh_lanes_reject_soa() reads one) at once: bits 0 .. VLANES-1 are lo's
 * mask, the next VLANES hi's, bit for bit. For a ray that is not fast,
 * no lane is rejected. This function can't fail. */
static inline unsigned mesh_wide_reject_soa2(const real *lo, const real *hi,
                                             const mesh_ray_t *mr,
                                             const mesh_wide_ray_t *w)
{
    if (!mr->fast)
        return 0;
#define MESH_SOA2_(k) VW_LOAD2(lo + (k) * VLANES, hi + (k) * VLANES)
    return MESH_PERMUTED(mr->kz, mesh_wide_reject_perm, MESH_SOA2_, w->o,
                         w->sx, w->sy);
#undef MESH_SOA2_
}
#else
#define MESH_WIDE 0
#endif
#else
#define MESH_WIDE 0
#endif

/* Which of the triangles q[0 .. MESH_BATCH) the ray surely misses: bit j
 * is set only when mesh_ray_intersect(q[j], mr, ...) returns false at its
 * sign test, whatever tmin and tmax (the edge functions differ in sign,
 * none is zero); a lane left clear must still go through
 * mesh_ray_intersect(), which decides. Every lane computes the scalar
 * test's operations in the scalar order (SSE2 has no fused multiply-add,
 * and the build has -ffp-contract=off), so the edge functions are the
 * scalar ones bit for bit and so is the mask: with SSE2 4 floats or 2
 * doubles at a time, else mesh_ray_reject_plain(). tests/mesh/test_mesh.c
 * compares the two lane by lane. For a ray that is not fast, no lane is
 * rejected. This function can't fail. */
static inline unsigned mesh_ray_reject(const real *const q[MESH_BATCH],
                                       const mesh_ray_t *mr)
{
#ifdef SIMD_REAL
    if (!mr->fast)
        return 0;
    unsigned m = 0;
    for (int j = 0; j < MESH_BATCH; j += VLANES)
        m |= mesh_lanes_reject(q + j, mr) << j;
    return m;
#else
    return mesh_ray_reject_plain(q, mr);
#endif
}

#endif
