/*
 * irrcache.c - the irradiance cache of ch. 9: records, Ward's weights,
 * neighbour clamping, and a loose octree that grows as records arrive.
 * Tests: tests/irradiance/test_irrcache.c
 */
#include "irradiance/irrcache.h"

#include <stdlib.h>
#include <string.h>

/* A loose octree (Ulrich, "Loose Octrees", Game Programming Gems, 2000):
 * a node of side s holds the records whose sphere of influence (radius
 * a R, where weights exceed 1 / a) has a radius of at most s / 2 and a
 * centre inside the node, so the sphere lies within the node's cube grown
 * by s / 2 on every side; a lookup visits the nodes whose grown cube
 * holds x. */
struct irr_node {
    VECTOR3 centre;
    real half;            /* half the side */
    irr_node_t *child[8];
    size_t *idx;          /* record indices held here, in order added */
    size_t n, cap;
};

static irr_node_t *node_new(const VECTOR3 centre, real half)
{
    irr_node_t *nd = calloc(1, sizeof *nd);
    if (nd) {
        vec_copy(nd->centre, centre);
        nd->half = half;
    }
    return nd;
}

static void node_free(irr_node_t *nd)
{
    if (!nd)
        return;
    for (int i = 0; i < 8; i++)
        node_free(nd->child[i]);
    free(nd->idx);
    free(nd);
}

svet_status irrcache_init(irrcache_t *c, real a, real r_min, real r_max,
                          const VECTOR3 lo, const VECTOR3 hi, svet_error *err)
{
    memset(c, 0, sizeof *c);
    if (!(a > 0 && a <= 1))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "irradiance cache accuracy a = %g: it must lie "
                              "in (0, 1]", (double)a);
    if (!(r_min > 0 && r_min <= r_max && isfinite(r_max)))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "irradiance cache radii %g to %g: need 0 < "
                              "minimum <= maximum, finite", (double)r_min,
                              (double)r_max);
    real half = 0;
    VECTOR3 centre;
    for (int k = 0; k < 3; k++) {
        if (!(isfinite(lo[k]) && isfinite(hi[k]) && lo[k] <= hi[k]))
            return svet_error_set(err, SVET_ERR_RANGE,
                                  "irradiance cache bounds must be finite, "
                                  "min <= max");
        centre[k] = (lo[k] + hi[k]) / 2;
        half = real_max(half, (hi[k] - lo[k]) / 2);
    }
    c->a = a;
    c->r_min = r_min;
    c->r_max = r_max;
    c->gradients = true;
    c->clamp_neighbours = true;
    c->root = node_new(centre, real_max(half, r_max * a));
    if (!c->root)
        return svet_error_set(err, SVET_ERR_NOMEM,
                              "irradiance cache: out of memory");
    return SVET_OK;
}

void irrcache_free(irrcache_t *c)
{
    node_free(c->root);
    free(c->rec);
    memset(c, 0, sizeof *c);
}

real irrcache_weight(const irr_record_t *r, const VECTOR3 x, const VECTOR3 n)
{
    VECTOR3 d;
    vec_sub(d, x, r->p);
    real c = SVECTOR3(n, r->n);
    real s = sqrt(real_max(REAL_C(0.0), 1 - c));
    real den = vec_length(d) / r->r + s;
    return den > 0 ? 1 / den : (real)INFINITY;
}

static bool inside(const irr_node_t *nd, const VECTOR3 p, real grow)
{
    for (int k = 0; k < 3; k++)
        if (fabs(p[k] - nd->centre[k]) > nd->half + grow)
            return false;
    return true;
}

/* Grow the root until it holds p: a new root twice the size, the old one
 * its child on the side away from p. */
static bool grow_root(irrcache_t *c, const VECTOR3 p)
{
    while (!inside(c->root, p, 0)) {
        irr_node_t *old = c->root;
        VECTOR3 centre;
        int slot = 0;
        for (int k = 0; k < 3; k++) {
            bool up = p[k] >= old->centre[k]; /* grow toward p */
            centre[k] = old->centre[k] + (up ? old->half : -old->half);
            if (!up)
                slot |= 1 << k; /* the old root lies above the new centre */
        }
        irr_node_t *nr = node_new(centre, 2 * old->half);
        if (!nr)
            return false;
        nr->child[slot] = old;
        c->root = nr;
    }
    return true;
}

static bool node_push(irr_node_t *nd, size_t i)
{
    if (nd->n == nd->cap) {
        size_t cap = nd->cap ? 2 * nd->cap : 4;
        size_t *p = realloc(nd->idx, cap * sizeof *p);
        if (!p)
            return false;
        nd->idx = p;
        nd->cap = cap;
    }
    nd->idx[nd->n++] = i;
    return true;
}

/* Insert record i of influence radius rad at p: down to the smallest
 * node of half side >= rad that holds p. */
static bool insert(irr_node_t *nd, size_t i, const VECTOR3 p, real rad)
{
    while (nd->half / 2 >= rad) {
        int slot = 0;
        VECTOR3 cc;
        for (int k = 0; k < 3; k++) {
            bool up = p[k] >= nd->centre[k];
            slot |= up ? 1 << k : 0;
            cc[k] = nd->centre[k] + (up ? nd->half / 2 : -nd->half / 2);
        }
        if (!nd->child[slot]) {
            nd->child[slot] = node_new(cc, nd->half / 2);
            if (!nd->child[slot])
                return false;
        }
        nd = nd->child[slot];
    }
    return node_push(nd, i);
}

/* Each record whose sphere of influence holds x (grown by extra), in the
 * order of the tree's walk; f gets its index. */
typedef void (*visit_fn)(void *ctx, size_t i);

static void visit(const irr_node_t *nd, const VECTOR3 x, real extra,
                  visit_fn f, void *ctx)
{
    if (!nd || !inside(nd, x, nd->half + extra))
        return;
    for (size_t j = 0; j < nd->n; j++)
        f(ctx, nd->idx[j]);
    for (int k = 0; k < 8; k++)
        visit(nd->child[k], x, extra, f, ctx);
}

typedef struct {
    irrcache_t *c;
    irr_record_t *r; /* the new record */
    size_t self;
} clamp_t;

static void clamp_pair(void *ctx, size_t j)
{
    clamp_t *k = ctx;
    if (j == k->self)
        return;
    irr_record_t *o = &k->c->rec[j];
    VECTOR3 d;
    vec_sub(d, k->r->p, o->p);
    real dist = vec_length(d);
    /* Krivanek et al. 2006: neither radius exceeds the other's plus the
     * distance between them, so no record reaches past a neighbour that
     * saw something close (a thin wall, a corner) */
    if (k->r->r > o->r + dist)
        k->r->r = o->r + dist;
    if (o->r > k->r->r + dist)
        o->r = k->r->r + dist;
}

static bool record_finite(const irr_record_t *r)
{
    if (!rad_is_finite(r->e) || !isfinite(r->r))
        return false;
    for (int k = 0; k < 3; k++) {
        if (!isfinite(r->p[k]) || !isfinite(r->n[k]))
            return false;
        for (int m = 0; m < 3; m++)
            if (!isfinite(r->grad_r[k][m]) || !isfinite(r->grad_t[k][m]))
                return false;
    }
    return true;
}

/* Ward's rule for the translational gradient where R was raised (Radiance,
 * ambcomp.c, doambient(): "cap gradient" when R is clamped to the minimum
 * radius): the factor that scales channel k's gradient so that
 * |grad_t| R <= E. A record is used within a R of its point, so its
 * extrapolation then stays within E (1 -/+ a); a gradient measured over a
 * nearer R, applied across the larger one, would otherwise overshoot E by
 * up to a |grad_t| R, isolated spikes where R was raised. Applied as the
 * record is read, with its R of that moment (neighbour clamping may lower
 * it later), so the record keeps the gradient its gather measured. */
static real gradient_limit(const irr_record_t *r, int k, real e)
{
    real g = vec_length(r->grad_t[k]) * r->r;
    return g > e ? real_max(e, 0) / g : 1;
}

svet_status irrcache_add(irrcache_t *c, const irr_record_t *r,
                         svet_error *err)
{
    if (!record_finite(r))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "an irradiance record that is not finite");
    if (c->n == c->cap) {
        size_t cap = c->cap ? 2 * c->cap : 256;
        irr_record_t *p = realloc(c->rec, cap * sizeof *p);
        if (!p)
            return svet_error_set(err, SVET_ERR_NOMEM,
                                  "irradiance cache: out of memory");
        c->rec = p;
        c->cap = cap;
    }
    size_t i = c->n;
    irr_record_t *nr = &c->rec[i];
    *nr = *r;
    nr->r = nr->r < c->r_min ? c->r_min : nr->r > c->r_max ? c->r_max : nr->r;
    if (c->clamp_neighbours) {
        /* only a record within r_max can clamp or be clamped (R <= r_max):
         * the walk visits every node that may hold one */
        clamp_t k = { c, nr, i };
        visit(c->root, nr->p, c->r_max, clamp_pair, &k);
    }
    if (!grow_root(c, nr->p) || !insert(c->root, i, nr->p, c->a * c->r_max))
        return svet_error_set(err, SVET_ERR_NOMEM,
                              "irradiance cache: out of memory");
    c->n++;
    return SVET_OK;
}

typedef struct {
    const irrcache_t *c;
    const real *x, *n;
    size_t *used;
    int count, cap;
} gather_t;

static void gather(void *ctx, size_t i)
{
    gather_t *g = ctx;
    if (g->count < g->cap)
        g->used[g->count] = i;
    g->count++;
}

static int by_index(const void *a, const void *b)
{
    size_t x = *(const size_t *)a, y = *(const size_t *)b;
    return (x > y) - (x < y);
}

int irrcache_lookup(const irrcache_t *c, const VECTOR3 x, const VECTOR3 n,
                    RADIANCE *e)
{
    *e = rad_grey(0);
    if (c->n == 0)
        return 0;
    /* candidates: records whose node's grown cube holds x */
    size_t small[256];
    gather_t g = { c, x, n, small, 0, 256 };
    visit(c->root, x, 0, gather, &g);
    size_t *cand = small;
    if (g.count > g.cap) {
        cand = malloc(sizeof *cand * (size_t)g.count);
        if (!cand)
            return 0;
        gather_t g2 = { c, x, n, cand, 0, g.count };
        visit(c->root, x, 0, gather, &g2);
    }
    int nc = g.count;
    /* summed in the order added, not the order of the walk */
    qsort(cand, (size_t)nc, sizeof *cand, by_index);
    double wsum = 0, s[3] = { 0, 0, 0 };
    int used = 0;
    for (int j = 0; j < nc; j++) {
        const irr_record_t *r = &c->rec[cand[j]];
        real w = irrcache_weight(r, x, n);
        if (!(w > 1 / c->a))
            continue;
        VECTOR3 d, nn;
        vec_sub(d, x, r->p);
        vec_add(nn, n, r->n);
        /* Ward 1988: a record in front of x saw less than x would */
        if (SVECTOR3(d, nn) / 2 < REAL_C(-0.05) * r->r)
            continue;
        if (isinf(w)) {
            /* x is the record itself: its value alone */
            *e = r->e;
            if (cand != small)
                free(cand);
            return 1;
        }
        RADIANCE v = r->e;
        if (c->gradients) {
            VECTOR3 cr;
            VVECTOR3(cr, r->n, n);
            const real ek[3] = { r->e.r, r->e.g, r->e.b };
            real add[3];
            for (int k = 0; k < 3; k++)
                add[k] = SVECTOR3(cr, r->grad_r[k]) +
                         gradient_limit(r, k, ek[k]) *
                             SVECTOR3(d, r->grad_t[k]);
            v = rad_add(v, rad_make(add[0], add[1], add[2]));
        }
        wsum += (double)w;
        s[0] += (double)w * (double)v.r;
        s[1] += (double)w * (double)v.g;
        s[2] += (double)w * (double)v.b;
        used++;
    }
    if (cand != small)
        free(cand);
    if (used == 0)
        return 0;
    *e = rad_make((real)(s[0] / wsum), (real)(s[1] / wsum), (real)(s[2] / wsum));
    return used;
}
