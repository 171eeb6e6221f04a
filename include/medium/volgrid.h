/*
 * volgrid.h - gridded media of ch. 11: a 3D grid of values (density,
 * albedo) over a box, read from and written to Mitsuba's binary .vol
 * format so that grids move between svet and Mitsuba 3, and looked up by
 * app. L's interpolation. The format (Mitsuba 3, src/render/volumegrid.cpp):
 * the bytes 'V' 'O' 'L', the version byte 3, then little-endian int32
 * encoding 1 (float32), int32 sizes x, y, z, int32 channel count, float32
 * bounding box min x y z and max x y z (48 bytes in all), then the
 * values, float32, channel fastest, then x, then y, then z. Values stand
 * at the cells' centres, as Mitsuba 3's grid volume reads them.
 * Tests: tests/medium/test_volgrid.c
 */
#ifndef SVET_VOLGRID_H
#define SVET_VOLGRID_H

#include <stddef.h>

#include "core/error.h"
#include "core/vec.h"
#include "texture/interp.h"

#define VOLGRID_MAX_CHANNELS 4
#define VOLGRID_HEADER_BYTES 48
/* The default limit of values (cells times channels) read from a file:
 * 2^28 floats, 1 GiB. A file declaring more is refused before anything
 * is allocated; volgrid_read takes another limit. */
#define VOLGRID_DEFAULT_MAX_VALUES ((size_t)1 << 28)

typedef struct {
    int nx, ny, nz;            /* cells along x, y, z; each >= 1 */
    int channels;              /* 1 (density) to 4 */
    float lo[3], hi[3];        /* the box the grid fills, lo < hi */
    float *plane[VOLGRID_MAX_CHANNELS]; /* channel c's nx*ny*nz values,
                                           x fastest */
    float max[VOLGRID_MAX_CHANNELS];    /* each channel's largest value */
} volgrid_t;

/* An empty grid of the given size over [lo, hi], every value 0. Fails
 * with SVET_ERR_RANGE on a size below 1, a channel count outside 1..4, a
 * box that is not finite or not lo < hi on every axis, or more than
 * max_values values; SVET_ERR_NOMEM. */
svet_status volgrid_alloc(volgrid_t *g, int nx, int ny, int nz, int channels,
                          const float lo[3], const float hi[3],
                          size_t max_values, svet_error *err);

void volgrid_free(volgrid_t *g);

/* Read a .vol file. Refuses, with the file's name and what is wrong: a
 * file that is not regular (a FIFO, a directory), a wrong magic, version
 * or encoding, sizes below 1 or above max_values in all (checked before
 * allocating), a channel count outside 1..4, a bad box, a file whose
 * length is not exactly the header and the values it declares (truncated
 * or with bytes after), and NaN or infinite values (SVET_ERR_PARSE or
 * SVET_ERR_RANGE; SVET_ERR_IO when it cannot be read). g is then empty. */
svet_status volgrid_read(volgrid_t *g, const char *path, size_t max_values,
                         svet_error *err);

/* Write g to path in the .vol format, replacing it only when complete
 * (io/fileio.h). Fails with SVET_ERR_IO. */
svet_status volgrid_write(const volgrid_t *g, const char *path,
                          svet_error *err);

/* Channel c of g as an interp_grid_t (app. L). */
interp_grid_t volgrid_channel(const volgrid_t *g, int c);

/* Channel c at the world point p by trilinear interpolation between the
 * cell centres; outside the box the border values continue (Mitsuba 3's
 * clamp). Can't fail. */
real volgrid_eval(const volgrid_t *g, int c, const VECTOR3 p);

#endif
