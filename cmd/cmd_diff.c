/*
 * diff.c - `svet diff A B`: how far image A is from the reference B
 * (imgcompare.h), for any two of EXR, PFM, PNG and PPM files of one size,
 * with an optional error image. The numbers are printed one per line,
 * "name value", so that scripts can grep them; lines about the inputs
 * start with '#'.
 * Tests: tests/cmd/test_svet.c
 */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmd.h"
#include "cmdutil.h"
#include "io/imageio.h"
#include "stats/imgcompare.h"

void cmd_diff_help(FILE *f)
{
    fprintf(f,
"usage: svet diff A B [options]\n"
"\n"
"Compare image A with the reference B, over R, G and B (alpha is not\n"
"compared). Both files are told apart by their contents, and may be EXR,\n"
"PFM, PNG or PPM, of the same width and height. Two display images (PNG,\n"
"PPM) are compared as codes in [0, 1]; a display image compared with a\n"
"linear one (EXR, PFM) is first decoded with the sRGB curve.\n"
"\n"
"Prints, one per line (name, then value):\n"
"  mse     mean of (a - b)^2\n"
"  rmse    its square root\n"
"  relmse  mean of (a - b)^2 / (b^2 + eps), eps 0.01 (pbrt-v4's MRSE\n"
"          divides by (b + 0.01)^2 instead)\n"
"  mae     mean of |a - b|\n"
"  psnr    10 log10(peak^2 / mse) in dB; inf for identical images\n"
"  max     the largest |a - b|, with its pixel and channel\n"
"Pairs with a NaN or Inf on either side are skipped and counted.\n"
"\n"
"options:\n"
"  --metric LIST        the metrics to print, comma-separated (default:\n"
"                       all, in the order above)\n"
"  --error-image FILE   write the per-pixel error (.exr or .pfm)\n"
"  --error KIND         abs (default), rel (|a-b| / sqrt(b^2 + eps)) or\n"
"                       squared\n"
"  --peak P             the peak of PSNR (default: 1 for two display\n"
"                       images, else the largest value of B)\n"
"  --eps E              the epsilon of relmse (default 0.01)\n"
"  --fail-above X       exit with 5 if the first metric listed exceeds X\n"
"                       (for psnr: falls below X)\n"
"  --max-pixels N       read images of up to N pixels (default 67108864,\n"
"                       8192 x 8192, or the environment's SVET_MAX_PIXELS);\n"
"                       a larger one is refused before it is allocated\n"
"  -h, --help           this text\n"
"\n"
"exit codes: 0 compared (and within --fail-above); 1 bad command line;\n"
"2 an image cannot be read, or the sizes differ; 3 the error image cannot\n"
"be written; 5 the first metric is beyond --fail-above.\n");
}

enum { M_MSE, M_RMSE, M_RELMSE, M_MAE, M_PSNR, M_MAX, M_COUNT };
_Static_assert(M_COUNT == sizeof ((cmd_diff_args_t *)0)->metrics /
                              sizeof(int), "cmd.h holds every metric");
static const char *const metric_names[M_COUNT] = { "mse",  "rmse", "relmse",
                                                   "mae",  "psnr", "max" };

/* Parse "rmse,psnr" into a list of metric indices; false on a bad name. */
static bool parse_metrics(const char *list, int *out, int *n)
{
    char buf[256];
    snprintf(buf, sizeof buf, "%s", list);
    *n = 0;
    for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
        int k = -1;
        for (int i = 0; i < M_COUNT; i++)
            if (strcmp(tok, metric_names[i]) == 0)
                k = i;
        if (k < 0 || *n == M_COUNT) {
            fprintf(stderr, "svet diff: unknown metric '%s' (mse, rmse, "
                            "relmse, mae, psnr, max)\n", tok);
            return false;
        }
        out[(*n)++] = k;
    }
    return *n > 0;
}

static double metric_value(const imgcompare_t *m, int k)
{
    switch (k) {
    case M_MSE: return m->mse;
    case M_RMSE: return m->rmse;
    case M_RELMSE: return m->relmse;
    case M_MAE: return m->mae;
    case M_PSNR: return m->psnr;
    default: return m->max_abs;
    }
}

static const char *format_name(imageio_format_t f)
{
    switch (f) {
    case IMAGEIO_EXR: return "EXR";
    case IMAGEIO_PFM: return "PFM";
    case IMAGEIO_PNG: return "PNG";
    case IMAGEIO_PPM: return "PPM";
    case IMAGEIO_UNKNOWN: break;
    }
    return "?";
}

static int read_input(const char *path, image_t *img, imageio_format_t *f,
                      const image_read_limits_t *lim)
{
    svet_error err;
    svet_error_clear(&err);
    if (imageio_read_with(path, img, false, f, lim, &err) != SVET_OK) {
        fprintf(stderr, "svet diff: %s\n", err.msg);
        return SVET_EXIT_INPUT;
    }
    return SVET_EXIT_OK;
}

static int opt_metric(void *args, const char *cmd, const char *opt,
                      const char *v)
{
    (void)cmd, (void)opt;
    cmd_diff_args_t *o = args;
    return parse_metrics(v, o->metrics, &o->nmetrics) ? SVET_EXIT_OK
                                                       : SVET_EXIT_USAGE;
}

static int opt_error_image(void *args, const char *cmd, const char *opt,
                           const char *v)
{
    (void)cmd, (void)opt;
    imageio_format_t f = imageio_format_from_name(v);
    if (f != IMAGEIO_EXR && f != IMAGEIO_PFM) {
        fprintf(stderr, "svet diff: the error image is linear: name it .exr "
                        "or .pfm, not '%s'\n", v);
        return SVET_EXIT_USAGE;
    }
    ((cmd_diff_args_t *)args)->err_path = v;
    return SVET_EXIT_OK;
}

static int opt_error(void *args, const char *cmd, const char *opt,
                     const char *v)
{
    (void)cmd, (void)opt;
    cmd_diff_args_t *o = args;
    if (!strcmp(v, "abs"))
        o->kind = IMGCOMPARE_ABS;
    else if (!strcmp(v, "rel"))
        o->kind = IMGCOMPARE_REL;
    else if (!strcmp(v, "squared"))
        o->kind = IMGCOMPARE_SQUARED;
    else {
        fprintf(stderr, "svet diff: --error %s: abs, rel or squared\n", v);
        return SVET_EXIT_USAGE;
    }
    return SVET_EXIT_OK;
}

/* --peak and --eps: a positive number */
static int opt_positive(void *args, const char *cmd, const char *opt,
                        const char *v)
{
    (void)cmd;
    cmd_diff_args_t *o = args;
    bool peak = !strcmp(opt, "--peak");
    double *x = peak ? &o->peak : &o->eps;
    if (!cmd_parse_double(v, x) || *x <= 0) {
        fprintf(stderr, "svet diff: %s %s: a positive number\n", opt, v);
        return SVET_EXIT_USAGE;
    }
    if (peak)
        o->have_peak = true;
    return SVET_EXIT_OK;
}

static int opt_fail_above(void *args, const char *cmd, const char *opt,
                          const char *v)
{
    (void)cmd, (void)opt;
    cmd_diff_args_t *o = args;
    if (!cmd_parse_double(v, &o->fail_above)) {
        fprintf(stderr, "svet diff: --fail-above %s: a number\n", v);
        return SVET_EXIT_USAGE;
    }
    o->have_fail = true;
    return SVET_EXIT_OK;
}

/* A or B; "-" too, a file of that name */
static int image_arg(void *args, const char *cmd, const char *a)
{
    (void)cmd;
    cmd_diff_args_t *o = args;
    if (o->paths[1]) {
        fprintf(stderr, "svet diff: one image too many: '%s' (svet diff "
                        "--help)\n", a);
        return SVET_EXIT_USAGE;
    }
    o->paths[o->paths[0] ? 1 : 0] = a;
    return SVET_EXIT_OK;
}

static const cmd_option_t options[] = {
    { "--metric", NULL, true, CMD_CALL, 0, opt_metric },
    { "--error-image", NULL, true, CMD_CALL, 0, opt_error_image },
    { "--error", NULL, true, CMD_CALL, 0, opt_error },
    { "--peak", NULL, true, CMD_CALL, 0, opt_positive },
    { "--eps", NULL, true, CMD_CALL, 0, opt_positive },
    { "--max-pixels", NULL, true, CMD_SET_TEXT,
      offsetof(cmd_diff_args_t, max_pixels), NULL },
    { "--fail-above", NULL, true, CMD_CALL, 0, opt_fail_above },
    { NULL, NULL, false, CMD_SET_TRUE, 0, NULL }
};

int cmd_diff_parse(int argc, char **argv, cmd_diff_args_t *o)
{
    memset(o, 0, sizeof *o);
    for (int k = 0; k < M_COUNT; k++)
        o->metrics[k] = k; /* every metric, in the order of metric_names */
    o->nmetrics = M_COUNT;
    o->kind = IMGCOMPARE_ABS;
    o->eps = IMGCOMPARE_EPS;
    const cmd_parser_t p = { "diff", options, o, image_arg, cmd_diff_help,
                             NULL, true, NULL };
    int rc = cmd_parse_options(&p, argc, argv);
    if (rc != CMD_RUN)
        return rc;
    if (!o->paths[1]) {
        fprintf(stderr, "svet diff: two images are needed: svet diff A B "
                        "(svet diff --help)\n");
        return SVET_EXIT_USAGE;
    }
    return CMD_RUN;
}

int cmd_diff(int argc, char **argv)
{
    cmd_diff_args_t o;
    int rc = cmd_diff_parse(argc, argv, &o);
    if (rc != CMD_RUN)
        return rc;
    const char *const *paths = o.paths, *err_path = o.err_path;
    const int *metrics = o.metrics, nmetrics = o.nmetrics;
    double peak = o.peak;
    const cmd_file_t outs[] = { { err_path, "the error image" } };
    const cmd_file_t ins[] = { { paths[0], "the image A" },
                               { paths[1], "the reference B" } };
    rc = cmd_check_outputs("diff", outs, 1, ins, 2);
    if (rc != SVET_EXIT_OK)
        return rc;

    image_read_limits_t lim;
    rc = cmd_read_limits("diff", o.max_pixels, &lim);
    if (rc != SVET_EXIT_OK)
        return rc;
    image_t img[2] = { { 0 }, { 0 } };
    imageio_format_t fmt[2];
    for (int k = 0; k < 2 && rc == SVET_EXIT_OK; k++)
        rc = read_input(paths[k], &img[k], &fmt[k], &lim);
    bool display[2] = { imageio_is_display(fmt[0]),
                        imageio_is_display(fmt[1]) };
    if (rc == SVET_EXIT_OK && display[0] != display[1])
        imageio_decode_srgb(display[0] ? &img[0] : &img[1]);
    if (rc == SVET_EXIT_OK && (img[0].width != img[1].width ||
                               img[0].height != img[1].height)) {
        fprintf(stderr, "svet diff: %s is %d x %d, %s is %d x %d: the sizes "
                        "differ\n", paths[0], img[0].width, img[0].height,
                paths[1], img[1].width, img[1].height);
        rc = SVET_EXIT_INPUT;
    }
    imgcompare_t m;
    svet_error err;
    svet_error_clear(&err);
    if (rc == SVET_EXIT_OK) {
        if (!o.have_peak && display[0] && display[1])
            peak = 1;
        if (imgcompare(&img[0], &img[1], peak, o.eps, &m, &err) != SVET_OK) {
            fprintf(stderr, "svet diff: %s\n", err.msg);
            rc = SVET_EXIT_INPUT;
        }
    }
    if (rc == SVET_EXIT_OK) {
        for (int k = 0; k < 2; k++)
            printf("# %s: %s (%s, %d x %d%s)\n", k ? "B" : "A", paths[k],
                   format_name(fmt[k]), img[k].width, img[k].height,
                   display[k] && display[0] != display[1]
                       ? ", display codes decoded with sRGB"
                       : "");
        printf("# compared %llu values (R, G, B); %llu NaN/Inf pairs "
               "skipped; psnr peak %g; relmse eps %g\n",
               (unsigned long long)m.n, (unsigned long long)m.nonfinite,
               m.peak, m.eps);
        for (int i = 0; i < nmetrics; i++) {
            int k = metrics[i];
            if (k == M_MAX)
                printf("max %.9g at %d %d %c\n", m.max_abs, m.max_x, m.max_y,
                       "RGB"[m.max_c]);
            else
                printf("%s %.9g\n", metric_names[k], metric_value(&m, k));
        }
        fflush(stdout);
    }
    if (rc == SVET_EXIT_OK && err_path) {
        image_t e;
        if (imgcompare_error_image(&img[0], &img[1], o.kind, o.eps, &e,
                                   &err) !=
                SVET_OK ||
            imageio_write(err_path, &e, &err) != SVET_OK) {
            fprintf(stderr, "svet diff: %s\n", err.msg);
            rc = SVET_EXIT_OUTPUT;
        }
        image_free(&e);
    }
    if (rc == SVET_EXIT_OK && o.have_fail) {
        double v = metric_value(&m, metrics[0]);
        bool bad = metrics[0] == M_PSNR ? v < o.fail_above
                                         : v > o.fail_above;
        if (bad) {
            fprintf(stderr, "svet diff: %s %.9g is beyond --fail-above %g\n",
                    metric_names[metrics[0]], v, o.fail_above);
            rc = SVET_EXIT_DIFFERENT;
        }
    }
    image_free(&img[0]);
    image_free(&img[1]);
    return rc;
}
