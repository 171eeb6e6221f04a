/*
 * primcheck.c - the geomcheck harness over scales and placements, and the
 * sweep of extreme rays; see primcheck.h.
 */
#include "primcheck.h"
#include "testutil.h"

#include <math.h>

#ifdef SVET_DOUBLE
static const real scales[] = { REAL_C(1e-8), REAL_C(1e-4), REAL_C(1.0),
                               REAL_C(1e4), REAL_C(1e8) };
#else
static const real scales[] = { REAL_C(1e-4), REAL_C(1e-2), REAL_C(1.0),
                               REAL_C(1e2), REAL_C(1e4), REAL_C(1e6) };
#endif

const real *primcheck_scales(int *n)
{
    *n = (int)(sizeof scales / sizeof scales[0]);
    return scales;
}

long primcheck_over_scales(primcheck_make_fn make, void *ctx,
                           primcheck_test test, geomcheck_kind kind,
                           bool uniform, uint64_t seed)
{
    /* centres: at the origin, a few sizes away, and far away relative to
     * the size (where the coordinates' rounding dominates) */
    static const real away[3][4] = { { 0, 0, 0, 0 },
                                     { 5, REAL_C(0.6), REAL_C(-0.48), REAL_C(0.64) },
                                     { 1000, REAL_C(-0.36), REAL_C(0.8), REAL_C(0.48) } };
    int ns;
    const real *sc = primcheck_scales(&ns);
    long cases = 0;
    for (int i = 0; i < ns; i++) {
        for (int j = 0; j < 3; j++) {
            VECTOR3 c;
            for (int k = 0; k < 3; k++)
                c[k] = away[j][0] * sc[i] * away[j][k + 1];
            COBJECT *obj = make(sc[i], c, ctx);
            if (!obj)
                continue;
            uint64_t s = seed + (uint64_t)(100 * i + j);
            switch (test) {
            case PRIMCHECK_SPAWN:
                cases += geomcheck_spawn_never_rehits(obj, kind, 100, 8, s);
                break;
            case PRIMCHECK_SAMPLED:
                cases += geomcheck_sampled_points_are_hit(obj, kind, 300,
                                                          sc[i], s);
                break;
            case PRIMCHECK_SHADOW:
                cases += geomcheck_shadow_rays_between_points_miss(obj, 300, s);
                break;
            case PRIMCHECK_FINITE:
                cases += geomcheck_hits_are_finite(obj, 400, sc[i], s);
                break;
            case PRIMCHECK_AREA:
                cases += geomcheck_sampling_matches_area(obj, 300, uniform, s);
                break;
            }
            cobject_free(obj);
        }
    }
    return cases;
}

/* A real of random sign and magnitude 2^e, e uniform over nearly the whole
 * exponent range of real (subnormals included); zero one time in 16. */
static real wild(pcg32_t *g)
{
    uint32_t z = pcg32_next(g);
    if ((z & 15) == 0)
        return 0;
#ifdef SVET_DOUBLE
    int lo = DBL_MIN_EXP - 40, hi = DBL_MAX_EXP - 2;
#else
    int lo = FLT_MIN_EXP - 20, hi = FLT_MAX_EXP - 2;
#endif
    int e = lo + (int)pcg32_bounded(g, (uint32_t)(hi - lo));
    real m = 1 + pcg32_real(g);
    real v = ldexp(m, e);
    return (z & 16) ? -v : v;
}

static void check_finite_unit(const char *nm, const char *what,
                              const VECTOR3 a, long i)
{
    ck_assert_msg(vec_is_finite(a), "%s: ray %ld: %s not finite", nm, i, what);
    ck_assert_msg(fabs(vec_length(a) - 1) <= 64 * REAL_EPSILON,
                  "%s: ray %ld: |%s| = %g", nm, i, what, (double)vec_length(a));
}

long primcheck_sweep_finite(const COBJECT *obj, int n, uint64_t seed)
{
    pcg32_t g;
    pcg32_seed(&g, seed, 0x5eed);
    const char *nm = obj->ops->name;
    bbox_t b;
    obj->ops->bounds(obj, -1, &b);
    ck_assert_msg(!(b.min[X] != b.min[X] || b.max[X] != b.max[X] ||
                    b.min[Y] != b.min[Y] || b.max[Y] != b.max[Y] ||
                    b.min[Z] != b.min[Z] || b.max[Z] != b.max[Z]),
                  "%s: NaN in bounds", nm);
    real area = obj->ops->area(obj);
    ck_assert_msg(area == area && area >= 0, "%s: area %g", nm, (double)area);
    long i;
    for (i = 0; i < n; i++) {
        ray_t r;
        int mode = (int)pcg32_bounded(&g, 4);
        for (int k = 0; k < 3; k++) {
            /* modes: wild origin; origin in the (finite part of the)
             * bound; origin in the bound and a wild direction; wild both */
            real in = b.min[k] + pcg32_real(&g) * (b.max[k] - b.min[k]);
            if (!isfinite(in))
                in = wild(&g);
            r.o[k] = (mode == 0 || mode == 3) ? wild(&g) : in;
            r.d[k] = (mode >= 2) ? wild(&g) : 2 * pcg32_real(&g) - 1;
        }
        if (r.d[X] == 0 && r.d[Y] == 0 && r.d[Z] == 0)
            r.d[pcg32_bounded(&g, 3)] = REAL_MIN;
        real tmin = (pcg32_next(&g) & 3) ? 0 : fabs(wild(&g));
        real tmax = (pcg32_next(&g) & 1) ? (real)INFINITY
                                         : tmin + fabs(wild(&g));
        hit_t h;
        if (!cobject_intersect(obj, &r, tmin, tmax, &h))
            continue;
        ck_assert_msg(isfinite(h.t) && h.t > tmin && h.t < tmax,
                      "%s: ray %ld: t = %g outside (%g, %g)", nm, i,
                      (double)h.t, (double)tmin, (double)tmax);
        PATHPOINT pp;
        cobject_fill(obj, &r, &h, &pp);
        /* r_dist = t |d| is left out: it may truly exceed REAL_MAX */
        ck_assert_msg(vec_is_finite(pp.cross_point) &&
                          vec_is_finite(pp.p_error) &&
                          vec_is_finite(pp.dpds) && vec_is_finite(pp.dpdt) &&
                          isfinite(pp.st[0]) && isfinite(pp.st[1]),
                      "%s: ray %ld: PATHPOINT not finite: p (%g %g %g) "
                      "p_error (%g %g %g) st (%g %g), t = %g, o = (%g %g "
                      "%g), d = (%g %g %g)", nm, i, (double)pp.cross_point[X],
                      (double)pp.cross_point[Y], (double)pp.cross_point[Z],
                      (double)pp.p_error[X], (double)pp.p_error[Y],
                      (double)pp.p_error[Z], (double)pp.st[0],
                      (double)pp.st[1], (double)h.t, (double)r.o[X],
                      (double)r.o[Y], (double)r.o[Z], (double)r.d[X],
                      (double)r.d[Y], (double)r.d[Z]);
        check_finite_unit(nm, "n", pp.n, i);
        check_finite_unit(nm, "ng", pp.ng, i);
        check_finite_unit(nm, "u", pp.u, i);
        check_finite_unit(nm, "v", pp.v, i);
    }
    for (int j = 0; j < n / 4; j++) {
        real u[2] = { pcg32_real(&g), pcg32_real(&g) };
        if (j == 0)
            u[0] = u[1] = 0;
        if (j == 1)
            u[0] = u[1] = nextafter(REAL_C(1.0), REAL_C(0.0));
        cobject_sample_t s;
        obj->ops->sample(obj, u, &s);
        ck_assert_msg(vec_is_finite(s.p) && vec_is_finite(s.n) &&
                          vec_is_finite(s.p_error) && isfinite(s.pdf) &&
                          s.pdf >= 0,
                      "%s: sample %d not finite", nm, j);
    }
    return i;
}

void primcheck_csv_vec(testcsv_t *c, const char *prefix, VECTOR3 v)
{
    char col[32];
    for (int k = 0; k < 3; k++) {
        snprintf(col, sizeof col, "%s%c", prefix, "xyz"[k]);
        v[k] = (real)testcsv_num(c, col);
    }
}

double primcheck_csv_tol(testcsv_t *c)
{
#ifdef SVET_DOUBLE
    return testcsv_num(c, "tol_double");
#else
    return testcsv_num(c, "tol_float");
#endif
}

bool primcheck_csv_hit(testcsv_t *c, const COBJECT *obj, const char *p,
                       const char *n, PATHPOINT *pp)
{
    ray_t r;
    primcheck_csv_vec(c, "o", r.o);
    primcheck_csv_vec(c, "d", r.d);
    hit_t h;
    bool hit = cobject_intersect(obj, &r, 0, (real)INFINITY, &h);
    ck_assert_msg(hit == (testcsv_num(c, "hit") == 1), "%s:%d: hit %d",
                  c->path, c->line, hit);
    if (!hit)
        return false;
    double tol = primcheck_csv_tol(c), scale = testcsv_num(c, "scale");
    cobject_fill(obj, &r, &h, pp);
    ck_assert_rel(h.t, testcsv_num(c, "t"), tol, 0);
    VECTOR3 want_p, want_n;
    primcheck_csv_vec(c, p, want_p);
    primcheck_csv_vec(c, n, want_n);
    for (int k = 0; k < 3; k++) {
        ck_assert_near(pp->cross_point[k], want_p[k], tol * scale);
        ck_assert_near(pp->ng[k], want_n[k], tol);
    }
    return true;
}
