/* image_decode.h -- PNG (libpng) and JPEG (libjpeg-turbo) decoding to RGBA8 for the importers
 * (private to tools/import/). Owned by the import/export layer. docs/security.md states the rules:
 *   - the format comes from the signature (never from a file name or a MIME type);
 *   - width x height is read from the header and checked against TLOD_IMPORT_MAX_IMAGE_PIXELS
 *     and taken from the import's memory budget BEFORE the pixels (and, for progressive JPEG,
 *     the coefficient buffers) are allocated;
 *   - decoder errors longjmp back into the decoder's own frame, which frees what it took;
 *     nothing is printed; a truncated file is an error (never a half-grey image);
 *   - the result is width * height RGBA8, top row first, in malloc memory.
 * Not thread-hostile: no global state; each call has its own decoder state. */
#ifndef TESSLOD_TOOLS_IMPORT_IMAGE_DECODE_H
#define TESSLOD_TOOLS_IMPORT_IMAGE_DECODE_H

#include "import_internal.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum _tlod_image_status {
  _TLOD_IMAGE_OK = 0,
  _TLOD_IMAGE_UNKNOWN_FORMAT, /* neither a PNG nor a JPEG signature */
  _TLOD_IMAGE_CORRUPT,        /* the decoder refused it (truncated, bad data, unsupported colour) */
  _TLOD_IMAGE_TOO_LARGE,      /* more than TLOD_IMPORT_MAX_IMAGE_PIXELS pixels */
  _TLOD_IMAGE_OVER_BUDGET,    /* its decoded size does not fit the import's remaining memory budget */
  _TLOD_IMAGE_OUT_OF_MEMORY   /* malloc failed */
} _tlod_image_status;

typedef struct _tlod_image {
  uint32_t width, height;
  unsigned char* rgba; /* width * height * 4 bytes, malloc; NULL unless _TLOD_IMAGE_OK */
} _tlod_image;

/* "image/png" or "image/jpeg" from the first bytes, NULL for anything else. */
const char* _tlod_image_sniff(const unsigned char* data, size_t size);

/* Decodes data by its signature. detail receives the decoder's message (may be NULL). */
_tlod_image_status _tlod_image_decode(const unsigned char* data, size_t size, _tlod_import_budget* budget,
                                      _tlod_image* out, char* detail, size_t detail_size);

/* The decoders themselves (image_png.c, image_jpeg.c), same contract. */
_tlod_image_status _tlod_png_decode(const unsigned char* data, size_t size, _tlod_import_budget* budget,
                                    _tlod_image* out, char* detail, size_t detail_size);
_tlod_image_status _tlod_jpeg_decode(const unsigned char* data, size_t size, _tlod_import_budget* budget,
                                     _tlod_image* out, char* detail, size_t detail_size);

/* For the decoders: checks width x height against the pixel limit and takes
 * width * height * bytes_per_pixel + extra from the budget. */
_tlod_image_status _tlod_image_reserve(uint32_t width, uint32_t height, size_t bytes_per_pixel, size_t extra,
                                       _tlod_import_budget* budget);

/* A short phrase for a status ("larger than the pixel limit"). */
const char* _tlod_image_message(_tlod_image_status status);

#ifdef __cplusplus
}
#endif
#endif
