/* tlod tool -- shared command plumbing: parsing, loading, timing. */
#define _POSIX_C_SOURCE 200809L
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "demo_scene.h"
#include "demo_shapes.h"
#include "tlod_import.h"

int cli_error(int code, const char* fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  fputs("tlod: error: ", stderr);
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  va_end(ap);
  return code;
}

bool cli_parse_float(const char* option, const char* text, double lo, double hi, float* out) {
  char* end = NULL;
  errno = 0;
  double v = text ? strtod(text, &end) : 0.0;
  if (!text || end == text || *end || errno || !isfinite(v) || v < lo || v > hi) {
    cli_error(CLI_USAGE, "%s: expected a number in [%g, %g], got '%s'", option, lo, hi, text ? text : "");
    return false;
  }
  *out = (float)v;
  return true;
}

bool cli_parse_uint(const char* option, const char* text, uint32_t lo, uint32_t hi, uint32_t* out) {
  char* end = NULL;
  errno = 0;
  unsigned long v = text && *text != '-' ? strtoul(text, &end, 10) : 0;
  if (!text || *text == '-' || end == text || *end || errno || v < lo || v > hi) {
    cli_error(CLI_USAGE, "%s: expected a whole number in [%u, %u], got '%s'", option, lo, hi, text ? text : "");
    return false;
  }
  *out = (uint32_t)v;
  return true;
}

int cli_parse_enum(const char* option, const char* text, const char* const* names) {
  for (int i = 0; text && names[i]; i++) {
    if (!strcmp(text, names[i])) return i;
  }
  char list[256] = "";
  for (int i = 0; names[i]; i++) {
    strncat(list, i ? "|" : "", sizeof(list) - strlen(list) - 1);
    strncat(list, names[i], sizeof(list) - strlen(list) - 1);
  }
  cli_error(CLI_USAGE, "%s: expected %s, got '%s'", option, list, text ? text : "");
  return -1;
}

const char* cli_value(int argc, char** argv, int* i) {
  if (*i + 1 >= argc) {
    cli_error(CLI_USAGE, "%s needs a value", argv[*i]);
    return NULL;
  }
  return argv[++*i];
}

double cli_now_ms(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

void cli_mesh_free(cli_mesh* m) {
  free(m->positions);
  free(m->normals);
  free(m->indices);
  free(m->face_sizes);
  free(m->face_source);
  memset(m, 0, sizeof(*m));
}

static void* dup_array(const void* src, size_t bytes) {
  void* p = malloc(bytes ? bytes : 1);
  if (p && bytes) memcpy(p, src, bytes);
  return p;
}

static int from_shape(demo_shape* s, cli_mesh* m) {
  m->vertex_count = s->vertex_count;
  m->positions = s->positions;
  m->normals = s->normals;
  m->indices = s->indices;
  m->index_count = s->quad_count * 4;
  m->face_count = s->quad_count;
  m->face_sizes = malloc(s->quad_count ? s->quad_count : 1);
  memset(s, 0, sizeof(*s));
  if (!m->face_sizes) return cli_error(CLI_FAILED, "out of memory");
  memset(m->face_sizes, 4, m->face_count);
  return CLI_OK;
}

const char* cli_demo_names(void) { return "demo:cow, demo:cylinder, demo:torus, demo:torus-NxM"; }

static int load_demo(const char* name, cli_mesh* m) {
  demo_shape s = {0};
  uint32_t rings = 0, segs = 0;
  if (!strcmp(name, "cow")) {
    const tlod_demo_mesh* d = &tlod_demo_cow;
    m->vertex_count = d->vertex_count;
    m->index_count = d->index_count;
    m->face_count = d->face_count;
    m->positions = dup_array(d->positions, sizeof(float) * 3 * d->vertex_count);
    m->indices = dup_array(d->indices, sizeof(uint32_t) * d->index_count);
    m->face_sizes = dup_array(d->face_sizes, d->face_count);
    if (!m->positions || !m->indices || !m->face_sizes) return cli_error(CLI_FAILED, "out of memory");
    return CLI_OK;
  }
  if (!strcmp(name, "cylinder")) {
    if (!demo_cylinder(32, &s)) return cli_error(CLI_FAILED, "out of memory");
    return from_shape(&s, m);
  }
  char tail;
  if (!strcmp(name, "torus")) {
    rings = 48, segs = 24;
  } else if (sscanf(name, "torus-%ux%u%c", &rings, &segs, &tail) != 2 || rings < 3 || segs < 3 ||
             (uint64_t)rings * segs > 50000000u) {
    return cli_error(CLI_FAILED, "unknown demo mesh 'demo:%s' (built-in: %s; torus-NxM with N, M >= 3)", name,
                     cli_demo_names());
  }
  if (!demo_torus(rings, segs, &s)) return cli_error(CLI_FAILED, "out of memory");
  return from_shape(&s, m);
}

static int load_file(const char* path, cli_mesh* m) {
  char err[512];
  tlod_import_result* r = NULL;
  if (tlod_import_file(path, NULL, &r, err, sizeof(err)) != TLOD_SUCCESS) return cli_error(CLI_FAILED, "%s", err);
  /* The importer allocated with malloc (NULL allocator): take the arrays over. */
  m->vertex_count = r->vertex_count;
  m->positions = r->positions;
  m->normals = r->normals;
  m->index_count = r->index_count;
  m->indices = r->indices;
  m->face_count = r->face_count;
  m->face_sizes = r->face_sizes;
  snprintf(m->warnings, sizeof(m->warnings), "%s", r->warnings);
  r->positions = r->normals = NULL;
  r->indices = NULL;
  r->face_sizes = NULL;
  tlod_import_free(r);
  return CLI_OK;
}

int cli_load(const char* in, cli_mesh* out) {
  memset(out, 0, sizeof(*out));
  snprintf(out->name, sizeof(out->name), "%s", in);
  int rc = !strncmp(in, "demo:", 5) ? load_demo(in + 5, out) : load_file(in, out);
  if (rc != CLI_OK) cli_mesh_free(out);
  out->source_face_count = out->face_sizes ? out->face_count : out->index_count / 3;
  return rc;
}

int cli_split_quads(cli_mesh* m) {
  if (!m->face_sizes) return CLI_OK;
  uint32_t quads = 0;
  for (uint32_t f = 0; f < m->face_count; f++)
    quads += m->face_sizes[f] == 4;
  uint32_t* idx = malloc(sizeof(uint32_t) * ((size_t)m->index_count + 2u * quads + 1));
  uint32_t* source = malloc(sizeof(uint32_t) * ((size_t)m->face_count + quads + 1));
  if (!idx || !source) {
    free(idx);
    free(source);
    return cli_error(CLI_FAILED, "out of memory");
  }
  uint32_t src = 0, dst = 0;
  for (uint32_t f = 0; f < m->face_count; f++) {
    const uint32_t* q = m->indices + src;
    source[dst / 3] = f;
    if (m->face_sizes[f] == 4) {
      uint32_t tris[6] = {q[0], q[1], q[2], q[0], q[2], q[3]};
      memcpy(idx + dst, tris, sizeof(tris));
      source[dst / 3 + 1] = f;
      dst += 6;
    } else {
      memcpy(idx + dst, q, sizeof(uint32_t) * 3);
      dst += 3;
    }
    src += m->face_sizes[f];
  }
  m->face_source = source;
  free(m->indices);
  free(m->face_sizes);
  m->indices = idx;
  m->index_count = dst;
  m->face_count = dst / 3;
  m->face_sizes = NULL;
  m->quads_split = quads;
  return CLI_OK;
}

int cli_create_mesh(tlod_context* ctx, const cli_mesh* m, tlod_normal_mode normals, float crease_deg, tlod_mesh** out) {
  tlod_mesh_desc desc = {
      .positions = m->positions,
      .normals = m->normals,
      .vertex_count = m->vertex_count,
      .indices = m->indices,
      .index_count = m->index_count,
      .face_type = m->face_sizes ? TLOD_FACE_MIXED : TLOD_FACE_TRIANGLES,
      .face_sizes = m->face_sizes,
      .face_count = m->face_sizes ? m->face_count : 0,
      .normal_mode = normals,
      .crease_angle_deg = crease_deg,
      .label = m->name,
  };
  if (tlod_mesh_create(ctx, &desc, out) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s", tlod_context_last_error(ctx));
  return CLI_OK;
}

void cli_print_findings(FILE* f, const tlod_mesh* mesh, uint32_t limit) {
  tlod_mesh_info info = tlod_mesh_query_info(mesh);
  uint32_t shown = info.finding_count < limit ? info.finding_count : limit;
  for (uint32_t i = 0; i < shown; i++) {
    tlod_finding fd = tlod_mesh_query_finding(mesh, i);
    fprintf(f, "  finding: %s\n", fd.message);
  }
  uint32_t more = info.finding_count - shown + info.findings_dropped;
  if (more) fprintf(f, "  ... and %u more findings (tlod info --findings N shows more)\n", more);
}
