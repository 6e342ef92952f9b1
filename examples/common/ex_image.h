/* ex_image.h — image files through OpenImageIO, behind a C interface.

   Buffers are linear RGB floats, row-major, top row first, 3 floats per pixel.
   The format follows the file extension: .png is written sRGB-encoded, 8-bit,
   clamped to [0, 1]; .exr is written linear, half float. Reading returns
   linear RGB whatever the file (PNG is decoded from sRGB).

   On failure these functions print one line on stderr,
   "<program>: cannot write out/x.png: <reason>", and return -1. */
#ifndef FILIGREE_EX_IMAGE_H
#define FILIGREE_EX_IMAGE_H

#ifdef __cplusplus
extern "C" {
#endif

/* Writes width × height RGB floats to `path` (.png or .exr). 0 or -1. */
int ex_image_write(const char *path, const float *rgb, int width, int height);

/* 0 when `path` has an extension ex_image_write handles (.png, .exr);
   otherwise prints the same one line ex_image_write would and returns -1.
   Call it before a long render. */
int ex_image_check_path(const char *path);

/* Reads `path` into a new linear RGB float buffer (*rgb, free with
   ex_image_free). Images with one channel are replicated, alpha is dropped.
   0 or -1. */
int ex_image_read(const char *path, float **rgb, int *width, int *height);
void ex_image_free(float *rgb);

/* Root-mean-square difference over all channels of two same-size buffers. */
double ex_image_rmse(const float *a, const float *b, int width, int height);

/* In place: multiply by 2^exposure_stops, then a gentle filmic shoulder that
   maps [0, ∞) to [0, 1) and keeps values below ~0.6 nearly linear. */
void ex_image_tonemap(float *rgb, int width, int height, double exposure_stops);

/* Round trip check used by `--selftest`: writes a gradient as PNG and EXR into
   `dir`, reads both back and compares (EXR to half precision, PNG to 8-bit
   sRGB quantisation), and checks that an unknown extension and an unwritable
   path fail. Prints one line per check; returns the number of failures. */
int ex_image_selftest(const char *dir);

#ifdef __cplusplus
}
#endif
#endif /* FILIGREE_EX_IMAGE_H */
