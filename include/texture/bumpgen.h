/*
 * bumpgen.h - app. G: generated bump textures, heights h(u, v) in [0, 1]
 * over a surface's texture coordinates with their partial derivatives,
 * for the bump mapping of ch. 10 (Blinn, "Simulation of Wrinkled
 * Surfaces", SIGGRAPH 1978): waves, ripples, bricks, orange peel and
 * dents. Each can be used procedurally or written to an image.
 * Tests: tests/texture/test_bumpgen.c
 */
#ifndef SVET_BUMPGEN_H
#define SVET_BUMPGEN_H

#include "core/error.h"
#include "core/real.h"

typedef enum {
    BUMPGEN_WAVES,       /* parallel sine waves across the direction angle */
    BUMPGEN_RIPPLES,     /* concentric waves about a centre, dying out */
    BUMPGEN_BRICKS,      /* a running bond of bricks in sunken mortar */
    BUMPGEN_ORANGE_PEEL, /* fine round bumps: two octaves of noise */
    BUMPGEN_DENTS        /* scattered smooth pits: noise thresholded */
} bumpgen_kind_t;

typedef struct {
    bumpgen_kind_t kind;
    real frequency;  /* waves and ripples per unit of u; noise's scale */
    real angle;      /* waves: the direction of travel, radians from u */
    real cu, cv;     /* ripples: the centre */
    real damping;    /* ripples: the amplitude falls as exp(-damping r) */
    real brick_w, brick_h; /* bricks: a brick's size in u and v */
    real mortar;     /* bricks: the mortar's width (the joint) */
} bumpgen_t;

/* A pattern of the kind with the defaults chapters/ch10 shows: frequency
 * 8, angle 0, centre (0.5, 0.5), damping 2, bricks 0.25 x 0.1 with
 * mortar 0.01. */
bumpgen_t bumpgen_default(bumpgen_kind_t kind);

/* The height at (u, v) in [0, 1], and dh/du, dh/dv in du, dv (either may
 * be NULL), exact where h is smooth. Can't fail. */
real bumpgen_height(const bumpgen_t *b, real u, real v, real *du, real *dv);

/* The height as an image of width x height floats, texel (x, y) sampled
 * at its centre ((x + 0.5) / width, (y + 0.5) / height), row by row.
 * Fails with SVET_ERR_RANGE on a size outside 1..65536, SVET_ERR_NOMEM;
 * *out is then NULL. The caller frees *out. */
svet_status bumpgen_image(const bumpgen_t *b, int width, int height,
                          float **out, svet_error *err);

#endif
