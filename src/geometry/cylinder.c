/*
 * cylinder.c - the finite cylinder of app. D: the lateral quadratic solved
 * in the frame of the axis with the discriminant of Haines et al. (Ray
 * Tracing Gems 2019, ch. 7) carried over to two dimensions, flat caps,
 * re-projected hit points and their error (pbrt-v3 sec. 3.9.4).
 * Tests: tests/geometry/test_cylinder.c; vectors: tests/vectors/cylinder.csv
 */
#include "geometry/cylinder.h"
#include "geometry/quadric.h"
#include "geometry/shape.h"

typedef struct {
    quadric_frame_t f; /* at the base; w = (top - base) / H */
    VECTOR3 top;
    real H, R;         /* height |top - base| and radius */
    bool capped;
    real area[3];      /* of the faces: lateral, base cap, top cap */
    real total;        /* area of the surface */
    real margin;       /* of lateral samples from the ends (quadric.h) */
} cylinder_t;

/* hit->b: the local (x, y, z) of a lateral hit, z in [0, H], or the local
 * (x, y) of a cap hit and b[2] = -CYLINDER_BASE or -CYLINDER_TOP, which no
 * lateral z can be. */
static bool cylinder_intersect(const COBJECT *obj, int prim, const ray_t *r,
                               real tmin, real tmax, hit_t *hit)
{
    const cylinder_t *cy = obj->shape;
    (void)prim;
    VECTOR3 ol, dl;
    int k = quadric_frame_ray(&cy->f, r, ol, dl);
    bool found = false;
    /* app. D: in the frame of the axis the lateral surface is
     * x^2 + y^2 = R^2, 0 <= z <= H: a t^2 + 2 bh t + c = 0 with
     * a = dx^2 + dy^2, bh = ox dx + oy dy, c = ox^2 + oy^2 - R^2. */
    real a = dl[X] * dl[X] + dl[Y] * dl[Y];
    if (a > 0) {
        real R2 = cy->R * cy->R;
        real bh = ol[X] * dl[X] + ol[Y] * dl[Y];
        real c = ol[X] * ol[X] + ol[Y] * ol[Y] - R2;
        /* The discriminant at the point of the projected ray nearest the
         * axis, l = o - (bh / a) d in the xy-plane: bh^2 - a c =
         * a (R^2 - |l|^2), as Haines et al. do for the sphere. A ray almost
         * along the axis makes bh / a overflow: disc is then -inf or NaN,
         * which quadric_roots rejects, and only the caps can be hit. */
        real lx = ol[X] - bh / a * dl[X], ly = ol[Y] - bh / a * dl[Y];
        real disc = a * (R2 - (lx * lx + ly * ly));
        real t[2];
        int n = quadric_roots(a, bh, c, disc, t);
        found = quadric_lateral_hit(t, n, k, ol, dl, 0, cy->H, tmin, &tmax,
                                    hit);
    }
    if (cy->capped) {
        found |= quadric_cap_hit(ol, dl, k, 0, cy->R, -CYLINDER_BASE, tmin,
                                 &tmax, hit);
        found |= quadric_cap_hit(ol, dl, k, cy->H, cy->R, -CYLINDER_TOP, tmin,
                                 &tmax, hit);
    }
    return found;
}

/* A lateral point of local (x, y, z), from a ray or a sample: z is clamped
 * to [0, H] and (x, y) re-projected onto the circle of radius R (as the
 * sphere's point in pbrt-v3 sec. 3.9.4). The re-projected x_i is within
 * gamma(6) |x_i| of a point exactly on that circle (quadric_project); that
 * is the `extra` error handed to quadric_frame_point. Sets p, p_error and
 * the outward normal n, and returns the projected local coordinates in
 * xyz. */
static void lateral_point(const cylinder_t *cy, VECTOR3 xyz, VECTOR3 p,
                          VECTOR3 p_error, VECTOR3 n)
{
    VECTOR3 q = { xyz[X], xyz[Y], 0 };
    if (!quadric_project(q, cy->R))
        vec_set(q, cy->R, 0, 0); /* on the axis: pick phi = 0 */
    real x = q[X], y = q[Y], z = fmin(fmax(xyz[Z], REAL_C(0.0)), cy->H);
    quadric_frame_point(&cy->f, cy->f.o, x, y, z,
                        ray_gamma(6) * (fabs(x) + fabs(y)), p, p_error);
    VECTOR3 nl = { x, y, 0 };
    frame_to_world(n, nl, cy->f.e1, cy->f.e2, cy->f.w);
    vec_normalize(n, n);
    vec_set(xyz, x, y, z);
}

static void cylinder_surface(const COBJECT *obj, const ray_t *r,
                             const hit_t *hit, PATHPOINT *pp)
{
    const cylinder_t *cy = obj->shape;
    (void)r;
    if (hit->b[2] == -CYLINDER_BASE || hit->b[2] == -CYLINDER_TOP) {
        bool top = hit->b[2] == -CYLINDER_TOP;
        pp->prim = top ? CYLINDER_TOP : CYLINDER_BASE;
        quadric_disk_surface(&cy->f, top ? cy->top : cy->f.o,
                             top ? cy->H : 0, cy->R, top ? 1 : -1, hit->b[0],
                             hit->b[1], pp);
        return;
    }
    pp->prim = CYLINDER_LATERAL;
    VECTOR3 q;
    vec_copy(q, hit->b);
    lateral_point(cy, q, pp->cross_point, pp->p_error, pp->ng);
    vec_copy(pp->n, pp->ng);
    /* s = phi / 2 pi, t = z / H (cylinder.h) */
    pp->st[0] = fmin(quadric_phi(q[X], q[Y]) / (2 * REAL_PI), REAL_C(1.0));
    pp->st[1] = q[Z] / cy->H;
    VECTOR3 ds = { -2 * REAL_PI * q[Y], 2 * REAL_PI * q[X], 0 };
    frame_to_world(pp->dpds, ds, cy->f.e1, cy->f.e2, cy->f.w);
    vec_scale(pp->dpdt, cy->f.w, cy->H);
    shape_frame(pp->u, pp->v, pp->n, pp->dpds);
}

static void cylinder_bounds(const COBJECT *obj, int prim, bbox_t *b)
{
    const cylinder_t *cy = obj->shape;
    (void)prim;
    /* The convex hull of the two end circles: tight. */
    bbox_empty(b);
    quadric_disk_bounds(b, cy->f.o, cy->f.w, cy->R);
    quadric_disk_bounds(b, cy->top, cy->f.w, cy->R);
}

static real cylinder_area(const COBJECT *obj)
{
    return ((const cylinder_t *)obj->shape)->total;
}

static void cylinder_sample(const COBJECT *obj, const real u[2],
                            cobject_sample_t *s)
{
    const cylinder_t *cy = obj->shape;
    real v[2] = { u[0], u[1] };
    int face = quadric_pick_face(&v[0], cy->area, cy->capped ? 3 : 1);
    if (face == CYLINDER_LATERAL) {
        /* Unrolled, the lateral face is a 2 pi R by H rectangle: phi and z
         * uniform (z kept the sample margin from the ends). */
        real phi = 2 * REAL_PI * v[1];
        real z = fmin(fmax(cy->H * v[0], cy->margin), cy->H - cy->margin);
        VECTOR3 q = { cy->R * cos(phi), cy->R * sin(phi), z };
        lateral_point(cy, q, s->p, s->p_error, s->n);
    } else if (face == CYLINDER_BASE) {
        quadric_disk_sample(&cy->f, cy->f.o, 0, cy->R, -1, v, s);
    } else {
        quadric_disk_sample(&cy->f, cy->top, cy->H, cy->R, 1, v, s);
    }
    s->pdf = 1 / cy->total;
}

/* The lateral face, F = x^2 + y^2 - R^2 about the axis; the caps are
 * flat. */
static void cylinder_normal_change(const COBJECT *obj, const PATHPOINT *pp,
                                   const VECTOR3 dp, VECTOR3 dn)
{
    const cylinder_t *cy = obj->shape;
    if (pp->prim == CYLINDER_LATERAL)
        quadric_lateral_normal_change(&cy->f, 0, pp, dp, dn);
    else
        vec_set(dn, 0, 0, 0);
}

static const cobject_ops cylinder_ops = {
    "cylinder", cylinder_intersect, cylinder_surface, cylinder_bounds,
    cylinder_area, cylinder_sample, NULL, cylinder_normal_change
};

COBJECT *cylinder_new(const VECTOR3 base, const VECTOR3 top, real radius,
                      bool capped, svet_error *err)
{
    VECTOR3 w;
    real H;
    if (quadric_check_axis("cylinder", "base", base, "top", top, radius, w,
                           &H, err) != SVET_OK)
        return NULL;
    COBJECT *obj = shape_alloc(&cylinder_ops, sizeof(cylinder_t), err);
    if (!obj)
        return NULL;
    cylinder_t *cy = obj->shape;
    quadric_frame_init(&cy->f, base, w);
    vec_copy(cy->top, top);
    cy->H = H;
    cy->R = radius;
    cy->capped = capped;
    cy->margin = quadric_lateral_margin(base, top, radius, H);
    cy->area[CYLINDER_LATERAL] = 2 * REAL_PI * radius * H;
    cy->area[CYLINDER_BASE] = cy->area[CYLINDER_TOP] =
        REAL_PI * radius * radius;
    cy->total = cy->area[CYLINDER_LATERAL] +
                (capped ? 2 * cy->area[CYLINDER_BASE] : 0);
    return quadric_object_done(obj, err);
}
