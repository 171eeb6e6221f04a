/*
 * test_render.c - the image loop: bit-identical images for any thread count
 * and pass split (the numbers of a sample depend only on seed, pixel and
 * sample index), two half renders merging into the full one, and the
 * variance image against the spread of the samples; a program that
 * offers no grid (ch. 5) renders with brute force the image the grid
 * gives.
 */
#include "testutil.h"
#include "accel/accel.h"
#include "render/allparts.h"
#include "geometry/disk.h"
#include "stats/imgcompare.h"
#include "materials/material.h"
#include "mesh/meshgen.h"
#include "render/render.h"
#include "geometry/sphere.h"

#include <signal.h>
#include <string.h>

static void small_scene(scene_t *s)
{
    scene_init(s);
    material_params p;
    material_params_default(&p);
    p.rho_d = rad_make(0.7, 0.5, 0.3);
    material_t *m;
    ck_assert_int_eq(material_new(&p, &m, NULL), SVET_OK);
    ck_assert_int_eq(scene_add_anon_material(s, m, NULL), SVET_OK);
    VECTOR3 c = { 0, 0, 0 }, up = { 0, 1, 0 }, floor_c = { 0, -1, 0 };
    VECTOR3 lc = { 0, 3, 0 }, down = { 0, -1, 0 };
    ck_assert_int_eq(scene_add_object(s, sphere_new(c, 1, NULL), m, NULL), SVET_OK);
    ck_assert_int_eq(scene_add_object(s, disk_new(floor_c, up, 5, NULL), m, NULL),
                     SVET_OK);
    COBJECT *l = disk_new(lc, down, 1, NULL);
    ck_assert_int_eq(scene_add_object(s, l, m, NULL), SVET_OK);
    ck_assert_int_eq(scene_set_emission(s, l, rad_grey(5), false, NULL), SVET_OK);
    VECTOR3 pl = { 2, 2, 2 };
    ck_assert_int_eq(scene_add_point_light(s, pl, rad_grey(3), NULL), SVET_OK);
    vec_set(s->camera.position, 0, 1, 5);
    vec_set(s->camera.target, 0, 0, 0);
    s->camera.width = 24;
    s->camera.height = 20;
    s->render.max_depth = 5;
    s->render.seed = 42;
}

/* Two renders' accumulators are the same, bit for bit, and so are their
 * ray counts. */
static void same_render(const render_t *a, const render_t *b, const char *what)
{
    size_t n = (size_t)a->camera.width * (size_t)a->camera.height;
    ck_assert_msg(memcmp(a->acc.sum, b->acc.sum, 3 * n * sizeof(image_fixed_t)) == 0 &&
                      memcmp(a->acc.count, b->acc.count,
                             n * sizeof(uint64_t)) == 0 &&
                      memcmp(a->sum2, b->sum2, 3 * n * sizeof(image_fixed_t)) == 0,
                  "%s: the images differ", what);
    ck_assert_msg(a->stats.rays == b->stats.rays && a->stats.paths ==
                      b->stats.paths && a->stats.rays > 0,
                  "%s: %llu against %llu rays", what,
                  (unsigned long long)a->stats.rays,
                  (unsigned long long)b->stats.rays);
}

START_TEST(image_is_identical_for_any_threads_and_passes)
{
    scene_t s;
    small_scene(&s);
    render_t a, b;
    ck_assert_int_eq(render_init(&a, &s, NULL), SVET_OK);
    ck_assert_int_eq(render_init(&b, &s, NULL), SVET_OK);
    render_pass(&a, 8, 1, NULL, NULL);             /* one thread, one pass */
    render_pass(&b, 3, 2, NULL, NULL);             /* two threads, 3 passes */
    render_pass(&b, 5, 2, NULL, NULL);
    render_pass(&b, 8, 2, NULL, NULL);
    size_t n = (size_t)s.camera.width * (size_t)s.camera.height;
    same_render(&a, &b, "one thread, one pass against two threads, three");
    ck_assert(image_accum_samples(&a.acc) == 8 * n);
    render_free(&a);
    render_free(&b);
    scene_free(&s);
}
END_TEST

/* small_scene() and a row of 30 small spheres: more primitives than AUTO
 * tests by brute force when a grid is offered (ACCEL_BRUTE_MAX). */
static void crowded_scene(scene_t *s)
{
    small_scene(s);
    for (int i = 0; i < 30; i++) {
        VECTOR3 c = { -3 + (real)i / 5, REAL_C(0.4) * (real)(i % 3), 1 };
        ck_assert_int_eq(scene_add_object(s, sphere_new(c, REAL_C(0.1), NULL),
                                          s->anon_materials[0], NULL),
                         SVET_OK);
    }
}

START_TEST(without_grids_auto_renders_with_brute_force_the_same_image)
{
    scene_t s;
    crowded_scene(&s);
    ck_assert(s.features == NULL); /* a program of ch. 5 */
    render_t brute, grid;
    ck_assert_int_eq(render_init(&brute, &s, NULL), SVET_OK);
    ck_assert_str_eq(brute.accel_choice, "brute (the list of 33 objects of "
                                         "ch. 5)");
    /* asking for a grid there fails, and says what to link */
    s.render.accel = SCENE_ACCEL_GRID;
    render_t r;
    svet_error err;
    ck_assert_int_eq(render_init(&r, &s, &err), SVET_ERR_UNSUPPORTED);
    ck_assert_str_eq(err.msg, "accel grid: this program was built without "
                              "the grids of ch. 7 (grid.c)");
    /* the svet command's parts: AUTO picks the grid; the same image */
    s.render.accel = SCENE_ACCEL_AUTO;
    s.features = scene_features_all();
    ck_assert_int_eq(render_init(&grid, &s, NULL), SVET_OK);
    ck_assert_msg(strncmp(grid.accel_choice, "grid (auto: ", 12) == 0, "%s",
                  grid.accel_choice);
    render_pass(&brute, 4, 2, NULL, NULL);
    render_pass(&grid, 4, 2, NULL, NULL);
    size_t n = (size_t)s.camera.width * (size_t)s.camera.height;
    same_render(&brute, &grid, "brute force against the grid");
    test_report_cases("without_grids_auto_renders_with_brute_force",
                      (long)(4 * n));
    render_free(&brute);
    render_free(&grid);
    scene_free(&s);
}
END_TEST

/* The camera rays render_pass() gave to the tracer's packets, counted by
 * a wrapper around accel_tracer_intersect_packet(). */
static long packet_rays;

static void counted_packet(const void *ctx, const ray_t *r, int n, real tmin,
                           real tmax, hit_t *hit, const COBJECT **obj,
                           bool *found)
{
#ifdef _OPENMP
#pragma omp atomic
#endif
    packet_rays += n;
    accel_tracer_intersect_packet(ctx, r, n, tmin, tmax, hit, obj, found);
}

/* Camera rays in packets of 8 x 8 (a grid's tracer) give the image of
 * camera rays one at a time and the image brute force gives, bit for
 * bit: a mesh among analytic objects, an image of 30 x 21 (blocks of 8 x
 * 8 cut at the tiles' and the image's edges), the path tracer and
 * ambient occlusion, two threads and passes. */
START_TEST(packets_of_camera_rays_render_the_same_image)
{
    scene_t s;
    crowded_scene(&s);
    COBJECT *mesh;
    VECTOR3 c = { REAL_C(0.5), REAL_C(0.2), REAL_C(-0.5) };
    ck_assert_int_eq(meshgen_uv_sphere(&mesh, c, REAL_C(0.9), 40, 20, NULL),
                     SVET_OK);
    ck_assert_int_eq(scene_add_object(&s, mesh, s.anon_materials[0], NULL),
                     SVET_OK);
    s.features = scene_features_all();
    s.camera.width = 30;
    s.camera.height = 21;
    const scene_integrator modes[2] = { SCENE_INTEGRATOR_PATH,
                                        SCENE_INTEGRATOR_AO };
    const scene_accel kinds[2] = { SCENE_ACCEL_GRID, SCENE_ACCEL_HGRID };
    for (int m = 0; m < 2; m++) {
        s.render.integrator = modes[m];
        s.render.accel = SCENE_ACCEL_BRUTE;
        render_t brute;
        ck_assert_int_eq(render_init(&brute, &s, NULL), SVET_OK);
        ck_assert(!brute.packets); /* brute force has none */
        render_pass(&brute, 3, 2, NULL, NULL);
        render_pass(&brute, 5, 2, NULL, NULL);
        for (int k = 0; k < 2; k++) {
            s.render.accel = kinds[k];
            render_t pk, one;
            ck_assert_int_eq(render_init(&pk, &s, NULL), SVET_OK);
            ck_assert_int_eq(render_init(&one, &s, NULL), SVET_OK);
            ck_assert(pk.packets);
            ck_assert_msg(strstr(pk.accel_choice,
                                 "; camera rays in packets of 8 x 8"),
                          "%s", pk.accel_choice);
            one.packets = false;
            /* every camera ray goes through the packets, once, or none */
            ck_assert(pk.intersect_packet == accel_tracer_intersect_packet);
            pk.intersect_packet = counted_packet;
            one.intersect_packet = counted_packet;
            packet_rays = 0;
            render_pass(&pk, 3, 2, NULL, NULL);
            render_pass(&pk, 5, 1, NULL, NULL);
            ck_assert_int_eq(packet_rays, 5L * 30 * 21);
            packet_rays = 0;
            render_pass(&one, 5, 2, NULL, NULL);
            ck_assert_int_eq(packet_rays, 0);
            same_render(&pk, &one, "packets against one at a time");
            same_render(&pk, &brute, "packets against brute force");
            render_free(&pk);
            render_free(&one);
        }
        render_free(&brute);
    }
    /* the scene's `packets off` leaves them out, and says nothing of them */
    s.render.packets = false;
    s.render.accel = SCENE_ACCEL_GRID;
    render_t off;
    ck_assert_int_eq(render_init(&off, &s, NULL), SVET_OK);
    ck_assert(!off.packets && !strstr(off.accel_choice, "packets"));
    render_free(&off);
    test_report_cases("packets_of_camera_rays_render_the_same_image (samples "
                      "x 2 integrators x 2 grids)",
                      5L * 30 * 21 * 2 * 2);
    scene_free(&s);
}
END_TEST

START_TEST(two_half_renders_merge_into_the_full_one)
{
    scene_t s;
    small_scene(&s);
    render_t full, h1, h2;
    ck_assert_int_eq(render_init(&full, &s, NULL), SVET_OK);
    ck_assert_int_eq(render_init(&h1, &s, NULL), SVET_OK);
    ck_assert_int_eq(render_init(&h2, &s, NULL), SVET_OK);
    render_pass(&full, 10, 2, NULL, NULL);
    render_pass(&h1, 5, 1, NULL, NULL);
    h2.spp_done = 5; /* the second machine renders samples 5..9 */
    render_pass(&h2, 10, 2, NULL, NULL);
    ck_assert_int_eq(image_accum_merge(&h1.acc, &h2.acc, NULL), SVET_OK);
    size_t n = (size_t)s.camera.width * (size_t)s.camera.height;
    ck_assert(memcmp(full.acc.count, h1.acc.count, n * sizeof(uint64_t)) == 0);
    /* The same samples, summed in another grouping: the same integers
     * (image.h), sums and sums of squares */
    ck_assert(memcmp(full.acc.sum, h1.acc.sum, 3 * n * sizeof(image_fixed_t))
              == 0);
    for (size_t i = 0; i < 3 * n; i++)
        image_fixed_add(&h1.sum2[i], &h2.sum2[i]);
    ck_assert(memcmp(full.sum2, h1.sum2, 3 * n * sizeof(image_fixed_t)) == 0);
    render_free(&full);
    render_free(&h1);
    render_free(&h2);
    scene_free(&s);
}
END_TEST

START_TEST(variance_image_matches_the_spread_of_the_samples)
{
    scene_t s;
    small_scene(&s);
    render_t r;
    ck_assert_int_eq(render_init(&r, &s, NULL), SVET_OK);
    const long spp = 16;
    render_pass(&r, spp, 0, NULL, NULL);
    image_t var;
    ck_assert_int_eq(render_variance(&r, &var, NULL), SVET_OK);
    /* recompute pixel (12, 10) from its samples by the two-pass formula */
    double v[16], mean = 0;
    integrator_stats_t st = { 0, 0 };
    for (long k = 0; k < spp; k++) {
        v[k] = (double)render_sample(&r, 12, 10, k, &st).g;
        mean += v[k] / spp;
    }
    double s2 = 0;
    for (long k = 0; k < spp; k++)
        s2 += (v[k] - mean) * (v[k] - mean) / (spp - 1);
    ck_assert_rel(image_at(&var, 12, 10)[1], s2 / spp, 1e-5, 1e-12);
    image_free(&var);
    render_free(&r);
    scene_free(&s);
}
END_TEST

/* Mean over pixels and channels of an image (the variance images). */
static double image_mean(const image_t *img)
{
    double sum = 0;
    size_t n = (size_t)img->width * (size_t)img->height * 3;
    for (size_t i = 0; i < n; i++)
        sum += (double)img->px[i];
    return sum / (double)n;
}

START_TEST(rmse_falls_as_one_over_sqrt_spp)
{
    /* The error of an unbiased render of N samples per pixel against the
     * truth has MSE = mean(sigma^2)/N; against a reference of M samples
     * it is mean(sigma^2)/N + mean(sigma^2)/M. Both variances are measured
     * (render_variance), so the prediction is independent of the RMSE it
     * checks. The MSE averages 24 x 20 x 3 = 1440 squared errors: for
     * Gaussian noise its relative standard deviation is sqrt(2/1440) =
     * 0.037, that of the RMSE half of it; with the heavier tails of path
     * tracing allow 3x that, and 0.2 is then ~3.6 sigma. */
    scene_t s;
    small_scene(&s);
    s.render.seed = 1;
    render_t ref;
    ck_assert_int_eq(render_init(&ref, &s, NULL), SVET_OK);
    render_pass(&ref, 2048, 0, NULL, NULL);
    image_t refimg, refvar;
    ck_assert_int_eq(render_image(&ref, &refimg, NULL), SVET_OK);
    ck_assert_int_eq(render_variance(&ref, &refvar, NULL), SVET_OK);
    double ref_mse = image_mean(&refvar);
    const long spp[3] = { 8, 32, 128 };
    double rmse[3];
    for (int k = 0; k < 3; k++) {
        s.render.seed = 100 + (uint64_t)k; /* independent of the reference */
        render_t r;
        ck_assert_int_eq(render_init(&r, &s, NULL), SVET_OK);
        render_pass(&r, spp[k], 0, NULL, NULL);
        image_t img, var;
        ck_assert_int_eq(render_image(&r, &img, NULL), SVET_OK);
        ck_assert_int_eq(render_variance(&r, &var, NULL), SVET_OK);
        imgcompare_t c;
        ck_assert_int_eq(imgcompare(&img, &refimg, 0, IMGCOMPARE_EPS, &c, NULL),
                         SVET_OK);
        double predicted = sqrt(image_mean(&var) + ref_mse);
        rmse[k] = c.rmse;
        ck_assert_msg(fabs(c.rmse / predicted - 1) < 0.2,
                      "spp %ld: RMSE %g, predicted %g", spp[k], c.rmse,
                      predicted);
        image_free(&img);
        image_free(&var);
        render_free(&r);
    }
    /* 16 times the samples, a quarter of the error (the reference's own
     * error, 1/16 of the 128-spp variance, barely shows) */
    ck_assert_msg(rmse[0] / rmse[2] > 3.2 && rmse[0] / rmse[2] < 4.8,
                  "RMSE ratio 8 to 128 spp: %g", rmse[0] / rmse[2]);
    image_free(&refimg);
    image_free(&refvar);
    render_free(&ref);
    scene_free(&s);
}
END_TEST

/* Stands for a signal handler: asks to stop once `after` tiles are done. */
static volatile sig_atomic_t stop_flag;
static long stop_after;

static void stop_after_tiles(void *ctx, long done, long total)
{
    (void)ctx;
    (void)total;
    if (done >= stop_after)
        stop_flag = 1;
}

/* A pass stopped after some of its tiles is undone: the render is the one
 * of the passes before it, bit for bit, and goes on from there to the
 * same image as one never stopped. */
START_TEST(an_abandoned_pass_leaves_the_render_as_it_was)
{
    scene_t s;
    small_scene(&s);
    render_t a, b;
    bool abandoned;
    ck_assert_int_eq(render_init(&a, &s, NULL), SVET_OK);
    ck_assert_int_eq(render_init(&b, &s, NULL), SVET_OK);
    render_pass(&a, 4, 1, NULL, NULL);
    stop_flag = 0;
    ck_assert_int_eq(render_pass_until(&b, 4, 1, NULL, NULL, &stop_flag,
                                       &abandoned, NULL), SVET_OK);
    ck_assert(!abandoned);
    same_render(&a, &b, "a pass not stopped");
    /* stopped after the first of the 4 tiles of 24 x 20 pixels, on one
     * thread and on two (another tile may be under way: it is undone too) */
    for (int threads = 1; threads <= 2; threads++) {
        stop_flag = 0;
        stop_after = 1;
        ck_assert_int_eq(render_pass_until(&b, 9, threads, stop_after_tiles,
                                           NULL, &stop_flag, &abandoned,
                                           NULL), SVET_OK);
        ck_assert(abandoned);
        ck_assert_int_eq(b.spp_done, 4);
        same_render(&a, &b, "an abandoned pass");
    }
    /* a stop asked before the pass: nothing is done */
    ck_assert_int_eq(render_pass_until(&b, 9, 1, NULL, NULL, &stop_flag,
                                       &abandoned, NULL), SVET_OK);
    ck_assert(abandoned);
    same_render(&a, &b, "a pass stopped before it began");
    stop_flag = 0;
    ck_assert_int_eq(render_pass_until(&b, 9, 2, NULL, NULL, &stop_flag,
                                       &abandoned, NULL), SVET_OK);
    render_pass(&a, 9, 1, NULL, NULL);
    same_render(&a, &b, "after an abandoned pass");
    render_free(&a);
    render_free(&b);
    scene_free(&s);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("render (" REAL_NAME ")");
    TCase *tc = tcase_create("loop");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, image_is_identical_for_any_threads_and_passes);
    tcase_add_test(tc, two_half_renders_merge_into_the_full_one);
    tcase_add_test(tc, variance_image_matches_the_spread_of_the_samples);
    tcase_add_test(tc, rmse_falls_as_one_over_sqrt_spp);
    tcase_add_test(tc,
                   without_grids_auto_renders_with_brute_force_the_same_image);
    tcase_add_test(tc, packets_of_camera_rays_render_the_same_image);
    tcase_add_test(tc, an_abandoned_pass_leaves_the_render_as_it_was);
    suite_add_tcase(s, tc);
    return s;
}
