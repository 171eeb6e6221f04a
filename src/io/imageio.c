/*
 * imageio.c - read any svet image format by its magic bytes, write by
 * extension, and save a render as HDR plus display image. See imageio.h.
 * Tests: tests/io/test_imageio.c
 */
#include "io/imageio.h"
#include "colour/colour.h"
#include "io/exrio.h"
#include "io/fileio.h"
#include "io/netpbm.h"
#include "io/pngio.h"

#include <ctype.h>
#include <stdio.h>
#include <string.h>

static bool ext_is(const char *path, const char *ext)
{
    const char *dot = strrchr(path, '.');
    if (!dot || strchr(dot, '/'))
        return false;
    dot++;
    for (; *dot && *ext; dot++, ext++)
        if (tolower((unsigned char)*dot) != *ext)
            return false;
    return *dot == '\0' && *ext == '\0';
}

imageio_format_t imageio_format_from_name(const char *path)
{
    if (ext_is(path, "exr"))
        return IMAGEIO_EXR;
    if (ext_is(path, "pfm"))
        return IMAGEIO_PFM;
    if (ext_is(path, "png"))
        return IMAGEIO_PNG;
    if (ext_is(path, "ppm") || ext_is(path, "pgm"))
        return IMAGEIO_PPM;
    return IMAGEIO_UNKNOWN;
}

bool imageio_is_display(imageio_format_t f)
{
    return f == IMAGEIO_PNG || f == IMAGEIO_PPM;
}

/* The format from the first four bytes. */
static svet_status sniff(const char *path, imageio_format_t *f,
                         svet_error *err)
{
    FILE *fp;
    svet_status st = fileio_open_read(path, &fp, err);
    if (st != SVET_OK)
        return st;
    unsigned char m[4] = { 0 };
    size_t n = fread(m, 1, sizeof m, fp);
    fclose(fp);
    *f = IMAGEIO_UNKNOWN;
    if (n == 4 && m[0] == 0x76 && m[1] == 0x2f && m[2] == 0x31 && m[3] == 1)
        *f = IMAGEIO_EXR;
    else if (n == 4 && m[0] == 0x89 && m[1] == 'P' && m[2] == 'N' &&
             m[3] == 'G')
        *f = IMAGEIO_PNG;
    else if (n >= 2 && m[0] == 'P' && (m[1] == 'F' || m[1] == 'f'))
        *f = IMAGEIO_PFM;
    else if (n >= 2 && m[0] == 'P' && (m[1] == '5' || m[1] == '6'))
        *f = IMAGEIO_PPM;
    if (*f == IMAGEIO_UNKNOWN)
        return svet_error_set(err, SVET_ERR_PARSE, "%s: %s", path,
                              n == 0 ? "empty file, not an image"
                                     : "not an EXR, PFM, PNG or PPM file");
    return SVET_OK;
}

svet_status imageio_read(const char *path, image_t *img, bool linearise,
                         imageio_format_t *format, svet_error *err)
{
    return imageio_read_with(path, img, linearise, format, NULL, err);
}

svet_status imageio_read_with(const char *path, image_t *img, bool linearise,
                              imageio_format_t *format,
                              const image_read_limits_t *lim, svet_error *err)
{
    memset(img, 0, sizeof *img);
    imageio_format_t f = IMAGEIO_UNKNOWN;
    svet_status st = sniff(path, &f, err);
    if (st != SVET_OK)
        return st;
    switch (f) {
    case IMAGEIO_EXR:
        st = exrio_read_with(path, img, lim, err);
        break;
    case IMAGEIO_PFM:
        st = netpbm_read_pfm_with(path, img, lim, err);
        break;
    case IMAGEIO_PNG:
        st = pngio_read_with(path, img, NULL, lim, err);
        break;
    case IMAGEIO_PPM:
    case IMAGEIO_UNKNOWN:
        st = netpbm_read_ppm_with(path, img, NULL, lim, err);
        break;
    }
    if (st == SVET_OK && linearise && imageio_is_display(f))
        imageio_decode_srgb(img);
    if (format)
        *format = f;
    return st;
}

void imageio_decode_srgb(image_t *img)
{
    size_t n = (size_t)img->width * (size_t)img->height;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            float *v = &img->px[i * (size_t)img->channels + (size_t)c];
            *v = (float)colour_srgb_decode((real)*v);
        }
}

svet_status imageio_write(const char *path, const image_t *img,
                          svet_error *err)
{
    switch (imageio_format_from_name(path)) {
    case IMAGEIO_EXR:
        return exrio_write(path, img, EXRIO_FLOAT, EXRIO_ZIP, err);
    case IMAGEIO_PFM:
        return netpbm_write_pfm(path, img, err);
    case IMAGEIO_PNG:
        return pngio_write(path, img, 8, err);
    case IMAGEIO_PPM:
        return netpbm_write_ppm(path, img, 8, err);
    case IMAGEIO_UNKNOWN:
        break;
    }
    return svet_error_set(err, SVET_ERR_UNSUPPORTED, "%s: unknown image "
                          "format; svet writes .exr, .pfm, .png and .ppm",
                          path);
}

svet_status imageio_save_render(const image_t *img, const char *hdr_path,
                                const char *display_path,
                                const tonemap_params_t *tm,
                                tonemap_result_t *res, svet_error *err)
{
    if (hdr_path && imageio_is_display(imageio_format_from_name(hdr_path)))
        return svet_error_set(err, SVET_ERR_UNSUPPORTED, "%s: a linear "
                              "image is saved as .exr or .pfm", hdr_path);
    if (display_path &&
        !imageio_is_display(imageio_format_from_name(display_path)))
        return svet_error_set(err, SVET_ERR_UNSUPPORTED, "%s: a display "
                              "image is saved as .png or .ppm", display_path);
    svet_status st;
    if (hdr_path && (st = imageio_write(hdr_path, img, err)) != SVET_OK)
        return st;
    if (!display_path)
        return SVET_OK;
    tonemap_params_t def;
    if (!tm) {
        tonemap_defaults(&def, TONEMAP_REINHARD);
        tm = &def;
    }
    image_t disp;
    if ((st = tonemap_apply(img, &disp, tm, res, err)) != SVET_OK)
        return st;
    st = imageio_write(display_path, &disp, err);
    image_free(&disp);
    return st;
}
