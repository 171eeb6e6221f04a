/*
 * fuzz_image.c - libFuzzer target for the image readers (imageio.h): the
 * input is written to a file and read by imageio_read_with(), which tells
 * EXR, PNG, PFM and PPM/PGM apart by their first bytes and hands the file
 * to exrio.c, pngio.c or netpbm.c. Any bytes must give SVET_OK and a sane
 * image, or an error whose message starts with the file's name; never a
 * crash, a hang, a leak or undefined behaviour. `make fuzz-image`;
 * fuzz/README.md has the runs and says why one target serves four formats.
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/imageio.h"

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static char path[64];

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    /* One file per process (fork mode runs several), in /tmp: rewritten
     * for every input, removed when the process ends. */
    snprintf(path, sizeof path, "/tmp/svet-fuzz-image-%ld", (long)getpid());
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f || fwrite(data, 1, size, f) != size || fclose(f) != 0)
        abort(); /* the machine, not the reader */
    /* A small limit keeps each run short and its memory low; the code
     * paths are those of the default limit. */
    image_read_limits_t lim = { 1 << 20 };
    image_t img;
    svet_error e;
    imageio_format_t fmt;
    svet_status st = imageio_read_with(path, &img, true, &fmt, &lim, &e);
    if (st == SVET_OK) {
        if (img.width < 1 || img.height < 1 ||
            (uint64_t)img.width * (uint64_t)img.height > lim.max_pixels ||
            (img.channels != 3 && img.channels != 4) || !img.px)
            abort();
        /* touch every value, so that a short buffer shows */
        size_t n = (size_t)img.width * (size_t)img.height *
                   (size_t)img.channels;
        volatile float sum = 0;
        for (size_t i = 0; i < n; i++)
            sum += img.px[i];
        (void)sum;
    } else if (strncmp(e.msg, path, strlen(path)) != 0 || img.px) {
        abort(); /* every message names the file; nothing is left */
    }
    image_free(&img);
    unlink(path);
    return 0;
}
