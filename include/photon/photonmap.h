/*
 * photonmap.h - the photon map of ch. 8 (Jensen, "Global Illumination
 * using Photon Maps", EGWR 1996; Jensen, "Realistic Image Synthesis Using
 * Photon Mapping", 2001): photons stored where they land, balanced into a
 * left-balanced kd-tree kept as a heap without pointers (Jensen 2001,
 * app. B), the k nearest photons within a radius by a max-heap, and the
 * density estimate of the irradiance with the cone and Gaussian filters
 * (Jensen 2001, sec. 7.2), and the irradiance precomputed at a subset of
 * the photons (Christensen 1999).
 * Tests: tests/photon/test_photonmap.c; benchmark: bench/bench_photon.c
 */
#ifndef SVET_PHOTONMAP_H
#define SVET_PHOTONMAP_H

#include <stddef.h>
#include <stdint.h>

#include "core/error.h"
#include "core/vec.h"
#include "materials/radiance.h"

/* One photon, 28 bytes: the position and the power as floats whatever the
 * build's real (a map holds millions; float's 24 bits resolve a position
 * to 1e-7 of the scene, far below any search radius, and keep the power
 * unquantised so that sums of equal powers stay exact, unlike Jensen's
 * 4-byte RGBE), the incident direction in Jensen's two bytes (theta and
 * phi in 256 steps each, 0.7 degrees), and the kd-tree's split axis. */
typedef struct {
    float pos[3];        /* where the photon landed */
    float power[3];      /* its flux, watts per channel */
    uint8_t theta, phi;  /* the direction it travelled, quantised */
    uint8_t axis;        /* the kd-tree's split axis at this node: 0, 1, 2 */
    uint8_t flags;       /* free for the maps' own marks (e.g. caustic) */
} photon_t;

/* A map: photons added one by one, then balanced once; lookups only after. */
typedef struct {
    photon_t *ph;     /* stored[0 .. n - 1]; after balancing the heap
                         ph[1 .. n] (1-based: the children of node i are
                         2i and 2i + 1) and ph[0] unused */
    size_t n, cap;
    bool balanced;
} photonmap_t;

/* The largest map: 2^31 - 1 photons (the heap's indices are int32 in the
 * queries' heaps), and no more than the machine's memory. */
#define PHOTONMAP_MAX_PHOTONS ((size_t)INT32_MAX - 1)

/* Whether a map of `count` photons can be made: SVET_OK, or the failure
 * photonmap_init gives before it allocates (SVET_ERR_RANGE for 0 or above
 * PHOTONMAP_MAX_PHOTONS, SVET_ERR_NOMEM beyond the physical memory), with
 * the bytes it would need in the message. Allocates nothing. */
svet_status photonmap_check_count(size_t count, svet_error *err);

/* An empty map with room for `count` photons, allocated at once. Fails
 * before allocating, with the bytes it would need in the message, when
 * count is 0 or above PHOTONMAP_MAX_PHOTONS (SVET_ERR_RANGE) or the map
 * would not fit in the machine's physical memory (SVET_ERR_NOMEM). */
svet_status photonmap_init(photonmap_t *m, size_t count, svet_error *err);

void photonmap_free(photonmap_t *m);

/* The bytes a map of count photons takes, the balancing's scratch
 * included. Can't fail. */
size_t photonmap_bytes(size_t count);

/* Store a photon at pos, with power and direction dir (unit, the way the
 * photon travelled). Returns false, storing nothing, when the map is full
 * or balanced, or pos or power is not finite. */
bool photonmap_store(photonmap_t *m, const VECTOR3 pos, RADIANCE power,
                     const VECTOR3 dir, uint8_t flags);

/* The direction a photon's two bytes stand for, a unit vector. */
void photonmap_direction(const photon_t *p, VECTOR3 dir);

/* Balance the map into the left-balanced kd-tree (Jensen 2001, app. B):
 * each node splits its subset at the median of the axis along which the
 * subset's bounding box is widest, the median chosen so that the tree is
 * complete and filled from the left, so the heap needs no pointers. Uses
 * the OpenMP threads for the upper levels; the tree is the same for any
 * thread count. Fails with SVET_ERR_NOMEM. */
svet_status photonmap_balance(photonmap_t *m, svet_error *err);

/* The k nearest photons to x within distance rmax (a photon at exactly
 * rmax counts), nearest first; ties in distance go to the lower heap
 * index. found[i] is a heap index into m->ph, d2[i] its squared
 * distance; both arrays hold k. Returns how many were found (at most k,
 * fewer where the map or the radius holds fewer). Needs a balanced map.
 * Can't fail. */
int photonmap_nearest(const photonmap_t *m, const VECTOR3 x, int k,
                      real rmax, int32_t *found, real *d2);

typedef enum {
    PHOTONMAP_FILTER_NONE,     /* every photon weighs 1 */
    PHOTONMAP_FILTER_CONE,     /* w = 1 - d / (k_cone r), Jensen 2001 eq. 7.6 */
    PHOTONMAP_FILTER_GAUSSIAN  /* Pavicic 1990's Gaussian, Jensen 2001 eq. 7.7 */
} photonmap_filter_t;

typedef struct {
    int k;                      /* photons in the estimate, >= 1 */
    real rmax;                  /* the largest search radius, > 0 */
    photonmap_filter_t filter;
    real cone_k;                /* the cone filter's k >= 1, e.g. 1.1 */
    /* Jensen 2001, sec. 7.2: count only photons within disc * r of the
     * surface's plane (those from another surface, a wall behind a thin
     * one or a corner, lie off it); 0 keeps every photon */
    real disc;
} photonmap_query_t;

/* The weight a photon at squared distance d2 gets in an estimate of
 * radius^2 r2 > 0 under q's filter (Jensen 2001, eqs. 7.6, 7.7), and the
 * area the weighted sum is divided by: pi r2 times the filter's mean
 * weight over the disc, so that a uniform density comes out unscaled.
 * These functions can't fail. */
real photonmap_filter_weight(const photonmap_query_t *q, real d2, real r2);
real photonmap_filter_area(const photonmap_query_t *q, real r2);

/* The irradiance at x on a surface of normal n (unit) from the map, by
 * the density estimate E = sum w_p dPhi_p / (pi r^2) over the k nearest
 * photons within rmax, r the distance of the k-th of them, or rmax where
 * fewer than k lie within it, as in Jensen 2001's code (app. B); of those
 * only photons that arrived from n's side (dir . n < 0) add their power
 * (Jensen 1996, eq. 9; the filters' normalisations of Jensen 2001, sec.
 * 7.2). No photon found, or k photons all at x, give 0. Can't fail. */
RADIANCE photonmap_irradiance(const photonmap_t *m, const VECTOR3 x,
                              const VECTOR3 n, const photonmap_query_t *q);

/* Christensen 1999 ("Faster Photon Map Global Illumination", JGT 4(3)):
 * the irradiance precomputed at n points of the map's surfaces (a subset
 * of the photons' positions, pos[i] with the unit normal nrm[i] of the
 * side the photons arrived from), each by photonmap_irradiance(m, pos[i],
 * nrm[i], q), into out: a balanced map whose photon i holds the point,
 * its irradiance as the power and its normal as the direction. Parallel
 * over the points (`threads`, 0: all), each result stored by its index,
 * so out is the same for any thread count. n = 0 gives an empty balanced
 * map. Fails with SVET_ERR_NOMEM (or SVET_ERR_RANGE for an absurd n);
 * out is then empty. */
svet_status photonmap_precompute(const photonmap_t *m,
                                 const photonmap_query_t *q,
                                 const float (*pos)[3], const float (*nrm)[3],
                                 size_t n, int threads, photonmap_t *out,
                                 svet_error *err);

/* The lookup of Christensen 1999: the precomputed irradiance of the
 * nearest point of irr (photonmap_precompute) within rmax whose normal
 * lies within about 25 degrees of n (dot >= 0.9: a point on another
 * surface, or the other side of a thin one, does not answer). Returns
 * false, leaving *e alone, when no such point is among the nearest
 * PHOTONMAP_PRECOMPUTED_K. Can't fail. */
#define PHOTONMAP_PRECOMPUTED_K 8
bool photonmap_precomputed(const photonmap_t *irr, const VECTOR3 x,
                           const VECTOR3 n, real rmax, RADIANCE *e);

#endif
