/*
 * tracer.c - ch. 5's tracer (tracer.h): the nearest hit of a ray found by
 * asking every object of the scene, in order, for its own nearest hit.
 * Tests: tests/render/test_tracer.c
 */
#include "render/tracer.h"

/* Every sub-primitive of every object, tested over (tmin, the nearest t
 * so far): a later one at the same t is not taken (the interval is open),
 * so ties go to the first object, as tracer.h promises. The scratch hit
 * starts zeroed, so the bytes of the answer do not depend on what an
 * earlier test left in it. A shadow ray (hit NULL) stops at the first
 * hit. */
static bool search(const scene_t *s, const ray_t *r, real tmin, real tmax,
                   hit_t *hit, const COBJECT **obj)
{
    bool found = false;
    if (!tracer_ray_ok(r, tmin, tmax))
        return false;
    for (int i = 0; i < s->nobjects; i++) {
        const COBJECT *o = s->objects[i];
        for (int k = 0; k < o->nprims; k++) {
            hit_t h = { 0, 0, { 0, 0, 0 } };
            if (!o->ops->intersect(o, k, r, tmin, tmax, &h))
                continue;
            if (!hit)
                return true;
            tmax = h.t;
            h.prim = k;
            *hit = h;
            *obj = o;
            found = true;
        }
    }
    return found;
}

/* skip is only a hint (tracer.h): the list tests everything */
static bool list_intersect(const void *ctx, const ray_t *r, real tmin,
                           real tmax, const COBJECT *const skip[2],
                           hit_t *hit, const COBJECT **obj)
{
    (void)skip;
    return search(ctx, r, tmin, tmax, hit, obj);
}

static bool list_occluded(const void *ctx, const ray_t *r, real tmin,
                          real tmax, const COBJECT *const skip[2])
{
    (void)skip;
    return search(ctx, r, tmin, tmax, NULL, NULL);
}

tracer_t tracer_brute(const scene_t *s)
{
    tracer_t t = { list_intersect, list_occluded, s };
    return t;
}
