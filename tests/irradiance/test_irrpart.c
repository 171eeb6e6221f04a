/*
 * test_irrpart.c - tests of the irradiance part (src/irradiance/irrpart.c):
 * the `irradiance` statement's messages, exact answers inside a closed
 * sphere, no leak through a thin wall, the same bits for any thread
 * count, and the cache approaching fresh gathers as a falls.
 */
#include "testutil.h"
#include "scenecheck.h"
#include "irradiance/irrpart.h"
#include "render/allparts.h"
#include "render/render.h"
#include "render/scenefile.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* --- the statement ---------------------------------------------------------- */

static const char base[] =
    "camera position 0 0 0 target 0 0 -1 up 0 1 0 width 4 height 4\n"
    "material wall lambert rho 0.5\n"
    "sphere centre 0 0 0 radius 1 material wall\n";

/* line 4 refused, with its column and what it names */
static void refused(const char *line, const char *where, const char *what)
{
    char text[512];
    snprintf(text, sizeof text, "%s%s\n", base, line);
    scene_t s;
    svet_error e;
    ck_assert_int_ne(scenecheck_parse(&s, text, &e), SVET_OK);
    ck_assert_msg(strstr(e.msg, where) && strstr(e.msg, what), "%s: %s",
                  line, e.msg);
}

START_TEST(irradiance_statement_messages)
{
    refused("irradiance a 0", "t.scn:4:12:", "'a'");
    refused("irradiance a 1.5", "t.scn:4:12:", "(0, 1]");
    refused("irradiance a nan", "t.scn:4:14:", "a");
    refused("irradiance m 0", "t.scn:4:14:", "'m'");
    refused("irradiance n 5000", "t.scn:4:14:", "'n'");
    refused("irradiance min_r -1", "t.scn:4:12:", "min_r");
    refused("irradiance max_r 0", "t.scn:4:12:", "max_r");
    refused("irradiance min_r 5 max_r 2", "t.scn:4:20:", "exceeds");
    refused("irradiance bounces 0", "t.scn:4:20:", "bounces");
    refused("irradiance gradients maybe", "t.scn:4:22:", "gradients");
    refused("irradiance clamp", "t.scn:4:17:", "clamp");
    refused("irradiance m 1024 n 4096", "t.scn:4:19:", "65536");
    refused("irradiance acc 0.1", "t.scn:4:12:", "unknown");
    scene_t s;
    svet_error e;
    scenecheck_parse_ok(&s, base);
    ck_assert_int_eq(scenefile_override(&s, "irradiance.a=0.3", &e), SVET_OK);
    ck_assert_int_eq(scenefile_override(&s, "irradiance.gradients=off", &e),
                     SVET_OK);
    irr_settings_t set;
    irr_settings_of(&s, &set);
    ck_assert(fabs((double)set.a - 0.3) < 1e-6);
    ck_assert(!set.gradients);
    ck_assert_int_eq(set.m, 8);
    ck_assert_int_ne(scenefile_override(&s, "irradiance.max_r=0.5", &e),
                     SVET_OK);
    ck_assert_int_eq(scenefile_override(&s, "integrator=irradiance", &e),
                     SVET_OK);
    scene_free(&s);
}
END_TEST

/* --- a scene set up for the method --------------------------------------- */

typedef struct {
    scene_t s;
    render_t r;
    void *state;
} setup_t;

static void setup(setup_t *u, const char *text, int threads)
{
    svet_error e;
    scenecheck_parse_ok(&u->s, text);
    ck_assert_msg(render_init(&u->r, &u->s, &e) == SVET_OK, "%s", e.msg);
    ck_assert_msg(irr_method.prepare(&u->state, &u->r, threads, &e) ==
                      SVET_OK, "%s", e.msg);
}

static void teardown(setup_t *u)
{
    irr_method.free(u->state);
    render_free(&u->r);
    scene_free(&u->s);
}

/* --- exact answers ------------------------------------------------------- */

/* Inside a closed sphere of radius 1 and albedo rho with a point light of
 * intensity I at its centre, the direct irradiance is I everywhere and
 * the wall's radiance is the same everywhere, so a gather path that
 * counts B diffuse vertices brings E = I (rho + ... + rho^B), and
 * I rho / (1 - rho) as B grows (pbrt-v3's analytic scene). Every gather
 * ray hits the wall, whose point light is sampled exactly and whose
 * Lambert weight is rho: the estimate has no variance, and the tolerance
 * is float's rounding. */
static void sphere_case(int bounces, double rho)
{
    char text[1024];
    snprintf(text, sizeof text,
             "camera position 0 0 0 target 0 0 -1 up 0 1 0 fov 90 "
             "width 16 height 16\n"
             "render maxdepth 100 integrator irradiance\n"
             "irradiance m 4 n 16 bounces %d a 0.2\n"
             "material wall lambert rho %g\n"
             "sphere centre 0 0 0 radius 1 material wall\n"
             "light point position 0 0 0 intensity 2\n", bounces, rho);
    setup_t u;
    setup(&u, text, 0);
    double exact = 0, p = 1;
    for (int k = 1; k <= bounces; k++)
        exact += 2 * (p *= rho);
    ck_assert_uint_gt(irr_state_cache(u.state)->n, 0);
    for (int y = 0; y < 16; y += 3)
        for (int x = 0; x < 16; x += 3) {
            RADIANCE c, g;
            bool found = false;
            ck_assert(irr_pixel_irradiance(u.state, &u.r, x, y, 1, &c,
                                           &found, &g));
            ck_assert(found);
            ck_assert_msg(fabs((double)c.g - exact) < 1e-3 * exact &&
                              fabs((double)g.g - exact) < 1e-3 * exact,
                          "B = %d at (%d, %d): cache %g, gather %g, exact %g",
                          bounces, x, y, (double)c.g, (double)g.g, exact);
        }
    teardown(&u);
}

START_TEST(closed_sphere_has_the_exact_irradiance)
{
    sphere_case(1, 0.5);
    sphere_case(2, 0.5);
    sphere_case(40, 0.5); /* 0.5^41 / 0.5 below float's rounding */
}
END_TEST

/* Two rooms side by side under an open sky, a point light in the left
 * one below the top of the wall between them: no straight path leads
 * from the left room into the right one (a ray must rise to cross the
 * wall's top and then keeps rising), so the right room is black, exactly.
 * Seen from above, every pixel right of the wall must be 0: any light
 * there leaked through the cache. With R forced large and neighbour
 * clamping off the same check sees the leak, so it can fail. */
static const char rooms[] =
    "camera position 0 6 0.001 target 0 0 0 up 0 0 -1 fov 60 "
    "width 24 height 24\n"
    "render maxdepth 8 integrator irradiance seed 3\n"
    "material wall lambert rho 0.7\n"
    "box min -2 -0.1 -1 max 2 0 1 material wall\n"      /* floor */
    "box min -0.02 0 -1 max 0.02 1 1 material wall\n"   /* the thin wall */
    "box min -2.1 0 -1 max -2 1 1 material wall\n"
    "box min 2 0 -1 max 2.1 1 1 material wall\n"
    "box min -2 0 -1.1 max 2 1 -1 material wall\n"
    "box min -2 0 1 max 2 1 1.1 material wall\n"
    "light point position -1 0.5 0 intensity 4\n";

static double right_room_light(const char *settings, double *left)
{
    char text[2048];
    snprintf(text, sizeof text, "%s%s\n", rooms, settings);
    setup_t u;
    setup(&u, text, 0);
    double right = 0;
    *left = 0;
    for (int y = 0; y < 24; y++)
        for (int x = 0; x < 24; x++) {
            RADIANCE c;
            bool found;
            if (!irr_pixel_irradiance(u.state, &u.r, x, y, 1, &c, &found,
                                      NULL))
                continue;
            if (x >= 13)
                right += (double)c.g;
            else if (x <= 10)
                *left += (double)c.g;
        }
    teardown(&u);
    return right;
}

START_TEST(no_light_leaks_through_a_thin_wall)
{
    double left;
    double right = right_room_light("irradiance m 4 n 16", &left);
    ck_assert_msg(left > 0, "the lit room is dark");
    ck_assert_msg(right == 0, "light leaked into the dark room: %g "
                  "(lit room %g)", right, left);
    right = right_room_light("irradiance m 4 n 16 min_r 40 max_r 40 "
                             "clamp off", &left);
    ck_assert_msg(right > 0, "no leak with R forced large: the check "
                  "cannot see one");
}
END_TEST

/* --- determinism --------------------------------------------------------- */

static const char small_box[] =
    "camera position 0 0 3.9 target 0 0 0 up 0 1 0 fov 39.3 width 24 "
    "height 24\n"
    "render maxdepth 5 integrator irradiance\n"
    "irradiance m 4 n 12 a 0.3\n"
    "material white lambert rho 0.8\n"
    "material red lambert rho 0.6 0.05 0.05\n"
    "parallelogram c0 -1 -1 1 c1 1 -1 1 c2 1 -1 -1 c3 -1 -1 -1 "
    "material white\n"
    "parallelogram c0 -1 1 -1 c1 1 1 -1 c2 1 1 1 c3 -1 1 1 material white\n"
    "parallelogram c0 -1 -1 -1 c1 1 -1 -1 c2 1 1 -1 c3 -1 1 -1 "
    "material white\n"
    "parallelogram c0 1 -1 -1 c1 1 -1 1 c2 1 1 1 c3 1 1 -1 material white\n"
    "parallelogram c0 -1 -1 1 c1 -1 -1 -1 c2 -1 1 -1 c3 -1 1 1 "
    "material red\n"
    "box min -0.3 -1 -0.3 max 0.3 -0.2 0.3 material white\n"
    "light point position 0 0.8 0 intensity 2\n";

static void render_small(const char *text, int threads, long spp,
                         image_t *img)
{
    scene_t s;
    svet_error e;
    scenecheck_parse_ok(&s, text);
    render_t r;
    ck_assert_msg(render_init(&r, &s, &e) == SVET_OK, "%s", e.msg);
    ck_assert_int_eq(render_pass(&r, spp, threads, NULL, NULL), SVET_OK);
    ck_assert_int_eq(render_image(&r, img, &e), SVET_OK);
    render_free(&r);
    scene_free(&s);
}

START_TEST(the_same_bits_for_any_thread_count)
{
    setup_t a, b;
    setup(&a, small_box, 1);
    setup(&b, small_box, 2);
    const irrcache_t *ca = irr_state_cache(a.state),
                     *cb = irr_state_cache(b.state);
    ck_assert_uint_gt(ca->n, 0);
    ck_assert_uint_eq(ca->n, cb->n);
    ck_assert(memcmp(ca->rec, cb->rec, ca->n * sizeof *ca->rec) == 0);
    teardown(&a);
    teardown(&b);
    image_t x, y;
    render_small(small_box, 1, 2, &x);
    render_small(small_box, 2, 2, &y);
    ck_assert(memcmp(x.px, y.px, (size_t)x.width * (size_t)x.height * 3 *
                                     sizeof(float)) == 0);
    image_free(&x);
    image_free(&y);
}
END_TEST

/* --- convergence ------------------------------------------------------- */

/* The cache's irradiance against the mean of four fresh gathers of 8 x 32
 * rays at every pixel's first hit (the reference; the same rays for every
 * a, so its noise adds the same floor to each): the mean squared
 * difference must fall as a falls, 0.6 to 0.1, with more records. */
static double cache_error(double a, size_t *records)
{
    char text[4096];
    snprintf(text, sizeof text, "%sirradiance a %g m 8 n 32\n", small_box,
             a);
    setup_t u;
    setup(&u, text, 0);
    *records = irr_state_cache(u.state)->n;
    double s = 0;
    int n = 0;
    for (int y = 0; y < 24; y++)
        for (int x = 0; x < 24; x++) {
            RADIANCE c, g = rad_grey(0);
            bool found;
            if (!irr_pixel_irradiance(u.state, &u.r, x, y, 7, &c, &found,
                                      NULL))
                continue;
            double ref = 0;
            for (uint64_t k = 0; k < 4; k++) {
                irr_pixel_irradiance(u.state, &u.r, x, y, 8 + k, NULL, NULL,
                                     &g);
                ref += (double)g.g / 4;
            }
            double d = (double)c.g - ref;
            s += d * d;
            n++;
        }
    teardown(&u);
    return s / n;
}

START_TEST(the_cache_approaches_the_gathers_as_a_falls)
{
    size_t n1, n2;
    double e1 = cache_error(0.6, &n1), e2 = cache_error(0.1, &n2);
    ck_assert_uint_gt(n2, n1);
    ck_assert_msg(e2 < e1, "a 0.6: %zu records, error %g; a 0.1: %zu, %g",
                  n1, e1, n2, e2);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("irrpart (" REAL_NAME ")");
    TCase *t = tcase_create("core");
    tcase_set_timeout(t, 600);
    tcase_add_test(t, irradiance_statement_messages);
    tcase_add_test(t, closed_sphere_has_the_exact_irradiance);
    tcase_add_test(t, no_light_leaks_through_a_thin_wall);
    tcase_add_test(t, the_same_bits_for_any_thread_count);
    tcase_add_test(t, the_cache_approaches_the_gathers_as_a_falls);
    suite_add_tcase(s, t);
    return s;
}
