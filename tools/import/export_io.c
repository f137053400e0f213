/* export_io.c -- the writers' plumbing: messages, the output file with a
 * sticky error, a raw/base64 byte sink, JSON text, and the atomic write.
 * Owned by the import/export layer (tools/import/).
 *
 * Files are written through tlod_atomic_file (platform/atomic_file/): under
 * a unique temporary name next to the target, renamed when complete, so a
 * failure never leaves a truncated file under the requested name. */
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "export_internal.h"
#include "tlod_atomic_file.h"

_exp_format _exp_format_of(const char* path) {
  if (_tlod_str_ends_with_nocase(path, ".obj")) return _EXP_OBJ;
  if (_tlod_str_ends_with_nocase(path, ".ply")) return _EXP_PLY;
  if (_tlod_str_ends_with_nocase(path, ".gltf")) return _EXP_GLTF;
  if (_tlod_str_ends_with_nocase(path, ".glb")) return _EXP_GLB;
  return _EXP_UNKNOWN;
}

_exp_job _exp_job_for(const char* path, char* error, size_t error_size) {
  if (error && error_size) error[0] = 0;
  _exp_job job = {path, "(null)", error, error_size, NULL, false};
  if (path) {
    const char* slash = strrchr(path, '/');
    job.name = slash ? slash + 1 : path;
  }
  return job;
}

tlod_result _exp_fail(_exp_job* job, tlod_result result, const char* fmt, ...) {
  if (!job->error || job->error_size == 0) return result;
  int n = snprintf(job->error, job->error_size, "%s: ", job->name);
  if (n < 0 || (size_t)n >= job->error_size) return result;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(job->error + n, job->error_size - (size_t)n, fmt, ap);
  va_end(ap);
  return result;
}

void _exp_write(_exp_job* job, const void* data, size_t size) {
  if (size && fwrite(data, 1, size, job->file) != size) job->write_failed = true;
}

void _exp_printf(_exp_job* job, const char* fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  if (vfprintf(job->file, fmt, ap) < 0) job->write_failed = true;
  va_end(ap);
}

void _exp_put_u32(unsigned char* p, uint32_t v) {
  p[0] = (unsigned char)v, p[1] = (unsigned char)(v >> 8), p[2] = (unsigned char)(v >> 16),
  p[3] = (unsigned char)(v >> 24);
}

uint32_t _exp_float_bits(float f) {
  uint32_t u;
  memcpy(&u, &f, 4);
  return u;
}

static void _exp_sink_flush(_exp_sink* s) {
  _exp_write(s->job, s->buf, s->used);
  s->used = 0;
}

static void _exp_sink_raw(_exp_sink* s, const unsigned char* p, size_t n) {
  while (n) {
    if (s->used == sizeof s->buf) _exp_sink_flush(s);
    size_t k = sizeof s->buf - s->used < n ? sizeof s->buf - s->used : n;
    memcpy(s->buf + s->used, p, k);
    s->used += k, p += k, n -= k;
  }
}

static void _exp_base64_group(_exp_sink* s, const unsigned char in[3], size_t n) {
  static const char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const uint32_t v = (uint32_t)in[0] << 16 | (uint32_t)(n > 1 ? in[1] : 0) << 8 | (n > 2 ? in[2] : 0);
  unsigned char out[4] = {(unsigned char)alphabet[v >> 18 & 63], (unsigned char)alphabet[v >> 12 & 63],
                          (unsigned char)(n > 1 ? alphabet[v >> 6 & 63] : '='),
                          (unsigned char)(n > 2 ? alphabet[v & 63] : '=')};
  _exp_sink_raw(s, out, 4);
}

void _exp_sink_put(_exp_sink* s, const unsigned char* p, size_t n) {
  if (!s->base64) {
    _exp_sink_raw(s, p, n);
    return;
  }
  for (size_t i = 0; i < n; ++i) {
    s->carry[s->carried++] = p[i];
    if (s->carried == 3) {
      _exp_base64_group(s, s->carry, 3);
      s->carried = 0;
    }
  }
}

void _exp_sink_end(_exp_sink* s) {
  if (s->base64 && s->carried) _exp_base64_group(s, s->carry, s->carried);
  s->carried = 0;
  _exp_sink_flush(s);
}

void _exp_sink_u32(_exp_sink* s, uint32_t v) {
  unsigned char b[4];
  _exp_put_u32(b, v);
  _exp_sink_put(s, b, 4);
}

/* Writes through the atomic file writer: a unique temporary next to path,
 * renamed over path when complete. */
tlod_result _exp_write_atomic(_exp_job* job, _exp_body body, const void* user) {
  char err[512];
  tlod_atomic_file file;
  _exp_sink* s = calloc(1, sizeof *s);
  if (!s) return _exp_fail(job, TLOD_ERROR_OUT_OF_MEMORY, "out of memory");
  s->job = job;
  if (!tlod_atomic_file_begin(&file, job->path, err, sizeof err)) {
    free(s);
    return _exp_fail(job, TLOD_ERROR_IO, "%s", err);
  }
  job->file = file.file;
  tlod_result res = body(job, s, user);
  free(s);
  if (res == TLOD_SUCCESS && job->write_failed) snprintf(err, sizeof err, "cannot write '%s'", job->path);
  const bool kept = tlod_atomic_file_end(&file, res == TLOD_SUCCESS && !job->write_failed, err, sizeof err);
  job->file = NULL;
  if (res == TLOD_SUCCESS && !kept) res = _exp_fail(job, TLOD_ERROR_IO, "%s", err);
  return res;
}
