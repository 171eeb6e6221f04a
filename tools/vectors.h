/*
 * vectors.h - how the programs tools/vectors_*.c write their CSV files
 * (tests/vectors/README.md): each file is written to DIR/NAME.tmp and
 * renamed over DIR/NAME when complete, so that a failed run leaves the
 * previous file whole. Header-only: each program is built from its own .c.
 */
#ifndef SVET_TOOLS_VECTORS_H
#define SVET_TOOLS_VECTORS_H

#include <stdio.h>
#include <stdlib.h>

/* Open DIR/NAME.tmp for writing. On failure prints why and exits 1. */
static inline FILE *vectors_open(const char *dir, const char *name)
{
    char tmp[1100];
    snprintf(tmp, sizeof tmp, "%s/%s.tmp", dir, name);
    FILE *f = fopen(tmp, "w");
    if (!f) {
        perror(tmp);
        exit(1);
    }
    return f;
}

/* Close f (from vectors_open(dir, name)) and rename DIR/NAME.tmp to
 * DIR/NAME. On failure prints why and exits 1. */
static inline void vectors_close(FILE *f, const char *dir, const char *name)
{
    char tmp[1100], path[1100];
    snprintf(tmp, sizeof tmp, "%s/%s.tmp", dir, name);
    snprintf(path, sizeof path, "%s/%s", dir, name);
    if (fclose(f) != 0 || rename(tmp, path) != 0) {
        perror(path);
        exit(1);
    }
}

#endif
