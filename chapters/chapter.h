/*
 * chapter.h - what the chapter programs share: the command line (--help,
 * options that take a value, at most one output directory; anything else
 * is refused with exit status 2 before a file is written), the output
 * directory, and the CSV files that the gnuplot scripts beside each
 * program draw (`make figures`, chapters/README.md). Header-only, so a
 * program's one cc line needs no extra file; only the programs include it.
 * Tests: tests/chapters/test_chapters.c
 */
#ifndef SVET_CHAPTER_H
#define SVET_CHAPTER_H

#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L /* mkdir */
#endif
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* Exit statuses: 0 done (or --help), 1 a failure while running, 2 a
 * command line that was refused. */
enum { CHAPTER_EXIT_FAIL = 1, CHAPTER_EXIT_USAGE = 2 };

/* One option that takes a number: --name VALUE, accepted in [min, max]. */
typedef struct {
    const char *name;    /* "--samples" */
    const char *metavar; /* "N", for the usage line */
    const char *help;    /* one line for --help */
    double *value;       /* where the number goes; holds the default */
    double min, max;     /* the accepted range, inclusive */
} chapter_opt_t;

/* The program's command line. */
typedef struct {
    const char *prog;         /* "ch01_brdf" */
    const char *what;         /* a sentence or two for --help */
    const char *dir_default;  /* the output directory when none is given */
    const chapter_opt_t *opts;
    int nopts;
} chapter_cli_t;

static inline void chapter_usage(const chapter_cli_t *c, FILE *f)
{
    fprintf(f, "usage: %s [OUTDIR]", c->prog);
    for (int i = 0; i < c->nopts; i++)
        fprintf(f, " [%s %s]", c->opts[i].name, c->opts[i].metavar);
    fprintf(f, "\n%s\n\n  OUTDIR%*s where the files go (default %s; made if "
               "missing)\n", c->what, 14, "", c->dir_default);
    for (int i = 0; i < c->nopts; i++) {
        const chapter_opt_t *o = &c->opts[i];
        int pad = 20 - (int)(strlen(o->name) + 1 + strlen(o->metavar));
        fprintf(f, "  %s %s%*s %s (default %.10g)\n", o->name, o->metavar,
                pad > 0 ? pad : 0, "", o->help, *o->value);
    }
    fprintf(f, "  -h, --help%*s this text\n", 10, "");
}

/*
 * Read argv into the options and *dir. Returns -1 when the program should
 * go on, else the status to exit with: 0 after printing the usage for
 * -h/--help, CHAPTER_EXIT_USAGE after a message on stderr for an unknown
 * option, a missing or bad value, or a second directory. An argument that
 * starts with '-' is always taken for an option, so no file is ever
 * written into a directory named like one.
 */
static inline int chapter_parse(const chapter_cli_t *c, int argc, char **argv,
                                const char **dir)
{
    *dir = c->dir_default;
    int have_dir = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            chapter_usage(c, stdout);
            return 0;
        }
        if (a[0] != '-' && a[0] != '\0') {
            if (have_dir) {
                fprintf(stderr, "%s: one output directory only: '%s', then "
                                "'%s'\n(%s --help for the usage)\n",
                        c->prog, *dir, a, c->prog);
                return CHAPTER_EXIT_USAGE;
            }
            *dir = a;
            have_dir = 1;
            continue;
        }
        const chapter_opt_t *o = NULL;
        for (int k = 0; k < c->nopts && !o; k++)
            if (!strcmp(a, c->opts[k].name))
                o = &c->opts[k];
        if (!o) {
            fprintf(stderr, "%s: unknown option '%s'\n(%s --help for the "
                            "usage)\n", c->prog, a, c->prog);
            return CHAPTER_EXIT_USAGE;
        }
        if (i + 1 >= argc) {
            fprintf(stderr, "%s: %s needs a value %s\n", c->prog, a,
                    o->metavar);
            return CHAPTER_EXIT_USAGE;
        }
        char *end;
        errno = 0;
        double v = strtod(argv[++i], &end);
        if (end == argv[i] || *end || errno || !(v >= o->min && v <= o->max)) {
            fprintf(stderr, "%s: %s wants a number from %g to %g, not '%s'\n",
                    c->prog, a, o->min, o->max, argv[i]);
            return CHAPTER_EXIT_USAGE;
        }
        *o->value = v;
    }
    return -1;
}

/* mkdir -p dir. Returns 0, or 1 after a message on stderr. */
static inline int chapter_make_dir(const char *prog, const char *dir)
{
    char buf[1024];
    size_t n = strlen(dir);
    if (n == 0 || n >= sizeof buf) {
        fprintf(stderr, "%s: bad output directory '%s'\n", prog, dir);
        return 1;
    }
    memcpy(buf, dir, n + 1);
    for (size_t i = 1; i <= n; i++) {
        if (buf[i] != '/' && buf[i] != '\0')
            continue;
        char ch = buf[i];
        buf[i] = '\0';
        if (mkdir(buf, 0777) != 0 && errno != EEXIST) {
            fprintf(stderr, "%s: cannot make %s: %s\n", prog, buf,
                    strerror(errno));
            return 1;
        }
        buf[i] = ch;
    }
    return 0;
}

/* chapter_parse, then chapter_make_dir: what a program's main() does
 * first. Returns -1 when the program should go on, else the status to
 * exit with (1 when the directory cannot be made). */
static inline int chapter_begin(const chapter_cli_t *c, int argc, char **argv,
                                const char **dir)
{
    int rc = chapter_parse(c, argc, argv, dir);
    if (rc < 0 && chapter_make_dir(c->prog, *dir) != 0)
        rc = CHAPTER_EXIT_FAIL;
    return rc;
}

/* A text file written under a temporary name and renamed when complete,
 * so that a failed run never leaves half a file under the real name. */
typedef struct {
    FILE *f;
    char path[1024], tmp[1040];
} chapter_file_t;

/* Open dir/name for writing. Returns the stream, or NULL after a message
 * on stderr. */
static inline FILE *chapter_open(chapter_file_t *cf, const char *prog,
                                 const char *dir, const char *name)
{
    snprintf(cf->path, sizeof cf->path, "%s/%s", dir, name);
    snprintf(cf->tmp, sizeof cf->tmp, "%s.tmp", cf->path);
    cf->f = fopen(cf->tmp, "w");
    if (!cf->f)
        fprintf(stderr, "%s: %s: %s\n", prog, cf->tmp, strerror(errno));
    return cf->f;
}

/* Close and rename into place. Returns 0, or 1 after a message on stderr
 * (the temporary file is removed). */
static inline int chapter_close(chapter_file_t *cf, const char *prog)
{
    if (!cf->f)
        return 1;
    int bad = ferror(cf->f);
    bad |= fclose(cf->f) != 0;
    cf->f = NULL;
    if (bad || rename(cf->tmp, cf->path) != 0) {
        fprintf(stderr, "%s: cannot write %s\n", prog, cf->path);
        remove(cf->tmp);
        return 1;
    }
    printf("wrote %s\n", cf->path);
    return 0;
}

#endif
