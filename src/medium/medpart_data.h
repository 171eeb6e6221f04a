/*
 * medpart_data.h - what the files of the media part (medpart.c, the
 * scene file; volpath.c, the renderer) share and nothing else: the media
 * a scene names and the records its boundaries point at.
 * Tests: tests/medium/test_medpart.c
 */
#ifndef SVET_MEDPART_DATA_H
#define SVET_MEDPART_DATA_H

#include "medium/medpart.h"

/* A named medium; its grid (when it has one) is owned here. */
typedef struct {
    char name[SCENE_MAX_NAME + 1];
    medium_t m;
    volgrid_t grid;
    bool has_grid;
} named_medium_t;

/* One side of the boundaries of one shape statement: the record objects
 * point at, and the medium it stands for (an index into media; -1:
 * vacuum; -2: the global medium, resolved by finish). */
typedef struct {
    struct medium rec;
    int index;
} side_t;

typedef struct {
    named_medium_t **media; /* each allocated alone: pointers stay put */
    int nmedia;
    side_t **sides;
    int nsides;
    int global;             /* index of the global medium, -1: none */
} medpart_data_t;

/* `render integrator volpath` (volpath.c). */
extern const render_method_t volpath_method;

#endif
