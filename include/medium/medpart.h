/*
 * medpart.h - the participating media of ch. 11 in the scene file and the
 * renderer: the statement `medium NAME KIND KEYS`, the shape keys
 * `medium NAME`, `outside NAME` and `invisible` that make a closed shape
 * the boundary of a medium, the scene's medium filling the space outside
 * every boundary (`global` on a medium statement), and the rendering
 * method `render integrator volpath` (volumetric path tracing). The rules
 * of boundaries are pbrt-v3's medium interface (sec. 11.3.1): each
 * boundary names the medium on its inside and on its outside, and a ray
 * leaving a boundary surface is in the medium of the side it goes to; a
 * surface that is no boundary leaves the ray's medium as it is.
 * Tests: tests/medium/test_medpart.c
 */
#ifndef SVET_MEDPART_H
#define SVET_MEDPART_H

#include <stdbool.h>

#include "medium/medium.h"
#include "render/scenepart.h"

/* What a boundary object's inside and outside (cobject.h) point at: the
 * medium on that side (NULL: vacuum) and whether the boundary has a
 * surface at all (invisible: rays and shadow rays pass it straight on,
 * only changing medium). Objects that are no boundary have both NULL. */
struct medium {
    const medium_t *m;
    bool invisible;
};

/* The part: the `medium` statement, the shape keys, `volpath`. */
extern const scene_part_t medium_part;

/* The scene's global medium (the fog outside every boundary), or NULL:
 * vacuum. This function can't fail. */
const medium_t *medpart_global(const scene_t *s);

#endif
