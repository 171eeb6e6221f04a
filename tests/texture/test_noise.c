/*
 * test_noise.c - Perlin's improved noise (ch. 10; Perlin 2002) against
 * values of his Java reference's algorithm (tests/vectors/noise_perlin.csv,
 * from tools/perlin/PerlinVectors.java, which reproduces Rosetta Code's
 * quoted value), and the properties the chapter relies on: zero at the
 * lattice, bounded, periodic, C2 across cell faces, and a gradient equal to
 * central differences; the fractal sums' octaves.
 */
#include "testutil.h"
#include "core/rng.h"
#include "texture/noise.h"

#include <math.h>

#ifdef SVET_DOUBLE
#define NOISE_TOL 1e-12 /* the CSV's tol_double */
#else
#define NOISE_TOL 4e-6 /* the CSV's tol_float */
#endif

START_TEST(the_reference_value_of_rosetta_code)
{
    VECTOR3 p = { REAL_C(3.14), 42, 7 };
#ifdef SVET_DOUBLE
    /* the same operations in the same order in IEEE double: every bit */
    ck_assert(noise_perlin(p) == 0.13691995878400012);
#else
    ck_assert_near(noise_perlin(p), 0.13691995878400012, NOISE_TOL);
#endif
}
END_TEST

START_TEST(values_match_the_reference_vectors)
{
    testcsv_t c;
    testcsv_open(&c, "noise_perlin.csv");
    long n = 0;
    double worst = 0;
    while (testcsv_next(&c)) {
        VECTOR3 p = { (real)testcsv_num(&c, "x"), (real)testcsv_num(&c, "y"),
                      (real)testcsv_num(&c, "z") };
        double e = testcsv_num(&c, "noise"), v = (double)noise_perlin(p);
        ck_assert_near(v, e, NOISE_TOL);
        worst = fmax(worst, fabs(v - e));
        n++;
    }
    testcsv_close(&c);
    ck_assert_int_ge(n, 180);
    test_report_cases("values_match_the_reference_vectors", n);
}
END_TEST

START_TEST(zero_at_every_lattice_point_and_not_elsewhere)
{
    long n = 0;
    for (int i = -300; i <= 300; i += 7)
        for (int j = -40; j <= 40; j += 3)
            for (int k = -5; k <= 5; k++, n++) {
                VECTOR3 p = { (real)i, (real)j, (real)k }, g;
                ck_assert(noise_perlin(p) == 0);
                /* the gradient there is the corner's own, of length sqrt 2 */
                noise_perlin_grad(p, g);
                ck_assert_near(SVECTOR3(g, g), 2, 8 * REAL_EPSILON);
            }
    /* a half-integer point is not a zero in general: the test is not empty */
    int nonzero = 0;
    for (int i = 0; i < 50; i++) {
        VECTOR3 p = { REAL_C(0.5) + (real)i, REAL_C(0.25), REAL_C(0.75) };
        nonzero += noise_perlin(p) != 0;
    }
    ck_assert_int_gt(nonzero, 40);
    test_report_cases("zero_at_every_lattice_point_and_not_elsewhere", n);
}
END_TEST

START_TEST(bounded_and_periodic_with_period_256)
{
    pcg32_t g;
    pcg32_seed(&g, 10, 1);
    double lo = 0, hi = 0;
    const long n = 400000;
    for (long i = 0; i < n; i++) {
        VECTOR3 p = { 64 * pcg32_real(&g) - 32, 64 * pcg32_real(&g) - 32,
                      64 * pcg32_real(&g) - 32 };
        double v = (double)noise_perlin(p);
        lo = fmin(lo, v);
        hi = fmax(hi, v);
        /* the provable bound: a convex blend of values below 2 */
        ck_assert(fabs(v) < 2);
        /* dyadic points with few bits stay exact when moved by 256 */
        VECTOR3 q = { floor(p[X] * 64) / 64, floor(p[Y] * 64) / 64,
                      floor(p[Z] * 64) / 64 };
        VECTOR3 s = { q[X] + 256, q[Y] - 512, q[Z] + 256 * 3 };
        ck_assert(noise_perlin(q) == noise_perlin(s));
    }
    /* the range found is about [-1, 1]: not scaled by mistake */
    ck_assert(hi > 0.9 && hi < 1.1 && lo < -0.9 && lo > -1.1);
    test_report_cases("bounded_and_periodic_with_period_256", n);
}
END_TEST

START_TEST(not_finite_inputs_give_zero)
{
    VECTOR3 p = { (real)NAN, 1, 2 }, q = { 1, (real)INFINITY, 2 }, g;
    ck_assert(noise_perlin(p) == 0);
    ck_assert(noise_perlin_grad(q, g) == 0);
    ck_assert(g[X] == 0 && g[Y] == 0 && g[Z] == 0);
    /* beyond int range the lattice cell is still computed without overflow */
    VECTOR3 big = { (real)1e30, REAL_C(0.5), REAL_C(0.5) };
    ck_assert(isfinite(noise_perlin(big)));
}
END_TEST

/* Central differences of f along each axis at p with step h. */
static void central(real (*f)(const VECTOR3, const noise_octaves_t *, VECTOR3),
                    const noise_octaves_t *o, const VECTOR3 p, real h,
                    VECTOR3 d)
{
    for (int k = 0; k < 3; k++) {
        VECTOR3 a = { p[X], p[Y], p[Z] }, b = { p[X], p[Y], p[Z] };
        a[k] += h;
        b[k] -= h;
        d[k] = (f(a, o, NULL) - f(b, o, NULL)) / (2 * h);
    }
}

static real plain(const VECTOR3 p, const noise_octaves_t *o, VECTOR3 g)
{
    (void)o;
    return noise_perlin_grad(p, g);
}

/* The step and tolerance of the central difference: its error is
 * h^2 / 6 |f'''| (|f'''| is below about 300: the fade curve's third
 * derivative is at most 60, times corner values below 2, times the blend's
 * terms) plus the value's rounding over h. In double h = 1e-5 gives 5e-8 +
 * 1e-11; in float h = 2^-7 gives 3e-3 + 4e-6 / h = 3.5e-3. */
#ifdef SVET_DOUBLE
#define DIFF_H REAL_C(1e-5)
#define DIFF_TOL 1e-4
#else
#define DIFF_H REAL_C(0.0078125)
#define DIFF_TOL 4e-3
#endif

START_TEST(gradient_equals_central_differences)
{
    pcg32_t g;
    pcg32_seed(&g, 10, 2);
    noise_octaves_t o = { 4, 2, REAL_C(0.5) };
    long n = 0;
    for (int i = 0; i < 3000; i++, n++) {
        VECTOR3 p = { 20 * pcg32_real(&g) - 10, 20 * pcg32_real(&g) - 10,
                      20 * pcg32_real(&g) - 10 }, a, d;
        real v = noise_perlin_grad(p, a);
        ck_assert(v == noise_perlin(p));
        central(plain, NULL, p, DIFF_H, d);
        for (int k = 0; k < 3; k++)
            ck_assert_near(a[k], d[k], DIFF_TOL);
        /* the fractal sum: octave i's gradient is scaled by 2^i, and its
         * third derivative by 8^i, against gain 0.5^i: the step shrinks */
        noise_fractal(p, &o, a);
        central(noise_fractal, &o, p, DIFF_H / 8, d);
        for (int k = 0; k < 3; k++)
            ck_assert_near(a[k], d[k], 8 * DIFF_TOL);
    }
    test_report_cases("gradient_equals_central_differences", n);
}
END_TEST

START_TEST(c2_across_cell_faces)
{
    /* on either side of the face x = k, the value, the gradient and the
     * second derivative d2n/dx2 (differences of the exact gradient) agree;
     * the face is where a C1 curve would show a jump in the second */
    pcg32_t g;
    pcg32_seed(&g, 10, 3);
    const real h = (real)(sizeof(real) == 8 ? 1e-6 : 1e-3);
    long n = 0;
    for (int i = 0; i < 2000; i++, n++) {
        real k = floor(16 * pcg32_real(&g) - 8);
        real y = 8 * pcg32_real(&g), z = 8 * pcg32_real(&g);
        VECTOR3 m = { k - h, y, z }, c = { k, y, z }, p = { k + h, y, z };
        VECTOR3 gm, gc, gp;
        real vm = noise_perlin_grad(m, gm), vc = noise_perlin_grad(c, gc);
        real vp = noise_perlin_grad(p, gp);
        ck_assert_near(vm, vc, 4 * h);
        ck_assert_near(vp, vc, 4 * h);
        for (int a = 0; a < 3; a++) {
            ck_assert_near(gm[a], gc[a], 400 * h);
            ck_assert_near(gp[a], gc[a], 400 * h);
        }
        /* second derivative from each side: one-sided differences of the
         * gradient; equal up to h |n'''| */
        real left = (gc[X] - gm[X]) / h, right = (gp[X] - gc[X]) / h;
        ck_assert_near(left, right, 600 * (double)h + 1e3 * (double)(REAL_EPSILON / h));
    }
    test_report_cases("c2_across_cell_faces", n);
}
END_TEST

START_TEST(octaves_of_the_fractal_sums)
{
    pcg32_t g;
    pcg32_seed(&g, 10, 4);
    noise_octaves_t one = { 1, 2, REAL_C(0.5) }, o = noise_octaves_default();
    noise_octaves_t none = { 0, 2, REAL_C(0.5) }, many = { 1000, 2, 0 };
    ck_assert_int_eq(o.octaves, 6);
    for (int i = 0; i < 1000; i++) {
        VECTOR3 p = { 8 * pcg32_real(&g), 8 * pcg32_real(&g),
                      8 * pcg32_real(&g) };
        real n = noise_perlin(p);
        /* one octave is the noise itself, and |noise| for turbulence */
        ck_assert(noise_fractal(p, &one, NULL) == n);
        ck_assert(noise_turbulence(p, &one, NULL) == fabs(n));
        ck_assert(noise_fractal(p, &none, NULL) == n); /* clamped to 1 */
        ck_assert(noise_fractal(p, &many, NULL) == n); /* gain 0 */
        /* the sum by hand */
        real sum = 0, tsum = 0, amp = 1, f = 1;
        for (int k = 0; k < 6; k++) {
            VECTOR3 q = { p[X] * f, p[Y] * f, p[Z] * f };
            sum += amp * noise_perlin(q);
            tsum += amp * fabs(noise_perlin(q));
            amp *= REAL_C(0.5);
            f *= 2;
        }
        ck_assert_near(noise_fractal(p, &o, NULL), sum, 8 * REAL_EPSILON);
        ck_assert_near(noise_turbulence(p, &o, NULL), tsum, 8 * REAL_EPSILON);
        ck_assert(noise_turbulence(p, &o, NULL) >= 0);
    }
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("noise (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, the_reference_value_of_rosetta_code);
    tcase_add_test(tc, values_match_the_reference_vectors);
    tcase_add_test(tc, zero_at_every_lattice_point_and_not_elsewhere);
    tcase_add_test(tc, bounded_and_periodic_with_period_256);
    tcase_add_test(tc, not_finite_inputs_give_zero);
    tcase_add_test(tc, gradient_equals_central_differences);
    tcase_add_test(tc, c2_across_cell_faces);
    tcase_add_test(tc, octaves_of_the_fractal_sums);
    suite_add_tcase(s, tc);
    return s;
}
