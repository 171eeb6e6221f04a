/*
 * test_cmd_render.c - `svet render` end to end (cmd/cmd_render.c): the EXR and
 * the PNG it writes, the same image for any thread count and pass split,
 * the exit codes of bad input and of a failing pass, and SIGTERM ending
 * the render after a pass with what was rendered written.
 */
#include "testutil.h"
#include "cmdtest.h"
#include "imgtest.h"
#include "io/exrio.h"
#include "io/pngio.h"

#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static char out[16384];
static char dir[256];

/* A scratch directory with a small scene in it. */
static void setup(void)
{
    snprintf(dir, sizeof dir, "/tmp/svet-cmd-render-XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(dir));
    char path[512];
    snprintf(path, sizeof path, "%s/tiny.scn", dir);
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    fprintf(f, "camera position 0 1 4 target 0 0 0 up 0 1 0 fov 40 width 24 "
               "height 16\n"
               "render spp 8 maxdepth 3 seed 7\n"
               "material grey lambert rho 0.5\n"
               "sphere centre 0 0 0 radius 1 material grey\n"
               "plane point 0 -1 0 normal 0 1 0 material grey\n"
               "light point position 2 3 2 intensity 10\n");
    fclose(f);
}

static void teardown(void)
{
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    ck_assert_int_eq(system(cmd), 0);
}

static bool same_file(const char *a, const char *b)
{
    FILE *fa = fopen(a, "rb"), *fb = fopen(b, "rb");
    bool same = fa && fb;
    while (same) {
        int ca = fgetc(fa), cb = fgetc(fb);
        if (ca != cb)
            same = false;
        if (ca == EOF || cb == EOF)
            break;
    }
    if (fa)
        fclose(fa);
    if (fb)
        fclose(fb);
    return same;
}

START_TEST(render_writes_an_exr_and_a_png_beside_it)
{
    char args[1024], exr[600], png[600];
    snprintf(exr, sizeof exr, "%s/a.exr", dir);
    snprintf(png, sizeof png, "%s/a.png", dir);
    snprintf(args, sizeof args, "render '%s/tiny.scn' -o '%s' --threads 1",
             dir, exr);
    ck_assert_int_eq(cmdtest_run(out, sizeof out, args), 0);
    ck_assert_ptr_nonnull(strstr(out, "samples/s"));  /* the summary line */
    image_t img;
    ck_assert_int_eq(exrio_read(exr, &img, NULL), SVET_OK);
    ck_assert_int_eq(img.width, 24);
    ck_assert_int_eq(img.height, 16);
    image_free(&img);
    int bits;
    ck_assert_int_eq(pngio_read(png, &img, &bits, NULL), SVET_OK);
    ck_assert_int_eq(img.width, 24);
    image_free(&img);
    /* two threads and five passes: the same file, bit for bit */
    char exr2[600];
    snprintf(exr2, sizeof exr2, "%s/b.exr", dir);
    snprintf(args, sizeof args, "render '%s/tiny.scn' -o '%s' --threads 2 "
             "--passes 5 --checkpoint -q", dir, exr2);
    ck_assert_int_eq(cmdtest_run(out, sizeof out, args), 0);
    ck_assert_str_eq(out, ""); /* --quiet */
    ck_assert(same_file(exr, exr2));
    /* another seed: another image */
    snprintf(args, sizeof args, "render '%s/tiny.scn' -o '%s' --seed 8 -q",
             dir, exr2);
    ck_assert_int_eq(cmdtest_run(out, sizeof out, args), 0);
    ck_assert(!same_file(exr, exr2));
}
END_TEST

START_TEST(bad_input_gives_a_message_and_an_exit_code)
{
    char args[1024];
    ck_assert_int_eq(cmdtest_run(out, sizeof out, "render"), 1);
    ck_assert_int_eq(cmdtest_run(out, sizeof out, "render --help"), 0);
    ck_assert_ptr_nonnull(strstr(out, "exit codes"));
    snprintf(args, sizeof args, "render '%s/tiny.scn' --spp zero", dir);
    ck_assert_int_eq(cmdtest_run(out, sizeof out, args), 1);
    ck_assert_ptr_nonnull(strstr(out, "bad value 'zero' for --spp"));
    snprintf(args, sizeof args, "render '%s/tiny.scn' --frobnicate", dir);
    ck_assert_int_eq(cmdtest_run(out, sizeof out, args), 1);
    ck_assert_int_eq(cmdtest_run(out, sizeof out,
                                 "render /nonexistent/none.scn"), 2);
    ck_assert_ptr_nonnull(strstr(out, "none.scn"));
    /* a typo in the scene: file and line in the message, no output */
    char path[512];
    snprintf(path, sizeof path, "%s/typo.scn", dir);
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    fprintf(f, "material grey lambert rho 0.5\nsphere centre 0 0 0 radius 1 "
               "material gery\n");
    fclose(f);
    snprintf(args, sizeof args, "render '%s' -o '%s/typo.exr'", path, dir);
    ck_assert_int_eq(cmdtest_run(out, sizeof out, args), 2);
    ck_assert_ptr_nonnull(strstr(out, "typo.scn:2"));
    snprintf(path, sizeof path, "%s/typo.exr", dir);
    ck_assert_int_ne(access(path, F_OK), 0);
    /* an output that cannot be written: exit 3. Its directory would lie
     * under a regular file, which no mkdir() can make (a path under
     * /nonexistent can be made by anyone who creates /nonexistent). */
    snprintf(args, sizeof args, "render '%s/tiny.scn' -o '%s/tiny.scn/x/a.exr' "
             "-q", dir, dir);
    ck_assert_int_eq(cmdtest_run(out, sizeof out, args), 3);
    /* an override with a bad value */
    snprintf(args, sizeof args, "render '%s/tiny.scn' --set spp=-3", dir);
    ck_assert_int_eq(cmdtest_run(out, sizeof out, args), 1);
}
END_TEST

/* An unknown option at the end of the line is unknown, not short of a
 * value; an empty file name is refused before anything is written. */
START_TEST(usage_errors_name_the_real_problem)
{
    char args[1024];
    snprintf(args, sizeof args, "render '%s/tiny.scn' --frobnicate", dir);
    ck_assert_int_eq(cmdtest_run(out, sizeof out, args), 1);
    ck_assert_msg(strstr(out, "unknown option '--frobnicate'"), "%s", out);
    snprintf(args, sizeof args, "render '%s/tiny.scn' --spp", dir);
    ck_assert_int_eq(cmdtest_run(out, sizeof out, args), 1);
    ck_assert_msg(strstr(out, "--spp needs a value"), "%s", out);
    snprintf(args, sizeof args, "render '%s/tiny.scn' --seed", dir);
    ck_assert_int_eq(cmdtest_run(out, sizeof out, args), 1);
    ck_assert_msg(strstr(out, "--seed needs a value"), "%s", out);
    ck_assert_int_eq(cmdtest_run(out, sizeof out, "diff a b --frobnicate"),
                     1);
    ck_assert_msg(strstr(out, "unknown option '--frobnicate'"), "%s", out);
    ck_assert_int_eq(cmdtest_run(out, sizeof out,
                                 "converge a --ref r.exr --frobnicate"), 1);
    ck_assert_msg(strstr(out, "unknown option '--frobnicate'"), "%s", out);
    const char *empty[] = { "-o", "--png", "--variance" };
    for (int i = 0; i < 3; i++) {
        snprintf(args, sizeof args, "render '%s/tiny.scn' %s ''", dir,
                 empty[i]);
        ck_assert_int_eq(cmdtest_run(out, sizeof out, args), 1);
        ck_assert_msg(strstr(out, "a file name cannot be empty"), "%s", out);
    }
    ck_assert_int_eq(cmdtest_run(out, sizeof out,
                                 "converge a --ref '' --no-plot"), 1);
    ck_assert_msg(strstr(out, "a file name cannot be empty"), "%s", out);
}
END_TEST

/* The outputs of a render replace the old ones together: a PNG that
 * cannot be written leaves the old EXR (and PNG) in place, so the pair on
 * disk still belongs together. A read-only output is kept, exit 3. */
START_TEST(outputs_are_replaced_together_or_not_at_all)
{
    char args[4096], exr[600], png[600], notdir[600];
    snprintf(exr, sizeof exr, "%s/pair.exr", dir);
    snprintf(png, sizeof png, "%s/pair.png", dir);
    snprintf(notdir, sizeof notdir, "%s/plain-file", dir);
    snprintf(args, sizeof args, "render '%s/tiny.scn' -o '%s' -q", dir, exr);
    ck_assert_int_eq(cmdtest_run(out, sizeof out, args), 0);
    char old_exr[600];
    snprintf(old_exr, sizeof old_exr, "%s/old.exr", dir);
    snprintf(args, sizeof args, "cp '%s' '%s'; : > '%s'", exr, old_exr,
             notdir);
    ck_assert_int_eq(system(args), 0);
    /* another seed, and a PNG under a plain file: ENOTDIR */
    snprintf(args, sizeof args, "render '%s/tiny.scn' -o '%s' --png "
             "'%s/a.png' --seed 9 -q", dir, exr, notdir);
    ck_assert_int_eq(cmdtest_run(out, sizeof out, args), 3);
    ck_assert_msg(strstr(out, "plain-file/a.png"), "%s", out);
    ck_assert_msg(same_file(exr, old_exr), "the EXR was replaced alone");
    /* the variance image likewise */
    snprintf(args, sizeof args, "render '%s/tiny.scn' -o '%s' --variance "
             "'%s/v.exr' --seed 9 -q", dir, exr, notdir);
    ck_assert_int_eq(cmdtest_run(out, sizeof out, args), 3);
    ck_assert_msg(same_file(exr, old_exr), "the EXR was replaced alone");
    /* mode 444: refused, untouched */
    ck_assert_int_eq(chmod(exr, 0444), 0);
    snprintf(args, sizeof args, "render '%s/tiny.scn' -o '%s' --seed 9 -q",
             dir, exr);
    ck_assert_int_eq(cmdtest_run(out, sizeof out, args), 3);
    ck_assert_msg(strstr(out, "read-only"), "%s", out);
    ck_assert(same_file(exr, old_exr));
}
END_TEST

/* Every way of naming one file twice, and an output that is an input,
 * is refused before anything is written (exit 1), the files untouched. */
START_TEST(an_output_that_is_another_output_or_an_input_is_refused)
{
    char args[2048], scene[600];
    snprintf(scene, sizeof scene, "%s/tiny.scn", dir);
    snprintf(args, sizeof args, "cp '%s' '%s/tiny.copy'; mkdir '%s/sub'; cp "
             "tests/data/scene/tri.obj '%s/tri.obj'", scene, dir, dir, dir);
    ck_assert_int_eq(system(args), 0);
    /* pairs of an option and a name in the scratch directory */
    const char *bad[][4] = {
        { "-o", "same.png", NULL, NULL },           /* the PNG beside it */
        { "-o", "x.exr", "--png", "x.exr" },
        { "-o", "x.exr", "--png", "sub/../x.exr" },
        { "-o", "x.exr", "--variance", "./x.exr" },
        { "-o", "tiny.scn", NULL, NULL },           /* the scene itself */
        { "-o", "a.exr", "--png", "sub/../tiny.scn" },
        { "-o", "a.exr", "--variance", "tri.obj" }, /* its mesh */
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        int n = snprintf(args, sizeof args, "render '%s' -q", scene);
        for (int k = 0; k < 4 && bad[i][k]; k += 2)
            n += snprintf(args + n, sizeof args - (size_t)n, " %s '%s/%s'",
                          bad[i][k], dir, bad[i][k + 1]);
        if (i == 6) { /* from now on the scene reads tri.obj */
            FILE *f = fopen(scene, "a");
            ck_assert_ptr_nonnull(f);
            fprintf(f, "mesh file tri.obj material grey\n");
            fclose(f);
        }
        ck_assert_msg(cmdtest_run(out, sizeof out, args) == 1, "%s: %s",
                      args, out);
        ck_assert_msg(strstr(out, "is the same file as"), "%s", out);
    }
    /* the scene's own output lines naming one file */
    FILE *f = fopen(scene, "a");
    ck_assert_ptr_nonnull(f);
    fprintf(f, "output exr %s/same.exr png %s/same.exr\n", dir, dir);
    fclose(f);
    snprintf(args, sizeof args, "render '%s' -q", scene);
    ck_assert_int_eq(cmdtest_run(out, sizeof out, args), 1);
    ck_assert_msg(strstr(out, "is the same file as"), "%s", out);
    /* nothing was written, nothing changed */
    const char *never[] = { "same.png", "same.exr", "x.exr", "a.exr",
                            "a.png" };
    for (int i = 0; i < 5; i++) {
        char path[700];
        snprintf(path, sizeof path, "%s/%s", dir, never[i]);
        ck_assert_msg(access(path, F_OK) != 0, "%s was written", path);
    }
    snprintf(args, sizeof args, "cmp -s '%s/tri.obj' tests/data/scene/tri.obj"
             " && head -n 6 '%s' | cmp -s - '%s/tiny.copy'", dir, scene, dir);
    ck_assert_int_eq(system(args), 0);
}
END_TEST

/* Start `svet render ARGS...` (NULL-terminated) in the background, its
 * stderr to log (NULL: /dev/null); returns its pid. */
static pid_t start_render(const char *log, ...)
{
    const char *argv[32] = { "svet", "render" };
    int n = 2;
    va_list ap;
    va_start(ap, log);
    for (const char *a; n < 31 && (a = va_arg(ap, const char *)) != NULL;)
        argv[n++] = a;
    va_end(ap);
    argv[n] = NULL;
    const char *svet = cmdtest_svet();
    pid_t pid = fork();
    ck_assert(pid >= 0);
    if (pid == 0) {
        if (!freopen(log ? log : "/dev/null", "w", stderr))
            _exit(126);
        execv(svet, (char *const *)argv);
        _exit(127);
    }
    return pid;
}

START_TEST(sigterm_finishes_the_pass_and_writes_the_image)
{
    /* A render long enough to be stopped: many passes of many samples. */
    char exr[600], scene[600];
    snprintf(exr, sizeof exr, "%s/stopped.exr", dir);
    snprintf(scene, sizeof scene, "%s/tiny.scn", dir);
    pid_t pid = start_render(NULL, scene, "-o", exr, "--spp", "200000",
                             "--passes", "100000", "--threads", "1",
                             "--checkpoint", (char *)NULL);
    /* The first checkpoint proves the render is under way (its signal
     * handlers are installed before the first pass); then ask it to stop.
     * Polled, not timed: a slow machine only waits longer. */
    struct timespec tick = { 0, 20000000 };
    for (int i = 0; i < 6000 && access(exr, F_OK) != 0; i++)
        nanosleep(&tick, NULL);
    ck_assert_int_eq(access(exr, F_OK), 0);
    kill(pid, SIGTERM);
    int status;
    ck_assert_int_eq(waitpid(pid, &status, 0), pid);
    ck_assert(WIFEXITED(status));
    ck_assert_int_eq(WEXITSTATUS(status), 4); /* interrupted, image written */
    image_t img;
    ck_assert_int_eq(exrio_read(exr, &img, NULL), SVET_OK);
    ck_assert_int_eq(img.width, 24);
    /* something was rendered: the lit sphere is not black */
    ck_assert(image_at(&img, 12, 8)[1] > 0);
    image_free(&img);
}
END_TEST

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* SIGINT during a pass: the pass is abandoned, not finished, and the
 * outputs hold the last whole pass, the same bits as a render asked for
 * that many samples. Work is counted, not timed: 8 passes of 512 samples
 * on 16 tiles, the signal sent as soon as the first pass's checkpoint is
 * on disk; a render that finished its second pass writes 1024 samples.
 * The time to exit is only compared, loosely, with the first pass's. */
START_TEST(sigint_abandons_the_pass_and_writes_the_last_whole_one)
{
    char exr[600], scene[600], log[600];
    snprintf(exr, sizeof exr, "%s/int.exr", dir);
    snprintf(scene, sizeof scene, "%s/tiny.scn", dir);
    snprintf(log, sizeof log, "%s/int.log", dir);
    double t0 = now();
    pid_t pid = start_render(log, scene, "-o", exr, "--spp", "4096",
                             "--passes", "8", "--threads", "1", "--set",
                             "resolution=64x64", "--checkpoint", (char *)NULL);
    struct timespec tick = { 0, 5000000 };
    for (int i = 0; i < 60000 && access(exr, F_OK) != 0; i++)
        nanosleep(&tick, NULL);
    ck_assert_int_eq(access(exr, F_OK), 0);
    double t1 = now();
    kill(pid, SIGINT);
    int status;
    ck_assert_int_eq(waitpid(pid, &status, 0), pid);
    double t2 = now();
    ck_assert(WIFEXITED(status));
    ck_assert_int_eq(WEXITSTATUS(status), 4);
    /* the summary names the samples written: the first pass's */
    FILE *f = fopen(log, "r");
    ck_assert_ptr_nonnull(f);
    size_t n = fread(out, 1, sizeof out - 1, f);
    out[n] = '\0';
    fclose(f);
    ck_assert_msg(strstr(out, ", 512 spp in") && strstr(out, "(interrupted)"),
                  "%s", out);
    /* well within a pass (1/16 of one at most, and the exit) */
    ck_assert_msg(t2 - t1 < 0.5 * (t1 - t0), "%.3f s to stop after a first "
                  "pass of %.3f s", t2 - t1, t1 - t0);
    char fresh[600], args[1400];
    snprintf(fresh, sizeof fresh, "%s/fresh.exr", dir);
    snprintf(args, sizeof args, "render '%s' -o '%s' --spp 512 --set "
             "resolution=64x64 -q", scene, fresh);
    ck_assert_int_eq(cmdtest_run(out, sizeof out, args), 0);
    ck_assert(same_file(exr, fresh));
}
END_TEST

/* Stopped before the first pass ends: nothing is written over the old
 * output (an image of no samples is no result). */
START_TEST(sigint_in_the_first_pass_keeps_the_old_output)
{
    char exr[600], scene[600];
    snprintf(exr, sizeof exr, "%s/first.exr", dir);
    snprintf(scene, sizeof scene, "%s/tiny.scn", dir);
    imgtest_write_bytes(exr, "old", 3);
    pid_t pid = start_render(NULL, scene, "-o", exr, "--spp", "100000",
                             "--passes", "1", "--threads", "1", "--set",
                             "resolution=64x64", (char *)NULL);
    /* nothing is on disk yet to say the pass is under way: wait until
     * svet catches SIGINT (Linux's /proc/PID/status, SigCgt bit 1), which
     * it starts to do just before the first pass. The process must be
     * svet already (Name: svet): between fork and exec it is a copy of
     * this suite, whose runner catches SIGINT too (check's handler, which
     * kills the test's process group). */
    struct timespec tick = { 0, 5000000 };
    char status_path[64], line[256];
    snprintf(status_path, sizeof status_path, "/proc/%ld/status", (long)pid);
    bool catching = false;
    for (int i = 0; i < 60000 && !catching; i++) {
        nanosleep(&tick, NULL);
        FILE *f = fopen(status_path, "r");
        bool is_svet = false, caught = false;
        while (f && fgets(line, sizeof line, f)) {
            if (!strncmp(line, "Name:", 5))
                is_svet = !strcmp(line + 5 + strspn(line + 5, " \t"),
                                  "svet\n");
            if (!strncmp(line, "SigCgt:", 7))
                caught = (strtoull(line + 7, NULL, 16) >> (SIGINT - 1)) & 1;
        }
        if (f)
            fclose(f);
        catching = is_svet && caught;
    }
    ck_assert(catching);
    kill(pid, SIGINT);
    int status;
    ck_assert_int_eq(waitpid(pid, &status, 0), pid);
    ck_assert(WIFEXITED(status));
    ck_assert_int_eq(WEXITSTATUS(status), 4);
    ck_assert(imgtest_file_is(exr, "old", 3));
    ck_assert_int_eq(imgtest_count_temps(exr), 0);
}
END_TEST

/* A pass that fails (here ppm's begin_pass: 500 photon maps of 5e6
 * photons for the 500 sample indices of a pass are more than a photon map
 * may hold, refused before anything is traced) exits 6, names the scene
 * and the reason, and leaves the earlier output as it was. */
START_TEST(a_failing_pass_exits_6_and_keeps_the_old_output)
{
    char args[1024], cmd[1200];
    snprintf(args, sizeof args, "render '%s/tiny.scn' -o '%s/a.exr' -q", dir,
             dir);
    ck_assert_int_eq(cmdtest_run(out, sizeof out, args), 0);
    snprintf(cmd, sizeof cmd, "cp '%s/a.exr' '%s/a0.exr'", dir, dir);
    ck_assert_int_eq(system(cmd), 0);
    snprintf(args, sizeof args, "render '%s/tiny.scn' -o '%s/a.exr' -q "
             "--set integrator=ppm --set photonmap.global=5000000 "
             "--spp 1000 --passes 2 --checkpoint", dir, dir);
    ck_assert_int_eq(cmdtest_run(out, sizeof out, args), 6);
    ck_assert_ptr_nonnull(strstr(out, "tiny.scn: ppm: 500 maps"));
    char a[512], a0[512];
    snprintf(a, sizeof a, "%s/a.exr", dir);
    snprintf(a0, sizeof a0, "%s/a0.exr", dir);
    ck_assert(same_file(a, a0));
    /* svet --help lists the code */
    ck_assert_int_eq(cmdtest_run(out, sizeof out, "--help"), 0);
    ck_assert_ptr_nonnull(strstr(out, "6  svet render: a pass"));
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("svet render");
    TCase *tc = tcase_create("command");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, render_writes_an_exr_and_a_png_beside_it);
    tcase_add_test(tc, bad_input_gives_a_message_and_an_exit_code);
    tcase_add_test(tc, usage_errors_name_the_real_problem);
    tcase_add_test(tc, outputs_are_replaced_together_or_not_at_all);
    tcase_add_test(tc, an_output_that_is_another_output_or_an_input_is_refused);
    tcase_add_test(tc, sigterm_finishes_the_pass_and_writes_the_image);
    tcase_add_test(tc, sigint_abandons_the_pass_and_writes_the_last_whole_one);
    tcase_add_test(tc, sigint_in_the_first_pass_keeps_the_old_output);
    tcase_add_test(tc, a_failing_pass_exits_6_and_keeps_the_old_output);
    suite_add_tcase(s, tc);
    return s;
}
