/*
 * test_photonsave.c - a photon map to a file and back (photonsave.h, ch.
 * 8): a balanced map of random photons reads back as the same bytes in
 * the same heap order, with the same nearest photons as the map written
 * (the independent check: the kd-tree's own query on the original); an
 * empty map round-trips; a map not balanced is not written; a file of
 * another photon size, another byte order, a truncated one and one that
 * is not a map are refused with their messages.
 */
#include "testutil.h"
#include "core/rng.h"
#include "photon/photonsave.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* n random photons in the unit cube, balanced */
static void fill(photonmap_t *m, size_t n, uint64_t seed)
{
    svet_error e;
    ck_assert_int_eq(photonmap_init(m, n, &e), SVET_OK);
    pcg32_t g;
    pcg32_seed(&g, seed, 1);
    for (size_t i = 0; i < n; i++) {
        VECTOR3 p = { pcg32_real(&g), pcg32_real(&g), pcg32_real(&g) };
        VECTOR3 d = { pcg32_real(&g) - REAL_C(0.5), pcg32_real(&g),
                      -pcg32_real(&g) - REAL_C(0.1) };
        vec_normalize(d, d);
        RADIANCE pw = { pcg32_real(&g), pcg32_real(&g), pcg32_real(&g) };
        ck_assert(photonmap_store(m, p, pw, d, (uint8_t)(i & 1)));
    }
    ck_assert_int_eq(photonmap_balance(m, &e), SVET_OK);
}

/* m written to a temporary file, rewound */
static FILE *written(const photonmap_t *m)
{
    FILE *f = tmpfile();
    ck_assert_ptr_nonnull(f);
    svet_error e;
    ck_assert_int_eq(photonmap_write(m, f, &e), SVET_OK);
    rewind(f);
    return f;
}

START_TEST(a_map_reads_back_as_the_same_heap)
{
    photonmap_t m, b;
    fill(&m, 5000, 3);
    FILE *f = written(&m);
    svet_error e;
    ck_assert_int_eq(photonmap_read(&b, f, &e), SVET_OK);
    ck_assert_int_eq(fgetc(f), EOF); /* nothing after the map */
    fclose(f);
    ck_assert(b.balanced);
    ck_assert_uint_eq(b.n, m.n);
    ck_assert_int_eq(memcmp(&b.ph[1], &m.ph[1], m.n * sizeof(photon_t)), 0);
    /* the read map answers queries as the written one does */
    pcg32_t g;
    pcg32_seed(&g, 9, 2);
    int32_t ia[20], ib[20];
    real da[20], db[20];
    for (int q = 0; q < 50; q++) {
        VECTOR3 x = { pcg32_real(&g), pcg32_real(&g), pcg32_real(&g) };
        int na = photonmap_nearest(&m, x, 20, REAL_C(0.2), ia, da);
        int nb = photonmap_nearest(&b, x, 20, REAL_C(0.2), ib, db);
        ck_assert_int_eq(na, nb);
        ck_assert_int_gt(na, 0);
        for (int i = 0; i < na; i++) {
            ck_assert_int_eq(ia[i], ib[i]);
            ck_assert(da[i] == db[i]);
        }
    }
    photonmap_free(&m);
    photonmap_free(&b);
}
END_TEST

START_TEST(two_maps_in_one_file_and_an_empty_one)
{
    photonmap_t m, z = { 0 }, a, b, c;
    fill(&m, 100, 4);
    z.balanced = true; /* an empty map, as a pre-pass of no photons has */
    FILE *f = tmpfile();
    ck_assert_ptr_nonnull(f);
    svet_error e;
    ck_assert_int_eq(photonmap_write(&m, f, &e), SVET_OK);
    ck_assert_int_eq(photonmap_write(&z, f, &e), SVET_OK);
    ck_assert_int_eq(photonmap_write(&m, f, &e), SVET_OK);
    rewind(f);
    ck_assert_int_eq(photonmap_read(&a, f, &e), SVET_OK);
    ck_assert_int_eq(photonmap_read(&b, f, &e), SVET_OK);
    ck_assert_int_eq(photonmap_read(&c, f, &e), SVET_OK);
    fclose(f);
    ck_assert_uint_eq(a.n, 100);
    ck_assert_uint_eq(b.n, 0);
    ck_assert(b.balanced);
    ck_assert_uint_eq(c.n, 100);
    ck_assert_int_eq(memcmp(&c.ph[1], &m.ph[1], 100 * sizeof(photon_t)), 0);
    photonmap_free(&m);
    photonmap_free(&a);
    photonmap_free(&b);
    photonmap_free(&c);
}
END_TEST

/* a file holding text, then (if mark) the byte-order mark, then n bytes
 * of zeros, rewound */
static FILE *file_of(const char *text, const unsigned char *mark, size_t n)
{
    FILE *f = tmpfile();
    ck_assert_ptr_nonnull(f);
    fputs(text, f);
    if (mark)
        fwrite(mark, 1, 4, f);
    for (size_t i = 0; i < n; i++)
        fputc(0, f);
    rewind(f);
    return f;
}

static void refused(FILE *f, const char *msg)
{
    photonmap_t m;
    svet_error e;
    ck_assert_int_eq(photonmap_read(&m, f, &e), SVET_ERR_PARSE);
    ck_assert_msg(strstr(e.msg, msg), "'%s' not in '%s'", msg, e.msg);
    ck_assert_ptr_null(m.ph);
    ck_assert_uint_eq(m.n, 0);
    fclose(f);
}

START_TEST(refusals)
{
    photonmap_t m;
    svet_error e;
    /* not balanced: not written */
    ck_assert_int_eq(photonmap_init(&m, 4, &e), SVET_OK);
    VECTOR3 p = { 0, 0, 0 }, d = { 0, 0, -1 };
    ck_assert(photonmap_store(&m, p, rad_grey(1), d, 0));
    FILE *f = tmpfile();
    ck_assert_ptr_nonnull(f);
    ck_assert_int_eq(photonmap_write(&m, f, &e), SVET_ERR_RANGE);
    ck_assert_ptr_nonnull(strstr(e.msg, "balanced"));
    fclose(f);
    photonmap_free(&m);
    /* the mark as this machine writes it, and reversed */
    const uint32_t mark = UINT32_C(0x01020304);
    unsigned char here[4], other[4];
    memcpy(here, &mark, 4);
    for (int i = 0; i < 4; i++)
        other[i] = here[3 - i];
    char line[64];
    snprintf(line, sizeof line, "photonmap 3 %zu\n", sizeof(photon_t));
    /* the well-formed file of 3 zero photons reads: the refusals below
     * differ from it in one thing each */
    f = file_of(line, here, 3 * sizeof(photon_t));
    ck_assert_int_eq(photonmap_read(&m, f, &e), SVET_OK);
    ck_assert_uint_eq(m.n, 3);
    photonmap_free(&m);
    fclose(f);
    refused(file_of(line, other, 3 * sizeof(photon_t)), "byte order");
    refused(file_of(line, here, 3 * sizeof(photon_t) - 1), "truncated");
    refused(file_of(line, NULL, 0), "truncated before");
    snprintf(line, sizeof line, "photonmap 3 %zu\n", sizeof(photon_t) + 4);
    refused(file_of(line, here, 3 * (sizeof(photon_t) + 4)),
            "-byte photons");
    refused(file_of("svet-part 3\n", here, 0), "not a photon map");
    refused(file_of("photonmap 3\n", here, 0), "not a photon map");
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("photonsave (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    /* wall-clock limit: the machine may be shared */
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, a_map_reads_back_as_the_same_heap);
    tcase_add_test(tc, two_maps_in_one_file_and_an_empty_one);
    tcase_add_test(tc, refusals);
    suite_add_tcase(s, tc);
    return s;
}
