/* image_png.c -- PNG to RGBA8 through libpng's classic API (image_decode.h). Owned by the import/export layer.
 * The classic API rather than png_image: the size is checked between png_read_info() and the
 * first pixel buffer, and errors come back through our own setjmp frame. */
#include <png.h>
#include <setjmp.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image_decode.h"

/* libpng's own heap (png/info structs, zlib, ancillary chunks) before the size is known;
 * its row buffers (two rows of up to 8 bytes per pixel) are added once it is. Every libpng
 * allocation goes through _tlod_png_malloc, which refuses past this: a chunk length field
 * or a zTXt stream cannot make libpng allocate more (fuzz_image found a zTXt claiming 925 MB
 * allocated by png_read_info). Taken from the budget with the pixels. */
#define _TLOD_PNG_OVERHEAD ((size_t)1 << 20)
#define _TLOD_PNG_ROWS(w) (2 * ((size_t)(w)*8 + 256))
/* A PNG ancillary chunk (iCCP, zTXt, ...) larger than this is skipped (libpng default: 8 MB). */
#define _TLOD_PNG_MAX_CHUNK ((png_alloc_size_t)1 << 19)

/* libpng's heap: sizes in a 16-byte header so that free can give them back. Volatile: changed
 * after setjmp and read (by the frees of png_destroy_read_struct) after the longjmp. */
typedef struct _tlod_png_heap {
  volatile size_t used, cap;
} _tlod_png_heap;

static png_voidp _tlod_png_malloc(png_structp png, png_alloc_size_t n) {
  _tlod_png_heap* h = (_tlod_png_heap*)png_get_mem_ptr(png);
  if (n > h->cap - h->used) return NULL; /* libpng turns this into its out-of-memory error */
  unsigned char* p = (unsigned char*)malloc(n + 16);
  if (!p) return NULL;
  memcpy(p, &n, sizeof n);
  h->used += n;
  return p + 16;
}

static void _tlod_png_free(png_structp png, png_voidp ptr) {
  if (!ptr) return;
  _tlod_png_heap* h = (_tlod_png_heap*)png_get_mem_ptr(png);
  unsigned char* p = (unsigned char*)ptr - 16;
  png_alloc_size_t n;
  memcpy(&n, p, sizeof n);
  h->used -= n;
  free(p);
}

/* Every chunk up to IEND must fit in the file: a length past the end is a truncated or
 * corrupt file, refused before libpng allocates for it. */
static bool _tlod_png_chunks_fit(const unsigned char* d, size_t size) {
  size_t pos = 8;
  while (size - pos >= 12) {
    const size_t len = (size_t)d[pos] << 24 | (size_t)d[pos + 1] << 16 | (size_t)d[pos + 2] << 8 | d[pos + 3];
    if (len > size - pos - 12) return false;
    if (!memcmp(d + pos + 4, "IEND", 4)) return true;
    pos += 12 + len;
  }
  return false; /* no IEND: truncated */
}

typedef struct _tlod_png_source {
  const unsigned char* data;
  size_t size, at;
  char* detail;
  size_t detail_size;
} _tlod_png_source;

/* Must not return: back to the setjmp in _tlod_png_decode. */
static void _tlod_png_error(png_structp png, png_const_charp msg) {
  _tlod_png_source* s = (_tlod_png_source*)png_get_error_ptr(png);
  if (s->detail && s->detail_size) snprintf(s->detail, s->detail_size, "%s", msg);
  png_longjmp(png, 1);
}

static void _tlod_png_warning(png_structp png, png_const_charp msg) {
  (void)png;
  (void)msg; /* never printed: a library must not write to stderr */
}

static void _tlod_png_read(png_structp png, png_bytep out, png_size_t n) {
  _tlod_png_source* s = (_tlod_png_source*)png_get_io_ptr(png);
  if (n > s->size - s->at) png_error(png, "truncated PNG");
  memcpy(out, s->data + s->at, n);
  s->at += n;
}

/* Every colour type and depth to 8-bit RGBA. */
static void _tlod_png_to_rgba8(png_structp png, png_infop info) {
  const int type = png_get_color_type(png, info);
  png_set_expand(png); /* palette -> RGB, gray < 8 bits -> 8, tRNS -> alpha */
  png_set_strip_16(png);
  if (type == PNG_COLOR_TYPE_GRAY || type == PNG_COLOR_TYPE_GRAY_ALPHA) png_set_gray_to_rgb(png);
  if (!(type & PNG_COLOR_MASK_ALPHA) && !png_get_valid(png, info, PNG_INFO_tRNS))
    png_set_add_alpha(png, 0xFF, PNG_FILLER_AFTER);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
}

_tlod_image_status _tlod_png_decode(const unsigned char* data, size_t size, _tlod_import_budget* budget,
                                    _tlod_image* out, char* detail, size_t detail_size) {
  if (size < 8 || !_tlod_png_chunks_fit(data, size)) {
    if (detail && detail_size) snprintf(detail, detail_size, "truncated PNG (a chunk runs past the end)");
    return _TLOD_IMAGE_CORRUPT;
  }
  _tlod_png_source src = {data, size, 0, detail, detail_size};
  _tlod_png_heap heap = {0, _TLOD_PNG_OVERHEAD};
  png_structp png = png_create_read_struct_2(PNG_LIBPNG_VER_STRING, &src, _tlod_png_error, _tlod_png_warning, &heap,
                                             _tlod_png_malloc, _tlod_png_free);
  if (!png) return _TLOD_IMAGE_OUT_OF_MEMORY;
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_read_struct(&png, NULL, NULL);
    return _TLOD_IMAGE_OUT_OF_MEMORY;
  }
  /* Changed after setjmp and read after the longjmp: volatile, or their values are indeterminate. */
  unsigned char* volatile rgba = NULL;
  png_bytep* volatile rows = NULL;
  volatile _tlod_image_status status = _TLOD_IMAGE_CORRUPT;
  if (setjmp(png_jmpbuf(png))) {
    free(rows);
    free(rgba);
    png_destroy_read_struct(&png, &info, NULL);
    return status;
  }
  png_set_read_fn(png, &src, _tlod_png_read);
  png_set_chunk_malloc_max(png, _TLOD_PNG_MAX_CHUNK);
  png_read_info(png, info);
  const uint32_t w = png_get_image_width(png, info), h = png_get_image_height(png, info);
  status = _tlod_image_reserve(w, h, 4 + sizeof(png_bytep), _TLOD_PNG_OVERHEAD + _TLOD_PNG_ROWS(w), budget);
  if (status != _TLOD_IMAGE_OK) png_error(png, _tlod_image_message(status));
  heap.cap += _TLOD_PNG_ROWS(w);
  status = _TLOD_IMAGE_CORRUPT;
  _tlod_png_to_rgba8(png, info);
  if (png_get_rowbytes(png, info) != (size_t)w * 4) png_error(png, "unexpected row size after conversion");
  rgba = (unsigned char*)malloc((size_t)w * h * 4);
  rows = (png_bytep*)malloc(sizeof(png_bytep) * h);
  if (!rgba || !rows) {
    status = _TLOD_IMAGE_OUT_OF_MEMORY;
    png_error(png, "out of memory");
  }
  for (uint32_t y = 0; y < h; ++y)
    rows[y] = rgba + (size_t)y * w * 4;
  png_read_image(png, rows);
  free(rows);
  png_destroy_read_struct(&png, &info, NULL);
  *out = (_tlod_image){w, h, rgba};
  return _TLOD_IMAGE_OK;
}
