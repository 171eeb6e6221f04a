/*
 * meshgen.h - procedural triangle meshes for ch. 7's tests, benchmarks and
 * pictures, so that none needs downloaded data: UV spheres and tori
 * (closed), a height-field terrain, a 5 x 5 x 5 grid of spheres of any
 * total triangle count, and the "teapot in a stadium" (a dense small mesh
 * inside a huge sparse one; Haines, "Spline surface rendering, and what's
 * wrong with octrees", Ray Tracing News 1(2), 1988).
 * Tests: tests/mesh/test_meshgen.c
 */
#ifndef SVET_MESHGEN_H
#define SVET_MESHGEN_H

#include <stdint.h>
#include "materials/cobject.h"
#include "core/error.h"

/* Every generator makes one mesh COBJECT (mesh.h) with unit vertex
 * normals and texture coordinates, wound counter-clockwise seen from
 * outside (ng points out). The closed ones (sphere, torus) are closed in
 * the watertight sense: vertices on a seam or at a pole are repeated (for
 * their texture coordinates) with bit-identical positions, so the
 * watertight test lets no ray through, and a ray from inside always hits.
 * Each fails with SVET_ERR_RANGE on a non-finite or non-positive size or a
 * count out of range (the limits of mesh.h), SVET_ERR_NOMEM. */

/* UV sphere of centre c and radius r: nu segments around z (>= 3), nv
 * bands from pole to pole (>= 2), 2 nu (nv - 1) triangles. */
svet_status meshgen_uv_sphere(COBJECT **out, const VECTOR3 c, real r, int nu,
                              int nv, svet_error *err);

/* The (nu, nv) with nu = 2 nv whose sphere has the triangle count closest
 * to ntris (at least 12: nu = 4, nv = 2 gives 8, so 12 is nu 6, nv 2). */
void meshgen_sphere_segments(long ntris, int *nu, int *nv);

/* Torus about the z axis through c: major radius R, minor radius r < R,
 * nu segments around z, nv around the tube (each >= 3); 2 nu nv
 * triangles. */
svet_status meshgen_torus(COBJECT **out, const VECTOR3 c, real R, real r,
                          int nu, int nv, svet_error *err);

/* Height field over the square of side `size` centred at c in the x-y
 * plane: n x n quads (2 n^2 triangles), heights z = c_z + height * f(x, y)
 * with f a sum of 5 octaves of value noise in [-1, 1] from a PCG32 seeded
 * with seed. Open (a sheet), facing +z. */
svet_status meshgen_terrain(COBJECT **out, const VECTOR3 c, real size,
                            real height, int n, uint64_t seed,
                            svet_error *err);

/* A scene: an array of objects (malloc'd; free it with
 * meshgen_free_objects). */
typedef struct {
    COBJECT **objs;
    int nobjs;
    long ntris; /* total triangles */
} meshgen_scene_t;

void meshgen_free_objects(meshgen_scene_t *s);

/* n x n x n closed UV spheres of radius 1 whose centres are 3 apart
 * (gaps of 1), one object each, about ntris triangles in all (at least 12
 * per sphere). The benchmark's scene: n = 5, ntris = 1e3 ... 1e6. */
svet_status meshgen_sphere_grid(meshgen_scene_t *s, int n, long ntris,
                                svet_error *err);

/* The teapot in a stadium: the "teapot" is a closed UV sphere of radius 1
 * at (0, 0, 1) with about teapot_tris triangles; the "stadium" a ground
 * square of side 2000 at z = 0 (2 triangles) and a stand, a torus of
 * major radius 600 and minor radius 120 about z with 512 triangles: the
 * teapot is 1/1000 of the scene's width. Three objects: teapot, ground,
 * stand. */
svet_status meshgen_teapot_stadium(meshgen_scene_t *s, long teapot_tris,
                                   svet_error *err);

#endif
