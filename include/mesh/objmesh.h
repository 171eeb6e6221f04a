/*
 * objmesh.h - the scene file's `mesh` statement's loader for Wavefront OBJ
 * files (ch. 7): the file read by obj.h, moved by the statement's
 * transform, split by usemtl into one mesh (mesh.h) per material. A
 * program offers it to the scene file through scene_features_t.mesh
 * (scene.h; allparts.h gathers it with the grids); without it a scene's
 * `mesh` line is refused, and the program links neither obj.c nor this.
 * Tests: tests/mesh/test_objmesh.c (and tests/render/test_scenefile.c's mesh scenes)
 */
#ifndef SVET_OBJMESH_H
#define SVET_OBJMESH_H

#include "render/scene.h"

/* scene.h's scene_mesh_loader for OBJ files: path read with obj_read()'s
 * default limits, moved by x (NULL: as in the file; positions by x,
 * normals by its inverse transpose, and a mirroring x reverses each
 * triangle's winding so that ng keeps pointing out of a closed mesh),
 * then one part per usemtl name that has faces (scene.h). obj_read()'s
 * warnings (statements skipped, "path:line:col: warning: ...") are added
 * to *warnings, counted in full (NULL: dropped). Fails as obj_read() does
 * (its message names path:line:col), or SVET_ERR_NOMEM ("path: out of
 * memory"). */
svet_status objmesh_load(const char *path, const xform_t *x,
                         scene_mesh_part_t **parts, int *nparts,
                         scene_warnings_t *warnings, svet_error *err);

#endif
