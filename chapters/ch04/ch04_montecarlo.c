/* cc -std=c11 -O2 -Iinclude chapters/ch04/ch04_montecarlo.c src/core/sample.c src/core/rng.c src/core/frame.c src/core/vec.c -lm -o ch04 */
/*
 * ch04_montecarlo.c - chapter 4, the Monte Carlo method: integrals whose
 * value we know, estimated with N = 1, 4, 16, ..., 4^10 samples by plain
 * (uniform), importance and stratified sampling; the error against N with
 * its fitted log-log slope (1/sqrt(N): slope -1/2), the variance of each
 * method per sample; and Russian roulette against truncation on the
 * furnace of ch. 5 reduced to one number.
 *
 *   ch04_irradiance.csv  RMS error against N, irradiance integral
 *   ch04_sine.csv        RMS error against N, int_0^pi sin x dx
 *   ch04_roulette.csv    Russian roulette and truncation
 *   ch04_montecarlo.md   all tables, as printed
 *
 * The CSV files are drawn by error.gp and roulette.gp beside this file
 * (`make figures`).
 * usage: ch04 [OUTDIR] [--kmax K] [--paths N]   (default out/; --help)
 */
#include <stdarg.h>

#include "../chapter.h"
#include "core/rng.h"
#include "core/sample.h"

#define PI_D 3.14159265358979323846
#define KMAX 10                  /* N = 4^0 .. 4^kmax, kmax <= KMAX */
#define SEED UINT64_C(20240401)  /* every number below follows from it */

static int kmax = KMAX;          /* --kmax */
static long npaths = 1000000;    /* --paths: Russian roulette's paths */

/* The irradiance integral: radiance L(theta) = cos^n(theta) arriving at a
 * surface gives the irradiance E = int_H L cos(theta) dw = 2 pi / (n + 2)
 * (sec. 4: the integrand f = cos^(n+1), with dw = sin dtheta dphi). */
#define IRR_N 3
static double irr_exact(void)
{
    return 2 * PI_D / (IRR_N + 2);
}

static double irr_f(double cos_theta)
{
    return cos_theta > 0 ? pow(cos_theta, IRR_N + 1) : 0;
}

/* --- the methods: one estimate of the integral from n samples ------------ */

typedef struct {
    const char *name;     /* column title */
    const char *what;     /* one line for the legend */
    /* estimate with n samples; pts holds room for 2 n reals */
    double (*estimate)(pcg32_t *g, long n, real *pts);
    double var_exact;     /* per-sample variance, where known; < 0 if not */
} method_t;

/* Fill pts with n points of [0,1)^2: jittered (one per cell of a
 * sqrt(n) x sqrt(n) grid, n a power of 4) or independent. */
static void uniform_points(real *pts, long n, pcg32_t *g, int stratified)
{
    if (stratified) {
        int m = (int)(sqrt((double)n) + 0.5);
        sample_stratified_2d(pts, m, m, g);
        return;
    }
    for (long i = 0; i < 2 * n; i++)
        pts[i] = pcg32_real(g);
}

enum { UNIFORM, COSINE, MATCHED }; /* how the directions are drawn */

/* One sample's f / p under the given sampling: a direction w from the
 * point u of [0,1)^2, and the integrand over the pdf there. */
static double irr_ratio(int how, const real u[2])
{
    VECTOR3 w;
    double pdf;
    switch (how) {
    case UNIFORM:
        sample_uniform_hemisphere(w, u);
        pdf = (double)sample_uniform_hemisphere_pdf();
        break;
    case COSINE:
        sample_cosine_hemisphere(w, u);
        pdf = (double)sample_cosine_hemisphere_pdf(w[Z]);
        break;
    default:
        /* p proportional to f: the Phong lobe cos^(n+1) about the normal.
         * f / p = 2 pi / (n + 2) for every sample: zero variance. */
        sample_phong_lobe(w, u, REAL_C(IRR_N + 1));
        pdf = (double)sample_phong_lobe_pdf(w[Z], REAL_C(IRR_N + 1));
        break;
    }
    return irr_f((double)w[Z]) / pdf;
}

/* f / p averaged: the estimator <I> = (1/N) sum f(x_i)/p(x_i) (sec. 4). */
static double irr_estimate(pcg32_t *g, long n, real *pts, int how, int strat)
{
    uniform_points(pts, n, g, strat);
    double sum = 0;
    for (long i = 0; i < n; i++)
        sum += irr_ratio(how, pts + 2 * i);
    return sum / (double)n;
}

static double m_irr_uniform(pcg32_t *g, long n, real *p) { return irr_estimate(g, n, p, UNIFORM, 0); }
static double m_irr_cosine(pcg32_t *g, long n, real *p) { return irr_estimate(g, n, p, COSINE, 0); }
static double m_irr_matched(pcg32_t *g, long n, real *p) { return irr_estimate(g, n, p, MATCHED, 0); }
static double m_irr_strat_uniform(pcg32_t *g, long n, real *p) { return irr_estimate(g, n, p, UNIFORM, 1); }
static double m_irr_strat_cosine(pcg32_t *g, long n, real *p) { return irr_estimate(g, n, p, COSINE, 1); }

/* A one-dimensional integral: int_0^pi sin x dx = 2. */

/* The triangle pdf p(x) = (4/pi^2) min(x, pi - x) on [0, pi], roughly the
 * shape of sin x: importance sampling with a density that is close to,
 * but not exactly, proportional to the integrand. Inverse cdf:
 * x = pi sqrt(u/2) for u < 1/2, pi - pi sqrt((1-u)/2) above. */
static double tri_x(double u)
{
    return u < 0.5 ? PI_D * sqrt(u / 2) : PI_D - PI_D * sqrt((1 - u) / 2);
}

static double tri_ratio(double x)
{
    double m = fmin(x, PI_D - x);
    /* sin x / p(x); at x = 0 the limit pi^2/4 (both vanish linearly) */
    return m > 0 ? sin(x) / (4 / (PI_D * PI_D) * m) : PI_D * PI_D / 4;
}

static double sine_estimate(pcg32_t *g, long n, int strat, int importance)
{
    double sum = 0;
    for (long i = 0; i < n; i++) {
        double u = (double)pcg32_real(g);
        if (strat)
            u = ((double)i + u) / (double)n; /* one sample per stratum */
        sum += importance ? tri_ratio(tri_x(u)) : PI_D * sin(PI_D * u);
    }
    return sum / (double)n;
}

static double m_sine_uniform(pcg32_t *g, long n, real *p) { (void)p; return sine_estimate(g, n, 0, 0); }
static double m_sine_importance(pcg32_t *g, long n, real *p) { (void)p; return sine_estimate(g, n, 0, 1); }
static double m_sine_strat(pcg32_t *g, long n, real *p) { (void)p; return sine_estimate(g, n, 1, 0); }
static double m_sine_strat_importance(pcg32_t *g, long n, real *p) { (void)p; return sine_estimate(g, n, 1, 1); }

/* --- output: stdout and a Markdown copy --------------------------------- */

static FILE *md; /* the Markdown file being written, or NULL */

#if defined(__GNUC__)
__attribute__((format(printf, 1, 2)))
#endif
static void out(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    if (md) {
        va_start(ap, fmt);
        vfprintf(md, fmt, ap);
        va_end(ap);
    }
}

/* --- the error against N ----------------------------------------------- */

/* Independent runs at each N: many where a run is cheap, fewer at the top
 * (the RMS error of R runs is itself uncertain by ~1/sqrt(2R)). */
static int runs_at(int k)
{
    return k <= 7 ? 64 : k == 8 ? 32 : 8;
}

/* Least-squares slope of log(err) against log(N) over k >= 2 (N >= 16). */
static double loglog_slope(const double *err)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int m = 0;
    for (int k = 2; k <= kmax; k++) {
        if (!(err[k] > 0))
            continue;
        double x = log(pow(4.0, k)), y = log(err[k]);
        sx += x; sy += y; sxx += x * x; sxy += x * y;
        m++;
    }
    if (m < 2)
        return (double)NAN;
    return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}

/* Run every method at every N, print the table, write CSV. Returns 0 on
 * success. */
static int error_table(const char *title, const char *csvname,
                       const char *dir, const method_t *ms, int nm,
                       double exact, uint64_t stream0)
{
    long nmax = 1L << (2 * kmax);
    real *pts = malloc((size_t)(2 * nmax) * sizeof *pts);
    double (*rmse)[KMAX + 1] = calloc((size_t)nm, sizeof *rmse);
    double *var_measured = calloc((size_t)nm, sizeof *var_measured);
    if (!pts || !rmse || !var_measured) {
        fprintf(stderr, "ch04: out of memory\n");
        free(pts); free(rmse); free(var_measured);
        return 1;
    }
    for (int m = 0; m < nm; m++)
        for (int k = 0; k <= kmax; k++) {
            long n = 1L << (2 * k);
            int runs = runs_at(k);
            estimator_t sq; /* squared errors of the runs */
            estimator_init(&sq);
            for (int r = 0; r < runs; r++) {
                pcg32_t g;
                /* one stream per (method, N, run): runs are independent */
                pcg32_seed(&g, SEED,
                           stream0 + (uint64_t)(m * 10000 + k * 1000 + r));
                double e = ms[m].estimate(&g, n, pts) - exact;
                estimator_add(&sq, e * e);
            }
            rmse[m][k] = sqrt(estimator_mean(&sq));
            if (k == kmax)
                var_measured[m] = (double)n * estimator_mean(&sq);
        }

    out("\n### %s\n\n", title);
    out("Exact value %.10g. RMS error over independent runs (64 runs up to "
        "N = 4^7, 32 at 4^8, 8 above).\n\n", exact);
    out("| N |");
    for (int m = 0; m < nm; m++)
        out(" %s |", ms[m].name);
    out("\n|---:|");
    for (int m = 0; m < nm; m++)
        out("---:|");
    out("\n");
    for (int k = 0; k <= kmax; k++) {
        out("| %ld |", 1L << (2 * k));
        for (int m = 0; m < nm; m++)
            out(" %.3e |", rmse[m][k]);
        out("\n");
    }
    out("| **log-log slope** (N >= 16) |");
    for (int m = 0; m < nm; m++) {
        double s = loglog_slope(rmse[m]);
        if (rmse[m][0] < 1e-6 * exact) /* one sample exact: zero variance */
            out(" none: exact to rounding |");
        else
            out(" %.3f |", s);
    }
    out("\n| **variance per sample**, exact |");
    for (int m = 0; m < nm; m++) {
        if (ms[m].var_exact >= 0)
            out(" %.4g |", ms[m].var_exact);
        else
            out(" - |");
    }
    out("\n| **N x MSE** at N = 4^%d |", kmax);
    for (int m = 0; m < nm; m++)
        out(" %.4g |", var_measured[m]);
    out("\n\n");
    for (int m = 0; m < nm; m++)
        out("- *%s*: %s\n", ms[m].name, ms[m].what);

    int rc = 0;
    chapter_file_t cf;
    FILE *f = chapter_open(&cf, "ch04", dir, csvname);
    if (!f) {
        rc = 1;
    } else {
        fprintf(f, "# %s: RMS error against N (exact %.17g); written by "
                   "chapters/ch04/ch04_montecarlo.c\nN", title, exact);
        for (int m = 0; m < nm; m++)
            fprintf(f, ",%s", ms[m].name);
        fprintf(f, "\n");
        for (int k = 0; k <= kmax; k++) {
            fprintf(f, "%ld", 1L << (2 * k));
            for (int m = 0; m < nm; m++)
                fprintf(f, ",%.6e", rmse[m][k]);
            fprintf(f, "\n");
        }
        rc = chapter_close(&cf, "ch04");
    }
    free(pts);
    free(rmse);
    free(var_measured);
    return rc;
}

/* --- Russian roulette ------------------------------------------------------ */

/* The furnace: a closed room whose walls emit Le = 1 and reflect rho of
 * what arrives, everywhere the same. Its radiance solves L = Le + rho L
 * (the rendering equation of ch. 3 with everything constant):
 * L = Le / (1 - rho) = Le (1 + rho + rho^2 + ...), one term per bounce.
 * A path tracer sums the terms along a random walk; it must stop somewhere.
 *  - Truncation after d bounces: zero variance here, but biased by
 *    -rho^d / (1 - rho).
 *  - Russian roulette: continue with probability q and divide what
 *    follows by q. X = sum_{k=0}^K (rho/q)^k with P(K >= k) = q^k is
 *    unbiased; E[X^2] = ((1 + rho)/(1 - rho)) / (1 - rho^2/q), finite only
 *    for q > rho^2; a path has 1/(1 - q) vertices on average. */
static int roulette_table(const char *dir)
{
    const double rho = 0.8, exact = 1 / (1 - rho);
    static const double qs[] = { 0.99, 0.9, 0.8, 0.7, 0.65, 0.6 };
    static const int depths[] = { 5, 10, 20, 50 };
    chapter_file_t cf;
    FILE *f = chapter_open(&cf, "ch04", dir, "ch04_roulette.csv");
    if (f)
        fprintf(f, "# Russian roulette and truncation on the furnace L = Le "
                   "+ rho L, rho = %g, exact %g; written by "
                   "chapters/ch04/ch04_montecarlo.c\n"
                   "strategy,parameter,mean,bias,variance,variance_exact,"
                   "vertices_per_path,efficiency\n", rho, exact);

    out("\n### Russian roulette against truncation (furnace, rho = %g, exact "
        "L = %g)\n\n", rho, exact);
    out("%ld paths each. Efficiency = 1 / (variance x vertices per path): "
        "higher is better.\n\n", npaths);
    out("| strategy | mean | bias | variance | variance, exact | vertices "
        "per path | efficiency |\n|---|---:|---:|---:|---:|---:|---:|\n");
    for (size_t i = 0; i < sizeof depths / sizeof depths[0]; i++) {
        double v = 0, t = 1;
        for (int k = 0; k < depths[i]; k++, t *= rho)
            v += t;
        out("| truncate after %d | %.6f | %.2e | 0 | 0 | %d | (biased) |\n",
            depths[i], v, v - exact, depths[i]);
        if (f)
            fprintf(f, "truncate,%d,%.9g,%.9g,0,0,%d,\n", depths[i], v,
                    v - exact, depths[i]);
    }
    for (size_t i = 0; i < sizeof qs / sizeof qs[0]; i++) {
        double q = qs[i];
        pcg32_t g;
        pcg32_seed(&g, SEED, 900 + (uint64_t)i);
        estimator_t e;
        estimator_init(&e);
        long vertices = 0;
        for (long p = 0; p < npaths; p++) {
            double x = 0, weight = 1;
            for (;;) {
                x += weight; /* Le = 1 at this vertex */
                vertices++;
                if ((double)pcg32_real(&g) >= q)
                    break; /* absorbed by the roulette */
                weight *= rho / q;
            }
            estimator_add(&e, x);
        }
        double ex2 = (1 + rho) / (1 - rho) / (1 - rho * rho / q);
        double var_exact = q > rho * rho ? ex2 - exact * exact : (double)INFINITY;
        double vpp = (double)vertices / (double)npaths;
        double var = estimator_variance(&e);
        char ve[32];
        if (isinf(var_exact))
            snprintf(ve, sizeof ve, "infinite (q <= rho^2)");
        else
            snprintf(ve, sizeof ve, "%.4f", var_exact);
        out("| roulette, q = %g | %.6f | %+.1e +- %.1e | %.4f | %s | %.3f | "
            "%.4f |\n",
            q, estimator_mean(&e), estimator_mean(&e) - exact,
            estimator_stderr(&e), var, ve, vpp, 1 / (var * vpp));
        if (f)
            fprintf(f, "roulette,%g,%.9g,%.9g,%.9g,%.9g,%.6g,%.6g\n", q,
                    estimator_mean(&e), estimator_mean(&e) - exact, var,
                    var_exact, vpp, 1 / (var * vpp));
    }
    out("\nThe bias column of roulette is the measured mean minus the exact "
        "value, +- one standard error: zero within noise. Below q = rho^2 = "
        "%.2f the variance is infinite: the measured one is then whatever "
        "the rare very long paths made it, and grows with the number of "
        "paths.\n", rho * rho);
    return chapter_close(&cf, "ch04");
}

int main(int argc, char **argv)
{
    double k_opt = KMAX, paths_opt = (double)npaths;
    const chapter_opt_t opts[] = {
        { "--kmax", "K", "the largest N is 4^K", &k_opt, 2, KMAX },
        { "--paths", "N", "paths per Russian roulette row", &paths_opt, 1,
          1e9 },
    };
    const chapter_cli_t cli = {
        "ch04",
        "Chapter 4: Monte Carlo integration by uniform, importance and "
        "stratified\nsampling, error against N, and Russian roulette, as "
        "tables (printed and\nMarkdown) and CSV files (for `make figures`).",
        "out", opts, 2
    };
    const char *dir;
    int rc = chapter_begin(&cli, argc, argv, &dir);
    if (rc >= 0)
        return rc;
    kmax = (int)k_opt;
    npaths = (long)paths_opt;
    chapter_file_t mdf;
    md = chapter_open(&mdf, cli.prog, dir, "ch04_montecarlo.md");
    if (!md)
        return 1;

    out("## Chapter 4: the Monte Carlo method (real = %s, seed %llu)\n",
        REAL_NAME, (unsigned long long)SEED);

    const double n = IRR_N;
    /* Per-sample variances. Uniform: f/p = 2 pi mu^(n+1), mu = cos uniform
     * on [0,1]: (2 pi)^2 (1/(2n+3) - 1/(n+2)^2). Cosine: f/p = pi mu^n with
     * density 2 mu: pi^2 (1/(n+1) - 4/(n+2)^2). Matched: 0. */
    method_t irr[5] = {
        { "uniform", "directions uniform on the hemisphere, p = 1/(2 pi)",
          m_irr_uniform,
          4 * PI_D * PI_D * (1 / (2 * n + 3) - 1 / ((n + 2) * (n + 2))) },
        { "cosine", "importance: p = cos/pi (Malley), matching the cosine "
                    "factor only",
          m_irr_cosine,
          PI_D * PI_D * (1 / (n + 1) - 4 / ((n + 2) * (n + 2))) },
        { "matched", "importance: p = (n+2)/(2 pi) cos^(n+1), proportional "
                     "to the integrand (the Phong lobe sampler)",
          m_irr_matched, 0 },
        { "strat. uniform", "uniform, with the N points of [0,1)^2 jittered "
                            "on a sqrt(N) x sqrt(N) grid",
          m_irr_strat_uniform, -1 },
        { "strat. cosine", "cosine, jittered", m_irr_strat_cosine, -1 },
    };
    char title[128];
    snprintf(title, sizeof title,
             "Irradiance from radiance cos^%d: int_H cos^%d(theta) dw = "
             "2 pi/%d", IRR_N, IRR_N + 1, IRR_N + 2);
    rc = error_table(title, "ch04_irradiance.csv", dir, irr, 5,
                         irr_exact(), 0);

    /* Uniform: pi sin(pi u): pi^2/2 - 4. Triangle: E[(sin/p)^2] - 4 by
     * quadrature below. Stratified: no closed form per sample. */
    double e2 = 0;
    for (int i = 0; i < 100000; i++) { /* midpoint rule for int sin^2/p */
        double x = PI_D * (i + 0.5) / 100000;
        double p = 4 / (PI_D * PI_D) * fmin(x, PI_D - x);
        e2 += sin(x) * sin(x) / p * (PI_D / 100000);
    }
    method_t sine[4] = {
        { "uniform", "x uniform on [0, pi]", m_sine_uniform,
          PI_D * PI_D / 2 - 4 },
        { "importance", "x from the triangle pdf 4/pi^2 min(x, pi - x)",
          m_sine_importance, e2 - 4 },
        { "stratified", "uniform, one sample in each of N equal strata",
          m_sine_strat, -1 },
        { "strat. importance", "triangle pdf, one sample per stratum of u",
          m_sine_strat_importance, -1 },
    };
    rc |= error_table("A 1D integral: int_0^pi sin x dx = 2", "ch04_sine.csv",
                      dir, sine, 4, 2.0, 100000);

    out("\nPlain and importance sampling fall as N^-1/2 (slope -0.5): "
        "importance changes the constant (the variance per sample), not "
        "the rate. Stratification changes the rate: for a smooth integrand "
        "in d dimensions the RMS error of jittered sampling falls as "
        "N^(-1/2 - 1/d), N^-1.5 in 1D and N^-1 in 2D (N^(-1/2 - 1/(2d)) "
        "where the integrand has edges; Mitchell 1996, \"Consequences of "
        "stratified sampling in graphics\"). A pdf proportional to the "
        "integrand has zero variance: every sample returns the exact value "
        "(here up to the rounding of `real`).\n");

    rc |= roulette_table(dir);
    md = NULL;
    rc |= chapter_close(&mdf, cli.prog);
    return rc ? 1 : 0;
}
