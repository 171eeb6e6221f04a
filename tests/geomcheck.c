/*
 * geomcheck.c - primitive-independent robustness tests; see geomcheck.h.
 * Origins, targets and directions come from a seeded PCG32, so a failure
 * reproduces exactly; each message names the case.
 */
#include "geomcheck.h"
#include "core/frame.h"
#include "testutil.h"

#include <math.h>

void geomcheck_random_dir(VECTOR3 w, pcg32_t *g)
{
    real z = 1 - 2 * pcg32_real(g), phi = 2 * REAL_PI * pcg32_real(g);
    real r = sqrt(fmax(REAL_C(0.0), 1 - z * z));
    vec_set(w, r * cos(phi), r * sin(phi), z);
}

real geomcheck_any_class(pcg32_t *g)
{
    static const real special[] = {
        0, -REAL_C(0.0), REAL_TRUE_MIN, -REAL_TRUE_MIN, REAL_MIN, REAL_MAX,
        -REAL_MAX, (real)INFINITY, -(real)INFINITY, (real)NAN, 1, -1,
    };
    uint32_t k = pcg32_bounded(g, 4);
    if (k == 0)
        return special[pcg32_bounded(g, sizeof special / sizeof *special)];
    real x = ldexp(REAL_C(1.0) + pcg32_real(g), (int)pcg32_bounded(g, 61) - 30);
    return k == 1 ? x : -x;
}

void geomcheck_any_ray(ray_t *r, real *tmin, real *tmax, pcg32_t *g)
{
    for (int k = 0; k < 3; k++) {
        r->o[k] = geomcheck_any_class(g);
        r->d[k] = geomcheck_any_class(g);
    }
    *tmin = pcg32_bounded(g, 2) ? 0 : geomcheck_any_class(g);
    *tmax = pcg32_bounded(g, 2) ? (real)INFINITY : geomcheck_any_class(g);
}

void geomcheck_random_hemisphere(VECTOR3 w, const VECTOR3 n, pcg32_t *g)
{
    geomcheck_random_dir(w, g);
    if (SVECTOR3(w, n) < 0)
        vec_neg(w, w);
}

static void bound_sphere(const COBJECT *obj, VECTOR3 c, real *radius)
{
    bbox_t b;
    obj->ops->bounds(obj, -1, &b);
    bbox_centroid(c, &b);
    VECTOR3 d;
    vec_sub(d, b.max, b.min);
    *radius = REAL_C(0.5) * vec_length(d);
}

static void random_in_box(VECTOR3 p, const bbox_t *b, pcg32_t *g)
{
    for (int i = 0; i < 3; i++) {
        real u = pcg32_real(g);
        p[i] = b->min[i] + u * (b->max[i] - b->min[i]);
    }
}

long geomcheck_spawn_never_rehits(const COBJECT *obj, geomcheck_kind kind,
                                  int n_rays, int n_spawn, uint64_t seed)
{
    pcg32_t g;
    pcg32_seed(&g, seed, 0x5a5a);
    bbox_t b;
    obj->ops->bounds(obj, -1, &b);
    VECTOR3 c;
    real R;
    bound_sphere(obj, c, &R);
    long tested = 0;
    for (int i = 0; i < n_rays; i++) {
        ray_t r;
        VECTOR3 dir, target;
        geomcheck_random_dir(dir, &g);
        vec_add_scaled(r.o, c, 3 * R, dir);
        random_in_box(target, &b, &g);
        vec_sub(r.d, target, r.o);
        if (vec_normalize(r.d, r.d) == 0)
            continue;
        hit_t h;
        if (!cobject_intersect(obj, &r, 0, (real)INFINITY, &h))
            continue;
        PATHPOINT pp;
        cobject_fill(obj, &r, &h, &pp);
        for (int k = 0; k < n_spawn; k++) {
            VECTOR3 w;
            geomcheck_random_dir(w, &g);
            if (kind != GEOMCHECK_FLAT && SVECTOR3(w, pp.ng) < 0)
                vec_neg(w, w);
            ray_t s;
            ray_spawn(&s, pp.cross_point, pp.p_error, pp.ng, w);
            hit_t h2;
            bool again = cobject_intersect(obj, &s, 0, (real)INFINITY, &h2);
            ck_assert_msg(!again,
                          "%s: ray %d spawn %d re-hits at t = %g: p = (%.9g "
                          "%.9g %.9g), ng = (%g %g %g), w = (%g %g %g)",
                          obj->ops->name, i, k, (double)h2.t,
                          (double)pp.cross_point[X], (double)pp.cross_point[Y],
                          (double)pp.cross_point[Z], (double)pp.ng[X],
                          (double)pp.ng[Y], (double)pp.ng[Z], (double)w[X],
                          (double)w[Y], (double)w[Z]);
            tested++;
        }
    }
    return tested;
}

static real max3(const VECTOR3 a)
{
    return fmax(fabs(a[X]), fmax(fabs(a[Y]), fabs(a[Z])));
}

long geomcheck_sampled_points_are_hit(const COBJECT *obj, geomcheck_kind kind,
                                      int n, real scale, uint64_t seed)
{
    pcg32_t g;
    pcg32_seed(&g, seed, 0xa5a5);
#ifdef SVET_DOUBLE
    const real rel = REAL_C(1e-12);
#else
    const real rel = REAL_C(1e-5);
#endif
    for (int i = 0; i < n; i++) {
        real u[2] = { pcg32_real(&g), pcg32_real(&g) };
        cobject_sample_t s;
        obj->ops->sample(obj, u, &s);
        VECTOR3 w;
        do
            geomcheck_random_hemisphere(w, s.n, &g);
        while (SVECTOR3(w, s.n) < REAL_C(0.05));
        real dist = scale * (REAL_C(0.01) + pcg32_real(&g));
        if (kind == GEOMCHECK_OPEN) {
            dist *= REAL_C(0.01);
            /* ... but off the surface by more than the sample's own error
             * box (8 times its half-width along n), or which side of the
             * surface the origin lies on is decided by rounding. */
            real box = fabs(s.n[X]) * s.p_error[X] +
                       fabs(s.n[Y]) * s.p_error[Y] +
                       fabs(s.n[Z]) * s.p_error[Z];
            dist = fmax(dist, 8 * box / SVECTOR3(w, s.n));
        }
        ray_t r;
        vec_add_scaled(r.o, s.p, dist, w);
        vec_sub(r.d, s.p, r.o);
        hit_t h;
        bool hit = cobject_intersect(obj, &r, 0, (real)INFINITY, &h);
        ck_assert_msg(hit, "%s: sample %d at (%.9g %.9g %.9g) not hit from "
                      "distance %g", obj->ops->name, i, (double)s.p[X],
                      (double)s.p[Y], (double)s.p[Z], (double)dist);
        PATHPOINT pp;
        cobject_fill(obj, &r, &h, &pp);
        real miss = vec_distance(pp.cross_point, s.p);
        real tol = 64 * (max3(s.p_error) + max3(pp.p_error)) +
                   rel * (dist + max3(s.p));
        ck_assert_msg(miss <= tol, "%s: sample %d: hit %g away from the "
                      "sampled point (tol %g), t = %g", obj->ops->name, i,
                      (double)miss, (double)tol, (double)h.t);
    }
    return n;
}

long geomcheck_shadow_rays_between_points_miss(const COBJECT *obj, int n,
                                               uint64_t seed)
{
    pcg32_t g;
    pcg32_seed(&g, seed, 0x3c3c);
    for (int i = 0; i < n; i++) {
        cobject_sample_t a, b;
        real u[2] = { pcg32_real(&g), pcg32_real(&g) };
        real v[2] = { pcg32_real(&g), pcg32_real(&g) };
        obj->ops->sample(obj, u, &a);
        obj->ops->sample(obj, v, &b);
        ray_t r;
        real tmax = ray_spawn_to(&r, a.p, a.p_error, a.n, b.p, b.p_error, b.n);
        hit_t h;
        bool hit = cobject_intersect(obj, &r, 0, tmax, &h);
        ck_assert_msg(!hit, "%s: pair %d: shadow ray from (%.9g %.9g %.9g) to "
                      "(%.9g %.9g %.9g) hits at t = %g", obj->ops->name, i,
                      (double)a.p[X], (double)a.p[Y], (double)a.p[Z],
                      (double)b.p[X], (double)b.p[Y], (double)b.p[Z],
                      (double)h.t);
    }
    return n;
}

static void check_unit(const char *name, const char *what, const VECTOR3 a)
{
    ck_assert_msg(vec_is_finite(a), "%s: %s not finite", name, what);
    ck_assert_msg(fabs(vec_length(a) - 1) <= 64 * REAL_EPSILON,
                  "%s: |%s| = %.9g", name, what, (double)vec_length(a));
}

long geomcheck_hits_are_finite(const COBJECT *obj, int n_rays, real scale,
                               uint64_t seed)
{
    pcg32_t g;
    pcg32_seed(&g, seed, 0x7e7e);
    bbox_t b;
    obj->ops->bounds(obj, -1, &b);
    VECTOR3 c;
    real R;
    bound_sphere(obj, c, &R);
    long hits = 0;
    for (int i = 0; i < n_rays; i++) {
        ray_t r;
        VECTOR3 dir;
        geomcheck_random_dir(dir, &g);
        vec_add_scaled(r.o, c, (R + scale) * pcg32_real(&g), dir);
        if (i % 2) {
            VECTOR3 target;
            random_in_box(target, &b, &g);
            vec_sub(r.d, target, r.o);
            if (vec_normalize(r.d, r.d) == 0)
                continue;
        } else {
            geomcheck_random_dir(r.d, &g);
        }
        hit_t h;
        if (!cobject_intersect(obj, &r, 0, (real)INFINITY, &h))
            continue;
        hits++;
        ck_assert(isfinite(h.t) && h.t > 0);
        PATHPOINT pp;
        cobject_fill(obj, &r, &h, &pp);
        const char *nm = obj->ops->name;
        ck_assert_msg(vec_is_finite(pp.cross_point), "%s: point", nm);
        ck_assert_msg(vec_is_finite(pp.p_error), "%s: p_error", nm);
        ck_assert_msg(isfinite(pp.st[0]) && isfinite(pp.st[1]), "%s: st", nm);
        ck_assert_msg(vec_is_finite(pp.dpds) && vec_is_finite(pp.dpdt),
                      "%s: dpds/dpdt", nm);
        ck_assert_msg(isfinite(pp.r_dist), "%s: r_dist", nm);
        check_unit(nm, "n", pp.n);
        check_unit(nm, "ng", pp.ng);
        check_unit(nm, "u", pp.u);
        check_unit(nm, "v", pp.v);
        ck_assert_msg(fabs(SVECTOR3(pp.u, pp.n)) <= 64 * REAL_EPSILON &&
                          fabs(SVECTOR3(pp.v, pp.n)) <= 64 * REAL_EPSILON &&
                          fabs(SVECTOR3(pp.u, pp.v)) <= 64 * REAL_EPSILON,
                      "%s: frame not orthogonal", nm);
    }
    return hits;
}

long geomcheck_sampling_matches_area(const COBJECT *obj, int n, bool uniform,
                                     uint64_t seed)
{
    pcg32_t g;
    pcg32_seed(&g, seed, 0x1f1f);
    real area = obj->ops->area(obj);
    ck_assert_msg(area > 0 && isfinite(area), "%s: area %g", obj->ops->name,
                  (double)area);
    bbox_t b;
    obj->ops->bounds(obj, -1, &b);
    for (int i = 0; i < n; i++) {
        real u[2] = { pcg32_real(&g), pcg32_real(&g) };
        if (i == 0)
            u[0] = u[1] = 0;
        if (i == 1) /* the largest real below 1 */
            u[0] = u[1] = nextafter(REAL_C(1.0), REAL_C(0.0));
        cobject_sample_t s;
        obj->ops->sample(obj, u, &s);
        ck_assert_msg(vec_is_finite(s.p) && isfinite(s.pdf) && s.pdf > 0,
                      "%s: sample %d not finite", obj->ops->name, i);
        check_unit(obj->ops->name, "sample n", s.n);
        if (uniform)
            ck_assert_rel(s.pdf, 1 / area, 64 * REAL_EPSILON, 0);
        for (int k = 0; k < 3; k++) {
            real pad = 4 * s.p_error[k] + 8 * REAL_EPSILON * fabs(s.p[k]);
            ck_assert_msg(s.p[k] >= b.min[k] - pad && s.p[k] <= b.max[k] + pad,
                          "%s: sample %d outside the bounds on axis %d",
                          obj->ops->name, i, k);
        }
    }
    return n;
}
