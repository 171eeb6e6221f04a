/*
 * material.c - the book's mixed surface (ch. 1): f = f_r^s + f_r^d + f_r^g
 * + f_t^s + f_t^d as a sum of brdf.h components, sampled one component at
 * a time with the combined pdf of the non-delta ones (one-sample MIS).
 * Tests: tests/materials/test_material.c
 */
#include "materials/material.h"

#include <stdlib.h>

#include "core/sample.h"

static const RADIANCE black = { 0, 0, 0 };

void material_params_default(material_params *p)
{
    p->rho_d = p->rho_s = p->rho_g = p->rho_t = p->rho_dt = black;
    p->gloss = MATERIAL_GLOSS_PHONG;
    p->e = 10; /* ch. 1: "e = 8...20" */
    p->alpha_x = p->alpha_y = REAL_C(0.1);
    p->eta = 1;
    p->fresnel_exact = false;
}

/* The sum of all reflectances may not exceed 1 in any channel; rounding of
 * a sum such as 0.3 + 0.7 may put it an ulp or two above. */
static svet_status check_sum(const material_params *p, svet_error *err)
{
    const RADIANCE *r[5] = { &p->rho_d, &p->rho_s, &p->rho_g, &p->rho_t,
                             &p->rho_dt };
    const char *name[3] = { "r", "g", "b" };
    for (int k = 0; k < 3; k++) {
        real sum = 0;
        for (int i = 0; i < 5; i++)
            sum += k == 0 ? r[i]->r : k == 1 ? r[i]->g : r[i]->b;
        if (!(sum <= 1 + 4 * REAL_EPSILON))
            return svet_error_set(err, SVET_ERR_RANGE,
                                  "rho_d + rho_s + rho_g + rho_t + rho_dt = %g "
                                  "in channel %s: the surface would reflect "
                                  "and transmit more than it receives (the "
                                  "sum must be <= 1)", (double)sum, name[k]);
    }
    return SVET_OK;
}

static bool is_black(RADIANCE c)
{
    return rad_is_black(c);
}

/* Append component b if it is not black. */
static void add(material_t *m, const brdf_t *b)
{
    if (!is_black(b->rho) || (b->kind == BRDF_MIRROR && !is_black(b->rho90)))
        m->comp[m->ncomp++] = *b;
}

/* material_is_specular()'s answer, for material_init: every component a
 * delta, and at least one. */
static bool all_delta(const material_t *m)
{
    for (int k = 0; k < m->ncomp; k++)
        if (!brdf_is_delta(&m->comp[k]))
            return false;
    return m->ncomp > 0;
}

static void make_black(material_t *m)
{
    material_params_default(&m->params);
    m->ncomp = 0;
    m->lambert = false;
    m->transmits = false; /* the default parameters are black */
    m->specular = false;  /* no component */
}

svet_status material_init(material_t *m, const material_params *p,
                          svet_error *err)
{
    make_black(m);
    brdf_t d, s, g, t, dt;
    /* Each constructor checks its own parameters; the glossy one only when
     * it is used, so that a material without gloss needs no valid e. */
    if (brdf_lambert(&d, p->rho_d, err) != SVET_OK ||
        brdf_mirror(&s, p->rho_s, p->eta, err) != SVET_OK ||
        brdf_specular_transmission(&t, p->rho_t, p->eta, err) != SVET_OK ||
        brdf_diffuse_transmission(&dt, p->rho_dt, err) != SVET_OK)
        return SVET_ERR_RANGE;
    svet_status st = SVET_OK;
    if (p->gloss == MATERIAL_GLOSS_PHONG)
        st = brdf_phong(&g, p->rho_g, p->e, err);
    else if (p->gloss == MATERIAL_GLOSS_WARD ||
             p->gloss == MATERIAL_GLOSS_WARD_BOUNDED)
        st = brdf_ward(&g, p->rho_g, p->alpha_x, p->alpha_y,
                       p->gloss == MATERIAL_GLOSS_WARD_BOUNDED, err);
    else
        st = svet_error_set(err, SVET_ERR_RANGE, "unknown gloss model %d",
                            (int)p->gloss);
    if (st != SVET_OK && !is_black(p->rho_g))
        return SVET_ERR_RANGE;
    if (check_sum(p, err) != SVET_OK)
        return SVET_ERR_RANGE;

    /* The Fresnel coupling (material.h): Schlick's curve of the mirror
     * rises to what the angle-independent components leave. */
    bool interface = !is_black(p->rho_s) || !is_black(p->rho_t);
    RADIANCE rest = rad_add(rad_add(p->rho_d, p->rho_g), p->rho_dt);
    s.rho90 = rad_make(fmax(1 - rest.r, p->rho_s.r),
                       fmax(1 - rest.g, p->rho_s.g),
                       fmax(1 - rest.b, p->rho_s.b));

    s.exact = t.exact = p->fresnel_exact;
    m->params = *p;
    add(m, &d);
    if (interface)
        add(m, &s);
    if (st == SVET_OK)
        add(m, &g);
    add(m, &t);
    add(m, &dt);
    m->lambert = m->ncomp == 1 && m->comp[0].kind == BRDF_LAMBERT;
    m->transmits = !is_black(p->rho_t) || !is_black(p->rho_dt);
    m->specular = all_delta(m);
    if (err)
        svet_error_clear(err);
    return SVET_OK;
}

svet_status material_new(const material_params *p, material_t **out,
                         svet_error *err)
{
    *out = NULL;
    material_t *m = malloc(sizeof *m);
    if (!m)
        return svet_error_set(err, SVET_ERR_NOMEM, "out of memory for a "
                              "material");
    svet_status st = material_init(m, p, err);
    if (st != SVET_OK) {
        free(m);
        return st;
    }
    *out = m;
    return SVET_OK;
}

void material_free(material_t *m)
{
    free(m);
}

svet_status material_lambert(material_t *m, RADIANCE rho_d, svet_error *err)
{
    material_params p;
    material_params_default(&p);
    p.rho_d = rho_d;
    return material_init(m, &p, err);
}

svet_status material_phong(material_t *m, RADIANCE rho_d, RADIANCE rho_g,
                           real e, svet_error *err)
{
    material_params p;
    material_params_default(&p);
    p.rho_d = rho_d;
    p.rho_g = rho_g;
    p.e = e;
    return material_init(m, &p, err);
}

svet_status material_ward(material_t *m, RADIANCE rho_d, RADIANCE rho_g,
                          real alpha_x, real alpha_y, svet_error *err)
{
    material_params p;
    material_params_default(&p);
    p.rho_d = rho_d;
    p.rho_g = rho_g;
    p.gloss = MATERIAL_GLOSS_WARD_BOUNDED;
    p.alpha_x = alpha_x;
    p.alpha_y = alpha_y;
    return material_init(m, &p, err);
}

svet_status material_mirror(material_t *m, RADIANCE rho_s, svet_error *err)
{
    material_params p;
    material_params_default(&p);
    p.rho_s = rho_s;
    return material_init(m, &p, err);
}

svet_status material_glass(material_t *m, RADIANCE rho_s, RADIANCE rho_t,
                           real eta, svet_error *err)
{
    material_params p;
    material_params_default(&p);
    p.rho_s = rho_s;
    p.rho_t = rho_t;
    p.eta = eta;
    return material_init(m, &p, err);
}

/* --- evaluation and sampling --------------------------------------------- */

RADIANCE material_eval(const material_t *m, const VECTOR3 wi,
                       const VECTOR3 wo)
{
    /* a single Lambert lobe: the loop below with its one term */
    if (m->lambert)
        return rad_add(black, brdf_eval(&m->comp[0], wi, wo));
    /* the book's f = f_r^s + f_r^d + f_r^g + f_t^s + f_t^d; the delta terms
     * are zero away from their one direction */
    RADIANCE f = black;
    for (int k = 0; k < m->ncomp; k++)
        if (!brdf_is_delta(&m->comp[k]))
            f = rad_add(f, brdf_eval(&m->comp[k], wi, wo));
    return f;
}

/* The selection weights Y_k at wo and their sum. */
static real weights(const material_t *m, const VECTOR3 wo,
                    real w[MATERIAL_MAX_COMPONENTS])
{
    real sum = 0;
    for (int k = 0; k < m->ncomp; k++) {
        w[k] = rad_luminance(brdf_nominal(&m->comp[k], wo));
        sum += w[k];
    }
    return sum;
}

/* sum over non-delta k of P_k pdf_k(wi, wo), the weights given */
static real combined_pdf(const material_t *m, const real w[], real sum,
                         const VECTOR3 wi, const VECTOR3 wo)
{
    real pdf = 0;
    for (int k = 0; k < m->ncomp; k++)
        if (w[k] > 0 && !brdf_is_delta(&m->comp[k]))
            pdf += w[k] / sum * brdf_pdf(&m->comp[k], wi, wo);
    return pdf;
}

/* The shortcuts for a single Lambert lobe of reflectance rho, and why
 * they give the general answers bit for bit. Its weight is w = Y(rho) and
 * the sum of the weights 0 + w = w; the general code gives up unless
 * w > 0, and then chooses it with probability w / w = 1 exactly (a finite
 * nonzero number divided by itself). Its combined pdf is 0 + 1 * pdf =
 * pdf, as pdf >= +0 (|cos| / pi or 0). Its one-sample MIS weight is
 * f |cos| / pdf with f = 0 + rho / pi, kept as written: rho may hold a
 * -0, which 0 + turns into +0. */
static real lambert_pdf(const material_t *m, const VECTOR3 wi,
                        const VECTOR3 wo)
{
    if (!(rad_luminance(m->comp[0].rho) > 0))
        return 0;
    return brdf_pdf(&m->comp[0], wi, wo);
}

/* material_sample for one Lambert lobe, s already cleared. brdf_sample
 * of Lambert draws wi cosine-weighted on wo's side, and rejects it within
 * BRDF_COS_MIN of the tangent plane; given that, wi and wo lie on the same
 * side, so brdf_pdf is |wi_z| / pi and brdf_eval rho / pi. */
static bool lambert_sample(const material_t *m, const VECTOR3 wo,
                           const real u[3], brdf_sample_t *s)
{
    const RADIANCE rho = m->comp[0].rho;
    if (!(rad_luminance(rho) > 0))
        return false; /* also when rho is black: brdf_sample's test */
    VECTOR3 wi;
    sample_cosine_hemisphere(wi, u + 1); /* about +z */
    if (wo[Z] < 0)
        wi[Z] = -wi[Z];
    real c = fabs(wi[Z]);
    if (c < BRDF_COS_MIN)
        return false;
    vec_copy(s->wi, wi);
    s->pdf = c * REAL_INV_PI;
    RADIANCE f = rad_add(black, rad_scale(rho, REAL_INV_PI));
    s->weight = rad_scale(f, c / s->pdf);
    return true;
}

/* For a single Lambert lobe, material_eval() is 0 + brdf_eval() and
 * material_pdf() is lambert_pdf(); brdf_eval() and brdf_pdf() of Lambert
 * are rho / pi and |wi_z| / pi where brdf_same_side(), else black and 0:
 * written out here on one side test, the same operations. */
RADIANCE material_eval_pdf(const material_t *m, const VECTOR3 wi,
                           const VECTOR3 wo, real *pdf)
{
    if (m->lambert) {
        const RADIANCE rho = m->comp[0].rho;
        if (!brdf_same_side(wi, wo)) {
            if (pdf)
                *pdf = 0;
            return black; /* 0 + 0 */
        }
        if (pdf)
            *pdf = rad_luminance(rho) > 0 ? fabs(wi[Z]) * REAL_INV_PI : 0;
        return rad_add(black, rad_scale(rho, REAL_INV_PI));
    }
    if (pdf)
        *pdf = material_pdf(m, wi, wo);
    return material_eval(m, wi, wo);
}

real material_pdf(const material_t *m, const VECTOR3 wi, const VECTOR3 wo)
{
    if (m->lambert)
        return lambert_pdf(m, wi, wo);
    real w[MATERIAL_MAX_COMPONENTS];
    real sum = weights(m, wo, w);
    if (!(sum > 0))
        return 0;
    return combined_pdf(m, w, sum, wi, wo);
}

/* Fill s with what material_sample() answers on false (wi = +z, weight
 * black, pdf 0); false when wo lies in the tangent plane, where it
 * answers so at once. */
static inline bool sample_start(const VECTOR3 wo, brdf_sample_t *s)
{
    vec_set(s->wi, 0, 0, 1);
    s->weight = black;
    s->pdf = 0;
    s->delta = false;
    s->component = 0;
    return fabs(wo[Z]) >= BRDF_COS_MIN;
}

/* material_sample() without its shortcut for a single Lambert lobe: the
 * same answers, bit for bit, for any material (tests/materials/test_material.c
 * compares material_sample() on a material with m->lambert cleared). */
static bool sample_general(const material_t *m, const VECTOR3 wo,
                           const real u[3], brdf_sample_t *s)
{
    if (!sample_start(wo, s))
        return false;
    real w[MATERIAL_MAX_COMPONENTS];
    real sum = weights(m, wo, w);
    if (!(sum > 0))
        return false;

    /* Choose component k with probability w[k] / sum by u[0]. Rounding of
     * the running sum could leave u[0] * sum beyond the last one: then
     * the last component of nonzero weight is taken. */
    real target = u[0] * sum, acc = 0;
    int k = -1;
    for (int j = 0; j < m->ncomp; j++) {
        if (!(w[j] > 0))
            continue;
        k = j;
        acc += w[j];
        if (target < acc)
            break;
    }
    const brdf_t *b = &m->comp[k];
    real p_k = w[k] / sum;
    brdf_sample_t c;
    if (!brdf_sample(b, wo, u + 1, &c))
        return false;
    s->component = k;
    vec_copy(s->wi, c.wi);
    if (c.delta) {
        /* the delta term alone: rho_k(theta) / P_k */
        s->weight = rad_scale(c.weight, 1 / p_k);
        s->pdf = p_k;
        s->delta = true;
        return true;
    }
    /* One-sample MIS with the balance heuristic over the components
     * (Veach 1997, sec. 9.2.4): the estimate f(wi) cos / sum_j P_j pdf_j
     * needs only the combined density of wi, whichever lobe drew it. */
    s->pdf = combined_pdf(m, w, sum, c.wi, wo);
    if (!(s->pdf > 0))
        return false;
    RADIANCE f = material_eval(m, c.wi, wo);
    s->weight = rad_scale(f, fabs(c.wi[Z]) / s->pdf);
    return true;
}

bool material_sample(const material_t *m, const VECTOR3 wo, const real u[3],
                     brdf_sample_t *s)
{
    /* the general way in a function of its own, so that the shortcut's
     * path saves none of the registers that one needs */
    if (!m->lambert)
        return sample_general(m, wo, u, s);
    return sample_start(wo, s) && lambert_sample(m, wo, u, s);
}
