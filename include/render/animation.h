/*
 * animation.h - animations: a scene of N frames whose camera moves between
 * keyframes (`animation frames N`, `key FRAME camera KEYS`; grammar in
 * scenes/README.md, "Animations"), a part of the scene file (scenepart.h)
 * that svet render offers. Frame k is the scene with the camera of frame k
 * and the seed of frame k, nothing else: it renders to the same bits alone
 * or in a sequence, on any thread count, and splits by samples or pixels
 * and merges (svet merge) like any scene. A later part (ch. 13's smoke)
 * reads the frame a scene was set to with animation_frame().
 * Tests: tests/render/test_animation.c, tests/cmd/test_frames.sh
 */
#ifndef SVET_ANIMATION_H
#define SVET_ANIMATION_H

#include <stdint.h>

#include "core/error.h"
#include "render/scene.h"
#include "render/scenepart.h"

/* The most frames an animation may have. */
#define ANIMATION_MAX_FRAMES 1000000

/* The part: the `animation` and `key` statements. */
extern const scene_part_t animation_part;

/* The number of frames of s (its `animation frames N`), or 0 when s has no
 * animation statement. This function can't fail. */
int animation_frames(const scene_t *s);

/* The frame s was set to with animation_set_frame, or -1. This function
 * can't fail. */
int animation_frame(const scene_t *s);

/* The seed frame k renders with, in a scene of seed `seed`:
 *   seed_k = seed ^ splitmix64(k)   (rng.h's SplitMix64),
 * so that each frame's noise differs from the next one's, and frame k's
 * numbers are the same whichever frames are rendered with it. This
 * function can't fail. */
uint64_t animation_frame_seed(uint64_t seed, int k);

/* Make s frame k of its animation: the camera's position, target, up and
 * fov are those of frame k (each interpolated linearly in the frame
 * number between the two keys around k that give it, held before the
 * first and after the last, the `camera` statement's where no key gives
 * it) and its seed animation_frame_seed(seed, k). The base camera and
 * seed are those s has at the first call, so later calls choose another
 * frame of the same scene. Fails with SVET_ERR_RANGE when s has no
 * animation or k is not one of its frames 0 .. N-1. */
svet_status animation_set_frame(scene_t *s, int k, svet_error *err);

#endif
