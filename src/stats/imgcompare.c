/*
 * imgcompare.c - error measures between an image and a reference, and the
 * error image. See imgcompare.h. Tests: tests/stats/test_imgcompare.c
 */
#include "stats/imgcompare.h"

#include <string.h>

static svet_status check_pair(const image_t *a, const image_t *b, double eps,
                              svet_error *err)
{
    if (a->width != b->width || a->height != b->height)
        return svet_error_set(err, SVET_ERR_RANGE, "images differ in size: "
                              "%d x %d against a %d x %d reference",
                              a->width, a->height, b->width, b->height);
    if (!(eps > 0) || !isfinite(eps))
        return svet_error_set(err, SVET_ERR_RANGE, "relative error epsilon "
                              "%g: must be a positive number", eps);
    return SVET_OK;
}

svet_status imgcompare(const image_t *a, const image_t *b, double peak,
                       double eps, imgcompare_t *out, svet_error *err)
{
    memset(out, 0, sizeof *out);
    svet_status st = check_pair(a, b, eps, err);
    if (st != SVET_OK)
        return st;
    double se = 0, rse = 0, ae = 0, bmax = 0;
    for (int y = 0; y < a->height; y++)
        for (int x = 0; x < a->width; x++) {
            const float *pa = image_at(a, x, y), *pb = image_at(b, x, y);
            for (int c = 0; c < 3; c++) {
                double va = (double)pa[c], vb = (double)pb[c];
                if (!isfinite(va) || !isfinite(vb)) {
                    out->nonfinite++;
                    continue;
                }
                double d = va - vb, ad = fabs(d);
                se += d * d;
                rse += d * d / (vb * vb + eps);
                ae += ad;
                bmax = fmax(bmax, vb);
                if (ad > out->max_abs || out->n == 0) {
                    out->max_abs = ad;
                    out->max_x = x;
                    out->max_y = y;
                    out->max_c = c;
                }
                out->n++;
            }
        }
    out->eps = eps;
    out->peak = peak > 0 ? peak : bmax > 0 ? bmax : 1;
    if (out->n > 0) {
        double n = (double)out->n;
        out->mse = se / n;
        out->relmse = rse / n;
        out->mae = ae / n;
    }
    out->rmse = sqrt(out->mse);
    out->psnr = out->mse > 0 ? 10 * log10(out->peak * out->peak / out->mse)
                             : (double)INFINITY;
    return SVET_OK;
}

svet_status imgcompare_error_image(const image_t *a, const image_t *b,
                                   imgcompare_kind_t kind, double eps,
                                   image_t *out, svet_error *err)
{
    memset(out, 0, sizeof *out);
    svet_status st = check_pair(a, b, eps, err);
    if (st == SVET_OK)
        st = image_alloc(out, a->width, a->height, 3, err);
    if (st != SVET_OK)
        return st;
    for (int y = 0; y < a->height; y++)
        for (int x = 0; x < a->width; x++) {
            const float *pa = image_at(a, x, y), *pb = image_at(b, x, y);
            float *o = image_at(out, x, y);
            for (int c = 0; c < 3; c++) {
                double va = (double)pa[c], vb = (double)pb[c];
                double d = va - vb, e;
                if (!isfinite(va) || !isfinite(vb))
                    e = (double)NAN;
                else if (kind == IMGCOMPARE_REL)
                    e = fabs(d) / sqrt(vb * vb + eps);
                else if (kind == IMGCOMPARE_SQUARED)
                    e = d * d;
                else
                    e = fabs(d);
                o[c] = (float)e;
            }
        }
    return SVET_OK;
}
