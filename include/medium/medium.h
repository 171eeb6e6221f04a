/*
 * medium.h - the participating media of ch. 11: absorption sigma_a,
 * scattering sigma_s and extinction sigma_t = sigma_a + sigma_s per unit
 * length (RGB, so that extinction may differ per channel), emission, and
 * a phase function (medium/phase.h), scaled in space by a density: 1
 * everywhere (homogeneous), a grid (medium/volgrid.h, gridded media and
 * ch. 13's smoke), or a function (ch. 12's exponential atmosphere). What a
 * renderer asks of a medium: the transmittance exp(-integral sigma_t)
 * along a segment, exact where the medium is homogeneous and by ratio
 * tracking otherwise (Novak, Selle, Jarosz, "Residual Ratio Tracking",
 * SIGGRAPH 2014), and a distance to the next scattering event, exact in a
 * homogeneous medium (pbrt-v3 sec. 15.2.1) and by delta tracking
 * (Woodcock et al. 1965) under a majorant otherwise; and the radiance
 * the medium emits along a segment (pbrt-v4 sec. 11.1.2).
 * Tests: tests/medium/test_medium.c
 */
#ifndef SVET_MEDIUM_H
#define SVET_MEDIUM_H

#include "core/error.h"
#include "core/rng.h"
#include "materials/radiance.h"
#include "medium/phase.h"
#include "medium/volgrid.h"

/* A density given as a function, with a bound no value exceeds. */
typedef real (*medium_density_fn)(const void *ctx, const VECTOR3 p);

/* A medium made of components (the design of ch. 12's air of molecules
 * and aerosols and ch. 13's smoke in air): a medium with ncomponents > 0
 * is the sum of components[0 .. ncomponents - 1], each a one-component
 * medium with its own sigma_a, sigma_s, density (1, a grid, or a function
 * with its bound) and phase; its own coefficients, density and phase are
 * then unused. At a point, sigma_t and sigma_s are the sums of the
 * components' (each times its density); transmittance and delta tracking
 * run under the sum of the components' majorants (exact when every
 * component is homogeneous); a scattering event belongs to component i
 * with probability proportional to its sigma_s at the point (the mean of
 * its channels), whose phase then scatters (medium_scatterer). With the
 * same phase everywhere, two components are the one medium of their
 * summed coefficients. A component has no components of its own. */
#define MEDIUM_MAX_COMPONENTS 8

typedef struct medium_s medium_t;

struct medium_s {
    RADIANCE sigma_a, sigma_s; /* per unit length at density 1 */
    RADIANCE emission;         /* L_e, the radiance the medium emits:
                                  the source term is sigma_a(x) L_e
                                  (pbrt-v4 sec. 11.1.2, eq. 11.3), so a
                                  density scales it as it scales sigma_a */
    phase_t phase;
    /* the density: exactly one of these, or none for 1 everywhere */
    const volgrid_t *grid;     /* channel 0 of a grid */
    medium_density_fn fn;
    const void *fn_ctx;
    real fn_max;               /* fn's bound, >= every value of fn */
    /* 0: the medium is the one component above; else the sum of these
       (see MEDIUM_MAX_COMPONENTS) */
    int ncomponents;
    const medium_t *components;
};

/* A homogeneous medium of the given coefficients and isotropic phase. */
medium_t medium_homogeneous(RADIANCE sigma_a, RADIANCE sigma_s);

/* The sum of the n one-component media c[0 .. n-1] (not copied: they must
 * outlive the result). Check it with medium_check. Can't fail. */
medium_t medium_mix(const medium_t *c, int n);

/* Check the coefficients: finite and >= 0, emission finite and >= 0, HG's
 * g in (-PHASE_MAX_G, PHASE_MAX_G), a density grid's values >= 0 and a
 * function's bound finite and > 0. The message says which value is wrong;
 * the caller adds the file and line. Returns SVET_ERR_RANGE.
 * A sum is checked component by component, and refused with more than
 * MEDIUM_MAX_COMPONENTS or with a component that has components. */
svet_status medium_check(const medium_t *m, svet_error *err);

/* true when the density is 1 everywhere (of every component). */
bool medium_is_homogeneous(const medium_t *m);

/* The density at p: 1, the grid's trilinear value, or fn's (of the
 * medium's own fields: a sum's components each have their own). */
real medium_density(const medium_t *m, const VECTOR3 p);

/* The largest density anywhere: 1, the grid's largest value, fn_max. */
real medium_density_max(const medium_t *m);

/* sigma_t = sigma_a + sigma_s at density 1 (summed over components). */
RADIANCE medium_sigma_t(const medium_t *m);

/* sigma_s at density 1 (summed over components). */
RADIANCE medium_sigma_s(const medium_t *m);

/* sigma_t and sigma_s at the point p: each component's at density 1
 * times its density at p, summed. Can't fail. */
void medium_coeffs_at(const medium_t *m, const VECTOR3 p, RADIANCE *sigma_t,
                      RADIANCE *sigma_s);

/* The component that scatters at p (m itself when it has none), picked
 * from u in [0, 1) with probability P_i proportional to the mean of the
 * channels of its sigma_s at p; *weight (may be NULL) is sigma_s_i /
 * (P_i sigma_s) per channel, which a path's throughput is multiplied by
 * (1 when the components' sigma_s are proportional). Can't fail. */
const medium_t *medium_scatterer(const medium_t *m, const VECTOR3 p, real u,
                                 RADIANCE *weight);

/* Transmittance over a distance d of a homogeneous medium: Beer-Lambert,
 * exp(-sigma_t d) per channel. Can't fail. */
RADIANCE medium_tr_homogeneous(const medium_t *m, real d);

/* Transmittance along o + t dir (dir unit) for t in [0, tmax]: exact for
 * a homogeneous medium; otherwise ratio tracking, an unbiased estimate
 * that draws from g (steps under the majorant medium_density_max times
 * the largest channel of sigma_t). Can't fail. */
RADIANCE medium_tr(const medium_t *m, const VECTOR3 o, const VECTOR3 dir,
                   real tmax, pcg32_t *g);

/* Where light travelling from o along dir first interacts within tmax:
 * returns true with *t the distance of a scattering event, false when it
 * passes the segment. *weight is what the path's throughput is multiplied
 * by: sigma_s Tr / pdf at an event, Tr / P(pass) when it passes, per
 * channel. Homogeneous media sample the distance exactly in one channel
 * picked uniformly, the pdf being the channels' average (pbrt-v3 sec.
 * 15.2.1); others by delta tracking on the largest channel's majorant
 * with the per-channel ratio as weight. Draws from g. Can't fail. */
bool medium_sample(const medium_t *m, const VECTOR3 o, const VECTOR3 dir,
                   real tmax, pcg32_t *g, real *t, RADIANCE *weight);

/* true when some component emits: sigma_a > 0 and L_e > 0 in some
 * channel (a medium with L_e but no absorption emits nothing). */
bool medium_emits(const medium_t *m);

/* The source term of emission at p, sum over components of sigma_a(p)
 * L_e (pbrt-v4 sec. 11.1.2). Can't fail. */
RADIANCE medium_source_at(const medium_t *m, const VECTOR3 p);

/* The emitted radiance reaching o from o + t dir, t in [0, tmax]:
 *   int_0^tmax Tr(0, t) sigma_a(x_t) L_e dt   (pbrt-v4 eq. 11.3 with
 * eq. 11.5 integrated along the ray), per channel. Exact when the medium
 * is homogeneous, S (1 - exp(-sigma_t tmax)) / sigma_t with S the source
 * term (tmax may be VOLPATH_FAR-large), drawing nothing; otherwise
 * ratio tracking with emission: tentative collisions at the majorant's
 * rate mu, each adding the estimate of Tr so far times S(x) / mu (an
 * unbiased estimate of the integral, by Campbell's theorem for the
 * Poisson process of collisions), which draws from g. Can't fail. */
RADIANCE medium_emitted(const medium_t *m, const VECTOR3 o,
                        const VECTOR3 dir, real tmax, pcg32_t *g);

#endif
