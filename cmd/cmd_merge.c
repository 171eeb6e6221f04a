/*
 * cmd_merge.c - `svet merge PART.exr ... -o OUT.exr`: the parts of a render
 * split by sample ranges (--samples) or by pixels (--crop) made into the
 * image one render makes. Each part's FILE.exr.part holds its per-pixel
 * sums, sums of squares and counts, the sums exact integers (image.h:
 * image_fixed_t), so their total is the one-pass sum bit for bit in any
 * order.
 * Tests: tests/cmd/test_merge.sh
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmd.h"
#include "io/fileio.h"
#include "render/animation.h"

svet_status cmd_part_identity(const char *scene_path, const scene_t *s,
                              const cmd_scene_opts_t *so,
                              unsigned long long *id, svet_error *err)
{
    /* FNV-1a over the scene file's bytes, then each file it names (a
     * mesh, a texture, a grid: an edit between two parts is refused),
     * then the seed, the size and the overrides */
    unsigned long long h = 1469598103934665603ULL; /* FNV-1a offset basis */
    for (int i = -1; i < s->nfiles; i++) {
        FILE *f;
        svet_status st =
            fileio_open_read(i < 0 ? scene_path : s->files[i], &f, err);
        if (st != SVET_OK)
            return st;
        int c;
        while ((c = getc(f)) != EOF)
            h = (h ^ (unsigned char)c) * 1099511628211ULL;
        fclose(f);
        h = (h ^ (unsigned char)'|') * 1099511628211ULL;
    }
    char buf[128];
    snprintf(buf, sizeof buf, "|seed %llu|size %d %d",
             (unsigned long long)s->render.seed, s->camera.width,
             s->camera.height);
    /* a frame of an animation (animation.h): its number too */
    if (animation_frame(s) >= 0)
        snprintf(buf + strlen(buf), sizeof buf - strlen(buf), "|frame %d",
                 animation_frame(s));
    for (const char *p = buf; *p; p++)
        h = (h ^ (unsigned char)*p) * 1099511628211ULL;
    for (int i = 0; i < so->nsets; i++)
        for (const char *p = so->sets[i]; ; p++) {
            h = (h ^ (unsigned char)*p) * 1099511628211ULL;
            if (!*p)
                break;
        }
    *id = h;
    return SVET_OK;
}

void cmd_merge_help(FILE *f)
{
    fprintf(f,
"usage: svet merge PART.exr ... -o OUT.exr [--variance VAR.exr] [--png P]\n"
"\n"
"Merge the parts of a split render (svet render --samples FROM:TO or\n"
"--crop X0:X1,Y0:Y1, each with its PART.exr.part) into OUT.exr, its PNG\n"
"and its variance, with OUT.exr.part (the samples FROM:TO of every pixel,\n"
"so that merged images merge again). Refuses parts of different scenes,\n"
"seeds, settings or sizes and overlapping sample ranges, and says which\n"
"samples or pixels are missing. OUT.exr holds half floats when the parts\n"
"were rendered with --half, else floats; half and float parts together\n"
"are refused. Exit 1: bad command line or parts that do not fit together;\n"
"2: a part is missing or malformed; 3: an output could not be written.\n");
}

void cmd_fixed_write(FILE *f, const image_fixed_t *v)
{
    image_fixed_t t = *v;
    if (t.w[2] >> 63) { /* negative: print "-" and the magnitude, ~t + 1 */
        for (int k = 0; k < 3; k++)
            t.w[k] = ~t.w[k];
        const image_fixed_t one = { { 1, 0, 0 } };
        image_fixed_add(&t, &one);
        putc('-', f);
    }
    if (t.w[2])
        fprintf(f, "%llx%016llx%016llx", (unsigned long long)t.w[2],
                (unsigned long long)t.w[1], (unsigned long long)t.w[0]);
    else if (t.w[1])
        fprintf(f, "%llx%016llx", (unsigned long long)t.w[1],
                (unsigned long long)t.w[0]);
    else
        fprintf(f, "%llx", (unsigned long long)t.w[0]);
}

bool cmd_fixed_parse(const char *s, image_fixed_t *v)
{
    const bool negative = *s == '-';
    s += negative;
    size_t n = strlen(s);
    if (n == 0 || n > 48)
        return false;
    image_fixed_t t = { { 0, 0, 0 } };
    for (; *s; s++) {
        int d = *s >= '0' && *s <= '9' ? *s - '0'
              : *s >= 'a' && *s <= 'f' ? *s - 'a' + 10 : -1;
        if (d < 0)
            return false;
        t.w[2] = t.w[2] << 4 | t.w[1] >> 60;
        t.w[1] = t.w[1] << 4 | t.w[0] >> 60;
        t.w[0] = t.w[0] << 4 | (uint64_t)d;
    }
    if (t.w[2] >> 63)
        return false; /* beyond the 191 bits of magnitude */
    if (negative) {
        for (int k = 0; k < 3; k++)
            t.w[k] = ~t.w[k];
        const image_fixed_t one = { { 1, 0, 0 } };
        image_fixed_add(&t, &one);
    }
    *v = t;
    return true;
}

int cmd_part_read(const char *exr, cmd_part_file_t *q)
{
    char path[4096];
    snprintf(path, sizeof path, "%s.part", exr);
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "svet merge: %s: cannot open (made by svet render "
                        "--samples or --crop?)\n", path);
        return SVET_EXIT_INPUT;
    }
    cmd_part_t *p = &q->p;
    int ver = 0;
    if (fscanf(f, "svet-part %d identity %llx size %d %d samples %ld %ld "
                  "crop %d %d %d %d tonemap %d %la %la %la %la %d %la",
               &ver, &p->identity, &p->width, &p->height, &p->from, &p->to,
               &p->x0, &p->x1, &p->y0, &p->y1, &q->tm_op, &q->tm[0],
               &q->tm[1], &q->tm[2], &q->tm[3], &q->tm_curve,
               &q->tm[4]) != 17 || (ver != 2 && ver != 3) || p->width <= 0 ||
        p->height <= 0 || p->x0 < 0 || p->x1 > p->width || p->x0 >= p->x1 ||
        p->y0 < 0 || p->y1 > p->height || p->y0 >= p->y1 || p->from < 0 ||
        p->to <= p->from) {
        fprintf(stderr, "svet merge: %s: not a part file\n", path);
        fclose(f);
        return SVET_EXIT_INPUT;
    }
    /* version 3 names the EXR's pixel type; version 2 wrote float only */
    char px[8] = "float";
    if (ver == 3 && (fscanf(f, " exr %7s", px) != 1 ||
                     (strcmp(px, "half") && strcmp(px, "float")))) {
        fprintf(stderr, "svet merge: %s: not a part file (no 'exr half' or "
                        "'exr float' line)\n", path);
        fclose(f);
        return SVET_EXIT_INPUT;
    }
    q->half = !strcmp(px, "half");
    size_t n = (size_t)(p->x1 - p->x0) * (size_t)(p->y1 - p->y0);
    q->v = malloc(n * sizeof *q->v);
    if (!q->v) {
        fprintf(stderr, "svet merge: %s: out of memory\n", path);
        fclose(f);
        return SVET_EXIT_OUTPUT;
    }
    for (size_t i = 0; i < n; i++) {
        unsigned long long c, nf;
        cmd_part_pixel_t *v = q->v + i;
        char w[6][64];
        if (fscanf(f, "%63s %63s %63s %63s %63s %63s %llu %llu", w[0], w[1],
                   w[2], w[3], w[4], w[5], &c, &nf) != 8) {
            fprintf(stderr, "svet merge: %s: truncated at pixel %zu\n", path,
                    i);
            fclose(f);
            return SVET_EXIT_INPUT;
        }
        for (int k = 0; k < 6; k++)
            if (!cmd_fixed_parse(w[k], k < 3 ? &v->sum[k] : &v->sum2[k - 3])) {
                fprintf(stderr, "svet merge: %s: pixel %zu: '%s' is not a "
                                "sum (a hexadecimal integer)\n", path, i, w[k]);
                fclose(f);
                return SVET_EXIT_INPUT;
            }
        if (c > IMAGE_MAX_COUNT || nf > IMAGE_MAX_COUNT) {
            fprintf(stderr, "svet merge: %s: pixel %zu: more than 2^46 "
                            "samples\n", path, i);
            fclose(f);
            return SVET_EXIT_INPUT;
        }
        v->count = c, v->nonfinite = nf;
    }
    fclose(f);
    return SVET_EXIT_OK;
}

static int by_from(const void *a, const void *b)
{
    const cmd_part_file_t *const *x = a, *const *y = b;
    return ((*x)->p.from > (*y)->p.from) - ((*x)->p.from < (*y)->p.from);
}

typedef struct {
    const char *exr, *png, *var;
    const char *ins[256];
    int nin;
} merge_args_t;

/* -o, --png, --variance: a file name, not empty */
static int opt_file(void *args, const char *cmd, const char *opt,
                    const char *v)
{
    merge_args_t *o = args;
    if (!*v)
        return cmd_error(cmd, SVET_EXIT_USAGE, "%s needs a file name", opt);
    *(opt[2] == 'p' ? &o->png : opt[2] == 'v' ? &o->var : &o->exr) = v;
    return SVET_EXIT_OK;
}

static int part_arg(void *args, const char *cmd, const char *a)
{
    merge_args_t *o = args;
    if (o->nin == 256)
        return cmd_error(cmd, SVET_EXIT_USAGE, "at most 256 parts");
    o->ins[o->nin++] = a;
    return SVET_EXIT_OK;
}

static const cmd_option_t options[] = {
    { "--output", "-o", true, CMD_CALL, 0, opt_file },
    { "--png", NULL, true, CMD_CALL, 0, opt_file },
    { "--variance", NULL, true, CMD_CALL, 0, opt_file },
    { NULL, NULL, false, CMD_SET_TRUE, 0, NULL }
};

int cmd_merge(int argc, char **argv)
{
    merge_args_t m;
    memset(&m, 0, sizeof m);
    const cmd_parser_t parser = { "merge", options, &m, part_arg,
                                  cmd_merge_help, NULL, false,
                                  "a file name" };
    int rc = cmd_parse_options(&parser, argc, argv);
    if (rc != CMD_RUN)
        return rc;
    rc = SVET_EXIT_OK;
    const char *exr = m.exr, *png = m.png, *var = m.var;
    const char *const *ins = m.ins;
    const int nin = m.nin;
    if (!exr || nin == 0)
        return cmd_error("merge", SVET_EXIT_USAGE,
                         "usage: svet merge PART.exr ... -o OUT.exr");
    cmd_part_file_t *q = calloc((size_t)nin, sizeof *q);
    cmd_part_file_t **order = calloc((size_t)nin, sizeof *order);
    char *png_alloc = NULL, *part_path = NULL;
    render_t r;
    memset(&r, 0, sizeof r);
    if (!q || !order) {
        rc = SVET_EXIT_OUTPUT;
        goto done;
    }
    for (int k = 0; k < nin; k++) {
        if ((rc = cmd_part_read(ins[k], &q[k])) != SVET_EXIT_OK)
            goto done;
        order[k] = &q[k];
        q[k].p.path = ins[k];
        const cmd_part_t *a = &q[0].p, *b = &q[k].p;
        if (b->identity != a->identity) {
            rc = cmd_error("merge", SVET_EXIT_USAGE, "%s and %s: different "
                           "scenes, seeds or settings", ins[0], ins[k]);
            goto done;
        }
        if (q[k].half != q[0].half) {
            rc = cmd_error("merge", SVET_EXIT_USAGE, "%s and %s: one EXR is "
                           "half, the other float: render every part with "
                           "--half or none", ins[0], ins[k]);
            goto done;
        }
        if (b->width != a->width || b->height != a->height) {
            rc = cmd_error("merge", SVET_EXIT_USAGE, "%s and %s: different "
                           "sizes (%dx%d, %dx%d)", ins[0], ins[k], a->width,
                           a->height, b->width, b->height);
            goto done;
        }
    }
    qsort(order, (size_t)nin, sizeof *order, by_from);
    const int W = q[0].p.width, H = q[0].p.height;
    svet_error err;
    svet_error_clear(&err);
    if (image_accum_alloc(&r.acc, W, H, &err) != SVET_OK ||
        !(r.sum2 = calloc((size_t)W * (size_t)H * 3, sizeof *r.sum2))) {
        rc = SVET_EXIT_OUTPUT;
        goto done;
    }
    r.camera.width = W, r.camera.height = H;
    /* the samples base:spp of every pixel; base is 0 but for a merge of
     * parts that are themselves later sample ranges */
    const long base = order[0]->p.from;
    long spp = -1;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            size_t i = (size_t)y * (size_t)W + (size_t)x;
            long next = base;
            for (int k = 0; k < nin; k++) {
                const cmd_part_t *p = &order[k]->p;
                if (x < p->x0 || x >= p->x1 || y < p->y0 || y >= p->y1)
                    continue;
                if (p->from < next) {
                    rc = cmd_error("merge", SVET_EXIT_USAGE, "%s: samples "
                                   "%ld:%ld of pixel (%d, %d) overlap "
                                   "another part's", p->path ? p->path : "",
                                   p->from, p->to, x, y);
                    goto done;
                }
                if (p->from > next) {
                    rc = cmd_error("merge", SVET_EXIT_USAGE, "samples %ld:%ld "
                                   "of pixel (%d, %d) are missing", next,
                                   p->from, x, y);
                    goto done;
                }
                next = p->to;
                const cmd_part_pixel_t *v = order[k]->v +
                    ((size_t)(y - p->y0) * (size_t)(p->x1 - p->x0) +
                     (size_t)(x - p->x0));
                for (int c = 0; c < 3; c++) {
                    image_fixed_add(&r.acc.sum[3 * i + c], &v->sum[c]);
                    image_fixed_add(&r.sum2[3 * i + c], &v->sum2[c]);
                }
                r.acc.count[i] += v->count;
                r.acc.nonfinite[i] += v->nonfinite;
                if (r.acc.count[i] > IMAGE_MAX_COUNT) {
                    rc = cmd_error("merge", SVET_EXIT_USAGE, "pixel (%d, %d): "
                                   "more than 2^46 samples", x, y);
                    goto done;
                }
            }
            if (next == base) {
                rc = cmd_error("merge", SVET_EXIT_USAGE, "pixel (%d, %d) is "
                               "in no part", x, y);
                goto done;
            }
            if (spp < 0)
                spp = next;
            else if (next != spp) {
                rc = cmd_error("merge", SVET_EXIT_USAGE, "samples %ld:%ld of "
                               "pixel (%d, %d) are missing", next < spp ? next
                               : spp, next < spp ? spp : next, x, y);
                goto done;
            }
        }
    scene_t s;
    memset(&s, 0, sizeof s);
    s.render.tonemap.op = (scene_tonemap_op)q[0].tm_op;
    s.render.tonemap.exposure = (real)q[0].tm[0];
    s.render.tonemap.key = (real)q[0].tm[1];
    s.render.tonemap.white = (real)q[0].tm[2];
    s.render.tonemap.bias = (real)q[0].tm[3];
    s.render.tonemap.curve = (scene_tonemap_curve)q[0].tm_curve;
    s.render.tonemap.gamma = (real)q[0].tm[4];
    if (!png && !(png = png_alloc = cmd_replace_ext(exr, ".png"))) {
        rc = SVET_EXIT_OUTPUT;
        goto done;
    }
    /* the merged sums as a part file of samples base:spp of every pixel, so
     * that merged images merge again (a merge of merges) */
    cmd_part_t whole = q[0].p;
    whole.from = base, whole.to = spp;
    whole.x0 = 0, whole.x1 = W, whole.y0 = 0, whole.y1 = H;
    if (!(part_path = malloc(strlen(exr) + 6))) {
        rc = SVET_EXIT_OUTPUT;
        goto done;
    }
    sprintf(part_path, "%s.part", exr);
    whole.path = part_path;
    r.spp_done = spp;
    outputs_t out = { exr, png, var, q[0].half, &whole };
    if (cmd_render_write(&r, &s, &out, &err) != SVET_OK) {
        fprintf(stderr, "svet merge: %s\n", err.msg);
        rc = SVET_EXIT_OUTPUT;
    }
done:
    for (int k = 0; q && k < nin; k++)
        free(q[k].v);
    free(q);
    free(order);
    free(png_alloc);
    free(part_path);
    image_accum_free(&r.acc);
    free(r.sum2);
    return rc;
}
