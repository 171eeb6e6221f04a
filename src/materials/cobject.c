/*
 * cobject.c - what every COBJECT shares: construction, destruction, the loop
 * over sub-primitives, and the book's PATHPOINT fields that depend on the
 * ray rather than the primitive (ch. 1).
 * Tests: tests/materials/test_cobject.c
 */
#include "materials/cobject.h"

#include <stdlib.h>
#include <string.h>

void cobject_init(COBJECT *obj, const cobject_ops *ops, void *shape)
{
    memset(obj, 0, sizeof *obj);
    obj->ops = ops;
    obj->shape = shape;
    obj->nprims = 1;
    obj->id = -1;
}

void cobject_free(COBJECT *obj)
{
    if (!obj)
        return;
    if (obj->ops && obj->ops->destroy)
        obj->ops->destroy(obj);
    free(obj);
}

bool cobject_intersect(const COBJECT *obj, const ray_t *r, real tmin,
                       real tmax, hit_t *hit)
{
    bool any = false;
    for (int i = 0; i < obj->nprims; i++) {
        if (obj->ops->intersect(obj, i, r, tmin, tmax, hit)) {
            any = true;
            tmax = hit->t; /* keep only what is nearer than the best so far */
        }
    }
    return any;
}

void cobject_fill(const COBJECT *obj, const ray_t *r, const hit_t *hit,
                  PATHPOINT *pp)
{
    if (obj->surface_fills) {
        /* surface() writes the rest (COBJECT.surface_fills): clear only
         * what it leaves, to the values the memset gives */
        vec_set(pp->in, 0, 0, 0);
        pp->bin = false;
        pp->intensity = (RADIANCE){ 0, 0, 0 };
        pp->nextpoint = NULL;
    } else {
        memset(pp, 0, sizeof *pp);
    }
    pp->prim = hit->prim; /* surface() may refine it, e.g. to a box face */
    obj->ops->surface(obj, r, hit, pp);
    real len = vec_length(r->d);
    pp->r_dist = hit->t * len;
    vec_scale(pp->out, r->d, -1 / len);
    pp->bout = SVECTOR3(pp->out, pp->n) > 0;
    pp->IntersectObj = obj;
}

void cobject_normal_change(const COBJECT *obj, const PATHPOINT *pp,
                           const VECTOR3 dp, VECTOR3 dn)
{
    if (obj->ops->normal_change)
        obj->ops->normal_change(obj, pp, dp, dn);
    else
        vec_set(dn, 0, 0, 0);
}

void pathpoint_set_in(PATHPOINT *pp, const VECTOR3 w)
{
    vec_copy(pp->in, w);
    pp->bin = SVECTOR3(w, pp->n) > 0;
}
