/*
 * texpart.h - the textures of ch. 10 as a part of the scene file and the
 * renderer (render/scenepart.h): the statement `texture NAME KIND KEYS`,
 * a texture's name in place of a material's colour or number (rho of
 * every component, Phong's e, Ward's alphas) and the material component
 * `bump NAME strength S`, and the per-hit shading that reads them
 * (scene_t.shade). A scene without textures runs none of this code.
 * scenes/README.md lists the keys; chapters/ch10/README.md the sources.
 * Tests: tests/texture/test_texpart.c
 */
#ifndef SVET_TEXPART_H
#define SVET_TEXPART_H

#include "render/scenepart.h"

/* The part, for scene_features_t.parts (render/allparts.c). */
extern const scene_part_t texpart_part;


#endif
