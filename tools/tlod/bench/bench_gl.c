/* tlod bench --suite gl -- GPU frame times on llvmpipe / lavapipe of the
 * --backend (gl, or vulkan: the same cases through the Vulkan device): wall
 * clock around a finish (gl: its timer queries miss most of the work,
 * docs/platform.md section 1.1) or the recording plus the submit (vulkan:
 * lavapipe runs the commands at submit): adaptive against uniform against
 * flat for the Table 1 scenes, Phong against flat at equal triangle counts,
 * and the pattern path against hardware tessellation. Ratios within one run
 * are the figures to read. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_gl.h"
#include "bench_lod.h"
#include "bench_stats.h"
#include "common/camera.h"

#if TLOD_HAS_GL || TLOD_HAS_VULKAN
#include "common/gpu_target.h"
#include "tesslod/backend.h"
#include "tlod_platform.h"

typedef struct gl_case {
  const char* label;
  tlod_scheduler_desc sched;
  bool hardware;
} gl_case;

/* The devices of one scene, made once (programs linked, patterns uploaded)
 * and shared by its cases: the pattern path and, when a case asks for it,
 * the hardware-tessellation path; the scene's surface on each. */
typedef struct gl_devices {
  tlod_platform* platform;
  const char* backend; /* "gl" or "vulkan" */
  const char* shader_cache;
  tlod_device* dev[2];
  tlod_device_surface* surface[2];
} gl_devices;

static void gl_devices_free(gl_devices* g) {
  for (int k = 0; k < 2; k++) {
    tlod_device_destroy(g->dev[k]); /* and its surface */
    g->dev[k] = NULL, g->surface[k] = NULL;
  }
}

static int gl_device_for(bench_scene* s, gl_devices* g, bool hardware, tlod_device** dev,
                         tlod_device_surface** surface) {
  int k = hardware ? 1 : 0;
  if (!g->dev[k]) {
    tlod_surface_type type = tlod_surface_query_view(s->setup.surface).type;
    tlod_device_desc d = {.backend = g->backend,
                          .patterns = s->setup.patterns,
                          .gl = {.hardware_tessellation = hardware, .surface_types = 1u << type},
                          .label = hardware ? "bench gpu (hardware tessellation)" : "bench gpu"};
    gpu_target_device_desc(g->platform, g->shader_cache, hardware, &d);
    if (tlod_device_create(s->ctx, &d, &g->dev[k]) != TLOD_SUCCESS ||
        tlod_device_create_surface(g->dev[k], s->setup.surface, &g->surface[k]) != TLOD_SUCCESS)
      return cli_error(CLI_FAILED, "%s", tlod_context_last_error(s->ctx));
  }
  *dev = g->dev[k];
  *surface = g->surface[k];
  return CLI_OK;
}

/* min and median ms over the frames of a case: the frame's wall clock, the
 * process CPU time of the frame (every thread: llvmpipe / lavapipe
 * rasterise on threads of this process) and the backend's own CPU time
 * (tlod_device_stats.cpu_ms: its API calls and uploads). */
typedef struct gl_figures {
  double wall[2], cpu[2], backend[2];
  uint64_t tris; /* drawn per frame */
} gl_figures;

static int draw_frame(bench_scene* s, gl_devices* g, tlod_device* dev, tlod_device_surface* ds, tlod_scheduler* sch,
                      uint32_t k, uint32_t w, uint32_t h, double* wall) {
  tlod_view_desc v;
  bench_orbit_view(s->setup.mesh, 0.6f + 0.02f * (float)k, 1.0f, w, h, &v);
  tlod_scheduler_update(sch, &(tlod_frame_desc){.views = &v, .view_count = 1, .dt_ms = 16.7f});
  tlod_draw_item item = {.surface = ds, .draw_list = tlod_scheduler_draw_list(sch, 0)};
  tlod_draw_desc fr = {.items = &item, .item_count = 1, .viewport = {0, 0, w, h}, .finish = true};
  memcpy(fr.view, v.view, sizeof(fr.view));
  memcpy(fr.proj, v.proj, sizeof(fr.proj));
  return bench_frame(g->platform, s->ctx, dev, &fr, wall);
}

/* The frames of an orbit (after one warm-up: the first draw's buffer set-up). */
static int run_case(bench_scene* s, gl_devices* g, const gl_case* c, uint32_t w, uint32_t h, uint32_t frames,
                    gl_figures* f) {
  tlod_scheduler* sch = NULL;
  tlod_device* dev = NULL;
  tlod_device_surface* ds = NULL;
  double* t = malloc(sizeof(double) * 3 * frames);
  int rc = t ? gl_device_for(s, g, c->hardware, &dev, &ds) : cli_error(CLI_FAILED, "out of memory");
  if (rc == CLI_OK &&
      tlod_scheduler_create(s->ctx, s->setup.surface, s->setup.patterns, &c->sched, &sch) != TLOD_SUCCESS)
    rc = cli_error(CLI_FAILED, "%s", tlod_context_last_error(s->ctx));
  for (uint32_t k = 0; rc == CLI_OK && k < frames + 1; k++) {
    double wall = 0.0, c0 = bench_cpu_ms();
    rc = draw_frame(s, g, dev, ds, sch, k, w, h, &wall);
    if (k == 0) continue;
    t[k - 1] = wall, t[frames + k - 1] = bench_cpu_ms() - c0;
    t[2 * frames + k - 1] = tlod_device_query_stats(dev).cpu_ms;
    f->tris = tlod_device_query_stats(dev).triangles;
  }
  if (rc == CLI_OK) {
    bench_min_median(t, frames, 1.0, f->wall);
    bench_min_median(t + frames, frames, 1.0, f->cpu);
    bench_min_median(t + 2 * frames, frames, 1.0, f->backend);
  }
  tlod_scheduler_destroy(sch);
  free(t);
  return rc;
}

static void report(FILE* csv, const char* backend, const char* scene, const char* what, const gl_figures* f,
                   double ref_median) {
  printf("%-10s %-28s %-34s wall min %8.2f median %8.2f ms | process cpu median %8.2f | backend cpu median %7.3f | "
         "%9llu tris %6.2f Mtri/s  x%.2f\n",
         backend, scene, what, f->wall[0], f->wall[1], f->cpu[1], f->backend[1], (unsigned long long)f->tris,
         (double)f->tris / (f->wall[1] * 1e3), f->wall[1] / ref_median);
  if (csv)
    fprintf(csv, "%s,%s,%s,%.4f,%.4f,%llu,%.4f,%.4f\n", backend, scene, what, f->wall[0], f->wall[1],
            (unsigned long long)f->tris, f->cpu[1], f->backend[1]);
}

/* Uniform level of the worst visible patch under the error rule. */
static uint32_t worst_level(bench_scene* s, uint32_t w, uint32_t h) {
  tlod_scheduler* sch = NULL;
  uint32_t worst = 0;
  tlod_view_desc v;
  bench_orbit_view(s->setup.mesh, 0.6f, 1.0f, w, h, &v);
  tlod_scheduler_desc d = {.policy = TLOD_POLICY_ERROR, .morph = TLOD_MORPH_NONE};
  if (tlod_scheduler_create(s->ctx, s->setup.surface, s->setup.patterns, &d, &sch) == TLOD_SUCCESS &&
      tlod_scheduler_update(sch, &(tlod_frame_desc){.views = &v, .view_count = 1}) == TLOD_SUCCESS) {
    const tlod_draw_list* dl = tlod_scheduler_draw_list(sch, 0);
    for (uint32_t l = 0; l <= TLOD_MAX_LEVEL; l++)
      if (dl->level_histogram[l]) worst = l;
  }
  tlod_scheduler_destroy(sch);
  return worst;
}

static int scene_cases(const char* in, const gl_devices* target, uint32_t w, uint32_t h, uint32_t frames, FILE* csv) {
  bench_scene s;
  int rc = bench_scene_load(in, 0, TLOD_SURFACE_PN, 6, &s);
  if (rc != CLI_OK) return rc;
  uint32_t worst = worst_level(&s, w, h);
  gl_case cases[] = {
      {"flat (no tessellation)", {.policy = TLOD_POLICY_FLAT, .morph = TLOD_MORPH_NONE}, false},
      {"adaptive error 0.5 px", {.policy = TLOD_POLICY_ERROR, .morph = TLOD_MORPH_NONE}, false},
      {"adaptive hybrid 0.5 px", {.policy = TLOD_POLICY_HYBRID, .morph = TLOD_MORPH_NONE}, false},
      {"uniform (worst patch's level)",
       {.policy = TLOD_POLICY_UNIFORM, .max_level = worst ? worst : 1, .morph = TLOD_MORPH_NONE},
       false},
      {"adaptive error, hardware tess.", {.policy = TLOD_POLICY_ERROR, .morph = TLOD_MORPH_NONE}, true},
  };
  double ref = 0.0;
  gl_devices g = *target;
  for (size_t k = 0; k < sizeof(cases) / sizeof(cases[0]) && rc == CLI_OK; k++) {
    gl_figures f = {0};
    rc = run_case(&s, &g, &cases[k], w, h, frames, &f);
    if (k == 0) ref = f.wall[1];
    if (rc == CLI_OK) report(csv, g.backend, in, cases[k].label, &f, ref);
  }
  printf("%-10s %-28s (uniform level %u; x = median frame time / flat's)\n", g.backend, in, worst);
  gl_devices_free(&g);
  bench_scene_free(&s);
  return rc;
}

/* Phong against flat tessellation at one uniform level: equal triangles. */
static int phong_vs_flat(const char* in, const gl_devices* target, uint32_t w, uint32_t h, uint32_t frames, FILE* csv) {
  int rc = CLI_OK;
  double flat_median = 0.0;
  for (int k = 0; k < 2 && rc == CLI_OK; k++) {
    bench_scene s;
    tlod_surface_type type = k ? TLOD_SURFACE_PHONG : TLOD_SURFACE_FLAT;
    if ((rc = bench_scene_load(in, 0, type, 6, &s)) != CLI_OK) break;
    gl_case c = {k ? "phong, uniform level 4" : "flat, uniform level 4",
                 {.policy = TLOD_POLICY_UNIFORM, .max_level = 4, .morph = TLOD_MORPH_NONE},
                 false};
    gl_figures f = {0};
    gl_devices g = *target;
    rc = run_case(&s, &g, &c, w, h, frames, &f);
    if (k == 0) flat_median = f.wall[1];
    if (rc == CLI_OK) report(csv, g.backend, in, c.label, &f, flat_median);
    gl_devices_free(&g);
    bench_scene_free(&s);
  }
  return rc;
}

int bench_gl(const bench_gpu* gpu, const char* const* models, uint32_t model_count, uint32_t frames, FILE* csv) {
  const uint32_t w = 1024, h = 732; /* the paper's 1600x1144 aspect, smaller for a software rasterizer */
  gl_devices g = {.backend = gpu->backend, .shader_cache = gpu->shader_cache};
  int rc = bench_gpu_open(gpu, w, h, &g.platform);
  if (rc != CLI_OK) return rc;
  char desc[256];
  printf("%s bench: %s, %ux%u, %s, %u frames per case\n", g.backend,
         tlod_platform_describe(g.platform, desc, sizeof(desc)), w, h,
         strcmp(g.backend, "vulkan") ? "wall clock around glFinish" : "recording + submit + wait for its fences",
         frames);
  for (uint32_t m = 0; m < model_count && rc == CLI_OK; m++)
    rc = scene_cases(models[m], &g, w, h, frames, csv);
  if (rc == CLI_OK) rc = phong_vs_flat(models[0], &g, w, h, frames, csv);
  gpu_target_close(g.platform);
  return rc;
}
#else
int bench_gl(const bench_gpu* gpu, const char* const* models, uint32_t model_count, uint32_t frames, FILE* csv) {
  (void)models, (void)model_count, (void)frames, (void)csv;
  return cli_error(CLI_FAILED, "bench gl: this build has no %s backend", gpu->backend);
}
#endif
