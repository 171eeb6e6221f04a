/*
 * cobject.h - the book's scene object and path vertex (ch. 1, end):
 * COBJECT, "class COBJECT" in the book's C++, here a struct with a table of
 * functions that each primitive of app. D fills in; and PATHPOINT, the point
 * where a ray meets an object, with the book's fields.
 * Tests: tests/materials/test_cobject.c (and one suite per primitive)
 */
#ifndef SVET_COBJECT_H
#define SVET_COBJECT_H

#include <stdbool.h>
#include "core/bbox.h"
#include "materials/radiance.h"
#include "core/ray.h"
#include "core/vec.h"

typedef struct cobject COBJECT;

/* ch. 1: a point of a light path. Fields above the marker are the book's,
 * spelled as the book spells them; the rest are what a robust renderer
 * needs beside them. Directions follow the book: `in` (Psi_i) points from
 * the surface toward where light comes from, `out` (Psi_r) from the surface
 * toward where it goes (for a camera ray, out = -ray direction). */
typedef struct pp {
    VECTOR3 u, v, n;         /* local frame (app. A): tangents u, v and the
                                shading normal n; u x v = n. n points out of
                                a closed object, along (c1-c0) x (c3-c0) of a
                                parallelogram, as each primitive documents */
    VECTOR3 cross_point;     /* the intersection point */
    VECTOR3 in, out;         /* Psi_i and Psi_r */
    bool bin, bout;          /* in (out) makes an acute angle with n */
    real r_dist;             /* distance from the ray origin to cross_point */
    RADIANCE intensity;      /* radiance along this vertex of the path */
    const COBJECT *IntersectObj; /* the object cross_point lies on */
    struct pp *nextpoint;    /* next vertex: a path is a linked list */
    /* -- beyond the book -- */
    VECTOR3 ng;              /* unit geometric normal; n may differ from it
                                where normals are interpolated (meshes) */
    VECTOR3 p_error;         /* bound on |cross_point - exact point| per
                                axis, for ray_spawn() (pbrt-v3 sec. 3.9) */
    real st[2];              /* surface parameters in [0,1]^2, the "(u,v)"
                                of texture mapping (ch. 10); named s, t
                                because u, v are the frame above */
    VECTOR3 dpds, dpdt;      /* dP/ds, dP/dt: tangents for bump maps */
    int prim;                /* sub-primitive hit: a triangle of a mesh, a
                                face of a box; 0 for single shapes */
} PATHPOINT;

/* What intersect() leaves for surface(): the hit distance and whatever the
 * primitive needs to finish the PATHPOINT later. Splitting the two lets an
 * acceleration structure test many objects and complete only the nearest. */
typedef struct {
    real t;      /* ray parameter of the hit, tmin < t < tmax */
    int prim;    /* sub-primitive index */
    real b[3];   /* primitive's scratch: barycentrics, local (s, t), ... */
} hit_t;

/* A point drawn on a surface by sample(). */
typedef struct {
    VECTOR3 p;       /* the point */
    VECTOR3 n;       /* unit normal there, the same orientation as
                        PATHPOINT.ng of a hit at p */
    VECTOR3 p_error; /* error bound of p, as PATHPOINT.p_error */
    real pdf;        /* probability density per unit area (1/m^2) */
} cobject_sample_t;

/* The table of functions of a primitive (the "methods" of the book's
 * class COBJECT). Every entry is a math kernel: it cannot fail. */
typedef struct {
    const char *name; /* "sphere", "triangle", ... */

    /* Nearest intersection of ray r with sub-primitive prim in the open
     * interval (tmin, tmax). On a hit fills hit and returns true. Rays of
     * any nonzero, finite direction length are accepted. */
    bool (*intersect)(const COBJECT *obj, int prim, const ray_t *r,
                      real tmin, real tmax, hit_t *hit);

    /* Complete pp for a hit that intersect() returned for the same ray:
     * cross_point, p_error, ng, the frame u v n, st, dpds, dpdt, and prim
     * where it differs from hit->prim (which cobject_fill puts there first,
     * e.g. a box sets the face it hit). The caller (cobject_fill) sets
     * r_dist, out, bout and IntersectObj. */
    void (*surface)(const COBJECT *obj, const ray_t *r, const hit_t *hit,
                    PATHPOINT *pp);

    /* Bounds of sub-primitive prim, or of the whole object when prim < 0. */
    void (*bounds)(const COBJECT *obj, int prim, bbox_t *b);

    /* Total surface area. */
    real (*area)(const COBJECT *obj);

    /* Map u in [0,1)^2 to a point on the surface and its area density.
     * Uniform by area for every primitive of app. D; a transformed curved
     * primitive returns the exact pdf of its (non-uniform) sampling. */
    void (*sample)(const COBJECT *obj, const real u[2], cobject_sample_t *s);

    /* Free what the primitive allocated in obj->shape. May be NULL. */
    void (*destroy)(COBJECT *obj);

    /* The change dn of the unit shading normal pp->n of a hit that
     * surface() filled, for a change dp of the point along the surface, to
     * first order (the surface's Weingarten map): what Igehy's ray
     * differentials need to reflect and refract off a curved surface
     * (texture/raydiff.h). May be NULL: a flat surface, dn = 0 (call it
     * through cobject_normal_change()). Each curved primitive's is checked
     * against traced neighbouring rays in tests/texture/test_raydiff.c. */
    void (*normal_change)(const COBJECT *obj, const PATHPOINT *pp,
                          const VECTOR3 dp, VECTOR3 dn);
} cobject_ops;

/* Forward declarations: what later chapters hang on a surface. The geometry
 * never looks inside them. */
struct material;   /* ch. 1: BRDF/BTDF of the surface */
struct light;      /* ch. 5: set when the surface emits (an area light) */
struct texture;    /* ch. 10 */
struct medium;     /* ch. 11: the media on each side of the boundary */

struct cobject {
    const cobject_ops *ops;
    void *shape;          /* the primitive's own data, owned by the object */
    int nprims;           /* sub-primitives: 1, or the triangles of a mesh */
    int id;               /* index in the scene, -1 when not in one */
    const struct material *material;
    const struct light *light;
    const struct texture *texture;
    const struct medium *inside, *outside; /* on the -ng and +ng sides */
    /* surface() writes every field its contract names (cross_point,
     * p_error, ng, u, v, n, st, dpds, dpdt, prim) at every hit, reading
     * none of them first, so cobject_fill() need not clear the PATHPOINT
     * before it: set by the constructors that promise it (parallelogram,
     * box, a transformed object whose inner one promises it), false
     * otherwise. tests/materials/test_cobject.c checks each promise. */
    bool surface_fills;
};

/* Initialise the fields every object has: ops, shape, nprims = 1, id = -1,
 * nothing attached. Primitives call it from their constructors. */
void cobject_init(COBJECT *obj, const cobject_ops *ops, void *shape);

/* Free the object's shape data and the object itself (obj from a
 * primitive's *_new constructor). NULL is allowed. */
void cobject_free(COBJECT *obj);

/* Nearest hit of r with any sub-primitive of obj in (tmin, tmax): loops over
 * them (brute force; ch. 7's grids do better for meshes). */
bool cobject_intersect(const COBJECT *obj, const ray_t *r, real tmin,
                       real tmax, hit_t *hit);

/* Complete the PATHPOINT of a hit: the primitive's surface(), then the
 * book's fields that depend on the ray: r_dist = t |d|, out = -d/|d|,
 * bout = out . n > 0, IntersectObj; in, bin, intensity and nextpoint are
 * cleared for the integrator to set. The rest of pp is cleared before
 * surface() runs unless obj->surface_fills. This function can't fail. */
void cobject_fill(const COBJECT *obj, const ray_t *r, const hit_t *hit,
                  PATHPOINT *pp);

/* obj's normal_change(), or dn = 0 where it has none (a flat surface). */
void cobject_normal_change(const COBJECT *obj, const PATHPOINT *pp,
                           const VECTOR3 dp, VECTOR3 dn);

/* Set pp->in to the unit direction w and bin = (in . n > 0). */
void pathpoint_set_in(PATHPOINT *pp, const VECTOR3 w);

#endif
