/* tlod bench --suite table1 -- the paper's Table 1 comparison (no
 * tessellation / adaptive / uniform at the worst patch's level) per policy,
 * with the strip overhead. */
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
    for (uint32_t f = 0; f < dl->patch_count; f++) {
      uint32_t l = tlod_level_for_error(dl->e_max[f], 0.5f, tlod_patterns_max_level(s.setup.patterns));
      if (dl->levels[f] >= 0 && l > worst) worst = l;
    }
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
