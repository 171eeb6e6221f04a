/*
 * scenecheck.c - scene files given as text for the suites of the scene
 * file's parts (scenecheck.h): scenefile_parse_with with every part
 * (render/allparts.h), checked with the check framework's asserts.
 */
#include "scenecheck.h"

#include "testutil.h"
#include <string.h>

#include "render/allparts.h"
#include "render/render.h"
#include "render/scenefile.h"

svet_status scenecheck_parse(scene_t *s, const char *text, svet_error *e)
{
    return scenefile_parse_with(s, text, strlen(text), "t.scn", NULL,
                                scene_features_all(), e);
}

void scenecheck_parse_ok(scene_t *s, const char *text)
{
    svet_error e;
    svet_status st = scenecheck_parse(s, text, &e);
    ck_assert_msg(st == SVET_OK, "%s", e.msg);
}

void scenecheck_refused(const char *text, const char *where,
                        const char *what)
{
    scene_t s;
    svet_error e;
    ck_assert_int_ne(scenecheck_parse(&s, text, &e), SVET_OK);
    ck_assert_msg(strncmp(e.msg, where, strlen(where)) == 0 &&
                      strstr(e.msg, what),
                  "expected '%s ... %s', got '%s'", where, what, e.msg);
}

void scenecheck_render(const char *text, int threads, image_t *img)
{
    scene_t s;
    svet_error e;
    ck_assert_msg(scenecheck_parse(&s, text, &e) == SVET_OK, "%s", e.msg);
    render_t r;
    ck_assert_int_eq(render_init(&r, &s, &e), SVET_OK);
    ck_assert_int_eq(render_pass(&r, s.render.spp, threads, NULL, NULL),
                     SVET_OK);
    ck_assert_int_eq(render_image(&r, img, &e), SVET_OK);
    render_free(&r);
    scene_free(&s);
}
