/*
 * photonsave.h - a balanced photon map (ch. 8) written to a file and read
 * back bit for bit: the pre-pass of a split render computed once and
 * read by every part (svet render --save-prepass / --load-prepass;
 * scenes/README.md, "Split renders").
 * Tests: tests/photon/test_photonsave.c
 */
#ifndef SVET_PHOTONSAVE_H
#define SVET_PHOTONSAVE_H

#include <stdio.h>

#include "core/error.h"
#include "photon/photonmap.h"

/* Writes the balanced map m to f at its position: a text line
 * "photonmap N SIZE" (N photons of SIZE bytes), a 32-bit byte-order mark,
 * then the heap's photons 1 .. N as they lie in memory. The file is for
 * machines of the same byte order and photon layout (photonmap_read
 * refuses others). SVET_ERR_RANGE for a map not balanced, SVET_ERR_IO
 * when a write fails. */
svet_status photonmap_write(const photonmap_t *m, FILE *f, svet_error *err);

/* Reads into m (which it initialises; photonmap_free frees it) a map
 * photonmap_write wrote, from f's position: the same photons in the same
 * heap order, balanced. SVET_ERR_PARSE with the reason for a file of
 * another layout or byte order, a truncated one or one that is not a
 * photon map; SVET_ERR_NOMEM, SVET_ERR_RANGE for a count photonmap_init
 * refuses. m is empty after a failure. */
svet_status photonmap_read(photonmap_t *m, FILE *f, svet_error *err);

#endif
