/* cc -std=c11 -O2 -Iinclude chapters/ch01/ch01_brdf.c src/materials/brdf.c src/core/sample.c src/core/frame.c src/core/vec.c src/core/rng.c src/core/error.c -lm -o ch01_brdf */
/*
 * ch01_brdf.c - chapter 1, the optical properties of materials, computed:
 * polar plots in the plane of incidence of the lobes (1.5), (1.8),
 * (1.9)-(1.10), the curves rho_s(theta) of Schlick (1.7) and rho_t(theta)
 * of the book, and the albedo of each model against its parameter and the
 * angle of incidence (Monte Carlo with the lobes' own sampling).
 *
 *   ch01_lambert.ppm      Lambert (1.5)
 *   ch01_phong.ppm        modified Phong (1.8), e = 1, 10, 100
 *   ch01_ward.ppm         Ward (1.9) as the book prints it, alpha = 0.05, 0.15, 0.4
 *   ch01_ward_bounded.ppm the same with the bounded normalisation
 *   ch01_ward_aniso.ppm   Ward (1.10), alpha_x = 0.4, alpha_y = 0.08, two planes
 *   ch01_schlick.ppm      rho_s(theta) (1.7) and rho_t(theta) against theta
 *   ch01_lobe_NAME.csv    the curves of each polar plot (NAME: lambert,
 *                         phong, ward, ward_bounded, ward_aniso)
 *   ch01_schlick.csv      the Schlick curves
 *   ch01_albedo.csv       albedo against each parameter and theta_o
 *   ch01_albedo.md        the same tables, as printed
 *
 * The CSV files are drawn with axes and legends by brdf_lobes.gp,
 * schlick.gp and albedo.gp beside this file (`make figures`).
 * usage: ch01_brdf [OUTDIR] [--samples N]   (default out/; --help)
 */
#include <stdbool.h>

#include "../chapter.h"
#include "materials/brdf.h"
#include "core/rng.h"
#include "core/sample.h"

#define PI_D 3.14159265358979323846
#define SEED UINT64_C(19920701) /* every number below follows from it */

/* --- a canvas and a PPM writer (no library) ------------------------------- */

typedef struct {
    int w, h;
    unsigned char *px; /* RGB, row-major, top row first */
} canvas_t;

typedef struct {
    unsigned char r, g, b;
} colour_t;

static const colour_t BLACK = { 0, 0, 0 }, GREY = { 170, 170, 170 },
                      LIGHT = { 225, 225, 225 };
static const colour_t PALETTE[4] = {
    { 200, 30, 30 }, { 20, 130, 40 }, { 30, 60, 200 }, { 230, 130, 0 }
};

static canvas_t canvas_new(int w, int h)
{
    canvas_t c = { w, h, malloc((size_t)w * (size_t)h * 3) };
    if (!c.px) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
    memset(c.px, 255, (size_t)w * (size_t)h * 3);
    return c;
}

static void plot(canvas_t *c, int x, int y, colour_t col)
{
    if (x < 0 || y < 0 || x >= c->w || y >= c->h)
        return;
    unsigned char *p = c->px + 3 * ((size_t)y * (size_t)c->w + (size_t)x);
    p[0] = col.r;
    p[1] = col.g;
    p[2] = col.b;
}

/* A line of width 2 (a 2x2 pen), dashed when dash > 0 (pixels on, off). */
static void line(canvas_t *c, double x0, double y0, double x1, double y1,
                 colour_t col, int dash)
{
    double dx = x1 - x0, dy = y1 - y0;
    int n = (int)(fmax(fabs(dx), fabs(dy)) + 1);
    for (int i = 0; i <= n; i++) {
        if (dash > 0 && (i / dash) % 2 == 1)
            continue;
        int x = (int)lround(x0 + dx * i / n), y = (int)lround(y0 + dy * i / n);
        plot(c, x, y, col);
        plot(c, x + 1, y, col);
        plot(c, x, y + 1, col);
        plot(c, x + 1, y + 1, col);
    }
}

/* P6, written to a temporary file and renamed. Returns 0 on success. */
static int write_ppm(const canvas_t *c, const char *dir, const char *name)
{
    chapter_file_t cf;
    FILE *f = chapter_open(&cf, "ch01_brdf", dir, name);
    if (!f)
        return 1;
    fprintf(f, "P6\n%d %d\n255\n", c->w, c->h);
    fwrite(c->px, 3, (size_t)c->w * (size_t)c->h, f);
    return chapter_close(&cf, "ch01_brdf");
}

/* --- polar plots in the plane of incidence --------------------------------- */
/*
 * The plot is the plane that holds the normal n (up) and the light
 * direction Psi_i (drawn on the left, at theta_i from n). For each Psi_r
 * of that plane, at theta_r from -90 to 90 degrees (positive to the
 * right), the curve lies at distance f(Psi_i, Psi_r) cos(theta_r) from
 * the centre: the intensity reflected toward Psi_r per unit irradiance,
 * the quantity the lobes of figs. 1.4-1.5 picture (Lambert's is the circle
 * of the cosine law). Each curve is scaled to its own peak, printed on
 * stdout with the peak of f, since the peaks differ by orders of
 * magnitude (Phong e = 100 peaks 34 times higher than e = 1). The thin
 * grey half circle is radius 1; the grey line is Psi_i, the dashed one its
 * mirror direction (1.4).
 */
#define PW 640
#define PH 360
#define PCX (PW / 2)
#define PCY (PH - 20)
#define PR 320.0

/* The in-plane direction at angle t from n; the plane holds n and the
 * tangent (cos(azim), sin(azim), 0). */
static void in_plane(VECTOR3 w, double t, double azim)
{
    vec_set(w, (real)(sin(t) * cos(azim)), (real)(sin(t) * sin(azim)),
            (real)cos(t));
}

static void polar_axes(canvas_t *c, double theta_i)
{
    for (int k = 0; k <= 720; k++) { /* radius 1 */
        double t = PI_D * (k / 720.0 - 0.5);
        plot(c, (int)lround(PCX + PR * 0.98 * sin(t)),
             (int)lround(PCY - PR * 0.98 * cos(t)), LIGHT);
    }
    line(c, 0, PCY, PW - 1, PCY, BLACK, 0);            /* the surface */
    line(c, PCX, PCY, PCX, PCY - PR * 0.98, LIGHT, 0); /* the normal */
    double r = PR * 0.98;
    line(c, PCX, PCY, PCX - r * sin(theta_i), PCY - r * cos(theta_i), GREY, 0);
    line(c, PCX, PCY, PCX + r * sin(theta_i), PCY - r * cos(theta_i), GREY, 6);
}

/* One curve: f cos(theta_r) of b for Psi_i at theta_i in the plane of
 * azimuth azim. Returns the largest f met (the book's Ward grows without
 * bound toward the horizon: that number shows it). */
static double polar_curve(canvas_t *c, const brdf_t *b, double theta_i,
                          double azim, colour_t col)
{
    enum { N = 3601 };
    static double r[N];
    VECTOR3 wi, wo;
    in_plane(wi, -theta_i, azim);
    double peak = 0, fpeak = 0;
    for (int k = 0; k < N; k++) {
        double t = PI_D * ((double)k / (N - 1) - 0.5) * 0.9999;
        in_plane(wo, t, azim);
        double f = (double)brdf_eval(b, wi, wo).r;
        r[k] = f * (double)wo[Z];
        peak = fmax(peak, r[k]);
        fpeak = fmax(fpeak, f);
    }
    double px = 0, py = 0;
    for (int k = 0; k < N; k++) {
        double t = PI_D * ((double)k / (N - 1) - 0.5) * 0.9999;
        double s = peak > 0 ? 0.98 * PR * r[k] / peak : 0;
        double x = PCX + s * sin(t), y = PCY - s * cos(t);
        if (k > 0)
            line(c, px, py, x, y, col, 0);
        px = x;
        py = y;
    }
    return fpeak;
}

static void check(svet_status st, const svet_error *err)
{
    if (st != SVET_OK) {
        fprintf(stderr, "%s\n", err->msg);
        exit(1);
    }
}

/* One polar plot: up to three curves, each a BRDF seen in the plane of
 * azimuth azim[k]; key[k] names its columns in the CSV, what[k] its line
 * on stdout. */
typedef struct {
    const char *name, *title; /* ch01_lobe_NAME.csv, and its first comment */
    int n;
    brdf_t b[3];
    double azim[3];
    const char *key[3], *what[3];
} lobes_t;

/* The curves as CSV: theta_r from -89.75 to 89.75 degrees in steps of
 * 0.25 (the horizon itself is left out: the book's Ward is infinite
 * there), and for each curve f in 1/sr and f cos(theta_r), the length
 * the polar plot draws. */
static int lobe_csv(const lobes_t *l, double theta_i, const char *dir)
{
    char name[64];
    snprintf(name, sizeof name, "ch01_lobe_%s.csv", l->name);
    chapter_file_t cf;
    FILE *f = chapter_open(&cf, "ch01_brdf", dir, name);
    if (!f)
        return 1;
    fprintf(f, "# ch01_brdf: %s, rho = 1, in the plane of incidence; Psi_i "
               "at theta_r = -%g deg; f in 1/sr\ntheta_r_deg",
            l->title, theta_i * 180 / PI_D);
    for (int k = 0; k < l->n; k++)
        fprintf(f, ",f_%s,fcos_%s", l->key[k], l->key[k]);
    fprintf(f, "\n");
    for (int i = 0; i <= 718; i++) {
        double deg = -89.75 + 0.25 * i, t = deg * PI_D / 180;
        fprintf(f, "%g", deg);
        for (int k = 0; k < l->n; k++) {
            VECTOR3 wi, wo;
            in_plane(wi, -theta_i, l->azim[k]);
            in_plane(wo, t, l->azim[k]);
            double v = (double)brdf_eval(&l->b[k], wi, wo).r;
            fprintf(f, ",%.6g,%.6g", v, v * (double)wo[Z]);
        }
        fprintf(f, "\n");
    }
    return chapter_close(&cf, "ch01_brdf");
}

static int polar_plots(const char *dir)
{
    const RADIANCE one = rad_grey(1);
    const double ti = 45 * PI_D / 180;
    static const char *const colour[3] = { "red", "green", "blue" };
    svet_error err;
    lobes_t l[5] = {
        { "lambert", "Lambert (1.5)", 1, .key = { "lambert" },
          .what = { "Lambert (1.5): f = 1/pi everywhere" } },
        { "phong", "modified Phong (1.8)", 3, .key = { "e1", "e10", "e100" },
          .what = { "Phong (1.8), e = 1", "Phong (1.8), e = 10",
                    "Phong (1.8), e = 100" } },
        { "ward", "Ward (1.9) as the book prints it", 3,
          .key = { "a0.05", "a0.15", "a0.4" },
          .what = { "Ward (1.9), alpha = 0.05", "Ward (1.9), alpha = 0.15",
                    "Ward (1.9), alpha = 0.4" } },
        { "ward_bounded", "Ward (1.9) with the bounded normalisation", 3,
          .key = { "a0.05", "a0.15", "a0.4" },
          .what = { "Ward bounded, alpha = 0.05", "Ward bounded, alpha = 0.15",
                    "Ward bounded, alpha = 0.4" } },
        { "ward_aniso", "Ward (1.10), alpha_x = 0.4, alpha_y = 0.08", 2,
          .azim = { 0, PI_D / 2 }, .key = { "u", "v" },
          .what = { "Ward (1.10), plane along u", "Ward (1.10), plane along v" } },
    };
    check(brdf_lambert(&l[0].b[0], one, &err), &err);
    const double es[3] = { 1, 10, 100 }, as[3] = { 0.05, 0.15, 0.4 };
    for (int k = 0; k < 3; k++) {
        check(brdf_phong(&l[1].b[k], one, (real)es[k], &err), &err);
        check(brdf_ward(&l[2].b[k], one, (real)as[k], (real)as[k], false, &err),
              &err);
        check(brdf_ward(&l[3].b[k], one, (real)as[k], (real)as[k], true, &err),
              &err);
    }
    check(brdf_ward(&l[4].b[0], one, REAL_C(0.4), REAL_C(0.08), false, &err),
          &err);
    l[4].b[1] = l[4].b[0];

    int bad = 0;
    canvas_t c = canvas_new(PW, PH);
    for (int i = 0; i < 5; i++) {
        memset(c.px, 255, (size_t)PW * PH * 3);
        polar_axes(&c, ti);
        for (int k = 0; k < l[i].n; k++) {
            int pen = l[i].n == 2 ? 2 * k : k; /* two curves: red, blue */
            printf("%s (%s): peak f = %.4f\n", l[i].what[k],
                   colour[pen], polar_curve(&c, &l[i].b[k], ti, l[i].azim[k],
                                            PALETTE[pen]));
        }
        char name[64];
        snprintf(name, sizeof name, "ch01_%s.ppm", l[i].name);
        bad |= write_ppm(&c, dir, name);
        bad |= lobe_csv(&l[i], ti, dir);
    }
    free(c.px);
    return bad;
}

/* --- the Schlick curve --------------------------------------------------- */
/*
 * x: theta from 0 to 90 degrees; y: 0 to 1; grid every 15 degrees and
 * 0.25. rho_s(theta) = rho_s(0) + (1 - rho_s(0)) (1 - cos theta)^5 (1.7)
 * for rho_s(0) = 0.04 (glass, red), 0.2 (green), 0.5 (blue), 0.9 (metal,
 * orange); dashed black: the book's rho_t(theta) = rho_t(0) (1 - (1 -
 * cos theta)^5) for rho_t(0) = 0.96, the glass's transmission.
 */
static int schlick_plot(const char *dir)
{
    const int W = 640, H = 400, X0 = 40, Y0 = H - 30, XS = 570, YS = 350;
    canvas_t c = canvas_new(W, H);
    for (int k = 0; k <= 6; k++)
        line(&c, X0 + XS * k / 6.0, Y0, X0 + XS * k / 6.0, Y0 - YS, LIGHT, 0);
    for (int k = 0; k <= 4; k++)
        line(&c, X0, Y0 - YS * k / 4.0, X0 + XS, Y0 - YS * k / 4.0, LIGHT, 0);
    line(&c, X0, Y0, X0 + XS, Y0, BLACK, 0);
    line(&c, X0, Y0, X0, Y0 - YS, BLACK, 0);
    const double rho0[4] = { 0.04, 0.2, 0.5, 0.9 };
    printf("Schlick (1.7): theta   ");
    for (int k = 0; k < 4; k++)
        printf("  rho_s(0)=%.2f", rho0[k]);
    printf("  rho_t, rho_t(0)=0.96\n");
    for (int curve = 0; curve < 5; curve++) {
        double px = 0, py = 0;
        for (int i = 0; i <= 900; i++) {
            double t = i / 10.0 * PI_D / 180;
            real f5 = brdf_schlick_factor((real)cos(t));
            double v = curve < 4 ? (double)brdf_schlick(rad_grey((real)rho0[curve]),
                                                         rad_grey(1),
                                                         (real)cos(t)).r
                                 : 0.96 * (1 - (double)f5);
            double x = X0 + XS * i / 900.0, y = Y0 - YS * v;
            bool gap = curve == 4 && (i / 15) % 2 == 1; /* dashed */
            if (i > 0 && !gap)
                line(&c, px, py, x, y, curve < 4 ? PALETTE[curve] : BLACK, 0);
            px = x;
            py = y;
        }
    }
    for (int deg = 0; deg <= 90; deg += 15) {
        double t = deg * PI_D / 180;
        real f5 = brdf_schlick_factor((real)cos(t));
        printf("                %5d  ", deg);
        for (int k = 0; k < 4; k++)
            printf("  %13.4f", rho0[k] + (1 - rho0[k]) * (double)f5);
        printf("  %12.4f\n", 0.96 * (1 - (double)f5));
    }
    int bad = write_ppm(&c, dir, "ch01_schlick.ppm");
    free(c.px);

    chapter_file_t cf;
    FILE *f = chapter_open(&cf, "ch01_brdf", dir, "ch01_schlick.csv");
    if (!f)
        return 1;
    fprintf(f, "# ch01_brdf: Schlick's rho_s(theta) (1.7) for four rho_s(0), "
               "and the book's rho_t(theta) for rho_t(0) = 0.96\ntheta_deg");
    for (int k = 0; k < 4; k++)
        fprintf(f, ",rho_s_%g", rho0[k]);
    fprintf(f, ",rho_t_0.96\n");
    for (int i = 0; i <= 180; i++) {
        double t = i * 0.5 * PI_D / 180;
        double f5 = (double)brdf_schlick_factor((real)cos(t));
        fprintf(f, "%g", i * 0.5);
        for (int k = 0; k < 4; k++)
            fprintf(f, ",%.6g", (double)brdf_schlick(rad_grey((real)rho0[k]),
                                                    rad_grey(1),
                                                    (real)cos(t)).r);
        fprintf(f, ",%.6g\n", 0.96 * (1 - f5));
    }
    return bad | chapter_close(&cf, "ch01_brdf");
}

/* --- albedo against each parameter --------------------------------------- */
/*
 * a(theta_o) = integral of f(Psi_i, Psi_r) cos(theta_i) d(omega_i), the
 * fraction of light from Psi_r's direction... by reciprocity, the fraction
 * of uniform incident radiance reflected toward Psi_r. Estimated by the
 * mean of N sample weights f cos / pdf (the lobes' own sampling, ch. 4),
 * with its standard error. rho = 1 throughout, so a = 1 is a surface
 * that loses nothing.
 */
#define NA 7
static const double theta_deg[NA] = { 0, 30, 60, 75, 85, 89, 89.9 };
static long nsamp = 100000; /* --samples */

typedef struct {
    const char *model, *param;
    double value;
    brdf_t b;
} row_t;

static void albedo(const brdf_t *b, double theta, uint64_t seed, double *mean,
                   double *se)
{
    VECTOR3 wo;
    in_plane(wo, theta, 0.3);
    pcg32_t g;
    pcg32_seed(&g, SEED, seed);
    estimator_t e;
    estimator_init(&e);
    for (long k = 0; k < nsamp; k++) {
        real u[2] = { pcg32_real(&g), pcg32_real(&g) };
        brdf_sample_t s;
        estimator_add(&e, brdf_sample(b, wo, u, &s) ? (double)s.weight.r : 0);
    }
    *mean = estimator_mean(&e);
    *se = estimator_stderr(&e);
}

static int albedo_tables(const char *dir)
{
    row_t rows[40];
    int n = 0;
    svet_error err;
    const RADIANCE one = rad_grey(1);
    rows[n].model = "lambert (1.5)";
    rows[n].param = "-";
    rows[n].value = 0;
    check(brdf_lambert(&rows[n++].b, one, &err), &err);
    const double es[] = { 0, 1, 2, 5, 10, 20, 50, 100, 1000 };
    for (size_t i = 0; i < sizeof es / sizeof *es; i++, n++) {
        rows[n].model = "phong (1.8)";
        rows[n].param = "e";
        rows[n].value = es[i];
        check(brdf_phong(&rows[n].b, one, (real)es[i], &err), &err);
    }
    const double as[] = { 0.01, 0.05, 0.1, 0.2, 0.4, 0.7, 1 };
    for (int bounded = 0; bounded < 2; bounded++)
        for (size_t i = 0; i < sizeof as / sizeof *as; i++, n++) {
            rows[n].model = bounded ? "ward bounded" : "ward (1.9)";
            rows[n].param = "alpha";
            rows[n].value = as[i];
            check(brdf_ward(&rows[n].b, one, (real)as[i], (real)as[i],
                            bounded, &err), &err);
        }
    const double r0[] = { 0.04, 0.5 };
    for (size_t i = 0; i < 2; i++, n++) {
        rows[n].model = "mirror (1.6)-(1.7)";
        rows[n].param = "rho_s(0)";
        rows[n].value = r0[i];
        check(brdf_mirror(&rows[n].b, rad_grey((real)r0[i]), 1, &err), &err);
    }
    rows[n].model = "transmission (1.13)";
    rows[n].param = "eta";
    rows[n].value = 1.5;
    check(brdf_specular_transmission(&rows[n++].b, one, REAL_C(1.5), &err),
          &err);

    chapter_file_t cf, cm;
    FILE *f = chapter_open(&cf, "ch01_brdf", dir, "ch01_albedo.csv");
    FILE *md = f ? chapter_open(&cm, "ch01_brdf", dir, "ch01_albedo.md") : NULL;
    if (!md) {
        if (f)
            fclose(f);
        return 1;
    }
    fprintf(f, "# Albedo (integral of f cos) of each component with rho = 1, by "
               "Monte Carlo, %ld samples each, seed %llu\nmodel,param,value,"
               "theta_deg,albedo,stderr\n", nsamp, (unsigned long long)SEED);
    FILE *outs[2] = { stdout, md };
    for (int o = 0; o < 2; o++) {
        fprintf(outs[o], "\nAlbedo with rho = 1 against theta_o (degrees); "
                         "%ld samples each, standard error < 0.005 unless "
                         "shown\n\n| model | param | ", nsamp);
        for (int j = 0; j < NA; j++)
            fprintf(outs[o], "%g | ", theta_deg[j]);
        fprintf(outs[o], "\n|---|---|");
        for (int j = 0; j < NA; j++)
            fprintf(outs[o], "---|");
        fprintf(outs[o], "\n");
    }
    for (int i = 0; i < n; i++) {
        char cell[NA][40];
        for (int j = 0; j < NA; j++) {
            double m, se;
            albedo(&rows[i].b, theta_deg[j] * PI_D / 180,
                   (uint64_t)(i * NA + j), &m, &se);
            fprintf(f, "%s,%s,%g,%g,%.6f,%.2g\n", rows[i].model, rows[i].param,
                    rows[i].value, theta_deg[j], m, se);
            if (se < 0.005)
                snprintf(cell[j], sizeof cell[j], "%.3f", m);
            else
                snprintf(cell[j], sizeof cell[j], "%.3f +- %.3f", m, se);
        }
        for (int o = 0; o < 2; o++) {
            if (rows[i].param[0] == '-')
                fprintf(outs[o], "| %s | | ", rows[i].model);
            else
                fprintf(outs[o], "| %s | %s = %g | ", rows[i].model,
                        rows[i].param, rows[i].value);
            for (int j = 0; j < NA; j++)
                fprintf(outs[o], "%s | ", cell[j]);
            fprintf(outs[o], "\n");
        }
    }
    int bad = chapter_close(&cf, "ch01_brdf");
    return bad | chapter_close(&cm, "ch01_brdf");
}

int main(int argc, char **argv)
{
    double samples = (double)nsamp;
    const chapter_opt_t opts[] = {
        { "--samples", "N", "Monte Carlo samples per albedo", &samples, 100,
          1e9 },
    };
    const chapter_cli_t cli = {
        "ch01_brdf",
        "Chapter 1's reflection models: polar plots of the lobes, the "
        "Schlick curves,\nand albedo tables, as PPM pictures, CSV files "
        "(for `make figures`) and Markdown.",
        "out", opts, 1
    };
    const char *dir;
    int rc = chapter_begin(&cli, argc, argv, &dir);
    if (rc >= 0)
        return rc;
    nsamp = (long)samples;
    int bad = polar_plots(dir);
    bad |= schlick_plot(dir);
    bad |= albedo_tables(dir);
    return bad ? 1 : 0;
}
