/*
 * scenefile.h - reading a scene file (the format of scenes/README.md) into a
 * scene_t, and command-line overrides of its settings ("spp=64"). Every
 * error names file:line:column and what was expected there. What a scene
 * may ask for beyond the core (the `mesh` statement, `accel grid`) is
 * what the program offers through scene_features_t (scene.h): the
 * *_with() readers take it, the plain ones offer nothing (ch. 5).
 * Tests: tests/render/test_scenefile.c; fuzzing: fuzz/fuzz_scene.c
 */
#ifndef SVET_SCENEFILE_H
#define SVET_SCENEFILE_H

#include <stddef.h>
#include "core/error.h"
#include "render/scene.h"

/* The largest scene file read (bytes); larger ones are refused. */
#define SCENEFILE_MAX_BYTES (64L << 20)

/* Read the scene file at path into s, which is initialised here (any
 * earlier content is not freed: pass a scene_init'ed or freed scene), with
 * the optional parts in features (NULL: none; borrowed, and kept in
 * s->features for the renderer and scenefile_override(): it must outlive
 * s). Mesh files named in it are found relative to the scene file's
 * directory and read by features->mesh. On failure s is freed (as
 * scene_free leaves it) and err holds "path:line:col: what was expected";
 * the status is SVET_ERR_IO (cannot read the scene or a mesh file),
 * SVET_ERR_PARSE (malformed text, unknown keyword or material),
 * SVET_ERR_RANGE (a value out of its domain: NaN, negative size, absurd
 * resolution), SVET_ERR_UNSUPPORTED (a keyword of a later chapter, or a
 * part the program does not offer: "'mesh': this program was built
 * without the OBJ meshes of ch. 7 ...", "'accel grid': this program was
 * built without the grids of ch. 7 (grid.c)") or SVET_ERR_NOMEM. A file
 * without statements is SVET_ERR_PARSE; a light brighter than the images
 * hold (scenes/README.md, "Errors and limits") is SVET_ERR_RANGE. On
 * success s->warnings holds what was valid but likely not meant (OBJ
 * statements skipped, nothing emits light, sizes beyond what real
 * resolves: scenes/README.md, "Warnings"), for the caller to show. */
svet_status scenefile_read_with(scene_t *s, const char *path,
                                const scene_features_t *features,
                                svet_error *err);

/* scenefile_read_with() offering nothing beyond the core: brute force
 * only, no `mesh` statement. */
svet_status scenefile_read(scene_t *s, const char *path, svet_error *err);

/* As scenefile_read_with, from the len bytes at text (need not end in
 * NUL; may contain NUL bytes, which are an error). name is what messages
 * call the text (e.g. "<string>"); dir is the directory for relative mesh
 * paths (NULL: the current directory). */
svet_status scenefile_parse_with(scene_t *s, const char *text, size_t len,
                                 const char *name, const char *dir,
                                 const scene_features_t *features,
                                 svet_error *err);

/* scenefile_parse_with() offering nothing beyond the core. */
svet_status scenefile_parse(scene_t *s, const char *text, size_t len,
                            const char *name, const char *dir,
                            svet_error *err);

/* Apply one command-line override "key=value" to a parsed scene, with the
 * validation the file gets. Keys: spp, maxdepth, seed, integrator,
 * ao_distance, roulette, roulette_depth, threads, time_limit, passes,
 * checkpoint, accel, packets, width, height, resolution (WxH), fov, fov_axis,
 * exr, png, tonemap, exposure, key, white, bias, curve, gamma; and
 * STATEMENT.KEY for the settings statements of the parts the scene's
 * features offer (scenepart.h: photonmap.k=50 is the line
 * "photonmap k 50"). Returns
 * SVET_OK, or SVET_ERR_PARSE / SVET_ERR_RANGE with "override 'spp=x': ..."
 * in err (SVET_ERR_UNSUPPORTED for an accel that s->features does not
 * offer); on failure s is unchanged. */
svet_status scenefile_override(scene_t *s, const char *setting,
                               svet_error *err);

#endif
