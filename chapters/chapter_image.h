/*
 * chapter_image.h - how the chapter programs that render a scene (ch. 5,
 * 8, 9, 11) write an image: DIR/STEM.pfm, linear as rendered, and beside it
 * DIR/STEM.ppm, tone-mapped (ch. 6) to 8-bit sRGB codes for any viewer.
 * Header-only like chapter.h, so a program's one cc line needs no extra
 * file (it lists src/io/netpbm.c and src/colour/tonemap.c already).
 * Tests: tests/chapters/test_chapters.c runs the programs.
 */
#ifndef SVET_CHAPTER_IMAGE_H
#define SVET_CHAPTER_IMAGE_H

#include <stdio.h>

#include "colour/tonemap.h"
#include "io/image.h"
#include "io/netpbm.h"

/* Write img as DIR/STEM.pfm and, mapped by tp (NULL: linear tone mapping
 * with the sRGB curve, tonemap_defaults), as DIR/STEM.ppm. The display
 * image goes to *shown when shown is not NULL (the caller frees it), for
 * a picture of several panels. Returns the first failure, with its
 * message in *e. */
static inline svet_status chapter_write_pair(const char *dir,
                                             const char *stem,
                                             const image_t *img,
                                             const tonemap_params_t *tp,
                                             image_t *shown, svet_error *e)
{
    tonemap_params_t linear;
    if (!tp) {
        tonemap_defaults(&linear, TONEMAP_LINEAR);
        tp = &linear;
    }
    image_t own = { 0 };
    image_t *out = shown ? shown : &own;
    char path[1200];
    snprintf(path, sizeof path, "%s/%s.pfm", dir, stem);
    svet_status st = netpbm_write_pfm(path, img, e);
    if (st == SVET_OK)
        st = tonemap_apply(img, out, tp, NULL, e);
    if (st == SVET_OK) {
        snprintf(path, sizeof path, "%s/%s.ppm", dir, stem);
        st = netpbm_write_ppm(path, out, 8, e);
    }
    image_free(&own);
    return st;
}

#endif
