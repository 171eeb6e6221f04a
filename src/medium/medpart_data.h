/*
 * medpart_data.h - what the files of the media part (medpart.c, the
 * scene file; volpath.c, volsingle.c and volphoton.c, the renderers)
 * share and nothing else: the media a scene names, the records its
 * boundaries point at, and volpath.c's walk, shadow rays and light
 * sampling.
 * Tests: tests/medium/test_medpart.c
 */
#ifndef SVET_MEDPART_DATA_H
#define SVET_MEDPART_DATA_H

#include "medium/medpart.h"
#include "medium/volsingle.h"
#include "render/integrator.h"

/* A named medium; its grid (when it has one) is owned here. */
typedef struct {
    char name[SCENE_MAX_NAME + 1];
    medium_t m;
    volgrid_t grid;
    bool has_grid;
    /* `mix`: copies of its components (their grids stay with the media
       that read them), m.components points here */
    medium_t parts[MEDIUM_MAX_COMPONENTS];
} named_medium_t;

/* One side of the boundaries of one shape statement: the record objects
 * point at, and the medium it stands for (an index into media; -1:
 * vacuum; -2: the global medium, resolved by finish). */
typedef struct {
    struct medium rec;
    int index;
} side_t;

typedef struct {
    named_medium_t **media; /* each allocated alone: pointers stay put */
    int nmedia;
    side_t **sides;
    int nsides;
    int global;             /* index of the global medium, -1: none */
    real step;              /* `volsingle step`, 0: not given */
} medpart_data_t;

/* volsingle's step when the scene gives none, in scene units. */
#define MEDPART_DEFAULT_STEP REAL_C(0.05)

/* `render integrator volpath` (volpath.c) and `volsingle` (volsingle.c). */
extern const render_method_t volpath_method;
extern const render_method_t volsingle_method;

/* --- what volsingle.c and volphoton.c take from volpath.c ------------- */

/* The most invisible boundaries one segment may cross before the path
 * is given up (a ray caught between coincident surfaces). */
#define VOLPATH_MAX_CROSSINGS 256

svet_status volpath_prepare(void **out, const struct render *r, int threads,
                            svet_error *err);
void volpath_free(void *state);

/* The medium a ray leaving a surface of obj (normal ng) in direction w
 * is in: the side's for a boundary, else med, the one it was in. */
const medium_t *volpath_medium_after(const COBJECT *obj, const VECTOR3 ng,
                                     const VECTOR3 w, const medium_t *med);

/* Transmittance over t in [0, len] of ray r (unit dir) in med (NULL:
 * vacuum); len may be infinite only in a homogeneous medium. */
RADIANCE volpath_segment_tr(const medium_t *med, const ray_t *r,
                            const VECTOR3 dir, real len, pcg32_t *g);

/* The walk of both methods (render_method_t.li): distance sampling in
 * media for volpath, the march (volsingle_march) when s->step > 0. */
RADIANCE volpath_li(const void *state, const struct render *r,
                    const ray_t *camera, long sample, pcg32_t *g,
                    integrator_stats_t *st);

/* The PATHPOINT of a point of a medium at distance t along r (unit dir):
 * no surface, its frame around dir. */
void volpath_medium_point(PATHPOINT *pp, const ray_t *r, const VECTOR3 dir,
                          real t);

/* The point a light is sampled from: the ray's medium there, the surface
 * (NULL: a point of the medium) and the direction the ray travelled. */
typedef struct {
    const volpath_state_t *s;
    const medium_t *med;
    const COBJECT *obj;
    VECTOR3 dir;
    const phase_t *ph; /* the scattering component's phase; NULL: med's */
    bool mix;          /* med is a mix whose components' phases scatter
                          together, each weighted by its sigma_s at x
                          (volsingle): phase_toward gives
                          sum_i sigma_s_i(x) p_i per channel */
    VECTOR3 x;         /* the point, for mix */
} volpath_at_t;

/* integrator_shadow_fn with ctx a volpath_at_t: the shadow ray's
 * transmittance, through invisible boundaries (ratio tracking in grids,
 * Novak et al. 2014). */
RADIANCE volpath_shadow(const void *ctx, const integrator_t *it,
                        const PATHPOINT *pp, const ray_t *sr, real tmax,
                        const COBJECT *const skip[2],
                        const light_sample_t *ls, pcg32_t *g,
                        integrator_stats_t *st);

/* Next-event estimation (integrator_nee) at a surface of material m (wo
 * in pp's local frame) or, with m NULL, at a point of at->med scattering
 * by its phase function; shadow rays by volpath_shadow. */
RADIANCE volpath_direct(const volpath_at_t *at, const integrator_t *it,
                        const PATHPOINT *pp, const struct material *m,
                        const VECTOR3 wo, bool mis, pcg32_t *g,
                        integrator_stats_t *st);
#endif
