/*
 * triangle.c - the triangle of app. D. Departs from the book's "hit the
 * plane, then test inside" with the watertight test of Woop, Benthin, Wald,
 * JCGT 2(1) 2013, and pbrt-v3 sec. 3.9 for the error bounds.
 * Tests: tests/test_triangle.c; vectors: tests/vectors/triangle.csv
 */
#include "triangle.h"
#include "frame.h"

#include <stdlib.h>

/* The exact sign of a*b - c*d. In float the two products are exact in
 * double (24 + 24 bits < 53) and the one rounding of their difference
 * keeps its sign: this is Woop et al.'s fallback. In double there is no
 * wider type that is exact, so Kahan's fma algorithm is used instead: its
 * relative error is below 2u (Jeannerod, Louvet, Muller, "Further analysis
 * of Kahan's algorithm for the accurate computation of 2x2 determinants",
 * Math. Comp. 82, 2013), so its result is zero exactly when a*b = c*d and
 * has the right sign otherwise. */
static real diff_of_products_exact(real a, real b, real c, real d)
{
#ifdef SVET_DOUBLE
    double w = c * d;
    double e = fma(-c, d, w); /* w - c*d, exactly */
    double f = fma(a, b, -w);
    return f + e;
#else
    return (real)((double)a * (double)b - (double)c * (double)d);
#endif
}

bool triangle_intersect_watertight(const VECTOR3 p0, const VECTOR3 p1,
                                   const VECTOR3 p2, const ray_t *r,
                                   real tmin, real tmax, real *t, real b[3])
{
    /* Scale d by a power of two (exact) when its largest component is far
     * from 1, so that 1/d_z and the sheared z's cannot overflow; the ray
     * parameter then scales back by the same power (o + t d = o + t' d'). */
    VECTOR3 d;
    vec_copy(d, r->d);
    int kz = vec_max_axis(d);
    if (!(d[kz] != 0 && isfinite(d[kz])))
        return false;
    int scale = ilogb(d[kz]);
    if (scale < -16 || scale > 16)
        for (int i = 0; i < 3; i++)
            d[i] = ldexp(d[i], -scale);
    else
        scale = 0;

    /* Woop et al. sec. 3: translate the vertices to the ray origin, then
     * permute the axes so that the ray's largest component is z, and shear
     * so that the ray runs along +z. Every vertex is transformed on its
     * own, so a vertex shared by two triangles lands on the same point in
     * both: the root of watertightness. */
    int kx = kz == 2 ? 0 : kz + 1;
    int ky = kx == 2 ? 0 : kx + 1;
    real sx = -d[kx] / d[kz], sy = -d[ky] / d[kz], sz = 1 / d[kz];
    VECTOR3 a0, a1, a2;
    vec_sub(a0, p0, r->o);
    vec_sub(a1, p1, r->o);
    vec_sub(a2, p2, r->o);
    real x0 = a0[kx] + sx * a0[kz], y0 = a0[ky] + sy * a0[kz];
    real x1 = a1[kx] + sx * a1[kz], y1 = a1[ky] + sy * a1[kz];
    real x2 = a2[kx] + sx * a2[kz], y2 = a2[ky] + sy * a2[kz];

    /* Edge functions (2D cross products) of the projected vertices: e_i is
     * the signed double area opposite vertex i, i.e. its unnormalised
     * barycentric. The shared edge of two triangles gives x1*y2 - y1*x2 in
     * one and x2*y1 - y2*x1 = -(x1*y2 - y1*x2) in the other, exactly. */
    real e0 = x1 * y2 - y1 * x2;
    real e1 = x2 * y0 - y2 * x0;
    real e2 = x0 * y1 - y0 * x1;
    /* A zero may be rounding: recompute exactly (Woop et al. sec. 3.3). */
    if (e0 == 0 || e1 == 0 || e2 == 0) {
        e0 = diff_of_products_exact(x1, y2, y1, x2);
        e1 = diff_of_products_exact(x2, y0, y2, x0);
        e2 = diff_of_products_exact(x0, y1, y0, x1);
    }
    /* Inside when all three have one sign; zero counts for both sides, so
     * a ray through an edge is inside both triangles that share it. */
    if ((e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0))
        return false;
    real det = e0 + e1 + e2;
    /* det = 0: the ray lies in the triangle's plane (or the projection is
     * degenerate). A non-finite det means an overflow: no reliable hit. */
    if (det == 0 || !isfinite(det))
        return false;

    /* t = sum e_i z_i / det with the sheared z's (Woop et al. eq. 8). */
    real z0 = sz * a0[kz], z1 = sz * a1[kz], z2 = sz * a2[kz];
    real tt = (e0 * z0 + e1 * z1 + e2 * z2) / det;
    if (!isfinite(tt))
        return false;

    /* pbrt-v3 sec. 3.9.6: a conservative bound deltaT on the error of tt.
     * z's: one product after one subtraction, gamma(3)... as derived there:
     * the sheared x, y carry gamma(5) (max|x| + max|z|), the edge functions
     * deltaE, and t = sum e_i z_i / det carries deltaT. A hit that may
     * truly lie at t <= 0 is rejected, so a ray leaving the triangle never
     * finds it again at t ~ 0. Applied when tmin >= 0 only, so a caller
     * asking for t < 0 still gets it. */
    if (tmin >= 0) {
        real max_z = fmax(fabs(z0), fmax(fabs(z1), fabs(z2)));
        real max_x = fmax(fabs(x0), fmax(fabs(x1), fabs(x2)));
        real max_y = fmax(fabs(y0), fmax(fabs(y1), fabs(y2)));
        real dz = ray_gamma(3) * max_z;
        real dx = ray_gamma(5) * (max_x + max_z);
        real dy = ray_gamma(5) * (max_y + max_z);
        real de = 2 * (ray_gamma(2) * max_x * max_y + dy * max_x +
                       dx * max_y);
        real max_e = fmax(fabs(e0), fmax(fabs(e1), fabs(e2)));
        real dt = 3 * (ray_gamma(3) * max_e * max_z + de * max_z +
                       dz * max_e) / fabs(det);
        if (tt <= dt)
            return false;
    }
    if (scale != 0)
        tt = ldexp(tt, -scale);
    if (!(tt > tmin && tt < tmax))
        return false;
    /* Only now, on the rare path of a hit: a triangle of no area has no
     * normal, so it is never hit (it would give NaN normals downstream). */
    if (triangle_is_degenerate(p0, p1, p2))
        return false;
    *t = tt;
    /* All e_i have det's sign and sum to it: each b_i lies in [0, 1]. */
    b[0] = e0 / det;
    b[1] = e1 / det;
    b[2] = e2 / det;
    return true;
}

bool triangle_is_degenerate(const VECTOR3 p0, const VECTOR3 p1,
                            const VECTOR3 p2)
{
    VECTOR3 a, b;
    vec_sub(a, p1, p0);
    vec_sub(b, p2, p0);
    if (!vec_is_finite(a) || !vec_is_finite(b))
        return true;
    /* Component k of a x b is a_j b_l - a_l b_j. The edges carry one
     * rounding each, the products one more, the difference one: the
     * computed component is within gamma(4) (|a_j b_l| + |a_l b_j|) of the
     * exact cross product of the exact edges (Higham 2002, sec. 3.1). When
     * every component lies within its bound, the exact area may be 0. */
    for (int k = 0; k < 3; k++) {
        int j = (k + 1) % 3, l = (k + 2) % 3;
        real c = a[j] * b[l] - a[l] * b[j];
        real bound = ray_gamma(4) * (fabs(a[j] * b[l]) + fabs(a[l] * b[j]));
        if (fabs(c) > bound)
            return false;
    }
    return true;
}
