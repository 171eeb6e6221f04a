/*
 * scenecheck.h - what the suites of the scene file's parts share (ch. 8-11:
 * test_medpart, test_volsingle, test_texpart, test_photon, test_irrpart,
 * test_animation): a scene given as text, read with every optional part
 * as the svet command reads it (allparts.h), accepted or refused with the
 * file:line:col of its message, and rendered at its own sample count.
 * The text is read as the file "t.scn", so messages start "t.scn:LINE:".
 */
#ifndef SVET_SCENECHECK_H
#define SVET_SCENECHECK_H

#include "core/error.h"
#include "io/image.h"
#include "render/scene.h"

/* Parse text (a C string) as the file "t.scn", files named relative to
 * the working directory. */
svet_status scenecheck_parse(scene_t *s, const char *text, svet_error *e);

/* Parse text that must be accepted; a failure fails the calling test with
 * the message. The caller frees *s. */
void scenecheck_parse_ok(scene_t *s, const char *text);

/* Parse text that must be refused with a message that starts with `where`
 * ("t.scn:3:" or "t.scn:3:22:") and holds `what`. */
void scenecheck_refused(const char *text, const char *where,
                        const char *what);

/* Render text at its own spp (`render spp N`) with `threads` threads into
 * img (the caller frees it); any failure fails the calling test. */
void scenecheck_render(const char *text, int threads, image_t *img);

#endif
