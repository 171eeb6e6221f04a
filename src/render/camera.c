/*
 * camera.c - the pinhole camera (ch. 5); the formula is in scenes/README.md.
 * Tests: tests/render/test_camera.c
 */
#include "render/camera.h"

svet_status camera_init(camera_t *c, const VECTOR3 eye, const VECTOR3 target,
                        const VECTOR3 up, real fov_degrees,
                        camera_fov_axis axis, int width, int height,
                        svet_error *err)
{
    if (!vec_is_finite(eye) || !vec_is_finite(target) || !vec_is_finite(up))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "camera: position, target and up must be finite");
    if (!(fov_degrees > 0 && fov_degrees < 180))
        return svet_error_set(err, SVET_ERR_RANGE, "camera: field of view %g "
                              "degrees is not in (0, 180)",
                              (double)fov_degrees);
    if (width <= 0 || height <= 0)
        return svet_error_set(err, SVET_ERR_RANGE, "camera: image size %d x %d "
                              "is not positive", width, height);
    VECTOR3 back;
    vec_sub(back, eye, target);
    if (!vec_is_finite(back) || !isfinite(vec_length(back)))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "camera: position - target overflows %s",
                              REAL_NAME);
    if (vec_normalize(c->w, back) == 0)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "camera: position and target coincide");
    VECTOR3 right;
    VVECTOR3(right, up, c->w);
    /* |up x w| = |up| sin(angle): below ~1e-6 rad the frame is unreliable */
    real upl = vec_length(up);
    if (!(vec_length(right) > REAL_C(1e-6) * upl))
        return svet_error_set(err, SVET_ERR_RANGE, "camera: up vector is "
                              "parallel to the viewing direction");
    vec_normalize(c->u, right);
    VVECTOR3(c->v, c->w, c->u);
    real t = tan(REAL_C(0.5) * fov_degrees * REAL_PI / 180);
    real aspect = (real)width / (real)height;
    switch (axis) {
    case CAMERA_FOV_X:
        c->tan_x = t;
        c->tan_y = t / aspect;
        break;
    case CAMERA_FOV_Y:
        c->tan_y = t;
        c->tan_x = t * aspect;
        break;
    case CAMERA_FOV_DIAGONAL: {
        real diag = hypot((real)width, (real)height);
        c->tan_x = t * (real)width / diag;
        c->tan_y = t * (real)height / diag;
        break;
    }
    default:
        return svet_error_set(err, SVET_ERR_RANGE, "camera: unknown fov axis");
    }
    vec_copy(c->eye, eye);
    c->width = width;
    c->height = height;
    return SVET_OK;
}

void camera_ray(const camera_t *c, real x, real y, ray_t *r)
{
    /* Screen coordinates in [-1, 1], y up: sx = 2x/W - 1, sy = 1 - 2y/H;
     * d = sx tan_x u + sy tan_y v - w, normalised. */
    real sx = 2 * x / (real)c->width - 1;
    real sy = 1 - 2 * y / (real)c->height;
    VECTOR3 d;
    for (int k = 0; k < 3; k++)
        d[k] = sx * c->tan_x * c->u[k] + sy * c->tan_y * c->v[k] - c->w[k];
    vec_normalize(r->d, d);
    vec_copy(r->o, c->eye);
}

bool camera_project(const camera_t *c, const VECTOR3 p, real *x, real *y)
{
    VECTOR3 d;
    vec_sub(d, p, c->eye);
    real depth = -SVECTOR3(d, c->w);
    if (!(depth > 0))
        return false;
    real sx = SVECTOR3(d, c->u) / (depth * c->tan_x);
    real sy = SVECTOR3(d, c->v) / (depth * c->tan_y);
    *x = (sx + 1) * REAL_C(0.5) * (real)c->width;
    *y = (1 - sy) * REAL_C(0.5) * (real)c->height;
    return true;
}
