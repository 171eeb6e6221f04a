/*
 * test_scenepart.c - the way a part of Part II joins the scene file and the
 * renderer (scenepart.h), through a toy part defined here: a `glow`
 * settings statement read with the core's key machinery, `--set
 * glow.level=...`, its data kept and freed with the scene, and a `render
 * integrator glow` method whose prepare, begin_pass and li the renderer
 * calls in that order, a `glowshape NAME KIND` statement of three kinds,
 * and a `halo` key on the shapes. Without the part, its keywords and keys
 * are refused.
 */
#include "testutil.h"
#include "render/render.h"
#include "render/scenefile.h"
#include "render/scenepart.h"

#include <stdlib.h>
#include <string.h>

/* --- the toy part --------------------------------------------------------- */

typedef struct {
    real level;
    int line_col;
} glow_t;

static int frees;
static void glow_free(void *p)
{
    frees++;
    free(p);
}

enum { G_LEVEL, G_N };
static const spec_t glow_spec[G_N] = {
    [G_LEVEL] = { "level", V_NUM, F_REQUIRED | F_NONNEG, 0, 0, NULL },
};

static svet_status glow_statement(scenefile_ctx *c)
{
    val_t v[G_N];
    svet_status st = scenefile_keys(c, "glow", glow_spec, G_N, v, false);
    if (st)
        return st;
    scene_t *s = scenefile_scene(c);
    glow_t *g = scene_part_data(s, "glow");
    if (!g) {
        g = calloc(1, sizeof *g);
        svet_error e;
        if (!g || scene_set_part_data(s, "glow", g, glow_free, &e))
            return scenefile_fail(c, 1, SVET_ERR_NOMEM, "out of memory");
    }
    g->level = v[G_LEVEL].v[0];
    g->line_col = v[G_LEVEL].col;
    return SVET_OK;
}

typedef struct {
    real level;
    long passes_begun, last_s0, last_s1;
} glow_state_t;

static svet_status glow_prepare(void **state, const render_t *r, int threads,
                                svet_error *err)
{
    (void)threads;
    const glow_t *g = scene_part_data(r->scene, "glow");
    glow_state_t *s = calloc(1, sizeof *s);
    if (!s)
        return svet_error_set(err, SVET_ERR_NOMEM, "out of memory");
    s->level = g ? g->level : 1;
    *state = s;
    return SVET_OK;
}

static svet_status glow_begin(void *state, const render_t *r, long s0,
                              long s1, int threads, svet_error *err)
{
    (void)r;
    (void)threads;
    glow_state_t *s = state;
    if (s->level > 100)
        return svet_error_set(err, SVET_ERR_RANGE, "glow: too bright");
    s->passes_begun++;
    s->last_s0 = s0;
    s->last_s1 = s1;
    return SVET_OK;
}

static RADIANCE glow_li(const void *state, const render_t *r,
                        const ray_t *ray, long sample, pcg32_t *g,
                        integrator_stats_t *st)
{
    (void)r;
    (void)ray;
    (void)g;
    st->paths++;
    const glow_state_t *s = state;
    real v = s->level * (real)(sample + 1);
    return (RADIANCE){ v, v, v };
}

static void glow_state_free(void *state)
{
    frees++;
    free(state);
}

static const render_method_t glow_method = {
    "glow", "a constant that grows with the sample index", glow_prepare,
    glow_begin, glow_li, glow_state_free, NULL, NULL, NULL, false
};
static const render_method_t *const glow_methods[] = { &glow_method, NULL };
/* `glowmap NAME FILE`: a name and a file path relative to the scene */
static char glowmap_name[SCENE_MAX_NAME + 1], *glowmap_path;
static svet_status glowmap_statement(scenefile_ctx *c)
{
    int col;
    svet_status st = scenefile_name(c, "glowmap", glowmap_name, &col);
    if (st)
        return st;
    int n;
    const tok_t *t = scenefile_tokens(c, &n);
    if (n != 1)
        return scenefile_fail(c, scenefile_eol_col(c), SVET_ERR_PARSE,
                              "glowmap expects one file after its name");
    svet_error e;
    free(glowmap_path);
    glowmap_path = scenefile_path(c, t, &e);
    scenefile_skip(c, 1);
    if (!glowmap_path)
        return scenefile_fail(c, t->col, e.status, "%s", e.msg);
    if (scenefile_tok_is(t, "dark.png"))
        scenefile_warn(c, t->col, "a dark glow map");
    return SVET_OK;
}

/* the whole scene: a glowmap needs a glow statement */
static svet_status glow_finish(scenefile_ctx *c)
{
    if (glowmap_path && !scene_part_data(scenefile_scene(c), "glow"))
        return scenefile_fail(c, 1, SVET_ERR_PARSE,
                              "glowmap '%s' without a glow", glowmap_name);
    return SVET_OK;
}

/* `glowshape NAME KIND`: a named thing of one of three kinds */
static const char *const glowshape_kinds[] = { "ring", "disc", "star", NULL };
static int glowshape_kind = -1;
static svet_status glowshape_statement(scenefile_ctx *c)
{
    char name[SCENE_MAX_NAME + 1];
    svet_status st = scenefile_name(c, "glowshape", name, NULL);
    if (st)
        return st;
    return scenefile_kind(c, "glowshape", name, glowshape_kinds,
                          &glowshape_kind);
}

static const scene_statement_t glow_statements[] = {
    { "glow", glow_statement }, { "glowmap", glowmap_statement },
    { "glowshape", glowshape_statement },
    { NULL, NULL }
};
/* `halo H` on a shape or mesh: the objects it names and the value */
enum { H_HALO, H_N };
static const spec_t halo_spec[H_N] = {
    [H_HALO] = { "halo", V_NUM, F_POSITIVE, 0, 0, NULL },
};
static int halo_calls, halo_objects, halo_first_id;
static real halo_value;
static svet_status halo_shape(scenefile_ctx *c, COBJECT *const *objs, int n,
                              const val_t *vals)
{
    if (vals[H_HALO].v[0] > 10)
        return scenefile_fail(c, vals[H_HALO].col, SVET_ERR_RANGE,
                              "a halo above 10");
    halo_calls++;
    halo_objects += n;
    halo_first_id = objs[0]->id;
    halo_value = vals[H_HALO].v[0];
    return SVET_OK;
}

static const scene_part_t glow_part = {
    .name = "glow",
    .statements = glow_statements,
    .methods = glow_methods,
    .finish = glow_finish,
    .shape_keys = halo_spec,
    .nshape_keys = H_N,
    .shape = halo_shape,
};
static const scene_part_t *const parts[] = { &glow_part, NULL };
static const scene_features_t features = { .parts = parts };

static const char scene_text[] =
    "camera width 4 height 2\n"
    "render spp 2 integrator glow\n"
    "glow level 0.5\n"
    "material m lambert rho 0.5\n"
    "sphere centre 0 0 -3 radius 1 material m\n";

/* a scene's one object, before the lines a test adds */
#define BALL "material m lambert rho 0.5\nsphere centre 0 0 -3 radius 1 material m\n"

static svet_status parse(scene_t *s, const char *text,
                         const scene_features_t *f, svet_error *e)
{
    return scenefile_parse_with(s, text, strlen(text), "t.scn", NULL, f, e);
}

/* --- tests ---------------------------------------------------------------- */

START_TEST(a_part_statement_is_read_with_the_core_keys)
{
    scene_t s;
    svet_error e;
    frees = 0;
    ck_assert_int_eq(parse(&s, scene_text, &features, &e), SVET_OK);
    const glow_t *g = scene_part_data(&s, "glow");
    ck_assert_ptr_nonnull(g);
    ck_assert_near(g->level, 0.5, 0);
    ck_assert_int_eq(g->line_col, 6);
    ck_assert(s.render.method == &glow_method);
    ck_assert_ptr_null(scene_part_data(&s, "other"));
    /* --set STATEMENT.KEY=VALUE reruns the statement */
    ck_assert_int_eq(scenefile_override(&s, "glow.level=2", &e), SVET_OK);
    ck_assert_near(((const glow_t *)scene_part_data(&s, "glow"))->level, 2,
                   0);
    ck_assert_int_eq(scenefile_override(&s, "glow.level=-1", &e),
                     SVET_ERR_RANGE);
    ck_assert_int_eq(scenefile_override(&s, "glow.levl=1", &e),
                     SVET_ERR_PARSE);
    ck_assert_msg(strstr(e.msg, "did you mean 'level'"), "%s", e.msg);
    ck_assert_int_eq(scenefile_override(&s, "render.spp=1", &e),
                     SVET_ERR_PARSE);
    scene_free(&s);
    ck_assert_int_eq(frees, 1);
}
END_TEST

START_TEST(a_part_statement_reports_file_line_and_column)
{
    scene_t s;
    svet_error e;
    const char *bad = BALL
        "glow level nan\n";
    ck_assert_int_ne(parse(&s, bad, &features, &e), SVET_OK);
    ck_assert_msg(strncmp(e.msg, "t.scn:3:12:", 11) == 0, "%s", e.msg);
    const char *typo = BALL
        "glwo level 1\n";
    ck_assert_int_eq(parse(&s, typo, &features, &e), SVET_ERR_PARSE);
    ck_assert_msg(strstr(e.msg, "did you mean 'glow'"), "%s", e.msg);
}
END_TEST

START_TEST(a_part_reads_names_files_and_checks_the_whole_scene)
{
    scene_t s;
    svet_error e;
    const char *ok = BALL "glow level 1\nglowmap g1 dark.png\n";
    ck_assert_int_eq(scenefile_parse_with(&s, ok, strlen(ok), "t.scn", "d",
                                          &features, &e), SVET_OK);
    ck_assert_str_eq(glowmap_name, "g1");
    ck_assert_str_eq(glowmap_path, "d/dark.png");
    /* and the core's "nothing emits light" after it */
    ck_assert_int_eq(s.warnings.n, 2);
    ck_assert_msg(strstr(s.warnings.msg[0], "t.scn:4:12: warning: a dark"),
                  "%s", s.warnings.msg[0]);
    scene_free(&s);
    const char *lone = BALL "glowmap g1 x.png\n";
    ck_assert_int_eq(parse(&s, lone, &features, &e), SVET_ERR_PARSE);
    ck_assert_msg(strstr(e.msg, "without a glow"), "%s", e.msg);
    const char *bad = BALL "glow level 1\nglowmap 9a x.png\n";
    ck_assert_int_eq(parse(&s, bad, &features, &e), SVET_ERR_PARSE);
    ck_assert_msg(strstr(e.msg, "t.scn:4:9: '9a' is not a glowmap name"),
                  "%s", e.msg);
    const char *two = BALL "glow level 1\nglowmap g x.png y.png\n";
    ck_assert_int_eq(parse(&s, two, &features, &e), SVET_ERR_PARSE);
    ck_assert_msg(strstr(e.msg, "one file"), "%s", e.msg);
    free(glowmap_path);
    glowmap_path = NULL;
}
END_TEST

START_TEST(a_part_reads_a_kind_among_its_words)
{
    scene_t s;
    svet_error e;
    const char *disc = BALL "glowshape g disc\n";
    ck_assert_int_eq(parse(&s, disc, &features, &e), SVET_OK);
    ck_assert_int_eq(glowshape_kind, 1);
    scene_free(&s);
    const char *none = BALL "glowshape g\n";
    ck_assert_int_eq(parse(&s, none, &features, &e), SVET_ERR_PARSE);
    ck_assert_str_eq(e.msg, "t.scn:3:12: glowshape 'g' expects a kind: "
                            "ring, disc or star");
    const char *cube = BALL "glowshape g cube size 2\n";
    ck_assert_int_eq(parse(&s, cube, &features, &e), SVET_ERR_PARSE);
    ck_assert_str_eq(e.msg, "t.scn:3:13: glowshape 'g' expects a kind: "
                            "ring, disc or star, not 'cube'");
}
END_TEST

START_TEST(a_part_adds_keys_to_the_shapes)
{
    scene_t s;
    svet_error e;
    halo_calls = halo_objects = 0;
    const char *ok = BALL
        "box min 0 0 -5 max 1 1 -4 material m halo 0.25 translate 1 0 0\n"
        "sphere centre 0 2 -3 radius 1 material m\n";
    ck_assert_int_eq(parse(&s, ok, &features, &e), SVET_OK);
    /* called once, for the box only (the scene's second object) */
    ck_assert_int_eq(halo_calls, 1);
    ck_assert_int_eq(halo_objects, 1);
    ck_assert_int_eq(halo_first_id, 1);
    ck_assert_near(halo_value, 0.25, 0);
    scene_free(&s);
    /* the part's message names the key's column; the core's checks apply */
    const char *big = BALL "sphere centre 0 0 -9 radius 1 halo 20 material m\n";
    ck_assert_int_eq(parse(&s, big, &features, &e), SVET_ERR_RANGE);
    ck_assert_msg(strstr(e.msg, "t.scn:3:31: a halo above 10"), "%s", e.msg);
    const char *neg = BALL "sphere centre 0 0 -9 radius 1 halo -1 material m\n";
    ck_assert_int_eq(parse(&s, neg, &features, &e), SVET_ERR_RANGE);
    ck_assert_msg(strstr(e.msg, "t.scn:3:"), "%s", e.msg);
    const char *typo = BALL "sphere centre 0 0 -9 radius 1 hallo 1 material m\n";
    ck_assert_int_eq(parse(&s, typo, &features, &e), SVET_ERR_PARSE);
    ck_assert_msg(strstr(e.msg, "did you mean 'halo'"), "%s", e.msg);
    /* without the part the key is unknown; a later chapter's names it */
    ck_assert_int_eq(parse(&s, ok, NULL, &e), SVET_ERR_PARSE);
    ck_assert_msg(strstr(e.msg, "t.scn:3:"), "%s", e.msg);
    const char *fog = BALL "sphere centre 0 0 -9 radius 1 medium fog material m\n";
    ck_assert_int_eq(parse(&s, fog, NULL, &e), SVET_ERR_UNSUPPORTED);
    ck_assert_msg(strstr(e.msg, "t.scn:3:31: 'medium' on a sphere is not "
                                "supported by this program: ch. 11"),
                  "%s", e.msg);
    ck_assert_int_eq(halo_calls, 1);
}
END_TEST

START_TEST(without_the_part_its_keywords_are_refused)
{
    scene_t s;
    svet_error e;
    ck_assert_int_eq(parse(&s, scene_text, NULL, &e), SVET_ERR_PARSE);
    ck_assert_msg(strstr(e.msg, "t.scn:2:25:"), "%s", e.msg);
    /* a later chapter's method names its chapter */
    const char *photon = BALL
        "render integrator photon\n";
    ck_assert_int_eq(parse(&s, photon, NULL, &e), SVET_ERR_UNSUPPORTED);
    ck_assert_msg(strstr(e.msg, "ch. 8"), "%s", e.msg);
    const char *typo = BALL
        "render integrator pth\n";
    ck_assert_int_eq(parse(&s, typo, NULL, &e), SVET_ERR_PARSE);
    ck_assert_msg(strstr(e.msg, "did you mean 'path'"), "%s", e.msg);
    /* the core's integrators are still chosen by name */
    const char *ao = BALL
        "render integrator ao\n";
    ck_assert_int_eq(parse(&s, ao, NULL, &e), SVET_OK);
    ck_assert_int_eq(s.render.integrator, SCENE_INTEGRATOR_AO);
    ck_assert_ptr_null(s.render.method);
    scene_free(&s);
}
END_TEST

START_TEST(the_renderer_runs_the_method_pass_by_pass)
{
    scene_t s;
    svet_error e;
    frees = 0;
    ck_assert_int_eq(parse(&s, scene_text, &features, &e), SVET_OK);
    render_t r;
    ck_assert_int_eq(render_init(&r, &s, &e), SVET_OK);
    ck_assert(r.method == &glow_method);
    ck_assert(!r.packets);
    ck_assert_int_eq(render_pass(&r, 1, 1, NULL, NULL), SVET_OK);
    const glow_state_t *gs = r.method_state;
    ck_assert_int_eq(gs->passes_begun, 1);
    ck_assert_int_eq(render_pass(&r, 3, 2, NULL, NULL), SVET_OK);
    ck_assert_int_eq(gs->passes_begun, 2);
    ck_assert_int_eq(gs->last_s0, 1);
    ck_assert_int_eq(gs->last_s1, 3);
    image_t img;
    ck_assert_int_eq(render_image(&r, &img, &e), SVET_OK);
    /* samples 0, 1, 2 give 0.5, 1, 1.5: their mean is 1 */
    for (int y = 0; y < 2; y++)
        for (int x = 0; x < 4; x++)
            ck_assert_near(image_at(&img, x, y)[0], 1, 1e-6);
    image_free(&img);
    ck_assert_int_eq(r.stats.paths, 3 * 8);
    render_free(&r);
    ck_assert_int_eq(frees, 1);
    /* a begin_pass that fails adds nothing and says why */
    ck_assert_int_eq(scenefile_override(&s, "glow.level=200", &e), SVET_OK);
    ck_assert_int_eq(render_init(&r, &s, &e), SVET_OK);
    ck_assert_int_eq(render_pass(&r, 1, 1, NULL, NULL), SVET_ERR_RANGE);
    ck_assert_msg(strstr(r.error.msg, "too bright"), "%s", r.error.msg);
    ck_assert_int_eq(r.spp_done, 0);
    render_free(&r);
    scene_free(&s);
    ck_assert_int_eq(frees, 3);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("scenepart");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, a_part_statement_is_read_with_the_core_keys);
    tcase_add_test(tc, a_part_statement_reports_file_line_and_column);
    tcase_add_test(tc, a_part_reads_names_files_and_checks_the_whole_scene);
    tcase_add_test(tc, a_part_reads_a_kind_among_its_words);
    tcase_add_test(tc, a_part_adds_keys_to_the_shapes);
    tcase_add_test(tc, without_the_part_its_keywords_are_refused);
    tcase_add_test(tc, the_renderer_runs_the_method_pass_by_pass);
    suite_add_tcase(s, tc);
    return s;
}
