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

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
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
    /* a directory in the target's place: refused, nothing stays */
    const char *dir = imgtest_path("d");
    ck_assert_int_eq(mkdir(dir, 0777), 0);
    ck_assert_int_eq(fileio_write_text(dir, "x", &err), SVET_ERR_IO);
    ck_assert_ptr_nonnull(strstr(err.msg, "is a directory"));
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
        ck_assert_int_eq(converge_csv_read(p, method, sizeof method, NULL,
                                           &pts, &npts, &err), SVET_ERR_IO);
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

/* A file of mode 444 is kept, as cp keeps it (also for root, who could
 * write it: the mode says "do not"), with a message and no temporary. */
START_TEST(a_read_only_file_is_not_replaced)
{
    const char *path = imgtest_path("ro.txt");
    svet_error err;
    ck_assert_int_eq(fileio_write_text(path, "keep", &err), SVET_OK);
    ck_assert_int_eq(chmod(path, 0444), 0);
    ck_assert_int_eq(fileio_write_text(path, "lost", &err), SVET_ERR_IO);
    ck_assert_msg(strstr(err.msg, "read-only") && strstr(err.msg, path),
                  "%s", err.msg);
    ck_assert(imgtest_file_is(path, "keep", 4));
    ck_assert_int_eq(imgtest_count_temps(path), 0);
    /* a FIFO or a device in the target's place is not replaced either */
    ck_assert_int_eq(fileio_write_text("/dev/null", "x", &err), SVET_ERR_IO);
    ck_assert_msg(strstr(err.msg, "not a regular file"), "%s", err.msg);
    /* an empty name says so */
    ck_assert_int_eq(fileio_write_text("", "x", &err), SVET_ERR_IO);
    ck_assert_msg(strstr(err.msg, "empty name"), "%s", err.msg);
}
END_TEST

/* Write "<n bytes>" of 'x' into f. */
static void fill(FILE *f, size_t n)
{
    for (size_t i = 0; i < n; i++)
        fputc('x', f);
}

/* Two outputs of one result: when the second cannot be written in full
 * (a file size limit standing in for a full disk), neither target
 * changes, although the first was written without error. */
START_TEST(a_set_replaces_all_its_files_or_none)
{
    const char *a = imgtest_path("set-a.exr"), *b = imgtest_path("set-b.png");
    imgtest_write_bytes(a, "old a", 5);
    imgtest_write_bytes(b, "old b", 5);
    struct rlimit saved, small;
    ck_assert_int_eq(getrlimit(RLIMIT_FSIZE, &saved), 0);
    small = saved;
    small.rlim_cur = 4096;
    void (*saved_handler)(int) = signal(SIGXFSZ, SIG_IGN);
    ck_assert_int_eq(setrlimit(RLIMIT_FSIZE, &small), 0);
    fileio_set_t set;
    fileio_set_init(&set);
    fileio_t *f;
    svet_error err;
    ck_assert_int_eq(fileio_set_begin(&set, a, &f, &err), SVET_OK);
    fill(f->f, 100);
    ck_assert_int_eq(fileio_set_begin(&set, b, &f, &err), SVET_OK);
    fill(f->f, 65536);
    svet_status st = fileio_set_commit(&set, &err);
    ck_assert_int_eq(setrlimit(RLIMIT_FSIZE, &saved), 0);
    signal(SIGXFSZ, saved_handler);
    ck_assert_int_eq(st, SVET_ERR_IO);
    ck_assert_msg(strstr(err.msg, b), "%s", err.msg);
    ck_assert(imgtest_file_is(a, "old a", 5));
    ck_assert(imgtest_file_is(b, "old b", 5));
    ck_assert_int_eq(imgtest_count_temps(a), 0);
    ck_assert_int_eq(imgtest_count_temps(b), 0);
    /* a second file that cannot even begin: the set is given up whole */
    ck_assert_int_eq(fileio_set_begin(&set, a, &f, &err), SVET_OK);
    fill(f->f, 10);
    ck_assert_int_eq(fileio_set_begin(&set, "/nonexistent-svet-dir/b", &f,
                                      &err), SVET_ERR_IO);
    ck_assert_ptr_null(f);
    fileio_set_abort(&set);
    ck_assert(imgtest_file_is(a, "old a", 5));
    ck_assert_int_eq(imgtest_count_temps(a), 0);
    /* without the limit both are replaced, together */
    ck_assert_int_eq(fileio_set_begin(&set, a, &f, &err), SVET_OK);
    fputs("new a", f->f);
    ck_assert_int_eq(fileio_set_begin(&set, b, &f, &err), SVET_OK);
    fputs("new b", f->f);
    ck_assert(imgtest_file_is(a, "old a", 5)); /* nothing before commit */
    ck_assert_int_eq(fileio_set_commit(&set, &err), SVET_OK);
    ck_assert(imgtest_file_is(a, "new a", 5));
    ck_assert(imgtest_file_is(b, "new b", 5));
    ck_assert_int_eq(imgtest_count_temps(a), 0);
    ck_assert_int_eq(imgtest_count_temps(b), 0);
    fileio_set_abort(&set); /* an empty set: nothing to do */
}
END_TEST

/* This host's name as fileio.c puts it into temporary names. */
static void host_tag(char *out, size_t cap)
{
    char name[256];
    ck_assert_int_eq(gethostname(name, sizeof name), 0);
    ck_assert(cap > 32);
    name[32] = '\0';
    memcpy(out, name, strlen(name) + 1);
    for (char *c = out; *c; c++)
        if (!(('a' <= *c && *c <= 'z') || ('A' <= *c && *c <= 'Z') ||
              ('0' <= *c && *c <= '9') || *c == '.'))
            *c = '_';
}

/* The id of a process that has just ended (and been reaped). */
static long dead_pid(void)
{
    pid_t pid = fork();
    ck_assert(pid >= 0);
    if (pid == 0)
        _exit(0);
    ck_assert_int_eq(waitpid(pid, NULL, 0), pid);
    return (long)pid;
}

START_TEST(a_killed_writers_temporary_file_is_removed_by_the_next_write)
{
    const char *path = imgtest_path("k.exr");
    char host[64], stale[1200], alive[1200], other[1200], locked[1200],
        foreign[1200];
    host_tag(host, sizeof host);
    /* the name a writer uses while it writes: host, pid, counter */
    fileio_t out;
    svet_error err;
    ck_assert_int_eq(fileio_begin(&out, path, &err), SVET_OK);
    char want[1200];
    snprintf(want, sizeof want, "%s.tmp-%s-%ld-", path, host,
             (long)getpid());
    ck_assert_msg(strncmp(out.tmp, want, strlen(want)) == 0, "%s", out.tmp);
    fileio_abort(&out);

    long gone = dead_pid();
    snprintf(stale, sizeof stale, "%s.tmp-%s-%ld-0", path, host, gone);
    snprintf(alive, sizeof alive, "%s.tmp-%s-1-0", path, host); /* init */
    snprintf(other, sizeof other, "%s.tmp-otherhost-%ld-0", path, gone);
    snprintf(locked, sizeof locked, "%s.tmp-%s-%ld-1", path, host, gone);
    snprintf(foreign, sizeof foreign, "%s.tmp-%ld-0", path, gone); /* not ours */
    imgtest_write_bytes(stale, "x", 1);
    imgtest_write_bytes(alive, "x", 1);
    imgtest_write_bytes(other, "x", 1);
    imgtest_write_bytes(locked, "x", 1);
    imgtest_write_bytes(foreign, "x", 1);
    /* a live writer whose id we cannot see (another PID namespace) still
     * holds its lock: a child holds one on `locked` until we let it go */
    int ready[2], done[2];
    ck_assert_int_eq(pipe(ready), 0);
    ck_assert_int_eq(pipe(done), 0);
    pid_t holder = fork();
    ck_assert(holder >= 0);
    if (holder == 0) {
        int fd = open(locked, O_WRONLY);
        struct flock lk;
        memset(&lk, 0, sizeof lk);
        lk.l_type = F_WRLCK;
        lk.l_whence = SEEK_SET;
        char c = fd >= 0 && fcntl(fd, F_SETLK, &lk) == 0 ? 'y' : 'n';
        if (write(ready[1], &c, 1) != 1 || read(done[0], &c, 1) < 0)
            _exit(1);
        _exit(0);
    }
    char c = 0;
    ck_assert_int_eq(read(ready[0], &c, 1), 1);
    ck_assert_int_eq(c, 'y');

    ck_assert_int_eq(fileio_write_text(path, "new", &err), SVET_OK);
    ck_assert_int_ne(access(stale, F_OK), 0);  /* removed */
    ck_assert_int_eq(access(alive, F_OK), 0);  /* its process lives */
    ck_assert_int_eq(access(other, F_OK), 0);  /* another host's */
    ck_assert_int_eq(access(locked, F_OK), 0); /* its lock is held */
    ck_assert_int_eq(access(foreign, F_OK), 0);
    ck_assert(imgtest_file_is(path, "new", 3));

    ck_assert_int_eq(write(done[1], "z", 1), 1);
    ck_assert_int_eq(waitpid(holder, NULL, 0), holder);
    ck_assert_int_eq(fileio_write_text(path, "newer", &err), SVET_OK);
    ck_assert_int_ne(access(locked, F_OK), 0); /* its holder is gone now */
    ck_assert_int_eq(access(alive, F_OK), 0);
    ck_assert_int_eq(access(other, F_OK), 0);
    unlink(alive);
    unlink(other);
    unlink(foreign);
    for (int i = 0; i < 2; i++) {
        close(ready[i]);
        close(done[i]);
    }
}
END_TEST

/* One file under several names is one file; two names in one place are
 * two; a name not yet there is compared by its directory's identity. */
START_TEST(same_file_compares_files_not_names)
{
    char a[1100], dot[1100], sym[1100], up[1100], sub[1100], none1[1100],
        none2[1100], deep1[1100], deep2[1100];
    const char *d = imgtest_path("same"); /* a directory of its own */
    ck_assert_int_eq(mkdir(d, 0777), 0);
    snprintf(a, sizeof a, "%s/a.exr", d);
    snprintf(dot, sizeof dot, "%s/./a.exr", d);
    snprintf(sym, sizeof sym, "%s/link.exr", d);
    snprintf(sub, sizeof sub, "%s/sub", d);
    snprintf(up, sizeof up, "%s/sub/../a.exr", d);
    imgtest_write_bytes(a, "a", 1);
    ck_assert_int_eq(symlink(a, sym), 0);
    ck_assert_int_eq(mkdir(sub, 0777), 0);
    ck_assert(fileio_same_file(a, a));
    ck_assert(fileio_same_file(a, dot));
    ck_assert(fileio_same_file(a, sym));
    ck_assert(fileio_same_file(up, a));
    snprintf(none1, sizeof none1, "%s/new.png", d);
    snprintf(none2, sizeof none2, "%s/sub/.././new.png", d);
    ck_assert(fileio_same_file(none1, none2));   /* neither exists yet */
    ck_assert(!fileio_same_file(none1, a));
    snprintf(deep1, sizeof deep1, "%s/x/y/z.exr", d);
    snprintf(deep2, sizeof deep2, "%s/sub/../x/./y/z.exr", d);
    ck_assert(fileio_same_file(deep1, deep2));   /* x/ is missing too */
    snprintf(deep2, sizeof deep2, "%s/x/y/w.exr", d);
    ck_assert(!fileio_same_file(deep1, deep2));
    ck_assert(!fileio_same_file(a, sub));
    /* a hard link is the same file; a copy is not */
    char hard[1100], copy[1100];
    snprintf(hard, sizeof hard, "%s/hard.exr", d);
    snprintf(copy, sizeof copy, "%s/copy.exr", d);
    ck_assert_int_eq(link(a, hard), 0);
    imgtest_write_bytes(copy, "a", 1);
    ck_assert(fileio_same_file(hard, a));
    ck_assert(!fileio_same_file(copy, a));
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
    tcase_add_test(tc, a_read_only_file_is_not_replaced);
    tcase_add_test(tc, same_file_compares_files_not_names);
    tcase_add_test(tc, a_set_replaces_all_its_files_or_none);
    tcase_add_test(tc,
                   a_killed_writers_temporary_file_is_removed_by_the_next_write);
    suite_add_tcase(s, tc);
    return s;
}
