/*
 * test_animation.c - animations (animation.h): `animation frames N` and
 * `key FRAME camera ...` read with their messages, the camera of a frame
 * interpolated linearly between keys (exact at dyadic values, so compared
 * with ==), held before the first and after the last, the `camera`
 * statement's where no key gives a value; the seed of frame k is
 * seed ^ splitmix64(k) whichever frames were set before; every refusal
 * with its message. Frames rendered and merged: tests/cmd/test_frames.sh.
 */
#include "testutil.h"
#include "scenecheck.h"
#include "core/rng.h"
#include "render/allparts.h"
#include "render/animation.h"
#include "render/scenefile.h"

#include <string.h>

#define BALL "material m lambert rho 0.5\n" \
             "sphere centre 0 0 -3 radius 1 material m\n"

static void vec_is(const VECTOR3 v, real x, real y, real z)
{
    ck_assert_msg(v[0] == x && v[1] == y && v[2] == z,
                  "(%g %g %g), expected (%g %g %g)", (double)v[0],
                  (double)v[1], (double)v[2], (double)x, (double)y,
                  (double)z);
}

/* Keys at frames 0 and 8 for the position, 2 and 6 for the target, 4 for
 * the fov; up from the camera statement. Every expected value is a
 * dyadic rational the lerp v0 + (v1 - v0) t computes exactly. */
static const char anim[] =
    "camera position 0 0 4 target 0 0 0 up 0 1 0 fov 40 width 8 height 8\n"
    "render seed 77\n"
    "animation frames 10\n"
    "key 8 camera position 1 0 4\n"
    "key 0 camera position -1 0 4\n"
    "key 2 camera target 0 0 0\n"
    "key 6 camera target 0 1 0\n"
    "key 4 camera fov 30\n"
    BALL;

START_TEST(a_frame_has_the_camera_of_its_keys)
{
    scene_t s;
    svet_error e;
    ck_assert_msg(scenecheck_parse(&s, anim, &e) == SVET_OK, "%s", e.msg);
    ck_assert_int_eq(animation_frames(&s), 10);
    ck_assert_int_eq(animation_frame(&s), -1);
    /* frame 2: position t = 2/8 of -1 -> 1; target at its key; fov held
     * before its only key */
    ck_assert_int_eq(animation_set_frame(&s, 2, &e), SVET_OK);
    ck_assert_int_eq(animation_frame(&s), 2);
    vec_is(s.camera.position, REAL_C(-0.5), 0, 4);
    vec_is(s.camera.target, 0, 0, 0);
    vec_is(s.camera.up, 0, 1, 0);
    ck_assert(s.camera.fov == 30);
    /* frame 4: halfway for both */
    ck_assert_int_eq(animation_set_frame(&s, 4, &e), SVET_OK);
    vec_is(s.camera.position, 0, 0, 4);
    vec_is(s.camera.target, 0, REAL_C(0.5), 0);
    /* frame 0: the first key; target held before its first key */
    ck_assert_int_eq(animation_set_frame(&s, 0, &e), SVET_OK);
    vec_is(s.camera.position, -1, 0, 4);
    vec_is(s.camera.target, 0, 0, 0);
    /* frames 8, 9: the last key's position, held after it */
    ck_assert_int_eq(animation_set_frame(&s, 9, &e), SVET_OK);
    vec_is(s.camera.position, 1, 0, 4);
    vec_is(s.camera.target, 0, 1, 0);
    ck_assert_int_eq(animation_set_frame(&s, 7, &e), SVET_OK);
    vec_is(s.camera.position, REAL_C(0.75), 0, 4);
    vec_is(s.camera.target, 0, 1, 0);
    /* the size and the rest are the camera statement's */
    ck_assert_int_eq(s.camera.width, 8);
    scene_free(&s);
}
END_TEST

START_TEST(a_frame_has_its_own_seed_whatever_came_before)
{
    scene_t s;
    svet_error e;
    ck_assert_msg(scenecheck_parse(&s, anim, &e) == SVET_OK, "%s", e.msg);
    ck_assert_int_eq(animation_set_frame(&s, 3, &e), SVET_OK);
    ck_assert(s.render.seed == (77 ^ splitmix64(3)));
    ck_assert_int_eq(animation_set_frame(&s, 5, &e), SVET_OK);
    ck_assert(s.render.seed == (77 ^ splitmix64(5)));
    ck_assert(animation_frame_seed(77, 0) == (77 ^ 0xe220a8397b1dcdafULL));
    /* a fresh read set straight to frame 5 is the same scene */
    scene_t t;
    ck_assert_msg(scenecheck_parse(&t, anim, &e) == SVET_OK, "%s", e.msg);
    ck_assert_int_eq(animation_set_frame(&t, 5, &e), SVET_OK);
    ck_assert(t.render.seed == s.render.seed);
    ck_assert(memcmp(&t.camera, &s.camera, sizeof t.camera) == 0);
    /* a refused frame leaves the scene as it was */
    ck_assert_int_eq(animation_set_frame(&t, 10, &e), SVET_ERR_RANGE);
    ck_assert_str_eq(e.msg, "frame 10 is not one of the animation's frames "
                            "0..9");
    ck_assert_int_eq(animation_frame(&t), 5);
    ck_assert_int_eq(animation_set_frame(&t, -1, &e), SVET_ERR_RANGE);
    scene_free(&s);
    scene_free(&t);
}
END_TEST

START_TEST(a_scene_without_animation_has_no_frames)
{
    scene_t s;
    svet_error e;
    ck_assert_msg(scenecheck_parse(&s, BALL, &e) == SVET_OK, "%s", e.msg);
    ck_assert_int_eq(animation_frames(&s), 0);
    ck_assert_int_eq(animation_frame(&s), -1);
    uint64_t seed = s.render.seed;
    ck_assert_int_eq(animation_set_frame(&s, 0, &e), SVET_ERR_RANGE);
    ck_assert(strstr(e.msg, "no animation") != NULL);
    ck_assert(s.render.seed == seed);
    scene_free(&s);
    /* frames without keys: the camera statement's camera in every one */
    scenecheck_parse_ok(&s, "animation frames 3\n" BALL);
    ck_assert_int_eq(animation_set_frame(&s, 2, &e), SVET_OK);
    vec_is(s.camera.position, 0, 0, 0);
    scene_free(&s);
}
END_TEST

/* Each bad line is refused with file:line:col and what is wrong. */
START_TEST(bad_animations_are_refused_with_their_messages)
{
    static const struct {
        const char *text, *msg;
    } bad[] = {
        { "key 0 camera position 0 0 1\n" BALL,
          "t.scn:1:1: 'key' before 'animation frames N'" },
        { "animation frames 4\nkey 4 camera position 0 0 1\n" BALL,
          "t.scn:2:5: frame 4 is not one of the animation's frames 0..3" },
        { "animation frames 4\nkey -1 camera position 0 0 1\n" BALL,
          "t.scn:2:5: frame -1 is not one of" },
        { "animation frames 4\nkey x camera position 0 0 1\n" BALL,
          "t.scn:2:5: 'x' is not a frame number" },
        { "animation frames 4\nkey 1.5 camera position 0 0 1\n" BALL,
          "t.scn:2:5: '1.5' is not a frame number" },
        { "animation frames 4\nkey 1 position 0 0 1\n" BALL,
          "t.scn:2:7: expected 'camera' after the frame number" },
        { "animation frames 4\nkey 1\n" BALL,
          "t.scn:2:6: expected 'camera'" },
        { "animation frames 4\nkey 1 camera\n" BALL,
          "t.scn:2:13: a camera key gives at least one of position" },
        { "animation frames 4\nkey 1 camera fov 180\n" BALL,
          "t.scn:2:14: 'fov' is the full angle in degrees" },
        { "animation frames 4\nkey 1 camera width 5\n" BALL,
          "t.scn:2:14: unknown parameter of key 'width'" },
        { "animation frames 4\nkey 1 camera up 0 0 0\n" BALL,
          "t.scn:2:14:" },
        { "animation frames 4\nkey 1 camera fov 30\nkey 1 camera fov 20\n"
          BALL, "t.scn:3:5: frame 1 has a key already" },
        { "animation frames 4\nanimation frames 5\n" BALL,
          "t.scn:2:1: a second 'animation' statement" },
        { "animation frames 0\n" BALL, "t.scn:1:" },
        { "animation frames 1000001\n" BALL, "t.scn:1:" },
        { "animation\n" BALL, "t.scn:1:" },
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        scene_t s;
        svet_error e;
        ck_assert_msg(scenecheck_parse(&s, bad[i].text, &e) != SVET_OK,
                      "accepted: %s", bad[i].text);
        ck_assert_msg(strstr(e.msg, bad[i].msg) != NULL,
                      "case %zu: '%s' is not in '%s'", i, bad[i].msg, e.msg);
        scene_free(&s);
    }
    test_report_cases("bad_animations_are_refused_with_their_messages",
                      (long)(sizeof bad / sizeof *bad));
}
END_TEST

/* A frame whose interpolated camera makes no image (its target at its
 * position) is refused with the frame's number; its neighbours render. */
START_TEST(a_frame_with_a_degenerate_camera_is_refused)
{
    scene_t s;
    svet_error e;
    const char *text =
        "camera position 0 0 4 target 0 0 0\n"
        "animation frames 3\n"
        "key 0 camera position 0 0 -1\n"
        "key 2 camera position 0 0 1\n" BALL;
    ck_assert_msg(scenecheck_parse(&s, text, &e) == SVET_OK, "%s", e.msg);
    ck_assert_int_eq(animation_set_frame(&s, 0, &e), SVET_OK);
    ck_assert_int_eq(animation_set_frame(&s, 1, &e), SVET_ERR_RANGE);
    ck_assert_msg(strncmp(e.msg, "frame 1: ", 9) == 0, "%s", e.msg);
    vec_is(s.camera.position, 0, 0, -1); /* still frame 0 */
    ck_assert_int_eq(animation_set_frame(&s, 2, &e), SVET_OK);
    scene_free(&s);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("animation");
    TCase *tc = tcase_create("animation");
    tcase_add_test(tc, a_frame_has_the_camera_of_its_keys);
    tcase_add_test(tc, a_frame_has_its_own_seed_whatever_came_before);
    tcase_add_test(tc, a_scene_without_animation_has_no_frames);
    tcase_add_test(tc, bad_animations_are_refused_with_their_messages);
    tcase_add_test(tc, a_frame_with_a_degenerate_camera_is_refused);
    suite_add_tcase(s, tc);
    return s;
}
