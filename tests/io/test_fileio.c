/*
 * test_fileio.c - writing through a temporary file and rename (fileio.h):
 * a failed or abandoned write leaves the earlier file as it was; opening
 * an input refuses directories, FIFOs and devices, in every reader.
 */
#include "testutil.h"
#include "imgtest.h"
#include "io/fileio.h"
#include "io/imageio.h"
#include "mesh/obj.h"
#include "render/scenefile.h"
#include "stats/converge.h"

#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

START_TEST(commit_replaces_the_file_and_leaves_no_temporary)
{
    const char *path = imgtest_path("a.txt");
    svet_error err;
    ck_assert_int_eq(fileio_write_text(path, "first\n", &err), SVET_OK);
    ck_assert(imgtest_file_is(path, "first\n", 6));
    ck_assert_int_eq(fileio_write_text(path, "second\n", &err), SVET_OK);
    ck_assert(imgtest_file_is(path, "second\n", 7));
    ck_assert_int_eq(imgtest_count_temps(path), 0);
    /* the mode is the usual one (0666 less the umask), not mkstemp's 0600 */
    struct stat st;
    ck_assert_int_eq(stat(path, &st), 0);
    mode_t mask = umask(0);
    umask(mask);
    ck_assert_uint_eq(st.st_mode & 0777, 0666 & ~mask);
}
END_TEST

START_TEST(abort_keeps_the_old_file_and_removes_the_temporary)
{
    const char *path = imgtest_path("b.txt");
    svet_error err;
    ck_assert_int_eq(fileio_write_text(path, "old", &err), SVET_OK);
    fileio_t out;
    ck_assert_int_eq(fileio_begin(&out, path, &err), SVET_OK);
    fputs("half of a new fi", out.f);
    ck_assert_int_eq(imgtest_count_temps(path), 1);
    fileio_abort(&out); /* e.g. the renderer was interrupted */
    fileio_abort(&out); /* and twice is harmless */
    ck_assert(imgtest_file_is(path, "old", 3));
    ck_assert_int_eq(imgtest_count_temps(path), 0);
    fileio_t zero;
    memset(&zero, 0, sizeof zero);
    fileio_abort(&zero);
    fileio_abort(NULL);
}
END_TEST

static svet_status write_megabyte(const char *path, const void *ctx,
                                  svet_error *err)
{
    (void)ctx;
    fileio_t out;
    svet_status st = fileio_begin(&out, path, err);
    if (st != SVET_OK)
        return st;
    static char block[4096];
    memset(block, 'x', sizeof block);
    for (int i = 0; i < 256; i++)
        fwrite(block, 1, sizeof block, out.f);
    return fileio_commit(&out, err);
}

START_TEST(a_write_failing_midway_keeps_the_old_file)
{
    /* 1 MiB through a file size limit of 64 KiB: the disk "fills up". */
    imgtest_check_failed_write_keeps_old(write_megabyte, NULL,
                                         imgtest_path("c.bin"), 65536);
}
END_TEST

START_TEST(an_unwritable_place_is_a_clear_io_error)
{
    svet_error err;
    ck_assert_int_eq(fileio_write_text("/nonexistent-svet-dir/out.png", "x",
                                       &err), SVET_ERR_IO);
    ck_assert_ptr_nonnull(strstr(err.msg, "/nonexistent-svet-dir/out.png"));
    ck_assert_ptr_nonnull(strstr(err.msg, "No such file"));
    /* a directory in the target's place: the rename fails, nothing stays */
    const char *dir = imgtest_path("d");
    ck_assert_int_eq(mkdir(dir, 0777), 0);
    ck_assert_int_eq(fileio_write_text(dir, "x", &err), SVET_ERR_IO);
    ck_assert_ptr_nonnull(strstr(err.msg, "cannot replace"));
    ck_assert_int_eq(imgtest_count_temps(dir), 0);
    struct stat st;
    ck_assert_int_eq(stat(dir, &st), 0);
    ck_assert(S_ISDIR(st.st_mode));
    rmdir(dir);
}
END_TEST

START_TEST(readers_refuse_what_is_not_a_regular_file_without_blocking)
{
    /* Opening a FIFO for reading waits for a writer, so a scene or an OBJ
     * file that is a FIFO hung svet; a directory read as "an empty file".
     * fileio_open_read() and every reader that opens through it say what
     * the file is instead, at once. */
    char fifo[1024], dir[1024];
    imgtest_special_files(fifo, dir, sizeof fifo);
    const struct {
        const char *path, *words;
    } cases[] = { { fifo, "is a FIFO (named pipe), not a regular file" },
                  { dir, "is a directory, not a file" },
                  { "/dev/null", "is a device, not a regular file" } };
    long n = 0;
    for (int i = 0; i < 3; i++, n += 5) {
        const char *p = cases[i].path;
        char want[1200];
        snprintf(want, sizeof want, "%s: %s", p, cases[i].words);
        svet_error err;
        FILE *f = stdin;
        ck_assert_int_eq(fileio_open_read(p, &f, &err), SVET_ERR_IO);
        ck_assert_ptr_null(f);
        ck_assert_str_eq(err.msg, want);
        scene_t s;
        ck_assert_int_eq(scenefile_read(&s, p, &err), SVET_ERR_IO);
        ck_assert_str_eq(err.msg, want);
        scene_free(&s);
        obj_t o;
        ck_assert_int_eq(obj_read(p, NULL, &o, &err), SVET_ERR_IO);
        ck_assert_str_eq(err.msg, want);
        obj_free(&o);
        char method[32];
        converge_point_t *pts = NULL;
        int npts = 0;
        ck_assert_int_eq(converge_csv_read(p, method, sizeof method, &pts,
                                           &npts, &err), SVET_ERR_IO);
        ck_assert_str_eq(err.msg, want);
        free(pts);
        image_t img;
        ck_assert_int_eq(imageio_read(p, &img, false, NULL, &err),
                         SVET_ERR_IO);
        ck_assert_str_eq(err.msg, want);
    }
    /* a regular file opens, for reading, at its start */
    const char *reg = imgtest_path("a.txt");
    imgtest_write_bytes(reg, "text", 4);
    FILE *f;
    svet_error err;
    ck_assert_int_eq(fileio_open_read(reg, &f, &err), SVET_OK);
    char buf[8] = "";
    ck_assert_uint_eq(fread(buf, 1, sizeof buf, f), 4);
    ck_assert_int_eq(fclose(f), 0);
    ck_assert_int_eq(fileio_open_read(imgtest_path("none"), &f, &err),
                     SVET_ERR_IO);
    ck_assert_ptr_nonnull(strstr(err.msg, "cannot open: No such file"));
    test_report_cases("readers_refuse_what_is_not_a_regular_file_without_"
                      "blocking", n + 2);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("fileio");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, commit_replaces_the_file_and_leaves_no_temporary);
    tcase_add_test(tc, abort_keeps_the_old_file_and_removes_the_temporary);
    tcase_add_test(tc, a_write_failing_midway_keeps_the_old_file);
    tcase_add_test(tc, an_unwritable_place_is_a_clear_io_error);
    tcase_add_test(tc,
                   readers_refuse_what_is_not_a_regular_file_without_blocking);
    suite_add_tcase(s, tc);
    return s;
}
