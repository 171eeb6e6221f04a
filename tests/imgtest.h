/*
 * imgtest.h - what the image suites share (test_image, test_fileio,
 * test_netpbm, test_exrio, test_pngio, test_imageio, test_svet): a scratch
 * directory, raw file bytes for hand-made bad files, deterministic test
 * images, the check that a writer failing half-way keeps the old file, and
 * a small disk to fill.
 */
#ifndef SVET_IMGTEST_H
#define SVET_IMGTEST_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "core/error.h"
#include "io/image.h"

/* "<scratch dir>/<name>". The directory is made on first use (mkdtemp
 * under $TMPDIR or /tmp) and removed with its files when the process
 * exits. The string lives until the 8th call after this one. */
const char *imgtest_path(const char *name);

/* Write / read a whole file; a failure fails the calling test. */
void imgtest_write_bytes(const char *path, const void *data, size_t n);
size_t imgtest_read_bytes(const char *path, unsigned char **data);

/* True if the file at path holds exactly these n bytes. */
bool imgtest_file_is(const char *path, const void *data, size_t n);

/* How many stray temporary files "<path>.tmp-*" lie beside path. */
int imgtest_count_temps(const char *path);

/* A w x h image of `channels` channels with distinct values spread over
 * several decades (linear HDR-like), deterministic. Fails the test if it
 * cannot allocate. */
void imgtest_hdr_image(image_t *img, int w, int h, int channels);

/* A writer under test: write something to path. */
typedef svet_status (*imgtest_writer_fn)(const char *path, const void *ctx,
                                         svet_error *err);

/* The check of every writer: put an old file at path, run `writer` with
 * the process's file size limit (RLIMIT_FSIZE) at `limit` bytes so that the
 * write fails part-way as a full disk would, and assert that it reported
 * SVET_ERR_IO naming the path, that the old file is byte for byte intact
 * and that no temporary file is left. Then, without the limit, the write
 * succeeds and replaces the old file. */
void imgtest_check_failed_write_keeps_old(imgtest_writer_fn writer,
                                          const void *ctx, const char *path,
                                          long limit);

/* Make a FIFO and a directory in the scratch directory, their names into
 * fifo and dir (cap bytes each): inputs that are not regular files. */
void imgtest_special_files(char *fifo, char *dir, size_t cap);

/* A directory on a tmpfs of its own of `kib` KiB (a small disk to fill),
 * as "/proc/self/fd/N": the mount is detached at once and lives as long
 * as descriptor N, in this process and the commands it runs. Returns
 * NULL, after printing why, where it cannot be mounted (not root, not
 * Linux): the caller skips its test. */
const char *imgtest_small_disk(int kib);

/* Fill the file system that holds dir to the last byte with a file
 * "<dir>/filler", so that the next write fails with ENOSPC. */
void imgtest_fill_disk(const char *dir);

/* The bad-file check of every reader: reader(path) must fail with `status`
 * and a message that starts with the path and contains `words` (NULL: any
 * message); the image must come back zeroed. With SVET_SHOW_ERRORS set in
 * the environment each message is printed, to read them over. */
typedef svet_status (*imgtest_reader_fn)(const char *path, image_t *img,
                                         svet_error *err);
void imgtest_check_bad_file(imgtest_reader_fn reader, const char *path,
                            svet_status status, const char *words);

/* CRC-32 of PNG chunks (ISO 3309, as in the PNG spec's annex D), for
 * making bad files whose checksums are right. */
uint32_t imgtest_png_crc32(const unsigned char *p, size_t n);

/* v big-endian into p[0..3]. */
void imgtest_put_be32(unsigned char *p, uint32_t v);

/* Set a PNG's IHDR width and height and recompute its CRC (IHDR is the
 * first chunk: type at 12, data 16..28, CRC at 29). */
void imgtest_png_patch_ihdr(unsigned char *png, uint32_t w, uint32_t h);

#endif
