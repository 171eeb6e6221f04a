/*
 * photon.h - the photon map method of ch. 8 (Jensen, "Global Illumination
 * using Photon Maps", EGWR 1996; Jensen, "Realistic Image Synthesis Using
 * Photon Mapping", 2001) as a part of the renderer (scenepart.h): the
 * `photonmap` settings statement, the tracing of photons from the lights
 * into a global and a caustic map (photonmap.h), the radiance estimate,
 * and two rendering methods: `render integrator photon` (Jensen's two
 * passes with final gathering) and `render integrator ppm` (Knaus &
 * Zwicker, "Progressive Photon Mapping: A Probabilistic Approach", ACM TOG
 * 30(3), 2011: a new map for every sample index, its radius shrinking),
 * with Christensen's precomputed irradiance ("Faster Photon Map Global
 * Illumination", JGT 4(3), 1999) as an option of the final gather.
 * Tests: tests/photon/test_photon.c
 */
#ifndef SVET_PHOTON_H
#define SVET_PHOTON_H

#include <stdbool.h>
#include <stdint.h>

#include "core/error.h"
#include "materials/cobject.h"
#include "materials/material.h"
#include "photon/photonmap.h"
#include "render/scenepart.h"

struct render;

/* The `photonmap` statement's settings (scenes/README.md). */
typedef struct {
    uint64_t global;     /* photons emitted for the global map (ppm: for
                            each sample index's map) */
    uint64_t caustic;    /* photons emitted for the caustic map */
    int k;               /* photons in an estimate (ppm: at most) */
    real max_radius;     /* the largest search radius (photon) */
    photonmap_filter_t filter;
    int gather;          /* final-gather rays; 0: the global map seen
                            directly (the fast preview) */
    real alpha;          /* ppm: the radius's shrinking, 0 < alpha < 1 */
    real radius;         /* ppm: r_1, the first sample index's radius */
    int precompute;      /* photon: Christensen 1999's irradiance at every
                            precompute-th global photon for the final
                            gather's lookups; 0: the plain estimate */
} photon_settings_t;

/* The defaults: 100 000 global and caustic photons, k = 50, max_radius
 * 0.1, no filter, 64 gather rays, alpha 0.7, radius 0.05. */
void photon_settings_default(photon_settings_t *s);

/* The largest k: the estimate's arrays live on the stack. */
#define PHOTON_MAX_K 1024

/* The part: the `photonmap` statement and the methods `photon` and
 * `ppm`. allparts.c lists it. */
extern const scene_part_t photon_part;
extern const render_method_t photon_method, photon_ppm_method;

/* The scene's settings (the defaults when it has no photonmap line). */
void photon_settings_of(const scene_t *s, photon_settings_t *out);

/* What photon tracing stores: the global map (every photon at a surface
 * with a non-delta component, photons straight from the light included
 * when direct), and the caustic map (those that came through delta
 * bounces only, at least one: L S+ D). */
typedef enum {
    PHOTON_GLOBAL,        /* every hit, direct included */
    PHOTON_INDIRECT,      /* every hit after at least one bounce */
    PHOTON_CAUSTIC        /* L S+ D */
} photon_kind_t;

/* Emit `count` photons from the lights of r (render.h: its lights and
 * tracer) and store those of `kind` in m, balanced. Photon i draws its
 * numbers from rng_for_sample(seed ^ PHOTON_SEED_SALT, stream, i), so the
 * map is the same for any thread count; `threads` (0: all) trace and
 * balance. Light l is chosen with chance p_l in proportion to the power
 * Phi_l it emits photons with (4 pi I, sides pi L_e A, and 4 pi^2 R^2 L for
 * the environment, R the radius of the sphere its photons leave from: the
 * bounded objects' box, and where an unbounded object such as a plane is
 * present, the ball about the camera's target reaching the eye), and each
 * photon carries Phi_l / (p_l count), the same for every light, so an
 * estimate is unbiased in the count. At each hit the scene's per-hit
 * shading (scene_t.shade, a texture) gives the material. The scene's
 * max_depth bounds the bounces. Fails with SVET_ERR_NOMEM (or a map too
 * large for memory, with its size); m is then empty. */
#define PHOTON_SEED_SALT UINT64_C(0x70686f746f6e6d70)
svet_status photon_trace(const struct render *r, uint64_t count,
                         photon_kind_t kind, uint64_t stream, int threads,
                         photonmap_t *m, svet_error *err);

/* Where photons come from: the sphere (centre, radius) that environment
 * photons leave from, and a discrete distribution over the lights in
 * proportion to the power each emits with, so that every photon carries
 * the same power whichever light it left (Jensen 2001, sec. 5.1, several
 * lights). The light set's own choice (lightset_pick) serves next-event
 * estimation, where the environment counts by pi^2 R^2 L; photons leave
 * it with 4 pi^2 R^2 L. */
typedef struct photon_emitters {
    VECTOR3 centre;
    real radius;
    real *cdf;         /* lights.n + 1 entries */
    int n;
} photon_emitters_t;

/* Build em for the lights of r (which must have at least one). Returns
 * SVET_ERR_NOMEM with err filled when out of memory. */
svet_status photon_emitters_build(photon_emitters_t *em,
                                  const struct render *r, svet_error *err);
/* Free what photon_emitters_build allocated. Can't fail. */
void photon_emitters_free(photon_emitters_t *em);

/* One photon of `count` leaving the lights of r as photon_trace emits
 * them: a light picked by its emitted power (em, chance p_l), the
 * photon's first ray from it and its power Phi_l / (p_l count) (Jensen
 * 2001, sec. 5.1.1), and in *from the object it leaves (an area light's,
 * for the first intersection to skip; NULL otherwise). Draws from g.
 * Returns false when no photon leaves (a light of no power, a degenerate
 * sample). Ch. 11's volume photon map (medium/volphoton.h) traces its
 * photons from here. Can't fail. */
bool photon_emit(const struct render *r, const photon_emitters_t *em,
                 uint64_t count, pcg32_t *g, ray_t *ray, RADIANCE *power,
                 const COBJECT **from);

/* The pieces of photon_trace that another map's tracing (ch. 11's volume
 * photon map, medium/volphoton.h) shares. A photon on its way to a map:
 * where it was stored, the direction it travelled, the normal of the
 * surface on the side it arrived from (zero where there is none, in a
 * medium), and its power. */
typedef struct {
    VECTOR3 pos, dir, n;
    RADIANCE power;
} photon_record_t;

/* A growing list of records; `failed` once a push ran out of memory
 * (that record and every later one are dropped). Zeroed: empty. */
typedef struct {
    photon_record_t *r;
    size_t n, cap;
    bool failed;
} photon_records_t;

/* Append a record to b (its memory grows by doubling). Can't fail: a
 * failure sets b->failed. */
void photon_records_push(photon_records_t *b, const VECTOR3 pos,
                         const VECTOR3 dir, const VECTOR3 n, RADIANCE power);

/* Free n lists' records and the array of lists (NULL: nothing). */
void photon_records_free(photon_records_t *lists, uint64_t n);

/* Photon `index` of `count`: its whole walk from photon_emit, its
 * numbers from its own stream (rng_for_sample), its records pushed into
 * out[0 .. nlists) of photon_trace_records. */
typedef void (*photon_walk_fn)(const struct render *r,
                               const photon_emitters_t *em, uint64_t count,
                               uint64_t index, void *ctx,
                               photon_records_t *out);

/* photons in a chunk, a thread's unit of work; and the most lists a
 * photon's walk may fill */
#define PHOTON_CHUNK 4096
#define PHOTON_MAX_LISTS 4

/* Build the emitters of r, and walk photons 0 .. count - 1 by `walk`
 * (with ctx), `threads` at a time (0: all), in chunks of PHOTON_CHUNK
 * photons, each chunk into nlists (1 .. PHOTON_MAX_LISTS) lists of its
 * own: list j of chunk c is (*lists)[j * *nchunks + c], so list j's
 * records joined in chunk order do not depend on which thread walked
 * which photon. No lights or count 0: *lists NULL, *nchunks 0. Fails
 * with SVET_ERR_NOMEM, the message starting with `what`; a list that ran
 * out of memory on the way says so in its `failed`. Free the lists with
 * photon_records_free(*lists, nlists * *nchunks). */
svet_status photon_trace_records(const struct render *r, uint64_t count,
                                 int threads, int nlists, photon_walk_fn walk,
                                 void *ctx, const char *what,
                                 photon_records_t **lists, uint64_t *nchunks,
                                 svet_error *err);

/* Store the records of lists[0 .. n) in order into the empty map m, with
 * `flags` (photonmap_store), and balance it; no records leave m as it
 * was. Fails with SVET_ERR_NOMEM (the message starting with `what`) when
 * a list ran out of memory, or as photonmap_init and photonmap_balance
 * do. */
svet_status photon_records_store(const photon_records_t *lists, uint64_t n,
                                 uint8_t flags, const char *what,
                                 photonmap_t *m, svet_error *err);

/* The photon at pp (m its material, as shaded) scatters: a new direction
 * by the material's own sampling, adjoint by reciprocity, *power times
 * the sample's weight f |cos| / pdf, then Russian roulette by the
 * weight's largest channel (Jensen 2001, sec. 5.2); *ray the ray on from
 * pp. Draws four numbers from g. *delta (when not NULL) says whether the
 * sample was a delta one. Returns false when the photon ends (no sample,
 * or roulette). */
bool photon_bounce(const material_t *m, const PATHPOINT *pp, pcg32_t *g,
                   RADIANCE *power, ray_t *ray, bool *delta);

/* photon_trace, and then Christensen 1999's precomputation: the
 * irradiance by q (photonmap_irradiance) at the position of every
 * `every`-th stored photon (in the order photon_trace stores them, so
 * the same for any thread count), on the side of the surface the photon
 * came from, into irr (photonmap_precompute). every = 0 leaves irr
 * empty. Fails as photon_trace does; m and irr are then empty. */
svet_status photon_trace_precomputed(const struct render *r, uint64_t count,
                                     photon_kind_t kind, uint64_t stream,
                                     int threads, size_t every,
                                     const photonmap_query_t *q,
                                     photonmap_t *m, photonmap_t *irr,
                                     svet_error *err);

/* The radiance leaving pp toward wo (local frame of pp) estimated from m:
 * L = sum_p w_p f(wi_p, wo) dPhi_p / A, over the k nearest photons within
 * rmax, wi_p the photon's incoming direction, A = pi r^2 times the
 * filter's mean weight (photonmap_filter_area), r the k-th photon's
 * distance or rmax where fewer lie within it (Jensen 1996, eq. 9; Jensen
 * 2001, eq. 7.4). Photons behind the surface get f = 0 from the
 * material's own sidedness; those more than q->disc r off the plane of
 * pp.ng are left out (another surface). q->k <= PHOTON_MAX_K. This
 * function can't fail. */
RADIANCE photon_radiance(const photonmap_t *m, const PATHPOINT *pp,
                         const material_t *mat, const VECTOR3 wo,
                         const photonmap_query_t *q);

#endif
