/*
 * camera.h - the pinhole camera of ch. 5: one ray per film position, with
 * the field of view measured along a chosen axis. Pixel jitter with a
 * one-pixel box filter is the caller's choice of (x, y) inside the pixel.
 * The ray formula is written out in scenes/README.md ("Camera").
 * Tests: tests/render/test_camera.c
 */
#ifndef SVET_CAMERA_H
#define SVET_CAMERA_H

#include "core/error.h"
#include "core/ray.h"

/* Which extent of the image the field of view spans. */
typedef enum {
    CAMERA_FOV_X,        /* the full horizontal angle */
    CAMERA_FOV_Y,        /* the full vertical angle */
    CAMERA_FOV_DIAGONAL  /* corner to opposite corner */
} camera_fov_axis;

typedef struct {
    VECTOR3 eye;        /* centre of projection */
    VECTOR3 u, v, w;    /* right, up, backward: an orthonormal frame with
                           w = (eye - target)/|eye - target| */
    real tan_x, tan_y;  /* tangents of the half angles of the image */
    int width, height;  /* pixels */
} camera_t;

/* Set up a camera at eye looking at target, with `up` giving the vertical
 * (it need not be perpendicular to the view direction), a full field of
 * view fov_degrees in (0, 180) along `axis`, and a width x height image.
 * Returns SVET_ERR_RANGE with a message for NaN or infinite input,
 * eye == target, up parallel to the view direction, a field of view out of
 * range, or a non-positive size. */
svet_status camera_init(camera_t *c, const VECTOR3 eye, const VECTOR3 target,
                        const VECTOR3 up, real fov_degrees,
                        camera_fov_axis axis, int width, int height,
                        svet_error *err);

/* The primary ray through the film position (x, y) in raster coordinates:
 * x in [0, width) to the right, y in [0, height) downward; pixel (i, j)
 * covers [i, i+1) x [j, j+1). The direction is unit length. This function
 * can't fail. */
void camera_ray(const camera_t *c, real x, real y, ray_t *r);

/* The raster position of the world point p; false if p is behind the
 * camera (or at the eye). The inverse of camera_ray. */
bool camera_project(const camera_t *c, const VECTOR3 p, real *x, real *y);

#endif
