/* sample_scene.c -- the samples' shared mesh, material, camera and tesslod objects. */
#include "sample_scene.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char* const sample_checker_hook =
    "vec4 tlod_shade(tlod_fragment f) {\n"
    "  vec2 cell = floor(f.attributes[0].xy * vec2(8.0, 4.0));\n"
    "  vec3 base = mod(cell.x + cell.y, 2.0) < 0.5 ? vec3(0.95, 0.7, 0.1) : vec3(0.1, 0.4, 0.95);\n"
    "  float lit = 0.25 + 0.75 * max(dot(f.normal, f.light_dir), 0.0);\n"
    "  float rim = pow(1.0 - max(dot(f.normal, normalize(f.eye - f.position)), 0.0), 4.0);\n"
    "  return vec4(base * lit + vec3(0.6 * rim), 1.0);\n"
    "}\n";

static void sphere_vertices(sample_mesh* m, uint32_t nlat, uint32_t nlon) {
  const double pi = 3.14159265358979323846;
  for (uint32_t i = 0; i <= nlat; ++i)
    for (uint32_t j = 0; j <= nlon; ++j) {
      double th = pi * i / nlat, ph = 2 * pi * (j % nlon) / nlon;
      bool pole = i == 0 || i == nlat;
      uint32_t v = i * (nlon + 1) + j;
      m->positions[3 * v] = pole ? 0.0f : (float)(sin(th) * cos(ph));
      m->positions[3 * v + 1] = pole ? 0.0f : (float)(sin(th) * sin(ph));
      m->positions[3 * v + 2] = (float)cos(th);
      m->uvs[2 * v] = (float)j / (float)nlon;
      m->uvs[2 * v + 1] = (float)i / (float)nlat;
    }
}

bool sample_sphere_make(sample_mesh* m, uint32_t nlat, uint32_t nlon) {
  memset(m, 0, sizeof *m);
  m->vertex_count = (nlat + 1) * (nlon + 1);
  m->index_count = 6 * nlon * (nlat - 1);
  m->positions = malloc(sizeof(float) * 3 * m->vertex_count);
  m->uvs = malloc(sizeof(float) * 2 * m->vertex_count);
  m->indices = malloc(sizeof(uint32_t) * m->index_count);
  if (!m->positions || !m->uvs || !m->indices) return false;
  sphere_vertices(m, nlat, nlon);
  uint32_t* ix = m->indices;
  for (uint32_t i = 0; i < nlat; ++i)
    for (uint32_t j = 0; j < nlon; ++j) {
      uint32_t a = i * (nlon + 1) + j, b = a + 1, c = a + nlon + 1, d = c + 1;
      if (i != 0) *ix++ = a, *ix++ = c, *ix++ = b; /* no triangle collapsed on a pole */
      if (i != nlat - 1) *ix++ = b, *ix++ = c, *ix++ = d;
    }
  return true;
}

void sample_mesh_free(sample_mesh* m) {
  free(m->positions);
  free(m->uvs);
  free(m->indices);
  memset(m, 0, sizeof *m);
}

static void normalize3(float v[3]) {
  float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  v[0] /= l, v[1] /= l, v[2] /= l;
}

static void cross3(const float a[3], const float b[3], float out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

/* gluLookAt towards the origin with z up. */
static void look_at_origin(const float eye[3], float m[16]) {
  float f[3] = {-eye[0], -eye[1], -eye[2]}, up[3] = {0, 0, 1}, s[3], u[3];
  normalize3(f);
  cross3(f, up, s);
  normalize3(s);
  cross3(s, f, u);
  memset(m, 0, 16 * sizeof *m);
  for (int k = 0; k < 3; ++k)
    m[4 * k] = s[k], m[4 * k + 1] = u[k], m[4 * k + 2] = -f[k];
  m[12] = -(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]);
  m[13] = -(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]);
  m[14] = f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2];
  m[15] = 1;
}

tlod_view_desc sample_orbit_camera(float angle, float distance, float height, uint32_t width, uint32_t height_px) {
  tlod_view_desc v = {.viewport_width = width, .viewport_height = height_px};
  look_at_origin((float[3]){distance * cosf(angle), distance * sinf(angle), height}, v.view);
  float F = 1.0f / tanf(0.3926991f), n = 0.1f, fa = 50.0f; /* gluPerspective, fovy 45 degrees */
  v.proj[0] = F * (float)height_px / (float)width, v.proj[5] = F;
  v.proj[10] = (fa + n) / (n - fa), v.proj[11] = -1, v.proj[14] = 2 * fa * n / (n - fa);
  return v;
}

bool sample_check(tlod_result r, const sample_scene* s, const char* call, const char* who) {
  if (r == TLOD_SUCCESS) return true;
  fprintf(stderr, "%s: %s: %s: %s\n", who, call, tlod_result_string(r), s->ctx ? tlod_context_last_error(s->ctx) : "");
  return false;
}

tlod_mesh_desc sample_mesh_desc(const sample_mesh* m, tlod_attribute_desc* uv) {
  *uv = (tlod_attribute_desc){.data = m->uvs, .components = 2, .name = "TEXCOORD_0"};
  return (tlod_mesh_desc){.positions = m->positions,
                          .vertex_count = m->vertex_count,
                          .indices = m->indices,
                          .index_count = m->index_count,
                          .normal_mode = TLOD_NORMALS_ANGLE,
                          .label = "sphere",
                          .attributes = uv,
                          .attribute_count = 1};
}

/* PN needs triangles: a mesh with quads becomes a Phong surface. */
static bool make_surface(sample_scene* s, const tlod_mesh_desc* md, const char* who) {
  bool quads = md->face_type == TLOD_FACE_QUADS || md->face_type == TLOD_FACE_MIXED;
  tlod_surface_desc sd = {.type = quads ? TLOD_SURFACE_PHONG : TLOD_SURFACE_PN, .label = md->label};
  return sample_check(tlod_mesh_create(s->ctx, md, &s->mesh), s, "tlod_mesh_create", who) &&
         sample_check(tlod_surface_create(s->ctx, s->mesh, &sd, &s->surface), s, "tlod_surface_create", who) &&
         sample_check(tlod_device_create_surface(s->dev, s->surface, &s->dsurf), s, "tlod_device_create_surface", who);
}

bool sample_scene_init(sample_scene* s, const tlod_mesh_desc* md, tlod_device_desc device, const char* who) {
  memset(s, 0, sizeof *s);
  tlod_scheduler_desc sd = {.epsilon_px = 1.0f};
  if (!sample_check(tlod_context_create(NULL, &s->ctx), s, "tlod_context_create", who) ||
      !sample_check(tlod_patterns_create(s->ctx, &(tlod_patterns_desc){.max_level = 5}, &s->patterns), s,
                    "tlod_patterns_create", who))
    return false;
  device.patterns = s->patterns;
  return sample_check(tlod_device_create(s->ctx, &device, &s->dev), s, "tlod_device_create", who) &&
         make_surface(s, md, who) &&
         sample_check(tlod_scheduler_create(s->ctx, s->surface, s->patterns, &sd, &s->scheduler), s,
                      "tlod_scheduler_create", who);
}

/* Every destroy takes NULL, so a half-made scene frees what it has. */
void sample_scene_free(sample_scene* s) {
  tlod_scheduler_destroy(s->scheduler);
  tlod_device_destroy_surface(s->dev, s->dsurf);
  tlod_surface_destroy(s->surface);
  tlod_mesh_destroy(s->mesh);
  tlod_device_destroy(s->dev);
  tlod_patterns_destroy(s->patterns);
  tlod_context_destroy(s->ctx);
  memset(s, 0, sizeof *s);
}

bool sample_scene_plan(sample_scene* s, const tlod_view_desc* v, float dt_ms, tlod_draw_item* item,
                       tlod_draw_desc* draw, const char* who) {
  tlod_frame_desc fd = {.views = v, .view_count = 1, .dt_ms = dt_ms};
  if (!sample_check(tlod_scheduler_update(s->scheduler, &fd), s, "tlod_scheduler_update", who)) return false;
  *item = (tlod_draw_item){.surface = s->dsurf, .draw_list = tlod_scheduler_draw_list(s->scheduler, 0)};
  *draw = (tlod_draw_desc){.items = item, .item_count = 1, .viewport = {0, 0, v->viewport_width, v->viewport_height}};
  memcpy(draw->view, v->view, sizeof draw->view);
  memcpy(draw->proj, v->proj, sizeof draw->proj);
  return true;
}

bool sample_parse_int(const char* who, const char* flag, const char* text, int lo, int hi, int* out) {
  char* end = NULL;
  errno = 0;
  long v = strtol(text, &end, 10);
  if (errno || end == text || *end || v < lo || v > hi) {
    fprintf(stderr, "%s: %s '%s': expected a whole number in %d..%d\n", who, flag, text, lo, hi);
    return false;
  }
  *out = (int)v;
  return true;
}
