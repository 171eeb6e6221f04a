/* cc -std=c11 -O2 -Iinclude chapters/ch10/ch10_textures.c src/texture/texture.c src/texture/solid.c src/texture/noise.c src/texture/bumpgen.c src/texture/mipmap.c src/texture/interp.c src/texture/raydiff.c src/render/camera.c src/geometry/shape.c src/materials/cobject.c src/core/frame.c src/core/vec.c src/colour/colour.c src/io/image.c src/io/netpbm.c src/io/fileio.c src/core/error.c -lm -o ch10 */
/*
 * ch10_textures.c - chapter 10, textures: spheres of noise, turbulence,
 * marble, wood and granite (Perlin 1985), a bump-mapped sphere beside the
 * smooth one (Blinn 1978; app. G's dents and bricks), the levels of a mip
 * map (Williams 1983), and a checkerboard plane toward the horizon looked
 * up with each filter against a supersampled reference; and a floor seen
 * directly and in a flat and a spherical mirror, coloured by the mip level
 * its lookups read through the ray differentials (Igehy 1999).
 *
 *   ch10_solids.ppm     noise, turbulence, marble, wood, granite spheres
 *   ch10_bump.ppm       smooth, dents, bricks: one sphere, bumped or not
 *   ch10_mipmap.ppm     the levels of a checker's mip map, side by side
 *   ch10_grazing.ppm    the plane by nearest, bilinear, trilinear, and the
 *                       reference (16 x 16 samples a pixel), top to bottom
 *   ch10_grazing.csv    each filter's RMS error against the reference by
 *                       image row (the distance grows upward)
 *   ch10_noise.csv      noise along a line, its analytic derivative and a
 *                       central difference
 *   ch10_mirror_levels.ppm  the mip level of each pixel's lookup, in false
 *                       colour (the key below the picture), through mirrors
 *
 * The CSV files are drawn by grazing.gp and noise.gp beside this file
 * (`make figures`). Spheres and plane are shaded here directly (a
 * Lambertian sphere under one distant light, an orthographic view), so
 * the program needs no renderer: scenes/textures.scn shows the same
 * textures path traced.
 * usage: ch10 [OUTDIR] [--size N]   (default out/; --help)
 */
#include "../chapter.h"
#include "colour/colour.h"
#include "io/image.h"
#include "io/netpbm.h"
#include "render/camera.h"
#include "texture/raydiff.h"
#include "texture/texture.h"

#include <math.h>

static int S = 128; /* a sphere's picture, pixels a side */

static void put(image_t *img, int x, int y, RADIANCE c)
{
    c = rad_make(colour_srgb_encode(c.r), colour_srgb_encode(c.g),
                 colour_srgb_encode(c.b));
    image_set(img, x, y, c);
}

/* The unit sphere seen along -z at pixel (i, j) of an S x S square: its
 * PATHPOINT, parametrised about the y axis, s = phi / 2 pi from +z toward
 * +x, t = theta / pi from +y. False outside the disk. */
static bool sphere_at(int i, int j, PATHPOINT *pp)
{
    real x = (2 * ((real)i + REAL_C(0.5)) / (real)S - 1) * REAL_C(1.05);
    real y = (1 - 2 * ((real)j + REAL_C(0.5)) / (real)S) * REAL_C(1.05);
    real r2 = x * x + y * y;
    if (r2 >= 1)
        return false;
    memset(pp, 0, sizeof *pp);
    real z = sqrt(1 - r2);
    vec_set(pp->cross_point, x, y, z);
    vec_copy(pp->n, pp->cross_point);
    vec_copy(pp->ng, pp->n);
    vec_set(pp->out, 0, 0, 1);
    real phi = atan2(x, z), theta = acos(y);
    pp->st[0] = (phi + REAL_PI) / (2 * REAL_PI);
    pp->st[1] = theta / REAL_PI;
    /* dP/ds = 2 pi (z, 0, -x); dP/dt = pi (cos theta sin phi, -sin theta,
     * cos theta cos phi) */
    vec_set(pp->dpds, 2 * REAL_PI * z, 0, -2 * REAL_PI * x);
    real st = sin(theta), ct = cos(theta);
    vec_set(pp->dpdt, REAL_PI * ct * sin(phi), -REAL_PI * st,
            REAL_PI * ct * cos(phi));
    return true;
}

/* Lambert under a light from the upper left, plus a little ambient. */
static real lit(const VECTOR3 n)
{
    VECTOR3 l = { REAL_C(-0.5), REAL_C(0.6), REAL_C(0.62) };
    vec_normalize(l, l);
    real c = SVECTOR3(n, l);
    return REAL_C(0.1) + REAL_C(0.9) * (c > 0 ? c : 0);
}

static int write_ppm(const char *dir, const char *name, const image_t *img)
{
    char path[1024];
    svet_error err;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    if (netpbm_write_ppm(path, img, 8, &err) != SVET_OK) {
        fprintf(stderr, "ch10: %s\n", err.msg);
        return 1;
    }
    printf("wrote %s\n", path);
    return 0;
}

static int solids(const char *dir)
{
    static const solid_kind_t kinds[] = { SOLID_NOISE, SOLID_TURBULENCE,
                                          SOLID_MARBLE, SOLID_WOOD,
                                          SOLID_GRANITE };
    const int n = 5;
    image_t img;
    svet_error err;
    if (image_alloc(&img, n * S, S, 3, &err) != SVET_OK) {
        fprintf(stderr, "ch10: %s\n", err.msg);
        return 1;
    }
    for (int k = 0; k < n; k++) {
        solid_texture_t t = solid_default(kinds[k],
                                          rad_make(REAL_C(0.1), REAL_C(0.1),
                                                   REAL_C(0.15)),
                                          rad_make(REAL_C(0.9), REAL_C(0.85),
                                                   REAL_C(0.75)));
        t.scale = kinds[k] == SOLID_GRANITE ? 6 : 2;
        for (int j = 0; j < S; j++)
            for (int i = 0; i < S; i++) {
                PATHPOINT pp;
                RADIANCE c = rad_grey(0);
                if (sphere_at(i, j, &pp))
                    c = rad_scale(solid_eval(&t, pp.cross_point), lit(pp.n));
                put(&img, k * S + i, j, c);
            }
    }
    int rc = write_ppm(dir, "ch10_solids.ppm", &img);
    image_free(&img);
    return rc;
}

static int bumps(const char *dir)
{
    image_t img;
    svet_error err;
    if (image_alloc(&img, 3 * S, S, 3, &err) != SVET_OK) {
        fprintf(stderr, "ch10: %s\n", err.msg);
        return 1;
    }
    texture_t tex[2];
    memset(tex, 0, sizeof tex);
    for (int k = 0; k < 2; k++) {
        tex[k].kind = TEXTURE_BUMPGEN;
        tex[k].scale = 1;
        tex[k].bump = bumpgen_default(k == 0 ? BUMPGEN_DENTS
                                             : BUMPGEN_BRICKS);
    }
    tex[0].bump.frequency = 24;
    const real strength[2] = { REAL_C(0.004), REAL_C(0.01) };
    for (int k = 0; k < 3; k++)
        for (int j = 0; j < S; j++)
            for (int i = 0; i < S; i++) {
                PATHPOINT pp;
                RADIANCE c = rad_grey(0);
                if (sphere_at(i, j, &pp)) {
                    if (k > 0) {
                        texture_point_t q;
                        texture_point_of(&q, &pp, 0);
                        real hs, ht;
                        texture_height(&tex[k - 1], &q, &hs, &ht);
                        texture_bump(&pp, strength[k - 1] * hs,
                                     strength[k - 1] * ht);
                    }
                    c = rad_scale(rad_make(REAL_C(0.8), REAL_C(0.45),
                                           REAL_C(0.15)), lit(pp.n));
                }
                put(&img, k * S + i, j, c);
            }
    int rc = write_ppm(dir, "ch10_bump.ppm", &img);
    image_free(&img);
    return rc;
}

/* A 256 x 256 checker of 16 squares a side, grey 0.1 and 0.9. */
static int checker_mip(mipmap_t *m)
{
    enum { N = 256 };
    static float px[N * N];
    for (int y = 0; y < N; y++)
        for (int x = 0; x < N; x++)
            px[y * N + x] = ((x / 16 + y / 16) % 2) ? 0.9f : 0.1f;
    svet_error err;
    if (mipmap_build(m, px, N, N, 1, MIPMAP_REPEAT, &err) != SVET_OK) {
        fprintf(stderr, "ch10: %s\n", err.msg);
        return 1;
    }
    return 0;
}

static int levels(const char *dir, const mipmap_t *m)
{
    /* level l drawn at 256 / 2^l pixels, left to right */
    int w = 0;
    for (int l = 0; l < m->levels; l++)
        w += m->level[l].width + 2;
    image_t img;
    svet_error err;
    if (image_alloc(&img, w, m->level[0].height, 3, &err) != SVET_OK) {
        fprintf(stderr, "ch10: %s\n", err.msg);
        return 1;
    }
    for (size_t i = 0; i < (size_t)w * (size_t)img.height * 3; i++)
        img.px[i] = 1;
    int x0 = 0;
    for (int l = 0; l < m->levels; l++) {
        const mipmap_level_t *lv = &m->level[l];
        for (int y = 0; y < lv->height; y++)
            for (int x = 0; x < lv->width; x++) {
                real v;
                mipmap_texel(m, l, x, y, &v);
                put(&img, x0 + x, y, rad_grey(v));
            }
        x0 += lv->width + 2;
    }
    int rc = write_ppm(dir, "ch10_mipmap.ppm", &img);
    image_free(&img);
    return rc;
}

/* The plane y = 0 seen from (0, 0.35, 0) looking along -z, 40 degrees
 * wide: the texture at (s, t) = (x, z) / 4, the footprint the renderer's
 * (texpart.c): the pixel's cone over |cos| at the distance. */
enum { GW = 256, GH = 64 };
static real grazing(const mipmap_t *m, mipmap_filter_t f, real px, real py,
                    bool *hit)
{
    const real spread = 2 * tan(REAL_C(20.0) * REAL_PI / 180) / GW;
    VECTOR3 d = { (px / GW - REAL_C(0.5)) * spread * GW,
                  (REAL_C(0.5) - py / GH) * spread * GH - REAL_C(0.12), -1 };
    *hit = d[Y] < 0;
    if (!*hit)
        return 1;
    real t = REAL_C(0.35) / -d[Y];
    real len = vec_length(d), dist = t * len;
    real cosv = -d[Y] / len;
    real width = dist * spread / cosv / 4;
    real out;
    mipmap_lookup(m, f, t * d[X] / 4, t * d[Z] / 4, width, &out);
    return out;
}

static int grazing_plots(const char *dir, const mipmap_t *m)
{
    image_t img;
    svet_error err;
    if (image_alloc(&img, GW, 4 * GH, 3, &err) != SVET_OK) {
        fprintf(stderr, "ch10: %s\n", err.msg);
        return 1;
    }
    static double ref[GH][GW];
    enum { SS = 16 };
    for (int j = 0; j < GH; j++)
        for (int i = 0; i < GW; i++) {
            double sum = 0;
            for (int b = 0; b < SS; b++)
                for (int a = 0; a < SS; a++) {
                    bool hit;
                    sum += (double)grazing(m, MIPMAP_BILINEAR,
                                           (real)i + ((real)a + REAL_C(0.5)) / SS,
                                           (real)j + ((real)b + REAL_C(0.5)) / SS,
                                           &hit);
                }
            ref[j][i] = sum / (SS * SS);
            put(&img, i, 3 * GH + j, rad_grey((real)ref[j][i]));
        }
    chapter_file_t cf;
    FILE *f = chapter_open(&cf, "ch10", dir, "ch10_grazing.csv");
    if (!f) {
        image_free(&img);
        return 1;
    }
    fprintf(f, "# ch10: RMS error by image row of one lookup a pixel "
               "against %d x %d bilinear samples; row 0 is the top\n"
               "row,nearest,bilinear,trilinear\n", SS, SS);
    double total[3] = { 0, 0, 0 };
    for (int j = 0; j < GH; j++) {
        double e[3] = { 0, 0, 0 };
        for (int k = 0; k < 3; k++)
            for (int i = 0; i < GW; i++) {
                bool hit;
                real v = grazing(m, (mipmap_filter_t)k, (real)i + REAL_C(0.5),
                                 (real)j + REAL_C(0.5), &hit);
                double d = (double)v - ref[j][i];
                e[k] += d * d;
                put(&img, i, k * GH + j, rad_grey(v));
            }
        fprintf(f, "%d", j);
        for (int k = 0; k < 3; k++) {
            total[k] += e[k];
            fprintf(f, ",%.6g", sqrt(e[k] / GW));
        }
        fprintf(f, "\n");
    }
    int rc = chapter_close(&cf, "ch10");
    printf("RMS error of the whole image: nearest %.4f, bilinear %.4f, "
           "trilinear %.4f\n", sqrt(total[0] / (GW * GH)),
           sqrt(total[1] / (GW * GH)), sqrt(total[2] / (GW * GH)));
    rc |= write_ppm(dir, "ch10_grazing.ppm", &img);
    image_free(&img);
    return rc;
}

static int noise_csv(const char *dir)
{
    chapter_file_t cf;
    FILE *f = chapter_open(&cf, "ch10", dir, "ch10_noise.csv");
    if (!f)
        return 1;
    fprintf(f, "# ch10: improved noise (Perlin 2002) along (x, 0.5, 0.3), "
               "its analytic d/dx and a central difference (h = 1e-3)\n"
               "x,noise,dnoise_dx,central\n");
    for (int i = 0; i <= 400; i++) {
        real x = (real)i / 100;
        VECTOR3 p = { x, REAL_C(0.5), REAL_C(0.3) }, g;
        real v = noise_perlin_grad(p, g);
        VECTOR3 a = { x + REAL_C(1e-3), REAL_C(0.5), REAL_C(0.3) };
        VECTOR3 b = { x - REAL_C(1e-3), REAL_C(0.5), REAL_C(0.3) };
        double c = ((double)noise_perlin(a) - (double)noise_perlin(b)) / 2e-3;
        fprintf(f, "%.3f,%.7g,%.7g,%.7g\n", (double)x, (double)v,
                (double)g[X], c);
    }
    return chapter_close(&cf, "ch10");
}

/* --- mip levels through mirrors ------------------------------------------- */

/* Level l's flat colour: a hue from red (level 0, the finest) through
 * yellow, green, cyan and blue to magenta (level 8), so that a trilinear
 * lookup's blend of two levels shows as the hue between them. */
static void level_colour(int l, float c[3])
{
    static const float hue[9][3] = {
        { 1, 0, 0 },       { 1, 0.5f, 0 }, { 1, 1, 0 },
        { 0, 1, 0 },       { 0, 1, 1 },    { 0, 0.5f, 1 },
        { 0, 0, 1 },       { 0.6f, 0, 1 }, { 1, 0, 1 } };
    const float *h = hue[l < 8 ? l : 8];
    c[0] = h[0], c[1] = h[1], c[2] = h[2];
}

/* A 256 x 256 mip map whose every level is one flat colour, level_colour:
 * a lookup then shows which levels it read, not the image. */
static int false_colour_mip(mipmap_t *m)
{
    enum { N = 256 };
    static float px[N * N * 3];
    svet_error err;
    if (mipmap_build(m, px, N, N, 3, MIPMAP_REPEAT, &err) != SVET_OK) {
        fprintf(stderr, "ch10: %s\n", err.msg);
        return 1;
    }
    for (int l = 0; l < m->levels; l++) {
        float c[3];
        level_colour(l, c);
        size_t n = (size_t)m->level[l].width * (size_t)m->level[l].height;
        for (size_t i = 0; i < n; i++)
            for (int k = 0; k < 3; k++)
                m->level[l].px[3 * i + (size_t)k] = c[k];
    }
    return 0;
}

/* The scene of the mirror figure: the floor y = 0 carrying the texture
 * at (s, t) = (x, z) / 2 (256 texels per 2 units), a flat mirror in the
 * plane z = -2 for x in [-3, 0.3], y in [0, 1.8], facing +z, and a mirror
 * sphere of radius 0.6 at (1.1, 0.6, -0.4). The nearest hit of ray (o, d)
 * beyond t_min: 0 none, 1 the floor, 2 the flat mirror, 3 the sphere,
 * 4 the mirror's black frame (0.05 wide at its top and right, where it
 * stands out of the floor); *t its distance, n the unit normal there. */
static const VECTOR3 ball = { REAL_C(1.1), REAL_C(0.6), REAL_C(-0.4) };
static const real ball_r = REAL_C(0.6);

static int mirror_hit(const VECTOR3 o, const VECTOR3 d, real *t, VECTOR3 n)
{
    const real t_min = REAL_C(1e-4);
    int what = 0;
    real best = 1e30;
    if (d[Y] < 0) {
        real tf = -o[Y] / d[Y];
        if (tf > t_min && tf < best)
            best = tf, what = 1, vec_set(n, 0, 1, 0);
    }
    if (d[Z] < 0) {
        real tm = (-2 - o[Z]) / d[Z];
        real x = o[X] + tm * d[X], y = o[Y] + tm * d[Y];
        if (tm > t_min && tm < best && x >= -3 && x <= REAL_C(0.3) &&
            y >= 0 && y <= REAL_C(1.8))
            best = tm, what = x < REAL_C(0.25) && y < REAL_C(1.75) ? 2 : 4,
            vec_set(n, 0, 0, 1);
    }
    VECTOR3 oc;
    vec_sub(oc, o, ball);
    real b = SVECTOR3(oc, d), c = SVECTOR3(oc, oc) - ball_r * ball_r;
    real disc = b * b - c;
    if (disc > 0) {
        real ts = -b - sqrt(disc);
        if (ts > t_min && ts < best) {
            best = ts, what = 3;
            VECTOR3 p;
            vec_add_scaled(p, o, ts, d);
            vec_sub(n, p, ball);
            vec_scale(n, n, 1 / ball_r);
        }
    }
    *t = best;
    return what;
}

/* One pixel's colour: the camera ray with its differentials, reflected
 * off the mirrors (at most 4 times; the sphere's normal turns by
 * dN = dP / r, the flat mirror's not at all) to the floor, where the
 * footprint in (s, t) picks the levels of a trilinear lookup, as the
 * renderer's texture part does (texpart.c, raydiff.c). The sky is grey. */
static void mirror_pixel(const camera_t *cam, const mipmap_t *m, int i, int j,
                         real c[3])
{
    ray_t r;
    camera_ray(cam, (real)i + REAL_C(0.5), (real)j + REAL_C(0.5), &r);
    raydiff_t rd;
    raydiff_camera(&rd, cam, r.d);
    c[0] = c[1] = c[2] = REAL_C(0.5);
    for (int bounce = 0; bounce <= 4; bounce++) {
        real t;
        VECTOR3 n, p;
        int what = mirror_hit(r.o, r.d, &t, n);
        if (what == 4)
            c[0] = c[1] = c[2] = 0;
        if (!what || what == 4 || !raydiff_transfer(&rd, r.d, t, n))
            return;
        vec_add_scaled(p, r.o, t, r.d);
        if (what == 1) {
            const VECTOR3 dpds = { 2, 0, 0 }, dpdt = { 0, 0, 2 };
            real w = raydiff_footprint(&rd, dpds, dpdt);
            mipmap_lookup(m, MIPMAP_TRILINEAR, p[X] / 2, p[Z] / 2, w, c);
            return;
        }
        VECTOR3 dndx = { 0, 0, 0 }, dndy = { 0, 0, 0 }, dr;
        if (what == 3) {
            vec_scale(dndx, rd.dpdx, 1 / ball_r);
            vec_scale(dndy, rd.dpdy, 1 / ball_r);
        }
        raydiff_reflect(&rd, r.d, n, dndx, dndy);
        vec_add_scaled(dr, r.d, -2 * SVECTOR3(r.d, n), n);
        vec_copy(r.o, p);
        vec_copy(r.d, dr);
    }
}

static int mirror_levels(const char *dir)
{
    mipmap_t m;
    if (false_colour_mip(&m))
        return 1;
    camera_t cam;
    svet_error err;
    const VECTOR3 eye = { 0, REAL_C(1.2), REAL_C(3.5) };
    const VECTOR3 target = { 0, REAL_C(0.5), -1 }, up = { 0, 1, 0 };
    int w = 5 * S / 2, h = 3 * S / 2;
    image_t img;
    if (camera_init(&cam, eye, target, up, 60, CAMERA_FOV_X, w, h, &err) !=
            SVET_OK ||
        image_alloc(&img, w, h + h / 8, 3, &err) != SVET_OK) {
        fprintf(stderr, "ch10: %s\n", err.msg);
        mipmap_free(&m);
        return 1;
    }
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            real c[3];
            mirror_pixel(&cam, &m, i, j, c);
            put(&img, i, j, rad_make(c[0], c[1], c[2]));
        }
    /* the key: levels 0 .. 8 left to right under the picture */
    for (int j = h; j < img.height; j++)
        for (int i = 0; i < w; i++) {
            float f[3];
            level_colour(9 * i / w, f);
            put(&img, i, j, rad_make(f[0], f[1], f[2]));
        }
    int rc = write_ppm(dir, "ch10_mirror_levels.ppm", &img);
    image_free(&img);
    mipmap_free(&m);
    return rc;
}

int main(int argc, char **argv)
{
    double size = 128;
    const chapter_opt_t opts[] = {
        { "--size", "N", "pixels a side of each sphere", &size, 16, 1024 },
    };
    const chapter_cli_t cli = {
        "ch10",
        "Chapter 10: solid textures, bump mapping, mip-map levels and the "
        "grazing\ncheckerboard by each filter, as PPM pictures and CSV files "
        "(for `make figures`).",
        "out", opts, 1
    };
    const char *dir;
    int rc = chapter_begin(&cli, argc, argv, &dir);
    if (rc >= 0)
        return rc;
    S = (int)size;
    mipmap_t m;
    if (checker_mip(&m))
        return 1;
    rc = solids(dir) || bumps(dir) || levels(dir, &m) ||
         grazing_plots(dir, &m) || noise_csv(dir) || mirror_levels(dir);
    mipmap_free(&m);
    return rc ? 1 : 0;
}
