/*
 * fileio.h - safe output for every svet writer (PFM, PPM, PNG, EXR, CSV):
 * the data goes to a temporary file in the target's directory, which
 * replaces the target by rename() only once everything is written and
 * flushed to disk. A failed or interrupted write therefore never destroys
 * an earlier output; a killed one leaves a "<name>.tmp-<host>-<pid>-<n>"
 * file, which the next write of <name> on that host removes. Several
 * outputs of one result go through a set (fileio_set_t), renamed only
 * when all are written. The read side is one call, fileio_open_read(),
 * that opens regular files only. POSIX (open, fsync, rename, fcntl
 * locks). Tests: tests/io/test_fileio.c
 */
#ifndef SVET_FILEIO_H
#define SVET_FILEIO_H

#include <stdbool.h>
#include <stdio.h>
#include "core/error.h"

typedef struct {
    FILE *f;    /* write the data here (or to fileno(f) with pwrite) */
    char *path; /* the name the file will have */
    char *tmp;  /* the temporary name it has until fileio_commit() */
} fileio_t;

/* Create a new temporary file beside `path` ("<path>.tmp-<host>-<pid>-<n>",
 * mode 0666 less the umask, like fopen; write-locked while it is written)
 * and open it for binary writing in out->f. out is zeroed first, so
 * fileio_abort() is always safe on it. First removes the temporary files
 * of `path` that killed writers left: those of this host whose process
 * is gone and whose lock is free (fileio.c says why all three). Fails
 * with SVET_ERR_IO (message: the path and the reason) when the name is
 * empty, when a directory, a device, a FIFO or a read-only file (no write
 * permission bit, or not writable by us; as cp refuses it) is in the
 * target's place, or when the directory does not exist or is not
 * writable; SVET_ERR_NOMEM when malloc fails. */
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

/* At most this many files in one set. */
#define FILEIO_SET_MAX 8

/* Outputs that replace their targets together: begin each, write each,
 * then commit the set. Every file is written, flushed and closed before
 * the first rename, so a failure while writing any of them (a full disk,
 * a file size limit) leaves every target as it was: the old files stay
 * a matching set. */
typedef struct {
    fileio_t file[FILEIO_SET_MAX];
    int n;
} fileio_set_t;

/* An empty set. This function can't fail. */
void fileio_set_init(fileio_set_t *set);

/* Begin one more file of the set, as fileio_begin(), and point *out at
 * it (write to (*out)->f; do not commit or abort it alone). Fails as
 * fileio_begin() does, or with SVET_ERR_RANGE past FILEIO_SET_MAX; the
 * files begun before are still in the set, to commit or abort. */
svet_status fileio_set_begin(fileio_set_t *set, const char *path,
                             fileio_t **out, svet_error *err);

/* Finish every file of the set (flush, check, fsync, close), and only
 * when all succeeded rename each over its target, in the order begun. On
 * a failure before the renames every temporary file is removed and every
 * target is unchanged (SVET_ERR_IO, naming the file). Should a rename
 * itself fail after an earlier one succeeded (fileio_begin checked each
 * target, so this is rare), the message lists the files already
 * replaced. The set is empty afterwards either way. */
svet_status fileio_set_commit(fileio_set_t *set, svet_error *err);

/* Give the whole set up: every temporary file removed, every target as it
 * was. Safe on an empty or committed set. This function can't fail. */
void fileio_set_abort(fileio_set_t *set);

/* Whether the paths a and b name one file: for files that exist, the same
 * device and inode (so "x.exr", "./x.exr", "../d/x.exr" and a link to it
 * are one); for a name not yet there, the same existing directory and the
 * same rest of the name. This function can't fail (out of memory it
 * compares the names). */
bool fileio_same_file(const char *a, const char *b);

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
