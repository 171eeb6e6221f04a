/*
 * render.h - the image loop of ch. 5: for every pixel, camera samples with
 * pixel jitter (a one-pixel box filter), each estimated by the integrator,
 * accumulated per pixel. Pixels are rendered in 16 x 16 tiles on several
 * threads (OpenMP) and in passes over ranges of sample indices. Sample s of
 * pixel p draws its numbers from rng_for_sample(seed, p, s) and each pixel
 * adds its samples in index order, so the image is bit-identical for any
 * thread count, tile order and pass split. Where the tracer takes packets
 * (the grids of ch. 7), the camera rays of 8 x 8 pixels go to it at once,
 * one sample of each: the same image, bit for bit. With app. F's
 * subsampling (scene_render_t.subsample_step, where the program offers
 * it: render/subsample.h) a pass computes only some pixels, each with
 * all its samples at once, and interpolates the others.
 * Tests: tests/render/test_render.c, tests/render/test_subsample.c
 */
#ifndef SVET_RENDER_H
#define SVET_RENDER_H

#include <stdio.h>
#include <signal.h>
#include <stdbool.h>

#include "render/camera.h"
#include "io/image.h"
#include "render/integrator.h"
#include "render/light.h"
#include "render/scene.h"
#include "render/tracer.h"

#define RENDER_TILE 16
/* Camera rays go to the tracer RENDER_PACKET x RENDER_PACKET pixels at a
 * time (one sample of each) where it takes packets: the grids' fastest
 * size at 1e6 triangles (bench/results/grid.md). */
#define RENDER_PACKET 8

/* Called after each finished tile, from whichever thread finished it, one
 * call at a time. */
typedef void (*render_progress_fn)(void *ctx, long tiles_done,
                                   long tiles_total);

typedef struct render {
    const scene_t *scene;
    camera_t camera;
    lightset_t lights;      /* empty (nothing allocated) without lights */
    tracer_t tracer;        /* ch. 5's list of the objects, or the tracer
                               of the acceleration layer the scene's
                               features offer (ch. 7) */
    const struct accel_layer *layer; /* that layer (accel.h), or NULL */
    void *accel;            /* and the accel_t it built: brute force, or
                               one of the structures the features offer */
    /* The camera rays of a block of pixels at once, as accel.h's
     * accel_tracer_intersect_packet() with accel as ctx: where the
     * structure takes packets (the grids of ch. 7); else NULL. */
    void (*intersect_packet)(const void *ctx, const ray_t *r, int n,
                             real tmin, real tmax, hit_t *hit,
                             const COBJECT **obj, bool *found);
    char accel_choice[200]; /* what was chosen for tracing, and why */
    bool packets;           /* camera rays in packets (intersect_packet):
                               where the scene asks for them
                               (scene_render_t.packets) and the structure
                               takes them; a caller may clear it to trace
                               them one at a time, for the same image */
    integrator_t integrator;
    image_accum_t acc;      /* per-pixel sums and counts (image.h) */
    image_fixed_t *sum2;    /* per pixel and channel: sum of squares of the
                               samples, for the variance of the mean, in
                               units of 2^-IMAGE_SUM2_Q (image.h) */
    long spp_done;          /* samples [0, spp_done) of every pixel are in */
    integrator_stats_t stats;
    /* The scene's rendering method of Part II (scenepart.h: `render
     * integrator photon`) and its state after prepare; NULL: the
     * integrator of ch. 5 */
    const struct render_method *method;
    void *method_state;
    svet_error error;       /* render_pass()'s failure, when it fails */
    /* Only the pixels [crop_x0, crop_x1) x [crop_y0, crop_y1) are rendered
     * when crop_x1 > 0 (svet render --crop, for a part of a split render:
     * each pixel's samples are the same as in the whole image) */
    int crop_x0, crop_x1, crop_y0, crop_y1;
    /* App. F (scene_render_t.subsample_step > 0): after the one pass,
     * the image (computed pixels the means of their samples, bit for bit
     * as without subsampling; the rest interpolated), which pixels were
     * computed (1) and how many; sub has no pixels before */
    image_t sub;
    uint8_t *sub_mask;
    long sub_computed;
} render_t;

/* Prepare to render scene s: the camera, the lights (only if the scene has
 * some), the tracer over the acceleration structure the scene asks for
 * among those s->features offers (scene.h; no acceleration layer: ch.
 * 5's list of the objects, tracer.h), the
 * accumulation images. s must outlive r. Returns SVET_ERR_RANGE for an
 * unusable camera, SVET_ERR_UNSUPPORTED for an accel the features do not
 * offer, SVET_ERR_NOMEM. */
svet_status render_init(render_t *r, const scene_t *s, svet_error *err);

/* render_init with the method's pre-pass read from f (at its position)
 * instead of computed: what render_save_prepass wrote for the same scene
 * and seed (the caller checks that; the file holds no identity of its
 * own). f NULL is render_init. SVET_ERR_UNSUPPORTED for a scene without
 * a method or with one that does not save its pre-pass (scenepart.h),
 * the method's load failure else. */
svet_status render_init_prepass(render_t *r, const scene_t *s, FILE *f,
                                svet_error *err);

/* SVET_OK when s's method saves its pre-pass, else SVET_ERR_UNSUPPORTED
 * with the reason (no method, or one without save and load). */
svet_status render_check_prepass(const scene_t *s, svet_error *err);

/* Writes r's pre-pass (render_init_prepass reads it) to f at its
 * position. SVET_ERR_UNSUPPORTED as above, SVET_ERR_IO. */
svet_status render_save_prepass(const render_t *r, FILE *f, svet_error *err);

/* Add samples [spp_done, spp_end) to every pixel with `threads` threads
 * (0 = all cores), calling progress (may be NULL) after each tile. With
 * subsampling (app. F) the pass is the only one, from sample 0 to spp_end,
 * over the whole image (its refinement needs every pixel's final value):
 * a second pass, a pass from a later sample or a crop (the parts of a
 * split render) fail with SVET_ERR_UNSUPPORTED and a message saying so,
 * and progress is called per computed pixel, with the image's pixel count
 * as the total. With
 * the integrators of ch. 5 this can't fail; a rendering method of Part II
 * (r->method) may fail in its begin_pass (out of memory for a new photon
 * map): then nothing is added, and the status is returned with its
 * message in r->error. */
svet_status render_pass(render_t *r, long spp_end, int threads,
                        render_progress_fn progress, void *ctx);

/* render_pass(), given up as soon as *stop is non-zero (a signal handler
 * sets it; read between tiles, so within one tile's samples of it): the
 * tiles not yet begun are skipped, and if any was, the pass is undone, r
 * holding exactly what it held before the call (sums, counts, spp_done,
 * statistics), so that its image is still the one of spp_done samples,
 * bit for bit. *abandoned says which. Fails with SVET_ERR_NOMEM (r
 * unchanged) when the copy of the sums kept meanwhile cannot be made. */
svet_status render_pass_until(render_t *r, long spp_end, int threads,
                              render_progress_fn progress, void *ctx,
                              const volatile sig_atomic_t *stop,
                              bool *abandoned, svet_error *err);

/* The mean image (linear radiance). */
svet_status render_image(const render_t *r, image_t *out, svet_error *err);

/* Per-pixel variance of the mean, sigma^2 / n, per channel (the estimate
 * s^2 / n with s^2 the unbiased sample variance); 0 where n < 2. */
svet_status render_variance(const render_t *r, image_t *out, svet_error *err);

/* The radiance estimate of one camera sample (for ch. 3's program and
 * tests): sample `sample` of pixel (x, y). */
RADIANCE render_sample(const render_t *r, int x, int y, long sample,
                       integrator_stats_t *st);

void render_free(render_t *r);

#endif
