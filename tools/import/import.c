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

size_t _tlod_budget_default(size_t input_bytes) {
  size_t share;
  if (!_tlod_size_mul(input_bytes, TLOD_IMPORT_MEMORY_PER_INPUT_BYTE, &share) ||
      share > TLOD_IMPORT_MEMORY_CAP - TLOD_IMPORT_MEMORY_BASE)
    return TLOD_IMPORT_MEMORY_CAP;
  return TLOD_IMPORT_MEMORY_BASE + share;
}

void _tlod_budget_add_input(_tlod_import_budget* b, size_t bytes) {
  if (!b->proportional) return;
  const size_t inputs = (b->limit - TLOD_IMPORT_MEMORY_BASE) / TLOD_IMPORT_MEMORY_PER_INPUT_BYTE;
  size_t sum;
  b->limit = _tlod_size_add(inputs, bytes, &sum) ? _tlod_budget_default(sum) : TLOD_IMPORT_MEMORY_CAP;
}

size_t _tlod_budget_file_limit(const _tlod_import_budget* b) {
  const size_t limit = b->proportional ? (size_t)TLOD_IMPORT_MEMORY_CAP : b->limit;
  const size_t room = limit > b->used ? (limit - b->used) / 2 : 0;
  return room < _TLOD_IMPORT_MAX_FILE_BYTES ? room : _TLOD_IMPORT_MAX_FILE_BYTES;
}

bool _tlod_budget_take(_tlod_import_budget* b, size_t bytes) {
  if (bytes > b->limit - b->used) return false;
  b->used += bytes;
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

static tlod_result _tlod_over_budget(const _tlod_import_job* job) {
  return _tlod_import_fail(
      job, TLOD_ERROR_OUT_OF_MEMORY,
      "the file is larger than the import's memory budget (%zu bytes; tlod_import_desc.memory_limit)",
      job->budget->limit);
}

static tlod_result _tlod_copy_memory(const _tlod_import_job* job, unsigned char** data, size_t* size) {
  _tlod_budget_add_input(job->budget, job->memory_size);
  if (job->memory_size > _TLOD_IMPORT_MAX_FILE_BYTES)
    return _tlod_import_fail(job, TLOD_ERROR_UNSUPPORTED, "file larger than %zu bytes",
                             (size_t)_TLOD_IMPORT_MAX_FILE_BYTES);
  if (!_tlod_budget_take(job->budget, job->memory_size + 1)) return _tlod_over_budget(job);
  unsigned char* buf = (unsigned char*)malloc(job->memory_size + 1);
  if (!buf) return _tlod_import_fail(job, TLOD_ERROR_OUT_OF_MEMORY, "out of memory reading the file");
  if (job->memory_size) memcpy(buf, job->memory, job->memory_size);
  buf[job->memory_size] = 0;
  *data = buf;
  *size = job->memory_size;
  return TLOD_SUCCESS;
}

/* Reads in chunks rather than trusting ftell: works for pipes, and a folder
 * fails in fread with EISDIR instead of reporting a bogus size. */
tlod_result _tlod_import_read_file(const _tlod_import_job* job, unsigned char** data, size_t* size) {
  *data = NULL;
  *size = 0;
  if (job->memory) return _tlod_copy_memory(job, data, size);
  FILE* f = fopen(job->path, "rb");
  if (!f) {
    return _tlod_import_fail(job, TLOD_ERROR_IO, "cannot open '%s': %s", job->path, strerror(errno));
  }
  unsigned char* buf = NULL;
  size_t cap = 0, len = 0;
  tlod_result res = TLOD_SUCCESS;
  const _tlod_import_budget* b = job->budget;
  for (;;) {
    if (!b->proportional && len + 65536 + 1 > b->limit - b->used) {
      res = _tlod_over_budget(job);
      break;
    }
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
  _tlod_budget_add_input(job->budget, len);
  if (!_tlod_budget_take(job->budget, cap)) {
    free(buf);
    return _tlod_over_budget(job);
  }
  buf[len] = 0;
  *data = buf;
  *size = len;
  return TLOD_SUCCESS;
}

/* ------------------------------------------------------------------------ */
/* Entry point                                                              */
/* ------------------------------------------------------------------------ */

static const char* _tlod_base_name(const char* path) {
  const char* s = strrchr(path, '/');
  return s ? s + 1 : path;
}

/* Resolves the options: allocator hooks and the budget's starting limit. */
static tlod_result _tlod_import_setup(_tlod_import_job* job, const tlod_import_desc* desc,
                                      _tlod_import_budget* budget) {
  const tlod_allocator* allocator = desc ? &desc->allocator : NULL;
  if (allocator && (!allocator->alloc_fn) != (!allocator->free_fn)) {
    return _tlod_import_fail(job, TLOD_ERROR_INVALID_ARGUMENT, "allocator needs both alloc_fn and free_fn, or neither");
  }
  if (allocator && allocator->alloc_fn) {
    job->allocator = *allocator;
  } else {
    job->allocator = (tlod_allocator){_tlod_default_alloc, _tlod_default_free, NULL};
  }
  const size_t limit = desc ? desc->memory_limit : 0;
  *budget = (_tlod_import_budget){limit ? limit : _tlod_budget_default(0), 0, limit == 0};
  job->keep_scene = desc && desc->keep_scene;
  job->progress = desc ? desc->progress : NULL;
  job->progress_user = desc ? desc->progress_user : NULL;
  job->budget = budget;
  return TLOD_SUCCESS;
}

static tlod_result _tlod_import_dispatch(_tlod_import_job* job) {
  const char* path = job->path;
  if (_tlod_str_ends_with_nocase(path, ".gltf") || _tlod_str_ends_with_nocase(path, ".glb")) {
    return _tlod_import_gltf(job);
  } else if (_tlod_str_ends_with_nocase(path, ".obj")) {
    return _tlod_import_obj(job);
  } else if (_tlod_str_ends_with_nocase(path, ".ply")) {
    return _tlod_import_ply(job);
  } else if (_tlod_is_vtk_path(path)) {
    return _tlod_import_vtk(job);
  }
  return _tlod_import_fail(job, TLOD_ERROR_UNSUPPORTED,
                           "unknown file extension (expected .gltf, .glb, .obj, .ply, .vtk, .vtu, .vtp, .pvtu, .pvd "
                           "or .stl)");
}

/* VTK's formats (vtk_import.cpp reads them; a build without TLOD_WITH_VTK refuses them below, naming the option).
 * A '*' in the file name is a numbered series of one of them. */
bool _tlod_is_vtk_path(const char* path) {
  return _tlod_str_ends_with_nocase(path, ".vtk") || _tlod_str_ends_with_nocase(path, ".vtu") ||
         _tlod_str_ends_with_nocase(path, ".vtp") || _tlod_str_ends_with_nocase(path, ".pvtu") ||
         _tlod_str_ends_with_nocase(path, ".pvd") || _tlod_str_ends_with_nocase(path, ".stl");
}

#if !TLOD_WITH_VTK
tlod_result _tlod_import_vtk(const _tlod_import_job* job) {
  const char* dot = strrchr(job->name, '.');
  return _tlod_import_fail(job, TLOD_ERROR_UNSUPPORTED, "%s files need VTK: this build has TLOD_WITH_VTK=OFF",
                           dot ? dot : ".vtk");
}
#endif

/* The folder part of path ("" for none), in buf. */
static const char* _tlod_folder_of(const char* path, char* buf, size_t size) {
  const char* s = strrchr(path, '/');
  const size_t n = s ? (size_t)(s - path) : 0;
  if (n >= size) return NULL;
  memcpy(buf, path, n);
  buf[n] = 0;
  if (s && n == 0) snprintf(buf, size, "/");
  return buf;
}

static tlod_result _tlod_import_run(_tlod_import_job* job, const tlod_import_desc* desc) {
  if (job->error && job->error_size) job->error[0] = 0;
  if (job->out) *job->out = NULL;
  if (!job->path || !job->out) {
    return _tlod_import_fail(job, TLOD_ERROR_INVALID_ARGUMENT, "path and out must not be NULL");
  }
  _tlod_import_budget budget;
  tlod_result res = _tlod_import_setup(job, desc, &budget);
  if (res == TLOD_SUCCESS) res = _tlod_import_dispatch(job);
  if (res == TLOD_SUCCESS && job->error && job->error_size) job->error[0] = 0;
  job->budget = NULL; /* lives in this frame only */
  return res;
}

tlod_result tlod_import_file_desc(const char* path, const tlod_import_desc* desc, tlod_import_result** out, char* error,
                                  size_t error_size) {
  char folder[4096];
  _tlod_import_job job = {
      path, path ? _tlod_base_name(path) : "(null)", NULL, NULL, 0, {0}, NULL, out, error, error_size, false, NULL,
      NULL};
  job.folder = path ? _tlod_folder_of(path, folder, sizeof folder) : NULL;
  return _tlod_import_run(&job, desc);
}

tlod_result tlod_import_file(const char* path, const tlod_allocator* allocator, tlod_import_result** out, char* error,
                             size_t error_size) {
  tlod_import_desc desc = {0};
  if (allocator) desc.allocator = *allocator;
  return tlod_import_file_desc(path, &desc, out, error, error_size);
}

tlod_result tlod_import_memory(const char* name, const void* data, size_t size, const tlod_import_desc* desc,
                               tlod_import_result** out, char* error, size_t error_size) {
  static const unsigned char empty[1] = {0};
  if (out) *out = NULL;
  _tlod_import_job job = {name,
                          name ? _tlod_base_name(name) : "(null)",
                          NULL,
                          data ? (const unsigned char*)data : empty,
                          data ? size : 0,
                          {0},
                          NULL,
                          out,
                          error,
                          error_size,
                          false,
                          NULL,
                          NULL};
  if (!data && size) return _tlod_import_fail(&job, TLOD_ERROR_INVALID_ARGUMENT, "data is NULL with size %zu", size);
  return _tlod_import_run(&job, desc);
}
