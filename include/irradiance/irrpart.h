/*
 * irrpart.h - the irradiance cache of ch. 9 as a part of the renderer: the
 * `irradiance` statement (Ward's accuracy a, the M x N gather, the clamp
 * of R in pixels, bounces, gradients, neighbour clamping) and the method
 * `render integrator irradiance`: a deterministic coarse-to-fine pre-pass
 * fills the cache (Ward, Rubinstein, Clear 1988; Ward & Heckbert 1992),
 * then the image reads it for the indirect diffuse light while direct
 * light, mirrors and glass are computed as in ch. 5.
 * Tests: tests/irradiance/test_irrpart.c
 */
#ifndef SVET_IRRPART_H
#define SVET_IRRPART_H

#include <stdbool.h>

#include "core/error.h"
#include "irradiance/irrcache.h"
#include "render/scenepart.h"

struct render;

typedef struct {
    real a;           /* Ward's accuracy, in (0, 1] */
    int m, n;         /* the gather's strata: M in theta, N in phi */
    real min_r, max_r; /* the clamp of R, in pixels at the record */
    int bounces;      /* diffuse vertices of a gather path lit directly */
    bool gradients;   /* interpolate with app. E's gradients */
    bool clamp;       /* neighbour clamping (Krivanek et al. 2006) */
} irr_settings_t;

/* a 0.15, M 8, N 32, R in [1, 20] pixels, 1 bounce, gradients and
 * neighbour clamping on. Can't fail. */
void irr_settings_default(irr_settings_t *s);

/* The scene's settings (the defaults when it has no `irradiance` line). */
void irr_settings_of(const scene_t *s, irr_settings_t *out);

/* The cache the method's pre-pass fills for render r, with `threads`
 * threads (0: all cores); the same records in the same order for any
 * thread count. c is initialised here (irrcache_free it). Fails with
 * SVET_ERR_NOMEM. */
svet_status irr_fill(irrcache_t *c, const struct render *r, int threads,
                     svet_error *err);

/* The cache of the method's state after prepare (for ch. 9's program and
 * the tests). */
const irrcache_t *irr_state_cache(const void *state);

/* The indirect irradiance at the first diffuse hit of the ray through the
 * centre of pixel (x, y) as the cache gives it (*found: a record covered
 * it), and by a fresh gather of the method's M x N with the stream
 * `stream` (either may be NULL). Returns false when the pixel sees no
 * diffuse surface. */
bool irr_pixel_irradiance(const void *state, const struct render *r, int x,
                          int y, uint64_t stream, RADIANCE *cached,
                          bool *found, RADIANCE *gathered);

extern const render_method_t irr_method;
extern const scene_part_t irr_part;

#endif
