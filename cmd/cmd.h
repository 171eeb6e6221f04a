/*
 * cmd.h - the subcommands of the svet command (cmd/svet.c dispatches) and
 * their exit codes, which `svet --help` documents.
 */
#ifndef SVET_CMD_H
#define SVET_CMD_H

#include <stdbool.h>
#include <stdio.h>

#include "cmdutil.h"
#include "render/render.h"
#include "stats/converge.h"
#include "stats/imgcompare.h"

/* Exit codes of every subcommand. */
enum {
    SVET_EXIT_OK = 0,          /* done */
    SVET_EXIT_USAGE = 1,       /* bad command line */
    SVET_EXIT_INPUT = 2,       /* an input file is missing or malformed */
    SVET_EXIT_OUTPUT = 3,      /* an output could not be written */
    SVET_EXIT_INTERRUPTED = 4, /* stopped by SIGINT/SIGTERM; what was
                                  rendered so far was written */
    SVET_EXIT_DIFFERENT = 5,   /* svet diff --fail-above: the images
                                  differ by more than the threshold */
    SVET_EXIT_RENDER = 6       /* svet render: a pass failed (out of
                                  memory, or a rendering method's pass,
                                  e.g. ppm's photon maps); nothing of
                                  that pass was written */
};

/* What a cmd_*_parse() returns when the command line is good and the
 * command is to run; any other value is the exit code to return at once
 * (SVET_EXIT_OK after --help, SVET_EXIT_USAGE after the message). */
#define CMD_RUN (-1)

/* svet render SCENE [options]: see cmd_render_help. */
typedef struct {
    const char *scene;           /* SCENE */
    const char *exr, *png, *var; /* -o, --png, --variance, or NULL */
    long spp, passes;            /* --spp, --passes; -1 when not given */
    double time_limit;           /* --time-limit; -1 when not given */
    bool checkpoint, quiet, half;
    long from, to;               /* --samples FROM:TO; to 0 when not given */
    int crop[4];                 /* --crop X0:X1,Y0:Y1 */
    bool cropped, part;          /* --crop given; --crop or --samples */
    bool resume;                 /* --resume */
    const char *save_prepass;    /* --save-prepass FILE, or NULL */
    const char *load_prepass;    /* --load-prepass FILE, or NULL */
    long frame_a, frame_b;       /* --frame K (K:K+1) or --frames A:B, the
                                    frames A..B-1; frame_b 0: not given */
    bool frames_range;           /* the frames came as --frames A:B */
    bool frame_count;            /* --frame-count */
    cmd_scene_opts_t so;         /* --threads, --seed, --set */
} cmd_render_args_t;
/* A part of a split render (svet render --samples/--crop, svet merge):
 * samples [from, to) of the pixels [x0, x1) x [y0, y1) of a width x height
 * image, of the scene whose identity is `identity`, in the file path. */
typedef struct {
    const char *path;
    unsigned long long identity;
    int width, height, x0, x1, y0, y1;
    long from, to;
} cmd_part_t;

/* The identity of a scene: FNV-1a (64 bits) of the scene file's bytes,
 * its seed, size, frame (of an animation) and --set overrides; parts of different identities are
 * never merged. Fails with SVET_ERR_IO when the file cannot be read. */
svet_status cmd_part_identity(const char *scene_path, const scene_t *s,
                              const cmd_scene_opts_t *so,
                              unsigned long long *id, svet_error *err);

/* One pixel of a part file: its exact sums (image.h), counts added and
 * dropped. */
typedef struct {
    image_fixed_t sum[3], sum2[3];
    uint64_t count, nonfinite;
} cmd_part_pixel_t;

/* A part file read back (FILE.exr.part): its header, tone map, EXR pixel
 * type, and the pixels of the crop, row by row. */
typedef struct {
    cmd_part_t p;
    int tm_op, tm_curve;
    double tm[5];
    bool half;                   /* the part's EXR was --half */
    cmd_part_pixel_t *v;
} cmd_part_file_t;

/* An exact sum in a part file: a signed hexadecimal integer, no prefix
 * ("-" and at most 48 digits). cmd_fixed_write prints one; cmd_fixed_parse
 * reads the word s, false if it is not one. */
void cmd_fixed_write(FILE *f, const image_fixed_t *v);
bool cmd_fixed_parse(const char *s, image_fixed_t *v);

/* Read exr's part file into q (q->v malloc'ed: free it). Returns
 * SVET_EXIT_OK, or SVET_EXIT_INPUT after printing why. */
int cmd_part_read(const char *exr, cmd_part_file_t *q);

/* The outputs of svet render and svet merge. */
typedef struct {
    const char *exr, *png, *var;
    bool half;
    const cmd_part_t *part;      /* write a part file too, or NULL */
} outputs_t;

/* Write the EXR, the PNG, the variance (if o->var) and the part file (if
 * o->part) of what r holds, as one set (fileio.h). r needs only its
 * camera's size, acc and sum2; s only its tonemap. */
svet_status cmd_render_write(const render_t *r, const scene_t *s,
                             const outputs_t *o, svet_error *err);

int cmd_render_parse(int argc, char **argv, cmd_render_args_t *a);
int cmd_render(int argc, char **argv);
void cmd_render_help(FILE *f);

/* svet merge PART.exr ... -o OUT.exr: see cmd_merge_help (cmd/cmd_merge.c). */
int cmd_merge(int argc, char **argv);
void cmd_merge_help(FILE *f);

/* svet diff A B [options]: see cmd_diff_help (cmd/cmd_diff.c). */
typedef struct {
    const char *paths[2];   /* A and B */
    const char *err_path;   /* --error-image, or NULL */
    const char *max_pixels; /* --max-pixels, or NULL */
    int metrics[6], nmetrics; /* --metric, in order */
    imgcompare_kind_t kind; /* --error */
    double peak, eps, fail_above;
    bool have_peak, have_fail;
} cmd_diff_args_t;
int cmd_diff_parse(int argc, char **argv, cmd_diff_args_t *a);
int cmd_diff(int argc, char **argv);
void cmd_diff_help(FILE *f);

/* svet converge SCENE --ref REF.exr [options], or --report CSV..., or
 * --ztest: see cmd_converge_help (cmd/cmd_converge.c). */
#define CMD_CONVERGE_MAX_POINTS 64
#define CMD_CONVERGE_MAX_FILES 256
typedef struct {
    const char *ref, *ref_var, *out_dir, *label, *script;
    const char *files[CMD_CONVERGE_MAX_FILES]; /* SCENE, or the CSVs */
    int nfiles, nlist;
    double list[CMD_CONVERGE_MAX_POINTS]; /* --spp-list or --time-list */
    double T, E, zspp, ref_spp;           /* --time, --error, --spp, --ref-spp */
    const char *ztest_img, *ztest_var, *pvalue;
    const char *max_pixels;               /* --max-pixels, or NULL */
    converge_metric metric;               /* --metric */
    converge_clock clock;                 /* --clock */
    bool time_mode, have_list, no_plot, quiet, report;
    cmd_scene_opts_t so;
} cmd_converge_args_t;
int cmd_converge_parse(int argc, char **argv, cmd_converge_args_t *a);
int cmd_converge(int argc, char **argv);
void cmd_converge_help(FILE *f);

#endif
