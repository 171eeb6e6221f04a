/*
 * obj.c - the Wavefront OBJ reader of obj.h: one pass over the file held
 * in memory, a hash of the (v, vt, vn) triples that faces use (each
 * distinct triple becomes one mesh vertex), fanned polygons. Memory and
 * time are linear in the input and bounded by obj_limits_t.
 * Tests: tests/mesh/test_obj.c; fuzzing: fuzz/fuzz_obj.c
 */
#include "mesh/obj.h"
#include "core/text.h"
#include "mesh/mesh.h"
#include "io/fileio.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void obj_limits_default(obj_limits_t *lim)
{
    lim->max_vertices = MESH_MAX_VERTICES;
    lim->max_triangles = MESH_MAX_TRIANGLES;
    lim->max_elements = 3 * MESH_MAX_VERTICES;
}

/* A growable array of fixed-size items. */
typedef struct {
    void *data;
    long n, cap;
} vec_t;

static bool grow(vec_t *a, size_t item, long need)
{
    if (need <= a->cap)
        return true;
    long cap = a->cap ? a->cap : 64;
    while (cap < need)
        cap *= 2;
    void *p = realloc(a->data, (size_t)cap * item);
    if (!p)
        return false;
    a->data = p;
    a->cap = cap;
    return true;
}

typedef struct {
    const char *name;
    const char *text;
    size_t len;
    obj_limits_t lim;
    obj_t *out;
    svet_error *err;
    /* the logical line being read: [ls, le), its first physical line
     * number, the read position; where the next one starts */
    size_t ls, le, cur;
    long line;
    size_t next;
    long next_line;
    /* elements as defined: v (3 reals), vt (2), vn (3) */
    vec_t v, vt, vn;
    /* mesh vertices: the distinct (v, vt, vn) index triples used by faces */
    vec_t combo;   /* int32_t[3] each; vt, vn = -1 when absent */
    int32_t *hash; /* open addressing over combo, -1 = empty */
    long hcap;
    bool any_vt, any_vn;
    /* triangles */
    vec_t tri, slot, group; /* int32_t[3], int32_t, int32_t */
    int32_t cur_slot, cur_group;
    bool any_slot, any_group;
    vec_t materials, groups; /* char * */
} parser_t;

/* --- positions and messages --------------------------------------------- */

/* Line and column (1-based) of byte offset off of the current line. */
static void locate(const parser_t *P, size_t off, long *line, long *col)
{
    long ln = P->line;
    size_t bol = P->ls;
    for (size_t i = P->ls; i < off && i < P->len; i++)
        if (P->text[i] == '\n') {
            ln++;
            bol = i + 1;
        }
    *line = ln;
    *col = (long)(off - bol) + 1;
}

#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
static svet_status fail(parser_t *P, svet_status st, size_t off,
                        const char *fmt, ...)
{
    char msg[SVET_ERROR_LEN];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    long line, col;
    locate(P, off, &line, &col);
    return svet_error_set(P->err, st, "%s:%ld:%ld: %s", P->name, line, col,
                          msg);
}

static void warn(parser_t *P, size_t off, const char *msg)
{
    obj_t *o = P->out;
    if (o->nwarnings < OBJ_MAX_WARNINGS) {
        long line, col;
        locate(P, off, &line, &col);
        snprintf(o->warnings[o->nwarnings], sizeof o->warnings[0],
                 "%s:%ld:%ld: warning: %s", P->name, line, col, msg);
    }
    o->nwarnings++;
}

static svet_status nomem(parser_t *P)
{
    return svet_error_set(P->err, SVET_ERR_NOMEM, "%s: out of memory",
                          P->name);
}

/* --- lines and tokens --------------------------------------------------- */

/* A backslash right before a line end joins the next line: returns the
 * length of "\\\n" or "\\\r\n" at i, else 0. */
static size_t continuation(const parser_t *P, size_t i)
{
    if (i < P->len && P->text[i] == '\\') {
        if (i + 1 < P->len && P->text[i + 1] == '\n')
            return 2;
        if (i + 2 < P->len && P->text[i + 1] == '\r' &&
            P->text[i + 2] == '\n')
            return 3;
    }
    return 0;
}

/* Move to the next logical line: [ls, le) up to the '\n' that is not
 * part of a continuation, or the end. Returns false past the end. */
static bool next_line(parser_t *P)
{
    if (P->next > P->len)
        return false;
    P->ls = P->cur = P->next;
    P->line = P->next_line;
    long physical = 1;
    size_t i = P->ls;
    while (i < P->len && P->text[i] != '\n') {
        size_t c = continuation(P, i);
        physical += c != 0;
        i += c ? c : 1;
    }
    P->le = i;
    P->next = i + 1;
    P->next_line = P->line + physical;
    return true;
}

static bool is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f' ||
           c == '\0';
}

/* Next whitespace-separated token of the line before any '#': [*b, *e).
 * Returns false when the line has no more. */
static bool token(parser_t *P, size_t *b, size_t *e)
{
    size_t i = P->cur;
    for (;;) {
        if (i >= P->le)
            break;
        size_t c = continuation(P, i);
        if (c) {
            i += c;
            continue;
        }
        if (!is_space(P->text[i]))
            break;
        i++;
    }
    if (i >= P->le || P->text[i] == '#') {
        P->cur = P->le;
        return false;
    }
    *b = i;
    while (i < P->le && !is_space(P->text[i]) && P->text[i] != '#' &&
           !continuation(P, i))
        i++;
    *e = i;
    P->cur = i;
    return true;
}

static bool token_is(const parser_t *P, size_t b, size_t e, const char *s)
{
    size_t n = strlen(s);
    return e - b == n && memcmp(P->text + b, s, n) == 0;
}

/* --- numbers ------------------------------------------------------------ */

/* A decimal number: [+-] digits [. digits] [(e|E) [+-] digits], at least
 * one digit before the exponent. */
static bool decimal_syntax(const char *s, size_t n)
{
    size_t i = 0, digits = 0;
    if (i < n && (s[i] == '+' || s[i] == '-'))
        i++;
    while (i < n && s[i] >= '0' && s[i] <= '9')
        i++, digits++;
    if (i < n && s[i] == '.') {
        i++;
        while (i < n && s[i] >= '0' && s[i] <= '9')
            i++, digits++;
    }
    if (digits == 0)
        return false;
    if (i < n && (s[i] == 'e' || s[i] == 'E')) {
        i++;
        if (i < n && (s[i] == '+' || s[i] == '-'))
            i++;
        size_t ed = 0;
        while (i < n && s[i] >= '0' && s[i] <= '9')
            i++, ed++;
        if (ed == 0)
            return false;
    }
    return i == n;
}

static svet_status parse_real(parser_t *P, size_t b, size_t e, real *x)
{
    char buf[128];
    size_t n = e - b;
    if (n >= sizeof buf)
        return fail(P, SVET_ERR_PARSE, b, "number too long (%zu characters)",
                    n);
    memcpy(buf, P->text + b, n);
    buf[n] = '\0';
    if (!decimal_syntax(buf, n))
        return fail(P, SVET_ERR_PARSE, b, "expected a number, found '%s'",
                    buf);
    errno = 0;
    double d = strtod(buf, NULL);
    real r = (real)d;
    if (!isfinite(d) || !isfinite(r))
        return fail(P, SVET_ERR_RANGE, b, "number '%s' is out of range", buf);
    *x = r;
    return SVET_OK;
}

/* Read between lo and hi numbers into x; the count in *n. */
static svet_status numbers(parser_t *P, size_t kw, const char *what, int lo,
                           int hi, real *x, int *n)
{
    size_t b, e;
    *n = 0;
    while (token(P, &b, &e)) {
        if (*n == hi)
            return fail(P, SVET_ERR_PARSE, b,
                        "'%s' takes at most %d numbers", what, hi);
        svet_status st = parse_real(P, b, e, &x[*n]);
        if (st != SVET_OK)
            return st;
        (*n)++;
    }
    if (*n < lo)
        return fail(P, SVET_ERR_PARSE, kw, "'%s' needs %d numbers, got %d",
                    what, lo, *n);
    return SVET_OK;
}

static svet_status element(parser_t *P, size_t kw, vec_t *a, int width,
                           const char *what, int lo, int hi)
{
    real x[8] = { 0 };
    int n;
    svet_status st = numbers(P, kw, what, lo, hi, x, &n);
    if (st != SVET_OK)
        return st;
    if (P->v.n + P->vt.n + P->vn.n >= P->lim.max_elements)
        return fail(P, SVET_ERR_RANGE, kw,
                    "more than %ld v/vt/vn elements (the limit)",
                    P->lim.max_elements);
    if (!grow(a, (size_t)width * sizeof(real), a->n + 1))
        return nomem(P);
    memcpy((real *)a->data + (size_t)a->n * (size_t)width, x,
           (size_t)width * sizeof(real));
    a->n++;
    return SVET_OK;
}

/* --- faces -------------------------------------------------------------- */

/* One index of a face vertex: [+-]digits, 1-based or negative. Resolves
 * it against count (the elements defined so far) into 0..count-1. */
static svet_status parse_index(parser_t *P, size_t b, size_t e, long count,
                               const char *what, int32_t *out)
{
    size_t i = b;
    bool neg = false;
    if (i < e && (P->text[i] == '+' || P->text[i] == '-'))
        neg = P->text[i++] == '-';
    if (i == e)
        return fail(P, SVET_ERR_PARSE, b, "expected a %s index", what);
    long long v = 0;
    for (; i < e; i++) {
        char c = P->text[i];
        if (c < '0' || c > '9')
            return fail(P, SVET_ERR_PARSE, i,
                        "malformed %s index: unexpected '%c'", what,
                        (c >= 32 && c < 127) ? c : '?');
        if (v < (1LL << 40))
            v = 10 * v + (c - '0');
    }
    if (v == 0)
        return fail(P, SVET_ERR_RANGE, b,
                    "%s index 0 (OBJ indices start at 1)", what);
    long long k = neg ? count - v : v - 1;
    if (k < 0 || k >= count)
        return fail(P, SVET_ERR_RANGE, b,
                    "%s index %s%lld out of range: %ld defined so far", what,
                    neg ? "-" : "", v, count);
    *out = (int32_t)k;
    return SVET_OK;
}

static uint32_t mix3(const int32_t k[3])
{
    uint64_t h = (uint32_t)k[0] * 0x9e3779b97f4a7c15ULL;
    h ^= ((uint64_t)(uint32_t)k[1] + 0x632be59bd9b4e019ULL) * 0xbf58476d1ce4e5b9ULL;
    h ^= ((uint64_t)(uint32_t)k[2] + 0x1b873593ULL) * 0x94d049bb133111ebULL;
    h ^= h >> 31;
    return (uint32_t)(h ^ (h >> 29));
}

static bool rehash(parser_t *P, long cap)
{
    int32_t *h = malloc((size_t)cap * sizeof *h);
    if (!h)
        return false;
    for (long i = 0; i < cap; i++)
        h[i] = -1;
    const int32_t(*c)[3] = P->combo.data;
    for (long i = 0; i < P->combo.n; i++) {
        long j = (long)(mix3(c[i]) & (uint32_t)(cap - 1));
        while (h[j] >= 0)
            j = (j + 1) & (cap - 1);
        h[j] = (int32_t)i;
    }
    free(P->hash);
    P->hash = h;
    P->hcap = cap;
    return true;
}

/* The mesh vertex of the triple k, made if new. */
static svet_status vertex_of(parser_t *P, size_t b, const int32_t k[3],
                             int32_t *out)
{
    if (2 * (P->combo.n + 1) > P->hcap && !rehash(P, P->hcap ? 2 * P->hcap : 1024))
        return nomem(P);
    long mask = P->hcap - 1;
    long j = (long)(mix3(k) & (uint32_t)mask);
    int32_t(*c)[3] = P->combo.data;
    while (P->hash[j] >= 0) {
        const int32_t *q = c[P->hash[j]];
        if (q[0] == k[0] && q[1] == k[1] && q[2] == k[2]) {
            *out = P->hash[j];
            return SVET_OK;
        }
        j = (j + 1) & mask;
    }
    if (P->combo.n >= P->lim.max_vertices)
        return fail(P, SVET_ERR_RANGE, b,
                    "more than %ld distinct face vertices (the limit)",
                    P->lim.max_vertices);
    if (!grow(&P->combo, sizeof(int32_t[3]), P->combo.n + 1))
        return nomem(P);
    c = P->combo.data;
    memcpy(c[P->combo.n], k, sizeof(int32_t[3]));
    P->hash[j] = (int32_t)P->combo.n;
    *out = (int32_t)P->combo.n++;
    return SVET_OK;
}

/* "v", "v/vt", "v//vn" or "v/vt/vn" at [b, e). */
static svet_status face_vertex(parser_t *P, size_t b, size_t e, int32_t *out)
{
    size_t f[3] = { b, e, e }, g[3] = { e, e, e };
    int parts = 1;
    for (size_t i = b; i < e; i++)
        if (P->text[i] == '/') {
            if (parts == 3)
                return fail(P, SVET_ERR_PARSE, i,
                            "malformed face vertex: more than two '/'");
            g[parts - 1] = i;
            f[parts] = i + 1;
            parts++;
        }
    g[parts - 1] = e;
    int32_t k[3] = { -1, -1, -1 };
    svet_status st = parse_index(P, f[0], g[0], P->v.n, "vertex", &k[0]);
    if (st != SVET_OK)
        return st;
    if (parts >= 2 && g[1] > f[1]) {
        st = parse_index(P, f[1], g[1], P->vt.n, "texture", &k[1]);
        if (st != SVET_OK)
            return st;
    } else if (parts == 2) {
        return fail(P, SVET_ERR_PARSE, f[1],
                    "malformed face vertex: nothing after '/'");
    }
    if (parts == 3) {
        if (g[2] == f[2])
            return fail(P, SVET_ERR_PARSE, f[2],
                        "malformed face vertex: no normal index after '/'");
        st = parse_index(P, f[2], g[2], P->vn.n, "normal", &k[2]);
        if (st != SVET_OK)
            return st;
    }
    P->any_vt |= k[1] >= 0;
    P->any_vn |= k[2] >= 0;
    return vertex_of(P, b, k, out);
}

static svet_status face(parser_t *P, size_t kw)
{
    size_t b, e;
    int32_t first = -1, prev = -1;
    long n = 0;
    while (token(P, &b, &e)) {
        int32_t v = -1;
        svet_status st = face_vertex(P, b, e, &v);
        if (st != SVET_OK)
            return st;
        if (n == 0)
            first = v;
        if (n >= 2) {
            /* fan: (first, prev, v) */
            if (P->tri.n >= P->lim.max_triangles)
                return fail(P, SVET_ERR_RANGE, b,
                            "more than %ld triangles (the limit)",
                            P->lim.max_triangles);
            if (!grow(&P->tri, sizeof(int32_t[3]), P->tri.n + 1) ||
                !grow(&P->slot, sizeof(int32_t), P->tri.n + 1) ||
                !grow(&P->group, sizeof(int32_t), P->tri.n + 1))
                return nomem(P);
            int32_t *t = (int32_t *)P->tri.data + 3 * P->tri.n;
            t[0] = first;
            t[1] = prev;
            t[2] = v;
            ((int32_t *)P->slot.data)[P->tri.n] = P->cur_slot;
            ((int32_t *)P->group.data)[P->tri.n] = P->cur_group;
            P->tri.n++;
        }
        prev = v;
        n++;
    }
    if (n < 3)
        return fail(P, SVET_ERR_PARSE, kw,
                    "a face needs at least 3 vertices, got %ld", n);
    return SVET_OK;
}

/* --- names -------------------------------------------------------------- */

/* The rest of the line after the keyword, trimmed (inner spacing
 * normalised to single spaces), as the index of a name in list. */
static svet_status name_slot(parser_t *P, size_t kw, vec_t *list,
                             const char *what, int32_t *slot)
{
    char buf[OBJ_MAX_NAME + 1];
    size_t n = 0, b, e;
    while (token(P, &b, &e)) {
        size_t need = (n ? 1 : 0) + (e - b);
        if (n + need > OBJ_MAX_NAME)
            return fail(P, SVET_ERR_RANGE, b, "%s name longer than %d bytes",
                        what, OBJ_MAX_NAME);
        if (n)
            buf[n++] = ' ';
        memcpy(buf + n, P->text + b, e - b);
        n += e - b;
    }
    if (n == 0)
        return fail(P, SVET_ERR_PARSE, kw, "'%s' needs a name", what);
    buf[n] = '\0';
    char **names = list->data;
    /* Linear search: files have few materials and groups; a file with many
     * gets at most OBJ_MAX_NAMES of them. */
    for (long i = list->n - 1; i >= 0; i--)
        if (strcmp(names[i], buf) == 0) {
            *slot = (int32_t)i;
            return SVET_OK;
        }
    if (list->n >= OBJ_MAX_NAMES)
        return fail(P, SVET_ERR_RANGE, kw, "more than %d %s names", OBJ_MAX_NAMES,
                    what);
    if (!grow(list, sizeof(char *), list->n + 1))
        return nomem(P);
    char *s = malloc(n + 1);
    if (!s)
        return nomem(P);
    memcpy(s, buf, n + 1);
    ((char **)list->data)[list->n] = s;
    *slot = (int32_t)list->n++;
    return SVET_OK;
}

/* --- one line ----------------------------------------------------------- */

static svet_status statement(parser_t *P)
{
    size_t b, e;
    if (!token(P, &b, &e))
        return SVET_OK; /* blank or comment */
    if (token_is(P, b, e, "v"))
        return element(P, b, &P->v, 3, "v", 3, 7);
    if (token_is(P, b, e, "vt"))
        return element(P, b, &P->vt, 2, "vt", 1, 3);
    if (token_is(P, b, e, "vn"))
        return element(P, b, &P->vn, 3, "vn", 3, 3);
    if (token_is(P, b, e, "f"))
        return face(P, b);
    if (token_is(P, b, e, "usemtl")) {
        P->any_slot = true;
        return name_slot(P, b, &P->materials, "usemtl", &P->cur_slot);
    }
    if (token_is(P, b, e, "g") || token_is(P, b, e, "o")) {
        size_t save = P->cur, b2, e2;
        if (!token(P, &b2, &e2)) {
            P->cur_group = -1; /* "g" alone: back to the default group */
            return SVET_OK;
        }
        P->cur = save;
        P->any_group = true;
        return name_slot(P, b, &P->groups, "group", &P->cur_group);
    }
    if (token_is(P, b, e, "mtllib") || token_is(P, b, e, "s"))
        return SVET_OK;
    char msg[160];
    if (token_is(P, b, e, "l") || token_is(P, b, e, "p")) {
        snprintf(msg, sizeof msg, "'%.*s' skipped: lines and points have "
                 "no surface", (int)(e - b), P->text + b);
    } else {
        int n = e - b > 32 ? 32 : (int)(e - b);
        char kwd[33];
        for (int i = 0; i < n; i++) {
            char c = P->text[b + (size_t)i];
            kwd[i] = (c >= 32 && c < 127) ? c : '?';
        }
        kwd[n] = '\0';
        snprintf(msg, sizeof msg, "unknown statement '%s' skipped", kwd);
    }
    warn(P, b, msg);
    return SVET_OK;
}

/* --- the mesh ----------------------------------------------------------- */

static svet_status build(parser_t *P)
{
    obj_t *o = P->out;
    if (P->tri.n == 0)
        return svet_error_set(P->err, SVET_ERR_PARSE, "%s: no faces",
                              P->name);
    long nv = P->combo.n;
    const int32_t(*c)[3] = P->combo.data;
    mesh_t m = { 0 };
    m.nverts = (int)nv;
    m.ntris = (int)P->tri.n;
    m.p = malloc((size_t)nv * sizeof *m.p);
    m.n = P->any_vn ? malloc((size_t)nv * sizeof *m.n) : NULL;
    m.st = P->any_vt ? malloc((size_t)nv * sizeof *m.st) : NULL;
    if (!m.p || (P->any_vn && !m.n) || (P->any_vt && !m.st)) {
        free(m.p);
        free(m.n);
        free(m.st);
        return nomem(P);
    }
    const real *v = P->v.data, *vt = P->vt.data, *vn = P->vn.data;
    for (long i = 0; i < nv; i++) {
        vec_copy(m.p[i], v + 3 * (size_t)c[i][0]);
        if (m.n) {
            if (c[i][2] >= 0)
                vec_copy(m.n[i], vn + 3 * (size_t)c[i][2]);
            else
                vec_set(m.n[i], 0, 0, 0);
        }
        if (m.st) {
            m.st[i][0] = c[i][1] >= 0 ? vt[2 * (size_t)c[i][1]] : (real)NAN;
            m.st[i][1] = c[i][1] >= 0 ? vt[2 * (size_t)c[i][1] + 1] : (real)NAN;
        }
    }
    /* The arrays move into the mesh. */
    m.tri = P->tri.data;
    P->tri.data = NULL;
    if (P->any_slot) {
        m.slot = P->slot.data;
        P->slot.data = NULL;
    }
    svet_status st = mesh_new(&o->mesh, &m, P->err);
    if (st != SVET_OK) {
        svet_error_prefix(P->err, P->name);
        return st;
    }
    if (P->any_group) {
        o->tri_group = P->group.data;
        P->group.data = NULL;
    }
    o->materials = P->materials.data;
    o->nmaterials = (int)P->materials.n;
    P->materials.data = NULL;
    P->materials.n = 0;
    o->groups = P->groups.data;
    o->ngroups = (int)P->groups.n;
    P->groups.data = NULL;
    P->groups.n = 0;
    return SVET_OK;
}

static void free_names(char **names, long n)
{
    for (long i = 0; i < n; i++)
        free(names[i]);
    free(names);
}

svet_status obj_parse(const char *name, const char *text, size_t len,
                      const obj_limits_t *lim, obj_t *o, svet_error *err)
{
    memset(o, 0, sizeof *o);
    parser_t P;
    memset(&P, 0, sizeof P);
    P.name = name ? name : "(obj)";
    /* A byte-order mark is no statement: kept, it would make the first
     * line's keyword unknown (text.h). */
    size_t bom = text ? text_bom_length(text, len) : 0;
    P.text = text ? text + bom : NULL;
    P.len = text ? len - bom : 0;
    P.out = o;
    P.err = err;
    P.cur_slot = -1;
    P.cur_group = -1;
    P.next_line = 1;
    if (lim)
        P.lim = *lim;
    else
        obj_limits_default(&P.lim);
    if (P.lim.max_vertices > MESH_MAX_VERTICES)
        P.lim.max_vertices = MESH_MAX_VERTICES;
    if (P.lim.max_triangles > MESH_MAX_TRIANGLES)
        P.lim.max_triangles = MESH_MAX_TRIANGLES;
    svet_status st = SVET_OK;
    if (P.len > OBJ_MAX_FILE_BYTES)
        st = svet_error_set(err, SVET_ERR_IO, "%s: larger than %zu bytes",
                            P.name, OBJ_MAX_FILE_BYTES);
    while (st == SVET_OK && next_line(&P))
        st = statement(&P);
    if (st == SVET_OK)
        st = build(&P);
    free(P.v.data);
    free(P.vt.data);
    free(P.vn.data);
    free(P.combo.data);
    free(P.hash);
    free(P.tri.data);
    free(P.slot.data);
    free(P.group.data);
    free_names(P.materials.data, P.materials.n);
    free_names(P.groups.data, P.groups.n);
    if (st != SVET_OK) {
        long nw = o->nwarnings;
        obj_free(o);
        o->nwarnings = nw;
    }
    return st;
}

svet_status obj_read(const char *path, const obj_limits_t *lim, obj_t *o,
                     svet_error *err)
{
    memset(o, 0, sizeof *o);
    FILE *f;
    svet_status st = fileio_open_read(path, &f, err); /* regular files */
    if (st != SVET_OK)
        return st;
    /* Read in chunks: no trust in a size from fseek/ftell (pipes, files
     * that grow while read). */
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap);
    while (buf) {
        if (n > OBJ_MAX_FILE_BYTES) {
            st = svet_error_set(err, SVET_ERR_IO, "%s: larger than %zu bytes",
                                path, OBJ_MAX_FILE_BYTES);
            break;
        }
        if (n == cap) {
            /* one byte past the limit tells a file that is too long */
            size_t ncap = 2 * cap > OBJ_MAX_FILE_BYTES + 1
                              ? OBJ_MAX_FILE_BYTES + 1 : 2 * cap;
            char *nb = realloc(buf, ncap);
            if (!nb) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = nb;
            cap = ncap;
        }
        size_t got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (got == 0)
            break;
    }
    if (!buf)
        st = svet_error_set(err, SVET_ERR_NOMEM, "%s: out of memory", path);
    else if (st == SVET_OK && ferror(f))
        st = svet_error_set(err, SVET_ERR_IO, "%s: read error", path);
    fclose(f);
    if (st == SVET_OK)
        st = obj_parse(path, buf, n, lim, o, err);
    free(buf);
    return st;
}

void obj_free(obj_t *o)
{
    if (!o)
        return;
    cobject_free(o->mesh);
    free_names(o->materials, o->nmaterials);
    free_names(o->groups, o->ngroups);
    free(o->tri_group);
    memset(o, 0, sizeof *o);
}
