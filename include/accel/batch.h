/*
 * batch.h - the batched brute force: brute force over a scene of analytic
 * primitives (no mesh triangles) that makes the culling tests of every
 * primitive itself instead of behind a call per primitive: the
 * parallelograms' early rejections sixty-four at a time
 * (parallelogram_batch_cull()), the transformed objects' culling spheres
 * side by side. An optional structure of kind ACCEL_BRUTE (accel.h),
 * offered by allparts.h's list; the answers are primset_test()'s over
 * every primitive, bit for bit, so it is a speed layer of brute force and
 * no chapter program needs it.
 * Tests: tests/accel/test_batch.c (and tests/accel/test_accel.c)
 */
#ifndef SVET_BATCH_H
#define SVET_BATCH_H

#include <stdint.h>
#include "accel/accel.h"

/* The structure's table: build fails with SVET_ERR_UNSUPPORTED on a
 * primset that has mesh triangles (accel_build() then tests by
 * primset_test(), as without it) and SVET_ERR_NOMEM; it answers whole
 * queries (accel_ops_t.tracer_intersect, .tracer_occluded). */
extern const accel_ops_t batch_accel;

/* Bit k set when ray r passes the k-th culling sphere of the batched
 * brute force s (built by batch_accel.build: those of the primset's
 * objects that xform_culling_sphere() gives one, in their order; k < 64),
 * as its vector test finds it. Test hook: tests/accel/test_batch.c
 * compares each bit with xform_sphere_misses_ray(). This function can't
 * fail. */
uint64_t batch_spheres_passed(const void *s, const ray_t *r);

#endif
