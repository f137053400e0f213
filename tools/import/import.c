/* import.c -- tlod_import_file() dispatch, result building and shared helpers.
 * Owned by the import/export layer (tools/import/). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "import_internal.h"

static void* _tlod_default_alloc(size_t size, void* user_data) {
  (void)user_data;
  return malloc(size);
}

static void _tlod_default_free(void* ptr, void* user_data) {
  (void)user_data;
  free(ptr);
}

static void _tlod_write_error(char* error, size_t size, const char* name, const char* fmt, va_list ap) {
  if (!error || size == 0) return;
  int n = snprintf(error, size, "%s: ", name);
  if (n < 0 || (size_t)n >= size) return; /* truncated: still terminated */
  vsnprintf(error + n, size - (size_t)n, fmt, ap);
}

tlod_result _tlod_import_fail(const _tlod_import_job* job, tlod_result result, const char* fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  _tlod_write_error(job->error, job->error_size, job->name, fmt, ap);
  va_end(ap);
  return result;
}

bool _tlod_str_ends_with_nocase(const char* s, const char* suffix) {
  size_t n = strlen(s), m = strlen(suffix);
  if (m > n) return false;
  for (size_t i = 0; i < m; ++i) {
    char a = s[n - m + i], b = suffix[i];
    if (a >= 'A' && a <= 'Z') a = (char)(a - 'A' + 'a');
    if (b >= 'A' && b <= 'Z') b = (char)(b - 'A' + 'a');
    if (a != b) return false;
  }
  return true;
}

/* Grows *buf to hold at least need bytes (doubling), capped by the file limit. */
static bool _tlod_grow(unsigned char** buf, size_t* cap, size_t need) {
  if (need <= *cap) return true;
  size_t c = *cap ? *cap : 65536;
  while (c < need)
    c *= 2;
  unsigned char* p = (unsigned char*)realloc(*buf, c);
  if (!p) return false;
  *buf = p;
  *cap = c;
  return true;
}

/* Reads in chunks rather than trusting ftell: works for pipes, and a folder
 * fails in fread with EISDIR instead of reporting a bogus size. */
tlod_result _tlod_import_read_file(const _tlod_import_job* job, unsigned char** data, size_t* size) {
  *data = NULL;
  *size = 0;
  FILE* f = fopen(job->path, "rb");
  if (!f) {
    return _tlod_import_fail(job, TLOD_ERROR_IO, "cannot open '%s': %s", job->path, strerror(errno));
  }
  unsigned char* buf = NULL;
  size_t cap = 0, len = 0;
  tlod_result res = TLOD_SUCCESS;
  for (;;) {
    if (!_tlod_grow(&buf, &cap, len + 65536 + 1)) {
      res = _tlod_import_fail(job, TLOD_ERROR_OUT_OF_MEMORY, "out of memory reading the file");
      break;
    }
    size_t got = fread(buf + len, 1, cap - len - 1, f);
    len += got;
    if (ferror(f)) {
      res = _tlod_import_fail(job, TLOD_ERROR_IO, "cannot read '%s': %s", job->path, strerror(errno));
      break;
    }
    if (feof(f)) break;
    if (len > _TLOD_IMPORT_MAX_FILE_BYTES) {
      res = _tlod_import_fail(job, TLOD_ERROR_UNSUPPORTED, "file larger than %zu bytes",
                              (size_t)_TLOD_IMPORT_MAX_FILE_BYTES);
      break;
    }
  }
  fclose(f);
  if (res != TLOD_SUCCESS) {
    free(buf);
    return res;
  }
  buf[len] = 0;
  *data = buf;
  *size = len;
  return TLOD_SUCCESS;
}

/* ------------------------------------------------------------------------ */
/* Result                                                                   */
/* ------------------------------------------------------------------------ */

static void* _tlod_copy(const tlod_allocator* a, const void* src, size_t size, bool* ok) {
  if (!src || size == 0) return NULL;
  void* p = a->alloc_fn(size, a->user_data);
  if (!p) {
    *ok = false;
    return NULL;
  }
  memcpy(p, src, size);
  return p;
}

/* Keeps whole lines: a truncated list ends with "...". */
static void _tlod_copy_warnings(char* dst, size_t size, const char* src) {
  dst[0] = 0;
  if (!src) return;
  size_t n = strlen(src);
  if (n < size) {
    memcpy(dst, src, n + 1);
    return;
  }
  size_t keep = size - 5; /* room for "...\n" and the terminator */
  while (keep > 0 && src[keep - 1] != '\n')
    keep--;
  memcpy(dst, src, keep);
  memcpy(dst + keep, "...\n", 5);
}

tlod_result _tlod_import_finish(const _tlod_import_job* job, const _tlod_import_data* d) {
  const tlod_allocator* a = &job->allocator;
  tlod_import_result* r = (tlod_import_result*)a->alloc_fn(sizeof *r, a->user_data);
  if (!r) return _tlod_import_fail(job, TLOD_ERROR_OUT_OF_MEMORY, "out of memory");
  memset(r, 0, sizeof *r);
  r->_allocator = *a;
  bool ok = true;
  r->vertex_count = d->vertex_count;
  r->positions = (float*)_tlod_copy(a, d->positions, (size_t)d->vertex_count * 12u, &ok);
  r->normals = (float*)_tlod_copy(a, d->normals, (size_t)d->vertex_count * 12u, &ok);
  r->index_count = d->index_count;
  r->indices = (uint32_t*)_tlod_copy(a, d->indices, (size_t)d->index_count * 4u, &ok);
  r->face_count = d->face_count;
  r->face_sizes = (uint8_t*)_tlod_copy(a, d->face_sizes, d->face_count, &ok);
  r->part_count = d->part_count;
  r->parts = (tlod_import_part*)_tlod_copy(a, d->parts, d->part_count * sizeof(tlod_import_part), &ok);
  r->polygons_triangulated = d->polygons_triangulated;
  r->strips_fans_converted = d->strips_fans_converted;
  r->primitives_skipped = d->primitives_skipped;
  r->warning_count = d->warning_count;
  _tlod_copy_warnings(r->warnings, sizeof r->warnings, d->warnings);
  if (!ok) {
    tlod_import_free(r);
    return _tlod_import_fail(job, TLOD_ERROR_OUT_OF_MEMORY, "out of memory for %u vertices", d->vertex_count);
  }
  *job->out = r;
  return TLOD_SUCCESS;
}

void tlod_import_free(tlod_import_result* r) {
  if (!r) return;
  tlod_allocator a = r->_allocator;
  a.free_fn(r->positions, a.user_data);
  a.free_fn(r->normals, a.user_data);
  a.free_fn(r->indices, a.user_data);
  a.free_fn(r->face_sizes, a.user_data);
  a.free_fn(r->parts, a.user_data);
  a.free_fn(r, a.user_data);
}

/* ------------------------------------------------------------------------ */
/* Entry point                                                              */
/* ------------------------------------------------------------------------ */

static const char* _tlod_base_name(const char* path) {
  const char* s = strrchr(path, '/');
  return s ? s + 1 : path;
}

tlod_result tlod_import_file(const char* path, const tlod_allocator* allocator, tlod_import_result** out, char* error,
                             size_t error_size) {
  if (error && error_size) error[0] = 0;
  if (out) *out = NULL;
  _tlod_import_job job = {path, path ? _tlod_base_name(path) : "(null)", {0}, out, error, error_size};
  if (!path || !out) {
    return _tlod_import_fail(&job, TLOD_ERROR_INVALID_ARGUMENT, "path and out must not be NULL");
  }
  if (allocator && (!allocator->alloc_fn) != (!allocator->free_fn)) {
    return _tlod_import_fail(&job, TLOD_ERROR_INVALID_ARGUMENT,
                             "allocator needs both alloc_fn and free_fn, or neither");
  }
  if (allocator && allocator->alloc_fn) {
    job.allocator = *allocator;
  } else {
    job.allocator = (tlod_allocator){_tlod_default_alloc, _tlod_default_free, NULL};
  }
  tlod_result res;
  if (_tlod_str_ends_with_nocase(path, ".gltf") || _tlod_str_ends_with_nocase(path, ".glb")) {
    res = _tlod_import_gltf(&job);
  } else if (_tlod_str_ends_with_nocase(path, ".obj")) {
    res = _tlod_import_obj(&job);
  } else if (_tlod_str_ends_with_nocase(path, ".ply")) {
    res = _tlod_import_ply(&job);
  } else {
    res =
        _tlod_import_fail(&job, TLOD_ERROR_UNSUPPORTED, "unknown file extension (expected .gltf, .glb, .obj or .ply)");
  }
  if (res == TLOD_SUCCESS && error && error_size) error[0] = 0;
  return res;
}
