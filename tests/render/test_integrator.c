/*
 * test_integrator.c - the estimators of ch. 5 on scenes whose answers are
 * known exactly:
 *  - the furnace: a diffuse sphere of albedo a in a uniform environment of
 *    radiance 1 looks exactly a (cosine-weighted sampling of both light and
 *    BSDF makes every estimate exact);
 *  - a point light of intensity pi at the centre of a closed diffuse sphere
 *    of radius 1 and albedo 1/2, seen from inside: L = rho I / (pi R^2
 *    (1 - rho)) = 1 (pbrt-v3's analytic_scenes test);
 *  - a diffuse plane under a point light: L = (rho/pi) I cos(theta) / r^2;
 *  - a disk light of radius a and radiance Le at height h above a diffuse
 *    point, facing it: E = pi Le a^2 / (h^2 + a^2), L = rho E / pi, by every
 *    strategy (path with MIS, direct, BSDF only, light sampling only);
 *  - an emitter seen directly, from the front and from the back;
 *  - `render light indirect`: inside the closed sphere above the indirect
 *    light is the total less the direct rho I / (pi R^2), 1 - 1/2 = 1/2,
 *    with MIS and by light sampling alone; on the plane under a point
 *    light, with nothing to bounce from, it is exactly 0;
 *  - Russian roulette keeps the expected throughput.
 * Statistical tolerances are 5 standard errors of the estimate (the
 * standard error measured from the same samples): a correct estimator
 * fails with probability below 6e-7 per check.
 */
#include "testutil.h"
#include "geometry/disk.h"
#include "render/integrator.h"
#include "materials/material.h"
#include "core/sample.h"
#include "render/scene.h"
#include "geometry/sphere.h"

#include <math.h>
#include <string.h>

static material_t *lambert(real rho)
{
    material_params p;
    material_params_default(&p);
    p.rho_d = rad_grey(rho);
    material_t *m;
    ck_assert_int_eq(material_new(&p, &m, NULL), SVET_OK);
    return m;
}

static COBJECT *add(scene_t *s, COBJECT *o, real rho)
{
    ck_assert(o != NULL);
    material_t *m = lambert(rho);
    ck_assert_int_eq(scene_add_anon_material(s, m, NULL), SVET_OK);
    ck_assert_int_eq(scene_add_object(s, o, m, NULL), SVET_OK);
    return o;
}

/* Estimate the radiance along r with n paths; mean and standard error. */
static void estimate(const integrator_t *it, const ray_t *r, int n,
                     uint64_t seed, double *mean, double *se)
{
    estimator_t e;
    estimator_init(&e);
    integrator_stats_t st = { 0, 0 };
    for (int i = 0; i < n; i++) {
        pcg32_t g;
        rng_for_sample(&g, seed, 0, (uint64_t)i);
        RADIANCE L = integrator_li(it, r, &g, &st);
        ck_assert(rad_is_finite(L) && L.r >= 0);
        estimator_add(&e, (double)L.r);
    }
    *mean = estimator_mean(&e);
    *se = estimator_stderr(&e);
}

START_TEST(furnace_sphere_looks_exactly_its_albedo)
{
    const real albedo[] = { 0.2, 0.5, 0.8, 1 };
    long cases = 0;
    for (int k = 0; k < 4; k++) {
        scene_t s;
        scene_init(&s);
        VECTOR3 c = { 0, 0, 0 };
        add(&s, sphere_new(c, 1, NULL), albedo[k]);
        s.has_environment = true;
        s.environment = rad_grey(1);
        s.render.max_depth = 10;
        lightset_t ls;
        ck_assert_int_eq(lightset_build(&ls, &s, NULL), SVET_OK);
        integrator_t it;
        integrator_init(&it, &s, &ls, tracer_brute(&s));
        pcg32_t dirs;
        pcg32_seed(&dirs, 7, (uint64_t)k);
        for (int i = 0; i < 200; i++, cases++) {
            /* rays from a sphere of radius 3 toward points near the centre */
            ray_t r;
            real u[2] = { pcg32_real(&dirs), pcg32_real(&dirs) };
            VECTOR3 w, target = { 0, 0, 0 };
            sample_uniform_sphere(w, u);
            vec_scale(r.o, w, 3);
            target[X] = REAL_C(0.9) * (pcg32_real(&dirs) - REAL_C(0.5));
            vec_sub(r.d, target, r.o);
            vec_normalize(r.d, r.d);
            pcg32_t g;
            rng_for_sample(&g, 1, (uint64_t)i, 0);
            integrator_stats_t st = { 0, 0 };
            RADIANCE L = integrator_li(&it, &r, &g, &st);
            /* exact up to the rounding of a few products */
            ck_assert_near(L.r, albedo[k], 64 * REAL_EPSILON);
            ck_assert_near(L.g, albedo[k], 64 * REAL_EPSILON);
        }
        /* a ray that misses sees the environment */
        ray_t miss = { { 0, 5, 0 }, { 0, 1, 0 } };
        pcg32_t g;
        rng_for_sample(&g, 1, 0, 0);
        integrator_stats_t st = { 0, 0 };
        ck_assert_near(integrator_li(&it, &miss, &g, &st).b, 1, 0);
        lightset_free(&ls);
        scene_free(&s);
    }
    test_report_cases("furnace_sphere_looks_exactly_its_albedo", cases);
}
END_TEST

/* A closed sphere of radius 1 and albedo 0.5 with a point light of
 * intensity 1 (power 4 pi) at its centre. */
static void closed_sphere(scene_t *s)
{
    scene_init(s);
    VECTOR3 c = { 0, 0, 0 };
    add(s, sphere_new(c, 1, NULL), REAL_C(0.5));
    ck_assert_int_eq(scene_add_point_light(s, c, rad_grey(REAL_PI), NULL),
                     SVET_OK);
}

START_TEST(point_light_inside_a_closed_sphere_gives_radiance_one)
{
    scene_t s;
    closed_sphere(&s);
    /* Truncating after D events loses rho^(D+1) of the total: 2^-41 here */
    s.render.max_depth = 40;
    s.render.roulette = true;
    s.render.roulette_depth = 3;
    lightset_t ls;
    ck_assert_int_eq(lightset_build(&ls, &s, NULL), SVET_OK);
    integrator_t it;
    integrator_init(&it, &s, &ls, tracer_brute(&s));
    ray_t r = { { REAL_C(0.2), REAL_C(0.1), 0 }, { 0, REAL_C(0.6), REAL_C(-0.8) } };
    double mean, se;
    estimate(&it, &r, 40000, 3, &mean, &se);
    ck_assert_msg(fabs(mean - 1) <= 5 * se + 1e-5, "L = %g +- %g", mean, se);
    ck_assert(se < 0.02);
    /* and with Russian roulette off */
    s.render.roulette = false;
    integrator_init(&it, &s, &ls, tracer_brute(&s));
    estimate(&it, &r, 20000, 4, &mean, &se);
    ck_assert_msg(fabs(mean - 1) <= 5 * se + 1e-5, "L = %g +- %g", mean, se);
    test_report_cases("point_light_inside_a_closed_sphere_gives_radiance_one",
                      60000);
    lightset_free(&ls);
    scene_free(&s);
}
END_TEST

START_TEST(diffuse_plane_under_a_point_light_follows_the_inverse_square_law)
{
    scene_t s;
    scene_init(&s);
    VECTOR3 c = { 0, 0, 0 }, up = { 0, 0, 1 }, lp = { 0, 0, 2 };
    const real rho = REAL_C(0.7), I = REAL_C(5.0);
    add(&s, disk_new(c, up, 100, NULL), rho);
    ck_assert_int_eq(scene_add_point_light(&s, lp, rad_grey(I), NULL), SVET_OK);
    s.render.max_depth = 5;
    lightset_t ls;
    ck_assert_int_eq(lightset_build(&ls, &s, NULL), SVET_OK);
    integrator_t it;
    integrator_init(&it, &s, &ls, tracer_brute(&s));
    long cases = 0;
    for (int i = 0; i < 8; i++, cases++) {
        /* the ray from above lands at x = 0.5 i on the plane */
        real x = REAL_C(0.5) * (real)i;
        ray_t r = { { x + 1, REAL_C(0.5), 3 }, { -1, REAL_C(-0.5), -3 } };
        pcg32_t g;
        rng_for_sample(&g, 5, (uint64_t)i, 0);
        integrator_stats_t st = { 0, 0 };
        RADIANCE L = integrator_li(&it, &r, &g, &st);
        double r2 = (double)x * (double)x + 4, cos_t = 2 / sqrt(r2);
        double expect = (double)rho / 3.14159265358979323846 * (double)I * cos_t / r2;
        /* one bounce only: nothing else is in the scene */
        ck_assert_rel(L.g, expect, 64 * REAL_EPSILON, 0);
    }
    test_report_cases("diffuse_plane_under_a_point_light_follows_the_inverse_"
                      "square_law", cases);
    lightset_free(&ls);
    scene_free(&s);
}
END_TEST

START_TEST(indirect_light_alone)
{
    scene_t s;
    closed_sphere(&s);
    s.render.max_depth = 40;
    s.render.light = SCENE_LIGHT_INDIRECT;
    lightset_t ls;
    ck_assert_int_eq(lightset_build(&ls, &s, NULL), SVET_OK);
    ray_t r = { { REAL_C(0.2), REAL_C(0.1), 0 }, { 0, REAL_C(0.6), REAL_C(-0.8) } };
    const scene_integrator modes[] = { SCENE_INTEGRATOR_PATH,
                                       SCENE_INTEGRATOR_NEE };
    for (int k = 0; k < 2; k++) {
        s.render.integrator = modes[k];
        integrator_t it;
        integrator_init(&it, &s, &ls, tracer_brute(&s));
        double mean, se;
        estimate(&it, &r, 40000, 13 + (uint64_t)k, &mean, &se);
        ck_assert_msg(fabs(mean - 0.5) <= 5 * se + 1e-5, "mode %d: L = %g +- "
                      "%g, not 1/2", (int)modes[k], mean, se);
        ck_assert(se < 0.02);
    }
    lightset_free(&ls);
    scene_free(&s);

    /* a plane under a point light: its light is all direct */
    scene_init(&s);
    VECTOR3 c = { 0, 0, 0 }, up = { 0, 0, 1 }, lp = { 0, 0, 2 };
    add(&s, disk_new(c, up, 100, NULL), REAL_C(0.7));
    ck_assert_int_eq(scene_add_point_light(&s, lp, rad_grey(5), NULL), SVET_OK);
    s.render.max_depth = 5;
    ck_assert_int_eq(lightset_build(&ls, &s, NULL), SVET_OK);
    for (int ind = 0; ind < 2; ind++) {
        s.render.light = ind ? SCENE_LIGHT_INDIRECT : SCENE_LIGHT_ALL;
        integrator_t it;
        integrator_init(&it, &s, &ls, tracer_brute(&s));
        for (int i = 0; i < 64; i++) {
            ray_t q = { { REAL_C(0.1) * (real)i + 1, REAL_C(0.5), 3 },
                        { -1, REAL_C(-0.5), -3 } };
            pcg32_t g;
            rng_for_sample(&g, 6, (uint64_t)i, 0);
            integrator_stats_t st = { 0, 0 };
            RADIANCE L = integrator_li(&it, &q, &g, &st);
            if (ind)
                ck_assert_msg(L.r == 0 && L.g == 0 && L.b == 0,
                              "ray %d: indirect light %g", i, (double)L.g);
            else
                ck_assert(L.g > 0);
        }
    }
    lightset_free(&ls);
    scene_free(&s);
}
END_TEST

START_TEST(disk_light_over_a_diffuse_point_by_every_strategy)
{
    /* E on the axis of a disk of radius a at height h: pi Le a^2/(h^2+a^2)
     * (the form factor of a coaxial disk; Howell's catalogue, C-12) */
    const real a = REAL_C(0.5), h = REAL_C(1.0), Le = REAL_C(3.0), rho = REAL_C(0.6);
    const double expect = (double)(rho * Le * a * a / (h * h + a * a));
    const scene_integrator modes[] = { SCENE_INTEGRATOR_PATH,
                                       SCENE_INTEGRATOR_DIRECT,
                                       SCENE_INTEGRATOR_BSDF,
                                       SCENE_INTEGRATOR_NEE };
    for (int k = 0; k < 4; k++) {
        scene_t s;
        scene_init(&s);
        VECTOR3 c = { 0, 0, 0 }, up = { 0, 0, 1 }, lc = { 0, 0, h },
                down = { 0, 0, -1 };
        /* a small receiving disk, so nothing bounces back to the light */
        add(&s, disk_new(c, up, REAL_C(0.01), NULL), rho);
        COBJECT *light = add(&s, disk_new(lc, down, a, NULL), 0);
        ck_assert_int_eq(scene_set_emission(&s, light, rad_grey(Le), false,
                                            NULL), SVET_OK);
        s.render.max_depth = 3;
        s.render.integrator = modes[k];
        lightset_t ls;
        ck_assert_int_eq(lightset_build(&ls, &s, NULL), SVET_OK);
        integrator_t it;
        integrator_init(&it, &s, &ls, tracer_brute(&s));
        ray_t r = { { REAL_C(0.5), 0, REAL_C(0.5) }, { REAL_C(-1.0), 0, REAL_C(-1.0) } };
        double mean, se;
        estimate(&it, &r, 40000, 10 + (uint64_t)k, &mean, &se);
        ck_assert_msg(fabs(mean - expect) <= 5 * se + 1e-5,
                      "mode %d: L = %g +- %g, exact %g", k, mean, se, expect);
        lightset_free(&ls);
        scene_free(&s);
    }
    test_report_cases("disk_light_over_a_diffuse_point_by_every_strategy",
                      4 * 40000);
}
END_TEST

START_TEST(emitter_seen_directly_from_front_and_back)
{
    scene_t s;
    scene_init(&s);
    VECTOR3 c = { 0, 0, 0 }, up = { 0, 0, 1 };
    COBJECT *d = add(&s, disk_new(c, up, 1, NULL), REAL_C(0.5));
    RADIANCE Le = rad_make(18.387, 13.9873, 6.75357);
    ck_assert_int_eq(scene_set_emission(&s, d, Le, false, NULL), SVET_OK);
    s.render.max_depth = 0;
    lightset_t ls;
    ck_assert_int_eq(lightset_build(&ls, &s, NULL), SVET_OK);
    integrator_t it;
    integrator_init(&it, &s, &ls, tracer_brute(&s));
    pcg32_t g;
    rng_for_sample(&g, 0, 0, 0);
    integrator_stats_t st = { 0, 0 };
    ray_t front = { { 0, 0, 2 }, { REAL_C(0.1), 0, -1 } };
    RADIANCE L = integrator_li(&it, &front, &g, &st);
    ck_assert(L.r == Le.r && L.g == Le.g && L.b == Le.b);
    ray_t back = { { 0, 0, -2 }, { 0, 0, 1 } };
    L = integrator_li(&it, &back, &g, &st);
    ck_assert(rad_is_black(L));
    lightset_free(&ls);
    scene_free(&s);
}
END_TEST

START_TEST(power_heuristic_weights_sum_to_one)
{
    const real p[] = { 0, 1e-30, 0.5, 1, 3, 1e30 };
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++) {
            real a = p[i], b = p[j];
            real w1 = integrator_mis_weight(a, b), w2 = integrator_mis_weight(b, a);
            ck_assert(w1 >= 0 && w1 <= 1 && isfinite(w1));
            if (a > 0 || b > 0)
                ck_assert_near(w1 + w2, 1, 4 * REAL_EPSILON);
        }
    ck_assert_near(integrator_mis_weight(1, 1), 0.5, 0);
    ck_assert_near(integrator_mis_weight(2, 1), 0.8, 2 * REAL_EPSILON);
}
END_TEST

/* Russian roulette, shared by the path tracer and volpath: one number
 * drawn whatever the settings; off or before roulette_depth beta is kept;
 * after it the path survives exactly when u < q = max channel of beta
 * (clamped to [0.05, 1]), beta / q then, so E[beta] is kept: over many
 * draws the survivors' mean weight times their share is beta within 5
 * standard errors. */
START_TEST(roulette_keeps_the_expected_throughput)
{
    integrator_t it;
    memset(&it, 0, sizeof it);
    it.roulette_depth = 3;
    pcg32_t g, h;
    pcg32_seed(&g, 9, 2);
    const RADIANCE b0 = rad_make(REAL_C(0.25), REAL_C(0.5), REAL_C(0.125));
    for (int on = 0; on < 2; on++) {
        it.roulette = on;
        RADIANCE b = b0;
        h = g;
        ck_assert(integrator_roulette(&it, 2, &g, &b));
        ck_assert(b.r == b0.r && b.g == b0.g && b.b == b0.b);
        (void)pcg32_real(&h);
        ck_assert(memcmp(&g, &h, sizeof g) == 0);
    }
    it.roulette = false;
    RADIANCE b = b0;
    ck_assert(integrator_roulette(&it, 10, &g, &b));
    ck_assert(b.g == b0.g);
    it.roulette = true;
    const int n = 100000;
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; i++) {
        b = b0;
        h = g;
        real u = pcg32_real(&h);
        bool alive = integrator_roulette(&it, 3, &g, &b);
        ck_assert(alive == (u < REAL_C(0.5)));
        double w = alive ? (double)b.g : 0;
        if (alive)
            ck_assert(b.g == 1 && b.r == REAL_C(0.5));
        sum += w;
        sum2 += w * w;
    }
    double mean = sum / n, se = sqrt((sum2 / n - mean * mean) / n);
    ck_assert_msg(fabs(mean - 0.5) < 5 * se, "E[beta] %g, not 0.5 (se %g)",
                  mean, se);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("integrator (" REAL_NAME ")");
    TCase *tc = tcase_create("analytic");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, power_heuristic_weights_sum_to_one);
    tcase_add_test(tc, roulette_keeps_the_expected_throughput);
    tcase_add_test(tc, furnace_sphere_looks_exactly_its_albedo);
    tcase_add_test(tc, point_light_inside_a_closed_sphere_gives_radiance_one);
    tcase_add_test(tc, diffuse_plane_under_a_point_light_follows_the_inverse_square_law);
    tcase_add_test(tc, disk_light_over_a_diffuse_point_by_every_strategy);
    tcase_add_test(tc, emitter_seen_directly_from_front_and_back);
    tcase_add_test(tc, indirect_light_alone);
    suite_add_tcase(s, tc);
    return s;
}
