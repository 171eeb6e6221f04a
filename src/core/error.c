/*
 * error.c - status codes and messages; see error.h for the convention.
 * Tests: tests/core/test_error.c
 */
#include "core/error.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

svet_status svet_error_set(svet_error *err, svet_status status,
                           const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->msg, sizeof err->msg, fmt, ap);
        va_end(ap);
        err->status = status;
    }
    return status;
}

void svet_error_prefix(svet_error *err, const char *prefix)
{
    if (!err || !prefix)
        return;
    /* Shift the message right by strlen(prefix) + 2, dropping its tail if
     * the whole no longer fits, and write the prefix in front. */
    size_t cap = sizeof err->msg - 1;
    size_t lp = strlen(prefix) + 2, lm = strlen(err->msg);
    if (lp > cap)
        lp = cap;
    if (lm > cap - lp)
        lm = cap - lp;
    memmove(err->msg + lp, err->msg, lm);
    err->msg[lp + lm] = '\0';
    char head[SVET_ERROR_LEN];
    snprintf(head, sizeof head, "%s: ", prefix);
    memcpy(err->msg, head, lp);
}

void svet_error_clear(svet_error *err)
{
    if (err) {
        err->status = SVET_OK;
        err->msg[0] = '\0';
    }
}

const char *svet_status_name(svet_status status)
{
    switch (status) {
    case SVET_OK: return "success";
    case SVET_ERR_IO: return "I/O error";
    case SVET_ERR_PARSE: return "parse error";
    case SVET_ERR_RANGE: return "value out of range";
    case SVET_ERR_NOMEM: return "out of memory";
    case SVET_ERR_UNSUPPORTED: return "unsupported";
    }
    return "unknown status";
}
