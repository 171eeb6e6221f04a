/*
 * test_box.c - the axis-aligned box of app. D: exact entry and exit hits,
 * face numbers and frames, the open interval, rays parallel to a face and
 * in its plane, edges and corners, input checks, sampling by face area,
 * the geomcheck harness (convex), tests/vectors/box.csv and a NaN sweep.
 */
#include "testutil.h"
#include "geometry/box.h"
#include "geomcheck.h"
#include "primcheck.h"

#include <string.h>

static COBJECT *box(real x0, real y0, real z0, real x1, real y1, real z1)
{
    VECTOR3 lo = { x0, y0, z0 }, hi = { x1, y1, z1 };
    svet_error err;
    COBJECT *o = box_new(lo, hi, &err);
    ck_assert_msg(o != NULL, "%s", err.msg);
    return o;
}

START_TEST(box_entry_and_exit_hits_are_exact)
{
    COBJECT *o = box(1, 2, 3, 2, 4, 7);
    ray_t r = { { -1, REAL_C(2.5), REAL_C(3.25) }, { 4, 0, 0 } };
    hit_t h;
    ck_assert(cobject_intersect(o, &r, 0, (real)INFINITY, &h));
    ck_assert(h.t == REAL_C(0.5));
    PATHPOINT pp;
    cobject_fill(o, &r, &h, &pp);
    ck_assert(pp.prim == BOX_XMIN);
    ck_assert(pp.cross_point[X] == 1 && pp.cross_point[Y] == REAL_C(2.5) &&
              pp.cross_point[Z] == REAL_C(3.25));
    ck_assert(pp.ng[X] == -1 && pp.ng[Y] == 0 && pp.ng[Z] == 0);
    ck_assert(pp.p_error[X] == 0);
    /* on a min face of x: u = +z, v = +y; st along z and y over the box */
    ck_assert(pp.u[Z] == 1 && pp.v[Y] == 1);
    ck_assert(pp.st[0] == REAL_C(0.0625) && pp.st[1] == REAL_C(0.25));
    ck_assert(pp.dpds[Z] == 4 && pp.dpdt[Y] == 2);
    /* from inside: the exit face */
    ray_t in = { { REAL_C(1.5), 3, 5 }, { 0, 0, -1 } };
    ck_assert(cobject_intersect(o, &in, 0, (real)INFINITY, &h));
    cobject_fill(o, &in, &h, &pp);
    ck_assert(pp.prim == BOX_ZMIN && pp.cross_point[Z] == 3 &&
              pp.ng[Z] == -1);
    ck_assert_near(h.t, 2, 8 * REAL_EPSILON);
    ck_assert(o->ops->area(o) == 2 * (2 + 8 + 4));
    bbox_t b;
    o->ops->bounds(o, -1, &b);
    ck_assert(b.min[X] == 1 && b.max[Z] == 7);
    cobject_free(o);
}
END_TEST

START_TEST(every_face_has_an_outward_right_handed_frame)
{
    COBJECT *o = box(-1, -2, -3, 1, 2, 3);
    for (int f = 0; f < 6; f++) {
        int k = f / 2;
        real sgn = (f & 1) ? 1 : -1;
        ray_t r;
        vec_set(r.o, REAL_C(0.1), REAL_C(0.2), REAL_C(0.3));
        r.o[k] = 10 * sgn;
        vec_set(r.d, 0, 0, 0);
        r.d[k] = -sgn;
        hit_t h;
        ck_assert(cobject_intersect(o, &r, 0, (real)INFINITY, &h));
        PATHPOINT pp;
        cobject_fill(o, &r, &h, &pp);
        ck_assert_int_eq(pp.prim, f);
        ck_assert(pp.ng[k] == sgn && pp.n[k] == sgn);
        VECTOR3 c;
        VVECTOR3(c, pp.u, pp.v);
        for (int j = 0; j < 3; j++)
            ck_assert(c[j] == pp.n[j]);
        ck_assert(pp.bout);
    }
    cobject_free(o);
}
END_TEST

START_TEST(box_respects_the_open_interval)
{
    COBJECT *o = box(0, 0, 0, 1, 1, 1);
    real inf = (real)INFINITY;
    ray_t r = { { REAL_C(0.5), REAL_C(0.5), 3 }, { 0, 0, -1 } };
    hit_t h;
    ck_assert(!cobject_intersect(o, &r, 0, 2, &h));
    ck_assert(cobject_intersect(o, &r, 0, nextafter(REAL_C(2.0), inf), &h));
    /* tmin past the entry: the exit face */
    ck_assert(cobject_intersect(o, &r, 2, inf, &h));
    ck_assert_near(h.t, 3, 16 * REAL_EPSILON); /* the exit is pushed out by 2 gamma(3) */
    ck_assert(!cobject_intersect(o, &r, REAL_C(3.1), inf, &h));
    ray_t away = { { REAL_C(0.5), REAL_C(0.5), 3 }, { 0, 0, 1 } };
    ck_assert(!cobject_intersect(o, &away, 0, inf, &h));
    cobject_free(o);
}
END_TEST

START_TEST(a_ray_whose_slab_times_overflow_never_hits)
{
    /* A ray far beyond the x slab, moving away from it slowly: its slab
     * times (1 - o_x) / d_x overflow to -infinity, and the other slabs
     * alone would let it in at t = 4. It never reaches the box; nor do
     * the rays moving toward it from there, whose entry overflows to
     * +infinity. Origins from 2^100 to REAL_MAX (float: all overflow at
     * d_x = 2^-40; double: those from 2^984). */
    COBJECT *o = box(-1, -1, -1, 1, 1, 1);
    hit_t h;
    long n = 0;
    for (int e = 100; e <= REAL_MAX_EXP; e += 4) {
        for (int s = -1; s <= 1; s += 2, n++) {
            real far = e == REAL_MAX_EXP ? REAL_MAX : ldexp(REAL_C(1.0), e - 1);
            ray_t away = { { s * far, 5, 0 },
                           { s * ldexp(REAL_C(1.0), -40), -1, 0 } };
            ray_t toward = away;
            toward.d[X] = -away.d[X];
            ck_assert_msg(!cobject_intersect(o, &away, 0, (real)INFINITY, &h),
                          "o_x %a moving away: hit at %a", (double)away.o[X],
                          (double)h.t);
            ck_assert_msg(!cobject_intersect(o, &toward, 0, (real)INFINITY,
                                             &h),
                          "o_x %a moving toward: hit at %a",
                          (double)toward.o[X], (double)h.t);
        }
    }
    test_report_cases("a_ray_whose_slab_times_overflow_never_hits", 2 * n);
    cobject_free(o);
}
END_TEST

START_TEST(rays_parallel_to_a_face_and_in_its_plane)
{
    COBJECT *o = box(0, 0, 0, 1, 1, 1);
    real inf = (real)INFINITY;
    hit_t h;
    PATHPOINT pp;
    /* parallel to the y faces, outside: miss; just inside: hit */
    ray_t out = { { -1, REAL_C(-0.01), REAL_C(0.5) }, { 1, 0, 0 } };
    ck_assert(!cobject_intersect(o, &out, 0, inf, &h));
    ray_t over = { { -1, REAL_C(1.01), REAL_C(0.5) }, { 1, 0, 0 } };
    ck_assert(!cobject_intersect(o, &over, 0, inf, &h));
    /* in the plane y = 0 of a face: counts as inside, enters by x = 0 */
    ray_t in = { { -1, 0, REAL_C(0.5) }, { 1, 0, 0 } };
    ck_assert(cobject_intersect(o, &in, 0, inf, &h) && h.t == 1);
    cobject_fill(o, &in, &h, &pp);
    ck_assert(pp.prim == BOX_XMIN && vec_is_finite(pp.cross_point));
    /* in the plane of a face and along an edge of it */
    ray_t edge = { { -1, 0, 0 }, { 1, 0, 0 } };
    ck_assert(cobject_intersect(o, &edge, 0, inf, &h) && h.t == 1);
    /* through a corner, diagonally, and through an edge from outside */
    ray_t corner = { { -1, -1, -1 }, { 1, 1, 1 } };
    ck_assert(cobject_intersect(o, &corner, 0, inf, &h) && h.t == 1);
    cobject_fill(o, &corner, &h, &pp);
    ck_assert(pp.cross_point[X] == 0 && pp.cross_point[Y] == 0 &&
              pp.cross_point[Z] == 0);
    ray_t through = { { -1, REAL_C(-1.5), REAL_C(0.3) }, { 2, 3, 0 } };
    ck_assert(cobject_intersect(o, &through, 0, inf, &h));
    cobject_free(o);
}
END_TEST

START_TEST(no_ray_slips_through_the_edges_of_a_box)
{
    COBJECT *o = box(REAL_C(-0.7), REAL_C(0.2), REAL_C(-1.3), REAL_C(0.9),
                     REAL_C(1.1), REAL_C(-0.4));
    bbox_t b;
    o->ops->bounds(o, -1, &b);
    pcg32_t g;
    pcg32_seed(&g, 31, 32);
    long n = 0;
    for (int i = 0; i < 30000; i++, n++) {
        /* a point on a random edge, a ray at it from inside and one from
         * outside, both must hit */
        VECTOR3 p, c;
        int a = (int)pcg32_bounded(&g, 3);
        for (int k = 0; k < 3; k++)
            p[k] = (pcg32_next(&g) & 1) ? b.max[k] : b.min[k];
        p[a] = b.min[a] + pcg32_real(&g) * (b.max[a] - b.min[a]);
        bbox_centroid(c, &b);
        ray_t r;
        vec_copy(r.o, c);
        vec_sub(r.d, p, c);
        hit_t h;
        ck_assert_msg(cobject_intersect(o, &r, 0, (real)INFINITY, &h),
                      "ray %d from inside slips through", i);
        vec_add_scaled(r.o, p, 1, r.d);
        vec_neg(r.d, r.d);
        ck_assert_msg(cobject_intersect(o, &r, 0, (real)INFINITY, &h),
                      "ray %d from outside slips through", i);
    }
    test_report_cases("no_ray_slips_through_the_edges_of_a_box", n);
    cobject_free(o);
}
END_TEST

START_TEST(box_rejects_bad_input_and_allows_a_flat_box)
{
    VECTOR3 lo = { 0, 0, 0 }, hi = { 1, 1, 1 }, nan = { 0, (real)NAN, 0 };
    svet_error err;
    ck_assert_ptr_null(box_new(hi, lo, &err));
    ck_assert_int_eq(err.status, SVET_ERR_RANGE);
    ck_assert_msg(strstr(err.msg, "min x = 1 > max x = 0") != NULL, "%s",
                  err.msg);
    ck_assert_ptr_null(box_new(nan, hi, &err));
    ck_assert_int_eq(err.status, SVET_ERR_RANGE);
    ck_assert_ptr_null(box_new(lo, lo, &err)); /* a point: no area */
    ck_assert_int_eq(err.status, SVET_ERR_RANGE);
    VECTOR3 line = { 1, 0, 0 };
    ck_assert_ptr_null(box_new(lo, line, &err));
    VECTOR3 m = { -REAL_MAX, 0, 0 }, M = { REAL_MAX, 1, 1 };
    ck_assert_ptr_null(box_new(m, M, &err)); /* extent overflows */
    ck_assert_ptr_null(box_new(hi, lo, NULL));
    /* flat in z: a double-sided square; hit from both sides, sampled only
     * on its two real faces */
    VECTOR3 flat = { 1, 1, 0 };
    COBJECT *o = box_new(lo, flat, &err);
    ck_assert_msg(o != NULL, "%s", err.msg);
    ck_assert(o->ops->area(o) == 2);
    ray_t down = { { REAL_C(0.5), REAL_C(0.5), 1 }, { 0, 0, -1 } };
    ray_t up = { { REAL_C(0.5), REAL_C(0.5), -1 }, { 0, 0, 1 } };
    hit_t h;
    PATHPOINT pp;
    ck_assert(cobject_intersect(o, &down, 0, (real)INFINITY, &h));
    cobject_fill(o, &down, &h, &pp);
    ck_assert(pp.prim == BOX_ZMAX && pp.ng[Z] == 1);
    ck_assert(cobject_intersect(o, &up, 0, (real)INFINITY, &h));
    cobject_fill(o, &up, &h, &pp);
    ck_assert(pp.prim == BOX_ZMIN && pp.ng[Z] == -1);
    pcg32_t g;
    pcg32_seed(&g, 1, 1);
    for (int i = 0; i < 1000; i++) {
        real u[2] = { pcg32_real(&g), pcg32_real(&g) };
        cobject_sample_t s;
        o->ops->sample(o, u, &s);
        ck_assert(s.n[Z] != 0 && s.p[Z] == 0 && s.pdf == REAL_C(0.5));
    }
    cobject_free(o);
}
END_TEST

START_TEST(box_samples_faces_in_proportion_to_their_area)
{
    /* faces of areas 6, 6, 3, 3, 2, 2 (extents 1 x 2 x 3): face f is
     * chosen with p_f = area_f / 22; N = 60000 gives sd
     * sqrt(p (1 - p) / N) <= 0.0019; 5 sd = 0.0095 */
    COBJECT *o = box(0, 0, 0, 1, 2, 3);
    pcg32_t g;
    pcg32_seed(&g, 33, 34);
    const int N = 60000;
    int count[6] = { 0 };
    for (int i = 0; i < N; i++) {
        real u[2] = { pcg32_real(&g), pcg32_real(&g) };
        cobject_sample_t s;
        o->ops->sample(o, u, &s);
        int k = s.n[X] != 0 ? X : s.n[Y] != 0 ? Y : Z;
        int f = 2 * k + (s.n[k] > 0);
        ck_assert(s.p[k] == (s.n[k] > 0 ? (k + 1) : 0));
        ck_assert(s.pdf == REAL_C(1.0) / 22);
        count[f]++;
    }
    const double area[6] = { 6, 6, 3, 3, 2, 2 };
    for (int f = 0; f < 6; f++)
        ck_assert_near((double)count[f] / N, area[f] / 22, 0.0095);
    test_report_cases("box_samples_faces_in_proportion_to_their_area", N);
    cobject_free(o);
}
END_TEST

static COBJECT *make_box(real s, const VECTOR3 c, void *ctx)
{
    (void)ctx;
    const real half[3] = { REAL_C(0.5), REAL_C(0.35), REAL_C(0.8) };
    VECTOR3 lo, hi;
    for (int k = 0; k < 3; k++) {
        lo[k] = c[k] - s * half[k];
        hi[k] = c[k] + s * half[k];
    }
    return box(lo[X], lo[Y], lo[Z], hi[X], hi[Y], hi[Z]);
}

START_TEST(box_spawned_rays_never_rehit_at_any_scale)
{
    test_report_cases("box_spawned_rays_never_rehit_at_any_scale",
                      primcheck_over_scales(make_box, NULL, PRIMCHECK_SPAWN,
                                            GEOMCHECK_CONVEX, true, 100));
}
END_TEST

START_TEST(box_sampled_points_are_hit_at_any_scale)
{
    test_report_cases("box_sampled_points_are_hit_at_any_scale",
                      primcheck_over_scales(make_box, NULL, PRIMCHECK_SAMPLED,
                                            GEOMCHECK_CONVEX, true, 200));
}
END_TEST

START_TEST(box_shadow_rays_between_its_points_miss_at_any_scale)
{
    test_report_cases("box_shadow_rays_between_its_points_miss_at_any_scale",
                      primcheck_over_scales(make_box, NULL, PRIMCHECK_SHADOW,
                                            GEOMCHECK_CONVEX, true, 300));
}
END_TEST

START_TEST(box_hits_are_finite_at_any_scale)
{
    test_report_cases("box_hits_are_finite_at_any_scale",
                      primcheck_over_scales(make_box, NULL, PRIMCHECK_FINITE,
                                            GEOMCHECK_CONVEX, true, 400));
}
END_TEST

START_TEST(box_sampling_has_pdf_one_over_area_at_any_scale)
{
    test_report_cases("box_sampling_has_pdf_one_over_area_at_any_scale",
                      primcheck_over_scales(make_box, NULL, PRIMCHECK_AREA,
                                            GEOMCHECK_CONVEX, true, 500));
}
END_TEST

START_TEST(box_matches_the_reference_vectors)
{
    testcsv_t c;
    testcsv_open(&c, "box.csv");
    long n = 0;
    for (; testcsv_next(&c); n++) {
        VECTOR3 lo, hi;
        primcheck_csv_vec(&c, "min", lo);
        primcheck_csv_vec(&c, "max", hi);
        COBJECT *o = box(lo[X], lo[Y], lo[Z], hi[X], hi[Y], hi[Z]);
        PATHPOINT pp;
        if (primcheck_csv_hit(&c, o, "p", "n", &pp))
            ck_assert_int_eq(pp.prim, (int)testcsv_num(&c, "face"));
        cobject_free(o);
    }
    testcsv_close(&c);
    ck_assert_int_gt(n, 0);
    test_report_cases("box_matches_the_reference_vectors", n);
}
END_TEST

START_TEST(box_sweep_never_returns_nan_or_inf)
{
    pcg32_t g;
    pcg32_seed(&g, 14, 15);
    long n = 0;
    for (int i = 0; i < 100; i++) {
        real s = ldexp(REAL_C(1.0), (int)pcg32_bounded(&g, 100) - 50);
        VECTOR3 a, b;
        for (int k = 0; k < 3; k++) {
            a[k] = s * (2 * pcg32_real(&g) - 1);
            b[k] = a[k] + s * pcg32_real(&g);
        }
        if (i % 5 == 0)
            b[i % 3] = a[i % 3]; /* flat */
        svet_error err;
        COBJECT *o = box_new(a, b, &err);
        ck_assert_msg(o != NULL, "%s", err.msg);
        n += primcheck_sweep_finite(o, 2000, (uint64_t)i);
        cobject_free(o);
    }
    test_report_cases("box_sweep_never_returns_nan_or_inf", n);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("box");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, box_entry_and_exit_hits_are_exact);
    tcase_add_test(tc, every_face_has_an_outward_right_handed_frame);
    tcase_add_test(tc, box_respects_the_open_interval);
    tcase_add_test(tc, a_ray_whose_slab_times_overflow_never_hits);
    tcase_add_test(tc, rays_parallel_to_a_face_and_in_its_plane);
    tcase_add_test(tc, no_ray_slips_through_the_edges_of_a_box);
    tcase_add_test(tc, box_rejects_bad_input_and_allows_a_flat_box);
    tcase_add_test(tc, box_samples_faces_in_proportion_to_their_area);
    tcase_add_test(tc, box_spawned_rays_never_rehit_at_any_scale);
    tcase_add_test(tc, box_sampled_points_are_hit_at_any_scale);
    tcase_add_test(tc, box_shadow_rays_between_its_points_miss_at_any_scale);
    tcase_add_test(tc, box_hits_are_finite_at_any_scale);
    tcase_add_test(tc, box_sampling_has_pdf_one_over_area_at_any_scale);
    tcase_add_test(tc, box_matches_the_reference_vectors);
    tcase_add_test(tc, box_sweep_never_returns_nan_or_inf);
    suite_add_tcase(s, tc);
    return s;
}
