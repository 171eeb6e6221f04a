/*
 * box.c - the axis-aligned box of app. D: Kay & Kajiya's slab test (1986)
 * with pbrt-v3's conservative exit distance (sec. 3.9.2), so no ray slips
 * through an edge, and hit points set exactly on the face.
 * Tests: tests/geometry/test_box.c; vectors: tests/vectors/box.csv
 */
#include "geometry/box.h"
#include "geometry/shape.h"

typedef struct {
    VECTOR3 min, max;
    VECTOR3 ext;       /* max - min */
    real face_area[3]; /* area of each of the two faces across axis k */
    real area;
} box_shape;

/* One axis k of box_intersect's slab test: narrows [lo, hi] and their
 * faces; false when the ray is parallel to the slab and outside it.
 * Inline, so that the three axes are written out with k a constant. */
static inline bool slab(const box_shape *s, const ray_t *r, int k, real *lo,
                        real *hi, int *face_lo, int *face_hi)
{
    if (r->d[k] == 0) {
        /* parallel to the slab: inside it for every t, or never */
        return !(r->o[k] < s->min[k] || r->o[k] > s->max[k]);
    }
    /* Division rather than a reciprocal: 1/d overflows for a tiny d,
     * and (min - o) * inf gives NaN when o lies on the slab plane. */
    real t0 = (s->min[k] - r->o[k]) / r->d[k];
    real t1 = (s->max[k] - r->o[k]) / r->d[k];
    int f0 = 2 * k, f1 = 2 * k + 1;
    if (r->d[k] < 0) {
        real tt = t0; t0 = t1; t1 = tt;
        int ff = f0; f0 = f1; f1 = ff;
    }
    /* pbrt-v3 sec. 3.9.2: t0 and t1 carry two roundings each (gamma(2)
     * relative); pushing the exit out by 2 gamma(3) |t1| keeps a ray
     * through an edge, where exactly t0 = t1 of another axis, inside. */
    t1 += 2 * ray_gamma(3) * fabs(t1);
    if (t0 > *lo) {
        *lo = t0;
        *face_lo = f0;
    }
    if (t1 < *hi) {
        *hi = t1;
        *face_hi = f1;
    } else if (t1 != t1) {
        /* an exit that overflowed to -infinity (a ray far beyond the
         * slab, moving away slowly) comes out of the push as NaN, which
         * no comparison would keep: the slab lies behind the ray */
        return false;
    }
    return true;
}

static bool box_intersect(const COBJECT *obj, int prim, const ray_t *r,
                          real tmin, real tmax, hit_t *hit)
{
    const box_shape *s = obj->shape;
    real lo = -(real)INFINITY, hi = (real)INFINITY;
    int face_lo = -1, face_hi = -1;
    if (!slab(s, r, 0, &lo, &hi, &face_lo, &face_hi) ||
        !slab(s, r, 1, &lo, &hi, &face_lo, &face_hi) ||
        !slab(s, r, 2, &lo, &hi, &face_lo, &face_hi))
        return false;
    if (!(lo <= hi))
        return false;
    /* the entry face, or the exit face for a ray that starts inside */
    if (lo > tmin && lo < tmax) {
        hit->t = lo;
        hit->b[0] = (real)face_lo;
    } else if (hi > tmin && hi < tmax) {
        hit->t = hi;
        hit->b[0] = (real)face_hi;
    } else {
        return false;
    }
    hit->prim = prim;
    return true;
}

/* The frame of face f: ng, the axes of u and v (see box.h). */
static void face_axes(int f, int *k, int *au, int *av)
{
    *k = f / 2;
    int a = (*k + 1) % 3, b = (*k + 2) % 3;
    *au = (f & 1) ? a : b;
    *av = (f & 1) ? b : a;
}

/* PATHPOINT fields that depend on the face only, and st from the point. */
static void face_fill(const box_shape *s, int f, PATHPOINT *pp)
{
    int k, au, av;
    face_axes(f, &k, &au, &av);
    vec_set(pp->ng, 0, 0, 0);
    pp->ng[k] = (f & 1) ? 1 : -1;
    vec_copy(pp->n, pp->ng);
    vec_set(pp->u, 0, 0, 0);
    vec_set(pp->v, 0, 0, 0);
    pp->u[au] = 1;
    pp->v[av] = 1;
    vec_set(pp->dpds, 0, 0, 0);
    vec_set(pp->dpdt, 0, 0, 0);
    pp->dpds[au] = s->ext[au];
    pp->dpdt[av] = s->ext[av];
    const int ax[2] = { au, av };
    for (int i = 0; i < 2; i++) {
        real e = s->ext[ax[i]];
        real x = e > 0 ? (pp->cross_point[ax[i]] - s->min[ax[i]]) / e
                       : REAL_C(0.5);
        pp->st[i] = real_min(real_max(x, REAL_C(0.0)), REAL_C(1.0));
    }
    pp->prim = f;
}

static void box_surface(const COBJECT *obj, const ray_t *r, const hit_t *hit,
                        PATHPOINT *pp)
{
    const box_shape *s = obj->shape;
    int f = (int)hit->b[0], k = f / 2;
    for (int j = 0; j < 3; j++) {
        if (j == k) {
            /* the face's own coordinate: exact */
            pp->cross_point[j] = (f & 1) ? s->max[j] : s->min[j];
            pp->p_error[j] = 0;
            continue;
        }
        /* o_j + t d_j: t carries gamma(2) from its subtraction and
         * division and up to 2 gamma(3) from the pushed exit, the product
         * and the sum two more roundings: within gamma(11) (|o_j| +
         * |t d_j|) of the exact hit. Clamping into the face, where the
         * exact hit lies, can only bring it closer. */
        real td = hit->t * r->d[j];
        real q = r->o[j] + td;
        /* real_min/real_max: no libm call, and the same answers as
         * fmin/fmax here, a NaN q included (it yields the bound) */
        pp->cross_point[j] = real_min(real_max(q, s->min[j]), s->max[j]);
        pp->p_error[j] = ray_gamma(11) * (fabs(r->o[j]) + fabs(td));
        if (!isfinite(pp->p_error[j]))
            pp->p_error[j] = s->ext[j];
    }
    face_fill(s, f, pp);
}

static void box_bounds(const COBJECT *obj, int prim, bbox_t *b)
{
    (void)prim;
    const box_shape *s = obj->shape;
    vec_copy(b->min, s->min);
    vec_copy(b->max, s->max);
}

static real box_area(const COBJECT *obj)
{
    return ((const box_shape *)obj->shape)->area;
}

static void box_sample(const COBJECT *obj, const real u[2],
                       cobject_sample_t *smp)
{
    const box_shape *s = obj->shape;
    /* Pick face f with probability area_f / area by walking the faces
     * along u0 * area, then reuse the rest of u0 inside the face. */
    real x = u[0] * s->area;
    int f = -1, last = 0;
    for (int i = 0; i < 6; i++) {
        real a = s->face_area[i / 2];
        if (a > 0)
            last = i;
        if (f < 0 && x < a)
            f = i;
        else if (f < 0)
            x -= a;
    }
    if (f < 0) /* u0 * area rounded up to the total: the last real face */
        f = last;
    int k, au, av;
    face_axes(f, &k, &au, &av);
    real a = s->face_area[k];
    real w[2] = { a > 0 ? fmin(fmax(x / a, REAL_C(0.0)), REAL_C(1.0)) : 0,
                  u[1] };
    const int ax[2] = { au, av };
    smp->p[k] = (f & 1) ? s->max[k] : s->min[k];
    smp->p_error[k] = 0;
    for (int i = 0; i < 2; i++) {
        int j = ax[i];
        real step = w[i] * s->ext[j];
        smp->p[j] = fmin(s->min[j] + step, s->max[j]);
        /* one product and one sum */
        smp->p_error[j] = ray_gamma(2) * (fabs(s->min[j]) + fabs(step));
    }
    vec_set(smp->n, 0, 0, 0);
    smp->n[k] = (f & 1) ? 1 : -1;
    smp->pdf = 1 / s->area;
}

static const cobject_ops box_ops = {
    "box", box_intersect, box_surface, box_bounds, box_area, box_sample,
    NULL, NULL
};

COBJECT *box_new(const VECTOR3 min, const VECTOR3 max, svet_error *err)
{
    if (shape_check_finite("box", "min", min, err) ||
        shape_check_finite("box", "max", max, err))
        return NULL;
    VECTOR3 ext;
    for (int k = 0; k < 3; k++) {
        if (min[k] > max[k]) {
            svet_error_set(err, SVET_ERR_RANGE, "box: min %c = %g > max %c "
                           "= %g", "xyz"[k], (double)min[k], "xyz"[k],
                           (double)max[k]);
            return NULL;
        }
        ext[k] = max[k] - min[k];
    }
    real fa[3], area = 0;
    for (int k = 0; k < 3; k++) {
        fa[k] = ext[(k + 1) % 3] * ext[(k + 2) % 3];
        area += 2 * fa[k];
    }
    if (!vec_is_finite(ext) || !isfinite(area) || !(area > 0) ||
        !isfinite(1 / area)) {
        svet_error_set(err, SVET_ERR_RANGE, "box: extents (%g, %g, %g) give "
                       "an area of %g, out of the range of %s",
                       (double)ext[X], (double)ext[Y], (double)ext[Z],
                       (double)area, REAL_NAME);
        return NULL;
    }
    COBJECT *obj = shape_alloc(&box_ops, sizeof(box_shape), err);
    if (!obj)
        return NULL;
    obj->surface_fills = true; /* box_surface() and face_fill() write all */
    box_shape *s = obj->shape;
    vec_copy(s->min, min);
    vec_copy(s->max, max);
    vec_copy(s->ext, ext);
    for (int k = 0; k < 3; k++)
        s->face_area[k] = fa[k];
    s->area = area;
    return obj;
}
