/* tlod bench --suite table1 -- the paper's Table 1 comparison (no
 * tessellation / adaptive / uniform at the worst patch's level) per policy,
 * with the strip overhead; the level rule of the per-level error tables
 * against the previous rule (error_bound 4^-l at the nearest depth, computed
 * here), and the surface build time per 100k patches. */
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "bench_lod.h"
#include "tool_names.h"

/* Uniform tessellation at the finest level any visible patch needs. */
static uint64_t uniform_triangles(const bench_scene* s, const tlod_draw_list* dl, uint32_t level) {
  uint64_t tris = 0;
  for (uint32_t f = 0; f < dl->patch_count; f++) {
    uint32_t corners[4];
    if (dl->levels[f] < 0) continue;
    bool quad = tlod_mesh_face_corners(s->setup.mesh, f, corners) == 4;
    tris += tlod_pattern_triangle_count(quad ? TLOD_PATTERN_QUAD : TLOD_PATTERN_TRIANGLE, level);
  }
  return tris;
}

/* Patches the contour crosses: corner normals facing both ways. */
static bool on_contour(const tlod_mesh* mesh, uint32_t f, const float view[16]) {
  float eye[3];
  for (int i = 0; i < 3; i++)
    eye[i] = -(view[i * 4 + 0] * view[12] + view[i * 4 + 1] * view[13] + view[i * 4 + 2] * view[14]);
  uint32_t corners[4], n = tlod_mesh_face_corners(mesh, f, corners);
  bool front = false, back = false;
  for (uint32_t c = 0; c < n; c++) {
    float p[3], nrm[3];
    tlod_mesh_vertex(mesh, corners[c], p, nrm);
    float d = nrm[0] * (eye[0] - p[0]) + nrm[1] * (eye[1] - p[1]) + nrm[2] * (eye[2] - p[2]);
    front = front || d > 0.0f;
    back = back || d <= 0.0f;
  }
  return front && back;
}

/* The previous rule (before the per-level tables): e = error_bound * f / z,
 * z the sphere's nearest view depth clamped at the near plane (no off-axis
 * factor), level = the smallest l with 4^-l e <= eps (tlod_level_for_error). */
static uint32_t previous_level(const tlod_view_desc* v, const tlod_patch_info* in, float eps, uint32_t max_level) {
  const float *V = v->view, *P = v->proj;
  float scale;
  if (P[15] == 1.0f && P[11] == 0.0f) {
    scale = tlod_projection_scale(P, v->viewport_height, 1.0f);
  } else {
    float z = -(V[2] * in->center[0] + V[6] * in->center[1] + V[10] * in->center[2] + V[14]) - in->radius;
    float denom = P[10] - 1.0f, n = denom != 0.0f ? P[14] / denom : 0.0f;
    float zmin = n > 0.0f ? n : 1e-4f * in->radius;
    scale = tlod_projection_scale(P, v->viewport_height, z > zmin ? z : zmin);
  }
  return tlod_level_for_error(in->error_bound * scale, eps, max_level);
}

/* Pattern and strip triangles of the visible patches (levels[f] >= 0) at the
 * given levels, strips as the scheduler draws them without morphs: across
 * every edge between visible patches whose levels differ or that is a crease. */
static void count_frame(const bench_scene* s, const int8_t* levels, uint64_t* pattern, uint64_t* strips) {
  tlod_mesh_view m = tlod_mesh_query_view(s->setup.mesh);
  *pattern = *strips = 0;
  for (uint32_t f = 0; f < m.face_count; f++) {
    if (levels[f] < 0) continue;
    tlod_pattern_shape sh = m.face_corners[f] == 4 ? TLOD_PATTERN_QUAD : TLOD_PATTERN_TRIANGLE;
    *pattern += tlod_pattern_triangle_count(sh, (uint32_t)levels[f]);
    for (uint32_t e = 0; e < m.face_corners[f]; e++) {
      tlod_edge_link link = m.links[f][e];
      if (link.face == UINT32_MAX || link.face < f || levels[link.face] < 0) continue;
      if (link.smooth && levels[f] == levels[link.face]) continue;
      uint32_t n = 0;
      tlod_patterns_connection(s->setup.patterns, (uint32_t)levels[f], (uint32_t)levels[link.face], &n);
      *strips += n;
    }
  }
}

/* Best of 5 surface builds (the model's surface desc), ms per 100k patches. */
static double surface_build_ms_per_100k(const bench_scene* s) {
  tlod_surface_desc d = tlod_surface_query_desc(s->setup.surface);
  double best = INFINITY;
  for (int r = 0; r < 5; r++) {
    tlod_surface* surf = NULL;
    double t0 = cli_now_ms();
    if (tlod_surface_create(s->ctx, s->setup.mesh, &d, &surf) != TLOD_SUCCESS) return NAN;
    double t = cli_now_ms() - t0;
    tlod_surface_destroy(surf);
    best = t < best ? t : best;
  }
  return best * 1e5 / (double)tlod_surface_patch_count(s->setup.surface);
}

/* The previous rule against the tables' at the ERROR policy's visible set,
 * and uniform tessellation at the finest level the tables' rule needs. */
static int rule_comparison(const char* in, const bench_scene* s, const tlod_view_desc* view, const tlod_draw_list* dl,
                           uint32_t worst, FILE* csv) {
  uint32_t patches = dl->patch_count, lmax = tlod_patterns_max_level(s->setup.patterns), worst_prev = 0;
  int8_t* prev = malloc(patches + 1u);
  if (!prev) return cli_error(CLI_FAILED, "out of memory");
  for (uint32_t f = 0; f < patches; f++) {
    prev[f] = -1;
    if (dl->levels[f] < 0) continue;
    tlod_patch_info info = tlod_surface_patch(s->setup.surface, f);
    prev[f] = (int8_t)previous_level(view, &info, 0.5f, lmax);
    worst_prev = (uint32_t)prev[f] > worst_prev ? (uint32_t)prev[f] : worst_prev;
  }
  uint64_t prev_pat, prev_strip, uni_pat, uni_strip;
  count_frame(s, prev, &prev_pat, &prev_strip);
  for (uint32_t f = 0; f < patches; f++)
    prev[f] = dl->levels[f] < 0 ? -1 : (int8_t)worst;
  count_frame(s, prev, &uni_pat, &uni_strip);
  free(prev);
  double build = surface_build_ms_per_100k(s);
  printf("table1rule %-24s tables: pattern %8llu strips %7llu | previous rule (error_bound 4^-l): pattern %8llu strips "
         "%7llu (worst L%u) | pattern ratio %5.2fx, total %5.2fx | uniform L%u: pattern %9llu strips %6llu | surface "
         "build %.1f ms per 100k patches\n",
         in, (unsigned long long)dl->pattern_triangles, (unsigned long long)dl->strip_triangles,
         (unsigned long long)prev_pat, (unsigned long long)prev_strip, worst_prev,
         (double)prev_pat / (double)dl->pattern_triangles,
         (double)(prev_pat + prev_strip) / (double)(dl->pattern_triangles + dl->strip_triangles), worst,
         (unsigned long long)uni_pat, (unsigned long long)uni_strip, build);
  if (csv)
    fprintf(csv, "table1rule,%s,%llu,%llu,%llu,%llu,%u,%llu,%llu,%.3f\n", in, (unsigned long long)dl->pattern_triangles,
            (unsigned long long)dl->strip_triangles, (unsigned long long)prev_pat, (unsigned long long)prev_strip,
            worst, (unsigned long long)uni_pat, (unsigned long long)uni_strip, build);
  return CLI_OK;
}

static int table1_case(const char* in, double distance, FILE* csv) {
  bench_scene s;
  int rc = bench_scene_load(in, 0, TLOD_SURFACE_PN, 8, &s);
  if (rc != CLI_OK) return rc;
  tlod_view_desc view;
  bench_orbit_view(s.setup.mesh, 0.6f, (float)distance, 1600, 1144, &view);
  uint32_t worst = 0, patches = tlod_surface_patch_count(s.setup.surface);
  int8_t* error_levels = calloc(patches + 1u, 1);
  if (!error_levels) {
    bench_scene_free(&s);
    return cli_error(CLI_FAILED, "out of memory");
  }
  for (int p = TLOD_POLICY_ERROR; p <= TLOD_POLICY_HYBRID && rc == CLI_OK; p++) {
    tlod_scheduler* sch = NULL;
    /* The silhouette policy refines contours to its max level whatever the
     * error: cap it at the level the error rule needs, as uniform is. */
    tlod_scheduler_desc d = {.epsilon_px = 0.5f,
                             .policy = (tlod_lod_policy)p,
                             .morph = TLOD_MORPH_NONE,
                             .max_level = p == TLOD_POLICY_SILHOUETTE && worst ? worst : 0};
    if (tlod_scheduler_create(s.ctx, s.setup.surface, s.setup.patterns, &d, &sch) != TLOD_SUCCESS ||
        tlod_scheduler_update(sch, &(tlod_frame_desc){.views = &view, .view_count = 1}) != TLOD_SUCCESS) {
      rc = cli_error(CLI_FAILED, "%s", tlod_context_last_error(s.ctx));
      tlod_scheduler_destroy(sch);
      break;
    }
    const tlod_draw_list* dl = tlod_scheduler_draw_list(sch, 0);
    uint32_t visible = dl->patch_count - dl->culled;
    /* The uniform comparison uses the error rule's level for the worst patch. */
    if (p == TLOD_POLICY_ERROR)
      for (uint32_t f = 0; f < dl->patch_count; f++)
        if (dl->levels[f] >= 0 && (uint32_t)dl->levels[f] > worst) worst = (uint32_t)dl->levels[f];
    if (p == TLOD_POLICY_ERROR) rc = rule_comparison(in, &s, &view, dl, worst, csv);
    uint64_t adaptive = dl->pattern_triangles + dl->strip_triangles, uniform = uniform_triangles(&s, dl, worst);
    /* At contours the silhouette error must stay the error policy's. */
    uint32_t contour = 0, coarser = 0;
    for (uint32_t f = 0; f < patches; f++) {
      if (p == TLOD_POLICY_ERROR) error_levels[f] = dl->levels[f];
      if (dl->levels[f] < 0 || !on_contour(s.setup.mesh, f, view.view)) continue;
      contour++;
      coarser += dl->levels[f] < error_levels[f];
    }
    printf("table1     %-24s %-10s base %6u  adaptive %8llu (strips %5.1f%%)  uniform L%u %9llu  uniform/adaptive "
           "%5.2fx  contour patches %u, coarser than error policy %u\n",
           in, tool_policy_name((tlod_lod_policy)p), visible, (unsigned long long)adaptive,
           100.0 * (double)dl->strip_triangles / adaptive, worst, (unsigned long long)uniform,
           (double)uniform / (double)adaptive, contour, coarser);
    if (csv)
      fprintf(csv, "table1,%s,%s,%u,%llu,%llu,%u,%llu\n", in, tool_policy_name((tlod_lod_policy)p), visible,
              (unsigned long long)adaptive, (unsigned long long)dl->strip_triangles, worst,
              (unsigned long long)uniform);
    tlod_scheduler_destroy(sch);
  }
  free(error_levels);
  bench_scene_free(&s);
  return rc;
}

int bench_table1(const bench_lod_options* o, FILE* csv) {
  int rc = CLI_OK;
  for (uint32_t i = 0; i < o->input_count && rc == CLI_OK; i++)
    rc = table1_case(o->inputs[i], 1.0, csv);
  return rc;
}
