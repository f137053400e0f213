/* tlod bench -- the scheduler suites: time per frame against patch count and
 * threads (with the memory-bandwidth bound of the bytes a frame touches), and
 * the paper's Table 1 comparison (no tessellation / adaptive / uniform at the
 * worst patch's level) per policy, with the strip overhead. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_lod.h"
#include "camera.h"

void bench_scene_free(bench_scene* s) {
  tlod_patterns_destroy(s->patterns);
  tlod_surface_destroy(s->surface);
  tlod_mesh_destroy(s->mesh);
  tlod_context_destroy(s->ctx);
  cli_mesh_free(&s->in);
}

int bench_scene_load(const char* in, uint32_t threads, tlod_surface_type type, uint32_t max_level, bench_scene* s) {
  memset(s, 0, sizeof(*s));
  if (tlod_context_create(&(tlod_context_desc){.thread_count = threads, .label = "bench"}, &s->ctx) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "cannot create a context");
  int rc = cli_load(in, &s->in);
  if (rc == CLI_OK && type == TLOD_SURFACE_PN) rc = cli_split_quads(&s->in);
  if (rc == CLI_OK) rc = cli_create_mesh(s->ctx, &s->in, TLOD_NORMALS_KEEP, 0.0f, &s->mesh);
  if (rc == CLI_OK &&
      (tlod_surface_create(s->ctx, s->mesh, &(tlod_surface_desc){.type = type}, &s->surface) != TLOD_SUCCESS ||
       tlod_patterns_create(s->ctx, &(tlod_patterns_desc){.max_level = max_level}, &s->patterns) != TLOD_SUCCESS))
    rc = cli_error(CLI_FAILED, "%s", tlod_context_last_error(s->ctx));
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

/* Bytes a frame must touch at least: per vertex position and normal read,
 * depth written; per patch its data read (sphere, bound, corner ids, corner
 * depths) and its state written (level, e_max, contour, target, level,
 * visibility, instance). */
static double frame_bytes(uint32_t vertices, uint32_t patches) {
  return (double)vertices * (24.0 + 4.0) +
         (double)patches * ((20.0 + 4.0 + 16.0 + 12.0) + (1 + 4 + 4 + 4 + 4 + 1 + 36));
}

static int scheduler_case(const char* in, uint32_t threads, uint32_t frames, double bandwidth, FILE* csv) {
  bench_scene s;
  int rc = bench_scene_load(in, threads, TLOD_SURFACE_PHONG, 6, &s);
  if (rc != CLI_OK) return rc;
  tlod_scheduler* sch = NULL;
  if (tlod_scheduler_create(s.ctx, s.surface, s.patterns, &(tlod_scheduler_desc){0}, &sch) != TLOD_SUCCESS) {
    bench_scene_free(&s);
    return cli_error(CLI_FAILED, "%s", tlod_context_last_error(s.ctx));
  }
  double best = INFINITY, sum = 0.0, worst = 0.0, stages[TLOD_STAGE_NUM] = {0};
  for (uint32_t k = 0; k < frames + 2; k++) {
    tlod_view_desc view;
    bench_orbit_view(s.mesh, 0.05f * (float)k, 1.2f, 1280, 720, &view);
    double t0 = cli_now_ms();
    tlod_scheduler_update(sch, &(tlod_frame_desc){.views = &view, .view_count = 1, .dt_ms = 16.7f});
    double dt = cli_now_ms() - t0;
    if (k < 2) continue; /* warm-up */
    best = dt < best ? dt : best;
    worst = dt > worst ? dt : worst;
    sum += dt;
    for (int st = 0; st < TLOD_STAGE_NUM; st++)
      stages[st] += tlod_scheduler_draw_list(sch, 0)->stage_ms[st];
  }
  uint32_t patches = tlod_surface_patch_count(s.surface), verts = tlod_mesh_vertex_count(s.mesh);
  double bytes = frame_bytes(verts, patches), rate = patches / (best * 1e-3);
  double bound_ms = bytes / bandwidth * 1e3;
  printf("scheduler  %-22s T%-2u %8u patches  best %8.3f ms mean %8.3f worst %8.3f  %7.2f Mpatch/s  "
         "bandwidth bound %.3f ms = %.0f%% of best  [stages mean ms: sil %.3f metric %.3f levels %.3f morph %.3f "
         "strips %.3f]\n",
         in, threads, patches, best, sum / frames, worst, rate * 1e-6, bound_ms, 100.0 * bound_ms / best,
         stages[0] / frames, stages[1] / frames, stages[2] / frames, stages[3] / frames, stages[4] / frames);
  if (csv)
    fprintf(csv, "scheduler,%s,%u,%u,%.4f,%.4f,%.4f,%.6g,%.4f\n", in, threads, patches, best, sum / frames, worst, rate,
            bound_ms);
  tlod_scheduler_destroy(sch);
  bench_scene_free(&s);
  return CLI_OK;
}

int bench_scheduler(const bench_lod_options* o, double bandwidth, FILE* csv) {
  static const char* const meshes[] = {"demo:torus-100x100", "demo:torus-320x320", "demo:torus-1000x1000"};
  int rc = CLI_OK;
  for (int m = 0; m < 3 && rc == CLI_OK; m++)
    for (uint32_t t = 0; t < o->thread_count && rc == CLI_OK; t++)
      rc = scheduler_case(meshes[m], o->threads[t], o->frames, bandwidth, csv);
  return rc;
}

static const char* const policy_names[] = {"-", "error", "silhouette", "hybrid"};

/* Uniform tessellation at the finest level any visible patch needs. */
static uint64_t uniform_triangles(const bench_scene* s, const tlod_draw_list* dl, uint32_t level) {
  uint64_t tris = 0;
  for (uint32_t f = 0; f < dl->patch_count; f++) {
    uint32_t corners[4];
    if (dl->levels[f] < 0) continue;
    bool quad = tlod_mesh_face_corners(s->mesh, f, corners) == 4;
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
  bench_orbit_view(s.mesh, 0.6f, (float)distance, 1600, 1144, &view);
  uint32_t worst = 0, patches = tlod_surface_patch_count(s.surface);
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
    if (tlod_scheduler_create(s.ctx, s.surface, s.patterns, &d, &sch) != TLOD_SUCCESS ||
        tlod_scheduler_update(sch, &(tlod_frame_desc){.views = &view, .view_count = 1}) != TLOD_SUCCESS) {
      rc = cli_error(CLI_FAILED, "%s", tlod_context_last_error(s.ctx));
      tlod_scheduler_destroy(sch);
      break;
    }
    const tlod_draw_list* dl = tlod_scheduler_draw_list(sch, 0);
    uint32_t visible = dl->patch_count - dl->culled;
    /* The uniform comparison uses the error rule's level for the worst patch. */
    for (uint32_t f = 0; f < dl->patch_count; f++) {
      uint32_t l = tlod_level_for_error(dl->e_max[f], 0.5f, tlod_patterns_max_level(s.patterns));
      if (dl->levels[f] >= 0 && l > worst) worst = l;
    }
    uint64_t adaptive = dl->pattern_triangles + dl->strip_triangles, uniform = uniform_triangles(&s, dl, worst);
    /* At contours the silhouette error must stay the error policy's. */
    uint32_t contour = 0, coarser = 0;
    for (uint32_t f = 0; f < patches; f++) {
      if (p == TLOD_POLICY_ERROR) error_levels[f] = dl->levels[f];
      if (dl->levels[f] < 0 || !on_contour(s.mesh, f, view.view)) continue;
      contour++;
      coarser += dl->levels[f] < error_levels[f];
    }
    printf("table1     %-24s %-10s base %6u  adaptive %8llu (strips %5.1f%%)  uniform L%u %9llu  uniform/adaptive "
           "%5.2fx  contour patches %u, coarser than error policy %u\n",
           in, policy_names[p], visible, (unsigned long long)adaptive, 100.0 * (double)dl->strip_triangles / adaptive,
           worst, (unsigned long long)uniform, (double)uniform / (double)adaptive, contour, coarser);
    if (csv)
      fprintf(csv, "table1,%s,%s,%u,%llu,%llu,%u,%llu\n", in, policy_names[p], visible, (unsigned long long)adaptive,
              (unsigned long long)dl->strip_triangles, worst, (unsigned long long)uniform);
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
