/*
 * cmdutil.h - what the subcommands of cmd/ share: the clock, numbers read
 * from the command line with their range checks, the usage messages, file
 * names, and the scene options of svet render and svet converge
 * (--threads, --seed, --set). Tests: tests/cmd/test_cmd_render.c,
 * tests/stats/test_converge.c, tests/cmd/test_svet.c (end to end).
 */
#ifndef SVET_CMDUTIL_H
#define SVET_CMDUTIL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "io/image.h"
#include "render/scene.h"

#if defined(__GNUC__)
#define CMD_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define CMD_PRINTF(f, a)
#endif

/* Seconds on the monotonic clock, from an arbitrary origin. This function
 * can't fail. */
double cmd_now(void);

/* Seconds of CPU time the process has used, all its threads together
 * (CLOCK_PROCESS_CPUTIME_ID). This function can't fail. */
double cmd_cpu_now(void);

/* The whole of s as a decimal integer in [lo, hi], into *out. Returns
 * false (and leaves *out alone) on anything else: empty, trailing bytes,
 * overflow, out of range. */
bool cmd_parse_long(const char *s, long lo, long hi, long *out);

/* The whole of s as a non-negative decimal seed, into *out. Returns false
 * (*out undefined) on a sign, trailing bytes or overflow. */
bool cmd_parse_seed(const char *s, unsigned long long *out);

/* The whole of s as a finite number, into *out. Returns false (*out
 * undefined) on empty text, trailing bytes, NaN or infinity; the caller
 * checks the range. */
bool cmd_parse_double(const char *s, double *out);

/* Print "svet CMD: <message>" and a newline to stderr; returns rc, so that
 * a caller can `return cmd_error("render", SVET_EXIT_USAGE, ...)`. */
int cmd_error(const char *cmd, int rc, const char *fmt, ...) CMD_PRINTF(3, 4);

/* The usage errors every subcommand reports alike: an option it does not
 * know, a value out of range. Each prints one line and returns
 * SVET_EXIT_USAGE. */
int cmd_unknown_option(const char *cmd, const char *opt);
int cmd_bad_value(const char *cmd, const char *opt, const char *value);

/* The limits of an image read from a file: `max_pixels` (the value of
 * --max-pixels, or NULL when not given), else the environment variable
 * SVET_MAX_PIXELS, else IMAGE_READ_MAX_PIXELS (image.h). A value must be
 * a whole number from 1 to IMAGE_MAX_PIXELS. Returns SVET_EXIT_OK, or
 * SVET_EXIT_USAGE after printing why the value was refused. */
int cmd_read_limits(const char *cmd, const char *max_pixels,
                    image_read_limits_t *lim);
/* value as the file name given to opt: value itself, or NULL after
 * printing that a file name cannot be empty. */
const char *cmd_file_name(const char *cmd, const char *opt,
                          const char *value);

/* path with its extension (the last '.' after the last '/', if any)
 * replaced by ext: ("a/b.exr", ".png") -> "a/b.png", ("a/b", "-var.exr")
 * -> "a/b-var.exr". Malloc'ed; NULL when out of memory. */
char *cmd_replace_ext(const char *path, const char *ext);

/* --set options kept for scenefile_override, at the most. */
#define CMD_MAX_SETS 64

/* The scene options of svet render and svet converge. */
typedef struct {
    long threads;                   /* --threads N; -1: the scene's */
    bool seed_set;                  /* --seed given */
    unsigned long long seed;        /* --seed N */
    const char *sets[CMD_MAX_SETS]; /* --set KEY=VALUE, in order */
    int nsets;
    bool strict;                    /* --strict: warnings are errors */
} cmd_scene_opts_t;

/* No options given. This function can't fail. */
void cmd_scene_opts_init(cmd_scene_opts_t *o);

/* Read the scene file at path into s (scene_init'ed here), print its
 * warnings on stderr (the first SCENE_MAX_WARNINGS, then how many more),
 * apply the --set overrides in order, then --threads and --seed. Returns
 * SVET_EXIT_OK, or after printing the error SVET_EXIT_INPUT (the file is
 * missing or malformed, or has warnings and o->strict is set) or
 * SVET_EXIT_USAGE (an override was refused); s may then still hold a
 * scene: scene_free it either way. */
int cmd_scene_load(const char *cmd, scene_t *s, const char *path,
                   const cmd_scene_opts_t *o);

/* A file a command reads or writes, and what it is to the user ("the
 * EXR output", "the scene file"), for the messages. */
typedef struct {
    const char *path;
    const char *what;
} cmd_file_t;

/* Refuse outputs that would overwrite each other or an input: each
 * output is compared with every other output, every input in `in`, and
 * every file the last cmd_scene_load() read besides the scene file (its
 * meshes), by file identity (fileio_same_file: the same file under any
 * name, or the same name in the same directory when it does not exist
 * yet). NULL paths are skipped. Returns SVET_EXIT_OK, or after printing
 * which two collide SVET_EXIT_USAGE; nothing has been written then. */
int cmd_check_outputs(const char *cmd, const cmd_file_t *out, int nout,
                      const cmd_file_t *in, int nin);

/* The option table of a subcommand, read by cmd_parse_options. An entry
 * names an option (and its other spelling, or NULL), whether it takes the
 * next argument as its value, and what it does: sets the bool at offset
 * `at` of the command's argument struct (CMD_SET_TRUE), stores the value
 * there as a const char * (CMD_SET_TEXT; CMD_SET_FILE refuses an empty
 * one), or calls `call` (CMD_CALL), which returns SVET_EXIT_OK to go on
 * or, after printing why, the exit code. */
typedef enum { CMD_SET_TRUE, CMD_SET_TEXT, CMD_SET_FILE, CMD_CALL } cmd_opt_do_t;
typedef struct {
    const char *name, *alias;
    bool value;
    cmd_opt_do_t what;
    size_t at;
    int (*call)(void *args, const char *cmd, const char *opt,
                const char *value);
} cmd_option_t;

/* A subcommand's command line: its name (for the messages), its options
 * (ending with a NULL name), its argument struct, the handler of the
 * other arguments (`positional`, which returns as `call` does), its help
 * text (-h, --help), and what it shares: so, if not NULL, takes the scene
 * options --threads N, --seed N, --set KEY=VALUE and --strict. With
 * dash_positional, "-" alone is an argument, not an option. `needs` is
 * the message's end for an option without its value (default "a value
 * (svet CMD --help)"). */
typedef struct {
    const char *cmd;
    const cmd_option_t *opts;
    void *args;
    int (*positional)(void *args, const char *cmd, const char *arg);
    void (*help)(FILE *f);
    cmd_scene_opts_t *so;
    bool dash_positional;
    const char *needs;
} cmd_parser_t;

/* Read argv[1..argc-1] by p's table, left to right. Returns CMD_RUN
 * (cmd.h) when every argument was taken, SVET_EXIT_OK after printing the
 * help, or an exit code after printing the first problem: an unknown
 * option, an option at the end without its value, or what a handler
 * refused. */
int cmd_parse_options(const cmd_parser_t *p, int argc, char **argv);

#endif
