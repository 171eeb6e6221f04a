/*
 * disk.c - the flat disk of app. D: the plane equation solved in the
 * disk's own frame (app. A), the hit point rebuilt from its plane
 * coordinates (pbrt-v3 sec. 3.9.4), uniform area sampling.
 * Tests: tests/geometry/test_disk.c; vectors: tests/vectors/disk.csv
 */
#include "geometry/disk.h"
#include "geometry/quadric.h"
#include "geometry/shape.h"

typedef struct {
    quadric_frame_t f; /* at the centre; w = the unit normal */
    real R;            /* radius */
    real area;         /* pi R^2 */
} disk_t;

/* hit->b holds the local (x, y) of the hit in the frame (e1, e2). */
static bool disk_intersect(const COBJECT *obj, int prim, const ray_t *r,
                           real tmin, real tmax, hit_t *hit)
{
    const disk_t *dk = obj->shape;
    (void)prim;
    /* app. D: the plane (p - centre) . n = 0 is z = 0 in local coordinates,
     * t = -o_z / d_z; the point lies on the disk when x^2 + y^2 <= R^2. */
    VECTOR3 ol, dl;
    int k = quadric_frame_ray(&dk->f, r, ol, dl);
    return quadric_cap_hit(ol, dl, k, 0, dk->R, 0, tmin, &tmax, hit);
}

static void disk_surface(const COBJECT *obj, const ray_t *r, const hit_t *hit,
                         PATHPOINT *pp)
{
    const disk_t *dk = obj->shape;
    (void)r;
    quadric_disk_surface(&dk->f, dk->f.o, 0, dk->R, 1, hit->b[0], hit->b[1],
                         pp);
}

static void disk_bounds(const COBJECT *obj, int prim, bbox_t *b)
{
    const disk_t *dk = obj->shape;
    (void)prim;
    bbox_empty(b);
    quadric_disk_bounds(b, dk->f.o, dk->f.w, dk->R);
}

static real disk_area(const COBJECT *obj)
{
    return ((const disk_t *)obj->shape)->area;
}

static void disk_sample(const COBJECT *obj, const real u[2],
                        cobject_sample_t *s)
{
    const disk_t *dk = obj->shape;
    quadric_disk_sample(&dk->f, dk->f.o, 0, dk->R, 1, u, s);
    s->pdf = 1 / dk->area;
}

static const cobject_ops disk_ops = {
    "disk", disk_intersect, disk_surface, disk_bounds,
    disk_area, disk_sample, NULL, NULL
};

COBJECT *disk_new(const VECTOR3 centre, const VECTOR3 normal, real radius,
                  svet_error *err)
{
    if (shape_check_finite("disk", "centre", centre, err) ||
        shape_check_finite("disk", "normal", normal, err) ||
        quadric_check_radius("disk", radius, err))
        return NULL;
    VECTOR3 n;
    if (vec_normalize(n, normal) == 0) {
        svet_error_set(err, SVET_ERR_RANGE, "disk: the normal is zero");
        return NULL;
    }
    COBJECT *obj = shape_alloc(&disk_ops, sizeof(disk_t), err);
    if (!obj)
        return NULL;
    disk_t *dk = obj->shape;
    quadric_frame_init(&dk->f, centre, n);
    dk->R = radius;
    dk->area = REAL_PI * radius * radius;
    return quadric_object_done(obj, err);
}
