/* tlod bench --suite vkstart -- the vulkan device's first start: device
 * create + surface + the first frame (pipelines made on first use count),
 * with its shader figures (tlod_device_vk_stats: stages compiled by
 * glslang, stages loaded from the SPIR-V cache, the ms of both), three
 * ways: no disk cache, an empty cache folder (compiles and fills it), and
 * the folder the empty start filled (loads only). Each round uses a fresh
 * temporary folder, removed at the end; best of --repeat rounds. */
#define _DEFAULT_SOURCE /* mkdtemp */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench_gl.h"
#include "bench_lod.h"
#include "common/gpu_target.h"

#if TLOD_HAS_VULKAN
#include "tlod_platform.h"

#define START_W 640
#define START_H 480

typedef struct start_figures {
  double start_ms; /* create + first frame, wall clock */
  tlod_device_vk_stats vk;
} start_figures;

/* Removes the files of folder dir (the cache writes no subfolders) and dir. */
static void remove_folder(const char* dir) {
  DIR* d = opendir(dir);
  char path[4096];
  for (struct dirent* e = d ? readdir(d) : NULL; e; e = readdir(d))
    if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..") &&
        snprintf(path, sizeof(path), "%s/%s", dir, e->d_name) < (int)sizeof(path))
      unlink(path);
  if (d) closedir(d);
  rmdir(dir);
}

/* One start on platform p with shader cache folder cache (NULL: none). */
static int start_once(bench_scene* s, tlod_platform* p, const char* cache, start_figures* f) {
  tlod_device_desc dd = {.backend = "vulkan", .patterns = s->setup.patterns, .label = "bench vkstart"};
  gpu_target_device_desc(p, cache, false, &dd);
  tlod_device* dev = NULL;
  tlod_device_surface* ds = NULL;
  tlod_scheduler* sch = NULL;
  tlod_scheduler_desc sd = {.morph = TLOD_MORPH_NONE};
  tlod_view_desc v;
  bench_orbit_view(s->setup.mesh, 0.6f, 1.0f, START_W, START_H, &v);
  double t0 = cli_now_ms(), wall = 0.0;
  int rc = tlod_device_create(s->ctx, &dd, &dev) == TLOD_SUCCESS &&
                   tlod_device_create_surface(dev, s->setup.surface, &ds) == TLOD_SUCCESS &&
                   tlod_scheduler_create(s->ctx, s->setup.surface, s->setup.patterns, &sd, &sch) == TLOD_SUCCESS &&
                   tlod_scheduler_update(sch, &(tlod_frame_desc){.views = &v, .view_count = 1}) == TLOD_SUCCESS
               ? CLI_OK
               : cli_error(CLI_FAILED, "vulkan: %s", tlod_context_last_error(s->ctx));
  tlod_draw_item item = {.surface = ds, .draw_list = sch ? tlod_scheduler_draw_list(sch, 0) : NULL};
  tlod_draw_desc d = {.items = &item, .item_count = 1, .viewport = {0, 0, START_W, START_H}};
  memcpy(d.view, v.view, sizeof(d.view));
  memcpy(d.proj, v.proj, sizeof(d.proj));
  if (rc == CLI_OK) rc = bench_frame(p, s->ctx, dev, &d, &wall);
  f->start_ms = cli_now_ms() - t0;
  if (rc == CLI_OK) f->vk = tlod_device_query_stats(dev).vk;
  tlod_scheduler_destroy(sch);
  tlod_device_destroy(dev);
  return rc;
}

static void report(const char* what, const start_figures* f, FILE* csv) {
  printf("vkstart    %-28s start %8.2f ms  device create %8.2f ms  shaders %8.2f ms: %3u compiled, %3u from the "
         "cache, %u pipelines\n",
         what, f->start_ms, f->vk.create_ms, f->vk.shader_ms, f->vk.shader_compiles, f->vk.shader_cache_hits,
         f->vk.pipelines);
  if (csv)
    fprintf(csv, "vkstart,%s,%.3f,%.3f,%.3f,%u,%u,%u\n", what, f->start_ms, f->vk.create_ms, f->vk.shader_ms,
            f->vk.shader_compiles, f->vk.shader_cache_hits, f->vk.pipelines);
}

/* Round r: the three starts, the best of each kept in best[3]. */
static int round_once(bench_scene* s, tlod_platform* p, start_figures best[3]) {
  char dir[4096];
  const char* tmp = getenv("TMPDIR");
  snprintf(dir, sizeof(dir), "%s/tlod-vkstart-XXXXXX", tmp && *tmp ? tmp : "/tmp");
  if (!mkdtemp(dir)) return cli_error(CLI_FAILED, "vkstart: cannot make a temporary folder '%s'", dir);
  const char* caches[3] = {NULL, dir, dir};
  int rc = CLI_OK;
  for (int k = 0; k < 3 && rc == CLI_OK; k++) {
    start_figures f;
    rc = start_once(s, p, caches[k], &f);
    if (rc == CLI_OK && f.start_ms < best[k].start_ms) best[k] = f;
  }
  remove_folder(dir);
  return rc;
}

int bench_vkstart(uint32_t repeat, FILE* csv) {
  bench_scene s;
  int rc = bench_scene_load("demo:cow", 0, TLOD_SURFACE_PHONG, 6, &s);
  if (rc != CLI_OK) return rc;
  tlod_platform* p = NULL;
  bench_gpu gpu = {.backend = "vulkan"};
  rc = bench_gpu_open(&gpu, START_W, START_H, &p);
  char desc[256];
  if (rc == CLI_OK)
    printf("vkstart bench: demo:cow, %s, best of %u rounds (create + surface + first frame)\n",
           tlod_platform_describe(p, desc, sizeof(desc)), repeat);
  if (rc == CLI_OK && csv)
    fprintf(csv, "suite,cache,start_ms,create_ms,shader_ms,shader_compiles,shader_cache_hits,pipelines\n");
  start_figures best[3] = {{.start_ms = INFINITY}, {.start_ms = INFINITY}, {.start_ms = INFINITY}};
  for (uint32_t r = 0; r < repeat && rc == CLI_OK; r++)
    rc = round_once(&s, p, best);
  static const char* const names[3] = {"no disk cache", "empty cache (first start)", "filled cache (next start)"};
  for (int k = 0; k < 3 && rc == CLI_OK; k++)
    report(names[k], &best[k], csv);
  gpu_target_close(p);
  bench_scene_free(&s);
  return rc;
}
#else
int bench_vkstart(uint32_t repeat, FILE* csv) {
  (void)repeat, (void)csv;
  return cli_error(CLI_FAILED, "bench vkstart: this build has no Vulkan backend (TLOD_BACKEND_VULKAN=OFF)");
}
#endif
