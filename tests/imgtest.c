/*
 * imgtest.c - shared support of the image suites; see imgtest.h.
 */
#include "imgtest.h"
#include "testutil.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>
#if defined(__linux__)
#include <sys/mount.h>
#endif

static char scratch[512];
static pid_t scratch_owner;

static void remove_scratch(void)
{
    if (!scratch[0] || getpid() != scratch_owner)
        return;
    DIR *d = opendir(scratch);
    if (d) {
        struct dirent *e;
        char p[1024];
        while ((e = readdir(d)) != NULL) {
            if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
                continue;
            snprintf(p, sizeof p, "%s/%s", scratch, e->d_name);
            if (unlink(p) != 0)
                rmdir(p); /* an (empty) directory a test made */
        }
        closedir(d);
    }
    rmdir(scratch);
}

const char *imgtest_path(const char *name)
{
    /* check forks a process per test: each makes (and removes) its own */
    if (!scratch[0] || scratch_owner != getpid()) {
        const char *tmp = getenv("TMPDIR");
        snprintf(scratch, sizeof scratch, "%s/svet-test-XXXXXX",
                 tmp && *tmp ? tmp : "/tmp");
        ck_assert_msg(mkdtemp(scratch) != NULL, "cannot make %s", scratch);
        scratch_owner = getpid();
        atexit(remove_scratch);
    }
    static char ring[8][1024];
    static int next;
    char *p = ring[next++ % 8];
    snprintf(p, sizeof ring[0], "%s/%s", scratch, name);
    return p;
}

void imgtest_write_bytes(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    ck_assert_msg(f != NULL, "cannot create %s", path);
    ck_assert_uint_eq(fwrite(data, 1, n, f), n);
    ck_assert_int_eq(fclose(f), 0);
}

size_t imgtest_read_bytes(const char *path, unsigned char **data)
{
    FILE *f = fopen(path, "rb");
    ck_assert_msg(f != NULL, "cannot open %s", path);
    size_t cap = 4096, n = 0;
    unsigned char *buf = malloc(cap);
    ck_assert_ptr_nonnull(buf);
    for (;;) {
        size_t got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (n < cap)
            break;
        cap *= 2;
        buf = realloc(buf, cap);
        ck_assert_ptr_nonnull(buf);
    }
    fclose(f);
    *data = buf;
    return n;
}

bool imgtest_file_is(const char *path, const void *data, size_t n)
{
    unsigned char *buf;
    size_t got = imgtest_read_bytes(path, &buf);
    bool same = got == n && memcmp(buf, data, n) == 0;
    free(buf);
    return same;
}

int imgtest_count_temps(const char *path)
{
    char dir[1024];
    snprintf(dir, sizeof dir, "%s", path);
    char *slash = strrchr(dir, '/');
    const char *base = slash ? slash + 1 : path;
    char prefix[1024];
    snprintf(prefix, sizeof prefix, "%s.tmp-", base);
    if (slash)
        *slash = '\0';
    else
        snprintf(dir, sizeof dir, ".");
    DIR *d = opendir(dir);
    ck_assert_ptr_nonnull(d);
    int count = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL)
        if (strncmp(e->d_name, prefix, strlen(prefix)) == 0)
            count++;
    closedir(d);
    return count;
}

void imgtest_hdr_image(image_t *img, int w, int h, int channels)
{
    svet_error err;
    ck_assert_int_eq(image_alloc(img, w, h, channels, &err), SVET_OK);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            float *p = image_at(img, x, y);
            /* 10^-3 .. 10^3 across the image, distinct per channel */
            float t = (float)(x + 3 * y) / (float)(w + 3 * h);
            p[0] = powf(10.0f, 6.0f * t - 3.0f);
            p[1] = 0.5f + (float)x / (float)w;
            p[2] = (float)(y + 1) * 0.25f;
            if (channels == 4)
                p[3] = (float)((x + y) % 5) / 4.0f;
        }
}

void imgtest_check_failed_write_keeps_old(imgtest_writer_fn writer,
                                          const void *ctx, const char *path,
                                          long limit)
{
    static const char old[] = "the previous output, which must survive";
    imgtest_write_bytes(path, old, sizeof old);

    struct rlimit saved, small;
    ck_assert_int_eq(getrlimit(RLIMIT_FSIZE, &saved), 0);
    small = saved;
    small.rlim_cur = (rlim_t)limit;
    /* Past the limit write() fails with EFBIG, unless SIGXFSZ kills us. */
    void (*saved_handler)(int) = signal(SIGXFSZ, SIG_IGN);
    ck_assert_int_eq(setrlimit(RLIMIT_FSIZE, &small), 0);
    svet_error err;
    svet_error_clear(&err);
    svet_status st = writer(path, ctx, &err);
    ck_assert_int_eq(setrlimit(RLIMIT_FSIZE, &saved), 0);
    signal(SIGXFSZ, saved_handler);

    ck_assert_msg(st == SVET_ERR_IO, "a write cut at %ld bytes returned %s: "
                  "%s", limit, svet_status_name(st), err.msg);
    ck_assert_msg(strstr(err.msg, path) != NULL, "message without the path: "
                  "%s", err.msg);
    ck_assert_msg(imgtest_file_is(path, old, sizeof old),
                  "the old %s was damaged by a failed write", path);
    ck_assert_int_eq(imgtest_count_temps(path), 0);

    ck_assert_msg(writer(path, ctx, &err) == SVET_OK, "%s", err.msg);
    ck_assert(!imgtest_file_is(path, old, sizeof old));
    ck_assert_int_eq(imgtest_count_temps(path), 0);
}

void imgtest_check_bad_file(imgtest_reader_fn reader, const char *path,
                            svet_status status, const char *words)
{
    image_t img;
    svet_error err;
    svet_error_clear(&err);
    svet_status st = reader(path, &img, &err);
    if (getenv("SVET_SHOW_ERRORS"))
        printf("    [%s]\n", err.msg);
    ck_assert_msg(st == status, "%s: expected %s, got %s: %s", path,
                  svet_status_name(status), svet_status_name(st), err.msg);
    ck_assert_msg(strncmp(err.msg, path, strlen(path)) == 0,
                  "message does not start with the path: %s", err.msg);
    ck_assert_msg(!words || strstr(err.msg, words) != NULL,
                  "message lacks '%s': %s", words, err.msg);
    ck_assert_ptr_null(img.px);
    ck_assert_int_eq(img.width, 0);
}

void imgtest_special_files(char *fifo, char *dir, size_t cap)
{
    snprintf(fifo, cap, "%s", imgtest_path("a-fifo"));
    ck_assert_int_eq(mkfifo(fifo, 0644), 0);
    snprintf(dir, cap, "%s", imgtest_path("a-dir"));
    ck_assert_int_eq(mkdir(dir, 0755), 0);
}

const char *imgtest_small_disk(int kib)
{
#if defined(__linux__)
    static char disk[1100];
    snprintf(disk, sizeof disk, "%s", imgtest_path("small-disk"));
    ck_assert_int_eq(mkdir(disk, 0755), 0);
    char opts[64];
    snprintf(opts, sizeof opts, "size=%dk", kib);
    if (mount("tmpfs", disk, "tmpfs", 0, opts) != 0) {
        printf("  skipped: cannot mount a %d KiB tmpfs at %s (%s; the full "
               "disk tests need root)\n", kib, disk, strerror(errno));
        rmdir(disk);
        return NULL;
    }
    /* Detach the mount at once and reach it through an open descriptor:
     * it lives while the descriptor does (this process and the commands
     * it runs, which inherit it), however the test ends. */
    int fd = open(disk, O_RDONLY | O_DIRECTORY);
    ck_assert_int_ge(fd, 0);
    ck_assert_int_eq(umount2(disk, MNT_DETACH), 0);
    rmdir(disk);
    snprintf(disk, sizeof disk, "/proc/self/fd/%d", fd);
    return disk;
#else
    (void)kib;
    printf("  skipped: the full disk tests mount a tmpfs (Linux only)\n");
    return NULL;
#endif
}

void imgtest_fill_disk(const char *dir)
{
    char p[1100];
    snprintf(p, sizeof p, "%s/filler", dir);
    FILE *f = fopen(p, "wb");
    ck_assert_msg(f != NULL, "cannot create %s", p);
    setvbuf(f, NULL, _IONBF, 0);
    static const char block[4096];
    while (fwrite(block, 1, sizeof block, f) == sizeof block)
        continue;
    while (fwrite(block, 1, 1, f) == 1) /* the last partial block */
        continue;
    ck_assert_int_eq(errno, ENOSPC);
    fclose(f);
}

uint32_t imgtest_png_crc32(const unsigned char *p, size_t n)
{
    uint32_t c = 0xffffffffu;
    for (size_t i = 0; i < n; i++) {
        c ^= p[i];
        for (int k = 0; k < 8; k++)
            c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
    }
    return c ^ 0xffffffffu;
}

void imgtest_put_be32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v >> 24);
    p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
}

void imgtest_png_patch_ihdr(unsigned char *png, uint32_t w, uint32_t h)
{
    imgtest_put_be32(png + 16, w);
    imgtest_put_be32(png + 20, h);
    imgtest_put_be32(png + 29, imgtest_png_crc32(png + 12, 17));
}
