/*
 * phase.c - isotropic, Henyey-Greenstein and Rayleigh phase functions of
 * ch. 11 and 12, evaluated and sampled exactly.
 * Tests: tests/medium/test_phase.c
 */
#include "medium/phase.h"
#include "core/frame.h"

#define INV_4PI REAL_C(0.0795774715459476679)

real phase_eval(const phase_t *p, real c)
{
    switch (p->kind) {
    case PHASE_HG: {
        /* p = (1 - g^2) / (4 pi (1 + g^2 - 2 g cos)^(3/2)) */
        real g = p->g, d = 1 + g * g - 2 * g * c;
        return INV_4PI * (1 - g * g) / (d * sqrt(d));
    }
    case PHASE_RAYLEIGH:
        /* 3 / (16 pi) (1 + cos^2) */
        return REAL_C(0.75) * INV_4PI * (1 + c * c);
    case PHASE_ISOTROPIC:
        break;
    }
    return INV_4PI;
}

real phase_sample_cos(const phase_t *p, real u)
{
    switch (p->kind) {
    case PHASE_HG: {
        real g = p->g;
        if (fabs(g) < REAL_C(1e-3))
            return 1 - 2 * u; /* the inverse below cancels for g -> 0 */
        /* the inverse CDF of HG in cos theta (Henyey & Greenstein 1941;
         * pbrt-v3 sec. 15.2.3): cos = (1 + g^2 - s^2) / (2 g) with
         * s = (1 - g^2) / (1 + g - 2 g u), the CDF measured from cos = 1 */
        real s = (1 - g * g) / (1 + g - 2 * g * u);
        real c = (1 + g * g - s * s) / (2 * g);
        return c < -1 ? -1 : c > 1 ? 1 : c;
    }
    case PHASE_RAYLEIGH: {
        /* the CDF 3/8 (c + c^3 / 3) + 1/2 = u is the cubic
         * c^3 + 3c - 2v = 0 with v = 4u - 2; Cardano's one real root is
         * z - 1 / z with z = cbrt(v + sqrt(v^2 + 1)) (Frisvad 2011). For
         * v < 0 the root is odd in v: computing it at |v| keeps v + sqrt
         * free of cancellation. */
        real v = 4 * u - 2, a = fabs(v);
        real z = cbrt(a + sqrt(a * a + 1));
        real c = z - 1 / z;
        c = v < 0 ? -c : c;
        return c < -1 ? -1 : c > 1 ? 1 : c;
    }
    case PHASE_ISOTROPIC:
        break;
    }
    return 1 - 2 * u;
}

real phase_sample(const phase_t *p, const VECTOR3 wi, const real u[2],
                  VECTOR3 wo)
{
    real c = phase_sample_cos(p, u[0]);
    real s = sqrt(fmax(REAL_C(0.0), 1 - c * c)), phi = 2 * REAL_PI * u[1];
    VECTOR3 a, b;
    frame_from_normal(a, b, wi);
    real x = s * cos(phi), y = s * sin(phi);
    for (int k = 0; k < 3; k++)
        wo[k] = x * a[k] + y * b[k] + c * wi[k];
    return phase_eval(p, c);
}
