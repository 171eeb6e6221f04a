/*
 * test_scenefile.c - the scene file reader (scenefile.h, scenes/README.md):
 * every statement and key parses to the right values, every shipped scene
 * parses, every kind of error gives its exact file:line:col message and
 * status, the inputs the fuzzer found (tests/data/scene/regress-*.scn)
 * are handled, and command-line overrides are checked like the file.
 * The scenes are read with every optional part (allparts.h), as the svet
 * command reads them; a program without them (ch. 5) refuses `mesh` and
 * `accel grid` with what to link.
 * Runs from the top directory (it reads scenes/ and tests/data/scene/).
 */
#include "testutil.h"

#include <dirent.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "irradiance/irrpart.h"
#include "render/allparts.h"
#include "colour/colour.h"
#include "materials/material.h"
#include "mesh/mesh.h"
#include "render/render.h"
#include "render/scenefile.h"

#define DATA "tests/data/scene"

/* Every statement keyword, in the order the parser's error lists them:
 * the core's, then each part's (allparts.c). */
#define KEYWORDS                                                             \
    "camera, render, output, tonemap, material, light, environment, "       \
    "sphere, plane, disk, parallelogram, triangle, box, cylinder, cone, "   \
    "mesh, photonmap, irradiance, texture, medium, volsingle, volphoton, "  \
    "animation, key"

/* Parse text (a C string) as the file "t.scn" with meshes in DATA. */
static svet_status parse(scene_t *s, const char *text, svet_error *err)
{
    return scenefile_parse_with(s, text, strlen(text), "t.scn", DATA,
                                scene_features_all(), err);
}

/* Read the file at path as the svet command does. */
static svet_status read_scene(scene_t *s, const char *path, svet_error *err)
{
    return scenefile_read_with(s, path, scene_features_all(), err);
}

/* Parse text that must succeed. */
static void parse_ok(scene_t *s, const char *text)
{
    svet_error err;
    svet_error_clear(&err);
    svet_status st = parse(s, text, &err);
    ck_assert_msg(st == SVET_OK, "parse failed: %s", err.msg);
}

/* Parse text that must fail with status st and exactly the message msg;
 * the scene is left empty. */
static void parse_err(const char *text, svet_status st, const char *msg)
{
    scene_t s;
    svet_error err;
    svet_error_clear(&err);
    svet_status got = parse(&s, text, &err);
    ck_assert_msg(got == st, "status %d (%s), expected %d, for:\n%s",
                  (int)got, err.msg, (int)st, text);
    ck_assert_str_eq(err.msg, msg);
    ck_assert_int_eq(s.nobjects + s.nmaterials + s.npoint_lights, 0);
    scene_free(&s);
}

/* The normal of an object's surface, from a sample at the centre of the
 * parameter square (every primitive gives ng there). */
static void normal_at_centre(const COBJECT *obj, VECTOR3 n)
{
    cobject_sample_t smp;
    real u[2] = { REAL_C(0.5), REAL_C(0.5) };
    obj->ops->sample(obj, u, &smp);
    vec_copy(n, smp.n);
}

static void bounds_of(const COBJECT *obj, bbox_t *b)
{
    obj->ops->bounds(obj, -1, b);
}

#define M "material m lambert rho 0.5\n"
#define PI_D 3.14159265358979323846

/* lo <= v <= hi, with a message. */
#define assert_between(v, lo, hi)                                        \
    ck_assert_msg((double)(v) >= (lo) && (double)(v) <= (hi),            \
                  "%s = %.9g not in [%.9g, %.9g]", #v, (double)(v),     \
                  (double)(lo), (double)(hi))

/* "<prefix> <words[i]>" sets the enum that get() reads to i, for each i:
 * the words of scene.h's enums are in the order of their values. */
static void each_word_gives_its_enum_value(const char *prefix,
                                           const char *const *words, int n,
                                           int (*get)(const scene_t *))
{
    for (int i = 0; i < n; i++) {
        scene_t s;
        char line[96];
        snprintf(line, sizeof line, "%s %s\n", prefix, words[i]);
        parse_ok(&s, line);
        ck_assert_int_eq(get(&s), i);
        scene_free(&s);
    }
}

static int integrator_of(const scene_t *s) { return s->render.integrator; }
static int accel_of(const scene_t *s) { return s->render.accel; }
static int tonemap_of(const scene_t *s) { return s->render.tonemap.op; }

/* --- settings ------------------------------------------------------------ */

START_TEST(camera_keys_parse_to_their_values)
{
    scene_t s;
    parse_ok(&s, "camera position 1 2 3 target 4 5 6 up 0 0 1 fov 39.3077 "
                 "fov_axis diagonal width 320 height 200 filter box "
                 "filter_width 1.5\n");
    const scene_camera_t *c = &s.camera;
    ck_assert_near(c->position[X], 1, 0);
    ck_assert_near(c->position[Z], 3, 0);
    ck_assert_near(c->target[Y], 5, 0);
    ck_assert_near(c->up[Z], 1, 0);
    ck_assert_near(c->fov, REAL_C(39.3077), 0);
    ck_assert_int_eq(c->fov_axis, SCENE_FOV_DIAGONAL);
    ck_assert_int_eq(c->width, 320);
    ck_assert_int_eq(c->height, 200);
    ck_assert_int_eq(c->filter, SCENE_FILTER_BOX);
    ck_assert_near(c->filter_width, REAL_C(1.5), 0);
    scene_free(&s);
    /* Several camera lines accumulate; later ones win. */
    parse_ok(&s, "camera width 10\ncamera height 20 fov_axis x\n"
                 "camera width 30\n");
    ck_assert_int_eq(s.camera.width, 30);
    ck_assert_int_eq(s.camera.height, 20);
    ck_assert_int_eq(s.camera.fov_axis, SCENE_FOV_X);
    ck_assert_near(s.camera.fov, 40, 0); /* the default, untouched */
    scene_free(&s);
}
END_TEST

START_TEST(render_keys_parse_to_their_values)
{
    scene_t s;
    parse_ok(&s, "render spp 0000000000000000000000000000000000000001024\n");
    ck_assert_int_eq(s.render.spp, 1024);
    scene_free(&s);
    parse_ok(&s, "render spp 1024 maxdepth 7 roulette off roulette_depth 9 "
                 "seed 18446744073709551615 integrator ao ao_distance 0.25 "
                 "threads 2 time_limit 12.5 passes 8 checkpoint on "
                 "accel hgrid packets off\n");
    const scene_render_t *r = &s.render;
    ck_assert_int_eq(r->spp, 1024);
    ck_assert_int_eq(r->max_depth, 7);
    ck_assert(!r->roulette);
    ck_assert_int_eq(r->roulette_depth, 9);
    ck_assert_uint_eq(r->seed, UINT64_MAX);
    ck_assert_int_eq(r->integrator, SCENE_INTEGRATOR_AO);
    ck_assert_near(r->ao_distance, REAL_C(0.25), 0);
    ck_assert_int_eq(r->threads, 2);
    ck_assert_near(r->time_limit, 12.5, 0);
    ck_assert_int_eq(r->passes, 8);
    ck_assert(r->checkpoint);
    ck_assert_int_eq(r->accel, SCENE_ACCEL_HGRID);
    ck_assert(!r->packets);
    scene_free(&s);
    parse_ok(&s, "render spp 4\n"); /* packets are on unless turned off */
    ck_assert(s.render.packets);
    scene_free(&s);
    static const char *const names[] = { "path", "direct", "bsdf", "ao",
                                         "nee" };
    each_word_gives_its_enum_value("render integrator", names, 5,
                                   integrator_of);
    static const char *const accels[] = { "auto", "brute", "grid", "hgrid" };
    each_word_gives_its_enum_value("render accel", accels, 4, accel_of);
}
END_TEST

START_TEST(output_and_tonemap_parse_to_their_values)
{
    scene_t s;
    parse_ok(&s, "output exr out/a.exr png \"my # render.png\"\n"
                 "tonemap operator reinhard exposure -1.5 key 0.36 white 4 "
                 "bias 0.7 curve gamma gamma 1.8\n"
                 "output png b.png\n");
    ck_assert_str_eq(s.render.output_exr, "out/a.exr");
    ck_assert_str_eq(s.render.output_png, "b.png"); /* the later wins */
    const scene_tonemap_t *t = &s.render.tonemap;
    ck_assert_int_eq(t->op, SCENE_TONEMAP_REINHARD);
    ck_assert_near(t->exposure, REAL_C(-1.5), 0);
    ck_assert_near(t->key, REAL_C(0.36), 0);
    ck_assert_near(t->white, 4, 0);
    ck_assert_near(t->bias, REAL_C(0.7), 0);
    ck_assert_int_eq(t->curve, SCENE_CURVE_GAMMA);
    ck_assert_near(t->gamma, REAL_C(1.8), 0);
    scene_free(&s);
    static const char *const ops[] = { "linear", "exponential", "reinhard",
                                       "drago", "histogram" };
    each_word_gives_its_enum_value("tonemap operator", ops, 5, tonemap_of);
}
END_TEST

START_TEST(comments_blank_lines_tabs_and_crlf_are_accepted)
{
    scene_t s;
    parse_ok(&s, "# a comment\n\n   \t\n\tcamera\twidth 8 # trailing\r\n"
                 "camera height 9#no blank needed\r\n" M
                 "sphere centre 0 0 0 radius 1 material m");
    ck_assert_int_eq(s.camera.width, 8);
    ck_assert_int_eq(s.camera.height, 9);
    ck_assert_int_eq(s.nobjects, 1); /* the last line has no newline */
    scene_free(&s);
}
END_TEST

START_TEST(a_byte_order_mark_at_the_start_is_skipped)
{
    /* Without the skip the first keyword read "???camera" */
    scene_t s;
    parse_ok(&s, "\xEF\xBB\xBF" "camera width 8\n" M
                 "sphere centre 0 0 0 radius 1 material m\n");
    ck_assert_int_eq(s.camera.width, 8);
    ck_assert_int_eq(s.nobjects, 1);
    scene_free(&s);
    /* the first line's columns count from the byte after it */
    parse_err("\xEF\xBB\xBF" "camera width 0\n", SVET_ERR_RANGE,
              "t.scn:1:14: 'width' = 0 is out of range: expected 1 to 16384");
    /* anywhere else it is no blank */
    parse_err(M "\xEF\xBB\xBF" "sphere centre 0 0 0 radius 1 material m\n",
              SVET_ERR_PARSE, "t.scn:2:1: unknown keyword '???sphere': "
              "expected one of " KEYWORDS);
}
END_TEST

START_TEST(a_file_without_statements_is_an_error)
{
    static const char *const empty[] = { "", "\n\n", "# only a comment\n",
                                         "  \t\r\n# two\n\n",
                                         "\xEF\xBB\xBF\n" };
    for (size_t i = 0; i < sizeof empty / sizeof *empty; i++)
        parse_err(empty[i], SVET_ERR_PARSE,
                  "t.scn: no statements (the file is empty or only "
                  "comments): a scene needs at least an object");
}
END_TEST

START_TEST(a_scene_without_light_parses_with_a_warning)
{
    static const char *const dark =
        "t.scn: warning: nothing emits light (no 'light', 'emit', "
        "'environment' or emitting medium above black): the image will be "
        "black";
    scene_t s;
    parse_ok(&s, M "sphere centre 0 0 0 radius 1 material m\n");
    ck_assert_int_eq(s.nobjects, 1);
    ck_assert_int_eq(s.warnings.n, 1);
    ck_assert_str_eq(s.warnings.msg[0], dark);
    scene_free(&s);
    /* black emitters give no light either */
    parse_ok(&s, M "sphere centre 0 0 0 radius 1 material m emit 0\n"
                   "light point position 0 2 0 intensity 0\n"
                   "environment radiance 0\n");
    ck_assert_int_eq(s.warnings.n, 1);
    ck_assert_str_eq(s.warnings.msg[0], dark);
    scene_free(&s);
    /* each kind of light is enough; ambient occlusion needs none */
    static const char *const lit[] = {
        M "sphere centre 0 0 0 radius 1 material m emit 0 0 1\n",
        M "sphere centre 0 0 0 radius 1 material m\n"
          "light point position 0 2 0 intensity 1\n",
        M "sphere centre 0 0 0 radius 1 material m\n"
          "environment radiance 0.5\n",
        M "sphere centre 0 0 0 radius 1 material m\nrender integrator ao\n",
    };
    for (size_t i = 0; i < sizeof lit / sizeof *lit; i++) {
        parse_ok(&s, lit[i]);
        ck_assert_msg(s.warnings.n == 0, "%s: %s", lit[i], s.warnings.msg[0]);
        scene_free(&s);
    }
}
END_TEST

START_TEST(numbers_in_every_decimal_form_are_read)
{
    static const struct {
        const char *text;
        double value;
    } cases[] = {
        { "1", 1 },       { "-2", -2 },     { "+3", 3 },   { "0.5", 0.5 },
        { ".25", 0.25 },  { "3.", 3 },      { "1e-3", 1e-3 },
        { "2.5E+2", 250 }, { "-0", 0 },     { "1e-50", 1e-50 },
    };
    int n = (int)(sizeof cases / sizeof *cases);
    for (int i = 0; i < n; i++) {
        scene_t s;
        char line[64];
        snprintf(line, sizeof line, "camera position %s 0 0\n",
                 cases[i].text);
        parse_ok(&s, line);
        ck_assert_near(s.camera.position[X], (real)cases[i].value, 0);
        scene_free(&s);
    }
    test_report_cases("numbers_in_every_decimal_form_are_read", n);
}
END_TEST

/* --- materials ----------------------------------------------------------- */

START_TEST(every_material_component_parses_with_its_parameters)
{
    scene_t s;
    parse_ok(&s,
             "material a lambert rho 0.1 0.2 0.3\n"
             "material b mirror rho 0.9 eta 1.33\n"
             "material c phong rho 0.4 e 50\n"
             "material d ward rho 0.3 alpha 0.15\n"
             "material e ward rho 0.6 alpha_x 0.05 alpha_y 0.3 bounded\n"
             "material f transmission rho 0.8 eta 1.5\n"
             "material g diffuse_transmission rho 0.4\n"
             "material h glass eta 1.5 tint 1 0.5 0.25\n"
             "material i lambert rho 0.4 0.25 0.1 + phong rho 0.2 e 30 + "
             "mirror rho 0.04 eta 1.5\n"
             "material j phong rho 0.5\n");
    ck_assert_int_eq(s.nmaterials, 10);
    const material_params *p;
    p = &scene_find_material(&s, "a")->params;
    ck_assert_near(p->rho_d.r, REAL_C(0.1), 0);
    ck_assert_near(p->rho_d.b, REAL_C(0.3), 0);
    p = &scene_find_material(&s, "b")->params;
    ck_assert_near(p->rho_s.g, REAL_C(0.9), 0);
    ck_assert_near(p->eta, REAL_C(1.33), 0);
    p = &scene_find_material(&s, "c")->params;
    ck_assert_int_eq(p->gloss, MATERIAL_GLOSS_PHONG);
    ck_assert_near(p->rho_g.r, REAL_C(0.4), 0);
    ck_assert_near(p->e, 50, 0);
    p = &scene_find_material(&s, "d")->params;
    ck_assert_int_eq(p->gloss, MATERIAL_GLOSS_WARD);
    ck_assert_near(p->alpha_x, REAL_C(0.15), 0);
    ck_assert_near(p->alpha_y, REAL_C(0.15), 0);
    p = &scene_find_material(&s, "e")->params;
    ck_assert_int_eq(p->gloss, MATERIAL_GLOSS_WARD_BOUNDED);
    ck_assert_near(p->alpha_x, REAL_C(0.05), 0);
    ck_assert_near(p->alpha_y, REAL_C(0.3), 0);
    p = &scene_find_material(&s, "f")->params;
    ck_assert_near(p->rho_t.r, REAL_C(0.8), 0);
    ck_assert_near(p->eta, REAL_C(1.5), 0);
    p = &scene_find_material(&s, "g")->params;
    ck_assert_near(p->rho_dt.r, REAL_C(0.4), 0);
    /* glass eta 1.5: R0 = (0.5 / 2.5)^2 = 0.04, rho_t = 0.96 tint. */
    p = &scene_find_material(&s, "h")->params;
    ck_assert_near(p->rho_s.r, 0.04, 4 * REAL_EPSILON);
    ck_assert_near(p->rho_t.r, 0.96, 4 * REAL_EPSILON);
    ck_assert_near(p->rho_t.g, 0.48, 4 * REAL_EPSILON);
    ck_assert_near(p->rho_t.b, 0.24, 4 * REAL_EPSILON);
    ck_assert_near(p->eta, REAL_C(1.5), 0);
    const material_t *mi = scene_find_material(&s, "i");
    ck_assert_int_eq(mi->ncomp, 3);
    ck_assert_near(mi->params.rho_d.g, REAL_C(0.25), 0);
    ck_assert_near(mi->params.rho_g.r, REAL_C(0.2), 0);
    ck_assert_near(mi->params.rho_s.r, REAL_C(0.04), 0);
    ck_assert_near(mi->params.e, 30, 0);
    /* Phong without e takes material.h's default, 10. */
    ck_assert_near(scene_find_material(&s, "j")->params.e, 10, 0);
    scene_free(&s);
}
END_TEST

/* --- objects ------------------------------------------------------------- */

START_TEST(every_shape_parses_with_its_material_and_name)
{
    scene_t s;
    parse_ok(&s, M
             "sphere centre 0 0 0 radius 1 material m\n"
             "plane point 0 -1 0 normal 0 1 0 material m\n"
             "disk centre 0 1 0 normal 0 -1 0 radius 0.25 material m\n"
             "parallelogram c0 -1 -1 1 c1 1 -1 1 c2 1 -1 -1 c3 -1 -1 -1 "
             "material m\n"
             "parallelogram c0 -1 -1 1 c1 1 -1 1 c3 -1 -1 -1 material m\n"
             "triangle p0 0 0 0 p1 1 0 0 p2 0 1 0 material m\n"
             "box min -1 -1 -1 max 1 1 1 material m\n"
             "cylinder base 0 -1 0 top 0 1 0 radius 0.5 material m\n"
             "cylinder base 0 -1 0 top 0 1 0 radius 0.5 open material m\n"
             "cone base 0 -1 0 apex 0 1 0 radius 0.5 material m\n"
             "cone base 0 -1 0 apex 0 1 0 radius 0.5 open material m\n");
    static const char *const names[] = {
        "sphere", "plane", "disk", "parallelogram", "parallelogram",
        "triangle", "box", "cylinder", "cylinder", "cone", "cone"
    };
    ck_assert_int_eq(s.nobjects, 11);
    const material_t *m = scene_find_material(&s, "m");
    for (int i = 0; i < 11; i++) {
        ck_assert_str_eq(s.objects[i]->ops->name, names[i]);
        ck_assert_ptr_eq(s.objects[i]->material, m);
        ck_assert_int_eq(s.objects[i]->id, i);
        ck_assert_ptr_null(s.objects[i]->light);
    }
    /* Open and capped differ by the area of the caps: a cylinder of
     * radius 0.5 and height 2 has 2 pi r h = 2 pi lateral, + 2 pi r^2 =
     * pi / 2 capped. */
    real a_capped = s.objects[7]->ops->area(s.objects[7]);
    real a_open = s.objects[8]->ops->area(s.objects[8]);
    ck_assert_near(a_open, 2 * REAL_PI, 1e-5);
    ck_assert_near(a_capped - a_open, REAL_PI / 2, 1e-5);
    scene_free(&s);
}
END_TEST

START_TEST(emission_is_front_only_unless_twosided)
{
    scene_t s;
    parse_ok(&s, M "disk centre 0 1 0 normal 0 -1 0 radius 0.5 material m "
                   "emit 1 2 3\n"
                   "sphere centre 0 0 0 radius 1 material m emit 5 "
                   "twosided\n"
                   "sphere centre 0 3 0 radius 1 material m\n");
    ck_assert_int_eq(s.nemitters, 2);
    ck_assert_ptr_eq(s.objects[0]->light, s.emitters[0]);
    ck_assert_ptr_eq(s.emitters[0]->obj, s.objects[0]);
    ck_assert(!s.emitters[0]->two_sided);
    ck_assert_near(s.emitters[0]->radiance.r, 1, 0);
    ck_assert_near(s.emitters[0]->radiance.b, 3, 0);
    ck_assert(s.emitters[1]->two_sided);
    ck_assert_near(s.emitters[1]->radiance.g, 5, 0);
    ck_assert_ptr_null(s.objects[2]->light);
    scene_free(&s);
}
END_TEST

START_TEST(parallelogram_normal_follows_the_corner_order)
{
    scene_t s;
    /* (c1 - c0) x (c3 - c0) = (2,0,0) x (0,0,-2) = (0,4,0): up. The
     * reverse order gives down. */
    parse_ok(&s, M "parallelogram c0 -1 0 1 c1 1 0 1 c3 -1 0 -1 material m\n"
                   "parallelogram c0 -1 0 1 c1 -1 0 -1 c3 1 0 1 material m\n"
                   "triangle p0 0 0 0 p1 1 0 0 p2 0 1 0 material m\n");
    VECTOR3 n;
    normal_at_centre(s.objects[0], n);
    ck_assert_near(n[Y], 1, 1e-6);
    normal_at_centre(s.objects[1], n);
    ck_assert_near(n[Y], -1, 1e-6);
    normal_at_centre(s.objects[2], n);
    ck_assert_near(n[Z], 1, 1e-6);
    scene_free(&s);
}
END_TEST

START_TEST(transforms_apply_in_the_written_order)
{
    scene_t s;
    /* A triangle's corners are moved directly. rotate y 90 takes +z to
     * +x (counter-clockwise seen from +y); then translate by 5 in x:
     * (0,0,1) -> (1,0,0) -> (6,0,0). In the other order: (5,0,1) ->
     * (1,0,-5). */
    parse_ok(&s, M "triangle p0 0 0 1 p1 0 1 1 p2 0 0 2 material m "
                   "rotate y 90 translate 5 0 0\n"
                   "triangle p0 0 0 1 p1 0 1 1 p2 0 0 2 material m "
                   "translate 5 0 0 rotate y 90\n"
                   "triangle p0 1 0 0 p1 0 1 0 p2 0 0 1 material m "
                   "scale 2 3 4\n"
                   "triangle p0 1 0 0 p1 0 1 0 p2 0 0 1 material m "
                   "rotate 0 0 2 90 scale 2\n");
    bbox_t b;
    bounds_of(s.objects[0], &b);
    ck_assert_near(b.min[X], 6, 1e-5);
    ck_assert_near(b.max[X], 7, 1e-5);
    ck_assert_near(b.min[Z], 0, 1e-5);
    ck_assert_near(b.max[Z], 0, 1e-5);
    bounds_of(s.objects[1], &b);
    ck_assert_near(b.min[X], 1, 1e-5);
    ck_assert_near(b.max[X], 2, 1e-5);
    ck_assert_near(b.min[Z], -5, 1e-5);
    bounds_of(s.objects[2], &b);
    ck_assert_near(b.max[X], 2, 1e-5);
    ck_assert_near(b.max[Y], 3, 1e-5);
    ck_assert_near(b.max[Z], 4, 1e-5);
    /* rotate about (0,0,2), i.e. z, by 90: x -> y, y -> -x; then x2. */
    bounds_of(s.objects[3], &b);
    ck_assert_near(b.min[X], -2, 1e-5);
    ck_assert_near(b.max[Y], 2, 1e-5);
    ck_assert_near(b.max[Z], 2, 1e-5);
    scene_free(&s);
}
END_TEST

START_TEST(cornell_box_boxes_land_where_the_reference_scene_puts_them)
{
    scene_t s;
    svet_error err;
    ck_assert_msg(read_scene(&s, "scenes/cbox.scn", &err) == SVET_OK,
                  "%s", err.msg);
    ck_assert_int_eq(s.nobjects, 8);
    /* The small box: [-1,1]^3 x 0.3, rotated -17 degrees about y, moved
     * to (0.335, -0.7, 0.38). Its x extent is 0.3 (cos 17 + sin 17) about
     * the centre, its y extent 0.3, exactly: the bounds of a rotated box
     * may be loose but must hold these. */
    bbox_t b;
    bounds_of(s.objects[6], &b);
    double a17 = 17 * PI_D / 180;
    double hx = 0.3 * (cos(a17) + sin(a17));
    assert_between(b.min[X], 0.335 - hx - 0.05, 0.335 - hx + 1e-5);
    assert_between(b.max[X], 0.335 + hx - 1e-5, 0.335 + hx + 0.05);
    assert_between(b.min[Y], -1.0 - 0.05, -1.0 + 1e-5);
    assert_between(b.max[Y], -0.4 - 1e-5, -0.4 + 0.05);
    /* The large box: scaled (0.3, 0.61, 0.3): y from -1.01 to 0.21. */
    bounds_of(s.objects[7], &b);
    assert_between(b.min[Y], -1.01 - 0.05, -1.01 + 1e-5);
    assert_between(b.max[Y], 0.21 - 1e-5, 0.21 + 0.05);
    scene_free(&s);
}
END_TEST

START_TEST(cornell_box_matches_the_reference_numbers)
{
    scene_t s;
    svet_error err;
    ck_assert_msg(read_scene(&s, "scenes/cbox.scn", &err) == SVET_OK,
                  "%s", err.msg);
    ck_assert_near(s.camera.position[Z], REAL_C(3.9), 0);
    ck_assert_near(s.camera.fov, REAL_C(39.3077), 0);
    ck_assert_int_eq(s.camera.width, 256);
    ck_assert_int_eq(s.camera.height, 256);
    ck_assert_int_eq(s.camera.filter, SCENE_FILTER_BOX);
    ck_assert_int_eq(s.render.max_depth, 7);
    const material_t *white = scene_find_material(&s, "white");
    ck_assert_near(white->params.rho_d.r, REAL_C(0.885809), 0);
    ck_assert_near(scene_find_material(&s, "green")->params.rho_d.g,
                   REAL_C(0.37798), 0);
    ck_assert_near(scene_find_material(&s, "red")->params.rho_d.r,
                   REAL_C(0.570068), 0);
    /* The five walls face into the box: the normal at a wall's centre
     * points toward the box's centre, the origin. */
    for (int i = 0; i < 5; i++) {
        cobject_sample_t smp;
        real u[2] = { REAL_C(0.5), REAL_C(0.5) };
        s.objects[i]->ops->sample(s.objects[i], u, &smp);
        ck_assert_msg(SVECTOR3(smp.n, smp.p) < 0, "wall %d faces out", i);
    }
    /* The light: faces -y, one-sided, the given radiance, white. */
    ck_assert_int_eq(s.nemitters, 1);
    const scene_emission_t *e = s.emitters[0];
    ck_assert_ptr_eq(e->obj, s.objects[5]);
    ck_assert(!e->two_sided);
    ck_assert_near(e->radiance.r, REAL_C(18.387), 0);
    ck_assert_near(e->radiance.g, REAL_C(13.9873), 0);
    ck_assert_near(e->radiance.b, REAL_C(6.75357), 0);
    ck_assert_ptr_eq(s.objects[5]->material, white);
    VECTOR3 n;
    normal_at_centre(s.objects[5], n);
    ck_assert_near(n[Y], -1, 1e-6);
    scene_free(&s);
}
END_TEST

/* --- lights -------------------------------------------------------------- */

START_TEST(point_lights_in_every_unit)
{
    scene_t s;
    parse_ok(&s, "light point position 1 2 3 intensity 0.5 1 2\n"
                 "light point position 0 0 0 power 100\n"
                 "light point position 0 0 0 candela 683 colour 1 1 1\n"
                 "light point position 0 0 0 lumens 1700\n"
                 "light point position 0 0 0 candela 100 colour 1 0.5 0\n");
    ck_assert_int_eq(s.npoint_lights, 5);
    const scene_point_light_t *l = s.point_lights;
    ck_assert_near(l[0].position[Y], 2, 0);
    ck_assert_near(l[0].intensity.b, 2, 0);
    /* Phi = 4 pi I. */
    ck_assert_rel(l[1].intensity.g, 100 / (4 * PI_D), 1e-6, 0);
    /* eq. (1.2): 683 cd of white is luminance 1 W/sr, and white (1,1,1)
     * has luminance 1 (colour_luminance: the Y row of the sRGB matrix). */
    ck_assert_rel(colour_luminance(l[2].intensity), 1, 1e-5, 0);
    ck_assert_rel(l[2].intensity.r, l[2].intensity.b, 1e-5, 0);
    /* 1700 lm over 4 pi sr, / 683. */
    ck_assert_rel(colour_luminance(l[3].intensity), 1700 / (4 * PI_D) / 683,
                  1e-5, 0);
    /* The colour sets the chromaticity only. */
    ck_assert_rel(colour_luminance(l[4].intensity), 100.0 / 683, 1e-5, 0);
    ck_assert_rel(l[4].intensity.g / l[4].intensity.r, 0.5, 1e-5, 0);
    ck_assert_near(l[4].intensity.b, 0, 1e-9);
    scene_free(&s);
}
END_TEST

START_TEST(environment_is_read_once)
{
    scene_t s;
    parse_ok(&s, "environment radiance 1\n");
    ck_assert(s.has_environment);
    ck_assert_near(s.environment.g, 1, 0);
    scene_free(&s);
    parse_err("environment radiance 1\nenvironment radiance 2\n",
              SVET_ERR_PARSE,
              "t.scn:2:1: the environment is already defined on line 1");
}
END_TEST

/* --- meshes -------------------------------------------------------------- */

START_TEST(mesh_usemtl_names_map_to_scene_materials)
{
    scene_t s;
    parse_ok(&s, "material red lambert rho 0.8 0.1 0.1\n"
                 "material blue lambert rho 0.1 0.1 0.8\n"
                 "material grey lambert rho 0.5\n"
                 "mesh file tri.obj material grey\n");
    ck_assert_int_eq(s.nobjects, 2);
    ck_assert_ptr_eq(s.objects[0]->material, scene_find_material(&s, "red"));
    ck_assert_ptr_eq(s.objects[1]->material,
                     scene_find_material(&s, "blue"));
    ck_assert_int_eq(s.objects[0]->nprims, 1);
    scene_free(&s);
    /* Names the scene does not define take the default... */
    parse_ok(&s, "material red lambert rho 0.8 0.1 0.1\n"
                 "material grey lambert rho 0.5\n"
                 "mesh file tri.obj material grey\n");
    ck_assert_int_eq(s.nobjects, 2);
    ck_assert_ptr_eq(s.objects[1]->material,
                     scene_find_material(&s, "grey"));
    scene_free(&s);
    /* ...unless strict, and there must be a default when one is needed. */
    parse_err("material red lambert rho 0.8 0.1 0.1\n"
              "material blu lambert rho 0.5\n"
              "mesh file tri.obj material red strict\n",
              SVET_ERR_PARSE,
              "t.scn:3:11: tri.obj: usemtl 'blue' is not a material of the "
              "scene (did you mean 'blu'?)");
    parse_err("material red lambert rho 0.8 0.1 0.1\n"
              "mesh file tri.obj\n",
              SVET_ERR_PARSE,
              "t.scn:2:1: tri.obj: usemtl 'blue' is not a material of the "
              "scene: give the mesh a default 'material'");
}
END_TEST

START_TEST(a_mesh_without_usemtl_is_one_object_and_may_emit)
{
    scene_t s;
    parse_ok(&s, M "mesh file quad.obj material m emit 2 twosided\n");
    ck_assert_int_eq(s.nobjects, 1);
    ck_assert_int_eq(s.objects[0]->nprims, 2);
    ck_assert_ptr_eq(s.objects[0]->material, scene_find_material(&s, "m"));
    ck_assert_int_eq(s.nemitters, 1);
    ck_assert(s.emitters[0]->two_sided);
    ck_assert_near(s.emitters[0]->radiance.r, 2, 0);
    scene_free(&s);
    parse_err("mesh file quad.obj\n", SVET_ERR_PARSE,
              "t.scn:1:1: quad.obj: faces without usemtl need a default "
              "'material'");
}
END_TEST

START_TEST(mesh_transforms_move_vertices_and_keep_normals_out)
{
    scene_t s;
    parse_ok(&s, "material red lambert rho 0.8 0.1 0.1\n"
                 "mesh file tri.obj material red scale 2 translate 0 0 1\n"
                 "mesh file tri.obj material red scale -1 1 1\n");
    ck_assert_int_eq(s.nobjects, 4);
    bbox_t b;
    bounds_of(s.objects[0], &b);
    ck_assert_near(b.min[Z], 1, 1e-6);
    ck_assert_near(b.max[X], 2, 1e-6);
    /* tri.obj faces +z (counter-clockwise seen from +z); a mirror in x
     * keeps it facing +z: the winding is reversed with the vertices. */
    for (int i = 0; i < 4; i++) {
        VECTOR3 n;
        normal_at_centre(s.objects[i], n);
        ck_assert_msg(n[Z] > REAL_C(0.999), "part %d: n.z = %g", i,
                      (double)n[Z]);
    }
    bounds_of(s.objects[2], &b);
    ck_assert_near(b.min[X], -1, 1e-6);
    ck_assert_near(b.max[X], 0, 1e-6);
    const mesh_t *mm = mesh_get(s.objects[2]);
    ck_assert_ptr_nonnull(mm);
    ck_assert_ptr_nonnull(mm->n);
    ck_assert_near(mm->n[0][Z], 1, 1e-6);
    scene_free(&s);
}
END_TEST

START_TEST(mesh_errors_name_both_files)
{
    parse_err(M "mesh file missing.obj material m\n", SVET_ERR_IO,
              "t.scn:2:11: tests/data/scene/missing.obj: cannot open: No "
              "such file or directory");
    parse_err(M "mesh file . material m\n", SVET_ERR_IO,
              "t.scn:2:11: tests/data/scene/.: not a regular file");
    parse_err(M "mesh file bad.obj material m\n", SVET_ERR_RANGE,
              "t.scn:2:11: tests/data/scene/bad.obj:5:7: vertex index 9 out "
              "of range: 3 defined so far");
}
END_TEST

START_TEST(mesh_warnings_reach_the_scene_and_strict_refuses_them)
{
    scene_t s;
    parse_ok(&s, M "mesh file warn.obj material m\n"
                   "light point position 0 0 1 intensity 1\n");
    ck_assert_int_eq(s.nobjects, 1);
    /* after the scene's file:line:col, the OBJ file's; all 11 counted */
    ck_assert_int_eq(s.warnings.n, 11);
    ck_assert_str_eq(s.warnings.msg[0],
                     "t.scn:2:11: tests/data/scene/warn.obj:4:1: warning: "
                     "unknown statement 'vv' skipped");
    ck_assert_str_eq(s.warnings.msg[2],
                     "t.scn:2:11: tests/data/scene/warn.obj:9:1: warning: "
                     "'l' skipped: lines and points have no surface");
    scene_free(&s);
    ck_assert_int_eq(s.warnings.n, 0);
    /* 'strict' makes the first an error */
    parse_err(M "mesh file warn.obj material m strict\n", SVET_ERR_PARSE,
              "t.scn:2:11: tests/data/scene/warn.obj:4:1: unknown statement "
              "'vv' skipped ('strict': the mesh file must have nothing to "
              "skip)");
    /* a clean file warns about nothing, strict or not */
    parse_ok(&s, "material red lambert rho 0.5\n"
                 "material blue lambert rho 0.5\n"
                 "mesh file tri.obj strict\n"
                 "light point position 0 0 1 intensity 1\n");
    ck_assert_int_eq(s.warnings.n, 0);
    scene_free(&s);
}
END_TEST

START_TEST(lights_whose_products_overflow_are_refused)
{
    /* emit 3e38 rendered with non-finite samples dropped and exit 0 */
    static const char *const bright =
        " is brighter than svet renders: at most 1.84e+19 per channel (a "
        "sample's square must fit in a float image)";
    char msg[512];
    snprintf(msg, sizeof msg, "t.scn:2:41: the radiance 'emit' 3e+38%s",
             bright);
    parse_err(M "sphere centre 0 0 0 radius 1 material m emit 3e38\n",
              SVET_ERR_RANGE, msg);
    snprintf(msg, sizeof msg, "t.scn:1:28: the intensity 1e+20%s", bright);
    parse_err("light point position 0 0 0 intensity 1 1e20 1\n",
              SVET_ERR_RANGE, msg);
    /* power 1e21 W is an intensity of 1e21 / (4 pi) = 7.96e19 W/sr */
    snprintf(msg, sizeof msg, "t.scn:1:28: the intensity 7.96e+19%s", bright);
    parse_err("light point position 0 0 0 power 1e21\n", SVET_ERR_RANGE, msg);
    snprintf(msg, sizeof msg, "t.scn:1:13: the radiance 1e+20%s", bright);
    parse_err("environment radiance 1e20\n", SVET_ERR_RANGE, msg);
    /* as bright as may be: fine */
    scene_t s;
    parse_ok(&s, M "sphere centre 0 0 0 radius 1 material m emit 1.8e19\n"
                   "light point position 0 2 0 intensity 1.8e19\n"
                   "environment radiance 1.8e19\n");
    ck_assert_int_eq(s.nemitters, 1);
    scene_free(&s);
#ifndef SVET_DOUBLE
    /* a light's power, pi A L per side, beyond float: a sphere of radius
     * 1e18 has A = 1.26e37 */
    parse_err(M "sphere centre 0 0 0 radius 1e18 material m emit 1000\n",
              SVET_ERR_RANGE, "t.scn:2:44: the light's power, 3.95e+40 W, "
              "is more than float holds");
    /* each fits, their sum does not */
    parse_err(M "sphere centre 0 0 0 radius 1e18 material m emit 5\n"
                "sphere centre 0 0 0 radius 1e18 material m emit 5\n",
              SVET_ERR_RANGE, "t.scn:3:44: the lights' powers add up to "
              "3.95e+38 W, more than float holds");
    /* the environment's, pi^2 r^2 L, with r around every object: told on
     * its own line, though the sphere comes after it */
    parse_err(M "environment radiance 1e4\n"
                "sphere centre 0 0 0 radius 1e17 material m\n",
              SVET_ERR_RANGE, "t.scn:2:13: the light's power, 2.96e+39 W, "
              "is more than float holds");
#else
    parse_ok(&s, M "sphere centre 0 0 0 radius 1e18 material m emit 1000\n"
                   "environment radiance 1e4\n");
    scene_free(&s);
#endif
}
END_TEST

/* --- sizes beyond what real resolves ------------------------------------ */

/* scenes/cbox.scn scaled by s about the origin, camera included, at 32 x 32
 * pixels and 4 spp: "scale s" after each object's own transforms. The
 * text is malloc'ed. */
static char *scaled_cbox(double s)
{
    FILE *f = fopen("scenes/cbox.scn", "r");
    ck_assert_ptr_nonnull(f);
    size_t cap = 1 << 16, n = 0;
    char *text = malloc(cap), line[512];
    ck_assert_ptr_nonnull(text);
    while (fgets(line, sizeof line, f)) {
        char *m = strstr(line, "material ");
        char out[640];
        if (strncmp(line, "camera position", 15) == 0)
            snprintf(out, sizeof out, "camera position 0 0 %.9g target 0 0 "
                     "0 up 0 1 0 width 32 height 32\n", 3.9 * s);
        else if (strncmp(line, "render spp", 10) == 0)
            snprintf(out, sizeof out, "render spp 4 maxdepth 7\n");
        else if (m && (strncmp(line, "parallelogram", 13) == 0 ||
                       strncmp(line, "box", 3) == 0))
            snprintf(out, sizeof out, "%.*sscale %.9g %s", (int)(m - line),
                     line, s, m);
        else
            snprintf(out, sizeof out, "%s", line);
        size_t k = strlen(out);
        ck_assert(n + k + 1 < cap);
        memcpy(text + n, out, k + 1);
        n += k;
    }
    fclose(f);
    return text;
}

/* The largest difference of the render of text from ref (NULL: keep
 * this render in ref instead), 1 thread; warnings in *nwarnings. */
static double render_difference(const char *text, image_t *ref,
                                long *nwarnings)
{
    scene_t s;
    parse_ok(&s, text);
    *nwarnings = s.warnings.n;
    render_t r;
    svet_error err;
    ck_assert_msg(render_init(&r, &s, &err) == SVET_OK, "%s", err.msg);
    render_pass(&r, s.render.spp, 1, NULL, NULL);
    image_t img;
    ck_assert_int_eq(render_image(&r, &img, &err), SVET_OK);
    render_free(&r);
    scene_free(&s);
    double worst = 0;
    if (ref->px) {
        size_t n = (size_t)img.width * (size_t)img.height * 3;
        for (size_t i = 0; i < n; i++) {
            double d = fabs((double)img.px[i] - (double)ref->px[i]);
            if (!(d <= worst)) /* a NaN counts as infinitely wrong */
                worst = isnan(d) ? (double)INFINITY : d;
        }
        image_free(&img);
    } else {
        *ref = img;
    }
    return worst;
}

START_TEST(scaled_cornell_boxes_warn_where_float_renders_them_wrong)
{
    /* The box scaled by s renders as the unscaled one (to rounding, a
     * largest difference near 1e-5) while s^3 times its sizes stays in
     * real's normal range; beyond, float's hits are lost (at 5e12) or
     * lose digits (at 1e-14), by 0.02 to 0.6. The warning must come
     * exactly where the image is wrong, at these scales. */
    static const double scales[] = { 1e-30, 1e-14, 1e-12, 1e12, 5e12, 1e30 };
    image_t ref = { 0 };
    long nw;
    char *text = scaled_cbox(1);
    render_difference(text, &ref, &nw);
    free(text);
    ck_assert_int_eq(nw, 0);
    for (size_t i = 0; i < sizeof scales / sizeof *scales; i++) {
#ifndef SVET_DOUBLE
        if (scales[i] < 1e-20 || scales[i] > 1e20)
            continue; /* float refuses their areas outright */
#endif
        text = scaled_cbox(scales[i]);
        double d = render_difference(text, &ref, &nw);
        free(text);
        bool wrong = !(d < 1e-3);
        ck_assert_msg(wrong == (nw > 0) && (wrong || d < 1e-4),
                      "scale %g: largest difference %g, %ld warnings",
                      scales[i], d, nw);
#ifdef SVET_DOUBLE
        ck_assert_msg(!wrong, "scale %g: %g", scales[i], d);
#else
        ck_assert_msg(wrong == (scales[i] < 1e-13 || scales[i] > 2e12),
                      "scale %g: %g", scales[i], d);
#endif
    }
    image_free(&ref);
}
END_TEST

/* The Cornell box scaled by s parses with the one warning msg in float
 * and none in double. */
static void expect_precision_warning(double s, const char *msg)
{
    scene_t sc;
    char *text = scaled_cbox(s);
    parse_ok(&sc, text);
    free(text);
#ifdef SVET_DOUBLE
    (void)msg;
    ck_assert_int_eq(sc.warnings.n, 0);
#else
    ck_assert_int_eq(sc.warnings.n, 1);
    ck_assert_str_eq(sc.warnings.msg[0], msg);
#endif
    scene_free(&sc);
}

START_TEST(precision_warnings_name_the_extent_and_the_smallest_object)
{
    expect_precision_warning(5e12,
                     "t.scn: warning: the scene spans 2.83e+13, more than "
                     "float resolves (lengths up to 6.98e+12: the flat "
                     "shapes' intersection multiplies three lengths); render "
                     "it with the double build (make REAL=double)");
    /* the smallest object is named by its line: the light, 0.6 s across */
    expect_precision_warning(1e-14,
                     "t.scn:34:1: warning: the object is 5.97e-15 across, "
                     "less than float resolves (lengths down to 2.27e-13: "
                     "the flat shapes' intersection multiplies three "
                     "lengths); render it with the double build (make "
                     "REAL=double)");
    scene_t s;
    /* a plane has no size: far planes alone warn of nothing */
    parse_ok(&s, M "plane point 0 -1e30 0 normal 0 1 0 material m\n"
                   "light point position 0 1 0 intensity 1\n");
    ck_assert_int_eq(s.warnings.n, 0);
    scene_free(&s);
}
END_TEST

/* --- errors -------------------------------------------------------------- */

#ifdef SVET_DOUBLE
#define BIG "1e300"
#else
#define BIG "1e+30" /* as long as the double one: same columns */
#endif

/* A coordinate of which twice overflows real. */
#ifdef SVET_DOUBLE
#define HUGE_COORD "1e308"
#else
#define HUGE_COORD "3e38"
#endif

/* Every kind of error, with its exact message and status. */
static const struct {
    const char *text;
    svet_status status;
    const char *msg;
} errors[] = {
    /* unknown words, with and without a suggestion */
    { "sphear centre 0 0 0 radius 1\n", SVET_ERR_PARSE,
      "t.scn:1:1: unknown keyword 'sphear' (did you mean 'sphere'?)" },
    { "\n  teapot\n", SVET_ERR_PARSE,
      "t.scn:2:3: unknown keyword 'teapot': expected one of " KEYWORDS },
    { M "sphere centre 0 0 0 radus 1 material m\n", SVET_ERR_PARSE,
      "t.scn:2:21: unknown parameter of sphere 'radus' (did you mean "
      "'radius'?)" },
    { "render integrator pathh\n", SVET_ERR_PARSE,
      "t.scn:1:19: unknown value of 'integrator' 'pathh' (did you mean "
      "'path'?)" },
    { "material m lambrt rho 1\n", SVET_ERR_PARSE,
      "t.scn:1:12: unknown material component 'lambrt' (did you mean "
      "'lambert'?)" },
    { "light spot position 0 0 0 intensity 1\n", SVET_ERR_PARSE,
      "t.scn:1:7: unknown kind of light 'spot': expected one of point" },
    { "light pont position 0 0 0 intensity 1\n", SVET_ERR_PARSE,
      "t.scn:1:7: unknown kind of light 'pont' (did you mean 'point'?)" },
    /* undefined and duplicate materials */
    { "material white lambert rho 0.5\n"
      "sphere centre 0 0 0 radius 1 material whte\n", SVET_ERR_PARSE,
      "t.scn:2:39: undefined material 'whte' (did you mean 'white'?)" },
    { "sphere centre 0 0 0 radius 1 material glass\n", SVET_ERR_PARSE,
      "t.scn:1:39: undefined material 'glass': define it with a 'material' "
      "line above this one" },
    { M "material m lambert rho 0.1\n", SVET_ERR_PARSE,
      "t.scn:2:10: material 'm' is already defined" },
    { "material 9lives lambert rho 0.1\n", SVET_ERR_PARSE,
      "t.scn:1:10: '9lives' is not a material name: expected a letter or "
      "'_' then letters, digits, '_', '-' or '.' (at most 64)" },
    /* missing and extra values */
    { M "sphere centre 0 0 radius 1 material m\n", SVET_ERR_PARSE,
      "t.scn:2:19: 'centre' expects 3 numbers x y z: got 2 numbers, then "
      "'radius'" },
    { M "sphere centre 0 0 0 radius\n", SVET_ERR_PARSE,
      "t.scn:2:27: 'radius' expects a number, got the end of the line" },
    { M "sphere centre 0 0 0 radius 1 2 material m\n", SVET_ERR_PARSE,
      "t.scn:2:30: one value too many: 'radius' takes a number, then comes "
      "a key, not '2'" },
    { M "sphere 0 0 0 radius 1 material m\n", SVET_ERR_PARSE,
      "t.scn:2:8: expected a key of sphere before the value '0'" },
    { M "sphere centre 0 0 0 radius 1 material m wobble 3\n",
      SVET_ERR_PARSE,
      "t.scn:2:41: unknown parameter of sphere 'wobble': expected one of "
      "centre, radius, material, emit, twosided, scale, rotate, "
      "translate, bump, strength, medium, outside, invisible" },
    { M "sphere centre 0 0 0 material m\n", SVET_ERR_PARSE,
      "t.scn:2:1: sphere needs 'radius' (a number)" },
    { "sphere centre 0 0 0 radius 1\n", SVET_ERR_PARSE,
      "t.scn:1:1: sphere needs 'material' (the name of a material defined "
      "above)" },
    { M "sphere centre 0 0 0 radius 1 radius 2 material m\n",
      SVET_ERR_PARSE,
      "t.scn:2:30: 'radius' is given twice (first at column 21)" },
    { "material m lambert rho 0.5 0.5\n", SVET_ERR_PARSE,
      "t.scn:1:31: 'rho' expects 1 number (grey) or 3 (r g b): got 2 "
      "numbers, then the end of the line" },
    { "material m lambert\n", SVET_ERR_PARSE,
      "t.scn:1:12: component 'lambert' needs 'rho' (1 number (grey) or 3 "
      "(r g b))" },
    { "material m lambert rho 0.5 +\n", SVET_ERR_PARSE,
      "t.scn:1:28: expected a component after '+'" },
    { "material m\n", SVET_ERR_PARSE,
      "t.scn:1:11: material 'm' expects a component: lambert, mirror, "
      "phong, ward, transmission, diffuse_transmission or glass" },
    { "camera fov\n", SVET_ERR_PARSE,
      "t.scn:1:11: 'fov' expects a number, got the end of the line" },
    { "render roulette maybe\n", SVET_ERR_PARSE,
      "t.scn:1:17: 'roulette' expects on or off, got 'maybe'" },
    { "light point position 0 0 0\n", SVET_ERR_PARSE,
      "t.scn:1:1: light point needs exactly one of 'intensity' (W/sr), "
      "'power' (W), 'candela' or 'lumens'" },
    { "light point position 0 0 0 intensity 1 colour 1 0 0\n",
      SVET_ERR_PARSE,
      "t.scn:1:40: 'colour' goes with 'candela' or 'lumens' only "
      "(intensity and power take r g b themselves)" },
    /* not numbers, not finite, out of range */
    { "camera width abc\n", SVET_ERR_PARSE,
      "t.scn:1:14: expected a whole number for 'width', got 'abc'" },
    { "camera width 2.5\n", SVET_ERR_PARSE,
      "t.scn:1:14: expected a whole number for 'width', got '2.5'" },
    { "camera position 0 x 0\n", SVET_ERR_PARSE,
      "t.scn:1:19: 'position' expects 3 numbers x y z: got 1 number, then "
      "'x'" },
    { "camera position 0 0x1 0\n", SVET_ERR_PARSE,
      "t.scn:1:19: 'position' expects 3 numbers x y z: got 1 number, then "
      "'0x1'" },
    { M "sphere centre nan 0 0 radius 1 material m\n", SVET_ERR_RANGE,
      "t.scn:2:15: 'centre' must be a finite number, not 'nan'" },
    { M "sphere centre 0 0 0 radius -Infinity material m\n", SVET_ERR_RANGE,
      "t.scn:2:28: 'radius' must be a finite number, not '-Infinity'" },
    { M "sphere centre 0 0 0 radius 1e999 material m\n", SVET_ERR_RANGE,
      "t.scn:2:28: 'radius' = 1e999 is too large for " REAL_NAME },
    { M "sphere centre 0 0 0 radius -1 material m\n", SVET_ERR_RANGE,
      "t.scn:2:21: 'radius' must be > 0" },
    { M "sphere centre 0 0 0 radius 0 material m\n", SVET_ERR_RANGE,
      "t.scn:2:21: 'radius' must be > 0" },
    { "material m lambert rho -0.5\n", SVET_ERR_RANGE,
      "t.scn:1:20: 'rho' must not be negative" },
    { M "box min 0 0 0 max 1 1 1 scale 0 material m\n", SVET_ERR_RANGE,
      "t.scn:2:25: a scale factor of 0 flattens the object: expected "
      "nonzero factors" },
    { M "box min 0 0 0 max 1 1 1 rotate 0 0 0 45 material m\n",
      SVET_ERR_RANGE,
      "t.scn:2:25: a rotation axis must be a nonzero vector" },
    { M "sphere centre 0 0 0 radius 1 scale 1e30 scale 1e30 scale 1e30 "
      "scale 1e30 scale 1e30 scale 1e30 scale 1e30 scale 1e30 scale 1e30 "
      "scale 1e30 scale 1e30 material m\n",
      SVET_ERR_RANGE,
      "t.scn:2:30: the transforms do not make an invertible map in "
      REAL_NAME " (a factor too large or too small)" },
    { M "mesh file tri.obj scale 1e-30 scale 1e-30 scale 1e-30 "
      "scale 1e-30 scale 1e-30 scale 1e-30 scale 1e-30 scale 1e-30 "
      "scale 1e-30 scale 1e-30 scale 1e-30 material m\n",
      SVET_ERR_RANGE,
      "t.scn:2:19: the transforms do not make an invertible map in "
      REAL_NAME " (a factor too large or too small)" },
    { M "disk centre 0 0 0 normal 0 0 0 radius 1 material m\n",
      SVET_ERR_RANGE, "t.scn:2:19: 'normal' must be a nonzero vector" },
    { M "plane point 0 0 0 normal 0 1 0 material m emit 1\n",
      SVET_ERR_RANGE,
      "t.scn:2:43: a plane has no finite area, so it cannot emit: use a "
      "parallelogram or a disk" },
    { M "sphere centre 0 0 0 radius 1 material m twosided\n",
      SVET_ERR_PARSE,
      "t.scn:2:41: 'twosided' says an emitter emits on both sides: it "
      "needs 'emit'" },
    /* BIG is finite in real, BIG^2 is not. */
    { M "triangle p0 0 0 0 p1 " BIG " 0 0 p2 0 1 0 material m translate 1 0 0 "
      "scale " BIG "\n", SVET_ERR_RANGE,
      "t.scn:2:52: the transformed corners overflow " REAL_NAME },
    { M "triangle p0 0 0 0 p1 1 1 1 p2 2 2 2 material m\n", SVET_ERR_RANGE,
      "t.scn:2:1: the triangle has no area: its corners are (nearly) "
      "collinear" },
    { "camera fov 180\n", SVET_ERR_RANGE,
      "t.scn:1:8: 'fov' is the full angle in degrees: expected more than 0 "
      "and less than 180" },
    { "camera width 16385\n", SVET_ERR_RANGE,
      "t.scn:1:14: 'width' = 16385 is out of range: expected 1 to 16384" },
    { "camera width 0\n", SVET_ERR_RANGE,
      "t.scn:1:14: 'width' = 0 is out of range: expected 1 to 16384" },
    { "camera width 16384 height 16384\n", SVET_ERR_RANGE,
      "t.scn:1:20: 16384 x 16384 pixels is more than the limit of "
      "67108864" },
    { "render spp 16777217\n", SVET_ERR_RANGE,
      "t.scn:1:12: 'spp' = 16777217 is out of range: expected 1 to "
      "16777216" },
    { "render spp 99999999999999999999999\n", SVET_ERR_RANGE,
      "t.scn:1:12: 'spp' = 99999999999999999999999 is out of range: "
      "expected 1 to 16777216" },
    { "render spp -00000000000000000000000000000000000000000000005\n",
      SVET_ERR_RANGE,
      "t.scn:1:12: 'spp' = -000000000000000000000000000000000000000... is "
      "out of range: expected 1 to 16777216" },
    { "render maxdepth -1\n", SVET_ERR_RANGE,
      "t.scn:1:17: 'maxdepth' = -1 is out of range: expected 0 to 1024" },
    { "render seed 18446744073709551616\n", SVET_ERR_RANGE,
      "t.scn:1:13: 'seed' = 18446744073709551616 is out of range: expected "
      "0 to 18446744073709551615" },
    { "render seed -1\n", SVET_ERR_PARSE,
      "t.scn:1:13: expected a whole number >= 0 for 'seed', got '-1'" },
    { "tonemap bias 2\n", SVET_ERR_RANGE,
      "t.scn:1:9: 'bias' must lie in (0, 1]" },
    /* materials the materials module refuses */
    { "material m lambert rho 0.7 + mirror rho 0.5\n", SVET_ERR_RANGE,
      "t.scn:1:10: material 'm': rho_d + rho_s + rho_g + rho_t + rho_dt = "
      "1.2 in channel r: the surface would reflect and transmit more than "
      "it receives (the sum must be <= 1)" },
    { "material m lambert rho 0.1 + lambert rho 0.2\n", SVET_ERR_PARSE,
      "t.scn:1:30: the material already has this kind of component (at "
      "column 12): a mixed surface sums one of each" },
    { "material m phong rho 0.1 + ward rho 0.2\n", SVET_ERR_PARSE,
      "t.scn:1:28: the material already has this kind of component (at "
      "column 12): a mixed surface sums one of each" },
    { "material m mirror rho 0.1 eta 1.5 + transmission rho 0.5 eta 1.3\n",
      SVET_ERR_PARSE,
      "t.scn:1:37: the material has one index ratio eta, and column 12 "
      "already set it to 1.5" },
    { "material m ward rho 0.1 alpha 0.1 alpha_x 0.2 alpha_y 0.2\n",
      SVET_ERR_PARSE,
      "t.scn:1:25: give either 'alpha' (isotropic) or 'alpha_x' and "
      "'alpha_y' (anisotropic), not both" },
    { "material m ward rho 0.1 alpha_x 0.2\n", SVET_ERR_PARSE,
      "t.scn:1:25: an anisotropic Ward lobe needs both 'alpha_x' and "
      "'alpha_y'" },
    /* shapes the primitives refuse */
    { M "parallelogram c0 0 0 0 c1 1 0 0 c2 1 1 1 c3 0 1 0 material m\n",
      SVET_ERR_RANGE, NULL },
    { M "cylinder base 0 0 0 top 0 0 0 radius 1 material m\n",
      SVET_ERR_RANGE, NULL },
    /* lexical errors */
    { "output exr \"a.exr\n", SVET_ERR_PARSE,
      "t.scn:1:12: unterminated string: expected a closing '\"' on this "
      "line" },
    { "output exr \"a.exr\"x\n", SVET_ERR_PARSE,
      "t.scn:1:19: expected a blank after the closing '\"'" },
    { "output exr a\"b.exr\"\n", SVET_ERR_PARSE,
      "t.scn:1:13: expected a blank before the opening '\"'" },
    { "camera\x01 width 1\n", SVET_ERR_PARSE,
      "t.scn:1:7: unexpected control character 0x01" },
    { "output exr \"\"\n", SVET_ERR_PARSE,
      "t.scn:1:12: 'exr' expects a file name, got an empty string" },
    /* the whole scene */
    { "camera position 0 0 0 target 0 0 0\n", SVET_ERR_RANGE,
      "t.scn:1:1: camera target must differ from its position" },
    { "camera target 0 5 0\n\n", SVET_ERR_RANGE,
      "t.scn:1:1: camera up must not be along the view direction" },
    { "camera position -" HUGE_COORD " 0 0 target " HUGE_COORD " 0 0\n",
      SVET_ERR_RANGE, "t.scn:1:1: camera target - position overflows "
      REAL_NAME ": bring them closer" },
    /* later chapters */
    { "sky clear\n", SVET_ERR_UNSUPPORTED,
      "t.scn:1:1: 'sky' is not supported yet: ch. 12 (the atmosphere)" },
    { "include other.scn\n", SVET_ERR_UNSUPPORTED,
      "t.scn:1:1: 'include' is not supported yet: no chapter: one scene is "
      "one file" },
};

START_TEST(every_error_names_file_line_column_and_what_was_expected)
{
    int n = (int)(sizeof errors / sizeof *errors);
    for (int i = 0; i < n; i++) {
        if (errors[i].msg) {
            parse_err(errors[i].text, errors[i].status, errors[i].msg);
            continue;
        }
        /* The primitive's own message, after the statement's place. */
        scene_t s;
        svet_error err;
        ck_assert_int_eq(parse(&s, errors[i].text, &err), errors[i].status);
        ck_assert_msg(strncmp(err.msg, "t.scn:2:", 8) == 0, "%s", err.msg);
        scene_free(&s);
    }
    test_report_cases("every_error_names_file_line_column_and_what_was_"
                      "expected", n);
}
END_TEST

START_TEST(a_line_of_too_many_words_is_refused)
{
    /* 5000 numbers after a keyword: refused before they cost memory, at
     * the 4097th word, number 4096 at column 8 + 2 * 4095. */
    size_t n = 5000, len = 8 + 2 * n + 2;
    char *text = malloc(len);
    ck_assert_ptr_nonnull(text);
    memcpy(text, "camera ", 7);
    for (size_t i = 0; i < n; i++)
        memcpy(text + 7 + 2 * i, "1 ", 2);
    memcpy(text + 7 + 2 * n, "\n", 2);
    parse_err(text, SVET_ERR_RANGE,
              "t.scn:1:8198: more than 4096 words on one line");
    free(text);
}
END_TEST

START_TEST(a_nul_byte_is_an_error_not_the_end)
{
    static const char text[] = "camera width 8\n\0camera width 9\n";
    scene_t s;
    svet_error err;
    ck_assert_int_eq(scenefile_parse(&s, text, sizeof text - 1, "t.scn", NULL,
                                     &err),
                     SVET_ERR_PARSE);
    ck_assert_str_eq(err.msg, "t.scn:2:1: unexpected control character 0x00");
    scene_free(&s);
}
END_TEST

START_TEST(long_tokens_are_cut_and_unprintable_bytes_shown_as_question_marks)
{
    char text[400];
    memset(text, 'z', 300);
    memcpy(text + 300, "\n", 2);
    parse_err(text, SVET_ERR_PARSE,
              "t.scn:1:1: unknown keyword "
              "'zzzzzzzzzzzzzzzzzzzzzzzzzzzzzzzzzzzzzzzz...': expected one "
              "of " KEYWORDS);
    parse_err("camer\xc3\xa9 1\n", SVET_ERR_PARSE,
              "t.scn:1:1: unknown keyword 'camer?" "?' (did you mean "
              "'camera'?)");
}
END_TEST

START_TEST(a_null_error_pointer_is_allowed)
{
    /* Every failing path must cope with err == NULL (error.h allows it). */
    int n = (int)(sizeof errors / sizeof *errors);
    for (int i = 0; i < n; i++) {
        scene_t s;
        ck_assert_int_eq(parse(&s, errors[i].text, NULL),
                         errors[i].status);
        scene_free(&s);
    }
    scene_t s;
    parse_ok(&s, M "light point position 0 0 0 intensity 1\n");
    ck_assert_int_eq(scenefile_override(&s, "spp=0", NULL), SVET_ERR_RANGE);
    scene_free(&s);
    ck_assert_int_eq(read_scene(&s, "nope.scn", NULL), SVET_ERR_IO);
    scene_free(&s);
}
END_TEST

/* --- files --------------------------------------------------------------- */

START_TEST(read_reports_missing_and_irregular_files)
{
    scene_t s;
    svet_error err;
    ck_assert_int_eq(read_scene(&s, "tests/data/scene/nope.scn", &err),
                     SVET_ERR_IO);
    ck_assert_str_eq(err.msg, "tests/data/scene/nope.scn: cannot open: No "
                              "such file or directory");
    ck_assert_int_eq(read_scene(&s, "tests/data/scene", &err),
                     SVET_ERR_IO);
    ck_assert_str_eq(err.msg, "tests/data/scene: is a directory, not a "
                              "file");
    ck_assert_int_eq(read_scene(&s, "/dev/zero", &err), SVET_ERR_IO);
    ck_assert_str_eq(err.msg, "/dev/zero: is a device, not a regular file");
    scene_free(&s);
}
END_TEST

START_TEST(read_finds_meshes_beside_the_scene_and_keeps_its_path)
{
    scene_t s;
    svet_error err;
    ck_assert_msg(read_scene(&s, "tests/data/scene/mesh.scn", &err) ==
                      SVET_OK,
                  "%s", err.msg);
    ck_assert_str_eq(s.path, "tests/data/scene/mesh.scn");
    ck_assert_int_eq(s.nobjects, 4);
    scene_free(&s);
}
END_TEST

/* Every .scn file in dir, read with scenefile_read; returns how many. With
 * must_parse, each must give SVET_OK; else any status will do (the fuzzer's
 * inputs), but never a crash, a leak or a hang. */
static int read_all(const char *dir, const char *prefix, bool must_parse)
{
    DIR *d = opendir(dir);
    ck_assert_ptr_nonnull(d);
    int n = 0;
    struct dirent *de;
    while ((de = readdir(d))) {
        size_t len = strlen(de->d_name);
        if (len < 4 || strcmp(de->d_name + len - 4, ".scn") != 0 ||
            strncmp(de->d_name, prefix, strlen(prefix)) != 0)
            continue;
        char path[512];
        snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
        scene_t s;
        svet_error err;
        svet_error_clear(&err);
        svet_status st = read_scene(&s, path, &err);
        if (must_parse)
            ck_assert_msg(st == SVET_OK, "%s", err.msg);
        else
            ck_assert_msg(st == SVET_OK || err.msg[0] != '\0',
                          "%s: failed without a message", path);
        scene_free(&s);
        n++;
    }
    closedir(d);
    return n;
}

START_TEST(every_shipped_scene_parses)
{
    int n = read_all("scenes", "", true);
    ck_assert_int_ge(n, 8);
    n += read_all(DATA, "", false);
    test_report_cases("every_shipped_scene_parses", n);
}
END_TEST

START_TEST(fuzzer_findings_are_handled)
{
    int n = read_all(DATA, "regress-", false);
    test_report_cases("fuzzer_findings_are_handled", n);
}
END_TEST

/* --- overrides ----------------------------------------------------------- */

START_TEST(overrides_set_one_value_each)
{
    scene_t s;
    svet_error err;
    parse_ok(&s, M "sphere centre 0 0 -3 radius 1 material m\n");
    static const char *const ok[] = {
        "spp=64", "maxdepth=7", "seed=42", "integrator=direct",
        "resolution=512x256", "fov=30", "fov_axis=x", "exr=out dir/#a.exr",
        "png=b.png", "tonemap=reinhard", "exposure=-2", "roulette=off",
        "threads=2", "time_limit=60", "passes=4", "checkpoint=on",
        "accel=grid", "curve=none", "width=100", "packets=off",
    };
    int n = (int)(sizeof ok / sizeof *ok);
    for (int i = 0; i < n; i++)
        ck_assert_msg(scenefile_override(&s, ok[i], &err) == SVET_OK,
                      "%s: %s", ok[i], err.msg);
    ck_assert_int_eq(s.render.spp, 64);
    ck_assert_int_eq(s.render.max_depth, 7);
    ck_assert_uint_eq(s.render.seed, 42);
    ck_assert_int_eq(s.render.integrator, SCENE_INTEGRATOR_DIRECT);
    ck_assert_int_eq(s.camera.width, 100);
    ck_assert_int_eq(s.camera.height, 256);
    ck_assert_near(s.camera.fov, 30, 0);
    ck_assert_int_eq(s.camera.fov_axis, SCENE_FOV_X);
    ck_assert_str_eq(s.render.output_exr, "out dir/#a.exr");
    ck_assert_str_eq(s.render.output_png, "b.png");
    ck_assert_int_eq(s.render.tonemap.op, SCENE_TONEMAP_REINHARD);
    ck_assert_near(s.render.tonemap.exposure, -2, 0);
    ck_assert(!s.render.roulette);
    ck_assert_int_eq(s.render.threads, 2);
    ck_assert_near(s.render.time_limit, 60, 0);
    ck_assert_int_eq(s.render.passes, 4);
    ck_assert(s.render.checkpoint);
    ck_assert_int_eq(s.render.accel, SCENE_ACCEL_GRID);
    ck_assert(!s.render.packets);
    ck_assert_int_eq(s.render.tonemap.curve, SCENE_CURVE_NONE);
    ck_assert_int_eq(s.nobjects, 1);
    test_report_cases("overrides_set_one_value_each", n);
    scene_free(&s);
}
END_TEST

/* The spellings scenes/README.md gives for `--set` of the irradiance
 * cache (ch. 9) and of app. F's subsampling: each is taken and lands in
 * its key; a near miss is refused. */
START_TEST(overrides_of_the_irradiance_cache_and_subsampling)
{
    scene_t s;
    svet_error err;
    parse_ok(&s, M "sphere centre 0 0 -3 radius 1 material m\n");
    static const char *const ok[] = {
        "integrator=irradiance", "irradiance.a=0.3", "irradiance.m=4",
        "irradiance.n=16", "irradiance.min_r=2", "irradiance.max_r=30",
        "irradiance.bounces=6", "irradiance.gradients=off",
        "irradiance.clamp=off", "subsample.step=8",
        "subsample.threshold=0.2",
    };
    for (size_t i = 0; i < sizeof ok / sizeof *ok; i++)
        ck_assert_msg(scenefile_override(&s, ok[i], &err) == SVET_OK,
                      "%s: %s", ok[i], err.msg);
    irr_settings_t set;
    irr_settings_of(&s, &set);
    ck_assert_near(set.a, 0.3, 1e-6);
    ck_assert_int_eq(set.m, 4);
    ck_assert_int_eq(set.n, 16);
    ck_assert_near(set.min_r, 2, 0);
    ck_assert_near(set.max_r, 30, 0);
    ck_assert_int_eq(set.bounces, 6);
    ck_assert(!set.gradients && !set.clamp);
    ck_assert_int_eq(s.render.subsample_step, 8);
    ck_assert_near(s.render.subsample_threshold, 0.2, 1e-6);
    static const char *const bad[] = {
        "irradiance.minr=2", "irradiance.M=4", "irradiance.gradient=on",
        "subsample.steps=4", "subsample.threshold=1", "irradiance.a=0",
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++)
        ck_assert_msg(scenefile_override(&s, bad[i], &err) != SVET_OK,
                      "%s taken", bad[i]);
    irr_settings_of(&s, &set);
    ck_assert_int_eq(set.m, 4);
    ck_assert_int_eq(s.render.subsample_step, 8);
    scene_free(&s);
}
END_TEST

START_TEST(bad_overrides_are_refused_and_change_nothing)
{
    static const struct {
        const char *setting;
        svet_status status;
        const char *msg;
    } bad[] = {
        { "spp=0", SVET_ERR_RANGE,
          "override 'spp=0': 'spp' = 0 is out of range: expected 1 to "
          "16777216" },
        { "spp=abc", SVET_ERR_PARSE,
          "override 'spp=abc': expected a whole number for 'spp', got "
          "'abc'" },
        { "spp", SVET_ERR_PARSE, "override 'spp': expected key=value" },
        { "=5", SVET_ERR_PARSE, "override '=5': expected key=value" },
        { "sp=5", SVET_ERR_PARSE,
          "override 'sp=5': unknown setting 'sp' (did you mean 'spp'?)" },
        { "spp=", SVET_ERR_PARSE,
          "override 'spp=': expected a value after '='" },
        { "spp=4 8", SVET_ERR_PARSE,
          "override 'spp=4 8': expected exactly one value after '='" },
        { "resolution=512", SVET_ERR_PARSE,
          "override 'resolution=512': expected a resolution WIDTHxHEIGHT, "
          "e.g. 512x512" },
        { "resolution=0x5", SVET_ERR_RANGE,
          "override 'resolution=0x5': 'width' = 0 is out of range: "
          "expected 1 to 16384" },
        { "resolution=16384x16384", SVET_ERR_RANGE,
          "override 'resolution=16384x16384': 16384 x 16384 pixels is more "
          "than the limit of 67108864" },
        { "fov=nan", SVET_ERR_RANGE,
          "override 'fov=nan': 'fov' must be a finite number, not 'nan'" },
        { "tonemap=aces", SVET_ERR_PARSE,
          "override 'tonemap=aces': unknown value of 'operator' 'aces': "
          "expected one of linear, exponential, reinhard, drago, "
          "histogram" },
        { "exr=a\"b", SVET_ERR_PARSE,
          "override 'exr=a\"b': a value cannot contain '\"'" },
        { "png=", SVET_ERR_PARSE, "override 'png=': expected a value after "
                                  "'='" },
        { "seed=1 # comment", SVET_ERR_PARSE,
          "override 'seed=1 # comment': expected exactly one value after "
          "'='" },
    };
    scene_t s;
    parse_ok(&s, "camera width 64 height 48\nrender spp 8\n"
                 "output exr keep.exr\n");
    int n = (int)(sizeof bad / sizeof *bad);
    for (int i = 0; i < n; i++) {
        svet_error err;
        ck_assert_msg(scenefile_override(&s, bad[i].setting, &err) ==
                          bad[i].status,
                      "%s: %s", bad[i].setting, err.msg);
        ck_assert_str_eq(err.msg, bad[i].msg);
        ck_assert_int_eq(s.camera.width, 64);
        ck_assert_int_eq(s.camera.height, 48);
        ck_assert_int_eq(s.render.spp, 8);
        ck_assert_str_eq(s.render.output_exr, "keep.exr");
    }
    /* A camera override that makes the camera blind is refused whole. */
    svet_error err;
    scene_free(&s);
    parse_ok(&s, "camera position 0 0 1 target 0 0 0 up 0 1 0\n");
    ck_assert_int_eq(scenefile_override(&s, "fov=30", &err), SVET_OK);
    test_report_cases("bad_overrides_are_refused_and_change_nothing", n);
    scene_free(&s);
}
END_TEST

/* --- a program without the optional parts (ch. 5) ----------------------- */

/* scenefile_parse() offers nothing beyond the core, as ch. 5 does. */
static void parse_plain_err(const char *text, const char *msg)
{
    scene_t s;
    svet_error err;
    svet_error_clear(&err);
    ck_assert_int_eq(scenefile_parse(&s, text, strlen(text), "t.scn", DATA,
                                     &err),
                     SVET_ERR_UNSUPPORTED);
    ck_assert_str_eq(err.msg, msg);
    ck_assert_int_eq(s.nobjects + s.nmaterials, 0);
    ck_assert(s.features == NULL);
    scene_free(&s);
}

START_TEST(without_the_optional_parts_mesh_and_grids_are_refused)
{
    parse_plain_err(M "mesh file tri.obj material m\n",
                    "t.scn:2:1: 'mesh': this program was built without the "
                    "OBJ meshes of ch. 7 (objmesh.c, offered through "
                    "scenefile_read_with)");
    parse_plain_err("render spp 4 accel grid\n",
                    "t.scn:1:14: 'accel grid': this program was built "
                    "without the grids of ch. 7 (grid.c)");
    parse_plain_err("render accel hgrid\n",
                    "t.scn:1:8: 'accel hgrid': this program was built "
                    "without the grids of ch. 7 (grid.c)");
    /* a file, too */
    scene_t s;
    svet_error err;
    ck_assert_int_eq(scenefile_read(&s, "tests/data/scene/mesh.scn", &err),
                     SVET_ERR_UNSUPPORTED);
    ck_assert_str_eq(err.msg, "tests/data/scene/mesh.scn:5:1: 'mesh': this "
                              "program was built without the OBJ meshes of "
                              "ch. 7 (objmesh.c, offered through "
                              "scenefile_read_with)");
    /* brute force and AUTO are always there; AUTO then means brute force
     * (tests/render/test_render.c renders such a scene) */
    const char *const fine[] = { "render accel auto\n",
                                 "render accel brute\n" };
    for (int i = 0; i < 2; i++) {
        ck_assert_int_eq(scenefile_parse(&s, fine[i], strlen(fine[i]),
                                         "t.scn", DATA, &err),
                         SVET_OK);
        ck_assert(s.features == NULL);
        scene_free(&s);
    }
    /* an override asks the scene's features */
    ck_assert_int_eq(scenefile_parse(&s, M, strlen(M), "t.scn", DATA, &err),
                     SVET_OK);
    ck_assert_int_eq(scenefile_override(&s, "accel=grid", &err),
                     SVET_ERR_UNSUPPORTED);
    ck_assert_str_eq(err.msg, "override 'accel=grid': 'accel grid': this "
                              "program was built without the grids of "
                              "ch. 7 (grid.c)");
    ck_assert_int_eq(s.render.accel, SCENE_ACCEL_AUTO);
    ck_assert_int_eq(scenefile_override(&s, "accel=brute", &err), SVET_OK);
    ck_assert_int_eq(s.render.accel, SCENE_ACCEL_BRUTE);
    scene_free(&s);
    /* the same text with every part offered */
    parse_ok(&s, M "render accel hgrid\nmesh file tri.obj material m\n");
    ck_assert(s.features == scene_features_all());
    ck_assert_int_eq(s.render.accel, SCENE_ACCEL_HGRID);
    ck_assert_int_eq(s.nobjects, 2);
    ck_assert_int_eq(scenefile_override(&s, "accel=grid", &err), SVET_OK);
    scene_free(&s);
}
END_TEST

START_TEST(fresnel_key_chooses_schlick_or_exact)
{
    scene_t s;
    parse_ok(&s, "material g glass eta 1.5 fresnel exact\n"
                 "material h glass eta 1.5\n"
                 "material m mirror rho 0.9 fresnel schlick\n"
                 "material w mirror rho 0.04 eta 1.33 + transmission rho 0.96 "
                 "eta 1.33 fresnel exact\n");
    ck_assert(scene_find_material(&s, "g")->params.fresnel_exact);
    ck_assert(scene_find_material(&s, "g")->comp[0].exact);
    ck_assert(!scene_find_material(&s, "h")->params.fresnel_exact);
    ck_assert(!scene_find_material(&s, "m")->params.fresnel_exact);
    ck_assert(scene_find_material(&s, "w")->params.fresnel_exact);
    scene_free(&s);
    parse_err("material g glass eta 1.5 fresnel exakt\n", SVET_ERR_PARSE,
              "t.scn:1:34: unknown value of 'fresnel' 'exakt' (did you mean "
              "'exact'?)");
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("scenefile");
    TCase *tc = tcase_create("scenefile");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, camera_keys_parse_to_their_values);
    tcase_add_test(tc, render_keys_parse_to_their_values);
    tcase_add_test(tc, output_and_tonemap_parse_to_their_values);
    tcase_add_test(tc, comments_blank_lines_tabs_and_crlf_are_accepted);
    tcase_add_test(tc, a_byte_order_mark_at_the_start_is_skipped);
    tcase_add_test(tc, a_file_without_statements_is_an_error);
    tcase_add_test(tc, a_scene_without_light_parses_with_a_warning);
    tcase_add_test(tc, numbers_in_every_decimal_form_are_read);
    tcase_add_test(tc, every_material_component_parses_with_its_parameters);
    tcase_add_test(tc, every_shape_parses_with_its_material_and_name);
    tcase_add_test(tc, emission_is_front_only_unless_twosided);
    tcase_add_test(tc, parallelogram_normal_follows_the_corner_order);
    tcase_add_test(tc, transforms_apply_in_the_written_order);
    tcase_add_test(tc, cornell_box_boxes_land_where_the_reference_scene_puts_them);
    tcase_add_test(tc, cornell_box_matches_the_reference_numbers);
    tcase_add_test(tc, point_lights_in_every_unit);
    tcase_add_test(tc, environment_is_read_once);
    tcase_add_test(tc, mesh_usemtl_names_map_to_scene_materials);
    tcase_add_test(tc, a_mesh_without_usemtl_is_one_object_and_may_emit);
    tcase_add_test(tc, mesh_transforms_move_vertices_and_keep_normals_out);
    tcase_add_test(tc, mesh_errors_name_both_files);
    tcase_add_test(tc, mesh_warnings_reach_the_scene_and_strict_refuses_them);
    tcase_add_test(tc, lights_whose_products_overflow_are_refused);
    tcase_add_test(tc,
                   scaled_cornell_boxes_warn_where_float_renders_them_wrong);
    tcase_add_test(
        tc, precision_warnings_name_the_extent_and_the_smallest_object);
    tcase_add_test(tc,
                   every_error_names_file_line_column_and_what_was_expected);
    tcase_add_test(tc, a_nul_byte_is_an_error_not_the_end);
    tcase_add_test(tc, a_line_of_too_many_words_is_refused);
    tcase_add_test(
        tc, long_tokens_are_cut_and_unprintable_bytes_shown_as_question_marks);
    tcase_add_test(tc, a_null_error_pointer_is_allowed);
    tcase_add_test(tc, read_reports_missing_and_irregular_files);
    tcase_add_test(tc, read_finds_meshes_beside_the_scene_and_keeps_its_path);
    tcase_add_test(tc, every_shipped_scene_parses);
    tcase_add_test(tc, fuzzer_findings_are_handled);
    tcase_add_test(tc, overrides_set_one_value_each);
    tcase_add_test(tc, overrides_of_the_irradiance_cache_and_subsampling);
    tcase_add_test(tc, bad_overrides_are_refused_and_change_nothing);
    tcase_add_test(tc, without_the_optional_parts_mesh_and_grids_are_refused);
    tcase_add_test(tc, fresnel_key_chooses_schlick_or_exact);
    suite_add_tcase(s, tc);
    return s;
}
