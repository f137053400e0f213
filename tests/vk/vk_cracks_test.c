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
 * of pure blue, with a fragment hook that writes what the test needs
 * instead of shading: red = facing (255 front, 128 back; never the
 * background's 0), green, blue = the window depth in 16 bits (the platform
 * has no stencil and reads back colour only).
 *
 * A HOLE is a pixel where the device shows something a closed surface
 * cannot show from outside, as in tests/gl/gl_cracks_test.c:
 *   (a) background not 4-connected to the image border, or
 *   (b) a back face (with no culling, a crack shows the far side's inside);
 * confirmed against the CPU reference of the same draw list
 * (tlod_cpu_tessellate: watertight by the unit tests) drawn by gl_test.h's
 * independent GL renderer with the stencil recording facing: the reference
 * shows a front face at the pixel and all 8 neighbours (keeps the torus's
 * hole and the silhouette band out), and what the device shows lies behind
 * the reference's surface (eye depth > 1.002 x the reference's + 1e-4;
 * 16-bit depth is fine enough for that margin here): a back face at the
 * surface's depth is a fold or z-fight on a contour (counted, printed, not
 * a hole), through a real crack the far side is a tube's thickness deeper.
 * Detector check: cube_soft under PN at close cameras drawn from a copy of
 * the draw list with strip_count = 0 (the crease strips left out) must show
 * holes for at least one camera, or the detector is blind.
 * Hardware path (hardware_tessellation, no strips, no geomorphs; split
 * normals crack there by design, so smooth shapes only): no holes either,
 * including a dense frame (every patch at level 5) whose tessellated
 * vertices exceed lavapipe's 65,536 per draw, so batching is exercised.
 */
#include "vk_gl_test.h"

#define W 128
#define H 128
#define CAMERAS 30
#define MAX_LEVEL 5

typedef struct cracks_env {
  vk_gl_env b;
  tlod_device* dev;
  uint8_t *rgba, *ref_rgba, *ref_stencil, *reached;
  float* ref_depth;
  uint32_t* queue;
} cracks_env;

typedef struct hole_count {
  uint32_t holes, covered, candidates, contour_back;
  int x, y; /* first hole (row 0 = top) */
} hole_count;

/* Facing and window depth instead of shading (see the top). */
static const char* const k_probe_hook =
    "vec4 tlod_shade(tlod_fragment f) {\n"
    "  uint q = uint(round(clamp(gl_FragCoord.z, 0.0, 1.0) * 65535.0));\n"
    "  return vec4(f.front_facing ? 1.0 : 128.0 / 255.0, float(q >> 8) / 255.0, float(q & 255u) / 255.0, 1.0);\n"
    "}\n";

static bool probe_back(const uint8_t* px) { return px[0] < 192; }
static float probe_depth(const uint8_t* px) { return (float)(px[1] * 256 + px[2]) / 65535.0f; }

static void env_close(cracks_env* env) {
  if (env->b.vk) tlod_platform_finish(env->b.vk);
  tlod_device_destroy(env->dev);
  free(env->rgba), free(env->ref_rgba), free(env->ref_stencil), free(env->reached), free(env->ref_depth);
  free(env->queue);
  vk_gl_close(&env->b);
  memset(env, 0, sizeof *env);
}

/* The platforms and a "vulkan" device drawing through the probe hook;
 * false with the reason printed. */
static bool env_open(cracks_env* env, bool hardware) {
  memset(env, 0, sizeof *env);
  if (!vk_gl_open(&env->b, W, H, MAX_LEVEL)) return false;
  env->rgba = malloc(4 * W * H), env->ref_rgba = malloc(4 * W * H), env->ref_stencil = malloc(W * H);
  env->reached = malloc(W * H), env->ref_depth = malloc(sizeof(float) * W * H);
  env->queue = malloc(sizeof(uint32_t) * W * H);
  if (!env->rgba || !env->ref_rgba || !env->ref_stencil || !env->reached || !env->ref_depth || !env->queue)
    return false;
  tlod_device_vk_desc vk = vk_desc_of(env->b.vk);
  vk.hardware_tessellation = hardware;
  vk.fragment_hook = k_probe_hook;
  return (env->dev = new_vk_device(env->b.ctx, env->b.pat, "vk_cracks", vk)) != NULL;
}

/* Rows of `row` bytes, bottom first (GL reads) -> top first. */
static void flip_rows(void* data, size_t row) {
  uint8_t *d = data, t[4 * W];
  for (uint32_t y = 0; y < H / 2; ++y) {
    memcpy(t, d + y * row, row);
    memcpy(d + y * row, d + (H - 1 - y) * row, row);
    memcpy(d + (H - 1 - y) * row, t, row);
  }
}

/* The reference (complete draw list) into ref_rgba / ref_stencil /
 * ref_depth, top row first like the platforms' reads. */
static bool draw_reference(cracks_env* env, const fixture* fx, const tlod_draw_list* dl, const tlod_view_desc* v) {
  tlod_platform_bind(env->b.gl);
  tlod_cpu_mesh* m = ref_draw_list(&env->b.ref, fx, dl, v, W, H, true);
  if (!m) return false;
  tlod_cpu_mesh_destroy(fx->ctx, m);
  gl_read_stencil(W, H, env->ref_stencil);
  gl_read_depth(W, H, env->ref_depth);
  flip_rows(env->ref_stencil, W);
  flip_rows(env->ref_depth, sizeof(float) * W);
  return tlod_platform_read_rgba(env->b.gl, env->ref_rgba);
}

/* Confirms the candidates of the device image against the reference. */
static void confirm(cracks_env* env, const camera* cam, hole_count* hc) {
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      uint32_t i = y * W + x;
      const uint8_t* px = env->rgba + 4 * i;
      bool bg = is_background(px), enclosed = bg && !env->reached[i], back = !bg && probe_back(px);
      if (!(enclosed || back) || !reference_solid(env->ref_rgba, env->ref_stencil, W, H, x, y)) continue;
      double seen = linear_depth(cam, probe_depth(px)), surface = linear_depth(cam, env->ref_depth[i]);
      if (back && !(seen > surface * 1.002 + 1e-4)) {
        hc->contour_back++;
        continue;
      }
      if (hc->holes++ == 0) hc->x = (int)x, hc->y = (int)y;
    }
}

/* Draws dl and counts holes against the reference of reference_dl (the
 * complete list; drawn only when there are candidates). */
static hole_count find_holes(cracks_env* env, const fixture* fx, const tlod_draw_list* dl,
                             const tlod_draw_list* reference_dl, const camera* cam, bool* ok) {
  tlod_view_desc v = make_view(cam);
  hole_count hc = {.x = -1, .y = -1};
  one_draw d;
  one_draw_make(&d, fx->ds, dl, &v);
  *ok = vk_draw_frame(env->b.vk, env->dev, env->b.ctx, &d.desc, env->rgba);
  if (!*ok) return hc;
  hc.covered = covered_pixels(env->rgba, W, H);
  flood_background(env->rgba, W, H, env->reached, env->queue);
  for (uint32_t i = 0; i < W * H; ++i) {
    bool bg = is_background(env->rgba + 4 * i);
    hc.candidates += (bg && !env->reached[i]) || (!bg && probe_back(env->rgba + 4 * i));
  }
  if (hc.candidates == 0) return hc;
  *ok = draw_reference(env, fx, reference_dl, &v);
  if (*ok) confirm(env, cam, &hc);
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
                              uint64_t seed, int cameras, uint32_t* mixed, uint64_t* contour_back) {
  fixture fx;
  if (!fixture_make(&fx, env->b.ctx, s, type, env->b.pat, env->dev)) return UINT32_MAX;
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
    *contour_back += hc.contour_back;
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
  uint64_t contour = 0;
  for (int si = 0; si < 3; ++si)
    for (int ti = 0; ti < 2; ++ti) {
      uint64_t seed = 0x5EED0000u + 10u * (uint64_t)si + (uint64_t)ti;
      uint32_t f = random_frames(&env, &shapes[si], types[ti], (tlod_scheduler_desc){.max_level = MAX_LEVEL}, seed,
                                 CAMERAS, &mixed, &contour);
      CHECK_MSG(f != UINT32_MAX, "%s %s: a frame failed (see above)", shapes[si].name, type_name(types[ti]));
      printf("  %-11s %-5s %d cameras: %u with holes\n", shapes[si].name, type_name(types[ti]), CAMERAS, f);
      failures += f;
    }
  for (int k = 0; k < 3; ++k)
    shape_free(&shapes[k]);
  env_close(&env);
  CALL(vk_check_no_messages());
  printf("  %d frames, %u with mixed levels, %llu back-face pixels at the surface's depth (contour folds), %u with "
         "holes\n",
         6 * CAMERAS, mixed, (unsigned long long)contour, failures);
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
  CHECK(fixture_make(&fx, env.b.ctx, &cube, TLOD_SURFACE_PN, env.b.pat, env.dev));
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
  CALL(vk_check_no_messages());
  CHECK_MSG(removed > 0, "the draw lists had no strips to remove");
  CHECK_MSG(full_holes == 0, "%u hole pixels with the strips drawn", full_holes);
  CHECK_MSG(frames_with_holes >= 1, "no holes found with the strips removed: the detector is blind");
}

/* Every patch at level 5 (817 tessellated vertices each): the draws must be
 * split under lavapipe's 65,536; lost patches show as holes. */
static void dense_frame(cracks_env* env, const shape* s) {
  fixture fx;
  CHECK(fixture_make(&fx, env->b.ctx, s, TLOD_SURFACE_PN, env->b.pat, env->dev));
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
  uint64_t contour = 0;
  tlod_scheduler_desc sd = {.max_level = MAX_LEVEL, .morph = TLOD_MORPH_NONE};
  for (int si = 0; si < 2; ++si)
    for (int ti = 0; ti < 2; ++ti) {
      uint64_t seed = 0xA4D00000u + 10u * (uint64_t)si + (uint64_t)ti;
      uint32_t f = random_frames(&env, &shapes[si], types[ti], sd, seed, 15, &mixed, &contour);
      CHECK_MSG(f != UINT32_MAX, "hardware path %s %s: a frame failed (see above)", shapes[si].name,
                type_name(types[ti]));
      failures += f;
    }
  CALL(dense_frame(&env, &shapes[0]));
  printf("  hardware path: 60 frames (%u with mixed levels), %u with holes\n", mixed, failures);
  for (int k = 0; k < 2; ++k)
    shape_free(&shapes[k]);
  env_close(&env);
  CALL(vk_check_no_messages());
  CHECK_MSG(failures == 0, "hardware path: %u frames with holes (see above)", failures);
}

int main(void) {
  RUN(test_detector_sees_missing_strips);
  RUN(test_no_holes);
  RUN(test_hardware_path_no_holes);
  VK_TEST_END();
}
