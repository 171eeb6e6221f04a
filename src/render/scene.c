/*
 * scene.c - the scene in memory: defaults, ownership of objects,
 * materials and emission records, and the checks only a whole scene can
 * make. See scene.h; the file format is in scenes/README.md.
 * Tests: tests/render/test_scene.c
 */
#include "render/scene.h"
#include "render/scenepart.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "materials/material.h"

/* One part's data (scenepart.h): its name is a string of the part's. */
struct scene_part_slot {
    const char *name;           /* the part's name: a string of the part's */
    void *data;
    void (*free_fn)(void *);
};

void scene_init(scene_t *s)
{
    memset(s, 0, sizeof *s);
    scene_camera_t *c = &s->camera;
    vec_set(c->position, 0, 0, 0);
    vec_set(c->target, 0, 0, -1);
    vec_set(c->up, 0, 1, 0);
    c->fov = 40;
    c->fov_axis = SCENE_FOV_Y;
    c->width = 256;
    c->height = 256;
    c->filter = SCENE_FILTER_BOX;
    c->filter_width = 1;

    scene_render_t *r = &s->render;
    r->spp = 16;
    r->max_depth = 5;
    r->roulette = true;
    r->roulette_depth = 3;
    r->seed = 0;
    r->integrator = SCENE_INTEGRATOR_PATH;
    r->ao_distance = 0;
    r->light = SCENE_LIGHT_ALL;
    r->threads = 0;
    r->time_limit = 0;
    r->passes = 1;
    r->checkpoint = false;
    r->tonemap.op = SCENE_TONEMAP_LINEAR;
    r->tonemap.exposure = 0;
    r->tonemap.key = REAL_C(0.18);
    r->tonemap.white = 0;
    r->tonemap.bias = REAL_C(0.85);
    r->tonemap.curve = SCENE_CURVE_SRGB;
    r->tonemap.gamma = REAL_C(2.2);
    r->accel = SCENE_ACCEL_AUTO;
    r->packets = true;
    r->subsample_step = 0;
    r->subsample_threshold = REAL_C(0.05);
}

void scene_free(scene_t *s)
{
    if (!s)
        return;
    for (int i = 0; i < s->nobjects; i++)
        cobject_free(s->objects[i]);
    for (int i = 0; i < s->nemitters; i++)
        free(s->emitters[i]);
    for (int i = 0; i < s->nmaterials; i++) {
        material_free(s->materials[i].material);
        free(s->materials[i].name);
    }
    for (int i = 0; i < s->nanon_materials; i++)
        material_free(s->anon_materials[i]);
    free(s->objects);
    free(s->emitters);
    free(s->materials);
    free(s->material_index);
    free(s->anon_materials);
    free(s->point_lights);
    free(s->render.output_exr);
    free(s->render.output_png);
    free(s->path);
    for (int i = 0; i < s->npart_data; i++)
        if (s->part_data[i].free_fn)
            s->part_data[i].free_fn(s->part_data[i].data);
    free(s->part_data);
    for (int i = 0; i < s->nfiles; i++)
        free(s->files[i]);
    free(s->files);
    scene_init(s);
}

/* --- the parts of Part II (scenepart.h) ----------------------------------- */

void *scene_part_data(const scene_t *s, const char *name)
{
    for (int i = 0; i < s->npart_data; i++)
        if (strcmp(s->part_data[i].name, name) == 0)
            return s->part_data[i].data;
    return NULL;
}

svet_status scene_set_part_data(scene_t *s, const char *name, void *data,
                                void (*free_fn)(void *), svet_error *err)
{
    for (int i = 0; i < s->npart_data; i++)
        if (strcmp(s->part_data[i].name, name) == 0) {
            if (s->part_data[i].free_fn && s->part_data[i].data != data)
                s->part_data[i].free_fn(s->part_data[i].data);
            s->part_data[i].data = data;
            s->part_data[i].free_fn = free_fn;
            return SVET_OK;
        }
    struct scene_part_slot *p =
        realloc(s->part_data, (size_t)(s->npart_data + 1) * sizeof *p);
    if (!p) {
        if (free_fn)
            free_fn(data);
        return svet_error_set(err, SVET_ERR_NOMEM, "out of memory");
    }
    s->part_data = p;
    p[s->npart_data++] = (struct scene_part_slot){ name, data, free_fn };
    return SVET_OK;
}

void *scene_part_data_new(scene_t *s, const char *name, size_t size,
                          void (*free_fn)(void *), bool *fresh)
{
    void *d = scene_part_data(s, name);
    *fresh = d == NULL;
    if (d)
        return d;
    svet_error e;
    if (!(d = calloc(1, size)))
        return NULL;
    if (scene_set_part_data(s, name, d, free_fn, &e) != SVET_OK) {
        if (!free_fn) /* else scene_set_part_data freed it */
            free(d);
        return NULL;
    }
    return d;
}

const render_method_t *scene_find_method(const scene_features_t *features,
                                         const char *name)
{
    if (!features || !features->parts)
        return NULL;
    for (int i = 0; features->parts[i]; i++) {
        const render_method_t *const *m = features->parts[i]->methods;
        for (int j = 0; m && m[j]; j++)
            if (strcmp(m[j]->name, name) == 0)
                return m[j];
    }
    return NULL;
}

void scene_warn(scene_warnings_t *w, const char *fmt, ...)
{
    if (w->n >= 0 && w->n < SCENE_MAX_WARNINGS) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(w->msg[w->n], sizeof w->msg[0], fmt, ap);
        va_end(ap);
    }
    w->n++;
}

void scene_mesh_parts_free(scene_mesh_part_t *parts, int n)
{
    for (int i = 0; parts && i < n; i++) {
        cobject_free(parts[i].obj);
        free(parts[i].material);
    }
    free(parts);
}

/* Make room for one more element of size `size` in *arr (count n, capacity
 * *cap), doubling. Returns false when memory runs out or the count would
 * overflow an int. */
static bool grow(void *arr, int n, int *cap, size_t size)
{
    if (n < *cap)
        return true;
    if (*cap > (1 << 29))
        return false;
    int ncap = *cap ? 2 * *cap : 8;
    void *p = realloc(*(void **)arr, (size_t)ncap * size);
    if (!p)
        return false;
    *(void **)arr = p;
    *cap = ncap;
    return true;
}

/* FNV-1a, the 32-bit hash of a name (Fowler, Noll, Vo). */
static unsigned hash_name(const char *name)
{
    unsigned h = 2166136261u;
    for (const unsigned char *p = (const unsigned char *)name; *p; p++)
        h = (h ^ *p) * 16777619u;
    return h;
}

/* The slot of name in the index: where it is, or the empty slot where it
 * would go. The table is never more than half full, so probing ends. */
static int find_slot(const scene_t *s, const char *name)
{
    unsigned mask = (unsigned)s->material_slots - 1;
    unsigned i = hash_name(name) & mask;
    while (s->material_index[i] >= 0 &&
           strcmp(s->materials[s->material_index[i]].name, name) != 0)
        i = (i + 1) & mask;
    return (int)i;
}

/* Make room in the index for one more name: keep it at most half full,
 * doubling and re-inserting. Returns false when memory runs out. */
static bool index_reserve(scene_t *s)
{
    if (2 * (s->nmaterials + 1) <= s->material_slots)
        return true;
    int nslots = s->material_slots ? 2 * s->material_slots : 16;
    int *idx = malloc((size_t)nslots * sizeof *idx);
    if (!idx)
        return false;
    for (int i = 0; i < nslots; i++)
        idx[i] = -1;
    free(s->material_index);
    s->material_index = idx;
    s->material_slots = nslots;
    for (int k = 0; k < s->nmaterials; k++)
        s->material_index[find_slot(s, s->materials[k].name)] = k;
    return true;
}

svet_status scene_add_material(scene_t *s, const char *name,
                               struct material *m, svet_error *err)
{
    size_t len = name ? strlen(name) : 0;
    if (len == 0 || len > SCENE_MAX_NAME) {
        material_free(m);
        return svet_error_set(err, SVET_ERR_RANGE,
                              "a material name must have 1 to %d bytes",
                              SCENE_MAX_NAME);
    }
    if (scene_find_material(s, name)) {
        material_free(m);
        return svet_error_set(err, SVET_ERR_PARSE,
                              "material '%s' is already defined", name);
    }
    char *copy = malloc(len + 1);
    if (!copy || !index_reserve(s) ||
        !grow(&s->materials, s->nmaterials, &s->cap_materials,
              sizeof *s->materials)) {
        free(copy);
        material_free(m);
        return svet_error_set(err, SVET_ERR_NOMEM, "out of memory");
    }
    memcpy(copy, name, len + 1);
    s->materials[s->nmaterials].name = copy;
    s->materials[s->nmaterials].material = m;
    s->material_index[find_slot(s, copy)] = s->nmaterials;
    s->nmaterials++;
    return SVET_OK;
}

svet_status scene_add_anon_material(scene_t *s, struct material *m,
                                    svet_error *err)
{
    if (!grow(&s->anon_materials, s->nanon_materials,
              &s->cap_anon_materials, sizeof *s->anon_materials)) {
        material_free(m);
        return svet_error_set(err, SVET_ERR_NOMEM, "out of memory");
    }
    s->anon_materials[s->nanon_materials++] = m;
    return SVET_OK;
}

struct material *scene_find_material(const scene_t *s, const char *name)
{
    if (s->material_slots == 0)
        return NULL;
    int k = s->material_index[find_slot(s, name)];
    return k >= 0 ? s->materials[k].material : NULL;
}

/* strlen(s), stopping at max: strnlen is POSIX, not C11, and the chapter
 * programs build with a bare cc -std=c11 line. */
static size_t length_upto(const char *s, size_t max)
{
    size_t n = 0;
    while (n < max && s[n])
        n++;
    return n;
}

/* Edit distance of a and b, each cut to 63 bytes (a suggestion for a
 * longer name is no help): the fewest insertions, deletions, substitutions
 * and swaps of two neighbouring bytes that turn one into the other (the
 * "optimal string alignment" form of the Damerau-Levenshtein distance, so
 * that the common typo "dsik" is one edit from "disk"). */
static int edit_distance(const char *a, const char *b)
{
    enum { N = 64 };
    size_t la = length_upto(a, N - 1), lb = length_upto(b, N - 1);
    int d[N][N];
    for (size_t i = 0; i <= la; i++)
        d[i][0] = (int)i;
    for (size_t j = 0; j <= lb; j++)
        d[0][j] = (int)j;
    for (size_t i = 1; i <= la; i++)
        for (size_t j = 1; j <= lb; j++) {
            int best = d[i - 1][j - 1] + (a[i - 1] != b[j - 1]);
            if (d[i - 1][j] + 1 < best)
                best = d[i - 1][j] + 1;
            if (d[i][j - 1] + 1 < best)
                best = d[i][j - 1] + 1;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] &&
                a[i - 2] == b[j - 1] && d[i - 2][j - 2] + 1 < best)
                best = d[i - 2][j - 2] + 1;
            d[i][j] = best;
        }
    return d[la][lb];
}

/* Nearest candidate so far in *best (distance *dbest), if close enough to
 * be a typo: at most 2 edits, and no more than about a third of the
 * name's length, so that 'x' does not suggest 'y'. */
static void consider(const char *name, const char *cand, const char **best,
                     int *dbest)
{
    int d = edit_distance(name, cand);
    size_t len = length_upto(name, 64);
    if (d > 2 || (size_t)d * 3 > len + 1)
        return;
    if (!*best || d < *dbest) {
        *best = cand;
        *dbest = d;
    }
}

const char *scene_nearest_name(const char *name, const char *const *names,
                               int n)
{
    const char *best = NULL;
    int dbest = 0;
    for (int i = 0; i < n; i++)
        consider(name, names[i], &best, &dbest);
    return best;
}

const char *scene_suggest_material(const scene_t *s, const char *name)
{
    const char *best = NULL;
    int dbest = 0;
    for (int i = 0; i < s->nmaterials; i++)
        consider(name, s->materials[i].name, &best, &dbest);
    return best;
}

svet_status scene_add_object(scene_t *s, COBJECT *obj,
                             const struct material *m, svet_error *err)
{
    if (!m) {
        cobject_free(obj);
        return svet_error_set(err, SVET_ERR_RANGE, "object has no material");
    }
    if (!grow(&s->objects, s->nobjects, &s->cap_objects,
              sizeof *s->objects)) {
        cobject_free(obj);
        return svet_error_set(err, SVET_ERR_NOMEM, "out of memory");
    }
    obj->material = m;
    obj->id = s->nobjects;
    s->objects[s->nobjects++] = obj;
    return SVET_OK;
}

static bool colour_is_valid(RADIANCE c)
{
    return rad_is_finite(c) && c.r >= 0 && c.g >= 0 && c.b >= 0;
}

svet_status scene_set_emission(scene_t *s, COBJECT *obj, RADIANCE L,
                               bool two_sided, svet_error *err)
{
    if (!colour_is_valid(L))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "emitted radiance must be finite and >= 0");
    if (obj->light)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "the object already emits");
    scene_emission_t *e = malloc(sizeof *e);
    if (!e || !grow(&s->emitters, s->nemitters, &s->cap_emitters,
                    sizeof *s->emitters)) {
        free(e);
        return svet_error_set(err, SVET_ERR_NOMEM, "out of memory");
    }
    e->radiance = L;
    e->two_sided = two_sided;
    e->obj = obj;
    e->radiance_at = NULL;
    e->texture_data = NULL;
    s->emitters[s->nemitters++] = e;
    obj->light = e;
    return SVET_OK;
}

svet_status scene_add_point_light(scene_t *s, const VECTOR3 p,
                                  RADIANCE intensity, svet_error *err)
{
    if (!vec_is_finite(p))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "a light's position must be finite");
    if (!colour_is_valid(intensity))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "a light's intensity must be finite and >= 0");
    if (!grow(&s->point_lights, s->npoint_lights, &s->cap_point_lights,
              sizeof *s->point_lights))
        return svet_error_set(err, SVET_ERR_NOMEM, "out of memory");
    scene_point_light_t *l = &s->point_lights[s->npoint_lights++];
    vec_copy(l->position, p);
    l->intensity = intensity;
    return SVET_OK;
}

svet_status scene_validate(const scene_t *s, svet_error *err)
{
    const scene_camera_t *c = &s->camera;
    VECTOR3 view, side;
    vec_sub(view, c->target, c->position);
    if (!vec_is_finite(view) || !isfinite(vec_length(view)))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "camera target - position overflows %s: "
                              "bring them closer", REAL_NAME);
    if (!(vec_length(view) > 0))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "camera target must differ from its position");
    vec_normalize(view, view);
    VECTOR3 up;
    if (vec_normalize(up, c->up) == 0)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "camera up must be a nonzero vector");
    /* The frame's side vector is view x up; |view x up| = sin(angle), and
     * below 1e-3 (0.06 degrees) the image would spin on rounding noise. */
    VVECTOR3(side, view, up);
    if (!(vec_length(side) > REAL_C(1e-3)))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "camera up must not be along the view "
                              "direction");
    return SVET_OK;
}

bool scene_has_lights(const scene_t *s)
{
    return s->npoint_lights > 0 || s->nemitters > 0 ||
           (s->has_environment && !rad_is_black(s->environment));
}
