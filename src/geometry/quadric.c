/*
 * quadric.c - the parts the quadrics of app. D share: stable quadratic
 * roots (Haines et al. 2019), power-of-two ray scaling, the axis frame
 * (app. A) with its error bounds (pbrt-v3 sec. 3.9), and flat disks.
 * Tests: tests/geometry/test_quadric.c
 */
#include "geometry/quadric.h"
#include "geometry/shape.h"

int quadric_roots(real a, real bh, real c, real disc, real t[2])
{
    if (!(disc >= 0))
        return 0;
    /* q = -(bh + sign(bh) sqrt(disc)) adds two numbers of the same sign:
     * no cancellation. copysign makes bh = +-0 count as positive. */
    real q = -(bh + copysign(sqrt(disc), bh));
    if (q == 0) {
        /* bh = 0 and disc = 0: a t^2 + c = 0 with a c = 0. */
        if (a == 0)
            return 0; /* 0 t = 0: no equation left */
        t[0] = t[1] = 0;
        return 2;
    }
    if (a == 0) {
        t[0] = c / q; /* the linear equation 2 bh t + c = 0 */
        return 1;
    }
    real t0 = c / q, t1 = q / a;
    if (t0 > t1) {
        real s = t0; t0 = t1; t1 = s;
    }
    t[0] = t0;
    t[1] = t1;
    return 2;
}

real quadric_diff_of_products(real a, real b, real c, real d)
{
    /* cd is c*d rounded; err its rounding error, exactly (fma rounds once). */
    real cd = c * d;
    real err = fma(-c, d, cd);
    real dop = fma(a, b, -cd);
    return dop + err;
}

int quadric_scale_dir(VECTOR3 ds, const VECTOR3 d)
{
    real ax = fabs(d[X]), ay = fabs(d[Y]), az = fabs(d[Z]);
    real m = ax > ay ? (ax > az ? ax : az) : (ay > az ? ay : az);
    /* Moderate lengths are left alone: their squares and products cannot
     * overflow or underflow, and even the bit-level scaling would cost a
     * good part of a sphere test. */
    if ((m >= REAL_C(0x1p-32) && m <= REAL_C(0x1p32)) || !(m > 0) ||
        !isfinite(m)) {
        vec_copy(ds, d);
        return 0;
    }
    return shape_scale_exponent(ds, d);
}

bool quadric_project(VECTOR3 q, real len)
{
    VECTOR3 s;
    quadric_scale_dir(s, q);
    real l = vec_length(s);
    if (!(l > 0) || !isfinite(l))
        return false;
    vec_scale(q, s, len / l);
    return true;
}

real quadric_phi(real x, real y)
{
    real phi = atan2(y, x);
    return phi < 0 ? phi + 2 * REAL_PI : phi;
}

void quadric_frame_init(quadric_frame_t *f, const VECTOR3 o, const VECTOR3 w)
{
    vec_copy(f->o, o);
    vec_copy(f->w, w);
    frame_from_normal(f->e1, f->e2, w);
}

int quadric_frame_ray(const quadric_frame_t *f, const ray_t *r, VECTOR3 ol,
                      VECTOR3 dl)
{
    VECTOR3 rel, ds;
    int k = quadric_scale_dir(ds, r->d);
    vec_sub(rel, r->o, f->o);
    frame_to_local(ol, rel, f->e1, f->e2, f->w);
    frame_to_local(dl, ds, f->e1, f->e2, f->w);
    return k;
}

void quadric_frame_point(const quadric_frame_t *f, const VECTOR3 at, real x,
                         real y, real z, real extra, VECTOR3 p,
                         VECTOR3 p_error)
{
    real g4 = ray_gamma(4);
    real frame = QUADRIC_FRAME_DELTA * (fabs(x) + fabs(y) + fabs(z)) + extra;
    for (int i = 0; i < 3; i++) {
        real tx = x * f->e1[i], ty = y * f->e2[i], tz = z * f->w[i];
        p[i] = at[i] + tx + ty + tz;
        p_error[i] = g4 * (fabs(at[i]) + fabs(tx) + fabs(ty) + fabs(tz)) +
                     frame;
    }
}

bool quadric_lateral_hit(const real ts[], int n, int k, const VECTOR3 ol,
                         const VECTOR3 dl, real zlo, real zhi, real tmin,
                         real *tmax, hit_t *hit)
{
    for (int i = 0; i < n; i++) {
        real t = quadric_unscale_t(ts[i], k);
        if (!(t > tmin && t < *tmax))
            continue;
        real x = ol[X] + ts[i] * dl[X], y = ol[Y] + ts[i] * dl[Y];
        real z = ol[Z] + ts[i] * dl[Z];
        if (z >= zlo && z <= zhi && isfinite(x) && isfinite(y)) {
            hit->t = *tmax = t;
            hit->prim = 0;
            vec_set(hit->b, x, y, z);
            return true;
        }
    }
    return false;
}

bool quadric_cap_hit(const VECTOR3 ol, const VECTOR3 dl, int k, real zc,
                     real R, real code, real tmin, real *tmax, hit_t *hit)
{
    real ts, x, y;
    if (!quadric_disk_hit(ol, dl, zc, R, &ts, &x, &y))
        return false;
    real t = quadric_unscale_t(ts, k);
    if (!(t > tmin && t < *tmax))
        return false;
    hit->t = *tmax = t;
    hit->prim = 0;
    vec_set(hit->b, x, y, code);
    return true;
}

bool quadric_disk_hit(const VECTOR3 ol, const VECTOR3 dl, real zc, real R,
                      real *ts, real *x, real *y)
{
    if (dl[Z] == 0)
        return false;
    real t = (zc - ol[Z]) / dl[Z];
    real hx = ol[X] + t * dl[X], hy = ol[Y] + t * dl[Y];
    /* Written so that NaN and overflow fail the test. */
    if (!(hx * hx + hy * hy <= R * R))
        return false;
    *ts = t;
    *x = hx;
    *y = hy;
    return true;
}

void quadric_lateral_normal_change(const quadric_frame_t *f, real a_z,
                                   const PATHPOINT *pp, const VECTOR3 dp,
                                   VECTOR3 dn)
{
    VECTOR3 q, x, dx, g, dg;
    vec_sub(q, pp->cross_point, f->o);
    frame_to_local(x, q, f->e1, f->e2, f->w);
    frame_to_local(dx, dp, f->e1, f->e2, f->w);
    x[Z] *= a_z;
    dx[Z] *= a_z;
    frame_to_world(g, x, f->e1, f->e2, f->w);
    frame_to_world(dg, dx, f->e1, f->e2, f->w);
    shape_normal_change(g, dg, pp->n, dn);
}

void quadric_disk_surface(const quadric_frame_t *f, const VECTOR3 centre,
                          real zc, real R, real sign, real x, real y,
                          PATHPOINT *pp)
{
    quadric_frame_point(f, centre, x, y, 0, QUADRIC_FRAME_DELTA * fabs(zc),
                        pp->cross_point, pp->p_error);
    vec_scale(pp->ng, f->w, sign);
    vec_copy(pp->n, pp->ng);
    real rho = hypot(x, y);
    real phi = quadric_phi(x, y);
    pp->st[0] = fmin(phi / (2 * REAL_PI), REAL_C(1.0));
    pp->st[1] = fmin(rho / R, REAL_C(1.0));
    VECTOR3 ds = { -2 * REAL_PI * y, 2 * REAL_PI * x, 0 };
    VECTOR3 dt = { R * cos(phi), R * sin(phi), 0 };
    frame_to_world(pp->dpds, ds, f->e1, f->e2, f->w);
    frame_to_world(pp->dpdt, dt, f->e1, f->e2, f->w);
    shape_frame(pp->u, pp->v, pp->n, pp->dpds);
}

void quadric_disk_sample(const quadric_frame_t *f, const VECTOR3 centre,
                         real zc, real R, real sign, const real u[2],
                         cobject_sample_t *s)
{
    real rim = fmax(R - quadric_sample_margin(centre, R), REAL_C(0.0));
    real rho = fmin(R * sqrt(u[0]), rim), phi = 2 * REAL_PI * u[1];
    quadric_frame_point(f, centre, rho * cos(phi), rho * sin(phi), 0,
                        QUADRIC_FRAME_DELTA * fabs(zc), s->p, s->p_error);
    vec_scale(s->n, f->w, sign);
}

void quadric_bounds_add(bbox_t *b, const VECTOR3 lo, const VECTOR3 hi)
{
    for (int i = 0; i < 3; i++) {
        b->min[i] = fmin(b->min[i], nextafter(lo[i], -(real)INFINITY));
        b->max[i] = fmax(b->max[i], nextafter(hi[i], (real)INFINITY));
    }
}

void quadric_disk_bounds(bbox_t *b, const VECTOR3 centre, const VECTOR3 w,
                         real R)
{
    VECTOR3 lo, hi;
    for (int i = 0; i < 3; i++) {
        real s = hypot(w[(i + 1) % 3], w[(i + 2) % 3]); /* sqrt(1 - w_i^2) */
        real e = R * (s + 4 * REAL_EPSILON);
        lo[i] = centre[i] - e;
        hi[i] = centre[i] + e;
    }
    quadric_bounds_add(b, lo, hi);
}

real quadric_sample_margin(const VECTOR3 at, real size)
{
    real m = fmax(fabs(at[X]), fmax(fabs(at[Y]), fabs(at[Z])));
    return 4 * (ray_gamma(4) * (m + 2 * size) +
                2 * QUADRIC_FRAME_DELTA * size);
}

int quadric_pick_face(real *u0, const real area[], int n)
{
    real total = 0;
    for (int i = 0; i < n; i++)
        total += area[i];
    real a = *u0 * total, below = 0;
    int i = 0;
    while (i < n - 1 && a >= below + area[i])
        below += area[i++];
    *u0 = fmin(fmax((a - below) / area[i], REAL_C(0.0)), REAL_C(1.0));
    return i;
}

svet_status quadric_check_radius(const char *shape, real radius,
                                 svet_error *err)
{
    if (radius > 0 && isfinite(radius))
        return SVET_OK;
    return svet_error_set(err, SVET_ERR_RANGE,
                          "%s: radius %g is not a positive finite number",
                          shape, (double)radius);
}

svet_status quadric_check_axis(const char *shape, const char *from_name,
                               const VECTOR3 from, const char *to_name,
                               const VECTOR3 to, real radius, VECTOR3 w,
                               real *H, svet_error *err)
{
    svet_status st = shape_check_finite(shape, from_name, from, err);
    if (st == SVET_OK)
        st = shape_check_finite(shape, to_name, to, err);
    if (st == SVET_OK)
        st = quadric_check_radius(shape, radius, err);
    if (st != SVET_OK)
        return st;
    VECTOR3 axis;
    vec_sub(axis, to, from);
    *H = vec_normalize(w, axis);
    if (*H == 0)
        return svet_error_set(err, SVET_ERR_RANGE, "%s: the axis from %s to "
                              "%s has zero (or infinite) length", shape,
                              from_name, to_name);
    return SVET_OK;
}

real quadric_lateral_margin(const VECTOR3 from, const VECTOR3 to, real radius,
                            real H)
{
    real size = fmax(radius, H);
    return fmin(fmax(quadric_sample_margin(from, size),
                     quadric_sample_margin(to, size)),
                REAL_C(0.5) * H);
}

COBJECT *quadric_object_done(COBJECT *obj, svet_error *err)
{
    real area = obj->ops->area(obj);
    bbox_t b;
    obj->ops->bounds(obj, -1, &b);
    if (!(area > 0) || !isfinite(area) || !isfinite(1 / area)) {
        svet_error_set(err, SVET_ERR_RANGE,
                       "%s: area %g is outside the range of %s",
                       obj->ops->name, (double)area, REAL_NAME);
    } else if (!vec_is_finite(b.min) || !vec_is_finite(b.max)) {
        svet_error_set(err, SVET_ERR_RANGE, "%s: the bounds overflow %s",
                       obj->ops->name, REAL_NAME);
    } else {
        return obj;
    }
    cobject_free(obj);
    return NULL;
}
