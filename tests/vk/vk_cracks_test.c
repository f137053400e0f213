/*
 * vk_cracks_test.c -- the "vulkan" device's images of closed meshes have no
 * holes at mixed levels, on the pattern path and the hardware path (owned
 * by the Vulkan tests). Public API only.
 *
 * For icosphere(2), torus(16, 10) and cube_soft (split normals: creases
 * whose two sides' curves really differ) under Phong and PN, CAMERAS random
 * cameras each (test_device.h's random_camera: near, far and grazing,
 * fields of view 30-75 degrees), one scheduler per case with its defaults
 * (adaptive levels, TIME geomorphs, frames 16 ms apart, so patches are
 * caught mid-morph), drawn by tlod_device_draw ("vulkan") at W x H in front
 * of pure blue WITH back faces culled (cull_back_faces): through a crack in
 * a closed outward-oriented surface the camera then sees the background
 * (the far side's inside is culled) instead of a back face.
 *
 * A HOLE is a background pixel of the Vulkan image where the CPU reference
 * of the same draw list (tlod_cpu_tessellate: watertight by the unit tests),
 * drawn by gl_test.h's independent GL renderer with the stencil recording
 * facing, shows a front face at the pixel and at all 8 neighbours: inside
 * the closed silhouette, off its 1-pixel band (legitimately open
 * background such as the torus's hole is not solid in the reference).
 *
 * Detector check: cube_soft under PN at close cameras drawn from a copy of
 * the draw list with strip_count = 0 (the crease strips left out) must show
 * holes for at least one camera, or the detector is blind.
 * Hardware path (hardware_tessellation, no strips, no geomorphs; split
 * normals crack there by design, so smooth shapes only): no holes either,
 * including a dense frame (every patch at level 5) whose tessellated
 * vertices exceed lavapipe's 65,536 per draw, so batching is exercised.
 */
#include "gl_test.h"
#include "vk_test.h"

#define W 128
#define H 128
#define CAMERAS 30
#define MAX_LEVEL 5

typedef struct cracks_env {
  tlod_platform *gl, *vk;
  tlod_context* ctx;
  tlod_patterns* pat;
  tlod_device* dev;
  ref_renderer ref;
  uint8_t *rgba, *ref_rgba, *ref_stencil;
} cracks_env;

typedef struct hole_count {
  uint32_t holes, covered;
  int x, y; /* first hole (row 0 = top) */
} hole_count;

static void env_close(cracks_env* env) {
  if (env->gl) tlod_platform_bind(env->gl), ref_free(&env->ref);
  tlod_device_destroy(env->dev);
  tlod_patterns_destroy(env->pat);
  tlod_context_destroy(env->ctx);
  free(env->rgba), free(env->ref_rgba), free(env->ref_stencil);
  if (env->vk) tlod_platform_destroy(env->vk);
  if (env->gl) tlod_platform_destroy(env->gl);
  memset(env, 0, sizeof *env);
}

/* The GL platform (the reference) and the Vulkan one with a "vulkan"
 * device; false with the reason printed. */
static bool env_open(cracks_env* env, bool hardware) {
  char err[512] = "";
  memset(env, 0, sizeof *env);
  env->gl = gl_test_platform(W, H, err, sizeof err);
  env->vk = env->gl ? vk_test_platform(W, H, false, err, sizeof err) : NULL;
  if (!env->vk) return false;
  tlod_platform_bind(env->gl);
  env->rgba = malloc(4 * W * H), env->ref_rgba = malloc(4 * W * H), env->ref_stencil = malloc(W * H);
  if (!env->rgba || !env->ref_rgba || !env->ref_stencil || !ref_init(&env->ref)) return false;
  if (tlod_context_create(&(tlod_context_desc){.thread_count = 2}, &env->ctx) != TLOD_SUCCESS) return false;
  if (!(env->pat = new_patterns(env->ctx, MAX_LEVEL))) return false;
  tlod_device_vk_desc vk = vk_desc_of(env->vk);
  vk.hardware_tessellation = hardware;
  return (env->dev = new_vk_device(env->ctx, env->pat, "vk_cracks", vk)) != NULL;
}

/* The reference (complete draw list) into ref_rgba / ref_stencil (top row
 * first, like the platforms' reads). */
static bool draw_reference(cracks_env* env, const fixture* fx, const tlod_draw_list* dl, const tlod_view_desc* v) {
  tlod_cpu_mesh* m = realise(fx, dl);
  if (!m) return false;
  tlod_platform_bind(env->gl);
  clear_frame(W, H);
  gl_stencil_facing_begin();
  ref_upload(&env->ref, m);
  ref_draw(&env->ref, v);
  gl_stencil_facing_end();
  tlod_cpu_mesh_destroy(fx->ctx, m);
  uint8_t* bottom_first = env->ref_stencil;
  gl_read_stencil(W, H, bottom_first);
  for (uint32_t y = 0; y < H / 2; ++y) /* flip to top row first */
    for (uint32_t x = 0; x < W; ++x) {
      uint8_t t = bottom_first[y * W + x];
      bottom_first[y * W + x] = bottom_first[(H - 1 - y) * W + x];
      bottom_first[(H - 1 - y) * W + x] = t;
    }
  return tlod_platform_read_rgba(env->gl, env->ref_rgba);
}

/* The reference shows a front face at (x, y) and its 8 neighbours. */
static bool reference_solid(const cracks_env* env, uint32_t x, uint32_t y) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      int nx = (int)x + dx, ny = (int)y + dy;
      if (nx < 0 || ny < 0 || nx >= W || ny >= H) return false;
      size_t j = (size_t)ny * W + (size_t)nx;
      if (env->ref_stencil[j] != 1 || is_background(env->ref_rgba + 4 * j)) return false;
    }
  return true;
}

/* Draws dl (culling back faces) and counts holes against the reference of
 * reference_dl (the complete list). */
static hole_count find_holes(cracks_env* env, const fixture* fx, const tlod_draw_list* dl,
                             const tlod_draw_list* reference_dl, const camera* cam, bool* ok) {
  tlod_view_desc v = make_view(cam);
  hole_count hc = {.x = -1, .y = -1};
  one_draw d;
  one_draw_make(&d, fx->ds, dl, &v);
  d.item.cull_back_faces = true;
  *ok = vk_draw_frame(env->vk, env->dev, env->ctx, &d.desc, env->rgba) && draw_reference(env, fx, reference_dl, &v);
  if (!*ok) return hc;
  hc.covered = covered_pixels(env->rgba, W, H);
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      if (!is_background(env->rgba + 4 * ((size_t)y * W + x)) || !reference_solid(env, x, y)) continue;
      if (hc.holes++ == 0) hc.x = (int)x, hc.y = (int)y;
    }
  return hc;
}

static void report(const char* what, int k, const hole_count* hc, const camera* cam) {
  char buf[256];
  camera_print(cam, buf, sizeof buf);
  fprintf(stderr, "%s camera %d: %u hole pixels, first at (%d, %d) (row 0 = top); %s\n", what, k, hc->holes, hc->x,
          hc->y, buf);
}

/* CAMERAS random frames of one shape and type; returns frames with holes. */
static uint32_t random_frames(cracks_env* env, const shape* s, tlod_surface_type type, tlod_scheduler_desc sd,
                              uint64_t seed, int cameras, uint32_t* mixed) {
  fixture fx;
  if (!fixture_make(&fx, env->ctx, s, type, env->pat, env->dev)) return UINT32_MAX;
  tlod_scheduler* sch = new_scheduler(&fx, sd);
  shape_rng rng = {seed};
  uint32_t failures = 0;
  for (int k = 0; k < cameras && sch; ++k) {
    camera cam = random_camera(&rng, W, H);
    tlod_view_desc v = make_view(&cam);
    const tlod_draw_list* dl = plan(&fx, sch, &v, 16.0f);
    bool ok = dl != NULL;
    hole_count hc = ok ? find_holes(env, &fx, dl, dl, &cam, &ok) : (hole_count){0};
    if (!ok) failures = UINT32_MAX;
    if (!ok) break;
    uint32_t levels = 0;
    for (int l = 0; l <= TLOD_MAX_LEVEL; ++l)
      levels += dl->level_histogram[l] > 0;
    *mixed += levels > 1;
    if (hc.holes) failures++, report(s->name, k, &hc, &cam);
  }
  if (!sch) failures = UINT32_MAX;
  tlod_scheduler_destroy(sch);
  fixture_free(&fx);
  return failures;
}

TEST(test_no_holes) {
  cracks_env env;
  bool opened = env_open(&env, false);
  if (!opened) env_close(&env);
  CHECK_MSG(opened, "no GL (reference) + Vulkan devices (see above)");
  shape shapes[3] = {shape_icosphere(2), shape_torus(16, 10), shape_cube_soft()};
  const tlod_surface_type types[2] = {TLOD_SURFACE_PHONG, TLOD_SURFACE_PN};
  uint32_t failures = 0, mixed = 0;
  for (int si = 0; si < 3; ++si)
    for (int ti = 0; ti < 2; ++ti) {
      uint64_t seed = 0x5EED0000u + 10u * (uint64_t)si + (uint64_t)ti;
      uint32_t f = random_frames(&env, &shapes[si], types[ti], (tlod_scheduler_desc){.max_level = MAX_LEVEL}, seed,
                                 CAMERAS, &mixed);
      CHECK_MSG(f != UINT32_MAX, "%s %s: a frame failed (see above)", shapes[si].name, type_name(types[ti]));
      printf("  %-11s %-5s %d cameras: %u with holes\n", shapes[si].name, type_name(types[ti]), CAMERAS, f);
      failures += f;
    }
  for (int k = 0; k < 3; ++k)
    shape_free(&shapes[k]);
  env_close(&env);
  printf("  %d frames, %u with mixed levels, %u with holes\n", 6 * CAMERAS, mixed, failures);
  CHECK_MSG(mixed >= 3 * CAMERAS, "only %u of %d frames had mixed levels: strips not exercised", mixed, 6 * CAMERAS);
  CHECK_MSG(failures == 0, "%u frames with holes (see above)", failures);
}

/* The detector sees the cracks that strips close. */
TEST(test_detector_sees_missing_strips) {
  cracks_env env;
  bool opened = env_open(&env, false);
  if (!opened) env_close(&env);
  CHECK_MSG(opened, "no GL (reference) + Vulkan devices (see above)");
  shape cube = shape_cube_soft();
  fixture fx;
  CHECK(fixture_make(&fx, env.ctx, &cube, TLOD_SURFACE_PN, env.pat, env.dev));
  tlod_scheduler* sch = new_scheduler(&fx, (tlod_scheduler_desc){.max_level = MAX_LEVEL});
  CHECK(sch);
  const double eyes[4][3] = {{1.3, 1.1, 0.9}, {-1.2, 1.0, -1.1}, {0.4, -1.5, 0.8}, {-1.0, -1.1, 1.2}};
  uint32_t frames_with_holes = 0, removed = 0, full_holes = 0;
  for (int k = 0; k < 4; ++k) {
    camera cam = camera_look(eyes[k][0], eyes[k][1], eyes[k][2], 0, 0, 0, 50, W, H);
    tlod_view_desc v = make_view(&cam);
    const tlod_draw_list* dl = plan(&fx, sch, &v, 0.0f);
    CHECK(dl);
    bool ok;
    hole_count full = find_holes(&env, &fx, dl, dl, &cam, &ok);
    CHECK(ok);
    tlod_draw_list open = *dl;
    open.strip_count = 0, open.strip_triangles = 0;
    removed += dl->strip_count;
    hole_count hc = find_holes(&env, &fx, &open, dl, &cam, &ok);
    CHECK(ok);
    printf("  camera %d: %3u strips removed -> %4u hole pixels (%u with the strips)\n", k, dl->strip_count, hc.holes,
           full.holes);
    frames_with_holes += hc.holes > 0;
    full_holes += full.holes;
  }
  tlod_scheduler_destroy(sch);
  fixture_free(&fx);
  shape_free(&cube);
  env_close(&env);
  CHECK_MSG(removed > 0, "the draw lists had no strips to remove");
  CHECK_MSG(full_holes == 0, "%u hole pixels with the strips drawn", full_holes);
  CHECK_MSG(frames_with_holes >= 1, "no holes found with the strips removed: the detector is blind");
}

/* Every patch at level 5 (817 tessellated vertices each): the draws must be
 * split under lavapipe's 65,536; lost patches show as holes. */
static void dense_frame(cracks_env* env, const shape* s) {
  fixture fx;
  CHECK(fixture_make(&fx, env->ctx, s, TLOD_SURFACE_PN, env->pat, env->dev));
  tlod_scheduler_desc sd = {.policy = TLOD_POLICY_ERROR,
                            .epsilon_px = 1e-6f,
                            .max_level = MAX_LEVEL,
                            .morph = TLOD_MORPH_NONE,
                            .no_frustum_cull = true};
  tlod_scheduler* sch = new_scheduler(&fx, sd);
  CHECK(sch);
  camera cam = camera_look(1.7, -2.2, 1.1, 0, 0, 0, 40, W, H);
  tlod_view_desc v = make_view(&cam);
  const tlod_draw_list* dl = plan(&fx, sch, &v, 0.0f);
  CHECK(dl);
  bool ok;
  hole_count hc = find_holes(env, &fx, dl, dl, &cam, &ok);
  CHECK(ok);
  tlod_device_stats t = tlod_device_query_stats(env->dev);
  printf("  hardware path, dense: %u patches at level %d, %llu tessellated vertices in %u draw calls, %u pixels "
         "covered, %u hole pixels\n",
         dl->level_histogram[MAX_LEVEL], MAX_LEVEL, (unsigned long long)t.vertices, t.draw_calls, hc.covered, hc.holes);
  tlod_scheduler_destroy(sch);
  fixture_free(&fx);
  CHECK_MSG(t.vertices > 65536 && t.draw_calls > 1, "dense frame: %llu vertices in %u draws: batching not exercised",
            (unsigned long long)t.vertices, t.draw_calls);
  CHECK_MSG(hc.holes == 0 && hc.covered > 1000, "dense frame: %u hole pixels, %u covered", hc.holes, hc.covered);
}

TEST(test_hardware_path_no_holes) {
  cracks_env env;
  bool opened = env_open(&env, true);
  if (!opened) env_close(&env);
  CHECK_MSG(opened, "no GL (reference) + Vulkan hardware-tessellation devices (see above)");
  shape shapes[2] = {shape_icosphere(2), shape_torus(16, 10)};
  const tlod_surface_type types[2] = {TLOD_SURFACE_PHONG, TLOD_SURFACE_PN};
  uint32_t failures = 0, mixed = 0;
  tlod_scheduler_desc sd = {.max_level = MAX_LEVEL, .morph = TLOD_MORPH_NONE};
  for (int si = 0; si < 2; ++si)
    for (int ti = 0; ti < 2; ++ti) {
      uint64_t seed = 0xA4D00000u + 10u * (uint64_t)si + (uint64_t)ti;
      uint32_t f = random_frames(&env, &shapes[si], types[ti], sd, seed, 15, &mixed);
      CHECK_MSG(f != UINT32_MAX, "hardware path %s %s: a frame failed (see above)", shapes[si].name,
                type_name(types[ti]));
      failures += f;
    }
  CALL(dense_frame(&env, &shapes[0]));
  printf("  hardware path: 60 frames (%u with mixed levels), %u with holes\n", mixed, failures);
  for (int k = 0; k < 2; ++k)
    shape_free(&shapes[k]);
  env_close(&env);
  CHECK_MSG(failures == 0, "hardware path: %u frames with holes (see above)", failures);
}

int main(void) {
  RUN(test_detector_sees_missing_strips);
  RUN(test_no_holes);
  RUN(test_hardware_path_no_holes);
  VK_TEST_END();
}
