/*
 * gradients.c - app. E: irradiance, its rotational and translational
 * gradients (Ward & Heckbert 1992) and the harmonic mean distance from a
 * stratified hemisphere.
 * Tests: tests/irradiance/test_gradients.c
 */
#include "irradiance/gradients.h"

void gradients_direction(int m, int n, int j, int k, const real u[2],
                         VECTOR3 w)
{
    /* cosine-weighted strata: sin^2 theta uniform in [j, j + 1) / M */
    real s2 = ((real)j + u[0]) / (real)m;
    real st = sqrt(s2), ct = sqrt(real_max(REAL_C(0.0), 1 - s2));
    real phi = 2 * REAL_PI * ((real)k + u[1]) / (real)n;
    vec_set(w, st * cos(phi), st * sin(phi), ct);
}

static real channel(RADIANCE c, int i) { return i == 0 ? c.r : i == 1 ? c.g : c.b; }

void gradients_compute(const gradients_samples_t *s, RADIANCE *e,
                       VECTOR3 grad_r[3], VECTOR3 grad_t[3], real *r_mean)
{
    const int m = s->m, n = s->n;
    double sum[3] = { 0, 0, 0 }, inv_r = 0;
    double gr[3][2] = { { 0 } }, gt[3][2] = { { 0 } };
    for (int k = 0; k < n; k++) {
        /* the cell's centre angle and the edge it shares with cell k - 1 */
        double phi_c = 2 * 3.14159265358979323846 * (k + 0.5) / n;
        double phi_e = 2 * 3.14159265358979323846 * k / n;
        double uk[2] = { cos(phi_c), sin(phi_c) };
        double vk[2] = { -sin(phi_c), cos(phi_c) };   /* phi_c + pi / 2 */
        double ve[2] = { -sin(phi_e), cos(phi_e) };   /* phi_e + pi / 2 */
        int km = (k + n - 1) % n;
        for (int j = 0; j < m; j++) {
            int i = j * n + k;
            double r = (double)s->dist[i];
            inv_r += 1 / r; /* 0 for the sky */
            double sm = sqrt((double)j / m), sp = sqrt((j + 1.0) / m);
            double cm = sqrt(1 - sm * sm);
            /* the mean of tan theta = sqrt(s / (1 - s)) over s = sin^2 in
             * [j, j + 1) / M: M (F(s+) - F(s-)), F = asin(sqrt s) -
             * sqrt(s (1 - s)) */
            double tan_mean = m * ((asin(sp) - sp * sqrt(1 - sp * sp)) -
                                   (asin(sm) - sm * cm));
            for (int c = 0; c < 3; c++) {
                double l = (double)channel(s->l[i], c);
                sum[c] += l;
                /* rotational: tan theta L along v_k, with tan theta the
                 * stratum's mean of it under the cosine-weighted measure
                 * (the sample's own tan theta gives the last stratum an
                 * estimate of infinite variance at the horizon) */
                double t = tan_mean * l;
                gr[c][0] += t * vk[0];
                gr[c][1] += t * vk[1];
                /* translational, across the phi edge with cell k - 1 */
                double rk = fmin(r, (double)s->dist[j * n + km]);
                double dl = l - (double)channel(s->l[j * n + km], c);
                double a = (sp - sm) / rk * dl;
                gt[c][0] += a * ve[0];
                gt[c][1] += a * ve[1];
                /* and across the theta edge with cell j - 1 */
                if (j > 0) {
                    int ip = (j - 1) * n + k;
                    double rj = fmin(r, (double)s->dist[ip]);
                    double dj = l - (double)channel(s->l[ip], c);
                    double b = 2 * 3.14159265358979323846 / n * sm * cm * cm /
                               rj * dj;
                    gt[c][0] += b * uk[0];
                    gt[c][1] += b * uk[1];
                }
            }
        }
    }
    double f = 3.14159265358979323846 / ((double)m * n);
    *e = rad_make((real)(f * sum[0]), (real)(f * sum[1]), (real)(f * sum[2]));
    for (int c = 0; c < 3; c++) {
        vec_set(grad_r[c], (real)(f * gr[c][0]), (real)(f * gr[c][1]), 0);
        vec_set(grad_t[c], (real)gt[c][0], (real)gt[c][1], 0);
    }
    *r_mean = inv_r > 0 ? (real)((double)m * n / inv_r) : (real)INFINITY;
}
