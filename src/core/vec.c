/*
 * vec.c - the vector operations of ch. 1 and app. B-C that are too long to
 * inline: reflection (1.4), refraction (1.11-1.12) and Rodrigues' rotation
 * (app. C). Normalisation is inline in vec.h.
 * Tests: tests/core/test_vec.c
 */
#include "core/vec.h"

void vec_reflect(VECTOR3 r, const VECTOR3 in, const VECTOR3 n)
{
    /* eq. (1.4): Psi_r = 2 (Psi_i . n) n - Psi_i */
    real c = 2 * SVECTOR3(in, n);
    r[X] = c * n[X] - in[X];
    r[Y] = c * n[Y] - in[Y];
    r[Z] = c * n[Z] - in[Z];
}

bool vec_refract(VECTOR3 t, const VECTOR3 in, const VECTOR3 n, real n1,
                 real n2)
{
    real cos_i = SVECTOR3(n, in);
    real eta = n1 / n2;
    /* eq. (1.12): c2 = (n1/n2) sqrt(1 - (n . Psi_i)^2) is sin(theta_t);
     * 1 - cos^2 is clamped because rounding can make it slightly negative. */
    real sin2_i = fmax(REAL_C(0.0), 1 - cos_i * cos_i);
    real c2_sq = eta * eta * sin2_i;
    if (c2_sq >= 1) {
        /* c2 > 1: total internal reflection, the BTDF is zero (ch. 1). */
        vec_reflect(t, in, n);
        return false;
    }
    real c1 = sqrt(1 - c2_sq); /* eq. (1.12): c1 = sqrt(1 - c2^2) = cos(theta_t) */
    /* eq. (1.11): Psi_t = c2 n_d -/+ c1 n with n_d = (Psi_i . n) n - Psi_i.
     * The tangential part c2 n_d / |n_d| equals (n1/n2) n_d exactly, since
     * |n_d| = sin(theta_i); writing it so avoids 0/0 at normal incidence.
     * The book takes the minus sign when n . Psi_i > 0. */
    real sign = cos_i > 0 ? REAL_C(-1.0) : REAL_C(1.0);
    VECTOR3 nd;
    nd[X] = cos_i * n[X] - in[X];
    nd[Y] = cos_i * n[Y] - in[Y];
    nd[Z] = cos_i * n[Z] - in[Z];
    t[X] = eta * nd[X] + sign * c1 * n[X];
    t[Y] = eta * nd[Y] + sign * c1 * n[Y];
    t[Z] = eta * nd[Z] + sign * c1 * n[Z];
    return true;
}

void vec_rotate(VECTOR3 r, const VECTOR3 a, const VECTOR3 k, real angle)
{
    /* app. C, Rodrigues: a' = a cos(f) + (k x a) sin(f) + k (k . a)(1 - cos(f)) */
    real c = cos(angle), s = sin(angle);
    real kd = SVECTOR3(k, a) * (1 - c);
    VECTOR3 kxa;
    VVECTOR3(kxa, k, a);
    real x = a[X] * c + kxa[X] * s + k[X] * kd;
    real y = a[Y] * c + kxa[Y] * s + k[Y] * kd;
    real z = a[Z] * c + kxa[Z] * s + k[Z] * kd;
    vec_set(r, x, y, z);
}
