/* The scheduler's fast path (fused SIMD passes, lod/src/scheduler_fast*)
 * against its oracle, tlod_scheduler_desc.reference_path: over sequences of
 * frames (morph history, a mesh update and refresh between frames), for
 * every SIMD level this processor has and 1, 2 and 3 threads, every policy,
 * morph mode and budget, orthographic and locked views, the draw lists are
 * bitwise equal (levels, e_max, vertex depths, instances, buckets, strips,
 * statistics; not stage_ms). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "shapes.h"
#include "tesslod/core.h"
#include "tesslod/lod.h"
#include "test.h"
#include "test_camera.h"
#include "test_fixture.h"
#include "test_lod.h"

#define MAX_LEVEL 6
#define FRAMES 7
#define MESHES 5

/* One mesh, its surface and patterns in one context. */
typedef struct world {
  tlod_context* ctx;
  tlod_mesh* mesh[MESHES];
  tlod_surface* surf[MESHES];
  tlod_patterns* pat;
} world;

typedef struct mesh_source {
  shape s;
  uint8_t* face_sizes; /* MIXED: some quads split in two triangles */
  uint32_t* indices;
  uint32_t index_count, face_count;
} mesh_source;

/* Every third quad of the quad sphere as two triangles. */
static mesh_source mixed_source(void) {
  mesh_source m = {.s = shape_quad_sphere(5)};
  uint32_t quads = m.s.index_count / 4;
  m.face_sizes = malloc(2 * quads);
  m.indices = malloc(sizeof(uint32_t) * 6 * quads);
  for (uint32_t q = 0; q < quads; ++q) {
    const uint32_t* c = m.s.indices + 4 * q;
    if (q % 3 == 0) {
      uint32_t t[6] = {c[0], c[1], c[2], c[0], c[2], c[3]};
      memcpy(m.indices + m.index_count, t, sizeof t);
      m.index_count += 6;
      m.face_sizes[m.face_count++] = 3, m.face_sizes[m.face_count++] = 3;
    } else {
      memcpy(m.indices + m.index_count, c, 4 * sizeof(uint32_t));
      m.index_count += 4;
      m.face_sizes[m.face_count++] = 4;
    }
  }
  return m;
}

static mesh_source g_src[MESHES];

static void sources_make(void) {
  g_src[0] = (mesh_source){.s = shape_torus(40, 24)};
  g_src[1] = (mesh_source){.s = shape_quad_sphere(8)};
  g_src[2] = mixed_source();
  g_src[3] = (mesh_source){.s = shape_cube_split()};
  g_src[4] = (mesh_source){.s = shape_open_grid(16)};
}

static void sources_free(void) {
  for (int m = 0; m < MESHES; ++m) {
    shape_free(&g_src[m].s);
    free(g_src[m].face_sizes);
    free(g_src[m].indices);
  }
}

static tlod_mesh_desc source_desc(const mesh_source* m) {
  tlod_mesh_desc d = shape_mesh_desc(&m->s);
  if (m->face_sizes) {
    d.face_type = TLOD_FACE_MIXED;
    d.face_sizes = m->face_sizes;
    d.face_count = m->face_count;
    d.indices = m->indices;
    d.index_count = m->index_count;
  }
  return d;
}

static void world_free(world* w) {
  for (int m = 0; m < MESHES; ++m) {
    tlod_surface_destroy(w->surf[m]);
    tlod_mesh_destroy(w->mesh[m]);
  }
  tlod_patterns_destroy(w->pat);
  tlod_context_destroy(w->ctx);
  memset(w, 0, sizeof *w);
}

/* Meshes 0 and 4 (triangles) PN, the others Phong (cube_split: creases). */
static bool world_make(world* w, tlod_simd simd, uint32_t threads) {
  memset(w, 0, sizeof *w);
  tlod_context_desc cd = {.thread_count = threads, .simd = simd};
  if (tlod_context_create(&cd, &w->ctx) != TLOD_SUCCESS) return false;
  tlod_result r = tlod_patterns_create(w->ctx, &(tlod_patterns_desc){.max_level = MAX_LEVEL}, &w->pat);
  for (int m = 0; m < MESHES && r == TLOD_SUCCESS; ++m) {
    tlod_mesh_desc md = source_desc(&g_src[m]);
    r = tlod_mesh_create(w->ctx, &md, &w->mesh[m]);
    tlod_surface_type type = m == 0 || m == 4 ? TLOD_SURFACE_PN : TLOD_SURFACE_PHONG;
    if (r == TLOD_SUCCESS) r = tlod_surface_create(w->ctx, w->mesh[m], &(tlod_surface_desc){.type = type}, &w->surf[m]);
  }
  if (r != TLOD_SUCCESS) {
    fprintf(stderr, "world: %s: %s\n", tlod_result_string(r), tlod_context_last_error(w->ctx));
    world_free(w);
  }
  return r == TLOD_SUCCESS;
}

/* Frame k's camera: from far to inside the shape, grazing, orthographic. */
static camera frame_camera(int k) {
  static const double eyes[FRAMES][3] = {{0, 0, 6},       {0.3, 1.2, 2.6}, {1.3, 0.2, 0.9}, {0.05, 0.02, 0.1},
                                         {2.0, 0.3, 0.0}, {0.2, 3.0, 0.4}, {0.9, 0.9, 0.9}};
  camera c = {.eye = {eyes[k][0], eyes[k][1], eyes[k][2]},
              .target = {0, 0, 0},
              .up = {0, 1, 0},
              .fovy = 1.0,
              .half_h = 1.5,
              .aspect = 4.0 / 3.0,
              .znear = 0.02,
              .zfar = 50,
              .ortho = k == 5,
              .width = 640,
              .height = 480};
  if (k == 3) c.target[0] = 1.0; /* inside, looking outwards */
  if (k == 5) c.up[0] = 1, c.up[1] = 0;
  return c;
}

/* The desc of case c: policy, morph mode, budget, epsilon. */
static tlod_scheduler_desc case_desc(int c, bool reference) {
  static const tlod_lod_policy policies[] = {TLOD_POLICY_FLAT, TLOD_POLICY_UNIFORM, TLOD_POLICY_SILHOUETTE,
                                             TLOD_POLICY_ERROR, TLOD_POLICY_HYBRID};
  static const tlod_morph_mode morphs[] = {TLOD_MORPH_NONE, TLOD_MORPH_TIME, TLOD_MORPH_CONTINUOUS};
  tlod_scheduler_desc d = {.policy = policies[c % 5],
                           .morph = morphs[(c / 5) % 3],
                           .triangle_budget = (c / 15) % 2 ? 6000u : 0u,
                           .epsilon_px = c % 4 == 1 ? 0.02f : 1.5f,
                           .max_level = MAX_LEVEL - (uint32_t)(c % 7 == 3),
                           .hybrid_relax = c % 2 ? 0.0f : 3.7f,
                           .silhouette_depth = c % 3 ? 0.0f : 23.0f,
                           .morph_ms = 40.0f,
                           .reference_path = reference};
  return d;
}
#define CASES 30

/* Views of frame k: one, or a second locked one (k odd) or free (k == 4). */
static uint32_t frame_views(int k, tlod_view_desc v[2]) {
  camera c = frame_camera(k), c2 = frame_camera((k + 2) % FRAMES);
  v[0] = make_view(&c);
  v[1] = make_view(&c2);
  v[1].lock_to_main = k % 2 == 1;
  return k % 2 == 1 || k == 4 ? 2u : 1u;
}

/* Positions of mesh m moved a little (a deforming mesh), then refreshed. */
static bool deform(world* w, int m, float t) {
  const shape* s = &g_src[m].s;
  float* p = malloc(sizeof(float) * 3 * s->vertex_count);
  for (uint32_t i = 0; i < 3 * s->vertex_count; ++i)
    p[i] = s->positions[i] * (1.0f + t * (float)(i % 5) * 0.01f);
  tlod_result r = tlod_mesh_update(w->mesh[m], p, 0, NULL, 0);
  free(p);
  if (r == TLOD_SUCCESS) r = tlod_surface_refresh(w->surf[m], NULL);
  return r == TLOD_SUCCESS;
}

#define WORLDS (4 * 3 + 1) /* every SIMD level x 1, 2, 3 threads, and the reference world 0 */

/* Runs case c on mesh m of every world over the frames, the reference
 * world (0: 1 thread, reference path) once; compares every fast world's
 * lists of every view with the reference's, frame by frame. */
static void run_case(world* w, int worlds, int m, int c) {
  tlod_scheduler* s[WORLDS] = {0};
  bool ok = true;
  for (int i = 0; i < worlds; ++i)
    ok = (s[i] = scheduler_create(w[i].ctx, w[i].surf[m], w[i].pat, case_desc(c, i == 0))) && ok;
  uint32_t vertices = tlod_mesh_vertex_count(tlod_surface_mesh(w[0].surf[m]));
  char why[96] = "create failed";
  int k = 0, at = 0;
  for (; ok && k < FRAMES; ++k) {
    for (int i = 0; ok && k == 4 && c % 5 == 4 && i < worlds; ++i)
      ok = deform(&w[i], m, 1.0f);
    tlod_view_desc views[2];
    tlod_frame_desc f = {.views = views, .view_count = frame_views(k, views), .dt_ms = 16.0f};
    for (int i = 0; ok && i < worlds; ++i)
      ok = tlod_scheduler_update(s[i], &f) == TLOD_SUCCESS;
    for (at = 1; ok && at < worlds; at += ok) /* stays at the world that differs */
      for (uint32_t v = 0; ok && v < f.view_count; ++v)
        ok = draw_lists_equal(tlod_scheduler_draw_list(s[0], v), tlod_scheduler_draw_list(s[at], v), vertices, why,
                              sizeof why);
  }
  for (int i = 0; c % 5 == 4 && i < worlds; ++i)
    if (!deform(&w[i], m, 0.0f)) ok = false, snprintf(why, sizeof why, "restore");
  for (int i = 0; i < worlds; ++i)
    tlod_scheduler_destroy(s[i]);
  tlod_context* ctx = w[at < worlds ? at : 0].ctx;
  CHECK_MSG(ok, "%s, %u threads, mesh %s, case %d, frame %d: %s", tlod_simd_name(tlod_context_simd(ctx)),
            tlod_context_query_desc(ctx).thread_count, g_src[m].s.name, c, k - 1, why);
}

/* The highest SIMD level this processor has. */
static tlod_simd best_simd(void) {
  tlod_context* ctx = NULL;
  if (tlod_context_create(NULL, &ctx) != TLOD_SUCCESS) return TLOD_SIMD_SCALAR;
  tlod_simd s = tlod_context_simd(ctx);
  tlod_context_destroy(ctx);
  return s;
}

TEST(test_fast_equals_reference) {
  world w[WORLDS];
  int worlds = 0;
  bool ok = world_make(&w[worlds++], TLOD_SIMD_SCALAR, 1);
  tlod_simd best = best_simd();
  for (tlod_simd simd = TLOD_SIMD_SCALAR; ok && simd <= best; simd++)
    for (uint32_t threads = 1; ok && threads <= 3; ++threads) {
      ok = world_make(&w[worlds], simd, threads);
      ok = ok && tlod_context_simd(w[worlds++].ctx) == simd;
    }
  for (int m = 0; ok && m < MESHES; ++m)
    for (int c = 0; c < CASES && ok; ++c) {
      int failed = _test_checks_failed;
      run_case(w, worlds, m, c);
      ok = failed == _test_checks_failed;
    }
  for (int i = 0; i < worlds; ++i)
    world_free(&w[i]);
  CHECK_MSG(ok, "a world failed (above)");
}

/* The levels must reach the refined range, or the equality above says little. */
TEST(test_cases_refine) {
  world w;
  CHECK(world_make(&w, TLOD_SIMD_DEFAULT, 2));
  tlod_scheduler* s = scheduler_create(w.ctx, w.surf[0], w.pat, case_desc(9, false)); /* HYBRID, TIME, eps 0.02 */
  CHECK(s);
  uint32_t hist[TLOD_MAX_LEVEL + 1] = {0}, culled = 0;
  for (int k = 0; k < FRAMES; ++k) {
    tlod_view_desc views[2];
    tlod_frame_desc f = {.views = views, .view_count = 1, .dt_ms = 1000.0f};
    frame_views(k, views);
    const tlod_draw_list* dl = scheduler_plan(w.ctx, s, &f);
    CHECK(dl);
    for (int l = 0; l <= TLOD_MAX_LEVEL; ++l)
      hist[l] += dl->level_histogram[l];
    culled += dl->culled;
  }
  tlod_scheduler_destroy(s);
  world_free(&w);
  uint32_t fine = hist[4] + hist[5] + hist[6];
  CHECK_MSG(hist[0] && hist[3] && fine && culled, "levels 0 %u, 3 %u, 4-6 %u, culled %u", hist[0], hist[3], fine,
            culled);
}

/* A group update under one budget: fast members equal reference members. */
TEST(test_group_budget) {
  world ref, w;
  CHECK(world_make(&ref, TLOD_SIMD_SCALAR, 1));
  CHECK(world_make(&w, TLOD_SIMD_DEFAULT, 3));
  tlod_scheduler *a[2], *b[2];
  for (int i = 0; i < 2; ++i) {
    a[i] = scheduler_create(ref.ctx, ref.surf[i], ref.pat, case_desc(4 + 5 * i, true));
    b[i] = scheduler_create(w.ctx, w.surf[i], w.pat, case_desc(4 + 5 * i, false));
  }
  bool ok = a[0] && a[1] && b[0] && b[1];
  char why[96] = "failed";
  for (int k = 0; ok && k < FRAMES; ++k) {
    tlod_view_desc views[2];
    tlod_frame_desc f[2] = {{.views = views, .view_count = frame_views(k, views), .dt_ms = 16.0f}};
    f[1] = f[0];
    ok = tlod_scheduler_update_group(a, f, 2, 9000) == TLOD_SUCCESS &&
         tlod_scheduler_update_group(b, f, 2, 9000) == TLOD_SUCCESS;
    for (int i = 0; ok && i < 2; ++i)
      for (uint32_t v = 0; ok && v < f[0].view_count; ++v)
        ok = draw_lists_equal(tlod_scheduler_draw_list(a[i], v), tlod_scheduler_draw_list(b[i], v),
                              tlod_mesh_vertex_count(tlod_surface_mesh(ref.surf[i])), why, sizeof why);
  }
  for (int i = 0; i < 2; ++i) {
    tlod_scheduler_destroy(a[i]);
    tlod_scheduler_destroy(b[i]);
  }
  world_free(&w);
  world_free(&ref);
  CHECK_MSG(ok, "%s", why);
}

/* Camera of test_culled_blocks' frame k: above one side of the torus
 * with a narrow view (whole blocks of patches culled), or far (all in view). */
static tlod_view_desc culling_view(int k) {
  bool close = k % 3 == 0;
  camera c = {.eye = {close ? 1.0 : 0, 0, close ? 2.0 : 6},
              .target = {close ? 1.0 : 0, 0, 0},
              .up = {0, 1, 0},
              .fovy = close ? 0.5 : 1.0,
              .aspect = 4.0 / 3.0,
              .znear = 0.02,
              .zfar = 50,
              .width = 640,
              .height = 480};
  return make_view(&c);
}

/* Blocks of 256 consecutive patches (the fast pass's) all culled. */
static uint32_t culled_blocks(const tlod_draw_list* dl) {
  uint32_t blocks = 0;
  for (uint32_t b = 0; b + 256 <= dl->patch_count; b += 256) {
    bool all = true;
    for (uint32_t f = b; f < b + 256; f++)
      all = all && dl->levels[f] < 0;
    blocks += all;
  }
  return blocks;
}

static bool culled_e_max_zero(const tlod_draw_list* dl) {
  bool ok = true;
  for (uint32_t f = 0; f < dl->patch_count; f++)
    ok = ok && (dl->levels[f] >= 0 || dl->e_max[f] == 0.0f);
  return ok;
}

/* Whether every patch culled before (levels) and visible in after is at the
 * level of a scheduler without history (fresh). */
static bool entered_at_goal(const int8_t* before, const tlod_draw_list* after, const tlod_draw_list* fresh,
                            uint32_t* entered) {
  bool ok = true;
  for (uint32_t f = 0; f < after->patch_count; f++) {
    if (before[f] >= 0 || after->levels[f] < 0) continue;
    ++*entered;
    ok = ok && after->levels[f] == fresh->levels[f];
  }
  return ok;
}

/* Whole blocks culled, then in view: fast equals reference at every SIMD
 * level and thread count; culled patches have e_max 0 and no morph
 * history (back in view they appear at their goal, as on a first frame). */
TEST(test_culled_blocks) {
  world w[WORLDS];
  int worlds = 0;
  bool ok = world_make(&w[worlds++], TLOD_SIMD_SCALAR, 1);
  tlod_simd best = best_simd();
  for (tlod_simd simd = TLOD_SIMD_SCALAR; ok && simd <= best; simd++)
    for (uint32_t threads = 1; ok && threads <= 3; ++threads)
      ok = world_make(&w[worlds++], simd, threads);
  tlod_scheduler* s[WORLDS] = {0};
  tlod_scheduler_desc d = case_desc(8, true); /* ERROR, TIME */
  for (int i = 0; ok && i < worlds; ++i, d.reference_path = false)
    ok = (s[i] = scheduler_create(w[i].ctx, w[i].surf[0], w[i].pat, d)) != NULL;
  uint32_t vertices = tlod_mesh_vertex_count(tlod_surface_mesh(w[0].surf[0])), blocks = 0, entered = 0;
  char why[96] = "create or update failed";
  int8_t* before = malloc(tlod_mesh_face_count(tlod_surface_mesh(w[0].surf[0])));
  for (int k = 0; ok && k < 5; ++k) {
    tlod_view_desc v = culling_view(k);
    tlod_frame_desc f = {.views = &v, .view_count = 1, .dt_ms = 16.0f};
    for (int i = 0; ok && i < worlds; ++i)
      ok = tlod_scheduler_update(s[i], &f) == TLOD_SUCCESS;
    const tlod_draw_list* ref = tlod_scheduler_draw_list(s[0], 0);
    for (int i = 1; ok && i < worlds; ++i)
      ok = draw_lists_equal(ref, tlod_scheduler_draw_list(s[i], 0), vertices, why, sizeof why);
    if (ok && k % 3 == 0) blocks += culled_blocks(ref);
    tlod_scheduler* fresh = ok && k % 3 == 1 ? scheduler_create(w[0].ctx, w[0].surf[0], w[0].pat, d) : NULL;
    const tlod_draw_list* fl = fresh ? scheduler_plan(w[0].ctx, fresh, &f) : NULL;
    if (ok) CHECK_MSG(culled_e_max_zero(ref), "frame %d: a culled patch has e_max > 0", k);
    if (fl) CHECK_MSG(entered_at_goal(before, ref, fl, &entered), "frame %d: a patch entered off its goal", k);
    tlod_scheduler_destroy(fresh);
    memcpy(before, ref->levels, ref->patch_count);
  }
  free(before);
  for (int i = 0; i < worlds; ++i) {
    tlod_scheduler_destroy(s[i]);
    world_free(&w[i]);
  }
  CHECK_MSG(ok, "%s", why);
  CHECK_MSG(blocks > 0 && entered > 0, "%u whole blocks culled, %u patches entered the view", blocks, entered);
}

/* ---- clusters: blocks all in, all out, half in view, the eye inside one ---- */

/* A torus big enough for many blocks (FAST_BLOCK patches) and vertex chunks. */
typedef struct big_world {
  tlod_context* ctx;
  shape s;
  tlod_mesh* mesh;
  tlod_surface* surf;
  tlod_patterns* pat;
} big_world;

static bool big_make(big_world* w, tlod_simd simd, uint32_t threads) {
  memset(w, 0, sizeof *w);
  w->s = shape_torus(200, 60); /* 24000 triangles, 12000 vertices */
  tlod_context_desc cd = {.thread_count = threads, .simd = simd};
  tlod_mesh_desc md = shape_mesh_desc(&w->s);
  tlod_result r = tlod_context_create(&cd, &w->ctx);
  if (r == TLOD_SUCCESS) r = tlod_patterns_create(w->ctx, &(tlod_patterns_desc){.max_level = MAX_LEVEL}, &w->pat);
  if (r == TLOD_SUCCESS) r = tlod_mesh_create(w->ctx, &md, &w->mesh);
  if (r == TLOD_SUCCESS)
    r = tlod_surface_create(w->ctx, w->mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_PHONG}, &w->surf);
  return r == TLOD_SUCCESS;
}

static void big_free(big_world* w) {
  tlod_surface_destroy(w->surf);
  tlod_mesh_destroy(w->mesh);
  tlod_patterns_destroy(w->pat);
  tlod_context_destroy(w->ctx);
  shape_free(&w->s);
}

/* Frame k: far (every block in view), close and narrow over one side (blocks
 * half in view and out), looking away (every block out), the eye on the
 * tube (inside its blocks' spheres), the mesh deformed (SoA and spheres
 * rebuilt), and again. */
static tlod_view_desc cluster_view(int k) {
  static const double eyes[6][3] = {{0, 0, 6}, {1, 0, 1.5}, {0, 0, 6}, {1.0, 0, 0.405}, {1, 0.2, 1.2}, {0, 0, 6}};
  static const double targets[6][3] = {{0, 0, 0}, {1, 0, 0}, {0, 0, 12}, {0, 1, 0.405}, {1, 0.2, 0}, {0, 0, 0}};
  camera c = {.up = {0, 1, 0},
              .fovy = k == 1 || k == 4 ? 0.4 : 1.0,
              .aspect = 4.0 / 3.0,
              .znear = 0.01,
              .zfar = 50,
              .width = 640,
              .height = 480};
  memcpy(c.eye, eyes[k], sizeof c.eye);
  memcpy(c.target, targets[k], sizeof c.target);
  if (k == 3) c.up[0] = 0, c.up[1] = 0, c.up[2] = 1;
  return make_view(&c);
}

static bool big_deform(big_world* w, float t) {
  float* p = malloc(sizeof(float) * 3 * w->s.vertex_count);
  for (uint32_t i = 0; i < 3 * w->s.vertex_count; ++i)
    p[i] = w->s.positions[i] * (1.0f + t * (float)(i % 7) * 0.004f);
  tlod_result r = tlod_mesh_update(w->mesh, p, 0, NULL, 0);
  free(p);
  return r == TLOD_SUCCESS && tlod_surface_refresh(w->surf, NULL) == TLOD_SUCCESS;
}

/* Counts of frames with every patch in view, every patch culled, and some of each. */
static void count_culling(const tlod_draw_list* dl, uint32_t seen[3]) {
  seen[dl->culled == 0 ? 0 : dl->culled == dl->patch_count ? 1 : 2]++;
}

static bool cluster_frame(big_world* w, tlod_scheduler** s, int worlds, int k, uint32_t seen[3], char* why, size_t n) {
  bool ok = true;
  for (int i = 0; ok && k == 4 && i < worlds; ++i)
    ok = big_deform(&w[i], 1.0f);
  tlod_view_desc v = cluster_view(k);
  tlod_frame_desc f = {.views = &v, .view_count = 1, .dt_ms = 16.0f};
  for (int i = 0; ok && i < worlds; ++i)
    ok = tlod_scheduler_update(s[i], &f) == TLOD_SUCCESS;
  const tlod_draw_list* ref = ok ? tlod_scheduler_draw_list(s[0], 0) : NULL;
  if (ref) count_culling(ref, seen);
  for (int i = 1; ok && i < worlds; ++i) {
    const tlod_draw_list* dl = tlod_scheduler_draw_list(s[i], 0);
    ok = draw_lists_equal(ref, dl, 0, why, n);
    if (ok && !(ok = visible_depths_equal(ref, dl, w[0].mesh))) snprintf(why, n, "visible vertex depths differ");
    if (!ok) snprintf(why + strlen(why), n - strlen(why), " (world %d)", i);
  }
  return ok;
}

/* Fast equals reference at every SIMD level, 1 and 2 threads, through the
 * cluster cases, for the ERROR, HYBRID and SILHOUETTE policies. */
TEST(test_cluster_views) {
  big_world w[9];
  int worlds = 0;
  bool ok = big_make(&w[worlds++], TLOD_SIMD_SCALAR, 1);
  for (tlod_simd simd = TLOD_SIMD_SCALAR; ok && simd <= best_simd(); simd++)
    for (uint32_t threads = 1; ok && threads <= 2; ++threads)
      ok = big_make(&w[worlds++], simd, threads);
  static const int cases[] = {8, 9, 2};
  uint32_t seen[3] = {0, 0, 0};
  char why[128] = "create failed";
  for (size_t c = 0; ok && c < sizeof cases / sizeof cases[0]; ++c) {
    tlod_scheduler* s[9] = {0};
    for (int i = 0; ok && i < worlds; ++i)
      ok = (s[i] = scheduler_create(w[i].ctx, w[i].surf, w[i].pat, case_desc(cases[c], i == 0))) != NULL;
    for (int k = 0; ok && k < 6; ++k)
      if (!(ok = cluster_frame(w, s, worlds, k, seen, why, sizeof why)))
        snprintf(why + strlen(why), sizeof why - strlen(why), ", case %d frame %d", cases[c], k);
    for (int i = 0; i < worlds; ++i) {
      tlod_scheduler_destroy(s[i]);
      ok = big_deform(&w[i], 0.0f) && ok;
    }
  }
  for (int i = 0; i < worlds; ++i)
    big_free(&w[i]);
  CHECK_MSG(ok, "%s", why);
  CHECK_MSG(seen[0] && seen[1] && seen[2], "frames all in view %u, all culled %u, partly %u", seen[0], seen[1],
            seen[2]);
}

/* The ERROR ladder on epsilons at rounding ties: epsilon = a visible
 * patch's e_max of the same view, fl(bound * scale), which the exact
 * product exceeds by under an ulp whenever the float product rounded down.
 * The fast path's ladder must decide every such patch as the reference's
 * exact double products do (a ladder in float rounded to nearest fails
 * here), also with flush-to-zero and denormals-are-zero set, as some
 * engines run. */
static bool ties_agree(world w[2], uint32_t tries, char* why, size_t n) {
  camera c = frame_camera(1);
  tlod_view_desc v = make_view(&c);
  tlod_frame_desc f = {.views = &v, .view_count = 1, .dt_ms = 16.0f};
  tlod_scheduler_desc d = {.policy = TLOD_POLICY_ERROR,
                           .morph = TLOD_MORPH_NONE,
                           .epsilon_px = 0.5f,
                           .max_level = MAX_LEVEL,
                           .reference_path = true};
  tlod_scheduler* probe = scheduler_create(w[0].ctx, w[0].surf[1], w[0].pat, d);
  const tlod_draw_list* dl = probe ? scheduler_plan(w[0].ctx, probe, &f) : NULL;
  bool ok = dl != NULL;
  for (uint32_t p = 0, done = 0; ok && p < dl->patch_count && done < tries; p += 7) {
    if (dl->levels[p] < 0 || !(dl->e_max[p] > 0.0f)) continue;
    d.epsilon_px = dl->e_max[p], done++;
    tlod_scheduler* s[2];
    for (int i = 0; i < 2; ++i) {
      d.reference_path = i == 0;
      s[i] = scheduler_create(w[i].ctx, w[i].surf[1], w[i].pat, d);
    }
    ok = s[0] && s[1] && scheduler_plan(w[0].ctx, s[0], &f) && scheduler_plan(w[1].ctx, s[1], &f) &&
         draw_lists_equal(tlod_scheduler_draw_list(s[0], 0), tlod_scheduler_draw_list(s[1], 0), 0, why, n);
    if (!ok) snprintf(why + strlen(why), n - strlen(why), " (epsilon %.9g, the e_max of patch %u)", d.epsilon_px, p);
    tlod_scheduler_destroy(s[0]);
    tlod_scheduler_destroy(s[1]);
  }
  tlod_scheduler_destroy(probe);
  return ok;
}

TEST(test_ladder_ties) {
  world w[2];
  char why[256] = "";
  bool ok = world_make(&w[0], TLOD_SIMD_SCALAR, 1) && world_make(&w[1], best_simd(), 2);
  CHECK_MSG(ok && ties_agree(w, 64, why, sizeof why), "%s: %s", tlod_simd_name(best_simd()), why);
#if defined(__x86_64__)
  unsigned csr = _mm_getcsr();
  _mm_setcsr(csr | _MM_FLUSH_ZERO_ON | 0x0040u); /* FTZ and DAZ, as some engines run */
  CHECK_MSG(ok && ties_agree(w, 16, why, sizeof why), "%s with FTZ and DAZ: %s", tlod_simd_name(best_simd()), why);
  _mm_setcsr(csr);
#endif
  world_free(&w[0]);
  world_free(&w[1]);
}

int main(void) {
  sources_make();
  RUN(test_cases_refine);
  RUN(test_fast_equals_reference);
  RUN(test_group_budget);
  RUN(test_culled_blocks);
  RUN(test_cluster_views);
  RUN(test_ladder_ties);
  sources_free();
  TEST_END();
}
