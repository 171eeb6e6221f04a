/*
 * allparts.h - every optional part of svet in one list, for the programs
 * that offer them all: the svet command, ch. 7, the fuzzers and the tests.
 * A part is optional when a chapter program may leave it out ("model only
 * what a scene requires": ch. 5 links no grid and no OBJ reader); it
 * reaches the core through scene_features_t (scene.h), never by name.
 * Today: the acceleration layer of ch. 7 (accel.h) with the batched brute
 * force (batch.h) and the grids (grid.h), and the OBJ meshes (objmesh.h).
 * Part II adds its parts here and in allparts.c, one line each. (Not
 * "features.h": that name is glibc's, which <stdint.h> includes.)
 * Tests: tests/render/test_allparts.c
 */
#ifndef SVET_ALLPARTS_H
#define SVET_ALLPARTS_H

#include "render/scene.h"

/* Everything: the acceleration layer, the batched brute force and the
 * grids as its structures, and the OBJ mesh
 * loader. Static; never NULL. This function can't fail. */
const scene_features_t *scene_features_all(void);

#endif
