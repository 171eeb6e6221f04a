/*
 * test_texpart.c - texpart.h, the textures in the scene file and the
 * renderer: every kind parses; bad input (an unknown kind or name, a key
 * the kind does not take, NaN, a missing, truncated, non-image or
 * decompression-bomb file, an EXR of channels it does not know) fails
 * with file:line:col and the reader's reason; a program without
 * the part refuses a texture's name; a zero bump and a constant texture
 * render the same bits as none; a bump on a shape renders the same bits
 * as on its material, and wins over the material's; the grazing checkerboard at 1 spp is
 * nearer a supersampled reference with the trilinear mip map than with
 * the nearest texel.
 */
#include "testutil.h"
#include "scenecheck.h"
#include "imgtest.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "io/exrio.h"
#include "io/pngio.h"
#include "render/allparts.h"
#include "render/render.h"
#include "render/scenefile.h"

#define HEAD "camera position 0 1 4 target 0 0 0 width 8 height 6\n"
#define BALL "sphere centre 0 0 0 radius 1 material m\n"

START_TEST(every_kind_of_texture_parses)
{
    static const char *const lines[] = {
        "texture t checker a 0.1 b 0.9 scale 8",
        "texture t checker solid scale 2",
        "texture t noise scale 4",
        "texture t fbm octaves 4 lacunarity 2.1 gain 0.4",
        "texture t turbulence octaves 3",
        "texture t marble a 0.1 0.1 0.3 b 0.9 amplitude 4",
        "texture t wood rings 6 amplitude 0.2",
        "texture t granite scale 10",
        "texture t waves frequency 5 angle 30",
        "texture t ripples damping 1",
        "texture t bricks",
        "texture t orange_peel frequency 20",
        "texture t dents",
    };
    for (size_t i = 0; i < sizeof lines / sizeof lines[0]; i++) {
        char text[512];
        snprintf(text, sizeof text,
                 HEAD "%s\nmaterial m lambert rho t + bump t strength 0.1\n"
                 BALL, lines[i]);
        scene_t s;
        svet_error e;
        ck_assert_msg(scenecheck_parse(&s, text, &e) == SVET_OK, "%s: %s",
                      lines[i], e.msg);
        ck_assert_ptr_nonnull(s.objects[0]->texture);
        ck_assert(s.shade != NULL);
        scene_free(&s);
    }
}
END_TEST

START_TEST(bad_texture_lines_name_file_line_and_column)
{
    scenecheck_refused(HEAD "texture t cheker\n", "t.scn:2:11:",
                       "expects a kind");
    scenecheck_refused(HEAD "texture 9t checker\n", "t.scn:2:9:",
                       "not a texture name");
    scenecheck_refused(HEAD "texture t checker\ntexture t noise\n",
                       "t.scn:3:9:", "already defined");
    scenecheck_refused(HEAD "texture t noise rings 3\n", "t.scn:2:17:",
                       "takes no 'rings'");
    scenecheck_refused(HEAD "texture t noise scale nan\n", "t.scn:2:23:", "");
    scenecheck_refused(HEAD "texture t noise scale -1\n", "t.scn:2:17:",
                       "> 0");
    scenecheck_refused(HEAD "texture t image\n", "t.scn:2:1:", "needs 'file'");
    scenecheck_refused(HEAD "texture t checker\n"
                            "material m lambert rho tt\n" BALL,
                       "t.scn:3:24:", "neither a number nor a texture");
    scenecheck_refused(HEAD "material m lambert rho 0.5 + bump 3\n" BALL,
                       "t.scn:2:35:", "expects the name of a texture");
    scenecheck_refused(HEAD "material m phong rho 0.5 e nope\n" BALL,
                       "t.scn:2:28:", "'nope' is neither");
}
END_TEST

START_TEST(a_program_without_textures_refuses_their_names)
{
    scene_t s;
    svet_error e;
    const char *text = HEAD "material m lambert rho wood\n" BALL;
    ck_assert_int_eq(scenefile_parse(&s, text, strlen(text), "t.scn", NULL, &e),
                     SVET_ERR_PARSE);
    ck_assert_msg(strstr(e.msg, "t.scn:2:24: expected a number, got 'wood'"),
                  "%s", e.msg);
    text = HEAD "texture t noise\n";
    ck_assert_int_ne(scenefile_parse(&s, text, strlen(text), "t.scn", NULL, &e),
                     SVET_OK);
    ck_assert_msg(strstr(e.msg, "t.scn:2:1:"), "%s", e.msg);
}
END_TEST

START_TEST(bad_texture_files_are_refused_with_the_readers_reason)
{
    char text[1024];
    /* missing */
    snprintf(text, sizeof text, HEAD "texture t image file \"%s\"\n",
             imgtest_path("none.png"));
    scenecheck_refused(text, "t.scn:2:22:", "none.png");
    /* not an image */
    const char *junk = imgtest_path("junk.png");
    imgtest_write_bytes(junk, "hello, world\n", 13);
    snprintf(text, sizeof text, HEAD "texture t image file \"%s\"\n", junk);
    scenecheck_refused(text, "t.scn:2:22:", "texture file:");
    /* truncated: a real PNG cut in half */
    image_t img;
    imgtest_hdr_image(&img, 16, 16, 3);
    for (size_t i = 0; i < 16 * 16 * 3; i++)
        img.px[i] = 0.5f;
    const char *good = imgtest_path("good.png");
    svet_error e;
    ck_assert_int_eq(pngio_write(good, &img, 8, &e), SVET_OK);
    image_free(&img);
    unsigned char *bytes;
    size_t n = imgtest_read_bytes(good, &bytes);
    const char *cut = imgtest_path("cut.png");
    imgtest_write_bytes(cut, bytes, n / 2);
    snprintf(text, sizeof text, HEAD "texture t image file \"%s\"\n", cut);
    scenecheck_refused(text, "t.scn:2:22:", "texture file:");
    /* the same PNG with a header that claims 100000 x 100000 pixels (a
     * decompression bomb): refused before anything is allocated, by the
     * readers' pixel limit (io/image.h) */
    imgtest_png_patch_ihdr(bytes, 100000, 100000);
    const char *bomb = imgtest_path("bomb.png");
    imgtest_write_bytes(bomb, bytes, n);
    free(bytes);
    snprintf(text, sizeof text, HEAD "texture t image file \"%s\"\n", bomb);
    scenecheck_refused(text, "t.scn:2:22:", "texture file:");
    /* an EXR holding a NaN: refused at its texel */
    imgtest_hdr_image(&img, 4, 4, 3);
    image_at(&img, 2, 1)[1] = NAN;
    const char *nan_exr = imgtest_path("nan.exr");
    ck_assert_int_eq(exrio_write(nan_exr, &img, EXRIO_FLOAT, EXRIO_ZIP, &e),
                     SVET_OK);
    image_free(&img);
    snprintf(text, sizeof text, HEAD "texture t image file \"%s\"\n",
             nan_exr);
    scenecheck_refused(text, "t.scn:2:22:",
                       "the texel (2, 1) is not a finite number");
    /* an EXR whose channels are none the reader knows (U V W: neither R G
     * B nor Y): the same file as an RGB one with its channel names
     * renamed in the header's chlist, so that nothing else changes */
    imgtest_hdr_image(&img, 4, 4, 3);
    const char *uvw = imgtest_path("uvw.exr");
    ck_assert_int_eq(exrio_write(uvw, &img, EXRIO_FLOAT, EXRIO_NONE, &e),
                     SVET_OK);
    image_free(&img);
    n = imgtest_read_bytes(uvw, &bytes);
    unsigned char *at = NULL;
    for (size_t i = 0; i + 7 <= n && !at; i++)
        if (memcmp(bytes + i, "chlist", 7) == 0)
            at = bytes + i;
    ck_assert_ptr_nonnull(at);
    /* after "chlist\0" and the int32 size, each channel is its name, NUL
     * and 16 bytes of type, linearity and sampling: "B" "G" "R" */
    unsigned char *name = at + 7 + 4;
    for (int k = 0; k < 3; k++, name += 2 + 16) {
        ck_assert_int_eq(name[0], "BGR"[k]);
        name[0] = (unsigned char)"UVW"[k];
    }
    imgtest_write_bytes(uvw, bytes, n);
    free(bytes);
    snprintf(text, sizeof text, HEAD "texture t image file \"%s\"\n", uvw);
    scenecheck_refused(text, "t.scn:2:22:", "the file has: U V W");
    /* and the whole one loads */
    snprintf(text, sizeof text,
             HEAD "texture t image file \"%s\" filter bilinear wrap mirror\n"
             "material m lambert rho t\n" BALL, good);
    scene_t s;
    ck_assert_msg(scenecheck_parse(&s, text, &e) == SVET_OK, "%s", e.msg);
    scene_free(&s);
}
END_TEST

static bool same_bits(const image_t *a, const image_t *b)
{
    return a->width == b->width && a->height == b->height &&
           a->channels == b->channels &&
           memcmp(a->px, b->px, (size_t)a->width * (size_t)a->height *
                                    (size_t)a->channels * sizeof(float)) == 0;
}

#define LIT HEAD "render spp 4 maxdepth 3 seed 7\n" \
    "light point position 2 3 3 intensity 20\n"
#define SCENE BALL "plane point 0 -1 0 normal 0 1 0 material m\n"

START_TEST(a_zero_bump_and_a_constant_texture_render_the_same_bits)
{
    image_t plain, zero, flat, grey, grey2;
    scenecheck_render(LIT "material m lambert rho 0.5 + phong rho 0.3 e 20\n"
                      SCENE, 1, &plain);
    /* strength 0 */
    scenecheck_render(LIT "texture w waves\n"
                      "material m lambert rho 0.5 + phong rho 0.3 e 20 + "
                      "bump w strength 0\n" SCENE, 1, &zero);
    ck_assert(same_bits(&plain, &zero));
    /* a height of zero gradient everywhere: a 2D checker */
    scenecheck_render(LIT "texture c checker\n"
                      "material m lambert rho 0.5 + phong rho 0.3 e 20 + "
                      "bump c strength 5\n" SCENE, 1, &flat);
    ck_assert(same_bits(&plain, &flat));
    /* rho and e from textures of constant value */
    scenecheck_render(LIT "texture h checker a 0.5 b 0.5\n"
                      "texture x noise a 20 b 20\n"
                      "material m lambert rho h + phong rho 0.3 e x\n" SCENE,
                      1, &grey);
    ck_assert(same_bits(&plain, &grey));
    /* and a textured image is the same for 1 and 2 threads */
    image_free(&grey);
    scenecheck_render(LIT "texture h marble\ntexture w waves\n"
                      "material m lambert rho h + bump w strength 0.05\n"
                      SCENE, 1, &grey);
    scenecheck_render(LIT "texture h marble\ntexture w waves\n"
                      "material m lambert rho h + bump w strength 0.05\n"
                      SCENE, 2, &grey2);
    ck_assert(same_bits(&grey, &grey2));
    ck_assert(!same_bits(&grey, &plain));
    image_free(&plain);
    image_free(&zero);
    image_free(&flat);
    image_free(&grey);
    image_free(&grey2);
}
END_TEST

START_TEST(a_bumped_shape_shades_as_its_bumped_material)
{
    image_t mat, shp, both, none, plain;
    /* the same waves on the plane: once as the material's component, once
     * as the plane's key (the sphere keeps the unbumped material) */
    scenecheck_render(LIT "texture w waves\n"
                      "material m lambert rho 0.5 + phong rho 0.3 e 20\n"
                      "material b lambert rho 0.5 + phong rho 0.3 e 20 + "
                      "bump w strength 0.05\n" BALL
                      "plane point 0 -1 0 normal 0 1 0 material b\n", 1, &mat);
    scenecheck_render(LIT "texture w waves\n"
                      "material m lambert rho 0.5 + phong rho 0.3 e 20\n" BALL
                      "plane point 0 -1 0 normal 0 1 0 material m bump w "
                      "strength 0.05\n", 1, &shp);
    ck_assert(same_bits(&mat, &shp));
    /* the shape's bump wins over its material's */
    scenecheck_render(LIT "texture w waves\ntexture r ripples\n"
                      "material m lambert rho 0.5 + phong rho 0.3 e 20\n"
                      "material b lambert rho 0.5 + phong rho 0.3 e 20 + "
                      "bump r strength 0.2\n" BALL
                      "plane point 0 -1 0 normal 0 1 0 material b bump w "
                      "strength 0.05\n", 1, &both);
    ck_assert(same_bits(&mat, &both));
    /* strength 0 on the shape takes the material's bump away */
    scenecheck_render(LIT "texture r ripples\n"
                      "material m lambert rho 0.5 + phong rho 0.3 e 20\n"
                      "material b lambert rho 0.5 + phong rho 0.3 e 20 + "
                      "bump r strength 0.2\n" BALL
                      "plane point 0 -1 0 normal 0 1 0 material b bump r "
                      "strength 0\n", 1, &none);
    scenecheck_render(LIT "material m lambert rho 0.5 + phong rho 0.3 e 20\n"
                      SCENE, 1, &plain);
    ck_assert(same_bits(&none, &plain));
    ck_assert(!same_bits(&mat, &plain));
    image_free(&mat);
    image_free(&shp);
    image_free(&both);
    image_free(&none);
    image_free(&plain);
    /* bad values */
    scenecheck_refused(HEAD "material m lambert rho 0.5\n"
                       "sphere centre 0 0 0 radius 1 material m bump nope\n",
                       "t.scn:3:46:", "'bump nope': no texture of that name");
    scenecheck_refused(HEAD "texture w waves\nmaterial m lambert rho 0.5\n"
                       "sphere centre 0 0 0 radius 1 material m strength 2\n",
                       "t.scn:4:41:", "give 'bump NAME' with it");
    scenecheck_refused(HEAD "texture w waves\nmaterial m lambert rho 0.5\n"
                       "sphere centre 0 0 0 radius 1 material m "
                       "bump w strength nan\n",
                       "t.scn:4:", "");
    scenecheck_refused(HEAD "texture w waves\nmaterial m lambert rho 0.5\n"
                       "sphere centre 0 0 0 radius 1 material m "
                       "bump w strength\n",
                       "t.scn:4:", "");
    scenecheck_refused(HEAD "texture w waves\nmaterial m lambert rho 0.5\n"
                       "sphere centre 0 0 0 radius 1 material m "
                       "bump w bump w\n",
                       "t.scn:4:", "");
    /* a program without textures names the chapter */
    scene_t s;
    svet_error e;
    const char *t = HEAD "material m lambert rho 0.5\n"
                    "sphere centre 0 0 0 radius 1 material m bump w\n";
    ck_assert_int_eq(scenefile_parse_with(&s, t, strlen(t), "t.scn", NULL,
                                          NULL, &e), SVET_ERR_UNSUPPORTED);
    ck_assert_msg(strstr(e.msg, "t.scn:3:41: 'bump' on a sphere is not "
                                "supported by this program: ch. 10"),
                  "%s", e.msg);
}
END_TEST

/* --- `emit TEXTURE` ------------------------------------------------------ */

/* An emitter of 2 x 2 unit squares over y = 2, facing down: s runs along
 * x, t along z, so a checker of scale 2 gives its a to the quadrants
 * x < 0, z < 0 and x > 0, z > 0 and its b to the other two. */
#define EMITTER(emit) \
    "parallelogram c0 -1 2 -1 c1 1 2 -1 c3 -1 2 1 material m emit " emit "\n"

START_TEST(a_constant_texture_emits_the_same_bits_as_its_colour)
{
    const char *head =
        "camera position 0 0.5 4 target 0 1 0 width 16 height 12\n"
        "render spp 4 maxdepth 3 seed 5\n"
        "material m lambert rho 0.6 0.5 0.4\n"
        BALL "plane point 0 -1 0 normal 0 1 0 material m\n";
    char text[1024];
    image_t plain, tex;
    snprintf(text, sizeof text, "%s" EMITTER("3 2 1"), head);
    scenecheck_render(text, 1, &plain);
    snprintf(text, sizeof text,
             "texture k checker a 3 2 1 b 3 2 1 scale 2\n%s" EMITTER("k"),
             head);
    scenecheck_render(text, 1, &tex);
    ck_assert(same_bits(&plain, &tex));
    image_free(&tex);
    /* a texture that varies does change the image */
    snprintf(text, sizeof text,
             "texture k checker a 3 2 1 b 1 2 3 scale 2\n%s" EMITTER("k"),
             head);
    scenecheck_render(text, 2, &tex);
    ck_assert(!same_bits(&plain, &tex));
    image_free(&plain);
    image_free(&tex);
}
END_TEST

START_TEST(a_checker_emitter_seen_by_the_camera_shows_both_colours)
{
    /* looking up at the emitter from below its centre, image top = -z and
     * image right = -x; maxdepth 0 shows emission only, and at 1 sample a
     * pixel each pixel is one colour */
    const char *text =
        "camera position 0 0.5 0 target 0 2 0 up 0 0 -1 fov 60 width 16 "
        "height 16\n"
        "render spp 1 maxdepth 0 seed 1\n"
        "texture k checker a 4 1 0.5 b 0.25 0.5 2 scale 2\n"
        "material m lambert rho 0.5\n" EMITTER("k");
    image_t img;
    scenecheck_render(text, 1, &img);
    int na = 0, nb = 0;
    for (int y = 0; y < img.height; y++)
        for (int x = 0; x < img.width; x++) {
            const float *p = image_at(&img, x, y);
            bool a = p[0] == 4.0f && p[1] == 1.0f && p[2] == 0.5f;
            bool b = p[0] == 0.25f && p[1] == 0.5f && p[2] == 2.0f;
            ck_assert_msg(a || b, "pixel (%d, %d) = %g %g %g", x, y,
                          (double)p[0], (double)p[1], (double)p[2]);
            /* the quadrant's colour, away from the seams */
            if ((x < 6 || x > 9) && (y < 6 || y > 9)) {
                bool left = x < 8, top = y < 8; /* x > 0, z < 0 */
                ck_assert_msg(left == top ? b : a, "pixel (%d, %d)", x, y);
            }
            na += a;
            nb += b;
        }
    ck_assert_int_gt(na, 0);
    ck_assert_int_gt(nb, 0);
    image_free(&img);
    /* a name that is no texture, and a program without textures */
    scenecheck_refused(HEAD "material m lambert rho 0.5\n" EMITTER("glow"),
                       "t.scn:3:62:", "neither a colour nor a texture");
    scene_t s;
    svet_error e;
    const char *t2 = HEAD "material m lambert rho 0.5\n" EMITTER("glow");
    ck_assert_int_eq(scenefile_parse(&s, t2, strlen(t2), "t.scn", NULL, &e),
                     SVET_ERR_PARSE);
    ck_assert_msg(strstr(e.msg, "t.scn:3:62: expected a number, got 'glow'"),
                  "%s", e.msg);
}
END_TEST

/* The floor under the emitter, seen from between the two, lit by it
 * alone: light sampling only (`nee`, no BSDF hits on the emitter), so
 * that each pixel's estimate is the emitter's light reflected once as
 * light_sample() finds it. */
static void floor_under(const char *emitters, image_t *img)
{
    char text[2048];
    snprintf(text, sizeof text,
             "camera position 0 1 0 target 0 0 0 up 0 0 -1 fov 60 width 32 "
             "height 32\n"
             "render spp 256 maxdepth 1 seed 11 integrator nee\n"
             "texture k checker a 8 4 2 b 0.5 1 0.25 scale 2\n"
             "material m lambert rho 0.7\n"
             "plane point 0 0 0 normal 0 1 0 material m\n%s", emitters);
    scenecheck_render(text, 0, img);
}

START_TEST(a_textured_emitter_lights_as_its_squares_do)
{
    /* The same emitter twice: one parallelogram reading the checker, and
     * four of one colour each. Both estimates are unbiased, each pixel's
     * with its own noise; over each 8 x 8 block the mean difference must
     * lie within 4 standard errors of zero, the standard error from the
     * block's own spread of differences. The floor's light is far from
     * uniform (the a squares are 16 times brighter in red than the b):
     * light samples that read the emitter's mean instead of the texture
     * at the sampled point move a block by 8 standard errors. */
    image_t one, four;
    floor_under(EMITTER("k"), &one);
    floor_under(
        "parallelogram c0 -1 2 -1 c1 0 2 -1 c3 -1 2 0 material m emit 8 4 2\n"
        "parallelogram c0 0 2 -1 c1 1 2 -1 c3 0 2 0 material m emit 0.5 1 0.25\n"
        "parallelogram c0 -1 2 0 c1 0 2 0 c3 -1 2 1 material m emit 0.5 1 0.25\n"
        "parallelogram c0 0 2 0 c1 1 2 0 c3 0 2 1 material m emit 8 4 2\n",
        &four);
    double spread = 0;
    for (int by = 0; by < 4; by++)
        for (int bx = 0; bx < 4; bx++)
            for (int k = 0; k < 3; k++) {
                double sum = 0, sum2 = 0, level = 0;
                int n = 0;
                for (int y = by * 8; y < by * 8 + 8; y++)
                    for (int x = bx * 8; x < bx * 8 + 8; x++) {
                        double a = image_at(&one, x, y)[k];
                        double b = image_at(&four, x, y)[k];
                        sum += a - b;
                        sum2 += (a - b) * (a - b);
                        level += b;
                        n++;
                    }
                double mean = sum / n;
                double var = (sum2 - sum * sum / n) / (n - 1);
                double se = sqrt(var / n);
                ck_assert_msg(fabs(mean) <= 4 * se,
                              "block (%d, %d) channel %d: %g +- %g", bx, by,
                              k, mean, se);
                spread = fmax(spread, se / (level / n));
            }
    /* the test has power: the noise is small beside the light's level */
    ck_assert_msg(spread < 0.05, "relative standard error %g", spread);
    /* and the floor does show the squares: looking down with image top
     * = -z, image right is +x, so the top left corner lies under an a
     * square, brighter in red than the top right one under a b square */
    ck_assert(image_at(&one, 4, 4)[0] > image_at(&one, 27, 4)[0]);
    image_free(&one);
    image_free(&four);
}
END_TEST

/* The grazing checkerboard: a plane of a 256 x 256 checker image of 16
 * squares a side, seen at 5 degrees above its horizon, lit evenly by a
 * uniform environment (the image is the texture times 1/2 of it: no
 * noise but the pixel's sampling). */
static const char *checker_scene(const char *png, const char *filter,
                                 long spp)
{
    static char text[1024];
    snprintf(text, sizeof text,
             "camera position 0 0.35 4 target 0 0 -4 up 0 1 0 fov 40 "
             "width 64 height 32\n"
             "render spp %ld maxdepth 1 seed 3 integrator direct\n"
             "environment radiance 1\n"
             "texture c image file \"%s\" data filter %s scale 4\n"
             "material m lambert rho c\n"
             "parallelogram c0 -8 0 8 c1 8 0 8 c3 -8 0 -40 material m\n",
             spp, png, filter);
    return text;
}

static double rmse(const image_t *a, const image_t *b)
{
    double s = 0;
    size_t n = (size_t)a->width * (size_t)a->height;
    for (size_t i = 0; i < n * (size_t)a->channels; i++) {
        double d = (double)a->px[i] - (double)b->px[i];
        s += d * d;
    }
    return sqrt(s / (double)(n * (size_t)a->channels));
}

START_TEST(the_grazing_checkerboard_is_nearer_the_reference_trilinear)
{
    image_t img;
    ck_assert_int_eq(image_alloc(&img, 256, 256, 3, NULL), SVET_OK);
    for (int y = 0; y < 256; y++)
        for (int x = 0; x < 256; x++) {
            float v = ((x / 16 + y / 16) % 2) ? 0.9f : 0.1f;
            float *p = image_at(&img, x, y);
            p[0] = p[1] = p[2] = v;
        }
    const char *png = imgtest_path("checker.png");
    svet_error e;
    ck_assert_int_eq(pngio_write(png, &img, 16, &e), SVET_OK);
    image_free(&img);
    image_t ref, nearest, tri;
    /* the reference: 1024 samples a pixel of the finest texels */
    scenecheck_render(checker_scene(png, "bilinear", 1024), 0, &ref);
    scenecheck_render(checker_scene(png, "nearest", 1), 0, &nearest);
    scenecheck_render(checker_scene(png, "trilinear", 1), 0, &tri);
    double en = rmse(&nearest, &ref), et = rmse(&tri, &ref);
    /* Fixed seeds make both numbers exact for the build; the margin is
     * the claim: with one sample a pixel the nearest texel aliases, its
     * error about the checker's contrast times the fraction of pixels
     * that span many squares, while the mip map's blur leaves only the
     * bias of an isotropic filter; the reference's own noise (1024
     * samples: 1/32 of a single sample's) is far below both. */
    ck_assert_msg(et < 0.8 * en, "trilinear %g, nearest %g", et, en);
    image_free(&ref);
    image_free(&nearest);
    image_free(&tri);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("texpart");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, every_kind_of_texture_parses);
    tcase_add_test(tc, bad_texture_lines_name_file_line_and_column);
    tcase_add_test(tc, a_program_without_textures_refuses_their_names);
    tcase_add_test(tc, bad_texture_files_are_refused_with_the_readers_reason);
    tcase_add_test(tc, a_zero_bump_and_a_constant_texture_render_the_same_bits);
    tcase_add_test(tc, a_bumped_shape_shades_as_its_bumped_material);
    tcase_add_test(tc, the_grazing_checkerboard_is_nearer_the_reference_trilinear);
    tcase_add_test(tc, a_constant_texture_emits_the_same_bits_as_its_colour);
    tcase_add_test(tc, a_checker_emitter_seen_by_the_camera_shows_both_colours);
    tcase_add_test(tc, a_textured_emitter_lights_as_its_squares_do);
    suite_add_tcase(s, tc);
    return s;
}
