/*
 * scenefile.c - the scene file reader: a line-oriented text format (one
 * statement per line, `#` comments, keyword-value pairs), documented with
 * its grammar in scenes/README.md. Every error names file:line:column and
 * what was expected there; a misspelt keyword gets a "did you mean".
 * Tests: tests/render/test_scenefile.c; fuzzing: fuzz/fuzz_scene.c
 */
#include "render/scenefile.h"
#include "render/scenepart.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "accel/accel.h"
#include "core/bbox.h"
#include "core/text.h"
#include "geometry/box.h"
#include "colour/colour.h"
#include "geometry/cone.h"
#include "geometry/cylinder.h"
#include "geometry/disk.h"
#include "materials/material.h"
#include "geometry/parallelogram.h"
#include "geometry/plane.h"
#include "geometry/shape.h"
#include "geometry/sphere.h"
#include "geometry/triangle.h"
#include "geometry/xform.h"
#include "io/fileio.h"

#define PI_D 3.14159265358979323846

/* The largest number of transforms on one line. */
#define MAX_XFORMS 64
/* The largest number of keys one statement takes. */
#define MAX_SPEC 32
/* The most words on one line: far more than any statement needs (a shape
 * with every key and 64 transforms has about 300), few enough that a line
 * of a million numbers costs no memory. */
#define MAX_TOKENS 4096
/* The most names in place of values on one material line: one per
 * parameter of the mixed surface (scenepart.h's scene_param_t). */
#define MAX_NAMED 16

/* tok_t, vtype, spec_t and val_t are scenepart.h's: the parts of Part
 * II read their statements' keys with them. */

/* One affine transform of an object, as written. */
typedef struct {
    enum { XF_SCALE, XF_ROTATE, XF_TRANSLATE } kind;
    real v[4];  /* scale: sx sy sz; rotate: axis x y z, degrees; translate */
    int col;
} xform_op;

/* The state of the parser. */
typedef struct scenefile_ctx {
    scene_t *scene;
    const char *name;      /* what messages call the file */
    const char *dir;       /* directory for relative mesh paths, or NULL */
    const char *override;  /* the key=value being applied, or NULL */
    const scene_features_t *features; /* what the program offers, or NULL */
    svet_error *err;
    int line;              /* current line, 1-based */
    int eol_col;           /* column just past the last token */
    tok_t *tok;            /* the tokens of the line */
    int ntok, cap;
    int pos;               /* the next token to read */
    int stmt_col;          /* column of the statement's keyword */
    xform_op xf[MAX_XFORMS]; /* the transforms of the current statement */
    int nxf;
    int camera_line;       /* last camera statement, for scene_validate */
    int environment_line;
    int nstatements;       /* statements read */
    int environment_col;   /* its 'radiance' */
    double power;          /* the lights' powers so far, W (check_light) */
    bbox_t bounds;         /* of the objects of finite size so far */
    double smallest;       /* the smallest such object's diagonal, */
    int smallest_line;     /* and its line (0: none yet) */
    scene_named_t named[MAX_NAMED]; /* names in place of the current
                                       material's values (F_NAMED) */
    int nnamed;
} ctx_t;


/* --- messages ------------------------------------------------------------ */

/* A message "file:line:col: ..." (or "override 'k=v': ...") in c->err,
 * from a va_list: fail() and scenefile_fail() are its front ends. */
#if defined(__GNUC__)
__attribute__((format(printf, 4, 0)))
#endif
static svet_status vfail(ctx_t *c, int col, svet_status st, const char *fmt,
                         va_list ap)
{
    char msg[SVET_ERROR_LEN];
    vsnprintf(msg, sizeof msg, fmt, ap);
    if (c->override)
        return svet_error_set(c->err, st, "override '%s': %s", c->override,
                              msg);
    return svet_error_set(c->err, st, "%s:%d:%d: %s", c->name, c->line, col,
                          msg);
}

#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
static svet_status fail(ctx_t *c, int col, svet_status st, const char *fmt,
                        ...)
{
    va_list ap;
    va_start(ap, fmt);
    st = vfail(c, col, st, fmt, ap);
    va_end(ap);
    return st;
}


/* A token as messages show it: at most 40 bytes, anything unprintable as
 * '?', so that a binary file gives a readable message. */
static const char *show_tok(const tok_t *t, char *buf, size_t size)
{
    size_t n = 0;
    int i;
    for (i = 0; i < t->len && n + 4 < size && i < 40; i++) {
        unsigned char ch = (unsigned char)t->s[i];
        buf[n++] = (ch >= 0x20 && ch < 0x7f) ? (char)ch : '?';
    }
    if (i < t->len) {
        buf[n++] = '.'; buf[n++] = '.'; buf[n++] = '.';
    }
    buf[n] = '\0';
    return buf;
}

static bool tok_is(const tok_t *t, const char *word)
{
    size_t n = strlen(word);
    return !t->quoted && (size_t)t->len == n && memcmp(t->s, word, n) == 0;
}

/* The token as a NUL-terminated string in buf (cut to size - 1). */
static void tok_copy(const tok_t *t, char *buf, size_t size)
{
    size_t n = (size_t)t->len < size - 1 ? (size_t)t->len : size - 1;
    memcpy(buf, t->s, n);
    buf[n] = '\0';
}

/* --- the lexer: one line into tokens ------------------------------------- */

/* Split the line [p, end) into tokens: runs of bytes other than blanks,
 * or "double-quoted strings" (no escapes; they may hold blanks and '#').
 * A '#' outside a string starts a comment. Control bytes other than tab
 * (and a CR just before the newline) are an error, as is a NUL. */
static svet_status lex(ctx_t *c, const char *p, const char *end)
{
    const char *line = p;
    c->ntok = 0;
    c->pos = 0;
    if (end > p && end[-1] == '\r')
        end--;
    while (p < end) {
        unsigned char ch = (unsigned char)*p;
        int col = (int)(p - line) + 1;
        if (ch == ' ' || ch == '\t') {
            p++;
            continue;
        }
        if (ch == '#')
            break;
        if (ch < 0x20 || ch == 0x7f)
            return fail(c, col, SVET_ERR_PARSE,
                        "unexpected control character 0x%02x", ch);
        if (c->ntok == c->cap) {
            if (c->cap >= MAX_TOKENS)
                return fail(c, col, SVET_ERR_RANGE,
                            "more than %d words on one line", MAX_TOKENS);
            int ncap = c->cap ? 2 * c->cap : 32;
            tok_t *nt = realloc(c->tok, (size_t)ncap * sizeof *nt);
            if (!nt)
                return fail(c, col, SVET_ERR_NOMEM, "out of memory");
            c->tok = nt;
            c->cap = ncap;
        }
        tok_t *t = &c->tok[c->ntok++];
        t->col = col;
        if (ch == '"') {
            const char *q = p + 1;
            while (q < end && *q != '"') {
                unsigned char qc = (unsigned char)*q;
                if ((qc < 0x20 && qc != '\t') || qc == 0x7f)
                    return fail(c, (int)(q - line) + 1, SVET_ERR_PARSE,
                                "unexpected control character 0x%02x "
                                "in a string", qc);
                q++;
            }
            if (q == end)
                return fail(c, col, SVET_ERR_PARSE,
                            "unterminated string: expected a closing "
                            "'\"' on this line");
            t->s = p + 1;
            t->len = (int)(q - p - 1);
            t->quoted = true;
            p = q + 1;
            if (p < end && *p != ' ' && *p != '\t' && *p != '#')
                return fail(c, (int)(p - line) + 1, SVET_ERR_PARSE,
                            "expected a blank after the closing '\"'");
        } else {
            const char *q = p;
            while (q < end && *q != ' ' && *q != '\t' && *q != '#' &&
                   *q != '"' && (unsigned char)*q >= 0x20 && *q != 0x7f)
                q++;
            if (q < end && *q == '"')
                return fail(c, (int)(q - line) + 1, SVET_ERR_PARSE,
                            "expected a blank before the opening '\"'");
            t->s = p;
            t->len = (int)(q - p);
            t->quoted = false;
            p = q;
        }
    }
    c->eol_col = (int)(p - line) + 1;
    if (c->ntok > 0) {
        const tok_t *last = &c->tok[c->ntok - 1];
        c->eol_col = last->col + last->len + (last->quoted ? 2 : 0);
    }
    return SVET_OK;
}

/* --- numbers ------------------------------------------------------------- */

/* Does the token look like a number: [+-] digits [. digits] [e [+-]
 * digits], or a NaN or infinity spelt as strtod would take it? The latter
 * count so that the error says "not finite" rather than "unknown word". */
static bool syntax_number(const tok_t *t, bool *nonfinite)
{
    const char *s = t->s, *e = t->s + t->len;
    *nonfinite = false;
    if (t->quoted || s == e)
        return false;
    if (*s == '+' || *s == '-')
        s++;
    static const char *const specials[] = { "nan", "inf", "infinity" };
    for (size_t k = 0; k < sizeof specials / sizeof *specials; k++) {
        size_t n = strlen(specials[k]);
        if ((size_t)(e - s) == n) {
            size_t i = 0;
            while (i < n && tolower((unsigned char)s[i]) == specials[k][i])
                i++;
            if (i == n) {
                *nonfinite = true;
                return true;
            }
        }
    }
    int digits = 0;
    while (s < e && isdigit((unsigned char)*s)) {
        s++;
        digits++;
    }
    if (s < e && *s == '.') {
        s++;
        while (s < e && isdigit((unsigned char)*s)) {
            s++;
            digits++;
        }
    }
    if (digits == 0)
        return false;
    if (s < e && (*s == 'e' || *s == 'E')) {
        s++;
        if (s < e && (*s == '+' || *s == '-'))
            s++;
        int edigits = 0;
        while (s < e && isdigit((unsigned char)*s)) {
            s++;
            edigits++;
        }
        if (edigits == 0)
            return false;
    }
    return s == e;
}

static bool is_number(const tok_t *t)
{
    bool nonfinite;
    return syntax_number(t, &nonfinite);
}

static svet_status number_tok(ctx_t *c, const tok_t *t, const char *what,
                              real *out)
{
    char buf[64], show[64];
    bool nonfinite;
    if (!syntax_number(t, &nonfinite))
        return fail(c, t->col, SVET_ERR_PARSE,
                    "expected a number for %s, got '%s'", what,
                    show_tok(t, show, sizeof show));
    if (nonfinite)
        return fail(c, t->col, SVET_ERR_RANGE,
                    "%s must be a finite number, not '%s'", what,
                    show_tok(t, show, sizeof show));
    if (t->len >= (int)sizeof buf)
        return fail(c, t->col, SVET_ERR_PARSE,
                    "number for %s is too long (more than %d characters)",
                    what, (int)sizeof buf - 1);
    tok_copy(t, buf, sizeof buf);
    double d = strtod(buf, NULL);
    /* An underflow to 0 or a subnormal is harmless; only an overflow (to
     * infinity, in double or on the conversion to real) is an error. */
    real r = (real)d;
    if (!isfinite(d) || !isfinite(r))
        return fail(c, t->col, SVET_ERR_RANGE,
                    "%s = %s is too large for %s", what, buf, REAL_NAME);
    *out = r;
    return SVET_OK;
}

/* A whole number [+-]digits in [lo, hi]; leading zeros are fine, and a
 * value of any length beyond the range is "out of range". */
static svet_status integer(ctx_t *c, const tok_t *t, const char *what,
                           long lo, long hi, long *out)
{
    char show[64];
    const char *s = t->s, *e = t->s + t->len;
    bool neg = !t->quoted && s < e && *s == '-';
    if (!t->quoted && s < e && (*s == '-' || *s == '+'))
        s++;
    bool ok = !t->quoted && s < e, big = false;
    long v = 0;
    for (const char *q = s; ok && q < e; q++) {
        ok = isdigit((unsigned char)*q);
        if (ok && !big) {
            int d = *q - '0';
            big = v > (LONG_MAX - d) / 10;
            v = big ? v : 10 * v + d;
        }
    }
    if (!ok)
        return fail(c, t->col, SVET_ERR_PARSE,
                    "expected a whole number for %s, got '%s'", what,
                    show_tok(t, show, sizeof show));
    if (neg)
        v = -v;
    if (big || v < lo || v > hi)
        return fail(c, t->col, SVET_ERR_RANGE,
                    "%s = %s is out of range: expected %ld to %ld", what,
                    show_tok(t, show, sizeof show), lo, hi);
    *out = v;
    return SVET_OK;
}

/* An unsigned 64-bit integer (the seed): digits only. */
static svet_status uint64_tok(ctx_t *c, const tok_t *t, const char *what,
                              uint64_t *out)
{
    char show[64];
    bool ok = !t->quoted && t->len > 0;
    uint64_t v = 0;
    for (int i = 0; ok && i < t->len; i++) {
        unsigned char ch = (unsigned char)t->s[i];
        if (!isdigit(ch)) {
            ok = false;
            break;
        }
        unsigned d = ch - '0';
        if (v > (UINT64_MAX - d) / 10)
            return fail(c, t->col, SVET_ERR_RANGE,
                        "%s = %s is out of range: expected 0 to %llu",
                        what, show_tok(t, show, sizeof show),
                        (unsigned long long)UINT64_MAX);
        v = 10 * v + d;
    }
    if (!ok)
        return fail(c, t->col, SVET_ERR_PARSE,
                    "expected a whole number >= 0 for %s, got '%s'", what,
                    show_tok(t, show, sizeof show));
    *out = v;
    return SVET_OK;
}

/* --- keyword-value lists ------------------------------------------------- */

/* What the key's values look like, for "expected" messages. */
static const char *type_hint(const spec_t *sp)
{
    switch (sp->type) {
    case V_NUM: return "a number";
    case V_INT: return "a whole number";
    case V_U64: return "a whole number >= 0";
    case V_VEC3: return "3 numbers x y z";
    case V_COLOUR: return "1 number (grey) or 3 (r g b)";
    case V_WORD: return "a word";
    case V_STRING: return "a file name";
    case V_FLAG: return "nothing";
    case V_ONOFF: return "on or off";
    case V_SCALE: return "1 number or 3 (sx sy sz)";
    case V_ROTATE: return "an axis (x, y, z or 3 numbers) and an angle in "
                           "degrees";
    case V_TRANSLATE: return "3 numbers x y z";
    }
    return "a value";
}

static svet_status missing_value(ctx_t *c, const spec_t *sp)
{
    char show[64];
    if (c->pos < c->ntok)
        return fail(c, c->tok[c->pos].col, SVET_ERR_PARSE,
                    "'%s' expects %s, got '%s'", sp->key, type_hint(sp),
                    show_tok(&c->tok[c->pos], show, sizeof show));
    return fail(c, c->eol_col, SVET_ERR_PARSE,
                "'%s' expects %s, got the end of the line", sp->key,
                type_hint(sp));
}

/* n numbers into v, from the current token on. */
static svet_status numbers(ctx_t *c, const spec_t *sp, int n, real *v)
{
    for (int i = 0; i < n; i++) {
        if (c->pos >= c->ntok)
            return missing_value(c, sp);
        const tok_t *t = &c->tok[c->pos];
        if (!is_number(t)) {
            char show[64];
            if (i == 0)
                return missing_value(c, sp);
            return fail(c, t->col, SVET_ERR_PARSE,
                        "'%s' expects %s: got %d number%s, then '%s'",
                        sp->key, type_hint(sp), i, i == 1 ? "" : "s",
                        show_tok(t, show, sizeof show));
        }
        char what[48];
        snprintf(what, sizeof what, "'%s'", sp->key);
        svet_status st = number_tok(c, t, what, &v[i]);
        if (st)
            return st;
        c->pos++;
    }
    return SVET_OK;
}

/* How many tokens from the current one on look like numbers (up to max). */
static int count_numbers(const ctx_t *c, int max)
{
    int n = 0;
    while (n < max && c->pos + n < c->ntok &&
           is_number(&c->tok[c->pos + n]))
        n++;
    return n;
}

/* One number, or three: a grey or RGB colour, a uniform or per-axis
 * scale. Two numbers are an error. */
static svet_status one_or_three(ctx_t *c, const spec_t *sp, real v[3])
{
    int n = count_numbers(c, 3);
    if (n == 2) {
        char show[64];
        if (c->pos + 2 < c->ntok)
            return fail(c, c->tok[c->pos + 2].col, SVET_ERR_PARSE,
                        "'%s' expects %s: got 2 numbers, then '%s'",
                        sp->key, type_hint(sp),
                        show_tok(&c->tok[c->pos + 2], show, sizeof show));
        return fail(c, c->eol_col, SVET_ERR_PARSE,
                    "'%s' expects %s: got 2 numbers, then the end of the "
                    "line", sp->key, type_hint(sp));
    }
    svet_status st = numbers(c, sp, n == 3 ? 3 : 1, v);
    if (st)
        return st;
    if (n != 3)
        v[1] = v[2] = v[0];
    return SVET_OK;
}

static const spec_t *find_spec(const spec_t *spec, int nspec,
                               const tok_t *t, int *index)
{
    for (int i = 0; i < nspec; i++)
        if (tok_is(t, spec[i].key)) {
            *index = i;
            return &spec[i];
        }
    return NULL;
}

static svet_status unknown(ctx_t *c, const tok_t *t, const char *what,
                           const char *const *names, int n)
{
    char show[64], word[64];
    tok_copy(t, word, sizeof word);
    const char *near = t->quoted ? NULL : scene_nearest_name(word, names, n);
    if (near)
        return fail(c, t->col, SVET_ERR_PARSE,
                    "unknown %s '%s' (did you mean '%s'?)", what,
                    show_tok(t, show, sizeof show), near);
    char list[320];
    size_t len = 0;
    list[0] = '\0';
    for (int i = 0; i < n && len + 24 < sizeof list; i++)
        len += (size_t)snprintf(list + len, sizeof list - len, "%s%s",
                                i ? ", " : "", names[i]);
    return fail(c, t->col, SVET_ERR_PARSE,
                "unknown %s '%s': expected one of %s", what,
                show_tok(t, show, sizeof show), list);
}

/* Append one transform to the statement's list. */
static svet_status push_xform(ctx_t *c, xform_op *x, int col)
{
    if (c->nxf == MAX_XFORMS)
        return fail(c, col, SVET_ERR_RANGE,
                    "more than %d transforms on one line", MAX_XFORMS);
    c->xf[c->nxf++] = *x;
    return SVET_OK;
}

static svet_status parse_xform(ctx_t *c, const spec_t *sp, int col)
{
    xform_op x;
    memset(&x, 0, sizeof x);
    x.col = col;
    svet_status st;
    switch (sp->type) {
    case V_SCALE:
        x.kind = XF_SCALE;
        st = one_or_three(c, sp, x.v);
        if (!st && (x.v[0] == 0 || x.v[1] == 0 || x.v[2] == 0))
            return fail(c, col, SVET_ERR_RANGE,
                        "a scale factor of 0 flattens the object: "
                        "expected nonzero factors");
        break;
    case V_TRANSLATE:
        x.kind = XF_TRANSLATE;
        st = numbers(c, sp, 3, x.v);
        break;
    default: /* V_ROTATE */
        x.kind = XF_ROTATE;
        if (c->pos < c->ntok && (tok_is(&c->tok[c->pos], "x") ||
                                 tok_is(&c->tok[c->pos], "y") ||
                                 tok_is(&c->tok[c->pos], "z"))) {
            x.v[c->tok[c->pos].s[0] - 'x'] = 1;
            c->pos++;
            st = numbers(c, sp, 1, &x.v[3]);
        } else {
            st = numbers(c, sp, 4, x.v);
            if (!st && !(vec_length(x.v) > 0))
                return fail(c, col, SVET_ERR_RANGE,
                            "a rotation axis must be a nonzero vector");
        }
        break;
    }
    if (st)
        return st;
    return push_xform(c, &x, col);
}

static bool name_ok(const tok_t *t);

/* A name where F_NAMED allows one in place of the number (a texture's,
 * ch. 10): taken into v->word, the value left 0, for a part to resolve. */
static bool named_value(ctx_t *c, const spec_t *sp, val_t *v)
{
    if (!(sp->flags & F_NAMED) || c->pos >= c->ntok ||
        is_number(&c->tok[c->pos]) || !name_ok(&c->tok[c->pos]))
        return false;
    v->named = true;
    v->word = c->tok[c->pos++];
    return true;
}

static svet_status parse_value(ctx_t *c, const spec_t *sp, val_t *v)
{
    svet_status st = SVET_OK;
    char what[48], show[64];
    snprintf(what, sizeof what, "'%s'", sp->key);
    if (named_value(c, sp, v))
        return SVET_OK;
    switch (sp->type) {
    case V_FLAG:
        v->on = true;
        return SVET_OK;
    case V_NUM:
        st = numbers(c, sp, 1, v->v);
        break;
    case V_VEC3:
        st = numbers(c, sp, 3, v->v);
        break;
    case V_COLOUR:
        st = one_or_three(c, sp, v->v);
        if (!st && (v->v[0] < 0 || v->v[1] < 0 || v->v[2] < 0))
            return fail(c, v->col, SVET_ERR_RANGE,
                        "%s must not be negative", what);
        return st;
    case V_INT:
        if (c->pos >= c->ntok)
            return missing_value(c, sp);
        st = integer(c, &c->tok[c->pos], what, sp->lo, sp->hi, &v->i);
        c->pos++;
        return st;
    case V_U64:
        if (c->pos >= c->ntok)
            return missing_value(c, sp);
        st = uint64_tok(c, &c->tok[c->pos], what, &v->u);
        c->pos++;
        return st;
    case V_STRING:
        if (c->pos >= c->ntok)
            return missing_value(c, sp);
        v->word = c->tok[c->pos++];
        if (v->word.len == 0)
            return fail(c, v->word.col, SVET_ERR_PARSE,
                        "%s expects a file name, got an empty string",
                        what);
        return SVET_OK;
    case V_ONOFF:
        if (c->pos >= c->ntok)
            return missing_value(c, sp);
        v->word = c->tok[c->pos++];
        if (tok_is(&v->word, "on"))
            v->on = true;
        else if (tok_is(&v->word, "off"))
            v->on = false;
        else
            return fail(c, v->word.col, SVET_ERR_PARSE,
                        "%s expects on or off, got '%s'", what,
                        show_tok(&v->word, show, sizeof show));
        return SVET_OK;
    case V_WORD: {
        if (c->pos >= c->ntok)
            return missing_value(c, sp);
        v->word = c->tok[c->pos++];
        int n = 0;
        while (sp->choices[n])
            n++;
        for (int i = 0; i < n; i++)
            if (tok_is(&v->word, sp->choices[i])) {
                v->i = i;
                return SVET_OK;
            }
        char kind[64];
        snprintf(kind, sizeof kind, "value of %s", what);
        return unknown(c, &v->word, kind, sp->choices, n);
    }
    case V_SCALE:
    case V_ROTATE:
    case V_TRANSLATE:
        return parse_xform(c, sp, v->col);
    }
    if (st)
        return st;
    if ((sp->flags & F_POSITIVE) && !(v->v[0] > 0))
        return fail(c, v->col, SVET_ERR_RANGE, "%s must be > 0", what);
    if ((sp->flags & F_NONNEG) && v->v[0] < 0)
        return fail(c, v->col, SVET_ERR_RANGE, "%s must be >= 0", what);
    if ((sp->flags & F_NONZERO) && !(vec_length(v->v) > 0))
        return fail(c, v->col, SVET_ERR_RANGE,
                    "%s must be a nonzero vector", what);
    return SVET_OK;
}

static bool is_shape_statement(const char *stmt);

/* Keys of shapes that a part of a later chapter adds (scenepart.h's shape
 * keys): a program without that part names the chapter rather than
 * saying "unknown parameter". */
static const char *reserved_shape_key(const char *stmt, const tok_t *t)
{
    static const struct {
        const char *key, *chapter;
    } keys[] = {
        { "medium", "ch. 11 (participating media)" },
        { "bump", "ch. 10 (textures)" },
    };
    if (!is_shape_statement(stmt))
        return NULL;
    for (size_t i = 0; i < sizeof keys / sizeof *keys; i++)
        if (tok_is(t, keys[i].key))
            return keys[i].chapter;
    return NULL;
}

static svet_status parse_keys(ctx_t *c, const char *stmt, const spec_t *spec,
                              int nspec, val_t *vals, bool stop_at_plus)
{
    const char *names[MAX_SPEC];
    const spec_t *last = NULL;
    char show[64];
    memset(vals, 0, (size_t)nspec * sizeof *vals);
    c->nxf = 0;
    while (c->pos < c->ntok) {
        const tok_t *t = &c->tok[c->pos];
        if (stop_at_plus && tok_is(t, "+"))
            break;
        int i = 0;
        const spec_t *sp = find_spec(spec, nspec, t, &i);
        if (!sp && is_number(t)) {
            /* A number where a key should be: one value too many. */
            if (last)
                return fail(c, t->col, SVET_ERR_PARSE,
                            "one value too many: '%s' takes %s, then "
                            "comes a key, not '%s'",
                            last->key, type_hint(last),
                            show_tok(t, show, sizeof show));
            return fail(c, t->col, SVET_ERR_PARSE,
                        "expected a key of %s before the value '%s'", stmt,
                        show_tok(t, show, sizeof show));
        }
        if (!sp) {
            const char *chapter = reserved_shape_key(stmt, t);
            if (chapter)
                return fail(c, t->col, SVET_ERR_UNSUPPORTED,
                            "'%s' on a %s is not supported by this "
                            "program: %s", show_tok(t, show, sizeof show),
                            stmt, chapter);
            for (int k = 0; k < nspec && k < MAX_SPEC; k++)
                names[k] = spec[k].key;
            char what[64];
            snprintf(what, sizeof what, "parameter of %s", stmt);
            return unknown(c, t, what, names,
                           nspec < MAX_SPEC ? nspec : MAX_SPEC);
        }
        last = sp;
        bool repeatable = sp->type == V_SCALE || sp->type == V_ROTATE ||
                          sp->type == V_TRANSLATE;
        if (vals[i].set && !repeatable)
            return fail(c, t->col, SVET_ERR_PARSE,
                        "'%s' is given twice (first at column %d)",
                        sp->key, vals[i].col);
        vals[i].set = true;
        vals[i].col = t->col;
        c->pos++;
        svet_status st = parse_value(c, sp, &vals[i]);
        if (st)
            return st;
    }
    for (int i = 0; i < nspec; i++)
        if ((spec[i].flags & F_REQUIRED) && !vals[i].set)
            return fail(c, c->stmt_col, SVET_ERR_PARSE,
                        "%s needs '%s' (%s)", stmt, spec[i].key,
                        type_hint(&spec[i]));
    return SVET_OK;
}

/* --- files --------------------------------------------------------------- */

/* Read the whole regular file at path (at most max bytes) into a new
 * buffer *text of *len bytes. A directory, FIFO or device is refused
 * (reading /dev/zero would never end). */
static svet_status read_file(const char *path, long max, char **text,
                             size_t *len, svet_error *err)
{
    *text = NULL;
    *len = 0;
    FILE *f;
    svet_status st = fileio_open_read(path, &f, err); /* regular files */
    if (st != SVET_OK)
        return st;
    struct stat sb;
    if (fstat(fileno(f), &sb) != 0 || !S_ISREG(sb.st_mode)) {
        fclose(f);
        return svet_error_set(err, SVET_ERR_IO, "%s: not a regular file",
                              path);
    }
    if (sb.st_size > max) {
        fclose(f);
        return svet_error_set(err, SVET_ERR_RANGE,
                              "%s: the file is larger than %ld bytes", path,
                              max);
    }
    char *buf = malloc((size_t)sb.st_size + 1);
    if (!buf) {
        fclose(f);
        return svet_error_set(err, SVET_ERR_NOMEM, "%s: out of memory",
                              path);
    }
    size_t n = fread(buf, 1, (size_t)sb.st_size, f);
    bool bad = ferror(f);
    fclose(f);
    if (bad) {
        free(buf);
        return svet_error_set(err, SVET_ERR_IO, "%s: read error", path);
    }
    buf[n] = '\0';
    *text = buf;
    *len = n;
    return SVET_OK;
}

/* The directory part of path ("." when it has none), newly allocated. */
static char *dir_name(const char *path)
{
    const char *slash = strrchr(path, '/');
    size_t n = slash ? (size_t)(slash - path) : 0;
    if (slash && n == 0)
        n = 1; /* "/scene.scn": the root */
    char *d = malloc(n + 2);
    if (!d)
        return NULL;
    if (slash)
        memcpy(d, path, n);
    else
        d[n++] = '.';
    d[n] = '\0';
    return d;
}

/* rel taken relative to dir (unless rel is absolute or dir NULL), newly
 * allocated; NULL when memory runs out. */
static char *path_join(const char *dir, const char *rel)
{
    size_t ld = (dir && rel[0] != '/') ? strlen(dir) : 0;
    size_t lr = strlen(rel);
    char *p = malloc(ld + lr + 2);
    if (!p)
        return NULL;
    if (ld) {
        memcpy(p, dir, ld);
        p[ld++] = '/';
    }
    memcpy(p + ld, rel, lr + 1);
    return p;
}

/* --- settings: camera, render, output, tonemap --------------------------- */

static const char *const fov_axes[] = { "x", "y", "diagonal", NULL };
static const char *const filters[] = { "box", NULL };

enum { CAM_POSITION, CAM_TARGET, CAM_UP, CAM_FOV, CAM_FOV_AXIS, CAM_WIDTH,
       CAM_HEIGHT, CAM_FILTER, CAM_FILTER_WIDTH, CAM_N };
static const spec_t camera_spec[CAM_N] = {
    [CAM_POSITION] = { "position", V_VEC3, 0, 0, 0, NULL },
    [CAM_TARGET] = { "target", V_VEC3, 0, 0, 0, NULL },
    [CAM_UP] = { "up", V_VEC3, F_NONZERO, 0, 0, NULL },
    [CAM_FOV] = { "fov", V_NUM, 0, 0, 0, NULL },
    [CAM_FOV_AXIS] = { "fov_axis", V_WORD, 0, 0, 0, fov_axes },
    [CAM_WIDTH] = { "width", V_INT, 0, 1, SCENE_MAX_RESOLUTION, NULL },
    [CAM_HEIGHT] = { "height", V_INT, 0, 1, SCENE_MAX_RESOLUTION, NULL },
    [CAM_FILTER] = { "filter", V_WORD, 0, 0, 0, filters },
    [CAM_FILTER_WIDTH] = { "filter_width", V_NUM, F_POSITIVE, 0, 0, NULL },
};

static svet_status st_camera(ctx_t *c)
{
    val_t v[CAM_N];
    svet_status st = parse_keys(c, "camera", camera_spec, CAM_N, v, false);
    if (st)
        return st;
    scene_camera_t cam = c->scene->camera;
    if (v[CAM_POSITION].set)
        vec_copy(cam.position, v[CAM_POSITION].v);
    if (v[CAM_TARGET].set)
        vec_copy(cam.target, v[CAM_TARGET].v);
    if (v[CAM_UP].set)
        vec_copy(cam.up, v[CAM_UP].v);
    if (v[CAM_FOV].set) {
        cam.fov = v[CAM_FOV].v[0];
        if (!(cam.fov > 0 && cam.fov < 180))
            return fail(c, v[CAM_FOV].col, SVET_ERR_RANGE,
                        "'fov' is the full angle in degrees: expected "
                        "more than 0 and less than 180");
    }
    if (v[CAM_FOV_AXIS].set)
        cam.fov_axis = (scene_fov_axis)v[CAM_FOV_AXIS].i;
    if (v[CAM_WIDTH].set)
        cam.width = (int)v[CAM_WIDTH].i;
    if (v[CAM_HEIGHT].set)
        cam.height = (int)v[CAM_HEIGHT].i;
    if ((long)cam.width * cam.height > SCENE_MAX_PIXELS) {
        int col = v[CAM_HEIGHT].set ? v[CAM_HEIGHT].col
                  : v[CAM_WIDTH].set ? v[CAM_WIDTH].col : c->stmt_col;
        return fail(c, col, SVET_ERR_RANGE,
                    "%d x %d pixels is more than the limit of %ld",
                    cam.width, cam.height, SCENE_MAX_PIXELS);
    }
    if (v[CAM_FILTER].set)
        cam.filter = (scene_filter)v[CAM_FILTER].i;
    if (v[CAM_FILTER_WIDTH].set) {
        cam.filter_width = v[CAM_FILTER_WIDTH].v[0];
        if (cam.filter_width > 16)
            return fail(c, v[CAM_FILTER_WIDTH].col, SVET_ERR_RANGE,
                        "'filter_width' is in pixels: expected at most 16");
    }
    c->scene->camera = cam;
    c->camera_line = c->line;
    return SVET_OK;
}

static const char *const integrators[] = { "path", "direct", "bsdf", "ao",
                                           "nee", NULL };
static const char *const lights_shown[] = { "all", "indirect", NULL };
static const char *const accels[] = { "auto", "brute", "grid", "hgrid",
                                      NULL };

enum { R_SPP, R_MAXDEPTH, R_ROULETTE, R_RRDEPTH, R_SEED, R_INTEGRATOR,
       R_AO_DISTANCE, R_THREADS, R_TIME_LIMIT, R_PASSES, R_CHECKPOINT,
       R_ACCEL, R_PACKETS, R_LIGHT, R_N };
static const spec_t render_spec[R_N] = {
    [R_SPP] = { "spp", V_INT, 0, 1, SCENE_MAX_SPP, NULL },
    [R_MAXDEPTH] = { "maxdepth", V_INT, 0, 0, SCENE_MAX_DEPTH, NULL },
    [R_ROULETTE] = { "roulette", V_ONOFF, 0, 0, 0, NULL },
    [R_RRDEPTH] = { "roulette_depth", V_INT, 0, 0, SCENE_MAX_DEPTH, NULL },
    [R_SEED] = { "seed", V_U64, 0, 0, 0, NULL },
    [R_INTEGRATOR] = { "integrator", V_STRING, 0, 0, 0, NULL },
    [R_AO_DISTANCE] = { "ao_distance", V_NUM, F_NONNEG, 0, 0, NULL },
    [R_THREADS] = { "threads", V_INT, 0, 0, SCENE_MAX_THREADS, NULL },
    [R_TIME_LIMIT] = { "time_limit", V_NUM, F_NONNEG, 0, 0, NULL },
    [R_PASSES] = { "passes", V_INT, 0, 1, SCENE_MAX_SPP, NULL },
    [R_CHECKPOINT] = { "checkpoint", V_ONOFF, 0, 0, 0, NULL },
    [R_ACCEL] = { "accel", V_WORD, 0, 0, 0, accels },
    [R_PACKETS] = { "packets", V_ONOFF, 0, 0, 0, NULL },
    [R_LIGHT] = { "light", V_WORD, 0, 0, 0, lights_shown },
};

/* `integrator WORD`: one of ch. 5's (integrators[]) or a rendering method
 * of a part the program offers (scenepart.h). */
static svet_status integrator_of(ctx_t *c, const tok_t *t,
                                 scene_render_t *r)
{
    for (int i = 0; integrators[i]; i++)
        if (tok_is(t, integrators[i])) {
            r->integrator = (scene_integrator)i;
            r->method = NULL;
            return SVET_OK;
        }
    char word[SCENE_MAX_NAME + 1];
    tok_copy(t, word, sizeof word);
    const render_method_t *m = t->quoted || t->len > SCENE_MAX_NAME
                                   ? NULL
                                   : scene_find_method(c->features, word);
    if (m) {
        r->integrator = SCENE_INTEGRATOR_PATH;
        r->method = m;
        return SVET_OK;
    }
    /* the methods of Part II that this program was built without */
    static const struct {
        const char *name, *chapter;
    } later[] = {
        { "photon", "the photon maps of ch. 8" },
        { "ppm", "the progressive photon maps of ch. 8" },
        { "irradiance", "the irradiance cache of ch. 9" },
        { "volpath", "the participating media of ch. 11" },
        { "volsingle", "the participating media of ch. 11" },
    };
    for (size_t i = 0; i < sizeof later / sizeof *later; i++)
        if (tok_is(t, later[i].name))
            return fail(c, t->col, SVET_ERR_UNSUPPORTED,
                        "'integrator %s': this program was built without "
                        "%s", later[i].name, later[i].chapter);
    const char *names[32];
    int n = 0;
    for (int i = 0; integrators[i] && n < 32; i++)
        names[n++] = integrators[i];
    const scene_part_t *const *parts = c->features ? c->features->parts
                                                   : NULL;
    for (int i = 0; parts && parts[i]; i++)
        for (int j = 0; parts[i]->methods && parts[i]->methods[j] && n < 32;
             j++)
            names[n++] = parts[i]->methods[j]->name;
    return unknown(c, t, "value of 'integrator'", names, n);
}

/* `render subsample step K threshold T`: app. F, where the program
 * offers it (scene_features_t.subsample; render/subsample.h's checks) */
enum { SS_STEP, SS_THRESHOLD, SS_N };
static const spec_t subsample_spec[SS_N] = {
    [SS_STEP] = { "step", V_INT, 0, 0, 256, NULL },
    [SS_THRESHOLD] = { "threshold", V_NUM, F_NONNEG, 0, 0, NULL },
};

static svet_status st_render_subsample(ctx_t *c)
{
    const tok_t *kw = &c->tok[c->pos++];
    if (!c->features || !c->features->subsample)
        return fail(c, kw->col, SVET_ERR_UNSUPPORTED,
                    "'render subsample': this program was built without "
                    "the subsampling of app. F");
    val_t v[SS_N];
    svet_status st = parse_keys(c, "render subsample", subsample_spec, SS_N,
                                v, false);
    if (st)
        return st;
    scene_render_t *r = &c->scene->render;
    long k = v[SS_STEP].set ? v[SS_STEP].i : r->subsample_step > 0
                                                 ? r->subsample_step : 4;
    if (k & (k - 1))
        return fail(c, v[SS_STEP].col, SVET_ERR_RANGE,
                    "'step' = %ld: must be 0 (off) or a power of 2 up to "
                    "256", k);
    if (v[SS_THRESHOLD].set && !(v[SS_THRESHOLD].v[0] < 1))
        return fail(c, v[SS_THRESHOLD].col, SVET_ERR_RANGE,
                    "'threshold' = %g: must lie in [0, 1)",
                    (double)v[SS_THRESHOLD].v[0]);
    r->subsample_step = (int)k;
    if (v[SS_THRESHOLD].set)
        r->subsample_threshold = v[SS_THRESHOLD].v[0];
    return SVET_OK;
}

static svet_status st_render(ctx_t *c)
{
    if (c->pos < c->ntok && tok_is(&c->tok[c->pos], "subsample"))
        return st_render_subsample(c);
    val_t v[R_N];
    svet_status st = parse_keys(c, "render", render_spec, R_N, v, false);
    if (st)
        return st;
    scene_render_t *r = &c->scene->render;
    if (v[R_SPP].set)
        r->spp = v[R_SPP].i;
    if (v[R_MAXDEPTH].set)
        r->max_depth = (int)v[R_MAXDEPTH].i;
    if (v[R_ROULETTE].set)
        r->roulette = v[R_ROULETTE].on;
    if (v[R_RRDEPTH].set)
        r->roulette_depth = (int)v[R_RRDEPTH].i;
    if (v[R_SEED].set)
        r->seed = v[R_SEED].u;
    if (v[R_INTEGRATOR].set) {
        st = integrator_of(c, &v[R_INTEGRATOR].word, r);
        if (st)
            return st;
    }
    if (v[R_AO_DISTANCE].set)
        r->ao_distance = v[R_AO_DISTANCE].v[0];
    if (v[R_THREADS].set)
        r->threads = (int)v[R_THREADS].i;
    if (v[R_TIME_LIMIT].set)
        r->time_limit = (double)v[R_TIME_LIMIT].v[0];
    if (v[R_PASSES].set)
        r->passes = (int)v[R_PASSES].i;
    if (v[R_CHECKPOINT].set)
        r->checkpoint = v[R_CHECKPOINT].on;
    if (v[R_ACCEL].set) {
        accel_kind k = (accel_kind)v[R_ACCEL].i;
        if (k > ACCEL_BRUTE &&
            !accel_offered(c->features ? c->features->accels : NULL, k))
            return fail(c, v[R_ACCEL].col, SVET_ERR_UNSUPPORTED,
                        "'accel %s': this program was built without %s",
                        accels[k], accel_kind_needs(k));
        r->accel = (scene_accel)k;
    }
    if (v[R_PACKETS].set)
        r->packets = v[R_PACKETS].on;
    if (v[R_LIGHT].set)
        r->light = (scene_light)v[R_LIGHT].i;
    return SVET_OK;
}

/* A copy of the string token in a new allocation, or NULL (out of memory). */
static char *tok_strdup(const tok_t *t)
{
    char *p = malloc((size_t)t->len + 1);
    if (p) {
        memcpy(p, t->s, (size_t)t->len);
        p[t->len] = '\0';
    }
    return p;
}

enum { O_EXR, O_PNG, O_N };
static const spec_t output_spec[O_N] = {
    [O_EXR] = { "exr", V_STRING, 0, 0, 0, NULL },
    [O_PNG] = { "png", V_STRING, 0, 0, 0, NULL },
};

static svet_status st_output(ctx_t *c)
{
    val_t v[O_N];
    svet_status st = parse_keys(c, "output", output_spec, O_N, v, false);
    if (st)
        return st;
    char *exr = NULL, *png = NULL;
    if ((v[O_EXR].set && !(exr = tok_strdup(&v[O_EXR].word))) ||
        (v[O_PNG].set && !(png = tok_strdup(&v[O_PNG].word)))) {
        free(exr);
        return fail(c, c->stmt_col, SVET_ERR_NOMEM, "out of memory");
    }
    scene_render_t *r = &c->scene->render;
    if (exr) {
        free(r->output_exr);
        r->output_exr = exr;
    }
    if (png) {
        free(r->output_png);
        r->output_png = png;
    }
    return SVET_OK;
}

static const char *const tonemaps[] = { "linear", "exponential",
                                        "reinhard", "drago", "histogram",
                                        NULL };
static const char *const curves[] = { "srgb", "gamma", "none", NULL };

enum { T_OPERATOR, T_EXPOSURE, T_KEY, T_WHITE, T_BIAS, T_CURVE, T_GAMMA,
       T_N };
static const spec_t tonemap_spec[T_N] = {
    [T_OPERATOR] = { "operator", V_WORD, 0, 0, 0, tonemaps },
    [T_EXPOSURE] = { "exposure", V_NUM, 0, 0, 0, NULL },
    [T_KEY] = { "key", V_NUM, F_POSITIVE, 0, 0, NULL },
    [T_WHITE] = { "white", V_NUM, F_NONNEG, 0, 0, NULL },
    [T_BIAS] = { "bias", V_NUM, F_POSITIVE, 0, 0, NULL },
    [T_CURVE] = { "curve", V_WORD, 0, 0, 0, curves },
    [T_GAMMA] = { "gamma", V_NUM, F_POSITIVE, 0, 0, NULL },
};

static svet_status st_tonemap(ctx_t *c)
{
    val_t v[T_N];
    svet_status st = parse_keys(c, "tonemap", tonemap_spec, T_N, v, false);
    if (st)
        return st;
    scene_tonemap_t tm = c->scene->render.tonemap;
    if (v[T_OPERATOR].set)
        tm.op = (scene_tonemap_op)v[T_OPERATOR].i;
    if (v[T_EXPOSURE].set) {
        tm.exposure = v[T_EXPOSURE].v[0];
        if (fabs(tm.exposure) > 100)
            return fail(c, v[T_EXPOSURE].col, SVET_ERR_RANGE,
                        "'exposure' is in stops: expected -100 to 100");
    }
    if (v[T_KEY].set) {
        tm.key = v[T_KEY].v[0];
        if (tm.key > 1)
            return fail(c, v[T_KEY].col, SVET_ERR_RANGE,
                        "'key' must lie in (0, 1]");
    }
    if (v[T_WHITE].set)
        tm.white = v[T_WHITE].v[0];
    if (v[T_BIAS].set) {
        tm.bias = v[T_BIAS].v[0];
        if (tm.bias > 1)
            return fail(c, v[T_BIAS].col, SVET_ERR_RANGE,
                        "'bias' must lie in (0, 1]");
    }
    if (v[T_CURVE].set)
        tm.curve = (scene_tonemap_curve)v[T_CURVE].i;
    if (v[T_GAMMA].set) {
        tm.gamma = v[T_GAMMA].v[0];
        if (tm.gamma > 10)
            return fail(c, v[T_GAMMA].col, SVET_ERR_RANGE,
                        "'gamma' must lie in (0, 10]");
    }
    c->scene->render.tonemap = tm;
    return SVET_OK;
}

/* --- lights -------------------------------------------------------------- */

/* The brightest radiance (W/(m^2 sr)) or intensity (W/sr) a light may
 * have, per channel: sqrt(FLT_MAX), about 1.8e19, in both builds. The
 * images are floats whatever real is (image.h), the variance image holds
 * squares of samples (render_variance), and the estimator multiplies a
 * light's L by ratios f cos / p that exceed 1 (next-event estimation near
 * a large emitter), so a light leaves that much headroom below FLT_MAX:
 * `emit 3e38` gave non-finite samples. */
static double max_emission(void)
{
    return sqrt((double)FLT_MAX);
}

/* Refuse the light colour L (named `what` in messages; given at col) when
 * a channel is brighter than max_emission(), or when its power, the
 * luminance of L times scale (pi A per emitting side, 4 pi, pi^2 r^2:
 * lightset_build's weights for choosing a light, light.c), overflows real
 * alone or added to the lights' powers before it. */
static svet_status check_light(ctx_t *c, int col, const char *what,
                               RADIANCE L, double scale)
{
    double top = fmax(fmax((double)L.r, (double)L.g), (double)L.b);
    if (top > max_emission())
        return fail(c, col, SVET_ERR_RANGE,
                    "%s %.3g is brighter than svet renders: at most %.3g per "
                    "channel (a sample's square must fit in a float image)",
                    what, top, max_emission());
    double phi = fmax(0.0, (double)rad_luminance(L)) * scale;
    if (!(scale <= (double)REAL_MAX) || !(phi <= (double)REAL_MAX))
        return fail(c, col, SVET_ERR_RANGE,
                    "the light's power, %.3g W, is more than %s holds", phi,
                    REAL_NAME);
    if (!(c->power + phi <= (double)REAL_MAX))
        return fail(c, col, SVET_ERR_RANGE,
                    "the lights' powers add up to %.3g W, more than %s holds",
                    c->power + phi, REAL_NAME);
    c->power += phi;
    return SVET_OK;
}

static const char *const light_kinds[] = { "point", NULL };

enum { L_POSITION, L_INTENSITY, L_POWER, L_CANDELA, L_LUMENS, L_COLOUR,
       L_N };
static const spec_t light_spec[L_N] = {
    [L_POSITION] = { "position", V_VEC3, F_REQUIRED, 0, 0, NULL },
    [L_INTENSITY] = { "intensity", V_COLOUR, 0, 0, 0, NULL },
    [L_POWER] = { "power", V_COLOUR, 0, 0, 0, NULL },
    [L_CANDELA] = { "candela", V_NUM, F_NONNEG, 0, 0, NULL },
    [L_LUMENS] = { "lumens", V_NUM, F_NONNEG, 0, 0, NULL },
    [L_COLOUR] = { "colour", V_COLOUR, 0, 0, 0, NULL },
};

static svet_status st_light(ctx_t *c)
{
    char show[64];
    if (c->pos >= c->ntok)
        return fail(c, c->eol_col, SVET_ERR_PARSE,
                    "light expects its kind: point");
    const tok_t *kind = &c->tok[c->pos];
    if (!tok_is(kind, "point"))
        return unknown(c, kind, "kind of light", light_kinds, 1);
    (void)show;
    c->pos++;
    val_t v[L_N];
    svet_status st = parse_keys(c, "light point", light_spec, L_N, v, false);
    if (st)
        return st;
    int given = v[L_INTENSITY].set + v[L_POWER].set + v[L_CANDELA].set +
                v[L_LUMENS].set;
    if (given != 1)
        return fail(c, c->stmt_col, SVET_ERR_PARSE,
                    "light point needs exactly one of 'intensity' (W/sr),"
                    " 'power' (W), 'candela' or 'lumens'");
    if (v[L_COLOUR].set && !v[L_CANDELA].set && !v[L_LUMENS].set)
        return fail(c, v[L_COLOUR].col, SVET_ERR_PARSE,
                    "'colour' goes with 'candela' or 'lumens' only "
                    "(intensity and power take r g b themselves)");
    RADIANCE I;
    if (v[L_INTENSITY].set) {
        I = rad_make(v[L_INTENSITY].v[0], v[L_INTENSITY].v[1],
                     v[L_INTENSITY].v[2]);
    } else if (v[L_POWER].set) {
        /* An isotropic source spreads Phi over 4 pi sr: I = Phi / (4 pi). */
        I = rad_scale(rad_make(v[L_POWER].v[0], v[L_POWER].v[1],
                               v[L_POWER].v[2]),
                      1 / (4 * REAL_PI));
    } else {
        RADIANCE colour = rad_grey(1);
        if (v[L_COLOUR].set)
            colour = rad_make(v[L_COLOUR].v[0], v[L_COLOUR].v[1],
                              v[L_COLOUR].v[2]);
        if (!(colour_luminance(colour) > 0))
            return fail(c, v[L_COLOUR].col, SVET_ERR_RANGE,
                        "'colour' must have a luminance > 0");
        /* eq. (1.2): candela = 683 lm/W times the luminance of the
         * intensity in W/sr; lumens spread over 4 pi sr (colour.h). */
        I = v[L_CANDELA].set
                ? colour_point_intensity(colour, v[L_CANDELA].v[0],
                                         COLOUR_UNIT_CANDELA, 0)
                : colour_point_intensity(colour, v[L_LUMENS].v[0],
                                         COLOUR_UNIT_LUMEN, 0);
    }
    if (!rad_is_finite(I))
        return fail(c, c->stmt_col, SVET_ERR_RANGE,
                    "the light's intensity overflows %s", REAL_NAME);
    /* Phi = 4 pi I (light.c) */
    int key = v[L_INTENSITY].set ? L_INTENSITY : v[L_POWER].set ? L_POWER
              : v[L_CANDELA].set ? L_CANDELA : L_LUMENS;
    st = check_light(c, v[key].col, "the intensity", I, 4 * PI_D);
    if (st)
        return st;
    svet_error e;
    st = scene_add_point_light(c->scene, v[L_POSITION].v, I, &e);
    if (st)
        return fail(c, c->stmt_col, st, "%s", e.msg);
    return SVET_OK;
}

enum { E_RADIANCE, E_N };
static const spec_t environment_spec[E_N] = {
    [E_RADIANCE] = { "radiance", V_COLOUR, F_REQUIRED, 0, 0, NULL },
};

static svet_status st_environment(ctx_t *c)
{
    val_t v[E_N];
    svet_status st = parse_keys(c, "environment", environment_spec, E_N, v,
                             false);
    if (st)
        return st;
    if (c->environment_line)
        return fail(c, c->stmt_col, SVET_ERR_PARSE,
                    "the environment is already defined on line %d",
                    c->environment_line);
    c->environment_line = c->line;
    c->environment_col = v[E_RADIANCE].col;
    c->scene->has_environment = true;
    c->scene->environment = rad_make(v[E_RADIANCE].v[0], v[E_RADIANCE].v[1],
                                     v[E_RADIANCE].v[2]);
    /* its power needs the scene's size: whole_scene() checks it */
    return check_light(c, v[E_RADIANCE].col, "the radiance",
                       c->scene->environment, 0);
}

/* --- materials ----------------------------------------------------------- */

/* The components of the book's mixed surface, f = f_r^d + f_r^s + f_r^g +
 * f_t^s + f_t^d (material.h), and `glass`, a shorthand for a mirror and a
 * transmission with Fresnel's reflectance at normal incidence. */
static const char *const components[] = {
    "lambert", "mirror", "phong", "ward", "transmission",
    "diffuse_transmission", "glass", "bump", NULL
};
enum { C_LAMBERT, C_MIRROR, C_PHONG, C_WARD, C_TRANSMISSION, C_DIFFUSE_T,
       C_GLASS, C_BUMP, C_N };

enum { M_RHO, M_E, M_ALPHA, M_ALPHA_X, M_ALPHA_Y, M_BOUNDED, M_ETA, M_TINT,
       M_N };
/* F_NAMED: a texture's name may stand in place of the value (ch. 10) */
static const spec_t lambert_spec[] = {
    { "rho", V_COLOUR, F_REQUIRED | F_NAMED, 0, 0, NULL },
};
/* `fresnel schlick|exact` on the smooth interface's components: the
 * book's Schlick (1.7), or Fresnel's exact reflectance (brdf.h) */
static const char *const fresnels[] = { "schlick", "exact", NULL };
static const spec_t mirror_spec[] = {
    { "rho", V_COLOUR, F_REQUIRED | F_NAMED, 0, 0, NULL },
    { "eta", V_NUM, F_POSITIVE, 0, 0, NULL },
    { "fresnel", V_WORD, 0, 0, 0, fresnels },
};
static const spec_t phong_spec[] = {
    { "rho", V_COLOUR, F_REQUIRED | F_NAMED, 0, 0, NULL },
    { "e", V_NUM, F_NONNEG | F_NAMED, 0, 0, NULL },
};
static const spec_t ward_spec[] = {
    { "rho", V_COLOUR, F_REQUIRED | F_NAMED, 0, 0, NULL },
    { "alpha", V_NUM, F_POSITIVE | F_NAMED, 0, 0, NULL },
    { "alpha_x", V_NUM, F_POSITIVE | F_NAMED, 0, 0, NULL },
    { "alpha_y", V_NUM, F_POSITIVE | F_NAMED, 0, 0, NULL },
    { "bounded", V_FLAG, 0, 0, 0, NULL },
};
static const spec_t transmission_spec[] = {
    { "rho", V_COLOUR, F_REQUIRED | F_NAMED, 0, 0, NULL },
    { "eta", V_NUM, F_POSITIVE, 0, 0, NULL },
    { "fresnel", V_WORD, 0, 0, 0, fresnels },
};
static const spec_t bump_spec[] = {
    { "strength", V_NUM, 0, 0, 0, NULL },
};

/* Note the names component `kind`'s keys v[] gave in place of values
 * (F_NAMED): key i of the component is parameter params[i]. A named number
 * is left unset, so that the material is built with its default. */
static svet_status note_named(ctx_t *c, val_t *v, int nv,
                              const scene_param_t *params)
{
    for (int i = 0; i < nv; i++) {
        if (!v[i].named)
            continue;
        if (c->nnamed == MAX_NAMED)
            return fail(c, v[i].word.col, SVET_ERR_RANGE,
                        "more than %d names in place of values on one "
                        "material", MAX_NAMED);
        c->named[c->nnamed++] = (scene_named_t){ params[i], v[i].word, 1 };
        if (i > 0)
            v[i].set = false; /* a number, not a colour: keep its default */
    }
    return SVET_OK;
}
static const spec_t glass_spec[] = {
    { "eta", V_NUM, F_REQUIRED | F_POSITIVE, 0, 0, NULL },
    { "tint", V_COLOUR, 0, 0, 0, NULL },
    { "fresnel", V_WORD, 0, 0, 0, fresnels },
};

static RADIANCE colour_of(const val_t *v)
{
    return rad_make(v->v[0], v->v[1], v->v[2]);
}

/* Parse one component (the current token names it) into p. seen[] marks
 * the kinds already given; *eta_col where eta was set. */
static svet_status component(ctx_t *c, material_params *p, int seen[C_N],
                             int *eta_col)
{
    const tok_t *t = &c->tok[c->pos];
    int kind = -1;
    for (int i = 0; i < C_N; i++)
        if (tok_is(t, components[i]))
            kind = i;
    if (kind < 0)
        return unknown(c, t, "material component", components, C_N);
    /* The mixed surface has one component of each kind, and one glossy
     * lobe, Phong or Ward (material.h). */
    int slot = kind == C_WARD ? C_PHONG : kind;
    int clash = slot == C_GLASS ? (seen[C_MIRROR] ? seen[C_MIRROR]
                                                  : seen[C_TRANSMISSION])
                : (kind == C_MIRROR || kind == C_TRANSMISSION)
                    ? (seen[slot] ? seen[slot] : seen[C_GLASS])
                    : seen[slot];
    if (clash)
        return fail(c, t->col, SVET_ERR_PARSE,
                    "the material already has this kind of component (at "
                    "column %d): a mixed surface sums one of each",
                    clash);
    seen[slot] = t->col;
    c->pos++;
    char what[48];
    snprintf(what, sizeof what, "component '%s'", components[kind]);
    val_t v[M_N];
    svet_status st;
    real eta = 0;
    /* A missing key is reported at the component, not the statement. */
    int stmt_col = c->stmt_col;
    c->stmt_col = t->col;
    static const scene_param_t rho_of[C_N] = {
        [C_LAMBERT] = SCENE_PARAM_RHO_D, [C_MIRROR] = SCENE_PARAM_RHO_S,
        [C_PHONG] = SCENE_PARAM_RHO_G, [C_WARD] = SCENE_PARAM_RHO_G,
        [C_TRANSMISSION] = SCENE_PARAM_RHO_T,
        [C_DIFFUSE_T] = SCENE_PARAM_RHO_DT
    };
    const scene_param_t params[5] = {
        rho_of[kind], kind == C_PHONG ? SCENE_PARAM_E : SCENE_PARAM_ALPHA,
        SCENE_PARAM_ALPHA_X, SCENE_PARAM_ALPHA_Y, SCENE_PARAM_ALPHA
    };
    switch (kind) {
    case C_LAMBERT:
        st = parse_keys(c, what, lambert_spec, 1, v, true);
        if (!st)
            st = note_named(c, v, 1, params);
        if (!st)
            p->rho_d = colour_of(&v[0]);
        break;
    case C_BUMP: {
        /* `bump NAME strength S`: a height map (Blinn 1978), ch. 10 */
        if (c->pos >= c->ntok || !name_ok(&c->tok[c->pos])) {
            st = fail(c, c->pos < c->ntok ? c->tok[c->pos].col : c->eol_col,
                      SVET_ERR_PARSE, "'bump' expects the name of a "
                      "texture, then 'strength S'");
            break;
        }
        tok_t name = c->tok[c->pos++];
        st = parse_keys(c, what, bump_spec, 1, v, true);
        if (st)
            break;
        if (c->nnamed == MAX_NAMED) {
            st = fail(c, name.col, SVET_ERR_RANGE, "too many names on one "
                      "material");
            break;
        }
        c->named[c->nnamed++] = (scene_named_t){
            SCENE_PARAM_BUMP, name, v[0].set ? v[0].v[0] : 1
        };
        break;
    }
    case C_MIRROR:
    case C_TRANSMISSION:
        st = parse_keys(c, what, kind == C_MIRROR ? mirror_spec
                                                  : transmission_spec,
                        3, v, true);
        if (!st)
            st = note_named(c, v, 1, params);
        if (st)
            break;
        if (v[2].set && v[2].i == 1)
            p->fresnel_exact = true;
        if (kind == C_MIRROR)
            p->rho_s = colour_of(&v[0]);
        else
            p->rho_t = colour_of(&v[0]);
        if (v[1].set)
            eta = v[1].v[0];
        break;
    case C_PHONG:
        st = parse_keys(c, what, phong_spec, 2, v, true);
        if (!st)
            st = note_named(c, v, 2, params);
        if (st)
            break;
        p->gloss = MATERIAL_GLOSS_PHONG;
        p->rho_g = colour_of(&v[0]);
        if (v[1].set)
            p->e = v[1].v[0];
        break;
    case C_WARD:
        st = parse_keys(c, what, ward_spec, 5, v, true);
        if (!st)
            st = note_named(c, v, 4, params);
        if (st)
            break;
        if (v[1].set && (v[2].set || v[3].set)) {
            st = fail(c, v[1].col, SVET_ERR_PARSE,
                      "give either 'alpha' (isotropic) or 'alpha_x' and "
                      "'alpha_y' (anisotropic), not both");
            break;
        }
        if (v[2].set != v[3].set) {
            st = fail(c, v[v[2].set ? 2 : 3].col, SVET_ERR_PARSE,
                      "an anisotropic Ward lobe needs both 'alpha_x' and "
                      "'alpha_y'");
            break;
        }
        p->gloss = v[4].on ? MATERIAL_GLOSS_WARD_BOUNDED : MATERIAL_GLOSS_WARD;
        p->rho_g = colour_of(&v[0]);
        if (v[1].set)
            p->alpha_x = p->alpha_y = v[1].v[0];
        if (v[2].set) {
            p->alpha_x = v[2].v[0];
            p->alpha_y = v[3].v[0];
        }
        break;
    case C_DIFFUSE_T:
        st = parse_keys(c, what, lambert_spec, 1, v, true);
        if (!st)
            st = note_named(c, v, 1, params);
        if (!st)
            p->rho_dt = colour_of(&v[0]);
        break;
    default: { /* C_GLASS */
        st = parse_keys(c, what, glass_spec, 3, v, true);
        if (st)
            break;
        if (v[2].set && v[2].i == 1)
            p->fresnel_exact = true;
        eta = v[0].v[0];
        /* Fresnel's reflectance at normal incidence, ((eta-1)/(eta+1))^2
         * (Schlick 1994, the rho_s(0) of eq. (1.7)); what is not
         * reflected is transmitted, times the tint. */
        real r0 = (eta - 1) / (eta + 1);
        r0 *= r0;
        RADIANCE tint = v[1].set ? colour_of(&v[1]) : rad_grey(1);
        p->rho_s = rad_grey(r0);
        p->rho_t = rad_scale(tint, 1 - r0);
        break;
    }
    }
    c->stmt_col = stmt_col;
    if (st)
        return st;
    if (eta > 0) {
        if (*eta_col && p->eta != eta)
            return fail(c, seen[slot], SVET_ERR_PARSE,
                        "the material has one index ratio eta, and column "
                        "%d already set it to %g",
                        *eta_col, (double)p->eta);
        p->eta = eta;
        *eta_col = seen[slot];
    }
    return SVET_OK;
}

static bool name_ok(const tok_t *t)
{
    if (t->quoted || t->len == 0 || t->len > SCENE_MAX_NAME ||
        !(isalpha((unsigned char)t->s[0]) || t->s[0] == '_'))
        return false;
    for (int i = 0; i < t->len; i++) {
        unsigned char ch = (unsigned char)t->s[i];
        if (!isalnum(ch) && ch != '_' && ch != '-' && ch != '.')
            return false;
    }
    return true;
}

/* Hand the names the material gave in place of values to the part that
 * resolves them (the textures of ch. 10, scenepart.h). */
static svet_status material_names(ctx_t *c, const char *name,
                                  const material_t *m)
{
    const scene_part_t *const *parts = c->features ? c->features->parts
                                                   : NULL;
    for (int i = 0; parts && parts[i]; i++)
        if (parts[i]->material_names)
            return parts[i]->material_names(c, name, m, c->named,
                                             c->nnamed);
    char show[64];
    const scene_named_t *n = &c->named[0];
    if (n->param == SCENE_PARAM_BUMP)
        return fail(c, n->name.col, SVET_ERR_UNSUPPORTED,
                    "'bump %s': this program was built without the "
                    "textures of ch. 10", show_tok(&n->name, show,
                                                   sizeof show));
    return fail(c, n->name.col, SVET_ERR_PARSE,
                "expected a number, got '%s' (a texture's name goes here "
                "only in a program built with the textures of ch. 10)",
                show_tok(&n->name, show, sizeof show));
}

static svet_status st_material(ctx_t *c)
{
    char show[64], name[SCENE_MAX_NAME + 1];
    if (c->pos >= c->ntok)
        return fail(c, c->eol_col, SVET_ERR_PARSE,
                    "material expects a name, then its components");
    const tok_t *nt = &c->tok[c->pos++];
    if (!name_ok(nt))
        return fail(c, nt->col, SVET_ERR_PARSE,
                    "'%s' is not a material name: expected a letter or '_' "
                    "then letters, digits, '_', '-' or '.' (at most %d)",
                    show_tok(nt, show, sizeof show), SCENE_MAX_NAME);
    tok_copy(nt, name, sizeof name);
    if (scene_find_material(c->scene, name))
        return fail(c, nt->col, SVET_ERR_PARSE,
                    "material '%s' is already defined", name);
    material_params p;
    material_params_default(&p);
    int seen[C_N] = { 0 };
    int eta_col = 0;
    c->nnamed = 0;
    if (c->pos >= c->ntok)
        return fail(c, c->eol_col, SVET_ERR_PARSE,
                    "material '%s' expects a component: %s", name,
                    "lambert, mirror, phong, ward, transmission, "
                    "diffuse_transmission or glass");
    for (;;) {
        svet_status st = component(c, &p, seen, &eta_col);
        if (st)
            return st;
        if (c->pos >= c->ntok)
            break;
        /* parse_keys stopped at a '+': another component follows. */
        int plus_col = c->tok[c->pos].col;
        c->pos++;
        if (c->pos >= c->ntok)
            return fail(c, plus_col, SVET_ERR_PARSE,
                        "expected a component after '+'");
    }
    material_t *m = NULL;
    svet_error e;
    svet_status st = material_new(&p, &m, &e);
    if (st)
        return fail(c, nt->col, st, "material '%s': %s", name, e.msg);
    st = scene_add_material(c->scene, name, m, &e);
    if (st)
        return fail(c, nt->col, st, "%s", e.msg);
    if (c->nnamed > 0)
        return material_names(c, name, m);
    return SVET_OK;
}

/* --- transforms ---------------------------------------------------------- */

/* The statement's transforms composed in the written order (xform.h):
 * T = T_n ... T_2 T_1. Each was checked when parsed (nonzero scale
 * factors and rotation axis, finite numbers), but their product may still
 * overflow or underflow (scale 1e30 scale 1e30): then it is refused. */
static svet_status xform_of_list(ctx_t *c, xform_t *x)
{
    *x = xform_identity();
    for (int i = 0; i < c->nxf; i++) {
        const xform_op *op = &c->xf[i];
        xform_t t = op->kind == XF_SCALE ? xform_scale(op->v)
                    : op->kind == XF_ROTATE ? xform_rotate(op->v, op->v[3])
                                            : xform_translate(op->v);
        *x = xform_compose(*x, t);
    }
    if (!x->valid)
        return fail(c, c->nxf ? c->xf[0].col : c->stmt_col, SVET_ERR_RANGE,
                    "the transforms do not make an invertible map in %s "
                    "(a factor too large or too small)", REAL_NAME);
    return SVET_OK;
}

/* --- objects ------------------------------------------------------------- */

/* Keys every object takes, after its own. */
enum { K_MATERIAL, K_EMIT, K_TWOSIDED, K_SCALE, K_ROTATE, K_TRANSLATE,
       K_COMMON };
static const spec_t common_spec[K_COMMON] = {
    [K_MATERIAL] = { "material", V_STRING, 0, 0, 0, NULL },
    /* F_NAMED: a texture's name may stand in place of the radiance */
    [K_EMIT] = { "emit", V_COLOUR, F_NAMED, 0, 0, NULL },
    [K_TWOSIDED] = { "twosided", V_FLAG, 0, 0, 0, NULL },
    [K_SCALE] = { "scale", V_SCALE, 0, 0, 0, NULL },
    [K_ROTATE] = { "rotate", V_ROTATE, 0, 0, 0, NULL },
    [K_TRANSLATE] = { "translate", V_TRANSLATE, 0, 0, 0, NULL },
};

enum { S_SPHERE, S_PLANE, S_DISK, S_PARALLELOGRAM, S_TRIANGLE, S_BOX,
       S_CYLINDER, S_CONE, S_NSHAPES };
#define MAX_GEO 5
static const struct {
    const char *name;
    int ngeo;
    spec_t geo[MAX_GEO];
} shapes[S_NSHAPES] = {
    [S_SPHERE] = { "sphere", 2, {
        { "centre", V_VEC3, F_REQUIRED, 0, 0, NULL },
        { "radius", V_NUM, F_REQUIRED | F_POSITIVE, 0, 0, NULL } } },
    [S_PLANE] = { "plane", 2, {
        { "point", V_VEC3, F_REQUIRED, 0, 0, NULL },
        { "normal", V_VEC3, F_REQUIRED | F_NONZERO, 0, 0, NULL } } },
    [S_DISK] = { "disk", 3, {
        { "centre", V_VEC3, F_REQUIRED, 0, 0, NULL },
        { "normal", V_VEC3, F_REQUIRED | F_NONZERO, 0, 0, NULL },
        { "radius", V_NUM, F_REQUIRED | F_POSITIVE, 0, 0, NULL } } },
    [S_PARALLELOGRAM] = { "parallelogram", 4, {
        { "c0", V_VEC3, F_REQUIRED, 0, 0, NULL },
        { "c1", V_VEC3, F_REQUIRED, 0, 0, NULL },
        { "c2", V_VEC3, 0, 0, 0, NULL },
        { "c3", V_VEC3, F_REQUIRED, 0, 0, NULL } } },
    [S_TRIANGLE] = { "triangle", 3, {
        { "p0", V_VEC3, F_REQUIRED, 0, 0, NULL },
        { "p1", V_VEC3, F_REQUIRED, 0, 0, NULL },
        { "p2", V_VEC3, F_REQUIRED, 0, 0, NULL } } },
    [S_BOX] = { "box", 2, {
        { "min", V_VEC3, F_REQUIRED, 0, 0, NULL },
        { "max", V_VEC3, F_REQUIRED, 0, 0, NULL } } },
    [S_CYLINDER] = { "cylinder", 4, {
        { "base", V_VEC3, F_REQUIRED, 0, 0, NULL },
        { "top", V_VEC3, F_REQUIRED, 0, 0, NULL },
        { "radius", V_NUM, F_REQUIRED | F_POSITIVE, 0, 0, NULL },
        { "open", V_FLAG, 0, 0, 0, NULL } } },
    [S_CONE] = { "cone", 4, {
        { "base", V_VEC3, F_REQUIRED, 0, 0, NULL },
        { "apex", V_VEC3, F_REQUIRED, 0, 0, NULL },
        { "radius", V_NUM, F_REQUIRED | F_POSITIVE, 0, 0, NULL },
        { "open", V_FLAG, 0, 0, 0, NULL } } },
};

/* The material named by the key, or a "did you mean" error. */
static svet_status find_material(ctx_t *c, const val_t *v,
                                 const material_t **m)
{
    char name[SCENE_MAX_NAME + 1], show[64];
    if (v->word.len > SCENE_MAX_NAME) {
        return fail(c, v->word.col, SVET_ERR_PARSE,
                    "undefined material '%s'",
                    show_tok(&v->word, show, sizeof show));
    }
    tok_copy(&v->word, name, sizeof name);
    *m = scene_find_material(c->scene, name);
    if (*m)
        return SVET_OK;
    const char *near = scene_suggest_material(c->scene, name);
    if (near)
        return fail(c, v->word.col, SVET_ERR_PARSE,
                    "undefined material '%s' (did you mean '%s'?)",
                    show_tok(&v->word, show, sizeof show), near);
    return fail(c, v->word.col, SVET_ERR_PARSE,
                "undefined material '%s': define it with a 'material' line "
                "above this one", show_tok(&v->word, show, sizeof show));
}

/* The length of the diagonal of b, in double (the float difference of
 * the corners may overflow). */
static double diagonal(const bbox_t *b)
{
    double d2 = 0;
    for (int k = 0; k < 3; k++) {
        double d = (double)b->max[k] - (double)b->min[k];
        d2 += d * d;
    }
    return sqrt(d2);
}

/* Keep obj's size for whole_scene()'s check of the range real resolves:
 * its bounds join the scene's, and the smallest object is remembered
 * with its line. Objects of infinite area (a plane, whose bounds span
 * the reals) are left out. */
static void note_size(ctx_t *c, const COBJECT *obj)
{
    bbox_t b;
    obj->ops->bounds(obj, -1, &b);
    if (!isfinite(obj->ops->area(obj)) || bbox_is_empty(&b) ||
        !vec_is_finite(b.min) || !vec_is_finite(b.max))
        return;
    bbox_union(&c->bounds, &b);
    double d = diagonal(&b);
    if (!c->smallest_line || d < c->smallest) {
        c->smallest = d;
        c->smallest_line = c->line;
    }
}

/* Hand a name given to `emit` to the part that resolves it (the textures
 * of ch. 10, scenepart.h). */
static svet_status emit_name(ctx_t *c, scene_emission_t *e, const tok_t *t,
                             RADIANCE *top)
{
    const scene_part_t *const *parts = c->features ? c->features->parts
                                                   : NULL;
    for (int i = 0; parts && parts[i]; i++)
        if (parts[i]->emit_name)
            return parts[i]->emit_name(c, e, t, top);
    char show[64];
    return fail(c, t->col, SVET_ERR_PARSE,
                "expected a number, got '%s' (a texture's name goes here "
                "only in a program built with the textures of ch. 10)",
                show_tok(t, show, sizeof show));
}

/* Add obj with material m to the scene, and its emission if the statement
 * gives one. obj is the scene's (or freed) afterwards. */
static svet_status add_object(ctx_t *c, COBJECT *obj, const material_t *m,
                              const val_t *common)
{
    svet_error e;
    svet_status st = scene_add_object(c->scene, obj, m, &e);
    if (st)
        return fail(c, c->stmt_col, st, "%s", e.msg);
    note_size(c, obj);
    if (common[K_EMIT].set) {
        /* Phi = pi A L per emitting side (light.c) */
        RADIANCE L = colour_of(&common[K_EMIT]);
        double scale = (common[K_TWOSIDED].on ? 2 : 1) * PI_D *
                       (double)obj->ops->area(obj);
        if (common[K_EMIT].named) {
            st = scene_set_emission(c->scene, obj, rad_grey(0),
                                    common[K_TWOSIDED].on, &e);
            if (st)
                return fail(c, common[K_EMIT].col, st, "%s", e.msg);
            st = emit_name(c, c->scene->emitters[c->scene->nemitters - 1],
                           &common[K_EMIT].word, &L);
            if (st)
                return st;
            /* the texture's brightest value, as if everywhere */
            return check_light(c, common[K_EMIT].col,
                               "the radiance 'emit'", L, scale);
        }
        st = check_light(c, common[K_EMIT].col, "the radiance 'emit'", L,
                         scale);
        if (st)
            return st;
        st = scene_set_emission(c->scene, obj, L, common[K_TWOSIDED].on,
                                &e);
        if (st)
            return fail(c, common[K_EMIT].col, st, "%s", e.msg);
    }
    return SVET_OK;
}

/* The shape keys of the parts the program offers (scenepart.h), appended
 * to spec after its n keys; returns the new count. */
static int part_shape_keys(const ctx_t *c, spec_t *spec, int n)
{
    const scene_part_t *const *parts = c->features ? c->features->parts
                                                   : NULL;
    int added = 0;
    for (int i = 0; parts && parts[i]; i++)
        for (int k = 0; k < parts[i]->nshape_keys &&
                        added < SCENE_MAX_SHAPE_KEYS; k++)
            spec[n + added++] = parts[i]->shape_keys[k];
    return n + added;
}

/* Hand each part the values of its shape keys (vals, in the order
 * part_shape_keys appended them) for the objects the statement added, the
 * scene's objects from index first on. */
static svet_status apply_shape_keys(ctx_t *c, const val_t *vals, int first)
{
    const scene_part_t *const *parts = c->features ? c->features->parts
                                                   : NULL;
    int at = 0;
    for (int i = 0; parts && parts[i]; i++) {
        const scene_part_t *p = parts[i];
        int n = p->nshape_keys;
        if (at + n > SCENE_MAX_SHAPE_KEYS)
            n = SCENE_MAX_SHAPE_KEYS - at;
        bool any = false;
        for (int k = 0; k < n; k++)
            any = any || vals[at + k].set;
        if (any && p->shape) {
            svet_status st = p->shape(c, c->scene->objects + first,
                                      c->scene->nobjects - first,
                                      vals + at);
            if (st)
                return st;
        }
        at += n;
    }
    return SVET_OK;
}

/* A corner given with the statement, moved by the statement's transform. */
static void corner(const xform_t *x, const val_t *v, VECTOR3 out)
{
    xform_point(x, out, v->v);
}

static svet_status st_shape(ctx_t *c)
{
    int kind = 0;
    while (!tok_is(&c->tok[0], shapes[kind].name))
        kind++;
    spec_t spec[MAX_GEO + K_COMMON + SCENE_MAX_SHAPE_KEYS];
    int ngeo = shapes[kind].ngeo;
    memcpy(spec, shapes[kind].geo, (size_t)ngeo * sizeof *spec);
    memcpy(spec + ngeo, common_spec, sizeof common_spec);
    int nspec = part_shape_keys(c, spec, ngeo + K_COMMON);
    val_t v[MAX_GEO + K_COMMON + SCENE_MAX_SHAPE_KEYS];
    svet_status st = parse_keys(c, shapes[kind].name, spec, nspec, v, false);
    if (st)
        return st;
    const val_t *common = v + ngeo;
    if (!common[K_MATERIAL].set)
        return fail(c, c->stmt_col, SVET_ERR_PARSE,
                    "%s needs 'material' (the name of a material defined "
                    "above)", shapes[kind].name);
    if (common[K_TWOSIDED].set && !common[K_EMIT].set)
        return fail(c, common[K_TWOSIDED].col, SVET_ERR_PARSE,
                    "'twosided' says an emitter emits on both sides: it "
                    "needs 'emit'");
    const material_t *m;
    st = find_material(c, &common[K_MATERIAL], &m);
    if (st)
        return st;
    if (kind == S_PLANE && common[K_EMIT].set)
        return fail(c, common[K_EMIT].col, SVET_ERR_RANGE,
                    "a plane has no finite area, so it cannot emit: use a "
                    "parallelogram or a disk");

    svet_error e;
    svet_error_clear(&e);
    COBJECT *obj = NULL;
    bool flat = kind == S_TRIANGLE || kind == S_PARALLELOGRAM;
    xform_t x;
    st = xform_of_list(c, &x);
    if (st)
        return st;
    switch (kind) {
    case S_SPHERE:
        obj = sphere_new(v[0].v, v[1].v[0], &e);
        break;
    case S_PLANE:
        obj = plane_new(v[0].v, v[1].v, &e);
        break;
    case S_DISK:
        obj = disk_new(v[0].v, v[1].v, v[2].v[0], &e);
        break;
    case S_TRIANGLE: {
        VECTOR3 p0, p1, p2;
        corner(&x, &v[0], p0);
        corner(&x, &v[1], p1);
        corner(&x, &v[2], p2);
        if (!vec_is_finite(p0) || !vec_is_finite(p1) || !vec_is_finite(p2))
            return fail(c, c->xf[0].col, SVET_ERR_RANGE,
                        "the transformed corners overflow %s", REAL_NAME);
        if (triangle_is_degenerate(p0, p1, p2))
            return fail(c, c->stmt_col, SVET_ERR_RANGE,
                        "the triangle has no area: its corners are (nearly)"
                        " collinear");
        obj = triangle_new(p0, p1, p2, &e);
        break;
    }
    case S_PARALLELOGRAM: {
        VECTOR3 c0, c1, c2, c3;
        corner(&x, &v[0], c0);
        corner(&x, &v[1], c1);
        corner(&x, &v[3], c3);
        if (v[2].set) {
            /* c2 is redundant (c1 + c3 - c0) and checked: a typo in a
             * corner must not silently make another shape. */
            corner(&x, &v[2], c2);
            obj = parallelogram_new4(c0, c1, c2, c3, &e);
            if (!obj)
                return fail(c, v[2].col, e.status, "%s", e.msg);
        } else {
            obj = parallelogram_new(c0, c1, c3, &e);
        }
        break;
    }
    case S_BOX:
        obj = box_new(v[0].v, v[1].v, &e);
        break;
    case S_CYLINDER:
        obj = cylinder_new(v[0].v, v[1].v, v[2].v[0], !v[3].on, &e);
        break;
    default: /* S_CONE */
        obj = cone_new(v[0].v, v[1].v, v[2].v[0], !v[3].on, &e);
        break;
    }
    if (!obj)
        return fail(c, c->stmt_col, e.status ? e.status : SVET_ERR_RANGE,
                    "%s", e.msg);
    if (c->nxf > 0 && !flat) {
        obj = xform_new(obj, &x, &e);
        if (!obj)
            return fail(c, c->xf[0].col, e.status ? e.status
                                                  : SVET_ERR_RANGE,
                        "%s", e.msg);
    }
    int first = c->scene->nobjects;
    st = add_object(c, obj, m, common);
    if (st)
        return st;
    return apply_shape_keys(c, common + K_COMMON, first);
}

/* Is stmt the keyword of a shape or of a mesh? */
static bool is_shape_statement(const char *stmt)
{
    for (int k = 0; k < S_NSHAPES; k++)
        if (strcmp(stmt, shapes[k].name) == 0)
            return true;
    return strcmp(stmt, "mesh") == 0;
}

/* --- meshes -------------------------------------------------------------- */

/* The mesh files are read by the loader the program offers
 * (scene_features_t.mesh, scene.h: objmesh.h's for OBJ files); this file
 * names no mesh or OBJ function, so ch. 5 links neither. */

enum { MESH_FILE, MESH_STRICT, MESH_NGEO };
static const spec_t mesh_geo[MESH_NGEO] = {
    [MESH_FILE] = { "file", V_STRING, F_REQUIRED, 0, 0, NULL },
    [MESH_STRICT] = { "strict", V_FLAG, 0, 0, 0, NULL },
};

/* Give each part of the mesh file the scene material of its usemtl name,
 * or the default (dflt, may be NULL) for faces before any usemtl and,
 * unless strict, for names the scene does not define; the parts taken by
 * the scene are set to NULL in parts. */
static svet_status add_mesh_parts(ctx_t *c, scene_mesh_part_t *parts,
                                  int nparts, const material_t *dflt,
                                  const val_t *v, const val_t *common)
{
    char show[64];
    tok_t file = v[MESH_FILE].word;
    for (int k = 0; k < nparts; k++) {
        const char *name = parts[k].material;
        const material_t *m = name ? scene_find_material(c->scene, name)
                                   : NULL;
        if (!m && name && v[MESH_STRICT].on) {
            const char *near = scene_suggest_material(c->scene, name);
            return fail(c, file.col, SVET_ERR_PARSE,
                        "%s: usemtl '%.64s' is not a material of the "
                        "scene%s%s%s",
                        show_tok(&file, show, sizeof show), name,
                        near ? " (did you mean '" : "", near ? near : "",
                        near ? "'?)" : "");
        }
        if (!m)
            m = dflt;
        if (!m && name)
            return fail(c, c->stmt_col, SVET_ERR_PARSE,
                        "%s: usemtl '%.64s' is not a material of the "
                        "scene: give the mesh a default 'material'",
                        show_tok(&file, show, sizeof show), name);
        if (!m)
            return fail(c, c->stmt_col, SVET_ERR_PARSE,
                        "%s: faces without usemtl need a default "
                        "'material'",
                        show_tok(&file, show, sizeof show));
        COBJECT *obj = parts[k].obj;
        parts[k].obj = NULL; /* the scene has it now */
        svet_status st = add_object(c, obj, m, common);
        if (st)
            return st;
    }
    return SVET_OK;
}

/* The mesh file's warnings w (each with its own file:line:col) into the
 * scene's, after the scene's file:line:col of the file name (col); with
 * `strict` the first is an error instead. */
static svet_status mesh_warnings(ctx_t *c, int col,
                                 const scene_warnings_t *w, bool strict)
{
    long kept = w->n < SCENE_MAX_WARNINGS ? w->n : SCENE_MAX_WARNINGS;
    if (strict && w->n > 0) {
        /* "x.obj:3:1: warning: what" is told as "x.obj:3:1: what" */
        char msg[SVET_ERROR_LEN];
        snprintf(msg, sizeof msg, "%s", w->msg[0]);
        char *tag = strstr(msg, ": warning: ");
        if (tag)
            memmove(tag + 2, tag + 11, strlen(tag + 11) + 1);
        return fail(c, col, SVET_ERR_PARSE,
                    "%s ('strict': the mesh file must have nothing to "
                    "skip)", msg);
    }
    scene_warnings_t *sw = &c->scene->warnings;
    for (long i = 0; i < kept; i++)
        scene_warn(sw, "%s:%d:%d: %s", c->name, c->line, col, w->msg[i]);
    sw->n += w->n - kept;
    return SVET_OK;
}

static svet_status st_mesh(ctx_t *c)
{
    if (!c->features || !c->features->mesh)
        return fail(c, c->stmt_col, SVET_ERR_UNSUPPORTED,
                    "'mesh': this program was built without the OBJ "
                    "meshes of ch. 7 (objmesh.c, offered through "
                    "scenefile_read_with)");
    spec_t spec[MESH_NGEO + K_COMMON + SCENE_MAX_SHAPE_KEYS];
    memcpy(spec, mesh_geo, sizeof mesh_geo);
    memcpy(spec + MESH_NGEO, common_spec, sizeof common_spec);
    int nspec = part_shape_keys(c, spec, MESH_NGEO + K_COMMON);
    val_t v[MESH_NGEO + K_COMMON + SCENE_MAX_SHAPE_KEYS];
    svet_status st = parse_keys(c, "mesh", spec, nspec, v, false);
    if (st)
        return st;
    const val_t *common = v + MESH_NGEO;
    if (common[K_TWOSIDED].set && !common[K_EMIT].set)
        return fail(c, common[K_TWOSIDED].col, SVET_ERR_PARSE,
                    "'twosided' says an emitter emits on both sides: it "
                    "needs 'emit'");
    xform_t x;
    st = xform_of_list(c, &x);
    if (st)
        return st;
    const material_t *dflt = NULL;
    if (common[K_MATERIAL].set) {
        st = find_material(c, &common[K_MATERIAL], &dflt);
        if (st)
            return st;
    }
    svet_error pe;
    char *path = scenefile_path(c, &v[MESH_FILE].word, &pe);
    if (!path)
        return fail(c, c->stmt_col, pe.status, "%s", pe.msg);
    /* The loader opens the file itself; refuse what is not a regular file
     * first, so that /dev/zero or a FIFO cannot hang the reader. */
    struct stat sb;
    int col = v[MESH_FILE].word.col;
    if (stat(path, &sb) != 0) {
        st = fail(c, col, SVET_ERR_IO, "%s: cannot open: %s", path,
                  strerror(errno));
    } else if (!S_ISREG(sb.st_mode)) {
        st = fail(c, col, SVET_ERR_IO, "%s: not a regular file", path);
    } else {
        scene_mesh_part_t *parts = NULL;
        int nparts = 0;
        svet_error e;
        scene_warnings_t w;
        w.n = 0;
        st = c->features->mesh(path, c->nxf > 0 ? &x : NULL, &parts,
                               &nparts, &w, &e);
        if (st) /* the loader's own file:line:col follows the scene's */
            st = fail(c, col, st, "%s", e.msg);
        else
            st = mesh_warnings(c, col, &w, v[MESH_STRICT].on);
        int first = c->scene->nobjects;
        if (!st)
            st = add_mesh_parts(c, parts, nparts, dflt, v, common);
        if (!st)
            st = apply_shape_keys(c, common + K_COMMON, first);
        scene_mesh_parts_free(parts, nparts);
    }
    free(path);
    return st;
}

/* --- statements ---------------------------------------------------------- */

typedef struct {
    const char *name;
    svet_status (*fn)(ctx_t *c);
} statement_t;

static const statement_t statements[] = {
    { "camera", st_camera },
    { "render", st_render },
    { "output", st_output },
    { "tonemap", st_tonemap },
    { "material", st_material },
    { "light", st_light },
    { "environment", st_environment },
    { "sphere", st_shape },
    { "plane", st_shape },
    { "disk", st_shape },
    { "parallelogram", st_shape },
    { "triangle", st_shape },
    { "box", st_shape },
    { "cylinder", st_shape },
    { "cone", st_shape },
    { "mesh", st_mesh },
};
enum { NSTATEMENTS = sizeof statements / sizeof *statements };

/* Keywords of later chapters: the file may not use them yet, and says so
 * rather than "unknown keyword". Each chapter that lands moves its
 * keyword into the table above. */
static const struct {
    const char *name, *chapter;
} reserved[] = {
    { "photonmap", "ch. 8 (photon maps)" },
    { "irradiance", "ch. 9 (irradiance caching)" },
    { "texture", "ch. 10 (textures)" },
    { "medium", "ch. 11 (participating media)" },
    { "volsingle", "ch. 11 (participating media)" },
    { "sky", "ch. 12 (the atmosphere)" },
    { "sun", "ch. 12 (the atmosphere)" },
    { "smoke", "ch. 13 (smoke)" },
    { "include", "no chapter: one scene is one file" },
};

/* The statement a part the program offers adds under keyword t, or NULL. */
static const scene_statement_t *part_statement(const ctx_t *c,
                                               const tok_t *t)
{
    const scene_part_t *const *parts = c->features ? c->features->parts
                                                   : NULL;
    for (int i = 0; parts && parts[i]; i++)
        for (const scene_statement_t *ps = parts[i]->statements;
             ps && ps->keyword; ps++)
            if (tok_is(t, ps->keyword))
                return ps;
    return NULL;
}

static svet_status statement(ctx_t *c)
{
    const tok_t *t = &c->tok[0];
    c->stmt_col = t->col;
    c->pos = 1;
    for (int i = 0; i < NSTATEMENTS; i++)
        if (tok_is(t, statements[i].name))
            return statements[i].fn(c);
    const scene_statement_t *ps = part_statement(c, t);
    if (ps)
        return ps->parse(c);
    const scene_part_t *const *parts = c->features ? c->features->parts
                                                   : NULL;
    for (size_t i = 0; i < sizeof reserved / sizeof *reserved; i++)
        if (tok_is(t, reserved[i].name))
            return fail(c, t->col, SVET_ERR_UNSUPPORTED,
                        "'%s' is not supported yet: %s", reserved[i].name,
                        reserved[i].chapter);
    const char *names[NSTATEMENTS + 16];
    int n = 0;
    for (int i = 0; i < NSTATEMENTS; i++)
        names[n++] = statements[i].name;
    for (int i = 0; parts && parts[i]; i++)
        for (const scene_statement_t *q = parts[i]->statements;
             q && q->keyword && n < NSTATEMENTS + 16; q++)
            names[n++] = q->keyword;
    return unknown(c, t, "keyword", names, n);
}

/* --- what a part of Part II reads its statements with (scenepart.h) ------ */

scene_t *scenefile_scene(scenefile_ctx *c)
{
    return c->scene;
}

const tok_t *scenefile_tokens(scenefile_ctx *c, int *n)
{
    *n = c->ntok - c->pos;
    return c->tok + c->pos;
}

void scenefile_skip(scenefile_ctx *c, int k)
{
    c->pos = c->pos + k < c->ntok ? c->pos + k : c->ntok;
}

int scenefile_stmt_col(const scenefile_ctx *c)
{
    return c->stmt_col;
}

int scenefile_eol_col(const scenefile_ctx *c)
{
    return c->eol_col;
}

svet_status scenefile_name(scenefile_ctx *c, const char *what, char *buf,
                           int *col)
{
    char show[64];
    if (c->pos >= c->ntok)
        return fail(c, c->eol_col, SVET_ERR_PARSE, "%s expects a name",
                    what);
    const tok_t *t = &c->tok[c->pos++];
    if (!name_ok(t))
        return fail(c, t->col, SVET_ERR_PARSE,
                    "'%s' is not a %s name: expected a letter or '_' then "
                    "letters, digits, '_', '-' or '.' (at most %d)",
                    show_tok(t, show, sizeof show), what, SCENE_MAX_NAME);
    tok_copy(t, buf, SCENE_MAX_NAME + 1);
    if (col)
        *col = t->col;
    return SVET_OK;
}

svet_status scenefile_kind(scenefile_ctx *c, const char *stmt,
                           const char *name, const char *const *kinds,
                           int *kind)
{
    const tok_t *t = c->pos < c->ntok ? &c->tok[c->pos] : NULL;
    for (int i = 0; t && kinds[i]; i++)
        if (tok_is(t, kinds[i])) {
            *kind = i;
            c->pos++;
            return SVET_OK;
        }
    /* the kinds as a list, "a, b or c" */
    char list[512] = "", show[SCENE_MAX_NAME + 1] = "";
    size_t len = 0;
    for (int i = 0; kinds[i] && len < sizeof list; i++) {
        const char *sep = i == 0 ? "" : kinds[i + 1] ? ", " : " or ";
        int w = snprintf(list + len, sizeof list - len, "%s%s", sep,
                         kinds[i]);
        len += w > 0 ? (size_t)w : 0;
    }
    if (t)
        tok_copy(t, show, sizeof show);
    return fail(c, t ? t->col : c->eol_col, SVET_ERR_PARSE,
                "%s '%s' expects a kind: %s%s%s%s", stmt, name, list,
                t ? ", not '" : "", show, t ? "'" : "");
}

svet_status scenefile_keys(scenefile_ctx *c, const char *stmt,
                           const spec_t *spec, int nspec, val_t *vals,
                           bool stop_at_plus)
{
    return parse_keys(c, stmt, spec, nspec, vals, stop_at_plus);
}

svet_status scenefile_fail(scenefile_ctx *c, int col, svet_status st,
                           const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    st = vfail(c, col, st, fmt, ap);
    va_end(ap);
    return st;
}

void scenefile_warn(scenefile_ctx *c, int col, const char *fmt, ...)
{
    char msg[SVET_ERROR_LEN];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    scene_warn(&c->scene->warnings, "%s:%d:%d: warning: %s", c->name,
               c->line, col, msg);
}

void scenefile_tok_copy(const tok_t *t, char *buf, size_t size)
{
    tok_copy(t, buf, size);
}

bool scenefile_tok_is(const tok_t *t, const char *w)
{
    return tok_is(t, w);
}

char *scenefile_path(scenefile_ctx *c, const tok_t *t, svet_error *err)
{
    char *rel = tok_strdup(t);
    char *p = rel ? path_join(c->dir, rel) : NULL;
    free(rel);
    scene_t *s = c->scene;
    char **f = p ? realloc(s->files, (size_t)(s->nfiles + 1) * sizeof *f)
                 : NULL;
    size_t size = p ? strlen(p) + 1 : 0;
    char *kept = f ? malloc(size) : NULL;
    if (kept)
        memcpy(kept, p, size);
    if (f)
        s->files = f;
    if (!kept) {
        free(p);
        svet_error_set(err, SVET_ERR_NOMEM, "out of memory");
        return NULL;
    }
    s->files[s->nfiles++] = kept;
    return p;
}

/* --- what only the whole scene can tell ---------------------------------- */

/* Does anything give light: a point light, an emitting object or the
 * environment, of a radiance other than black? */
static bool anything_emits(const scene_t *s)
{
    for (int i = 0; i < s->npoint_lights; i++)
        if (!rad_is_black(s->point_lights[i].intensity))
            return true;
    for (int i = 0; i < s->nemitters; i++)
        if (!rad_is_black(s->emitters[i]->radiance))
            return true;
    return s->has_environment && !rad_is_black(s->environment);
}

/* The lengths the build's real resolves. The flat shapes' intersection
 * tests (parallelogram, triangle and mesh, app. D; Woop et al. 2013 for
 * the triangle) multiply three lengths: the unnormalised normal e1 x e2,
 * a product of two edges, dotted with a distance. While that product is
 * a normal number (REAL_MIN to REAL_MAX) the offsets of ray.c, which
 * scale with the hit points' error bounds, hold at any scale; beyond it
 * the product overflows (hits are lost: the image goes black) or loses
 * digits to underflow. So lengths L with L^3 in [REAL_MIN, REAL_MAX] are
 * resolved: cbrt(FLT_MIN) ~ 2.3e-13 to cbrt(FLT_MAX) ~ 7e12 in float,
 * 2.8e-103 to 5.6e102 in double. */
static double shortest_length(void)
{
    return cbrt((double)REAL_MIN);
}

static double longest_length(void)
{
    return cbrt((double)REAL_MAX);
}

#ifdef SVET_DOUBLE
#define OTHER_BUILD ""
#else
#define OTHER_BUILD "; render it with the double build (make REAL=double)"
#endif

/* The scene's extent and smallest object against the range real
 * resolves; a warning for each that falls outside it. The extent is the
 * diagonal of the box of the finite objects, the camera and the point
 * lights: every distance a ray travels lies within it. */
static void precision_warnings(ctx_t *c)
{
    scene_t *s = c->scene;
    bbox_t all = c->bounds;
    bbox_add_point(&all, s->camera.position);
    for (int i = 0; i < s->npoint_lights; i++)
        bbox_add_point(&all, s->point_lights[i].position);
    double extent = diagonal(&all);
    if (extent > longest_length())
        scene_warn(&s->warnings, "%s: warning: the scene spans %.3g, more "
                   "than %s resolves (lengths up to %.3g: the flat shapes' "
                   "intersection multiplies three lengths)" OTHER_BUILD,
                   c->name, extent, REAL_NAME, longest_length());
    if (c->smallest_line && c->smallest < shortest_length())
        scene_warn(&s->warnings, "%s:%d:1: warning: the object is %.3g "
                   "across, less than %s resolves (lengths down to %.3g: "
                   "the flat shapes' intersection multiplies three "
                   "lengths)" OTHER_BUILD, c->name, c->smallest_line,
                   c->smallest, REAL_NAME, shortest_length());
}

/* What only the whole scene can tell: the environment's power, which
 * depends on the scene's size (pi^2 r^2 L, r the radius of the sphere
 * around the objects, light.c), is refused when it overflows; then the
 * warnings (scene.h's scene_warnings_t): nothing emits light (the image
 * is black, except by ambient occlusion, which needs none), and sizes
 * beyond what real resolves. */
static svet_status whole_scene(ctx_t *c)
{
    scene_t *s = c->scene;
    if (s->has_environment) {
        double r = bbox_is_empty(&c->bounds) ? 1
                                             : 0.5 * diagonal(&c->bounds);
        c->line = c->environment_line;
        svet_status st = check_light(c, c->environment_col, "the radiance",
                                     s->environment, PI_D * PI_D * r * r);
        if (st)
            return st;
    }
    const scene_part_t *const *parts = c->features ? c->features->parts
                                                   : NULL;
    bool emits = anything_emits(s);
    for (int i = 0; !emits && parts && parts[i]; i++)
        emits = parts[i]->emits && parts[i]->emits(s);
    if (s->render.integrator != SCENE_INTEGRATOR_AO && !emits)
        scene_warn(&s->warnings, "%s: warning: nothing emits light (no "
                   "'light', 'emit', 'environment' or emitting medium above "
                   "black): the image will be black", c->name);
    precision_warnings(c);
    for (int i = 0; parts && parts[i]; i++)
        if (parts[i]->finish) {
            svet_status st = parts[i]->finish(c);
            if (st)
                return st;
        }
    return SVET_OK;
}

static void ctx_free(ctx_t *c)
{
    free(c->tok);
    c->tok = NULL;
    c->cap = c->ntok = 0;
}

svet_status scenefile_parse_with(scene_t *s, const char *text, size_t len,
                                 const char *name, const char *dir,
                                 const scene_features_t *features,
                                 svet_error *err)
{
    scene_init(s);
    s->features = features;
    ctx_t c;
    memset(&c, 0, sizeof c);
    c.scene = s;
    c.features = features;
    bbox_empty(&c.bounds);
    c.name = name ? name : "<string>";
    c.dir = dir;
    c.err = err;
    svet_status st = SVET_OK;
    /* A byte-order mark is no statement (text.h); the first line's columns
     * count from the byte after it, as an editor shows them. */
    const char *p = text + text_bom_length(text, len), *end = text + len;
    if (len > (size_t)SCENEFILE_MAX_BYTES) {
        c.line = 1;
        st = fail(&c, 1, SVET_ERR_RANGE,
                  "the file is larger than %ld bytes",
                  SCENEFILE_MAX_BYTES);
    }
    while (!st && p < end) {
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        const char *eol = nl ? nl : end;
        c.line++;
        st = lex(&c, p, eol);
        if (!st && c.ntok > 0) {
            st = statement(&c);
            c.nstatements++;
        }
        p = nl ? nl + 1 : end;
    }
    /* An empty file is more likely a wrong name or a failed copy than a
     * scene of nothing. */
    if (!st && c.nstatements == 0)
        st = svet_error_set(err, SVET_ERR_PARSE, "%s: no statements (the "
                            "file is empty or only comments): a scene needs "
                            "at least an object", c.name);
    if (!st) {
        svet_error e;
        if (scene_validate(s, &e)) {
            c.line = c.camera_line;
            st = c.camera_line
                     ? fail(&c, 1, e.status, "%s", e.msg)
                     : svet_error_set(err, e.status, "%s: %s", c.name,
                                      e.msg);
        }
    }
    if (!st)
        st = whole_scene(&c);
    if (!st && name) {
        size_t n = strlen(name);
        s->path = malloc(n + 1);
        if (!s->path)
            st = svet_error_set(err, SVET_ERR_NOMEM, "out of memory");
        else
            memcpy(s->path, name, n + 1);
    }
    ctx_free(&c);
    if (st)
        scene_free(s);
    return st;
}

svet_status scenefile_parse(scene_t *s, const char *text, size_t len,
                            const char *name, const char *dir,
                            svet_error *err)
{
    return scenefile_parse_with(s, text, len, name, dir, NULL, err);
}

svet_status scenefile_read_with(scene_t *s, const char *path,
                                const scene_features_t *features,
                                svet_error *err)
{
    scene_init(s);
    char *text = NULL;
    size_t len = 0;
    svet_status st = read_file(path, SCENEFILE_MAX_BYTES, &text, &len,
                                  err);
    if (st)
        return st;
    /* Mesh files are found relative to the scene file's directory. */
    char *dir = dir_name(path);
    if (!dir) {
        free(text);
        return svet_error_set(err, SVET_ERR_NOMEM, "out of memory");
    }
    st = scenefile_parse_with(s, text, len, path, dir, features, err);
    free(dir);
    free(text);
    return st;
}

svet_status scenefile_read(scene_t *s, const char *path, svet_error *err)
{
    return scenefile_read_with(s, path, NULL, err);
}

/* --- overrides ----------------------------------------------------------- */

/* key=value: which statement and which of its keys takes the value. */
static const struct {
    const char *key, *statement, *param;
} overrides[] = {
    { "spp", "render", "spp" },
    { "maxdepth", "render", "maxdepth" },
    { "seed", "render", "seed" },
    { "integrator", "render", "integrator" },
    { "ao_distance", "render", "ao_distance" },
    { "roulette", "render", "roulette" },
    { "roulette_depth", "render", "roulette_depth" },
    { "threads", "render", "threads" },
    { "time_limit", "render", "time_limit" },
    { "passes", "render", "passes" },
    { "checkpoint", "render", "checkpoint" },
    { "accel", "render", "accel" },
    { "packets", "render", "packets" },
    { "light", "render", "light" },
    { "subsample.step", "render subsample", "step" },
    { "subsample.threshold", "render subsample", "threshold" },
    { "width", "camera", "width" },
    { "height", "camera", "height" },
    { "resolution", "camera", NULL },
    { "fov", "camera", "fov" },
    { "fov_axis", "camera", "fov_axis" },
    { "exr", "output", "exr" },
    { "png", "output", "png" },
    { "tonemap", "tonemap", "operator" },
    { "exposure", "tonemap", "exposure" },
    { "curve", "tonemap", "curve" },
    { "gamma", "tonemap", "gamma" },
    { "key", "tonemap", "key" },
    { "white", "tonemap", "white" },
    { "bias", "tonemap", "bias" },
};
enum { NOVERRIDES = sizeof overrides / sizeof *overrides };

svet_status scenefile_override(scene_t *s, const char *setting,
                               svet_error *err)
{
    ctx_t c;
    memset(&c, 0, sizeof c);
    c.scene = s;
    c.features = s->features;
    c.err = err;
    c.override = setting;
    c.name = "override";
    const char *eq = strchr(setting, '=');
    if (!eq || eq == setting)
        return fail(&c, 1, SVET_ERR_PARSE, "expected key=value");
    size_t klen = (size_t)(eq - setting);
    const char *value = eq + 1;
    int k;
    for (k = 0; k < NOVERRIDES; k++)
        if (strlen(overrides[k].key) == klen &&
            memcmp(overrides[k].key, setting, klen) == 0)
            break;
    const char *dot = memchr(setting, '.', klen);
    if (k == NOVERRIDES && dot && dot > setting && dot + 1 < eq) {
        /* STATEMENT.KEY=VALUE: a key of a part's settings statement,
         * e.g. photonmap.k=50 is the line "photonmap k 50" */
        size_t vlen0 = strlen(value);
        if (vlen0 == 0 || vlen0 > 4096 || strpbrk(value, " \t#\""))
            return fail(&c, 1, SVET_ERR_PARSE,
                        "expected exactly one value after '='");
        char *line = malloc(klen + vlen0 + 4);
        if (!line)
            return svet_error_set(err, SVET_ERR_NOMEM, "out of memory");
        snprintf(line, klen + vlen0 + 4, "%.*s %.*s %s",
                 (int)(dot - setting), setting, (int)(eq - dot - 1), dot + 1,
                 value);
        svet_status st = lex(&c, line, line + strlen(line));
        if (!st && c.ntok != 3)
            st = fail(&c, 1, SVET_ERR_PARSE,
                      "expected exactly one value after '='");
        if (!st && !part_statement(&c, &c.tok[0]))
            st = fail(&c, 1, SVET_ERR_PARSE,
                      "'%.*s' is not a settings statement this program "
                      "offers", (int)(dot - setting), setting);
        if (!st)
            st = statement(&c);
        free(line);
        ctx_free(&c);
        return st;
    }
    if (k == NOVERRIDES) {
        const char *names[NOVERRIDES];
        for (int i = 0; i < NOVERRIDES; i++)
            names[i] = overrides[i].key;
        tok_t t = { setting, (int)klen, 1, false };
        return unknown(&c, &t, "setting", names, NOVERRIDES);
    }
    /* Build the statement the setting stands for, e.g. "render spp 64",
     * and run it through the parser so it gets the file's checks. A
     * resolution WxH becomes "camera width W height H". */
    size_t vlen = strlen(value);
    if (vlen == 0)
        return fail(&c, 1, SVET_ERR_PARSE, "expected a value after '='");
    if (strchr(value, '"'))
        return fail(&c, 1, SVET_ERR_PARSE, "a value cannot contain '\"'");
    /* A file name may hold blanks and '#' (it is quoted below); any other
     * value is one word. */
    if (strcmp(overrides[k].statement, "output") != 0 &&
        strpbrk(value, " \t#"))
        return fail(&c, 1, SVET_ERR_PARSE,
                    "expected exactly one value after '='");
    if (vlen > 4096)
        return fail(&c, 1, SVET_ERR_RANGE, "the value is too long");
    char *line = malloc(vlen + 64);
    if (!line)
        return svet_error_set(err, SVET_ERR_NOMEM, "out of memory");
    if (!overrides[k].param) {
        const char *x = strchr(value, 'x');
        if (!x || strchr(x + 1, 'x')) {
            free(line);
            return fail(&c, 1, SVET_ERR_PARSE,
                        "expected a resolution WIDTHxHEIGHT, e.g. 512x512");
        }
        snprintf(line, vlen + 64, "camera width %.*s height %s",
                 (int)(x - value), value, x + 1);
    } else if (strcmp(overrides[k].statement, "output") == 0) {
        snprintf(line, vlen + 64, "output %s \"%s\"", overrides[k].param,
                 value);
    } else {
        snprintf(line, vlen + 64, "%s %s %s", overrides[k].statement,
                 overrides[k].param, value);
    }
    svet_status st = lex(&c, line, line + strlen(line));
    if (!st) {
        /* An override sets one value: "spp=64 seed=1" is two overrides. */
        int expect = overrides[k].param ? 3 : 5;
        if (!strcmp(overrides[k].statement, "render subsample"))
            expect = 4;
        if (c.ntok != expect)
            st = fail(&c, 1, SVET_ERR_PARSE,
                      "expected exactly one value after '='");
    }
    if (!st) {
        scene_camera_t cam = s->camera;
        scene_render_t r = s->render;
        st = statement(&c);
        if (!st) {
            svet_error e;
            if (scene_validate(s, &e))
                st = fail(&c, 1, e.status, "%s", e.msg);
        }
        if (st) {
            s->camera = cam;
            s->render = r;
        }
    }
    free(line);
    ctx_free(&c);
    return st;
}
