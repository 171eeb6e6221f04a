/*
 * cmd_render.c - `svet render`: read a scene file, render it progressively
 * in passes (ch. 5), and write the linear image (EXR) and a tone-mapped one
 * (PNG, ch. 6) side by side. SIGINT or SIGTERM abandons the current pass
 * within a tile's work and writes the last whole one (the image of that
 * many samples); a second signal ends the program at once. An animation
 * (animation.h) renders frame by frame, each to its own files. A part of
 * a split render (--samples, --crop) writes its exact sums for svet merge,
 * and photon's maps can be saved once and read by every part
 * (--save-prepass, --load-prepass).
 * Tests: tests/cmd/test_cmd_render.c, tests/cmd/test_frames.sh,
 * tests/cmd/test_merge.sh
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stddef.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cmd.h"
#include "cmdutil.h"
#include "io/exrio.h"
#include "io/pngio.h"
#include "render/animation.h"
#include "render/render.h"
#include "render/scenefile.h"
#include "render/scenepart.h"
#include "colour/tonemap.h"

static volatile sig_atomic_t stop_requested = 0;

static void on_signal(int sig)
{
    (void)sig;
    stop_requested = 1;
}

void cmd_render_help(FILE *f)
{
    fprintf(f,
"usage: svet render SCENE [options]\n"
"\n"
"Render the scene file SCENE (format: scenes/README.md) and write the linear\n"
"image as OpenEXR and a tone-mapped PNG beside it.\n"
"\n"
"options:\n"
"  -o, --output FILE.exr   linear output (default: the scene's `output exr`,\n"
"                          else out/<scene name>.exr); the PNG goes beside it\n"
"      --png FILE.png      tone-mapped output (default: FILE.exr with .png)\n"
"      --variance FILE.exr per-pixel variance of the mean, for error bars\n"
"      --spp N             samples per pixel\n"
"      --threads N         render threads (0 = every core)\n"
"      --seed N            seed of the random numbers (rng.h)\n"
"      --time-limit S      stop after the pass that passes S seconds\n"
"      --passes N          split the samples into N passes (default: the\n"
"                          scene's `passes`, or min(spp, 16) when it is 1)\n"
"      --checkpoint        write the outputs after every pass, and\n"
"                          FILE.exr.part with the exact sums\n"
"      --resume            continue from FILE.exr.part (a checkpoint of\n"
"                          the same scene): the same bits as one render\n"
"      --samples FROM:TO   only sample indices FROM..TO-1 of every pixel\n"
"      --crop X0:X1,Y0:Y1  only the pixels X0..X1-1, Y0..Y1-1\n"
"                          (either makes a part: FILE.exr.part beside the\n"
"                          EXR holds its exact sums for svet merge)\n"
"      --frame K           of an animation: only frame K (0-based)\n"
"      --frames A:B        of an animation: frames A..B-1 (default: all)\n"
"      --frame-count       print the number of frames (0: no animation)\n"
"      --half              write the EXR as half floats (default: float)\n"
"      --save-prepass FILE write the photon maps (integrator photon) to FILE\n"
"      --load-prepass FILE read them from FILE instead of tracing them: the\n"
"                          same bits; FILE must be of the same scene, seed\n"
"                          and settings, from a build of the same real\n"
"                          type (float, double), else it is refused\n"
"      --set KEY=VALUE     any scene setting, as scenefile_override() takes:\n"
"                          maxdepth, integrator, roulette, accel, tonemap, ...\n"
"      --strict            refuse a scene that reading warns about (exit 2)\n"
"  -q, --quiet             no progress and no summary\n"
"  -h, --help              this text\n"
"\n"
"Progress with an ETA goes to stderr when it is a terminal; otherwise one\n"
"summary line (wall and CPU seconds of the sampling and of the set-up:\n"
"acceleration structure and a method's pre-pass; samples per second, rays\n"
"per second) at the end.\n"
"The image depends only on the scene, the seed and the sample count: the\n"
"same for any number of threads or passes.\n"
"\n"
"Each frame of an animation is written to its own files: every output\n"
"name (-o, --png, --variance, the scene's `output`, the default) is a\n"
"pattern in which one %%d, %%Nd or %%0Nd (N a digit) is the frame number\n"
"and %%%% a %%; a name without one gets -%%04d before its extension\n"
"(out/anim.exr: out/anim-0007.exr). Frame k has the seed\n"
"seed ^ splitmix64(k) and the same bits alone or among other frames.\n"
"\n"
"exit codes: 0 done; 1 bad command line; 2 the scene or a file it names is\n"
"missing or malformed; 3 an output could not be written; 4 interrupted\n"
"(SIGINT/SIGTERM): the pass under way is abandoned and the outputs hold\n"
"the passes completed, the same image as a render asked for that many\n"
"samples (nothing is written when the first pass had not ended); 6 a\n"
"pass failed (out of memory, or the rendering method's pass, e.g. ppm's\n"
"photon maps): nothing more is written.\n"
"\n"
"Outputs are written in full to temporary files beside them\n"
"(NAME.tmp-HOST-PID-N) and then renamed over the old ones together, so a\n"
"failed or interrupted write keeps the previous EXR, PNG and variance as\n"
"a matching set; a read-only file (mode 444) is never replaced, and an\n"
"output that is the same file as another output or an input (the scene,\n"
"a mesh) is refused. A killed render's temporary files are removed by the\n"
"next write of the same output on the same host.\n");
}

typedef struct {
    double t0;          /* start of the render */
    double last;        /* last progress line */
    long pass, passes;  /* current pass (1-based) and total */
    long spp0, spp1, spp; /* samples of this pass, and in all */
    bool tty;
} progress_t;

static void on_tile(void *ctx, long done, long total)
{
    progress_t *p = ctx;
    double t = cmd_now();
    if (!p->tty || (t - p->last < 0.2 && done < total))
        return;
    p->last = t;
    /* fraction of all samples done, counting finished tiles of this pass */
    double frac = ((double)p->spp0 + (double)(p->spp1 - p->spp0) *
                   (double)done / (double)total) / (double)p->spp;
    double el = t - p->t0, eta = frac > 0 ? el / frac - el : 0;
    fprintf(stderr, "\rpass %ld/%ld  %5.1f%%  %6.1f s elapsed  ETA %6.1f s ",
            p->pass, p->passes, 100 * frac, el, eta);
    fflush(stderr);
}

static char *default_exr(const scene_t *s, const char *scene_path)
{
    if (s->render.output_exr)
        return strdup(s->render.output_exr);
    const char *base = strrchr(scene_path, '/');
    base = base ? base + 1 : scene_path;
    char *stem = cmd_replace_ext(base, "");
    if (!stem)
        return NULL;
    char *out = malloc(strlen(stem) + 9);
    if (out)
        sprintf(out, "out/%s.exr", stem);
    free(stem);
    return out;
}

/* Make the directory of path if it is missing (one level, as out/). */
static void ensure_dir(const char *path)
{
    const char *slash = strrchr(path, '/');
    if (!slash || slash == path)
        return;
    char dir[4096];
    size_t n = (size_t)(slash - path);
    if (n >= sizeof dir)
        return;
    memcpy(dir, path, n);
    dir[n] = '\0';
    if (mkdir(dir, 0777) != 0 && errno != EEXIST)
        return; /* the writer will report the real problem */
}


/* Write the EXR, the PNG and (if asked) the variance image of what r holds
 * so far, as one set of outputs (fileio.h): each is written in full to a
 * temporary file before any replaces its target, so an interrupted or
 * failed write leaves the previous checkpoint's files, all of them. */
/* The part file beside a part's EXR (cmd.h: cmd_part_t): the exact
 * per-pixel sums, sums of squares and counts of its crop, the sums as
 * the hexadecimal integers of image.h's fixed point, so that svet merge
 * adds the same integers; and the EXR's pixel type (--half), so that the
 * merge writes what one render would. */
static void write_part(FILE *f, const render_t *r, const scene_t *s,
                       const cmd_part_t *p, bool half)
{
    const scene_tonemap_t *t = &s->render.tonemap;
    fprintf(f, "svet-part 3\nidentity %016llx\nsize %d %d\nsamples %ld %ld\n"
               "crop %d %d %d %d\ntonemap %d %a %a %a %a %d %a\nexr %s\n",
            (unsigned long long)p->identity, p->width, p->height, p->from,
            r->spp_done, p->x0, p->x1, p->y0, p->y1, (int)t->op,
            (double)t->exposure, (double)t->key, (double)t->white,
            (double)t->bias, (int)t->curve, (double)t->gamma,
            half ? "half" : "float");
    for (int y = p->y0; y < p->y1; y++)
        for (int x = p->x0; x < p->x1; x++) {
            size_t i = (size_t)y * (size_t)p->width + (size_t)x;
            for (int c = 0; c < 3; c++) {
                cmd_fixed_write(f, &r->acc.sum[3 * i + (size_t)c]);
                putc(' ', f);
            }
            for (int c = 0; c < 3; c++) {
                cmd_fixed_write(f, &r->sum2[3 * i + (size_t)c]);
                putc(' ', f);
            }
            fprintf(f, "%llu %llu\n", (unsigned long long)r->acc.count[i],
                    (unsigned long long)r->acc.nonfinite[i]);
        }
}

svet_status cmd_render_write(const render_t *r, const scene_t *s,
                             const outputs_t *o, svet_error *err)
{
    image_t img, ldr;
    memset(&ldr, 0, sizeof ldr);
    svet_status st = render_image(r, &img, err);
    if (st != SVET_OK)
        return st;
    fileio_set_t set;
    fileio_set_init(&set);
    fileio_t *f;
    ensure_dir(o->exr);
    st = fileio_set_begin(&set, o->exr, &f, err);
    if (st == SVET_OK)
        st = exrio_write_to(f, &img, o->half ? EXRIO_HALF : EXRIO_FLOAT,
                            EXRIO_ZIP, err);
    if (st == SVET_OK) {
        tonemap_params_t tp;
        const scene_tonemap_t *t = &s->render.tonemap;
        tonemap_defaults(&tp, (tonemap_op_t)t->op);
        tp.stops = (double)t->exposure;
        tp.key = (double)t->key;
        tp.white = (double)t->white;
        tp.bias = (double)t->bias;
        tp.curve = (tonemap_curve_t)t->curve;
        tp.gamma = (double)t->gamma;
        st = tonemap_apply(&img, &ldr, &tp, NULL, err);
        if (st == SVET_OK) {
            ensure_dir(o->png);
            st = fileio_set_begin(&set, o->png, &f, err);
        }
        if (st == SVET_OK)
            st = pngio_write_to(f, &ldr, 8, err);
    }
    if (st == SVET_OK && o->var) {
        image_t var;
        st = render_variance(r, &var, err);
        if (st == SVET_OK) {
            ensure_dir(o->var);
            st = fileio_set_begin(&set, o->var, &f, err);
            if (st == SVET_OK)
                st = exrio_write_to(f, &var, EXRIO_FLOAT, EXRIO_ZIP, err);
            image_free(&var);
        }
    }
    if (st == SVET_OK && o->part) {
        st = fileio_set_begin(&set, o->part->path, &f, err);
        if (st == SVET_OK) {
            write_part(f->f, r, s, o->part, o->half);
            if (ferror(f->f))
                st = svet_error_set(err, SVET_ERR_IO, "%s: write failed",
                                    o->part->path);
        }
    }
    if (st == SVET_OK)
        st = fileio_set_commit(&set, err);
    else
        fileio_set_abort(&set);
    image_free(&ldr);
    image_free(&img);
    return st;
}

static int opt_resume(void *args, const char *cmd, const char *opt,
                      const char *v)
{
    (void)cmd, (void)opt, (void)v;
    cmd_render_args_t *o = args;
    o->resume = o->checkpoint = true;
    return SVET_EXIT_OK;
}

static int opt_count(void *args, const char *cmd, const char *opt,
                     const char *v)
{
    cmd_render_args_t *o = args;
    if (!cmd_parse_long(v, 1, SCENE_MAX_SPP,
                        !strcmp(opt, "--spp") ? &o->spp : &o->passes))
        return cmd_bad_value(cmd, opt, v);
    return SVET_EXIT_OK;
}

static int opt_samples(void *args, const char *cmd, const char *opt,
                       const char *v)
{
    cmd_render_args_t *o = args;
    char *e1, *e2;
    errno = 0;
    long f = strtol(v, &e1, 10), t = *e1 == ':' ? strtol(e1 + 1, &e2, 10) : -1;
    if (errno || *e1 != ':' || e2 == e1 + 1 || *e2 || f < 0 || t <= f ||
        t > SCENE_MAX_SPP)
        return cmd_bad_value(cmd, opt, v);
    o->from = f, o->to = t, o->part = true;
    return SVET_EXIT_OK;
}

static int opt_crop(void *args, const char *cmd, const char *opt,
                    const char *v)
{
    cmd_render_args_t *o = args;
    int c[4], n = -1;
    if (sscanf(v, "%d:%d,%d:%d%n", &c[0], &c[1], &c[2], &c[3], &n) != 4 ||
        n < 0 || v[n] || c[0] < 0 || c[1] <= c[0] || c[2] < 0 || c[3] <= c[2])
        return cmd_bad_value(cmd, opt, v);
    memcpy(o->crop, c, sizeof c);
    o->cropped = o->part = true;
    return SVET_EXIT_OK;
}

/* --frame K, --frames A:B (the frames A..B-1) */
static int opt_frames(void *args, const char *cmd, const char *opt,
                      const char *v)
{
    cmd_render_args_t *o = args;
    long a, b;
    if (!strcmp(opt, "--frame")) {
        if (!cmd_parse_long(v, 0, ANIMATION_MAX_FRAMES - 1, &a))
            return cmd_bad_value(cmd, opt, v);
        b = a + 1;
    } else {
        const char *colon = strchr(v, ':');
        char left[32];
        size_t n = colon ? (size_t)(colon - v) : 0;
        if (!colon || n >= sizeof left)
            return cmd_bad_value(cmd, opt, v);
        memcpy(left, v, n);
        left[n] = '\0';
        if (!cmd_parse_long(left, 0, ANIMATION_MAX_FRAMES - 1, &a) ||
            !cmd_parse_long(colon + 1, 1, ANIMATION_MAX_FRAMES, &b) ||
            b <= a)
            return cmd_bad_value(cmd, opt, v);
    }
    o->frame_a = a, o->frame_b = b;
    o->frames_range = strcmp(opt, "--frame") != 0;
    return SVET_EXIT_OK;
}

static int opt_time_limit(void *args, const char *cmd, const char *opt,
                          const char *v)
{
    cmd_render_args_t *o = args;
    if (!cmd_parse_double(v, &o->time_limit) || o->time_limit < 0 ||
        o->time_limit > 1e9)
        return cmd_bad_value(cmd, opt, v);
    return SVET_EXIT_OK;
}

static int scene_arg(void *args, const char *cmd, const char *a)
{
    cmd_render_args_t *o = args;
    if (o->scene)
        return cmd_error(cmd, SVET_EXIT_USAGE, "one scene at a time ('%s' "
                         "and '%s')", o->scene, a);
    o->scene = a;
    return SVET_EXIT_OK;
}

#define AT(f) offsetof(cmd_render_args_t, f)
static const cmd_option_t options[] = {
    { "--checkpoint", NULL, false, CMD_SET_TRUE, AT(checkpoint), NULL },
    { "--quiet", "-q", false, CMD_SET_TRUE, AT(quiet), NULL },
    { "--resume", NULL, false, CMD_CALL, 0, opt_resume },
    { "--half", NULL, false, CMD_SET_TRUE, AT(half), NULL },
    { "--output", "-o", true, CMD_SET_FILE, AT(exr), NULL },
    { "--png", NULL, true, CMD_SET_FILE, AT(png), NULL },
    { "--variance", NULL, true, CMD_SET_FILE, AT(var), NULL },
    { "--spp", NULL, true, CMD_CALL, 0, opt_count },
    { "--passes", NULL, true, CMD_CALL, 0, opt_count },
    { "--samples", NULL, true, CMD_CALL, 0, opt_samples },
    { "--crop", NULL, true, CMD_CALL, 0, opt_crop },
    { "--time-limit", NULL, true, CMD_CALL, 0, opt_time_limit },
    { "--frame", NULL, true, CMD_CALL, 0, opt_frames },
    { "--frames", NULL, true, CMD_CALL, 0, opt_frames },
    { "--frame-count", NULL, false, CMD_SET_TRUE, AT(frame_count), NULL },
    { "--save-prepass", NULL, true, CMD_SET_FILE, AT(save_prepass), NULL },
    { "--load-prepass", NULL, true, CMD_SET_FILE, AT(load_prepass), NULL },
    { NULL, NULL, false, CMD_SET_TRUE, 0, NULL }
};
#undef AT

int cmd_render_parse(int argc, char **argv, cmd_render_args_t *o)
{
    memset(o, 0, sizeof *o);
    o->spp = o->passes = -1;
    o->time_limit = -1;
    cmd_scene_opts_init(&o->so);
    const cmd_parser_t p = { "render", options, o, scene_arg,
                             cmd_render_help, &o->so, false, NULL };
    int rc = cmd_parse_options(&p, argc, argv);
    if (rc != CMD_RUN)
        return rc;
    if (!o->scene)
        return cmd_error("render", SVET_EXIT_USAGE,
                         "no scene file (svet render --help)");
    return CMD_RUN;
}

/* The name of frame k's file from pattern `name` (cmd_render_help): one
 * %d, %Nd or %0Nd (N a digit) is the frame number, %% a %; without one,
 * -%04d goes before the extension of the file's name (or at its end).
 * NULL with *why set when the pattern is bad, or out of memory (*why
 * NULL). */
static char *frame_name(const char *name, int k, const char **why)
{
    *why = NULL;
    size_t n = strlen(name);
    char num[32];
    const char *conv = NULL; /* the conversion's '%' */
    size_t conv_len = 0;
    for (size_t i = 0; i < n; i++) {
        if (name[i] != '%')
            continue;
        if (name[i + 1] == '%') {
            i++;
            continue;
        }
        size_t j = i + 1;
        bool zero = name[j] == '0';
        j += zero;
        int width = 0;
        if (name[j] >= '1' && name[j] <= '9')
            width = name[j++] - '0';
        if (name[j] != 'd' || (zero && !width)) {
            *why = "a '%' starts the frame number %d, %Nd or %0Nd (N a "
                   "digit 1-9), or is %%";
            return NULL;
        }
        if (conv) {
            *why = "it has two frame numbers: one %d at the most";
            return NULL;
        }
        conv = name + i;
        conv_len = j + 1 - i;
        snprintf(num, sizeof num, zero ? "%0*d" : "%*d", width, k);
        i = j;
    }
    /* without a conversion: -%04d before the extension of the name's last
     * component (not a leading dot) */
    size_t at = n;
    if (!conv) {
        const char *base = strrchr(name, '/');
        base = base ? base + 1 : name;
        const char *dot = strrchr(base, '.');
        if (dot && dot > base)
            at = (size_t)(dot - name);
        snprintf(num, sizeof num, "-%04d", k);
    } else {
        at = (size_t)(conv - name);
    }
    char *out = malloc(n + strlen(num) + 1);
    if (!out)
        return NULL;
    char *w = out;
    for (size_t i = 0; i < n; i++) {
        if (i == at) {
            w += sprintf(w, "%s", num);
            if (conv) {
                i += conv_len - 1;
                continue;
            }
        }
        if (name[i] == '%' && name[i + 1] == '%')
            i++;
        *w++ = name[i];
    }
    if (at == n)
        w += sprintf(w, "%s", num);
    *w = '\0';
    return out;
}

/* The outputs of frame k (-1: not an animation): *exr, *png and *var
 * (NULL without --variance) malloc'ed, from the options or the scene.
 * The exit code; a bad pattern is a bad command line (or a bad scene, in
 * the scene's `output`), with nothing written. */
static int frame_names(const cmd_render_args_t *o, const scene_t *s, int k,
                       char **exr, char **png, char **var)
{
    char *e = o->exr ? strdup(o->exr) : default_exr(s, o->scene);
    char *p = o->png ? strdup(o->png)
            : (!o->exr && s->render.output_png) ? strdup(s->render.output_png)
            : NULL;
    char *v = o->var ? strdup(o->var) : NULL;
    const bool scene_png = !o->png && p;
    int rc = SVET_EXIT_OK;
    if (!e || (!p && (o->png || scene_png)) || (!v && o->var))
        rc = SVET_EXIT_OUTPUT;
    const struct { char **name; const char *what; bool scene; } f[] = {
        { &e, "the EXR output", !o->exr && s->render.output_exr },
        { &p, "the PNG output", scene_png },
        { &v, "the variance output", false },
    };
    for (int i = 0; i < 3 && rc == SVET_EXIT_OK && k >= 0; i++) {
        if (!*f[i].name)
            continue;
        const char *why;
        char *x = frame_name(*f[i].name, k, &why);
        if (!x && why)
            rc = cmd_error("render", f[i].scene ? SVET_EXIT_INPUT
                                                : SVET_EXIT_USAGE,
                           "%s: %s '%s' is a bad frame pattern: %s "
                           "(nothing was written)", o->scene, f[i].what,
                           *f[i].name, why);
        else if (!x)
            rc = SVET_EXIT_OUTPUT;
        free(*f[i].name);
        *f[i].name = x;
    }
    if (rc == SVET_EXIT_OK && !p && !(p = cmd_replace_ext(e, ".png")))
        rc = SVET_EXIT_OUTPUT;
    if (rc == SVET_EXIT_OUTPUT)
        fprintf(stderr, "svet render: out of memory\n");
    if (rc != SVET_EXIT_OK) {
        free(e), free(p), free(v);
        e = p = v = NULL;
    }
    *exr = e, *png = p, *var = v;
    return rc;
}

/* The first lines of a saved pre-pass: what it is of (cmd_part_identity)
 * and the build's real type, whose tracing made it */
#define PREPASS_HEAD "svet-prepass 1\nidentity %016llx\nreal %s\n"

/* --save-prepass, --load-prepass: refused for an animation (each frame
 * has a pre-pass of its own) and together; for --load-prepass the file
 * opened at its pre-pass in *pre, once its identity and real type are
 * the scene's. The exit code. */
static int prepass_check(const cmd_render_args_t *o, const scene_t *scene,
                         int frame, FILE **pre)
{
    svet_error err;
    svet_error_clear(&err);
    if (o->load_prepass && o->save_prepass)
        return cmd_error("render", SVET_EXIT_USAGE, "--save-prepass and "
                         "--load-prepass: one of them at a time");
    if (frame >= 0)
        return cmd_error("render", SVET_EXIT_USAGE, "%s: an animation: "
                         "--save-prepass and --load-prepass take one "
                         "frame's scene", o->scene);
    if (render_check_prepass(scene, &err) != SVET_OK)
        return cmd_error("render", SVET_EXIT_USAGE, "%s", err.msg);
    if (!o->load_prepass)
        return SVET_EXIT_OK;
    unsigned long long id, fid;
    char real_name[16];
    if (cmd_part_identity(o->scene, scene, &o->so, &id, &err) != SVET_OK)
        return cmd_error("render", SVET_EXIT_INPUT, "%s", err.msg);
    FILE *f;
    if (fileio_open_read(o->load_prepass, &f, &err) != SVET_OK)
        return cmd_error("render", SVET_EXIT_INPUT, "%s", err.msg);
    if (fscanf(f, "svet-prepass 1 identity %llx real %15s", &fid,
               real_name) != 2 || fgetc(f) != '\n') {
        fclose(f);
        return cmd_error("render", SVET_EXIT_INPUT, "%s: not a pre-pass "
                         "file of svet render --save-prepass",
                         o->load_prepass);
    }
    if (fid != id) {
        fclose(f);
        return cmd_error("render", SVET_EXIT_USAGE, "%s: the pre-pass of "
                         "another scene, seed or settings (identity "
                         "%016llx, this scene's %016llx); nothing was "
                         "written", o->load_prepass, fid, id);
    }
    if (strcmp(real_name, REAL_NAME)) {
        fclose(f);
        return cmd_error("render", SVET_EXIT_USAGE, "%s: a pre-pass of a "
                         "%s build, this one is %s; nothing was written",
                         o->load_prepass, real_name, REAL_NAME);
    }
    *pre = f;
    return SVET_EXIT_OK;
}

/* --save-prepass: r's pre-pass to the file, replaced only when whole */
static int prepass_save(const cmd_render_args_t *o, const scene_t *scene,
                        const render_t *r)
{
    svet_error err;
    svet_error_clear(&err);
    unsigned long long id;
    if (cmd_part_identity(o->scene, scene, &o->so, &id, &err) != SVET_OK)
        return cmd_error("render", SVET_EXIT_INPUT, "%s", err.msg);
    fileio_t out;
    if (fileio_begin(&out, o->save_prepass, &err) != SVET_OK)
        return cmd_error("render", SVET_EXIT_OUTPUT, "%s", err.msg);
    svet_status st = SVET_OK;
    if (fprintf(out.f, PREPASS_HEAD, id, REAL_NAME) < 0)
        st = svet_error_set(&err, SVET_ERR_IO, "a write failed");
    if (st == SVET_OK)
        st = render_save_prepass(r, out.f, &err);
    if (st != SVET_OK) {
        fileio_abort(&out);
        return cmd_error("render", st == SVET_ERR_UNSUPPORTED
                         ? SVET_EXIT_USAGE : SVET_EXIT_OUTPUT, "%s: %s",
                         o->save_prepass, err.msg);
    }
    if (fileio_commit(&out, &err) != SVET_OK)
        return cmd_error("render", SVET_EXIT_OUTPUT, "%s", err.msg);
    return SVET_EXIT_OK;
}

/* Render the loaded scene (frame `frame` of its animation, or -1) to the
 * outputs o names, expanded for the frame; the exit code. */
static int render_loaded(const cmd_render_args_t *o, scene_t *scene,
                         int frame)
{
    const char *scene_path = o->scene;
    char *opt_var = NULL;
    svet_error err;
    svet_error_clear(&err);
    int rc = SVET_EXIT_OK;
    if (o->spp > 0)
        scene->render.spp = o->spp;
    if (o->time_limit >= 0)
        scene->render.time_limit = o->time_limit;
    if (o->checkpoint)
        scene->render.checkpoint = true;
    if (o->passes > 0)
        scene->render.passes = (int)o->passes;

    char *exr = NULL, *png = NULL;
    render_t r;
    bool r_live = false;
    char *part_path = NULL;
    rc = frame_names(o, scene, frame, &exr, &png, &opt_var);
    if (rc != SVET_EXIT_OK)
        goto done;
    if (!exr || !png) {
        fprintf(stderr, "svet render: out of memory\n");
        rc = SVET_EXIT_OUTPUT;
        goto done;
    }
    const cmd_file_t outs[] = { { exr, "the EXR output" },
                                { png, "the PNG output" },
                                { opt_var, "the variance output" } };
    const cmd_file_t ins[] = { { scene_path, "the scene file" } };
    rc = cmd_check_outputs("render", outs, 3, ins, 1);
    if (rc != SVET_EXIT_OK)
        goto done;
    /* the set-up's time (acceleration structure, lights, a method's
     * pre-pass) is in the summary: every part of a split render pays it */
    const double t_setup = cmd_now(), c_setup = cmd_cpu_now();
    if (scene_validate(scene, &err) != SVET_OK) {
        fprintf(stderr, "svet render: %s: %s\n", scene_path, err.msg);
        rc = SVET_EXIT_INPUT;
        goto done;
    }
    FILE *pre = NULL;
    if (o->load_prepass || o->save_prepass) {
        rc = prepass_check(o, scene, frame, &pre);
        if (rc != SVET_EXIT_OK)
            goto done;
    }
    const bool loaded = pre != NULL;
    svet_status ist = render_init_prepass(&r, scene, pre, &err);
    if (pre)
        fclose(pre);
    if (ist != SVET_OK) {
        fprintf(stderr, "svet render: %s: %s%s%s\n", scene_path,
                loaded ? o->load_prepass : "", loaded ? ": " : "", err.msg);
        rc = SVET_EXIT_INPUT;
        goto done;
    }
    r_live = true;
    if (o->save_prepass &&
        (rc = prepass_save(o, scene, &r)) != SVET_EXIT_OK)
        goto done;
    const double setup_secs = cmd_now() - t_setup;
    const double setup_cpu = cmd_cpu_now() - c_setup;
    if (scene->render.subsample_step > 0 &&
        (o->part || o->checkpoint || o->resume)) {
        /* app. F refines on every pixel's final value: a part of the
         * samples or of the image, or a checkpoint to resume from, would
         * refine on other values than the whole render */
        fprintf(stderr, "svet render: %s: `render subsample` renders the "
                        "whole image with all its samples at once: "
                        "--samples, --crop, --checkpoint and --resume are "
                        "refused (subsample.step=0 turns it off); nothing "
                        "was written\n", scene_path);
        rc = SVET_EXIT_USAGE;
        goto done;
    }
    cmd_part_t part = { 0 };
    if (o->part || o->checkpoint) {
        const int W = scene->camera.width, H = scene->camera.height;
        if (o->cropped && (o->crop[1] > W || o->crop[3] > H)) {
            fprintf(stderr, "svet render: --crop %d:%d,%d:%d: outside the "
                    "%dx%d image\n", o->crop[0], o->crop[1], o->crop[2],
                    o->crop[3], W, H);
            rc = SVET_EXIT_USAGE;
            goto done;
        }
        part.width = W, part.height = H;
        part.from = o->to > 0 ? o->from : 0;
        part.to = o->to > 0 ? o->to : scene->render.spp;
        part.x0 = o->cropped ? o->crop[0] : 0;
        part.x1 = o->cropped ? o->crop[1] : W;
        part.y0 = o->cropped ? o->crop[2] : 0;
        part.y1 = o->cropped ? o->crop[3] : H;
        if (cmd_part_identity(scene_path, scene, &o->so, &part.identity,
                              &err) != SVET_OK) {
            fprintf(stderr, "svet render: %s\n", err.msg);
            rc = SVET_EXIT_INPUT;
            goto done;
        }
        part_path = malloc(strlen(exr) + 6);
        if (!part_path) {
            rc = SVET_EXIT_OUTPUT;
            goto done;
        }
        sprintf(part_path, "%s.part", exr);
        part.path = part_path;
        r.crop_x0 = part.x0, r.crop_x1 = part.x1;
        r.crop_y0 = part.y0, r.crop_y1 = part.y1;
        r.spp_done = part.from; /* sample indices from FROM on */
        scene->render.spp = part.to;
    }
    if (o->resume) {
        cmd_part_file_t q;
        memset(&q, 0, sizeof q);
        rc = cmd_part_read(exr, &q);
        if (rc == SVET_EXIT_OK &&
            (q.p.identity != part.identity || q.p.from != part.from ||
             q.p.x0 != part.x0 || q.p.x1 != part.x1 || q.p.y0 != part.y0 ||
             q.p.y1 != part.y1 || q.p.to > part.to)) {
            fprintf(stderr, "svet render: --resume: %s.part is of another "
                            "scene, seed, setting, crop or sample range\n",
                    exr);
            rc = SVET_EXIT_USAGE;
        }
        if (rc == SVET_EXIT_OK)
            for (int y = part.y0; y < part.y1; y++)
                for (int x = part.x0; x < part.x1; x++) {
                    size_t i = (size_t)y * (size_t)part.width + (size_t)x;
                    const cmd_part_pixel_t *v = q.v + ((size_t)(y - part.y0) *
                        (size_t)(part.x1 - part.x0) + (size_t)(x - part.x0));
                    memcpy(r.acc.sum + 3 * i, v->sum, sizeof v->sum);
                    memcpy(r.sum2 + 3 * i, v->sum2, sizeof v->sum2);
                    r.acc.count[i] = v->count;
                    r.acc.nonfinite[i] = v->nonfinite;
                }
        free(q.v);
        if (rc != SVET_EXIT_OK)
            goto done;
        r.spp_done = q.p.to;
    }

    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESETHAND; /* a second signal ends the program at once */
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);

    const long total = scene->render.spp, first = r.spp_done;
    long npass = scene->render.passes > 1 ? scene->render.passes
                 : (total - first < 16 ? total - first : 16);
    if (npass > total - first)
        npass = total - first;
    if (scene->render.subsample_step > 0)
        npass = 1; /* app. F: every sample of a pixel in one pass */
    outputs_t out = { exr, png, opt_var, o->half,
                      o->part || o->checkpoint ? &part : NULL };
    progress_t pr = { cmd_now(), 0, 0, npass, 0, 0, total,
                      !o->quiet && isatty(STDERR_FILENO) };
    const double c_sampling = cmd_cpu_now();
    bool interrupted = false;
    long written = o->resume ? -1 : first; /* the samples on disk */
    for (long k = 1; k <= npass; k++) {
        long end = first + (long)((double)(total - first) * (double)k /
                                  (double)npass);
        pr.pass = k;
        pr.spp0 = r.spp_done;
        pr.spp1 = end;
        /* a signal abandons the pass at the next tile: what is written
         * is then the last whole pass, the image of r.spp_done samples */
        bool abandoned;
        if (render_pass_until(&r, end, scene->render.threads, on_tile, &pr,
                              &stop_requested, &abandoned, &err) != SVET_OK) {
            fprintf(stderr, "\nsvet render: %s: %s\n", scene_path, err.msg);
            rc = SVET_EXIT_RENDER;
            goto done;
        }
        if (stop_requested) {
            interrupted = true;
            break;
        }
        if (scene->render.time_limit > 0 &&
            cmd_now() - pr.t0 >= scene->render.time_limit)
            break;
        if (scene->render.checkpoint && k < npass) {
            if (cmd_render_write(&r, scene, &out, &err) != SVET_OK) {
                fprintf(stderr, "\nsvet render: %s\n", err.msg);
                rc = SVET_EXIT_OUTPUT;
                goto done;
            }
            written = r.spp_done;
        }
    }
    double secs = cmd_now() - pr.t0;
    double cpu_secs = cmd_cpu_now() - c_sampling;
    if (pr.tty)
        fputc('\n', stderr);
    if (r.spp_done == first && !o->resume) {
        /* stopped in the first pass: an image of no samples would only
         * replace a good earlier one */
        fprintf(stderr, "svet render: %s: interrupted before the first pass "
                        "ended: nothing written\n", scene_path);
        rc = SVET_EXIT_INTERRUPTED;
        goto done;
    }
    if (r.spp_done != written &&
        cmd_render_write(&r, scene, &out, &err) != SVET_OK) {
        fprintf(stderr, "svet render: %s\n", err.msg);
        rc = SVET_EXIT_OUTPUT;
        goto done;
    }
    uint64_t nonfinite = image_accum_nonfinite(&r.acc);
    if (!o->quiet) {
        double samples = (double)r.spp_done * (double)scene->camera.width *
                         (double)scene->camera.height;
        /* CPU seconds (all threads) beside wall seconds: on a shared
         * machine they count only this process's work */
        fprintf(stderr, "svet render: %s: %dx%d, %ld spp in %.2f s "
                        "(%.2f CPU-s) after %.2f s (%.2f CPU-s) of "
                        "set-up: %.3g "
                        "samples/s, %.3g rays/s; %s%s%s; wrote %s and "
                        "%s%s%s\n",
                scene_path, scene->camera.width, scene->camera.height,
                r.spp_done, secs, cpu_secs, setup_secs, setup_cpu,
                samples / secs,
                (double)r.stats.rays / secs,
                r.method ? r.method->describe : "", r.method ? "; " : "",
                r.accel_choice, exr, png,
                interrupted ? " (interrupted)" : "",
                nonfinite ? " (some samples were NaN/Inf and were dropped)"
                          : "");
        if (nonfinite)
            fprintf(stderr, "svet render: %llu non-finite samples dropped\n",
                    (unsigned long long)nonfinite);
        if (r.method && r.method->report && r.method_state) {
            char line[512];
            r.method->report(r.method_state, line, sizeof line);
            fprintf(stderr, "svet render: %s\n", line);
        }
        if (scene->render.subsample_step > 0)
            fprintf(stderr, "svet render: subsample step %d threshold %g "
                            "(app. F): %ld of %ld pixels computed, the "
                            "rest interpolated\n",
                    scene->render.subsample_step,
                    (double)scene->render.subsample_threshold,
                    r.sub_computed,
                    (long)scene->camera.width * scene->camera.height);
    }
    if (interrupted)
        rc = SVET_EXIT_INTERRUPTED;
done:
    if (r_live)
        render_free(&r);
    free(exr);
    free(png);
    free(opt_var);
    free(part_path);
    return rc;
}

int cmd_render(int argc, char **argv)
{
    cmd_render_args_t o;
    int rc = cmd_render_parse(argc, argv, &o);
    if (rc != CMD_RUN)
        return rc;
    scene_t scene;
    rc = cmd_scene_load("render", &scene, o.scene, &o.so);
    if (rc != SVET_EXIT_OK) {
        scene_free(&scene);
        return rc;
    }
    const int n = animation_frames(&scene);
    if (o.frame_count) {
        printf("%d\n", n);
        scene_free(&scene);
        return SVET_EXIT_OK;
    }
    const bool some = o.frame_b > 0;
    const long a = some ? o.frame_a : 0, b = some ? o.frame_b : n;
    if (some && n == 0)
        rc = cmd_error("render", SVET_EXIT_USAGE, "%s: --frame(s): the "
                       "scene has no animation ('animation frames N'); "
                       "nothing was written", o.scene);
    else if (some && b > n)
        rc = cmd_error("render", SVET_EXIT_USAGE, "%s: --frame%s %ld%s%.0ld: "
                       "the animation has frames 0..%d; nothing was "
                       "written", o.scene, o.frames_range ? "s" : "", a,
                       o.frames_range ? ":" : "", o.frames_range ? b : 0,
                       n - 1);
    /* every frame's camera and output names before any frame renders */
    svet_error err;
    svet_error_clear(&err);
    for (long k = a; k < b && rc == SVET_EXIT_OK; k++)
        if (animation_set_frame(&scene, (int)k, &err) != SVET_OK)
            rc = cmd_error("render", SVET_EXIT_INPUT, "%s: %s; nothing was "
                           "written", o.scene, err.msg);
    if (rc == SVET_EXIT_OK && n > 0) {
        char *e, *p, *v;
        rc = frame_names(&o, &scene, (int)a, &e, &p, &v);
        if (rc == SVET_EXIT_OK)
            free(e), free(p), free(v);
    }
    if (rc != SVET_EXIT_OK || n == 0) {
        if (rc == SVET_EXIT_OK)
            rc = render_loaded(&o, &scene, -1);
        scene_free(&scene);
        return rc;
    }
    /* frame by frame, each from the scene read afresh: frame k is the
     * same whichever frames come before it */
    for (long k = a; k < b && rc == SVET_EXIT_OK; k++) {
        if (k > a) {
            scene_free(&scene);
            rc = cmd_scene_load("render", &scene, o.scene, &o.so);
        }
        if (rc == SVET_EXIT_OK &&
            animation_set_frame(&scene, (int)k, &err) != SVET_OK)
            rc = cmd_error("render", SVET_EXIT_INPUT, "%s: %s", o.scene,
                           err.msg);
        if (rc == SVET_EXIT_OK)
            rc = render_loaded(&o, &scene, (int)k);
    }
    scene_free(&scene);
    return rc;
}
