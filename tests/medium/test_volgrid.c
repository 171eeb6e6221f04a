/*
 * test_volgrid.c - Mitsuba's .vol grids: a file laid out byte by byte in
 * the test (not by the writer) reads back as declared; write then read is
 * exact; every malformed file is refused with its name and reason, sizes
 * before any allocation; FIFOs and directories are refused without
 * blocking; lookups at cell centres, on a linear ramp, and outside.
 */
#include "testutil.h"
#include "medium/volgrid.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char dir[64];

static void make_dir(void)
{
    snprintf(dir, sizeof dir, "/tmp/svet-volgrid-XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(dir));
}

static void remove_dir(void)
{
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    ck_assert_int_eq(system(cmd), 0);
}

static void le32(unsigned char *b, uint32_t u)
{
    for (int i = 0; i < 4; i++)
        b[i] = (unsigned char)(u >> (8 * i));
}

static uint32_t fbits(float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    return u;
}

/* A .vol file by hand: header fields as given, then `values` floats
 * v(i) = i * 0.5 (or NaN at index nan_at), then `extra` bytes. */
static void write_vol(const char *path, const char *magic, int version,
                      int encoding, int nx, int ny, int nz, int ch,
                      long values, long nan_at, int extra)
{
    FILE *f = fopen(path, "wb");
    ck_assert_ptr_nonnull(f);
    unsigned char h[48];
    memcpy(h, magic, 3);
    h[3] = (unsigned char)version;
    le32(h + 4, (uint32_t)encoding);
    le32(h + 8, (uint32_t)nx);
    le32(h + 12, (uint32_t)ny);
    le32(h + 16, (uint32_t)nz);
    le32(h + 20, (uint32_t)ch);
    const float box[6] = { -1, 0, 2, 1, 4, 3 };
    for (int k = 0; k < 6; k++)
        le32(h + 24 + 4 * k, fbits(box[k]));
    ck_assert_int_eq(fwrite(h, 1, 48, f), 48);
    for (long i = 0; i < values; i++) {
        unsigned char b[4];
        le32(b, fbits(i == nan_at ? NAN : (float)i * 0.5f));
        ck_assert_int_eq(fwrite(b, 1, 4, f), 4);
    }
    for (int i = 0; i < extra; i++)
        fputc(0, f);
    ck_assert_int_eq(fclose(f), 0);
}

START_TEST(a_file_laid_out_by_hand_reads_as_declared)
{
    make_dir();
    char path[128];
    snprintf(path, sizeof path, "%s/g.vol", dir);
    write_vol(path, "VOL", 3, 1, 3, 2, 4, 2, 3 * 2 * 4 * 2, -1, 0);
    volgrid_t g;
    svet_error e;
    ck_assert_int_eq(volgrid_read(&g, path, VOLGRID_DEFAULT_MAX_VALUES, &e),
                     SVET_OK);
    ck_assert_int_eq(g.nx, 3);
    ck_assert_int_eq(g.ny, 2);
    ck_assert_int_eq(g.nz, 4);
    ck_assert_int_eq(g.channels, 2);
    ck_assert(g.lo[0] == -1 && g.lo[1] == 0 && g.lo[2] == 2);
    ck_assert(g.hi[0] == 1 && g.hi[1] == 4 && g.hi[2] == 3);
    /* value i of the file is channel i % 2 of cell i / 2, x fastest */
    for (int z = 0; z < 4; z++)
        for (int y = 0; y < 2; y++)
            for (int x = 0; x < 3; x++)
                for (int c = 0; c < 2; c++) {
                    long cell = ((long)z * 2 + y) * 3 + x;
                    ck_assert(g.plane[c][cell] == (float)(cell * 2 + c) * 0.5f);
                }
    ck_assert(g.max[0] == 23.0f && g.max[1] == 23.5f); /* values 46 and 47 */
    /* written back, the same bytes */
    char again[128];
    snprintf(again, sizeof again, "%s/again.vol", dir);
    ck_assert_int_eq(volgrid_write(&g, again, &e), SVET_OK);
    FILE *a = fopen(path, "rb"), *b = fopen(again, "rb");
    int ca, cb;
    long n = 0;
    do {
        ca = fgetc(a);
        cb = fgetc(b);
        ck_assert_int_eq(ca, cb);
        n++;
    } while (ca != EOF);
    ck_assert_int_eq(n, 48 + 48 * 4 + 1);
    fclose(a);
    fclose(b);
    volgrid_free(&g);
    remove_dir();
}
END_TEST

static void expect_refusal(const char *path, size_t max_values,
                           const char *words)
{
    volgrid_t g;
    svet_error e;
    svet_status st = volgrid_read(&g, path, max_values, &e);
    ck_assert_msg(st != SVET_OK, "%s was read", path);
    ck_assert_msg(strstr(e.msg, path) != NULL, "no file name in '%s'", e.msg);
    ck_assert_msg(strstr(e.msg, words) != NULL, "'%s' does not say '%s'",
                  e.msg, words);
    ck_assert_ptr_null(g.plane[0]);
}

START_TEST(malformed_files_are_refused_with_their_reason)
{
    make_dir();
    char p[128];
    snprintf(p, sizeof p, "%s/bad.vol", dir);
    write_vol(p, "VOX", 3, 1, 2, 2, 2, 1, 8, -1, 0);
    expect_refusal(p, VOLGRID_DEFAULT_MAX_VALUES, "does not start with VOL");
    write_vol(p, "VOL", 2, 1, 2, 2, 2, 1, 8, -1, 0);
    expect_refusal(p, VOLGRID_DEFAULT_MAX_VALUES, "version 2");
    write_vol(p, "VOL", 3, 2, 2, 2, 2, 1, 8, -1, 0);
    expect_refusal(p, VOLGRID_DEFAULT_MAX_VALUES, "encoding 2");
    write_vol(p, "VOL", 3, 1, 2, 2, 2, 1, 7, -1, 0);
    expect_refusal(p, VOLGRID_DEFAULT_MAX_VALUES, "truncated");
    write_vol(p, "VOL", 3, 1, 2, 2, 2, 1, 8, -1, 3);
    expect_refusal(p, VOLGRID_DEFAULT_MAX_VALUES, "bytes after the grid");
    write_vol(p, "VOL", 3, 1, 2, 0, 2, 1, 0, -1, 0);
    expect_refusal(p, VOLGRID_DEFAULT_MAX_VALUES, "1 or more");
    write_vol(p, "VOL", 3, 1, 2, -5, 2, 1, 8, -1, 0);
    expect_refusal(p, VOLGRID_DEFAULT_MAX_VALUES, "1 or more");
    write_vol(p, "VOL", 3, 1, 2, 2, 2, 5, 40, -1, 0);
    expect_refusal(p, VOLGRID_DEFAULT_MAX_VALUES, "5 channels");
    write_vol(p, "VOL", 3, 1, 2, 2, 2, 1, 8, 5, 0);
    expect_refusal(p, VOLGRID_DEFAULT_MAX_VALUES, "must be finite");
    /* absurd sizes: 2^31 - 1 cubed, refused from the header alone (the
     * file holds no values; reading them would take forever) */
    write_vol(p, "VOL", 3, 1, 2147483647, 2147483647, 2147483647, 1, 0, -1, 0);
    expect_refusal(p, VOLGRID_DEFAULT_MAX_VALUES, "at most");
    /* a limit set lower than the file: refused, the same way */
    write_vol(p, "VOL", 3, 1, 4, 4, 4, 1, 64, -1, 0);
    expect_refusal(p, 63, "at most 63");
    /* a short file */
    FILE *f = fopen(p, "wb");
    fputs("VOL", f);
    fclose(f);
    expect_refusal(p, VOLGRID_DEFAULT_MAX_VALUES, "shorter than a .vol header");
    /* missing, a directory, a FIFO (which must not block) */
    snprintf(p, sizeof p, "%s/missing.vol", dir);
    expect_refusal(p, VOLGRID_DEFAULT_MAX_VALUES, "cannot open");
    expect_refusal(dir, VOLGRID_DEFAULT_MAX_VALUES, "is a directory");
    snprintf(p, sizeof p, "%s/fifo.vol", dir);
    ck_assert_int_eq(mkfifo(p, 0600), 0);
    expect_refusal(p, VOLGRID_DEFAULT_MAX_VALUES, "is a FIFO");
    remove_dir();
}
END_TEST

START_TEST(lookups_at_cell_centres_on_a_ramp_and_outside)
{
    volgrid_t g;
    const float lo[3] = { 0, 0, 0 }, hi[3] = { 2, 1, 4 };
    ck_assert_int_eq(volgrid_alloc(&g, 4, 2, 8, 1, lo, hi,
                                   VOLGRID_DEFAULT_MAX_VALUES, NULL),
                     SVET_OK);
    /* a linear ramp in the cell centres' world positions: 1 + x + 2 z */
    for (int z = 0; z < 8; z++)
        for (int y = 0; y < 2; y++)
            for (int x = 0; x < 4; x++) {
                double wx = (x + 0.5) * 0.5, wz = (z + 0.5) * 0.5;
                g.plane[0][(z * 2 + y) * 4 + x] = (float)(1 + wx + 2 * wz);
            }
    for (int i = 0; i < 100; i++) {
        /* within the centres' hull the ramp is reproduced */
        real x = REAL_C(0.25) + REAL_C(1.5) * (real)i / 99;
        real z = REAL_C(0.25) + REAL_C(3.5) * (real)((i * 37) % 100) / 99;
        VECTOR3 p = { x, REAL_C(0.6), z };
        ck_assert_near(volgrid_eval(&g, 0, p), 1 + x + 2 * z, 1e-5);
    }
    /* outside the box, the border continues */
    VECTOR3 far = { 100, -100, REAL_C(0.25) }, edge = { REAL_C(1.75), REAL_C(0.25), REAL_C(0.25) };
    ck_assert(volgrid_eval(&g, 0, far) == volgrid_eval(&g, 0, edge));
    volgrid_free(&g);
    /* bad sizes, channels and boxes are refused */
    svet_error e;
    const float bad_hi[3] = { 2, 0, 4 };
    ck_assert_int_eq(volgrid_alloc(&g, 1, 1, 1, 1, lo, bad_hi, 10, &e),
                     SVET_ERR_RANGE);
    ck_assert_int_eq(volgrid_alloc(&g, 1, 1, 1, 0, lo, hi, 10, &e),
                     SVET_ERR_RANGE);
    ck_assert_int_eq(volgrid_alloc(&g, 10, 10, 10, 1, lo, hi, 999, &e),
                     SVET_ERR_RANGE);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("volgrid (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, a_file_laid_out_by_hand_reads_as_declared);
    tcase_add_test(tc, malformed_files_are_refused_with_their_reason);
    tcase_add_test(tc, lookups_at_cell_centres_on_a_ramp_and_outside);
    suite_add_tcase(s, tc);
    return s;
}
