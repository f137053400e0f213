/* tlod bench --suite draw -- the backend's CPU time per frame
 * (tlod_device_stats.cpu_ms: gl its GL calls and uploads, vulkan its
 * recording and ring writes; no GPU wait) for about 100k visible patches:
 * a 320 x 320 torus (102,400 quads, Phong), whole in view, drawn by
 * --backend at uniform level 1 (GPU work small, per-patch work the same)
 * and adaptively. The wall time beside it includes the GPU (gl: finish,
 * vulkan: submit). */
#include <stdlib.h>
#include <string.h>

#include "bench_gl.h"
#include "bench_lod.h"
#include "bench_report.h"
#include "bench_stats.h"
#include "common/gpu_target.h"

#if TLOD_HAS_GL || TLOD_HAS_VULKAN
#include "tlod_platform.h"

#define DRAW_W 1024
#define DRAW_H 732
#define DRAW_MESH "demo:torus-320x320"

typedef struct draw_case {
  const char* name;
  tlod_scheduler_desc sched;
} draw_case;

/* ms of every frame (after two warm-up frames): the backend's stat
 * (tlod_device_stats.cpu_ms, the clock around its own calls) into
 * t[0..frames), the wall clock, the process CPU time (with the driver's
 * threads) and the calling thread's CPU time of the draw into the next
 * three runs of frames. */
static int run_case(bench_scene* s, tlod_platform* p, tlod_device* dev, tlod_device_surface* ds, const draw_case* c,
                    uint32_t frames, double* t, uint32_t* visible, uint32_t* instances) {
  tlod_scheduler* sch = NULL;
  int rc = tlod_scheduler_create(s->ctx, s->setup.surface, s->setup.patterns, &c->sched, &sch) == TLOD_SUCCESS
               ? CLI_OK
               : cli_error(CLI_FAILED, "%s", tlod_context_last_error(s->ctx));
  for (uint32_t k = 0; rc == CLI_OK && k < frames + 2; k++) {
    tlod_view_desc v;
    bench_orbit_view(s->setup.mesh, 0.6f + 0.01f * (float)k, 1.0f, DRAW_W, DRAW_H, &v);
    tlod_scheduler_update(sch, &(tlod_frame_desc){.views = &v, .view_count = 1, .dt_ms = 16.7f});
    const tlod_draw_list* dl = tlod_scheduler_draw_list(sch, 0);
    tlod_draw_item item = {.surface = ds, .draw_list = dl};
    tlod_draw_desc d = {.items = &item, .item_count = 1, .viewport = {0, 0, DRAW_W, DRAW_H}, .finish = true};
    memcpy(d.view, v.view, sizeof(d.view));
    memcpy(d.proj, v.proj, sizeof(d.proj));
    double wall = 0.0, c0 = bench_cpu_ms(), h0 = bench_thread_cpu_ms();
    rc = bench_frame(p, s->ctx, dev, &d, &wall);
    if (k < 2) continue;
    t[k - 2] = tlod_device_query_stats(dev).cpu_ms;
    t[frames + k - 2] = wall;
    t[2 * frames + k - 2] = bench_cpu_ms() - c0;
    t[3 * frames + k - 2] = bench_thread_cpu_ms() - h0;
    *visible = dl->patch_count - dl->culled;
    *instances = dl->instance_count;
  }
  tlod_scheduler_destroy(sch);
  return rc;
}

static void write_json(json_writer* w, const char* backend, const char* mode, uint32_t visible, const double cpu[2],
                       const double wall[2], double caller_cpu) {
  json_object_begin(w, NULL);
  json_string(w, "backend", backend);
  json_string(w, "mode", mode);
  json_uint(w, "visible_patches", visible);
  json_number(w, "backend_cpu_min_ms", cpu[0]);
  json_number(w, "backend_cpu_median_ms", cpu[1]);
  json_number(w, "caller_thread_cpu_median_ms", caller_cpu);
  json_number(w, "wall_median_ms", wall[1]);
  json_object_end(w);
}

static int draw_cases(bench_scene* s, tlod_platform* p, const bench_gpu* gpu, uint32_t frames, bench_report* rep,
                      FILE* csv) {
  static const draw_case cases[] = {
      {"uniform:1", {.policy = TLOD_POLICY_UNIFORM, .max_level = 1, .morph = TLOD_MORPH_NONE}},
      {"adaptive", {.morph = TLOD_MORPH_NONE}}};
  tlod_device* dev = NULL;
  tlod_device_surface* ds = NULL;
  tlod_device_desc dd = {.backend = gpu->backend, .patterns = s->setup.patterns, .label = "bench draw"};
  gpu_target_device_desc(p, gpu->shader_cache, false, &dd);
  double* t = malloc(sizeof(double) * 4 * frames);
  int rc = t ? CLI_OK : cli_error(CLI_FAILED, "out of memory");
  if (rc == CLI_OK && (tlod_device_create(s->ctx, &dd, &dev) != TLOD_SUCCESS ||
                       tlod_device_create_surface(dev, s->setup.surface, &ds) != TLOD_SUCCESS))
    rc = cli_error(CLI_FAILED, "%s: %s", gpu->backend, tlod_context_last_error(s->ctx));
  for (size_t k = 0; rc == CLI_OK && k < sizeof(cases) / sizeof(cases[0]); k++) {
    uint32_t visible = 0, instances = 0;
    double cpu[2], wall[2], proc[2], caller[2];
    rc = run_case(s, p, dev, ds, &cases[k], frames, t, &visible, &instances);
    if (rc != CLI_OK) break;
    bench_min_median(t, frames, 1.0, cpu);
    bench_min_median(t + frames, frames, 1.0, wall);
    bench_min_median(t + 2 * frames, frames, 1.0, proc);
    bench_min_median(t + 3 * frames, frames, 1.0, caller);
    printf("draw       %-6s %-10s %7u visible patches %7u instances  backend (its calls' clock) min %7.3f median "
           "%7.3f ms (%.3f us/patch) | calling thread cpu median %7.3f | process cpu median %7.3f | wall median "
           "%8.2f ms\n",
           gpu->backend, cases[k].name, visible, instances, cpu[0], cpu[1], 1e3 * cpu[1] / (visible ? visible : 1),
           caller[1], proc[1], wall[1]);
    if (csv)
      fprintf(csv, "draw,%s,%s,%u,%u,%.4f,%.4f,%.4f\n", gpu->backend, cases[k].name, visible, instances, cpu[0], cpu[1],
              wall[1]);
    if (rep->json) write_json(rep->json, gpu->backend, cases[k].name, visible, cpu, wall, caller[1]);
  }
  tlod_device_destroy(dev);
  free(t);
  return rc;
}

int bench_draw(const bench_gpu* gpu, uint32_t frames, bench_report* rep, FILE* csv) {
  bench_scene s;
  int rc = bench_scene_load(DRAW_MESH, 0, TLOD_SURFACE_PHONG, 6, &s);
  if (rc != CLI_OK) return rc;
  tlod_platform* p = NULL;
  rc = bench_gpu_open(gpu, DRAW_W, DRAW_H, &p);
  char desc[256];
  if (rc == CLI_OK)
    printf("draw bench: %s (%u patches), %s, %ux%u, %u frames per case\n", DRAW_MESH,
           tlod_surface_patch_count(s.setup.surface), tlod_platform_describe(p, desc, sizeof(desc)), DRAW_W, DRAW_H,
           frames);
  if (rc == CLI_OK && csv) fprintf(csv, "suite,backend,mode,visible,instances,cpu_min,cpu_median,wall_median\n");
  if (rc == CLI_OK && rep->json) json_array_begin(rep->json, "draw");
  if (rc == CLI_OK) rc = draw_cases(&s, p, gpu, frames, rep, csv);
  if (rep->json) json_array_end(rep->json);
  gpu_target_close(p);
  bench_scene_free(&s);
  return rc;
}
#else
int bench_draw(const bench_gpu* gpu, uint32_t frames, bench_report* rep, FILE* csv) {
  (void)frames, (void)rep, (void)csv;
  return cli_error(CLI_FAILED, "bench draw: this build has no %s backend", gpu->backend);
}
#endif
