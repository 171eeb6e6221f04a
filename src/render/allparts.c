/*
 * allparts.c - the list of every optional part (see allparts.h): the one
 * place that names them, so that linking this file links them all.
 * Tests: tests/render/test_allparts.c
 */
#include "render/allparts.h"

#include "accel/accel.h"
#include "accel/grid.h"
#include "mesh/objmesh.h"

static const scene_features_t all = {
    .accels = grid_accels, /* ch. 7: the uniform and hierarchical grids */
    .mesh = objmesh_load,  /* ch. 7: OBJ files for the `mesh` statement */
};

const scene_features_t *scene_features_all(void)
{
    return &all;
}
