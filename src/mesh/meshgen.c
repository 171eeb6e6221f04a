/*
 * meshgen.c - procedural meshes (see meshgen.h): parametric surfaces
 * sampled on a (u, v) lattice whose seam and pole vertices are repeated
 * with bit-identical positions, and value-noise terrain.
 * Tests: tests/mesh/test_meshgen.c
 */
#include "mesh/meshgen.h"
#include "mesh/mesh.h"
#include "core/rng.h"

#include <stdlib.h>
#include <string.h>

/* A (nu + 1) x (nv + 1) lattice of vertices, index i + (nu + 1) j. */
static svet_status lattice_alloc(mesh_t *m, int nu, int nv, long ntris,
                                 svet_error *err)
{
    memset(m, 0, sizeof *m);
    long nverts = (long)(nu + 1) * (nv + 1);
    if (nverts > MESH_MAX_VERTICES || ntris > MESH_MAX_TRIANGLES)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "meshgen: %ld triangles exceed the limit",
                              ntris);
    m->nverts = (int)nverts;
    m->ntris = 0;
    m->p = malloc((size_t)nverts * sizeof *m->p);
    m->n = malloc((size_t)nverts * sizeof *m->n);
    m->st = malloc((size_t)nverts * sizeof *m->st);
    m->tri = malloc((size_t)ntris * sizeof *m->tri);
    if (!m->p || !m->n || !m->st || !m->tri) {
        free(m->p);
        free(m->n);
        free(m->st);
        free(m->tri);
        memset(m, 0, sizeof *m);
        return svet_error_set(err, SVET_ERR_NOMEM, "meshgen: out of memory");
    }
    return SVET_OK;
}

static void add_tri(mesh_t *m, int a, int b, int c)
{
    m->tri[m->ntris][0] = a;
    m->tri[m->ntris][1] = b;
    m->tri[m->ntris][2] = c;
    m->ntris++;
}

/* Two triangles per lattice quad (a b / d e, a = (i, j), b = (i+1, j),
 * d = (i, j+1)): (a b d) (b e d), counter-clockwise when (du x dv) points
 * out; `flip` reverses both for lattices where (dv x du) does. `poles`
 * leaves out the triangle that a pole row would make of zero area. */
static void lattice_quads(mesh_t *m, int nu, int nv, bool flip, bool poles)
{
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            int a = i + (nu + 1) * j, b = a + 1;
            int d = a + (nu + 1), e = d + 1;
            if (!(poles && j == 0))
                flip ? add_tri(m, a, d, b) : add_tri(m, a, b, d);
            if (!(poles && j == nv - 1))
                flip ? add_tri(m, b, d, e) : add_tri(m, b, e, d);
        }
}

static bool positive(real x)
{
    return x > 0 && isfinite(x);
}

svet_status meshgen_uv_sphere(COBJECT **out, const VECTOR3 c, real r, int nu,
                              int nv, svet_error *err)
{
    *out = NULL;
    if (!vec_is_finite(c) || !positive(r) || nu < 3 || nv < 2 ||
        nu > (1 << 15) || nv > (1 << 15))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "meshgen_uv_sphere: need finite c, r > 0, "
                              "nu >= 3, nv >= 2 (got r = %g, %d x %d)",
                              (double)r, nu, nv);
    mesh_t m;
    long ntris = 2L * nu * (nv - 1);
    svet_status st = lattice_alloc(&m, nu, nv, ntris, err);
    if (st != SVET_OK)
        return st;
    for (int j = 0; j <= nv; j++) {
        /* theta from the north pole (+z) down; the poles exactly */
        double theta = 3.14159265358979323846 * j / nv;
        for (int i = 0; i <= nu; i++) {
            /* i = nu repeats i = 0: same angle, so the same bits */
            double phi = 2 * 3.14159265358979323846 * (i % nu) / nu;
            double s = sin(theta), z = cos(theta);
            if (j == 0 || j == nv)
                s = 0, z = j == 0 ? 1 : -1;
            int k = i + (nu + 1) * j;
            vec_set(m.n[k], (real)(s * cos(phi)), (real)(s * sin(phi)),
                    (real)z);
            vec_add_scaled(m.p[k], c, r, m.n[k]);
            m.st[k][0] = (real)i / (real)nu;
            m.st[k][1] = (real)j / (real)nv;
        }
    }
    /* Counter-clockwise seen from outside: dtheta x dphi is outward. */
    lattice_quads(&m, nu, nv, true, true);
    return mesh_new(out, &m, err);
}

void meshgen_sphere_segments(long ntris, int *nu, int *nv)
{
    /* 2 nu (nv - 1) = 4 nv (nv - 1) = ntris */
    double x = 0.5 * (1 + sqrt(1 + (double)(ntris > 0 ? ntris : 0)));
    long v = lround(x);
    if (v < 2)
        v = 2;
    if (v > (1 << 14))
        v = 1 << 14;
    *nv = (int)v;
    *nu = (int)(2 * v);
    if (*nu < 6)
        *nu = 6;
}

svet_status meshgen_torus(COBJECT **out, const VECTOR3 c, real R, real r,
                          int nu, int nv, svet_error *err)
{
    *out = NULL;
    if (!vec_is_finite(c) || !positive(R) || !positive(r) || !(r < R) ||
        nu < 3 || nv < 3 || nu > (1 << 15) || nv > (1 << 15))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "meshgen_torus: need finite c, 0 < r < R, "
                              "nu, nv >= 3 (got R = %g, r = %g, %d x %d)",
                              (double)R, (double)r, nu, nv);
    mesh_t m;
    svet_status st = lattice_alloc(&m, nu, nv, 2L * nu * nv, err);
    if (st != SVET_OK)
        return st;
    for (int j = 0; j <= nv; j++) {
        double v = 2 * 3.14159265358979323846 * (j % nv) / nv;
        for (int i = 0; i <= nu; i++) {
            double u = 2 * 3.14159265358979323846 * (i % nu) / nu;
            int k = i + (nu + 1) * j;
            VECTOR3 q;
            double rho = (double)R + (double)r * cos(v);
            vec_set(q, (real)(rho * cos(u)), (real)(rho * sin(u)),
                    (real)((double)r * sin(v)));
            vec_add(m.p[k], c, q);
            vec_set(m.n[k], (real)(cos(v) * cos(u)), (real)(cos(v) * sin(u)),
                    (real)sin(v));
            m.st[k][0] = (real)i / (real)nu;
            m.st[k][1] = (real)j / (real)nv;
        }
    }
    /* du x dv is outward */
    lattice_quads(&m, nu, nv, false, false);
    return mesh_new(out, &m, err);
}

/* Value noise: random values on the integer lattice (a 64 x 64 table,
 * wrapped), smoothstep-interpolated. */
#define NOISE_N 64
static double value_noise(const double *tab, double x, double y)
{
    double fx = floor(x), fy = floor(y);
    int ix = (int)fx & (NOISE_N - 1), iy = (int)fy & (NOISE_N - 1);
    int jx = (ix + 1) & (NOISE_N - 1), jy = (iy + 1) & (NOISE_N - 1);
    double tx = x - fx, ty = y - fy;
    tx = tx * tx * (3 - 2 * tx);
    ty = ty * ty * (3 - 2 * ty);
    double a = tab[ix + NOISE_N * iy], b = tab[jx + NOISE_N * iy];
    double c = tab[ix + NOISE_N * jy], d = tab[jx + NOISE_N * jy];
    return (a + (b - a) * tx) * (1 - ty) + (c + (d - c) * tx) * ty;
}

static double fbm(const double *tab, double x, double y)
{
    /* 5 octaves, amplitudes 1/2^k; the sum of amplitudes is 31/16, so
     * dividing by it keeps f in [-1, 1]. */
    double f = 0, a = 1;
    for (int k = 0; k < 5; k++) {
        f += a * value_noise(tab, x, y);
        x *= 2;
        y *= 2;
        a *= 0.5;
    }
    return f / (31.0 / 16.0);
}

svet_status meshgen_terrain(COBJECT **out, const VECTOR3 c, real size,
                            real height, int n, uint64_t seed,
                            svet_error *err)
{
    *out = NULL;
    if (!vec_is_finite(c) || !positive(size) || !isfinite(height) || n < 1 ||
        n > (1 << 14))
        return svet_error_set(err, SVET_ERR_RANGE,
                              "meshgen_terrain: need finite c and height, "
                              "size > 0, 1 <= n <= 16384 (got %g, %d)",
                              (double)size, n);
    double tab[NOISE_N * NOISE_N];
    pcg32_t g;
    pcg32_seed(&g, seed, 0x7e77a1);
    for (int i = 0; i < NOISE_N * NOISE_N; i++)
        tab[i] = 2 * (pcg32_next(&g) * 0x1p-32) - 1;
    mesh_t m;
    svet_status st = lattice_alloc(&m, n, n, 2L * n * n, err);
    if (st != SVET_OK)
        return st;
    /* 4 noise lattice cells across the square */
    double scale = 4.0 / n, h = (double)height, cell = (double)size / n;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            int k = i + (n + 1) * j;
            double x = i * scale, y = j * scale, e = 1e-3 * scale;
            double z = h * fbm(tab, x, y);
            /* normal from the gradient by central differences */
            double dzdx = h * (fbm(tab, x + e, y) - fbm(tab, x - e, y)) /
                          (2 * e) * scale / cell;
            double dzdy = h * (fbm(tab, x, y + e) - fbm(tab, x, y - e)) /
                          (2 * e) * scale / cell;
            vec_set(m.p[k], (real)((double)c[X] + (i - 0.5 * n) * cell),
                    (real)((double)c[Y] + (j - 0.5 * n) * cell),
                    (real)((double)c[Z] + z));
            VECTOR3 nn = { (real)-dzdx, (real)-dzdy, 1 };
            vec_normalize(m.n[k], nn);
            m.st[k][0] = (real)i / (real)n;
            m.st[k][1] = (real)j / (real)n;
        }
    lattice_quads(&m, n, n, false, false); /* dx x dy = +z */
    return mesh_new(out, &m, err);
}

void meshgen_free_objects(meshgen_scene_t *s)
{
    if (!s)
        return;
    for (int i = 0; i < s->nobjs; i++)
        cobject_free(s->objs[i]);
    free(s->objs);
    memset(s, 0, sizeof *s);
}

static svet_status scene_alloc(meshgen_scene_t *s, int n, svet_error *err)
{
    memset(s, 0, sizeof *s);
    s->objs = calloc((size_t)n, sizeof *s->objs);
    if (!s->objs)
        return svet_error_set(err, SVET_ERR_NOMEM, "meshgen: out of memory");
    return SVET_OK;
}

/* Append o, made with status st (arguments are evaluated in no fixed
 * order, so callers make o first). */
static svet_status scene_add(meshgen_scene_t *s, svet_status st, COBJECT *o)
{
    if (st != SVET_OK) {
        meshgen_free_objects(s);
        return st;
    }
    s->objs[s->nobjs++] = o;
    s->ntris += o->nprims;
    return SVET_OK;
}

svet_status meshgen_sphere_grid(meshgen_scene_t *s, int n, long ntris,
                                svet_error *err)
{
    if (n < 1 || n > 64 || ntris < 1 || ntris > MESH_MAX_TRIANGLES) {
        memset(s, 0, sizeof *s);
        return svet_error_set(err, SVET_ERR_RANGE,
                              "meshgen_sphere_grid: need 1 <= n <= 64 and "
                              "1 <= ntris <= %ld (got %d, %ld)",
                              MESH_MAX_TRIANGLES, n, ntris);
    }
    svet_status st = scene_alloc(s, n * n * n, err);
    if (st != SVET_OK)
        return st;
    int nu, nv;
    meshgen_sphere_segments(ntris / ((long)n * n * n), &nu, &nv);
    for (int k = 0; k < n; k++)
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                VECTOR3 c = { (real)(3 * i), (real)(3 * j), (real)(3 * k) };
                COBJECT *o = NULL;
                st = meshgen_uv_sphere(&o, c, 1, nu, nv, err);
                st = scene_add(s, st, o);
                if (st != SVET_OK)
                    return st;
            }
    return SVET_OK;
}

svet_status meshgen_teapot_stadium(meshgen_scene_t *s, long teapot_tris,
                                   svet_error *err)
{
    svet_status st = scene_alloc(s, 3, err);
    if (st != SVET_OK)
        return st;
    int nu, nv;
    meshgen_sphere_segments(teapot_tris, &nu, &nv);
    VECTOR3 c = { 0, 0, 1 };
    COBJECT *o = NULL;
    st = meshgen_uv_sphere(&o, c, 1, nu, nv, err);
    st = scene_add(s, st, o);
    if (st != SVET_OK)
        return st;
    /* the ground: one quad of side 2000, facing +z */
    mesh_t m = { 0 };
    m.nverts = 4;
    m.p = malloc(4 * sizeof *m.p);
    m.tri = malloc(2 * sizeof *m.tri);
    if (m.p && m.tri) {
        vec_set(m.p[0], -1000, -1000, 0);
        vec_set(m.p[1], 1000, -1000, 0);
        vec_set(m.p[2], 1000, 1000, 0);
        vec_set(m.p[3], -1000, 1000, 0);
        add_tri(&m, 0, 1, 2);
        add_tri(&m, 0, 2, 3);
        st = mesh_new(&o, &m, err); /* frees m's arrays on failure */
    } else {
        free(m.p);
        free(m.tri);
        st = svet_error_set(err, SVET_ERR_NOMEM, "meshgen: out of memory");
    }
    st = scene_add(s, st, o);
    if (st != SVET_OK)
        return st;
    VECTOR3 z = { 0, 0, 0 };
    st = meshgen_torus(&o, z, 600, 120, 32, 8, err);
    return scene_add(s, st, o);
}
