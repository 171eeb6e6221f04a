/*
 * scene.h - the scene in memory: what a scene file (scenes/README.md,
 * scenefile.h) describes and what the renderer of ch. 3 and 5 reads.
 * Plain data (camera, render settings, point lights) plus the built objects
 * and materials, all owned by the scene. "Model only what the scene
 * requires": no acceleration structure and no light-sampling table lives
 * here; the renderer builds them from this description when it needs them.
 * Tests: tests/render/test_scene.c (and tests/render/test_scenefile.c for the parser)
 */
#ifndef SVET_SCENE_H
#define SVET_SCENE_H

#include <stdbool.h>
#include <stdint.h>
#include "materials/cobject.h"
#include "core/error.h"
#include "materials/radiance.h"
#include "core/vec.h"
#include "geometry/xform.h"

/* --- limits (documented in scenes/README.md) ----------------------------- */
#define SCENE_MAX_RESOLUTION 16384    /* pixels on either side of the image */
#define SCENE_MAX_PIXELS (1L << 26)   /* width * height: 64 Mpixel */
#define SCENE_MAX_SPP (1L << 24)      /* samples per pixel */
#define SCENE_MAX_DEPTH 1024          /* scattering events per path */
#define SCENE_MAX_THREADS 1024        /* render threads */
#define SCENE_MAX_NAME 64             /* bytes of a material name */

/* --- the camera (ch. 5; its ray formula is in scenes/README.md) ---------- */

/* Which extent of the image the field of view spans. */
typedef enum {
    SCENE_FOV_X = 0,        /* full horizontal angle */
    SCENE_FOV_Y = 1,        /* full vertical angle */
    SCENE_FOV_DIAGONAL = 2  /* full angle along the image diagonal */
} scene_fov_axis;

/* The pixel reconstruction filter. Only the box exists so far: each sample
 * counts with weight 1 in the pixel it falls in. */
typedef enum {
    SCENE_FILTER_BOX = 0
} scene_filter;

/* A pinhole camera. */
typedef struct {
    VECTOR3 position;        /* the eye (pinhole) */
    VECTOR3 target;          /* the point seen at the image centre */
    VECTOR3 up;              /* roughly "up" on the image; not along the
                                view direction */
    real fov;                /* full field of view in degrees, in (0, 180) */
    scene_fov_axis fov_axis; /* which image extent fov spans */
    int width, height;       /* image size in pixels */
    scene_filter filter;     /* pixel filter */
    real filter_width;       /* filter support in pixels (box: 1 = the
                                pixel itself) */
} scene_camera_t;

/* --- render settings ----------------------------------------------------- */

typedef enum {
    SCENE_INTEGRATOR_PATH = 0,   /* path tracing: NEE + BSDF sampling + MIS */
    SCENE_INTEGRATOR_DIRECT = 1, /* direct lighting only (one bounce) */
    SCENE_INTEGRATOR_BSDF = 2,   /* BSDF sampling only, no light sampling */
    SCENE_INTEGRATOR_AO = 3,     /* ambient occlusion within ao_distance */
    SCENE_INTEGRATOR_NEE = 4     /* light sampling without MIS: emitters
                                    that a BSDF sample hits count only after
                                    a delta bounce (ch. 5's comparison) */
} scene_integrator;

/* Which light the image shows (`render light`). */
typedef enum {
    SCENE_LIGHT_ALL = 0,     /* everything the integrator computes */
    SCENE_LIGHT_INDIRECT = 1 /* the indirect diffuse light alone: what the
                                first non-specular vertex's non-delta parts
                                reflect of light that did not come straight
                                from an emitter */
} scene_light;

typedef enum {
    SCENE_ACCEL_AUTO = 0,  /* the renderer chooses from the scene (ch. 7) */
    SCENE_ACCEL_BRUTE = 1, /* test every object */
    SCENE_ACCEL_GRID = 2,  /* uniform grid */
    SCENE_ACCEL_HGRID = 3  /* hierarchical grid */
} scene_accel;

/* Tone-mapping operators of ch. 6, in the order of tonemap.h's
 * tonemap_op_t (the values are equal, so a cast converts). */
typedef enum {
    SCENE_TONEMAP_LINEAR = 0,      /* exposure only: clips the highlights */
    SCENE_TONEMAP_EXPONENTIAL = 1, /* 1 - exp(-L/L_avg) */
    SCENE_TONEMAP_REINHARD = 2,    /* Reinhard et al. 2002, global */
    SCENE_TONEMAP_DRAGO = 3,       /* logarithmic, Drago et al. 2003 */
    SCENE_TONEMAP_HISTOGRAM = 4    /* Ward Larson, Rushmeier, Piatko 1997 */
} scene_tonemap_op;

/* The display curve after the operator, in the order of tonemap.h's
 * tonemap_curve_t. */
typedef enum {
    SCENE_CURVE_SRGB = 0,  /* IEC 61966-2-1 */
    SCENE_CURVE_GAMMA = 1, /* v^(1/gamma) */
    SCENE_CURVE_NONE = 2   /* display-linear */
} scene_tonemap_curve;

typedef struct {
    scene_tonemap_op op;
    real exposure;             /* stops: the image is scaled by 2^exposure
                                  first */
    real key;                  /* Reinhard's key value a (0.18) */
    real white;                /* Reinhard's L_white, in units of the scaled
                                  luminance; 0 = the image maximum */
    real bias;                 /* Drago's bias b, in (0, 1] (0.85) */
    scene_tonemap_curve curve; /* the display curve (sRGB) */
    real gamma;                /* SCENE_CURVE_GAMMA's exponent, > 0 (2.2) */
} scene_tonemap_t;

typedef struct {
    long spp;              /* camera samples per pixel, >= 1 */
    int max_depth;         /* the most scattering events on a path: a path
                              has at most max_depth + 1 segments (camera
                              ray included). 0 = emitters seen directly
                              only; the Cornell box uses 7 */
    bool roulette;         /* Russian roulette on (ch. 4) */
    int roulette_depth;    /* scattering events before roulette may start */
    uint64_t seed;         /* rng_for_sample's seed */
    scene_integrator integrator;
    real ao_distance;      /* AO: occluders farther than this are ignored;
                              0 = unlimited */
    scene_light light;     /* all, or the indirect diffuse light alone
                              (the path tracer's modes and the methods
                              whose indirect_light is set) */
    int threads;           /* 0 = every core */
    double time_limit;     /* seconds of rendering; 0 = none. The image
                              stops after the pass that exceeds it */
    int passes;            /* the spp are spread over this many passes */
    bool checkpoint;       /* write the outputs after every pass */
    char *output_exr;      /* linear output, or NULL: the renderer derives
                              it from the scene file name. Owned */
    char *output_png;      /* tone-mapped output, or NULL (as above). Owned */
    scene_tonemap_t tonemap;
    scene_accel accel;
    bool packets;          /* camera rays traced in packets of 8 x 8 pixels
                              where the structure takes them (the grids of
                              ch. 7); off: one at a time. The image is the
                              same bit for bit */
    /* A rendering method of Part II (scenepart.h), chosen with `render
     * integrator NAME` among those the features' parts offer; NULL: the
     * integrator above. Its own settings are its part's data
     * (scene_part_data). Borrowed from the part */
    const struct render_method *method;
    /* App. F's subsampling (`render subsample step K threshold T`, where
     * the program offers it: scene_features_t.subsample): 0 = off, every
     * pixel by the image loop; K >= 1 (a power of 2): every K-th pixel of
     * every K-th row, then the blocks whose corners differ by a contrast
     * above the threshold, in [0, 1), refined; K = 1 computes every
     * pixel through the same loop */
    int subsample_step;
    real subsample_threshold;
} scene_render_t;

/* --- lights (ch. 5) ------------------------------------------------------ */

/* A point isotropic source: radiant intensity I (W/sr) in every direction,
 * so its power is Phi = 4 pi I. */
typedef struct {
    VECTOR3 position;
    RADIANCE intensity; /* W/sr per RGB channel */
} scene_point_light_t;

/* The emission of a surface: an area light is an object that emits. It is
 * cobject.h's `struct light`, reached from the object as obj->light. */
typedef struct light {
    RADIANCE radiance;    /* emitted radiance L_e, W/(m^2 sr), the same in
                             every direction (a Lambertian emitter); with
                             radiance_at, its mean over the surface, which
                             weighs the light's choice by power (light.c) */
    bool two_sided;       /* false: emits on the +ng (front) side only;
                             true: on both sides */
    const COBJECT *obj;   /* the emitting object */
    /* A radiance that varies over the surface (ch. 10's `emit TEXTURE`):
     * L_e at the filled PATHPOINT pp of obj, >= 0 and finite, set by the
     * part that reads the texture (texture_data its binding); NULL: L_e is
     * `radiance` everywhere. Called from several threads at once. */
    RADIANCE (*radiance_at)(const struct light *e, const PATHPOINT *pp);
    const void *texture_data;
} scene_emission_t;

/* A named material, owned by the scene. */
typedef struct {
    char *name;
    struct material *material; /* material_t of material.h */
} scene_material_t;

/* --- warnings ------------------------------------------------------------ */

/* Warning messages a scene keeps, at the most; the count goes on. */
#define SCENE_MAX_WARNINGS 8

/* What reading a scene found that is valid but likely not what was meant:
 * an OBJ statement skipped, nothing that emits light, sizes beyond what
 * the build's real resolves. Each is "file[:line:col]: warning: ...".
 * Library code never prints: the program that read the scene shows them
 * (the svet command on stderr, the first few and then how many more). */
typedef struct {
    long n;                                       /* warnings issued */
    char msg[SCENE_MAX_WARNINGS][SVET_ERROR_LEN]; /* the first ones */
} scene_warnings_t;

/* Add a printf-style message to w (kept if fewer than SCENE_MAX_WARNINGS
 * are, counted in any case). This function can't fail. */
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
void scene_warn(scene_warnings_t *w, const char *fmt, ...);

/* --- the optional parts a program links (ch. 7 on) ----------------------- */

/* "Model only what the scene requires" holds for programs too: the
 * acceleration structures and the OBJ meshes of ch. 7 (and Part II's
 * photon maps, media, ...) are linked only by the programs that offer
 * them, which say so by handing a scene_features_t to the scene file
 * reader (scenefile_read_with), which keeps it in scene_t.features for
 * the renderer. The svet command, the fuzzers and the tests pass
 * allparts.h's scene_features_all(); ch. 5 passes nothing and links none
 * of them, tracing with its own list of the objects (tracer.h); ch. 7's
 * program hands grid.h's grid_accels to accel.h directly. */

/* One object a mesh loader made, and the material its faces asked for
 * (the OBJ file's usemtl name; NULL for faces before any usemtl). */
typedef struct {
    COBJECT *obj;
    char *material;
} scene_mesh_part_t;

/* Read the mesh file at path for the scene file's `mesh` statement: its
 * triangles moved by x (NULL: as in the file), one object per group of
 * faces of one usemtl name that has faces, in the file's order of the
 * names (faces before any usemtl first); a mesh of one group is one
 * object. On success *parts (malloc'ed; *nparts > 0) and its objects and
 * names (malloc'ed) are the caller's, to free with
 * scene_mesh_parts_free(), and what the file had that was skipped is in
 * *warnings (added with the file's own file:line:col; NULL: not kept).
 * Fails with the file's own file:line:col in err: SVET_ERR_IO,
 * SVET_ERR_PARSE, SVET_ERR_RANGE, SVET_ERR_NOMEM. */
typedef svet_status (*scene_mesh_loader)(const char *path,
                                         const xform_t *x,
                                         scene_mesh_part_t **parts,
                                         int *nparts,
                                         scene_warnings_t *warnings,
                                         svet_error *err);

/* Free n parts (objects not yet handed on are NULL or freed here). NULL
 * is allowed. */
void scene_mesh_parts_free(scene_mesh_part_t *parts, int n);

struct accel_ops;
struct accel_layer;
struct subsample_ops;

typedef struct scene_features {
    /* The acceleration layer of ch. 7 (accel.h's accel_layer), through
     * which the renderer builds its tracer over the structure the scene
     * asks for among `accels`; NULL: ch. 5's list of the objects
     * (tracer.h's tracer_brute), and a scene may ask for no structure. */
    const struct accel_layer *accel;
    /* The acceleration structures offered besides brute force (accel.h's
     * accel_ops_t: the grids, the batched brute force), NULL-terminated;
     * NULL: brute force only. */
    const struct accel_ops *const *accels;
    /* The `mesh` statement's loader; NULL: the statement is refused. */
    scene_mesh_loader mesh;
    /* The parts of Part II offered (scenepart.h: photon maps, the
     * irradiance cache, textures, media), NULL-terminated; NULL: none.
     * Each brings its statements and rendering methods. */
    const struct scene_part *const *parts;
    /* App. F's subsampling (render/subsample.h's subsample_ops); NULL:
     * `render subsample` is refused. */
    const struct subsample_ops *subsample;
} scene_features_t;

/* --- the scene ----------------------------------------------------------- */

struct scene;

/* Ray differentials (Igehy 1999): how a ray's origin and unit direction
 * change per pixel of the image along x and y. Data only: the part that
 * reads textures computes them (texture/raydiff.h), through the hooks of
 * scene_raydiff_ops_t, and reads them at a hit for the pixel's footprint
 * on the texture. */
typedef struct raydiff {
    VECTOR3 dpdx, dpdy; /* the origin's change per pixel along x and y */
    VECTOR3 dddx, dddy; /* the unit direction's change per pixel */
} raydiff_t;

/* A part's per-hit shading (scene_t.shade): at the hit pp of obj (whose
 * `texture` field holds the part's binding) by ray r after `depth`
 * scattering events, it may move pp's shading frame u, v, n (a bump map;
 * bout follows n) and returns the material to shade with: obj->material,
 * or one it built in *scratch for this hit. rd: the ray's differentials
 * carried to pp, or NULL where the caller carries none. Called from
 * several threads at once; it must not draw random numbers. Can't fail. */
typedef const struct material *(*scene_shade_fn)(const struct scene *s,
                                                 const COBJECT *obj,
                                                 const ray_t *r, int depth,
                                                 PATHPOINT *pp,
                                                 const raydiff_t *rd,
                                                 struct material *scratch);

/* How a path carries its camera ray's differentials (scene_t.raydiff, set
 * by the part that reads textures): from the camera, to each hit, and
 * through each delta bounce (mirror, glass); a sampled bounce ends them.
 * Called from several threads at once; none can fail. */
typedef struct scene_raydiff_ops {
    /* the differentials of camera ray r (ctx: scene_t.raydiff_ctx) */
    void (*camera)(const void *ctx, const ray_t *r, raydiff_t *rd);
    /* carried along r (unit direction) to its hit pp; false: lost (the
     * ray runs in the tangent plane) */
    bool (*hit)(raydiff_t *rd, const ray_t *r, const PATHPOINT *pp);
    /* through the delta bounce at pp, by material m, from r's direction to
     * the unit direction wi; false: lost */
    bool (*scatter)(raydiff_t *rd, const ray_t *r, const PATHPOINT *pp,
                    const struct material *m, const VECTOR3 wi);
} scene_raydiff_ops_t;

typedef struct scene {
    char *path;                 /* the file it was read from, or NULL. Owned */
    const scene_features_t *features; /* what the program that read it
                                   offers (the renderer builds from these),
                                   or NULL: the core only. Borrowed */
    scene_camera_t camera;
    scene_render_t render;

    scene_material_t *materials; /* named materials, in order of definition */
    int nmaterials, cap_materials;
    int *material_index;        /* hash of the names: open addressing over
                                   material_slots slots, each an index into
                                   materials or -1; finding a name costs
                                   O(1), so a file of many materials loads
                                   in linear time */
    int material_slots;
    /* Materials no name refers to (e.g. the defaults an OBJ file needs),
     * freed with the scene. */
    struct material **anon_materials;
    int nanon_materials, cap_anon_materials;

    COBJECT **objects;          /* every surface; objects[i]->id == i.
                                   Each has ->material set (never NULL) and
                                   ->light when it emits. Owned */
    int nobjects, cap_objects;

    scene_emission_t **emitters; /* the emitting objects' records. Owned */
    int nemitters, cap_emitters;

    scene_point_light_t *point_lights;
    int npoint_lights, cap_point_lights;

    bool has_environment;       /* a uniform environment surrounds the scene */
    RADIANCE environment;       /* its radiance, W/(m^2 sr) (the furnace) */

    scene_warnings_t warnings;  /* what the reader found worth telling */

    /* What the parts of Part II keep (scenepart.h's scene_part_data):
     * textures (ch. 10), media (ch. 11), their settings. Owned */
    struct scene_part_slot *part_data;
    int npart_data;

    /* The files the scene names (meshes, textures, grids) as opened, in
     * the order read: their bytes are part of a split render's identity
     * (svet render --samples). Owned */
    char **files;
    int nfiles;

    /* The per-hit shading a part installs (ch. 10's textures), called by
     * the integrator for an object whose `texture` field is set, once its
     * PATHPOINT is filled; NULL when no object has one, and an untextured
     * object costs the integrator one NULL test. */
    scene_shade_fn shade;
    /* The ray differentials the same part carries (ch. 10), with its
     * context; NULL when no object reads a texture. */
    const scene_raydiff_ops_t *raydiff;
    const void *raydiff_ctx;
} scene_t;

/* Set s to an empty scene with the defaults of scenes/README.md: camera at
 * the origin looking down -z, up +y, 40 degrees along y, 256 x 256, box
 * filter; 16 spp, max_depth 5, roulette from depth 3, seed 0, path
 * integrator, all threads, tone mapping LINEAR at exposure 0, accel AUTO.
 * This function can't fail. */
void scene_init(scene_t *s);

/* Free everything the scene owns (objects, materials, emission records,
 * strings) and leave s as scene_init() does. Safe on a half-built scene
 * and on one already freed. NULL is allowed. */
void scene_free(scene_t *s);

/* Add material m (from material.h, owned by the scene from now on) under
 * name. On failure m is freed too, so the caller never has to. Fails with
 * SVET_ERR_PARSE when the name is already defined, SVET_ERR_RANGE when it
 * is empty or longer than SCENE_MAX_NAME, SVET_ERR_NOMEM. */
svet_status scene_add_material(scene_t *s, const char *name,
                               struct material *m, svet_error *err);

/* Keep an unnamed material m; same ownership rule as scene_add_material.
 * Fails only with SVET_ERR_NOMEM. */
svet_status scene_add_anon_material(scene_t *s, struct material *m,
                                    svet_error *err);

/* The material defined under name, or NULL. This function can't fail. */
struct material *scene_find_material(const scene_t *s, const char *name);

/* The defined material name nearest to name, as scene_nearest_name()
 * chooses, or NULL when none is close. This function can't fail. */
const char *scene_suggest_material(const scene_t *s, const char *name);

/* Of the n names, the one nearest to name by edit distance (Damerau),
 * if it is close enough to be a typo (at most 2 edits, and at most about a
 * third of name's length); else NULL. For "did you mean" messages. This
 * function can't fail. */
const char *scene_nearest_name(const char *name, const char *const *names,
                               int n);

/* Append obj (owned by the scene from now on, freed on failure) with
 * material m (not NULL; owned by the scene already) and set obj->id.
 * Fails with SVET_ERR_RANGE when m is NULL, SVET_ERR_NOMEM. */
svet_status scene_add_object(scene_t *s, COBJECT *obj,
                             const struct material *m, svet_error *err);

/* Make obj (already in s) an area light of radiance L, on its front side
 * only or on both; sets obj->light. Fails with SVET_ERR_RANGE on a
 * negative or non-finite L or when obj already emits, SVET_ERR_NOMEM. */
svet_status scene_set_emission(scene_t *s, COBJECT *obj, RADIANCE L,
                               bool two_sided, svet_error *err);

/* Append a point isotropic source of the given intensity (W/sr) at p.
 * Fails with SVET_ERR_RANGE on a non-finite p or a negative or non-finite
 * intensity, SVET_ERR_NOMEM. */
svet_status scene_add_point_light(scene_t *s, const VECTOR3 p,
                                  RADIANCE intensity, svet_error *err);

/* Check what only the whole scene can tell: the camera's target differs
 * from its position and up is not along the view direction. Returns
 * SVET_OK or SVET_ERR_RANGE with the reason. */
svet_status scene_validate(const scene_t *s, svet_error *err);

/* True when something can emit light: a point light, an emitting object or
 * the environment. This function can't fail. */
bool scene_has_lights(const scene_t *s);

#endif
