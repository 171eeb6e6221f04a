/*
 * texpart.c - the textures of ch. 10 in the scene file and the renderer
 * (texpart.h): `texture NAME KIND KEYS`, names of textures in place of a
 * material's values, `bump NAME strength S` on a material or a shape, and
 * the per-hit shading hook
 * (scene_t.shade) that reads them.
 * Tests: tests/texture/test_texpart.c
 */
#include "texture/texpart.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/imageio.h"
#include "materials/material.h"
#include "render/camera.h"
#include "texture/raydiff.h"
#include "texture/texture.h"

#define TEXPART_MAX_TEXTURES 4096
#define PI_D 3.14159265358979323846

/* A named texture. */
typedef struct {
    char name[SCENE_MAX_NAME + 1];
    texture_t tex;
} named_texture_t;

/* What a textured material reads at a hit: the textures standing for its
 * parameters (NULL: the material's own value). cobject.h's COBJECT.texture
 * points at one. */
struct texture {
    const material_t *base;                        /* the scene's material */
    const texture_t *param[SCENE_PARAM_BUMP + 1];  /* by scene_param_t */
    int index[SCENE_PARAM_BUMP + 1]; /* the same as indices into the
                                        part's textures, -1: none (the
                                        pointers are set by finish, once
                                        the list has stopped growing) */
    real strength;                                 /* the bump's scale */
    bool reparam;   /* some parameter other than the bump is textured */
    real spread;    /* the camera's angle per pixel, radians (footprint) */
};
typedef struct texture binding_t;

/* A `bump NAME strength S` given on a shape or mesh: it replaces its
 * material's bump (if any) on those objects. */
typedef struct {
    COBJECT *obj;
    int index;     /* into the part's textures */
    real strength;
} shape_bump_t;

/* An `emit NAME`: the emitter reads texture `index` (its pointer is set
 * by finish, as the bindings' are). */
typedef struct {
    scene_emission_t *e;
    int index;
} emitter_t;

typedef struct {
    named_texture_t *tex;  /* every texture, in order */
    int ntex;
    binding_t *bind;       /* every textured material, then every object
                              of a bumped shape (set up by finish) */
    int nbind;
    shape_bump_t *bumps;   /* every bumped shape's objects */
    int nbumps;
    emitter_t *emitters;   /* every textured emitter */
    int nemitters;
    camera_t camera;       /* the scene's, for the camera rays'
                              differentials (raydiff_ops) */
} texpart_data_t;

static void data_free(void *p)
{
    texpart_data_t *d = p;
    for (int i = 0; i < d->ntex; i++)
        texture_free(&d->tex[i].tex);
    free(d->tex);
    free(d->bind);
    free(d->bumps);
    free(d->emitters);
    free(d);
}

static texpart_data_t *data_of(scenefile_ctx *c)
{
    bool fresh;
    return scene_part_data_new(scenefile_scene(c), "texture",
                               sizeof(texpart_data_t), data_free, &fresh);
}

/* --- `texture NAME KIND KEYS` -------------------------------------------- */

static const char *const kinds[] = {
    "image", "checker", "noise", "fbm", "turbulence", "marble", "wood",
    "granite", "waves", "ripples", "bricks", "orange_peel", "dents", NULL
};
enum { K_IMAGE, K_CHECKER, K_NOISE, K_FBM, K_TURBULENCE, K_MARBLE, K_WOOD,
       K_GRANITE, K_WAVES, K_RIPPLES, K_BRICKS, K_ORANGE_PEEL, K_DENTS,
       K_N };

static const char *const filters[] = { "nearest", "bilinear", "trilinear",
                                       NULL };
static const char *const wraps[] = { "repeat", "clamp", "mirror", NULL };

enum { T_FILE, T_FILTER, T_WRAP, T_DATA, T_A, T_B, T_SCALE, T_SOLID,
       T_OCTAVES, T_LACUNARITY, T_GAIN, T_AMPLITUDE, T_RINGS, T_FREQUENCY,
       T_ANGLE, T_DAMPING, T_N };
static const spec_t texture_spec[T_N] = {
    [T_FILE] = { "file", V_STRING, 0, 0, 0, NULL },
    [T_FILTER] = { "filter", V_WORD, 0, 0, 0, filters },
    [T_WRAP] = { "wrap", V_WORD, 0, 0, 0, wraps },
    [T_DATA] = { "data", V_FLAG, 0, 0, 0, NULL },
    [T_A] = { "a", V_COLOUR, 0, 0, 0, NULL },
    [T_B] = { "b", V_COLOUR, 0, 0, 0, NULL },
    [T_SCALE] = { "scale", V_NUM, F_POSITIVE, 0, 0, NULL },
    [T_SOLID] = { "solid", V_FLAG, 0, 0, 0, NULL },
    [T_OCTAVES] = { "octaves", V_INT, 0, 1, NOISE_MAX_OCTAVES, NULL },
    [T_LACUNARITY] = { "lacunarity", V_NUM, F_POSITIVE, 0, 0, NULL },
    [T_GAIN] = { "gain", V_NUM, F_POSITIVE, 0, 0, NULL },
    [T_AMPLITUDE] = { "amplitude", V_NUM, F_NONNEG, 0, 0, NULL },
    [T_RINGS] = { "rings", V_NUM, F_POSITIVE, 0, 0, NULL },
    [T_FREQUENCY] = { "frequency", V_NUM, F_POSITIVE, 0, 0, NULL },
    [T_ANGLE] = { "angle", V_NUM, 0, 0, 0, NULL },
    [T_DAMPING] = { "damping", V_NUM, F_NONNEG, 0, 0, NULL },
};

/* Which keys each kind takes (bit i: key i). */
#define B(k) (1u << (k))
#define SOLID_KEYS (B(T_A) | B(T_B) | B(T_SCALE) | B(T_OCTAVES) | \
                    B(T_LACUNARITY) | B(T_GAIN))
#define PATTERN_KEYS (B(T_A) | B(T_B) | B(T_SCALE) | B(T_FREQUENCY))
static const unsigned kind_keys[K_N] = {
    [K_IMAGE] = B(T_FILE) | B(T_FILTER) | B(T_WRAP) | B(T_DATA) |
                B(T_SCALE),
    [K_CHECKER] = B(T_A) | B(T_B) | B(T_SCALE) | B(T_SOLID),
    [K_NOISE] = B(T_A) | B(T_B) | B(T_SCALE),
    [K_FBM] = SOLID_KEYS,
    [K_TURBULENCE] = SOLID_KEYS,
    [K_MARBLE] = SOLID_KEYS | B(T_AMPLITUDE),
    [K_WOOD] = SOLID_KEYS | B(T_AMPLITUDE) | B(T_RINGS),
    [K_GRANITE] = SOLID_KEYS,
    [K_WAVES] = PATTERN_KEYS | B(T_ANGLE),
    [K_RIPPLES] = PATTERN_KEYS | B(T_DAMPING),
    [K_BRICKS] = B(T_A) | B(T_B) | B(T_SCALE),
    [K_ORANGE_PEEL] = PATTERN_KEYS,
    [K_DENTS] = PATTERN_KEYS,
};

/* Read the image of an `image` texture into t's mip map. */
static svet_status load_image(scenefile_ctx *c, texture_t *t, const val_t *v)
{
    svet_error e;
    char *path = scenefile_path(c, &v[T_FILE].word, &e);
    if (!path)
        return scenefile_fail(c, v[T_FILE].col, e.status, "%s", e.msg);
    image_t img;
    memset(&img, 0, sizeof img);
    /* a colour stored as sRGB codes (PNG, PPM) is decoded to linear; a
     * data image (heights) is read as stored */
    svet_status st = imageio_read(path, &img, !v[T_DATA].on, NULL, &e);
    free(path);
    if (st)
        return scenefile_fail(c, v[T_FILE].word.col, st, "texture file: %s",
                              e.msg);
    /* three channels: an alpha is dropped; a non-finite texel (an EXR may
     * hold NaN) is refused, the mip map's means would spread it */
    const int n = img.width * img.height;
    float *rgb = malloc((size_t)n * 3 * sizeof *rgb);
    if (!rgb) {
        image_free(&img);
        return scenefile_fail(c, v[T_FILE].col, SVET_ERR_NOMEM,
                              "out of memory");
    }
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            float x = img.px[(size_t)i * (size_t)img.channels + (size_t)k];
            if (!isfinite(x)) {
                int w = img.width;
                free(rgb);
                image_free(&img);
                return scenefile_fail(c, v[T_FILE].word.col, SVET_ERR_RANGE,
                                      "texture file: the texel (%d, %d) is "
                                      "not a finite number", i % w, i / w);
            }
            rgb[(size_t)i * 3 + (size_t)k] = x;
        }
    mipmap_wrap_t wrap = v[T_WRAP].set ? (mipmap_wrap_t)v[T_WRAP].i
                                       : MIPMAP_REPEAT;
    st = mipmap_build(&t->mip, rgb, img.width, img.height, 3, wrap, &e);
    free(rgb);
    image_free(&img);
    if (st)
        return scenefile_fail(c, v[T_FILE].col, st, "texture file: %s",
                              e.msg);
    t->filter = v[T_FILTER].set ? (mipmap_filter_t)v[T_FILTER].i
                                : MIPMAP_TRILINEAR;
    return SVET_OK;
}

static svet_status texture_statement(scenefile_ctx *c)
{
    char name[SCENE_MAX_NAME + 1];
    int col = 1;
    svet_status st = scenefile_name(c, "texture", name, &col);
    if (st)
        return st;
    texpart_data_t *d = data_of(c);
    if (!d)
        return scenefile_fail(c, col, SVET_ERR_NOMEM, "out of memory");
    for (int i = 0; i < d->ntex; i++)
        if (!strcmp(d->tex[i].name, name))
            return scenefile_fail(c, col, SVET_ERR_PARSE,
                                  "texture '%s' is already defined", name);
    int kind;
    st = scenefile_kind(c, "texture", name, kinds, &kind);
    if (st)
        return st;
    val_t v[T_N];
    char stmt[96];
    snprintf(stmt, sizeof stmt, "texture %s", kinds[kind]);
    st = scenefile_keys(c, stmt, texture_spec, T_N, v, false);
    if (st)
        return st;
    for (int k = 0; k < T_N; k++)
        if (v[k].set && !(kind_keys[kind] & B(k)))
            return scenefile_fail(c, v[k].col, SVET_ERR_PARSE,
                                  "a texture of kind %s takes no '%s'",
                                  kinds[kind], texture_spec[k].key);
    if (kind == K_IMAGE && !v[T_FILE].set)
        return scenefile_fail(c, scenefile_stmt_col(c), SVET_ERR_PARSE,
                              "texture image needs 'file' (a PNG or EXR "
                              "image)");
    if (d->ntex == TEXPART_MAX_TEXTURES)
        return scenefile_fail(c, col, SVET_ERR_RANGE,
                              "more than %d textures", TEXPART_MAX_TEXTURES);
    named_texture_t *nt = realloc(d->tex, (size_t)(d->ntex + 1) * sizeof *nt);
    if (!nt)
        return scenefile_fail(c, col, SVET_ERR_NOMEM, "out of memory");
    d->tex = nt;
    nt = &d->tex[d->ntex];
    memset(nt, 0, sizeof *nt);
    snprintf(nt->name, sizeof nt->name, "%s", name);
    texture_t *tx = &nt->tex;
    tx->a = v[T_A].set ? rad_make(v[T_A].v[0], v[T_A].v[1], v[T_A].v[2])
                       : rad_grey(0);
    tx->b = v[T_B].set ? rad_make(v[T_B].v[0], v[T_B].v[1], v[T_B].v[2])
                       : rad_grey(1);
    tx->scale = v[T_SCALE].set ? v[T_SCALE].v[0] : 1;
    switch (kind) {
    case K_IMAGE:
        tx->kind = TEXTURE_IMAGE;
        st = load_image(c, tx, v);
        if (st)
            return st;
        break;
    case K_CHECKER:
        tx->kind = TEXTURE_CHECKER;
        if (!v[T_SOLID].on)
            break;
        /* fall through - the 3D checker is a solid */
    case K_NOISE: case K_FBM: case K_TURBULENCE: case K_MARBLE: case K_WOOD:
    case K_GRANITE: {
        static const solid_kind_t sk[K_N] = {
            [K_CHECKER] = SOLID_CHECKER, [K_NOISE] = SOLID_NOISE,
            [K_FBM] = SOLID_FRACTAL, [K_TURBULENCE] = SOLID_TURBULENCE,
            [K_MARBLE] = SOLID_MARBLE, [K_WOOD] = SOLID_WOOD,
            [K_GRANITE] = SOLID_GRANITE
        };
        tx->kind = TEXTURE_SOLID;
        tx->solid = solid_default(sk[kind], tx->a, tx->b);
        tx->solid.scale = tx->scale;
        tx->scale = 1;
        if (v[T_OCTAVES].set)
            tx->solid.octaves.octaves = (int)v[T_OCTAVES].i;
        if (v[T_LACUNARITY].set)
            tx->solid.octaves.lacunarity = v[T_LACUNARITY].v[0];
        if (v[T_GAIN].set)
            tx->solid.octaves.gain = v[T_GAIN].v[0];
        if (v[T_AMPLITUDE].set)
            tx->solid.amplitude = v[T_AMPLITUDE].v[0];
        if (v[T_RINGS].set)
            tx->solid.rings = v[T_RINGS].v[0];
        break;
    }
    default: {
        static const bumpgen_kind_t bk[K_N] = {
            [K_WAVES] = BUMPGEN_WAVES, [K_RIPPLES] = BUMPGEN_RIPPLES,
            [K_BRICKS] = BUMPGEN_BRICKS, [K_ORANGE_PEEL] = BUMPGEN_ORANGE_PEEL,
            [K_DENTS] = BUMPGEN_DENTS
        };
        tx->kind = TEXTURE_BUMPGEN;
        tx->bump = bumpgen_default(bk[kind]);
        if (v[T_FREQUENCY].set)
            tx->bump.frequency = v[T_FREQUENCY].v[0];
        if (v[T_ANGLE].set) /* degrees in the scene, radians in bumpgen */
            tx->bump.angle = v[T_ANGLE].v[0] * REAL_PI / 180;
        if (v[T_DAMPING].set)
            tx->bump.damping = v[T_DAMPING].v[0];
        break;
    }
    }
    d->ntex++;
    return SVET_OK;
}

/* --- names in place of a material's values -------------------------------- */

static svet_status material_names(scenefile_ctx *c, const char *material,
                                  const material_t *m,
                                  const scene_named_t *names, int n)
{
    texpart_data_t *d = data_of(c);
    if (!d)
        return scenefile_fail(c, names[0].name.col, SVET_ERR_NOMEM,
                              "out of memory");
    binding_t b;
    memset(&b, 0, sizeof b);
    b.base = m;
    for (int k = 0; k <= SCENE_PARAM_BUMP; k++)
        b.index[k] = -1;
    for (int i = 0; i < n; i++) {
        char name[SCENE_MAX_NAME + 1];
        scenefile_tok_copy(&names[i].name, name, sizeof name);
        int found = -1;
        for (int k = 0; k < d->ntex && found < 0; k++)
            if (!strcmp(d->tex[k].name, name))
                found = k;
        if (found < 0)
            return scenefile_fail(c, names[i].name.col, SVET_ERR_PARSE,
                                  "material '%s': '%s' is neither a number "
                                  "nor a texture defined above", material,
                                  name);
        b.index[names[i].param] = found;
        if (names[i].param == SCENE_PARAM_BUMP)
            b.strength = names[i].strength;
        else
            b.reparam = true;
    }
    if (!b.reparam && b.strength == 0) {
        /* a bump of strength 0 changes nothing: the material is shaded
         * as if it had none, and costs nothing */
        return SVET_OK;
    }
    binding_t *nb = realloc(d->bind, (size_t)(d->nbind + 1) * sizeof *nb);
    if (!nb)
        return scenefile_fail(c, names[0].name.col, SVET_ERR_NOMEM,
                              "out of memory");
    d->bind = nb;
    d->bind[d->nbind++] = b;
    return SVET_OK;
}

/* --- `bump NAME strength S` on a shape or mesh ---------------------------- */

enum { SK_BUMP, SK_STRENGTH, SK_N };
static const spec_t shape_spec[SK_N] = {
    [SK_BUMP] = { "bump", V_STRING, 0, 0, 0, NULL },
    [SK_STRENGTH] = { "strength", V_NUM, 0, 0, 0, NULL },
};

static svet_status shape_keys(scenefile_ctx *c, COBJECT *const *objs, int n,
                              const val_t *vals)
{
    if (!vals[SK_BUMP].set)
        return scenefile_fail(c, vals[SK_STRENGTH].col, SVET_ERR_PARSE,
                              "'strength' is the scale of a bump: give "
                              "'bump NAME' with it");
    texpart_data_t *d = data_of(c);
    if (!d)
        return scenefile_fail(c, vals[SK_BUMP].col, SVET_ERR_NOMEM,
                              "out of memory");
    char name[SCENE_MAX_NAME + 1];
    const tok_t *t = &vals[SK_BUMP].word;
    scenefile_tok_copy(t, name, sizeof name);
    int found = -1;
    for (int k = 0; k < d->ntex && found < 0; k++)
        if (t->len <= SCENE_MAX_NAME && !strcmp(d->tex[k].name, name))
            found = k;
    if (found < 0)
        return scenefile_fail(c, t->col, SVET_ERR_PARSE,
                              "'bump %s': no texture of that name is "
                              "defined above", name);
    if (n <= 0)
        return SVET_OK;
    if (d->nbumps > INT_MAX - n)
        return scenefile_fail(c, t->col, SVET_ERR_RANGE, "too many bumps");
    shape_bump_t *nb = realloc(d->bumps,
                               (size_t)(d->nbumps + n) * sizeof *nb);
    if (!nb)
        return scenefile_fail(c, t->col, SVET_ERR_NOMEM, "out of memory");
    d->bumps = nb;
    for (int i = 0; i < n; i++)
        d->bumps[d->nbumps++] = (shape_bump_t){
            objs[i], found,
            vals[SK_STRENGTH].set ? vals[SK_STRENGTH].v[0] : 1
        };
    return SVET_OK;
}

/* --- `emit NAME`: a textured emitter -------------------------------------- */

static svet_status emit_name(scenefile_ctx *c, scene_emission_t *e,
                             const tok_t *t, RADIANCE *top)
{
    texpart_data_t *d = data_of(c);
    if (!d)
        return scenefile_fail(c, t->col, SVET_ERR_NOMEM, "out of memory");
    char name[SCENE_MAX_NAME + 1];
    scenefile_tok_copy(t, name, sizeof name);
    int found = -1;
    for (int k = 0; k < d->ntex && found < 0; k++)
        if (t->len <= SCENE_MAX_NAME && !strcmp(d->tex[k].name, name))
            found = k;
    if (found < 0)
        return scenefile_fail(c, t->col, SVET_ERR_PARSE,
                              "'emit %s': '%s' is neither a colour nor a "
                              "texture defined above", name, name);
    if (d->nemitters == INT_MAX)
        return scenefile_fail(c, t->col, SVET_ERR_RANGE,
                              "too many emitters");
    emitter_t *ne = realloc(d->emitters,
                            (size_t)(d->nemitters + 1) * sizeof *ne);
    if (!ne)
        return scenefile_fail(c, t->col, SVET_ERR_NOMEM, "out of memory");
    d->emitters = ne;
    d->emitters[d->nemitters++] = (emitter_t){ e, found };
    RADIANCE mean;
    texture_range(&d->tex[found].tex, &mean, top);
    /* the light is chosen by its mean power; an image's negative texels
     * (an EXR may hold them) emit nothing */
    e->radiance = rad_make(real_max(mean.r, REAL_C(0.0)),
                           real_max(mean.g, REAL_C(0.0)),
                           real_max(mean.b, REAL_C(0.0)));
    return SVET_OK;
}

/* L_e at a point of a textured emitter: the texture's colour there, read
 * at the finest level (emission is read without a footprint), negative
 * values emitting nothing. */
static RADIANCE emitted_at(const scene_emission_t *e, const PATHPOINT *pp)
{
    texture_point_t q;
    texture_point_of(&q, pp, 0);
    RADIANCE c = texture_eval(e->texture_data, &q);
    return rad_make(real_max(c.r, REAL_C(0.0)), real_max(c.g, REAL_C(0.0)),
                    real_max(c.b, REAL_C(0.0)));
}

/* --- the shading at a hit ------------------------------------------------- */

/* The width, in (s, t) units, of the pixel's footprint at the hit: from
 * the ray's differentials where the integrator carries them, from the
 * camera through mirrors and glass (Igehy 1999, raydiff.h). Where it
 * carries none (the volume path tracer of ch. 11), at the camera ray's hit
 * a ray cone of the camera's angle per pixel (Amanatides 1984; as
 * Akenine-Moller et al. 2019 use it for texture level of detail), spread
 * over distance r_dist and stretched by 1 / |cos| on the surface, divided
 * by the shorter tangent so that the width follows the major axis of the
 * footprint as a mip map's isotropic level must (Williams 1983). After a
 * sampled (diffuse or glossy) bounce, the finest level. */
static real footprint(const binding_t *b, const PATHPOINT *pp, int depth,
                      const raydiff_t *rd)
{
    if (rd)
        return raydiff_footprint(rd, pp->dpds, pp->dpdt);
    if (depth > 0 || !(b->spread > 0))
        return 0;
    real c = fabs(SVECTOR3(pp->out, pp->ng));
    real w = pp->r_dist * b->spread / real_max(c, REAL_C(1e-3));
    real ls = vec_length(pp->dpds), lt = vec_length(pp->dpdt);
    real l = real_min(ls, lt);
    return l > 0 && isfinite(w / l) ? w / l : 0;
}

static RADIANCE clamp01(RADIANCE c)
{
    return rad_make(real_min(real_max(c.r, REAL_C(0.0)), REAL_C(1.0)),
                    real_min(real_max(c.g, REAL_C(0.0)), REAL_C(1.0)),
                    real_min(real_max(c.b, REAL_C(0.0)), REAL_C(1.0)));
}

/* The material's parameters with the textured ones read at q. Colours are
 * clamped to [0, 1] and, where the components' sum exceeds 1 in a
 * channel, all reflectances scaled down together so that material_init's
 * energy bound holds; numbers are a texture's first channel, clamped to
 * the ranges of brdf.h. */
static void textured_params(const binding_t *b, const texture_point_t *q,
                            material_params *p)
{
    *p = b->base->params;
    RADIANCE *rho[SCENE_PARAM_BUMP] = {
        [SCENE_PARAM_RHO_D] = &p->rho_d, [SCENE_PARAM_RHO_S] = &p->rho_s,
        [SCENE_PARAM_RHO_G] = &p->rho_g, [SCENE_PARAM_RHO_T] = &p->rho_t,
        [SCENE_PARAM_RHO_DT] = &p->rho_dt
    };
    for (int k = 0; k < SCENE_PARAM_BUMP; k++) {
        const texture_t *t = b->param[k];
        if (!t)
            continue;
        RADIANCE c = texture_eval(t, q);
        if (rho[k]) {
            *rho[k] = clamp01(c);
            continue;
        }
        real x = c.r;
        if (k == SCENE_PARAM_E)
            p->e = real_min(real_max(x, REAL_C(0.0)), BRDF_PHONG_E_MAX);
        else {
            x = real_min(real_max(x, BRDF_WARD_ALPHA_MIN), BRDF_WARD_ALPHA_MAX);
            if (k != SCENE_PARAM_ALPHA_Y)
                p->alpha_x = x;
            if (k != SCENE_PARAM_ALPHA_X)
                p->alpha_y = x;
        }
    }
    RADIANCE sum = rad_add(rad_add(rad_add(p->rho_d, p->rho_s),
                                   rad_add(p->rho_g, p->rho_t)), p->rho_dt);
    real most = rad_max(sum);
    if (most > 1) {
        real f = (1 - 8 * REAL_EPSILON) / most;
        p->rho_d = rad_scale(p->rho_d, f);
        p->rho_s = rad_scale(p->rho_s, f);
        p->rho_g = rad_scale(p->rho_g, f);
        p->rho_t = rad_scale(p->rho_t, f);
        p->rho_dt = rad_scale(p->rho_dt, f);
    }
}

static const material_t *shade(const scene_t *s, const COBJECT *obj,
                               const ray_t *r, int depth, PATHPOINT *pp,
                               const raydiff_t *rd, material_t *scratch)
{
    (void)s;
    (void)r;
    const binding_t *b = obj->texture;
    texture_point_t q;
    texture_point_of(&q, pp, footprint(b, pp, depth, rd));
    const material_t *m = b->base;
    if (b->reparam) {
        material_params p;
        textured_params(b, &q, &p);
        svet_error e;
        if (material_init(scratch, &p, &e) == SVET_OK)
            m = scratch;
    }
    const texture_t *h = b->param[SCENE_PARAM_BUMP];
    if (h && b->strength != 0) {
        real hs, ht;
        texture_height(h, &q, &hs, &ht);
        texture_bump(pp, b->strength * hs, b->strength * ht);
    }
    return m;
}

/* --- the ray differentials a path carries (scene.h) ---------------------- */

static void diff_camera(const void *ctx, const ray_t *r, raydiff_t *rd)
{
    raydiff_camera(rd, ctx, r->d);
}

static bool diff_hit(raydiff_t *rd, const ray_t *r, const PATHPOINT *pp)
{
    VECTOR3 d;
    vec_normalize(d, r->d);
    return raydiff_transfer(rd, d, pp->r_dist, pp->ng);
}

/* A delta bounce: back to the side the ray came from is the mirror's
 * reflection, through to the other side the glass's refraction, whose
 * index ratio n_from / n_to is 1 / eta entering from the +n side
 * (material.h's eta = n_inside / n_outside) and eta leaving. About the
 * shading normal, the frame the material sampled wi in, whose change per
 * pixel is the surface's for the hit's (cobject_normal_change(): 0 on
 * flat ones); a bump map's own turning is left out, as pbrt-v3's bump
 * mapping (sec. 9.3) keeps the surface's dn/du. */
static bool diff_scatter(raydiff_t *rd, const ray_t *r, const PATHPOINT *pp,
                         const material_t *m, const VECTOR3 wi)
{
    VECTOR3 d, dndx, dndy;
    vec_normalize(d, r->d);
    cobject_normal_change(pp->IntersectObj, pp, rd->dpdx, dndx);
    cobject_normal_change(pp->IntersectObj, pp, rd->dpdy, dndy);
    real dn = SVECTOR3(d, pp->n), wn = SVECTOR3(wi, pp->n);
    if ((dn < 0) != (wn < 0)) {
        raydiff_reflect(rd, d, pp->n, dndx, dndy);
        return true;
    }
    real eta = m->params.eta > 0 ? m->params.eta : 1;
    return raydiff_refract(rd, d, pp->n, dndx, dndy,
                           dn < 0 ? 1 / eta : eta, wi);
}

static const scene_raydiff_ops_t raydiff_ops = {
    diff_camera, diff_hit, diff_scatter
};

/* --- the whole scene ------------------------------------------------------ */

/* The camera's angle per pixel along the axis its field of view spans. */
static real pixel_spread(const scene_camera_t *cam)
{
    double w = cam->width, h = cam->height;
    double px = cam->fov_axis == SCENE_FOV_X   ? w
                : cam->fov_axis == SCENE_FOV_Y ? h
                                               : sqrt(w * w + h * h);
    return (real)(2 * tan(0.5 * (double)cam->fov * PI_D / 180) / px);
}

static svet_status finish(scenefile_ctx *c)
{
    scene_t *s = scenefile_scene(c);
    texpart_data_t *d = scene_part_data(s, "texture");
    if (!d)
        return SVET_OK;
    for (int k = 0; k < d->nemitters; k++) {
        d->emitters[k].e->texture_data = &d->tex[d->emitters[k].index].tex;
        d->emitters[k].e->radiance_at = emitted_at;
    }
    if (d->nbind == 0 && d->nbumps == 0)
        return SVET_OK;
    /* room for a binding per bumped object, before any pointer into the
     * list is taken */
    if (d->nbumps > 0) {
        binding_t *nb = realloc(d->bind, (size_t)(d->nbind + d->nbumps) *
                                             sizeof *nb);
        if (!nb)
            return scenefile_fail(c, scenefile_stmt_col(c), SVET_ERR_NOMEM,
                                  "out of memory");
        d->bind = nb;
    }
    real spread = pixel_spread(&s->camera);
    for (int k = 0; k < d->nbind; k++) {
        binding_t *b = &d->bind[k];
        b->spread = spread;
        for (int j = 0; j <= SCENE_PARAM_BUMP; j++)
            b->param[j] = b->index[j] >= 0 ? &d->tex[b->index[j]].tex : NULL;
    }
    /* every object of a textured material reads its binding; the rest
     * keep texture NULL and the integrator passes them by */
    for (int i = 0; i < s->nobjects; i++)
        for (int k = 0; k < d->nbind; k++)
            if (s->objects[i]->material == d->bind[k].base)
                s->objects[i]->texture = &d->bind[k];
    /* a shape's bump replaces its material's: the object reads a copy of
     * the material's binding (or a new one) with the shape's height */
    for (int k = 0; k < d->nbumps; k++) {
        const shape_bump_t *sb = &d->bumps[k];
        binding_t b;
        if (sb->obj->texture)
            b = *sb->obj->texture;
        else {
            memset(&b, 0, sizeof b);
            b.base = sb->obj->material;
            for (int j = 0; j <= SCENE_PARAM_BUMP; j++)
                b.index[j] = -1;
            b.spread = spread;
        }
        b.index[SCENE_PARAM_BUMP] = sb->index;
        b.param[SCENE_PARAM_BUMP] = &d->tex[sb->index].tex;
        b.strength = sb->strength;
        if (!b.reparam && b.strength == 0) {
            /* as on a material: a bump of strength 0 is no bump */
            sb->obj->texture = NULL;
            continue;
        }
        d->bind[d->nbind] = b;
        sb->obj->texture = &d->bind[d->nbind++];
    }
    if (d->nbind > 0) {
        s->shade = shade;
        /* the differentials start from the renderer's own camera (render.c
         * makes it from the same fields) */
        const scene_camera_t *sc = &s->camera;
        camera_fov_axis axis = sc->fov_axis == SCENE_FOV_Y ? CAMERA_FOV_Y
                               : sc->fov_axis == SCENE_FOV_DIAGONAL
                                   ? CAMERA_FOV_DIAGONAL
                                   : CAMERA_FOV_X;
        svet_error e;
        if (camera_init(&d->camera, sc->position, sc->target, sc->up,
                        sc->fov, axis, sc->width, sc->height, &e) == SVET_OK) {
            s->raydiff = &raydiff_ops;
            s->raydiff_ctx = &d->camera;
        }
    }
    return SVET_OK;
}

static const scene_statement_t statements[] = {
    { "texture", texture_statement },
    { NULL, NULL }
};

const scene_part_t texpart_part = {
    .name = "texture",
    .statements = statements,
    .methods = NULL,
    .finish = finish,
    .material_names = material_names,
    .shape_keys = shape_spec,
    .nshape_keys = SK_N,
    .shape = shape_keys,
    .emit_name = emit_name,
};
