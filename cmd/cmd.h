/*
 * cmd.h - the subcommands of the svet command (cmd/svet.c dispatches) and
 * their exit codes, which `svet --help` documents.
 */
#ifndef SVET_CMD_H
#define SVET_CMD_H

#include <stdio.h>

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

/* svet render SCENE [options]: see cmd_render_help. */
int cmd_render(int argc, char **argv);
void cmd_render_help(FILE *f);

/* svet diff A B [options]: see cmd_diff_help (cmd/cmd_diff.c). */
int cmd_diff(int argc, char **argv);
void cmd_diff_help(FILE *f);

/* svet converge SCENE --ref REF.exr [options], or --report CSV...: see
 * cmd_converge_help (cmd/cmd_converge.c). */
int cmd_converge(int argc, char **argv);
void cmd_converge_help(FILE *f);

#endif
