/*
 * vk_cache_test.c -- the "vulkan" device's SPIR-V cache at device level
 * (owned by the Vulkan tests; the cache file format and its hostile-file
 * checks are the shader module's own test). Public API only.
 *
 * On one platform, with shader_cache_dir a folder this test empties first:
 *   1. a device draws a frame: stages compiled (> 0), files left (a stage
 *      source shared by two pipelines is compiled once and then hits);
 *   2. a second device with the same folder draws the same frame: nothing
 *      compiled, as many hits as (1) loaded stages (compiles + hits), and
 *      the image is (1)'s byte for byte (same SPIR-V, same driver);
 *   3. a device with a fragment hook: the hooked stages are compiled
 *      (their source differs, so does the key), the others still hit.
 * Counted after a draw, so stages a device makes lazily at its first draw
 * are counted too.
 */
#define _POSIX_C_SOURCE 200809L /* mkdir, opendir */
#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

#include "vk_test.h"

#define W 96
#define H 96

static const char* const k_hook = "vec4 tlod_shade(tlod_fragment f) { return vec4(0.5 * f.normal + 0.5, 1.0); }\n";

/* Removes the files in dir (creating dir and its parent when missing);
 * returns how many there were. */
static int empty_folder(const char* parent, const char* dir) {
  mkdir(parent, 0755);
  mkdir(dir, 0755);
  DIR* d = opendir(dir);
  int n = 0;
  for (struct dirent* e = d ? readdir(d) : NULL; e; e = readdir(d)) {
    if (e->d_name[0] == '.') continue;
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
    n += unlink(path) == 0;
  }
  if (d) closedir(d);
  return n;
}

static int count_files(const char* dir) {
  DIR* d = opendir(dir);
  int n = 0;
  for (struct dirent* e = d ? readdir(d) : NULL; e; e = readdir(d))
    n += e->d_name[0] != '.';
  if (d) closedir(d);
  return n;
}

typedef struct cache_run {
  tlod_device_vk_stats vk;
  uint32_t covered;
} cache_run;

/* A device on the platform with the cache folder (and hook) draws one
 * sphere frame into rgba, then is destroyed; its stats after the draw. */
static void run_device(tlod_platform* p, tlod_context* ctx, const tlod_patterns* pat, const char* dir, const char* hook,
                       uint8_t* rgba, cache_run* out) {
  memset(out, 0, sizeof *out);
  tlod_device_vk_desc vk = vk_desc_of(p);
  vk.shader_cache_dir = dir;
  vk.fragment_hook = hook;
  tlod_device* dev = new_vk_device(ctx, pat, "vk_cache", vk);
  CHECK(dev);
  shape sph = shape_icosphere(2);
  fixture fx;
  bool made = fixture_make(&fx, ctx, &sph, TLOD_SURFACE_PN, pat, dev);
  tlod_scheduler* sch = made ? new_scheduler(&fx, (tlod_scheduler_desc){.max_level = 4}) : NULL;
  camera cam = camera_look(2.0, -2.6, 1.2, 0, 0, 0, 45, W, H);
  tlod_view_desc v = make_view(&cam);
  const tlod_draw_list* dl = sch ? plan(&fx, sch, &v, 0.0f) : NULL;
  one_draw od;
  if (dl) one_draw_make(&od, fx.ds, dl, &v);
  bool drawn = dl && vk_draw_frame(p, dev, ctx, &od.desc, rgba);
  out->vk = tlod_device_query_stats(dev).vk;
  out->covered = drawn ? covered_pixels(rgba, W, H) : 0;
  tlod_platform_finish(p);
  tlod_scheduler_destroy(sch);
  if (made) fixture_free(&fx);
  shape_free(&sph);
  tlod_device_destroy(dev);
  CHECK_MSG(drawn, "the frame was not drawn");
}

static void print_run(const char* what, const cache_run* r) {
  printf("  %-28s %2u stages compiled, %2u cache hits, %.1f ms in shaders, %u pixels covered\n", what,
         r->vk.shader_compiles, r->vk.shader_cache_hits, r->vk.shader_ms, r->covered);
}

TEST(test_second_device_compiles_nothing) {
  char err[512] = "", dir[600];
  snprintf(dir, sizeof dir, "%s/cache", TLOD_VK_TEST_SCRATCH);
  int stale = empty_folder(TLOD_VK_TEST_SCRATCH, dir);
  tlod_platform* p = vk_test_platform(W, H, false, err, sizeof err);
  CHECK_MSG(p, "no Vulkan device: %s", err);
  tlod_context* ctx = NULL;
  CHECK(tlod_context_create(&(tlod_context_desc){.thread_count = 2}, &ctx) == TLOD_SUCCESS);
  tlod_patterns* pat = new_patterns(ctx, 4);
  uint8_t *first = malloc(4 * W * H), *second = malloc(4 * W * H);
  CHECK(pat && first && second);
  cache_run a, b, c;
  CALL(run_device(p, ctx, pat, dir, NULL, first, &a));
  int files = count_files(dir);
  CALL(run_device(p, ctx, pat, dir, NULL, second, &b));
  bool same = memcmp(first, second, 4 * W * H) == 0;
  CALL(run_device(p, ctx, pat, dir, k_hook, second, &c));
  printf("  cache folder emptied (%d stale files), %d files after the first device\n", stale, files);
  print_run("first device (empty cache)", &a);
  print_run("second device (same folder)", &b);
  print_run("with a fragment hook", &c);
  CHECK_MSG(a.vk.shader_compiles > 0 && files > 0, "first device: %u compiles, %d files", a.vk.shader_compiles, files);
  uint32_t stages = a.vk.shader_compiles + a.vk.shader_cache_hits;
  CHECK_MSG(b.vk.shader_compiles == 0 && b.vk.shader_cache_hits == stages,
            "second device: %u compiles (want 0), %u hits (want %u)", b.vk.shader_compiles, b.vk.shader_cache_hits,
            stages);
  CHECK_MSG(a.covered > 500 && same, "covered %u then %u pixels; images %s", a.covered, b.covered,
            same ? "equal" : "differ");
  CHECK_MSG(c.vk.shader_compiles > 0 && c.vk.shader_cache_hits > 0,
            "hooked device: %u compiles, %u hits (want both > 0: only the hooked stages are new)", c.vk.shader_compiles,
            c.vk.shader_cache_hits);
  free(first);
  free(second);
  tlod_patterns_destroy(pat);
  tlod_context_destroy(ctx);
  tlod_platform_destroy(p);
}

int main(void) {
  RUN(test_second_device_compiles_nothing);
  VK_TEST_END();
}
