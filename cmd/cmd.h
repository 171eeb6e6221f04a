/*
 * cmd.h - the subcommands of the svet command (cmd/svet.c dispatches) and
 * their exit codes, which `svet --help` documents.
 */
#ifndef SVET_CMD_H
#define SVET_CMD_H

#include <stdbool.h>
#include <stdio.h>

#include "cmdutil.h"
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
    SVET_EXIT_DIFFERENT = 5    /* svet diff --fail-above: the images
                                  differ by more than the threshold */
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
    cmd_scene_opts_t so;         /* --threads, --seed, --set */
} cmd_render_args_t;
int cmd_render_parse(int argc, char **argv, cmd_render_args_t *a);
int cmd_render(int argc, char **argv);
void cmd_render_help(FILE *f);

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
    bool time_mode, have_list, no_plot, quiet, report;
    cmd_scene_opts_t so;
} cmd_converge_args_t;
int cmd_converge_parse(int argc, char **argv, cmd_converge_args_t *a);
int cmd_converge(int argc, char **argv);
void cmd_converge_help(FILE *f);

#endif
