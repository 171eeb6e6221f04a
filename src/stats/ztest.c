/*
 * ztest.c - the Z-test of a render against a reference, per pixel and on
 * blocks of pixels, with Sidak's correction. See ztest.h.
 * Tests: tests/stats/test_ztest.c, tests/render/test_reference.c
 */
#include "stats/ztest.h"

#include <stdlib.h>
#include <string.h>

void ztest_params_default(ztest_params_t *p)
{
    p->alpha = ZTEST_ALPHA;
    p->min_pass = ZTEST_MIN_PASS;
    p->block_factor = ZTEST_BLOCK_FACTOR;
    p->round_rel = ZTEST_ROUND_REL;
}

double ztest_pvalue(double z)
{
    /* P(|Z| >= |z|) = 2 (1 - Phi(|z|)) = erfc(|z| / sqrt(2)); erfc keeps
     * the tail's relative accuracy where 1 - Phi would cancel to 0 */
    return erfc(fabs(z) / sqrt(2.0));
}

double ztest_sidak(double alpha, double n)
{
    /* 1 - (1 - alpha)^(1/n) = -expm1(log1p(-alpha) / n): for n = 10^5 the
     * direct form loses half its digits */
    return -expm1(log1p(-alpha) / n);
}

/* The pixel-level values of both sides: means and effective variances of
 * the mean, in double, 3 per pixel. */
typedef struct {
    double *ma, *va, *mb, *vb;
} values_t;

static double var_at(const image_t *v, int x, int y, int c)
{
    return v ? (double)image_at(v, x, y)[c] : 0.0;
}

static svet_status check_inputs(const ztest_image_t *a, const ztest_image_t *b,
                                const ztest_params_t *p, svet_error *err)
{
    const image_t *ma = a->mean, *mb = b->mean;
    if (!ma || !mb || ma->channels < 3 || mb->channels < 3)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "z-test: both images need R, G, B");
    if (ma->width != mb->width || ma->height != mb->height)
        return svet_error_set(err, SVET_ERR_RANGE, "z-test: images differ in "
                              "size: %d x %d against %d x %d", ma->width,
                              ma->height, mb->width, mb->height);
    const image_t *vs[2] = { a->var, b->var };
    for (int i = 0; i < 2; i++)
        if (vs[i] && (vs[i]->width != ma->width ||
                      vs[i]->height != ma->height || vs[i]->channels < 3))
            return svet_error_set(err, SVET_ERR_RANGE, "z-test: the variance "
                                  "image of side %c is %d x %d, not %d x %d",
                                  "ab"[i], vs[i]->width, vs[i]->height,
                                  ma->width, ma->height);
    if (!(p->alpha > 0 && p->alpha < 1) || !(p->min_pass >= 0 &&
        p->min_pass <= 1) || p->block_factor < 1 ||
        !(p->round_rel >= 0))
        return svet_error_set(err, SVET_ERR_RANGE, "z-test: parameters out "
                              "of range (alpha in (0,1), min_pass in [0,1], "
                              "block_factor >= 1, round_rel >= 0)");
    if (!(a->spp >= 0) || !(b->spp >= 0))
        return svet_error_set(err, SVET_ERR_RANGE, "z-test: negative spp");
    return SVET_OK;
}

static void load_values(const ztest_image_t *a, const ztest_image_t *b,
                        values_t *v)
{
    const int W = a->mean->width, H = a->mean->height;
    const bool floor = a->spp > 0 && b->spp > 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            for (int c = 0; c < 3; c++) {
                size_t i = 3 * ((size_t)y * (size_t)W + (size_t)x) + (size_t)c;
                v->ma[i] = (double)image_at(a->mean, x, y)[c];
                v->mb[i] = (double)image_at(b->mean, x, y)[c];
                double va = var_at(a->var, x, y, c);
                double vb = var_at(b->var, x, y, c);
                if (floor) {
                    /* per-sample variance s^2 = var x spp, of the other
                     * side, over this side's spp */
                    double va_from_b = vb * b->spp / a->spp;
                    double vb_from_a = va * a->spp / b->spp;
                    va = fmax(va, va_from_b);
                    vb = fmax(vb, vb_from_a);
                }
                v->va[i] = va;
                v->vb[i] = vb;
            }
}

/* The block sides of the levels: 1, f, f^2, ... until one block covers the
 * image. Returns the number of levels. */
static int level_sides(int W, int H, int f, int side[ZTEST_MAX_LEVELS])
{
    int n = 0, s = 1, big = W > H ? W : H;
    side[n++] = 1;
    if (f < 2)
        return n;
    while (s < big && n < ZTEST_MAX_LEVELS) {
        s = s > big / f ? big : s * f;
        side[n++] = s;
    }
    return n;
}

/* Test one value: returns its p-value and sets *z. */
static double test_value(double ma, double va, double mb, double vb,
                         double round_rel, double *z)
{
    if (!isfinite(ma) || !isfinite(mb) || !isfinite(va) || !isfinite(vb) ||
        va < 0 || vb < 0) {
        *z = (double)NAN;
        return 0;
    }
    /* the difference beyond rounding, with its sign */
    double d = ma - mb;
    double excess =
        fmax(0.0, fabs(d) - round_rel * fmax(fabs(ma), fabs(mb)));
    double s2 = va + vb;
    if (excess == 0) {
        *z = 0;
        return 1;
    }
    if (s2 == 0) {
        /* nothing random on either side, and more than rounding apart */
        *z = d > 0 ? (double)INFINITY : -(double)INFINITY;
        return 0;
    }
    *z = copysign(excess, d) / sqrt(s2);
    return ztest_pvalue(*z);
}

static void run_level(const values_t *v, int W, int H, int side,
                      double threshold, const ztest_params_t *p,
                      ztest_level_t *L, image_t *pvalue)
{
    memset(L, 0, sizeof *L);
    L->block = side;
    L->cols = (W + side - 1) / side;
    L->rows = (H + side - 1) / side;
    L->min_p = 2;
    for (int by = 0; by < L->rows; by++)
        for (int bx = 0; bx < L->cols; bx++) {
            int x0 = bx * side, y0 = by * side;
            int x1 = x0 + side < W ? x0 + side : W;
            int y1 = y0 + side < H ? y0 + side : H;
            double k = (double)(x1 - x0) * (double)(y1 - y0);
            bool cell_ok = true;
            for (int c = 0; c < 3; c++) {
                /* the mean of k independent pixel means: sum / k, its
                 * variance sum of variances / k^2 */
                double ma = 0, va = 0, mb = 0, vb = 0;
                for (int y = y0; y < y1; y++)
                    for (int x = x0; x < x1; x++) {
                        size_t i = 3 * ((size_t)y * (size_t)W + (size_t)x) +
                                   (size_t)c;
                        ma += v->ma[i];
                        va += v->va[i];
                        mb += v->mb[i];
                        vb += v->vb[i];
                    }
                ma /= k;
                mb /= k;
                va /= k * k;
                vb /= k * k;
                if (va + vb == 0 && (va != 0 || vb != 0))
                    va = vb = 0; /* underflow of tiny variances */
                double z, pv = test_value(ma, va, mb, vb, p->round_rel, &z);
                if (va == 0 && vb == 0)
                    L->zero_var++;
                if (pv < L->min_p) {
                    L->min_p = pv;
                    L->worst_z = z;
                    L->worst_x = bx;
                    L->worst_y = by;
                    L->worst_c = c;
                }
                if (!(pv > threshold))
                    cell_ok = false;
                if (pvalue)
                    image_at(pvalue, bx, by)[c] = (float)pv;
            }
            L->cells++;
            if (!cell_ok)
                L->failed++;
        }
    L->pass = (double)(L->cells - L->failed) >= p->min_pass * (double)L->cells;
}

svet_status ztest_run(const ztest_image_t *a, const ztest_image_t *b,
                      const ztest_params_t *p, ztest_result_t *res,
                      image_t *pvalue, svet_error *err)
{
    memset(res, 0, sizeof *res);
    if (pvalue)
        memset(pvalue, 0, sizeof *pvalue);
    svet_status st = check_inputs(a, b, p, err);
    if (st != SVET_OK)
        return st;
    const int W = a->mean->width, H = a->mean->height;
    size_t n = 3 * (size_t)W * (size_t)H;
    values_t v;
    v.ma = malloc(4 * n * sizeof(double));
    if (!v.ma)
        return svet_error_set(err, SVET_ERR_NOMEM, "z-test: out of memory");
    v.va = v.ma + n;
    v.mb = v.ma + 2 * n;
    v.vb = v.ma + 3 * n;
    if (pvalue && (st = image_alloc(pvalue, W, H, 3, err)) != SVET_OK) {
        free(v.ma);
        return st;
    }
    load_values(a, b, &v);

    int side[ZTEST_MAX_LEVELS];
    res->nlevels = level_sides(W, H, p->block_factor, side);
    /* Sidak over every value of every level. The levels are not
     * independent (a block holds the pixels below it), but for two-sided
     * tests of jointly normal z's Sidak's inequality holds whatever their
     * correlations (Sidak 1967), so a correct render fails with
     * probability at most alpha. */
    for (int l = 0; l < res->nlevels; l++)
        res->values += 3L * ((W + side[l] - 1) / side[l]) *
                       ((H + side[l] - 1) / side[l]);
    res->threshold = ztest_sidak(p->alpha, (double)res->values);
    res->pass = true;
    for (int l = 0; l < res->nlevels; l++) {
        run_level(&v, W, H, side[l], res->threshold, p, &res->level[l],
                  l == 0 ? pvalue : NULL);
        res->pass = res->pass && res->level[l].pass;
    }
    free(v.ma);
    return SVET_OK;
}
