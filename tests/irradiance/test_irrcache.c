/*
 * test_irrcache.c - the irradiance cache of ch. 9: Ward's weight; a record
 * read back at its own point; one record's gradients applied exactly; a
 * translational gradient limited where the clamp raised R; the octree's
 * lookups and the neighbour clamping bit for bit equal to brute force
 * over every record, with records outside the first bounds (the tree
 * grows); records in front of x left out; bad parameters.
 */
#include "testutil.h"
#include "core/rng.h"
#include "irradiance/irrcache.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static irr_record_t record_at(const VECTOR3 p, const VECTOR3 n, real e, real r)
{
    irr_record_t x;
    memset(&x, 0, sizeof x);
    vec_copy(x.p, p);
    vec_copy(x.n, n);
    x.e = rad_grey(e);
    x.r = r;
    return x;
}

START_TEST(ward_weight_and_a_record_read_at_its_own_point)
{
    VECTOR3 p = { 1, 2, 3 }, n = { 0, 0, 1 };
    irr_record_t r = record_at(p, n, 5, 2);
    VECTOR3 x = { 2, 2, 3 }, m = { 0, REAL_C(0.6), REAL_C(0.8) };
    /* 1 / (|x - p| / R + sqrt(1 - n . n_i)) */
    ck_assert_near(irrcache_weight(&r, x, n), 2, 1e-6);
    ck_assert_near(irrcache_weight(&r, x, m), 1 / (0.5 + sqrt(0.2)), 1e-6);
    ck_assert(isinf(irrcache_weight(&r, p, n)));
    irrcache_t c;
    VECTOR3 lo = { 0, 0, 0 }, hi = { 4, 4, 4 };
    ck_assert_int_eq(irrcache_init(&c, REAL_C(0.2), REAL_C(0.1), 4, lo, hi, NULL),
                     SVET_OK);
    ck_assert_int_eq(irrcache_add(&c, &r, NULL), SVET_OK);
    RADIANCE e;
    ck_assert_int_eq(irrcache_lookup(&c, p, n, &e), 1);
    ck_assert(e.r == 5 && e.g == 5 && e.b == 5);
    /* beyond the weight's reach (w <= 1 / a = 5 past |d| = R / 5): none */
    VECTOR3 far = { REAL_C(1.5), 2, 3 };
    ck_assert_int_eq(irrcache_lookup(&c, far, n, &e), 0);
    ck_assert(e.r == 0);
    irrcache_free(&c);
}
END_TEST

START_TEST(one_record_applies_its_gradients_exactly)
{
    VECTOR3 p = { 0, 0, 0 }, n = { 0, 0, 1 };
    irr_record_t r = record_at(p, n, 10, 10);
    vec_set(r.grad_t[0], REAL_C(0.5), REAL_C(-0.25), 0);
    vec_set(r.grad_r[1], REAL_C(0.3), REAL_C(0.7), 0);
    irrcache_t c;
    VECTOR3 lo = { -1, -1, -1 }, hi = { 1, 1, 1 };
    ck_assert_int_eq(irrcache_init(&c, REAL_C(0.5), 1, 10, lo, hi, NULL),
                     SVET_OK);
    ck_assert_int_eq(irrcache_add(&c, &r, NULL), SVET_OK);
    VECTOR3 x = { REAL_C(0.2), REAL_C(0.4), 0 };
    VECTOR3 m = { REAL_C(0.1), 0, 0 };
    m[Z] = sqrt(1 - m[X] * m[X]);
    RADIANCE e;
    ck_assert_int_eq(irrcache_lookup(&c, x, m, &e), 1);
    /* E + (n_i x n) . grad_r + (x - x_i) . grad_t, channel by channel */
    VECTOR3 cr;
    VVECTOR3(cr, n, m);
    ck_assert_near(e.r, 10 + 0.5 * 0.2 - 0.25 * 0.4, 1e-5);
    ck_assert_near(e.g, 10 + (double)SVECTOR3(cr, r.grad_r[1]), 1e-5);
    ck_assert_near(e.b, 10, 1e-5);
    c.gradients = false;
    ck_assert_int_eq(irrcache_lookup(&c, x, m, &e), 1);
    ck_assert(e.r == 10 && e.g == 10);
    irrcache_free(&c);
}
END_TEST

/* A record whose R the clamp raised from 0.1 to 1 keeps a translational
 * gradient measured over 0.1: 5 E per unit, 0.5 E across its own R. Used
 * 0.4 away (a = 0.5) it would predict 1 + 5 * 0.4 = 3 times E; scaled so
 * that |grad_t| R <= E, it predicts E (1 +/- 0.4), and never less than 0
 * (the channel whose gradient was within the limit keeps it). */
START_TEST(a_raised_radius_limits_the_gradient)
{
    VECTOR3 p = { 0, 0, 0 }, n = { 0, 0, 1 };
    irr_record_t r = record_at(p, n, 1, REAL_C(0.1));
    vec_set(r.grad_t[0], 5, 0, 0);
    vec_set(r.grad_t[1], REAL_C(0.5), 0, 0);
    irrcache_t c;
    VECTOR3 lo = { -1, -1, -1 }, hi = { 1, 1, 1 };
    ck_assert_int_eq(irrcache_init(&c, REAL_C(0.5), 1, 10, lo, hi, NULL),
                     SVET_OK);
    ck_assert_int_eq(irrcache_add(&c, &r, NULL), SVET_OK);
    ck_assert(c.rec[0].r == 1);
    /* the record keeps its gather's gradient; the limit is the lookup's */
    ck_assert(c.rec[0].grad_t[0][X] == 5 &&
              c.rec[0].grad_t[1][X] == REAL_C(0.5));
    VECTOR3 ahead = { REAL_C(0.4), 0, 0 }, behind = { REAL_C(-0.4), 0, 0 };
    RADIANCE e;
    ck_assert_int_eq(irrcache_lookup(&c, ahead, n, &e), 1);
    ck_assert_near(e.r, 1.4, 1e-6);
    ck_assert_near(e.g, 1.2, 1e-6);
    ck_assert_int_eq(irrcache_lookup(&c, behind, n, &e), 1);
    ck_assert_near(e.r, 0.6, 1e-6);
    ck_assert_near(e.g, 0.8, 1e-6);
    ck_assert_near(e.b, 1, 1e-6);
    irrcache_free(&c);
}
END_TEST

/* The brute force: every record, in order, with the same rules. */
static int brute_lookup(const irr_record_t *rec, size_t n, real a, bool grads,
                        const VECTOR3 x, const VECTOR3 nx, RADIANCE *e)
{
    double wsum = 0, s[3] = { 0, 0, 0 };
    int used = 0;
    for (size_t i = 0; i < n; i++) {
        const irr_record_t *r = &rec[i];
        real w = irrcache_weight(r, x, nx);
        if (!(w > 1 / a))
            continue;
        VECTOR3 d, nn;
        vec_sub(d, x, r->p);
        vec_add(nn, nx, r->n);
        if (SVECTOR3(d, nn) / 2 < REAL_C(-0.05) * r->r)
            continue;
        if (isinf(w)) {
            *e = r->e;
            return 1;
        }
        RADIANCE v = r->e;
        if (grads) {
            VECTOR3 cr;
            VVECTOR3(cr, r->n, nx);
            real add[3];
            for (int k = 0; k < 3; k++)
                add[k] = SVECTOR3(cr, r->grad_r[k]) + SVECTOR3(d, r->grad_t[k]);
            v = rad_add(v, rad_make(add[0], add[1], add[2]));
        }
        wsum += (double)w;
        s[0] += (double)w * (double)v.r;
        s[1] += (double)w * (double)v.g;
        s[2] += (double)w * (double)v.b;
        used++;
    }
    *e = used ? rad_make((real)(s[0] / wsum), (real)(s[1] / wsum),
                         (real)(s[2] / wsum))
              : rad_grey(0);
    return used;
}

START_TEST(octree_and_clamping_equal_brute_force)
{
    pcg32_t g;
    pcg32_seed(&g, 90, 1);
    const real a = REAL_C(0.25), rmin = REAL_C(0.02), rmax = REAL_C(0.8);
    irrcache_t c;
    /* first bounds smaller than where the records go: the tree grows */
    VECTOR3 lo = { 0, 0, 0 }, hi = { REAL_C(0.5), REAL_C(0.5), REAL_C(0.5) };
    ck_assert_int_eq(irrcache_init(&c, a, rmin, rmax, lo, hi, NULL), SVET_OK);
    const size_t n = 3000;
    irr_record_t *ref = malloc(sizeof *ref * n);
    /* records on the floor, a wall and a tilted plane of a 4 x 4 x 4 room */
    for (size_t i = 0; i < n; i++) {
        VECTOR3 p, nn;
        int plane = (int)(i % 3);
        real u = 4 * pcg32_real(&g), v = 4 * pcg32_real(&g);
        if (plane == 0) {
            vec_set(p, u, 0, v);
            vec_set(nn, 0, 1, 0);
        } else if (plane == 1) {
            vec_set(p, 0, u, v);
            vec_set(nn, 1, 0, 0);
        } else {
            vec_set(p, u, v, REAL_C(0.5) * u);
            vec_set(nn, REAL_C(-0.4472136), 0, REAL_C(0.8944272));
        }
        irr_record_t r = record_at(p, nn, 1 + pcg32_real(&g),
                                   REAL_C(1.2) * pcg32_real(&g));
        for (int k = 0; k < 3; k++)
            for (int m = 0; m < 3; m++) {
                r.grad_r[k][m] = pcg32_real(&g) - REAL_C(0.5);
                r.grad_t[k][m] = pcg32_real(&g) - REAL_C(0.5);
            }
        ck_assert_int_eq(irrcache_add(&c, &r, NULL), SVET_OK);
        /* the brute-force clamping against every earlier record */
        irr_record_t *nr = &ref[i];
        *nr = r;
        nr->r = nr->r < rmin ? rmin : nr->r > rmax ? rmax : nr->r;
        for (size_t j = 0; j < i; j++) {
            real dist = vec_distance(nr->p, ref[j].p);
            if (nr->r > ref[j].r + dist)
                nr->r = ref[j].r + dist;
            if (ref[j].r > nr->r + dist)
                ref[j].r = nr->r + dist;
        }
    }
    for (size_t i = 0; i < n; i++)
        ck_assert(c.rec[i].r == ref[i].r);
    /* the clamping did something: not every R stayed as drawn */
    int clamped = 0;
    for (size_t i = 0; i < n; i++)
        clamped += ref[i].r < rmax && ref[i].r > rmin;
    ck_assert_int_gt(clamped, 100);
    long used = 0;
    for (int q = 0; q < 4000; q++) {
        VECTOR3 x, nx;
        int plane = q % 3;
        real u = 4 * pcg32_real(&g), v = 4 * pcg32_real(&g);
        if (plane == 0) {
            vec_set(x, u, 0, v);
            vec_set(nx, 0, 1, 0);
        } else if (plane == 1) {
            vec_set(x, 0, u, v);
            vec_set(nx, 1, 0, 0);
        } else {
            vec_set(x, u, v, REAL_C(0.5) * u);
            vec_set(nx, REAL_C(-0.4472136), 0, REAL_C(0.8944272));
        }
        RADIANCE e1, e2;
        int n1 = irrcache_lookup(&c, x, nx, &e1);
        int n2 = brute_lookup(ref, n, a, true, x, nx, &e2);
        ck_assert_int_eq(n1, n2);
        ck_assert(e1.r == e2.r && e1.g == e2.g && e1.b == e2.b);
        used += n1;
    }
    ck_assert_int_gt(used, 1000); /* the lookups do find records */
    irrcache_free(&c);
    free(ref);
}
END_TEST

START_TEST(a_record_in_front_is_left_out)
{
    /* a record on a step 0.1 above the floor, facing up: x on the floor
     * below it sees what the record cannot */
    VECTOR3 p = { 0, REAL_C(0.1), 0 }, up = { 0, 1, 0 }, x = { REAL_C(0.05), 0, 0 };
    irr_record_t r = record_at(p, up, 3, 1);
    irrcache_t c;
    VECTOR3 lo = { -1, -1, -1 }, hi = { 1, 1, 1 };
    ck_assert_int_eq(irrcache_init(&c, REAL_C(0.5), REAL_C(0.5), 1, lo, hi, NULL),
                     SVET_OK);
    ck_assert_int_eq(irrcache_add(&c, &r, NULL), SVET_OK);
    RADIANCE e;
    ck_assert_int_eq(irrcache_lookup(&c, x, up, &e), 0);
    /* the same record below x is used */
    VECTOR3 above = { REAL_C(0.05), REAL_C(0.12), 0 };
    ck_assert_int_eq(irrcache_lookup(&c, above, up, &e), 1);
    irrcache_free(&c);
}
END_TEST

START_TEST(bad_parameters_and_records)
{
    irrcache_t c;
    svet_error e;
    VECTOR3 lo = { 0, 0, 0 }, hi = { 1, 1, 1 };
    ck_assert_int_eq(irrcache_init(&c, 0, 1, 2, lo, hi, &e), SVET_ERR_RANGE);
    ck_assert_ptr_nonnull(strstr(e.msg, "a = 0"));
    ck_assert_int_eq(irrcache_init(&c, REAL_C(0.2), 2, 1, lo, hi, &e),
                     SVET_ERR_RANGE);
    ck_assert_int_eq(irrcache_init(&c, REAL_C(0.2), (real)NAN, 1, lo, hi, &e),
                     SVET_ERR_RANGE);
    ck_assert_int_eq(irrcache_init(&c, REAL_C(0.2), 1, 2, lo, hi, &e), SVET_OK);
    VECTOR3 p = { (real)NAN, 0, 0 }, n = { 0, 0, 1 };
    irr_record_t r = record_at(p, n, 1, 1);
    ck_assert_int_eq(irrcache_add(&c, &r, &e), SVET_ERR_RANGE);
    ck_assert_int_eq((int)c.n, 0);
    irrcache_free(&c);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("irrcache (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, ward_weight_and_a_record_read_at_its_own_point);
    tcase_add_test(tc, one_record_applies_its_gradients_exactly);
    tcase_add_test(tc, a_raised_radius_limits_the_gradient);
    tcase_add_test(tc, octree_and_clamping_equal_brute_force);
    tcase_add_test(tc, a_record_in_front_is_left_out);
    tcase_add_test(tc, bad_parameters_and_records);
    suite_add_tcase(s, tc);
    return s;
}
