/*
 * texture.h - a texture of ch. 10 as the renderer uses it: one of image
 * (a mip map, texture/mipmap.h), checker (2D over the surface's (s, t) or
 * 3D in space), the solids of texture/solid.h (noise, fractal sum,
 * turbulence, marble, wood, granite) and app. G's generated bumps
 * (texture/bumpgen.h); its colour at a surface point, its height and the
 * height's partial derivatives for bump mapping (Blinn, "Simulation of
 * Wrinkled Surfaces", SIGGRAPH 1978), and the bumped shading frame.
 * Tests: tests/texture/test_texture.c
 */
#ifndef SVET_TEXTURE_H
#define SVET_TEXTURE_H

#include <stdbool.h>

#include "materials/cobject.h"
#include "texture/bumpgen.h"
#include "texture/mipmap.h"
#include "texture/solid.h"

typedef enum {
    TEXTURE_IMAGE,   /* an image over (s, t): the mip map */
    TEXTURE_CHECKER, /* squares of side 1 / scale over (s, t), a then b */
    TEXTURE_SOLID,   /* a solid texture of point p (solid.h; its checker
                        is the 3D checker) */
    TEXTURE_BUMPGEN  /* an app. G pattern over (s, t): a at h = 0, b at 1 */
} texture_kind_t;

typedef struct {
    texture_kind_t kind;
    RADIANCE a, b;          /* checker, bumpgen: the colours at 0 and 1 */
    real scale;             /* (s, t) are multiplied by it (2D kinds); the
                               solids carry their own in solid.scale */
    solid_texture_t solid;  /* TEXTURE_SOLID */
    bumpgen_t bump;         /* TEXTURE_BUMPGEN */
    mipmap_t mip;           /* TEXTURE_IMAGE: owned, texture_free frees it */
    mipmap_filter_t filter; /* TEXTURE_IMAGE */
} texture_t;

/* Where a texture is read: the surface point and its parameters. */
typedef struct {
    VECTOR3 p;          /* the point, in world space (solid textures) */
    real s, t;          /* PATHPOINT.st */
    VECTOR3 dpds, dpdt; /* PATHPOINT.dpds, dpdt */
    real width;         /* the footprint in (s, t) units (mip map level),
                           0: the finest */
} texture_point_t;

/* The point of a filled PATHPOINT, with footprint width. */
void texture_point_of(texture_point_t *q, const PATHPOINT *pp, real width);

/* The colour at q. Never NaN. Can't fail. */
RADIANCE texture_eval(const texture_t *t, const texture_point_t *q);

/* The height at q (an image's or a colour's first channel, a solid's or a
 * pattern's factor in [0, 1]) and its partial derivatives along s and t:
 * analytic for the solids (the gradient dotted with dP/ds, dP/dt) and the
 * app. G patterns, central differences one texel apart for an image (the
 * bilinear lookup is linear between texel centres, so they are exact for
 * a linear image), 0 for a checker. Can't fail. */
real texture_height(const texture_t *t, const texture_point_t *q,
                    real *dhds, real *dhdt);

/* Blinn's bump: the surface P + h N moved along its normal, whose
 * tangents to first order are dP/ds + dh/ds N and dP/dt + dh/dt N (the
 * term h dN/ds is dropped, as Blinn does for small h); the shading normal
 * becomes their unit cross product, turned to the side of the unbumped
 * pp->n, and the frame u, v, n and bout follow it. Where the bumped
 * normal would put the viewer (pp->out) on the other side than the
 * geometric normal does, the hit keeps its unbumped frame: a normal the
 * viewer sees from behind would shade black (see chapters/ch10/README.md
 * for why this fix rather than Schussler et al. 2017's microfacet one).
 * dhds = dhdt = 0 leaves pp untouched, bit for bit. Returns whether the
 * frame moved. Can't fail. */
bool texture_bump(PATHPOINT *pp, real dhds, real dhdt);

/* The texture's mean colour over its domain and its brightest value per
 * channel: for an image, the top of its mip map (the mean of the texels,
 * halved level by level) and its largest texel; for the others, which
 * blend a and b by a factor in [0, 1], (a + b) / 2 and max(a, b). An
 * emitter's radiance reads them (its power for choosing it among the
 * lights, the checks of its brightness). Can't fail. */
void texture_range(const texture_t *t, RADIANCE *mean, RADIANCE *top);

/* Free what t owns (an image's mip map). */
void texture_free(texture_t *t);

#endif
