/*
 * scenepart.h - how a part of Part II of the book (photon maps, ch. 8; the
 * irradiance cache, ch. 9; textures, ch. 10; media, ch. 11) joins the scene
 * file and the renderer without the core naming it: its statements
 * (`texture`, `medium`, `photonmap`), its data kept in the scene, and its
 * rendering methods (`render integrator photon`). A program offers a part by
 * listing it in scene_features_t.parts (scene.h; allparts.c lists them all);
 * a program that does not (ch. 5) links none of its code, and its keywords
 * are refused with the chapter that brings them. The keys of a part's
 * statements are read with the scene file's own machinery (spec_t,
 * scenefile_keys), so their messages name file:line:column as the core's do.
 * Tests: tests/render/test_scenepart.c
 */
#ifndef SVET_SCENEPART_H
#define SVET_SCENEPART_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "core/error.h"
#include "core/rng.h"
#include "core/ray.h"
#include "materials/radiance.h"
#include "render/scene.h"

struct render;
struct integrator_stats;

/* --- the scene file's keys, for a part's statements ----------------------- */

/* The parser's state while it reads one line (scenefile.c). */
typedef struct scenefile_ctx scenefile_ctx;

/* A token of a line: a word, or a "quoted string" without its quotes. */
typedef struct {
    const char *s; /* first byte (not NUL-terminated) */
    int len;
    int col;       /* 1-based column of its first byte (of the quote) */
    bool quoted;
} tok_t;

/* What a key's values look like. */
typedef enum {
    V_NUM,       /* one number */
    V_INT,       /* a whole number in [lo, hi] */
    V_U64,       /* a whole number 0 .. 2^64 - 1 */
    V_VEC3,      /* three numbers */
    V_COLOUR,    /* one number (grey) or three (RGB), each >= 0 */
    V_WORD,      /* one of `choices` */
    V_STRING,    /* a word or a quoted string (a file name) */
    V_FLAG,      /* no value: present or not */
    V_ONOFF,     /* on or off */
    V_SCALE,     /* transforms: repeatable, applied in written order */
    V_ROTATE,
    V_TRANSLATE
} vtype;

enum {
    F_REQUIRED = 1, /* the statement needs this key */
    F_POSITIVE = 2, /* the number must be > 0 */
    F_NONNEG = 4,   /* the number must be >= 0 */
    F_NONZERO = 8,  /* the vector must not be zero */
    F_NAMED = 16    /* V_NUM, V_COLOUR: a name may stand in place of the
                       value (a texture, ch. 10): val_t.named is set, the
                       number is left 0, and a part resolves the name */
};

/* One key a statement takes. */
typedef struct {
    const char *key;
    vtype type;
    int flags;
    long lo, hi;                 /* V_INT's range */
    const char *const *choices;  /* V_WORD's words, NULL-terminated */
} spec_t;

/* The value of one key after parsing. */
typedef struct {
    bool set;
    int col;     /* column of the key */
    real v[3];   /* numbers, vector, colour */
    long i;      /* integer, or index of a V_WORD choice */
    uint64_t u;  /* V_U64 */
    bool on;     /* V_FLAG, V_ONOFF */
    tok_t word;  /* V_WORD, V_STRING, V_ONOFF: the token; F_NAMED: the
                    name given in place of the value */
    bool named;  /* F_NAMED: a name was given, not a number */
} val_t;

/* The scene being read. */
scene_t *scenefile_scene(scenefile_ctx *c);

/* The rest of the line's tokens, from the next one to read: *n of them
 * at the returned pointer. scenefile_skip(c, k) moves past k of them. */
const tok_t *scenefile_tokens(scenefile_ctx *c, int *n);
void scenefile_skip(scenefile_ctx *c, int k);

/* Column of the statement's keyword, and of the end of the line. */
int scenefile_stmt_col(const scenefile_ctx *c);
int scenefile_eol_col(const scenefile_ctx *c);

/* The next token as a name (a letter or '_', then letters, digits, '_',
 * '-', '.'; at most SCENE_MAX_NAME bytes) into buf of SCENE_MAX_NAME + 1
 * bytes, its column in *col. `what` says what the name is for the
 * message ("texture"). Fails with SVET_ERR_PARSE and file:line:col. */
svet_status scenefile_name(scenefile_ctx *c, const char *what, char *buf,
                           int *col);

/* The next token as the kind of a statement `STMT NAME KIND key ...`
 * (`texture`, `medium`): one of the words kinds[] (NULL-terminated),
 * whose index goes to *kind; the token is passed. A missing or unknown
 * kind fails with SVET_ERR_PARSE at its column (the end of the line when
 * missing), listing the kinds: "medium 'fog' expects a kind: homogeneous
 * or grid, not 'gas'". */
svet_status scenefile_kind(scenefile_ctx *c, const char *stmt,
                           const char *name, const char *const *kinds,
                           int *kind);

/* Read the rest of the line as keys of statement stmt (spec's nspec keys,
 * values into vals[nspec]), with the core's checks and messages: unknown
 * keys with "did you mean", a key given twice, missing required keys,
 * NaN, ranges. Stops at a '+' when stop_at_plus. */
svet_status scenefile_keys(scenefile_ctx *c, const char *stmt,
                           const spec_t *spec, int nspec, val_t *vals,
                           bool stop_at_plus);

/* Fail with "file:line:col: message" (or "override 'k=v': message"). */
#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
svet_status scenefile_fail(scenefile_ctx *c, int col, svet_status st,
                           const char *fmt, ...);

/* Add a warning "file:line:col: warning: message" to the scene. */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
void scenefile_warn(scenefile_ctx *c, int col, const char *fmt, ...);

/* The token as a NUL-terminated string in buf (cut to size - 1). */
void scenefile_tok_copy(const tok_t *t, char *buf, size_t size);

/* True when t is the unquoted word w. */
bool scenefile_tok_is(const tok_t *t, const char *w);

/* The file a token names, relative to the scene file's directory unless
 * absolute, newly allocated (NULL: out of memory, err set); kept in the
 * scene's list of files too (scene_t.files), whose bytes identify it. */
char *scenefile_path(scenefile_ctx *c, const tok_t *t, svet_error *err);

/* --- a part's data in the scene ------------------------------------------- */

/* The data part `name` keeps in s (its textures, its media, its settings),
 * or NULL when it has none yet. */
void *scene_part_data(const scene_t *s, const char *name);

/* Keep data (owned by s from now on, freed with free_fn at scene_free;
 * free_fn may be NULL) as part `name`'s; replaces what was there (freeing
 * it). Fails with SVET_ERR_NOMEM (data freed then too). */
svet_status scene_set_part_data(scene_t *s, const char *name, void *data,
                                void (*free_fn)(void *), svet_error *err);

/* Part `name`'s data in s; when it has none yet, a new zeroed block of
 * size bytes kept as its data (freed with free_fn) and *fresh set, so the
 * part can give it its defaults. NULL when out of memory. */
void *scene_part_data_new(scene_t *s, const char *name, size_t size,
                          void (*free_fn)(void *), bool *fresh);

/* --- a part's statements and rendering methods ----------------------------- */

/* A statement a part adds, e.g. { "texture", texture_statement }. */
typedef struct {
    const char *keyword;
    svet_status (*parse)(scenefile_ctx *c);
} scene_statement_t;

/* A way of rendering a part offers: the word after `render integrator`.
 * The renderer (render.c) calls prepare once, after its tracer and
 * lights exist (a photon map's tracing, an irradiance cache's pre-pass),
 * then begin_pass before each pass over the samples [s0, s1) of every
 * pixel (may be NULL; a progressive photon map's new map), then li for
 * every camera sample, from several threads at once. The image must
 * depend on the scene, the seed and the sample indices only: not on the
 * thread count, nor on how the samples are split into passes or parts
 * (svet merge). A part of a split render (--samples FROM:TO, --crop)
 * runs prepare in full: a pre-pass depends on the scene and the seed
 * only, never on the part's sample range or crop, so that every part
 * sees the same photon map or cache. begin_pass may then first be called
 * with s0 = FROM > 0. free is called only for a state prepare made. */
typedef struct render_method {
    const char *name;                /* "photon", "ppm", "irradiance" */
    const char *describe;            /* a line for the summary */
    svet_status (*prepare)(void **state, const struct render *r,
                           int threads, svet_error *err);
    svet_status (*begin_pass)(void *state, const struct render *r, long s0,
                              long s1, int threads, svet_error *err);
    RADIANCE (*li)(const void *state, const struct render *r,
                   const ray_t *ray, long sample, pcg32_t *g,
                   struct integrator_stats *st);
    void (*free)(void *state);
    /* What the method counted while rendering, one line for the render
     * log without a newline (the irradiance cache's records and lookups),
     * into buf of size bytes; may be NULL. */
    void (*report)(const void *state, char *buf, size_t size);
    /* The pre-pass to a file and back (both NULL for a method that does
     * not save it): save writes what prepare computed to f, load makes
     * from it the state prepare would have made for the same scene and
     * seed, bit for bit, so that the parts of a split render can read one
     * pre-pass (render_init_prepass). load fails with the reason for a
     * file of another method or layout. */
    svet_status (*save)(const void *state, FILE *f, svet_error *err);
    svet_status (*load)(void **state, const struct render *r, FILE *f,
                        svet_error *err);
    /* Whether li takes `render light indirect` (scene.h's scene_light):
     * render_init refuses that setting for a method without it. */
    bool indirect_light;
} render_method_t;

/* Called once the whole file is read (may be NULL): what only the whole
 * scene can tell (a medium's boundary is closed, a texture is used). */
typedef svet_status (*scene_part_finish_fn)(scenefile_ctx *c);

/* --- names in place of a material's numbers (ch. 10) ---------------------- */

/* Which parameter of a material (material.h's material_params) a name
 * stands for: `material m lambert rho wood` gives SCENE_PARAM_RHO_D, and
 * the component `+ bump NAME strength S` SCENE_PARAM_BUMP. */
typedef enum {
    SCENE_PARAM_RHO_D,   /* lambert rho */
    SCENE_PARAM_RHO_S,   /* mirror rho */
    SCENE_PARAM_RHO_G,   /* phong or ward rho */
    SCENE_PARAM_E,       /* phong e */
    SCENE_PARAM_ALPHA,   /* ward alpha: alpha_x = alpha_y */
    SCENE_PARAM_ALPHA_X, /* ward alpha_x */
    SCENE_PARAM_ALPHA_Y, /* ward alpha_y */
    SCENE_PARAM_RHO_T,   /* transmission rho */
    SCENE_PARAM_RHO_DT,  /* diffuse_transmission rho */
    SCENE_PARAM_BUMP     /* the height of a bump map (Blinn 1978) */
} scene_param_t;

/* One name a material statement gave in place of a value. */
typedef struct {
    scene_param_t param;
    tok_t name;     /* the name, with its column */
    real strength;  /* SCENE_PARAM_BUMP: the height's scale (1 when not
                       given); 1 otherwise */
} scene_named_t;

/* Called after a material whose statement gave names (F_NAMED keys, a
 * bump) was added to the scene as m, the material with each named colour
 * black and each named number at its default: the part resolves the names
 * (an unknown one fails with scenefile_fail at its column) and arranges
 * the per-hit shading (scene_t.shade, scene.h). */
typedef svet_status (*scene_part_names_fn)(scenefile_ctx *c,
                                           const char *material,
                                           const struct material *m,
                                           const scene_named_t *names,
                                           int n);

/* --- a name in place of an emitter's radiance (ch. 10) --------------------- */

/* Called after a shape or mesh statement's `emit NAME` made an object an
 * emitter, e (the scene's record, radiance black): the part resolves the
 * name (an unknown one fails with scenefile_fail at name's column), sets
 * e->radiance to the texture's mean (the light's power, light.c) and
 * *top to its brightest value per channel (which the scene file's
 * checks of a light's brightness and power read), and arranges, by the
 * end of the file, e->radiance_at (scene.h). */
typedef svet_status (*scene_part_emit_fn)(scenefile_ctx *c,
                                          scene_emission_t *e,
                                          const tok_t *name, RADIANCE *top);

/* --- keys a part adds to the shapes (ch. 10, 11) --------------------------- */

/* Called after a shape or mesh statement added its objects to the scene
 * (objs[0 .. n): one for a shape, one per part of a mesh), with the values
 * of the part's shape keys in the order of scene_part_t.shape_keys, when
 * at least one of them is set: `medium NAME` (ch. 11) marks the objects
 * as the boundary of a medium. */
typedef svet_status (*scene_part_shape_fn)(scenefile_ctx *c,
                                           COBJECT *const *objs, int n,
                                           const val_t *vals);

/* The most shape keys all parts together may add. */
#define SCENE_MAX_SHAPE_KEYS 8

/* Define a part with designated initializers (.name = "photon", ...), so
 * that the fields it does not use are NULL. */
typedef struct scene_part {
    const char *name;                      /* "photon", "texture", ... */
    const scene_statement_t *statements;   /* ends with { NULL, NULL } */
    const render_method_t *const *methods; /* NULL-terminated, or NULL */
    scene_part_finish_fn finish;
    /* resolves names in place of a material's values (may be NULL: a
     * name there is refused, unless another part offers this) */
    scene_part_names_fn material_names;
    /* keys every shape and mesh statement takes (nshape_keys of them),
     * and what is done with them (shape; both may be NULL) */
    const spec_t *shape_keys;
    int nshape_keys;
    scene_part_shape_fn shape;
    /* resolves a name given to `emit` (may be NULL: refused, unless
     * another part offers this) */
    scene_part_emit_fn emit_name;
    /* whether the part's data emits light the core does not see (a
     * medium's emission), so that "nothing emits light" is not said of
     * a scene lit that way (may be NULL: it emits nothing) */
    bool (*emits)(const struct scene *s);
} scene_part_t;

/* The method `name` among the parts features offers, or NULL. */
const render_method_t *scene_find_method(const scene_features_t *features,
                                         const char *name);

#endif
