/*
 * error.h - how svet reports failure. Functions that touch resources (read
 * a scene, allocate, write an image) return a status and fill an svet_error
 * with a message that names the file and line; only main() prints it.
 * Math kernels (intersect, evaluate, sample) cannot fail and never use this.
 * Tests: tests/core/test_error.c
 */
#ifndef SVET_ERROR_H
#define SVET_ERROR_H

#include <stddef.h>

/* Status codes. main() maps them to the exit codes of the svet command. */
typedef enum {
    SVET_OK = 0,
    SVET_ERR_IO = 1,      /* a file cannot be opened, read or written */
    SVET_ERR_PARSE = 2,   /* malformed input: scene, OBJ, image header */
    SVET_ERR_RANGE = 3,   /* a value out of its domain: NaN, negative size */
    SVET_ERR_NOMEM = 4,   /* allocation failed, or a size would overflow */
    SVET_ERR_UNSUPPORTED = 5 /* valid input that svet does not handle */
} svet_status;

#define SVET_ERROR_LEN 512

typedef struct {
    svet_status status;
    char msg[SVET_ERROR_LEN]; /* "scenes/cbox.scn:14:3: unknown material 'whte'" */
} svet_error;

/* Record status and a printf-style message in err (which may be NULL) and
 * return status, so that a failing function can end with
 *     return svet_error_set(err, SVET_ERR_IO, "%s: cannot open", path);
 * A longer message is truncated. This function can't fail. */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
svet_status svet_error_set(svet_error *err, svet_status status,
                           const char *fmt, ...);

/* Put "prefix: " before the message already in err, e.g. the name of the
 * file being read when a lower level reported only the problem. */
void svet_error_prefix(svet_error *err, const char *prefix);

/* Reset err to SVET_OK and an empty message. */
void svet_error_clear(svet_error *err);

/* A short English name of a status: "I/O error", "parse error", ... */
const char *svet_status_name(svet_status status);

#endif
