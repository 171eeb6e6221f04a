/*
 * accel.c - the acceleration interface of ch. 7: brute force, the grids of
 * grid.c, and the automatic choice between them (the rule in accel.h).
 * Tests: tests/test_accel.c
 */
#define _POSIX_C_SOURCE 200809L
#include "accel.h"
#include "grid.h"
#include "primset.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

struct accel {
    accel_kind kind;
    primset_t ps;
    grid_t *grid; /* NULL for brute force */
    double build_seconds;
    char describe[256];
};

void accel_params_default(accel_params_t *p)
{
    memset(p, 0, sizeof *p);
    p->kind = ACCEL_AUTO;
}

const char *accel_kind_name(accel_kind k)
{
    switch (k) {
    case ACCEL_AUTO: return "auto";
    case ACCEL_BRUTE: return "brute";
    case ACCEL_GRID: return "grid";
    case ACCEL_HGRID: return "hgrid";
    }
    return "?";
}

svet_status accel_kind_parse(const char *s, accel_kind *k, svet_error *err)
{
    for (int i = ACCEL_AUTO; i <= ACCEL_HGRID; i++)
        if (s && strcmp(s, accel_kind_name((accel_kind)i)) == 0) {
            *k = (accel_kind)i;
            return SVET_OK;
        }
    return svet_error_set(err, SVET_ERR_PARSE,
                          "unknown acceleration structure '%s' (expected "
                          "auto, brute, grid or hgrid)", s ? s : "");
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The fraction of a uniform grid's references that sit in cells of more
 * than `crowd` primitives. */
static double crowded_fraction(const grid_t *g, long crowd)
{
    const grid_node_t *top = &g->nodes[0];
    long nc = (long)top->res[0] * top->res[1] * top->res[2];
    double crowded = 0, all = 0;
    for (long c = 0; c < nc; c++) {
        double n = g->cells[top->first + c + 1] - g->cells[top->first + c];
        all += n;
        if (n > crowd)
            crowded += n;
    }
    return all > 0 ? crowded / all : 0;
}

svet_status accel_build(accel_t **out, COBJECT *const *objs, int nobjs,
                        const accel_params_t *p, svet_error *err)
{
    *out = NULL;
    accel_params_t def;
    if (!p) {
        accel_params_default(&def);
        p = &def;
    }
    if (p->kind < ACCEL_AUTO || p->kind > ACCEL_HGRID || p->grid_k < 0 ||
        p->hgrid_k < 0 || p->hgrid_leaf < 0 || p->hgrid_depth < 0 ||
        p->brute_max < 0 || p->hgrid_child_k < 0 || !isfinite(p->grid_k) ||
        !isfinite(p->hgrid_k) || !isfinite(p->hgrid_child_k))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "accel: invalid parameters");
    double t0 = now();
    accel_t *a = calloc(1, sizeof *a);
    if (!a)
        return svet_error_set(err, SVET_ERR_NOMEM, "accel: out of memory");
    svet_status st = primset_build(&a->ps, objs, nobjs, err);
    if (st != SVET_OK) {
        free(a);
        return st;
    }
    grid_params_t gu, gh;
    grid_params_uniform(&gu);
    grid_params_hierarchical(&gh);
    if (p->grid_k > 0)
        gu.k = p->grid_k;
    if (p->hgrid_k > 0)
        gh.k = p->hgrid_k;
    if (p->hgrid_leaf > 0)
        gh.leaf_max = gu.leaf_max = p->hgrid_leaf;
    if (p->hgrid_depth > 0)
        gh.max_depth = p->hgrid_depth;
    if (p->hgrid_child_k > 0)
        gh.child_k = p->hgrid_child_k;
    long brute_max = p->brute_max > 0 ? p->brute_max : ACCEL_BRUTE_MAX;
    long n = (long)a->ps.nbounded;
    char why[160] = "";
    accel_kind kind = p->kind;
    if (kind == ACCEL_AUTO) {
        if (n <= brute_max) {
            kind = ACCEL_BRUTE;
            snprintf(why, sizeof why, " (auto: %ld primitives, at most %ld)",
                     n, brute_max);
        } else {
            st = grid_build(&a->grid, &a->ps, &gu, err);
            if (st == SVET_OK) {
                double f = crowded_fraction(a->grid, ACCEL_AUTO_CELL);
                kind = f > ACCEL_AUTO_CROWDED ? ACCEL_HGRID : ACCEL_GRID;
                snprintf(why, sizeof why, " (auto: %.3g%% of the references "
                         "in cells of more than %d; %ld primitives)",
                         100 * f, ACCEL_AUTO_CELL, n);
                if (kind == ACCEL_HGRID) {
                    grid_free(a->grid);
                    a->grid = NULL;
                }
            }
        }
    }
    if (st == SVET_OK && kind == ACCEL_GRID && !a->grid)
        st = grid_build(&a->grid, &a->ps, &gu, err);
    else if (st == SVET_OK && kind == ACCEL_HGRID && !a->grid)
        st = grid_build(&a->grid, &a->ps, &gh, err);
    if (st == SVET_ERR_UNSUPPORTED) {
        snprintf(why, sizeof why, " (fell back from %s: %.96s)",
                 accel_kind_name(kind), err ? err->msg : "unsupported");
        kind = ACCEL_BRUTE;
        st = SVET_OK;
        if (err)
            svet_error_clear(err);
    }
    if (st != SVET_OK) {
        accel_free(a);
        return st;
    }
    primset_drop_bounds(&a->ps);
    a->kind = kind;
    a->build_seconds = now() - t0;
    snprintf(a->describe, sizeof a->describe, "%s%s", accel_kind_name(kind),
             why);
    *out = a;
    return SVET_OK;
}

void accel_free(accel_t *a)
{
    if (!a)
        return;
    grid_free(a->grid);
    primset_free(&a->ps);
    free(a);
}

static bool ray_ok(const ray_t *r, real tmin, real tmax)
{
    return vec_is_finite(r->o) && vec_is_finite(r->d) &&
           (r->d[X] != 0 || r->d[Y] != 0 || r->d[Z] != 0) &&
           !isnan(tmin) && !isnan(tmax) && tmin < tmax;
}

/* Brute force, and the unbounded primitives of a grid: refs [from, to). */
static bool test_range(const primset_t *ps, primset_query_t *q, uint32_t from,
                       uint32_t to, bool shadow)
{
    for (uint32_t i = from; i < to; i++)
        if (primset_test(ps, q, i) && shadow)
            return true;
    return q->found;
}

static bool run(const accel_t *a, primset_query_t *q, bool shadow)
{
    if (!a->grid)
        return test_range(&a->ps, q, 0, a->ps.nrefs, shadow);
    if (test_range(&a->ps, q, a->ps.nbounded, a->ps.nrefs, shadow) && shadow)
        return true;
    return shadow ? grid_occluded(a->grid, q) : grid_intersect(a->grid, q);
}

static bool nearest(const accel_t *a, const ray_t *r, real tmin, real tmax,
                    accel_hit_t *h, accel_counters_t *c)
{
    if (!a || !ray_ok(r, tmin, tmax))
        return false;
    primset_query_t q;
    primset_query_init(&q, r, tmin, tmax);
    run(a, &q, false);
    if (c) {
        c->cells += q.cells;
        c->tests += q.tests;
    }
    if (!q.found)
        return false;
    h->obj = primset_query_finish(&a->ps, &q);
    h->hit = q.hit;
    return true;
}

bool accel_intersect(const accel_t *a, const ray_t *r, real tmin, real tmax,
                     accel_hit_t *h)
{
    return nearest(a, r, tmin, tmax, h, NULL);
}

bool accel_intersect_counted(const accel_t *a, const ray_t *r, real tmin,
                             real tmax, accel_hit_t *h, accel_counters_t *c)
{
    return nearest(a, r, tmin, tmax, h, c);
}

bool accel_occluded(const accel_t *a, const ray_t *r, real tmin, real tmax)
{
    if (!a || !ray_ok(r, tmin, tmax))
        return false;
    primset_query_t q;
    primset_query_init(&q, r, tmin, tmax);
    return run(a, &q, true);
}

void accel_get_stats(const accel_t *a, accel_stats_t *s)
{
    memset(s, 0, sizeof *s);
    if (!a)
        return;
    s->kind = a->kind;
    s->build_seconds = a->build_seconds;
    s->bytes = sizeof *a + primset_bytes(&a->ps) + grid_bytes(a->grid);
    s->prims = (long)a->ps.nrefs;
    s->unbounded = (long)(a->ps.nrefs - a->ps.nbounded);
    if (a->grid) {
        const grid_t *g = a->grid;
        s->nodes = (long)g->nnodes;
        s->cells = (long)g->ncells;
        s->items = (long)g->nitems;
        s->empty_cells = (long)g->empty_cells;
        s->max_cell = (long)g->max_items;
        s->depth = g->depth;
        for (int k = 0; k < 3; k++) {
            s->res[k] = g->nodes[0].res[k];
            s->box_min[k] = g->nodes[0].min[k];
            s->box_max[k] = g->nodes[0].max[k];
        }
    }
}

const char *accel_describe(const accel_t *a)
{
    return a ? a->describe : "none";
}
