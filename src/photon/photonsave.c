/*
 * photonsave.c - a balanced photon map (ch. 8) to a file and back, bit
 * for bit, so that a split render can compute its photon maps once and
 * every part read them (scenes/README.md, "Split renders").
 * Tests: tests/photon/test_photonsave.c
 */
#include "photon/photonsave.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* written as 4 bytes in the machine's order: another order reads back
 * as another number */
#define BYTE_ORDER_MARK UINT32_C(0x01020304)

svet_status photonmap_write(const photonmap_t *m, FILE *f, svet_error *err)
{
    if (!m->balanced)
        return svet_error_set(err, SVET_ERR_RANGE,
                              "photon map: only a balanced map is written");
    const uint32_t mark = BYTE_ORDER_MARK;
    if (fprintf(f, "photonmap %zu %zu\n", m->n, sizeof(photon_t)) < 0 ||
        fwrite(&mark, sizeof mark, 1, f) != 1 ||
        (m->n > 0 && fwrite(&m->ph[1], sizeof(photon_t), m->n, f) != m->n))
        return svet_error_set(err, SVET_ERR_IO,
                              "photon map: a write failed");
    return SVET_OK;
}

svet_status photonmap_read(photonmap_t *m, FILE *f, svet_error *err)
{
    memset(m, 0, sizeof *m);
    size_t n, size;
    uint32_t mark;
    if (fscanf(f, "photonmap %zu %zu", &n, &size) != 2 || fgetc(f) != '\n')
        return svet_error_set(err, SVET_ERR_PARSE,
                              "not a photon map (no 'photonmap N SIZE' "
                              "line)");
    if (size != sizeof(photon_t))
        return svet_error_set(err, SVET_ERR_PARSE,
                              "a photon map of %zu-byte photons, this "
                              "program's are %zu bytes", size,
                              sizeof(photon_t));
    if (fread(&mark, sizeof mark, 1, f) != 1)
        return svet_error_set(err, SVET_ERR_PARSE,
                              "a photon map truncated before its photons");
    if (mark != BYTE_ORDER_MARK)
        return svet_error_set(err, SVET_ERR_PARSE,
                              "a photon map of another byte order");
    m->balanced = true;
    if (n == 0)
        return SVET_OK;
    svet_status st = photonmap_init(m, n, err);
    if (st != SVET_OK)
        return st;
    memset(&m->ph[0], 0, sizeof m->ph[0]);
    if (fread(&m->ph[1], sizeof(photon_t), n, f) != n) {
        photonmap_free(m);
        return svet_error_set(err, SVET_ERR_PARSE,
                              "a photon map of %zu photons truncated", n);
    }
    m->n = n;
    m->balanced = true;
    return SVET_OK;
}
