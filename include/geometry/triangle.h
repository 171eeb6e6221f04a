/*
 * triangle.h - the triangle of app. D, with the watertight ray/triangle test
 * of Woop, Benthin, Wald, "Watertight Ray/Triangle Intersection", JCGT 2(1),
 * 2013 (a departure from the book's plane-then-inside test: no ray slips
 * through a shared edge or vertex of a closed mesh). The test and the
 * surface completion are public so that triangle meshes reuse them.
 * Tests: tests/geometry/test_triangle.c; vectors: tests/vectors/triangle.csv
 */
#ifndef SVET_TRIANGLE_H
#define SVET_TRIANGLE_H

#include <stdbool.h>
#include "materials/cobject.h"
#include "core/error.h"

/* Nearest-hit test of ray r against the triangle p0 p1 p2 in the open
 * interval (tmin, tmax), either side of the triangle (no culling).
 * Returns true and the ray parameter *t and the barycentrics b[0..2]
 * (b >= 0, b[0] + b[1] + b[2] = 1 to rounding; the hit point is
 * b[0] p0 + b[1] p1 + b[2] p2) on a hit; on a miss *t and b are untouched.
 *
 * Watertight (Woop et al. 2013): the ray is sheared so it runs along +z,
 * and the edge functions of the projected vertices are evaluated so that
 * an edge shared by two triangles gives exactly opposite values in both;
 * a value that rounds to zero is recomputed exactly (the paper's fallback
 * to double), and zero counts as inside. So a ray through a shared edge or
 * vertex of a closed mesh hits at least one of the triangles around it.
 * When tmin >= 0, a hit whose t cannot be told from 0 by its rounding
 * error is rejected (pbrt-v3 sec. 3.9.6, with the units of its bound
 * corrected for rays of any length). A triangle that
 * triangle_is_degenerate() calls degenerate never reports a hit (a
 * zero-area triangle has no normal). r->d may be any nonzero finite vector. Finite input never
 * yields a NaN or infinite output. This function can't fail. */
bool triangle_intersect_watertight(const VECTOR3 p0, const VECTOR3 p1,
                                   const VECTOR3 p2, const ray_t *r,
                                   real tmin, real tmax, real *t, real b[3]);

/* A ray prepared once for many triangles: the axis permutation and shear
 * of Woop et al. (one division per ray instead of three per triangle). */
typedef struct {
    VECTOR3 o;        /* the ray's origin */
    int kx, ky, kz;   /* kz: the axis of d's largest component */
    real sx, sy, sz;  /* shear -d_x/d_z, -d_y/d_z and 1/d_z */
    int scale;        /* d was scaled by 2^-scale first (exact) */
    bool ok;          /* false for a zero or non-finite d: nothing is hit */
} triangle_ray_t;

/* The rare part of triangle_ray_prepare: d far from unit length. */
void triangle_ray_prepare_scaled(triangle_ray_t *pr, const ray_t *r);

/* Prepare r for triangle_intersect_prepared. Inline, so that a shape made
 * of a few triangles (the parallelogram) keeps the prepared ray in
 * registers. This function can't fail. */
static inline void triangle_ray_prepare(triangle_ray_t *pr, const ray_t *r)
{
    /* Woop et al. sec. 3: permute the axes so that the ray's largest
     * component is z, and shear so that the ray runs along +z. */
    vec_copy(pr->o, r->o);
    int kz = vec_max_axis(r->d);
    real dz = r->d[kz];
    pr->kz = kz;
    pr->kx = kz == 2 ? 0 : kz + 1;
    pr->ky = pr->kx == 2 ? 0 : pr->kx + 1;
    pr->scale = 0;
    /* |d_z| in [2^-16, 2^17), i.e. ilogb(d_z) in [-16, 16]: no rescaling
     * (the comparisons are false for 0, NaN and infinity) */
    real ad = fabs(dz);
    if (!(ad >= REAL_C(0x1p-16) && ad < REAL_C(0x1p17))) {
        triangle_ray_prepare_scaled(pr, r);
        return;
    }
    pr->ok = true;
    /* one division per ray; sx, sy carry two roundings */
    real inv = 1 / dz;
    pr->sx = -r->d[pr->kx] * inv;
    pr->sy = -r->d[pr->ky] * inv;
    pr->sz = inv;
}

/* A vertex in the prepared ray's space: translated to the ray's origin
 * and sheared (Woop et al. sec. 3), x and y across the ray; az is the
 * translated coordinate along the axis kz, before the scaling by sz. */
typedef struct {
    real x, y, az;
} triangle_sheared_t;

/* v = vertex p in the space of pr, in two steps: triangle_shear_z sets
 * v->az, triangle_shear_xy then v->x and v->y (a shape may look at the
 * z's of its vertices before it shears them across the ray). Every vertex
 * is transformed on its own, so a vertex shared by two triangles lands on
 * the same point in both: the root of watertightness. These functions
 * can't fail. */
static inline void triangle_shear_z(triangle_sheared_t *v, const VECTOR3 p,
                                    const triangle_ray_t *pr)
{
    v->az = p[pr->kz] - pr->o[pr->kz];
}

static inline void triangle_shear_xy(triangle_sheared_t *v, const VECTOR3 p,
                                     const triangle_ray_t *pr)
{
    real ax = p[pr->kx] - pr->o[pr->kx], ay = p[pr->ky] - pr->o[pr->ky];
    v->x = ax + pr->sx * v->az;
    v->y = ay + pr->sy * v->az;
}

static inline void triangle_shear(triangle_sheared_t *v, const VECTOR3 p,
                                  const triangle_ray_t *pr)
{
    triangle_shear_z(v, p, pr);
    triangle_shear_xy(v, p, pr);
}

/* The edge function of the sheared vertices a, b: a.x b.y - a.y b.x, twice
 * the signed area of the triangle (ray, a, b) in the projection along the
 * ray. Swapping a and b negates the value exactly (the same two products,
 * subtracted the other way round), so two triangles that share the edge
 * see one value with opposite signs. Its sign is exact when it is not
 * zero: rounding is monotonic, so fl(p) - fl(q) never has the opposite
 * sign of p - q. A zero may be rounding: the caller recomputes exactly
 * (triangle_intersect_prepared does). This function can't fail. */
static inline real triangle_edge(const triangle_sheared_t *a,
                                 const triangle_sheared_t *b)
{
    return a->x * b->y - a->y * b->x;
}

/* The rest of the watertight test, for the sheared vertices v0 v1 v2 and
 * their edge functions e0 = edge(v1, v2), e1 = edge(v2, v0),
 * e2 = edge(v0, v1) as triangle_edge computes them, or, when one of those
 * is zero, as triangle_intersect_prepared recomputes all three exactly:
 * the inside test, t and its error bound, b. Given those, the same answers
 * bit for bit as triangle_intersect_prepared, but for the degeneracy test,
 * which is the caller's (a shape can make it once, when it is built).
 * What a caller may rely on to skip the test: t is computed as
 * (sum e_i z_i / det) 2^-scale with z_i = sz az_i (pr's sz and scale),
 * a mean of the z_i with the weights e_i / det, which are >= 0 and sum to
 * 1 on a hit; with the roundings of the sums and the division it lies
 * within [min z_i - gamma(8) M, max z_i + gamma(8) M] 2^-scale, M =
 * max |z_i| (tests/geometry/test_triangle.c checks this). This function can't
 * fail. */
bool triangle_hit_sheared(const triangle_sheared_t *v0,
                          const triangle_sheared_t *v1,
                          const triangle_sheared_t *v2, real e0, real e1,
                          real e2, const triangle_ray_t *pr, real tmin,
                          real tmax, real *t, real b[3]);

/* triangle_intersect_watertight with the ray prepared once: the same
 * answers, bit for bit. For meshes and shapes made of triangles. This
 * function can't fail. */
bool triangle_intersect_prepared(const VECTOR3 p0, const VECTOR3 p1,
                                 const VECTOR3 p2, const triangle_ray_t *pr,
                                 real tmin, real tmax, real *t, real b[3]);

/* True when the triangle's area cannot be told from zero at working
 * precision: every component of the computed (p1 - p0) x (p2 - p0) lies
 * within its own rounding-error bound. Repeated vertices, exactly
 * collinear vertices and non-finite vertices are degenerate. This function
 * can't fail. */
bool triangle_is_degenerate(const VECTOR3 p0, const VECTOR3 p1,
                            const VECTOR3 p2);

/* The point p = b0 p0 + b1 p1 + b2 p2 of the triangle at barycentrics b
 * (b as triangle_intersect_watertight or a sampler computed them, so their
 * sum is 1 only to rounding) and p_error, a bound per axis on its distance
 * from the triangle: gamma(7) sum_i |b_i p_i| (pbrt-v3 sec. 3.9.5).
 * Inline: every hit on a parallelogram and every light sample on one
 * makes it. This function can't fail. */
static inline void triangle_point(VECTOR3 p, VECTOR3 p_error,
                                  const VECTOR3 p0, const VECTOR3 p1,
                                  const VECTOR3 p2, const real b[3])
{
    /* Reconstructing the point from barycentrics instead of o + t d keeps
     * it on the triangle's plane (pbrt-v3 sec. 3.9.5). Error: the real
     * numbers b_i sum to 1 + eps with |eps| <= gamma(4) (each b_i = e_i/det
     * carries one division, det two additions; a sampler's b2 = 1 - b0 - b1
     * two subtractions), so the exact sum_i b_i p_i lies within
     * gamma(4) sum|b_i p_i| of the affine combination sum_i b_i p_i /
     * sum_j b_j, a point of the triangle's plane; evaluating the sum costs
     * one product and two additions, gamma(3) sum|b_i p_i| more:
     * gamma(4) + gamma(3) <= gamma(7). */
    for (int k = 0; k < 3; k++) {
        real a = b[0] * p0[k], c = b[1] * p1[k], d = b[2] * p2[k];
        p[k] = a + c + d;
        p_error[k] = ray_gamma(7) * (fabs(a) + fabs(c) + fabs(d));
    }
}

/* Fill the geometric part of pp for the point with barycentrics b of the
 * triangle p0 p1 p2 (as triangle_intersect_watertight returns them):
 * cross_point = b0 p0 + b1 p1 + b2 p2 and its error bound p_error; ng =
 * unit (p1 - p0) x (p2 - p0); the shading normal n = unit(b0 n0 + b1 n1 +
 * b2 n2) when normals (an array of three unit vertex normals) is not NULL,
 * else ng; st = (b1, b2), so that p = p0 + s (p1 - p0) + t (p2 - p0),
 * dpds = p1 - p0, dpdt = p2 - p0; u = dpds made perpendicular to n,
 * v = n x u. Does not touch pp->prim. A degenerate triangle gets a finite
 * frame anyway (ng = +z). This function can't fail. */
void triangle_fill_surface(const VECTOR3 p0, const VECTOR3 p1,
                           const VECTOR3 p2, const VECTOR3 normals[3],
                           const real b[3], PATHPOINT *pp);

/* The change dn of the shading normal pp->n that triangle_fill_surface
 * interpolated from normals (either way round, as a mesh may turn it),
 * for a step dp of the point in the triangle's plane: the barycentrics'
 * change db1, db2 from the least-squares solution of dp = db1 (p1 - p0) +
 * db2 (p2 - p0), the interpolation's db1 (n1 - n0) + db2 (n2 - n0), and
 * shape_normal_change(). dn = 0 where normals is NULL or the triangle is
 * degenerate. This function can't fail. */
void triangle_normal_change(const VECTOR3 p0, const VECTOR3 p1,
                            const VECTOR3 p2, const VECTOR3 normals[3],
                            const PATHPOINT *pp, const VECTOR3 dp,
                            VECTOR3 dn);

/* Uniform point of the triangle by area from u in [0,1)^2: pdf = 1/area,
 * normal along (p1 - p0) x (p2 - p0), and the point's error bound. A
 * degenerate triangle returns p0 with pdf 0 (it has no area to sample).
 * This function can't fail. */
void triangle_sample_point(const VECTOR3 p0, const VECTOR3 p1,
                           const VECTOR3 p2, const real u[2],
                           cobject_sample_t *s);

/* A triangle COBJECT with corners p0 p1 p2; its geometric normal ng is
 * along (p1 - p0) x (p2 - p0) (counter-clockwise seen from the front).
 * A zero-area triangle may be constructed (meshes contain them): it has
 * area 0, never reports a hit and samples with pdf 0.
 * Returns NULL on a NaN or infinite coordinate (SVET_ERR_RANGE) or when
 * memory runs out (SVET_ERR_NOMEM), with the reason in err. */
COBJECT *triangle_new(const VECTOR3 p0, const VECTOR3 p1, const VECTOR3 p2,
                      svet_error *err);

/* Give a triangle per-vertex shading normals n0 n1 n2 (normalised here),
 * interpolated by barycentrics into PATHPOINT.n; ng stays the geometric
 * normal, and n is used as interpolated, not flipped toward ng. Returns
 * SVET_OK, or SVET_ERR_RANGE when obj is not a triangle or a normal is
 * zero, NaN or infinite (obj is then unchanged). */
svet_status triangle_set_normals(COBJECT *obj, const VECTOR3 n0,
                                 const VECTOR3 n1, const VECTOR3 n2,
                                 svet_error *err);

#endif
