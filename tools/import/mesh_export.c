/* mesh_export.c -- tlod_export_file(): OBJ, binary PLY, .gltf and .glb writers in C11.
 * Owned by the import/export layer (tools/import/).
 *
 * Every format carries positions bit-exactly: OBJ and the glTF min/max use
 * "%.9g", which round-trips any float through strtof; the binary formats
 * store the float bits little-endian. Files are written through
 * tlod_atomic_file (tools/atomic_file/): under a unique temporary name next
 * to the target, renamed when complete, so a failure never leaves a
 * truncated file under the requested name. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "import_internal.h"
#include "tlod_atomic_file.h"

typedef struct _exp_job {
  const char* path;
  const char* name; /* for messages */
  const tlod_export_mesh* mesh;
  char* error;
  size_t error_size;
  FILE* file;
  bool write_failed; /* sticky: checked once at the end */
} _exp_job;

static tlod_result _exp_fail(_exp_job* job, tlod_result result, const char* fmt, ...) _TLOD_IMPORT_PRINTF(3, 4);
static tlod_result _exp_fail(_exp_job* job, tlod_result result, const char* fmt, ...) {
  if (!job->error || job->error_size == 0) return result;
  int n = snprintf(job->error, job->error_size, "%s: ", job->name);
  if (n < 0 || (size_t)n >= job->error_size) return result;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(job->error + n, job->error_size - (size_t)n, fmt, ap);
  va_end(ap);
  return result;
}

/* ------------------------------------------------------------------------ */
/* Output plumbing                                                          */
/* ------------------------------------------------------------------------ */

static void _exp_write(_exp_job* job, const void* data, size_t size) {
  if (size && fwrite(data, 1, size, job->file) != size) job->write_failed = true;
}

static void _exp_printf(_exp_job* job, const char* fmt, ...) _TLOD_IMPORT_PRINTF(2, 3);
static void _exp_printf(_exp_job* job, const char* fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  if (vfprintf(job->file, fmt, ap) < 0) job->write_failed = true;
  va_end(ap);
}

static void _exp_put_u32(unsigned char* p, uint32_t v) {
  p[0] = (unsigned char)v, p[1] = (unsigned char)(v >> 8), p[2] = (unsigned char)(v >> 16),
  p[3] = (unsigned char)(v >> 24);
}

static uint32_t _exp_float_bits(float f) {
  uint32_t u;
  memcpy(&u, &f, 4);
  return u;
}

/* A byte stream into the file, raw or base64, fed in small pieces. */
typedef struct _exp_sink {
  _exp_job* job;
  bool base64;
  unsigned char carry[3];
  size_t carried;
  unsigned char buf[65536];
  size_t used;
} _exp_sink;

static void _exp_sink_flush(_exp_sink* s) {
  _exp_write(s->job, s->buf, s->used);
  s->used = 0;
}

static void _exp_sink_raw(_exp_sink* s, const unsigned char* p, size_t n) {
  if (s->used + n > sizeof s->buf) _exp_sink_flush(s);
  memcpy(s->buf + s->used, p, n);
  s->used += n;
}

static void _exp_base64_group(_exp_sink* s, const unsigned char in[3], size_t n) {
  static const char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const uint32_t v = (uint32_t)in[0] << 16 | (uint32_t)(n > 1 ? in[1] : 0) << 8 | (n > 2 ? in[2] : 0);
  unsigned char out[4] = {(unsigned char)alphabet[v >> 18 & 63], (unsigned char)alphabet[v >> 12 & 63],
                          (unsigned char)(n > 1 ? alphabet[v >> 6 & 63] : '='),
                          (unsigned char)(n > 2 ? alphabet[v & 63] : '=')};
  _exp_sink_raw(s, out, 4);
}

static void _exp_sink_put(_exp_sink* s, const unsigned char* p, size_t n) {
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

static void _exp_sink_end(_exp_sink* s) {
  if (s->base64 && s->carried) _exp_base64_group(s, s->carry, s->carried);
  s->carried = 0;
  _exp_sink_flush(s);
}

static void _exp_sink_u32(_exp_sink* s, uint32_t v) {
  unsigned char b[4];
  _exp_put_u32(b, v);
  _exp_sink_put(s, b, 4);
}

/* ------------------------------------------------------------------------ */
/* OBJ                                                                      */
/* ------------------------------------------------------------------------ */

static void _exp_obj(_exp_job* job) {
  const tlod_export_mesh* m = job->mesh;
  _exp_printf(job, "# tesslod export: %u vertices, %u triangles\n", m->vertex_count, m->triangle_count);
  for (uint32_t i = 0; i < m->vertex_count; ++i) {
    const float* p = m->positions + 3 * (size_t)i;
    _exp_printf(job, "v %.9g %.9g %.9g\n", (double)p[0], (double)p[1], (double)p[2]);
  }
  for (uint32_t i = 0; m->normals && i < m->vertex_count; ++i) {
    const float* n = m->normals + 3 * (size_t)i;
    _exp_printf(job, "vn %.9g %.9g %.9g\n", (double)n[0], (double)n[1], (double)n[2]);
  }
  for (uint32_t t = 0; t < m->triangle_count; ++t) {
    const uint32_t* c = m->indices + 3 * (size_t)t;
    if (m->normals)
      _exp_printf(job, "f %u//%u %u//%u %u//%u\n", c[0] + 1, c[0] + 1, c[1] + 1, c[1] + 1, c[2] + 1, c[2] + 1);
    else
      _exp_printf(job, "f %u %u %u\n", c[0] + 1, c[1] + 1, c[2] + 1);
  }
}

/* ------------------------------------------------------------------------ */
/* PLY                                                                      */
/* ------------------------------------------------------------------------ */

static void _exp_ply(_exp_job* job, _exp_sink* s) {
  const tlod_export_mesh* m = job->mesh;
  _exp_printf(job,
              "ply\nformat binary_little_endian 1.0\ncomment tesslod export\nelement vertex %u\n"
              "property float x\nproperty float y\nproperty float z\n",
              m->vertex_count);
  if (m->normals) _exp_printf(job, "property float nx\nproperty float ny\nproperty float nz\n");
  _exp_printf(job, "element face %u\nproperty list uchar uint vertex_indices\nend_header\n", m->triangle_count);
  for (uint32_t i = 0; i < m->vertex_count; ++i) {
    for (int c = 0; c < 3; ++c)
      _exp_sink_u32(s, _exp_float_bits(m->positions[3 * (size_t)i + (size_t)c]));
    for (int c = 0; m->normals && c < 3; ++c)
      _exp_sink_u32(s, _exp_float_bits(m->normals[3 * (size_t)i + (size_t)c]));
  }
  for (uint32_t t = 0; t < m->triangle_count; ++t) {
    const unsigned char three = 3;
    _exp_sink_put(s, &three, 1);
    for (int c = 0; c < 3; ++c)
      _exp_sink_u32(s, m->indices[3 * (size_t)t + (size_t)c]);
  }
  _exp_sink_end(s);
}

/* ------------------------------------------------------------------------ */
/* glTF                                                                     */
/* ------------------------------------------------------------------------ */

/* Binary buffer layout: positions, normals (optional), indices; all 4-aligned. */
typedef struct _exp_layout {
  size_t positions, normals, indices, total;
} _exp_layout;

static _exp_layout _exp_gltf_layout(const tlod_export_mesh* m) {
  _exp_layout l;
  l.positions = (size_t)m->vertex_count * 12;
  l.normals = m->normals ? l.positions : 0;
  l.indices = (size_t)m->triangle_count * 12;
  l.total = l.positions + l.normals + l.indices;
  return l;
}

static void _exp_gltf_binary(_exp_sink* s, const tlod_export_mesh* m) {
  for (size_t i = 0; i < 3 * (size_t)m->vertex_count; ++i)
    _exp_sink_u32(s, _exp_float_bits(m->positions[i]));
  for (size_t i = 0; m->normals && i < 3 * (size_t)m->vertex_count; ++i)
    _exp_sink_u32(s, _exp_float_bits(m->normals[i]));
  for (size_t i = 0; i < 3 * (size_t)m->triangle_count; ++i)
    _exp_sink_u32(s, m->indices[i]);
}

/* A growable string for the JSON part (it holds no vertex data). */
typedef struct _exp_text {
  char* s;
  size_t len, cap;
  bool failed;
} _exp_text;

static void _exp_text_add(_exp_text* t, const char* fmt, ...) _TLOD_IMPORT_PRINTF(2, 3);
static void _exp_text_add(_exp_text* t, const char* fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int n = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  if (n < 0 || t->failed) {
    t->failed = true;
    return;
  }
  if (t->len + (size_t)n + 1 > t->cap) {
    size_t cap = (t->len + (size_t)n + 1) * 2;
    char* p = realloc(t->s, cap);
    if (!p) {
      t->failed = true;
      return;
    }
    t->s = p, t->cap = cap;
  }
  va_start(ap, fmt);
  vsnprintf(t->s + t->len, (size_t)n + 1, fmt, ap);
  va_end(ap);
  t->len += (size_t)n;
}

/* POSITION min and max are required by glTF; %.9g keeps them exact. */
static void _exp_bounds(const tlod_export_mesh* m, float lo[3], float hi[3]) {
  for (int c = 0; c < 3; ++c)
    lo[c] = hi[c] = m->positions[c];
  for (size_t i = 0; i < m->vertex_count; ++i)
    for (int c = 0; c < 3; ++c) {
      const float v = m->positions[3 * i + (size_t)c];
      lo[c] = v < lo[c] ? v : lo[c];
      hi[c] = v > hi[c] ? v : hi[c];
    }
}

static void _exp_gltf_views(_exp_text* t, const tlod_export_mesh* m, const _exp_layout* l) {
  _exp_text_add(t, "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":%zu,\"target\":34962}",
                l->positions);
  if (m->normals)
    _exp_text_add(t, ",{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"target\":34962}", l->positions,
                  l->normals);
  _exp_text_add(t, ",{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"target\":34963}],",
                l->positions + l->normals, l->indices);
}

static void _exp_gltf_accessors(_exp_text* t, const tlod_export_mesh* m) {
  float lo[3], hi[3];
  _exp_bounds(m, lo, hi);
  _exp_text_add(t,
                "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":%u,\"type\":\"VEC3\","
                "\"min\":[%.9g,%.9g,%.9g],\"max\":[%.9g,%.9g,%.9g]}",
                m->vertex_count, (double)lo[0], (double)lo[1], (double)lo[2], (double)hi[0], (double)hi[1],
                (double)hi[2]);
  if (m->normals)
    _exp_text_add(t, ",{\"bufferView\":1,\"componentType\":5126,\"count\":%u,\"type\":\"VEC3\"}", m->vertex_count);
  _exp_text_add(t, ",{\"bufferView\":%d,\"componentType\":5125,\"count\":%zu,\"type\":\"SCALAR\"}],",
                m->normals ? 2 : 1, 3 * (size_t)m->triangle_count);
}

/* Everything but the buffers array, which goes last so that the .gltf's
 * base64 data can be streamed after the text. */
static void _exp_gltf_json(_exp_text* t, const tlod_export_mesh* m, const _exp_layout* l) {
  _exp_text_add(t, "{\"asset\":{\"version\":\"2.0\",\"generator\":\"tesslod\"},\"scene\":0,"
                   "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],");
  if (m->normals)
    _exp_text_add(t, "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1},\"indices\":2,"
                     "\"mode\":4}]}],");
  else
    _exp_text_add(t, "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"mode\":4}]}],");
  _exp_gltf_views(t, m, l);
  _exp_gltf_accessors(t, m);
  _exp_text_add(t, "\"buffers\":[{\"byteLength\":%zu", l->total);
}

static tlod_result _exp_gltf(_exp_job* job, _exp_sink* s) {
  const _exp_layout l = _exp_gltf_layout(job->mesh);
  _exp_text t = {0};
  _exp_gltf_json(&t, job->mesh, &l);
  _exp_text_add(&t, ",\"uri\":\"data:application/octet-stream;base64,");
  if (t.failed) {
    free(t.s);
    return _exp_fail(job, TLOD_ERROR_OUT_OF_MEMORY, "out of memory");
  }
  _exp_write(job, t.s, t.len);
  free(t.s);
  s->base64 = true;
  _exp_gltf_binary(s, job->mesh);
  _exp_sink_end(s);
  _exp_printf(job, "\"}]}\n");
  return TLOD_SUCCESS;
}

static void _exp_glb_chunk_header(_exp_job* job, size_t length, uint32_t type) {
  unsigned char h[8];
  _exp_put_u32(h, (uint32_t)length);
  _exp_put_u32(h + 4, type);
  _exp_write(job, h, 8);
}

static tlod_result _exp_glb(_exp_job* job, _exp_sink* s) {
  const _exp_layout l = _exp_gltf_layout(job->mesh);
  _exp_text t = {0};
  _exp_gltf_json(&t, job->mesh, &l);
  _exp_text_add(&t, "}]}");
  while (!t.failed && t.len % 4)
    _exp_text_add(&t, " "); /* JSON chunk padding is spaces */
  if (t.failed) {
    free(t.s);
    return _exp_fail(job, TLOD_ERROR_OUT_OF_MEMORY, "out of memory");
  }
  const size_t total = 12 + 8 + t.len + 8 + l.total; /* l.total is a multiple of 4 */
  if (total > 0xFFFFFFFFu) {
    free(t.s);
    return _exp_fail(job, TLOD_ERROR_UNSUPPORTED, "%zu bytes do not fit a GLB (4 GiB limit)", total);
  }
  unsigned char header[12] = {'g', 'l', 'T', 'F'};
  _exp_put_u32(header + 4, 2);
  _exp_put_u32(header + 8, (uint32_t)total);
  _exp_write(job, header, 12);
  _exp_glb_chunk_header(job, t.len, 0x4E4F534Au);
  _exp_write(job, t.s, t.len);
  free(t.s);
  _exp_glb_chunk_header(job, l.total, 0x004E4942u);
  _exp_gltf_binary(s, job->mesh);
  _exp_sink_end(s);
  return TLOD_SUCCESS;
}

/* ------------------------------------------------------------------------ */
/* Entry point                                                              */
/* ------------------------------------------------------------------------ */

static tlod_result _exp_check_mesh(_exp_job* job) {
  const tlod_export_mesh* m = job->mesh;
  if (!m->positions || !m->indices || m->vertex_count == 0 || m->triangle_count == 0)
    return _exp_fail(job, TLOD_ERROR_INVALID_ARGUMENT, "mesh needs positions, indices, >= 1 vertex and >= 1 triangle");
  for (size_t i = 0; i < 3 * (size_t)m->vertex_count; ++i) {
    if (!isfinite(m->positions[i]))
      return _exp_fail(job, TLOD_ERROR_INVALID_ARGUMENT, "vertex %zu: position is not finite", i / 3);
    if (m->normals && !isfinite(m->normals[i]))
      return _exp_fail(job, TLOD_ERROR_INVALID_ARGUMENT, "vertex %zu: normal is not finite", i / 3);
  }
  for (size_t i = 0; i < 3 * (size_t)m->triangle_count; ++i)
    if (m->indices[i] >= m->vertex_count)
      return _exp_fail(job, TLOD_ERROR_INVALID_ARGUMENT, "triangle %zu: index %u out of range (%u vertices)", i / 3,
                       m->indices[i], m->vertex_count);
  return TLOD_SUCCESS;
}

typedef enum { _EXP_OBJ, _EXP_PLY, _EXP_GLTF, _EXP_GLB, _EXP_UNKNOWN } _exp_format;

static _exp_format _exp_format_of(const char* path) {
  if (_tlod_str_ends_with_nocase(path, ".obj")) return _EXP_OBJ;
  if (_tlod_str_ends_with_nocase(path, ".ply")) return _EXP_PLY;
  if (_tlod_str_ends_with_nocase(path, ".gltf")) return _EXP_GLTF;
  if (_tlod_str_ends_with_nocase(path, ".glb")) return _EXP_GLB;
  return _EXP_UNKNOWN;
}

static tlod_result _exp_write_format(_exp_job* job, _exp_format format) {
  _exp_sink* s = calloc(1, sizeof *s);
  if (!s) return _exp_fail(job, TLOD_ERROR_OUT_OF_MEMORY, "out of memory");
  s->job = job;
  tlod_result res = TLOD_SUCCESS;
  switch (format) {
  case _EXP_OBJ:
    _exp_obj(job);
    break;
  case _EXP_PLY:
    _exp_ply(job, s);
    break;
  case _EXP_GLTF:
    res = _exp_gltf(job, s);
    break;
  default:
    res = _exp_glb(job, s);
    break;
  }
  free(s);
  return res;
}

/* Writes through the atomic file writer: a unique temporary next to path,
 * renamed over path when complete. */
static tlod_result _exp_write_atomic(_exp_job* job, _exp_format format) {
  char err[512];
  tlod_atomic_file file;
  if (!tlod_atomic_file_begin(&file, job->path, err, sizeof err)) return _exp_fail(job, TLOD_ERROR_IO, "%s", err);
  job->file = file.file;
  tlod_result res = _exp_write_format(job, format);
  if (res == TLOD_SUCCESS && job->write_failed) snprintf(err, sizeof err, "cannot write '%s'", job->path);
  const bool kept = tlod_atomic_file_end(&file, res == TLOD_SUCCESS && !job->write_failed, err, sizeof err);
  job->file = NULL;
  if (res == TLOD_SUCCESS && !kept) res = _exp_fail(job, TLOD_ERROR_IO, "%s", err);
  return res;
}

tlod_result tlod_export_file(const char* path, const tlod_export_mesh* mesh, char* error, size_t error_size) {
  if (error && error_size) error[0] = 0;
  _exp_job job = {path, "(null)", mesh, error, error_size, NULL, false};
  if (path) {
    const char* slash = strrchr(path, '/');
    job.name = slash ? slash + 1 : path;
  }
  if (!path || !mesh) return _exp_fail(&job, TLOD_ERROR_INVALID_ARGUMENT, "path and mesh must not be NULL");
  const _exp_format format = _exp_format_of(path);
  if (format == _EXP_UNKNOWN)
    return _exp_fail(&job, TLOD_ERROR_UNSUPPORTED, "unknown file extension (expected .obj, .ply, .gltf or .glb)");
  tlod_result res = _exp_check_mesh(&job);
  if (res != TLOD_SUCCESS) return res;
  return _exp_write_atomic(&job, format);
}
