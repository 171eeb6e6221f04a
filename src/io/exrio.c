/*
 * exrio.c - OpenEXR scanline files through OpenEXRCore, the library's C
 * API (docs: openexr.com, "Reading and Writing Image Files with the
 * C-language API"). The library reads and writes through our own callbacks
 * (pread/pwrite on a descriptor), so that writing goes through fileio.h's
 * temporary file and every library message lands in our svet_error rather
 * than on stderr. See exrio.h. Tests: tests/io/test_exrio.c
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L /* pread, pwrite, fstat */
#endif
#include "io/exrio.h"
#include "io/fileio.h"

#include <errno.h>
#include <math.h>
#include <openexr.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* What the library's callbacks see as user data. */
typedef struct {
    int fd;
    int os_error;  /* errno of a failed pread/pwrite: an I/O error rather
                      than a short (truncated) file */
    char msg[256]; /* the library's first error message, if any */
} stream_t;

/* The stream of the read or write this thread is running. The error
 * handler cannot ask the context for its user data: in a write context
 * exr_get_user_data() takes the context's lock, which the failing call
 * (exr_write_header on a full disk) already holds, and the handler would
 * wait on it for ever. The library calls the handler on the thread of the
 * call that failed, so a thread-local pointer reaches the right stream. */
static _Thread_local stream_t *active_stream;

static void on_error(exr_const_context_t ctxt, exr_result_t code,
                     const char *msg)
{
    (void)ctxt;
    stream_t *s = active_stream;
    if (!s)
        return;
    /* The first message names the cause; later ones its consequences. */
    if (s->msg[0] == '\0')
        snprintf(s->msg, sizeof s->msg, "%s",
                 msg ? msg : exr_get_default_error_message(code));
}

static int64_t read_cb(exr_const_context_t ctxt, void *ud, void *buffer,
                       uint64_t sz, uint64_t offset,
                       exr_stream_error_func_ptr_t error_cb)
{
    stream_t *s = ud;
    uint64_t done = 0;
    if (offset > (uint64_t)INT64_MAX - sz) {
        error_cb(ctxt, EXR_ERR_READ_IO, "offset %llu out of range",
                 (unsigned long long)offset);
        return -1;
    }
    while (done < sz) {
        ssize_t n = pread(s->fd, (char *)buffer + done, (size_t)(sz - done),
                          (off_t)(offset + done));
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0) {
            s->os_error = errno;
            error_cb(ctxt, EXR_ERR_READ_IO, "read error: %s",
                     strerror(errno));
            return -1;
        }
        if (n == 0)
            break; /* end of file: the library reports the short read */
        done += (uint64_t)n;
    }
    return (int64_t)done;
}

static int64_t size_cb(exr_const_context_t ctxt, void *ud)
{
    (void)ctxt;
    stream_t *s = ud;
    struct stat st;
    return fstat(s->fd, &st) == 0 ? (int64_t)st.st_size : -1;
}

static int64_t write_cb(exr_const_context_t ctxt, void *ud, const void *buffer,
                        uint64_t sz, uint64_t offset,
                        exr_stream_error_func_ptr_t error_cb)
{
    stream_t *s = ud;
    uint64_t done = 0;
    while (done < sz) {
        ssize_t n = pwrite(s->fd, (const char *)buffer + done,
                           (size_t)(sz - done), (off_t)(offset + done));
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0) {
            s->os_error = n < 0 ? errno : EIO;
            error_cb(ctxt, EXR_ERR_WRITE_IO, "write error: %s",
                     n < 0 ? strerror(errno) : "no progress");
            return -1;
        }
        done += (uint64_t)n;
    }
    return (int64_t)done;
}

/* The message for a failed library call: the library's own words if it
 * gave any, else the text of its error code. */
static svet_status fail(svet_error *err, svet_status st, const char *path,
                        const stream_t *s, const char *doing, exr_result_t rv)
{
    return svet_error_set(err, st, "%s: %s: %s", path, doing,
                          s->msg[0] ? s->msg
                                    : exr_get_default_error_message(rv));
}

/* --- writing --------------------------------------------------------------- */

static const char *const channel_name[4] = { "R", "G", "B", "A" };

static int channel_index(const char *name)
{
    for (int k = 0; k < 4; k++)
        if (name && strcmp(name, channel_name[k]) == 0)
            return k;
    return -1;
}

/* OpenEXRCore before 3.4.8 (openexr issue #2306, fixed by pull request
 * #2307) stores a zlib stream that came out exactly as long as the raw
 * (packed) chunk; a reader then takes those bytes for raw data, since a
 * stored size equal to the raw size means "not compressed", and the chunk
 * reads back as noise. About one chunk in a few hundred of a rendered image
 * hits it. The library's own compress step is wrapped: in that one case the
 * raw bytes are stored instead, which every reader decodes correctly and
 * which is what the fixed library does. */
typedef exr_result_t (*compress_fn_t)(exr_encode_pipeline_t *);

static exr_result_t compress_exact_size_safe(exr_encode_pipeline_t *enc)
{
    compress_fn_t inner = (compress_fn_t)(uintptr_t)enc->encoding_user_data;
    exr_result_t rv = inner(enc);
    if (rv == EXR_ERR_SUCCESS && enc->compressed_bytes == enc->packed_bytes &&
        enc->compressed_buffer != enc->packed_buffer)
        memcpy(enc->compressed_buffer, enc->packed_buffer, enc->packed_bytes);
    return rv;
}

/* Everything between creating the context and exr_finish: returns the
 * library's result and names the failing step in *doing. */
static exr_result_t write_parts(exr_context_t ctx, const image_t *img,
                                exrio_pixel_t pixel,
                                exrio_compression_t compression,
                                const char **doing)
{
    int part = 0;
    exr_result_t rv;
    exr_pixel_type_t ptype = pixel == EXRIO_HALF ? EXR_PIXEL_HALF
                                                 : EXR_PIXEL_FLOAT;
    *doing = "cannot set up the header";
    rv = exr_add_part(ctx, NULL, EXR_STORAGE_SCANLINE, &part);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr_simple(
            ctx, part, img->width, img->height,
            compression == EXRIO_ZIP ? EXR_COMPRESSION_ZIP
                                     : EXR_COMPRESSION_NONE);
    for (int k = 0; k < img->channels && rv == EXR_ERR_SUCCESS; k++)
        rv = exr_add_channel(ctx, part, channel_name[k], ptype,
                             k == 3 ? EXR_PERCEPTUALLY_LINEAR
                                    : EXR_PERCEPTUALLY_LOGARITHMIC,
                             1, 1);
    if (rv != EXR_ERR_SUCCESS)
        return rv;
    *doing = "cannot write the header";
    if ((rv = exr_write_header(ctx)) != EXR_ERR_SUCCESS)
        return rv;

    int32_t lines = 1;
    *doing = "cannot write the pixels";
    if ((rv = exr_get_scanlines_per_chunk(ctx, part, &lines)) !=
        EXR_ERR_SUCCESS)
        return rv;
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    bool started = false;
    const size_t stride = (size_t)img->channels * sizeof(float);
    for (int y = 0; y < img->height && rv == EXR_ERR_SUCCESS; y += lines) {
        exr_chunk_info_t cinfo;
        rv = exr_write_scanline_chunk_info(ctx, part, y, &cinfo);
        if (rv != EXR_ERR_SUCCESS)
            break;
        rv = started ? exr_encoding_update(ctx, part, &cinfo, &enc)
                     : exr_encoding_initialize(ctx, part, &cinfo, &enc);
        if (rv != EXR_ERR_SUCCESS)
            break;
        /* The library sorts channels by name (A B G R); find each one's
         * place in our interleaved floats. It converts float to half. */
        for (int c = 0; c < enc.channel_count; c++) {
            exr_coding_channel_info_t *ch = &enc.channels[c];
            int k = channel_index(ch->channel_name);
            ch->user_pixel_stride = (int32_t)stride;
            ch->user_line_stride = (int32_t)(stride * (size_t)img->width);
            ch->user_data_type = EXR_PIXEL_FLOAT;
            ch->user_bytes_per_element = sizeof(float);
            ch->encode_from_ptr =
                (const uint8_t *)(image_at(img, 0, cinfo.start_y) + k);
        }
        if (!started) {
            rv = exr_encoding_choose_default_routines(ctx, part, &enc);
            started = true;
            if (rv != EXR_ERR_SUCCESS)
                break;
            if (enc.compress_fn) {
                enc.encoding_user_data = (void *)(uintptr_t)enc.compress_fn;
                enc.compress_fn = compress_exact_size_safe;
            }
        }
        rv = exr_encoding_run(ctx, part, &enc);
    }
    if (started)
        exr_encoding_destroy(ctx, &enc);
    return rv;
}

svet_status exrio_write_to(fileio_t *out, const image_t *img,
                           exrio_pixel_t pixel,
                           exrio_compression_t compression, svet_error *err)
{
    const char *path = out->path;
    stream_t s = { .fd = fileno(out->f) };
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = on_error;
    init.user_data = &s;
    init.write_fn = write_cb;
    exr_context_t ctx = NULL;
    const char *doing = "cannot start writing";
    stream_t *outer = active_stream;
    active_stream = &s;
    exr_result_t rv = exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY,
                                      &init);
    if (rv == EXR_ERR_SUCCESS)
        rv = write_parts(ctx, img, pixel, compression, &doing);
    if (ctx) {
        /* exr_finish writes the chunk offset table: it can fail too. */
        exr_result_t fin = exr_finish(&ctx);
        if (rv == EXR_ERR_SUCCESS && fin != EXR_ERR_SUCCESS) {
            rv = fin;
            doing = "cannot finish the file";
        }
    }
    active_stream = outer;
    if (rv != EXR_ERR_SUCCESS)
        return fail(err, rv == EXR_ERR_OUT_OF_MEMORY ? SVET_ERR_NOMEM
                                                     : SVET_ERR_IO,
                    path, &s, doing, rv);
    return SVET_OK;
}

svet_status exrio_write(const char *path, const image_t *img,
                        exrio_pixel_t pixel, exrio_compression_t compression,
                        svet_error *err)
{
    fileio_t out;
    svet_status st = fileio_begin(&out, path, err);
    if (st == SVET_OK)
        st = exrio_write_to(&out, img, pixel, compression, err);
    if (st != SVET_OK) {
        fileio_abort(&out);
        return st;
    }
    return fileio_commit(&out, err);
}

/* --- reading --------------------------------------------------------------- */

/* Where each channel we want is in the file: index into the channel list,
 * or -1. */
typedef struct {
    int rgba[4]; /* R G B A */
    int y;       /* Y (luminance) */
} channel_map_t;

static svet_status map_channels(const exr_attr_chlist_t *cl,
                                channel_map_t *map, const char *path,
                                svet_error *err)
{
    map->rgba[0] = map->rgba[1] = map->rgba[2] = map->rgba[3] = -1;
    map->y = -1;
    char found[160] = "";
    size_t used = 0;
    for (int i = 0; i < cl->num_channels; i++) {
        const exr_attr_chlist_entry_t *e = &cl->entries[i];
        const char *name = e->name.str ? e->name.str : "";
        int k = channel_index(name);
        if (k >= 0)
            map->rgba[k] = i;
        else if (strcmp(name, "Y") == 0)
            map->y = i;
        if (used < sizeof found - 1) {
            int n = snprintf(found + used, sizeof found - used, "%s%s",
                             i ? " " : "", name);
            if (n > 0)
                used += (size_t)n;
        }
    }
    bool rgb = map->rgba[0] >= 0 && map->rgba[1] >= 0 && map->rgba[2] >= 0;
    if (!rgb && map->y < 0)
        return svet_error_set(err, SVET_ERR_PARSE,
                              "%s: no R, G, B channels (and no Y) to read; "
                              "the file has: %s", path,
                              cl->num_channels ? found : "no channels");
    if (rgb)
        map->y = -1; /* colour wins over a luminance channel beside it */
    /* The channels read must be full resolution; others may be anything. */
    const int read[4] = { rgb ? map->rgba[0] : map->y,
                          rgb ? map->rgba[1] : -1, rgb ? map->rgba[2] : -1,
                          map->rgba[3] };
    for (int j = 0; j < 4; j++) {
        if (read[j] < 0)
            continue;
        const exr_attr_chlist_entry_t *e = &cl->entries[read[j]];
        if (e->x_sampling != 1 || e->y_sampling != 1)
            return svet_error_set(err, SVET_ERR_UNSUPPORTED,
                                  "%s: channel %s is subsampled (%d x %d); "
                                  "svet reads full-resolution channels only",
                                  path, e->name.str ? e->name.str : "",
                                  e->x_sampling, e->y_sampling);
    }
    return SVET_OK;
}

/* The scratch planes of one chunk: one float plane per channel of the
 * file, sized by the channel's own (possibly subsampled) width and
 * height. */
typedef struct {
    float *buf;
    size_t cap;  /* floats */
    int *filled; /* per channel: lines unpacked into its plane so far */
    int nchannels;
} scratch_t;

/* Point every channel of the chunk at its own plane of scratch, growing it
 * as needed; at[c] is where channel c's plane starts. Every channel gets a
 * buffer, skipped ones too: OpenEXRCore 3.1.5 takes a NULL decode_to_ptr
 * for "skip this channel", but its specialised half unpackers (three or
 * four channels of one type) write through every pointer without looking,
 * so a half R G B file with a Z or Y beside it crashed the reader. */
static exr_result_t point_channels(exr_decode_pipeline_t *dec, scratch_t *sc,
                                   size_t *at)
{
    size_t need = 0;
    for (int c = 0; c < dec->channel_count; c++) {
        const exr_coding_channel_info_t *ch = &dec->channels[c];
        if (ch->width < 0 || ch->height < 0)
            return EXR_ERR_CORRUPT_CHUNK;
        at[c] = need;
        need += (size_t)ch->width * (size_t)ch->height;
    }
    if (need > sc->cap) {
        float *nb = realloc(sc->buf, (need ? need : 1) * sizeof(float));
        if (!nb)
            return EXR_ERR_OUT_OF_MEMORY;
        sc->buf = nb;
        sc->cap = need;
    }
    for (int c = 0; c < dec->channel_count; c++) {
        exr_coding_channel_info_t *ch = &dec->channels[c];
        ch->decode_to_ptr = (uint8_t *)(sc->buf + at[c]);
        ch->user_pixel_stride = sizeof(float);
        ch->user_line_stride = (int32_t)((size_t)ch->width * sizeof(float));
        ch->user_data_type = EXR_PIXEL_FLOAT;
        ch->user_bytes_per_element = sizeof(float);
    }
    return EXR_ERR_SUCCESS;
}

/* An IEEE 754 binary16 value as a float, exactly (NaN payloads kept). */
static float half_to_float(uint16_t h)
{
    uint32_t sign = (uint32_t)(h >> 15) << 31, e = (h >> 10) & 31u,
             m = h & 1023u, bits;
    if (e == 31) { /* Inf, NaN */
        bits = sign | 0x7f800000u | m << 13;
    } else if (e != 0) { /* normal: rebias the exponent 15 -> 127 */
        bits = sign | (e + 112u) << 23 | m << 13;
    } else { /* zero and subnormals: m 2^-24 */
        float v = ldexpf((float)m, -24);
        return sign ? -v : v;
    }
    float v;
    memcpy(&v, &bits, sizeof v);
    return v;
}

/* The decoded (uncompressed) chunk into the float planes: the unpack step
 * of the decode pipeline, in place of the library's. The format stores,
 * line by line, each channel's samples of that line in channel order,
 * little-endian (half, float or uint); a channel subsampled in y has a
 * line only where y is a multiple of its factor. OpenEXRCore 3.1.5's own
 * routines for three or four channels of one type ignore subsampling
 * (they read every channel as wide as the first, so Y of a Y RY BY file
 * came out half garbage) and put A where R belongs when interleaving four
 * halves; this loop is the format's plain definition. */
static exr_result_t unpack_to_planes(exr_decode_pipeline_t *dec)
{
    const uint8_t *src = dec->unpacked_buffer;
    const uint8_t *end = src ? src + dec->chunk.unpacked_size : NULL;
    scratch_t *sc = dec->decoding_user_data;
    if (!src || !sc || dec->channel_count > sc->nchannels)
        return EXR_ERR_CORRUPT_CHUNK;
    int *filled = sc->filled;
    memset(filled, 0, (size_t)dec->channel_count * sizeof *filled);
    for (int j = 0; j < dec->chunk.height; j++) {
        int64_t y = (int64_t)dec->chunk.start_y + j;
        for (int c = 0; c < dec->channel_count; c++) {
            const exr_coding_channel_info_t *ch = &dec->channels[c];
            if (ch->y_samples > 1 && y % ch->y_samples != 0)
                continue;
            size_t bpe = (size_t)ch->bytes_per_element;
            size_t n = (size_t)ch->width;
            if ((bpe != 2 && bpe != 4) || filled[c] >= ch->height ||
                (size_t)(end - src) / bpe < n)
                return EXR_ERR_CORRUPT_CHUNK;
            float *out = (float *)ch->decode_to_ptr + (size_t)filled[c] * n;
            for (size_t x = 0; x < n; x++, src += bpe) {
                uint32_t v = bpe == 2 ? (uint32_t)src[0] | (uint32_t)src[1] << 8
                                      : (uint32_t)src[0] |
                                            (uint32_t)src[1] << 8 |
                                            (uint32_t)src[2] << 16 |
                                            (uint32_t)src[3] << 24;
                if (ch->data_type == EXR_PIXEL_HALF)
                    out[x] = half_to_float((uint16_t)v);
                else if (ch->data_type == EXR_PIXEL_FLOAT)
                    memcpy(&out[x], &v, sizeof v);
                else
                    out[x] = (float)v; /* uint */
            }
            filled[c]++;
        }
    }
    return EXR_ERR_SUCCESS;
}

/* The library's read and decompress steps, and unpack_to_planes. For an
 * uncompressed file whose channels are all float, the library would
 * choose a reader that copies the chunk straight into the planes and skips
 * the unpack step; it does so only when no channel changes type, so the
 * choice is made with one channel asking for halves (unpack_to_planes
 * does not look at the requested type). */
static exr_result_t choose_routines(exr_context_t ctx,
                                    exr_decode_pipeline_t *dec)
{
    exr_coding_channel_info_t *ch0 = &dec->channels[0];
    bool changes = false;
    for (int c = 0; c < dec->channel_count; c++)
        changes |= dec->channels[c].data_type != EXR_PIXEL_FLOAT;
    if (!changes) {
        ch0->user_data_type = EXR_PIXEL_HALF;
        ch0->user_bytes_per_element = 2;
    }
    exr_result_t rv = exr_decoding_choose_default_routines(ctx, 0, dec);
    ch0->user_data_type = EXR_PIXEL_FLOAT;
    ch0->user_bytes_per_element = sizeof(float);
    dec->unpack_and_convert_fn = unpack_to_planes;
    return rv;
}

/* Which of img's channels (0..3, or -1 for none) the file's channel
 * `name` fills. */
static int target_channel(const char *name, const channel_map_t *map,
                          const image_t *img)
{
    int k = channel_index(name);
    if (map->y >= 0) /* grey: Y into R, A into A */
        k = (name && strcmp(name, "Y") == 0) ? 0 : (k == 3 ? 3 : -1);
    return k < img->channels ? k : -1;
}

/* OpenEXRCore 3.1's B44 and B44A decoders can read past the end of their
 * scratch buffer on a corrupt chunk (found by fuzz/fuzz_image.c): before
 * each such chunk, give the decoder a zeroed scratch buffer large enough
 * for every read, each channel's rows rounded up to whole 4 x 4 blocks and
 * to the chunk's height. The library keeps a buffer it is given when it
 * is large enough, and frees it with the context's allocator (malloc's
 * free, the default: exrio sets none). A valid file decodes as before. */
static exr_result_t pad_b44_scratch(exr_context_t ctx,
                                    exr_decode_pipeline_t *dec,
                                    const exr_chunk_info_t *cinfo)
{
    exr_compression_t comp = EXR_COMPRESSION_NONE;
    exr_result_t rv = exr_get_compression(ctx, 0, &comp);
    if (rv != EXR_ERR_SUCCESS)
        return rv;
    if (comp != EXR_COMPRESSION_B44 && comp != EXR_COMPRESSION_B44A)
        return EXR_ERR_SUCCESS;
    uint64_t need = 0;
    for (int c = 0; c < dec->channel_count; c++) {
        const exr_coding_channel_info_t *ch = &dec->channels[c];
        uint64_t nx = (uint64_t)(ch->width > 0 ? ch->width : 0);
        uint64_t ny = (uint64_t)(ch->height > cinfo->height ? ch->height
                                                            : cinfo->height);
        nx = (nx + 3) / 4 * 4;
        ny = (ny + 3) / 4 * 4;
        need += nx * ny * 8; /* 8: the widest element, with room to spare */
    }
    need += cinfo->unpacked_size + 64;
    if (dec->scratch_buffer_1 && dec->scratch_alloc_size_1 >= need) {
        memset(dec->scratch_buffer_1, 0, dec->scratch_alloc_size_1);
        return EXR_ERR_SUCCESS;
    }
    void *buf = calloc(1, (size_t)need);
    if (!buf)
        return EXR_ERR_OUT_OF_MEMORY;
    free(dec->scratch_buffer_1);
    dec->scratch_buffer_1 = buf;
    dec->scratch_alloc_size_1 = (size_t)need;
    return EXR_ERR_SUCCESS;
}

/* Decode every chunk into planar floats (one plane per channel, by
 * unpack_to_planes) and interleave the wanted ones into img
 * (test_exrio's every_layout_and_compression_reads_back tries the
 * layouts). */
static exr_result_t read_pixels(exr_context_t ctx, const exr_attr_box2i_t *dw,
                                const channel_map_t *map, int nchannels,
                                image_t *img)
{
    int32_t lines = 1;
    exr_result_t rv = exr_get_scanlines_per_chunk(ctx, 0, &lines);
    if (rv != EXR_ERR_SUCCESS)
        return rv;
    if (lines < 1 || lines > 256) /* 1, 16, 32 or 256 in the format */
        return EXR_ERR_CORRUPT_CHUNK;
    size_t nch = (size_t)(nchannels > 0 ? nchannels : 1);
    size_t *at = malloc(nch * sizeof *at);
    scratch_t sc = { NULL, 0, calloc(nch, sizeof(int)), nchannels };
    if (!at || !sc.filled) {
        free(at);
        free(sc.filled);
        return EXR_ERR_OUT_OF_MEMORY;
    }
    const size_t w = (size_t)img->width;
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    bool started = false;
    for (int64_t y = dw->min.y; y <= dw->max.y && rv == EXR_ERR_SUCCESS;
         y += lines) {
        exr_chunk_info_t cinfo;
        rv = exr_read_scanline_chunk_info(ctx, 0, (int)y, &cinfo);
        if (rv != EXR_ERR_SUCCESS)
            break;
        int64_t row = (int64_t)cinfo.start_y - dw->min.y;
        if (cinfo.height < 1 || cinfo.height > lines || row < 0 ||
            row + cinfo.height > img->height) {
            rv = EXR_ERR_CORRUPT_CHUNK;
            break;
        }
        rv = started ? exr_decoding_update(ctx, 0, &cinfo, &dec)
                     : exr_decoding_initialize(ctx, 0, &cinfo, &dec);
        if (rv != EXR_ERR_SUCCESS)
            break;
        if (dec.channel_count != nchannels) {
            rv = EXR_ERR_CORRUPT_CHUNK;
            break;
        }
        if ((rv = point_channels(&dec, &sc, at)) != EXR_ERR_SUCCESS)
            break;
        if (!started) {
            rv = choose_routines(ctx, &dec);
            started = true;
            if (rv != EXR_ERR_SUCCESS)
                break;
        }
        /* An uncompressed chunk shorter than its pixels: without a
         * decompress step the library would leave the rest of its buffer
         * unwritten, and the image would read garbage (or zeros). */
        if (!dec.decompress_fn && cinfo.packed_size != cinfo.unpacked_size) {
            rv = EXR_ERR_CORRUPT_CHUNK;
            break;
        }
        dec.decoding_user_data = &sc; /* for unpack_to_planes */
        if ((rv = pad_b44_scratch(ctx, &dec, &cinfo)) != EXR_ERR_SUCCESS)
            break;
        if ((rv = exr_decoding_run(ctx, 0, &dec)) != EXR_ERR_SUCCESS)
            break;
        for (int c = 0; c < dec.channel_count; c++) {
            const exr_coding_channel_info_t *ch = &dec.channels[c];
            int k = target_channel(ch->channel_name, map, img);
            /* map_channels refused subsampled channels that are read */
            if (k < 0 || (size_t)ch->width != w ||
                ch->height != cinfo.height)
                continue;
            const float *plane = sc.buf + at[c];
            int kmax = map->y >= 0 && k == 0 ? 3 : k + 1; /* grey: R G B */
            for (int j = 0; j < cinfo.height; j++)
                for (size_t x = 0; x < w; x++) {
                    float *p = image_at(img, (int)x, (int)row + j);
                    for (int kk = k; kk < kmax; kk++)
                        p[kk] = plane[(size_t)j * w + x];
                }
        }
    }
    if (started)
        exr_decoding_destroy(ctx, &dec);
    free(sc.buf);
    free(sc.filled);
    free(at);
    return rv;
}

svet_status exrio_read(const char *path, image_t *img, svet_error *err)
{
    return exrio_read_with(path, img, NULL, err);
}

svet_status exrio_read_with(const char *path, image_t *img,
                            const image_read_limits_t *lim, svet_error *err)
{
    memset(img, 0, sizeof *img);
    FILE *f;
    svet_status st = fileio_open_read(path, &f, err);
    if (st != SVET_OK)
        return st;
    stream_t s = { .fd = fileno(f) };
    stream_t *outer = active_stream;
    active_stream = &s;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = on_error;
    init.user_data = &s;
    init.read_fn = read_cb;
    init.size_fn = size_cb;
    /* Let the library refuse absurd sizes while parsing the header, and
     * report missing chunks rather than search the file for them. */
    init.max_image_width = IMAGE_MAX_DIM;
    init.max_image_height = IMAGE_MAX_DIM;
    init.flags = EXR_CONTEXT_FLAG_DISABLE_CHUNK_RECONSTRUCTION;

    exr_context_t ctx = NULL;
    exr_result_t rv = exr_start_read(&ctx, path, &init);
    if (rv != EXR_ERR_SUCCESS) {
        /* A short read is a truncated file (PARSE); only a failing
         * pread is an I/O error. */
        st = fail(err, rv == EXR_ERR_OUT_OF_MEMORY ? SVET_ERR_NOMEM
                  : s.os_error                    ? SVET_ERR_IO
                                                  : SVET_ERR_PARSE,
                  path, &s, "not a readable EXR file", rv);
        goto done;
    }
    exr_storage_t storage;
    const exr_attr_chlist_t *cl = NULL;
    exr_attr_box2i_t dw;
    if ((rv = exr_get_storage(ctx, 0, &storage)) != EXR_ERR_SUCCESS ||
        (rv = exr_get_data_window(ctx, 0, &dw)) != EXR_ERR_SUCCESS ||
        (rv = exr_get_channels(ctx, 0, &cl)) != EXR_ERR_SUCCESS) {
        st = fail(err, SVET_ERR_PARSE, path, &s, "bad header", rv);
        goto done;
    }
    if (storage != EXR_STORAGE_SCANLINE) {
        st = svet_error_set(err, SVET_ERR_UNSUPPORTED,
                            "%s: %s EXR files are not supported; svet reads "
                            "scanline images (convert it, e.g. oiiotool "
                            "IN.exr --scanline -o OUT.exr)", path,
                            storage == EXR_STORAGE_TILED ? "tiled"
                            : storage == EXR_STORAGE_DEEP_SCANLINE
                                ? "deep scanline"
                                : "deep tiled");
        goto done;
    }
    channel_map_t map;
    if ((st = map_channels(cl, &map, path, err)) != SVET_OK)
        goto done;
    int64_t w = (int64_t)dw.max.x - dw.min.x + 1;
    int64_t h = (int64_t)dw.max.y - dw.min.y + 1;
    int nch = map.rgba[3] >= 0 ? 4 : 3;
    if ((st = image_check_read_size(w, h, nch, sizeof(float), lim, NULL,
                                    err)) != SVET_OK ||
        (st = image_alloc(img, (int)w, (int)h, nch, err)) != SVET_OK) {
        svet_error_prefix(err, path);
        goto done;
    }
    if ((rv = read_pixels(ctx, &dw, &map, cl->num_channels, img)) != EXR_ERR_SUCCESS) {
        st = fail(err, rv == EXR_ERR_OUT_OF_MEMORY ? SVET_ERR_NOMEM
                  : s.os_error                    ? SVET_ERR_IO
                                                  : SVET_ERR_PARSE,
                  path, &s, "cannot read the pixels (corrupt or truncated)",
                  rv);
        goto done;
    }
done:
    if (ctx)
        exr_finish(&ctx);
    active_stream = outer;
    fclose(f);
    if (st != SVET_OK)
        image_free(img);
    return st;
}
