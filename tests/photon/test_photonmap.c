/*
 * test_photonmap.c - the photon map of ch. 8: the balanced heap is a
 * left-balanced kd-tree, the same for any thread count; k-nearest queries
 * equal brute force as sets and in order (random, clustered, planar,
 * duplicate sets, one photon, k beyond the map); the density estimate on
 * a uniformly lit plane has the mean the k-nearest estimate is known to
 * have (k / (k - 1) times the exact value, and the filters' own factors)
 * with the spread near 1 / sqrt(k); directions, refusals.
 */
#include "testutil.h"
#include "core/rng.h"
#include "photon/photonmap.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

typedef enum { SET_UNIFORM, SET_CLUSTERED, SET_PLANE, SET_DUPLICATES } set_t;

static void fill(photonmap_t *m, size_t n, set_t kind, uint64_t seed)
{
    svet_error e;
    ck_assert_int_eq(photonmap_init(m, n, &e), SVET_OK);
    pcg32_t g;
    pcg32_seed(&g, seed, 1);
    VECTOR3 centres[5];
    for (int c = 0; c < 5; c++)
        vec_set(centres[c], pcg32_real(&g), pcg32_real(&g), pcg32_real(&g));
    VECTOR3 down = { 0, 0, -1 };
    for (size_t i = 0; i < n; i++) {
        VECTOR3 p = { pcg32_real(&g), pcg32_real(&g), pcg32_real(&g) };
        if (kind == SET_CLUSTERED) {
            const real *c = centres[pcg32_next(&g) % 5];
            for (int k = 0; k < 3; k++)
                p[k] = c[k] + REAL_C(0.01) * (p[k] - REAL_C(0.5));
        } else if (kind == SET_PLANE) {
            p[Z] = REAL_C(0.5);
        } else if (kind == SET_DUPLICATES) {
            /* 20 distinct positions, many photons on each */
            real v = (real)(pcg32_next(&g) % 20) / 20;
            vec_set(p, v, 1 - v, v * v);
        }
        ck_assert(photonmap_store(m, p, rad_grey(1), down, 0));
    }
}

/* every node's left subtree lies at or below its split, the right at or
 * above: checked against the node's own coordinate down each subtree */
static void check_subtree(const photonmap_t *m, size_t i, int axis, float v,
                          bool left)
{
    if (i > m->n)
        return;
    float c = m->ph[i].pos[axis];
    ck_assert(left ? c <= v : c >= v);
    check_subtree(m, 2 * i, axis, v, left);
    check_subtree(m, 2 * i + 1, axis, v, left);
}

START_TEST(the_heap_is_a_kd_tree_and_the_same_for_any_thread_count)
{
    static const size_t sizes[] = { 1, 2, 3, 7, 100, 1000, 150000 };
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        size_t n = sizes[s];
        photonmap_t a, b;
        svet_error e;
        fill(&a, n, s % 2 ? SET_DUPLICATES : SET_UNIFORM, 3 + s);
        fill(&b, n, s % 2 ? SET_DUPLICATES : SET_UNIFORM, 3 + s);
        omp_set_num_threads(1);
        ck_assert_int_eq(photonmap_balance(&a, &e), SVET_OK);
        omp_set_num_threads(2);
        ck_assert_int_eq(photonmap_balance(&b, &e), SVET_OK);
        ck_assert(memcmp(&a.ph[1], &b.ph[1], n * sizeof(photon_t)) == 0);
        if (n <= 1000)
            for (size_t i = 1; i <= n; i++) {
                int axis = a.ph[i].axis;
                ck_assert_int_lt(axis, 3);
                check_subtree(&a, 2 * i, axis, a.ph[i].pos[axis], true);
                check_subtree(&a, 2 * i + 1, axis, a.ph[i].pos[axis], false);
            }
        photonmap_free(&a);
        photonmap_free(&b);
    }
}
END_TEST

/* the k nearest by brute force, with the same distance arithmetic and the
 * same tie-break (lower heap index first) */
typedef struct {
    real d2;
    int32_t i;
} cand_t;

static int by_distance(const void *x, const void *y)
{
    const cand_t *a = x, *b = y;
    if (a->d2 != b->d2)
        return a->d2 < b->d2 ? -1 : 1;
    return (a->i > b->i) - (a->i < b->i);
}

static int brute(const photonmap_t *m, const VECTOR3 x, int k, real rmax,
                 cand_t *c)
{
    int n = 0;
    for (size_t i = 1; i <= m->n; i++) {
        const photon_t *p = &m->ph[i];
        real dx = (real)p->pos[0] - x[0], dy = (real)p->pos[1] - x[1];
        real dz = (real)p->pos[2] - x[2];
        real d2 = dx * dx + dy * dy + dz * dz;
        if (d2 <= rmax * rmax) {
            c[n].d2 = d2;
            c[n].i = (int32_t)i;
            n++;
        }
    }
    qsort(c, (size_t)n, sizeof *c, by_distance);
    return n < k ? n : k;
}

START_TEST(nearest_photons_equal_brute_force_in_order)
{
    static const struct {
        size_t n;
        set_t kind;
    } sets[] = { { 3000, SET_UNIFORM }, { 3000, SET_CLUSTERED },
                 { 2000, SET_PLANE }, { 2000, SET_DUPLICATES }, { 1, SET_UNIFORM },
                 { 5, SET_UNIFORM } };
    static const int ks[] = { 1, 2, 8, 50, 300, 6000 };
    static const real radii[] = { REAL_C(0.05), REAL_C(0.2), 10 };
    cand_t *c = malloc(sizeof *c * 3001);
    int32_t *idx = malloc(sizeof *idx * 6000);
    real *d2 = malloc(sizeof *d2 * 6000);
    pcg32_t g;
    pcg32_seed(&g, 60, 2);
    long n = 0;
    for (size_t s = 0; s < sizeof sets / sizeof sets[0]; s++) {
        photonmap_t m;
        svet_error e;
        fill(&m, sets[s].n, sets[s].kind, 10 + s);
        ck_assert_int_eq(photonmap_balance(&m, &e), SVET_OK);
        for (int q = 0; q < 60; q++) {
            /* query points inside and around the set, and on photons */
            VECTOR3 x = { REAL_C(1.4) * pcg32_real(&g) - REAL_C(0.2),
                          REAL_C(1.4) * pcg32_real(&g) - REAL_C(0.2),
                          REAL_C(1.4) * pcg32_real(&g) - REAL_C(0.2) };
            if (q % 4 == 0)
                for (int k = 0; k < 3; k++)
                    x[k] = (real)m.ph[1 + pcg32_next(&g) % m.n].pos[k];
            for (size_t ki = 0; ki < sizeof ks / sizeof ks[0]; ki++)
                for (size_t ri = 0; ri < 3; ri++, n++) {
                    int k = ks[ki];
                    int got = photonmap_nearest(&m, x, k, radii[ri], idx, d2);
                    int want = brute(&m, x, k, radii[ri], c);
                    ck_assert_int_eq(got, want);
                    for (int i = 0; i < got; i++) {
                        ck_assert_int_eq(idx[i], c[i].i);
                        ck_assert(d2[i] == c[i].d2);
                    }
                }
        }
        photonmap_free(&m);
    }
    /* every photon in one place: the ties go to heap indices 1, 2, 3, ...
     * which lie on both sides of every split */
    photonmap_t m;
    ck_assert_int_eq(photonmap_init(&m, 1000, NULL), SVET_OK);
    VECTOR3 p = { REAL_C(0.5), REAL_C(0.25), 1 }, d = { 0, 0, -1 };
    for (int i = 0; i < 1000; i++)
        ck_assert(photonmap_store(&m, p, rad_grey(1), d, 0));
    ck_assert_int_eq(photonmap_balance(&m, NULL), SVET_OK);
    ck_assert_int_eq(photonmap_nearest(&m, p, 10, 1, idx, d2), 10);
    for (int i = 0; i < 10; i++)
        ck_assert_int_eq(idx[i], i + 1);
    photonmap_free(&m);
    free(c);
    free(idx);
    free(d2);
    test_report_cases("nearest_photons_equal_brute_force_in_order", n);
}
END_TEST

/* Photons uniform over the unit square z = 0, total power 1, arriving
 * straight down: irradiance 1 everywhere. With r the distance to the
 * k-th nearest, pi r^2 lambda is Gamma(k, 1) (a Poisson process, which N
 * uniform photons approach), so the plain estimate k dPhi / (pi r^2) has
 * mean E k / (k - 1) and standard deviation E k / ((k - 1) sqrt(k - 2));
 * a filter with mean weight N_f over the disc and weight w_1 at its rim
 * has mean E (1 + w_1 / (N_f (k - 1))), the other k - 1 photons being
 * uniform inside the disc. */
static void density_case(photonmap_filter_t filter, double n_f, double w_1)
{
    const size_t n = 400000;
    const int k = 50;
    photonmap_t m;
    svet_error e;
    ck_assert_int_eq(photonmap_init(&m, n, &e), SVET_OK);
    pcg32_t g;
    pcg32_seed(&g, 60, 3);
    VECTOR3 down = { 0, 0, -1 }, up = { 0, 0, 1 };
    for (size_t i = 0; i < n; i++) {
        VECTOR3 p = { pcg32_real(&g), pcg32_real(&g), 0 };
        ck_assert(photonmap_store(&m, p, rad_grey((real)(1.0 / (double)n)),
                                  down, 0));
    }
    ck_assert_int_eq(photonmap_balance(&m, &e), SVET_OK);
    photonmap_query_t q = { k, REAL_C(0.1), filter, REAL_C(1.1), 0 };
    /* queries on a grid whose spacing is several search radii (r is about
     * sqrt(k / (pi n)) = 0.0063), so that they share no photon */
    double sum = 0, sum2 = 0;
    int nq = 0;
    for (int i = 0; i < 30; i++)
        for (int j = 0; j < 30; j++, nq++) {
            VECTOR3 x = { REAL_C(0.2) + REAL_C(0.02) * (real)i,
                          REAL_C(0.2) + REAL_C(0.02) * (real)j, 0 };
            double v = (double)photonmap_irradiance(&m, x, up, &q).g;
            sum += v;
            sum2 += v * v;
        }
    double mean = sum / nq, sd = sqrt(fmax(0, sum2 / nq - mean * mean));
    double expect = 1 + w_1 / (n_f * (k - 1));
    /* four standard errors of the mean, from the sample itself */
    ck_assert_msg(fabs(mean - expect) < 4 * sd / sqrt((double)nq),
                  "filter %d: mean %g, expected %g (sd %g)", filter, mean,
                  expect, sd);
    /* the spread: near 1 / sqrt(k - 2) for the plain estimate; a filter
     * weighs fewer photons fully, so its spread is larger, not smaller */
    double plain_sd = (double)k / ((k - 1) * sqrt((double)k - 2));
    ck_assert_msg(sd > 0.8 * plain_sd && sd < 1.6 * plain_sd,
                  "filter %d: sd %g against %g", filter, sd, plain_sd);
    /* from below the surface nothing arrives */
    VECTOR3 x = { REAL_C(0.5), REAL_C(0.5), 0 };
    ck_assert(photonmap_irradiance(&m, x, down, &q).g == 0);
    photonmap_free(&m);
}

START_TEST(density_estimate_on_a_uniformly_lit_plane)
{
    const double c = 1.1, a = 0.918, b = 1.953;
    density_case(PHOTONMAP_FILTER_NONE, 1, 1);
    density_case(PHOTONMAP_FILTER_CONE, 1 - 2 / (3 * c), 1 - 1 / c);
    double n_g = a * (1 - (1 - (2 / b) * (1 - exp(-b / 2))) / (1 - exp(-b)));
    double w_g = a * (1 - (1 - exp(-b / 2)) / (1 - exp(-b)));
    density_case(PHOTONMAP_FILTER_GAUSSIAN, n_g, w_g);
}
END_TEST

START_TEST(a_photon_on_another_surface_is_left_out_by_the_disc)
{
    /* a floor lit at z = 0 and, 0.001 below it, a second surface lit
     * from above too (as the far side of a thin wall would be): the disc
     * keeps the estimate to the floor's photons */
    const size_t n = 20000;
    photonmap_t m;
    ck_assert_int_eq(photonmap_init(&m, 2 * n, NULL), SVET_OK);
    pcg32_t g;
    pcg32_seed(&g, 60, 4);
    VECTOR3 down = { 0, 0, -1 }, up = { 0, 0, 1 };
    for (size_t i = 0; i < 2 * n; i++) {
        VECTOR3 p = { pcg32_real(&g), pcg32_real(&g),
                      i < n ? 0 : REAL_C(-0.001) };
        ck_assert(photonmap_store(&m, p, rad_grey((real)(1.0 / n)), down, 0));
    }
    ck_assert_int_eq(photonmap_balance(&m, NULL), SVET_OK);
    photonmap_query_t all = { 100, REAL_C(0.5), PHOTONMAP_FILTER_NONE, 1, 0 };
    photonmap_query_t disc = all;
    disc.disc = REAL_C(0.02);
    /* the same k nearest and the same radius, so the disc's estimate is
     * the full one times the share of the floor's photons among them */
    int32_t idx[100];
    real d2[100];
    for (int i = 0; i < 20; i++) {
        VECTOR3 x = { REAL_C(0.2) + REAL_C(0.03) * (real)i, REAL_C(0.5), 0 };
        real both = photonmap_irradiance(&m, x, up, &all).g;
        real one = photonmap_irradiance(&m, x, up, &disc).g;
        int found = photonmap_nearest(&m, x, 100, REAL_C(0.5), idx, d2);
        ck_assert_int_eq(found, 100);
        int floor_photons = 0;
        for (int j = 0; j < found; j++)
            floor_photons += m.ph[idx[j]].pos[2] == 0;
        ck_assert(floor_photons > 0 && floor_photons < 100);
        ck_assert_near(one, both * (real)floor_photons / 100,
                       16 * (double)REAL_EPSILON * (double)both);
    }
    photonmap_free(&m);
}
END_TEST

START_TEST(directions_round_trip_within_one_bin)
{
    pcg32_t g;
    pcg32_seed(&g, 60, 5);
    photonmap_t m;
    ck_assert_int_eq(photonmap_init(&m, 20000, NULL), SVET_OK);
    VECTOR3 o = { 0, 0, 0 };
    for (int i = 0; i < 20000; i++) {
        real z = 1 - 2 * pcg32_real(&g), f = 2 * REAL_PI * pcg32_real(&g);
        real r = sqrt(fmax(REAL_C(0.0), 1 - z * z));
        VECTOR3 d = { r * cos(f), r * sin(f), z }, back;
        if (i == 0)
            vec_set(d, 0, 0, 1);
        if (i == 1)
            vec_set(d, 0, 0, -1);
        ck_assert(photonmap_store(&m, o, rad_grey(1), d, 0));
        photonmap_direction(&m.ph[i], back);
        /* half a bin in theta (0.35 degrees) and in phi times sin(theta)
         * (0.7 degrees at the equator): within 1 degree */
        ck_assert(SVECTOR3(d, back) > cos(REAL_PI / 180));
    }
    photonmap_free(&m);
}
END_TEST

START_TEST(refusals_before_any_allocation)
{
    photonmap_t m;
    svet_error e;
    ck_assert_int_eq(photonmap_init(&m, 0, &e), SVET_ERR_RANGE);
    ck_assert_ptr_nonnull(strstr(e.msg, "0 photons"));
    /* 2^31 photons: past the heap's index range */
    ck_assert_int_eq(photonmap_init(&m, (size_t)1 << 31, &e), SVET_ERR_RANGE);
    /* more than memory: 2e9 photons need 112 GB */
    ck_assert_int_eq(photonmap_init(&m, 2000000000, &e), SVET_ERR_NOMEM);
    ck_assert_ptr_nonnull(strstr(e.msg, "GB"));
    ck_assert_ptr_null(m.ph);
    /* a full map and a balanced one refuse more photons, and NaN */
    ck_assert_int_eq(photonmap_init(&m, 2, &e), SVET_OK);
    VECTOR3 p = { 0, 0, 0 }, d = { 0, 0, 1 }, bad = { (real)NAN, 0, 0 };
    ck_assert(!photonmap_store(&m, bad, rad_grey(1), d, 0));
    ck_assert(!photonmap_store(&m, p, rad_grey((real)INFINITY), d, 0));
    ck_assert(photonmap_store(&m, p, rad_grey(1), d, 0));
    ck_assert(photonmap_store(&m, p, rad_grey(1), d, 0));
    ck_assert(!photonmap_store(&m, p, rad_grey(1), d, 0));
    ck_assert_int_eq(photonmap_balance(&m, &e), SVET_OK);
    m.cap = 10;
    ck_assert(!photonmap_store(&m, p, rad_grey(1), d, 0));
    /* k of 0, a negative or NaN radius: nothing found */
    int32_t idx[2];
    real d2[2];
    ck_assert_int_eq(photonmap_nearest(&m, p, 0, 1, idx, d2), 0);
    ck_assert_int_eq(photonmap_nearest(&m, p, 2, -1, idx, d2), 0);
    ck_assert_int_eq(photonmap_nearest(&m, p, 2, (real)NAN, idx, d2), 0);
    /* two photons at the query point: no radius to divide by, 0 */
    photonmap_query_t q = { 2, 1, PHOTONMAP_FILTER_NONE, 1, 0 };
    VECTOR3 n = { 0, 0, -1 };
    ck_assert(photonmap_irradiance(&m, p, n, &q).g == 0);
    photonmap_free(&m);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("photonmap (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    /* wall-clock limit: the machine may be shared, check's 4 s is not enough */
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, the_heap_is_a_kd_tree_and_the_same_for_any_thread_count);
    tcase_add_test(tc, nearest_photons_equal_brute_force_in_order);
    tcase_add_test(tc, density_estimate_on_a_uniformly_lit_plane);
    tcase_add_test(tc, a_photon_on_another_surface_is_left_out_by_the_disc);
    tcase_add_test(tc, directions_round_trip_within_one_bin);
    tcase_add_test(tc, refusals_before_any_allocation);
    suite_add_tcase(s, tc);
    return s;
}
