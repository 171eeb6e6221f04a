/*
 * mesh.c - triangle meshes (ch. 7): shared vertex arrays, the watertight
 * triangle of triangle.h for every face, interpolated normals and texture
 * coordinates (pbrt-v3 sec. 3.6.2 for dp/ds, dp/dt), and area sampling by
 * Walker's alias table (Vose 1991) and triangle_sample_point().
 * Tests: tests/mesh/test_mesh.c
 */
#include "mesh/mesh.h"
#include "geometry/shape.h"

#include <stdlib.h>
#include <string.h>

static const cobject_ops mesh_ops;

const mesh_t *mesh_get(const COBJECT *obj)
{
    return obj && obj->ops == &mesh_ops ? (const mesh_t *)obj->shape : NULL;
}

static void corners(const mesh_t *m, int i, const real **p0, const real **p1,
                    const real **p2)
{
    *p0 = m->p[m->tri[i][0]];
    *p1 = m->p[m->tri[i][1]];
    *p2 = m->p[m->tri[i][2]];
}

void mesh_triangle_corners(const mesh_t *m, int i, real q[9])
{
    for (int k = 0; k < 3; k++)
        vec_copy(q + 3 * k, m->p[m->tri[i][k]]);
}

bool mesh_triangle_is_degenerate(const mesh_t *m, int i)
{
    const real *p0, *p1, *p2;
    corners(m, i, &p0, &p1, &p2);
    return triangle_is_degenerate(p0, p1, p2);
}

/* --- the COBJECT operations --------------------------------------------- */

static bool mesh_intersect(const COBJECT *obj, int prim, const ray_t *r,
                           real tmin, real tmax, hit_t *hit)
{
    const mesh_t *m = obj->shape;
    const real *p0, *p1, *p2;
    corners(m, prim, &p0, &p1, &p2);
    real t, b[3];
    if (!triangle_intersect_watertight(p0, p1, p2, r, tmin, tmax, &t, b))
        return false;
    hit->t = t;
    hit->prim = prim;
    hit->b[0] = b[0];
    hit->b[1] = b[1];
    hit->b[2] = b[2];
    return true;
}

/* Texture coordinates from the vertices' st, with dp/ds and dp/dt solved
 * from the two edges (pbrt-v3 sec. 3.6.2):
 *   p0 - p2 = (s0 - s2) dpds + (t0 - t2) dpdt,
 *   p1 - p2 = (s1 - s2) dpds + (t1 - t2) dpdt.
 * Returns false (pp untouched) when a vertex has no st or the st triangle
 * is degenerate. */
static bool surface_st(const mesh_t *m, const int32_t v[3], const real b[3],
                       PATHPOINT *pp)
{
    const real *s0 = m->st[v[0]], *s1 = m->st[v[1]], *s2 = m->st[v[2]];
    if (isnan(s0[0]) || isnan(s0[1]) || isnan(s1[0]) || isnan(s1[1]) ||
        isnan(s2[0]) || isnan(s2[1]))
        return false;
    real ds02 = s0[0] - s2[0], dt02 = s0[1] - s2[1];
    real ds12 = s1[0] - s2[0], dt12 = s1[1] - s2[1];
    real det = ds02 * dt12 - dt02 * ds12;
    VECTOR3 dp02, dp12, dpds, dpdt, c;
    vec_sub(dp02, m->p[v[0]], m->p[v[2]]);
    vec_sub(dp12, m->p[v[1]], m->p[v[2]]);
    if (!(fabs(det) > REAL_C(1e-12)))
        return false;
    real inv = 1 / det;
    for (int k = 0; k < 3; k++) {
        dpds[k] = (dt12 * dp02[k] - dt02 * dp12[k]) * inv;
        dpdt[k] = (ds02 * dp12[k] - ds12 * dp02[k]) * inv;
    }
    VVECTOR3(c, dpds, dpdt);
    if (!vec_is_finite(c) || vec_length2(c) == 0)
        return false;
    pp->st[0] = b[0] * s0[0] + b[1] * s1[0] + b[2] * s2[0];
    pp->st[1] = b[0] * s0[1] + b[1] * s1[1] + b[2] * s2[1];
    vec_copy(pp->dpds, dpds);
    vec_copy(pp->dpdt, dpdt);
    return true;
}

static void mesh_surface(const COBJECT *obj, const ray_t *r, const hit_t *hit,
                         PATHPOINT *pp)
{
    (void)r;
    const mesh_t *m = obj->shape;
    const int32_t *v = m->tri[hit->prim];
    const real *p0, *p1, *p2;
    corners(m, hit->prim, &p0, &p1, &p2);
    /* Shading normals only where all three vertices have one. */
    const VECTOR3 *normals = NULL;
    VECTOR3 nv[3];
    if (m->n) {
        normals = (const VECTOR3 *)nv;
        for (int k = 0; k < 3; k++) {
            vec_copy(nv[k], m->n[v[k]]);
            if (vec_length2(nv[k]) == 0)
                normals = NULL;
        }
    }
    /* cross_point, p_error = gamma(7) sum |b_i p_i| (pbrt-v3 sec. 3.9.6),
     * ng from the winding, n interpolated, st = (b1, b2). */
    triangle_fill_surface(p0, p1, p2, normals, hit->b, pp);
    bool refit = false;
    /* The winding decides the sides of the surface (ng, and with it the
     * inside and outside media and sample()'s normal); a shading normal
     * that points to the other side, from a file whose normals disagree
     * with its winding, is turned round to ng's side. */
    if (SVECTOR3(pp->n, pp->ng) < 0) {
        vec_neg(pp->n, pp->n);
        refit = true;
    }
    if (m->st && surface_st(m, v, hit->b, pp))
        refit = true;
    if (refit)
        shape_frame(pp->u, pp->v, pp->n, pp->dpds);
}

static void mesh_bounds(const COBJECT *obj, int prim, bbox_t *b)
{
    const mesh_t *m = obj->shape;
    if (prim < 0) {
        *b = m->bounds;
        return;
    }
    const real *p0, *p1, *p2;
    corners(m, prim, &p0, &p1, &p2);
    bbox_empty(b);
    bbox_add_point(b, p0);
    bbox_add_point(b, p1);
    bbox_add_point(b, p2);
}

static real mesh_area(const COBJECT *obj)
{
    const mesh_t *m = obj->shape;
    return (real)m->area;
}

/* Uniform by area: the alias table picks triangle i with probability
 * A_i / A from u[0], the part of u[0] left over picks the point in it
 * (uniform, density 1/A_i), so the density is (A_i/A)(1/A_i) = 1/A.
 * The leftover has fewer bits than u[0] (log2(ntris) of them went into
 * the choice): with a million triangles a float u[0] keeps 4 bits inside
 * the triangle, a double one 12. The density is exact either way. */
static void mesh_sample(const COBJECT *obj, const real u[2],
                        cobject_sample_t *s)
{
    const mesh_t *m = obj->shape;
    if (!(m->area > 0)) {
        /* Nothing to sample: a point of the mesh with density 0. */
        memset(s, 0, sizeof *s);
        vec_copy(s->p, m->p[m->tri[0][0]]);
        vec_set(s->n, 0, 0, 1);
        return;
    }
    double x = (double)u[0] * m->ntris;
    int i = (int)x;
    if (i >= m->ntris)
        i = m->ntris - 1;
    double f = x - i, keep = (double)m->alias_prob[i];
    double w;
    if (f < keep) {
        w = f / keep;
    } else {
        w = (f - keep) / (1 - keep);
        i = m->alias[i];
    }
    real uu[2] = { (real)w, u[1] };
    if (!(uu[0] < 1))
        uu[0] = nextafter(REAL_C(1.0), REAL_C(0.0));
    if (!(uu[0] >= 0))
        uu[0] = 0;
    const real *p0, *p1, *p2;
    corners(m, i, &p0, &p1, &p2);
    triangle_sample_point(p0, p1, p2, uu, s);
    s->pdf = (real)(1 / m->area);
}

static void mesh_destroy(COBJECT *obj)
{
    mesh_t *m = obj->shape;
    if (!m)
        return;
    free(m->p);
    free(m->n);
    free(m->st);
    free(m->tri);
    free(m->slot);
    free(m->alias_prob);
    free(m->alias);
    free(m);
    obj->shape = NULL;
}

/* Where the triangle hit has a normal at each vertex, the change of
 * their interpolation (turned round or not, triangle_normal_change); a
 * flat facet otherwise. */
static void mesh_normal_change(const COBJECT *obj, const PATHPOINT *pp,
                               const VECTOR3 dp, VECTOR3 dn)
{
    const mesh_t *m = obj->shape;
    vec_set(dn, 0, 0, 0);
    if (!m->n || pp->prim < 0 || pp->prim >= obj->nprims)
        return;
    const int32_t *v = m->tri[pp->prim];
    VECTOR3 nv[3];
    for (int k = 0; k < 3; k++) {
        vec_copy(nv[k], m->n[v[k]]);
        if (vec_length2(nv[k]) == 0)
            return;
    }
    const real *p0, *p1, *p2;
    corners(m, pp->prim, &p0, &p1, &p2);
    triangle_normal_change(p0, p1, p2, (const VECTOR3 *)nv, pp, dp, dn);
}

static const cobject_ops mesh_ops = {
    "mesh", mesh_intersect, mesh_surface, mesh_bounds, mesh_area,
    mesh_sample, mesh_destroy, mesh_normal_change
};

/* --- construction ------------------------------------------------------- */

static void free_given(mesh_t *m)
{
    free(m->p);
    free(m->n);
    free(m->st);
    free(m->tri);
    free(m->slot);
    memset(m, 0, sizeof *m);
}

static svet_status validate(const mesh_t *m, svet_error *err)
{
    if (m->nverts <= 0 || m->nverts > MESH_MAX_VERTICES || !m->p)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "mesh: %d vertices (need 1 to %ld)", m->nverts,
                              MESH_MAX_VERTICES);
    if (m->ntris <= 0 || m->ntris > MESH_MAX_TRIANGLES || !m->tri)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "mesh: %d triangles (need 1 to %ld)", m->ntris,
                              MESH_MAX_TRIANGLES);
    for (int i = 0; i < m->nverts; i++) {
        if (!vec_is_finite(m->p[i]))
            return svet_error_set(err, SVET_ERR_RANGE,
                                  "mesh: vertex %d is not finite", i);
        if (m->n && !vec_is_finite(m->n[i]))
            return svet_error_set(err, SVET_ERR_RANGE,
                                  "mesh: normal of vertex %d is not finite",
                                  i);
        if (m->st && (isinf(m->st[i][0]) || isinf(m->st[i][1])))
            return svet_error_set(err, SVET_ERR_RANGE,
                                  "mesh: st of vertex %d is infinite", i);
    }
    for (int i = 0; i < m->ntris; i++)
        for (int k = 0; k < 3; k++)
            if (m->tri[i][k] < 0 || m->tri[i][k] >= m->nverts)
                return svet_error_set(err, SVET_ERR_RANGE,
                                      "mesh: triangle %d refers to vertex "
                                      "%ld of %d",
                                      i, (long)m->tri[i][k], m->nverts);
    return SVET_OK;
}

/* Vose's stable form of Walker's alias method, in double: every slot
 * starts with weight n A_i / A; slots below 1 are topped up from one
 * above 1, which becomes their alias. O(n) (M. D. Vose, "A linear
 * algorithm for generating random numbers with a given distribution",
 * IEEE Trans. Software Eng. 17(9), 1991). */
static svet_status build_alias(mesh_t *m, const double *area)
{
    int n = m->ntris;
    double *w = malloc((size_t)n * sizeof *w);
    int32_t *small = malloc((size_t)n * sizeof *small);
    int32_t *large = malloc((size_t)n * sizeof *large);
    m->alias_prob = malloc((size_t)n * sizeof *m->alias_prob);
    m->alias = malloc((size_t)n * sizeof *m->alias);
    if (!w || !small || !large || !m->alias_prob || !m->alias) {
        free(w);
        free(small);
        free(large);
        return SVET_ERR_NOMEM;
    }
    int ns = 0, nl = 0;
    for (int i = 0; i < n; i++) {
        w[i] = m->area > 0 ? area[i] * n / m->area : 1;
        m->alias[i] = i;
        if (w[i] < 1)
            small[ns++] = i;
        else
            large[nl++] = i;
    }
    while (ns > 0 && nl > 0) {
        int s = small[--ns], l = large[nl - 1];
        m->alias_prob[s] = (real)w[s];
        m->alias[s] = l;
        w[l] -= 1 - w[s];
        if (w[l] < 1) {
            nl--;
            small[ns++] = l;
        }
    }
    /* What remains is 1 up to rounding. */
    while (nl > 0)
        m->alias_prob[large[--nl]] = 1;
    while (ns > 0)
        m->alias_prob[small[--ns]] = 1;
    free(w);
    free(small);
    free(large);
    return SVET_OK;
}

svet_status mesh_new(COBJECT **out, mesh_t *given, svet_error *err)
{
    *out = NULL;
    svet_status st = validate(given, err);
    if (st != SVET_OK) {
        free_given(given);
        return st;
    }
    mesh_t *m = calloc(1, sizeof *m);
    COBJECT *obj = malloc(sizeof *obj);
    if (!m || !obj) {
        free(m);
        free(obj);
        free_given(given);
        return svet_error_set(err, SVET_ERR_NOMEM, "mesh: out of memory");
    }
    *m = *given;
    memset(given, 0, sizeof *given);
    m->alias = NULL;
    m->alias_prob = NULL;
    cobject_init(obj, &mesh_ops, m);
    obj->nprims = m->ntris;

    int n = m->ntris;
    double *area = malloc((size_t)n * sizeof *area);
    if (!area) {
        free(area);
        cobject_free(obj);
        return svet_error_set(err, SVET_ERR_NOMEM, "mesh: out of memory");
    }
    if (m->n)
        for (int i = 0; i < m->nverts; i++)
            vec_normalize(m->n[i], m->n[i]); /* a zero stays zero */
    bbox_empty(&m->bounds);
    m->area = 0;
    for (int i = 0; i < n; i++) {
        for (int k = 0; k < 3; k++)
            bbox_add_point(&m->bounds, m->p[m->tri[i][k]]);
        /* Area = |(p1 - p0) x (p2 - p0)| / 2, in double; 0 for a triangle
         * the intersection test calls degenerate, so sampling never picks
         * a triangle a ray cannot hit. */
        area[i] = 0;
        if (!mesh_triangle_is_degenerate(m, i)) {
            double e1[3], e2[3];
            real q[9];
            mesh_triangle_corners(m, i, q);
            for (int k = 0; k < 3; k++) {
                e1[k] = (double)q[3 + k] - (double)q[k];
                e2[k] = (double)q[6 + k] - (double)q[k];
            }
            double cx = e1[1] * e2[2] - e1[2] * e2[1];
            double cy = e1[2] * e2[0] - e1[0] * e2[2];
            double cz = e1[0] * e2[1] - e1[1] * e2[0];
            area[i] = 0.5 * sqrt(cx * cx + cy * cy + cz * cz);
        }
        m->area += area[i];
    }
    st = build_alias(m, area);
    free(area);
    if (st != SVET_OK) {
        cobject_free(obj);
        return svet_error_set(err, SVET_ERR_NOMEM, "mesh: out of memory");
    }
    *out = obj;
    return SVET_OK;
}

size_t mesh_bytes(const COBJECT *obj)
{
    const mesh_t *m = mesh_get(obj);
    if (!m)
        return 0;
    size_t v = (size_t)m->nverts, t = (size_t)m->ntris;
    size_t b = sizeof *obj + sizeof *m + v * sizeof *m->p +
               t * (sizeof *m->tri + sizeof *m->alias_prob +
                    sizeof *m->alias);
    if (m->n)
        b += v * sizeof *m->n;
    if (m->st)
        b += v * sizeof *m->st;
    if (m->slot)
        b += t * sizeof *m->slot;
    return b;
}

svet_status mesh_new_subset(COBJECT **out, const COBJECT *src, int32_t slot,
                            svet_error *err)
{
    *out = NULL;
    const mesh_t *s = mesh_get(src);
    if (!s)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "mesh_new_subset: not a mesh");
    int nt = 0;
    for (int i = 0; i < s->ntris; i++)
        nt += (s->slot ? s->slot[i] : 0) == slot;
    if (nt == 0)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "mesh_new_subset: no triangle has slot %ld",
                              (long)slot);
    int32_t *map = malloc((size_t)s->nverts * sizeof *map);
    mesh_t m = { 0 };
    m.tri = malloc((size_t)nt * sizeof *m.tri);
    m.slot = s->slot ? malloc((size_t)nt * sizeof *m.slot) : NULL;
    if (!map || !m.tri || (s->slot && !m.slot)) {
        free(map);
        free_given(&m);
        return svet_error_set(err, SVET_ERR_NOMEM, "mesh: out of memory");
    }
    for (int i = 0; i < s->nverts; i++)
        map[i] = -1;
    int nv = 0;
    for (int i = 0; i < s->ntris; i++) {
        if ((s->slot ? s->slot[i] : 0) != slot)
            continue;
        for (int k = 0; k < 3; k++) {
            int32_t v = s->tri[i][k];
            if (map[v] < 0)
                map[v] = nv++;
            m.tri[m.ntris][k] = map[v];
        }
        if (m.slot)
            m.slot[m.ntris] = slot;
        m.ntris++;
    }
    m.nverts = nv;
    m.p = malloc((size_t)nv * sizeof *m.p);
    m.n = s->n ? malloc((size_t)nv * sizeof *m.n) : NULL;
    m.st = s->st ? malloc((size_t)nv * sizeof *m.st) : NULL;
    if (!m.p || (s->n && !m.n) || (s->st && !m.st)) {
        free(map);
        free_given(&m);
        return svet_error_set(err, SVET_ERR_NOMEM, "mesh: out of memory");
    }
    for (int i = 0; i < s->nverts; i++) {
        int32_t j = map[i];
        if (j < 0)
            continue;
        vec_copy(m.p[j], s->p[i]);
        if (m.n)
            vec_copy(m.n[j], s->n[i]);
        if (m.st) {
            m.st[j][0] = s->st[i][0];
            m.st[j][1] = s->st[i][1];
        }
    }
    free(map);
    return mesh_new(out, &m, err);
}
