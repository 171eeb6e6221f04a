/*
 * render.c - tiles, passes and threads around the integrator (ch. 5), a
 * pass abandoned and undone when asked (render_pass_until: Ctrl-C), and
 * the camera rays of 8 x 8 pixels given to the tracer at once where it
 * takes packets (the grids of ch. 7: chapters/ch07/README.md), and the
 * pass of app. F's subsampling through the program's subsample_ops; a
 * method's pre-pass computed or read from a file (render_init_prepass).
 * Tests: tests/render/test_render.c, tests/render/test_subsample.c,
 * tests/cmd/test_merge.sh (the saved pre-pass)
 */
#include "render/render.h"

#include "accel/accel.h"
#include "render/scenepart.h"
#include "render/subsample.h" /* its types; the code is the program's */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

/* The tracer of r: through the acceleration layer of ch. 7 where the
 * program offers it (s->features->accel: the grids and the batched brute
 * force in the svet command), which builds the scene's choice among the
 * structures offered (AUTO picks brute force for a few primitives and a
 * grid only when there are many: accel.h); else ch. 5's list of the
 * objects (tracer.h), and the scene may ask for nothing else. */
static svet_status tracer_init(render_t *r, const scene_t *s,
                               svet_error *err)
{
    const accel_layer_t *L = s->features ? s->features->accel : NULL;
    const accel_kind kind = (accel_kind)s->render.accel;
    if (!L) {
        if (kind != ACCEL_AUTO && kind != ACCEL_BRUTE)
            return svet_error_set(err, SVET_ERR_UNSUPPORTED,
                                  "accel %s: this program was built "
                                  "without %s", accel_kind_name(kind),
                                  accel_kind_needs(kind));
        r->tracer = tracer_brute(s);
        snprintf(r->accel_choice, sizeof r->accel_choice,
                 "brute (the list of %d objects of ch. 5)", s->nobjects);
        return SVET_OK;
    }
    /* every number 0: its default (accel_params_default()) */
    accel_params_t ap = { .kind = kind, .structures = s->features->accels };
    accel_t *a = NULL;
    svet_status st = L->build(&a, s->objects, s->nobjects, &ap, err);
    if (st != SVET_OK)
        return st;
    r->layer = L;
    r->accel = a;
    r->tracer = L->tracer(a);
    /* packets of camera rays only where the structure is faster with
     * them: brute force (the Cornell box) keeps the per-pixel loop */
    if (L->has_packets(a))
        r->intersect_packet = L->intersect_packet;
    r->packets = s->render.packets && r->intersect_packet;
    if (r->packets)
        snprintf(r->accel_choice, sizeof r->accel_choice,
                 "%s; camera rays in packets of %d x %d", L->describe(a),
                 RENDER_PACKET, RENDER_PACKET);
    else
        snprintf(r->accel_choice, sizeof r->accel_choice, "%s",
                 L->describe(a));
    return SVET_OK;
}

svet_status render_check_prepass(const scene_t *s, svet_error *err)
{
    if (!s->render.method)
        return svet_error_set(err, SVET_ERR_UNSUPPORTED,
                              "a saved pre-pass: the integrator has no "
                              "pre-pass");
    if (!s->render.method->save || !s->render.method->load)
        return svet_error_set(err, SVET_ERR_UNSUPPORTED,
                              "a saved pre-pass: integrator %s does not "
                              "save its pre-pass (photon does)",
                              s->render.method->name);
    return SVET_OK;
}

svet_status render_save_prepass(const render_t *r, FILE *f, svet_error *err)
{
    svet_status st = render_check_prepass(r->scene, err);
    if (st != SVET_OK)
        return st;
    return r->method->save(r->method_state, f, err);
}

svet_status render_init(render_t *r, const scene_t *s, svet_error *err)
{
    return render_init_prepass(r, s, NULL, err);
}

svet_status render_init_prepass(render_t *r, const scene_t *s, FILE *f,
                                svet_error *err)
{
    memset(r, 0, sizeof *r);
    if (f) {
        svet_status saves = render_check_prepass(s, err);
        if (saves != SVET_OK)
            return saves;
    }
    r->scene = s;
    const scene_camera_t *c = &s->camera;
    camera_fov_axis axis = c->fov_axis == SCENE_FOV_Y ? CAMERA_FOV_Y
                           : c->fov_axis == SCENE_FOV_DIAGONAL
                               ? CAMERA_FOV_DIAGONAL
                               : CAMERA_FOV_X;
    svet_status st = camera_init(&r->camera, c->position, c->target, c->up,
                                 c->fov, axis, c->width, c->height, err);
    if (st != SVET_OK)
        return st;
    /* "Model only what the scene requires": no light table without lights */
    if (scene_has_lights(s)) {
        st = lightset_build(&r->lights, s, err);
        if (st != SVET_OK)
            return st;
    }
    st = tracer_init(r, s, err);
    if (st != SVET_OK) {
        render_free(r);
        return st;
    }
    if (s->render.subsample_step > 0 &&
        !(s->features && s->features->subsample)) {
        render_free(r);
        return svet_error_set(err, SVET_ERR_UNSUPPORTED,
                              "subsample: this program was built without "
                              "the subsampling of app. F");
    }
    /* the indirect diffuse light alone: the path tracer's modes but
     * ambient occlusion, and the methods that say they separate it */
    if (s->render.light == SCENE_LIGHT_INDIRECT &&
        (s->render.method ? !s->render.method->indirect_light
                          : s->render.integrator == SCENE_INTEGRATOR_AO)) {
        render_free(r);
        return svet_error_set(err, SVET_ERR_UNSUPPORTED,
                              "'render light indirect': integrator %s does "
                              "not separate the indirect diffuse light (path, "
                              "nee, bsdf, direct and the methods that do: "
                              "irradiance)",
                              s->render.method ? s->render.method->name
                                               : "ao");
    }
    integrator_init(&r->integrator, s, &r->lights, r->tracer);
    /* a rendering method of Part II (scenepart.h): its pre-pass now,
     * camera rays one at a time (it traces them itself) */
    if (s->render.method) {
        r->method = s->render.method;
        r->packets = false;
        st = f ? r->method->load(&r->method_state, r, f, err)
               : r->method->prepare(&r->method_state, r, s->render.threads,
                                    err);
        if (st != SVET_OK) {
            r->method_state = NULL;
            render_free(r);
            return st;
        }
    }
    st = image_accum_alloc(&r->acc, c->width, c->height, err);
    if (st != SVET_OK) {
        render_free(r);
        return st;
    }
    r->sum2 = calloc((size_t)c->width * (size_t)c->height * 3, sizeof *r->sum2);
    if (!r->sum2) {
        render_free(r);
        return svet_error_set(err, SVET_ERR_NOMEM, "render: out of memory");
    }
    return SVET_OK;
}

void render_free(render_t *r)
{
    lightset_free(&r->lights);
    if (r->accel && r->layer)
        r->layer->free(r->accel);
    if (r->method && r->method->free && r->method_state)
        r->method->free(r->method_state);
    image_accum_free(&r->acc);
    free(r->sum2);
    image_free(&r->sub);
    free(r->sub_mask);
    memset(r, 0, sizeof *r);
}

/* Sample `sample` of pixel (x, y): its numbers g and its camera ray. */
static void camera_sample(const render_t *r, int x, int y, long sample,
                          pcg32_t *g, ray_t *ray)
{
    uint64_t pixel = (uint64_t)y * (uint64_t)r->camera.width + (uint64_t)x;
    rng_for_sample(g, r->scene->render.seed, pixel, (uint64_t)sample);
    /* dimensions 0, 1: the position in the pixel (box filter) */
    real jx = pcg32_real(g), jy = pcg32_real(g);
    camera_ray(&r->camera, (real)x + jx, (real)y + jy, ray);
}

RADIANCE render_sample(const render_t *r, int x, int y, long sample,
                       integrator_stats_t *st)
{
    pcg32_t g;
    ray_t ray;
    camera_sample(r, x, y, sample, &g, &ray);
    if (r->method)
        return r->method->li(r->method_state, r, &ray, sample, &g, st);
    return integrator_li(&r->integrator, &ray, &g, st);
}

/* Add sample L to pixel (x, y): its sum, count and sum of squares. */
static void accumulate(render_t *r, int x, int y, RADIANCE L)
{
    if (image_accum_add(&r->acc, x, y, L)) {
        image_fixed_t *q = r->sum2 + 3 * ((size_t)y * (size_t)r->camera.width +
                                          (size_t)x);
        image_fixed_add_double(&q[0], (double)L.r * (double)L.r, IMAGE_SUM2_Q);
        image_fixed_add_double(&q[1], (double)L.g * (double)L.g, IMAGE_SUM2_Q);
        image_fixed_add_double(&q[2], (double)L.b * (double)L.b, IMAGE_SUM2_Q);
    }
}

/* Samples [s0, s1) of the pixels [x0, x1) x [y0, y1), one at a time. */
static void pixels_one_by_one(render_t *r, int x0, int y0, int x1, int y1,
                              long s0, long s1, integrator_stats_t *st)
{
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++)
            for (long s = s0; s < s1; s++)
                accumulate(r, x, y, render_sample(r, x, y, s, st));
}

/* The same, with the camera rays of each sample of each block of
 * RENDER_PACKET x RENDER_PACKET pixels traced at once
 * (intersect_packet: one walk of the grid for them all). A pixel
 * still adds its samples in index order and each sample draws its own
 * numbers, and the packet gives each ray the hit it would find alone, so
 * the image is pixels_one_by_one()'s, bit for bit. */
static void pixels_in_packets(render_t *r, int x0, int y0, int x1, int y1,
                              long s0, long s1, integrator_stats_t *st)
{
    enum { N = RENDER_PACKET * RENDER_PACKET };
    ray_t ray[N];
    pcg32_t g[N];
    hit_t hit[N];
    const COBJECT *obj[N];
    bool found[N];
    for (int by = y0; by < y1; by += RENDER_PACKET)
        for (int bx = x0; bx < x1; bx += RENDER_PACKET) {
            int bx1 = bx + RENDER_PACKET < x1 ? bx + RENDER_PACKET : x1;
            int by1 = by + RENDER_PACKET < y1 ? by + RENDER_PACKET : y1;
            for (long s = s0; s < s1; s++) {
                int n = 0;
                for (int y = by; y < by1; y++)
                    for (int x = bx; x < bx1; x++, n++)
                        camera_sample(r, x, y, s, &g[n], &ray[n]);
                r->intersect_packet(r->accel, ray, n, 0, (real)INFINITY, hit,
                                    obj, found);
                n = 0;
                for (int y = by; y < by1; y++)
                    for (int x = bx; x < bx1; x++, n++) {
                        /* hit[n], obj[n] were written only on a hit,
                         * and are read only then */
                        accumulate(r, x, y,
                                   integrator_li_hit(&r->integrator,
                                                     &ray[n], found[n],
                                                     &hit[n],
                                                     found[n] ? obj[n] : NULL,
                                                     &g[n], st));
                    }
            }
        }
}

/* Samples [spp_done, spp_end) of every tile, skipping the tiles not yet
 * begun once *stop (when not NULL) is non-zero; returns how many were
 * skipped. The statistics and spp_done move on only for a whole pass. */
static long pass(render_t *r, long spp_end, int threads,
                 render_progress_fn progress, void *ctx,
                 const volatile sig_atomic_t *stop)
{
    const int W = r->camera.width, H = r->camera.height;
    const int tx = (W + RENDER_TILE - 1) / RENDER_TILE;
    const int ty = (H + RENDER_TILE - 1) / RENDER_TILE;
    const long ntiles = (long)tx * ty;
    const long s0 = r->spp_done;
    long done = 0, skipped = 0;
    uint64_t rays = 0, paths = 0;
#ifdef _OPENMP
    int nt = threads > 0 ? threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt) \
    reduction(+ : rays, paths, skipped)
#else
    (void)threads;
#endif
    for (long t = 0; t < ntiles; t++) {
        if (stop && *stop) {
            skipped++; /* an OpenMP loop cannot break: pass over the rest */
            continue;
        }
        integrator_stats_t st = { 0, 0 };
        int x0 = (int)(t % tx) * RENDER_TILE, y0 = (int)(t / tx) * RENDER_TILE;
        int x1 = x0 + RENDER_TILE < W ? x0 + RENDER_TILE : W;
        int y1 = y0 + RENDER_TILE < H ? y0 + RENDER_TILE : H;
        if (r->crop_x1 > 0) { /* the tile's part inside the crop */
            x0 = x0 > r->crop_x0 ? x0 : r->crop_x0;
            y0 = y0 > r->crop_y0 ? y0 : r->crop_y0;
            x1 = x1 < r->crop_x1 ? x1 : r->crop_x1;
            y1 = y1 < r->crop_y1 ? y1 : r->crop_y1;
        }
        if (r->packets && r->intersect_packet)
            pixels_in_packets(r, x0, y0, x1, y1, s0, spp_end, &st);
        else
            pixels_one_by_one(r, x0, y0, x1, y1, s0, spp_end, &st);
        rays += st.rays;
        paths += st.paths;
        if (progress) {
#ifdef _OPENMP
#pragma omp critical(svet_render_progress)
#endif
            {
                done++;
                progress(ctx, done, ntiles);
            }
        }
    }
    if (skipped == 0) {
        r->stats.rays += rays;
        r->stats.paths += paths;
        r->spp_done = spp_end > s0 ? spp_end : s0;
    }
    return skipped;
}

/* --- app. F: subsampling --------------------------------------------- */

/* What a computed pixel needs: the renderer, its samples, the totals. */
typedef struct {
    render_t *r;
    long s0, s1;
    uint64_t rays, paths;
    long done, total;
    render_progress_fn progress;
    void *ctx;
} sparse_t;

/* Pixel (x, y) with all its samples, added to the sums in index order as
 * the image loop adds them; out is the mean image_accum_resolve() gives
 * it. Called from several threads, never twice for one pixel. */
static void sparse_pixel(void *c, int x, int y, float out[3])
{
    sparse_t *q = c;
    render_t *r = q->r;
    integrator_stats_t st = { 0, 0 };
    pixels_one_by_one(r, x, y, x + 1, y + 1, q->s0, q->s1, &st);
    size_t i = (size_t)y * (size_t)r->camera.width + (size_t)x;
    double n = (double)r->acc.count[i];
    for (int k = 0; k < 3; k++)
        out[k] = n > 0 ? (float)(image_fixed_value(&r->acc.sum[3 * i +
                                                               (size_t)k],
                                                   IMAGE_SUM_Q) / n)
                       : 0.0f;
#ifdef _OPENMP
#pragma omp atomic
#endif
    q->rays += st.rays;
#ifdef _OPENMP
#pragma omp atomic
#endif
    q->paths += st.paths;
    if (q->progress) {
#ifdef _OPENMP
#pragma omp critical(svet_render_progress)
#endif
        {
            q->done++;
            q->progress(q->ctx, q->done, q->total);
        }
    }
}

/* Whether a pass to spp_end can be subsampled: the first and only one,
 * over the whole image. */
static svet_status sparse_check(const render_t *r, long spp_end,
                                svet_error *err)
{
    if (r->scene->render.subsample_step <= 0)
        return SVET_OK;
    if (r->crop_x1 > 0)
        return svet_error_set(err, SVET_ERR_UNSUPPORTED,
                              "subsample: a crop of the image (a part of a "
                              "split render) cannot be subsampled: the "
                              "refinement needs the whole image");
    if (r->spp_done > 0 || r->sub.px)
        return svet_error_set(err, SVET_ERR_UNSUPPORTED,
                              "subsample: the samples of a pixel are "
                              "computed in one pass, from sample 0: no "
                              "further pass, and no part of a split render "
                              "from sample %ld", r->spp_done);
    if (spp_end <= 0)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "subsample: a pass of no samples");
    return SVET_OK;
}

/* The one pass of a subsampled render: samples [0, spp_end) of the
 * pixels app. F chooses; *skipped non-zero when *stop ended it (r then
 * holds no image, its sums are the caller's to undo). */
static svet_status sparse_pass(render_t *r, long spp_end, int threads,
                               render_progress_fn progress, void *ctx,
                               const volatile sig_atomic_t *stop,
                               long *skipped, svet_error *err)
{
    const int W = r->camera.width, H = r->camera.height;
    const scene_render_t *sr = &r->scene->render;
    *skipped = 0;
    image_t img;
    svet_status st = image_alloc(&img, W, H, 3, err);
    if (st != SVET_OK)
        return st;
    uint8_t *mask = malloc((size_t)W * (size_t)H);
    if (!mask) {
        image_free(&img);
        return svet_error_set(err, SVET_ERR_NOMEM, "render: out of memory");
    }
    sparse_t q = { r, 0, spp_end, 0, 0, 0, (long)W * H, progress, ctx };
    subsample_params_t p = { sr->subsample_step, sr->subsample_threshold };
    long n = 0;
    bool stopped = false;
    st = r->scene->features->subsample->image(&img, &p, sparse_pixel, &q,
                                              mask, &n, threads, stop,
                                              &stopped, err);
    if (st != SVET_OK || stopped) {
        image_free(&img);
        free(mask);
        *skipped = stopped ? 1 : 0;
        return st;
    }
    r->sub = img;
    r->sub_mask = mask;
    r->sub_computed = n;
    r->stats.rays += q.rays;
    r->stats.paths += q.paths;
    r->spp_done = spp_end;
    return SVET_OK;
}

/* One pass: the image loop's, or app. F's. */
static svet_status run_pass(render_t *r, long spp_end, int threads,
                            render_progress_fn progress, void *ctx,
                            const volatile sig_atomic_t *stop,
                            long *skipped, svet_error *err)
{
    if (r->scene->render.subsample_step > 0)
        return sparse_pass(r, spp_end, threads, progress, ctx, stop, skipped,
                           err);
    *skipped = pass(r, spp_end, threads, progress, ctx, stop);
    return SVET_OK;
}

/* A method's begin_pass for samples [spp_done, spp_end), if it has one. */
static svet_status begin_pass(render_t *r, long spp_end, int threads,
                              svet_error *err)
{
    if (!r->method || !r->method->begin_pass || spp_end <= r->spp_done)
        return SVET_OK;
    return r->method->begin_pass(r->method_state, r, r->spp_done, spp_end,
                                 threads, err);
}

svet_status render_pass(render_t *r, long spp_end, int threads,
                        render_progress_fn progress, void *ctx)
{
    svet_status st = sparse_check(r, spp_end, &r->error);
    if (st == SVET_OK)
        st = begin_pass(r, spp_end, threads, &r->error);
    long skipped;
    if (st == SVET_OK)
        st = run_pass(r, spp_end, threads, progress, ctx, NULL, &skipped,
                      &r->error);
    return st;
}

svet_status render_pass_until(render_t *r, long spp_end, int threads,
                              render_progress_fn progress, void *ctx,
                              const volatile sig_atomic_t *stop,
                              bool *abandoned, svet_error *err)
{
    /* The sums as they are, to put back if the pass is cut short: a
     * sample added cannot be taken out again exactly in floating point. */
    const size_t n = (size_t)r->camera.width * (size_t)r->camera.height;
    image_fixed_t *sum = malloc(3 * n * sizeof *sum),
                  *sum2 = malloc(3 * n * sizeof *sum2);
    uint64_t *count = malloc(n * sizeof *count),
             *nonfinite = malloc(n * sizeof *nonfinite);
    *abandoned = false;
    svet_status st = sparse_check(r, spp_end, err);
    if (st != SVET_OK || !sum || !sum2 || !count || !nonfinite) {
        free(sum);
        free(sum2);
        free(count);
        free(nonfinite);
        return st != SVET_OK ? st : svet_error_set(err, SVET_ERR_NOMEM,
                                                   "render: out of memory");
    }
    st = begin_pass(r, spp_end, threads, err);
    if (st != SVET_OK) {
        free(sum);
        free(sum2);
        free(count);
        free(nonfinite);
        return st;
    }
    memcpy(sum, r->acc.sum, 3 * n * sizeof *sum);
    memcpy(sum2, r->sum2, 3 * n * sizeof *sum2);
    memcpy(count, r->acc.count, n * sizeof *count);
    memcpy(nonfinite, r->acc.nonfinite, n * sizeof *nonfinite);
    long skipped = 0;
    st = run_pass(r, spp_end, threads, progress, ctx, stop, &skipped, err);
    if (st != SVET_OK || skipped > 0) {
        memcpy(r->acc.sum, sum, 3 * n * sizeof *sum);
        memcpy(r->sum2, sum2, 3 * n * sizeof *sum2);
        memcpy(r->acc.count, count, n * sizeof *count);
        memcpy(r->acc.nonfinite, nonfinite, n * sizeof *nonfinite);
        *abandoned = st == SVET_OK;
    }
    free(sum);
    free(sum2);
    free(count);
    free(nonfinite);
    return st;
}

svet_status render_image(const render_t *r, image_t *out, svet_error *err)
{
    if (r->sub.px) { /* app. F: computed and interpolated pixels */
        svet_status st = image_alloc(out, r->sub.width, r->sub.height, 3,
                                     err);
        if (st == SVET_OK)
            memcpy(out->px, r->sub.px, 3 * (size_t)r->sub.width *
                                           (size_t)r->sub.height *
                                           sizeof *out->px);
        return st;
    }
    uint64_t empty;
    return image_accum_resolve(&r->acc, out, &empty, err);
}

svet_status render_variance(const render_t *r, image_t *out, svet_error *err)
{
    const int W = r->camera.width, H = r->camera.height;
    svet_status st = image_alloc(out, W, H, 3, err);
    if (st != SVET_OK)
        return st;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            size_t i = (size_t)y * (size_t)W + (size_t)x;
            double n = (double)r->acc.count[i];
            float *p = image_at(out, x, y);
            for (int c = 0; c < 3; c++) {
                if (n < 2) {
                    p[c] = 0;
                    continue;
                }
                double mean = image_fixed_value(&r->acc.sum[3 * i + c],
                                                IMAGE_SUM_Q) / n;
                double s2 = (image_fixed_value(&r->sum2[3 * i + c],
                                               IMAGE_SUM2_Q) - n * mean * mean)
                            / (n - 1);
                p[c] = (float)(s2 > 0 ? s2 / n : 0);
            }
        }
    return SVET_OK;
}
