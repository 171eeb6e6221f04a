/*
 * chapter_scene.h - what the chapter programs that render a scene of
 * Part II (ch. 8, 9, 11) share: the scene (a file or a text, offering the
 * program's parts) at a fraction of its resolution with the program's
 * settings, and the message of a failure.
 * Header-only like chapter.h, so a program's one cc line needs no extra
 * file (it lists src/render/ already).
 * Tests: tests/chapters/test_chapters.c runs the programs.
 */
#ifndef SVET_CHAPTER_SCENE_H
#define SVET_CHAPTER_SCENE_H

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "chapter.h"
#include "render/scenefile.h"

/* Where a program's scene comes from. */
typedef struct {
    const char *path;  /* a scene file (from the top directory), or NULL */
    const char *text;  /* else the scene itself, called `name` in messages */
    const char *name;
    const scene_features_t *features; /* the parts the program offers */
    int min_width, min_height; /* the smallest image a small scale gives */
} chapter_scene_t;

/* Print "PROG: WHAT: the error" on stderr; returns CHAPTER_EXIT_FAIL, for
 * `return chapter_fail(...)` in main(). */
static inline int chapter_fail(const char *prog, const char *what,
                               const svet_error *e)
{
    fprintf(stderr, "%s: %s: %s\n", prog, what, e->msg);
    return CHAPTER_EXIT_FAIL;
}

/* Read the scene of `src` into *s at `scale` of its resolution (no smaller
 * than src's minimum), with `threads` threads for the methods' pre-passes
 * (0 = every core) and then the settings in `set` ("key=value" as
 * scenefile_override takes them, NULL-terminated; set may be NULL). On
 * failure s is freed and *e says why. */
static inline svet_status chapter_scene_load(scene_t *s,
                                             const chapter_scene_t *src,
                                             double scale, int threads,
                                             const char *const *set,
                                             svet_error *e)
{
    svet_status st =
        src->path ? scenefile_read_with(s, src->path, src->features, e)
                  : scenefile_parse_with(s, src->text, strlen(src->text),
                                         src->name, NULL, src->features, e);
    if (st != SVET_OK)
        return st;
    char buf[96];
    snprintf(buf, sizeof buf, "resolution=%dx%d",
             (int)fmax(src->min_width, s->camera.width * scale),
             (int)fmax(src->min_height, s->camera.height * scale));
    st = scenefile_override(s, buf, e);
    snprintf(buf, sizeof buf, "threads=%d", threads);
    if (st == SVET_OK)
        st = scenefile_override(s, buf, e);
    for (int i = 0; st == SVET_OK && set && set[i]; i++)
        st = scenefile_override(s, set[i], e);
    if (st != SVET_OK)
        scene_free(s);
    return st;
}

#endif
