/*
 * converge.c - error against a reference, efficiency, bias, and reading a
 * convergence series off its log-log line. See converge.h.
 * Tests: tests/stats/test_converge.c
 */
#include "stats/converge.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/text.h"
#include "io/fileio.h"
#include "stats/imgcompare.h"

/* The means over the R, G, B values where both a and b are finite (the
 * values imgcompare counts) of v and of v / (b^2 + eps). */
static void mean_variance(const image_t *v, const image_t *a,
                          const image_t *b, double out[2])
{
    out[CONVERGE_ABS] = out[CONVERGE_REL] = 0;
    if (!v)
        return;
    double sum = 0, rsum = 0;
    long n = 0;
    for (int y = 0; y < a->height; y++)
        for (int x = 0; x < a->width; x++)
            for (int c = 0; c < 3; c++) {
                double va = (double)image_at(a, x, y)[c];
                double vb = (double)image_at(b, x, y)[c];
                double s2 = (double)image_at(v, x, y)[c];
                if (!isfinite(va) || !isfinite(vb) || !isfinite(s2))
                    continue;
                sum += s2;
                rsum += s2 / (vb * vb + IMGCOMPARE_EPS);
                n++;
            }
    if (n) {
        out[CONVERGE_ABS] = sum / (double)n;
        out[CONVERGE_REL] = rsum / (double)n;
    }
}

static svet_status same_size(const image_t *v, const image_t *a,
                             const char *what, svet_error *err)
{
    if (v && (v->width != a->width || v->height != a->height ||
              v->channels < 3))
        return svet_error_set(err, SVET_ERR_RANGE, "%s is %d x %d, the image "
                              "%d x %d", what, v->width, v->height, a->width,
                              a->height);
    return SVET_OK;
}

svet_status converge_measure(const image_t *img, const image_t *var,
                             const image_t *ref, const image_t *ref_var,
                             converge_point_t *pt, svet_error *err)
{
    imgcompare_t c;
    svet_status st = imgcompare(img, ref, CONVERGE_PSNR_PEAK, IMGCOMPARE_EPS,
                                &c, err);
    if (st == SVET_OK)
        st = same_size(var, img, "the variance image", err);
    if (st == SVET_OK)
        st = same_size(ref_var, img, "the reference's variance image", err);
    if (st != SVET_OK)
        return st;
    pt->rmse = c.rmse;
    pt->psnr = c.psnr;
    pt->mse[CONVERGE_ABS] = c.mse;
    pt->mse[CONVERGE_REL] = c.relmse;
    mean_variance(var, img, ref, pt->variance);
    mean_variance(ref_var, img, ref, pt->ref_variance);
    return SVET_OK;
}

/* the render's own MSE against the exact image */
static double own_mse(const converge_point_t *p, converge_metric m)
{
    return fmax(0.0, p->mse[m] - p->ref_variance[m]);
}

double converge_error(const converge_point_t *p, converge_metric m)
{
    return sqrt(own_mse(p, m));
}

double converge_bias2(const converge_point_t *p, converge_metric m)
{
    return p->mse[m] - p->variance[m] - p->ref_variance[m];
}

double converge_efficiency(const converge_point_t *p, converge_metric m)
{
    double d = p->variance[m] * p->seconds;
    return d > 0 ? 1 / d : 0;
}

double converge_efficiency_mse(const converge_point_t *p, converge_metric m)
{
    double d = own_mse(p, m) * p->seconds;
    return d > 0 ? 1 / d : 0;
}

bool converge_biased(const converge_point_t *p, int n, converge_metric m,
                     double *bias)
{
    if (bias)
        *bias = 0;
    if (n <= 0)
        return false;
    const converge_point_t *last = &p[n - 1];
    double b2 = converge_bias2(last, m);
    if (bias)
        *bias = sqrt(fmax(0.0, b2));
    /* one sample per pixel has no variance estimate (render_variance
     * gives 0): nothing to tell bias from noise by */
    if (last->spp == 1)
        return false;
    return b2 > last->variance[m] + last->ref_variance[m];
}

/* The squared bias the extrapolation keeps: 0 for an unbiased series. */
static double floor2(const converge_point_t *p, int n, converge_metric m)
{
    double b;
    return converge_biased(p, n, m, &b) ? b * b : 0;
}

/* Interpolate y at x between (x0, y0) and (x1, y1), linearly in
 * log y against log x, or linearly where a y is 0. */
static double loglog(double x, double x0, double y0, double x1, double y1)
{
    if (x1 == x0)
        return y1;
    if (y0 > 0 && y1 > 0 && x0 > 0 && x1 > 0 && x > 0) {
        double f = (log(x) - log(x0)) / (log(x1) - log(x0));
        return exp(log(y0) + f * (log(y1) - log(y0)));
    }
    return y0 + (x - x0) * (y1 - y0) / (x1 - x0);
}

double converge_error_at(const converge_point_t *p, int n, converge_metric m,
                         double t, converge_how *how)
{
    converge_how dummy;
    how = how ? how : &dummy;
    if (n <= 0 || !(t > 0)) {
        *how = CONVERGE_UNKNOWN;
        return (double)NAN;
    }
    if (t >= p[0].seconds && t <= p[n - 1].seconds) {
        *how = CONVERGE_MEASURED;
        if (n == 1)
            return converge_error(&p[0], m);
        int i = 0;
        while (i + 1 < n - 1 && p[i + 1].seconds < t)
            i++;
        return loglog(t, p[i].seconds, converge_error(&p[i], m),
                      p[i + 1].seconds, converge_error(&p[i + 1], m));
    }
    /* MSE = b^2 + noise, the noise falling as 1/t (variance ~ 1/N, N ~ t) */
    *how = CONVERGE_EXTRAPOLATED;
    const converge_point_t *e = t > p[n - 1].seconds ? &p[n - 1] : &p[0];
    double b2 = floor2(p, n, m);
    double noise = fmax(0.0, own_mse(e, m) - b2);
    return sqrt(b2 + noise * e->seconds / t);
}

double converge_time_to(const converge_point_t *p, int n, converge_metric m,
                        double e, converge_how *how)
{
    converge_how dummy;
    how = how ? how : &dummy;
    if (n <= 0 || !(e >= 0)) {
        *how = CONVERGE_UNKNOWN;
        return (double)NAN;
    }
    for (int i = 0; i < n; i++) {
        /* e read off this very series (converge_error_at) may come back a
         * rounding above its own point: that point still reaches it */
        double ei = converge_error(&p[i], m);
        if (ei > e * (1 + 1e-12))
            continue;
        if (i > 0) {
            *how = CONVERGE_MEASURED;
            /* e lies between the errors of points i - 1 and i: swap the
             * roles of time and error in the log-log interpolation */
            return loglog(e, converge_error(&p[i - 1], m), p[i - 1].seconds,
                          ei, p[i].seconds);
        }
        break; /* reached at the first point already: extrapolate back */
    }
    double b2 = floor2(p, n, m);
    const converge_point_t *q =
        converge_error(&p[0], m) <= e ? &p[0] : &p[n - 1];
    if (e * e <= b2) {
        *how = CONVERGE_NEVER;
        return (double)INFINITY;
    }
    *how = CONVERGE_EXTRAPOLATED;
    double noise = fmax(0.0, own_mse(q, m) - b2);
    return q->seconds * noise / (e * e - b2);
}

/* --- CSV ----------------------------------------------------------------- */

const char *converge_clock_name(converge_clock c)
{
    return c == CONVERGE_CPU ? "cpu" : "wall";
}

const char *converge_clock_column(converge_clock c)
{
    return c == CONVERGE_CPU ? "cpu_seconds" : "seconds";
}

/* The header after "method,spp,SECONDS," */
static const char *const header_rest =
    "rays,rmse,psnr,"
    "mse,variance,ref_variance,rmse_noref,bias2,efficiency,"
    "relmse,relvariance,ref_relvariance,relrmse_noref,relbias2,relefficiency";

svet_status converge_csv_write(const char *path, const char *method,
                               const char *comment, converge_clock clock,
                               const converge_point_t *p, int n,
                               svet_error *err)
{
    if (!method || !*method || method[0] == '#' ||
        strpbrk(method, ",\"\r\n"))
        return svet_error_set(err, SVET_ERR_RANGE, "%s: method name '%s' "
                              "must be non-empty, without commas, quotes or "
                              "line breaks", path, method ? method : "");
    fileio_t out;
    svet_status st = fileio_begin(&out, path, err);
    if (st != SVET_OK)
        return st;
    FILE *f = out.f;
    for (const char *c = comment; c && *c;) {
        size_t len = strcspn(c, "\n");
        fprintf(f, "# %.*s\n", (int)len, c);
        c += len + (c[len] == '\n');
    }
    fprintf(f, "method,spp,%s,%s\n", converge_clock_column(clock),
            header_rest);
    for (int i = 0; i < n; i++) {
        const converge_point_t *q = &p[i];
        fprintf(f, "%s,%ld,%.9g,%.17g,%.9g,%.9g", method, q->spp, q->seconds,
                q->rays, q->rmse, q->psnr);
        for (int m = CONVERGE_ABS; m <= CONVERGE_REL; m++)
            fprintf(f, ",%.9g,%.9g,%.9g,%.9g,%.9g,%.9g", q->mse[m],
                    q->variance[m], q->ref_variance[m],
                    converge_error(q, (converge_metric)m),
                    converge_bias2(q, (converge_metric)m),
                    converge_efficiency(q, (converge_metric)m));
        fputc('\n', f);
    }
    return fileio_commit(&out, err);
}

/* The columns read back, in the order of `wanted`. */
enum { COL_METHOD, COL_SPP, COL_SECONDS, COL_RAYS, COL_RMSE, COL_PSNR,
       COL_MSE, COL_VARIANCE, COL_REF_VARIANCE, COL_RELMSE, COL_RELVARIANCE,
       COL_REF_RELVARIANCE, NCOLS };
static const char *const wanted[NCOLS] = {
    "method", "spp", "seconds", "rays", "rmse", "psnr", "mse", "variance",
    "ref_variance", "relmse", "relvariance", "ref_relvariance"
};

#define CSV_MAXFIELDS 64

/* Split line (modified in place) at commas; returns the field count, or
 * -1 when there are more than CSV_MAXFIELDS. */
static int split(char *line, char *field[CSV_MAXFIELDS])
{
    int n = 0;
    line[strcspn(line, "\r\n")] = '\0';
    for (char *s = line;;) {
        if (n == CSV_MAXFIELDS)
            return -1;
        field[n++] = s;
        char *comma = strchr(s, ',');
        if (!comma)
            return n;
        *comma = '\0';
        s = comma + 1;
    }
}

static bool parse_double(const char *s, double *out)
{
    char *end;
    errno = 0;
    *out = strtod(s, &end);
    return end != s && *end == '\0';
}

svet_status converge_csv_read(const char *path, char *method,
                              size_t method_len, converge_clock *clock,
                              converge_point_t **p, int *n, svet_error *err)
{
    *p = NULL;
    *n = 0;
    if (method_len)
        method[0] = '\0';
    if (clock)
        *clock = CONVERGE_WALL;
    FILE *f;
    svet_status st = fileio_open_read(path, &f, err);
    if (st != SVET_OK)
        return st;
    char line[4096];
    char *field[CSV_MAXFIELDS];
    int col[NCOLS], lineno = 0, cap = 0;
    bool have_header = false;
    while (fgets(line, sizeof line, f)) {
        lineno++;
        if (lineno == 1) { /* a byte-order mark is no part of the header */
            size_t bom = text_bom_length(line, strlen(line));
            memmove(line, line + bom, strlen(line + bom) + 1);
        }
        if (!strchr(line, '\n') && !feof(f)) {
            st = svet_error_set(err, SVET_ERR_PARSE, "%s:%d: line longer "
                                "than %zu bytes", path, lineno, sizeof line);
            break;
        }
        if (line[0] == '#' || line[strspn(line, " \t\r\n")] == '\0')
            continue;
        int nf = split(line, field);
        if (nf < 0) {
            st = svet_error_set(err, SVET_ERR_PARSE, "%s:%d: more than %d "
                                "columns", path, lineno, CSV_MAXFIELDS);
            break;
        }
        if (!have_header) {
            /* the seconds column names its clock */
            int wall = -1, cpu = -1;
            for (int j = 0; j < nf; j++) {
                if (!strcmp(field[j], converge_clock_column(CONVERGE_WALL)))
                    wall = j;
                if (!strcmp(field[j], converge_clock_column(CONVERGE_CPU)))
                    cpu = j;
            }
            if ((wall >= 0) == (cpu >= 0)) {
                st = svet_error_set(err, SVET_ERR_PARSE, "%s:%d: %s column "
                                    "'seconds' (wall clock) or "
                                    "'cpu_seconds' (CPU clock) in the "
                                    "header", path, lineno,
                                    wall >= 0 ? "both a" : "no");
                break;
            }
            if (clock)
                *clock = cpu >= 0 ? CONVERGE_CPU : CONVERGE_WALL;
            for (int k = 0; k < NCOLS; k++) {
                col[k] = k == COL_SECONDS ? (cpu >= 0 ? cpu : wall) : -1;
                for (int j = 0; j < nf && k != COL_SECONDS; j++)
                    if (strcmp(field[j], wanted[k]) == 0)
                        col[k] = j;
                if (col[k] < 0) {
                    st = svet_error_set(err, SVET_ERR_PARSE, "%s:%d: no "
                                        "column '%s' in the header", path,
                                        lineno, wanted[k]);
                    break;
                }
            }
            if (st != SVET_OK)
                break;
            have_header = true;
            continue;
        }
        if (*n == cap) {
            int ncap = cap ? 2 * cap : 16;
            converge_point_t *np = realloc(*p, (size_t)ncap * sizeof **p);
            if (!np) {
                st = svet_error_set(err, SVET_ERR_NOMEM, "%s: out of memory",
                                    path);
                break;
            }
            *p = np;
            cap = ncap;
        }
        converge_point_t *q = &(*p)[*n];
        memset(q, 0, sizeof *q);
        double v[NCOLS] = { 0 };
        for (int k = COL_SPP; k < NCOLS && st == SVET_OK; k++) {
            if (col[k] < 0)
                continue;
            if (col[k] >= nf || !parse_double(field[col[k]], &v[k]))
                st = svet_error_set(err, SVET_ERR_PARSE, "%s:%d: column '%s':"
                                    " expected a number, got '%s'", path,
                                    lineno, wanted[k],
                                    col[k] < nf ? field[col[k]] : "");
        }
        if (st == SVET_OK && (col[COL_METHOD] >= nf ||
                              !(v[COL_SPP] >= 0 && v[COL_SPP] < 1e18)))
            st = svet_error_set(err, SVET_ERR_PARSE, "%s:%d: a row needs a "
                                "method and spp >= 0", path, lineno);
        if (st != SVET_OK)
            break;
        if (*n == 0 && method_len)
            snprintf(method, method_len, "%s", field[col[COL_METHOD]]);
        q->spp = (long)v[COL_SPP];
        q->seconds = v[COL_SECONDS];
        q->rays = v[COL_RAYS];
        q->rmse = v[COL_RMSE];
        q->psnr = v[COL_PSNR];
        q->mse[CONVERGE_ABS] = v[COL_MSE];
        q->variance[CONVERGE_ABS] = v[COL_VARIANCE];
        q->ref_variance[CONVERGE_ABS] = v[COL_REF_VARIANCE];
        q->mse[CONVERGE_REL] = v[COL_RELMSE];
        q->variance[CONVERGE_REL] = v[COL_RELVARIANCE];
        q->ref_variance[CONVERGE_REL] = v[COL_REF_RELVARIANCE];
        (*n)++;
    }
    if (st == SVET_OK && ferror(f))
        st = svet_error_set(err, SVET_ERR_IO, "%s: read error", path);
    if (st == SVET_OK && !have_header)
        st = svet_error_set(err, SVET_ERR_PARSE, "%s: no header row", path);
    fclose(f);
    if (st != SVET_OK) {
        free(*p);
        *p = NULL;
        *n = 0;
    }
    return st;
}
