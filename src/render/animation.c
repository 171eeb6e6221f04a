/*
 * animation.c - animations (animation.h): `animation frames N` and
 * keyframes of the camera, `key FRAME camera [position V] [target V]
 * [up V] [fov F]`, interpolated linearly in the frame number, the way a
 * first animation in a textbook moves a camera between two poses (the
 * keyframes of Burtnyk and Wein 1971, in their simplest, piecewise-linear
 * form). Grammar and examples: scenes/README.md, "Animations".
 * Tests: tests/render/test_animation.c, tests/cmd/test_frames.sh
 */
#include "render/animation.h"

#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"

/* The camera keys a keyframe may give, in this order. */
enum { A_POSITION, A_TARGET, A_UP, A_FOV, A_N };

static const spec_t key_spec[A_N] = {
    [A_POSITION] = { "position", V_VEC3, 0, 0, 0, NULL },
    [A_TARGET] = { "target", V_VEC3, 0, 0, 0, NULL },
    [A_UP] = { "up", V_VEC3, F_NONZERO, 0, 0, NULL },
    [A_FOV] = { "fov", V_NUM, 0, 0, 0, NULL },
};

/* One keyframe: the values it gives (set[p]) at frame `frame`. */
typedef struct {
    int frame;
    bool set[A_N];
    real v[A_N][3];
} anim_key_t;

typedef struct {
    int frames;          /* N; 0 until the animation statement */
    anim_key_t *keys;    /* sorted by frame once the file is read */
    int nkeys, cap;
    int *by[A_N];        /* per key kind: indices of the keys giving it,
                            in frame order (made once the file is read) */
    int nby[A_N];
    int current;         /* the frame set, or -1 */
    bool based;          /* base and base_seed hold the scene's own */
    scene_camera_t base;
    uint64_t base_seed;
} anim_t;

static void anim_free(void *p)
{
    anim_t *a = p;
    if (!a)
        return;
    free(a->keys);
    for (int k = 0; k < A_N; k++)
        free(a->by[k]);
    free(a);
}

static anim_t *anim_of(const scene_t *s)
{
    return scene_part_data(s, "animation");
}

int animation_frames(const scene_t *s)
{
    const anim_t *a = anim_of(s);
    return a ? a->frames : 0;
}

int animation_frame(const scene_t *s)
{
    const anim_t *a = anim_of(s);
    return a && a->frames > 0 ? a->current : -1;
}

uint64_t animation_frame_seed(uint64_t seed, int k)
{
    return seed ^ splitmix64((uint64_t)k);
}

/* --- the statements ------------------------------------------------------- */

static svet_status st_animation(scenefile_ctx *c)
{
    static const spec_t spec[] = {
        { "frames", V_INT, F_REQUIRED, 1, ANIMATION_MAX_FRAMES, NULL },
    };
    val_t v[1];
    svet_status st = scenefile_keys(c, "animation", spec, 1, v, false);
    if (st)
        return st;
    bool fresh;
    anim_t *a = scene_part_data_new(scenefile_scene(c), "animation",
                                    sizeof *a, anim_free, &fresh);
    if (!a)
        return scenefile_fail(c, scenefile_stmt_col(c), SVET_ERR_NOMEM,
                              "out of memory");
    if (fresh)
        a->current = -1;
    if (a->frames > 0)
        return scenefile_fail(c, scenefile_stmt_col(c), SVET_ERR_PARSE,
                              "a second 'animation' statement: a scene "
                              "has one");
    a->frames = (int)v[0].i;
    return SVET_OK;
}

static svet_status st_key(scenefile_ctx *c)
{
    anim_t *a = anim_of(scenefile_scene(c));
    int n;
    const tok_t *t = scenefile_tokens(c, &n);
    if (!a || a->frames == 0)
        return scenefile_fail(c, scenefile_stmt_col(c), SVET_ERR_PARSE,
                              "'key' before 'animation frames N': the "
                              "frames come first");
    if (n < 1)
        return scenefile_fail(c, scenefile_eol_col(c), SVET_ERR_PARSE,
                              "expected the frame number after 'key'");
    char buf[32], *end;
    scenefile_tok_copy(&t[0], buf, sizeof buf);
    errno = 0;
    long f = strtol(buf, &end, 10);
    if (t[0].quoted || end == buf || *end || errno ||
        t[0].len >= (int)sizeof buf)
        return scenefile_fail(c, t[0].col, SVET_ERR_PARSE,
                              "'%s' is not a frame number", buf);
    if (f < 0 || f >= a->frames)
        return scenefile_fail(c, t[0].col, SVET_ERR_RANGE,
                              "frame %ld is not one of the animation's "
                              "frames 0..%d", f, a->frames - 1);
    if (n < 2 || !scenefile_tok_is(&t[1], "camera"))
        return scenefile_fail(c, n < 2 ? scenefile_eol_col(c) : t[1].col,
                              SVET_ERR_PARSE, "expected 'camera' after "
                              "the frame number (what the key moves)");
    for (int i = 0; i < a->nkeys; i++)
        if (a->keys[i].frame == f)
            return scenefile_fail(c, t[0].col, SVET_ERR_PARSE,
                                  "frame %ld has a key already: give its "
                                  "keys on one line", f);
    scenefile_skip(c, 2);
    val_t v[A_N];
    svet_status st = scenefile_keys(c, "key", key_spec, A_N, v, false);
    if (st)
        return st;
    anim_key_t k;
    memset(&k, 0, sizeof k);
    k.frame = (int)f;
    bool any = false;
    for (int p = 0; p < A_N; p++)
        if (v[p].set) {
            k.set[p] = any = true;
            memcpy(k.v[p], v[p].v, sizeof k.v[p]);
        }
    if (!any)
        return scenefile_fail(c, scenefile_eol_col(c), SVET_ERR_PARSE,
                              "a camera key gives at least one of "
                              "position, target, up, fov");
    if (v[A_FOV].set && !(v[A_FOV].v[0] > 0 && v[A_FOV].v[0] < 180))
        return scenefile_fail(c, v[A_FOV].col, SVET_ERR_RANGE,
                              "'fov' is the full angle in degrees: "
                              "expected more than 0 and less than 180");
    if (a->nkeys == a->cap) {
        int cap = a->cap ? 2 * a->cap : 8;
        anim_key_t *nk = realloc(a->keys, (size_t)cap * sizeof *nk);
        if (!nk)
            return scenefile_fail(c, scenefile_stmt_col(c), SVET_ERR_NOMEM,
                                  "out of memory");
        a->keys = nk, a->cap = cap;
    }
    a->keys[a->nkeys++] = k;
    return SVET_OK;
}

static int by_frame(const void *x, const void *y)
{
    const anim_key_t *a = x, *b = y;
    return (a->frame > b->frame) - (a->frame < b->frame);
}

/* Sort the keys and index them by kind, for animation_set_frame. */
static svet_status finish(scenefile_ctx *c)
{
    anim_t *a = anim_of(scenefile_scene(c));
    if (!a || a->nkeys == 0)
        return SVET_OK;
    qsort(a->keys, (size_t)a->nkeys, sizeof *a->keys, by_frame);
    for (int p = 0; p < A_N; p++) {
        a->by[p] = malloc((size_t)a->nkeys * sizeof *a->by[p]);
        if (!a->by[p])
            return scenefile_fail(c, 1, SVET_ERR_NOMEM, "out of memory");
        a->nby[p] = 0;
        for (int i = 0; i < a->nkeys; i++)
            if (a->keys[i].set[p])
                a->by[p][a->nby[p]++] = i;
    }
    return SVET_OK;
}

/* --- a frame -------------------------------------------------------------- */

/* Value kind p (n numbers) at frame k into out: the base's (in out
 * already) when no key gives p; the first key's before it, the last's
 * after it; else linear between the keys k0 <= k < k1 around k, with
 * weight t = (k - k0) / (k1 - k0), so a frame with a key has that key's
 * values exactly (t = 0). */
static void value_at(const anim_t *a, int p, int n, int k, real *out)
{
    const int m = a->nby[p];
    if (m == 0)
        return;
    /* the last key giving p at a frame <= k (binary search), or -1 */
    int lo = 0, hi = m; /* keys [0, lo) are <= k, [hi, m) are > k */
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        if (a->keys[a->by[p][mid]].frame <= k)
            lo = mid + 1;
        else
            hi = mid;
    }
    const anim_key_t *k0 = lo > 0 ? &a->keys[a->by[p][lo - 1]] : NULL;
    const anim_key_t *k1 = lo < m ? &a->keys[a->by[p][lo]] : NULL;
    if (!k0 || !k1 || k0->frame == k) {
        const anim_key_t *q = k0 ? k0 : k1;
        memcpy(out, q->v[p], (size_t)n * sizeof *out);
        return;
    }
    const real t = (real)(k - k0->frame) / (real)(k1->frame - k0->frame);
    for (int i = 0; i < n; i++)
        out[i] = k0->v[p][i] + (k1->v[p][i] - k0->v[p][i]) * t;
}

svet_status animation_set_frame(scene_t *s, int k, svet_error *err)
{
    anim_t *a = anim_of(s);
    if (!a || a->frames == 0)
        return svet_error_set(err, SVET_ERR_RANGE, "the scene has no "
                              "animation ('animation frames N')");
    if (k < 0 || k >= a->frames)
        return svet_error_set(err, SVET_ERR_RANGE, "frame %d is not one of "
                              "the animation's frames 0..%d", k,
                              a->frames - 1);
    if (!a->based) {
        a->base = s->camera;
        a->base_seed = s->render.seed;
        a->based = true;
    }
    scene_camera_t cam = a->base;
    value_at(a, A_POSITION, 3, k, cam.position);
    value_at(a, A_TARGET, 3, k, cam.target);
    value_at(a, A_UP, 3, k, cam.up);
    value_at(a, A_FOV, 1, k, &cam.fov);
    /* the camera of this frame must make an image, as the `camera`
     * statement's must (scene_validate) */
    scene_t probe = *s;
    probe.camera = cam;
    svet_error e;
    if (scene_validate(&probe, &e) != SVET_OK)
        return svet_error_set(err, e.status, "frame %d: %s", k, e.msg);
    s->camera = cam;
    s->render.seed = animation_frame_seed(a->base_seed, k);
    a->current = k;
    return SVET_OK;
}

static const scene_statement_t statements[] = {
    { "animation", st_animation },
    { "key", st_key },
    { NULL, NULL }
};

const scene_part_t animation_part = {
    .name = "animation",
    .statements = statements,
    .finish = finish,
};
