/*
 * texture.c - a texture of ch. 10 read at a surface point: its colour,
 * its height with the height's derivatives, and Blinn's (1978) bumped
 * shading frame (texture.h).
 * Tests: tests/texture/test_texture.c
 */
#include "texture/texture.h"

#include <math.h>
#include <string.h>

#include "geometry/shape.h"

void texture_point_of(texture_point_t *q, const PATHPOINT *pp, real width)
{
    vec_copy(q->p, pp->cross_point);
    q->s = pp->st[0];
    q->t = pp->st[1];
    vec_copy(q->dpds, pp->dpds);
    vec_copy(q->dpdt, pp->dpdt);
    q->width = width;
}

/* The first channel, or three, of an image lookup. */
static RADIANCE image_colour(const texture_t *t, real s, real u, real width)
{
    real out[MIPMAP_MAX_CHANNELS] = { 0, 0, 0, 0 };
    mipmap_lookup(&t->mip, t->filter, s, u, width, out);
    if (t->mip.channels < 3)
        return rad_grey(out[0]);
    return rad_make(out[0], out[1], out[2]);
}

/* The 2D checker's factor: 0 or 1 by the parity of the square. */
static real checker2(real s, real t)
{
    real f = floor(s) + floor(t);
    return f - 2 * floor(f / 2);
}

static RADIANCE blend(RADIANCE a, RADIANCE b, real f)
{
    return rad_add(rad_scale(a, 1 - f), rad_scale(b, f));
}

RADIANCE texture_eval(const texture_t *t, const texture_point_t *q)
{
    const real s = q->s * t->scale, u = q->t * t->scale;
    switch (t->kind) {
    case TEXTURE_IMAGE:
        return image_colour(t, s, u, q->width * t->scale);
    case TEXTURE_CHECKER:
        return blend(t->a, t->b, checker2(s, u));
    case TEXTURE_SOLID:
        return solid_eval(&t->solid, q->p);
    default: /* TEXTURE_BUMPGEN */
        return blend(t->a, t->b, bumpgen_height(&t->bump, s, u, NULL, NULL));
    }
}

real texture_height(const texture_t *t, const texture_point_t *q,
                    real *dhds, real *dhdt)
{
    const real s = q->s * t->scale, u = q->t * t->scale;
    real hs = 0, ht = 0, h = 0;
    switch (t->kind) {
    case TEXTURE_IMAGE: {
        /* central differences one texel of level 0 apart, in (s, t) */
        const real ds = REAL_C(1.0) / (real)t->mip.level[0].width;
        const real dt = REAL_C(1.0) / (real)t->mip.level[0].height;
        const real w = q->width * t->scale;
        h = image_colour(t, s, u, w).r;
        real sp = image_colour(t, s + ds, u, w).r;
        real sm = image_colour(t, s - ds, u, w).r;
        real tp = image_colour(t, s, u + dt, w).r;
        real tm = image_colour(t, s, u - dt, w).r;
        hs = (sp - sm) / (2 * ds) * t->scale;
        ht = (tp - tm) / (2 * dt) * t->scale;
        break;
    }
    case TEXTURE_CHECKER:
        h = checker2(s, u);
        break;
    case TEXTURE_SOLID: {
        VECTOR3 g;
        h = solid_factor(&t->solid, q->p, g);
        hs = SVECTOR3(g, q->dpds); /* chain rule: dh/ds = grad h . dP/ds */
        ht = SVECTOR3(g, q->dpdt);
        break;
    }
    default: /* TEXTURE_BUMPGEN */
        h = bumpgen_height(&t->bump, s, u, &hs, &ht);
        hs *= t->scale;
        ht *= t->scale;
        break;
    }
    if (dhds)
        *dhds = isfinite(hs) ? hs : 0;
    if (dhdt)
        *dhdt = isfinite(ht) ? ht : 0;
    return isfinite(h) ? h : 0;
}

bool texture_bump(PATHPOINT *pp, real dhds, real dhdt)
{
    if (dhds == 0 && dhdt == 0)
        return false;
    /* Blinn 1978: P' = P + h N, dP'/ds = dP/ds + dh/ds N (+ h dN/ds,
     * dropped), the same along t, N' = dP'/ds x dP'/dt */
    VECTOR3 ts, tt, n;
    for (int k = 0; k < 3; k++) {
        ts[k] = pp->dpds[k] + dhds * pp->n[k];
        tt[k] = pp->dpdt[k] + dhdt * pp->n[k];
    }
    VVECTOR3(n, ts, tt);
    real len = vec_length(n);
    if (!(len > 0) || !isfinite(len))
        return false;
    vec_scale(n, n, 1 / len);
    /* dP/ds x dP/dt may point either way relative to the outward normal
     * (a primitive's s may run clockwise): keep the side of pp->n */
    if (SVECTOR3(n, pp->n) < 0)
        vec_scale(n, n, -1);
    /* the viewer must stay on the side the geometric normal gives it */
    const real on = SVECTOR3(pp->out, n), og = SVECTOR3(pp->out, pp->ng);
    if ((on > 0) != (og > 0) || on == 0)
        return false;
    vec_copy(pp->n, n);
    shape_frame(pp->u, pp->v, pp->n, ts);
    pp->bout = on > 0;
    return true;
}

void texture_range(const texture_t *t, RADIANCE *mean, RADIANCE *top)
{
    if (t->kind == TEXTURE_IMAGE) {
        const mipmap_t *m = &t->mip;
        real c[MIPMAP_MAX_CHANNELS] = { 0, 0, 0, 0 };
        mipmap_texel(m, m->levels - 1, 0, 0, c);
        *mean = m->channels < 3 ? rad_grey(c[0]) : rad_make(c[0], c[1], c[2]);
        real hi[3] = { 0, 0, 0 };
        const mipmap_level_t *l = &m->level[0];
        const size_t n = (size_t)l->width * (size_t)l->height;
        const int nc = m->channels < 3 ? 1 : 3;
        for (size_t i = 0; i < n; i++)
            for (int k = 0; k < nc; k++)
                hi[k] = real_max(hi[k],
                                 l->px[i * (size_t)m->channels + (size_t)k]);
        *top = nc == 1 ? rad_grey(hi[0]) : rad_make(hi[0], hi[1], hi[2]);
        return;
    }
    const RADIANCE a = t->kind == TEXTURE_SOLID ? t->solid.a : t->a;
    const RADIANCE b = t->kind == TEXTURE_SOLID ? t->solid.b : t->b;
    /* a / 2 + b / 2: a constant texture, a = b, gives a exactly */
    *mean = rad_add(rad_scale(a, REAL_C(0.5)), rad_scale(b, REAL_C(0.5)));
    *top = rad_make(real_max(a.r, b.r), real_max(a.g, b.g),
                    real_max(a.b, b.b));
}

void texture_free(texture_t *t)
{
    if (t && t->kind == TEXTURE_IMAGE)
        mipmap_free(&t->mip);
}
