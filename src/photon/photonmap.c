/*
 * photonmap.c - the photon map of ch. 8: storing photons, balancing them
 * into a left-balanced kd-tree (Jensen 2001, app. B), the k nearest by a
 * max-heap, the irradiance estimate with its filters, and the irradiance
 * precomputed at a subset of the photons (Christensen 1999).
 * Tests: tests/photon/test_photonmap.c
 */
#include "photon/photonmap.h"

#ifdef _OPENMP
#include <omp.h>
#endif
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PI_D 3.14159265358979323846

size_t photonmap_bytes(size_t count)
{
    /* the heap (count + 1 records) and the balancing's copy of the input */
    return (2 * count + 1) * sizeof(photon_t);
}

svet_status photonmap_check_count(size_t count, svet_error *err)
{
    if (count == 0 || count > PHOTONMAP_MAX_PHOTONS)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "a photon map of %zu photons (%.3g GB): the "
                              "count must be 1 to %zu", count,
                              (double)count * (double)(2 * sizeof(photon_t)) /
                                  1e9,
                              PHOTONMAP_MAX_PHOTONS);
    size_t need = photonmap_bytes(count);
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    if (pages > 0 && page > 0 &&
        (double)need > (double)pages * (double)page)
        return svet_error_set(err, SVET_ERR_NOMEM,
                              "a photon map of %zu photons needs %.3g GB, more "
                              "than this machine's %.3g GB of memory", count,
                              (double)need / 1e9,
                              (double)pages * (double)page / 1e9);
    return SVET_OK;
}

svet_status photonmap_init(photonmap_t *m, size_t count, svet_error *err)
{
    memset(m, 0, sizeof *m);
    svet_status st = photonmap_check_count(count, err);
    if (st != SVET_OK)
        return st;
    size_t need = photonmap_bytes(count);
    m->ph = malloc((count + 1) * sizeof(photon_t));
    if (!m->ph)
        return svet_error_set(err, SVET_ERR_NOMEM,
                              "a photon map of %zu photons: out of memory "
                              "(%.3g GB)", count, (double)need / 1e9);
    m->cap = count;
    return SVET_OK;
}

void photonmap_free(photonmap_t *m)
{
    free(m->ph);
    memset(m, 0, sizeof *m);
}

/* Jensen 2001, sec. 5.2: theta = acos(d.z) and phi = atan2(d.y, d.x) in
 * 256 steps each */
bool photonmap_store(photonmap_t *m, const VECTOR3 pos, RADIANCE power,
                     const VECTOR3 dir, uint8_t flags)
{
    if (m->balanced || m->n >= m->cap)
        return false;
    if (!(isfinite(pos[X]) && isfinite(pos[Y]) && isfinite(pos[Z])) ||
        !rad_is_finite(power))
        return false;
    photon_t *p = &m->ph[m->n++];
    for (int k = 0; k < 3; k++)
        p->pos[k] = (float)pos[k];
    p->power[0] = (float)power.r;
    p->power[1] = (float)power.g;
    p->power[2] = (float)power.b;
    double z = (double)dir[Z] < -1 ? -1 : (double)dir[Z] > 1 ? 1 : (double)dir[Z];
    int t = (int)(acos(z) * (256 / PI_D));
    int f = (int)floor(atan2((double)dir[Y], (double)dir[X]) * (256 / (2 * PI_D)));
    p->theta = (uint8_t)(t > 255 ? 255 : t);
    p->phi = (uint8_t)(f < 0 ? f + 256 : f > 255 ? 255 : f);
    p->axis = 0;
    p->flags = flags;
    return true;
}

void photonmap_direction(const photon_t *p, VECTOR3 dir)
{
    /* the middle of the photon's bin */
    double t = ((double)p->theta + 0.5) * (PI_D / 256);
    double f = ((double)p->phi + 0.5) * (2 * PI_D / 256);
    vec_set(dir, (real)(sin(t) * cos(f)), (real)(sin(t) * sin(f)),
            (real)cos(t));
}

/* --- balancing (Jensen 2001, app. B) ------------------------------------ */

/* How many of n nodes a left-balanced tree puts left of its root: the
 * levels above the last are full, and the last level fills from the
 * left, its first half under the left subtree. */
static size_t left_count(size_t n)
{
    size_t full = 1; /* the largest power of two <= n */
    while (full <= n / 2)
        full *= 2;
    size_t last = n - (full - 1); /* nodes on the last level */
    size_t half = full / 2;       /* the last level's room on the left */
    return (half - 1) + (last < half ? last : half);
}

static void swap_photons(photon_t *a, size_t i, size_t j)
{
    photon_t t = a[i];
    a[i] = a[j];
    a[j] = t;
}

/* Reorder a[0 .. n-1] so that a[mid] holds the photon that sorting along
 * axis would put there, none after it smaller and none before it larger:
 * Hoare's selection, each round splitting the range three ways (smaller,
 * equal, larger than a median-of-three pivot) so that runs of equal
 * coordinates end it at once. Deterministic: the tree depends on the
 * order photons were stored in and on nothing else. */
static void select_median(photon_t *a, size_t n, size_t mid, int axis)
{
    size_t lo = 0, hi = n; /* the range [lo, hi) still holds mid */
    while (hi - lo > 1) {
        float x = a[lo].pos[axis], y = a[lo + (hi - lo) / 2].pos[axis];
        float z = a[hi - 1].pos[axis];
        float pv = (x < y) ? ((y < z) ? y : (x < z) ? z : x)
                           : ((x < z) ? x : (y < z) ? z : y);
        /* [lo, lt) < pv, [lt, i) == pv, [gt, hi) > pv */
        size_t lt = lo, i = lo, gt = hi;
        while (i < gt) {
            float v = a[i].pos[axis];
            if (v < pv)
                swap_photons(a, lt++, i++);
            else if (v > pv)
                swap_photons(a, i, --gt);
            else
                i++;
        }
        if (mid < lt)
            hi = lt;
        else if (mid >= gt)
            lo = gt;
        else
            return;
    }
}

/* The axis of a[0 .. n-1]'s bounding box's widest extent. */
static int widest_axis(const photon_t *a, size_t n)
{
    float lo[3] = { a[0].pos[0], a[0].pos[1], a[0].pos[2] };
    float hi[3] = { lo[0], lo[1], lo[2] };
    for (size_t i = 1; i < n; i++)
        for (int k = 0; k < 3; k++) {
            if (a[i].pos[k] < lo[k])
                lo[k] = a[i].pos[k];
            if (a[i].pos[k] > hi[k])
                hi[k] = a[i].pos[k];
        }
    int axis = 0;
    for (int k = 1; k < 3; k++)
        if (hi[k] - lo[k] > hi[axis] - lo[axis])
            axis = k;
    return axis;
}

/* Balance a[0 .. n-1] into the heap's subtree rooted at node i. */
static void balance(photon_t *heap, photon_t *a, size_t n, size_t i)
{
    if (n == 0)
        return;
    if (n == 1) {
        heap[i] = a[0];
        heap[i].axis = 0;
        return;
    }
    int axis = widest_axis(a, n);
    size_t mid = left_count(n);
    select_median(a, n, mid, axis);
    heap[i] = a[mid];
    heap[i].axis = (uint8_t)axis;
    /* subtrees of many photons as OpenMP tasks: they touch disjoint parts
     * of a and of the heap, so the order they run in changes nothing */
    if (n > 65536) {
#pragma omp task
        balance(heap, a, mid, 2 * i);
#pragma omp task
        balance(heap, a + mid + 1, n - mid - 1, 2 * i + 1);
#pragma omp taskwait
    } else {
        balance(heap, a, mid, 2 * i);
        balance(heap, a + mid + 1, n - mid - 1, 2 * i + 1);
    }
}

svet_status photonmap_balance(photonmap_t *m, svet_error *err)
{
    if (m->balanced)
        return SVET_OK;
    size_t n = m->n;
    photon_t *heap = malloc((n + 1) * sizeof(photon_t));
    if (!heap)
        return svet_error_set(err, SVET_ERR_NOMEM,
                              "balancing %zu photons: out of memory", n);
    memset(&heap[0], 0, sizeof heap[0]);
#pragma omp parallel
#pragma omp single
    balance(heap, m->ph, n, 1);
    free(m->ph);
    m->ph = heap;
    m->balanced = true;
    return SVET_OK;
}

/* --- the k nearest (Jensen 2001, app. B: locate_photons) ---------------- */

typedef struct {
    int k, found;
    real max_d2;     /* the search radius squared; the k-th's once full */
    int32_t *idx;    /* a max-heap on (d2, idx) while full */
    real *d2;
    const real *x;
    const photon_t *ph;
    size_t n;
} search_t;

/* (d2, i) lexicographically after (d2', j): the order ties are broken by */
static bool later(real a, int32_t i, real b, int32_t j)
{
    return a > b || (a == b && i > j);
}

static void sift_down(search_t *s, int at)
{
    int n = s->found;
    for (;;) {
        int l = 2 * at + 1, r = l + 1, big = at;
        if (l < n && later(s->d2[l], s->idx[l], s->d2[big], s->idx[big]))
            big = l;
        if (r < n && later(s->d2[r], s->idx[r], s->d2[big], s->idx[big]))
            big = r;
        if (big == at)
            return;
        real td = s->d2[at];
        int32_t ti = s->idx[at];
        s->d2[at] = s->d2[big];
        s->idx[at] = s->idx[big];
        s->d2[big] = td;
        s->idx[big] = ti;
        at = big;
    }
}

static void sift_up(search_t *s, int at)
{
    while (at > 0) {
        int up = (at - 1) / 2;
        if (!later(s->d2[at], s->idx[at], s->d2[up], s->idx[up]))
            return;
        real td = s->d2[at];
        int32_t ti = s->idx[at];
        s->d2[at] = s->d2[up];
        s->idx[at] = s->idx[up];
        s->d2[up] = td;
        s->idx[up] = ti;
        at = up;
    }
}

static void consider(search_t *s, int32_t i)
{
    const photon_t *p = &s->ph[i];
    real dx = (real)p->pos[0] - s->x[0], dy = (real)p->pos[1] - s->x[1];
    real dz = (real)p->pos[2] - s->x[2];
    real d2 = dx * dx + dy * dy + dz * dz;
    if (d2 > s->max_d2)
        return;
    if (s->found < s->k) {
        s->d2[s->found] = d2;
        s->idx[s->found] = i;
        sift_up(s, s->found++);
        if (s->found == s->k)
            s->max_d2 = s->d2[0];
    } else if (later(s->d2[0], s->idx[0], d2, i)) {
        s->d2[0] = d2;
        s->idx[0] = i;
        sift_down(s, 0);
        s->max_d2 = s->d2[0];
    }
}

static void locate(search_t *s, size_t i)
{
    const photon_t *p = &s->ph[i];
    if (2 * i <= s->n) {
        int axis = p->axis;
        real d = s->x[axis] - (real)p->pos[axis];
        size_t near = d > 0 ? 2 * i + 1 : 2 * i, far = near ^ 1;
        if (near <= s->n)
            locate(s, near);
        /* the far side can hold a photon no farther than the plane; an
         * equal distance can still win a tie on the index */
        if (far <= s->n && d * d <= s->max_d2)
            locate(s, far);
    }
    consider(s, (int32_t)i);
}

int photonmap_nearest(const photonmap_t *m, const VECTOR3 x, int k,
                      real rmax, int32_t *found, real *d2)
{
    if (k < 1 || m->n == 0 || !(rmax >= 0))
        return 0;
    search_t s = { k, 0, rmax * rmax, found, d2, x, m->ph, m->n };
    locate(&s, 1);
    /* heap sort into ascending (d2, index) */
    int n = s.found;
    for (int end = n - 1; end > 0; end--) {
        real td = d2[0];
        int32_t ti = found[0];
        d2[0] = d2[end];
        found[0] = found[end];
        d2[end] = td;
        found[end] = ti;
        s.found = end;
        sift_down(&s, 0);
    }
    return n;
}

/* --- the irradiance estimate -------------------------------------------- */

#define PHOTONMAP_STACK_K 512

/* Pavicic's Gaussian (Jensen 2001, eq. 7.7) */
static const real gauss_alpha = REAL_C(0.918), gauss_beta = REAL_C(1.953);

real photonmap_filter_weight(const photonmap_query_t *q, real d2, real r2)
{
    if (q->filter == PHOTONMAP_FILTER_CONE)
        return 1 - sqrt(d2) / (q->cone_k * sqrt(r2));
    if (q->filter == PHOTONMAP_FILTER_GAUSSIAN)
        return gauss_alpha * (1 - (1 - exp(-gauss_beta * d2 / (2 * r2))) /
                                      (1 - exp(-gauss_beta)));
    return 1;
}

/* The disc's area times the filter's mean weight over it: the cone's
 * weights average 1 - 2 / (3 k) (Jensen 2001, eq. 7.6); the Gaussian's,
 * with u = d^2 / r^2 uniform on the disc,
 * alpha (1 - (1 - (2 / beta)(1 - e^(-beta / 2))) / (1 - e^(-beta))),
 * about 0.531 */
real photonmap_filter_area(const photonmap_query_t *q, real r2)
{
    real norm = REAL_PI * r2;
    if (q->filter == PHOTONMAP_FILTER_CONE)
        norm *= 1 - 2 / (3 * q->cone_k);
    else if (q->filter == PHOTONMAP_FILTER_GAUSSIAN)
        norm *= gauss_alpha *
                (1 - (1 - (2 / gauss_beta) * (1 - exp(-gauss_beta / 2))) /
                         (1 - exp(-gauss_beta)));
    return norm;
}

RADIANCE photonmap_irradiance(const photonmap_t *m, const VECTOR3 x,
                              const VECTOR3 n, const photonmap_query_t *q)
{
    int32_t idx_small[PHOTONMAP_STACK_K];
    real d2_small[PHOTONMAP_STACK_K];
    int32_t *idx = idx_small;
    real *d2 = d2_small;
    if (q->k > PHOTONMAP_STACK_K) {
        idx = malloc(sizeof *idx * (size_t)q->k);
        d2 = malloc(sizeof *d2 * (size_t)q->k);
        if (!idx || !d2) {
            free(idx == idx_small ? NULL : idx);
            free(d2 == d2_small ? NULL : d2);
            return rad_grey(0);
        }
    }
    int found = photonmap_nearest(m, x, q->k, q->rmax, idx, d2);
    real r2 = found == q->k ? d2[found - 1] : q->rmax * q->rmax;
    RADIANCE e = rad_grey(0);
    if (found > 0 && r2 > 0) {
        real r = sqrt(r2);
        for (int i = 0; i < found; i++) {
            const photon_t *p = &m->ph[idx[i]];
            VECTOR3 dir, off = { (real)p->pos[0] - x[X], (real)p->pos[1] - x[Y],
                                 (real)p->pos[2] - x[Z] };
            photonmap_direction(p, dir);
            if (SVECTOR3(dir, n) >= 0)
                continue; /* arrived from behind the surface */
            if (q->disc > 0 && fabs(SVECTOR3(off, n)) > q->disc * r)
                continue; /* off the surface's plane: another surface */
            real w = photonmap_filter_weight(q, d2[i], r2);
            e = rad_add(e, rad_scale(rad_make((real)p->power[0],
                                              (real)p->power[1],
                                              (real)p->power[2]), w));
        }
        e = rad_scale(e, 1 / photonmap_filter_area(q, r2));
    }
    if (idx != idx_small) {
        free(idx);
        free(d2);
    }
    return e;
}

/* --- the precomputed irradiance (Christensen 1999) ---------------------- */

svet_status photonmap_precompute(const photonmap_t *m,
                                 const photonmap_query_t *q,
                                 const float (*pos)[3], const float (*nrm)[3],
                                 size_t n, int threads, photonmap_t *out,
                                 svet_error *err)
{
    memset(out, 0, sizeof *out);
    out->balanced = true;
    if (n == 0)
        return SVET_OK;
    if (n > SIZE_MAX / sizeof(RADIANCE))
        return svet_error_set(err, SVET_ERR_RANGE, "precomputing the "
                              "irradiance at %zu points: too many", n);
    RADIANCE *e = malloc(n * sizeof *e);
    if (!e)
        return svet_error_set(err, SVET_ERR_NOMEM, "precomputing the "
                              "irradiance at %zu points: out of memory", n);
#ifdef _OPENMP
    int nt = threads > 0 ? threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 256) num_threads(nt)
#else
    (void)threads;
#endif
    for (long long i = 0; i < (long long)n; i++) {
        VECTOR3 x = { pos[i][0], pos[i][1], pos[i][2] };
        VECTOR3 nv = { nrm[i][0], nrm[i][1], nrm[i][2] };
        e[i] = photonmap_irradiance(m, x, nv, q);
    }
    svet_status st = photonmap_init(out, n, err);
    if (st == SVET_OK) {
        for (size_t i = 0; i < n; i++) {
            VECTOR3 x = { pos[i][0], pos[i][1], pos[i][2] };
            VECTOR3 nv = { nrm[i][0], nrm[i][1], nrm[i][2] };
            photonmap_store(out, x, e[i], nv, 0);
        }
        st = photonmap_balance(out, err);
    }
    free(e);
    if (st != SVET_OK) {
        photonmap_free(out);
        out->balanced = true;
    }
    return st;
}

bool photonmap_precomputed(const photonmap_t *irr, const VECTOR3 x,
                           const VECTOR3 n, real rmax, RADIANCE *e)
{
    int32_t idx[PHOTONMAP_PRECOMPUTED_K];
    real d2[PHOTONMAP_PRECOMPUTED_K];
    int found = photonmap_nearest(irr, x, PHOTONMAP_PRECOMPUTED_K, rmax, idx,
                                  d2);
    for (int i = 0; i < found; i++) {
        const photon_t *p = &irr->ph[idx[i]];
        VECTOR3 pn;
        photonmap_direction(p, pn);
        if (SVECTOR3(pn, n) >= REAL_C(0.9)) {
            *e = rad_make((real)p->power[0], (real)p->power[1],
                          (real)p->power[2]);
            return true;
        }
    }
    return false;
}
