/*
 * test_interp.c - app. L's interpolation of a 3D grid of samples: every
 * method returns the samples at the samples; trilinear reproduces
 * trilinear functions and parabolic (both forms) quadratics, to rounding,
 * and neither reproduces the next degree up; clamping at the borders;
 * grids of 1 and 2 samples along an axis; the blend's continuity.
 */
#include "testutil.h"
#include "core/rng.h"
#include "texture/interp.h"

#include <math.h>
#include <stdlib.h>

typedef real (*interp_fn)(const interp_grid_t *, const VECTOR3);

static const interp_fn methods[4] = { interp_nearest, interp_trilinear,
                                      interp_parabolic,
                                      interp_parabolic_blend };

/* A grid sampled from f at the integer points; integer-valued functions
 * with small coefficients give samples that a float holds exactly. */
typedef double (*field_fn)(const double c[], double x, double y, double z);

static float *make_grid(interp_grid_t *g, int nx, int ny, int nz,
                        field_fn f, const double c[])
{
    float *v = malloc(sizeof *v * (size_t)nx * (size_t)ny * (size_t)nz);
    ck_assert_ptr_nonnull(v);
    for (int k = 0; k < nz; k++)
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++)
                v[((long)k * ny + j) * nx + i] = (float)f(c, i, j, k);
    g->nx = nx;
    g->ny = ny;
    g->nz = nz;
    g->v = v;
    return v;
}

static double random_field(const double c[], double x, double y, double z)
{
    /* a hash of the point: any values at all */
    unsigned h = (unsigned)(x * 73856093 + y * 19349663 + z * 83492791 +
                            c[0]);
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    return (double)(h % 2001) - 1000;
}

static double trilinear_field(const double c[], double x, double y, double z)
{
    return c[0] + c[1] * x + c[2] * y + c[3] * z + c[4] * x * y +
           c[5] * x * z + c[6] * y * z + c[7] * x * y * z;
}

/* a product of quadratics in each coordinate: x^2 y^2 z^2 among its terms */
static double quadratic_field(const double c[], double x, double y, double z)
{
    return (c[0] + c[1] * x + c[2] * x * x) *
           (c[3] + c[4] * y + c[5] * y * y) *
           (c[6] + c[7] * z + c[8] * z * z);
}

static void random_coefficients(pcg32_t *g, double c[], int n)
{
    for (int i = 0; i < n; i++)
        c[i] = (double)((int)(pcg32_real(g) * 7) - 3);
}

/* The largest |sample| of a grid. */
static double grid_max(const interp_grid_t *g)
{
    double m = 0;
    for (long i = 0; i < (long)g->nx * g->ny * g->nz; i++)
        m = fmax(m, fabs((double)g->v[i]));
    return m;
}

static void random_point(pcg32_t *r, const interp_grid_t *g, VECTOR3 p)
{
    p[X] = (real)(g->nx - 1) * pcg32_real(r);
    p[Y] = (real)(g->ny - 1) * pcg32_real(r);
    p[Z] = (real)(g->nz - 1) * pcg32_real(r);
}

/* The rounding of a blend of values up to m in magnitude, after a few
 * dozen operations: the tolerance of "exact to rounding". */
static double round_tol(double m) { return 16 * (double)REAL_EPSILON * m; }

START_TEST(every_method_returns_the_samples_at_the_samples)
{
    static const int sizes[][3] = { { 1, 1, 1 }, { 2, 1, 1 }, { 1, 2, 3 },
                                    { 5, 4, 3 }, { 7, 2, 6 }, { 3, 3, 1 } };
    long n = 0;
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        interp_grid_t g;
        double c[1] = { (double)s };
        float *v = make_grid(&g, sizes[s][0], sizes[s][1], sizes[s][2],
                             random_field, c);
        for (int k = 0; k < g.nz; k++)
            for (int j = 0; j < g.ny; j++)
                for (int i = 0; i < g.nx; i++) {
                    VECTOR3 p = { (real)i, (real)j, (real)k };
                    double e = v[((long)k * g.ny + j) * g.nx + i];
                    bool border = i == g.nx - 1 || j == g.ny - 1 ||
                                  k == g.nz - 1 || i == 0 || j == 0 || k == 0;
                    for (int m = 0; m < 4; m++, n++) {
                        double got = (double)methods[m](&g, p);
                        /* inside, every weight is exactly 0 or 1; at a
                         * border a fraction of 1 or a parabola's end may
                         * round */
                        if (border)
                            ck_assert_near(got, e, round_tol(1000));
                        else
                            ck_assert(got == e);
                    }
                }
        free(v);
    }
    test_report_cases("every_method_returns_the_samples_at_the_samples", n);
}
END_TEST

START_TEST(trilinear_reproduces_trilinear_functions_and_no_more)
{
    pcg32_t r;
    pcg32_seed(&r, 20, 1);
    long n = 0;
    double worst_quadratic = 0;
    for (int t = 0; t < 40; t++) {
        double c[9];
        random_coefficients(&r, c, 9);
        interp_grid_t g, q;
        int nx = 2 + t % 5, ny = 2 + t % 3, nz = 2 + t % 4;
        float *v = make_grid(&g, nx, ny, nz, trilinear_field, c);
        float *w = make_grid(&q, nx, ny, nz, quadratic_field, c);
        double m = grid_max(&g);
        for (int i = 0; i < 200; i++, n++) {
            VECTOR3 p;
            random_point(&r, &g, p);
            double e = trilinear_field(c, (double)p[X], (double)p[Y],
                                       (double)p[Z]);
            ck_assert_near(interp_trilinear(&g, p), e, round_tol(m));
            double eq = quadratic_field(c, (double)p[X], (double)p[Y],
                                        (double)p[Z]);
            worst_quadratic = fmax(worst_quadratic,
                                   fabs((double)interp_trilinear(&q, p) - eq));
        }
        free(v);
        free(w);
    }
    /* the quadratic's error half-way is a quarter of its second difference */
    ck_assert(worst_quadratic > 1);
    test_report_cases("trilinear_reproduces_trilinear_functions_and_no_more",
                      n);
}
END_TEST

static double cubic_field(const double c[], double x, double y, double z)
{
    (void)y;
    (void)z;
    return c[0] * x * x * x;
}

START_TEST(parabolic_reproduces_quadratics_and_not_cubics)
{
    pcg32_t r;
    pcg32_seed(&r, 20, 2);
    long n = 0;
    for (int t = 0; t < 40; t++) {
        double c[9];
        random_coefficients(&r, c, 9);
        interp_grid_t g;
        int nx = 3 + t % 3, ny = 3 + t % 2, nz = 3 + t % 3;
        float *v = make_grid(&g, nx, ny, nz, quadratic_field, c);
        /* a parabola overshoots its samples by 1/8 of their range at
         * most: 1.25^3 < 2 for the three axes */
        double m = 2 * grid_max(&g);
        for (int i = 0; i < 200; i++, n++) {
            VECTOR3 p;
            random_point(&r, &g, p);
            double e = quadratic_field(c, (double)p[X], (double)p[Y],
                                       (double)p[Z]);
            ck_assert_near(interp_parabolic(&g, p), e, round_tol(m));
            ck_assert_near(interp_parabolic_blend(&g, p), e, round_tol(m));
        }
        free(v);
    }
    /* a cubic along x is not reproduced: the test would see a cubic rule */
    interp_grid_t g;
    double c[1] = { 1 };
    float *v = make_grid(&g, 8, 1, 1, cubic_field, c);
    VECTOR3 p = { REAL_C(3.25), 0, 0 };
    ck_assert(fabs((double)interp_parabolic(&g, p) - 3.25 * 3.25 * 3.25) > 0.1);
    free(v);
    test_report_cases("parabolic_reproduces_quadratics_and_not_cubics", n);
}
END_TEST

START_TEST(outside_the_grid_is_the_border_continued)
{
    interp_grid_t g;
    double c[1] = { 5 };
    float *v = make_grid(&g, 4, 3, 5, random_field, c);
    pcg32_t r;
    pcg32_seed(&r, 20, 3);
    for (int i = 0; i < 500; i++) {
        VECTOR3 p = { 10 * pcg32_real(&r) - 3, 10 * pcg32_real(&r) - 3,
                      10 * pcg32_real(&r) - 3 };
        VECTOR3 q = { fmin(fmax(p[X], REAL_C(0.0)), REAL_C(3.0)),
                      fmin(fmax(p[Y], REAL_C(0.0)), REAL_C(2.0)),
                      fmin(fmax(p[Z], REAL_C(0.0)), REAL_C(4.0)) };
        for (int m = 0; m < 4; m++)
            ck_assert(methods[m](&g, p) == methods[m](&g, q));
    }
    VECTOR3 nan = { (real)NAN, 1, 1 }, zero = { 0, 1, 1 };
    VECTOR3 inf = { (real)INFINITY, -(real)INFINITY, 1 };
    VECTOR3 corner = { 3, 0, 1 };
    for (int m = 0; m < 4; m++) {
        ck_assert(methods[m](&g, nan) == methods[m](&g, zero));
        ck_assert(methods[m](&g, inf) == methods[m](&g, corner));
    }
    free(v);
}
END_TEST

START_TEST(an_image_is_bilinear_as_the_textbook_writes_it)
{
    /* nz = 1: trilinear is bilinear, (1-s)(1-t) f00 + s(1-t) f10 + ... */
    interp_grid_t g;
    double c[1] = { 9 };
    float *v = make_grid(&g, 6, 5, 1, random_field, c);
    pcg32_t r;
    pcg32_seed(&r, 20, 4);
    for (int i = 0; i < 1000; i++) {
        VECTOR3 p = { 5 * pcg32_real(&r), 4 * pcg32_real(&r),
                      3 * pcg32_real(&r) - 1 };
        int x0 = (int)p[X], y0 = (int)p[Y];
        if (x0 > 4)
            x0 = 4;
        if (y0 > 3)
            y0 = 3;
        double s = (double)p[X] - x0, t = (double)p[Y] - y0;
        double f00 = v[y0 * 6 + x0], f10 = v[y0 * 6 + x0 + 1];
        double f01 = v[(y0 + 1) * 6 + x0], f11 = v[(y0 + 1) * 6 + x0 + 1];
        double e = (1 - s) * (1 - t) * f00 + s * (1 - t) * f10 +
                   (1 - s) * t * f01 + s * t * f11;
        ck_assert_near(interp_trilinear(&g, p), e, round_tol(1000));
    }
    free(v);
}
END_TEST

START_TEST(the_blend_is_continuous_where_the_parabola_jumps)
{
    interp_grid_t g;
    double c[1] = { 1 };
    float *v = make_grid(&g, 9, 1, 1, cubic_field, c);
    const real h = (real)(sizeof(real) == 8 ? 1e-9 : 1e-4);
    double jump_parabola = 0, jump_blend = 0;
    for (int i = 1; i < 8; i++) {
        for (int half = 0; half < 2; half++) {
            real x = (real)i + (half ? REAL_C(0.5) : 0);
            VECTOR3 a = { x - h, 0, 0 }, b = { x + h, 0, 0 };
            jump_parabola = fmax(jump_parabola,
                                 fabs((double)(interp_parabolic(&g, a) -
                                               interp_parabolic(&g, b))));
            jump_blend = fmax(jump_blend,
                              fabs((double)(interp_parabolic_blend(&g, a) -
                                            interp_parabolic_blend(&g, b))));
        }
    }
    /* x^3's third difference is 6: the parabola jumps by 6 / 8 = 0.75 at
     * half-way; the blend moves by its slope (below 3 * 64) times 2h */
    ck_assert_near(jump_parabola, 0.75, 1e-3 + 400 * (double)h);
    ck_assert(jump_blend < 400 * (double)h + round_tol(512));
    free(v);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("interp (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, every_method_returns_the_samples_at_the_samples);
    tcase_add_test(tc, trilinear_reproduces_trilinear_functions_and_no_more);
    tcase_add_test(tc, parabolic_reproduces_quadratics_and_not_cubics);
    tcase_add_test(tc, outside_the_grid_is_the_border_continued);
    tcase_add_test(tc, an_image_is_bilinear_as_the_textbook_writes_it);
    tcase_add_test(tc, the_blend_is_continuous_where_the_parabola_jumps);
    suite_add_tcase(s, tc);
    return s;
}
