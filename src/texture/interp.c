/*
 * interp.c - app. L: nearest, trilinear and parabolic interpolation of a
 * regular 3D grid of samples, and Overhauser's parabolic blending.
 * Tests: tests/texture/test_interp.c
 */
#include "texture/interp.h"

static real sample(const interp_grid_t *g, int i, int j, int k)
{
    return (real)g->v[((long)k * g->ny + j) * g->nx + i];
}

/* A coordinate clamped to [0, n - 1]; NaN reads as 0. */
static real clamp_coord(real x, int n)
{
    if (!(x > 0))
        return 0;
    return x < (real)(n - 1) ? x : (real)(n - 1);
}

real interp_nearest(const interp_grid_t *g, const VECTOR3 p)
{
    int i = (int)floor(clamp_coord(p[X], g->nx) + REAL_C(0.5));
    int j = (int)floor(clamp_coord(p[Y], g->ny) + REAL_C(0.5));
    int k = (int)floor(clamp_coord(p[Z], g->nz) + REAL_C(0.5));
    return sample(g, i, j, k);
}

/* The cell of x along an axis of n samples: the lower sample i0 (so that
 * i0 + 1 is a sample too, where n > 1) and the fraction t in [0, 1]. */
static int cell_of(real x, int n, real *t)
{
    x = clamp_coord(x, n);
    int i = (int)floor(x);
    if (i > n - 2)
        i = n > 1 ? n - 2 : 0;
    *t = x - (real)i;
    return i;
}

real interp_trilinear(const interp_grid_t *g, const VECTOR3 p)
{
    real tx, ty, tz;
    int i = cell_of(p[X], g->nx, &tx), j = cell_of(p[Y], g->ny, &ty);
    int k = cell_of(p[Z], g->nz, &tz);
    int i1 = g->nx > 1 ? i + 1 : i, j1 = g->ny > 1 ? j + 1 : j;
    int k1 = g->nz > 1 ? k + 1 : k;
    /* app. L: along x, then y, then z */
    real c00 = interp_lerp(tx, sample(g, i, j, k), sample(g, i1, j, k));
    real c10 = interp_lerp(tx, sample(g, i, j1, k), sample(g, i1, j1, k));
    real c01 = interp_lerp(tx, sample(g, i, j, k1), sample(g, i1, j, k1));
    real c11 = interp_lerp(tx, sample(g, i, j1, k1), sample(g, i1, j1, k1));
    return interp_lerp(tz, interp_lerp(ty, c00, c10),
                       interp_lerp(ty, c01, c11));
}

/* The three samples of a parabola along an axis of n samples: the centre
 * c (the nearest sample, moved in by one at a border so that c - 1 and
 * c + 1 exist) and t = x - c in [-1, 1]. With n = 2 the axis is the line
 * through samples 0 and 1 (idx 0, 0, 1 and t = x), with n = 1 constant. */
typedef struct {
    int idx[3];   /* sample indices for -1, 0, +1 */
    real t;
} axis3_t;

static axis3_t axis3(real x, int n)
{
    axis3_t a;
    x = clamp_coord(x, n);
    if (n == 1) {
        a.idx[0] = a.idx[1] = a.idx[2] = 0;
        a.t = 0;
        return a;
    }
    if (n == 2) {
        a.idx[0] = a.idx[1] = 0;
        a.idx[2] = 1;
        a.t = x;
        return a;
    }
    int c = (int)floor(x + REAL_C(0.5));
    if (c < 1)
        c = 1;
    if (c > n - 2)
        c = n - 2;
    a.idx[0] = c - 1;
    a.idx[1] = c;
    a.idx[2] = c + 1;
    a.t = x - (real)c;
    return a;
}

/* The 1D rule of an axis3_t over its three samples' values. */
static real axis3_eval(const axis3_t *a, int n, const real f[3])
{
    if (n == 1)
        return f[1];
    if (n == 2)
        return interp_lerp(a->t, f[1], f[2]);
    return interp_parabola(a->t, f[0], f[1], f[2]);
}

real interp_parabolic(const interp_grid_t *g, const VECTOR3 p)
{
    axis3_t ax = axis3(p[X], g->nx), ay = axis3(p[Y], g->ny);
    axis3_t az = axis3(p[Z], g->nz);
    /* app. L: parabolas along x for each of the 9 rows, then along y for
     * each of the 3 planes, then along z */
    real fz[3];
    for (int c = 0; c < 3; c++) {
        real fy[3];
        for (int b = 0; b < 3; b++) {
            real fx[3];
            for (int a = 0; a < 3; a++)
                fx[a] = sample(g, ax.idx[a], ay.idx[b], az.idx[c]);
            fy[b] = axis3_eval(&ax, g->nx, fx);
        }
        fz[c] = axis3_eval(&ay, g->ny, fy);
    }
    return axis3_eval(&az, g->nz, fz);
}

/* Overhauser's blend along one axis of n samples: the four samples
 * i - 1 .. i + 2 around the cell (i, i + 1) that holds x, the fraction t,
 * and which parabolas exist (not at a border). */
typedef struct {
    int idx[4];
    real t;
    bool left, right; /* the parabola through i-1, i, i+1 / i, i+1, i+2 */
} axis4_t;

static axis4_t axis4(real x, int n)
{
    axis4_t a;
    int i = cell_of(x, n, &a.t);
    for (int m = 0; m < 4; m++) {
        int s = i - 1 + m;
        a.idx[m] = s < 0 ? 0 : s > n - 1 ? n - 1 : s;
    }
    a.left = i >= 1 && i + 1 <= n - 1;
    a.right = i + 2 <= n - 1;
    return a;
}

static real axis4_eval(const axis4_t *a, int n, const real f[4])
{
    if (n == 1)
        return f[1];
    if (!a->left && !a->right) /* n = 2: the line */
        return interp_lerp(a->t, f[1], f[2]);
    /* the left parabola is centred at i (t), the right one at i + 1
     * (t - 1); blended by t (Overhauser 1968) */
    real l = a->left ? interp_parabola(a->t, f[0], f[1], f[2]) : 0;
    real r = a->right ? interp_parabola(a->t - 1, f[1], f[2], f[3]) : 0;
    if (!a->left)
        return r;
    if (!a->right)
        return l;
    return interp_lerp(a->t, l, r);
}

real interp_parabolic_blend(const interp_grid_t *g, const VECTOR3 p)
{
    axis4_t ax = axis4(p[X], g->nx), ay = axis4(p[Y], g->ny);
    axis4_t az = axis4(p[Z], g->nz);
    real fz[4];
    for (int c = 0; c < 4; c++) {
        real fy[4];
        for (int b = 0; b < 4; b++) {
            real fx[4];
            for (int a = 0; a < 4; a++)
                fx[a] = sample(g, ax.idx[a], ay.idx[b], az.idx[c]);
            fy[b] = axis4_eval(&ax, g->nx, fx);
        }
        fz[c] = axis4_eval(&ay, g->ny, fy);
    }
    return axis4_eval(&az, g->nz, fz);
}
