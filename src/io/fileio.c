/*
 * fileio.c - write to a temporary file, then rename() over the target;
 * open an input, refusing what is not a regular file.
 * rename() within one directory is atomic on POSIX file systems: a reader
 * sees the old file or the new one, never half of either. fsync() before
 * the rename keeps a crash right after it from leaving an empty file.
 * Tests: tests/io/test_fileio.c
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L /* open, fsync, fdopen, getpid: POSIX */
#endif
#include "io/fileio.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char *dup_string(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d)
        memcpy(d, s, n);
    return d;
}

static void release(fileio_t *out)
{
    free(out->path);
    free(out->tmp);
    memset(out, 0, sizeof *out);
}

svet_status fileio_begin(fileio_t *out, const char *path, svet_error *err)
{
    memset(out, 0, sizeof *out);
    size_t cap = strlen(path) + 64;
    out->path = dup_string(path);
    out->tmp = malloc(cap);
    if (!out->path || !out->tmp) {
        release(out);
        return svet_error_set(err, SVET_ERR_NOMEM, "%s: out of memory", path);
    }
    /* O_EXCL makes the name ours alone; the counter moves past a stray
     * file left by an earlier crash of a process with the same pid. */
    static _Atomic unsigned counter;
    int fd = -1, e = 0;
    for (int attempt = 0; attempt < 100 && fd < 0; attempt++) {
        snprintf(out->tmp, cap, "%s.tmp-%ld-%u", path, (long)getpid(),
                 counter++);
        fd = open(out->tmp, O_WRONLY | O_CREAT | O_EXCL, 0666);
        e = errno;
        if (fd < 0 && e != EEXIST)
            break;
    }
    if (fd < 0) {
        svet_error_set(err, SVET_ERR_IO, "%s: cannot create a file there: %s",
                       path, strerror(e));
        release(out);
        return SVET_ERR_IO;
    }
    out->f = fdopen(fd, "wb");
    if (!out->f) {
        e = errno;
        close(fd);
        unlink(out->tmp);
        svet_error_set(err, SVET_ERR_IO, "%s: %s", path, strerror(e));
        release(out);
        return SVET_ERR_IO;
    }
    return SVET_OK;
}

svet_status fileio_commit(fileio_t *out, svet_error *err)
{
    if (!out->f) {
        release(out);
        return svet_error_set(err, SVET_ERR_IO, "fileio_commit without a "
                              "file");
    }
    const char *what = NULL;
    int e = 0;
    /* Each step records the first failure; later steps still run so that
     * the descriptor is closed exactly once. */
    if (fflush(out->f) != 0 || ferror(out->f)) {
        what = "cannot write";
        e = errno;
    } else if (fsync(fileno(out->f)) != 0 && errno != EINVAL) {
        /* EINVAL: a file system (or pipe) without fsync; nothing to do. */
        what = "cannot flush to disk";
        e = errno;
    }
    if (fclose(out->f) != 0 && !what) {
        what = "cannot close";
        e = errno;
    }
    out->f = NULL;
    if (!what && rename(out->tmp, out->path) != 0) {
        what = "cannot replace";
        e = errno;
    }
    if (what) {
        unlink(out->tmp);
        svet_error_set(err, SVET_ERR_IO, "%s: %s: %s (the previous file, if "
                       "any, is unchanged)", out->path, what,
                       e ? strerror(e) : "write error");
        release(out);
        return SVET_ERR_IO;
    }
    release(out);
    return SVET_OK;
}

void fileio_abort(fileio_t *out)
{
    if (!out)
        return;
    if (out->f) {
        fclose(out->f);
        unlink(out->tmp);
    }
    release(out);
}

svet_status fileio_write_text(const char *path, const char *text,
                              svet_error *err)
{
    fileio_t out;
    svet_status st = fileio_begin(&out, path, err);
    if (st != SVET_OK)
        return st;
    fputs(text, out.f); /* a failure shows in ferror(), checked at commit */
    return fileio_commit(&out, err);
}

/* --- reading ------------------------------------------------------------- */

/* What a file that is not a regular one is, for the message. */
static const char *kind_of(mode_t m)
{
    if (S_ISDIR(m))
        return "is a directory, not a file";
    if (S_ISFIFO(m))
        return "is a FIFO (named pipe), not a regular file";
    if (S_ISCHR(m) || S_ISBLK(m))
        return "is a device, not a regular file";
    if (S_ISSOCK(m))
        return "is a socket, not a regular file";
    return "is not a regular file";
}

svet_status fileio_open_read(const char *path, FILE **f, svet_error *err)
{
    *f = NULL;
    /* O_NONBLOCK: opening a FIFO for reading would otherwise wait for a
     * writer before fstat() could say what it is. */
    int fd = open(path, O_RDONLY | O_NONBLOCK);
    if (fd < 0)
        return svet_error_set(err, SVET_ERR_IO, "%s: cannot open: %s", path,
                              strerror(errno));
    struct stat sb;
    if (fstat(fd, &sb) != 0) {
        int e = errno;
        close(fd);
        return svet_error_set(err, SVET_ERR_IO, "%s: cannot open: %s", path,
                              strerror(e));
    }
    if (!S_ISREG(sb.st_mode)) {
        close(fd);
        return svet_error_set(err, SVET_ERR_IO, "%s: %s", path,
                              kind_of(sb.st_mode));
    }
    int fl = fcntl(fd, F_GETFL);
    if (fl != -1)
        fcntl(fd, F_SETFL, fl & ~O_NONBLOCK);
    *f = fdopen(fd, "rb");
    if (!*f) {
        int e = errno;
        close(fd);
        return svet_error_set(err, SVET_ERR_NOMEM, "%s: cannot open: %s",
                              path, strerror(e));
    }
    return SVET_OK;
}
