/*
 * sample.c - the samplers of ch. 4: maps from [0,1)^2 to directions and
 * points with known densities (pbrt-v3 sec. 13.6; Shirley & Chiu 1997;
 * Walter 2005; Shirley, Wang, Zimmerman 1996), jittered strata, and the
 * running estimators of the Monte Carlo method (Welford 1962; Chan, Golub,
 * LeVeque 1983). Tests: tests/core/test_sample.c; vectors: tests/vectors/sample_*.csv
 */
#include "core/sample.h"

#include "core/frame.h"

#define TWO_PI (2 * REAL_PI)
#define INV_2PI (REAL_C(0.5) * REAL_INV_PI)
#define INV_4PI (REAL_C(0.25) * REAL_INV_PI)

/* The direction at polar angle theta (given by cos and sin) and azimuth phi
 * about +z. */
static void spherical_direction(VECTOR3 w, real cos_theta, real sin_theta,
                                real phi)
{
    vec_set(w, sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
}

/* --- directions --------------------------------------------------------- */

void sample_uniform_sphere(VECTOR3 w, const real u[2])
{
    /* pbrt-v3 sec. 13.6.1: z = 1 - 2 u0 is uniform on [-1, 1] (Archimedes'
     * hat-box theorem). sin(theta) = sqrt((1 - z)(1 + z)) = 2 sqrt(u0 (1 -
     * u0)): no cancellation in 1 - z^2 near the poles. */
    real z = 1 - 2 * u[0];
    real s = 2 * sqrt(fmax(REAL_C(0.0), u[0] * (1 - u[0])));
    spherical_direction(w, z, s, TWO_PI * u[1]);
}

real sample_uniform_sphere_pdf(void)
{
    return INV_4PI;
}

void sample_uniform_hemisphere(VECTOR3 w, const real u[2])
{
    /* pbrt-v3 sec. 13.6.1: z = u0 is uniform on [0, 1). */
    real z = u[0];
    real s = sqrt(fmax(REAL_C(0.0), (1 - z) * (1 + z)));
    spherical_direction(w, z, s, TWO_PI * u[1]);
}

real sample_uniform_hemisphere_pdf(void)
{
    return INV_2PI;
}

/* The concentric map (Shirley & Chiu 1997; pbrt-v3 sec. 13.6.2): each of
 * the four triangles of the square [-1,1]^2 cut by its diagonals maps to a
 * quarter of the disk, the square of half-side r to the circle of radius r.
 * Also returns 1 - r exactly: r = |2 u - 1| for the u of the dominant axis,
 * so 1 - r = 2 min(u, 1 - u) (2u is exact, and so is 1 - u for u >= 1/2). */
static void concentric(real d[2], real *one_minus_r, const real u[2])
{
    real ox = 2 * u[0] - 1, oy = 2 * u[1] - 1;
    if (ox == 0 && oy == 0) {
        d[0] = d[1] = 0;
        *one_minus_r = 1;
        return;
    }
    real r, theta, m;
    if (fabs(ox) > fabs(oy)) {
        r = ox;
        theta = (REAL_PI / 4) * (oy / ox);
        m = u[0];
    } else {
        r = oy;
        theta = REAL_PI / 2 - (REAL_PI / 4) * (ox / oy);
        m = u[1];
    }
    d[0] = r * cos(theta);
    d[1] = r * sin(theta);
    /* real_min, no libm call: fmin's answer here (a NaN m makes both
     * arguments NaN) */
    *one_minus_r = 2 * real_min(m, 1 - m);
}

#define COSINE_Z_MIN REAL_C(0x1p-12)

void sample_cosine_hemisphere(VECTOR3 w, const real u[2])
{
    /* Malley's method (pbrt-v3 sec. 13.6.3): points uniform on the unit
     * disk, projected up onto the hemisphere, have density cos(theta)/pi
     * per solid angle. z = sqrt(1 - r^2) = sqrt((1 - r)(1 + r)) from the
     * exact 1 - r: near the rim 1 - x^2 - y^2 would lose every digit. */
    real d[2], omr;
    concentric(d, &omr, u);
    real z = sqrt(omr * (2 - omr));
    if (z < COSINE_Z_MIN) {
        /* u within 2^-25 of the square's edge (u = 0 included) maps to
         * the disk's rim, i.e. the horizon, where the pdf is 0 and a weight
         * f cos / pdf is 0/0. Lift such samples to z = 2^-12: |w| stays 1
         * to within 3e-8. */
        real s = sqrt(1 - COSINE_Z_MIN * COSINE_Z_MIN) /
                 fmax(hypot(d[0], d[1]), REAL_MIN);
        vec_set(w, d[0] * s, d[1] * s, COSINE_Z_MIN);
        return;
    }
    vec_set(w, d[0], d[1], z);
}

real sample_cosine_hemisphere_pdf(real cos_theta)
{
    return cos_theta > 0 ? cos_theta * REAL_INV_PI : 0;
}

/* Uniform in the cone 1 - cos(theta) <= h about +z, given h = 1 - cos of the
 * cone's half-angle directly: a small cone (a far light) has h far below
 * the spacing of reals near 1, where 1 - cos_theta_max would round to 0. */
static void cone_by_height(VECTOR3 w, const real u[2], real h)
{
    /* pbrt-v3 sec. 13.6.4: cos(theta) = (1 - u0) + u0 cos_theta_max, i.e.
     * 1 - cos(theta) = u0 h; sin^2 = (1 - cos)(1 + cos) = u0 h (2 - u0 h). */
    real omc = u[0] * h;
    real s = sqrt(fmax(REAL_C(0.0), omc * (2 - omc)));
    spherical_direction(w, 1 - omc, s, TWO_PI * u[1]);
}

/* The cone's pdf 1/(2 pi h), finite for every h: a cone too narrow for
 * `real` (h below REAL_MIN) is treated as one of height REAL_MIN. */
static real cone_pdf_by_height(real h)
{
    return INV_2PI / fmax(h, REAL_MIN);
}

static real cone_height(real cos_theta_max)
{
    /* Clamped to [0, 2]: cos_theta_max outside [-1, 1] (or NaN) means the
     * whole sphere or a single direction. */
    real h = 1 - cos_theta_max;
    return h > 2 ? 2 : h >= 0 ? h : 0;
}

void sample_uniform_cone(VECTOR3 w, const real u[2], real cos_theta_max)
{
    cone_by_height(w, u, cone_height(cos_theta_max));
}

real sample_uniform_cone_pdf(real cos_theta_max)
{
    return cone_pdf_by_height(cone_height(cos_theta_max));
}

void sample_phong_lobe(VECTOR3 w, const real u[2], real e)
{
    /* Inverting the cdf of cos(alpha) under (e + 1)/(2 pi) cos^e(alpha)
     * (Lafortune & Willems 1994; pbrt-v3 sec. 13.6 style):
     * cos(alpha) = (1 - u0)^(1/(e+1)). Written as exp(t), t = log(1 - u0) /
     * (e + 1), so that 1 - cos(alpha) = -expm1(t) keeps its digits when the
     * lobe is narrow (e = 1e5: 1 - cos ~ 1e-5, below float's spacing near
     * 1 in relative terms). 1 - u0 > 0 always, so t is finite and the pdf at
     * the sample is at least (e + 1)/(2 pi) (1 - u0): never 0. */
    e = fmax(e, REAL_C(0.0)); /* a NaN or negative e means e = 0 */
    real t = log(1 - u[0]) / (e + 1);
    real omc = -expm1(t); /* 1 - cos(alpha) */
    real s = sqrt(fmax(REAL_C(0.0), omc * (2 - omc)));
    spherical_direction(w, exp(t), s, TWO_PI * u[1]);
}

real sample_phong_lobe_pdf(real cos_alpha, real e)
{
    e = fmax(e, REAL_C(0.0));
    if (!(cos_alpha >= 0))
        return 0;
    /* pow(0, 0) = 1: at e = 0 the lobe is uniform up to the horizon. */
    return (e + 1) * INV_2PI * pow(fmin(cos_alpha, REAL_C(1.0)), e);
}

/* Ward's roughness, kept where every quantity below stays finite in
 * float: the peak pdf 1/(pi alpha^2) is 3e13 at alpha = 1e-7. */
#define WARD_ALPHA_MIN REAL_C(1e-7)
#define WARD_ALPHA_MAX REAL_C(1e7)

static real ward_alpha(real a)
{
    return fmin(fmax(a, WARD_ALPHA_MIN), WARD_ALPHA_MAX); /* NaN -> min */
}

void sample_ward_half(VECTOR3 h, const real u[2], real alpha_x, real alpha_y)
{
    /* Walter 2005, "Notes on the Ward BRDF", eqs. (6)-(7): the azimuth from
     * tan(phi) = (alpha_y / alpha_x) tan(2 pi u1), in the quadrant of
     * 2 pi u1, which is the direction of (alpha_x cos 2 pi u1,
     * alpha_y sin 2 pi u1); then tan^2(delta) = -log(u0) / A(phi),
     * A = cos^2(phi)/alpha_x^2 + sin^2(phi)/alpha_y^2. We use 1 - u0 for u0
     * so that u0 = 0 gives the peak (delta = 0) and no u gives log(0). */
    real ax = ward_alpha(alpha_x), ay = ward_alpha(alpha_y);
    real psi = TWO_PI * u[1];
    real px = ax * cos(psi), py = ay * sin(psi);
    real len = hypot(px, py);
    real cp = len > 0 ? px / len : 1, sp = len > 0 ? py / len : 0;
    real a = (cp / ax) * (cp / ax) + (sp / ay) * (sp / ay);
    real tan2 = -log(1 - u[0]) / a;
    /* cos^2 = 1/(1 + tan^2), sin^2 = tan^2/(1 + tan^2): no 1 - cos^2, which
     * would lose a delta of 1e-4 (alpha = 1e-4) entirely in float. */
    real cos_d, sin_d;
    if (isinf(tan2)) {
        cos_d = 0;
        sin_d = 1;
    } else {
        cos_d = 1 / sqrt(1 + tan2);
        sin_d = sqrt(tan2) * cos_d;
    }
    vec_set(h, sin_d * cp, sin_d * sp, cos_d);
}

real sample_ward_half_pdf(const VECTOR3 h, real alpha_x, real alpha_y)
{
    real ax = ward_alpha(alpha_x), ay = ward_alpha(alpha_y);
    if (!(h[Z] > 0))
        return 0;
    /* tan^2(delta) (cos^2 phi/ax^2 + sin^2 phi/ay^2)
     *   = ((hx/ax)^2 + (hy/ay)^2) / hz^2, no trigonometry; the pdf is then
     * exp(that) / (pi ax ay hz^3), taken as one exp of a sum of logs so that
     * a tiny hz (hz^3 -> 0) meets a huge exponent (exp -> 0) as 0, not 0/0. */
    real qx = h[X] / ax, qy = h[Y] / ay;
    real num = qx * qx + qy * qy;
    real expo = num > 0 ? num / (h[Z] * h[Z]) : 0;
    real p = exp(-expo - 3 * log(h[Z])) * REAL_INV_PI / (ax * ay);
    return fmin(p, REAL_MAX); /* finite even for a non-unit h */
}

/* --- points ------------------------------------------------------------- */

void sample_concentric_disk(real d[2], const real u[2])
{
    real omr;
    concentric(d, &omr, u);
}

void sample_triangle(real b[2], const real u[2])
{
    /* pbrt-v3 sec. 13.6.5: b0 = 1 - sqrt(u0) has the marginal density
     * 2 (1 - b0) of a uniform triangle; given b0, b1 is uniform on
     * [0, 1 - b0]. */
    real su0 = sqrt(u[0]);
    b[0] = 1 - su0;
    b[1] = u[1] * su0;
}

void sample_parallelogram(VECTOR3 p, const VECTOR3 p0, const VECTOR3 e1,
                          const VECTOR3 e2, const real u[2])
{
    /* An affine map of the unit square: its Jacobian |e1 x e2| is constant,
     * so uniform stays uniform. */
    for (int k = 0; k < 3; k++)
        p[k] = p0[k] + u[0] * e1[k] + u[1] * e2[k];
}

void sample_sphere_area(VECTOR3 p, VECTOR3 n, const VECTOR3 c, real r,
                        const real u[2])
{
    VECTOR3 d;
    sample_uniform_sphere(d, u);
    vec_copy(n, d);
    vec_add_scaled(p, c, r, d);
}

real sample_sphere_solid_angle_pdf(const VECTOR3 w, const VECTOR3 x,
                                   const VECTOR3 c, real r)
{
    VECTOR3 cx; /* c - x (not -(x - c): a zero component stays +0, which
                 * picks the frame branch of frame_from_normal) */
    vec_sub(cx, c, x);
    real d = vec_length(cx);
    if (!(r > 0) || !(d == d))
        return 0;
    if (d >= r) {
        /* The cone of the sphere (Shirley, Wang, Zimmerman 1996; pbrt-v3
         * sec. 14.2.2): sin^2(theta_max) = r^2/d^2, and
         * h = 1 - cos(theta_max) = sin^2 / (1 + cos) without cancellation.
         * w is inside when 1 - cos(w, axis) = |w - axis|^2 / 2 <= h. The
         * slack allows for the rounding of w and axis (components of error
         * ~eps, so |w - axis| is off by up to ~4 eps): a sample drawn at the
         * edge of a tiny cone (h = 5e-13 at 1e6 radii) must not get pdf 0. */
        real s = r / d;
        real s2 = s * s;
        real h = s2 / (1 + sqrt(fmax(REAL_C(0.0), (1 - s) * (1 + s))));
        VECTOR3 axis, diff;
        vec_scale(axis, cx, 1 / d);
        vec_sub(diff, w, axis);
        real omc = REAL_C(0.5) * vec_length2(diff);
        real slack = 4 * REAL_EPSILON * sqrt(2 * h) + 8 * REAL_EPSILON * REAL_EPSILON;
        if (omc > h + slack)
            return 0;
        return cone_pdf_by_height(h);
    }
    /* Inside: every direction leaves through the sphere once, at
     * t = -b + sqrt(b^2 - cc) along w, b = (x - c).w, cc = |x - c|^2 - r^2
     * < 0; there cos = n.w = sqrt(b^2 - cc)/r, and the area density
     * 1/(4 pi r^2) becomes t^2 / (4 pi r^2 cos) per solid angle
     * (pbrt-v3 sec. 5.5.1, dw = cos dA / t^2). */
    real b = -SVECTOR3(cx, w); /* (x - c).w */
    real cc = (d - r) * (d + r);
    real disc = sqrt(b * b - cc);
    /* For b > 0, -b + disc cancels; -cc / (b + disc) is the same root. */
    real t = b > 0 ? -cc / (b + disc) : disc - b;
    real denom = 4 * REAL_PI * r * disc;
    return denom > 0 ? t * t / denom : 0;
}

real sample_sphere_solid_angle(VECTOR3 w, const VECTOR3 x, const VECTOR3 c,
                               real r, const real u[2])
{
    VECTOR3 cx;
    vec_sub(cx, c, x);
    real d = vec_length(cx);
    if (!(r > 0) || !(d == d)) {
        vec_set(w, 0, 0, 1);
        return 0;
    }
    if (d >= r) {
        real s = r / d;
        real h = s * s / (1 + sqrt(fmax(REAL_C(0.0), (1 - s) * (1 + s))));
        VECTOR3 axis, e1, e2, l;
        vec_scale(axis, cx, 1 / d);
        frame_from_normal(e1, e2, axis);
        cone_by_height(l, u, h);
        frame_to_world(w, l, e1, e2, axis);
        return cone_pdf_by_height(h);
    }
    /* Inside the sphere: sample its area, and return the density of the
     * resulting direction per unit solid angle. */
    VECTOR3 p, n;
    sample_sphere_area(p, n, c, r, u);
    vec_sub(w, p, x);
    if (vec_normalize(w, w) == 0) /* can't happen for x strictly inside */
        vec_set(w, n[X], n[Y], n[Z]);
    return sample_sphere_solid_angle_pdf(w, x, c, r);
}

/* --- strata ------------------------------------------------------------- */

/* (i + v) / n below (i + 1) / n as computed in `real`: with v the largest
 * real below 1 the quotient can round up onto the next cell's edge. */
static real stratum(int i, int n, real v)
{
    real x = ((real)i + v) / (real)n;
    real hi = (real)(i + 1) / (real)n;
    return x < hi ? x : nextafter(hi, REAL_C(0.0));
}

void sample_stratified_2d(real *pts, int nx, int ny, pcg32_t *g)
{
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            real *p = pts + 2 * ((long)j * nx + i);
            p[0] = stratum(i, nx, pcg32_real(g));
            p[1] = stratum(j, ny, pcg32_real(g));
        }
}

/* --- estimators (ch. 4) --------------------------------------------------- */

void estimator_init(estimator_t *e)
{
    e->n = 0;
    e->mean = 0;
    e->m2 = 0;
}

void estimator_add(estimator_t *e, double x)
{
    /* Welford 1962: update the mean, then add (x - old mean)(x - new mean)
     * to the sum of squared deviations; no sum of squares that could
     * cancel catastrophically. */
    e->n++;
    double delta = x - e->mean;
    e->mean += delta / (double)e->n;
    e->m2 += delta * (x - e->mean);
}

void estimator_merge(estimator_t *a, const estimator_t *b)
{
    /* Chan, Golub, LeVeque 1983: M2 = M2a + M2b + delta^2 na nb / n. */
    if (b->n == 0)
        return;
    if (a->n == 0) {
        *a = *b;
        return;
    }
    double na = (double)a->n, nb = (double)b->n, n = na + nb;
    double delta = b->mean - a->mean;
    a->mean += delta * (nb / n);
    a->m2 += b->m2 + delta * delta * (na * nb / n);
    a->n += b->n;
}

double estimator_mean(const estimator_t *e)
{
    return e->mean;
}

double estimator_variance(const estimator_t *e)
{
    return e->n < 2 ? 0.0 : e->m2 / (double)(e->n - 1);
}

double estimator_stderr(const estimator_t *e)
{
    return e->n < 2 ? 0.0 : sqrt(estimator_variance(e) / (double)e->n);
}
