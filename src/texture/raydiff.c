/*
 * raydiff.c - ray differentials after Igehy 1999 (raydiff.h): from the
 * camera, to a hit, through mirrors and glass, and the footprint they
 * give in a surface's (s, t).
 * Tests: tests/texture/test_raydiff.c
 */
#include "texture/raydiff.h"

#include <math.h>

/* The change of d = D / |D| for a change dD of D: (dD - (d . dD) d) / |D|. */
static void unit_diff(VECTOR3 out, const VECTOR3 d, real len,
                      const VECTOR3 dD)
{
    real k = SVECTOR3(d, dD);
    for (int i = 0; i < 3; i++)
        out[i] = (dD[i] - k * d[i]) / len;
}

void raydiff_camera(raydiff_t *rd, const camera_t *c, const VECTOR3 d)
{
    /* D with w component -1 is d / (-d . w) (camera_ray's D up to its
     * length, which the unit direction does not see) */
    real dw = -SVECTOR3(d, c->w);
    real len = dw > 0 ? 1 / dw : 1;
    VECTOR3 dx, dy;
    real kx = 2 * c->tan_x / (real)c->width;
    real ky = -2 * c->tan_y / (real)c->height;
    for (int i = 0; i < 3; i++) {
        dx[i] = kx * c->u[i];
        dy[i] = ky * c->v[i];
    }
    vec_set(rd->dpdx, 0, 0, 0);
    vec_set(rd->dpdy, 0, 0, 0);
    unit_diff(rd->dddx, d, len, dx);
    unit_diff(rd->dddy, d, len, dy);
}

bool raydiff_transfer(raydiff_t *rd, const VECTOR3 d, real t,
                      const VECTOR3 n)
{
    real dn = SVECTOR3(d, n);
    if (dn == 0 || !isfinite(t))
        return false;
    VECTOR3 px, py;
    for (int i = 0; i < 3; i++) {
        px[i] = rd->dpdx[i] + t * rd->dddx[i];
        py[i] = rd->dpdy[i] + t * rd->dddy[i];
    }
    real tx = -SVECTOR3(px, n) / dn, ty = -SVECTOR3(py, n) / dn;
    for (int i = 0; i < 3; i++) {
        rd->dpdx[i] = px[i] + tx * d[i];
        rd->dpdy[i] = py[i] + ty * d[i];
    }
    return true;
}

void raydiff_reflect(raydiff_t *rd, const VECTOR3 d, const VECTOR3 n,
                     const VECTOR3 dndx, const VECTOR3 dndy)
{
    real dn = SVECTOR3(d, n);
    real *dd[2] = { rd->dddx, rd->dddy };
    const real *dN[2] = { dndx, dndy };
    for (int k = 0; k < 2; k++) {
        /* d(D . N) = dD . N + D . dN */
        real ddn = SVECTOR3(dd[k], n) + SVECTOR3(d, dN[k]);
        for (int i = 0; i < 3; i++)
            dd[k][i] -= 2 * (ddn * n[i] + dn * dN[k][i]);
    }
}

bool raydiff_refract(raydiff_t *rd, const VECTOR3 d, const VECTOR3 n,
                     const VECTOR3 dndx, const VECTOR3 dndy, real eta,
                     const VECTOR3 tr)
{
    real dn = SVECTOR3(d, n), tn = SVECTOR3(tr, n);
    if (tn == 0)
        return false;
    real mu = eta * dn - tn;
    real k = eta - eta * eta * dn / tn;
    real *dd[2] = { rd->dddx, rd->dddy };
    const real *dN[2] = { dndx, dndy };
    for (int j = 0; j < 2; j++) {
        real dmu = k * (SVECTOR3(dd[j], n) + SVECTOR3(d, dN[j]));
        for (int i = 0; i < 3; i++)
            dd[j][i] = eta * dd[j][i] - dmu * n[i] - mu * dN[j][i];
    }
    return true;
}

real raydiff_footprint(const raydiff_t *rd, const VECTOR3 dpds,
                       const VECTOR3 dpdt)
{
    /* [a b; b c] (ds, dt) = (dpds . dP, dpdt . dP) */
    real a = SVECTOR3(dpds, dpds), b = SVECTOR3(dpds, dpdt);
    real c = SVECTOR3(dpdt, dpdt);
    real det = a * c - b * b;
    if (!(det > 0))
        return 0;
    real best = 0;
    const real *dp[2] = { rd->dpdx, rd->dpdy };
    for (int k = 0; k < 2; k++) {
        real ps = SVECTOR3(dpds, dp[k]), pt = SVECTOR3(dpdt, dp[k]);
        real ds = (c * ps - b * pt) / det, dt = (a * pt - b * ps) / det;
        real l = sqrt(ds * ds + dt * dt);
        best = l > best ? l : best;
    }
    return isfinite(best) ? best : 0;
}
