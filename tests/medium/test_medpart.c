/*
 * test_medpart.c - medpart.h, the media of ch. 11 in the scene file and
 * `render integrator volpath`: the statement and the shape keys parse;
 * bad input (negative or NaN coefficients, g outside (-1, 1), an unknown
 * medium, a boundary that is not closed, a bad .vol file) fails with
 * file:line:col; a light seen through an absorbing slab is dimmed by
 * Beer-Lambert's exp(-sigma_a d) in each channel; an emitting absorbing
 * slab glows as L_e (1 - exp(-sigma_a d)) by volpath and by volsingle;
 * a ray that slips out of a gridded medium ends.
 */
#include "testutil.h"
#include "scenecheck.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "medium/medpart.h"
#include "render/allparts.h"
#include "render/render.h"
#include "render/scenefile.h"

static void accepted(const char *text)
{
    scene_t s;
    scenecheck_parse_ok(&s, text);
    scene_free(&s);
}

#define HEAD "camera position 0 0 3 target 0 0 0 width 8 height 6\n" \
    "material m lambert rho 0.5\n"

START_TEST(media_and_boundaries_parse)
{
    accepted(HEAD "medium fog homogeneous sigma_a 0.1 sigma_s 0.2 0.3 0.4 "
                  "global\n"
                  "medium smoke homogeneous sigma_s 1 phase hg g -0.5\n"
                  "medium air homogeneous sigma_s 0.01 phase rayleigh\n"
                  "sphere centre 0 0 0 radius 1 material m medium smoke\n"
                  "box min -1 -1 -1 max 1 1 1 material m medium air "
                  "outside smoke invisible\n"
                  "cylinder base 0 0 0 top 0 1 0 radius 1 material m "
                  "medium smoke rotate 1 0 0 30\n"
                  "render integrator volpath\n");
    /* the objects point at their sides, the global medium is found */
    scene_t s;
    svet_error e;
    ck_assert_int_eq(scenecheck_parse(&s, HEAD
                         "medium fog homogeneous sigma_a 0.1 global\n"
                         "medium smoke homogeneous sigma_s 1\n"
                         "sphere centre 0 0 0 radius 1 material m "
                         "medium smoke invisible\n"
                         "sphere centre 0 0 5 radius 1 material m\n", &e),
                     SVET_OK);
    const medium_t *fog = medpart_global(&s);
    ck_assert_ptr_nonnull(fog);
    ck_assert(fog->sigma_a.r == REAL_C(0.1));
    ck_assert_ptr_nonnull(s.objects[0]->inside);
    ck_assert(s.objects[0]->inside->invisible);
    ck_assert(s.objects[0]->inside->m->sigma_s.g == 1);
    ck_assert_ptr_eq(s.objects[0]->outside->m, fog);
    ck_assert_ptr_null(s.objects[1]->inside);
    ck_assert_ptr_null(s.objects[1]->outside);
    scene_free(&s);
}
END_TEST

/* A scene lit only by a medium's emission is not "dark": the warning
 * counts a used medium that emits (inside a boundary, globally, or as a
 * component of a mix), and still comes for one defined but unused. */
static long dark_warnings(const char *text)
{
    scene_t s;
    scenecheck_parse_ok(&s, text);
    long n = 0;
    for (long i = 0; i < s.warnings.n && i < SCENE_MAX_WARNINGS; i++)
        n += strstr(s.warnings.msg[i], "nothing emits light") != NULL;
    scene_free(&s);
    return n;
}

START_TEST(an_emitting_medium_lights_the_scene)
{
#define GLOWS "medium glow homogeneous sigma_a 1 emission 0 0 2\n"
    ck_assert_int_eq(dark_warnings(HEAD GLOWS "sphere centre 0 0 0 radius 1 "
                                   "material m medium glow invisible\n"), 0);
    ck_assert_int_eq(dark_warnings(HEAD "medium glow homogeneous sigma_a 1 "
                                   "emission 0 0 2 global\n"
                                   "sphere centre 0 0 0 radius 1 material "
                                   "m\n"), 0);
    ck_assert_int_eq(dark_warnings(HEAD GLOWS "medium dust homogeneous "
                                   "sigma_s 1\nmedium both mix glow dust\n"
                                   "sphere centre 0 0 0 radius 1 material m "
                                   "medium both invisible\n"), 0);
    /* defined but not used, or used but black: dark */
    ck_assert_int_eq(dark_warnings(HEAD GLOWS "sphere centre 0 0 0 radius 1 "
                                   "material m\n"), 1);
    ck_assert_int_eq(dark_warnings(HEAD "medium dust homogeneous sigma_s 1\n"
                                   "sphere centre 0 0 0 radius 1 material m "
                                   "medium dust invisible\n"), 1);
#undef GLOWS
}
END_TEST

/* `medium NAME mix A B ...`: the components are copies of the named
 * media, the global flag anywhere on the line. */
START_TEST(a_mix_sums_named_media)
{
    scene_t s;
    svet_error e;
    ck_assert_msg(scenecheck_parse(&s, HEAD "medium a homogeneous sigma_a 0.1 sigma_s 1\n"
                                 "medium b homogeneous sigma_s 2 phase hg g "
                                 "0.5\nmedium air mix a b global\n", &e) ==
                      SVET_OK, "%s", e.msg);
    const medium_t *m = medpart_global(&s);
    ck_assert_ptr_nonnull(m);
    ck_assert_int_eq(m->ncomponents, 2);
    ck_assert(m->components[1].phase.kind == PHASE_HG);
    ck_assert(m->components[1].phase.g == REAL_C(0.5));
    RADIANCE st = medium_sigma_t(m);
    ck_assert(st.r == REAL_C(0.1) + 3);
    scene_free(&s);
}
END_TEST

START_TEST(bad_media_name_file_line_and_column)
{
    scenecheck_refused(HEAD "medium a homogeneous sigma_a -1\n", "t.scn:3:",
                       "must not be negative");
    scenecheck_refused(HEAD "medium a homogeneous sigma_s 1 nan 1\n",
                       "t.scn:3:", "");
    scenecheck_refused(HEAD "medium a homogeneous sigma_s 1 phase hg g 1\n",
                       "t.scn:3:41:", "g must be in (-1, 1)");
    scenecheck_refused(HEAD "medium a homogeneous sigma_s 1 phase hg g -1.5\n",
                       "t.scn:3:41:", "g must be in (-1, 1)");
    scenecheck_refused(HEAD "medium a homogeneous sigma_s 1 g 0.5\n",
                       "t.scn:3:32:", "phase hg");
    scenecheck_refused(HEAD "medium a fluffy\n", "t.scn:3:10:",
                       "expects a kind");
    scenecheck_refused(HEAD "medium a homogeneous sigma_s 1\n"
                            "medium a homogeneous\n",
                       "t.scn:4:8:", "already defined");
    scenecheck_refused(HEAD "medium smoke homogeneous sigma_s 1\n"
                            "sphere centre 0 0 0 radius 1 material m "
                            "medium smoek\n",
                       "t.scn:4:48:", "did you mean 'smoke'");
    scenecheck_refused(HEAD "sphere centre 0 0 0 radius 1 material m "
                            "medium x\n",
                       "t.scn:3:48:", "unknown medium 'x'");
    scenecheck_refused(HEAD "sphere centre 0 0 0 radius 1 material m "
                            "invisible\n",
                       "t.scn:3:41:", "needs 'medium NAME'");
    static const char *const open[] = {
        "plane point 0 0 0 normal 0 1 0",
        "disk centre 0 0 0 normal 0 1 0 radius 1",
        "parallelogram c0 0 0 0 c1 1 0 0 c3 0 1 0",
        "triangle p0 0 0 0 p1 1 0 0 p2 0 1 0",
        "cylinder base 0 0 0 top 0 1 0 radius 0.5 open",
        "cone base 0 0 0 apex 0 1 0 radius 0.5 open",
        "cylinder base 0 0 0 top 0 1 0 radius 0.5 open rotate 1 1 0 40",
    };
    for (size_t i = 0; i < sizeof open / sizeof *open; i++) {
        char text[512];
        snprintf(text, sizeof text,
                 HEAD "medium a homogeneous sigma_s 1\n%s material m "
                      "medium a\n", open[i]);
        scenecheck_refused(text, "t.scn:4:", "must be a closed surface");
    }
    scenecheck_refused(HEAD "medium a grid sigma_s 1\n", "t.scn:3:1:", "needs 'file'");
    scenecheck_refused(HEAD "medium a grid sigma_s 1 file missing.vol\n", "t.scn:3:",
            "missing.vol");
    scenecheck_refused(HEAD "medium a homogeneous sigma_s 1 file x.vol\n",
            "t.scn:3:32:", "takes no 'file'");
    scenecheck_refused(HEAD "medium a homogeneous sigma_s 1 emission 1\n",
            "t.scn:3:32:", "give it 'sigma_a' > 0");
    /* mixes: components defined above, none a mix, not the mix itself */
    scenecheck_refused(HEAD "medium a homogeneous sigma_s 1\nmedium b mix a c\n",
            "t.scn:4:16:", "unknown medium 'c'");
    scenecheck_refused(HEAD "medium a homogeneous sigma_s 1\nmedium b mix a b\n",
            "t.scn:4:16:", "component of itself");
    scenecheck_refused(HEAD "medium aa homogeneous sigma_s 1\nmedium b mix ab\n",
            "t.scn:4:14:", "did you mean 'aa'");
    scenecheck_refused(HEAD "medium a homogeneous sigma_s 1\nmedium b mix a a\n"
                 "medium c mix a b\n", "t.scn:5:16:", "is a mix itself");
    scenecheck_refused(HEAD "medium b mix\n", "t.scn:3:13:", "names of its components");
    scenecheck_refused(HEAD "medium a homogeneous sigma_s 1\nmedium b mix a 1x\n",
            "t.scn:4:16:", "");
    scenecheck_refused(HEAD "medium a homogeneous sigma_s 1\n"
                 "medium b mix a a a a a a a a a\n", "t.scn:4:30:",
            "at most 8 components");
}
END_TEST

/* Write n bytes of a .vol header declaring nx ny nz and then `values`
 * floats of 0.5 to path. */
static void write_vol(const char *path, int32_t nx, int32_t ny, int32_t nz,
                      long values)
{
    FILE *f = fopen(path, "wb");
    ck_assert_ptr_nonnull(f);
    const unsigned char magic[4] = { 'V', 'O', 'L', 3 };
    fwrite(magic, 1, 4, f);
    int32_t h[5] = { 1, nx, ny, nz, 1 };
    fwrite(h, 4, 5, f);
    float box[6] = { 0, 0, 0, 1, 1, 1 };
    fwrite(box, 4, 6, f);
    for (long i = 0; i < values; i++) {
        float v = 0.5f;
        fwrite(&v, 4, 1, f);
    }
    fclose(f);
}

START_TEST(bad_vol_files_are_refused)
{
    char dir[] = "/tmp/medpartXXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    char good[256], trunc[256], huge[256], text[1024];
    snprintf(good, sizeof good, "%s/good.vol", dir);
    snprintf(trunc, sizeof trunc, "%s/trunc.vol", dir);
    snprintf(huge, sizeof huge, "%s/huge.vol", dir);
    write_vol(good, 2, 2, 2, 8);
    write_vol(trunc, 2, 2, 2, 7);
    write_vol(huge, 100000, 100000, 100000, 0);
    snprintf(text, sizeof text, HEAD "medium a grid sigma_s 1 file \"%s\" "
             "scale 2 min -1 -1 -1 max 1 1 1\n"
             "box min -1 -1 -1 max 1 1 1 material m medium a invisible\n",
             good);
    accepted(text);
    snprintf(text, sizeof text, HEAD "medium a grid sigma_s 1 file \"%s\"\n",
             trunc);
    scenecheck_refused(text, "t.scn:3:", "trunc.vol");
    snprintf(text, sizeof text, HEAD "medium a grid sigma_s 1 file \"%s\"\n",
             huge);
    scenecheck_refused(text, "t.scn:3:", "huge.vol");
    snprintf(text, sizeof text, HEAD "medium a grid sigma_s 1 file \"%s\" "
             "min 0 0 0\n", good);
    scenecheck_refused(text, "t.scn:3:", "both 'min' and 'max'");
    snprintf(text, sizeof text, HEAD "medium a grid sigma_s 1 file \"%s\" "
             "global\n", good);
    scenecheck_refused(text, "t.scn:3:", "bound it by a shape");
    remove(good);
    remove(trunc);
    remove(huge);
    rmdir(dir);
}
END_TEST

/* A square light of radiance 1 seen along z through a slab 1 thick of
 * purely absorbing medium (invisible boundary), with a field of view of
 * 1 degree: every path crosses the slab within 1e-4 of straight on. */
#define SLAB "camera position 0 0 3 target 0 0 0 fov 1 width 4 height 4\n" \
    "render spp 1024 maxdepth 2 integrator volpath seed 3\n" \
    "material black lambert rho 0\n" \
    "medium ink homogeneous sigma_a 0.5 1 2\n" \
    "parallelogram c0 -1 -1 0 c1 1 -1 0 c3 -1 1 0 material black emit 1\n" \
    "box min -2 -2 0.5 max 2 2 1.5 material black medium ink invisible\n"

START_TEST(beer_lambert_through_a_slab_per_channel)
{
    image_t img;
    scenecheck_render(SLAB, 0, &img);
    const double sig[3] = { 0.5, 1, 2 };
    double T[3], P = 0;
    for (int k = 0; k < 3; k++) {
        T[k] = exp(-sig[k]);
        P += T[k] / 3;
    }
    /* Each sample picks a channel, passes the slab with probability P =
     * the channels' mean transmittance, and then carries T_c / P in
     * channel c (0 if it was absorbed): mean T_c, variance T_c^2 (1/P -
     * 1). The image mean of N = 16 * 1024 samples is within 4 standard
     * errors T_c sqrt((1/P - 1) / N), about 4% of T_c; the slant of the
     * rays adds below 1e-4. */
    const double N = 16.0 * 1024;
    for (int k = 0; k < 3; k++) {
        double sum = 0;
        for (int y = 0; y < 4; y++)
            for (int x = 0; x < 4; x++)
                sum += (double)image_at(&img, x, y)[k];
        double mean = sum / 16, se = T[k] * sqrt((1 / P - 1) / N);
        ck_assert_msg(fabs(mean - T[k]) < 4 * se,
                      "channel %d: %g, exp(-sigma_t d) = %g (se %g)", k, mean,
                      T[k], se);
    }
    image_free(&img);
}
END_TEST

/* The furnace: a sphere of purely scattering medium (albedo 1, an
 * invisible boundary, optical radius 1) under an environment of radiance
 * 1 is everywhere lit by radiance 1, so every pixel's expected value is
 * 1 (Pharr et al., pbrt-v3 sec. 15.2: no absorption, nothing is lost),
 * whatever the phase function: HG at g = -0.5 (backward), 0 and 0.8
 * (forward). The pixels are independent:
 * their mean must lie within 4 of their own standard errors of 1, and
 * that error must be small enough for the test to see a loss of a few
 * per cent. */
#define FURNACE_G(g) \
    "camera position 0 0 4 target 0 0 0 fov 40 width 8 height 8\n" \
    "render spp 64 maxdepth 200 integrator volpath seed 5\n" \
    "material black lambert rho 0\n" \
    "environment radiance 1\n" \
    "medium fog homogeneous sigma_a 0 sigma_s 1 phase hg g " g "\n" \
    "sphere centre 0 0 0 radius 1 material black medium fog invisible\n"
#define FURNACE FURNACE_G("0.4")

START_TEST(a_scattering_sphere_in_a_furnace_keeps_radiance_one)
{
    static const char *const scenes[] = { FURNACE_G("-0.5"), FURNACE_G("0"),
                                          FURNACE_G("0.8") };
    for (int i = 0; i < 3; i++) {
        image_t img;
        scenecheck_render(scenes[i], 0, &img);
        for (int k = 0; k < 3; k++) {
            double sum = 0, sum2 = 0;
            for (int y = 0; y < 8; y++)
                for (int x = 0; x < 8; x++) {
                    double v = (double)image_at(&img, x, y)[k];
                    sum += v;
                    sum2 += v * v;
                }
            double mean = sum / 64, var = (sum2 / 64 - mean * mean) * 64 / 63;
            double se = sqrt(var > 0 ? var / 64 : 0);
            ck_assert_msg(se < 0.01, "scene %d, channel %d: standard error "
                          "%g", i, k, se);
            ck_assert_msg(fabs(mean - 1) < 4 * se + 1e-6,
                          "scene %d, channel %d: mean %g, expected 1 (se %g)",
                          i, k, mean, se);
        }
        image_free(&img);
    }
}
END_TEST

/* Scattering, shadow rays and MIS draw from the pixel's own stream: one
 * thread and two give the same bits. */
START_TEST(one_thread_and_two_give_the_same_bits)
{
    image_t a, b;
    scenecheck_render(FURNACE, 1, &a);
    scenecheck_render(FURNACE, 2, &b);
    ck_assert_int_eq(a.width, b.width);
    for (int y = 0; y < a.height; y++)
        for (int x = 0; x < a.width; x++)
            ck_assert(memcmp(image_at(&a, x, y), image_at(&b, x, y),
                             3 * sizeof *image_at(&a, x, y)) == 0);
    image_free(&a);
    image_free(&b);
}
END_TEST

/* Without media, volpath estimates what the path tracer does: the same
 * closed room rendered both ways. The paired pixel differences are
 * independent with mean 0; their mean must lie within 4 of its own
 * standard errors of 0, and that error must be small against the
 * image's mean for the test to see a difference. Where the two draw the
 * same samples the images are equal to the bit (the double build). */
#define ROOM(method) \
    "camera position 0 0 0 target 0 0 -1 fov 60 width 12 height 12\n" \
    "render spp 64 maxdepth 6 integrator " method " seed 7\n" \
    "material grey lambert rho 0.6\n" \
    "light point position 0 1 -1 intensity 2\n" \
    "box min -2 -2 -4 max 2 2 2 material grey\n" \
    "sphere centre 0 -1 -2 radius 0.7 material grey\n"

START_TEST(without_media_volpath_agrees_with_the_path_tracer)
{
    image_t a, b;
    scenecheck_render(ROOM("path"), 0, &a);
    scenecheck_render(ROOM("volpath"), 0, &b);
    const int n = a.width * a.height;
    for (int k = 0; k < 3; k++) {
        double sa = 0, sd = 0, sd2 = 0;
        for (int y = 0; y < a.height; y++)
            for (int x = 0; x < a.width; x++) {
                double va = (double)image_at(&a, x, y)[k];
                double d = (double)image_at(&b, x, y)[k] - va;
                sa += va;
                sd += d;
                sd2 += d * d;
            }
        double ma = sa / n, md = sd / n;
        if (sd2 == 0) /* the same samples, to the bit: exact agreement */
            continue;
        double se = sqrt((sd2 / n - md * md) / (n - 1));
        ck_assert_msg(se < 0.02 * ma, "channel %d: se %g of mean %g", k, se,
                      ma);
        ck_assert_msg(fabs(md) < 4 * se, "channel %d: volpath - path = %g "
                      "(se %g, path's mean %g)", k, md, se, ma);
    }
    image_free(&a);
    image_free(&b);
}
END_TEST

/* An emitting, purely absorbing slab 1 thick (invisible boundary, no
 * light, nothing behind it) seen straight on: pbrt-v4's source sigma_a
 * L_e (sec. 11.1.2) integrated along the ray gives L = L_e (1 -
 * exp(-sigma_a d)) per channel. volpath integrates each segment exactly;
 * volsingle marches it with step h from a jittered start, a shifted
 * rectangle rule whose sample deviates by at most h |f(d) - f(0)| /
 * sqrt(12) = h S (1 - exp(-sigma_a d)) / sqrt(12) (f = S exp(-sigma_a t),
 * S = sigma_a L_e), so the mean of N samples lies within 4 of those over
 * sqrt(N); the rays' slant (fov 1 degree) adds below 1e-4 of L. A source
 * of L_e alone would give L_e (1 - exp(-sigma_a d)) / sigma_a. */
#define GLOW(method) \
    "camera position 0 0 3 target 0 0 0 fov 1 width 4 height 4\n" \
    "render spp 16 maxdepth 2 integrator " method " seed 3\n" \
    "volsingle step 0.01\n" \
    "material black lambert rho 0\n" \
    "medium glow homogeneous sigma_a 0.5 1 2 emission 1 2 3\n" \
    "box min -2 -2 0.5 max 2 2 1.5 material black medium glow invisible\n"

START_TEST(an_emitting_absorbing_slab_glows_as_its_closed_form)
{
    const char *methods[2] = { GLOW("volpath"), GLOW("volsingle") };
    const double sig[3] = { 0.5, 1, 2 }, Le[3] = { 1, 2, 3 }, h = 0.01;
    for (int i = 0; i < 2; i++) {
        image_t img;
        scenecheck_render(methods[i], 0, &img);
        for (int k = 0; k < 3; k++) {
            double want = Le[k] * (1 - exp(-sig[k]));
            double sum = 0;
            for (int y = 0; y < 4; y++)
                for (int x = 0; x < 4; x++)
                    sum += (double)image_at(&img, x, y)[k];
            double mean = sum / 16;
            double tol = 1e-4 * want +
                         (i == 0 ? 1e-5 * want
                                 : 4 * h * sig[k] * want / sqrt(12) /
                                       sqrt(16.0 * 16));
            ck_assert_msg(fabs(mean - want) < tol,
                          "%s channel %d: %.7g, L_e (1 - exp(-sigma_a d)) "
                          "= %.7g (tolerance %g)", i ? "volsingle" : "volpath",
                          k, mean, want, tol);
        }
        image_free(&img);
    }
}
END_TEST

/* The grid walk that slipped: a ray in a gridded medium that finds no
 * exit (here by construction: the boundary is one triangle of a mesh,
 * whose closedness the reader cannot check, so the ray enters it and
 * never leaves) used to be tracked to VOLPATH_FAR under the majorant of
 * a grid whose border density, continued outside by the clamp, is 0:
 * about 1e30 null collisions. volpath takes such a ray to have slipped
 * out of its medium (volpath.c). The render of the case must end (the
 * suite's "slip" case has a timeout) and see the environment through
 * the vanished medium: exactly 1, by volpath and by volsingle. */
static void write_ramp_vol(const char *path)
{
    FILE *f = fopen(path, "wb");
    ck_assert_ptr_nonnull(f);
    const unsigned char magic[4] = { 'V', 'O', 'L', 3 };
    fwrite(magic, 1, 4, f);
    int32_t h[5] = { 1, 3, 1, 1, 1 };
    fwrite(h, 4, 5, f);
    float box[6] = { -1, -1, -1, 1, 1, 1 };
    fwrite(box, 4, 6, f);
    const float v[3] = { 0, 4, 0 };
    fwrite(v, 4, 3, f);
    fclose(f);
}

START_TEST(a_ray_that_slips_out_of_a_grid_ends)
{
    char dir[] = "/tmp/medslipXXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    char vol[64], obj[64], scn[2][1024];
    snprintf(vol, sizeof vol, "%s/d.vol", dir);
    snprintf(obj, sizeof obj, "%s/t.obj", dir);
    write_ramp_vol(vol);
    FILE *f = fopen(obj, "w");
    ck_assert_ptr_nonnull(f);
    /* one triangle in z = 0 facing +z, across the camera's view */
    fputs("v -5 -5 0\nv 5 -5 0\nv 0 5 0\nf 1 2 3\n", f);
    fclose(f);
    const char *methods[2] = { "volpath", "volsingle" };
    for (int i = 0; i < 2; i++) {
        snprintf(scn[i], sizeof scn[i],
                 "camera position 0 0 3 target 0 0 0 fov 10 width 4 "
                 "height 4\n"
                 "render spp 4 maxdepth 4 integrator %s seed 3\n"
                 "material black lambert rho 0\n"
                 "environment radiance 1\n"
                 "medium smoke grid sigma_s 1 file \"%s\"\n"
                 "mesh file \"%s\" material black medium smoke invisible\n",
                 methods[i], vol, obj);
        image_t img;
        scenecheck_render(scn[i], 0, &img);
        for (int y = 0; y < img.height; y++)
            for (int x = 0; x < img.width; x++)
                for (int k = 0; k < 3; k++)
                    ck_assert_msg(image_at(&img, x, y)[k] == 1,
                                  "%s: pixel %d %d channel %d: %g",
                                  methods[i], x, y, k,
                                  (double)image_at(&img, x, y)[k]);
        image_free(&img);
    }
    remove(vol);
    remove(obj);
    rmdir(dir);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("medpart");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, media_and_boundaries_parse);
    tcase_add_test(tc, an_emitting_medium_lights_the_scene);
    tcase_add_test(tc, bad_media_name_file_line_and_column);
    tcase_add_test(tc, a_mix_sums_named_media);
    tcase_add_test(tc, bad_vol_files_are_refused);
    tcase_add_test(tc, beer_lambert_through_a_slab_per_channel);
    tcase_add_test(tc, a_scattering_sphere_in_a_furnace_keeps_radiance_one);
    tcase_add_test(tc, one_thread_and_two_give_the_same_bits);
    tcase_add_test(tc, without_media_volpath_agrees_with_the_path_tracer);
    tcase_add_test(tc, an_emitting_absorbing_slab_glows_as_its_closed_form);
    suite_add_tcase(s, tc);
    /* the slipped ray: a hang fails here, by the timeout */
    TCase *slip = tcase_create("slip");
    tcase_set_timeout(slip, 30);
    tcase_add_test(slip, a_ray_that_slips_out_of_a_grid_ends);
    suite_add_tcase(s, slip);
    return s;
}
