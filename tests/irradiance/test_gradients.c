/*
 * test_gradients.c - app. E's gradients (Ward & Heckbert 1992) against
 * exact answers: the irradiance and rotational gradient under a sky whose
 * radiance is linear in the direction (E(n) = pi a + 2 pi / 3 b . n), and
 * the translational gradient under a ceiling whose radiance varies across
 * it, against the finite difference of its irradiance integrated by a
 * dense quadrature; both errors fall as the strata are refined.
 */
#include "testutil.h"
#include "core/rng.h"
#include "irradiance/gradients.h"

#include <math.h>
#include <stdlib.h>

#define PI_D 3.14159265358979323846

typedef struct {
    RADIANCE *l;
    real *dist;
} buffers_t;

/* Fill the M x N strata of the point (0, y, 0), normal +z: the sky's
 * a + b . w (dist infinite), or a ceiling at height 1 of radiance
 * 1 + 0.8 tanh(y' / 0.5) at the point (x', y', 1) it is hit. */
static gradients_samples_t gather(int m, int n, double y, bool ceiling,
                                  const double b[3], pcg32_t *g, buffers_t *bf)
{
    bf->l = malloc(sizeof *bf->l * (size_t)(m * n));
    bf->dist = malloc(sizeof *bf->dist * (size_t)(m * n));
    for (int j = 0; j < m; j++)
        for (int k = 0; k < n; k++) {
            real u[2] = { pcg32_real(g), pcg32_real(g) };
            VECTOR3 w;
            gradients_direction(m, n, j, k, u, w);
            int i = j * n + k;
            if (ceiling) {
                double t = 1 / (double)w[Z];
                double yy = y + t * (double)w[Y];
                bf->l[i] = rad_grey((real)(1 + 0.8 * tanh(yy / 0.5)));
                bf->dist[i] = (real)t;
            } else {
                double v = 1 + b[0] * (double)w[X] + b[1] * (double)w[Y] +
                           b[2] * (double)w[Z];
                bf->l[i] = rad_grey((real)v);
                bf->dist[i] = (real)INFINITY;
            }
        }
    gradients_samples_t s = { m, n, bf->l, bf->dist };
    return s;
}

static void release(buffers_t *bf)
{
    free(bf->l);
    free(bf->dist);
}

START_TEST(irradiance_and_rotational_gradient_under_a_linear_sky)
{
    const double b[3] = { 0.3, -0.2, 0.4 };
    /* E = pi a + 2 pi / 3 b . n; rotating n by the small vector w changes
     * it by 2 pi / 3 b . (w x n) = w . (2 pi / 3 n x b) */
    double e_exact = PI_D + 2 * PI_D / 3 * b[2];
    double gx = 2 * PI_D / 3 * -b[1], gy = 2 * PI_D / 3 * b[0];
    double err[2];
    for (int level = 0; level < 2; level++) {
        int m = level ? 48 : 6, n = 4 * m;
        pcg32_t g;
        pcg32_seed(&g, 100, (uint64_t)level);
        buffers_t bf;
        gradients_samples_t s = gather(m, n, 0, false, b, &g, &bf);
        RADIANCE e;
        VECTOR3 gr[3], gt[3];
        real rm;
        gradients_compute(&s, &e, gr, gt, &rm);
        ck_assert(isinf(rm)); /* nothing hit */
        ck_assert_near(e.g, e_exact, 0.02 * e_exact);
        ck_assert(gt[1][X] == 0 && gt[1][Y] == 0); /* the sky has no parallax */
        err[level] = hypot((double)gr[1][X] - gx, (double)gr[1][Y] - gy);
        release(&bf);
    }
    /* the fine strata within 1% of the gradient's length, and better */
    ck_assert_msg(err[1] < 0.01 * hypot(gx, gy), "rotational error %g", err[1]);
    ck_assert(err[1] < err[0]);
}
END_TEST

/* The ceiling's irradiance at (0, y, 0), by the midpoint rule over
 * 600 x 2400 cosine-weighted strata: an independent integral. */
static double ceiling_irradiance(double y)
{
    const int m = 600, n = 2400;
    double sum = 0;
    for (int j = 0; j < m; j++) {
        double s2 = (j + 0.5) / m, st = sqrt(s2), ct = sqrt(1 - s2);
        for (int k = 0; k < n; k++) {
            double phi = 2 * PI_D * (k + 0.5) / n;
            double yy = y + st * sin(phi) / ct;
            sum += 1 + 0.8 * tanh(yy / 0.5);
        }
    }
    return PI_D * sum / ((double)m * n);
}

START_TEST(translational_gradient_under_a_varying_ceiling)
{
    const double d = 1e-3;
    double fd = (ceiling_irradiance(d) - ceiling_irradiance(-d)) / (2 * d);
    ck_assert(fd > 0.3); /* the irradiance does change with y */
    double err[2];
    for (int level = 0; level < 2; level++) {
        int m = level ? 48 : 6, n = 4 * m;
        pcg32_t g;
        pcg32_seed(&g, 100, 10 + (uint64_t)level);
        buffers_t bf;
        const double none[3] = { 0, 0, 0 };
        gradients_samples_t s = gather(m, n, 0, true, none, &g, &bf);
        RADIANCE e;
        VECTOR3 gr[3], gt[3];
        real rm;
        gradients_compute(&s, &e, gr, gt, &rm);
        /* the harmonic mean of 1 / cos theta over a cosine-weighted
         * hemisphere: 1 / E[cos] = 1.5 */
        ck_assert_near(rm, 1.5, 0.05);
        err[level] = hypot((double)gt[0][X], (double)gt[0][Y] - fd);
        release(&bf);
    }
    ck_assert_msg(err[1] < 0.02 * fd, "translational error %g of %g", err[1], fd);
    ck_assert(err[1] < err[0]);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("gradients (" REAL_NAME ")");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, irradiance_and_rotational_gradient_under_a_linear_sky);
    tcase_add_test(tc, translational_gradient_under_a_varying_ceiling);
    suite_add_tcase(s, tc);
    return s;
}
