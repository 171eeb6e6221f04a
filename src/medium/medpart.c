/*
 * medpart.c - the participating media of ch. 11 in the scene file
 * (medpart.h): `medium NAME homogeneous|grid KEYS`, `medium NAME mix
 * A B ...` (medium_mix of named media), the shape keys
 * `medium NAME`, `outside NAME`, `invisible`, and the check that a
 * boundary is closed. The rendering method is in volpath.c.
 * Tests: tests/medium/test_medpart.c
 */
#include "medium/medpart.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "core/sample.h"
#include "medpart_data.h"

#define MEDPART_MAX_MEDIA 4096

static void data_free(void *p)
{
    medpart_data_t *d = p;
    for (int i = 0; i < d->nmedia; i++) {
        volgrid_free(&d->media[i]->grid);
        free(d->media[i]);
    }
    free(d->media);
    for (int i = 0; i < d->nsides; i++)
        free(d->sides[i]);
    free(d->sides);
    free(d);
}

static medpart_data_t *data_of(scenefile_ctx *c)
{
    bool fresh;
    medpart_data_t *d = scene_part_data_new(scenefile_scene(c), "medium",
                                            sizeof *d, data_free, &fresh);
    if (d && fresh)
        d->global = -1;
    return d;
}

const medium_t *medpart_global(const scene_t *s)
{
    const medpart_data_t *d = scene_part_data(s, "medium");
    return d && d->global >= 0 ? &d->media[d->global]->m : NULL;
}

/* --- `medium NAME KIND KEYS` ---------------------------------------------- */

static const char *const kinds[] = { "homogeneous", "grid", "mix", NULL };
enum { K_HOMOGENEOUS, K_GRID, K_MIX, K_N };
static const char *const phases[] = { "isotropic", "hg", "rayleigh", NULL };

enum { M_SIGMA_A, M_SIGMA_S, M_EMISSION, M_PHASE, M_G, M_GLOBAL, M_FILE,
       M_SCALE, M_MIN, M_MAX, M_N };
static const spec_t medium_spec[M_N] = {
    [M_SIGMA_A] = { "sigma_a", V_COLOUR, 0, 0, 0, NULL },
    [M_SIGMA_S] = { "sigma_s", V_COLOUR, 0, 0, 0, NULL },
    [M_EMISSION] = { "emission", V_COLOUR, 0, 0, 0, NULL },
    [M_PHASE] = { "phase", V_WORD, 0, 0, 0, phases },
    [M_G] = { "g", V_NUM, 0, 0, 0, NULL },
    [M_GLOBAL] = { "global", V_FLAG, 0, 0, 0, NULL },
    [M_FILE] = { "file", V_STRING, 0, 0, 0, NULL },
    [M_SCALE] = { "scale", V_NUM, F_NONNEG, 0, 0, NULL },
    [M_MIN] = { "min", V_VEC3, 0, 0, 0, NULL },
    [M_MAX] = { "max", V_VEC3, 0, 0, 0, NULL },
};

static RADIANCE colour_of(const val_t *v, real dflt)
{
    return v->set ? rad_make(v->v[0], v->v[1], v->v[2]) : rad_grey(dflt);
}

/* The .vol file of a grid medium, its density scaled by `scale` and moved
 * to the box min..max when given. */
static svet_status load_grid(scenefile_ctx *c, named_medium_t *nm,
                             const val_t *v)
{
    if (!v[M_FILE].set)
        return scenefile_fail(c, scenefile_stmt_col(c), SVET_ERR_PARSE,
                              "medium grid needs 'file' (a Mitsuba .vol "
                              "grid)");
    svet_error e;
    char *path = scenefile_path(c, &v[M_FILE].word, &e);
    if (!path)
        return scenefile_fail(c, v[M_FILE].col, e.status, "%s", e.msg);
    svet_status st = volgrid_read(&nm->grid, path, VOLGRID_DEFAULT_MAX_VALUES,
                                  &e);
    free(path);
    if (st)
        return scenefile_fail(c, v[M_FILE].word.col, st, "medium file: %s",
                              e.msg);
    if (v[M_MIN].set != v[M_MAX].set)
        return scenefile_fail(c, v[v[M_MIN].set ? M_MIN : M_MAX].col,
                              SVET_ERR_PARSE,
                              "the grid's box needs both 'min' and 'max'");
    if (v[M_MIN].set) {
        for (int k = 0; k < 3; k++) {
            if (!(v[M_MIN].v[k] < v[M_MAX].v[k]))
                return scenefile_fail(c, v[M_MAX].col, SVET_ERR_RANGE,
                                      "the grid's box needs min < max on "
                                      "every axis");
            nm->grid.lo[k] = (float)v[M_MIN].v[k];
            nm->grid.hi[k] = (float)v[M_MAX].v[k];
        }
    }
    if (v[M_SCALE].set) {
        float s = (float)v[M_SCALE].v[0];
        size_t n = (size_t)nm->grid.nx * (size_t)nm->grid.ny *
                   (size_t)nm->grid.nz;
        for (int ch = 0; ch < nm->grid.channels; ch++) {
            for (size_t i = 0; i < n; i++)
                nm->grid.plane[ch][i] *= s;
            nm->grid.max[ch] *= s;
        }
    }
    nm->has_grid = true;
    nm->m.grid = &nm->grid;
    return SVET_OK;
}

/* A new named medium at the end of d's list (NULL: out of memory). */
static named_medium_t *new_medium(medpart_data_t *d, const char *name)
{
    named_medium_t **grown = realloc(d->media, (size_t)(d->nmedia + 1) *
                                                   sizeof *grown);
    if (!grown)
        return NULL;
    d->media = grown;
    named_medium_t *nm = calloc(1, sizeof *nm);
    if (!nm)
        return NULL;
    d->media[d->nmedia++] = nm;
    snprintf(nm->name, sizeof nm->name, "%s", name);
    return nm;
}

/* `medium NAME mix A B ... [global]`: the sum of media defined above
 * (medium_mix), each a homogeneous or grid medium; defined above, so a
 * mix cannot reach itself. */
static svet_status mix_statement(scenefile_ctx *c, medpart_data_t *d,
                                 const char *name, int col)
{
    int idx[MEDIUM_MAX_COMPONENTS], n = 0, ntok;
    bool global = false;
    int global_col = 0;
    while (scenefile_tokens(c, &ntok), ntok > 0) {
        const tok_t *t = scenefile_tokens(c, &ntok);
        if (scenefile_tok_is(&t[0], "global")) {
            global = true;
            global_col = t[0].col;
            scenefile_skip(c, 1);
            continue;
        }
        char comp[SCENE_MAX_NAME + 1];
        int ccol;
        svet_status st = scenefile_name(c, "medium (a component of the mix)",
                                        comp, &ccol);
        if (st)
            return st;
        if (!strcmp(comp, name))
            return scenefile_fail(c, ccol, SVET_ERR_PARSE,
                                  "medium '%s' cannot be a component of "
                                  "itself", name);
        int k = -1;
        for (int i = 0; i < d->nmedia; i++)
            if (!strcmp(d->media[i]->name, comp))
                k = i;
        if (k < 0) {
            const char *names[64];
            int nn = 0;
            for (int i = 0; i < d->nmedia && nn < 64; i++)
                names[nn++] = d->media[i]->name;
            const char *near = scene_nearest_name(comp, names, nn);
            return scenefile_fail(c, ccol, SVET_ERR_PARSE,
                                  "unknown medium '%s'%s%s%s", comp,
                                  near ? " (did you mean '"
                                       : " (define the components above "
                                         "the mix",
                                  near ? near : "", near ? "'?)" : ")");
        }
        if (d->media[k]->m.ncomponents > 0)
            return scenefile_fail(c, ccol, SVET_ERR_PARSE,
                                  "'%s' is a mix itself: a mix sums "
                                  "homogeneous and grid media", comp);
        if (n == MEDIUM_MAX_COMPONENTS)
            return scenefile_fail(c, ccol, SVET_ERR_RANGE,
                                  "a mix has at most %d components",
                                  MEDIUM_MAX_COMPONENTS);
        idx[n++] = k;
    }
    if (n == 0)
        return scenefile_fail(c, scenefile_eol_col(c), SVET_ERR_PARSE,
                              "medium '%s' mix expects the names of its "
                              "components", name);
    if (global && d->global >= 0)
        return scenefile_fail(c, global_col, SVET_ERR_PARSE,
                              "medium '%s' is the global medium already",
                              d->media[d->global]->name);
    for (int i = 0; global && i < n; i++)
        if (!medium_is_homogeneous(&d->media[idx[i]]->m))
            return scenefile_fail(c, global_col, SVET_ERR_PARSE,
                                  "'%s' is a grid, which fills a box, not "
                                  "the whole scene", d->media[idx[i]]->name);
    if (d->nmedia == MEDPART_MAX_MEDIA)
        return scenefile_fail(c, col, SVET_ERR_RANGE, "more than %d media",
                              MEDPART_MAX_MEDIA);
    named_medium_t *nm = new_medium(d, name);
    if (!nm)
        return scenefile_fail(c, col, SVET_ERR_NOMEM, "out of memory");
    for (int i = 0; i < n; i++)
        nm->parts[i] = d->media[idx[i]]->m;
    nm->m = medium_mix(nm->parts, n);
    svet_error e;
    if (medium_check(&nm->m, &e))
        return scenefile_fail(c, col, SVET_ERR_RANGE, "medium '%s': %s",
                              name, e.msg);
    if (global)
        d->global = d->nmedia - 1;
    return SVET_OK;
}

static svet_status medium_statement(scenefile_ctx *c)
{
    char name[SCENE_MAX_NAME + 1];
    int col = 1;
    svet_status st = scenefile_name(c, "medium", name, &col);
    if (st)
        return st;
    medpart_data_t *d = data_of(c);
    if (!d)
        return scenefile_fail(c, col, SVET_ERR_NOMEM, "out of memory");
    for (int i = 0; i < d->nmedia; i++)
        if (!strcmp(d->media[i]->name, name))
            return scenefile_fail(c, col, SVET_ERR_PARSE,
                                  "medium '%s' is already defined", name);
    int kind = 0;
    st = scenefile_kind(c, "medium", name, kinds, &kind);
    if (st)
        return st;
    if (kind == K_MIX)
        return mix_statement(c, d, name, col);
    val_t v[M_N];
    char stmt[64];
    snprintf(stmt, sizeof stmt, "medium %s", kinds[kind]);
    st = scenefile_keys(c, stmt, medium_spec, M_N, v, false);
    if (st)
        return st;
    if (kind == K_HOMOGENEOUS)
        for (int k = M_FILE; k <= M_MAX; k++)
            if (v[k].set)
                return scenefile_fail(c, v[k].col, SVET_ERR_PARSE,
                                      "a homogeneous medium takes no '%s'",
                                      medium_spec[k].key);
    if (v[M_G].set && !(v[M_PHASE].set && v[M_PHASE].i == PHASE_HG))
        return scenefile_fail(c, v[M_G].col, SVET_ERR_PARSE,
                              "'g' is the asymmetry of 'phase hg'");
    if (v[M_G].set && !(fabs(v[M_G].v[0]) < PHASE_MAX_G))
        return scenefile_fail(c, v[M_G].col, SVET_ERR_RANGE,
                              "g must be in (-1, 1) (at most %g in size)",
                              (double)PHASE_MAX_G);
    if (v[M_EMISSION].set && !rad_is_black(colour_of(&v[M_EMISSION], 0)) &&
        rad_is_black(colour_of(&v[M_SIGMA_A], 0)))
        return scenefile_fail(c, v[M_EMISSION].col, SVET_ERR_PARSE,
                              "a medium emits sigma_a times 'emission' "
                              "(pbrt-v4's L_e): give it 'sigma_a' > 0");
    if (v[M_GLOBAL].on && d->global >= 0)
        return scenefile_fail(c, v[M_GLOBAL].col, SVET_ERR_PARSE,
                              "medium '%s' is the global medium already",
                              d->media[d->global]->name);
    if (v[M_GLOBAL].on && kind == K_GRID)
        return scenefile_fail(c, v[M_GLOBAL].col, SVET_ERR_PARSE,
                              "a grid fills a box, not the whole scene: "
                              "bound it by a shape ('medium NAME' on a "
                              "box)");
    if (d->nmedia == MEDPART_MAX_MEDIA)
        return scenefile_fail(c, col, SVET_ERR_RANGE, "more than %d media",
                              MEDPART_MAX_MEDIA);
    named_medium_t *nm = new_medium(d, name);
    if (!nm)
        return scenefile_fail(c, col, SVET_ERR_NOMEM, "out of memory");
    nm->m = medium_homogeneous(colour_of(&v[M_SIGMA_A], 0),
                               colour_of(&v[M_SIGMA_S], 0));
    nm->m.emission = colour_of(&v[M_EMISSION], 0);
    nm->m.phase.kind = v[M_PHASE].set ? (phase_kind_t)v[M_PHASE].i
                                      : PHASE_ISOTROPIC;
    nm->m.phase.g = v[M_G].set ? v[M_G].v[0] : 0;
    if (kind == K_GRID) {
        st = load_grid(c, nm, v);
        if (st)
            return st;
    }
    svet_error e;
    if (medium_check(&nm->m, &e))
        return scenefile_fail(c, col, SVET_ERR_RANGE, "medium '%s': %s",
                              name, e.msg);
    if (v[M_GLOBAL].on)
        d->global = d->nmedia - 1;
    return SVET_OK;
}

/* --- the shape keys ------------------------------------------------------- */

enum { B_MEDIUM, B_OUTSIDE, B_INVISIBLE, B_N };
static const spec_t shape_spec[B_N] = {
    [B_MEDIUM] = { "medium", V_STRING, 0, 0, 0, NULL },
    [B_OUTSIDE] = { "outside", V_STRING, 0, 0, 0, NULL },
    [B_INVISIBLE] = { "invisible", V_FLAG, 0, 0, 0, NULL },
};

/* The medium a key names, or fail at its column with "did you mean". */
static svet_status find_medium(scenefile_ctx *c, medpart_data_t *d,
                               const val_t *v, int *index)
{
    char name[SCENE_MAX_NAME + 1];
    scenefile_tok_copy(&v->word, name, sizeof name);
    for (int i = 0; d && i < d->nmedia; i++)
        if (!strcmp(d->media[i]->name, name)) {
            *index = i;
            return SVET_OK;
        }
    if (!strcmp(name, "vacuum")) {
        *index = -1;
        return SVET_OK;
    }
    const char *names[64];
    int n = 0;
    for (int i = 0; d && i < d->nmedia && n < 63; i++)
        names[n++] = d->media[i]->name;
    names[n++] = "vacuum";
    const char *near = scene_nearest_name(name, names, n);
    return scenefile_fail(c, v->word.col, SVET_ERR_PARSE,
                          "unknown medium '%s'%s%s%s", name,
                          near ? " (did you mean '" : " (define it with "
                                                      "'medium NAME ...' "
                                                      "above",
                          near ? near : "", near ? "'?)" : ")");
}

/* Is obj closed? Rays from a point inside it (the mean of points sampled
 * on it: inside, for the convex primitives of app. D and their affine
 * images) in directions spread over the sphere must all leave it through
 * its surface; an open end, or the free side of a flat shape, lets some
 * escape. The directions are a fixed stratified set, so the answer
 * depends on the shape only. */
static bool is_closed(const COBJECT *obj)
{
    enum { NS = 16, ND = 32 };
    VECTOR3 centre = { 0, 0, 0 };
    for (int i = 0; i < NS; i++)
        for (int j = 0; j < NS; j++) {
            real u[2] = { ((real)i + REAL_C(0.5)) / NS,
                          ((real)j + REAL_C(0.5)) / NS };
            cobject_sample_t s;
            obj->ops->sample(obj, u, &s);
            vec_add(centre, centre, s.p);
        }
    vec_scale(centre, centre, (real)1 / (NS * NS));
    for (int i = 0; i < ND; i++)
        for (int j = 0; j < ND; j++) {
            real u[2] = { ((real)i + REAL_C(0.5)) / ND,
                          ((real)j + REAL_C(0.5)) / ND };
            ray_t r;
            vec_copy(r.o, centre);
            sample_uniform_sphere(r.d, u);
            hit_t h;
            if (!cobject_intersect(obj, &r, 0, (real)INFINITY, &h))
                return false;
            PATHPOINT pp;
            cobject_fill(obj, &r, &h, &pp);
            if (SVECTOR3(pp.ng, r.d) <= 0)
                return false;
        }
    return true;
}

static svet_status add_side(scenefile_ctx *c, medpart_data_t *d, int index,
                            bool invisible, struct medium **out)
{
    side_t **grown = realloc(d->sides, (size_t)(d->nsides + 1) *
                                           sizeof *grown);
    if (!grown)
        return scenefile_fail(c, scenefile_stmt_col(c), SVET_ERR_NOMEM,
                              "out of memory");
    d->sides = grown;
    side_t *s = calloc(1, sizeof *s);
    if (!s)
        return scenefile_fail(c, scenefile_stmt_col(c), SVET_ERR_NOMEM,
                              "out of memory");
    d->sides[d->nsides++] = s;
    s->index = index;
    s->rec.invisible = invisible;
    *out = &s->rec;
    return SVET_OK;
}

static svet_status shape_keys(scenefile_ctx *c, COBJECT *const *objs, int n,
                              const val_t *v)
{
    if (!v[B_MEDIUM].set)
        return scenefile_fail(c, v[v[B_OUTSIDE].set ? B_OUTSIDE
                                                    : B_INVISIBLE].col,
                              SVET_ERR_PARSE,
                              "'%s' belongs to the boundary of a medium: "
                              "it needs 'medium NAME'",
                              v[B_OUTSIDE].set ? "outside" : "invisible");
    medpart_data_t *d = data_of(c);
    if (!d)
        return scenefile_fail(c, v[B_MEDIUM].col, SVET_ERR_NOMEM,
                              "out of memory");
    int in = -1, out = -2; /* -2: the global medium, found at the end */
    svet_status st = find_medium(c, d, &v[B_MEDIUM], &in);
    if (st)
        return st;
    if (v[B_OUTSIDE].set && (st = find_medium(c, d, &v[B_OUTSIDE], &out)))
        return st;
    for (int i = 0; i < n; i++) {
        if (objs[i]->light && v[B_INVISIBLE].on)
            return scenefile_fail(c, v[B_INVISIBLE].col, SVET_ERR_PARSE,
                                  "an invisible boundary has no surface, "
                                  "so it cannot emit");
        if (strcmp(objs[i]->ops->name, "mesh") && !is_closed(objs[i]))
            return scenefile_fail(c, v[B_MEDIUM].col, SVET_ERR_RANGE,
                                  "the boundary of a medium must be a "
                                  "closed surface (a sphere, a box, a "
                                  "cylinder or cone without 'open', a "
                                  "closed mesh), not this %s",
                                  objs[i]->ops->name);
    }
    struct medium *ins = NULL, *outs = NULL;
    if ((st = add_side(c, d, in, v[B_INVISIBLE].on, &ins)) ||
        (st = add_side(c, d, out, v[B_INVISIBLE].on, &outs)))
        return st;
    for (int i = 0; i < n; i++) {
        objs[i]->inside = ins;
        objs[i]->outside = outs;
    }
    return SVET_OK;
}

/* --- the whole scene ------------------------------------------------------ */

static svet_status finish(scenefile_ctx *c)
{
    medpart_data_t *d = scene_part_data(scenefile_scene(c), "medium");
    if (!d)
        return SVET_OK;
    /* the media array has stopped growing: the sides point into it now */
    for (int i = 0; i < d->nsides; i++) {
        int k = d->sides[i]->index == -2 ? d->global : d->sides[i]->index;
        d->sides[i]->rec.m = k >= 0 ? &d->media[k]->m : NULL;
    }
    return SVET_OK;
}

/* Whether a medium the scene uses (a boundary's side, or the global
 * medium) emits (medium_emits). */
static bool emits(const scene_t *s)
{
    const medpart_data_t *d = scene_part_data(s, "medium");
    if (!d)
        return false;
    if (d->global >= 0 && medium_emits(&d->media[d->global]->m))
        return true;
    for (int i = 0; i < d->nsides; i++) {
        int k = d->sides[i]->index == -2 ? d->global : d->sides[i]->index;
        if (k >= 0 && medium_emits(&d->media[k]->m))
            return true;
    }
    return false;
}

/* --- `volsingle step H` ----------------------------------------------------- */

enum { VS_STEP, VS_N };
static const spec_t volsingle_spec[VS_N] = {
    [VS_STEP] = { "step", V_NUM, F_POSITIVE, 0, 0, NULL },
};

static svet_status volsingle_statement(scenefile_ctx *c)
{
    val_t v[VS_N];
    svet_status st = scenefile_keys(c, "volsingle", volsingle_spec, VS_N, v,
                                    false);
    if (st)
        return st;
    medpart_data_t *d = data_of(c);
    if (!d)
        return scenefile_fail(c, scenefile_stmt_col(c), SVET_ERR_NOMEM,
                              "out of memory");
    if (v[VS_STEP].set) {
        if (!isfinite(v[VS_STEP].v[0]))
            return scenefile_fail(c, v[VS_STEP].col, SVET_ERR_RANGE,
                                  "the step must be finite");
        d->step = v[VS_STEP].v[0];
    }
    return SVET_OK;
}

static const scene_statement_t statements[] = {
    { "medium", medium_statement },
    { "volsingle", volsingle_statement },
    { NULL, NULL }
};

static const render_method_t *const methods[] = { &volpath_method,
                                                   &volsingle_method, NULL };

const scene_part_t medium_part = {
    .name = "medium",
    .statements = statements,
    .methods = methods,
    .finish = finish,
    .emits = emits,
    .shape_keys = shape_spec,
    .nshape_keys = B_N,
    .shape = shape_keys,
};
