/*
 * gl_cracks_test.c -- the GL backend's images of closed meshes have no
 * holes at mixed levels (owned by the GL tests). Public API only.
 *
 * For icosphere(2), torus(16, 10) and cube_soft (split normals: creases
 * whose two sides' curves really differ), under Phong and PN, 50 random
 * cameras each (near, far and grazing, fields of view 30-75 degrees), one
 * scheduler per case with its defaults (adaptive levels, TIME geomorphs;
 * frames 16 ms apart, so patches are caught mid-morph), rendered by
 * tlod_device_draw at 128 x 128 in front of pure blue.
 *
 * A HOLE is a pixel where the backend shows something a closed surface
 * cannot show from outside:
 *   (a) background not 4-connected to the image border (flood fill from
 *       the border), or
 *   (b) a back face: with no culling, a crack in a closed mesh shows the
 *       inside of the far side rather than the background, so (a) alone
 *       only sees cracks that line up with another crack behind them. The
 *       stencil records the facing of the visible fragment (stencil state
 *       is not in the backend's save list, so it is left as the test set
 *       it). Outward-oriented shapes, counter-clockwise front faces.
 * Candidates are confirmed against the CPU reference of the same draw list
 * (watertight by the unit tests) drawn by gl_test.h's renderer with the same
 * stencil and depth: a candidate is a hole only when
 *   - the reference shows a front face at the pixel and all 8 neighbours
 *     (keeps legitimate enclosed background, the torus's hole, and the
 *     silhouette band out), and
 *   - what the backend shows there lies behind the reference's surface
 *     (eye depth > 1.002 x the reference's + 1e-4; background is at the far
 *     plane). A back-facing strip wall seen edge-on may own a pixel beside
 *     its shared edge with a front triangle at the same depth: a z-fight on
 *     a contour (measured once in 300 frames: torus PN, pixel 0.001 px from
 *     the edge, backend vertices bitwise equal across pattern and strip
 *     programs by transform feedback), counted and printed, not a hole.
 * The reference is only drawn when there are candidates.
 *
 * Negative control: cube_soft under PN at close cameras, drawn from a copy
 * of the draw list with strip_count = 0 (the crease strips left out), must
 * show holes for at least one camera, or the detector is blind.
 */
#include "gl_test.h"

#define W 128
#define H 128
#define CAMERAS 50
#define MAX_LEVEL 5

typedef struct gl_env {
  tlod_platform* platform;
  ref_renderer ref;
  uint8_t *rgba, *stencil, *ref_rgba, *ref_stencil, *reached;
  float *depth, *ref_depth; /* window depth [0, 1] */
  uint32_t* queue;
} gl_env;

typedef struct hole_count {
  uint32_t enclosed_candidates, back_candidates; /* (a), (b) before confirmation */
  uint32_t contour_back;                         /* (b) candidates at the reference's depth: z-fights, not holes */
  uint32_t enclosed, back;                       /* confirmed */
  int x, y;                                      /* first confirmed hole (row 0 = bottom) */
  bool reference_drawn;
} hole_count;

/* Draws dl with the backend (stencil records facing) and counts holes;
 * reference_dl is the complete draw list for the reference. */
static hole_count find_holes(gl_env* env, tlod_device* dev, const fixture* fx, const tlod_draw_list* dl,
                             const tlod_draw_list* reference_dl, const camera* cam, bool* ok) {
  tlod_view_desc view = make_view(cam);
  const tlod_view_desc* v = &view;
  hole_count hc;
  memset(&hc, 0, sizeof hc);
  hc.x = hc.y = -1;
  *ok = false;
  tlod_platform_bind(env->platform);
  clear_frame(W, H);
  gl_stencil_facing_begin();
  one_draw d;
  one_draw_make(&d, fx->ds, dl, v);
  tlod_result r = tlod_device_draw(dev, &d.desc);
  gl_stencil_facing_end();
  if (r != TLOD_SUCCESS) {
    fprintf(stderr, "tlod_device_draw: %s: %s\n", tlod_result_string(r), tlod_context_last_error(fx->ctx));
    return hc;
  }
  gl_read_rgba(W, H, env->rgba);
  gl_read_stencil(W, H, env->stencil);
  gl_read_depth(W, H, env->depth);
  flood_background(env->rgba, W, H, env->reached, env->queue);
  for (uint32_t i = 0; i < W * H; ++i) {
    bool bg = is_background(env->rgba + 4 * i);
    hc.enclosed_candidates += bg && !env->reached[i];
    hc.back_candidates += !bg && env->stencil[i] == 2;
  }
  if (hc.enclosed_candidates + hc.back_candidates > 0) {
    tlod_cpu_mesh* m = ref_draw_list(&env->ref, fx, reference_dl, v, W, H, true);
    if (!m) return hc;
    tlod_cpu_mesh_destroy(fx->ctx, m);
    gl_read_rgba(W, H, env->ref_rgba);
    gl_read_stencil(W, H, env->ref_stencil);
    gl_read_depth(W, H, env->ref_depth);
    hc.reference_drawn = true;
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        uint32_t i = y * W + x;
        bool bg = is_background(env->rgba + 4 * i);
        bool enclosed = bg && !env->reached[i], back = !bg && env->stencil[i] == 2;
        if (!(enclosed || back) || !reference_solid(env->ref_rgba, env->ref_stencil, W, H, x, y)) continue;
        /* Seen through: what the backend shows lies behind the reference's
         * surface (background is at the far plane). A back-facing strip
         * wall seen edge-on can own a pixel next to its shared edge with a
         * front triangle at the same depth (sub-pixel snapping; measured:
         * torus PN, 0.001 px from the edge, bitwise-equal vertices): a
         * z-fight on a contour, not a hole. Through a real crack the far
         * side is at least a tube's thickness deeper. */
        double seen = linear_depth(cam, env->depth[i]), surface = linear_depth(cam, env->ref_depth[i]);
        if (back && !(seen > surface * 1.002 + 1e-4)) {
          hc.contour_back++;
          continue;
        }
        hc.enclosed += enclosed;
        hc.back += back;
        if (hc.x < 0) hc.x = (int)x, hc.y = (int)y;
      }
  }
  *ok = true;
  return hc;
}

static bool env_init(gl_env* env, char* err, size_t err_size) {
  memset(env, 0, sizeof *env);
  env->platform = gl_test_platform(W, H, err, err_size);
  if (!env->platform) return false;
  env->rgba = malloc(4 * W * H);
  env->ref_rgba = malloc(4 * W * H);
  env->stencil = malloc(W * H);
  env->ref_stencil = malloc(W * H);
  env->reached = malloc(W * H);
  env->depth = malloc(sizeof *env->depth * W * H);
  env->ref_depth = malloc(sizeof *env->ref_depth * W * H);
  env->queue = malloc(sizeof *env->queue * W * H);
  if (!ref_init(&env->ref)) {
    snprintf(err, err_size, "reference renderer failed");
    return false;
  }
  return env->rgba && env->ref_rgba && env->stencil && env->ref_stencil && env->reached && env->queue && env->depth &&
         env->ref_depth;
}

static void env_free(gl_env* env) {
  ref_free(&env->ref);
  free(env->rgba);
  free(env->ref_rgba);
  free(env->stencil);
  free(env->ref_stencil);
  free(env->reached);
  free(env->depth);
  free(env->ref_depth);
  free(env->queue);
  tlod_platform_destroy(env->platform);
  memset(env, 0, sizeof *env);
}

/* What every test here starts with: the GL context and buffers, a tesslod
 * context, patterns to MAX_LEVEL and a "gl" device on them. Close with
 * cracks_close. */
static void cracks_open(gl_env* env, tlod_context** ctx, tlod_patterns** pat, tlod_device** dev,
                        tlod_device_gl_desc gl) {
  char err[512] = "";
  *ctx = NULL, *pat = NULL, *dev = NULL;
  CHECK_MSG(env_init(env, err, sizeof err), "cannot create a GL context: %s", err);
  CHECK(tlod_context_create(&(tlod_context_desc){.thread_count = 2}, ctx) == TLOD_SUCCESS);
  *pat = new_patterns(*ctx, MAX_LEVEL);
  CHECK(*pat);
  *dev = new_gl_device(*ctx, *pat, "gl_cracks", gl);
  CHECK(*dev);
}

static void cracks_close(gl_env* env, tlod_context* ctx, tlod_patterns* pat, tlod_device* dev) {
  tlod_device_destroy(dev);
  tlod_patterns_destroy(pat);
  tlod_context_destroy(ctx);
  env_free(env);
}

TEST(test_no_holes) {
  gl_env env;
  tlod_context* ctx;
  tlod_patterns* pat;
  tlod_device* dev;
  CALL(cracks_open(&env, &ctx, &pat, &dev, (tlod_device_gl_desc){0}));
  shape shapes[3] = {shape_icosphere(2), shape_torus(16, 10), shape_cube_soft()};
  const tlod_surface_type types[2] = {TLOD_SURFACE_PHONG, TLOD_SURFACE_PN};
  uint32_t frames = 0, failures = 0, mixed = 0, references = 0;
  uint64_t candidates = 0, strips = 0, contour_back = 0;
  for (int si = 0; si < 3; ++si)
    for (int ti = 0; ti < 2; ++ti) {
      fixture fx;
      CHECK(fixture_make(&fx, ctx, &shapes[si], types[ti], pat, dev));
      tlod_scheduler* sch = new_scheduler(&fx, (tlod_scheduler_desc){.max_level = MAX_LEVEL});
      CHECK(sch);
      shape_rng rng = {0x5EED0000u + 10u * (uint64_t)si + (uint64_t)ti};
      uint32_t case_failures = 0;
      for (int k = 0; k < CAMERAS; ++k) {
        camera cam = random_camera(&rng, W, H);
        tlod_view_desc v = make_view(&cam);
        const tlod_draw_list* dl = plan(&fx, sch, &v, 16.0f);
        CHECK(dl);
        uint32_t levels_used = 0;
        for (int l = 0; l <= TLOD_MAX_LEVEL; ++l)
          levels_used += dl->level_histogram[l] > 0;
        mixed += levels_used > 1;
        strips += dl->strip_count;
        bool ok;
        hole_count hc = find_holes(&env, dev, &fx, dl, dl, &cam, &ok);
        CHECK_MSG(ok, "%s %s camera %d: draw failed", shapes[si].name, type_name(types[ti]), k);
        frames++;
        candidates += hc.enclosed_candidates + hc.back_candidates;
        contour_back += hc.contour_back;
        references += hc.reference_drawn;
        if (hc.enclosed + hc.back > 0) {
          char buf[256];
          camera_print(&cam, buf, sizeof buf);
          fprintf(stderr,
                  "%s %s camera %d: %u hole pixels (%u enclosed background, %u back faces), first at (%d, %d) "
                  "(row 0 = bottom); %s; %u strips\n",
                  shapes[si].name, type_name(types[ti]), k, hc.enclosed + hc.back, hc.enclosed, hc.back, hc.x, hc.y,
                  buf, dl->strip_count);
          case_failures++;
        }
      }
      printf("  %-11s %-5s %d cameras: %u with holes\n", shapes[si].name, type_name(types[ti]), CAMERAS, case_failures);
      failures += case_failures;
      tlod_scheduler_destroy(sch);
      fixture_free(&fx);
    }
  printf("  %u frames (%u with mixed levels, %llu strips drawn): %llu candidate pixels, reference drawn for %u "
         "frames, %llu back-face pixels at the surface's depth (contour z-fights), %u frames with holes\n",
         frames, mixed, (unsigned long long)strips, (unsigned long long)candidates, references,
         (unsigned long long)contour_back, failures);
  for (int k = 0; k < 3; ++k)
    shape_free(&shapes[k]);
  cracks_close(&env, ctx, pat, dev);
  CHECK_MSG(mixed >= frames / 2, "only %u of %u frames had mixed levels: the test does not exercise strips", mixed,
            frames);
  CHECK_MSG(failures == 0, "%u frames with holes (see above)", failures);
}

/* The detector sees the cracks that strips close. */
TEST(test_detector_sees_missing_strips) {
  gl_env env;
  tlod_context* ctx;
  tlod_patterns* pat;
  tlod_device* dev;
  CALL(cracks_open(&env, &ctx, &pat, &dev, (tlod_device_gl_desc){0}));
  shape cube = shape_cube_soft();
  fixture fx;
  CHECK(fixture_make(&fx, ctx, &cube, TLOD_SURFACE_PN, pat, dev));
  tlod_scheduler* sch = new_scheduler(&fx, (tlod_scheduler_desc){.max_level = MAX_LEVEL});
  CHECK(sch);
  /* close cameras on the diagonals and faces */
  const double eyes[8][3] = {{1.3, 1.1, 0.9},   {-1.2, 1.0, -1.1}, {1.6, 0.2, 0.3},   {0.4, -1.5, 0.8},
                             {-1.0, -1.1, 1.2}, {0.2, 0.3, 1.7},   {1.1, -1.2, -1.0}, {-1.5, 0.6, 0.4}};
  uint32_t frames_with_holes = 0, most = 0;
  uint64_t total_enclosed = 0, total_back = 0, removed = 0;
  for (int k = 0; k < 8; ++k) {
    camera cam = camera_look(eyes[k][0], eyes[k][1], eyes[k][2], 0, 0, 0, 50, W, H);
    tlod_view_desc v = make_view(&cam);
    const tlod_draw_list* dl = plan(&fx, sch, &v, 0.0f);
    CHECK(dl);
    /* the full list is hole-free ... */
    bool ok;
    hole_count full = find_holes(&env, dev, &fx, dl, dl, &cam, &ok);
    CHECK(ok);
    CHECK_MSG(full.enclosed + full.back == 0, "camera %d: %u holes with strips", k, full.enclosed + full.back);
    /* ... the copy without strips is not */
    tlod_draw_list open = *dl;
    open.strip_count = 0;
    open.strip_triangles = 0;
    removed += dl->strip_count;
    hole_count hc = find_holes(&env, dev, &fx, &open, dl, &cam, &ok);
    CHECK(ok);
    printf("  camera %d: %3u strips removed -> %4u hole pixels (%u enclosed background, %u back faces; "
           "candidates %u + %u)\n",
           k, dl->strip_count, hc.enclosed + hc.back, hc.enclosed, hc.back, hc.enclosed_candidates, hc.back_candidates);
    frames_with_holes += hc.enclosed + hc.back > 0;
    total_enclosed += hc.enclosed;
    total_back += hc.back;
    if (hc.enclosed + hc.back > most) most = hc.enclosed + hc.back;
  }
  printf("  negative control: %u of 8 cameras show holes (%llu enclosed-background + %llu back-face pixels, at most "
         "%u in one frame) after removing %llu strips\n",
         frames_with_holes, (unsigned long long)total_enclosed, (unsigned long long)total_back, most,
         (unsigned long long)removed);
  tlod_scheduler_destroy(sch);
  fixture_free(&fx);
  shape_free(&cube);
  cracks_close(&env, ctx, pat, dev);
  CHECK_MSG(removed > 0, "the draw lists had no strips to remove");
  CHECK_MSG(frames_with_holes >= 1, "no holes found with the strips removed: the detector is blind");
}

/* The hardware-tessellation path (GL_PATCHES; tesslod/backend.h: each edge at the
 * finer side's level, no strips, no geomorphs, split-normal edges crack by
 * design) on the smooth shapes: no holes either. Close cameras make draws
 * that need batching under Mesa's 65,536 tessellated vertices per draw. */
TEST(test_hardware_path_no_holes) {
  gl_env env;
  tlod_context* ctx;
  tlod_patterns* pat;
  tlod_device* dev;
  CALL(cracks_open(&env, &ctx, &pat, &dev, (tlod_device_gl_desc){.hardware_tessellation = true}));
  shape shapes[2] = {shape_icosphere(2), shape_torus(16, 10)};
  const tlod_surface_type types[2] = {TLOD_SURFACE_PHONG, TLOD_SURFACE_PN};
  uint32_t frames = 0, failures = 0, most_calls = 0;
  uint64_t most_vertices = 0;
  for (int si = 0; si < 2; ++si)
    for (int ti = 0; ti < 2; ++ti) {
      fixture fx;
      CHECK(fixture_make(&fx, ctx, &shapes[si], types[ti], pat, dev));
      tlod_scheduler* sch = new_scheduler(&fx, (tlod_scheduler_desc){.max_level = MAX_LEVEL, .morph = TLOD_MORPH_NONE});
      CHECK(sch);
      shape_rng rng = {0xA4D00000u + 10u * (uint64_t)si + (uint64_t)ti};
      for (int k = 0; k < 20; ++k) {
        camera cam = random_camera(&rng, W, H);
        tlod_view_desc v = make_view(&cam);
        const tlod_draw_list* dl = plan(&fx, sch, &v, 16.0f);
        CHECK(dl);
        bool ok;
        hole_count hc = find_holes(&env, dev, &fx, dl, dl, &cam, &ok);
        CHECK_MSG(ok, "%s %s camera %d: draw failed", shapes[si].name, type_name(types[ti]), k);
        tlod_device_stats t = tlod_device_query_stats(dev);
        if (t.draw_calls > most_calls) most_calls = t.draw_calls;
        if (t.vertices > most_vertices) most_vertices = t.vertices;
        frames++;
        if (hc.enclosed + hc.back > 0) {
          char buf[256];
          camera_print(&cam, buf, sizeof buf);
          fprintf(stderr,
                  "hardware path %s %s camera %d: %u hole pixels (%u enclosed, %u back faces) first at (%d, %d); %s\n",
                  shapes[si].name, type_name(types[ti]), k, hc.enclosed + hc.back, hc.enclosed, hc.back, hc.x, hc.y,
                  buf);
          failures++;
        }
      }
      tlod_scheduler_destroy(sch);
      fixture_free(&fx);
    }
  /* dense: every patch at level 5 (817 tessellated vertices each, 261k in
   * one bucket), so the draws must be split; lost patches show as holes */
  {
    fixture fx;
    CHECK(fixture_make(&fx, ctx, &shapes[0], TLOD_SURFACE_PN, pat, dev));
    tlod_scheduler* sch = new_scheduler(&fx, (tlod_scheduler_desc){.policy = TLOD_POLICY_ERROR,
                                                                   .epsilon_px = 1e-6f,
                                                                   .max_level = MAX_LEVEL,
                                                                   .morph = TLOD_MORPH_NONE,
                                                                   .no_frustum_cull = true});
    CHECK(sch);
    camera cam = camera_look(1.7, -2.2, 1.1, 0, 0, 0, 40, W, H);
    tlod_view_desc v = make_view(&cam);
    const tlod_draw_list* dl = plan(&fx, sch, &v, 0.0f);
    CHECK(dl);
    bool ok;
    hole_count hc = find_holes(&env, dev, &fx, dl, dl, &cam, &ok);
    CHECK(ok);
    tlod_device_stats t = tlod_device_query_stats(dev);
    uint32_t covered = 0;
    for (uint32_t i = 0; i < W * H; ++i)
      covered += !is_background(env.rgba + 4 * i);
    printf("  hardware path, dense: %u patches at level %d, %llu tessellated vertices in %u draw calls, %u pixels "
           "covered, %u hole pixels\n",
           dl->level_histogram[MAX_LEVEL], MAX_LEVEL, (unsigned long long)t.vertices, t.draw_calls, covered,
           hc.enclosed + hc.back);
    CHECK_MSG(t.vertices > 65536 && t.draw_calls > 1, "dense frame: %llu vertices in %u draws: batching not exercised",
              (unsigned long long)t.vertices, t.draw_calls);
    CHECK_MSG(hc.enclosed + hc.back == 0,
              "dense frame: %u hole pixels (geometry past Mesa's 65,536-vertex limit lost?)", hc.enclosed + hc.back);
    tlod_scheduler_destroy(sch);
    fixture_free(&fx);
  }
  printf("  hardware path: %u frames, %u with holes; at most %llu tessellated vertices in %u draw calls in one frame\n",
         frames, failures, (unsigned long long)most_vertices, most_calls);
  for (int k = 0; k < 2; ++k)
    shape_free(&shapes[k]);
  cracks_close(&env, ctx, pat, dev);
  CHECK_MSG(failures == 0, "hardware path: %u frames with holes (see above)", failures);
}

/* A UV seam (shape_seam_sphere's copied column and pole copies, whose
 * TEXCOORD_0 differs across the edge while positions and normals are
 * bitwise equal) is smooth geometry: the attribute split opens no crack. */
TEST(test_uv_seam_no_holes) {
  gl_env env;
  tlod_context* ctx;
  tlod_patterns* pat;
  tlod_device* dev;
  CALL(cracks_open(&env, &ctx, &pat, &dev, (tlod_device_gl_desc){0}));
  enum { NLON = 20, SEAM_CAMERAS = 30 };
  uv_sphere us;
  CHECK(uv_sphere_make(&us, 10, NLON));
  const tlod_surface_type types[2] = {TLOD_SURFACE_PHONG, TLOD_SURFACE_PN};
  uint32_t failures = 0, mixed = 0;
  for (int ti = 0; ti < 2; ++ti) {
    fixture fx;
    CHECK(fixture_make_desc(&fx, ctx, &us.desc, types[ti], pat, dev));
    uint32_t seams = tlod_mesh_query_info(fx.mesh).attribute_seam_edges;
    CHECK_MSG(seams >= NLON, "only %u attribute seam edges: the mesh does not exercise seams", seams);
    tlod_scheduler* sch = new_scheduler(&fx, (tlod_scheduler_desc){.max_level = MAX_LEVEL});
    CHECK(sch);
    shape_rng rng = {0x5EA40000u + (uint64_t)ti};
    uint32_t case_failures = 0;
    for (int k = 0; k < SEAM_CAMERAS; ++k) {
      camera cam = random_camera(&rng, W, H);
      tlod_view_desc v = make_view(&cam);
      const tlod_draw_list* dl = plan(&fx, sch, &v, 16.0f);
      CHECK(dl);
      mixed += dl->strip_count > 0;
      bool ok;
      hole_count hc = find_holes(&env, dev, &fx, dl, dl, &cam, &ok);
      CHECK_MSG(ok, "seam sphere %s camera %d: draw failed", type_name(types[ti]), k);
      if (hc.enclosed + hc.back > 0) {
        fprintf(stderr, "seam sphere %s camera %d: %u hole pixels, first at (%d, %d)\n", type_name(types[ti]), k,
                hc.enclosed + hc.back, hc.x, hc.y);
        case_failures++;
      }
    }
    printf("  seam_sphere %-5s %d cameras (%u attribute seam edges): %u with holes\n", type_name(types[ti]),
           SEAM_CAMERAS, seams, case_failures);
    failures += case_failures;
    tlod_scheduler_destroy(sch);
    fixture_free(&fx);
  }
  uv_sphere_free(&us);
  cracks_close(&env, ctx, pat, dev);
  CHECK_MSG(mixed >= SEAM_CAMERAS, "only %u of %d frames had strips", mixed, 2 * SEAM_CAMERAS);
  CHECK_MSG(failures == 0, "%u frames with holes (see above)", failures);
}

int main(void) {
  RUN(test_uv_seam_no_holes);
  RUN(test_detector_sees_missing_strips);
  RUN(test_no_holes);
  RUN(test_hardware_path_no_holes);
  GL_TEST_END();
}
