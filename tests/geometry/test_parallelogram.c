/*
 * test_parallelogram.c - the parallelogram of app. D: exact hits, (s, t)
 * and the frame, the open interval, parallel rays, the Cornell box's
 * rectangles and their normals, no ray slipping through a closed box of
 * parallelograms, input checks (degenerate, not a parallelogram), uniform
 * sampling, the geomcheck harness, tests/vectors/parallelogram.csv and a
 * NaN sweep; the plain test (two triangles, no early rejection) and the
 * speed layer's (SIMD=on: early rejections, shared shears, and the batch
 * of brute force) give the same answers and hits bit for bit.
 */
#include "testutil.h"
#include "geomcheck.h"
#include "geometry/parallelogram.h"
#include "primcheck.h"
#include "geometry/triangle.h"

#include <string.h>

static COBJECT *para(const VECTOR3 c0, const VECTOR3 c1, const VECTOR3 c3)
{
    svet_error err;
    COBJECT *o = parallelogram_new(c0, c1, c3, &err);
    ck_assert_msg(o != NULL, "%s", err.msg);
    return o;
}

START_TEST(parallelogram_hit_has_exact_st_point_and_frame)
{
    VECTOR3 c0 = { 1, 1, 0 }, c1 = { 3, 1, 0 }, c3 = { 2, 2, 0 };
    COBJECT *o = para(c0, c1, c3);
    /* p(s, t) = c0 + s (2,0,0) + t (1,1,0); aim at s = 0.25, t = 0.75 */
    ray_t r = { { REAL_C(2.25), REAL_C(1.75), 4 }, { 0, 0, -1 } };
    hit_t h;
    ck_assert(cobject_intersect(o, &r, 0, (real)INFINITY, &h));
    ck_assert(h.t == 4);
    PATHPOINT pp;
    cobject_fill(o, &r, &h, &pp);
    ck_assert(pp.cross_point[X] == REAL_C(2.25) &&
              pp.cross_point[Y] == REAL_C(1.75) && pp.cross_point[Z] == 0);
    ck_assert(pp.st[0] == REAL_C(0.25) && pp.st[1] == REAL_C(0.75));
    ck_assert(pp.ng[Z] == 1 && pp.n[Z] == 1);
    ck_assert(pp.u[X] == 1 && pp.v[Y] == 1); /* u along c1 - c0 */
    ck_assert(pp.dpds[X] == 2 && pp.dpdt[X] == 1 && pp.dpdt[Y] == 1);
    ck_assert(o->ops->area(o) == 2);
    bbox_t b;
    o->ops->bounds(o, -1, &b);
    ck_assert(b.min[X] == 1 && b.max[X] == 4 && b.min[Y] == 1 &&
              b.max[Y] == 2); /* c2 = (4, 2, 0) */
    /* the other triangle: s > t */
    ray_t r2 = { { REAL_C(3.0), REAL_C(1.25), 4 }, { 0, 0, -2 } };
    ck_assert(cobject_intersect(o, &r2, 0, (real)INFINITY, &h));
    cobject_fill(o, &r2, &h, &pp);
    ck_assert(pp.st[0] == REAL_C(0.875) && pp.st[1] == REAL_C(0.25));
    /* just outside each side; on the sides and corners (inclusive) */
    real inf = (real)INFINITY;
    const real out[4][2] = { { 2, REAL_C(0.999) }, { REAL_C(3.5), REAL_C(2.001) },
                             { REAL_C(1.499), REAL_C(1.5) },
                             { REAL_C(3.501), REAL_C(1.5) } };
    for (int i = 0; i < 4; i++) {
        ray_t m = { { out[i][0], out[i][1], 1 }, { 0, 0, -1 } };
        ck_assert(!cobject_intersect(o, &m, 0, inf, &h));
    }
    const real on[6][2] = { { 2, 1 }, { REAL_C(3.5), 2 }, { REAL_C(1.5), REAL_C(1.5) },
                            { REAL_C(3.5), REAL_C(1.5) }, { 1, 1 }, { 4, 2 } };
    for (int i = 0; i < 6; i++) {
        ray_t m = { { on[i][0], on[i][1], 1 }, { 0, 0, -1 } };
        ck_assert_msg(cobject_intersect(o, &m, 0, inf, &h), "point %d", i);
    }
    cobject_free(o);
}
END_TEST

START_TEST(parallelogram_respects_the_interval_and_parallel_rays_miss)
{
    VECTOR3 c0 = { 0, 0, 0 }, c1 = { 1, 0, 0 }, c3 = { 0, 1, 0 };
    COBJECT *o = para(c0, c1, c3);
    real inf = (real)INFINITY;
    hit_t h;
    ray_t r = { { REAL_C(0.5), REAL_C(0.5), 2 }, { 0, 0, -1 } };
    ck_assert(!cobject_intersect(o, &r, 0, 2, &h));
    ck_assert(cobject_intersect(o, &r, 0, nextafter(REAL_C(2.0), inf), &h));
    ck_assert(!cobject_intersect(o, &r, 2, inf, &h));
    ray_t up = { { REAL_C(0.5), REAL_C(0.5), -1 }, { 0, 0, 1 } };
    ck_assert(cobject_intersect(o, &up, 0, inf, &h));
    PATHPOINT pp;
    cobject_fill(o, &up, &h, &pp);
    ck_assert(pp.ng[Z] == 1 && !pp.bout); /* seen from behind */
    ray_t above = { { -1, REAL_C(0.5), 1 }, { 1, 0, 0 } };
    ray_t in = { { -1, REAL_C(0.5), 0 }, { 1, 0, 0 } };
    ray_t diag = { { -1, -1, 0 }, { 1, 1, 0 } };
    ray_t edge = { { -1, 0, 0 }, { 1, 0, 0 } };
    ck_assert(!cobject_intersect(o, &above, 0, inf, &h));
    ck_assert(!cobject_intersect(o, &in, 0, inf, &h));
    ck_assert(!cobject_intersect(o, &diag, 0, inf, &h));
    ck_assert(!cobject_intersect(o, &edge, 0, inf, &h));
    cobject_free(o);
}
END_TEST

/* The rectangles of the Cornell box, as in the common reference scene
 * (scenes/cbox.scn). */
static const real cbox[7][4][3] = {
    { { -1, -1, 1 }, { 1, -1, 1 }, { 1, -1, -1 }, { -1, -1, -1 } }, /* floor */
    { { -1, 1, -1 }, { 1, 1, -1 }, { 1, 1, 1 }, { -1, 1, 1 } },     /* ceiling */
    { { -1, -1, -1 }, { 1, -1, -1 }, { 1, 1, -1 }, { -1, 1, -1 } }, /* back */
    { { 1, -1, -1 }, { 1, -1, 1 }, { 1, 1, 1 }, { 1, 1, -1 } },     /* right */
    { { -1, -1, 1 }, { -1, -1, -1 }, { -1, 1, -1 }, { -1, 1, 1 } }, /* left */
    { { REAL_C(-0.23), REAL_C(0.99), REAL_C(-0.18) },
      { REAL_C(0.23), REAL_C(0.99), REAL_C(-0.18) },
      { REAL_C(0.23), REAL_C(0.99), REAL_C(0.2) },
      { REAL_C(-0.23), REAL_C(0.99), REAL_C(0.2) } },               /* light */
    /* not in the scene: a front wall that closes the box for the tests */
    { { 1, -1, 1 }, { -1, -1, 1 }, { -1, 1, 1 }, { 1, 1, 1 } } };

START_TEST(cornell_box_rectangles_face_into_the_box)
{
    /* expected normals: floor +y, ceiling -y, back +z, right -x, left +x,
     * light -y ("facing -y"), front -z */
    const real want[7][3] = { { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 },
                              { -1, 0, 0 }, { 1, 0, 0 }, { 0, -1, 0 },
                              { 0, 0, -1 } };
    for (int i = 0; i < 7; i++) {
        svet_error err;
        COBJECT *o = parallelogram_new4(cbox[i][0], cbox[i][1], cbox[i][2],
                                        cbox[i][3], &err);
        ck_assert_msg(o != NULL, "%d: %s", i, err.msg);
        real u[2] = { REAL_C(0.5), REAL_C(0.5) };
        cobject_sample_t s;
        o->ops->sample(o, u, &s);
        for (int k = 0; k < 3; k++)
            ck_assert(s.n[k] == want[i][k]);
        real area = i == 5 ? REAL_C(0.46) * REAL_C(0.38) : 4;
        ck_assert_near(o->ops->area(o), area, 4 * REAL_EPSILON);
        cobject_free(o);
    }
}
END_TEST

START_TEST(no_ray_slips_through_a_closed_box_of_parallelograms)
{
    COBJECT *wall[7];
    int walls[6] = { 0, 1, 2, 3, 4, 6 };
    for (int i = 0; i < 6; i++) {
        svet_error err;
        const real (*c)[3] = cbox[walls[i]];
        wall[i] = parallelogram_new4(c[0], c[1], c[2], c[3], &err);
        ck_assert_msg(wall[i] != NULL, "%s", err.msg);
    }
    pcg32_t g;
    pcg32_seed(&g, 21, 22);
    long n = 0;
    for (int i = 0; i < 30000; i++, n++) {
        ray_t r;
        for (int k = 0; k < 3; k++)
            r.o[k] = REAL_C(1.8) * pcg32_real(&g) - REAL_C(0.9);
        /* aim at edges and corners of the box (coordinates +-1 on two or
         * three axes), at the diagonals of the faces (two coordinates
         * equal in magnitude), or anywhere */
        VECTOR3 target;
        int kind = i % 4;
        for (int k = 0; k < 3; k++)
            target[k] = 2 * pcg32_real(&g) - 1;
        int a = (int)pcg32_bounded(&g, 3), b = (a + 1) % 3;
        if (kind == 0) {
            target[a] = pcg32_next(&g) & 1 ? 1 : -1;
            target[b] = pcg32_next(&g) & 1 ? 1 : -1;
        } else if (kind == 1) {
            for (int k = 0; k < 3; k++)
                target[k] = pcg32_next(&g) & 1 ? 1 : -1;
        } else if (kind == 2) {
            target[a] = pcg32_next(&g) & 1 ? 1 : -1;
            target[(a + 2) % 3] = pcg32_next(&g) & 1 ? target[b] : -target[b];
        }
        vec_sub(r.d, target, r.o);
        bool any = false;
        for (int w = 0; w < 6 && !any; w++) {
            hit_t h;
            any = cobject_intersect(wall[w], &r, 0, (real)INFINITY, &h);
        }
        ck_assert_msg(any, "ray %d from (%g %g %g) to (%g %g %g) escapes", i,
                      (double)r.o[X], (double)r.o[Y], (double)r.o[Z],
                      (double)target[X], (double)target[Y], (double)target[Z]);
    }
    for (int i = 0; i < 6; i++)
        cobject_free(wall[i]);
    test_report_cases("no_ray_slips_through_a_closed_box_of_parallelograms", n);
}
END_TEST

/* The parallelogram as two separate watertight triangle tests, A =
 * (c0, c1, c2) then B = (c0, c2, c3) if nearer: what parallelogram.c
 * shares between the two must not change a bit of this. */
static bool two_triangle_reference(const VECTOR3 c[4], const ray_t *r,
                                   real tmin, real tmax, hit_t *h)
{
    real t, b[3], st[2];
    bool any = false;
    if (triangle_intersect_watertight(c[0], c[1], c[2], r, tmin, tmax, &t,
                                      b)) {
        any = true;
        tmax = t;
        st[0] = b[1] + b[2];
        st[1] = b[2];
    }
    if (triangle_intersect_watertight(c[0], c[2], c[3], r, tmin, tmax, &t,
                                      b)) {
        any = true;
        st[0] = b[1];
        st[1] = b[1] + b[2];
    }
    if (any) {
        h->t = t;
        h->b[0] = fmin(fmax(st[0], REAL_C(0.0)), REAL_C(1.0));
        h->b[1] = fmin(fmax(st[1], REAL_C(0.0)), REAL_C(1.0));
    }
    return any;
}

/* The same hit to the last bit, field by field (a hit_t of doubles has
 * padding). */
static bool same_hit(const hit_t *a, const hit_t *b)
{
    return memcmp(&a->t, &b->t, sizeof a->t) == 0 && a->prim == b->prim &&
           memcmp(a->b, b->b, sizeof a->b) == 0;
}

#ifdef SVET_SIMD
/* o's intersect() the way the batched brute force makes it (batch.c):
 * the early rejections from a batch (of o alone, or of o among others at
 * bit i), then the watertight test on a ray prepared apart. */
static bool via_batch(const parallelogram_batch_t *batch, int i,
                      const COBJECT *o, const ray_t *r, real tmin, real tmax,
                      hit_t *h)
{
    const uint64_t all = ~(uint64_t)0;
    if (!((parallelogram_batch_cull(batch, r, tmin, tmax, all) >> i) & 1))
        return false;
    triangle_ray_t pr;
    triangle_ray_prepare(&pr, r);
    return parallelogram_intersect_prepared(o, 0, &pr, tmin, tmax, h);
}
#endif

/* One ray against o over (tmin, tmax): the same answer, bit for bit, as
 * the two triangles, through intersect() and through a batch. Returns
 * whether it hit. */
static bool agrees_with_two_triangles(const COBJECT *o, const VECTOR3 c[4],
                                      const ray_t *r, real tmin, real tmax)
{
    hit_t h1 = { 0, 0, { 0, 0, 0 } }, h2 = h1, h3 = h1, h4 = h1;
    bool a = two_triangle_reference(c, r, tmin, tmax, &h1);
    bool b = o->ops->intersect(o, 0, r, tmin, tmax, &h2);
    /* the plain test, field by field */
    bool b4 = parallelogram_intersect_plain(o, 0, r, tmin, tmax, &h4);
    ck_assert(b4 == b && (!b || same_hit(&h2, &h4)));
    triangle_ray_t pr;
    triangle_ray_prepare(&pr, r);
    hit_t h5 = { 0, 0, { 0, 0, 0 } }, h6 = h5;
    bool b5 = parallelogram_prepared_plain(o, 0, &pr, tmin, tmax, &h5);
    bool b6 = parallelogram_intersect_prepared(o, 0, &pr, tmin, tmax, &h6);
    ck_assert(b5 == b && b6 == b && (!b || (same_hit(&h2, &h5) &&
                                            same_hit(&h2, &h6))));
#ifdef SVET_SIMD
    parallelogram_batch_t *batch = parallelogram_batch_new(&o, 1);
    ck_assert_ptr_nonnull(batch);
    bool b3 = via_batch(batch, 0, o, r, tmin, tmax, &h3);
    parallelogram_batch_free(batch);
    ck_assert(b3 == b && (!b || same_hit(&h2, &h3)));
#else
    (void)h3;
#endif
    ck_assert_msg(a == b, "hit %d vs %d: o (%a %a %a) d (%a %a %a) "
                  "(%a, %a)", (int)a, (int)b, (double)r->o[X],
                  (double)r->o[Y], (double)r->o[Z], (double)r->d[X],
                  (double)r->d[Y], (double)r->d[Z], (double)tmin,
                  (double)tmax);
    if (a) {
        ck_assert(memcmp(&h1.t, &h2.t, sizeof h1.t) == 0);
        ck_assert(memcmp(h1.b, h2.b, 2 * sizeof h1.b[0]) == 0);
    }
    return a;
}

START_TEST(parallelogram_answers_as_its_two_triangles_bit_for_bit)
{
    /* Random parallelograms, and small-integer ones whose edge functions
     * come out exactly zero for rays through corners, edges and the
     * diagonal (the exact recomputation); rays aimed at such points, with
     * directions of every length from 2^-40 to 2^40 (the rescaled
     * preparation), over (0, inf), (-inf, inf) and a finite tmax. */
    pcg32_t g;
    pcg32_seed(&g, 31, 32);
    long n = 0, hits = 0;
    for (int i = 0; i < 4000; i++) {
        VECTOR3 c[4];
        bool grid = i % 2 == 0;
        for (int k = 0; k < 3; k++) {
            c[0][k] = grid ? (real)pcg32_bounded(&g, 5) - 2
                           : 4 * pcg32_real(&g) - 2;
            c[1][k] = grid ? (real)pcg32_bounded(&g, 5) - 2
                           : 4 * pcg32_real(&g) - 2;
            c[3][k] = grid ? (real)pcg32_bounded(&g, 5) - 2
                           : 4 * pcg32_real(&g) - 2;
        }
        svet_error err;
        COBJECT *o = parallelogram_new(c[0], c[1], c[3], &err);
        if (!o)
            continue; /* degenerate draw */
        for (int k = 0; k < 3; k++)
            c[2][k] = c[1][k] + (c[3][k] - c[0][k]); /* as the constructor */
        for (int j = 0; j < 20; j++, n++) {
            /* a point of the plane at (s, t): the diagonal s = t, an edge,
             * a corner, or anywhere in and around the parallelogram */
            real s = REAL_C(1.4) * pcg32_real(&g) - REAL_C(0.2);
            real t = REAL_C(1.4) * pcg32_real(&g) - REAL_C(0.2);
            int kind = j % 4;
            if (kind == 0)
                t = s;
            else if (kind == 1)
                s = (real)pcg32_bounded(&g, 2);
            else if (kind == 2)
                s = (real)pcg32_bounded(&g, 2), t = (real)pcg32_bounded(&g, 2);
            VECTOR3 target, e1, e2;
            vec_sub(e1, c[1], c[0]);
            vec_sub(e2, c[3], c[0]);
            for (int k = 0; k < 3; k++)
                target[k] = c[0][k] + s * e1[k] + t * e2[k];
            ray_t r;
            for (int k = 0; k < 3; k++)
                r.o[k] = grid ? (real)pcg32_bounded(&g, 9) - 4
                              : 8 * pcg32_real(&g) - 4;
            vec_sub(r.d, target, r.o);
            if (j % 5 == 0)
                vec_scale(r.d, r.d,
                          ldexp(REAL_C(1.0), (int)pcg32_bounded(&g, 81) - 40));
            const real tmins[3] = { 0, -(real)INFINITY, 0 };
            const real tmaxs[3] = { (real)INFINITY, (real)INFINITY,
                                    REAL_C(0.5) };
            for (int q = 0; q < 3; q++) {
                real tmax = tmaxs[q];
                if (q == 2 && j % 5 == 0)
                    tmax = (real)INFINITY; /* t is scaled there */
                if (agrees_with_two_triangles(o, (const VECTOR3 *)c, &r,
                                              tmins[q], tmax))
                    hits++;
            }
        }
        cobject_free(o);
    }
    ck_assert(hits > n / 2);
    test_report_cases("parallelogram_answers_as_its_two_triangles_bit_for_bit",
                      3 * n);
}
END_TEST

/* A parallelogram for the probes below (draw i): corners at a scale
 * *size from 2^-10 to 2^10, every third one axis-aligned; with thin set,
 * every fourth one thin (c3 - c0 shorter by up to 2^-11). c[2] is set as
 * the shape sets it, e1, e2 to the edges and nrm to the unit normal.
 * NULL when the draw is degenerate. */
static COBJECT *probe_parallelogram(pcg32_t *g, int i, bool thin,
                                    VECTOR3 c[4], VECTOR3 e1, VECTOR3 e2,
                                    VECTOR3 nrm, real *size)
{
    *size = ldexp(REAL_C(1.0), (int)pcg32_bounded(g, 21) - 10);
    real f = thin && i % 4 == 1
                 ? ldexp(REAL_C(1.0), -(int)pcg32_bounded(g, 12))
                 : 1;
    for (int k = 0; k < 3; k++) {
        c[0][k] = *size * (4 * pcg32_real(g) - 2);
        c[1][k] = c[0][k] + *size * (2 * pcg32_real(g) - 1);
        c[3][k] = c[0][k] + f * *size * (2 * pcg32_real(g) - 1);
    }
    if (i % 3 == 0) /* axis-aligned, as the Cornell box's walls */
        for (int j = 1; j < 4; j += 2)
            c[j][i % 9 / 3] = c[0][i % 9 / 3];
    svet_error err;
    COBJECT *o = parallelogram_new(c[0], c[1], c[3], &err);
    if (!o)
        return NULL;
    for (int k = 0; k < 3; k++)
        c[2][k] = c[1][k] + (c[3][k] - c[0][k]);
    vec_sub(e1, c[1], c[0]);
    vec_sub(e2, c[3], c[0]);
    VVECTOR3(nrm, e1, e2);
    vec_normalize(nrm, nrm);
    return o;
}

START_TEST(parallelogram_early_rejections_lose_no_hit)
{
    /* The parallelogram rejects a ray early when it leaves the plane
     * behind it, crosses it clearly outside, or ends before it
     * (fast/parallelogram_cull.c). Probe them where they are closest to wrong:
     * origins at 2^-k of the size off the plane on either side (and on
     * it), directions grazing the plane from either side, and intervals
     * that end one ulp before, at and after the hit. */
    pcg32_t g;
    pcg32_seed(&g, 41, 42);
    long n = 0, hits = 0;
    for (int i = 0; i < 3000; i++) {
        VECTOR3 c[4], e1, e2, nrm;
        real size;
        COBJECT *o = probe_parallelogram(&g, i, false, c, e1, e2, nrm, &size);
        if (!o)
            continue;
        for (int j = 0; j < 30; j++) {
            /* origin off the plane by +-2^-k size (or on it), over a point
             * in or around the parallelogram */
            real off = pcg32_bounded(&g, 8) == 0
                           ? 0
                           : ldexp(size, -(int)pcg32_bounded(&g, 40));
            if (pcg32_next(&g) & 1)
                off = -off;
            ray_t r;
            real s0 = REAL_C(3.0) * pcg32_real(&g) - 1;
            real t0 = REAL_C(3.0) * pcg32_real(&g) - 1;
            for (int k = 0; k < 3; k++)
                r.o[k] = c[0][k] + s0 * e1[k] + t0 * e2[k] + off * nrm[k];
            /* toward a point of the parallelogram (or near it) lifted off
             * the plane by a tiny amount: grazing either way */
            real s1 = REAL_C(1.2) * pcg32_real(&g) - REAL_C(0.1);
            real t1 = REAL_C(1.2) * pcg32_real(&g) - REAL_C(0.1);
            real lift = ldexp(size, -(int)pcg32_bounded(&g, 50)) *
                        (pcg32_next(&g) & 1 ? 1 : -1);
            for (int k = 0; k < 3; k++)
                r.d[k] = c[0][k] + s1 * e1[k] + t1 * e2[k] + lift * nrm[k] -
                         r.o[k];
            if (pcg32_next(&g) & 1)
                vec_neg(r.d, r.d); /* and away from it */
            n++;
            if (!agrees_with_two_triangles(o, (const VECTOR3 *)c, &r, 0,
                                           (real)INFINITY))
                continue;
            hits++;
            /* the interval's ends around the hit */
            hit_t h;
            two_triangle_reference((const VECTOR3 *)c, &r, 0,
                                   (real)INFINITY, &h);
            const real ends[3] = { nextafter(h.t, -(real)INFINITY), h.t,
                                   nextafter(h.t, (real)INFINITY) };
            for (int q = 0; q < 3; q++, n += 2) {
                agrees_with_two_triangles(o, (const VECTOR3 *)c, &r, 0,
                                          ends[q]);
                agrees_with_two_triangles(o, (const VECTOR3 *)c, &r,
                                          ends[q], (real)INFINITY);
            }
        }
        cobject_free(o);
    }
    ck_assert(hits > n / 20);
    test_report_cases("parallelogram_early_rejections_lose_no_hit", n);
}
END_TEST

START_TEST(parallelogram_plain_and_fast_agree_on_extreme_rays)
{
    /* The intersect() of the build (with the speed layer's rejections
     * where SIMD=on) and the plain test, field by field, on the Cornell
     * box's walls and random parallelograms at scales 2^-20 to 2^20: rays
     * whose coordinates are of every class (NaN, infinite, zero
     * directions), rays grazing the plane, and intervals from the same
     * classes. */
    pcg32_t g;
    pcg32_seed(&g, 71, 72);
    long n = 0, hits = 0;
    for (int i = 0; i < 400; i++) {
        VECTOR3 c0, c1, c3;
        if (i < 7) {
            vec_copy(c0, cbox[i][0]);
            vec_copy(c1, cbox[i][1]);
            vec_copy(c3, cbox[i][3]);
        } else {
            real size = ldexp(REAL_C(1.0), (int)pcg32_bounded(&g, 41) - 20);
            for (int k = 0; k < 3; k++) {
                c0[k] = size * (2 * pcg32_real(&g) - 1);
                c1[k] = c0[k] + size * (2 * pcg32_real(&g) - 1);
                c3[k] = c0[k] + size * (2 * pcg32_real(&g) - 1);
            }
        }
        svet_error err;
        COBJECT *o = parallelogram_new(c0, c1, c3, &err);
        if (!o)
            continue;
        VECTOR3 e1, e2, nrm;
        vec_sub(e1, c1, c0);
        vec_sub(e2, c3, c0);
        VVECTOR3(nrm, e1, e2);
        for (int j = 0; j < 500; j++, n++) {
            ray_t r;
            real tmin = 0, tmax = (real)INFINITY;
            if (j % 3 == 0) { /* every class */
                geomcheck_any_ray(&r, &tmin, &tmax, &g);
            } else { /* toward the parallelogram, or grazing its plane */
                real s = REAL_C(1.4) * pcg32_real(&g) - REAL_C(0.2);
                real t = REAL_C(1.4) * pcg32_real(&g) - REAL_C(0.2);
                real off = ldexp(REAL_C(1.0), -(int)pcg32_bounded(&g, 40));
                for (int k = 0; k < 3; k++) {
                    r.o[k] = c0[k] + 2 * e1[k] * pcg32_real(&g) +
                             2 * e2[k] * pcg32_real(&g) +
                             (j % 3 == 1 ? 1 : off) * nrm[k];
                    r.d[k] = c0[k] + s * e1[k] + t * e2[k] - r.o[k];
                }
                if (j % 7 == 0)
                    tmax = REAL_C(0.5) + pcg32_real(&g);
            }
            hit_t a = { 0, 0, { 0, 0, 0 } }, b = a;
            bool ha = o->ops->intersect(o, 0, &r, tmin, tmax, &a);
            bool hb = parallelogram_intersect_plain(o, 0, &r, tmin, tmax, &b);
            ck_assert_msg(ha == hb && (!ha || same_hit(&a, &b)),
                          "case %d/%d: o (%a %a %a) d (%a %a %a) (%a, %a)", i,
                          j, (double)r.o[X], (double)r.o[Y], (double)r.o[Z],
                          (double)r.d[X], (double)r.d[Y], (double)r.d[Z],
                          (double)tmin, (double)tmax);
            hits += ha;
        }
        cobject_free(o);
    }
    ck_assert(hits > n / 10);
    test_report_cases("parallelogram_plain_and_fast_agree_on_extreme_rays", n);
}
END_TEST

#ifdef SVET_SIMD
START_TEST(segments_that_end_before_the_plane_lose_no_hit)
{
    /* A ray over (0, tmax) whose origin and end lie on one side of the
     * plane is rejected before the watertight test (stays_before() in
     * fast/parallelogram_cull.c). Probe it where it is closest to wrong: segments
     * toward a point of the parallelogram (or near its edges), grazing
     * ones included, that end 2^-k of the way short of the plane's
     * crossing or 2^-k past it, from origins near and far, on thin and
     * axis-aligned parallelograms at scales 2^-10 to 2^10: intersect()
     * and the batch answer as the two watertight triangles, bit for bit.
     * The rejection must have been taken (the batch's answer for the
     * segment differs from its answer for the whole ray) in more than 1 %
     * of the cases. */
    pcg32_t g;
    pcg32_seed(&g, 61, 62);
    long n = 0, hits = 0, rejected = 0;
    for (int i = 0; i < 2000; i++) {
        VECTOR3 c[4], e1, e2, nrm;
        real size;
        COBJECT *o = probe_parallelogram(&g, i, true, c, e1, e2, nrm, &size);
        if (!o)
            continue;
        parallelogram_batch_t *batch =
            parallelogram_batch_new((const COBJECT *const *)&o, 1);
        ck_assert_ptr_nonnull(batch);
        for (int j = 0; j < 20; j++) {
            /* the origin 2^-k to 2^3 of the size off the plane */
            real off = ldexp(size, 3 - (int)pcg32_bounded(&g, 30));
            if (pcg32_next(&g) & 1)
                off = -off;
            ray_t r;
            real s0 = REAL_C(5.0) * pcg32_real(&g) - 2;
            real t0 = REAL_C(5.0) * pcg32_real(&g) - 2;
            for (int k = 0; k < 3; k++)
                r.o[k] = c[0][k] + s0 * e1[k] + t0 * e2[k] + off * nrm[k];
            /* toward a point in or around it; the length of d is the
             * distance to that point, or far from it */
            real s1 = REAL_C(1.2) * pcg32_real(&g) - REAL_C(0.1);
            real t1 = REAL_C(1.2) * pcg32_real(&g) - REAL_C(0.1);
            for (int k = 0; k < 3; k++)
                r.d[k] = c[0][k] + s1 * e1[k] + t1 * e2[k] - r.o[k];
            if (j % 5 == 0)
                vec_scale(r.d, r.d,
                          ldexp(REAL_C(1.0), (int)pcg32_bounded(&g, 41) - 20));
            /* the crossing of the plane through c0, in long double */
            long double sn = 0, dn = 0;
            for (int k = 0; k < 3; k++) {
                sn += ((long double)c[0][k] - r.o[k]) * nrm[k];
                dn += (long double)r.d[k] * nrm[k];
            }
            if (dn == 0)
                continue;
            long double tc = sn / dn;
            if (!(tc > 0))
                continue;
            for (int q = 0; q < 8; q++) {
                int k = (int)pcg32_bounded(&g, 32);
                long double f = q < 6 ? 1 - ldexpl(1, -k) : 1 + ldexpl(1, -k);
                real tmax = (real)(tc * f);
                if (!(tmax > 0) || !isfinite(tmax))
                    continue;
                n++;
                hits += agrees_with_two_triangles(o, (const VECTOR3 *)c, &r,
                                                  0, tmax);
                rejected += parallelogram_batch_cull(batch, &r, 0, tmax, 1) !=
                            parallelogram_batch_cull(batch, &r, 0,
                                                     (real)INFINITY, 1);
            }
        }
        parallelogram_batch_free(batch);
        cobject_free(o);
    }
    ck_assert(hits > n / 20);
    /* about 1.6 % in float (the pad grows as A^3 / area, large for the
     * thin ones and far origins), more in double */
    ck_assert(rejected > n / 100);
    test_report_cases("segments_that_end_before_the_plane_lose_no_hit", n);
}
END_TEST
#endif

#ifdef SVET_SIMD
START_TEST(parallelogram_batch_answers_as_each_parallelogram_bit_for_bit)
{
    /* Batches of 1 to 64 parallelograms (whole vector steps and padding
     * lanes): for every ray the batch answers as its plain loop, bit for
     * bit (NaN and infinite rays too); each bit of the answer is the bit
     * of a batch of that parallelogram alone, and where the batch
     * lets the ray through, the prepared test gives intersect()'s hit to
     * the last bit; where it does not, intersect() reports no hit. */
    pcg32_t g;
    pcg32_seed(&g, 51, 52);
    long n = 0, hits = 0;
    for (int round = 0; round < 60; round++) {
        int m = 1 + (int)pcg32_bounded(&g, PARALLELOGRAM_BATCH_MAX);
        COBJECT *o[PARALLELOGRAM_BATCH_MAX];
        parallelogram_batch_t *one[PARALLELOGRAM_BATCH_MAX];
        int k = 0;
        while (k < m) {
            VECTOR3 c0, c1, c3;
            if (k < 7 && round % 2 == 0) { /* the Cornell box's */
                vec_copy(c0, cbox[k][0]);
                vec_copy(c1, cbox[k][1]);
                vec_copy(c3, cbox[k][3]);
            } else {
                for (int a = 0; a < 3; a++) {
                    c0[a] = 4 * pcg32_real(&g) - 2;
                    c1[a] = c0[a] + 2 * pcg32_real(&g) - 1;
                    c3[a] = c0[a] + 2 * pcg32_real(&g) - 1;
                }
            }
            svet_error err;
            o[k] = parallelogram_new(c0, c1, c3, &err);
            if (!o[k])
                continue;
            one[k] = parallelogram_batch_new((const COBJECT *const *)&o[k],
                                             1);
            ck_assert_ptr_nonnull(one[k]);
            k++;
        }
        parallelogram_batch_t *all =
            parallelogram_batch_new((const COBJECT *const *)o, m);
        ck_assert_ptr_nonnull(all);
        for (int j = 0; j < 500; j++) {
            ray_t r;
            for (int a = 0; a < 3; a++)
                r.o[a] = 6 * pcg32_real(&g) - 3;
            real u[2] = { pcg32_real(&g), pcg32_real(&g) };
            cobject_sample_t sm;
            const COBJECT *aim = o[pcg32_bounded(&g, (uint32_t)m)];
            aim->ops->sample(aim, u, &sm);
            vec_sub(r.d, sm.p, r.o); /* at a point of one of them */
            if (j % 3 == 0)
                geomcheck_random_dir(r.d, &g);
            if (j % 13 == 0) /* lengths far from 1 */
                vec_scale(r.d, r.d,
                          ldexp(REAL_C(1.0), (int)pcg32_bounded(&g, 61) - 30));
            if (j % 17 == 0) /* along an axis: n . d is 0 for some */
                vec_set(r.d, 0, j % 2 ? 1 : -1, 0);
            if (j % 17 == 1) { /* grazing: n . d tiny but not 0 */
                int a = (int)pcg32_bounded(&g, 3);
                vec_set(r.d, 0, 0, 0);
                r.d[a] = j % 2 ? 1 : -1;
                r.d[(a + 1) % 3] =
                    ldexp(REAL_C(1.0), -(int)pcg32_bounded(&g, 40));
            }
            if (vec_length2(r.d) == 0)
                continue;
            real tmin = j % 7 == 0 ? -(real)INFINITY : 0;
            /* an open ray, a segment that ends at the point aimed at or
             * anywhere up to twice as far, one that ends before it
             * starts */
            real tmax = j % 4 == 0   ? (real)INFINITY
                        : j % 4 == 1 ? 1
                        : j % 23 == 2 ? -(real)INFINITY
                                      : 2 * pcg32_real(&g);
            const uint64_t every = ~(uint64_t)0;
            uint64_t mask = parallelogram_batch_cull(all, &r, tmin, tmax,
                                                     every);
            ck_assert(m == 64 || mask >> m == 0);
            ck_assert(mask == parallelogram_batch_cull_plain(all, &r, tmin,
                                                             tmax, every));
            /* some objects left out: their bits are 0, the others' the
             * same (and a step of lanes all left out or rejected by the
             * plane tests skips the rest) */
            uint64_t want = (uint64_t)pcg32_next(&g) << 32 | pcg32_next(&g);
            if (j % 3 == 0)
                want &= (uint64_t)pcg32_next(&g) << 32 | pcg32_next(&g);
            ck_assert(parallelogram_batch_cull(all, &r, tmin, tmax, want) ==
                      (mask & want));
            ck_assert(parallelogram_batch_cull_plain(all, &r, tmin, tmax,
                                                     want) == (mask & want));
            if (j % 19 == 0) { /* NaN and infinity: every lane as the plain
                                  loop answers */
                ray_t bad = r;
                bad.o[j % 3] = j % 2 ? (real)NAN : (real)INFINITY;
                ck_assert(parallelogram_batch_cull(all, &bad, 0, tmax, want) ==
                          parallelogram_batch_cull_plain(all, &bad, 0, tmax,
                                                         want));
                bad = r;
                bad.d[j % 3] = (real)NAN;
                ck_assert(parallelogram_batch_cull(all, &bad, 0, tmax, want) ==
                          parallelogram_batch_cull_plain(all, &bad, 0, tmax,
                                                         want));
            }
            for (int i = 0; i < m; i++, n++) {
                uint64_t bit = (mask >> i) & 1;
                ck_assert(bit ==
                          parallelogram_batch_cull(one[i], &r, tmin, tmax,
                                                   every));
                hit_t h1 = { 0, 0, { 0, 0, 0 } }, h2 = h1;
                bool a = o[i]->ops->intersect(o[i], 0, &r, tmin, tmax, &h1);
                bool b = via_batch(all, i, o[i], &r, tmin, tmax,
                                   &h2);
                ck_assert(a == b && (!a || same_hit(&h1, &h2)));
                hits += a;
            }
        }
        parallelogram_batch_free(all);
        for (int i = 0; i < m; i++) {
            parallelogram_batch_free(one[i]);
            cobject_free(o[i]);
        }
    }
    ck_assert(hits > n / 50);
    /* only parallelograms, at most 64 of them */
    ck_assert_ptr_null(parallelogram_batch_new(NULL, -1));
    ck_assert_ptr_null(parallelogram_batch_new(NULL,
                                               PARALLELOGRAM_BATCH_MAX + 1));
    VECTOR3 v = { 0, 0, 0 };
    svet_error err;
    COBJECT *t = triangle_new(v, cbox[0][1], cbox[0][3], &err);
    ck_assert(!parallelogram_is(t) &&
              parallelogram_batch_new((const COBJECT *const *)&t, 1) == NULL);
    cobject_free(t);
    test_report_cases("parallelogram_batch_answers_as_each_parallelogram_bit_"
                      "for_bit", n);
}
END_TEST
#endif

#ifdef SVET_SIMD
START_TEST(parallelogram_batch_answers_as_its_plain_loop_on_extreme_rays)
{
    /* The vector batch and its plain loop on rays whose coordinates and
     * interval ends are drawn from zeros of both signs, the smallest
     * subnormal, 1, numbers whose products overflow (2^70, REAL_MAX),
     * infinities and NaN (one to six of them at once), over the Cornell
     * box's walls and random parallelograms: the same bits. */
    const real pick[] = { 0, REAL_C(-0.0), REAL_TRUE_MIN, 1, REAL_C(-2.5),
                          REAL_C(0x1p70), -REAL_C(0x1p70), REAL_MAX,
                          -REAL_MAX, (real)INFINITY, -(real)INFINITY,
                          (real)NAN };
    const uint32_t np = (uint32_t)(sizeof pick / sizeof pick[0]);
    pcg32_t g;
    pcg32_seed(&g, 53, 54);
    COBJECT *o[PARALLELOGRAM_BATCH_MAX];
    int m = 0;
    while (m < 21) {
        VECTOR3 c0, c1, c3;
        for (int a = 0; a < 3; a++) {
            c0[a] = m < 7 ? cbox[m][0][a] : 4 * pcg32_real(&g) - 2;
            c1[a] = m < 7 ? cbox[m][1][a] : c0[a] + 2 * pcg32_real(&g) - 1;
            c3[a] = m < 7 ? cbox[m][3][a] : c0[a] + 2 * pcg32_real(&g) - 1;
        }
        svet_error err;
        o[m] = parallelogram_new(c0, c1, c3, &err);
        if (o[m])
            m++;
    }
    parallelogram_batch_t *all =
        parallelogram_batch_new((const COBJECT *const *)o, m);
    ck_assert_ptr_nonnull(all);
    long n = 0, kept = 0;
    for (int j = 0; j < 200000; j++, n++) {
        real v[8];
        for (int k = 0; k < 8; k++)
            v[k] = pcg32_next(&g) % 3 ? 6 * pcg32_real(&g) - 3
                                      : pick[pcg32_bounded(&g, np)];
        ray_t r;
        vec_set(r.o, v[0], v[1], v[2]);
        vec_set(r.d, v[3], v[4], v[5]);
        real tmin = j % 2 ? 0 : v[6], tmax = j % 3 ? (real)INFINITY : v[7];
        uint64_t want = ~(uint64_t)0;
        uint64_t mask = parallelogram_batch_cull(all, &r, tmin, tmax, want);
        ck_assert_msg(mask == parallelogram_batch_cull_plain(all, &r, tmin,
                                                             tmax, want),
                      "o (%a %a %a) d (%a %a %a) (%a, %a)", (double)r.o[X],
                      (double)r.o[Y], (double)r.o[Z], (double)r.d[X],
                      (double)r.d[Y], (double)r.d[Z], (double)tmin,
                      (double)tmax);
        kept += mask != 0;
    }
    ck_assert(kept > n / 20 && kept < n - n / 20);
    parallelogram_batch_free(all);
    for (int i = 0; i < m; i++)
        cobject_free(o[i]);
    test_report_cases("parallelogram_batch_answers_as_its_plain_loop_on_"
                      "extreme_rays", n);
}
END_TEST
#endif

START_TEST(parallelogram_rejects_degenerate_and_non_parallelogram_input)
{
    svet_error err;
    VECTOR3 c0 = { 0, 0, 0 }, c1 = { 1, 0, 0 }, c3 = { 0, 1, 0 };
    VECTOR3 col = { 2, 0, 0 }, nan = { 0, (real)NAN, 0 };
    ck_assert_ptr_null(parallelogram_new(c0, c1, col, &err));
    ck_assert_int_eq(err.status, SVET_ERR_RANGE);
    ck_assert_msg(strstr(err.msg, "degenerate") != NULL, "%s", err.msg);
    ck_assert_ptr_null(parallelogram_new(c0, c0, c3, &err));
    ck_assert_int_eq(err.status, SVET_ERR_RANGE);
    ck_assert_ptr_null(parallelogram_new(c0, nan, c3, &err));
    ck_assert_int_eq(err.status, SVET_ERR_RANGE);
    VECTOR3 big = { REAL_MAX, 0, 0 }, big3 = { 0, REAL_MAX, 0 },
            nbig = { -REAL_MAX, 0, 0 };
    ck_assert_ptr_null(parallelogram_new(c0, big, big3, &err));
    ck_assert_int_eq(err.status, SVET_ERR_RANGE); /* area overflows */
    ck_assert_ptr_null(parallelogram_new(nbig, big, big3, &err));
    ck_assert_int_eq(err.status, SVET_ERR_RANGE); /* an edge overflows */
    /* four corners: right, non-planar by 0.01, planar but a trapezoid */
    VECTOR3 c2 = { 1, 1, 0 }, lift = { 1, 1, REAL_C(0.01) },
            trap = { REAL_C(1.5), 1, 0 };
    COBJECT *o = parallelogram_new4(c0, c1, c2, c3, &err);
    ck_assert_ptr_nonnull(o);
    cobject_free(o);
    ck_assert_ptr_null(parallelogram_new4(c0, c1, lift, c3, &err));
    ck_assert_int_eq(err.status, SVET_ERR_RANGE);
    ck_assert_msg(strstr(err.msg, "0.01 of it out of the plane") != NULL,
                  "%s", err.msg);
    ck_assert_ptr_null(parallelogram_new4(c0, c1, trap, c3, &err));
    ck_assert_msg(strstr(err.msg, "off by (0.5, 0, 0), 0 of it out") != NULL,
                  "%s", err.msg);
    /* a rounding-level mismatch passes: 0.1 + 0.7 - 0.3 in float */
    VECTOR3 a0 = { REAL_C(0.3), 0, 0 }, a1 = { REAL_C(0.1), 1, 0 },
            a3 = { REAL_C(0.7), 0, 1 }, a2 = { REAL_C(0.5), 1, 1 };
    o = parallelogram_new4(a0, a1, a2, a3, &err);
    ck_assert_msg(o != NULL, "%s", err.msg);
    cobject_free(o);
    ck_assert_ptr_null(parallelogram_new4(c0, c1, nan, c3, NULL));
}
END_TEST

START_TEST(perpendicular_edges_are_not_called_parallel_at_any_scale)
{
    /* At 1e19 the products of the edges overflow float: the corners'
     * degeneracy test said "parallel or zero" of perpendicular edges. */
    static const double scales[] = { 1e-30, 1e-19, 1e-10, 1, 1e10, 1e18,
                                     1e19, 1e30 };
    for (size_t i = 0; i < sizeof scales / sizeof *scales; i++) {
        real k = (real)scales[i];
        VECTOR3 c0 = { -k, -k, k }, c1 = { k, -k, k }, c3 = { -k, -k, -k };
        svet_error err;
        svet_error_clear(&err);
        COBJECT *o = parallelogram_new(c0, c1, c3, &err);
        ck_assert_msg(!strstr(err.msg, "parallel or zero"), "scale %g: %s",
                      scales[i], err.msg);
        /* the area 4 k^2 is made, or refused as out of range */
        if (o)
            ck_assert_rel(o->ops->area(o), 4 * (double)k * (double)k, 1e-6,
                          0);
        else
            ck_assert_msg(strstr(err.msg, "out of the range of " REAL_NAME),
                          "scale %g: %s", scales[i], err.msg);
        cobject_free(o);
    }
    /* the float build refuses 1e19 by its area, told as a number */
    svet_error err;
    VECTOR3 c0 = { -1e19, -1e19, 1e19 }, c1 = { 1e19, -1e19, 1e19 },
            c3 = { -1e19, -1e19, -1e19 };
    COBJECT *o = parallelogram_new(c0, c1, c3, &err);
#ifdef SVET_DOUBLE
    ck_assert_ptr_nonnull(o);
    cobject_free(o);
#else
    ck_assert_ptr_null(o);
    ck_assert_str_eq(err.msg, "parallelogram: area 4e+38 is out of the "
                              "range of float");
#endif
    /* edges along one line are still parallel, at any scale */
    VECTOR3 b0 = { 0, 0, 0 }, b1 = { 2e19, 0, 0 }, b3 = { 4e19, 0, 0 };
    ck_assert_ptr_null(parallelogram_new(b0, b1, b3, &err));
    ck_assert_msg(strstr(err.msg, "parallel or zero"), "%s", err.msg);
}
END_TEST

START_TEST(parallelogram_samples_are_uniform_by_area)
{
    /* a skew parallelogram; the fraction of samples with s < 0.5 and
     * t < 0.3 is 0.15: binomial sd sqrt(0.15 0.85 / 50000) = 0.0016, and
     * 5 sd = 0.008. The (s, t) of a sample is recovered by hitting it. */
    VECTOR3 c0 = { 1, 2, 3 }, c1 = { 4, 2, 3 }, c3 = { 2, 4, 5 };
    COBJECT *o = para(c0, c1, c3);
    pcg32_t g;
    pcg32_seed(&g, 23, 24);
    const int N = 50000;
    int in = 0;
    for (int i = 0; i < N; i++) {
        real u[2] = { pcg32_real(&g), pcg32_real(&g) };
        cobject_sample_t s;
        o->ops->sample(o, u, &s);
        ck_assert(s.pdf == 1 / o->ops->area(o));
        ray_t r;
        vec_add_scaled(r.o, s.p, 1, s.n);
        vec_neg(r.d, s.n);
        hit_t h;
        ck_assert(cobject_intersect(o, &r, 0, (real)INFINITY, &h));
        PATHPOINT pp;
        cobject_fill(o, &r, &h, &pp);
        if (pp.st[0] < REAL_C(0.5) && pp.st[1] < REAL_C(0.3))
            in++;
    }
    ck_assert_near((double)in / N, 0.15, 0.008);
    test_report_cases("parallelogram_samples_are_uniform_by_area", N);
    cobject_free(o);
}
END_TEST

static COBJECT *make_para(real s, const VECTOR3 c, void *ctx)
{
    (void)ctx;
    const real e1[3] = { REAL_C(0.9), REAL_C(0.3), REAL_C(-0.2) },
               e2[3] = { REAL_C(-0.25), REAL_C(0.8), REAL_C(0.45) };
    VECTOR3 c0, c1, c3;
    for (int k = 0; k < 3; k++) {
        c0[k] = c[k] - s * REAL_C(0.5) * (e1[k] + e2[k]);
        c1[k] = c0[k] + s * e1[k];
        c3[k] = c0[k] + s * e2[k];
    }
    return para(c0, c1, c3);
}

START_TEST(parallelogram_spawned_rays_never_rehit_at_any_scale)
{
    test_report_cases("parallelogram_spawned_rays_never_rehit_at_any_scale",
                      primcheck_over_scales(make_para, NULL, PRIMCHECK_SPAWN,
                                            GEOMCHECK_FLAT, true, 100));
}
END_TEST

START_TEST(parallelogram_sampled_points_are_hit_at_any_scale)
{
    test_report_cases("parallelogram_sampled_points_are_hit_at_any_scale",
                      primcheck_over_scales(make_para, NULL, PRIMCHECK_SAMPLED,
                                            GEOMCHECK_FLAT, true, 200));
}
END_TEST

START_TEST(parallelogram_hits_are_finite_at_any_scale)
{
    test_report_cases("parallelogram_hits_are_finite_at_any_scale",
                      primcheck_over_scales(make_para, NULL, PRIMCHECK_FINITE,
                                            GEOMCHECK_FLAT, true, 300));
}
END_TEST

START_TEST(parallelogram_sampling_has_pdf_one_over_area_at_any_scale)
{
    test_report_cases("parallelogram_sampling_has_pdf_one_over_area_at_any_scale",
                      primcheck_over_scales(make_para, NULL, PRIMCHECK_AREA,
                                            GEOMCHECK_FLAT, true, 400));
}
END_TEST

START_TEST(parallelogram_matches_the_reference_vectors)
{
    testcsv_t c;
    testcsv_open(&c, "parallelogram.csv");
    long n = 0;
    for (; testcsv_next(&c); n++) {
        VECTOR3 c0, c1, c3;
        primcheck_csv_vec(&c, "c0", c0);
        primcheck_csv_vec(&c, "c1", c1);
        primcheck_csv_vec(&c, "c3", c3);
        COBJECT *o = para(c0, c1, c3);
        PATHPOINT pp;
        if (primcheck_csv_hit(&c, o, "p", "n", &pp)) {
            double tol = primcheck_csv_tol(&c);
            ck_assert_near(pp.st[0], testcsv_num(&c, "s"), tol);
            ck_assert_near(pp.st[1], testcsv_num(&c, "t_param"), tol);
        }
        cobject_free(o);
    }
    testcsv_close(&c);
    ck_assert_int_gt(n, 0);
    test_report_cases("parallelogram_matches_the_reference_vectors", n);
}
END_TEST

START_TEST(parallelogram_sweep_never_returns_nan_or_inf)
{
    pcg32_t g;
    pcg32_seed(&g, 14, 15);
    long n = 0;
    for (int i = 0; i < 100; i++) {
        real s = ldexp(REAL_C(1.0), (int)pcg32_bounded(&g, 100) - 50);
        VECTOR3 p[3];
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++)
                p[j][k] = s * (2 * pcg32_real(&g) - 1);
        svet_error err;
        COBJECT *o = parallelogram_new(p[0], p[1], p[2], &err);
        if (!o)
            continue; /* a random degenerate one: rejected, fine */
        n += primcheck_sweep_finite(o, 2000, (uint64_t)i);
        cobject_free(o);
    }
    test_report_cases("parallelogram_sweep_never_returns_nan_or_inf", n);
}
END_TEST

Suite *test_suite(void)
{
    Suite *s = suite_create("parallelogram");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, parallelogram_hit_has_exact_st_point_and_frame);
    tcase_add_test(tc, parallelogram_respects_the_interval_and_parallel_rays_miss);
    tcase_add_test(tc, cornell_box_rectangles_face_into_the_box);
    tcase_add_test(tc, no_ray_slips_through_a_closed_box_of_parallelograms);
    tcase_add_test(tc, parallelogram_answers_as_its_two_triangles_bit_for_bit);
    tcase_add_test(tc, parallelogram_early_rejections_lose_no_hit);
    tcase_add_test(tc, parallelogram_plain_and_fast_agree_on_extreme_rays);
#ifdef SVET_SIMD
    tcase_add_test(tc, segments_that_end_before_the_plane_lose_no_hit);
#endif
#ifdef SVET_SIMD
    tcase_add_test(tc,
                   parallelogram_batch_answers_as_each_parallelogram_bit_for_bit);
#endif
#ifdef SVET_SIMD
    tcase_add_test(tc,
                   parallelogram_batch_answers_as_its_plain_loop_on_extreme_rays);
#endif
    tcase_add_test(tc, parallelogram_rejects_degenerate_and_non_parallelogram_input);
    tcase_add_test(
        tc, perpendicular_edges_are_not_called_parallel_at_any_scale);
    tcase_add_test(tc, parallelogram_samples_are_uniform_by_area);
    tcase_add_test(tc, parallelogram_spawned_rays_never_rehit_at_any_scale);
    tcase_add_test(tc, parallelogram_sampled_points_are_hit_at_any_scale);
    tcase_add_test(tc, parallelogram_hits_are_finite_at_any_scale);
    tcase_add_test(tc, parallelogram_sampling_has_pdf_one_over_area_at_any_scale);
    tcase_add_test(tc, parallelogram_matches_the_reference_vectors);
    tcase_add_test(tc, parallelogram_sweep_never_returns_nan_or_inf);
    suite_add_tcase(s, tc);
    return s;
}
