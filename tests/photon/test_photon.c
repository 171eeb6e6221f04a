/*
 * test_photon.c - the photon map method of ch. 8 (photon/photon.h): the
 * power balance of a closed box against Phi / (A (1 - rho)); photons from
 * a uniform environment against pi L on an open square; the lights
 * chosen by the power they emit photons with (equal photon powers) and
 * the flux under an environment and a disc light against the form
 * factor's; an infinite plane under an environment lit where the camera
 * looks; photon tracing through a texture against the closed box's
 * balance per channel and the untextured map's bits; the density
 * estimate on uniform photons against its exact mean k/(k-1) and standard
 * deviation; Christensen's precomputed irradiance on uniform photons
 * against its exact mean k/(k-2) and the plain estimate, and in the box
 * against the plain estimate at each point; maps and images the same
 * bits for 1 and 2 threads and, for ppm, for any split into passes;
 * photon and ppm renders of a caustic scene and the Cornell box against
 * the path tracer's converged image;
 * ppm's error falling as samples are added; the photonmap statement's
 * messages.
 */
#include "testutil.h"
#include "scenecheck.h"
#include "photon/photon.h"
#include "render/allparts.h"
#include "render/render.h"
#include "render/scenefile.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* --- power balance ---------------------------------------------------------- */

/* a closed unit-cube box of reflectance rho around a point light of power
 * 4 pi I = 4 pi W */
static const char box_scene[] =
    "camera position 0 0 0 target 0 0 -1 up 0 1 0 width 4 height 4\n"
    "render maxdepth 1000\n"
    "material wall lambert rho 0.5\n"
    "box min -1 -1 -1 max 1 1 1 material wall\n"
    "light point position 0.1 -0.2 0.3 intensity 1\n";

/* the box scene read and ready to trace photons in */
static void box_render(scene_t *s, render_t *r)
{
    svet_error e;
    scenecheck_parse_ok(s, box_scene);
    ck_assert_msg(render_init(r, s, &e) == SVET_OK, "%s", e.msg);
}

START_TEST(power_balance_in_a_closed_box)
{
    /* Every photon lands on a wall, and goes on with chance rho keeping
     * its power (grey walls: roulette by the reflectance, Jensen 2001
     * sec. 5.2), so the flux stored is Phi (1 + rho + rho^2 + ...) =
     * Phi / (1 - rho) in expectation and the mean irradiance of the walls
     * Phi / (A (1 - rho)). A photon stores H times, H geometric with
     * variance rho / (1 - rho)^2: the mean's relative standard deviation
     * is sqrt(rho / N); the tolerance is 4 of those. */
    scene_t s;
    render_t r;
    svet_error e;
    box_render(&s, &r);
    const uint64_t n = 40000;
    photonmap_t m;
    ck_assert_int_eq(photon_trace(&r, n, PHOTON_GLOBAL, 0, 0, &m, &e),
                     SVET_OK);
    double sum = 0;
    for (size_t i = 1; i <= m.n; i++)
        sum += (double)m.ph[i].power[1];
    const double rho = 0.5, phi = 4 * 3.14159265358979323846, area = 24;
    double exact = phi / (area * (1 - rho)), got = sum / area;
    double tol = 4 * sqrt(rho / (double)n);
    ck_assert_msg(fabs(got / exact - 1) < tol, "mean wall irradiance %g, "
                  "exact %g (tolerance %g relative)", got, exact, tol);
    /* the photons are stored where they land: on the walls */
    for (size_t i = 1; i <= m.n; i++) {
        float mx = 0;
        for (int a = 0; a < 3; a++)
            mx = fmaxf(mx, fabsf(m.ph[i].pos[a]));
        ck_assert(fabsf(mx - 1) < 1e-4f);
    }
    /* and in a caustic map of a box without glass there is nothing */
    photonmap_t c;
    ck_assert_int_eq(photon_trace(&r, 1000, PHOTON_CAUSTIC, 1, 0, &c, &e),
                     SVET_OK);
    ck_assert_uint_eq(c.n, 0);
    photonmap_free(&m);
    photonmap_free(&c);
    render_free(&r);
    scene_free(&s);
}
END_TEST

START_TEST(maps_are_the_same_for_any_thread_count)
{
    scene_t s;
    render_t r;
    svet_error e;
    box_render(&s, &r);
    photonmap_t a, b;
    ck_assert_int_eq(photon_trace(&r, 30000, PHOTON_GLOBAL, 0, 1, &a, &e),
                     SVET_OK);
    ck_assert_int_eq(photon_trace(&r, 30000, PHOTON_GLOBAL, 0, 2, &b, &e),
                     SVET_OK);
    ck_assert_uint_eq(a.n, b.n);
    ck_assert(a.n > 30000);
    ck_assert(memcmp(a.ph + 1, b.ph + 1, a.n * sizeof(photon_t)) == 0);
    photonmap_free(&a);
    photonmap_free(&b);
    /* and Christensen's precomputed irradiance with them */
    photonmap_t ia, ib;
    photonmap_query_t q = { 50, REAL_C(0.3), PHOTONMAP_FILTER_NONE,
                            REAL_C(1.1), REAL_C(0.25) };
    ck_assert_int_eq(photon_trace_precomputed(&r, 30000, PHOTON_GLOBAL, 0, 1,
                                              4, &q, &a, &ia, &e), SVET_OK);
    ck_assert_int_eq(photon_trace_precomputed(&r, 30000, PHOTON_GLOBAL, 0, 2,
                                              4, &q, &b, &ib, &e), SVET_OK);
    ck_assert_uint_eq(ia.n, (a.n - 1) / 4 + 1);
    ck_assert_uint_eq(ia.n, ib.n);
    ck_assert(memcmp(ia.ph + 1, ib.ph + 1, ia.n * sizeof(photon_t)) == 0);
    photonmap_free(&ia);
    photonmap_free(&ib);
    photonmap_free(&a);
    photonmap_free(&b);
    /* another stream is another map */
    ck_assert_int_eq(photon_trace(&r, 1000, PHOTON_GLOBAL, 0, 2, &a, &e),
                     SVET_OK);
    ck_assert_int_eq(photon_trace(&r, 1000, PHOTON_GLOBAL, 7, 2, &b, &e),
                     SVET_OK);
    ck_assert(a.n != b.n ||
              memcmp(a.ph + 1, b.ph + 1, a.n * sizeof(photon_t)) != 0);
    photonmap_free(&a);
    photonmap_free(&b);
    render_free(&r);
    scene_free(&s);
}
END_TEST

/* --- the environment ------------------------------------------------------- */

START_TEST(environment_photons_give_pi_L_on_an_open_plane)
{
    /* A grey square of side 2 under a uniform environment of radiance
     * L = 1.5 (green): the irradiance on either side is pi L, so the power
     * of the photons stored on a side, over the area 4, is pi L in
     * expectation. The square cannot see itself, so every stored photon
     * came straight from the environment. Each carries the same power
     * pi R^2 4 pi L / N and lands on the top with chance p = 4 E[|d_y|;
     * d_y < 0] / (pi R^2) = 1 / (pi R^2) (projected area over the disc of
     * the bounding sphere, radius R = sqrt 2 here), so the sum is binomial
     * with relative standard deviation sqrt((1 - p) / (N p)); the
     * tolerance is 4 of those (0.7 % each for N = 100000). */
    static const char text[] =
        "camera position 0 3 0 target 0 0 0 up 0 0 -1 width 4 height 4\n"
        "material grey lambert rho 0.5\n"
        "parallelogram c0 -1 0 -1 c1 1 0 -1 c3 -1 0 1 material grey\n"
        "environment radiance 0.5 1.5 1\n";
    scene_t s;
    render_t r;
    svet_error e;
    scenecheck_parse_ok(&s, text);
    ck_assert_msg(render_init(&r, &s, &e) == SVET_OK, "%s", e.msg);
    const uint64_t n = 100000;
    photonmap_t m;
    ck_assert_int_eq(photon_trace(&r, n, PHOTON_GLOBAL, 0, 0, &m, &e),
                     SVET_OK);
    double top = 0, below = 0;
    size_t ntop = 0, nbelow = 0;
    for (size_t i = 1; i <= m.n; i++) {
        VECTOR3 d;
        photonmap_direction(&m.ph[i], d);
        ck_assert(fabs((double)m.ph[i].pos[1]) < 1e-5);
        if (d[Y] < 0) {
            top += (double)m.ph[i].power[1];
            ntop++;
        } else {
            below += (double)m.ph[i].power[1];
            nbelow++;
        }
    }
    const double pi = 3.14159265358979323846;
    const double R = (double)r.lights.radius, p = 1 / (pi * R * R);
    const double exact = pi * 1.5;
    const double tol = 4 * sqrt((1 - p) / ((double)n * p));
    ck_assert_msg(fabs(top / 4 / exact - 1) < tol, "irradiance from above "
                  "%g, exact pi L = %g (tolerance %g relative, %zu photons)",
                  top / 4, exact, tol, ntop);
    /* the bottom sees the same environment */
    ck_assert_msg(fabs(below / 4 / exact - 1) < tol, "irradiance from below "
                  "%g, exact pi L = %g (tolerance %g relative, %zu photons)",
                  below / 4, exact, tol, nbelow);
    photonmap_free(&m);
    render_free(&r);
    scene_free(&s);
}
END_TEST

/* The irradiance at distance rho from the axis of a disc of radius a at
 * height h facing a parallel plane, over pi L: the form factor from a
 * point to a coaxial parallel disc (Howell, "A Catalog of Radiation Heat
 * Transfer Configuration Factors", B-13) */
static double disc_form_factor(double rho, double h, double a)
{
    double h2 = h * h, r2 = rho * rho, a2 = a * a;
    return 0.5 * (1 - (h2 + r2 - a2) /
                          sqrt((h2 + r2 + a2) * (h2 + r2 + a2) - 4 * a2 * r2));
}

/* the exact flux onto the plane through the ring r0 <= rho < r1 under
 * the disc (radiance Le) and the environment (L) it hides: E(rho) =
 * pi L (1 - F) + pi Le F, integrated by Simpson's rule over 2000 steps */
static double ring_flux(double r0, double r1, double h, double a, double Le,
                        double L)
{
    const double pi = 3.14159265358979323846;
    const int n = 2000;
    double step = (r1 - r0) / n, sum = 0;
    for (int i = 0; i <= n; i++) {
        double rho = r0 + i * step, F = disc_form_factor(rho, h, a);
        double f = (pi * L * (1 - F) + pi * Le * F) * 2 * pi * rho;
        sum += f * (i == 0 || i == n ? 1 : i % 2 ? 4 : 2);
    }
    return sum * step / 3;
}

START_TEST(emission_by_power_with_an_environment_and_a_disc_light)
{
    /* A grey square of side 4 under a disc light (radius 0.5, radiance
     * 20, facing down from height 1) and a uniform environment of
     * radiance 1, photons stored where they first land (maxdepth 0).
     * The environment emits 4 pi^2 R^2 L, the disc pi^2 a^2 L_e; with the
     * lights chosen in proportion to those, every photon carries the same
     * power, total / N. The flux on the square's top through a disc and
     * a ring about the axis is then the photons' count there times that
     * power, and must match pi L (1 - F) + pi L_e F integrated over them,
     * F the disc's form factor (the disc hides the sky it covers). The
     * count is binomial: the flux's standard deviation is at most the
     * power times sqrt(count), and the tolerance 4 of those. */
    static const char text[] =
        "camera position 0 3 4 target 0 0 0 up 0 1 0 width 4 height 4\n"
        "render maxdepth 0\n"
        "material grey lambert rho 0.5\n"
        "parallelogram c0 -2 0 2 c1 2 0 2 c3 -2 0 -2 material grey\n"
        "disk centre 0 1 0 normal 0 -1 0 radius 0.5 material grey emit 20\n"
        "environment radiance 1 1 1\n";
    scene_t s;
    render_t r;
    svet_error e;
    scenecheck_parse_ok(&s, text);
    ck_assert_msg(render_init(&r, &s, &e) == SVET_OK, "%s", e.msg);
    const uint64_t n = 400000;
    photonmap_t m;
    ck_assert_int_eq(photon_trace(&r, n, PHOTON_GLOBAL, 0, 0, &m, &e),
                     SVET_OK);
    ck_assert(m.n > 1000);
    /* every photon the same power */
    float pmin = m.ph[1].power[1], pmax = pmin;
    for (size_t i = 1; i <= m.n; i++) {
        for (int c = 0; c < 3; c++) {
            pmin = fminf(pmin, m.ph[i].power[c]);
            pmax = fmaxf(pmax, m.ph[i].power[c]);
        }
    }
    ck_assert_msg(pmax / pmin - 1 < 1e-5f, "photon powers from %g to %g: "
                  "the lights are not chosen by their power", (double)pmin,
                  (double)pmax);
    const double ring[3] = { 0, 0.5, 1.5 };
    double flux[2] = { 0, 0 };
    size_t cnt[2] = { 0, 0 };
    for (size_t i = 1; i <= m.n; i++) {
        const photon_t *p = &m.ph[i];
        VECTOR3 d;
        photonmap_direction(p, d);
        if (fabs((double)p->pos[1]) > 1e-4 || !(d[Y] < 0))
            continue; /* the disc's top, or the square's underside */
        double rho = hypot((double)p->pos[0], (double)p->pos[2]);
        for (int k = 0; k < 2; k++)
            if (rho >= ring[k] && rho < ring[k + 1]) {
                flux[k] += (double)p->power[1];
                cnt[k]++;
            }
    }
    for (int k = 0; k < 2; k++) {
        double exact = ring_flux(ring[k], ring[k + 1], 1, 0.5, 20, 1);
        double tol = 4 * (double)pmax * sqrt((double)cnt[k]);
        ck_assert_msg(fabs(flux[k] - exact) < tol, "flux through %g <= rho "
                      "< %g: %g, exact %g (tolerance %g, %zu photons)",
                      ring[k], ring[k + 1], flux[k], exact, tol, cnt[k]);
    }
    photonmap_free(&m);
    render_free(&r);
    scene_free(&s);
}
END_TEST

START_TEST(environment_photons_reach_an_infinite_plane_where_the_camera_looks)
{
    /* An infinite plane, whose box spans the reals, under a uniform
     * environment of radiance 1.5, the camera far from the origin looking
     * down at it: the square of side 2 about the target must get the
     * irradiance pi L, which it does only if the photons' sphere holds
     * it. Every photon carries the same power; the count on the square
     * is binomial, so the tolerance is 4 times the power times its square
     * root. */
    static const char text[] =
        "camera position 30 3 24 target 30 0 20 up 0 1 0 width 4 height 4\n"
        "render maxdepth 0\n"
        "material grey lambert rho 0.5\n"
        "plane point 0 0 0 normal 0 1 0 material grey\n"
        "environment radiance 1.5 1.5 1.5\n";
    scene_t s;
    render_t r;
    svet_error e;
    scenecheck_parse_ok(&s, text);
    ck_assert_msg(render_init(&r, &s, &e) == SVET_OK, "%s", e.msg);
    photonmap_t m;
    ck_assert_int_eq(photon_trace(&r, 100000, PHOTON_GLOBAL, 0, 0, &m, &e),
                     SVET_OK);
    double flux = 0, power = 0;
    size_t cnt = 0;
    for (size_t i = 1; i <= m.n; i++) {
        const photon_t *p = &m.ph[i];
        VECTOR3 d;
        photonmap_direction(p, d);
        power = fmax(power, (double)p->power[1]);
        if (d[Y] < 0 && fabs((double)p->pos[0] - 30) < 1 &&
            fabs((double)p->pos[2] - 20) < 1) {
            flux += (double)p->power[1];
            cnt++;
        }
    }
    const double exact = 3.14159265358979323846 * 1.5 * 4;
    const double tol = 4 * power * sqrt((double)cnt);
    ck_assert_msg(cnt > 100 && fabs(flux - exact) < tol, "flux onto the "
                  "square about the target %g, exact pi L A = %g (tolerance "
                  "%g, %zu photons)", flux, exact, tol, cnt);
    photonmap_free(&m);
    render_free(&r);
    scene_free(&s);
}
END_TEST

/* --- textures ------------------------------------------------------------- */

START_TEST(photon_tracing_reads_the_texture)
{
    /* The closed box of the power balance with walls of a texture that is
     * the same colour everywhere, rho = (0.5, 0.25, 0) (a checker of two
     * equal squares): the photons take its colour at every bounce, so each
     * channel's mean irradiance is Phi / (A (1 - rho_c)), and the map is
     * the bits of the same box with that colour as the material's own.
     * Roulette by the largest channel, 0.5, keeps the red powers equal:
     * the red mean has the grey box's relative standard deviation
     * sqrt(rho / N), the others less; the tolerance is 4 of those. */
    static const char textured[] =
        "camera position 0 0 0 target 0 0 -1 up 0 1 0 width 4 height 4\n"
        "render maxdepth 1000\n"
        "texture c checker a 0.5 0.25 0 b 0.5 0.25 0 scale 3\n"
        "material wall lambert rho c\n"
        "box min -1 -1 -1 max 1 1 1 material wall\n"
        "light point position 0.1 -0.2 0.3 intensity 1\n";
    static const char plain[] =
        "camera position 0 0 0 target 0 0 -1 up 0 1 0 width 4 height 4\n"
        "render maxdepth 1000\n"
        "material wall lambert rho 0.5 0.25 0\n"
        "box min -1 -1 -1 max 1 1 1 material wall\n"
        "light point position 0.1 -0.2 0.3 intensity 1\n";
    scene_t s, sp;
    render_t r, rp;
    svet_error e;
    scenecheck_parse_ok(&s, textured);
    ck_assert(s.shade != NULL);
    scenecheck_parse_ok(&sp, plain);
    ck_assert_msg(render_init(&r, &s, &e) == SVET_OK, "%s", e.msg);
    ck_assert_msg(render_init(&rp, &sp, &e) == SVET_OK, "%s", e.msg);
    const uint64_t n = 40000;
    photonmap_t m, mp;
    ck_assert_int_eq(photon_trace(&r, n, PHOTON_GLOBAL, 0, 0, &m, &e),
                     SVET_OK);
    ck_assert_int_eq(photon_trace(&rp, n, PHOTON_GLOBAL, 0, 0, &mp, &e),
                     SVET_OK);
    double sum[3] = { 0, 0, 0 };
    for (size_t i = 1; i <= m.n; i++)
        for (int c = 0; c < 3; c++)
            sum[c] += (double)m.ph[i].power[c];
    const double rho[3] = { 0.5, 0.25, 0 }, area = 24;
    const double phi = 4 * 3.14159265358979323846;
    const double tol = 4 * sqrt(0.5 / (double)n);
    for (int c = 0; c < 3; c++) {
        double exact = phi / (area * (1 - rho[c])), got = sum[c] / area;
        ck_assert_msg(fabs(got / exact - 1) < tol, "channel %d: mean wall "
                      "irradiance %g, exact %g (tolerance %g relative)", c,
                      got, exact, tol);
    }
    ck_assert_uint_eq(m.n, mp.n);
    ck_assert(memcmp(m.ph + 1, mp.ph + 1, m.n * sizeof(photon_t)) == 0);
    photonmap_free(&m);
    photonmap_free(&mp);
    render_free(&r);
    render_free(&rp);
    scene_free(&s);
    scene_free(&sp);
}
END_TEST

/* --- the density estimate ------------------------------------------------- */

START_TEST(density_estimate_on_uniform_photons_has_its_exact_mean)
{
    /* N photons uniform on the unit square at z = 0, each Phi / N: the
     * irradiance is E = Phi. With r the distance of the k-th nearest, the
     * photons are locally Poisson of density lambda = N, pi r^2 lambda is
     * Gamma(k, 1), and the estimate k Phi / (N pi r^2) has mean E k/(k-1)
     * and relative standard deviation k / ((k-1) sqrt(k-2)). The query
     * points of a 30 x 30 grid lie far further apart than 2r, so their
     * estimates are nearly independent: the mean of 900 has a relative
     * standard deviation of 0.354 / 30 = 1.2 % for k = 10, and 4 of those
     * is the tolerance (the uncorrected E lies 9 of them away). */
    const size_t n = 200000;
    const int k = 10;
    photonmap_t m;
    svet_error e;
    ck_assert_int_eq(photonmap_init(&m, n, &e), SVET_OK);
    pcg32_t g;
    pcg32_seed(&g, 42, 7);
    const real phi = 2;
    VECTOR3 down = { 0, 0, -1 };
    for (size_t i = 0; i < n; i++) {
        VECTOR3 p = { pcg32_real(&g), pcg32_real(&g), 0 };
        ck_assert(photonmap_store(&m, p, rad_grey(phi / (real)n), down, 0));
    }
    ck_assert_int_eq(photonmap_balance(&m, &e), SVET_OK);
    photonmap_query_t q = { k, 1, PHOTONMAP_FILTER_NONE, REAL_C(1.1), 0 };
    material_t lam;
    ck_assert_int_eq(material_lambert(&lam, rad_grey(REAL_C(0.6)), &e),
                     SVET_OK);
    double sum = 0, sum2 = 0;
    int nq = 0;
    for (int i = 0; i < 30; i++)
        for (int j = 0; j < 30; j++, nq++) {
            VECTOR3 x = { (real)(0.05 + 0.03 * i), (real)(0.05 + 0.03 * j), 0 };
            VECTOR3 nrm = { 0, 0, 1 };
            RADIANCE est = photonmap_irradiance(&m, x, nrm, &q);
            double v = (double)est.g / (double)phi;
            sum += v;
            sum2 += v * v;
            /* photon_radiance of a Lambert surface is rho / pi times it */
            PATHPOINT pp;
            memset(&pp, 0, sizeof pp);
            vec_copy(pp.cross_point, x);
            vec_set(pp.u, 1, 0, 0);
            vec_set(pp.v, 0, 1, 0);
            vec_set(pp.n, 0, 0, 1);
            vec_set(pp.ng, 0, 0, 1);
            VECTOR3 wo = { 0, 0, 1 };
            RADIANCE L = photon_radiance(&m, &pp, &lam, wo, &q);
            ck_assert_rel(L.g, est.g * REAL_C(0.6) * REAL_INV_PI,
                          64 * REAL_EPSILON, 0);
        }
    double mean = sum / nq, sd = sqrt(sum2 / nq - mean * mean);
    double exact = (double)k / (k - 1);
    double rel_sd = k / ((k - 1) * sqrt(k - 2.0));
    double tol = 4 * rel_sd / sqrt((double)nq);
    ck_assert_msg(fabs(mean / exact - 1) < tol, "mean %g, exact %g (tol %g)",
                  mean, exact, tol);
    ck_assert_msg(fabs(mean - 1) > tol, "the mean %g is not biased by k/(k-1)",
                  mean);
    /* the sample standard deviation of 900: within 20 % of its exact
     * value (its own relative error is about sqrt((kurtosis - 1) / 4n),
     * a few per cent for this skewed law) */
    ck_assert_msg(fabs(sd / (exact * rel_sd) - 1) < 0.2, "sd %g, exact %g",
                  sd, exact * rel_sd);
    photonmap_free(&m);
}
END_TEST

/* --- Christensen's precomputed irradiance ---------------------------------- */

START_TEST(precomputed_irradiance_on_uniform_photons_has_its_exact_mean)
{
    /* The photons of the density test; the irradiance precomputed at
     * every 4th of them (Christensen 1999) and looked up at the 30 x 30
     * grid. At a photon's own position its k nearest are itself and k - 1
     * Poisson neighbours: pi r^2 lambda is Gamma(k - 1, 1), and the
     * estimate k Phi / (N pi r^2) has mean E k/(k-2) and relative standard
     * deviation 1 / sqrt(k - 3), against the plain estimate's E k/(k-1)
     * at an arbitrary point. The grid's lookups reach distinct points
     * (their spacing 0.03 is far above the precomputed points' 0.004), so
     * the mean of 900 has a relative standard deviation of 0.146 / 30 =
     * 0.49 % for k = 50, and 4 of those is the tolerance: the two means
     * must agree once the known factor (k-1)/(k-2) is taken out. A lookup
     * from the other side of the plane, or beyond rmax, finds nothing. */
    const size_t n = 200000;
    const int k = 50;
    photonmap_t m, irr;
    svet_error e;
    ck_assert_int_eq(photonmap_init(&m, n, &e), SVET_OK);
    pcg32_t g;
    pcg32_seed(&g, 42, 7);
    const real phi = 2;
    VECTOR3 down = { 0, 0, -1 }, up = { 0, 0, 1 };
    size_t np = n / 4;
    float (*pos)[3] = malloc(np * sizeof *pos), (*nrm)[3] = malloc(np *
                                                                   sizeof *nrm);
    ck_assert(pos && nrm);
    for (size_t i = 0; i < n; i++) {
        VECTOR3 p = { pcg32_real(&g), pcg32_real(&g), 0 };
        ck_assert(photonmap_store(&m, p, rad_grey(phi / (real)n), down, 0));
        if (i % 4 == 0)
            for (int a = 0; a < 3; a++) {
                pos[i / 4][a] = (float)p[a];
                nrm[i / 4][a] = (float)up[a];
            }
    }
    ck_assert_int_eq(photonmap_balance(&m, &e), SVET_OK);
    photonmap_query_t q = { k, 1, PHOTONMAP_FILTER_NONE, REAL_C(1.1), 0 };
    ck_assert_int_eq(photonmap_precompute(&m, &q, (const float (*)[3])pos,
                                          (const float (*)[3])nrm, np, 0,
                                          &irr, &e), SVET_OK);
    ck_assert_uint_eq(irr.n, np);
    double sum = 0, sum2 = 0, plain = 0;
    int nq = 0;
    for (int i = 0; i < 30; i++)
        for (int j = 0; j < 30; j++, nq++) {
            VECTOR3 x = { (real)(0.05 + 0.03 * i), (real)(0.05 + 0.03 * j), 0 };
            RADIANCE est;
            ck_assert(photonmap_precomputed(&irr, x, up, REAL_C(0.05), &est));
            double v = (double)est.g / (double)phi;
            sum += v;
            sum2 += v * v;
            plain += (double)photonmap_irradiance(&m, x, up, &q).g /
                     (double)phi;
            ck_assert(!photonmap_precomputed(&irr, x, down, REAL_C(0.05),
                                             &est));
        }
    VECTOR3 far = { 3, 3, 0 };
    RADIANCE est;
    ck_assert(!photonmap_precomputed(&irr, far, up, 1, &est));
    double mean = sum / nq, sd = sqrt(sum2 / nq - mean * mean);
    plain /= nq;
    double exact = (double)k / (k - 2), rel_sd = 1 / sqrt(k - 3.0);
    double tol = 4 * rel_sd / sqrt((double)nq);
    ck_assert_msg(fabs(mean / exact - 1) < tol, "mean %g, exact %g (tol %g)",
                  mean, exact, tol);
    ck_assert_msg(fabs(mean / (plain * (k - 1) / (k - 2)) - 1) < tol,
                  "precomputed mean %g, plain %g (tol %g)", mean, plain, tol);
    ck_assert_msg(fabs(sd / (exact * rel_sd) - 1) < 0.2, "sd %g, exact %g",
                  sd, exact * rel_sd);
    free(pos);
    free(nrm);
    photonmap_free(&irr);
    photonmap_free(&m);
}
END_TEST

START_TEST(precomputed_irradiance_in_the_box_is_the_estimate_at_its_photons)
{
    /* In the closed box every precomputed point is a stored photon on a
     * wall, its normal the wall's inward one, and its value the plain
     * estimate there: a lookup at the very point answers with exactly
     * photonmap_irradiance at it (the point is its own nearest). */
    scene_t s;
    render_t r;
    svet_error e;
    box_render(&s, &r);
    photonmap_t m, irr;
    photonmap_query_t q = { 50, REAL_C(0.3), PHOTONMAP_FILTER_NONE,
                            REAL_C(1.1), REAL_C(0.25) };
    ck_assert_int_eq(photon_trace_precomputed(&r, 20000, PHOTON_GLOBAL, 0, 0,
                                              16, &q, &m, &irr, &e), SVET_OK);
    ck_assert(irr.n > 1000);
    for (size_t i = 1; i <= irr.n; i++) {
        const photon_t *p = &irr.ph[i];
        VECTOR3 x = { p->pos[0], p->pos[1], p->pos[2] }, nv = { 0, 0, 0 };
        int axis = 0;
        for (int a = 1; a < 3; a++)
            if (fabs(x[a]) > fabs(x[axis]))
                axis = a;
        ck_assert(fabs(fabs(x[axis]) - 1) < REAL_C(1e-4));
        nv[axis] = x[axis] > 0 ? -1 : 1; /* inward */
        VECTOR3 d;
        photonmap_direction(p, d);
        ck_assert_msg(SVECTOR3(d, nv) > REAL_C(0.99), "normal %g %g %g at %g %g %g",
                      (double)d[X], (double)d[Y], (double)d[Z], (double)x[X],
                      (double)x[Y], (double)x[Z]);
        RADIANCE got, want = photonmap_irradiance(&m, x, nv, &q);
        ck_assert(photonmap_precomputed(&irr, x, nv, REAL_C(0.01), &got));
        ck_assert_rel(got.g, want.g, 1e-6, 0);
        ck_assert(want.g > 0);
    }
    photonmap_free(&irr);
    photonmap_free(&m);
    render_free(&r);
    scene_free(&s);
}
END_TEST

/* --- renders -------------------------------------------------------------- */

/* caustic.scn at a small size */
static const char caustic_scene[] =
    "camera position 0 2.2 4.2 target 0 0.45 0 up 0 1 0 fov 38 fov_axis x "
    "width 24 height 18\n"
    "render maxdepth 10 seed 0\n"
    "photonmap global 20000 caustic 60000 k 50 max_radius 0.1 gather 8 "
    "radius 0.1 alpha 0.7\n"
    "material glass glass eta 1.5\n"
    "material white lambert rho 0.75\n"
    "material grey lambert rho 0.5\n"
    "parallelogram c0 -3 0 3 c1 3 0 3 c3 -3 0 -3 material white\n"
    "parallelogram c0 -3 0 -3 c1 3 0 -3 c3 -3 3 -3 material grey\n"
    "sphere centre 0 0.5 0 radius 0.5 material glass\n"
    "disk centre -0.6 2.6 -0.6 normal 0 -1 0 radius 0.15 material white "
    "emit 80\n";

static void render_with(const char *text, const char *method, long spp,
                        int threads, long passes, image_t *img)
{
    scene_t s;
    scenecheck_parse_ok(&s, text);
    svet_error e;
    char set[64];
    snprintf(set, sizeof set, "integrator=%s", method);
    ck_assert_int_eq(scenefile_override(&s, set, &e), SVET_OK);
    render_t r;
    ck_assert_msg(render_init(&r, &s, &e) == SVET_OK, "%s", e.msg);
    for (long p = 1; p <= passes; p++)
        ck_assert_int_eq(render_pass(&r, spp * p / passes, threads, NULL,
                                     NULL), SVET_OK);
    ck_assert_int_eq(render_image(&r, img, &e), SVET_OK);
    render_free(&r);
    scene_free(&s);
}

static double image_mean(const image_t *a)
{
    double s = 0;
    size_t n = (size_t)a->width * (size_t)a->height * 3;
    for (size_t i = 0; i < n; i++)
        s += (double)a->px[i];
    return s / (double)n;
}

/* root mean square difference of the means of bw x bh blocks of pixels,
 * relative to b's mean; 1 x 1 blocks are the pixels */
static double rel_rms(const image_t *a, const image_t *b, int bw, int bh)
{
    double s = 0;
    int n = 0;
    for (int y0 = 0; y0 + bh <= a->height; y0 += bh)
        for (int x0 = 0; x0 + bw <= a->width; x0 += bw)
            for (int c = 0; c < 3; c++, n++) {
                double d = 0;
                for (int y = y0; y < y0 + bh; y++)
                    for (int x = x0; x < x0 + bw; x++)
                        d += (double)image_at(a, x, y)[c] -
                             (double)image_at(b, x, y)[c];
                d /= bw * bh;
                s += d * d;
            }
    return sqrt(s / n) / image_mean(b);
}

/* method's image of spp samples: one thread and one pass against two
 * threads and `passes` passes, the same bits */
static void same_bits(const char *method, long spp, long passes)
{
    image_t a, b;
    render_with(caustic_scene, method, spp, 1, 1, &a);
    render_with(caustic_scene, method, spp, 2, passes, &b);
    ck_assert_msg(memcmp(a.px, b.px, (size_t)a.width * (size_t)a.height * 3 *
                                         sizeof(float)) == 0,
                  "%s: the images differ", method);
    image_free(&a);
    image_free(&b);
}

START_TEST(images_are_the_same_for_threads_and_passes)
{
    same_bits("photon", 2, 2);
    /* ppm: sample i sees map i whichever pass it falls in */
    same_bits("ppm", 4, 3);
}
END_TEST

/* The path tracer's image of 4096 samples as the reference. The photon
 * map's estimate blurs the caustic's focus over its radius (that bias
 * goes to zero only with the radius), so the images are compared in
 * blocks of 4 x 3 pixels, over which the blur moves little light: the
 * image means must agree within 5 % and the blocks' RMS difference stay
 * below 10 % of the mean (the reference's own, against 16384 samples, is
 * about 3 %). ppm's per-pixel error must fall with the samples: it holds
 * both the noise and the blur, and both shrink. */
START_TEST(photon_and_ppm_converge_to_the_path_tracer)
{
    image_t ref, ph, pp[3];
    render_with(caustic_scene, "path", 4096, 0, 1, &ref);
    render_with(caustic_scene, "photon", 16, 0, 1, &ph);
    double mref = image_mean(&ref);
    ck_assert_msg(fabs(image_mean(&ph) / mref - 1) < 0.05,
                  "photon mean %g, path %g", image_mean(&ph), mref);
    double e_ph = rel_rms(&ph, &ref, 4, 3);
    ck_assert_msg(e_ph < 0.10, "photon: relative RMS %g", e_ph);
    const long spp[3] = { 4, 32, 256 };
    double e[3];
    for (int i = 0; i < 3; i++) {
        render_with(caustic_scene, "ppm", spp[i], 0, i + 1, &pp[i]);
        e[i] = rel_rms(&pp[i], &ref, 1, 1);
    }
    ck_assert_msg(fabs(image_mean(&pp[2]) / mref - 1) < 0.05,
                  "ppm mean %g, path %g", image_mean(&pp[2]), mref);
    ck_assert_msg(rel_rms(&pp[2], &ref, 4, 3) < 0.10, "ppm: block RMS %g",
                  rel_rms(&pp[2], &ref, 4, 3));
    /* the slope of log error against log samples, least squares */
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int i = 0; i < 3; i++) {
        double x = log((double)spp[i]), y = log(e[i]);
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
    }
    double slope = (3 * sxy - sx * sy) / (3 * sxx - sx * sx);
    ck_assert_msg(slope < -0.1 && e[2] < e[1] && e[1] < e[0],
                  "ppm: RMS %g, %g, %g at 4, 32, 256 samples: slope %g", e[0],
                  e[1], e[2], slope);
    image_free(&ref);
    image_free(&ph);
    for (int i = 0; i < 3; i++)
        image_free(&pp[i]);
}
END_TEST

/* The Cornell box (scenes/cbox.scn's numbers) at 16 x 16: the photon
 * map with final gathering and ppm against the path tracer, in 8 x 4
 * blocks, where the blur of the estimate moves little light and the
 * light, a few pixels seen directly and noisy at a few samples, falls in
 * one block. The light's few pixels carry the jitter's noise, the same
 * numbers as the path tracer's at 64 samples (dimensions 0 and 1 of a
 * sample are its position in the pixel): about 10 % block RMS at 64
 * samples alone, so the blocks must agree within 15 %, the means within
 * 5 %. */
static char *cbox_text(void)
{
    static char text[8192];
    FILE *f = fopen("scenes/cbox.scn", "r");
    ck_assert_ptr_nonnull(f);
    size_t n = fread(text, 1, sizeof text - 200, f);
    fclose(f);
    text[n] = 0;
    strcat(text, "camera width 16 height 16\n"
                 "photonmap global 50000 caustic 1000 k 50 max_radius 0.2 "
                 "gather 4 radius 0.1\n");
    return text;
}

START_TEST(cornell_box_converges_to_the_path_tracer)
{
    const char *text = cbox_text();
    image_t ref, ph, pp;
    render_with(text, "path", 2048, 0, 1, &ref);
    render_with(text, "photon", 64, 0, 1, &ph);
    render_with(text, "ppm", 64, 0, 2, &pp);
    double mref = image_mean(&ref);
    ck_assert_msg(fabs(image_mean(&ph) / mref - 1) < 0.05,
                  "photon mean %g, path %g", image_mean(&ph), mref);
    ck_assert_msg(fabs(image_mean(&pp) / mref - 1) < 0.05,
                  "ppm mean %g, path %g", image_mean(&pp), mref);
    double e_ph = rel_rms(&ph, &ref, 8, 4), e_pp = rel_rms(&pp, &ref, 8, 4);
    ck_assert_msg(e_ph < 0.15 && e_pp < 0.15, "block RMS photon %g, ppm %g",
                  e_ph, e_pp);
    image_free(&ref);
    image_free(&ph);
    image_free(&pp);
}
END_TEST

/* --- the statement's messages --------------------------------------------- */

static void refused(const char *line, const char *what)
{
    char text[512];
    snprintf(text, sizeof text, "%s\n%s\n", box_scene, line);
    scene_t s;
    svet_error e;
    ck_assert_int_ne(scenecheck_parse(&s, text, &e), SVET_OK);
    ck_assert_msg(strstr(e.msg, "t.scn:7:") && strstr(e.msg, what),
                  "%s: %s", line, e.msg);
}

START_TEST(photonmap_statement_messages)
{
    refused("photonmap global 0", "at least 1 photon");
    refused("photonmap caustic 0", "at least 1 photon");
    refused("photonmap k 0", "k");
    refused("photonmap max_radius -1", "max_radius");
    refused("photonmap radius 0", "radius");
    refused("photonmap alpha 1.5", "alpha");
    refused("photonmap global 100000000000000", "GB");
    /* below the largest count, a map the memory cannot hold, when this
     * machine's is below 2e9 photons' 112 GB */
    svet_error big;
    if (photonmap_check_count(2000000000, &big) == SVET_ERR_NOMEM)
        refused("photonmap caustic 2000000000", "GB of memory");
    refused("photonmap filter box", "filter");
    refused("photonmap gathr 4", "did you mean 'gather'");
    refused("photonmap precompute -1", "precompute");
    scene_t s;
    scenecheck_parse_ok(&s, box_scene);
    svet_error e;
    ck_assert_int_eq(scenefile_override(&s, "photonmap.k=20", &e), SVET_OK);
    ck_assert_int_eq(scenefile_override(&s, "photonmap.gather=0", &e),
                     SVET_OK);
    photon_settings_t set;
    photon_settings_of(&s, &set);
    ck_assert_int_eq(set.k, 20);
    ck_assert_int_eq(set.gather, 0);
    ck_assert_uint_eq(set.global, 100000);
    ck_assert_int_eq(scenefile_override(&s, "photonmap.precompute=8", &e),
                     SVET_OK);
    photon_settings_of(&s, &set);
    ck_assert_int_eq(set.precompute, 8);
    ck_assert_int_ne(scenefile_override(&s, "photonmap.k=0", &e), SVET_OK);
    scene_free(&s);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("photon (" REAL_NAME ")");
    TCase *t = tcase_create("core");
    tcase_set_timeout(t, 600);
    tcase_add_test(t, photonmap_statement_messages);
    tcase_add_test(t, power_balance_in_a_closed_box);
    tcase_add_test(t, maps_are_the_same_for_any_thread_count);
    tcase_add_test(t, environment_photons_give_pi_L_on_an_open_plane);
    tcase_add_test(t, emission_by_power_with_an_environment_and_a_disc_light);
    tcase_add_test(t,
                   environment_photons_reach_an_infinite_plane_where_the_camera_looks);
    tcase_add_test(t, photon_tracing_reads_the_texture);
    tcase_add_test(t, density_estimate_on_uniform_photons_has_its_exact_mean);
    tcase_add_test(t,
                   precomputed_irradiance_on_uniform_photons_has_its_exact_mean);
    tcase_add_test(t,
                   precomputed_irradiance_in_the_box_is_the_estimate_at_its_photons);
    tcase_add_test(t, images_are_the_same_for_threads_and_passes);
    tcase_add_test(t, photon_and_ppm_converge_to_the_path_tracer);
    tcase_add_test(t, cornell_box_converges_to_the_path_tracer);
    suite_add_tcase(s, t);
    return s;
}
