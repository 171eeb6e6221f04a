/*
 * medium.c - the participating media of ch. 11: coefficients and their
 * checks, Beer-Lambert transmittance, ratio tracking, and distance
 * sampling exactly (homogeneous) or by delta tracking (gridded), for one
 * component or a sum of them, and the radiance a medium emits along a
 * segment (medium.h).
 * Tests: tests/medium/test_medium.c
 */
#include "medium/medium.h"

medium_t medium_homogeneous(RADIANCE sigma_a, RADIANCE sigma_s)
{
    medium_t m = { sigma_a, sigma_s, rad_grey(0), { PHASE_ISOTROPIC, 0 },
                   NULL, NULL, NULL, 0, 0, NULL };
    return m;
}

medium_t medium_mix(const medium_t *c, int n)
{
    medium_t m = medium_homogeneous(rad_grey(0), rad_grey(0));
    m.ncomponents = n;
    m.components = c;
    return m;
}

static bool nonneg(RADIANCE c)
{
    return rad_is_finite(c) && c.r >= 0 && c.g >= 0 && c.b >= 0;
}

static svet_status check_one(const medium_t *m, svet_error *err);

svet_status medium_check(const medium_t *m, svet_error *err)
{
    if (m->ncomponents == 0)
        return check_one(m, err);
    if (m->ncomponents < 0 || m->ncomponents > MEDIUM_MAX_COMPONENTS ||
        !m->components)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "a medium is the sum of 1 to %d components, "
                              "not %d", MEDIUM_MAX_COMPONENTS,
                              m->ncomponents);
    for (int i = 0; i < m->ncomponents; i++) {
        if (m->components[i].ncomponents != 0)
            return svet_error_set(err, SVET_ERR_RANGE,
                                  "component %d has components of its own",
                                  i + 1);
        svet_status st = check_one(&m->components[i], err);
        if (st)
            return st;
    }
    return SVET_OK;
}

static svet_status check_one(const medium_t *m, svet_error *err)
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

bool medium_is_homogeneous(const medium_t *m)
{
    for (int i = 0; i < m->ncomponents; i++)
        if (!medium_is_homogeneous(&m->components[i]))
            return false;
    return m->ncomponents > 0 || (!m->grid && !m->fn);
}

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
    if (m->ncomponents == 0)
        return rad_add(m->sigma_a, m->sigma_s);
    RADIANCE st = rad_grey(0);
    for (int i = 0; i < m->ncomponents; i++)
        st = rad_add(st, medium_sigma_t(&m->components[i]));
    return st;
}

RADIANCE medium_sigma_s(const medium_t *m)
{
    if (m->ncomponents == 0)
        return m->sigma_s;
    RADIANCE ss = rad_grey(0);
    for (int i = 0; i < m->ncomponents; i++)
        ss = rad_add(ss, m->components[i].sigma_s);
    return ss;
}

void medium_coeffs_at(const medium_t *m, const VECTOR3 p, RADIANCE *sigma_t,
                      RADIANCE *sigma_s)
{
    if (m->ncomponents == 0) {
        real rho = medium_density(m, p);
        *sigma_t = rad_scale(medium_sigma_t(m), rho);
        *sigma_s = rad_scale(m->sigma_s, rho);
        return;
    }
    *sigma_t = *sigma_s = rad_grey(0);
    for (int i = 0; i < m->ncomponents; i++) {
        RADIANCE st, ss;
        medium_coeffs_at(&m->components[i], p, &st, &ss);
        *sigma_t = rad_add(*sigma_t, st);
        *sigma_s = rad_add(*sigma_s, ss);
    }
}

static real rad_mean(RADIANCE c) { return (c.r + c.g + c.b) / 3; }

const medium_t *medium_scatterer(const medium_t *m, const VECTOR3 p, real u,
                                 RADIANCE *weight)
{
    if (weight)
        *weight = rad_grey(1);
    if (m->ncomponents == 0)
        return m;
    /* the discrete distribution P_i = mean sigma_s_i(p) / sum of them */
    RADIANCE ss[MEDIUM_MAX_COMPONENTS], total = rad_grey(0);
    real mean[MEDIUM_MAX_COMPONENTS], sum = 0;
    int n = m->ncomponents, last = 0;
    for (int i = 0; i < n; i++) {
        RADIANCE st;
        medium_coeffs_at(&m->components[i], p, &st, &ss[i]);
        total = rad_add(total, ss[i]);
        mean[i] = rad_mean(ss[i]);
        sum += mean[i];
        if (mean[i] > 0)
            last = i;
    }
    if (!(sum > 0))
        return &m->components[0];
    real target = u * sum, acc = 0;
    int k = last; /* rounding: u near 1 falls to the last possible one */
    for (int i = 0; i < n; i++) {
        acc += mean[i];
        if (target < acc && mean[i] > 0) {
            k = i;
            break;
        }
    }
    if (weight) {
        real pk = mean[k] / sum;
        RADIANCE w = rad_make(total.r > 0 ? ss[k].r / (pk * total.r) : 0,
                              total.g > 0 ? ss[k].g / (pk * total.g) : 0,
                              total.b > 0 ? ss[k].b / (pk * total.b) : 0);
        *weight = w;
    }
    return &m->components[k];
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
    if (m->ncomponents == 0)
        return rad_max(medium_sigma_t(m)) * medium_density_max(m);
    /* the sum of the components' bounds bounds their sum */
    real mu = 0;
    for (int i = 0; i < m->ncomponents; i++)
        mu += majorant(&m->components[i]);
    return mu;
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
    RADIANCE tr = rad_grey(1);
    real t = 0;
    for (;;) {
        t -= log(1 - pcg32_real(g)) / mu;
        if (t >= tmax)
            return tr;
        VECTOR3 p;
        point_at(o, dir, t, p);
        RADIANCE sig, ss;
        medium_coeffs_at(m, p, &sig, &ss);
        tr = rad_mul(tr, rad_make(1 - sig.r / mu, 1 - sig.g / mu,
                                  1 - sig.b / mu));
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
        *weight = pdf > 0 ? rad_scale(scattered ? rad_mul(medium_sigma_s(m), tr)
                                                : tr,
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
        RADIANCE sig, ss;
        medium_coeffs_at(m, p, &sig, &ss);
        real h = hero == 0 ? sig.r : hero == 1 ? sig.g : sig.b;
        real pr = h / mu; /* the chance this collision is real */
        if (pcg32_real(g) < pr) {
            /* real: weight sigma_s(x) / sigma_t(x) in the hero channel's
             * terms, i.e. sigma_s / h per channel times the pass ratio */
            *t = s;
            *weight = rad_mul(w, rad_scale(ss, 1 / h));
            return true;
        }
        /* null: each channel's chance of a null collision over the hero's */
        real pn = 1 - pr;
        w = rad_mul(w, rad_make((1 - sig.r / mu) / pn, (1 - sig.g / mu) / pn,
                                (1 - sig.b / mu) / pn));
    }
}

static bool emits_one(const medium_t *m)
{
    return (m->sigma_a.r > 0 && m->emission.r > 0) ||
           (m->sigma_a.g > 0 && m->emission.g > 0) ||
           (m->sigma_a.b > 0 && m->emission.b > 0);
}

bool medium_emits(const medium_t *m)
{
    for (int i = 0; i < m->ncomponents; i++)
        if (emits_one(&m->components[i]))
            return true;
    return m->ncomponents == 0 && emits_one(m);
}

RADIANCE medium_source_at(const medium_t *m, const VECTOR3 p)
{
    if (m->ncomponents == 0)
        return rad_scale(rad_mul(m->sigma_a, m->emission),
                         medium_density(m, p));
    RADIANCE s = rad_grey(0);
    for (int i = 0; i < m->ncomponents; i++)
        s = rad_add(s, medium_source_at(&m->components[i], p));
    return s;
}

/* int_0^d S exp(-st t) dt in one channel; st = 0 leaves no absorption,
 * so S = 0 there as well. */
static real emitted_channel(real S, real st, real d)
{
    if (!(S > 0))
        return 0;
    return st > 0 ? S * (real)-expm1(-st * d) / st : S * d;
}

RADIANCE medium_emitted(const medium_t *m, const VECTOR3 o,
                        const VECTOR3 dir, real tmax, pcg32_t *g)
{
    if (medium_is_homogeneous(m)) {
        RADIANCE S = medium_source_at(m, o), st = medium_sigma_t(m);
        return rad_make(emitted_channel(S.r, st.r, tmax),
                        emitted_channel(S.g, st.g, tmax),
                        emitted_channel(S.b, st.b, tmax));
    }
    real mu = majorant(m);
    if (!(mu > 0))
        return rad_grey(0);
    RADIANCE tr = rad_grey(1), L = rad_grey(0);
    real t = 0;
    for (;;) {
        t -= log(1 - pcg32_real(g)) / mu;
        if (t >= tmax)
            return L;
        VECTOR3 p;
        point_at(o, dir, t, p);
        L = rad_add(L, rad_mul(tr, rad_scale(medium_source_at(m, p),
                                             1 / mu)));
        RADIANCE sig, ss;
        medium_coeffs_at(m, p, &sig, &ss);
        tr = rad_mul(tr, rad_make(1 - sig.r / mu, 1 - sig.g / mu,
                                  1 - sig.b / mu));
        if (rad_max(tr) <= 0)
            return L;
    }
}
