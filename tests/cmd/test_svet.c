/*
 * test_svet.c - the svet command itself (cmd/svet.c, cmd/cmd_diff.c): help,
 * exit codes and `svet diff` on files made here; inputs beyond the pixel
 * limit, inputs that are not regular files, and a full disk; outputs that
 * are inputs; and what `svet render` says about a scene (its warnings,
 * --strict); the integrator and the clock svet converge's CSV names. The command is the one built beside this suite: <build>/svet
 * for <build>/tests/test_svet, so `make test` (which builds it first)
 * tests the matching REAL.
 */
#include "testutil.h"
#include "cmdtest.h"
#include "imgtest.h"
#include "io/imageio.h"
#include "io/netpbm.h"
#include "io/exrio.h"
#include "colour/colour.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static int run(char *out, size_t cap, const char *args)
{
    return cmdtest_run(out, cap, args);
}

/* The value printed on the line "name value". */
static double value_of(const char *out, const char *name)
{
    char key[64];
    snprintf(key, sizeof key, "\n%s ", name);
    const char *p = strstr(out, key);
    ck_assert_msg(p != NULL, "no '%s' in:\n%s", name, out);
    return strtod(p + strlen(key), NULL);
}

static char out[16384];

/* Run `svet ARGS` (ARGS made by printf from fmt), killed after a minute
 * should it hang, and check its exit code and that its output holds
 * `words` (NULL: anything). */
static void CK_ATTRIBUTE_FORMAT(printf, 3, 4)
expect(int rc, const char *words, const char *fmt, ...)
{
    char args[4096];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(args, sizeof args, fmt, ap);
    va_end(ap);
    int got = cmdtest_run_timed(out, sizeof out, 60, args);
    ck_assert_msg(got == rc, "svet %s: exit %d, not %d:\n%s", args, got, rc,
                  out);
    ck_assert_msg(!words || strstr(out, words), "svet %s: no '%s' in:\n%s",
                  args, words, out);
}

START_TEST(help_and_usage_errors_have_their_exit_codes)
{
    ck_assert_int_eq(run(out, sizeof out, "--help"), 0);
    ck_assert_ptr_nonnull(strstr(out, "exit codes"));
    ck_assert_ptr_nonnull(strstr(out, "diff"));
    ck_assert_ptr_nonnull(strstr(out, "render"));
    ck_assert_int_eq(run(out, sizeof out, "help diff"), 0);
    ck_assert_ptr_nonnull(strstr(out, "usage: svet diff"));
    ck_assert_int_eq(run(out, sizeof out, "diff --help"), 0);
    ck_assert_int_eq(run(out, sizeof out, ""), 1);
    ck_assert_int_eq(run(out, sizeof out, "frobnicate"), 1);
    ck_assert_ptr_nonnull(strstr(out, "unknown command 'frobnicate'"));
    ck_assert_int_eq(run(out, sizeof out, "help frobnicate"), 1);
    ck_assert_int_eq(run(out, sizeof out, "diff onlyone.exr"), 1);
    ck_assert_int_eq(run(out, sizeof out, "diff a b c"), 1);
    ck_assert_int_eq(run(out, sizeof out, "diff a b --metric rsme"), 1);
    ck_assert_ptr_nonnull(strstr(out, "unknown metric 'rsme'"));
    ck_assert_int_eq(run(out, sizeof out, "diff a b --peak -1"), 1);
    ck_assert_int_eq(run(out, sizeof out, "diff a b --error-image e.png"), 1);
    ck_assert_int_eq(run(out, sizeof out, "diff a b --bogus 1"), 1);
    ck_assert_int_eq(run(out, sizeof out, "diff a b --eps"), 1);
}
END_TEST

/* Two files: B a test image, A = B + d in every value (exact: B on a grid
 * of 2^-8, d = 2^-6). */
static void make_pair(const char *a, const char *b, float d)
{
    image_t ib, ia;
    svet_error err;
    imgtest_hdr_image(&ib, 24, 16, 3);
    for (size_t i = 0; i < 24 * 16 * 3; i++)
        ib.px[i] = floorf(ib.px[i] * 256.0f) / 256.0f;
    ck_assert_int_eq(image_copy(&ia, &ib, &err), SVET_OK);
    for (size_t i = 0; i < 24 * 16 * 3; i++)
        ia.px[i] += d;
    ck_assert_msg(imageio_write(a, &ia, &err) == SVET_OK, "%s", err.msg);
    ck_assert_msg(imageio_write(b, &ib, &err) == SVET_OK, "%s", err.msg);
    image_free(&ia);
    image_free(&ib);
}

START_TEST(diff_prints_the_metrics_of_a_known_difference)
{
    char a[1024], b[1024], args[4096];
    snprintf(a, sizeof a, "%s", imgtest_path("a.exr"));
    snprintf(b, sizeof b, "%s", imgtest_path("b.pfm"));
    make_pair(a, b, 0.015625f);
    snprintf(args, sizeof args, "diff '%s' '%s'", a, b);
    ck_assert_int_eq(run(out, sizeof out, args), 0);
    /* every value off by 2^-6: mse 2^-12, rmse = mae = max = 2^-6 */
    ck_assert_rel(value_of(out, "mse"), 0x1p-12, 1e-8, 0);
    ck_assert_rel(value_of(out, "rmse"), 0x1p-6, 1e-8, 0);
    ck_assert_rel(value_of(out, "mae"), 0x1p-6, 1e-8, 0);
    ck_assert_rel(value_of(out, "max"), 0x1p-6, 1e-8, 0);
    ck_assert_ptr_nonnull(strstr(out, "(EXR, 24 x 16)"));
    ck_assert_ptr_nonnull(strstr(out, "(PFM, 24 x 16)"));
    /* the metric list and the threshold: exit 5 beyond it */
    snprintf(args, sizeof args, "diff '%s' '%s' --metric rmse,psnr "
             "--fail-above 0.01", a, b);
    ck_assert_int_eq(run(out, sizeof out, args), 5);
    ck_assert_ptr_null(strstr(out, "\nmae "));
    snprintf(args, sizeof args, "diff '%s' '%s' --metric rmse "
             "--fail-above 0.02", a, b);
    ck_assert_int_eq(run(out, sizeof out, args), 0);
    /* psnr with peak 1: 20 log10(64) = 36.12 dB; below 40 fails */
    snprintf(args, sizeof args, "diff '%s' '%s' --metric psnr --peak 1 "
             "--fail-above 40", a, b);
    ck_assert_int_eq(run(out, sizeof out, args), 5);
    ck_assert_rel(value_of(out, "psnr"), 20 * log10(64.0), 1e-8, 0);
    /* identical: zero and infinity */
    snprintf(args, sizeof args, "diff '%s' '%s'", b, b);
    ck_assert_int_eq(run(out, sizeof out, args), 0);
    ck_assert(value_of(out, "mse") == 0);
    ck_assert_ptr_nonnull(strstr(out, "\npsnr inf"));
}
END_TEST

START_TEST(diff_writes_an_error_image)
{
    char a[1024], b[1024], e[1024], args[4096];
    snprintf(a, sizeof a, "%s", imgtest_path("a.pfm"));
    snprintf(b, sizeof b, "%s", imgtest_path("b.exr"));
    snprintf(e, sizeof e, "%s", imgtest_path("err.exr"));
    make_pair(a, b, 0.25f);
    snprintf(args, sizeof args, "diff '%s' '%s' --error-image '%s'", a, b, e);
    ck_assert_int_eq(run(out, sizeof out, args), 0);
    image_t img;
    svet_error err;
    ck_assert_int_eq(exrio_read(e, &img, &err), SVET_OK);
    for (size_t i = 0; i < 24 * 16 * 3; i++)
        ck_assert(img.px[i] == 0.25f);
    image_free(&img);
    /* an error image that cannot be written: exit 3, metrics printed */
    snprintf(args, sizeof args, "diff '%s' '%s' --error-image "
             "/nonexistent-svet-dir/e.exr", a, b);
    ck_assert_int_eq(run(out, sizeof out, args), 3);
    ck_assert_ptr_nonnull(strstr(out, "/nonexistent-svet-dir/e.exr"));
}
END_TEST

START_TEST(diff_decodes_a_png_compared_with_a_linear_image)
{
    /* a PNG of sRGB codes against the EXR of their linear values: the
     * difference is only the 8-bit quantisation */
    image_t lin, enc;
    svet_error err;
    imgtest_hdr_image(&lin, 20, 10, 3);
    for (size_t i = 0; i < 20 * 10 * 3; i++)
        lin.px[i] = fminf(lin.px[i], 1.0f);
    ck_assert_int_eq(image_copy(&enc, &lin, &err), SVET_OK);
    for (size_t i = 0; i < 20 * 10 * 3; i++)
        enc.px[i] = (float)colour_srgb_encode((real)enc.px[i]);
    char a[1024], b[1024], args[4096];
    snprintf(a, sizeof a, "%s", imgtest_path("enc.png"));
    snprintf(b, sizeof b, "%s", imgtest_path("lin.exr"));
    ck_assert_int_eq(imageio_write(b, &lin, &err), SVET_OK);
    ck_assert_int_eq(imageio_write(a, &enc, &err), SVET_OK); /* 8 bits */
    snprintf(args, sizeof args, "diff '%s' '%s' --metric max", a, b);
    ck_assert_int_eq(run(out, sizeof out, args), 0);
    ck_assert_ptr_nonnull(strstr(out, "decoded with sRGB"));
    /* an 8-bit code is within half a step, 1/510, of the encoded value;
     * the decoding curve's slope is at most 2.4 / 1.055 (at code 1), so
     * the linear values differ by less than 2.4 / 510 */
    ck_assert(value_of(out, "max") < 2.4 / 510);
    image_free(&lin);
    image_free(&enc);
}
END_TEST

START_TEST(diff_refuses_bad_inputs_with_exit_code_2)
{
    char a[1024], b[1024], args[4096];
    snprintf(a, sizeof a, "%s", imgtest_path("a.pfm"));
    snprintf(b, sizeof b, "%s", imgtest_path("b.pfm"));
    make_pair(a, b, 0.5f);
    image_t small;
    svet_error err;
    imgtest_hdr_image(&small, 5, 5, 3);
    ck_assert_int_eq(netpbm_write_pfm(b, &small, &err), SVET_OK);
    image_free(&small);
    snprintf(args, sizeof args, "diff '%s' '%s'", a, b);
    ck_assert_int_eq(run(out, sizeof out, args), 2);
    ck_assert_ptr_nonnull(strstr(out, "sizes differ"));
    snprintf(args, sizeof args, "diff '%s' '%s'", a, imgtest_path("none.exr"));
    ck_assert_int_eq(run(out, sizeof out, args), 2);
    ck_assert_ptr_nonnull(strstr(out, "cannot open"));
    imgtest_write_bytes(b, "PF\n3 3\n-1\n", 10);
    snprintf(args, sizeof args, "diff '%s' '%s'", a, b);
    ck_assert_int_eq(run(out, sizeof out, args), 2);
    ck_assert_ptr_nonnull(strstr(out, "truncated"));
}
END_TEST

START_TEST(images_beyond_the_pixel_limit_are_refused)
{
    /* A header claiming 16384 x 16384 pixels (as a 783 KB PNG can) made
     * svet diff allocate gigabytes; the limit is checked first, and
     * --max-pixels or SVET_MAX_PIXELS move it. */
    char a[1024], b[1024], big[1024];
    snprintf(a, sizeof a, "%s", imgtest_path("a.pfm"));
    snprintf(b, sizeof b, "%s", imgtest_path("b.pfm"));
    make_pair(a, b, 0.5f); /* 24 x 16 = 384 pixels */
    snprintf(big, sizeof big, "%s", imgtest_path("big.pfm"));
    imgtest_write_bytes(big, "PF\n16384 16384\n-1\n0123456789ab", 30);
    expect(2, "exceeds the limit of 67108864", "diff '%s' '%s'", big, a);
    expect(2, "exceeds the limit of 383 pixels",
           "diff '%s' '%s' --max-pixels 383", a, b);
    expect(0, NULL, "diff '%s' '%s' --max-pixels 384", a, b);
    expect(1, "--max-pixels 0", "diff '%s' '%s' --max-pixels 0", a, b);
    /* the environment, when the option is not given */
    ck_assert_int_eq(setenv("SVET_MAX_PIXELS", "383", 1), 0);
    expect(2, "limit of 383", "diff '%s' '%s'", a, b);
    expect(0, NULL, "diff '%s' '%s' --max-pixels 400", a, b);
    ck_assert_int_eq(setenv("SVET_MAX_PIXELS", "lots", 1), 0);
    expect(1, "SVET_MAX_PIXELS lots", "diff '%s' '%s'", a, b);
    unsetenv("SVET_MAX_PIXELS");
    /* svet converge reads its images with the same limit */
    image_t img;
    svet_error err;
    imgtest_hdr_image(&img, 12, 10, 3);
    snprintf(a, sizeof a, "%s", imgtest_path("img.exr"));
    snprintf(b, sizeof b, "%s", imgtest_path("ref.exr"));
    ck_assert_int_eq(exrio_write(a, &img, EXRIO_FLOAT, EXRIO_ZIP, &err),
                     SVET_OK);
    ck_assert_int_eq(exrio_write(b, &img, EXRIO_FLOAT, EXRIO_ZIP, &err),
                     SVET_OK);
    image_free(&img);
    expect(2, "exceeds the limit of 100 pixels",
           "converge --ztest '%s' --spp 4 --ref '%s' --max-pixels 100", a, b);
}
END_TEST

START_TEST(inputs_that_are_not_regular_files_are_refused_at_once)
{
    /* A FIFO as the scene or as an image once blocked svet for ever; a
     * directory was "an empty file". */
    char a[1024], fifo[1024], dir[1024];
    snprintf(a, sizeof a, "%s", imgtest_path("a.pfm"));
    make_pair(a, imgtest_path("b.pfm"), 0.5f);
    imgtest_special_files(fifo, dir, sizeof fifo);
    expect(2, "is a FIFO", "render '%s' -q -o '%s'", fifo,
           imgtest_path("r.exr"));
    expect(2, "is a FIFO", "diff '%s' '%s'", fifo, a);
    expect(2, "is a directory", "diff '%s' '%s'", a, dir);
}
END_TEST

START_TEST(a_full_disk_fails_with_exit_3_and_keeps_the_old_outputs)
{
    /* On a full disk the EXR header cannot be written; that once hung
     * svet render (also with --checkpoint) and svet diff --error-image
     * for ever, leaving an empty temporary file. */
    const char *disk = imgtest_small_disk(128);
    if (!disk)
        return;
    char a[1024], b[1024], exr[1100], png[1100], e[1100];
    snprintf(a, sizeof a, "%s", imgtest_path("a.pfm"));
    snprintf(b, sizeof b, "%s", imgtest_path("b.pfm"));
    make_pair(a, b, 0.25f);
    snprintf(exr, sizeof exr, "%s/r.exr", disk);
    snprintf(png, sizeof png, "%s/r.png", disk);
    snprintf(e, sizeof e, "%s/e.exr", disk);
    static const char old[] = "an earlier output";
    const char *const outputs[] = { exr, png, e };
    for (int i = 0; i < 3; i++)
        imgtest_write_bytes(outputs[i], old, sizeof old);
    imgtest_fill_disk(disk);
    const char *const renders[] = { "", " --checkpoint --passes 2" };
    for (int i = 0; i < 2; i++)
        expect(3, exr, "render scenes/cbox.scn -q --spp 2 "
               "--set resolution=8x8 -o '%s'%s", exr, renders[i]);
    expect(3, e, "diff '%s' '%s' --error-image '%s'", a, b, e);
    for (int i = 0; i < 3; i++) {
        ck_assert_msg(imgtest_file_is(outputs[i], old, sizeof old),
                      "%s was changed", outputs[i]);
        ck_assert_int_eq(imgtest_count_temps(outputs[i]), 0);
    }
}
END_TEST

/* An output that is an input, under any name, is refused with exit 1
 * before anything is read or written; the input stays as it was. */
START_TEST(an_output_that_is_an_input_is_refused)
{
    char a[1024], b[1024], args[8192];
    snprintf(a, sizeof a, "%s", imgtest_path("in-a.exr"));
    snprintf(b, sizeof b, "%s", imgtest_path("in-b.pfm"));
    make_pair(a, b, 0.25f);
    image_t before;
    svet_error err;
    ck_assert_int_eq(exrio_read(a, &before, &err), SVET_OK);
    /* svet diff --error-image A: A itself, then through a symbolic link */
    snprintf(args, sizeof args, "diff '%s' '%s' --error-image '%s'", a, b, a);
    ck_assert_int_eq(run(out, sizeof out, args), 1);
    ck_assert_msg(strstr(out, "is the same file as the image A"), "%s", out);
    char sym[1100];
    snprintf(sym, sizeof sym, "%s.link.exr", a);
    ck_assert_int_eq(symlink(a, sym), 0);
    snprintf(args, sizeof args, "diff '%s' '%s' --error-image '%s'", b, a,
             sym);
    ck_assert_int_eq(run(out, sizeof out, args), 1);
    ck_assert_msg(strstr(out, "is the same file as the reference B"), "%s",
                  out);
    /* svet converge --ztest --pvalue REF */
    snprintf(args, sizeof args, "converge --ztest '%s' --var '%s' --spp 4 "
             "--ref '%s' --ref-var '%s' --pvalue '%s'", a, a, a, a, sym);
    ck_assert_int_eq(run(out, sizeof out, args), 1);
    ck_assert_msg(strstr(out, "is the same file as"), "%s", out);
    /* svet converge: the CSV it would write is the reference */
    char dir[1024], ref[1100];
    snprintf(dir, sizeof dir, "%s", imgtest_path("conv"));
    ck_assert_int_eq(mkdir(dir, 0777), 0);
    snprintf(ref, sizeof ref, "%s/m.csv", dir);
    ck_assert_int_eq(exrio_write(ref, &before, EXRIO_FLOAT, EXRIO_ZIP, &err),
                     SVET_OK);
    snprintf(args, sizeof args, "converge tests/data/scene/mesh.scn --ref "
             "'%s' --out '%s' --label m --no-plot -q", ref, dir);
    ck_assert_int_eq(run(out, sizeof out, args), 1);
    ck_assert_msg(strstr(out, "the CSV output") &&
                  strstr(out, "is the same file as the reference"), "%s",
                  out);
    image_t after;
    ck_assert_int_eq(exrio_read(ref, &after, &err), SVET_OK);
    image_free(&after);
    ck_assert_int_eq(exrio_read(a, &after, &err), SVET_OK);
    for (size_t i = 0; i < 24 * 16 * 3; i++)
        ck_assert(after.px[i] == before.px[i]);
    image_free(&after);
    image_free(&before);
}
END_TEST

/* --- what svet render says about the scene ---------------------------- */

/* Write text to the file name in the scratch directory; its path in
 * path. */
static void write_text(char *path, size_t cap, const char *name,
                       const char *text)
{
    snprintf(path, cap, "%s", imgtest_path(name));
    imgtest_write_bytes(path, text, strlen(text));
}

/* Write the scene `name` in the scratch directory (its path in scn): a
 * small camera, 1 spp and material m, then objects; render it to exr
 * (-q, and flags) and return the exit code, what was printed in out. */
static int render_scene(char *scn, size_t cap, const char *name,
                        const char *objects, const char *exr,
                        const char *flags)
{
    char text[1024], args[4096];
    snprintf(text, sizeof text,
             "camera position 0 0 3 target 0 0 0 width 8 height 8\n"
             "render spp 1\nmaterial m lambert rho 0.5\n%s", objects);
    write_text(scn, cap, name, text);
    snprintf(args, sizeof args, "render '%s' -o '%s' -q %s", scn, exr, flags);
    return run(out, sizeof out, args);
}

/* out holds the printf-style text. */
#if defined(__GNUC__)
__attribute__((format(printf, 1, 2)))
#endif
static void expect_printed(const char *fmt, ...)
{
    char want[2048];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(want, sizeof want, fmt, ap);
    va_end(ap);
    ck_assert_msg(strstr(out, want), "no '%s' in:\n%s", want, out);
}

#define MESH_LIT "mesh file %s material m\n" \
                 "light point position 0 0 2 intensity 1\n"

START_TEST(render_prints_the_mesh_warnings_and_strict_refuses_them)
{
    char obj[1024], scn[1024], exr[1024], objects[1200];
    /* two unknown statements, then ten more: eight shown, then a count */
    char text[1024] = "v 0 0 0\nvv 1 1 1\nv 1 0 0\nv 0 1 0\nff 2 4 3\n"
                      "f 1 2 3\n";
    for (int i = 0; i < 10; i++)
        strcat(text, "xx\n");
    write_text(obj, sizeof obj, "warn.obj", text);
    snprintf(exr, sizeof exr, "%s", imgtest_path("warn.exr"));
    snprintf(objects, sizeof objects, MESH_LIT, "warn.obj");
    ck_assert_int_eq(render_scene(scn, sizeof scn, "warn.scn", objects, exr,
                                  ""), 0);
    expect_printed("svet render: %s:4:11: %s:2:1: warning: unknown "
                   "statement 'vv' skipped\n", scn, obj);
    expect_printed("%s:5:1: warning: unknown statement 'ff' skipped", obj);
    expect_printed("svet render: %s: 4 more warnings\n", scn);
    ck_assert_int_eq(access(exr, F_OK), 0);
    /* --strict: the same warnings, then exit 2 and no image */
    unlink(exr);
    ck_assert_int_eq(render_scene(scn, sizeof scn, "warn.scn", objects, exr,
                                  "--strict"), 2);
    expect_printed("svet render: %s: 12 warnings, and --strict makes "
                   "warnings errors", scn);
    ck_assert_int_ne(access(exr, F_OK), 0);
    /* a clean mesh: nothing said, strict or not */
    write_text(obj, sizeof obj, "clean.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
               "f 1 2 3\n");
    snprintf(objects, sizeof objects, MESH_LIT, "clean.obj");
    ck_assert_int_eq(render_scene(scn, sizeof scn, "clean.scn", objects, exr,
                                  "--strict"), 0);
    ck_assert_str_eq(out, "");
}
END_TEST

START_TEST(render_refuses_empty_and_too_bright_scenes_and_warns_of_dark)
{
    char scn[1024], exr[1024], args[4096];
    snprintf(exr, sizeof exr, "%s", imgtest_path("dark.exr"));
    write_text(scn, sizeof scn, "empty.scn", "# nothing here\n\n");
    snprintf(args, sizeof args, "render '%s' -o '%s' -q", scn, exr);
    ck_assert_int_eq(run(out, sizeof out, args), 2);
    expect_printed("svet render: %s: no statements", scn);
    ck_assert_int_ne(access(exr, F_OK), 0);
    /* no light: rendered (black), with the warning */
    ck_assert_int_eq(render_scene(scn, sizeof scn, "dark.scn",
                                  "sphere centre 0 0 0 radius 1 material m\n",
                                  exr, ""), 0);
    expect_printed("svet render: %s: warning: nothing emits light", scn);
    ck_assert_int_eq(access(exr, F_OK), 0);
    /* a light whose products overflow is refused where it is written,
     * and the image of the dark scene stays */
    ck_assert_int_eq(render_scene(scn, sizeof scn, "bright.scn",
                                  "sphere centre 0 0 0 radius 1 material m "
                                  "emit 3e38\n", exr, ""), 2);
    expect_printed("svet render: %s:4:41: the radiance 'emit' 3e+38 is "
                   "brighter than svet renders", scn);
    ck_assert_int_eq(access(exr, F_OK), 0);
}
END_TEST

/* The text of file path (malloc'ed). */
static char *file_text(const char *path)
{
    unsigned char *bytes;
    size_t n = imgtest_read_bytes(path, &bytes);
    char *t = malloc(n + 1);
    ck_assert_ptr_nonnull(t);
    memcpy(t, bytes, n);
    t[n] = '\0';
    free(bytes);
    return t;
}

/* Write the scene `text` to NAME.scn and render it to NAME-ref.exr, both
 * in the test's directory: their paths to scn and ref, the directory to
 * dir (each of 1024 bytes). */
static void scene_and_ref(const char *name, const char *text, char *scn,
                          char *ref, char *dir)
{
    snprintf(scn, 1024, "%s/%s.scn", imgtest_path("."), name);
    snprintf(ref, 1024, "%s/%s-ref.exr", imgtest_path("."), name);
    snprintf(dir, 1024, "%s", imgtest_path("."));
    imgtest_write_bytes(scn, text, strlen(text));
    expect(0, NULL, "render '%s' -o '%s' -q", scn, ref);
}

/* svet converge's CSV names the scene's rendering method in its header
 * (`integrator NAME`): a part's method (volsingle, volpath) as the core's
 * integrators, also when --set changes it. */
START_TEST(the_converge_csv_names_the_scenes_integrator)
{
    char scn[1024], ref[1024], dir[1024], csv[1100], args[4096];
    scene_and_ref("fog",
        "camera position 0 0 3 target 0 0 0 fov 30 width 4 height 4\n"
        "render spp 2 maxdepth 2 integrator volsingle seed 3\n"
        "material black lambert rho 0\n"
        "environment radiance 1\n"
        "medium fog homogeneous sigma_a 0.5 sigma_s 0.5\n"
        "sphere centre 0 0 0 radius 1 material black medium fog invisible\n",
        scn, ref, dir);
    const char *sets[3][2] = { { "", "integrator volsingle," },
                               { "--set integrator=volpath",
                                 "integrator volpath," },
                               { "--set integrator=path",
                                 "integrator path," } };
    for (int i = 0; i < 3; i++) {
        snprintf(args, sizeof args, "converge '%s' --ref '%s' --out '%s' "
                 "--label m%d --no-plot -q %s", scn, ref, dir, i, sets[i][0]);
        expect(0, NULL, "%s", args);
        snprintf(csv, sizeof csv, "%s/m%d.csv", dir, i);
        char *t = file_text(csv);
        ck_assert_msg(strstr(t, sets[i][1]), "no '%s' in:\n%s", sets[i][1],
                      t);
        free(t);
    }
}
END_TEST

/* svet converge --clock: wall or cpu, anything else refused as any bad
 * value is; the CSV's seconds column names the clock, and --report refuses
 * to put series of two clocks on one time axis. */
START_TEST(converge_clock_is_named_in_the_csv_and_refused_when_mixed)
{
    char scn[1024], ref[1024], dir[1024], csv[2][1100];
    scene_and_ref("clock",
        "camera position 0 0 3 target 0 0 0 fov 30 width 4 height 4\n"
        "render spp 4 maxdepth 2 seed 3\n"
        "material grey lambert rho 0.5\n"
        "environment radiance 1\n"
        "sphere centre 0 0 0 radius 1 material grey\n", scn, ref, dir);
    expect(1, "svet converge: bad value 'gpu' for --clock\n",
           "converge '%s' --ref '%s' --clock gpu", scn, ref);
    expect(1, NULL, "converge '%s' --ref '%s' --clock", scn, ref);
    const char *clock[2] = { "wall", "cpu" };
    const char *head[2] = { "\nmethod,spp,seconds,rays,",
                            "\nmethod,spp,cpu_seconds,rays," };
    const char *says[2] = { "seconds = wall-clock render set-up",
                            "cpu_seconds = CPU time (all threads)" };
    for (int i = 0; i < 2; i++) {
        expect(0, NULL, "converge '%s' --ref '%s' --out '%s' --label c%s "
               "--clock %s --time-list 0.001,0.002 --no-plot -q", scn, ref,
               dir, clock[i], clock[i]);
        snprintf(csv[i], sizeof csv[i], "%s/c%s.csv", dir, clock[i]);
        char *t = file_text(csv[i]);
        ck_assert_msg(strstr(t, head[i]) && strstr(t, says[i]),
                      "--clock %s:\n%s", clock[i], t);
        free(t);
    }
    expect(0, "| rays/CPU-s |", "converge --report '%s'", csv[1]);
    expect(0, "Times on the cpu clock", "converge --report '%s'", csv[1]);
    expect(0, "Times on the wall clock", "converge --report '%s'", csv[0]);
    expect(2, "by the cpu clock", "converge --report '%s' '%s'", csv[0],
           csv[1]);
}
END_TEST

/* A series whose first point already reaches the baseline's error: the
 * report gives the first point's time as a bound ("<= 0.5", speed-up
 * ">= 2") instead of the 1/t law read backwards (0.00125 s, 800 times),
 * which would leave out a method's fixed cost. Hand-made, unbiased
 * series: the baseline's MSE 0.04 at 1 s, so E = 0.2 at T = 1. */
#define CONV_ROW(m, spp, t, v)                                            \
    m "," #spp "," #t ",100," "0,0," #v "," #v ",0,0,0,1,"                 \
    #v "," #v ",0,0,0,1\n"
START_TEST(converge_report_bounds_a_time_before_the_first_point)
{
    const char *head = "method,spp,seconds,rays,rmse,psnr,mse,variance,"
                       "ref_variance,rmse_noref,bias2,efficiency,relmse,"
                       "relvariance,ref_relvariance,relrmse_noref,relbias2,"
                       "relefficiency\n";
    char a[1024], b[1024], text[1024];
    snprintf(text, sizeof text, "%s" CONV_ROW("slow", 1, 1, 0.04)
             CONV_ROW("slow", 4, 4, 0.01), head);
    write_text(a, sizeof a, "slow.csv", text);
    snprintf(text, sizeof text, "%s" CONV_ROW("fast", 1, 0.5, 0.0001)
             CONV_ROW("fast", 2, 1, 0.00005), head);
    write_text(b, sizeof b, "fast.csv", text);
    expect(0, "| fast | 2 | 0.00707 | <= 0.5 s | >= 2.00 |",
           "converge --report '%s' '%s'", a, b);
    expect(0, "| slow | 4 | 0.2 | 1 s | 1.00 |", "converge --report '%s' '%s'",
           a, b);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("svet");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 30);
    tcase_add_test(tc, help_and_usage_errors_have_their_exit_codes);
    tcase_add_test(tc, converge_report_bounds_a_time_before_the_first_point);
    tcase_add_test(tc, diff_prints_the_metrics_of_a_known_difference);
    tcase_add_test(tc, diff_writes_an_error_image);
    tcase_add_test(tc, diff_decodes_a_png_compared_with_a_linear_image);
    tcase_add_test(tc, diff_refuses_bad_inputs_with_exit_code_2);
    tcase_add_test(tc, images_beyond_the_pixel_limit_are_refused);
    tcase_add_test(tc, inputs_that_are_not_regular_files_are_refused_at_once);
    tcase_add_test(tc, a_full_disk_fails_with_exit_3_and_keeps_the_old_outputs);
    tcase_add_test(tc, an_output_that_is_an_input_is_refused);
    tcase_add_test(
        tc, render_prints_the_mesh_warnings_and_strict_refuses_them);
    tcase_add_test(
        tc, render_refuses_empty_and_too_bright_scenes_and_warns_of_dark);
    tcase_add_test(tc, the_converge_csv_names_the_scenes_integrator);
    tcase_add_test(tc,
                   converge_clock_is_named_in_the_csv_and_refused_when_mixed);
    suite_add_tcase(s, tc);
    return s;
}
