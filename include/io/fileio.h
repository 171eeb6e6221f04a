/*
 * fileio.h - safe output for every svet writer (PFM, PPM, PNG, EXR, CSV):
 * the data goes to a temporary file in the target's directory, which
 * replaces the target by rename() only once everything is written and
 * flushed to disk. A failed or interrupted write therefore never destroys
 * an earlier output; at worst it leaves a stray "<name>.tmp-*" file.
 * The read side is one call, fileio_open_read(), that opens regular files
 * only.
 * POSIX (open, fsync, rename). Tests: tests/io/test_fileio.c
 */
#ifndef SVET_FILEIO_H
#define SVET_FILEIO_H

#include <stdio.h>
#include "core/error.h"

typedef struct {
    FILE *f;    /* write the data here (or to fileno(f) with pwrite) */
    char *path; /* the name the file will have */
    char *tmp;  /* the temporary name it has until fileio_commit() */
} fileio_t;

/* Create a new temporary file beside `path` ("<path>.tmp-<pid>-<n>", mode
 * 0666 less the umask, like fopen) and open it for binary writing in
 * out->f. out is zeroed first, so fileio_abort() is always safe on it.
 * Fails with SVET_ERR_IO (message: the path and the system's reason) when
 * the directory does not exist or is not writable; SVET_ERR_NOMEM when
 * malloc fails. */
svet_status fileio_begin(fileio_t *out, const char *path, svet_error *err);

/* Finish: flush, check that every write succeeded, fsync, close, and
 * rename the temporary file to the target, atomically replacing any file
 * there. On any failure the temporary file is removed, the target is left
 * as it was, and SVET_ERR_IO is returned with the reason. Either way the
 * fileio_t is released (a later fileio_abort() does nothing). */
svet_status fileio_commit(fileio_t *out, svet_error *err);

/* Give up: close and remove the temporary file, leaving the target as it
 * was. Safe after fileio_commit(), after a failed fileio_begin() and on a
 * zeroed fileio_t. This function can't fail. */
void fileio_abort(fileio_t *out);

/* Write a whole text file through the same path (for CSV and Markdown):
 * fileio_begin, fputs(text), fileio_commit. Fails as they do. */
svet_status fileio_write_text(const char *path, const char *text,
                              svet_error *err);

/* Open path for binary reading into *f, for every reader of svet (scene
 * files, images, OBJ files): a directory, FIFO, device or socket is
 * refused with a message naming the file and what it is ("is a
 * directory, not a file"), without blocking on a FIFO that has no writer
 * and without reading from a device such as /dev/zero for ever. *f is
 * NULL on failure. Fails with SVET_ERR_IO (cannot open: the system's
 * reason; not a regular file), SVET_ERR_NOMEM. */
svet_status fileio_open_read(const char *path, FILE **f, svet_error *err);

#endif
