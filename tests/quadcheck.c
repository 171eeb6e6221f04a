/*
 * quadcheck.c - the checks shared by the suites of the quadric primitives;
 * see quadcheck.h. Every random number comes from a seeded PCG32, so a
 * failure reproduces exactly; messages name the shape, scale and case.
 */
#include "quadcheck.h"
#include "chi2.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static double identity(void *ctx, double x)
{
    (void)ctx;
    return x;
}

void quadcheck_ks(const COBJECT *obj, int n, uint64_t seed,
                  quadcheck_cdf_fn cdf, void *ctx, const char *test)
{
    double *x = malloc((size_t)n * sizeof *x);
    ck_assert(x != NULL);
    pcg32_t g;
    pcg32_seed(&g, seed, 0x4b53);
    for (int i = 0; i < n; i++) {
        real u[2] = { pcg32_real(&g), pcg32_real(&g) };
        cobject_sample_t s;
        obj->ops->sample(obj, u, &s);
        x[i] = cdf(&s, ctx);
    }
    /* the values are already F(x): compare them with U(0,1) */
    double d = chi2_ks_statistic(x, n, identity, NULL);
    free(x);
    const double alpha = 1e-6;
    double eps = sqrt(log(2 / alpha) / (2.0 * n));
    ck_assert_msg(d <= eps, "%s: Kolmogorov-Smirnov D = %g > %g (n = %d)",
                  test, d, eps, n);
    test_report_cases(test, n);
}

bool quadcheck_trace(const COBJECT *obj, const ray_t *r, real tmin, real tmax,
                     PATHPOINT *pp)
{
    hit_t h;
    if (!cobject_intersect(obj, r, tmin, tmax, &h))
        return false;
    ck_assert_msg(h.t > tmin && h.t < tmax && isfinite(h.t),
                  "%s: t = %g outside (%g, %g)", obj->ops->name, (double)h.t,
                  (double)tmin, (double)tmax);
    cobject_fill(obj, r, &h, pp);
    return true;
}

void quadcheck_assert_finite(const PATHPOINT *pp, const char *what)
{
    ck_assert_msg(vec_is_finite(pp->cross_point) && vec_is_finite(pp->p_error)
                      && vec_is_finite(pp->ng) && vec_is_finite(pp->n) &&
                      vec_is_finite(pp->u) && vec_is_finite(pp->v) &&
                      vec_is_finite(pp->dpds) && vec_is_finite(pp->dpdt),
                  "%s: a vector of the PATHPOINT is not finite", what);
    ck_assert_msg(pp->st[0] >= 0 && pp->st[0] <= 1 && pp->st[1] >= 0 &&
                      pp->st[1] <= 1,
                  "%s: st = (%g, %g) outside [0,1]^2", what,
                  (double)pp->st[0], (double)pp->st[1]);
    ck_assert_msg(fabs(vec_length(pp->ng) - 1) <= 64 * REAL_EPSILON,
                  "%s: |ng| = %g", what, (double)vec_length(pp->ng));
}

long double quadcheck_meridian_distance(const VECTOR3 p, const VECTOR3 a,
                                        const VECTOR3 b,
                                        const long double seg[][4], int n)
{
    long double w[3], q[3], H2 = 0, h = 0, r2 = 0;
    for (int k = 0; k < 3; k++) {
        w[k] = (long double)b[k] - (long double)a[k];
        q[k] = (long double)p[k] - (long double)a[k];
        H2 += w[k] * w[k];
    }
    long double H = sqrtl(H2);
    for (int k = 0; k < 3; k++)
        h += q[k] * w[k] / H;
    for (int k = 0; k < 3; k++) {
        long double t = q[k] - h * w[k] / H;
        r2 += t * t;
    }
    long double rho = sqrtl(r2), best = (long double)INFINITY;
    for (int i = 0; i < n; i++) {
        /* the nearest point of the segment: clamp the projection */
        long double er = seg[i][2] - seg[i][0], eh = seg[i][3] - seg[i][1];
        long double s = ((rho - seg[i][0]) * er + (h - seg[i][1]) * eh) /
                        (er * er + eh * eh);
        s = fminl(fmaxl(s, 0), 1);
        long double dr = rho - (seg[i][0] + s * er);
        long double dh = h - (seg[i][1] + s * eh);
        best = fminl(best, sqrtl(dr * dr + dh * dh));
    }
    return best;
}

/* The centres of quadcheck_error_bound and quadcheck_sweep: the origin,
 * and 10 scale away, where the coordinates dwarf the shape. */
static void centre_at(VECTOR3 c, real scale, int away)
{
    vec_set(c, 10 * scale * away, -6 * scale * away, 3 * scale * away);
}

static long double support(const VECTOR3 n, const VECTOR3 e)
{
    long double s = 0;
    for (int k = 0; k < 3; k++)
        s += fabsl((long double)n[k]) * (long double)e[k];
    return s;
}

/* One point of quadcheck_error_bound: dist(p) <= the box's half-width
 * along n. Returns dist / bound. */
static long double within_bound(const COBJECT *obj, quadcheck_dist_fn dist,
                                void *ctx, real scale, const VECTOR3 centre,
                                const VECTOR3 p, const VECTOR3 n,
                                const VECTOR3 p_error, const char *what)
{
    long double d = dist(p, scale, centre, ctx);
    long double e = support(n, p_error);
    ck_assert_msg(d <= e, "%s, scale %g: %s %Lg off the surface, bound %Lg",
                  obj->ops->name, (double)scale, what, d, e);
    return d / e;
}

long quadcheck_error_bound(primcheck_make_fn make, quadcheck_dist_fn dist,
                           void *ctx, int n, uint64_t seed)
{
    int ns;
    const real *sc = primcheck_scales(&ns);
    pcg32_t g;
    pcg32_seed(&g, seed, 0xe770);
    long cases = 0;
    long double worst = 0;
    for (int i = 0; i < ns; i++)
        for (int away = 0; away < 2; away++) {
            VECTOR3 c, bc, dir;
            centre_at(c, sc[i], away);
            COBJECT *obj = make(sc[i], c, ctx);
            bbox_t b;
            obj->ops->bounds(obj, -1, &b);
            bbox_centroid(bc, &b);
            real R = vec_distance(b.max, b.min);
            for (int k = 0; k < n; k++) {
                ray_t r;
                VECTOR3 target;
                geomcheck_random_dir(dir, &g);
                vec_add_scaled(r.o, bc, 2 * R, dir);
                for (int j = 0; j < 3; j++)
                    target[j] = b.min[j] +
                                pcg32_real(&g) * (b.max[j] - b.min[j]);
                vec_sub(r.d, target, r.o);
                PATHPOINT pp;
                if (quadcheck_trace(obj, &r, 0, (real)INFINITY, &pp)) {
                    worst = fmaxl(worst, within_bound(obj, dist, ctx, sc[i],
                                                      c, pp.cross_point,
                                                      pp.ng, pp.p_error,
                                                      "hit"));
                    cases++;
                }
                real u[2] = { pcg32_real(&g), pcg32_real(&g) };
                cobject_sample_t s;
                obj->ops->sample(obj, u, &s);
                worst = fmaxl(worst, within_bound(obj, dist, ctx, sc[i], c,
                                                  s.p, s.n, s.p_error,
                                                  "sample"));
                cases++;
            }
            cobject_free(obj);
        }
    printf("  largest distance / bound: %.3g\n", (double)worst);
    return cases;
}

long quadcheck_harness(primcheck_make_fn make, int n,
                       const geomcheck_kind kinds[], primcheck_test test,
                       uint64_t seed)
{
    long cases = 0;
    for (int v = 0; v < n; v++) {
        if (test == PRIMCHECK_SHADOW && kinds[v] != GEOMCHECK_CONVEX)
            continue;
        cases += primcheck_over_scales(make, &v, test, kinds[v], true,
                                       seed + (uint64_t)v);
    }
    return cases;
}

long quadcheck_sweep(primcheck_make_fn make, void *ctx, int n, uint64_t seed)
{
    int ns;
    const real *sc = primcheck_scales(&ns);
    long cases = 0;
    for (int i = 0; i < ns; i++)
        for (int away = 0; away < 2; away++) {
            VECTOR3 c;
            centre_at(c, sc[i], away);
            COBJECT *obj = make(sc[i], c, ctx);
            cases += primcheck_sweep_finite(obj, n, seed++);
            cobject_free(obj);
        }
    return cases;
}

void quadcheck_expect_hit(const COBJECT *c, const ray_t *r, real t, int face,
                          real nx, real ny, real nz)
{
    PATHPOINT pp;
    ck_assert_msg(quadcheck_trace(c, r, 0, (real)INFINITY, &pp),
                  "no hit, expected t = %g", (double)t);
    ck_assert_near(pp.r_dist / vec_length(r->d), t, 8 * REAL_EPSILON * t);
    ck_assert_int_eq(pp.prim, face);
    ck_assert_near(pp.ng[X], nx, 8 * REAL_EPSILON);
    ck_assert_near(pp.ng[Y], ny, 8 * REAL_EPSILON);
    ck_assert_near(pp.ng[Z], nz, 8 * REAL_EPSILON);
    quadcheck_assert_finite(&pp, c->ops->name);
}

/* The shape of quadcheck_add_harness; set before the tests run (and
 * inherited by check's forked test processes). */
static quadcheck_shape_t shape;

static void run_harness(primcheck_test test, const char *name)
{
    test_report_cases(name, quadcheck_harness(shape.make, shape.n,
                                              shape.kinds, test,
                                              shape.seed[test]));
}

START_TEST(spawned_rays_never_rehit_the_shape)
{
    char name[96];
    snprintf(name, sizeof name, "spawned_rays_never_rehit_the_%s",
             shape.name);
    run_harness(PRIMCHECK_SPAWN, name);
}
END_TEST

START_TEST(sampled_points_are_hit)
{
    run_harness(PRIMCHECK_SAMPLED, "sampled_points_are_hit");
}
END_TEST

START_TEST(shadow_rays_between_points_of_convex_placements_miss)
{
    run_harness(PRIMCHECK_SHADOW,
                "shadow_rays_between_points_of_convex_placements_miss");
}
END_TEST

START_TEST(hits_are_finite)
{
    run_harness(PRIMCHECK_FINITE, "hits_are_finite");
}
END_TEST

START_TEST(sampling_matches_area)
{
    run_harness(PRIMCHECK_AREA, "sampling_matches_area");
}
END_TEST

START_TEST(no_routine_returns_nan_or_inf)
{
    long cases = 0;
    for (int v = 0; v < shape.n; v++)
        cases += quadcheck_sweep(shape.make, &v, shape.sweep_rays,
                                 shape.sweep_seed + (uint64_t)v);
    test_report_cases("no_routine_returns_nan_or_inf", cases);
}
END_TEST

void quadcheck_add_harness(TCase *tc, const quadcheck_shape_t *s)
{
    /* no ck_assert here: check allows them only inside a test */
    if (shape.make && shape.make != s->make) {
        fprintf(stderr, "quadcheck_add_harness: one shape per suite\n");
        abort();
    }
    shape = *s;
    bool convex = false;
    for (int v = 0; v < s->n; v++)
        convex = convex || s->kinds[v] == GEOMCHECK_CONVEX;
    tcase_add_test(tc, spawned_rays_never_rehit_the_shape);
    tcase_add_test(tc, sampled_points_are_hit);
    if (convex)
        tcase_add_test(tc,
                       shadow_rays_between_points_of_convex_placements_miss);
    tcase_add_test(tc, hits_are_finite);
    tcase_add_test(tc, sampling_matches_area);
    tcase_add_test(tc, no_routine_returns_nan_or_inf);
}

void quadcheck_vectors(const char *file, COBJECT *(*make_row)(testcsv_t *c),
                       const char *test)
{
    testcsv_t c;
    testcsv_open(&c, file);
    long rows = 0;
#ifdef SVET_DOUBLE
    const char *tol_col = "tol_double", *ntol_col = "ntol_double";
#else
    const char *tol_col = "tol_float", *ntol_col = "ntol_float";
#endif
    while (testcsv_next(&c)) {
        rows++;
        const char *name = testcsv_str(&c, "case");
        COBJECT *obj = make_row(&c);
        ck_assert_msg(obj != NULL, "%s:%d (%s): cannot build the shape", file,
                      c.line, name);
        ray_t r;
        primcheck_csv_vec(&c, "o", r.o);
        primcheck_csv_vec(&c, "d", r.d);
        bool expect = testcsv_num(&c, "hit") != 0;
        PATHPOINT pp;
        bool got = quadcheck_trace(obj, &r, 0, (real)INFINITY, &pp);
        ck_assert_msg(got == expect, "%s:%d (%s): hit = %d, expected %d",
                      file, c.line, name, got, expect);
        if (expect) {
            double tol = testcsv_num(&c, tol_col);
            double ntol = testcsv_num(&c, ntol_col);
            double len = (double)vec_length(r.d);
            VECTOR3 p, n;
            primcheck_csv_vec(&c, "p", p);
            primcheck_csv_vec(&c, "n", n);
            ck_assert_msg(fabs((double)pp.r_dist - testcsv_num(&c, "t") * len)
                              <= tol,
                          "%s:%d (%s): t = %.9g, expected %.9g (tol %g)", file,
                          c.line, name, (double)pp.r_dist / len,
                          testcsv_num(&c, "t"), tol / len);
            for (int k = 0; k < 3; k++) {
                ck_assert_msg(fabs((double)pp.cross_point[k] - (double)p[k])
                                  <= tol,
                              "%s:%d (%s): p[%d] = %.9g, expected %.9g (tol "
                              "%g)", file, c.line, name, k,
                              (double)pp.cross_point[k], (double)p[k], tol);
                ck_assert_msg(fabs((double)pp.ng[k] - (double)n[k]) <= ntol,
                              "%s:%d (%s): n[%d] = %.9g, expected %.9g (tol "
                              "%g)", file, c.line, name, k, (double)pp.ng[k],
                              (double)n[k], ntol);
            }
        }
        cobject_free(obj);
    }
    testcsv_close(&c);
    ck_assert_msg(rows > 0, "%s: no rows", file);
    test_report_cases(test, rows);
}
