/*
 * cmdutil.c - what the subcommands share: the clock, command-line numbers,
 * usage messages, file names and the scene options --threads, --seed,
 * --set and --strict (cmdutil.h). Not a subcommand itself.
 * Tests: tests/cmd/test_cmd_render.c, tests/stats/test_converge.c, tests/cmd/test_svet.c
 */
#define _POSIX_C_SOURCE 200809L
#include "cmdutil.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cmd.h"
#include "io/fileio.h"
#include "render/allparts.h"
#include "render/scenefile.h"

double cmd_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double cmd_cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

bool cmd_parse_long(const char *s, long lo, long hi, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (errno || end == s || *end || v < lo || v > hi)
        return false;
    *out = v;
    return true;
}

int cmd_read_limits(const char *cmd, const char *max_pixels,
                    image_read_limits_t *lim)
{
    lim->max_pixels = IMAGE_READ_MAX_PIXELS;
    const char *v = max_pixels ? max_pixels : getenv("SVET_MAX_PIXELS");
    if (!v)
        return SVET_EXIT_OK;
    long n;
    if (!cmd_parse_long(v, 1, (long)IMAGE_MAX_PIXELS, &n))
        return cmd_error(cmd, SVET_EXIT_USAGE, "%s %s: a whole number of "
                         "pixels from 1 to %ld", max_pixels ? "--max-pixels"
                         : "SVET_MAX_PIXELS", v, (long)IMAGE_MAX_PIXELS);
    lim->max_pixels = (uint64_t)n;
    return SVET_EXIT_OK;
}

bool cmd_parse_seed(const char *s, unsigned long long *out)
{
    char *end;
    errno = 0;
    *out = strtoull(s, &end, 10);
    /* strtoull takes "-3" as 2^64 - 3: refuse the sign instead */
    return !errno && end != s && !*end && s[0] != '-';
}

bool cmd_parse_double(const char *s, double *out)
{
    char *end;
    *out = strtod(s, &end);
    return end != s && !*end && isfinite(*out);
}

int cmd_error(const char *cmd, int rc, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "svet %s: ", cmd);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    return rc;
}

int cmd_unknown_option(const char *cmd, const char *opt)
{
    return cmd_error(cmd, SVET_EXIT_USAGE,
                     "unknown option '%s' (svet %s --help)", opt, cmd);
}

int cmd_bad_value(const char *cmd, const char *opt, const char *value)
{
    return cmd_error(cmd, SVET_EXIT_USAGE, "bad value '%s' for %s", value,
                     opt);
}

const char *cmd_file_name(const char *cmd, const char *opt,
                          const char *value)
{
    if (*value)
        return value;
    cmd_error(cmd, SVET_EXIT_USAGE, "%s '': a file name cannot be empty", opt);
    return NULL;
}

char *cmd_replace_ext(const char *path, const char *ext)
{
    size_t n = strlen(path);
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    if (dot && (!slash || dot > slash))
        n = (size_t)(dot - path);
    char *out = malloc(n + strlen(ext) + 1);
    if (out) {
        memcpy(out, path, n);
        strcpy(out + n, ext);
    }
    return out;
}

void cmd_scene_opts_init(cmd_scene_opts_t *o)
{
    memset(o, 0, sizeof *o);
    o->threads = -1;
}

/* The scene options, which svet render and svet converge share. Returns
 * CMD_OPT_NONE when opt is none of them, else SVET_EXIT_OK or, after the
 * message, SVET_EXIT_USAGE. */
enum { CMD_OPT_NONE = -2 };
static bool scene_option_takes_value(const char *opt)
{
    return !strcmp(opt, "--threads") || !strcmp(opt, "--seed") ||
           !strcmp(opt, "--set");
}

static int scene_option(const char *cmd, const char *opt, const char *value,
                        cmd_scene_opts_t *o)
{
    if (!strcmp(opt, "--strict")) {
        o->strict = true;
    } else if (!strcmp(opt, "--threads")) {
        if (!cmd_parse_long(value, 0, SCENE_MAX_THREADS, &o->threads))
            return cmd_bad_value(cmd, opt, value);
    } else if (!strcmp(opt, "--seed")) {
        if (!cmd_parse_seed(value, &o->seed))
            return cmd_bad_value(cmd, opt, value);
        o->seed_set = true;
    } else if (!strcmp(opt, "--set")) {
        if (o->nsets == CMD_MAX_SETS)
            return cmd_error(cmd, SVET_EXIT_USAGE, "at most %d --set options",
                             CMD_MAX_SETS);
        o->sets[o->nsets++] = value;
    } else {
        return CMD_OPT_NONE;
    }
    return SVET_EXIT_OK;
}

static const cmd_option_t *find_option(const cmd_option_t *t, const char *a)
{
    for (; t->name; t++)
        if (!strcmp(a, t->name) || (t->alias && !strcmp(a, t->alias)))
            return t;
    return NULL;
}

int cmd_parse_options(const cmd_parser_t *p, int argc, char **argv)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        int rc;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            p->help(stdout);
            return SVET_EXIT_OK;
        }
        if (a[0] != '-' || (p->dash_positional && a[1] == '\0')) {
            if ((rc = p->positional(p->args, p->cmd, a)) != SVET_EXIT_OK)
                return rc;
            continue;
        }
        const cmd_option_t *o = find_option(p->opts, a);
        bool scene = !o && p->so && (!strcmp(a, "--strict") ||
                                     scene_option_takes_value(a));
        if (!o && !scene)
            return cmd_unknown_option(p->cmd, a);
        bool takes = o ? o->value : scene_option_takes_value(a);
        if (takes && !v) {
            if (p->needs)
                return cmd_error(p->cmd, SVET_EXIT_USAGE, "%s needs %s", a,
                                 p->needs);
            return cmd_error(p->cmd, SVET_EXIT_USAGE,
                             "%s needs a value (svet %s --help)", a, p->cmd);
        }
        if (!takes)
            v = NULL;
        else
            i++;
        char *at = o ? (char *)p->args + o->at : NULL;
        if (scene) {
            rc = scene_option(p->cmd, a, v, p->so);
        } else if (o->what == CMD_SET_TRUE) {
            *(bool *)(void *)at = true;
            rc = SVET_EXIT_OK;
        } else if (o->what == CMD_SET_TEXT) {
            *(const char **)(void *)at = v;
            rc = SVET_EXIT_OK;
        } else if (o->what == CMD_SET_FILE) {
            const char *f = cmd_file_name(p->cmd, a, v);
            if (f)
                *(const char **)(void *)at = f;
            rc = f ? SVET_EXIT_OK : SVET_EXIT_USAGE;
        } else {
            rc = o->call(p->args, p->cmd, a, v);
        }
        if (rc != SVET_EXIT_OK)
            return rc;
    }
    return CMD_RUN;
}

/* The mesh files the scene file names, recorded as the loader is called
 * (the loader has no context pointer, hence file scope). */
#define MAX_SCENE_INPUTS 256
static char *scene_inputs[MAX_SCENE_INPUTS];
static int nscene_inputs;

static svet_status record_mesh(const char *path, const xform_t *x,
                               scene_mesh_part_t **parts, int *nparts,
                               scene_warnings_t *warnings, svet_error *err)
{
    if (nscene_inputs < MAX_SCENE_INPUTS) {
        char *p = strdup(path);
        if (!p)
            return svet_error_set(err, SVET_ERR_NOMEM, "%s: out of memory",
                                  path);
        scene_inputs[nscene_inputs++] = p;
    }
    return scene_features_all()->mesh(path, x, parts, nparts, warnings, err);
}

int cmd_scene_load(const char *cmd, scene_t *s, const char *path,
                   const cmd_scene_opts_t *o)
{
    /* every part, with the mesh loader wrapped to note its files; static:
     * the scene keeps the pointer */
    static scene_features_t features;
    features = *scene_features_all();
    features.mesh = record_mesh;
    while (nscene_inputs > 0)
        free(scene_inputs[--nscene_inputs]);
    svet_error err;
    svet_error_clear(&err);
    scene_init(s);
    if (scenefile_read_with(s, path, &features, &err) != SVET_OK)
        return cmd_error(cmd, SVET_EXIT_INPUT, "%s", err.msg);
    const scene_warnings_t *w = &s->warnings;
    for (long i = 0; i < w->n && i < SCENE_MAX_WARNINGS; i++)
        cmd_error(cmd, 0, "%s", w->msg[i]);
    if (w->n > SCENE_MAX_WARNINGS)
        cmd_error(cmd, 0, "%s: %ld more warnings", path,
                  w->n - SCENE_MAX_WARNINGS);
    if (o->strict && w->n > 0)
        return cmd_error(cmd, SVET_EXIT_INPUT, "%s: %ld warning%s, and "
                         "--strict makes warnings errors", path, w->n,
                         w->n == 1 ? "" : "s");
    for (int i = 0; i < o->nsets; i++)
        if (scenefile_override(s, o->sets[i], &err) != SVET_OK)
            return cmd_error(cmd, SVET_EXIT_USAGE, "%s", err.msg);
    if (o->threads >= 0)
        s->render.threads = (int)o->threads;
    if (o->seed_set)
        s->render.seed = o->seed;
    return SVET_EXIT_OK;
}

int cmd_check_outputs(const char *cmd, const cmd_file_t *out, int nout,
                      const cmd_file_t *in, int nin)
{
    for (int i = 0; i < nout; i++) {
        if (!out[i].path)
            continue;
        for (int j = 0; j < i + nin + nscene_inputs; j++) {
            /* the outputs before this one, the inputs, the meshes */
            cmd_file_t b = j < i         ? out[j]
                         : j < i + nin   ? in[j - i]
                                         : (cmd_file_t){
                                               scene_inputs[j - i - nin],
                                               "a mesh file of the scene" };
            if (b.path && fileio_same_file(out[i].path, b.path))
                return cmd_error(cmd, SVET_EXIT_USAGE,
                                 "%s '%s' is the same file as %s '%s': "
                                 "refusing to overwrite it (nothing was "
                                 "written)", out[i].what, out[i].path,
                                 b.what, b.path);
        }
    }
    return SVET_EXIT_OK;
}
