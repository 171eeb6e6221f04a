/*
 * primset.c - listing a scene's sub-primitives for the acceleration
 * structures of ch. 7 (see primset.h): mesh triangles first, with their
 * corners copied side by side, then the other bounded primitives, then the
 * unbounded ones.
 * Tests: tests/accel/test_primset.c
 */
#include "accel/primset.h"

#include <stdlib.h>

/* Bounds that reach past +-REAL_MAX / 16 are taken for infinite: an
 * infinite plane reports +-REAL_MAX, and a grid over such a box would have
 * cells wider than anything in the scene. */
static bool bounds_finite(const bbox_t *b)
{
    const real huge = REAL_MAX / 16;
    for (int k = 0; k < 3; k++)
        if (!(fabs(b->min[k]) <= huge && fabs(b->max[k]) <= huge))
            return false;
    return !bbox_is_empty(b);
}

/* Which of the three groups of primset.h primitive (o, k) belongs to. */
enum { GROUP_TRI, GROUP_BOUNDED, GROUP_UNBOUNDED, GROUP_NONE };

static int group_of(const COBJECT *o, int k, bbox_t *b)
{
    const mesh_t *m = mesh_get(o);
    if (m && mesh_triangle_is_degenerate(m, k))
        return GROUP_NONE;
    o->ops->bounds(o, k, b);
    if (!bounds_finite(b))
        return GROUP_UNBOUNDED;
    return m ? GROUP_TRI : GROUP_BOUNDED;
}

/* Spread the low 10 bits of x to every third bit. */
static uint32_t spread3(uint32_t x)
{
    x &= 0x3ff;
    x = (x | (x << 16)) & 0x030000ff;
    x = (x | (x << 8)) & 0x0300f00f;
    x = (x | (x << 4)) & 0x030c30c3;
    x = (x | (x << 2)) & 0x09249249;
    return x;
}

/* Sort the triangles refs[0 .. ntri) (with their bounds and corners) by
 * the 30-bit Morton code of their centroids on a 1024^3 lattice over the
 * triangles' box: a least-significant-digit radix sort, 3 passes of 10
 * bits, stable. Returns false when memory runs out (nothing changed). */
static bool morton_sort(primset_t *ps)
{
    uint32_t n = ps->ntri;
    if (n < 2)
        return true;
    bbox_t box;
    bbox_empty(&box);
    for (uint32_t i = 0; i < n; i++)
        bbox_union(&box, &ps->bounds[i]);
    uint32_t *key = malloc(2 * (size_t)n * sizeof *key);
    uint32_t *idx = malloc(2 * (size_t)n * sizeof *idx);
    primref_t *refs = malloc((size_t)n * sizeof *refs);
    bbox_t *bounds = malloc((size_t)n * sizeof *bounds);
    real(*tri)[9] = malloc((size_t)n * sizeof *tri);
    bool ok = key && idx && refs && bounds && tri;
    if (ok) {
        double lo[3], scale[3];
        for (int a = 0; a < 3; a++) {
            lo[a] = (double)box.min[a];
            double ext = (double)box.max[a] - lo[a];
            scale[a] = ext > 0 && isfinite(ext) ? 1023.999 / ext : 0;
        }
        for (uint32_t i = 0; i < n; i++) {
            uint32_t c[3];
            for (int a = 0; a < 3; a++) {
                double m = 0.5 * (double)ps->bounds[i].min[a] +
                           0.5 * (double)ps->bounds[i].max[a];
                double q = (m - lo[a]) * scale[a];
                c[a] = q > 0 ? (uint32_t)fmin(q, 1023.0) : 0;
            }
            key[i] = spread3(c[0]) | spread3(c[1]) << 1 | spread3(c[2]) << 2;
            idx[i] = i;
        }
        uint32_t *k0 = key, *k1 = key + n, *i0 = idx, *i1 = idx + n;
        uint32_t count[1025];
        for (int shift = 0; shift < 30; shift += 10) {
            memset(count, 0, sizeof count);
            for (uint32_t i = 0; i < n; i++)
                count[((k0[i] >> shift) & 1023) + 1]++;
            for (int b = 0; b < 1024; b++)
                count[b + 1] += count[b];
            for (uint32_t i = 0; i < n; i++) {
                uint32_t d = count[(k0[i] >> shift) & 1023]++;
                k1[d] = k0[i];
                i1[d] = i0[i];
            }
            uint32_t *t = k0; k0 = k1; k1 = t;
            t = i0; i0 = i1; i1 = t;
        }
        for (uint32_t i = 0; i < n; i++) {
            refs[i] = ps->refs[i0[i]];
            bounds[i] = ps->bounds[i0[i]];
            memcpy(tri[i], ps->tri[i0[i]], sizeof tri[i]);
        }
        memcpy(ps->refs, refs, (size_t)n * sizeof *refs);
        memcpy(ps->bounds, bounds, (size_t)n * sizeof *bounds);
        memcpy(ps->tri, tri, (size_t)n * sizeof *tri);
    }
    free(key);
    free(idx);
    free(refs);
    free(bounds);
    free(tri);
    return ok;
}

svet_status primset_build(primset_t *ps, COBJECT *const *objs, int nobjs,
                          svet_error *err)
{
    memset(ps, 0, sizeof *ps);
    bbox_empty(&ps->box);
    ps->objs = objs;
    ps->nobjs = nobjs > 0 ? nobjs : 0;
    /* Count each group (bounds are cheap to recompute: mesh triangles
     * and analytic shapes alike). */
    uint64_t count[4] = { 0, 0, 0, 0 };
    for (int i = 0; i < ps->nobjs; i++) {
        const COBJECT *o = objs[i];
        for (int k = 0; o && k < o->nprims; k++) {
            bbox_t b;
            count[group_of(o, k, &b)]++;
        }
    }
    uint64_t total = count[GROUP_TRI] + count[GROUP_BOUNDED] +
                     count[GROUP_UNBOUNDED];
    if (total > PRIMSET_MAX_REFS)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "accel: %llu primitives, more than %u",
                              (unsigned long long)total, PRIMSET_MAX_REFS);
    size_t n = (size_t)total;
    ps->refs = malloc((n + 1) * sizeof *ps->refs);
    ps->bounds = malloc((n + 1) * sizeof *ps->bounds);
    ps->tri = malloc(((size_t)count[GROUP_TRI] + 1) * sizeof *ps->tri);
    if (!ps->refs || !ps->bounds || !ps->tri) {
        primset_free(ps);
        return svet_error_set(err, SVET_ERR_NOMEM, "accel: out of memory");
    }
    ps->ntri = (uint32_t)count[GROUP_TRI];
    ps->nbounded = ps->ntri + (uint32_t)count[GROUP_BOUNDED];
    ps->nrefs = (uint32_t)n;
    uint32_t next[3] = { 0, ps->ntri, ps->nbounded };
    for (int i = 0; i < ps->nobjs; i++) {
        const COBJECT *o = objs[i];
        const mesh_t *m = mesh_get(o);
        for (int k = 0; o && k < o->nprims; k++) {
            bbox_t b;
            int g = group_of(o, k, &b);
            if (g == GROUP_NONE)
                continue;
            uint32_t r = next[g]++;
            ps->refs[r].obj = (uint32_t)i;
            ps->refs[r].prim = (uint32_t)k;
            if (g == GROUP_UNBOUNDED)
                continue;
            ps->bounds[r] = b;
            bbox_union(&ps->box, &b);
            if (g == GROUP_TRI)
                mesh_triangle_corners(m, k, ps->tri[r]);
        }
    }
    if (!morton_sort(ps)) {
        primset_free(ps);
        return svet_error_set(err, SVET_ERR_NOMEM, "accel: out of memory");
    }
    if (ps->nbounded > 0) {
        double dx = (double)ps->box.max[X] - (double)ps->box.min[X];
        double dy = (double)ps->box.max[Y] - (double)ps->box.min[Y];
        double dz = (double)ps->box.max[Z] - (double)ps->box.min[Z];
        double diag = sqrt(dx * dx + dy * dy + dz * dz);
        double big = 0;
        for (int k = 0; k < 3; k++)
            big = fmax(big, fmax(fabs((double)ps->box.min[k]),
                                 fabs((double)ps->box.max[k])));
        ps->pad = diag * 0x1p-20 + 8 * (double)REAL_EPSILON * big;
        if (!(ps->pad > 0))
            ps->pad = 0x1p-60;
    }
    return SVET_OK;
}

void primset_drop_bounds(primset_t *ps)
{
    free(ps->bounds);
    ps->bounds = NULL;
}

void primset_free(primset_t *ps)
{
    if (!ps)
        return;
    free(ps->refs);
    free(ps->bounds);
    free(ps->tri);
    memset(ps, 0, sizeof *ps);
}

size_t primset_bytes(const primset_t *ps)
{
    size_t b = (size_t)ps->nrefs * sizeof *ps->refs +
               (size_t)ps->ntri * sizeof *ps->tri;
    if (ps->bounds)
        b += (size_t)ps->nbounded * sizeof *ps->bounds;
    return b;
}
