/*
 * raydiff.h - ray differentials (Igehy, "Tracing Ray Differentials",
 * SIGGRAPH 1999): how a ray's origin P and unit direction D change from
 * one pixel to the next, dP/dx, dP/dy, dD/dx, dD/dy, started at the
 * pinhole camera (ch. 5), carried to a hit (his eq. 2-3, transfer) and
 * through a mirror's reflection and a glass's refraction (eq. 4-5 and
 * 6-7), so that a texture read after specular bounces knows the pixel's
 * footprint on the surface (Williams 1983's mip map level, texture/
 * mipmap.h). The integrator carries them, through the hooks the texture
 * part installs (scene_t.raydiff, texpart.c), only when the scene reads a
 * texture, so that other scenes compute nothing new and the programs
 * without textures link none of this.
 * On a curved surface the normal turns from one pixel's hit to the next,
 * by dN/dx, which the primitive gives (cobject_normal_change(), the
 * surface's Weingarten map applied to dP/dx) and which enters Igehy's
 * reflection and refraction: a curved mirror spreads (convex) or focuses
 * (concave) the footprint as the real neighbouring rays do.
 * Tests: tests/texture/test_raydiff.c
 */
#ifndef SVET_RAYDIFF_H
#define SVET_RAYDIFF_H

#include <stdbool.h>

#include "core/vec.h"
#include "render/camera.h"
#include "render/scene.h" /* raydiff_t */

/* The differentials of camera c's ray of unit direction d (camera_ray's):
 * the origin is the eye for every pixel, dP = 0; the unnormalised
 * direction D = sx tan_x u + sy tan_y v - w has dD/dx = (2 tan_x / W) u and
 * dD/dy = -(2 tan_y / H) v, and d = D / |D| changes by
 * (dD - (d . dD) d) / |D|. Can't fail. */
void raydiff_camera(raydiff_t *rd, const camera_t *c, const VECTOR3 d);

/* Carry the differentials of a ray of unit direction d along it to its
 * hit at distance t on a surface of normal n (Igehy's eq. 2-3):
 * dP' = dP + t dD + dt D with dt = -(dP + t dD) . n / (D . n), which keeps
 * the neighbouring rays' hits on the tangent plane; dD is unchanged.
 * False (rd untouched) where D . n is 0. Can't fail. */
bool raydiff_transfer(raydiff_t *rd, const VECTOR3 d, real t,
                      const VECTOR3 n);

/* At a hit already transferred to, the differentials of the mirror
 * direction R = D - 2 (D . n) n of unit direction d about unit normal n,
 * whose change per pixel is dndx, dndy (Igehy's eq. 4-5):
 * dR = dD - 2 ((dD . n + d . dN) n + (d . n) dN). Can't fail. */
void raydiff_reflect(raydiff_t *rd, const VECTOR3 d, const VECTOR3 n,
                     const VECTOR3 dndx, const VECTOR3 dndy);

/* At a hit already transferred to, the differentials of the refracted
 * unit direction tr = eta d - mu n of unit d through unit normal n (its
 * change per pixel dndx, dndy), eta the ratio n_from / n_to of the
 * indices (Igehy's eq. 6-7): mu = eta (d . n) - (tr . n),
 * dtr = eta dD - dmu n - mu dN, dmu = (eta - eta^2 (d . n) / (tr . n))
 * (dD . n + d . dN). False (rd untouched) where tr . n is 0 (grazing).
 * Can't fail. */
bool raydiff_refract(raydiff_t *rd, const VECTOR3 d, const VECTOR3 n,
                     const VECTOR3 dndx, const VECTOR3 dndy, real eta,
                     const VECTOR3 tr);

/* The pixel's footprint in a surface's parameters (s, t), whose tangents
 * are dpds and dpdt: the least-squares (s, t) steps of dP/dx and dP/dy
 * (the tangent plane's 2 x 2 normal equations), and of the two the
 * longer, the major axis that an isotropic mip map level must follow
 * (Williams 1983). 0 where the tangents are degenerate or the result is
 * not finite. Can't fail. */
real raydiff_footprint(const raydiff_t *rd, const VECTOR3 dpds,
                       const VECTOR3 dpdt);

#endif
