/* tlod bench -- a model set up for the suites, and the orbiting camera. */
#include <math.h>
#include <string.h>

#include "bench_lod.h"
#include "common/camera.h"

void bench_scene_free(bench_scene* s) {
  scene_setup_destroy(&s->setup);
  tlod_context_destroy(s->ctx);
}

int bench_scene_load(const char* in, uint32_t threads, tlod_surface_type type, uint32_t max_level, bench_scene* s) {
  memset(s, 0, sizeof(*s));
  if (tlod_context_create(&(tlod_context_desc){.thread_count = threads, .label = "bench"}, &s->ctx) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "cannot create a context");
  scene_setup_desc d = {.input = in, .surface = type, .pattern_level = max_level};
  int rc = scene_setup_create(s->ctx, &d, &s->setup);
  if (rc != CLI_OK) bench_scene_free(s);
  return rc;
}

void bench_orbit_view(const tlod_mesh* mesh, float angle, float distance_scale, uint32_t w, uint32_t h,
                      tlod_view_desc* v) {
  tlod_mesh_info info = tlod_mesh_query_info(mesh);
  float c[3], r = 0.0f;
  for (int i = 0; i < 3; i++) {
    c[i] = 0.5f * (info.bbox_min[i] + info.bbox_max[i]);
    r += 0.25f * (info.bbox_max[i] - info.bbox_min[i]) * (info.bbox_max[i] - info.bbox_min[i]);
  }
  r = sqrtf(r);
  float fovy = 45.0f, d = distance_scale * r / tanf(fovy * 3.14159265f / 360.0f);
  float eye[3] = {c[0] + d * sinf(angle), c[1] + 0.3f * d, c[2] + d * cosf(angle)}, up[3] = {0, 1, 0}, n, f;
  *v = (tlod_view_desc){.viewport_width = w, .viewport_height = h};
  camera_look_at(eye, c, up, v->view);
  camera_fit_planes(eye, info.bbox_min, info.bbox_max, &n, &f);
  camera_perspective(fovy, (float)w / (float)h, n, f, v->proj);
}

/* A camera just above the top of the torus tube (demo:torus-NxM: ring
 * radius 1, tube 0.35, axis z), looking along the ring and down a little,
 * at ring angle `angle`: the tube near the eye refines to the finest
 * levels, the part towards the horizon falls to level 0, the tube's
 * contours cross the view, and the ring behind the eye is culled. */
void bench_refine_view(float angle, uint32_t w, uint32_t h, tlod_view_desc* v) {
  const float ring = 1.0f, top = 0.35f, height = 0.03f;
  float eye[3] = {ring * cosf(angle), ring * sinf(angle), top + height};
  float ahead[3] = {eye[0] - 0.6f * sinf(angle), eye[1] + 0.6f * cosf(angle), top - 0.12f}, up[3] = {0, 0, 1};
  *v = (tlod_view_desc){.viewport_width = w, .viewport_height = h};
  camera_look_at(eye, ahead, up, v->view);
  camera_perspective(60.0f, (float)w / (float)h, 0.2f * height, 4.0f, v->proj);
}
