/*
 * irrcache.h - the irradiance cache of ch. 9 (Ward, Rubinstein, Clear,
 * "A Ray Tracing Solution for Diffuse Interreflection", SIGGRAPH 1988;
 * Ward & Heckbert, "Irradiance Gradients", EGWR 1992): records of the
 * irradiance at points of diffuse surfaces with the harmonic mean distance
 * R of what their hemisphere saw and their rotational and translational
 * gradients (app. E), kept in an octree that grows as records arrive, and
 * interpolated where Ward's weight says a record is valid, with R clamped
 * to a range and to its neighbours' (Krivanek, Gautron, Bouatouch,
 * Pattanaik, "Improved Radiance Gradient Computation", SCCG 2005, and
 * Krivanek et al., "Making Radiance and Irradiance Caching Practical",
 * IEEE TVCG 2006: neighbour clamping).
 * Tests: tests/irradiance/test_irrcache.c
 */
#ifndef SVET_IRRCACHE_H
#define SVET_IRRCACHE_H

#include <stddef.h>

#include "core/error.h"
#include "core/vec.h"
#include "materials/radiance.h"

typedef struct {
    VECTOR3 p, n;        /* where, and the surface's unit normal */
    RADIANCE e;          /* irradiance */
    real r;              /* harmonic mean distance, after clamping */
    VECTOR3 grad_r[3];   /* rotational gradient of each channel's e */
    VECTOR3 grad_t[3];   /* translational gradient of each channel's e */
} irr_record_t;

typedef struct irr_node irr_node_t;

typedef struct {
    real a;              /* Ward's accuracy: records valid where w > 1 / a */
    real r_min, r_max;   /* the clamp of R, world units (> 0) */
    bool gradients;      /* interpolate with the gradients */
    bool clamp_neighbours; /* R <= R_j + |x - x_j| for each neighbour j */

    irr_record_t *rec;   /* records in the order they were added */
    size_t n, cap;
    irr_node_t *root;    /* the octree of record indices */
} irrcache_t;

/* An empty cache over the box [lo, hi] (the scene's bounds; records may
 * still fall outside: the octree grows). a in (0, 1], 0 < r_min <= r_max.
 * Fails with SVET_ERR_RANGE naming the bad value, SVET_ERR_NOMEM. */
svet_status irrcache_init(irrcache_t *c, real a, real r_min, real r_max,
                          const VECTOR3 lo, const VECTOR3 hi,
                          svet_error *err);

void irrcache_free(irrcache_t *c);

/* Ward's weight of record r at x with normal n:
 * 1 / (|x - x_i| / R_i + sqrt(1 - n . n_i)), infinite where x = x_i and
 * n = n_i. Can't fail. */
real irrcache_weight(const irr_record_t *r, const VECTOR3 x, const VECTOR3 n);

/* Add a record: R is clamped to [r_min, r_max], then, with
 * clamp_neighbours, to each existing record's R_j + |x - x_j| (and each
 * neighbour's R_j to R + |x - x_j|, for the records whose spheres of
 * influence it overlaps). The gradients are kept as given. Records are
 * kept in the order added, so a cache filled in a fixed order is the same
 * whatever the thread count of the pass that computed them. Fails with SVET_ERR_NOMEM; SVET_ERR_RANGE for a
 * record that is not finite. */
svet_status irrcache_add(irrcache_t *c, const irr_record_t *r,
                         svet_error *err);

/* The interpolated irradiance at x, normal n: sum w_i (E_i + (n_i x n) .
 * grad_r + (x - x_i) . grad_t) / sum w_i over the records with
 * w_i > 1 / a that do not lie in front of x (Ward 1988: d_i =
 * (x - x_i) . (n + n_i) / 2 >= -0.05 R_i), the gradient terms only with
 * `gradients`; each channel's grad_t scaled down where |grad_t| R_i > E_i
 * (Ward's Radiance, ambcomp.c: a gradient measured over a short R must not
 * extrapolate past E across a clamped, longer one). Returns the number
 * of records used (0: no valid record; *e is then black), summed in the
 * order they were added. Can't fail. */
int irrcache_lookup(const irrcache_t *c, const VECTOR3 x, const VECTOR3 n,
                    RADIANCE *e);

#endif
