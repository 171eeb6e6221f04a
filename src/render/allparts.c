/*
 * allparts.c - the list of every optional part (see allparts.h): the one
 * place that names them, so that linking this file links them all.
 * Tests: tests/render/test_allparts.c
 */
#include "render/allparts.h"

#include "accel/accel.h"
#include "accel/batch.h"
#include "accel/grid.h"
#include "irradiance/irrpart.h"
#include "medium/medpart.h"
#include "medium/volphoton.h"
#include "mesh/objmesh.h"
#include "photon/photon.h"
#include "render/animation.h"
#include "render/scenepart.h"
#include "render/subsample.h"
#include "texture/texpart.h"

/* ch. 7: the batched brute force and the uniform and hierarchical grids,
 * in the order of their kinds */
static const accel_ops_t *const accels[] = { &batch_accel,
                                             &grid_uniform_accel,
                                             &grid_hierarchical_accel, NULL };

/* Part II: photon maps (ch. 8), the irradiance cache (ch. 9), textures
 * (ch. 10), media (ch. 11), each a scenepart.h scene_part_t; and the
 * animations of svet render (animation.h) */
static const scene_part_t *const parts[] = { &photon_part, &irr_part,
                                             &texpart_part,
                                             &medium_part,
                                             &volphoton_part,
                                             &animation_part, NULL };

static const scene_features_t all = {
    .accel = &accel_layer, /* ch. 7: the acceleration layer */
    .accels = accels,
    .mesh = objmesh_load,  /* ch. 7: OBJ files for the `mesh` statement */
    .parts = parts,
    .subsample = &subsample_ops, /* app. F */
};

const scene_features_t *scene_features_all(void)
{
    return &all;
}
