/* image_jpeg.c -- JPEG to RGBA8 through libjpeg-turbo (image_decode.h). Owned by the import/export layer.
 * libjpeg reports errors by calling error_exit, which must not return: ours longjmps back into
 * _tlod_jpeg_decode, which destroys the decompressor and frees the pixels. */
#include <stdio.h> /* jpeglib.h needs FILE */

#include <jerror.h>
#include <jpeglib.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>

#include "image_decode.h"

/* libjpeg's own buffers besides the coefficient arrays of progressive files. */
#define _TLOD_JPEG_OVERHEAD ((size_t)1 << 20)

typedef struct _tlod_jpeg_error {
  struct jpeg_error_mgr pub; /* first: libjpeg sees a jpeg_error_mgr* */
  jmp_buf jump;
  char* detail;
  size_t detail_size;
} _tlod_jpeg_error;

static void _tlod_jpeg_exit(j_common_ptr c) {
  _tlod_jpeg_error* e = (_tlod_jpeg_error*)c->err;
  char msg[JMSG_LENGTH_MAX];
  (*c->err->format_message)(c, msg);
  if (e->detail && e->detail_size) snprintf(e->detail, e->detail_size, "%s", msg);
  longjmp(e->jump, 1);
}

/* Never printed. A premature end is fatal: libjpeg would otherwise pad the picture with grey. */
static void _tlod_jpeg_emit(j_common_ptr c, int level) {
  if (level < 0 && c->err->msg_code == JWRN_JPEG_EOF) _tlod_jpeg_exit(c);
}

static void _tlod_jpeg_output(j_common_ptr c) { (void)c; }

/* Pixels, plus for progressive (and multi-scan) files the whole coefficient image
 * (2 bytes per component and pixel), which libjpeg keeps until the last scan. */
static _tlod_image_status _tlod_jpeg_reserve(const struct jpeg_decompress_struct* d, _tlod_import_budget* budget,
                                             size_t* library_bytes) {
  const size_t coefficients = jpeg_has_multiple_scans((j_decompress_ptr)d) ? 2u * (size_t)d->num_components : 0u;
  *library_bytes = (size_t)d->image_width * d->image_height * coefficients + _TLOD_JPEG_OVERHEAD;
  return _tlod_image_reserve(d->image_width, d->image_height, 4 + coefficients, _TLOD_JPEG_OVERHEAD, budget);
}

/* On the heap: libjpeg changes both after setjmp, and a changed non-volatile automatic
 * object is indeterminate after the longjmp (C11 7.13.2.1); the pointer to them is not. */
typedef struct _tlod_jpeg_state {
  struct jpeg_decompress_struct d;
  _tlod_jpeg_error err;
} _tlod_jpeg_state;

static _tlod_jpeg_state* _tlod_jpeg_state_new(char* detail, size_t detail_size) {
  _tlod_jpeg_state* s = (_tlod_jpeg_state*)calloc(1, sizeof *s);
  if (!s) return NULL;
  s->d.err = jpeg_std_error(&s->err.pub);
  s->err.pub.error_exit = _tlod_jpeg_exit;
  s->err.pub.emit_message = _tlod_jpeg_emit;
  s->err.pub.output_message = _tlod_jpeg_output;
  s->err.detail = detail;
  s->err.detail_size = detail_size;
  return s;
}

static void _tlod_jpeg_state_free(_tlod_jpeg_state* s) {
  jpeg_destroy_decompress(&s->d); /* also after a failed jpeg_create_decompress: it checks d.mem */
  free(s);
}

/* Header, size check and budget, then the scanlines. */
static _tlod_image_status _tlod_jpeg_run(_tlod_jpeg_state* s, const unsigned char* data, size_t size,
                                         _tlod_import_budget* budget, unsigned char* volatile* rgba,
                                         volatile _tlod_image_status* status) {
  struct jpeg_decompress_struct* d = &s->d;
  jpeg_create_decompress(d);
  jpeg_mem_src(d, data, (unsigned long)size);
  jpeg_read_header(d, TRUE);
  size_t library_bytes = 0;
  const _tlod_image_status st = _tlod_jpeg_reserve(d, budget, &library_bytes);
  if (st != _TLOD_IMAGE_OK) return st;
  d->mem->max_memory_to_use = (long)library_bytes; /* no backing store: past it libjpeg fails */
  d->out_color_space = JCS_EXT_RGBA;
  jpeg_start_decompress(d);
  const uint32_t w = d->output_width, h = d->output_height;
  *status = _TLOD_IMAGE_OUT_OF_MEMORY;
  *rgba = (unsigned char*)malloc((size_t)w * h * 4);
  if (!*rgba) return _TLOD_IMAGE_OUT_OF_MEMORY;
  *status = _TLOD_IMAGE_CORRUPT;
  while (d->output_scanline < h) {
    JSAMPROW row = *rgba + (size_t)d->output_scanline * w * 4;
    jpeg_read_scanlines(d, &row, 1);
  }
  jpeg_finish_decompress(d);
  return _TLOD_IMAGE_OK;
}

_tlod_image_status _tlod_jpeg_decode(const unsigned char* data, size_t size, _tlod_import_budget* budget,
                                     _tlod_image* out, char* detail, size_t detail_size) {
  _tlod_jpeg_state* const s = _tlod_jpeg_state_new(detail, detail_size);
  if (!s) return _TLOD_IMAGE_OUT_OF_MEMORY;
  /* Changed after setjmp and read after the longjmp: volatile. */
  unsigned char* volatile rgba = NULL;
  volatile _tlod_image_status status = _TLOD_IMAGE_CORRUPT;
  if (setjmp(s->err.jump)) {
    _tlod_jpeg_state_free(s);
    free(rgba);
    return status;
  }
  const _tlod_image_status st = _tlod_jpeg_run(s, data, size, budget, &rgba, &status);
  const uint32_t w = s->d.output_width, h = s->d.output_height;
  _tlod_jpeg_state_free(s);
  if (st != _TLOD_IMAGE_OK) {
    free(rgba);
    return st;
  }
  *out = (_tlod_image){w, h, rgba};
  return _TLOD_IMAGE_OK;
}
