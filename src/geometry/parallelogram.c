/*
 * parallelogram.c - the parallelogram of app. D as two triangles under the
 * watertight test of Woop, Benthin, Wald 2013 (a departure from the book's
 * plane-then-inside test, which leaks along shared edges), with points
 * rebuilt from barycentrics (pbrt-v3 sec. 3.9.5).
 * Tests: tests/geometry/test_parallelogram.c; vectors: tests/vectors/parallelogram.csv
 */
#include "geometry/parallelogram.h"

#include <stdlib.h>

#include "geometry/shape.h"
#include "core/simd.h"

/* What the early rejections below read of a parallelogram, side by side:
 * in the shape, and copied into a batch for brute force. */
typedef struct {
    VECTOR3 n;       /* unit e1 x e2, as in the shape */
    VECTOR3 c0;      /* corner c0 */
    real h_lo, h_hi; /* min and max of the computed n . c_i: the slab
                        h_lo <= n . p <= h_hi holds the parallelogram */
    real h_mid, h_half; /* its middle plane n . p = h_mid, half-width */
    real c_max;      /* max |c_i| over corners and axes */
    VECTOR3 a, b;    /* dual to e1, e2 in the plane: (p - c0) . a = s,
                        (p - c0) . b = t for p = c0 + s e1 + t e2 */
    real a1, b1;     /* |a|_1, |b|_1, rounded up */
    real k_area;     /* 2 / (the smaller of the two triangles' areas),
                        rounded up; infinite when that is not positive or
                        the quotient overflows (stays_before()) */
} para_cull_t;

typedef struct {
    VECTOR3 c[4];   /* corners c0 c1 c2 c3 */
    VECTOR3 e1, e2; /* c1 - c0, c3 - c0 */
    VECTOR3 n;      /* unit e1 x e2 */
    VECTOR3 u, v;   /* the frame of every point: shape_frame(n, e1) */
    bool degenerate[2]; /* triangle_is_degenerate of A and B: never hit */
    real cs[3][4];  /* the corners by axis, cs[k][i] = c[i][k]: a vector
                       of the four along each axis (shear_corners()) */
    real area;
    para_cull_t k;   /* what the early rejections read */
} para_shape;

/* The surface point at (s, t): in triangle A = (c0, c1, c2) where s >= t,
 * with barycentrics (1 - s, s - t, t), else in B = (c0, c2, c3) with
 * (1 - t, s, t - s). Rebuilt on the triangle, so that it lies on the very
 * surface the intersection test sees, with triangle_point's bound. */
static void point_at(const para_shape *sh, real s, real t, VECTOR3 p,
                     VECTOR3 p_error)
{
    if (s >= t) {
        real b[3] = { 1 - s, s - t, t };
        triangle_point(p, p_error, sh->c[0], sh->c[1], sh->c[2], b);
    } else {
        real b[3] = { 1 - t, s, t - s };
        triangle_point(p, p_error, sh->c[0], sh->c[2], sh->c[3], b);
    }
}

static real clamp01(real x)
{
    return real_min(real_max(x, REAL_C(0.0)), REAL_C(1.0));
}

/* The edge functions of one triangle have mixed signs: the ray passes
 * outside it (triangle_hit_sheared's inside test). */
static bool mixed(real e0, real e1, real e2)
{
    return (e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0);
}

/* (s, t) of a hit of triangle A or B from its barycentrics:
 * A: p = c0 + (b1 + b2) e1 + b2 e2; B: p = c0 + b1 e1 + (b1 + b2) e2. */
static void st_of(int tri, const real b[3], real st[2])
{
    st[0] = tri == 0 ? b[1] + b[2] : b[1];
    st[1] = tri == 0 ? b[2] : b[1] + b[2];
}

/* The two triangles one after the other, each with its own exact
 * recomputation of a zero edge function (triangle.c): the way of a ray
 * through a corner, an edge or the diagonal. */
static bool two_triangles(const para_shape *sh, const triangle_ray_t *pr,
                          real tmin, real tmax, real *t, real st[2])
{
    real b[3];
    bool any = false;
    if (triangle_intersect_prepared(sh->c[0], sh->c[1], sh->c[2], pr, tmin,
                                    tmax, t, b)) {
        any = true;
        tmax = *t; /* B only if nearer */
        st_of(0, b, st);
    }
    if (triangle_intersect_prepared(sh->c[0], sh->c[2], sh->c[3], pr, tmin,
                                    tmax, t, b)) {
        any = true;
        st_of(1, b, st);
    }
    return any;
}

/* Scale of the slab's padding below, in units of the unit roundoff. */
#define SLAB_PAD (128 * REAL_UNIT_ROUNDOFF)
#define DIR_PAD (16 * REAL_UNIT_ROUNDOFF)

/* What the two plane tests below need of the ray: max|o| and max|d|,
 * the same for every parallelogram (a batch computes them once per ray),
 * and n . o, n . d. */
typedef struct {
    real o_max, d_max;
} ray_size_t;

typedef struct {
    real s, dn, o_max, d_max;
} plane_ray_t;

static inline void ray_size(const ray_t *r, ray_size_t *rs)
{
    rs->o_max = real_max(fabs(r->o[X]),
                         real_max(fabs(r->o[Y]), fabs(r->o[Z])));
    rs->d_max = real_max(fabs(r->d[X]),
                         real_max(fabs(r->d[Y]), fabs(r->d[Z])));
}

static inline void plane_ray(const para_cull_t *k, const ray_t *r,
                             const ray_size_t *rs, plane_ray_t *pl)
{
    pl->s = SVECTOR3(k->n, r->o);
    pl->dn = SVECTOR3(k->n, r->d);
    pl->o_max = rs->o_max;
    pl->d_max = rs->d_max;
}

/* The two tests below rest on one fact of the watertight test
 * (triangle.c): it reports a hit only where the exact ray meets the
 * triangle whose corners are the computed sheared ones, i.e. each corner
 * moved across the ray (along the axes kx, ky) by at most
 * xi = gamma(5) (max|x| + max|a_z|) <= 3 gamma(5) A, A = max|c_i - o|
 * <= c_max + max|o| (|sx|, |sy| <= 1). Every point of that triangle has
 * n . p within eta = (|n_kx| + |n_ky|) xi < 22 u A of [h_lo, h_hi],
 * beyond the gamma(3) sqrt(3) c_max < 6 u c_max to which the computed
 * n . c_i are exact; and it lies within sqrt(2) xi of the parallelogram.
 * n . o and n . d are computed within sqrt(3) gamma(3) max|o| and
 * sqrt(3) gamma(3) max|d|, less than 6 u of each. */

/* True when the ray leaves the parallelogram's plane behind it: its
 * origin lies beyond the slab h_lo <= n . p <= h_hi (padded) and it
 * moves away from it, so no hit at t > 0 can be reported. A test of a
 * few products before any shear, true for about half the parallelograms
 * of a closed room. Why no reported hit is lost: the watertight test's
 * error bound dt makes sure the ray meets the moved triangle at t > 0,
 * where n . p = n . o + t n . d >= n . o > h_hi + eta when n . d >= 0. So
 * a pad of 128 u (c_max + max|o|), more than three times the 34 u needed
 * with the rounding of the test's own sums, and n . d >= 16 u max|d|
 * keep every reported hit. */
static inline bool leaves_plane(const para_cull_t *k, const plane_ray_t *pl)
{
    real pad = SLAB_PAD * (k->c_max + pl->o_max);
    real dpad = DIR_PAD * pl->d_max;
    /* a NaN anywhere makes both comparisons false: no early answer. & and
     * | rather than && and ||: no branches, so that a batch's loop
     * vectorises (the same values either way) */
    return ((pl->s > k->h_hi + pad) & (pl->dn >= dpad)) |
           ((pl->s < k->h_lo - pad) & (pl->dn <= -dpad));
}

/* True when the ray's line crosses the middle plane n . p = h_mid
 * clearly outside the parallelogram: (s, t) of the crossing outside
 * [0, 1]^2 by more than the margins below. The watertight test would
 * then reject it too, after the shear and five edge functions: in a
 * closed room this is the usual answer for every wall the ray does not
 * hit. Not for grazing rays (|n . d| < 16 u max|d|), whose crossing is
 * too uncertain.
 *   Why no reported hit is lost. A reported hit means the exact line meets
 * the moved triangle at some q' (see above), within sqrt(2) xi < 5 u A of
 * a point q of the parallelogram (which, with c2 = c1 + c3 - c0 rounded,
 * lies within 11 u c_max of the exact parallelogram on c0, e1, e2). With
 * |n . q' - h_mid| <= h_half + eta + 7 u c_max, the line's crossing p* of
 * the middle plane lies within G (h_half + eta + 7 u c_max) of q', G =
 * |d| / |n . d| <= 4 max|d| / |computed n . d| (the dot's error is below
 * 6/16 of it). The computed crossing p = o + t d, t = (h_mid - n . o) /
 * n . d, is within 11 G u (|t d| + A) of p* (the errors of n . o and
 * n . d over |n . d|, two roundings of t, two of p). Its (s, t) carry
 * 6 u |a|_1 (|p| + c_max) more (p - c0, the dot, a's rounding), and
 * |p| <= sqrt(3) max|p|, max|p| <= (max|o| + |t| max|d|) (1 + 2u) with
 * max|o| <= A, so that term is below 11 u (A + |t| max|d|). All told,
 * with room to spare for the rounding of the margin itself:
 *   dist = G (h_half + 64 u B) + 64 u B,  B = A + |t| max|d|,
 * and |a|_1 dist, |b|_1 dist bound the distance in s and t. */
static inline bool misses_quad(const para_cull_t *k, const ray_t *r,
                               const plane_ray_t *pl)
{
    const real u = REAL_UNIT_ROUNDOFF;
    real adn = fabs(pl->dn);
    /* not grazing; what follows is computed in any case (no branch: see
     * leaves_plane) and counts only then */
    bool steep = adn >= DIR_PAD * pl->d_max;
    real t = (k->h_mid - pl->s) / pl->dn;
    VECTOR3 p, q;
    vec_add_scaled(p, r->o, t, r->d);
    vec_sub(q, p, k->c0);
    real s = SVECTOR3(q, k->a), tt = SVECTOR3(q, k->b);
    real A = k->c_max + pl->o_max;
    real G = 4 * pl->d_max / adn;
    real B = A + fabs(t) * pl->d_max;
    real dist = G * (k->h_half + 64 * u * B) + 64 * u * B;
    real ms = k->a1 * dist, mt = k->b1 * dist;
    /* a NaN or an infinity makes every comparison false */
    return steep & ((s < -ms) | (s > 1 + ms) | (tt < -mt) | (tt > 1 + mt));
}

#define STEEP_PAD (1024 * REAL_UNIT_ROUNDOFF)
#define TRI_PAD (512 * REAL_UNIT_ROUNDOFF)

/* True when the segment of the ray over [0, tmax] stays on one side of
 * the slab: its origin beyond h_hi + pad (or below h_lo - pad, the pad of
 * leaves_plane) and its end o + tmax d beyond h_hi + pad2 (below
 * h_lo - pad2). For tmin >= 0 only. The mirror of leaves_plane() for a
 * ray that comes toward the plane but ends before it: a shadow ray to a
 * light just under the ceiling, a bounce ray whose tmax a box in front of
 * the wall has shortened.
 *   Why no reported hit is lost. A reported hit has tt > dt and
 * tt < tmax (triangle_hit_sheared; the same in units of 2^-scale), where
 * dt is pbrt-v3's bound (sec. 3.9.6) on the distance of tt from the t' at
 * which the exact ray meets the moved triangle, so 0 < t' < tmax + dt;
 * the point there has n . p within eta + 6 u c_max of [h_lo, h_hi] (see
 * above). n . p is linear along the ray, so over [0, tmax + dt] it is no
 * lower than min(n . o, n . (o + tmax d) - dt |n . d|), the side of h_hi
 * (h_lo alike). What dt |n . d| can be: dt = 3 (gamma(3) max_e max_z +
 * de max_z + dz max_e) / |det|, with max_e <= |det| (1 + gamma(2)) on a
 * hit (the e_i share det's sign), dz = gamma(3) max_z, and
 * max_z |n . d| <= sqrt(3) max_z |d_kz| <= sqrt(3) A (1 + 2u), A = c_max
 * + max|o|: the first and last terms give less than 32 u A. The sheared
 * |x|, |y| are at most |a_x| + |a_z| <= 2 A (|sx|, |sy| <= 1), so de <=
 * (8 gamma(2) + 24 gamma(5)) A^2 < 136 u A^2. det is the sum of the e_i,
 * each within de of the exact edge functions, whose sum is twice the
 * triangle's area T' projected along d: 2 T' |n . d| / |d_kz| (signed).
 * "Steep": |n . d| >= 1024 u max|d| A^2 k_area, k_area = 2 / T with T the
 * smaller triangle's area (T' >= T / 2 for both triangles, with room for
 * the rounding of T, of c2 and of the computed n . d, less than 1/256 of
 * it here), gives 2 T' |n . d| / |d_kz| >= 12 de, so |det| >= (3/4) 2 T'
 * |n . d| / |d_kz| (1 - gamma(2)), and 3 de max_z |n . d| / |det| <=
 * 272 u A^3 / T' (1 + 4 u). So for a steep ray
 *   pad2 = 128 u (A + tmax max|d|) + 512 u A (A^2 k_area)
 * covers eta + 6 u c_max < 28 u A, dt |n . d| < 32 u A + 288 u A^3 / T',
 * the errors of n . o, n . d and of e = n . o + tmax n . d (less than
 * 6 u max|o|, 6 u tmax max|d| and 2 u (|n . o| + tmax |n . d|)) and its
 * own rounding. When tmax is infinite (or A^2 k_area overflows), pad2 is
 * infinite and nothing is rejected; a NaN makes every comparison false. */
static inline bool stays_before(const para_cull_t *k, const plane_ray_t *pl,
                                real tmax)
{
    real A = k->c_max + pl->o_max;
    real pad = SLAB_PAD * A;
    real q = A * A * k->k_area;
    bool steep = fabs(pl->dn) >= STEEP_PAD * pl->d_max * q;
    real e = pl->s + tmax * pl->dn;
    real pad2 = SLAB_PAD * (A + tmax * pl->d_max) + TRI_PAD * (A * q);
    return steep & (((pl->s > k->h_hi + pad) & (e > k->h_hi + pad2)) |
                    ((pl->s < k->h_lo - pad) & (e < k->h_lo - pad2)));
}

/* The early rejections: true only when the watertight test would report
 * no hit in (tmin, tmax) (the proofs above). */
static inline bool rejects(const para_cull_t *k, const ray_t *r,
                           const ray_size_t *rs, real tmin, real tmax)
{
    plane_ray_t pl;
    plane_ray(k, r, rs, &pl);
    /* & and | on purpose: every test made, no branch between them */
    return ((int)(tmin >= 0) &
            ((int)leaves_plane(k, &pl) | (int)stays_before(k, &pl, tmax))) |
           (int)misses_quad(k, r, &pl);
}

/* A sheared corner in a slot of four reals, so that a vector of four
 * can be stored into it whole (shear_corners()). */
typedef union {
    triangle_sheared_t v;
    real r[4];
} sheared_slot;
_Static_assert(sizeof(triangle_sheared_t) == 3 * sizeof(real),
               "triangle_sheared_t: x, y, az without padding");

/* The four corners sheared into pr's space, v[i].v from c[i] as
 * triangle_shear() makes it, and the five edge functions of exact() as
 * triangle_edge() makes them: e[0..4] = e01, e12, e20, e23, e30 (eij =
 * edge(vi, vj)). */
#if defined(SIMD_REAL) && !defined(SVET_DOUBLE)
/* With SSE, lane i of a vector holding corner i: every lane gets the
 * IEEE operations triangle_shear() and triangle_edge() make, on the same
 * operands (a product's two factors in either order give the same
 * bits), so the same numbers bit for bit (tests/geometry/test_parallelogram.c
 * compares exact() with two triangle tests on millions of rays). */
static inline void shear_corners(const para_shape *sh,
                                 const triangle_ray_t *pr,
                                 sheared_slot v[4], real e[5])
{
    const __m128 az = _mm_sub_ps(_mm_loadu_ps(sh->cs[pr->kz]),
                                 _mm_set1_ps(pr->o[pr->kz]));
    const __m128 ax = _mm_sub_ps(_mm_loadu_ps(sh->cs[pr->kx]),
                                 _mm_set1_ps(pr->o[pr->kx]));
    const __m128 ay = _mm_sub_ps(_mm_loadu_ps(sh->cs[pr->ky]),
                                 _mm_set1_ps(pr->o[pr->ky]));
    const __m128 x = _mm_add_ps(ax, _mm_mul_ps(_mm_set1_ps(pr->sx), az));
    const __m128 y = _mm_add_ps(ay, _mm_mul_ps(_mm_set1_ps(pr->sy), az));
    /* lane i of x1, y1 holds corner i + 1 (mod 4), of x2, y2 corner i + 2:
     * lanes of e1v: edge(v0, v1), edge(v1, v2), edge(v2, v3),
     * edge(v3, v0); lane 2 of e2v: edge(v2, v0) */
    const __m128 x1 = _mm_shuffle_ps(x, x, _MM_SHUFFLE(0, 3, 2, 1)),
                 y1 = _mm_shuffle_ps(y, y, _MM_SHUFFLE(0, 3, 2, 1));
    const __m128 x2 = _mm_shuffle_ps(x, x, _MM_SHUFFLE(1, 0, 3, 2)),
                 y2 = _mm_shuffle_ps(y, y, _MM_SHUFFLE(1, 0, 3, 2));
    const __m128 e1v = _mm_sub_ps(_mm_mul_ps(x, y1), _mm_mul_ps(y, x1));
    const __m128 e2v = _mm_sub_ps(_mm_mul_ps(x, y2), _mm_mul_ps(y, x2));
    real a[4], b[4];
    _mm_storeu_ps(a, e1v);
    _mm_storeu_ps(b, e2v);
    e[0] = a[0];
    e[1] = a[1];
    e[2] = b[2];
    e[3] = a[2];
    e[4] = a[3];
    /* (x_i, y_i, az_i) into slot i */
    const __m128 xy01 = _mm_unpacklo_ps(x, y), xy23 = _mm_unpackhi_ps(x, y);
    const __m128 z01 = _mm_unpacklo_ps(az, az), z23 = _mm_unpackhi_ps(az, az);
    _mm_storeu_ps(v[0].r, _mm_movelh_ps(xy01, z01));
    _mm_storeu_ps(v[1].r, _mm_movehl_ps(z01, xy01));
    _mm_storeu_ps(v[2].r, _mm_movelh_ps(xy23, z23));
    _mm_storeu_ps(v[3].r, _mm_movehl_ps(z23, xy23));
}
#else
static inline void shear_corners(const para_shape *sh,
                                 const triangle_ray_t *pr,
                                 sheared_slot v[4], real e[5])
{
    for (int i = 0; i < 4; i++)
        triangle_shear(&v[i].v, sh->c[i], pr);
    e[0] = triangle_edge(&v[0].v, &v[1].v);
    e[1] = triangle_edge(&v[1].v, &v[2].v);
    e[2] = triangle_edge(&v[2].v, &v[0].v);
    e[3] = triangle_edge(&v[2].v, &v[3].v);
    e[4] = triangle_edge(&v[3].v, &v[0].v);
}
#endif

/* The watertight test of the two triangles A = (c0, c1, c2) and
 * B = (c0, c2, c3), sharing what they share: the ray is prepared once,
 * each corner is sheared once, and the diagonal's edge function once
 * (B's edge (c0, c2) is -edge(c2, c0) exactly, triangle.h). Each triangle
 * then gets exactly the numbers it would get on its own, so the answers
 * are those of two triangle tests bit for bit, and watertight as they
 * are: a parallelogram sharing an edge with another shears the same two
 * corners into the same points. Only a zero edge function, which needs
 * the exact recomputation, takes the way of two separate tests. No early
 * check of the corners' z against (tmin, tmax) here any more: every
 * caller has made rejects() first, whose stays_before() turns away what
 * that check did (a segment that ends before the plane), so it found
 * almost nothing left. */
static bool exact(const para_shape *sh, int prim, const triangle_ray_t *pr,
                  real tmin, real tmax, hit_t *hit)
{
    if (!pr->ok)
        return false;
    sheared_slot vs[4];
    real e[5];
    shear_corners(sh, pr, vs, e);
    const triangle_sheared_t *v0 = &vs[0].v, *v1 = &vs[1].v, *v2 = &vs[2].v,
                             *v3 = &vs[3].v;
    const real e01 = e[0], e12 = e[1], e20 = e[2], e23 = e[3], e30 = e[4];
    real t, st[2];
    bool any = false;
    if (e01 == 0 || e12 == 0 || e20 == 0 || e23 == 0 || e30 == 0) {
        any = two_triangles(sh, pr, tmin, tmax, &t, st);
    } else {
        bool out_a = mixed(e12, e20, e01), out_b = mixed(e23, e30, -e20);
        if (out_a && out_b)
            return false; /* the usual answer, at the price of 4 shears */
        real b[3];
        if (!out_a && !sh->degenerate[0] &&
            triangle_hit_sheared(v0, v1, v2, e12, e20, e01, pr, tmin,
                                 tmax, &t, b)) {
            any = true;
            tmax = t;
            st_of(0, b, st);
        }
        if (!out_b && !sh->degenerate[1] &&
            triangle_hit_sheared(v0, v2, v3, e23, e30, -e20, pr, tmin,
                                 tmax, &t, b)) {
            any = true;
            st_of(1, b, st);
        }
    }
    if (!any)
        return false;
    hit->t = t;
    hit->prim = prim;
    hit->b[0] = clamp01(st[0]);
    hit->b[1] = clamp01(st[1]);
    hit->b[2] = 0;
    return true;
}

static bool para_intersect(const COBJECT *obj, int prim, const ray_t *r,
                           real tmin, real tmax, hit_t *hit)
{
    const para_shape *sh = obj->shape;
    ray_size_t rs;
    ray_size(r, &rs);
    if (rejects(&sh->k, r, &rs, tmin, tmax))
        return false;
    triangle_ray_t pr;
    triangle_ray_prepare(&pr, r);
    return exact(sh, prim, &pr, tmin, tmax, hit);
}

static void para_surface(const COBJECT *obj, const ray_t *r, const hit_t *hit,
                         PATHPOINT *pp)
{
    (void)r;
    const para_shape *sh = obj->shape;
    point_at(sh, hit->b[0], hit->b[1], pp->cross_point, pp->p_error);
    pp->st[0] = hit->b[0];
    pp->st[1] = hit->b[1];
    vec_copy(pp->dpds, sh->e1);
    vec_copy(pp->dpdt, sh->e2);
    vec_copy(pp->ng, sh->n);
    vec_copy(pp->n, sh->n);
    vec_copy(pp->u, sh->u);
    vec_copy(pp->v, sh->v);
}

static void para_bounds(const COBJECT *obj, int prim, bbox_t *b)
{
    (void)prim;
    const para_shape *sh = obj->shape;
    bbox_empty(b);
    for (int i = 0; i < 4; i++)
        bbox_add_point(b, sh->c[i]);
}

static real para_area(const COBJECT *obj)
{
    return ((const para_shape *)obj->shape)->area;
}

static void para_sample(const COBJECT *obj, const real u[2],
                        cobject_sample_t *smp)
{
    /* (s, t) = u is uniform by area: the map is affine */
    const para_shape *sh = obj->shape;
    point_at(sh, u[0], u[1], smp->p, smp->p_error);
    vec_copy(smp->n, sh->n);
    smp->pdf = 1 / sh->area;
}

static const cobject_ops parallelogram_ops = {
    "parallelogram", para_intersect, para_surface, para_bounds, para_area,
    para_sample, NULL
};

/* --- many parallelograms at once (brute force, accel.c) ------------------ */

/* The early rejections of a whole batch run from one flat array, with
 * max|o| and max|d| once per ray and no call per parallelogram; the
 * watertight test (exact()) then runs only for those that pass, with
 * the ray prepared once for all of them. Both are the very functions
 * para_intersect() runs, so the answers are its answers bit for bit. */
/* The fields of para_cull_t, each an array over the batch (structure of
 * arrays: lane j of a vector step reads element i + j of every array),
 * zero past n (whole steps of VWLANES lanes, at most 8, their answers
 * dropped). */
struct parallelogram_batch {
    int n;
    real nx[PARALLELOGRAM_BATCH_MAX], ny[PARALLELOGRAM_BATCH_MAX],
        nz[PARALLELOGRAM_BATCH_MAX];
    real c0x[PARALLELOGRAM_BATCH_MAX], c0y[PARALLELOGRAM_BATCH_MAX],
        c0z[PARALLELOGRAM_BATCH_MAX];
    real h_lo[PARALLELOGRAM_BATCH_MAX], h_hi[PARALLELOGRAM_BATCH_MAX],
        h_mid[PARALLELOGRAM_BATCH_MAX], h_half[PARALLELOGRAM_BATCH_MAX],
        c_max[PARALLELOGRAM_BATCH_MAX];
    real ax[PARALLELOGRAM_BATCH_MAX], ay[PARALLELOGRAM_BATCH_MAX],
        az[PARALLELOGRAM_BATCH_MAX];
    real bx[PARALLELOGRAM_BATCH_MAX], by[PARALLELOGRAM_BATCH_MAX],
        bz[PARALLELOGRAM_BATCH_MAX];
    real a1[PARALLELOGRAM_BATCH_MAX], b1[PARALLELOGRAM_BATCH_MAX];
    real k_area[PARALLELOGRAM_BATCH_MAX];
};

bool parallelogram_is(const COBJECT *obj)
{
    return obj && obj->ops == &parallelogram_ops;
}

parallelogram_batch_t *parallelogram_batch_new(const COBJECT *const *objs,
                                               int n)
{
    if (n < 0 || n > PARALLELOGRAM_BATCH_MAX)
        return NULL;
    for (int i = 0; i < n; i++)
        if (!parallelogram_is(objs[i]))
            return NULL;
    parallelogram_batch_t *b = calloc(1, sizeof *b);
    if (!b)
        return NULL;
    b->n = n;
    for (int i = 0; i < n; i++) {
        const para_cull_t *k = &((const para_shape *)objs[i]->shape)->k;
        b->nx[i] = k->n[X], b->ny[i] = k->n[Y], b->nz[i] = k->n[Z];
        b->c0x[i] = k->c0[X], b->c0y[i] = k->c0[Y], b->c0z[i] = k->c0[Z];
        b->h_lo[i] = k->h_lo, b->h_hi[i] = k->h_hi;
        b->h_mid[i] = k->h_mid, b->h_half[i] = k->h_half;
        b->c_max[i] = k->c_max;
        b->ax[i] = k->a[X], b->ay[i] = k->a[Y], b->az[i] = k->a[Z];
        b->bx[i] = k->b[X], b->by[i] = k->b[Y], b->bz[i] = k->b[Z];
        b->a1[i] = k->a1, b->b1[i] = k->b1;
        b->k_area[i] = k->k_area;
    }
    return b;
}

void parallelogram_batch_free(parallelogram_batch_t *b)
{
    free(b);
}

uint64_t parallelogram_batch_cull_plain(const parallelogram_batch_t *b,
                                        const ray_t *r, real tmin, real tmax,
                                        uint64_t want)
{
    ray_size_t rs;
    ray_size(r, &rs);
    uint64_t maybe = 0;
    for (int i = 0; i < b->n; i++) {
        if (!((want >> i) & 1))
            continue;
        const para_cull_t k = {
            { b->nx[i], b->ny[i], b->nz[i] },
            { b->c0x[i], b->c0y[i], b->c0z[i] },
            b->h_lo[i], b->h_hi[i], b->h_mid[i], b->h_half[i], b->c_max[i],
            { b->ax[i], b->ay[i], b->az[i] },
            { b->bx[i], b->by[i], b->bz[i] },
            b->a1[i], b->b1[i], b->k_area[i]
        };
        if (!rejects(&k, r, &rs, tmin, tmax))
            maybe |= (uint64_t)1 << i;
    }
    return maybe;
}

#ifdef SIMD_REAL
/* rejects() on a vector of parallelograms at once (simd.h's widest:
 * 8 floats or 4 doubles with AVX, else 4 or 2 with SSE2): every
 * operation is the IEEE operation rejects() makes, on the same operands in
 * the same order, so each lane gets exactly the bits of the plain loop.
 * tests/geometry/test_parallelogram.c compares the two. A step whose wanted lanes
 * the plane tests (leaves_plane, stays_before) all reject skips
 * misses_quad(), whose answer could only repeat theirs. */
uint64_t parallelogram_batch_cull(const parallelogram_batch_t *b,
                                  const ray_t *r, real tmin, real tmax,
                                  uint64_t want)
{
    const real u = REAL_UNIT_ROUNDOFF;
    ray_size_t rs;
    ray_size(r, &rs);
    const vwreal sign = VW_SET1(-REAL_C(0.0)); /* fabs: clear the sign bit */
    const vwreal ox = VW_SET1(r->o[X]), oy = VW_SET1(r->o[Y]),
                oz = VW_SET1(r->o[Z]);
    const vwreal dx = VW_SET1(r->d[X]), dy = VW_SET1(r->d[Y]),
                dz = VW_SET1(r->d[Z]);
    const vwreal o_max = VW_SET1(rs.o_max), d_max = VW_SET1(rs.d_max);
    const vwreal dpad = VW_SET1(DIR_PAD * rs.d_max);
    const vwreal g4 = VW_SET1(4 * rs.d_max);
    const vwreal one = VW_SET1(1), slab = VW_SET1(SLAB_PAD);
    const vwreal u64 = VW_SET1(64 * u);
    const int ahead = tmin >= 0;
    /* stays_before() is false in every lane for tmax = +infinity */
    const bool segment = ahead && tmax != (real)INFINITY;
    const vwreal vtmax = VW_SET1(tmax), tdm = VW_SET1(tmax * rs.d_max);
    const vwreal steep_d = VW_SET1(STEEP_PAD * rs.d_max);
    const vwreal tri = VW_SET1(TRI_PAD);
    uint64_t maybe = 0;
    for (int i = 0; i < b->n; i += VWLANES) {
        /* plane_ray(): n . o, n . d */
        vwreal nx = VW_LOAD(b->nx + i), ny = VW_LOAD(b->ny + i),
              nz = VW_LOAD(b->nz + i);
        vwreal s = VW_ADD(VW_ADD(VW_MUL(nx, ox), VW_MUL(ny, oy)), VW_MUL(nz, oz));
        vwreal dn = VW_ADD(VW_ADD(VW_MUL(nx, dx), VW_MUL(ny, dy)), VW_MUL(nz, dz));
        /* leaves_plane() */
        vwreal c_max = VW_LOAD(b->c_max + i);
        vwreal A = VW_ADD(c_max, o_max);
        vwreal pad = VW_MUL(slab, A);
        vwreal h_hi = VW_LOAD(b->h_hi + i), h_lo = VW_LOAD(b->h_lo + i);
        vwreal above = VW_GT(s, VW_ADD(h_hi, pad)),
              below = VW_LT(s, VW_SUB(h_lo, pad));
        vwreal leaves = VW_OR(VW_AND(above, VW_GE(dn, dpad)),
                            VW_AND(below, VW_LE(dn, VW_XOR(dpad, sign))));
        vwreal adn = VW_ANDNOT(sign, dn);
        if (segment) { /* stays_before() */
            vwreal q = VW_MUL(VW_MUL(A, A), VW_LOAD(b->k_area + i));
            vwreal steep2 = VW_GE(adn, VW_MUL(steep_d, q));
            vwreal e = VW_ADD(s, VW_MUL(vtmax, dn));
            vwreal pad2 = VW_ADD(VW_MUL(slab, VW_ADD(A, tdm)),
                               VW_MUL(tri, VW_MUL(A, q)));
            leaves = VW_OR(leaves,
                          VW_AND(steep2,
                                VW_OR(VW_AND(above,
                                           VW_GT(e, VW_ADD(h_hi, pad2))),
                                     VW_AND(below,
                                           VW_LT(e, VW_SUB(h_lo, pad2))))));
        }
        const int lanes = (1 << VWLANES) - 1;
        int wanted = (int)(want >> i) & lanes;
        int left = wanted & ~(ahead ? VW_MASK(leaves) : 0);
        if (!left)
            continue;
        /* misses_quad() */
        vwreal steep = VW_GE(adn, dpad);
        vwreal t = VW_DIV(VW_SUB(VW_LOAD(b->h_mid + i), s), dn);
        vwreal px = VW_ADD(ox, VW_MUL(t, dx)), py = VW_ADD(oy, VW_MUL(t, dy)),
              pz = VW_ADD(oz, VW_MUL(t, dz));
        vwreal qx = VW_SUB(px, VW_LOAD(b->c0x + i)),
              qy = VW_SUB(py, VW_LOAD(b->c0y + i)),
              qz = VW_SUB(pz, VW_LOAD(b->c0z + i));
        vwreal ss = VW_ADD(VW_ADD(VW_MUL(qx, VW_LOAD(b->ax + i)),
                               VW_MUL(qy, VW_LOAD(b->ay + i))),
                         VW_MUL(qz, VW_LOAD(b->az + i)));
        vwreal tt = VW_ADD(VW_ADD(VW_MUL(qx, VW_LOAD(b->bx + i)),
                               VW_MUL(qy, VW_LOAD(b->by + i))),
                         VW_MUL(qz, VW_LOAD(b->bz + i)));
        vwreal G = VW_DIV(g4, adn);
        vwreal B = VW_ADD(A, VW_MUL(VW_ANDNOT(sign, t), d_max));
        vwreal u64B = VW_MUL(u64, B);
        vwreal dist = VW_ADD(VW_MUL(G, VW_ADD(VW_LOAD(b->h_half + i), u64B)),
                           u64B);
        vwreal ms = VW_MUL(VW_LOAD(b->a1 + i), dist),
              mt = VW_MUL(VW_LOAD(b->b1 + i), dist);
        vwreal outside = VW_OR(
            VW_OR(VW_LT(ss, VW_XOR(ms, sign)), VW_GT(ss, VW_ADD(one, ms))),
            VW_OR(VW_LT(tt, VW_XOR(mt, sign)), VW_GT(tt, VW_ADD(one, mt))));
        vwreal misses = VW_AND(steep, outside);
        maybe |= (uint64_t)(left & ~VW_MASK(misses)) << i;
    }
    /* the padding lanes past n */
    return b->n < 64 ? maybe & (((uint64_t)1 << b->n) - 1) : maybe;
}
#else
uint64_t parallelogram_batch_cull(const parallelogram_batch_t *b,
                                  const ray_t *r, real tmin, real tmax,
                                  uint64_t want)
{
    return parallelogram_batch_cull_plain(b, r, tmin, tmax, want);
}
#endif

bool parallelogram_intersect_prepared(const COBJECT *obj, int prim,
                                      const triangle_ray_t *pr, real tmin,
                                      real tmax, hit_t *hit)
{
    return exact(obj->shape, prim, pr, tmin, tmax, hit);
}

/* a and b of para_cull_t, in long double from the exact edges c1 - c0 and
 * c3 - c0 and the stored n: a = (E2 x n) / (E1 . (E2 x n)) has a . E1 = 1,
 * a . E2 = a . n = 0; b likewise with E1 and E2 swapped. If they do not
 * come out finite (an edge far below the scale of the corners), a1 and b1
 * are infinite and misses_quad never answers early. */
static void dual_vectors(const para_shape *sh, para_cull_t *kc)
{
    long double E1[3], E2[3], n[3], x[3], y[3];
    for (int k = 0; k < 3; k++) {
        E1[k] = (long double)sh->c[1][k] - (long double)sh->c[0][k];
        E2[k] = (long double)sh->c[3][k] - (long double)sh->c[0][k];
        n[k] = (long double)sh->n[k];
    }
    for (int k = 0; k < 3; k++) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        x[k] = E2[i] * n[j] - E2[j] * n[i]; /* E2 x n */
        y[k] = n[i] * E1[j] - n[j] * E1[i]; /* n x E1 */
    }
    long double da = E1[0] * x[0] + E1[1] * x[1] + E1[2] * x[2];
    long double db = E2[0] * y[0] + E2[1] * y[1] + E2[2] * y[2];
    kc->a1 = kc->b1 = 0;
    for (int k = 0; k < 3; k++) {
        kc->a[k] = (real)(x[k] / da);
        kc->b[k] = (real)(y[k] / db);
        kc->a1 += fabs(kc->a[k]);
        kc->b1 += fabs(kc->b[k]);
    }
    kc->a1 = real_next_up(real_next_up(kc->a1));
    kc->b1 = real_next_up(real_next_up(kc->b1));
    if (!vec_is_finite(kc->a) || !vec_is_finite(kc->b) || !isfinite(kc->a1) ||
        !isfinite(kc->b1))
        kc->a1 = kc->b1 = (real)INFINITY;
}

/* k_area of para_cull_t: 2 / T, T the smaller of the areas of the
 * triangles (c0, c1, c2) and (c0, c2, c3) with the corners as stored,
 * computed in long double (its error is far below the factor 2 that
 * stays_before() allows for), rounded up; infinite when T is not
 * positive or 2 / T overflows. */
static real k_area(const para_shape *sh)
{
    long double T = (long double)INFINITY;
    for (int tri = 0; tri < 2; tri++) {
        const real *p = sh->c[0], *q = sh->c[1 + tri], *w = sh->c[2 + tri];
        long double a[3], b[3], c2 = 0;
        for (int k = 0; k < 3; k++) {
            a[k] = (long double)q[k] - (long double)p[k];
            b[k] = (long double)w[k] - (long double)p[k];
        }
        for (int k = 0; k < 3; k++) {
            int i = (k + 1) % 3, j = (k + 2) % 3;
            long double c = a[i] * b[j] - a[j] * b[i];
            c2 += c * c;
        }
        long double area = sqrtl(c2) / 2;
        if (area < T)
            T = area;
    }
    real k = (real)(2 / T);
    if (!(T > 0) || !isfinite(k))
        return (real)INFINITY;
    return real_next_up(k);
}

/* The checks both constructors share, and the object. */
static COBJECT *make(const VECTOR3 c0, const VECTOR3 c1, const VECTOR3 c2,
                     const VECTOR3 c3, svet_error *err)
{
    VECTOR3 e1, e2, n;
    vec_sub(e1, c1, c0);
    vec_sub(e2, c3, c0);
    if (!vec_is_finite(e1) || !vec_is_finite(e2) || !vec_is_finite(c2)) {
        svet_error_set(err, SVET_ERR_RANGE, "parallelogram: edges exceed "
                       "the largest %s", REAL_NAME);
        return NULL;
    }
    /* The test of (c0, c1, c3) on the edges scaled to near 1 by powers
     * of 2 (exact, shape.h): the same answer where the edges' products
     * are normal numbers, and no "parallel" for perpendicular edges
     * whose products overflow (beyond sqrt(REAL_MAX)) or underflow. */
    VECTOR3 origin = { 0, 0, 0 }, s1, s2;
    int x1 = shape_scale_exponent(s1, e1), x2 = shape_scale_exponent(s2, e2);
    if (triangle_is_degenerate(origin, s1, s2) ||
        !shape_unit_cross(n, e1, e2)) {
        svet_error_set(err, SVET_ERR_RANGE, "parallelogram: degenerate, the "
                       "edges c1 - c0 = (%g, %g, %g) and c3 - c0 = (%g, %g, "
                       "%g) are parallel or zero", (double)e1[X],
                       (double)e1[Y], (double)e1[Z], (double)e2[X],
                       (double)e2[Y], (double)e2[Z]);
        return NULL;
    }
    real area = shape_cross_length(e1, e2);
    if (!isfinite(area) || !isfinite(1 / area)) {
        /* told in double, where it is a number */
        double a = ldexp((double)shape_cross_length(s1, s2), x1 + x2);
        svet_error_set(err, SVET_ERR_RANGE, "parallelogram: area %g is out "
                       "of the range of %s", a, REAL_NAME);
        return NULL;
    }
    COBJECT *obj = shape_alloc(&parallelogram_ops, sizeof(para_shape), err);
    if (!obj)
        return NULL;
    obj->surface_fills = true; /* para_surface() writes every field */
    para_shape *sh = obj->shape;
    vec_copy(sh->c[0], c0);
    vec_copy(sh->c[1], c1);
    vec_copy(sh->c[2], c2);
    vec_copy(sh->c[3], c3);
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++)
            sh->cs[k][i] = sh->c[i][k];
    vec_copy(sh->e1, e1);
    vec_copy(sh->e2, e2);
    vec_copy(sh->n, n);
    shape_frame(sh->u, sh->v, sh->n, sh->e1);
    sh->degenerate[0] = triangle_is_degenerate(c0, c1, c2);
    sh->degenerate[1] = triangle_is_degenerate(c0, c2, c3);
    sh->area = area;
    para_cull_t *k = &sh->k;
    vec_copy(k->n, n);
    vec_copy(k->c0, c0);
    k->h_lo = (real)INFINITY;
    k->h_hi = -(real)INFINITY;
    k->c_max = 0;
    for (int i = 0; i < 4; i++) {
        real h = SVECTOR3(n, sh->c[i]);
        k->h_lo = real_min(k->h_lo, h);
        k->h_hi = real_max(k->h_hi, h);
        for (int j = 0; j < 3; j++)
            k->c_max = real_max(k->c_max, fabs(sh->c[i][j]));
    }
    k->h_mid = REAL_C(0.5) * k->h_lo + REAL_C(0.5) * k->h_hi;
    k->k_area = k_area(sh);
    k->h_half = real_next_up(REAL_C(0.5) * (k->h_hi - k->h_lo));
    dual_vectors(sh, k);
    return obj;
}

static bool check_corners(const VECTOR3 c0, const VECTOR3 c1,
                          const VECTOR3 c3, svet_error *err)
{
    return shape_check_finite("parallelogram", "c0", c0, err) == SVET_OK &&
           shape_check_finite("parallelogram", "c1", c1, err) == SVET_OK &&
           shape_check_finite("parallelogram", "c3", c3, err) == SVET_OK;
}

COBJECT *parallelogram_new(const VECTOR3 c0, const VECTOR3 c1,
                           const VECTOR3 c3, svet_error *err)
{
    if (!check_corners(c0, c1, c3, err))
        return NULL;
    VECTOR3 e2, c2;
    vec_sub(e2, c3, c0);
    vec_add(c2, c1, e2);
    return make(c0, c1, c2, c3, err);
}

COBJECT *parallelogram_new4(const VECTOR3 c0, const VECTOR3 c1,
                            const VECTOR3 c2, const VECTOR3 c3,
                            svet_error *err)
{
    if (!check_corners(c0, c1, c3, err) ||
        shape_check_finite("parallelogram", "c2", c2, err))
        return NULL;
    /* Each corner given in decimal is its exact value rounded once, u
     * relative; c1 + c3 - c0 costs two roundings more and the difference
     * one: an exact parallelogram leaves a mismatch below about
     * 4u (|c0| + |c1| + |c2| + |c3|) per axis; 16u allows for corners
     * computed by a few operations before they were written. */
    VECTOR3 want, miss, e1, e2, n;
    real worst = 0, worst_tol = 0;
    bool bad = false;
    for (int k = 0; k < 3; k++) {
        want[k] = c1[k] + c3[k] - c0[k];
        miss[k] = c2[k] - want[k];
        real tol = 16 * REAL_UNIT_ROUNDOFF *
                   (fabs(c0[k]) + fabs(c1[k]) + fabs(c2[k]) + fabs(c3[k]));
        if (!(fabs(miss[k]) <= tol))
            bad = true;
        if (fabs(miss[k]) > worst) {
            worst = fabs(miss[k]);
            worst_tol = tol;
        }
    }
    if (bad) {
        vec_sub(e1, c1, c0);
        vec_sub(e2, c3, c0);
        real out = shape_unit_cross(n, e1, e2) ? fabs(SVECTOR3(miss, n)) : 0;
        svet_error_set(err, SVET_ERR_RANGE, "parallelogram: c2 (%g, %g, %g) "
                       "is not c1 + c3 - c0 = (%g, %g, %g): off by (%g, %g, "
                       "%g), %g of it out of the plane (tolerance %g)",
                       (double)c2[X], (double)c2[Y], (double)c2[Z],
                       (double)want[X], (double)want[Y], (double)want[Z],
                       (double)miss[X], (double)miss[Y], (double)miss[Z],
                       (double)out, (double)worst_tol);
        return NULL;
    }
    return make(c0, c1, c2, c3, err);
}
