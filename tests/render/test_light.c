/*
 * test_light.c - light sampling (light.c, ch. 5): what a sample carries for
 * the MIS weights. light_sample() returns the density light_pdf() gives
 * its direction (light_sample_t.pdf_mis), made from the numbers the
 * sample already has instead of by a second call; this checks it bit for
 * bit against light_pdf() on area lights of several shapes (one- and
 * two-sided, an infinite plane whose area is not finite), point lights and
 * the environment, from random shading points on both sides.
 */
#include "testutil.h"
#include "geomcheck.h"
#include "geometry/disk.h"
#include "core/frame.h"
#include "render/light.h"
#include "materials/material.h"
#include "geometry/parallelogram.h"
#include "geometry/plane.h"
#include "render/scene.h"
#include "geometry/sphere.h"

#include <string.h>

static void add_emitter(scene_t *s, COBJECT *o, const material_t *m,
                        bool two_sided)
{
    ck_assert(o != NULL);
    ck_assert_int_eq(scene_add_object(s, o, m, NULL), SVET_OK);
    ck_assert_int_eq(scene_set_emission(s, o, rad_grey(2), two_sided, NULL),
                     SVET_OK);
}

START_TEST(light_sample_carries_light_pdf_bit_for_bit)
{
    scene_t s;
    scene_init(&s);
    material_params p;
    material_params_default(&p);
    p.rho_d = rad_grey(REAL_C(0.5));
    material_t *m;
    ck_assert_int_eq(material_new(&p, &m, NULL), SVET_OK);
    ck_assert_int_eq(scene_add_anon_material(&s, m, NULL), SVET_OK);
    VECTOR3 c0 = { -1, 2, -1 }, c1 = { 1, 2, -1 }, c3 = { -1, 2, 1 };
    VECTOR3 t0 = { 3, -1, 0 }, t1 = { 3, REAL_C(-1.5), REAL_C(0.25) },
            t3 = { REAL_C(3.001), -1, REAL_C(1e-3) };
    VECTOR3 dc = { 0, -3, 0 }, dn = { 0, 1, 1 }, sc = { -3, 0, 1 };
    VECTOR3 pp0 = { 0, 0, -5 }, pn = { 0, 0, 1 };
    add_emitter(&s, parallelogram_new(c0, c1, c3, NULL), m, false);
    add_emitter(&s, parallelogram_new(t0, t1, t3, NULL), m, true);
    add_emitter(&s, disk_new(dc, dn, REAL_C(0.75), NULL), m, false);
    add_emitter(&s, sphere_new(sc, REAL_C(0.5), NULL), m, true);
    add_emitter(&s, plane_new(pp0, pn, NULL), m, false); /* infinite area */
    VECTOR3 lp = { REAL_C(0.5), REAL_C(0.25), 3 };
    ck_assert_int_eq(scene_add_point_light(&s, lp, rad_grey(5), NULL),
                     SVET_OK);
    s.has_environment = true;
    s.environment = rad_grey(1);
    lightset_t ls;
    ck_assert_int_eq(lightset_build(&ls, &s, NULL), SVET_OK);
    ck_assert_int_eq(ls.n, 7);
    pcg32_t g;
    pcg32_seed(&g, 7, 11);
    long cases = 0, samples = 0;
    for (int i = 0; i < 20000; i++) {
        PATHPOINT pp;
        memset(&pp, 0, sizeof pp);
        for (int k = 0; k < 3; k++)
            pp.cross_point[k] = 8 * pcg32_real(&g) - 4;
        geomcheck_random_dir(pp.n, &g);
        vec_copy(pp.ng, pp.n);
        frame_from_normal(pp.u, pp.v, pp.n);
        geomcheck_random_dir(pp.out, &g);
        bool two = pcg32_real(&g) < REAL_C(0.5);
        real u[2] = { pcg32_real(&g), pcg32_real(&g) };
        if (i % 16 == 0) /* corners of the square of u */
            u[0] = (real)(i / 16 % 2), u[1] = (real)(i / 32 % 2);
        for (int l = 0; l < ls.n; l++) {
            light_sample_t smp;
            cases++;
            if (!light_sample(&ls.lights[l], &pp, two, u, &smp))
                continue;
            samples++;
            real want = light_pdf(&ls.lights[l], &pp, two, smp.wi, smp.p,
                                  smp.n);
            ck_assert_msg(memcmp(&want, &smp.pdf_mis, sizeof want) == 0,
                          "light %d: pdf_mis %a, light_pdf %a", l,
                          (double)smp.pdf_mis, (double)want);
        }
    }
    /* most samples carry light: the comparisons are not vacuous */
    ck_assert(samples > cases / 4);
    test_report_cases("light_sample_carries_light_pdf_bit_for_bit", cases);
    lightset_free(&ls);
    scene_free(&s);
}
END_TEST

START_TEST(a_plane_leaves_the_environment_a_finite_share_of_light_samples)
{
    /* The plane's bounds span the reals: in the bounding sphere they made
     * the environment's power pi^2 r^2 L infinite, its share of the light
     * samples NaN, and the point light was never chosen. */
    scene_t s;
    scene_init(&s);
    material_params p;
    material_params_default(&p);
    material_t *m;
    ck_assert_int_eq(material_new(&p, &m, NULL), SVET_OK);
    ck_assert_int_eq(scene_add_anon_material(&s, m, NULL), SVET_OK);
    VECTOR3 p0 = { 0, -1, 0 }, n = { 0, 1, 0 }, c = { 0, 0, 0 };
    ck_assert_int_eq(scene_add_object(&s, plane_new(p0, n, NULL), m, NULL),
                     SVET_OK);
    ck_assert_int_eq(scene_add_object(&s, sphere_new(c, 1, NULL), m, NULL),
                     SVET_OK);
    VECTOR3 lp = { 0, 3, 0 };
    ck_assert_int_eq(scene_add_point_light(&s, lp, rad_grey(10), NULL),
                     SVET_OK);
    s.has_environment = true;
    s.environment = rad_grey(REAL_C(0.2));
    lightset_t ls;
    ck_assert_int_eq(lightset_build(&ls, &s, NULL), SVET_OK);
    ck_assert_int_eq(ls.n, 2);
    /* the sphere's bounds alone: radius sqrt(3) */
    ck_assert_near(ls.radius, sqrt(3.0), 1e-6);
    for (int i = 0; i < ls.n; i++) {
        ck_assert(isfinite(ls.lights[i].power));
        ck_assert_msg(ls.cdf[i + 1] > ls.cdf[i], "light %d: cdf %g to %g", i,
                      (double)ls.cdf[i], (double)ls.cdf[i + 1]);
    }
    lightset_free(&ls);
    scene_free(&s);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("light (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, light_sample_carries_light_pdf_bit_for_bit);
    tcase_add_test(
        tc, a_plane_leaves_the_environment_a_finite_share_of_light_samples);
    suite_add_tcase(s, tc);
    return s;
}
