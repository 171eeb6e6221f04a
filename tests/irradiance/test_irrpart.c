/*
 * test_irrpart.c - tests of the irradiance part (src/irradiance/irrpart.c):
 * the `irradiance` statement's messages; exact answers inside a closed
 * sphere (pbrt-v3's analytic scene) and a closed box (the mean irradiance
 * Phi / (A (1 - rho))); the records' rotational and translational
 * gradients (app. E, Ward & Heckbert 1992) against finite differences of
 * a brute-force hemisphere integral of an independent model of the scene,
 * on a floor under a sphere and in a corner; no leak through a thin wall;
 * lookups no record covers gathering afresh, and the log's counts of
 * records, lookups and records per lookup; the same bits for any thread
 * count; the cache approaching fresh gathers,
 * and the Cornell box approaching the path tracer, as a falls; with
 * `render light indirect` the Cornell box's indirect light against the
 * path tracer's (and not twice it), none on a plane under a light, and
 * the setting refused where a method does not separate it.
 */
#include "testutil.h"
#include "scenecheck.h"
#include "core/rng.h"
#include "irradiance/gradients.h"
#include "irradiance/irrpart.h"
#include "render/allparts.h"
#include "render/render.h"
#include "render/scenefile.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI_D 3.14159265358979323846

/* --- the statement ---------------------------------------------------------- */

static const char base[] =
    "camera position 0 0 0 target 0 0 -1 up 0 1 0 width 4 height 4\n"
    "material wall lambert rho 0.5\n"
    "sphere centre 0 0 0 radius 1 material wall\n";

/* line 4 refused, with its column and what it names */
static void refused(const char *line, const char *where, const char *what)
{
    char text[512];
    snprintf(text, sizeof text, "%s%s\n", base, line);
    scene_t s;
    svet_error e;
    ck_assert_int_ne(scenecheck_parse(&s, text, &e), SVET_OK);
    ck_assert_msg(strstr(e.msg, where) && strstr(e.msg, what), "%s: %s",
                  line, e.msg);
}

START_TEST(irradiance_statement_messages)
{
    refused("irradiance a 0", "t.scn:4:12:", "'a'");
    refused("irradiance a 1.5", "t.scn:4:12:", "(0, 1]");
    refused("irradiance a nan", "t.scn:4:14:", "a");
    refused("irradiance m 0", "t.scn:4:14:", "'m'");
    refused("irradiance n 5000", "t.scn:4:14:", "'n'");
    refused("irradiance min_r -1", "t.scn:4:12:", "min_r");
    refused("irradiance max_r 0", "t.scn:4:12:", "max_r");
    refused("irradiance min_r 5 max_r 2", "t.scn:4:20:", "exceeds");
    refused("irradiance bounces 0", "t.scn:4:20:", "bounces");
    refused("irradiance gradients maybe", "t.scn:4:22:", "gradients");
    refused("irradiance clamp", "t.scn:4:17:", "clamp");
    refused("irradiance m 1024 n 4096", "t.scn:4:19:", "65536");
    /* the gather's size over two lines, and over the default n = 32 */
    refused("irradiance m 1024\nirradiance n 4096", "t.scn:5:12:", "65536");
    refused("irradiance m 1024 n 65", "t.scn:4:19:", "65536");
    refused("irradiance acc 0.1", "t.scn:4:12:", "unknown");
    scene_t s;
    svet_error e;
    scenecheck_parse_ok(&s, base);
    ck_assert_int_eq(scenefile_override(&s, "irradiance.a=0.3", &e), SVET_OK);
    ck_assert_int_eq(scenefile_override(&s, "irradiance.gradients=off", &e),
                     SVET_OK);
    irr_settings_t set;
    irr_settings_of(&s, &set);
    ck_assert(fabs((double)set.a - 0.3) < 1e-6);
    ck_assert(!set.gradients);
    ck_assert_int_eq(set.m, 8);
    /* --set is checked against the settings the scene already has */
    ck_assert_int_eq(scenefile_override(&s, "irradiance.n=4096", &e),
                     SVET_OK);
    ck_assert_int_ne(scenefile_override(&s, "irradiance.m=17", &e), SVET_OK);
    ck_assert_msg(strstr(e.msg, "65536"), "%s", e.msg);
    ck_assert_int_eq(scenefile_override(&s, "irradiance.n=32", &e), SVET_OK);
    ck_assert_int_ne(scenefile_override(&s, "irradiance.max_r=0.5", &e),
                     SVET_OK);
    ck_assert_int_eq(scenefile_override(&s, "integrator=irradiance", &e),
                     SVET_OK);
    scene_free(&s);
}
END_TEST

/* --- a scene set up for the method --------------------------------------- */

typedef struct {
    scene_t s;
    render_t r;
    void *state;
} setup_t;

static void setup(setup_t *u, const char *text, int threads)
{
    svet_error e;
    scenecheck_parse_ok(&u->s, text);
    ck_assert_msg(render_init(&u->r, &u->s, &e) == SVET_OK, "%s", e.msg);
    ck_assert_msg(irr_method.prepare(&u->state, &u->r, threads, &e) ==
                      SVET_OK, "%s", e.msg);
}

static void teardown(setup_t *u)
{
    irr_method.free(u->state);
    render_free(&u->r);
    scene_free(&u->s);
}

/* --- exact answers ------------------------------------------------------- */

/* Inside a closed sphere of radius 1 and albedo rho with a point light of
 * intensity I at its centre, the direct irradiance is I everywhere and
 * the wall's radiance is the same everywhere, so a gather path that
 * counts B diffuse vertices brings E = I (rho + ... + rho^B), and
 * I rho / (1 - rho) as B grows (pbrt-v3's analytic scene). Every gather
 * ray hits the wall, whose point light is sampled exactly and whose
 * Lambert weight is rho: the estimate has no variance, and the tolerance
 * is float's rounding. */
static void sphere_case(int bounces, double rho)
{
    char text[1024];
    snprintf(text, sizeof text,
             "camera position 0 0 0 target 0 0 -1 up 0 1 0 fov 90 "
             "width 16 height 16\n"
             "render maxdepth 100 integrator irradiance\n"
             "irradiance m 4 n 16 bounces %d a 0.2\n"
             "material wall lambert rho %g\n"
             "sphere centre 0 0 0 radius 1 material wall\n"
             "light point position 0 0 0 intensity 2\n", bounces, rho);
    setup_t u;
    setup(&u, text, 0);
    double exact = 0, p = 1;
    for (int k = 1; k <= bounces; k++)
        exact += 2 * (p *= rho);
    ck_assert_uint_gt(irr_state_cache(u.state)->n, 0);
    for (int y = 0; y < 16; y += 3)
        for (int x = 0; x < 16; x += 3) {
            RADIANCE c, g;
            bool found = false;
            ck_assert(irr_pixel_irradiance(u.state, &u.r, x, y, 1, &c,
                                           &found, &g));
            ck_assert(found);
            ck_assert_msg(fabs((double)c.g - exact) < 1e-3 * exact &&
                              fabs((double)g.g - exact) < 1e-3 * exact,
                          "B = %d at (%d, %d): cache %g, gather %g, exact %g",
                          bounces, x, y, (double)c.g, (double)g.g, exact);
        }
    teardown(&u);
}

START_TEST(closed_sphere_has_the_exact_irradiance)
{
    sphere_case(1, 0.5);
    sphere_case(2, 0.5);
    sphere_case(40, 0.5); /* 0.5^41 / 0.5 below float's rounding */
}
END_TEST

/* Two rooms side by side under an open sky, a point light in the left
 * one below the top of the wall between them: no straight path leads
 * from the left room into the right one (a ray must rise to cross the
 * wall's top and then keeps rising), so the right room is black, exactly.
 * Seen from above, every pixel right of the wall must be 0: any light
 * there leaked through the cache. With R forced large and neighbour
 * clamping off the same check sees the leak, so it can fail. */
static const char rooms[] =
    "camera position 0 6 0.001 target 0 0 0 up 0 0 -1 fov 60 "
    "width 24 height 24\n"
    "render maxdepth 8 integrator irradiance seed 3\n"
    "material wall lambert rho 0.7\n"
    "box min -2 -0.1 -1 max 2 0 1 material wall\n"      /* floor */
    "box min -0.02 0 -1 max 0.02 1 1 material wall\n"   /* the thin wall */
    "box min -2.1 0 -1 max -2 1 1 material wall\n"
    "box min 2 0 -1 max 2.1 1 1 material wall\n"
    "box min -2 0 -1.1 max 2 1 -1 material wall\n"
    "box min -2 0 1 max 2 1 1.1 material wall\n"
    "light point position -1 0.5 0 intensity 4\n";

static double right_room_light(const char *settings, double *left)
{
    char text[2048];
    snprintf(text, sizeof text, "%s%s\n", rooms, settings);
    setup_t u;
    setup(&u, text, 0);
    double right = 0;
    *left = 0;
    for (int y = 0; y < 24; y++)
        for (int x = 0; x < 24; x++) {
            RADIANCE c;
            bool found;
            if (!irr_pixel_irradiance(u.state, &u.r, x, y, 1, &c, &found,
                                      NULL))
                continue;
            if (x >= 13)
                right += (double)c.g;
            else if (x <= 10)
                *left += (double)c.g;
        }
    teardown(&u);
    return right;
}

START_TEST(no_light_leaks_through_a_thin_wall)
{
    double left;
    double right = right_room_light("irradiance m 4 n 16", &left);
    ck_assert_msg(left > 0, "the lit room is dark");
    ck_assert_msg(right == 0, "light leaked into the dark room: %g "
                  "(lit room %g)", right, left);
    right = right_room_light("irradiance m 4 n 16 min_r 40 max_r 40 "
                             "clamp off", &left);
    ck_assert_msg(right > 0, "no leak with R forced large: the check "
                  "cannot see one");
}
END_TEST

/* --- the closed box ------------------------------------------------------ */

/* Inside a closed cube of side 2 and albedo rho with a point light of
 * intensity I at its centre, every photon lands on a wall and a fraction
 * rho of what lands is reflected onto the walls again, so the mean
 * irradiance over the walls, of area A = 24, is Phi / (A (1 - rho)) with
 * Phi = 4 pi I; its direct part is Phi / A, and a gather path of B
 * diffuse vertices brings the mean indirect irradiance
 * Phi / A (rho + ... + rho^B), Phi rho / (A (1 - rho)) as B grows. The
 * camera at the centre with a field of 90 degrees sees exactly the back
 * wall, its pixel centres a uniform grid on it, and by the cube's symmetry
 * the back wall's mean is every wall's: the mean over the pixels is the
 * midpoint rule of the wall's mean, whose own error is measured on the
 * direct irradiance I / d^3, known everywhere. */
static void closed_box_case(int bounces, double rho, double a)
{
    enum { W = 24 };
    const double intensity = 3;
    char text[1024];
    snprintf(text, sizeof text,
             "camera position 0 0 0 target 0 0 -1 up 0 1 0 fov 90 "
             "width %d height %d\n"
             "render maxdepth 100 integrator irradiance seed 5\n"
             "irradiance m 8 n 32 bounces %d a %g\n"
             "material wall lambert rho %g\n"
             "box min -1 -1 -1 max 1 1 1 material wall\n"
             "light point position 0 0 0 intensity %g\n", W, W, bounces, a,
             rho, intensity);
    setup_t u;
    setup(&u, text, 0);
    double geo = 0, p = 1;
    for (int k = 1; k <= bounces; k++)
        geo += (p *= rho);
    const double direct_mean = 4 * PI_D * intensity / 24;
    const double exact = direct_mean * geo;
    double cache = 0, gathers = 0, var = 0, direct = 0;
    int n = 0;
    for (int y = 0; y < W; y++)
        for (int x = 0; x < W; x++) {
            RADIANCE c, g1, g2;
            bool found;
            ck_assert(irr_pixel_irradiance(u.state, &u.r, x, y, 1, &c,
                                           &found, &g1));
            irr_pixel_irradiance(u.state, &u.r, x, y, 2, NULL, NULL, &g2);
            /* a point no record covers (neighbour clamping may shrink a
             * record after it kept a candidate out) is gathered afresh,
             * as the image's pass does */
            cache += found ? (double)c.g : (double)g1.g;
            gathers += ((double)g1.g + (double)g2.g) / 2;
            /* one gather's variance from two independent ones */
            var += ((double)g1.g - (double)g2.g) *
                   ((double)g1.g - (double)g2.g) / 2;
            double px = -1 + (2 * x + 1) / (double)W,
                   py = -1 + (2 * y + 1) / (double)W;
            double d = sqrt(px * px + py * py + 1);
            direct += intensity / (d * d * d);
            n++;
        }
    cache /= n;
    gathers /= n;
    var /= n;
    direct /= n;
    double quad = fabs(direct - direct_mean) * geo; /* the midpoint rule */
    /* the mean of 2 n independent gathers: its standard error */
    double se = sqrt(var / (2.0 * n));
    ck_assert_msg(fabs(gathers - exact) < 4 * se + quad,
                  "B = %d: gathers' mean %g, exact %g (se %g, rule %g)",
                  bounces, gathers, exact, se, quad);
    /* the cache: Ward's weight bounds the first-order relative error of a
     * record used where w > 1 / a by a (Ward et al. 1988, sec. 2.2), and
     * its records' noise is at most one gather's */
    double tol = a * exact + 4 * sqrt(var) + quad;
    ck_assert_msg(fabs(cache - exact) < tol,
                  "B = %d: cache's mean %g, exact %g (tolerance %g)",
                  bounces, cache, exact, tol);
    /* a quarter too much or too little is seen */
    ck_assert(tol < 0.25 * exact);
    teardown(&u);
}

START_TEST(closed_box_has_the_exact_mean_irradiance)
{
    closed_box_case(1, 0.5, 0.1);
    closed_box_case(3, 0.5, 0.1);
    closed_box_case(12, 0.3, 0.1); /* the rest, 0.3^13 / 0.7 = 2e-7: float */
}
END_TEST

/* --- gradients against finite differences -------------------------------- */

/* An independent model of what a gather ray with `bounces 1` sees, in
 * double: the first hit among axis-aligned rectangles and spheres, and
 * there the radiance rho / pi I |cos| / d^2 of a Lambert surface lit by a
 * point light of intensity I (0 where the light is behind it as seen from
 * the ray, or shadowed). */
typedef struct {
    int kind;          /* 0: rectangle with normal along axis `axis`, 1: sphere */
    int axis;          /* rectangle: its normal axis; at coordinate `at` */
    double at, lo[3], hi[3];
    double c[3], r;    /* sphere */
} prim_t;

typedef struct {
    const prim_t *p;
    int n;
    double light[3], intensity, rho;
} model_t;

static double dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* the nearest hit along o + t d, t > eps: its t (INFINITY: none), prim and
 * unit normal */
static double model_hit(const model_t *m, const double *o, const double *d,
                        double tmax, int *which, double *nrm)
{
    double best = tmax;
    *which = -1;
    for (int i = 0; i < m->n; i++) {
        const prim_t *p = &m->p[i];
        double t;
        if (p->kind == 0) {
            int ax = p->axis;
            if (d[ax] == 0)
                continue;
            t = (p->at - o[ax]) / d[ax];
            if (!(t > 1e-9 && t < best))
                continue;
            bool in = true;
            for (int k = 0; k < 3; k++)
                if (k != ax) {
                    double q = o[k] + t * d[k];
                    in = in && q >= p->lo[k] && q <= p->hi[k];
                }
            if (!in)
                continue;
        } else {
            double oc[3] = { o[0] - p->c[0], o[1] - p->c[1], o[2] - p->c[2] };
            double b = dot3(oc, d), cc = dot3(oc, oc) - p->r * p->r;
            double disc = b * b - cc;
            if (disc < 0)
                continue;
            double sq = sqrt(disc);
            t = -b - sq;
            if (!(t > 1e-9))
                t = -b + sq;
            if (!(t > 1e-9 && t < best))
                continue;
        }
        best = t;
        *which = i;
    }
    if (*which < 0)
        return (double)INFINITY;
    const prim_t *p = &m->p[*which];
    if (p->kind == 0) {
        nrm[0] = nrm[1] = nrm[2] = 0;
        nrm[p->axis] = 1;
    } else {
        for (int k = 0; k < 3; k++)
            nrm[k] = (o[k] + best * d[k] - p->c[k]) / p->r;
    }
    return best;
}

static double model_radiance(const model_t *m, const double *o,
                             const double *d, double *dist)
{
    int w;
    double nrm[3];
    double t = model_hit(m, o, d, (double)INFINITY, &w, nrm);
    *dist = t;
    if (w < 0)
        return 0;
    double q[3], l[3];
    for (int k = 0; k < 3; k++) {
        q[k] = o[k] + t * d[k];
        l[k] = m->light[k] - q[k];
    }
    double dl = sqrt(dot3(l, l));
    for (int k = 0; k < 3; k++)
        l[k] /= dl;
    double cl = dot3(nrm, l), cv = -dot3(nrm, d);
    if (cl * cv <= 0)
        return 0;
    int w2;
    double n2[3];
    /* the light's shadow ray, the hit's own primitive included (a sphere
     * is convex: cl's sign has said it) */
    model_hit(m, q, l, dl, &w2, n2);
    if (w2 >= 0 && w2 != w)
        return 0;
    return m->rho / PI_D * m->intensity * fabs(cl) / (dl * dl);
}

/* an orthonormal frame t1, t2 around the unit n */
static void frame3(const double *n, double *t1, double *t2)
{
    double a[3] = { 1, 0, 0 };
    if (fabs(n[0]) > 0.9) {
        a[0] = 0;
        a[1] = 1;
    }
    double s = dot3(a, n);
    for (int k = 0; k < 3; k++)
        t1[k] = a[k] - s * n[k];
    double l = sqrt(dot3(t1, t1));
    for (int k = 0; k < 3; k++)
        t1[k] /= l;
    t2[0] = n[1] * t1[2] - n[2] * t1[1];
    t2[1] = n[2] * t1[0] - n[0] * t1[2];
    t2[2] = n[0] * t1[1] - n[1] * t1[0];
}

/* Brute force: E(p, n) by the midpoint rule over mb x nb cosine-weighted
 * strata of the model; the same strata at every p and n, so that finite
 * differences do not see the rule's error change from place to place
 * more than the integrand does. */
static double brute_irradiance(const model_t *m, const double *p,
                               const double *n, int mb, int nb)
{
    double t1[3], t2[3];
    frame3(n, t1, t2);
    double sum = 0;
    for (int j = 0; j < mb; j++) {
        double s2 = (j + 0.5) / mb, st = sqrt(s2), ct = sqrt(1 - s2);
        for (int k = 0; k < nb; k++) {
            double phi = 2 * PI_D * (k + 0.5) / nb;
            double lx = st * cos(phi), ly = st * sin(phi), d[3], dist;
            for (int c = 0; c < 3; c++)
                d[c] = lx * t1[c] + ly * t2[c] + ct * n[c];
            sum += model_radiance(m, p, d, &dist);
        }
    }
    return PI_D * sum / ((double)mb * nb);
}

/* One jittered gather of app. E at (p, n) on the model, through
 * gradients_compute: the gradients' components along the world vectors
 * t (rotational) and t (translational), green channel. */
static void model_gradients(const model_t *m, const double *p,
                            const double *n, int mm, int nn, pcg32_t *g,
                            const double *t, double *gr_t, double *gt_t,
                            double *e)
{
    double t1[3], t2[3];
    frame3(n, t1, t2);
    RADIANCE *l = malloc(sizeof *l * (size_t)(mm * nn));
    real *dist = malloc(sizeof *dist * (size_t)(mm * nn));
    ck_assert(l && dist);
    for (int j = 0; j < mm; j++)
        for (int k = 0; k < nn; k++) {
            real u[2] = { pcg32_real(g), pcg32_real(g) };
            VECTOR3 w;
            gradients_direction(mm, nn, j, k, u, w);
            double d[3], dd;
            for (int c = 0; c < 3; c++)
                d[c] = (double)w[X] * t1[c] + (double)w[Y] * t2[c] +
                       (double)w[Z] * n[c];
            double len = sqrt(dot3(d, d));
            for (int c = 0; c < 3; c++)
                d[c] /= len;
            l[j * nn + k] = rad_grey((real)model_radiance(m, p, d, &dd));
            dist[j * nn + k] = (real)dd;
        }
    gradients_samples_t s = { mm, nn, l, dist };
    RADIANCE er;
    VECTOR3 gr[3], gt[3];
    real rm;
    gradients_compute(&s, &er, gr, gt, &rm);
    /* local (x, y) along t1, t2 */
    double grw[3], gtw[3];
    for (int c = 0; c < 3; c++) {
        grw[c] = (double)gr[1][X] * t1[c] + (double)gr[1][Y] * t2[c];
        gtw[c] = (double)gt[1][X] * t1[c] + (double)gt[1][Y] * t2[c];
    }
    *gr_t = dot3(grw, t);
    *gt_t = dot3(gtw, t);
    *e = (double)er.g;
    free(l);
    free(dist);
}

/* The cache's records on the model's rectangles (the floor, the corner's
 * wall), each of up to `want` records spread over the cache, checked
 * along both tangents: the record's gradient (the renderer's gather,
 * turned to the world's frame) against the central finite difference of
 * the brute-force irradiance at points (translational) or normals
 * (rotational) a step delta either side. The tolerance is 4 standard
 * deviations of one estimate (measured over K gathers of the record's
 * M x N on the model) plus the finite difference's own error, estimated
 * as the change from step delta to 2 delta (Richardson: the central
 * difference's error is a third of it, and the rule's error enters both).
 * The difference must be large beside that tolerance, so that a gradient
 * of the wrong sign or of zero is seen. The record keeps the gradient
 * its gather measured (the cache limits the translational one only as it
 * reads it, test_irrcache.c), so records the clamp raised are compared
 * too. Returns how many checks were made. */
/* the brute force's strata: its midpoint rule's error, and how it moves
 * from point to point, enter each tolerance through the change from step
 * delta to 2 delta */
enum { BM = 200, BN = 800 };
static int check_gradients(const char *text, const model_t *m, int want)
{
    setup_t u;
    setup(&u, text, 0);
    irr_settings_t set;
    irr_settings_of(&u.s, &set);
    const irrcache_t *c = irr_state_cache(u.state);
    ck_assert_uint_gt(c->n, 0);
    int checks = 0, used = 0, strong = 0;
    size_t stride = c->n / (size_t)(2 * want) + 1;
    for (size_t i = 0; i < c->n && used < want; i += stride) {
        const irr_record_t *rec = &c->rec[i];
        double p[3], n[3];
        for (int k = 0; k < 3; k++) {
            p[k] = (double)rec->p[k];
            n[k] = (double)rec->n[k];
        }
        int on = -1;
        for (int q = 0; q < m->n && on < 0; q++) {
            const prim_t *pr = &m->p[q];
            if (pr->kind == 0 && fabs(n[pr->axis]) > 0.999 &&
                fabs(p[pr->axis] - pr->at) < 1e-3)
                on = q;
        }
        if (on < 0)
            continue;
        const prim_t *pr = &m->p[on];
        p[pr->axis] = pr->at;
        for (int k = 0; k < 3; k++)
            n[k] = k == pr->axis ? (n[k] > 0 ? 1 : -1) : 0;
        double e0 = brute_irradiance(m, p, n, BM, BN);
        if (!(e0 > 0.05 * (double)rec->e.g + 1e-12) || e0 < 1e-3)
            continue;
        used++;
        double t1[3], t2[3];
        frame3(n, t1, t2);
        for (int axis = 0; axis < 2; axis++) {
            const double *t = axis ? t2 : t1;
            /* the estimator's spread at this point */
            enum { K = 16 };
            double sr = 0, sr2 = 0, st = 0, st2 = 0;
            for (int k = 0; k < K; k++) {
                pcg32_t g;
                pcg32_seed(&g, 300 + i, (uint64_t)(2 * k + axis));
                double gr, gt, e;
                model_gradients(m, p, n, set.m, set.n, &g, t, &gr, &gt, &e);
                sr += gr;
                sr2 += gr * gr;
                st += gt;
                st2 += gt * gt;
            }
            double sd_r = sqrt(fmax(0, (sr2 - sr * sr / K) / (K - 1)));
            double sd_t = sqrt(fmax(0, (st2 - st * st / K) / (K - 1)));
            double fd_t[2], fd_r[2];
            for (int h = 0; h < 2; h++) {
                double delta = 0.01 * (h + 1), pp[3], pm[3], np[3], nm[3];
                double txn[3] = { t[1] * n[2] - t[2] * n[1],
                                  t[2] * n[0] - t[0] * n[2],
                                  t[0] * n[1] - t[1] * n[0] };
                for (int k = 0; k < 3; k++) {
                    pp[k] = p[k] + delta * t[k];
                    pm[k] = p[k] - delta * t[k];
                    np[k] = n[k] * cos(delta) + txn[k] * sin(delta);
                    nm[k] = n[k] * cos(delta) - txn[k] * sin(delta);
                }
                fd_t[h] = (brute_irradiance(m, pp, n, BM, BN) -
                           brute_irradiance(m, pm, n, BM, BN)) /
                          (2 * delta);
                /* n x n_+ = sin(delta) t: E(n_+) = E + sin(delta) t . grad_r */
                fd_r[h] = (brute_irradiance(m, p, np, BM, BN) -
                           brute_irradiance(m, p, nm, BM, BN)) /
                          (2 * sin(delta));
            }
            double rec_t = 0, rec_r = 0;
            for (int k = 0; k < 3; k++) {
                rec_t += (double)rec->grad_t[1][k] * t[k];
                rec_r += (double)rec->grad_r[1][k] * t[k];
            }
            double tol_t = 4 * sd_t + fabs(fd_t[1] - fd_t[0]);
            double tol_r = 4 * sd_r + fabs(fd_r[1] - fd_r[0]);
            checks++;
            /* both estimators' bias at this M x N, from 4 gathers at
             * 4 M x 4 N */
            double fine_r = 0, fine_t = 0;
            for (int k = 0; k < 4; k++) {
                pcg32_t g;
                pcg32_seed(&g, 400 + i, (uint64_t)(2 * k + axis));
                double gr, gt, e;
                model_gradients(m, p, n, 4 * set.m, 4 * set.n, &g, t, &gr,
                                &gt, &e);
                fine_r += gr / 4;
                fine_t += gt / 4;
            }
            /* rotational: the record against the finite difference, within
             * the noise, the difference's error and the change of the
             * estimator's mean when its strata are refined */
            tol_r += fabs(sr / K - fine_r);
            ck_assert_msg(fabs(rec_r - fd_r[0]) < tol_r, "record %zu, "
                          "tangent %d: rotational %g, finite difference %g "
                          "(tolerance %g)", i, axis, rec_r, fd_r[0], tol_r);
            /* translational: the record is what app. E's estimator gives
             * on the model (one draw against K) */
            double mean_t = st / K;
            ck_assert_msg(fabs(rec_t - mean_t) < 4 * sd_t * sqrt(1 + 1.0 / K),
                          "record %zu, tangent %d: translational %g, the "
                          "estimator's mean %g (sd %g)", i, axis, rec_t,
                          mean_t, sd_t);
            /* and that estimator approaches the finite difference as the
             * strata are refined: Ward & Heckbert's translational
             * gradient is biased at finite M x N where the radiance
             * changes within strata (an edge, a near wall), and the bias
             * falls slowly (Jarosz, Schoenefeld, Kobbelt, Jensen, "Theory,
             * Analysis and Applications of 2D Global Illumination", ACM
             * TOG 2012, sec. 6); checked where the difference stands out
             * of the noise, at 4 M x 4 N */
            if (fabs(fd_t[0]) > 4 * tol_t) {
                double fine = fine_t;
                ck_assert_msg(fabs(fine - fd_t[0]) <= fabs(mean_t - fd_t[0]) +
                                  tol_t, "record %zu, tangent %d: "
                              "translational %g at M = %d, %g at %d, finite "
                              "difference %g", i, axis, mean_t, set.m, fine,
                              4 * set.m, fd_t[0]);
                ck_assert_msg(fine * fd_t[0] > 0 && fabs(fine - fd_t[0]) <
                                  0.25 * fabs(fd_t[0]),
                              "record %zu, tangent %d: translational %g at "
                              "M = %d, finite difference %g", i, axis, fine,
                              4 * set.m, fd_t[0]);
                strong++;
            }
            if (fabs(fd_r[0]) > 4 * tol_r)
                strong++;
        }
    }
    teardown(&u);
    /* gradients that stand out of the noise were checked, so a zero or a
     * wrong sign would have been seen */
    ck_assert_int_ge(strong, checks / 2);
    return checks;
}

START_TEST(gradients_match_finite_differences_on_a_floor_under_a_sphere)
{
    static const char text[] =
        "camera position 0 2.5 3 target 0 0.3 0 up 0 1 0 fov 50 "
        "width 16 height 16\n"
        "render maxdepth 4 integrator irradiance seed 1\n"
        "irradiance m 32 n 128 bounces 1 a 0.4\n"
        "material wall lambert rho 0.5\n"
        "parallelogram c0 -20 0 20 c1 20 0 20 c2 20 0 -20 c3 -20 0 -20 "
        "material wall\n"
        "sphere centre 0 1 0 radius 0.5 material wall\n"
        "light point position 1.5 0.6 0 intensity 5\n";
    static const prim_t prims[] = {
        { 0, 1, 0, { -20, 0, -20 }, { 20, 0, 20 }, { 0 }, 0 },
        { 1, 0, 0, { 0 }, { 0 }, { 0, 1, 0 }, 0.5 },
    };
    const model_t m = { prims, 2, { 1.5, 0.6, 0 }, 5, 0.5 };
    ck_assert_int_ge(check_gradients(text, &m, 4), 4);
}
END_TEST

START_TEST(gradients_match_finite_differences_in_a_corner)
{
    static const char text[] =
        "camera position 2.5 2 2.5 target 0 0.3 0 up 0 1 0 fov 50 "
        "width 16 height 16\n"
        "render maxdepth 4 integrator irradiance seed 1\n"
        "irradiance m 32 n 128 bounces 1 a 0.4\n"
        "material wall lambert rho 0.5\n"
        "parallelogram c0 0 0 30 c1 30 0 30 c2 30 0 -30 c3 0 0 -30 "
        "material wall\n"
        "parallelogram c0 0 0 -30 c1 0 0 30 c2 0 30 30 c3 0 30 -30 "
        "material wall\n"
        "light point position 1 1 0 intensity 5\n";
    static const prim_t prims[] = {
        { 0, 1, 0, { 0, 0, -30 }, { 30, 0, 30 }, { 0 }, 0 },
        { 0, 0, 0, { 0, 0, -30 }, { 0, 30, 30 }, { 0 }, 0 },
    };
    const model_t m = { prims, 2, { 1, 1, 0 }, 5, 0.5 };
    ck_assert_int_ge(check_gradients(text, &m, 4), 4);
}
END_TEST

/* --- the final pass: lookups no record covers, and the log ------------- */

/* The closed sphere of sphere_case at 8 x 8 pixels with a = 0.01: the
 * records' R is the sphere's radius 1 and neighbouring pixels' hits lie
 * 0.25 apart, so no record covers another pixel's point and the pre-pass
 * keeps one record per pixel, by its grid: 1 at step 16 (pixel (0, 0)),
 * none at step 8 (its only cell is (0, 0)), 4 - 1 at step 4, 16 - 4 at 2,
 * 64 - 16 at 1. Each of the 4 jittered camera samples of a pixel makes one
 * lookup (every camera ray hits the wall, and the path stops there), and
 * a sample covers a record only within a R = 0.01 of it: nearly every
 * lookup gathers afresh, and that gather, exact here (sphere_case), makes
 * every pixel rho / pi (E_direct + E_indirect). A lookup that returned
 * black, or a record's value, where nothing covers it would show as
 * rho / pi E_direct. */
START_TEST(uncovered_lookups_gather_afresh_and_the_log_counts_them)
{
    const double rho = 0.5;
    char text[1024];
    snprintf(text, sizeof text,
             "camera position 0 0 0 target 0 0 -1 up 0 1 0 fov 90 "
             "width 8 height 8\n"
             "render maxdepth 100 integrator irradiance seed 3\n"
             "irradiance m 4 n 16 bounces 2 a 0.01\n"
             "material wall lambert rho %g\n"
             "sphere centre 0 0 0 radius 1 material wall\n"
             "light point position 0 0 0 intensity 2\n", rho);
    scene_t s;
    svet_error e;
    scenecheck_parse_ok(&s, text);
    render_t r;
    ck_assert_msg(render_init(&r, &s, &e) == SVET_OK, "%s", e.msg);
    ck_assert_int_eq(render_pass(&r, 4, 1, NULL, NULL), SVET_OK);
    ck_assert(r.method == &irr_method && r.method_state);
    ck_assert_uint_eq(irr_state_cache(r.method_state)->n, 64);
    char log[512];
    r.method->report(r.method_state, log, sizeof log);
    ck_assert_msg(strstr(log, "irradiance cache: 64 records (1 at step 16, "
                              "0 at step 8, 3 at step 4, 12 at step 2, 48 "
                              "at step 1); 256 lookups, ") != NULL,
                  "%s", log);
    ck_assert_msg(strstr(log, "records per lookup 25 %") != NULL, "%s", log);
    unsigned long gathers = 0;
    const char *f = strstr(log, "lookups, ");
    ck_assert(f && sscanf(f, "lookups, %lu of them", &gathers) == 1);
    /* a sample within 0.01 of its pixel's record: well under a tenth */
    ck_assert_msg(gathers >= 230 && gathers <= 256, "%s", log);
    image_t img;
    ck_assert_int_eq(render_image(&r, &img, &e), SVET_OK);
    const double direct = 2, indirect = 2 * (rho + rho * rho);
    const double want = rho / PI_D * (direct + indirect);
    for (int y = 0; y < 8; y++)
        for (int x = 0; x < 8; x++) {
            RADIANCE c = image_get(&img, x, y);
            ck_assert_msg(fabs((double)c.g - want) < 1e-3 * want,
                          "pixel (%d, %d): %g, exact %g", x, y, (double)c.g,
                          want);
        }
    image_free(&img);
    render_free(&r);
    scene_free(&s);
}
END_TEST

/* --- determinism --------------------------------------------------------- */

static const char small_box[] =
    "camera position 0 0 3.9 target 0 0 0 up 0 1 0 fov 39.3 width 24 "
    "height 24\n"
    "render maxdepth 5 integrator irradiance\n"
    "irradiance m 4 n 12 a 0.3\n"
    "material white lambert rho 0.8\n"
    "material red lambert rho 0.6 0.05 0.05\n"
    "parallelogram c0 -1 -1 1 c1 1 -1 1 c2 1 -1 -1 c3 -1 -1 -1 "
    "material white\n"
    "parallelogram c0 -1 1 -1 c1 1 1 -1 c2 1 1 1 c3 -1 1 1 material white\n"
    "parallelogram c0 -1 -1 -1 c1 1 -1 -1 c2 1 1 -1 c3 -1 1 -1 "
    "material white\n"
    "parallelogram c0 1 -1 -1 c1 1 -1 1 c2 1 1 1 c3 1 1 -1 material white\n"
    "parallelogram c0 -1 -1 1 c1 -1 -1 -1 c2 -1 1 -1 c3 -1 1 1 "
    "material red\n"
    "box min -0.3 -1 -0.3 max 0.3 -0.2 0.3 material white\n"
    "light point position 0 0.8 0 intensity 2\n";

static void render_small(const char *text, int threads, long spp,
                         image_t *img)
{
    scene_t s;
    svet_error e;
    scenecheck_parse_ok(&s, text);
    render_t r;
    ck_assert_msg(render_init(&r, &s, &e) == SVET_OK, "%s", e.msg);
    ck_assert_int_eq(render_pass(&r, spp, threads, NULL, NULL), SVET_OK);
    ck_assert_int_eq(render_image(&r, img, &e), SVET_OK);
    render_free(&r);
    scene_free(&s);
}

START_TEST(the_same_bits_for_any_thread_count)
{
    setup_t a, b;
    setup(&a, small_box, 1);
    setup(&b, small_box, 2);
    const irrcache_t *ca = irr_state_cache(a.state),
                     *cb = irr_state_cache(b.state);
    ck_assert_uint_gt(ca->n, 0);
    ck_assert_uint_eq(ca->n, cb->n);
    ck_assert(memcmp(ca->rec, cb->rec, ca->n * sizeof *ca->rec) == 0);
    teardown(&a);
    teardown(&b);
    image_t x, y;
    render_small(small_box, 1, 2, &x);
    render_small(small_box, 2, 2, &y);
    ck_assert(memcmp(x.px, y.px, (size_t)x.width * (size_t)x.height * 3 *
                                     sizeof(float)) == 0);
    image_free(&x);
    image_free(&y);
}
END_TEST

/* --- convergence ------------------------------------------------------- */

/* The cache's irradiance against the mean of four fresh gathers of 8 x 32
 * rays at every pixel's first hit (the reference; the same rays for every
 * a, so its noise adds the same floor to each): the mean squared
 * difference must fall as a falls, 0.6 to 0.1, with more records. */
static double cache_error(double a, size_t *records)
{
    char text[4096];
    snprintf(text, sizeof text, "%sirradiance a %g m 8 n 32\n", small_box,
             a);
    setup_t u;
    setup(&u, text, 0);
    *records = irr_state_cache(u.state)->n;
    double s = 0;
    int n = 0;
    for (int y = 0; y < 24; y++)
        for (int x = 0; x < 24; x++) {
            RADIANCE c, g = rad_grey(0);
            bool found;
            if (!irr_pixel_irradiance(u.state, &u.r, x, y, 7, &c, &found,
                                      NULL))
                continue;
            double ref = 0;
            for (uint64_t k = 0; k < 4; k++) {
                irr_pixel_irradiance(u.state, &u.r, x, y, 8 + k, NULL, NULL,
                                     &g);
                ref += (double)g.g / 4;
            }
            double d = (double)c.g - ref;
            s += d * d;
            n++;
        }
    teardown(&u);
    return s / n;
}

START_TEST(the_cache_approaches_the_gathers_as_a_falls)
{
    size_t n1, n2;
    double e1 = cache_error(0.6, &n1), e2 = cache_error(0.1, &n2);
    ck_assert_uint_gt(n2, n1);
    ck_assert_msg(e2 < e1, "a 0.6: %zu records, error %g; a 0.1: %zu, %g",
                  n1, e1, n2, e2);
}
END_TEST

/* --- the Cornell box against the path tracer ------------------------------ */

/* scenes/cbox.scn at 24 x 24, rendered with `settings` and spp samples
 * per pixel: its mean image and the variance of each pixel's mean */
static void render_cbox(const char *const *settings, long spp, image_t *img,
                        image_t *var)
{
    scene_t s;
    svet_error e;
    ck_assert_msg(scenefile_read_with(&s, "scenes/cbox.scn",
                                      scene_features_all(), &e) == SVET_OK,
                  "%s", e.msg);
    ck_assert_int_eq(scenefile_override(&s, "resolution=24x24", &e), SVET_OK);
    for (int i = 0; settings[i]; i++)
        ck_assert_msg(scenefile_override(&s, settings[i], &e) == SVET_OK,
                      "%s: %s", settings[i], e.msg);
    render_t r;
    ck_assert_msg(render_init(&r, &s, &e) == SVET_OK, "%s", e.msg);
    ck_assert_int_eq(render_pass(&r, spp, 0, NULL, NULL), SVET_OK);
    ck_assert_int_eq(render_image(&r, img, &e), SVET_OK);
    ck_assert_int_eq(render_variance(&r, var, &e), SVET_OK);
    render_free(&r);
    scene_free(&s);
}

/* The mean over pixels and channels of the squared difference of image a
 * and the reference b, and of their summed variances (what noise alone
 * would give), over the pixels that do not see the light (b below 1 in
 * every channel: at the light's edge a pixel's variance dwarfs every
 * other's, and the cache does not change what the camera sees there) */
static void cbox_error(const image_t *a, const image_t *va, const image_t *b,
                       const image_t *vb, double *d2, double *noise,
                       double *noise_b)
{
    size_t n = (size_t)a->width * (size_t)a->height, used = 0;
    double s = 0, v = 0, w = 0;
    for (size_t i = 0; i < n; i++) {
        const float *p = b->px + 3 * i;
        if (p[0] >= 1 || p[1] >= 1 || p[2] >= 1)
            continue;
        for (int c = 0; c < 3; c++) {
            double d = (double)a->px[3 * i + c] - (double)p[c];
            s += d * d;
            v += (double)va->px[3 * i + c] + (double)vb->px[3 * i + c];
            w += (double)vb->px[3 * i + c];
        }
        used += 3;
    }
    ck_assert_uint_gt(used, n);
    *d2 = s / (double)used;
    *noise = v / (double)used;
    *noise_b = w / (double)used;
}

/* The Cornell box by the cache with as many bounces as the path tracer's
 * (maxdepth 7: 6 diffuse vertices after the first), at 4 samples per
 * pixel, against the path tracer at 1024. The expected squared difference
 * per pixel is the cache's bias squared plus both renders' variances of
 * the mean, which render_variance estimates (the cache's records are the
 * same for every sample, so their noise counts as bias). The squared
 * difference must fall as a falls, and at a = 0.1 the bias squared must
 * be below the variance of a pixel of the path tracer at 32 samples
 * (1024 / 32 times the reference's): the cache at 4 samples is then
 * closer to the converged image than the path tracer at 32 would be. */
START_TEST(the_cornell_box_converges_to_the_path_tracer_as_a_falls)
{
    static const char *const path[] = { "integrator=path", "seed=11", NULL };
    image_t ref, vref;
    render_cbox(path, 1024, &ref, &vref);
    const double as[] = { 0.5, 0.25, 0.1 };
    double d2s[3], bias2[3], noise_ref = 0;
    for (int k = 0; k < 3; k++) {
        char a[32];
        snprintf(a, sizeof a, "irradiance.a=%g", as[k]);
        const char *const set[] = { "integrator=irradiance", a,
                                    "irradiance.bounces=6", NULL };
        image_t img, var;
        render_cbox(set, 4, &img, &var);
        double d2, noise;
        cbox_error(&img, &var, &ref, &vref, &d2, &noise, &noise_ref);
        d2s[k] = d2;
        bias2[k] = d2 - noise;
        image_free(&img);
        image_free(&var);
    }
    image_free(&ref);
    image_free(&vref);
    ck_assert_msg(d2s[2] < d2s[1] && d2s[2] < d2s[0], "squared differences "
                  "%g, %g, %g at a = 0.5, 0.25, 0.1", d2s[0], d2s[1], d2s[2]);
    ck_assert_msg(bias2[2] < noise_ref * 1024 / 32, "a 0.1: the cache's "
                  "squared error %g, the path tracer's variance at 32 "
                  "samples %g", bias2[2], noise_ref * 1024 / 32);
}
END_TEST

/* `render light indirect`: the cache's E rho / pi at the first diffuse
 * vertex alone, against the path tracer's indirect light (integrator.c)
 * at 1024 samples, as above; the cache at a = 0.1 and 4 samples must lie
 * closer to it than the path tracer at 128 samples would (its bias
 * squared below that variance: about the requirement's 100 samples), and
 * an image with twice the cache's indirect light must not. */
static double indirect_bias2(const image_t *img, const image_t *var,
                             const image_t *ref, const image_t *vref,
                             double *noise_ref)
{
    double d2, noise;
    cbox_error(img, var, ref, vref, &d2, &noise, noise_ref);
    return d2 - noise;
}

START_TEST(the_indirect_light_agrees_with_the_path_tracer)
{
    static const char *const path[] = { "integrator=path", "seed=11",
                                         "light=indirect", NULL };
    static const char *const set[] = { "integrator=irradiance",
                                       "irradiance.a=0.1",
                                       "irradiance.bounces=6",
                                       "light=indirect", NULL };
    image_t ref, vref, img, var;
    render_cbox(path, 1024, &ref, &vref);
    render_cbox(set, 4, &img, &var);
    double noise_ref, b2 = indirect_bias2(&img, &var, &ref, &vref,
                                          &noise_ref);
    double limit = noise_ref * 1024 / 128;
    size_t n = (size_t)img.width * (size_t)img.height * 3;
    double mean = 0, mean_ref = 0;
    for (size_t i = 0; i < n; i++) {
        mean += (double)img.px[i] / (double)n;
        mean_ref += (double)ref.px[i] / (double)n;
    }
    ck_assert_msg(b2 < limit, "the cache's squared error %g, the path "
                  "tracer's variance at 128 samples %g (means %g, %g)", b2,
                  limit, mean, mean_ref);
    for (size_t i = 0; i < n; i++) {
        img.px[i] *= 2;
        var.px[i] *= 4;
    }
    b2 = indirect_bias2(&img, &var, &ref, &vref, &noise_ref);
    ck_assert_msg(b2 > limit, "twice the indirect light: squared error %g, "
                  "below %g", b2, limit);
    image_free(&img);
    image_free(&var);
    image_free(&ref);
    image_free(&vref);
}
END_TEST

/* A plane under a point light has no bounce light: with `light
 * indirect` every pixel is black, without it none that sees the plane. */
START_TEST(no_indirect_light_on_a_plane_under_a_light)
{
    static const char plane[] =
        "camera position 0 0 3 target 0 0 0 up 0 1 0 fov 30 width 12 "
        "height 12\n"
        "render spp 4 maxdepth 5 integrator irradiance light %s\n"
        "irradiance m 4 n 12\n"
        "material white lambert rho 0.8\n"
        "parallelogram c0 -4 -4 0 c1 4 -4 0 c2 4 4 0 c3 -4 4 0 "
        "material white\n"
        "light point position 0 0 2 intensity 2\n";
    for (int ind = 0; ind < 2; ind++) {
        char text[1024];
        snprintf(text, sizeof text, plane, ind ? "indirect" : "all");
        image_t img;
        scenecheck_render(text, 0, &img);
        size_t n = (size_t)img.width * (size_t)img.height * 3;
        for (size_t i = 0; i < n; i++)
            if (ind)
                ck_assert_msg(img.px[i] == 0, "value %zu: %g", i,
                              (double)img.px[i]);
            else
                ck_assert_msg(img.px[i] > 0, "value %zu: %g", i,
                              (double)img.px[i]);
        image_free(&img);
    }
}
END_TEST

/* `render light indirect` where the method does not separate it */
START_TEST(indirect_light_refused_where_not_separated)
{
    scene_t s;
    svet_error e;
    scenecheck_parse_ok(&s, "camera position 0 0 3 target 0 0 0 up 0 1 0\n"
                            "render integrator ao light indirect\n"
                            "material m lambert rho 0.5\n"
                            "sphere centre 0 0 0 radius 1 material m\n");
    render_t r;
    ck_assert_int_eq(render_init(&r, &s, &e), SVET_ERR_UNSUPPORTED);
    ck_assert_msg(strstr(e.msg, "light indirect") != NULL, "%s", e.msg);
    scene_free(&s);
    scenecheck_refused("render light direct\n", "t.scn:1:", "light");
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("irrpart (" REAL_NAME ")");
    TCase *t = tcase_create("core");
    tcase_set_timeout(t, 600);
    tcase_add_test(t, irradiance_statement_messages);
    tcase_add_test(t, closed_sphere_has_the_exact_irradiance);
    tcase_add_test(t, closed_box_has_the_exact_mean_irradiance);
    tcase_add_test(t, gradients_match_finite_differences_on_a_floor_under_a_sphere);
    tcase_add_test(t, gradients_match_finite_differences_in_a_corner);
    tcase_add_test(t, no_light_leaks_through_a_thin_wall);
    tcase_add_test(t, uncovered_lookups_gather_afresh_and_the_log_counts_them);
    tcase_add_test(t, the_same_bits_for_any_thread_count);
    tcase_add_test(t, the_cache_approaches_the_gathers_as_a_falls);
    tcase_add_test(t, the_cornell_box_converges_to_the_path_tracer_as_a_falls);
    tcase_add_test(t, the_indirect_light_agrees_with_the_path_tracer);
    tcase_add_test(t, no_indirect_light_on_a_plane_under_a_light);
    tcase_add_test(t, indirect_light_refused_where_not_separated);
    suite_add_tcase(s, t);
    return s;
}
