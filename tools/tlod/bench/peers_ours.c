/* tlod bench --peers -- tesslod's side: a one-thread context whose allocator
 * counts the bytes in use (the preprocessing's peak memory), Phong surfaces,
 * uniform evaluation into one reused output. */
#include <malloc.h>
#include <math.h>
#include <stdlib.h>

#include "peers.h"

static void* count_alloc(size_t size, void* user) {
  peers_ours* s = user;
  void* p = malloc(size);
  if (p) s->heap_now += malloc_usable_size(p);
  if (s->heap_now > s->heap_peak) s->heap_peak = s->heap_now;
  return p;
}

static void count_free(void* p, void* user) {
  peers_ours* s = user;
  if (p) s->heap_now -= malloc_usable_size(p);
  free(p);
}

static bool make_mesh(peers_ours* s, const peers_mesh* m) {
  tlod_mesh_desc d = {.positions = m->positions,
                      .vertex_count = m->vertex_count,
                      .indices = m->indices,
                      .index_count = m->index_count,
                      .face_type = TLOD_FACE_MIXED,
                      .face_sizes = m->face_sizes,
                      .face_count = m->face_count,
                      .normal_mode = TLOD_NORMALS_ANGLE,
                      .label = m->kind};
  return tlod_mesh_create(s->ctx, &d, &s->mesh) == TLOD_SUCCESS;
}

bool peers_ours_create(peers_ours* s, const peers_mesh* m, uint32_t level, tlod_error_tables tables, double* ms,
                       uint64_t* peak) {
  *s = (peers_ours){0};
  tlod_context_desc cd = {.allocator = {count_alloc, count_free, s}, .thread_count = 1, .label = "bench peers"};
  if (tlod_context_create(&cd, &s->ctx) != TLOD_SUCCESS) return false;
  uint64_t before = s->heap_peak = s->heap_now;
  double t0 = peers_thread_ms();
  bool ok =
      make_mesh(s, m) &&
      tlod_surface_create(s->ctx, s->mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_PHONG, .error_tables = tables},
                          &s->surface) == TLOD_SUCCESS &&
      tlod_patterns_create(s->ctx, &(tlod_patterns_desc){.max_level = level}, &s->patterns) == TLOD_SUCCESS;
  *ms = peers_thread_ms() - t0;
  *peak = s->heap_peak - before;
  return ok;
}

uint64_t peers_ours_evaluate(peers_ours* s, const float* control, uint32_t level, bool normals) {
  if (control && (tlod_mesh_update(s->mesh, control, 0, NULL, 0) != TLOD_SUCCESS ||
                  tlod_surface_refresh(s->surface, NULL) != TLOD_SUCCESS))
    return 0;
  tlod_cpu_tessellate_desc d = {.level = level, .no_normals = !normals};
  tlod_result r = s->out ? tlod_cpu_tessellate_into(s->ctx, s->surface, s->patterns, &d, s->out)
                         : tlod_cpu_tessellate(s->ctx, s->surface, s->patterns, &d, &s->out);
  return r == TLOD_SUCCESS ? s->out->vertex_count : 0;
}

double peers_ours_vertex_distance(const peers_ours* s) {
  static const float tri[3][2] = {{1, 0}, {0, 1}, {0, 0}}, quad[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  tlod_mesh_view v = tlod_mesh_query_view(s->mesh);
  double worst = 0.0;
  for (uint32_t f = 0; f < v.face_count; f++) {
    for (uint32_t c = 0; c < v.face_corners[f]; c++) {
      const float* uv = v.face_corners[f] == 3 ? tri[c] : quad[c];
      tlod_surface_point p;
      if (tlod_surface_eval(s->surface, f, uv[0], uv[1], &p) != TLOD_SUCCESS) return INFINITY;
      const float* q = v.positions[v.faces[f][c]];
      double dx = (double)p.position[0] - q[0], dy = (double)p.position[1] - q[1], dz = (double)p.position[2] - q[2];
      double d = sqrt(dx * dx + dy * dy + dz * dz);
      worst = d > worst ? d : worst;
    }
  }
  return worst;
}

void peers_ours_destroy(peers_ours* s) {
  if (s->out) tlod_cpu_mesh_destroy(s->ctx, s->out);
  tlod_patterns_destroy(s->patterns);
  tlod_surface_destroy(s->surface);
  tlod_mesh_destroy(s->mesh);
  tlod_context_destroy(s->ctx);
  *s = (peers_ours){0};
}
