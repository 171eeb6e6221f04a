/*
 * fileio.c - write to a temporary file, then rename() over the target;
 * open an input, refusing what is not a regular file.
 * rename() within one directory is atomic on POSIX file systems: a reader
 * sees the old file or the new one, never half of either. fsync() before
 * the rename keeps a crash right after it from leaving an empty file. A
 * set of outputs is written in full before the first rename, so that the
 * files of one result replace their predecessors together; temporary
 * files a killed process left behind are removed by the next write of
 * the same output. Tests: tests/io/test_fileio.c
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L /* open, fsync, fdopen, getpid: POSIX */
#endif
#include "io/fileio.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdbool.h>
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

/* --- temporary names and the stale files of killed writers ----------------
 * A temporary file is "<path>.tmp-<host>-<pid>-<n>": the host's name (at
 * most 32 bytes, every byte but letters, digits and '.' made '_', so that
 * the fields split at '-'), the writer's process id and a counter. While
 * it writes, the writer holds a write lock (fcntl) on the file. A later
 * write of the same path removes such a file only when all three say its
 * writer is gone: the host is this one (a process id means nothing on
 * another machine sharing the directory), no process has that id, and the
 * lock can be taken (the kernel drops it when its holder dies, which also
 * covers a writer in another PID namespace of this host, where its id is
 * not seen). A file of another host is left for that host to remove. */

enum { HOST_MAX = 32 };

/* This host's name as it appears in temporary names; false when the
 * system does not say (nothing is then ever removed as stale). */
static bool host_tag(char out[HOST_MAX + 1])
{
    char name[256];
    if (gethostname(name, sizeof name) != 0)
        return false;
    name[sizeof name - 1] = '\0';
    size_t n = strlen(name);
    if (n == 0)
        return false;
    if (n > HOST_MAX)
        n = HOST_MAX;
    for (size_t i = 0; i < n; i++) {
        char c = name[i];
        bool ok = ('a' <= c && c <= 'z') || ('A' <= c && c <= 'Z') ||
                  ('0' <= c && c <= '9') || c == '.';
        out[i] = ok ? c : '_';
    }
    out[n] = '\0';
    return true;
}

/* The process id in the temporary name `name` of the file `base` written
 * on host `host`, or 0 when name is not one. */
static long stale_pid(const char *name, const char *base, const char *host)
{
    size_t nb = strlen(base), nh = strlen(host);
    if (strncmp(name, base, nb) != 0 || strncmp(name + nb, ".tmp-", 5) != 0)
        return 0;
    const char *p = name + nb + 5;
    if (strncmp(p, host, nh) != 0 || p[nh] != '-')
        return 0;
    p += nh + 1;
    char *end;
    long pid = strtol(p, &end, 10);
    if (end == p || *end != '-' || pid <= 0)
        return 0;
    p = end + 1;
    strtoul(p, &end, 10);
    return end != p && *end == '\0' ? pid : 0;
}

/* Whether the writer of the temporary file at tmp, process pid of this
 * host, is certainly gone: no such process, and its lock is free. */
static bool writer_is_gone(const char *tmp, long pid)
{
    if (pid == (long)getpid() || kill((pid_t)pid, 0) == 0 || errno != ESRCH)
        return false;
    /* O_NONBLOCK: a FIFO of that name cannot block us */
    int fd = open(tmp, O_RDONLY | O_NONBLOCK | O_NOFOLLOW);
    if (fd < 0)
        return false;
    struct stat st;
    struct flock lk;
    memset(&lk, 0, sizeof lk);
    lk.l_type = F_RDLCK; /* conflicts with the writer's F_WRLCK */
    lk.l_whence = SEEK_SET;
    bool gone = fstat(fd, &st) == 0 && S_ISREG(st.st_mode) &&
                fcntl(fd, F_SETLK, &lk) == 0;
    close(fd); /* drops our lock */
    return gone;
}

/* Remove the temporary files of path that writers on this host left
 * when they were killed. Best effort: nothing to report. */
static void remove_stale(const char *path, const char *host)
{
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    size_t nd = slash ? (size_t)(slash - path) : 0;
    char *dir = malloc(nd + 2);
    if (!dir)
        return;
    if (slash) {
        memcpy(dir, path, nd ? nd : 1); /* "/x" lives in "/" */
        dir[nd ? nd : 1] = '\0';
    } else {
        strcpy(dir, ".");
    }
    DIR *d = opendir(dir);
    struct dirent *e;
    while (d && (e = readdir(d)) != NULL) {
        long pid = stale_pid(e->d_name, base, host);
        if (!pid)
            continue;
        size_t n = strlen(dir) + strlen(e->d_name) + 2;
        char *tmp = malloc(n);
        if (!tmp)
            break;
        snprintf(tmp, n, "%s/%s", dir, e->d_name);
        if (writer_is_gone(tmp, pid))
            unlink(tmp);
        free(tmp);
    }
    if (d)
        closedir(d);
    free(dir);
}

/* Refuse to replace what cp would not: a directory, something that is
 * not a regular file (a device, a FIFO: rename would replace the node
 * itself), or a file without write permission (also when root, who may
 * write anything: mode 444 says "keep"). */
static svet_status check_target(const char *path, svet_error *err)
{
    struct stat st;
    if (!*path)
        return svet_error_set(err, SVET_ERR_IO, "cannot write a file with "
                              "an empty name");
    if (stat(path, &st) != 0)
        return SVET_OK; /* a new file: fileio_begin finds out the rest */
    if (S_ISDIR(st.st_mode))
        return svet_error_set(err, SVET_ERR_IO, "%s: is a directory: not "
                              "replaced by a file", path);
    if (!S_ISREG(st.st_mode))
        return svet_error_set(err, SVET_ERR_IO, "%s: not a regular file: "
                              "not replaced", path);
    if ((st.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0 ||
        access(path, W_OK) != 0)
        return svet_error_set(err, SVET_ERR_IO, "%s: the file is read-only "
                              "(mode %03o): not replaced", path,
                              (unsigned)(st.st_mode & 0777));
    return SVET_OK;
}

svet_status fileio_begin(fileio_t *out, const char *path, svet_error *err)
{
    memset(out, 0, sizeof *out);
    svet_status st = check_target(path, err);
    if (st != SVET_OK)
        return st;
    char host[HOST_MAX + 1];
    bool known_host = host_tag(host);
    if (!known_host)
        strcpy(host, "unknown");
    else
        remove_stale(path, host);
    size_t cap = strlen(path) + 96;
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
        snprintf(out->tmp, cap, "%s.tmp-%s-%ld-%u", path, host,
                 (long)getpid(), counter++);
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
    /* The lock that tells a later writer this file is in use; where the
     * file system has no locks it is not taken, and the file is then never
     * removed as stale. */
    struct flock lk;
    memset(&lk, 0, sizeof lk);
    lk.l_type = F_WRLCK;
    lk.l_whence = SEEK_SET;
    (void)fcntl(fd, F_SETLK, &lk);
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

/* Flush, check, fsync and close out->f; on failure remove the temporary
 * file and say why. The temporary file stays otherwise, to be renamed. */
static svet_status finish(fileio_t *out, svet_error *err)
{
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
    if (!what)
        return SVET_OK;
    unlink(out->tmp);
    free(out->tmp);
    out->tmp = NULL;
    return svet_error_set(err, SVET_ERR_IO, "%s: %s: %s (the previous file, "
                          "if any, is unchanged)", out->path, what,
                          e ? strerror(e) : "write error");
}

/* Rename the finished temporary file over the target. */
static svet_status replace(fileio_t *out, svet_error *err)
{
    int rc = rename(out->tmp, out->path), e = errno;
    if (rc != 0)
        unlink(out->tmp);
    free(out->tmp);
    out->tmp = NULL; /* renamed or removed: nothing left to abort */
    if (rc == 0)
        return SVET_OK;
    return svet_error_set(err, SVET_ERR_IO, "%s: cannot replace: %s (the "
                          "previous file, if any, is unchanged)", out->path,
                          strerror(e));
}

svet_status fileio_commit(fileio_t *out, svet_error *err)
{
    if (!out->f) {
        release(out);
        return svet_error_set(err, SVET_ERR_IO, "fileio_commit without a "
                              "file");
    }
    svet_status st = finish(out, err);
    if (st == SVET_OK)
        st = replace(out, err);
    release(out);
    return st;
}

void fileio_abort(fileio_t *out)
{
    if (!out)
        return;
    if (out->f)
        fclose(out->f);
    if (out->tmp)
        unlink(out->tmp);
    release(out);
}

/* --- a set of outputs, replaced together ----------------------------------- */

void fileio_set_init(fileio_set_t *set)
{
    memset(set, 0, sizeof *set);
}

svet_status fileio_set_begin(fileio_set_t *set, const char *path,
                             fileio_t **out, svet_error *err)
{
    *out = NULL;
    if (set->n == FILEIO_SET_MAX)
        return svet_error_set(err, SVET_ERR_RANGE, "%s: more than %d files "
                              "in one set of outputs", path, FILEIO_SET_MAX);
    svet_status st = fileio_begin(&set->file[set->n], path, err);
    if (st != SVET_OK)
        return st;
    *out = &set->file[set->n++];
    return SVET_OK;
}

svet_status fileio_set_commit(fileio_set_t *set, svet_error *err)
{
    svet_status st = SVET_OK;
    for (int i = 0; i < set->n && st == SVET_OK; i++)
        if (!set->file[i].f)
            st = svet_error_set(err, SVET_ERR_IO, "%s: not written (the set "
                                "of outputs is unchanged)",
                                set->file[i].path ? set->file[i].path : "?");
        else
            st = finish(&set->file[i], err);
    /* every file is on disk before the first target changes */
    int renamed = 0;
    for (int i = 0; i < set->n && st == SVET_OK; i++, renamed++)
        st = replace(&set->file[i], err);
    if (st != SVET_OK && renamed > 0 && err) {
        /* A rename failed after others succeeded (every target was
         * checked by fileio_begin, so this is rare): say which files
         * are new. */
        size_t len = strlen(err->msg);
        for (int i = 0; i < renamed && len + 8 < sizeof err->msg; i++) {
            snprintf(err->msg + len, sizeof err->msg - len, "%s%s",
                     i ? ", " : "; already replaced: ", set->file[i].path);
            len = strlen(err->msg);
        }
    }
    fileio_set_abort(set);
    return st;
}

void fileio_set_abort(fileio_set_t *set)
{
    for (int i = 0; i < set->n; i++)
        fileio_abort(&set->file[i]); /* renamed ones: nothing to remove */
    set->n = 0;
}

/* --- which file a name means ------------------------------------------------ */

/* The identity of path: the device and inode of its longest leading part
 * that exists (st), and the components after that part, each followed by
 * '/' ("" when the whole path exists). Malloc'ed; NULL when out of
 * memory. */
static char *identify(const char *path, struct stat *st)
{
    size_t n = strlen(path);
    char *p = malloc(n + 2), *rest = malloc(n + 2);
    if (!p || !rest) {
        free(p);
        free(rest);
        return NULL;
    }
    memcpy(p, path, n + 1);
    rest[0] = '\0';
    memset(st, 0, sizeof *st);
    for (;;) {
        while (n > 1 && p[n - 1] == '/')
            p[--n] = '\0';
        if (stat(n ? p : ".", st) == 0)
            break;
        char *cut = strrchr(p, '/');
        const char *comp = cut ? cut + 1 : p;
        if (strcmp(comp, ".") != 0) { /* "a/./b" is "a/b" */
            size_t nc = strlen(comp), nr = strlen(rest);
            memmove(rest + nc + 1, rest, nr + 1);
            memcpy(rest, comp, nc);
            rest[nc] = '/';
        }
        if (!cut) {
            p[0] = '\0';
            n = 0;
        } else if (cut == p) {
            strcpy(p, "/");
            n = 1;
        } else {
            *cut = '\0';
            n = (size_t)(cut - p);
        }
        if (n == 1 && p[0] == '/' && stat(p, st) != 0)
            break; /* no root: nothing more to learn */
    }
    free(p);
    return rest;
}

bool fileio_same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    char *ra = identify(a, &sa), *rb = identify(b, &sb);
    bool same = ra && rb ? sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino &&
                               strcmp(ra, rb) == 0
                         : strcmp(a, b) == 0;
    free(ra);
    free(rb);
    return same;
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
