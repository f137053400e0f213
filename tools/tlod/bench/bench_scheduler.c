/* tlod bench --suite scheduler -- time per frame against patch count and
 * threads, with the memory-bandwidth bound of the bytes a frame touches. */
#include <math.h>

#include "bench_lod.h"

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
  if (tlod_scheduler_create(s.ctx, s.setup.surface, s.setup.patterns, &(tlod_scheduler_desc){0}, &sch) !=
      TLOD_SUCCESS) {
    bench_scene_free(&s);
    return cli_error(CLI_FAILED, "%s", tlod_context_last_error(s.ctx));
  }
  double best = INFINITY, sum = 0.0, worst = 0.0, stages[TLOD_STAGE_NUM] = {0};
  for (uint32_t k = 0; k < frames + 2; k++) {
    tlod_view_desc view;
    bench_orbit_view(s.setup.mesh, 0.05f * (float)k, 1.2f, 1280, 720, &view);
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
  uint32_t patches = tlod_surface_patch_count(s.setup.surface), verts = tlod_mesh_vertex_count(s.setup.mesh);
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
