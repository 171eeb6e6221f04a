/*
 * volphoton.h - the volume photon map of ch. 11 (Jensen & Christensen,
 * "Efficient Simulation of Light Transport in Scenes with Participating
 * Media using Photon Maps", SIGGRAPH 1998; Jensen, "Realistic Image
 * Synthesis Using Photon Mapping", 2001, ch. 10): photons traced from the
 * lights through the media and stored where they scatter, the volume
 * radiance estimate over the k nearest of them in a sphere, and the
 * rendering method `render integrator volphoton` with its statement
 * `volphoton photons N k K max_radius R step H` (scenes/README.md).
 * Tests: tests/medium/test_volphoton.c
 */
#ifndef SVET_VOLPHOTON_H
#define SVET_VOLPHOTON_H

#include <stdint.h>

#include "core/error.h"
#include "medium/medium.h"
#include "photon/photonmap.h"
#include "render/scenepart.h"

struct render;

/* The `volphoton` statement's settings. */
typedef struct {
    uint64_t photons; /* photons emitted; both maps come from them */
    int k;            /* photons in a volume estimate */
    real max_radius;  /* the volume estimate's largest radius */
    real step;        /* the camera rays' march step in a medium */
} volphoton_settings_t;

/* The defaults: 200 000 photons, k = 50, max_radius 0.2, step 0.05. */
void volphoton_settings_default(volphoton_settings_t *s);

/* The scene's settings (the defaults when it has no volphoton line). */
void volphoton_settings_of(const scene_t *s, volphoton_settings_t *out);

/* The part: the statement and the method. allparts.c lists it. */
extern const scene_part_t volphoton_part;
extern const render_method_t volphoton_method;

/* Trace `count` photons from the lights of r (photon_emit) through its
 * media, photon i from rng_for_sample(seed ^ VOLPHOTON_SEED_SALT, 0, i),
 * into two balanced maps: vol, the photons where they scatter in a
 * medium, and surf, where they land on a surface with a non-delta part;
 * in both only photons that have scattered or bounced before (light
 * straight from a light is the light sampling's). In a medium the
 * distance to the next event is sampled by medium_sample (exact in
 * homogeneous media, delta tracking in grids); at an event Russian
 * roulette by the weight sigma_s Tr / pdf (the albedo, in a grey medium)
 * keeps the photon with its power or ends it (Jensen 2001, sec. 10.3), a
 * kept photon is stored with its power and the direction it travelled,
 * then scattered by the phase function (of the component that scatters,
 * in a sum: medium_scatterer). At surfaces the photon bounces as
 * photon_trace's do. The media are the scene's (medpart.h): a photon
 * leaves its light in the global medium. The scene's max_depth bounds
 * the events. Where a medium inside a boundary emits, `count` photons
 * more leave the media: photon i from rng_for_sample(seed ^
 * VOLPHOTON_SEED_SALT, 1, i) at a point x uniform in the box around the
 * emitting media's boundaries, kept where x's medium emits, in a
 * direction uniform over the sphere, with power 4 pi sigma_a(x) L_e V /
 * count (V the box's volume: the source term sigma_a L_e integrated over
 * volume and directions, pbrt-v4 sec. 11.1.2), and stored from its first
 * event on, which no light sampling covers (the march adds the emission
 * seen directly); the global medium's emission, which fills all space,
 * sends none. The maps are the same for any `threads` (0: all). Fails
 * with SVET_ERR_NOMEM; both maps are then empty. */
#define VOLPHOTON_SEED_SALT UINT64_C(0x766f6c70686f746e)
svet_status volphoton_trace(const struct render *r, uint64_t count,
                            int threads, photonmap_t *vol, photonmap_t *surf,
                            svet_error *err);

/* The volume radiance estimate (Jensen & Christensen 1998, sec. 3.2;
 * Jensen 2001, sec. 10.4): the radiance scattered at x in med toward
 * -dir (dir: the camera ray's direction) per unit length,
 *   sigma_s(x) L_i(x, -dir) = sum_p p(w_p, -dir) dPhi_p / ((4/3) pi r^3),
 * over the k nearest photons of vol within rmax, r the distance of the
 * k-th, or rmax where fewer lie within it; p the medium's phase function
 * (in a sum, the components' weighted by their sigma_s at x) of the
 * cosine between the photon's direction and -dir. Jensen writes the
 * estimate of L_i, this sum divided by sigma_s(x); the march multiplies
 * by sigma_s again, so this is the product. k <= PHOTON_MAX_K. Can't
 * fail. */
RADIANCE volphoton_radiance(const photonmap_t *vol, const medium_t *med,
                            const VECTOR3 x, const VECTOR3 dir, int k,
                            real rmax);

#endif
