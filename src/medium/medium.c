/*
 * medium.c - the participating media of ch. 11: coefficients and their
 * checks, Beer-Lambert transmittance, ratio tracking, and distance
 * sampling exactly (homogeneous) or by delta tracking (gridded).
 * Tests: tests/medium/test_medium.c
 */
#include "medium/medium.h"

medium_t medium_homogeneous(RADIANCE sigma_a, RADIANCE sigma_s)
{
    medium_t m = { sigma_a, sigma_s, rad_grey(0), { PHASE_ISOTROPIC, 0 },
                   NULL, NULL, NULL, 0 };
    return m;
}

static bool nonneg(RADIANCE c)
{
    return rad_is_finite(c) && c.r >= 0 && c.g >= 0 && c.b >= 0;
}

svet_status medium_check(const medium_t *m, svet_error *err)
{
    if (!nonneg(m->sigma_a))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "sigma_a (%g %g %g) must be finite and >= 0",
                              (double)m->sigma_a.r, (double)m->sigma_a.g,
                              (double)m->sigma_a.b);
    if (!nonneg(m->sigma_s))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "sigma_s (%g %g %g) must be finite and >= 0",
                              (double)m->sigma_s.r, (double)m->sigma_s.g,
                              (double)m->sigma_s.b);
    if (!nonneg(m->emission))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "emission must be finite and >= 0");
    if (m->phase.kind == PHASE_HG &&
        !(fabs(m->phase.g) < PHASE_MAX_G))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "g = %g: the Henyey-Greenstein asymmetry must "
                              "lie in (-%g, %g)", (double)m->phase.g,
                              (double)PHASE_MAX_G, (double)PHASE_MAX_G);
    if (m->grid && !(m->grid->max[0] >= 0))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "the density grid has no values >= 0");
    if (m->grid) {
        size_t n = (size_t)m->grid->nx * (size_t)m->grid->ny *
                   (size_t)m->grid->nz;
        for (size_t i = 0; i < n; i++)
            if (m->grid->plane[0][i] < 0)
                return svet_error_set(err, SVET_ERR_RANGE,
                                      "the density grid holds %g at cell "
                                      "%zu: densities must be >= 0",
                                      (double)m->grid->plane[0][i], i);
    }
    if (m->fn && !(isfinite(m->fn_max) && m->fn_max > 0))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "the density function's bound %g must be "
                              "finite and > 0", (double)m->fn_max);
    return SVET_OK;
}

bool medium_is_homogeneous(const medium_t *m) { return !m->grid && !m->fn; }

real medium_density(const medium_t *m, const VECTOR3 p)
{
    if (m->grid)
        return volgrid_eval(m->grid, 0, p);
    if (m->fn)
        return m->fn(m->fn_ctx, p);
    return 1;
}

real medium_density_max(const medium_t *m)
{
    if (m->grid)
        return (real)m->grid->max[0];
    if (m->fn)
        return m->fn_max;
    return 1;
}

RADIANCE medium_sigma_t(const medium_t *m)
{
    return rad_add(m->sigma_a, m->sigma_s);
}

static RADIANCE rad_exp_neg(RADIANCE a)
{
    return rad_make(exp(-a.r), exp(-a.g), exp(-a.b));
}

RADIANCE medium_tr_homogeneous(const medium_t *m, real d)
{
    /* Beer-Lambert: L(d) = L(0) exp(-sigma_t d) */
    return rad_exp_neg(rad_scale(medium_sigma_t(m), d));
}

/* The majorant of sigma_t along any ray: the largest channel at the
 * largest density. */
static real majorant(const medium_t *m)
{
    return rad_max(medium_sigma_t(m)) * medium_density_max(m);
}

static void point_at(const VECTOR3 o, const VECTOR3 d, real t, VECTOR3 p)
{
    p[X] = o[X] + t * d[X];
    p[Y] = o[Y] + t * d[Y];
    p[Z] = o[Z] + t * d[Z];
}

RADIANCE medium_tr(const medium_t *m, const VECTOR3 o, const VECTOR3 dir,
                   real tmax, pcg32_t *g)
{
    if (medium_is_homogeneous(m))
        return medium_tr_homogeneous(m, tmax);
    real mu = majorant(m);
    if (!(mu > 0))
        return rad_grey(1);
    /* ratio tracking (Novak et al. 2014, eq. 8): tentative collisions at
     * the majorant's rate, each multiplying the estimate by the chance
     * 1 - sigma_t(x) / mu that it was a null collision */
    RADIANCE tr = rad_grey(1), st = medium_sigma_t(m);
    real t = 0;
    for (;;) {
        t -= log(1 - pcg32_real(g)) / mu;
        if (t >= tmax)
            return tr;
        VECTOR3 p;
        point_at(o, dir, t, p);
        real rho = medium_density(m, p);
        tr = rad_mul(tr, rad_make(1 - st.r * rho / mu, 1 - st.g * rho / mu,
                                  1 - st.b * rho / mu));
        if (rad_max(tr) <= 0)
            return rad_grey(0);
    }
}

bool medium_sample(const medium_t *m, const VECTOR3 o, const VECTOR3 dir,
                   real tmax, pcg32_t *g, real *t, RADIANCE *weight)
{
    RADIANCE st = medium_sigma_t(m);
    if (medium_is_homogeneous(m)) {
        /* pbrt-v3 sec. 15.2.1: sample t in one channel, weigh by the
         * average pdf over the channels */
        real c[3] = { st.r, st.g, st.b };
        int ch = (int)(pcg32_real(g) * 3);
        ch = ch > 2 ? 2 : ch;
        real s = c[ch] > 0 ? -log(1 - pcg32_real(g)) / c[ch] : tmax;
        bool scattered = s < tmax;
        real d = scattered ? s : tmax;
        RADIANCE tr = medium_tr_homogeneous(m, d);
        real pdf = scattered ? (st.r * tr.r + st.g * tr.g + st.b * tr.b) / 3
                             : (tr.r + tr.g + tr.b) / 3;
        *t = d;
        *weight = pdf > 0 ? rad_scale(scattered ? rad_mul(m->sigma_s, tr) : tr,
                                      1 / pdf)
                          : rad_grey(0);
        return scattered;
    }
    /* delta tracking (Woodcock et al. 1965) under the majorant of the
     * largest channel: a tentative collision is real with probability
     * sigma_t(x) / mu in that channel; the others carry the ratio of
     * their own chances (the weights of spectral tracking, Kutz et al.,
     * "Spectral and Decomposition Tracking", SIGGRAPH 2017, with the
     * majorant's channel as the hero) */
    real mu = majorant(m);
    RADIANCE w = rad_grey(1);
    real s = 0;
    int hero = st.r >= st.g && st.r >= st.b ? 0 : st.g >= st.b ? 1 : 2;
    for (;;) {
        if (!(mu > 0)) {
            *t = tmax;
            *weight = w;
            return false;
        }
        s -= log(1 - pcg32_real(g)) / mu;
        if (s >= tmax) {
            *t = tmax;
            *weight = w;
            return false;
        }
        VECTOR3 p;
        point_at(o, dir, s, p);
        real rho = medium_density(m, p);
        RADIANCE sig = rad_scale(st, rho);
        real h = hero == 0 ? sig.r : hero == 1 ? sig.g : sig.b;
        real pr = h / mu; /* the chance this collision is real */
        if (pcg32_real(g) < pr) {
            /* real: weight sigma_s(x) / sigma_t(x) in the hero channel's
             * terms, i.e. sigma_s / h per channel times the pass ratio */
            *t = s;
            *weight = rad_mul(w, rad_scale(rad_scale(m->sigma_s, rho), 1 / h));
            return true;
        }
        /* null: each channel's chance of a null collision over the hero's */
        real pn = 1 - pr;
        w = rad_mul(w, rad_make((1 - sig.r / mu) / pn, (1 - sig.g / mu) / pn,
                                (1 - sig.b / mu) / pn));
    }
}
