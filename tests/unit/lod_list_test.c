/*
 * lod_list_test.c -- the scheduler's draw-list build (tesslod/lod.h:
 * tlod_draw_list) over thread counts and engine job systems, and its
 * temporal coherence (tlod_draw_list.generation).
 * Reads private state: none (public API only).
 *
 * References. The one-thread list is checked against what is computed here
 * from its per-patch levels and e_max alone (bucket order, patch order in
 * a bucket, strips in patch order, a strip on every edge between visible
 * patches of different levels, the statistics); every other build (2 and 3
 * threads, an engine parallel-for that splits unevenly and out of order)
 * must be bitwise the one-thread list of the reference path
 * (tlod_scheduler_desc.reference_path). The meshes have more patches than
 * one draw-list chunk, so several chunks meet in every build.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "shapes.h"
#include "tesslod/lod.h"
#include "test.h"
#include "test_camera.h"
#include "test_context.h"
#include "test_fixture.h"
#include "test_lod.h"

/* An engine job system of uneven chunks (1, 2, 3, ... items, growing)
 * run last to first on 5 workers. */
static void uneven_parallel_for(tlod_task_fn fn, void* task_data, uint32_t count, void* user_data) {
  (void)user_data;
  uint32_t bounds[4096], n = 0, at = 0;
  for (uint32_t size = 1; at < count && n + 1 < 4096; size += size / 2 + 1) {
    bounds[n++] = at;
    at = count - at > size ? at + size : count;
  }
  bounds[n] = count;
  for (uint32_t c = n; c-- > 0;)
    fn(task_data, bounds[c], c + 1 < n ? bounds[c + 1] : count, c % 5);
}

static tlod_context* uneven_context(void) {
  tlod_context_desc desc = {.parallel_for = {.func = uneven_parallel_for, .worker_count = 5}};
  tlod_context* ctx = NULL;
  return tlod_context_create(&desc, &ctx) == TLOD_SUCCESS ? ctx : NULL;
}

/* threads threads at SIMD level simd or the best below it this processor
 * has (the draw list's kernels have a copy per level). */
static tlod_context* simd_context(uint32_t threads, tlod_simd simd) {
  tlod_context_desc desc = {.thread_count = threads, .simd = simd};
  tlod_context* ctx = NULL;
  return tlod_context_create(&desc, &ctx) == TLOD_SUCCESS ? ctx : NULL;
}

static const tlod_draw_list* plan(const fixture* fx, tlod_scheduler* s, const tlod_view_desc* v, uint32_t count,
                                  float dt_ms) {
  tlod_frame_desc f = {.views = v, .view_count = count, .dt_ms = dt_ms};
  return scheduler_plan(fx->ctx, s, &f);
}

/* Bitwise equality of everything a draw list holds but stage_ms and generation. */
static bool same_list(const tlod_draw_list* a, const tlod_draw_list* b, const tlod_mesh* m) {
  bool same = a->patch_count == b->patch_count && a->instance_count == b->instance_count &&
              a->bucket_count == b->bucket_count && a->strip_count == b->strip_count;
  same = same && !memcmp(a->levels, b->levels, a->patch_count) &&
         !memcmp(a->e_max, b->e_max, sizeof(float) * a->patch_count) && visible_depths_equal(a, b, m) &&
         !memcmp(a->instances, b->instances, sizeof(tlod_draw_instance) * a->instance_count) &&
         !memcmp(a->buckets, b->buckets, sizeof(tlod_draw_bucket) * a->bucket_count);
  for (uint32_t k = 0; same && k < a->strip_count; ++k) {
    const tlod_draw_strip *x = &a->strips[k], *y = &b->strips[k];
    same = x->patch_a == y->patch_a && x->patch_b == y->patch_b && x->edge_a == y->edge_a && x->edge_b == y->edge_b &&
           x->level_a == y->level_a && x->level_b == y->level_b && x->crease == y->crease;
  }
  return same && a->pattern_triangles == b->pattern_triangles && a->strip_triangles == b->strip_triangles &&
         a->culled == b->culled && !memcmp(a->level_histogram, b->level_histogram, sizeof a->level_histogram) &&
         !memcmp(&a->e_max_min, &b->e_max_min, sizeof(float)) && !memcmp(&a->e_max_max, &b->e_max_max, sizeof(float)) &&
         !memcmp(&a->effective_epsilon, &b->effective_epsilon, sizeof(float));
}

static uint32_t bucket_key(const tlod_mesh* m, uint32_t p, uint32_t level) {
  uint32_t c[4];
  return (tlod_mesh_face_corners(m, p, c) == 4 ? 1000u : 0u) + level;
}

/* Instances: every visible patch once, in (shape, level) bucket order and
 * patch order inside a bucket, the buckets covering them in order. */
static bool check_instances(const fixture* fx, const tlod_draw_list* dl) {
  uint32_t visible = 0;
  for (uint32_t p = 0; p < dl->patch_count; ++p)
    visible += dl->levels[p] >= 0;
  bool ok = dl->instance_count == visible && dl->culled == dl->patch_count - visible;
  for (uint32_t i = 0; ok && i < dl->instance_count; ++i) {
    const tlod_draw_instance* in = &dl->instances[i];
    ok = (int)in->level == dl->levels[in->patch];
    if (ok && i > 0) {
      const tlod_draw_instance* pr = &dl->instances[i - 1];
      uint32_t kp = bucket_key(fx->mesh, pr->patch, pr->level), ki = bucket_key(fx->mesh, in->patch, in->level);
      ok = kp < ki || (kp == ki && pr->patch < in->patch);
    }
  }
  uint32_t next = 0;
  for (uint32_t b = 0; ok && b < dl->bucket_count; ++b) {
    ok = dl->buckets[b].first == next && dl->buckets[b].count > 0;
    next += dl->buckets[b].count;
  }
  return ok && next == dl->instance_count;
}

/* Strips: in patch order, from the lower patch, at the patches' levels,
 * on exactly the edges between visible patches across a crease or of
 * different levels or blends. */
static bool check_strips(const fixture* fx, const tlod_draw_list* dl) {
  float* morph = calloc(dl->patch_count + 1, sizeof(float));
  for (uint32_t i = 0; i < dl->instance_count; ++i)
    morph[dl->instances[i].patch] = dl->instances[i].morph;
  uint64_t tris = 0;
  uint32_t k = 0;
  bool ok = true;
  for (uint32_t p = 0; ok && p < dl->patch_count; ++p) {
    uint32_t c[4], n = tlod_mesh_face_corners(fx->mesh, p, c);
    for (uint32_t e = 0; ok && e < n && dl->levels[p] >= 0; ++e) {
      tlod_edge_link l = tlod_mesh_edge_link(fx->mesh, p, e);
      bool here = k < dl->strip_count && dl->strips[k].patch_a == p && dl->strips[k].edge_a == e;
      /* Needed exactly towards a visible neighbour of higher index across a
       * crease, at another level or at another blend (from the instances). */
      bool needed = l.face != UINT32_MAX && l.face > p && dl->levels[l.face] >= 0 &&
                    (!l.smooth || dl->levels[l.face] != dl->levels[p] || morph[l.face] != morph[p]);
      ok = here == needed;
      if (!here || !ok) continue;
      const tlod_draw_strip* s = &dl->strips[k++];
      /* Exact: smooth, different levels, the coarser side at rest. */
      bool exact = l.smooth && s->level_a != s->level_b && morph[s->level_a < s->level_b ? p : l.face] == 1.0f;
      ok = s->patch_b == l.face && s->edge_b == l.edge && s->level_a == dl->levels[p] &&
           s->level_b == dl->levels[l.face] && s->crease == !l.smooth && s->exact == exact;
      uint32_t t = 0;
      if (exact)
        tlod_patterns_connection_exact(fx->pat, s->level_a, s->level_b, &t);
      else
        tlod_patterns_connection(fx->pat, s->level_a, s->level_b, &t);
      tris += t;
    }
  }
  free(morph);
  return ok && k == dl->strip_count && tris == dl->strip_triangles;
}

static bool check_stats(const fixture* fx, const tlod_draw_list* dl) {
  uint32_t hist[TLOD_MAX_LEVEL + 1] = {0};
  uint64_t tris = 0;
  float lo = INFINITY, hi = 0.0f;
  for (uint32_t p = 0; p < dl->patch_count; ++p) {
    if (dl->levels[p] < 0) continue;
    uint32_t c[4], l = (uint32_t)dl->levels[p];
    hist[l]++;
    tris += tlod_pattern_triangle_count(
        tlod_mesh_face_corners(fx->mesh, p, c) == 4 ? TLOD_PATTERN_QUAD : TLOD_PATTERN_TRIANGLE, l);
    lo = dl->e_max[p] < lo ? dl->e_max[p] : lo;
    hi = dl->e_max[p] > hi ? dl->e_max[p] : hi;
  }
  if (dl->culled == dl->patch_count) lo = 0.0f;
  return !memcmp(hist, dl->level_histogram, sizeof hist) && tris == dl->pattern_triangles && lo == dl->e_max_min &&
         hi == dl->e_max_max;
}

/* A camera at distance dist from the origin along direction k, looking at
 * a point of the shape (close ones refine to the top levels and cull). */
static tlod_view_desc view_at(int k, double dist) {
  double dirs[5][3] = {{0.3, -1.0, 0.8}, {1.0, 0.2, 0.1}, {-0.4, 0.5, 1.0}, {0.1, 0.9, -0.6}, {-1.0, -0.3, 0.2}};
  double len = len3(dirs[k % 5]);
  camera c = {.up = {0, 0, 1}, .fovy = 1.0, .aspect = 1.5, .znear = 0.01, .zfar = 100, .width = 1200, .height = 800};
  for (int a = 0; a < 3; ++a)
    c.eye[a] = dirs[k % 5][a] / len * dist, c.target[a] = dirs[(k + 1) % 5][a] * 0.2;
  return make_view(&c);
}

/* Frame f's first view: the cameras of view_at, then one looking away
 * from the shape (every block culled) and one at its centre (the culled
 * and visible blocks interleave round the eye). */
static tlod_view_desc view_of_frame(int f, double radius) {
  tlod_view_desc v = view_at(f, radius * (1.03 + 0.12 * f));
  if (f < 8) return v;
  camera c = {.up = {0, 0, 1}, .fovy = 1.0, .aspect = 1.5, .znear = 0.01, .zfar = 100, .width = 1200, .height = 800};
  for (int a = 0; a < 3; ++a)
    c.eye[a] = f == 8 ? 3.0 * radius : 0.0, c.target[a] = f == 8 ? 6.0 * radius : (a == 0 ? 1.0 : 0.1);
  return make_view(&c);
}

enum { BUILDS = 4, FRAMES = 10 };

/* Builds: the reference path on one scalar thread, then 2 threads at
 * the best SIMD level, 3 at AVX2 (or the best below it) and the uneven
 * engine parallel-for at the best level. */
static void run_builds(const shape* sh, double radius, tlod_surface_type type, tlod_scheduler_desc d) {
  tlod_context* ctx[BUILDS] = {simd_context(1, TLOD_SIMD_SCALAR), new_context(2, NULL, NULL),
                               simd_context(3, TLOD_SIMD_AVX2), uneven_context()};
  fixture fx[BUILDS];
  tlod_scheduler* s[BUILDS];
  for (int b = 0; b < BUILDS; ++b) {
    CHECK(ctx[b] && fixture_make(&fx[b], ctx[b], sh, type));
    tlod_scheduler_desc db = d;
    db.reference_path = b == 0; /* the oracle: the stage-by-stage path on one thread */
    s[b] = scheduler_create(fx[b].ctx, fx[b].surf, fx[b].pat, db);
    CHECK(s[b]);
  }
  uint32_t strips = 0, levels = 0, creases = 0;
  for (int f = 0; f < FRAMES; ++f) {
    tlod_view_desc v[2] = {view_of_frame(f, radius), view_at(f + 2, radius * 1.8)};
    v[1].lock_to_main = f % 2;
    const tlod_draw_list* ref = plan(&fx[0], s[0], v, 2, 40.0f);
    CHECK(ref);
    for (uint32_t view = 0; ref && view < 2; ++view) {
      const tlod_draw_list* r = tlod_scheduler_draw_list(s[0], view);
      CHECK_MSG(check_instances(&fx[0], r) && check_strips(&fx[0], r) && check_stats(&fx[0], r),
                "%s frame %d view %u: the reference list fails the oracle", sh->name, f, view);
    }
    if (f == 8)
      CHECK_MSG(ref->culled == ref->patch_count, "%s: the camera looking away culled only %u", sh->name, ref->culled);
    for (int b = 1; b < BUILDS; ++b) {
      CHECK(plan(&fx[b], s[b], v, 2, 40.0f));
      for (uint32_t view = 0; view < 2; ++view) {
        const tlod_draw_list* r = tlod_scheduler_draw_list(s[b], view);
        CHECK_MSG(check_strips(&fx[b], r), "%s frame %d view %u: build %d (%s) fails the strip oracle", sh->name, f,
                  view, b, tlod_simd_name(tlod_context_simd(ctx[b])));
        CHECK_MSG(same_list(tlod_scheduler_draw_list(s[0], view), r, fx[0].mesh),
                  "%s %s frame %d view %u: build %d differs from the one-thread reference", sh->name,
                  tlod_lod_policy_name(d.policy), f, view, b);
      }
    }
    strips += ref->strip_count;
    for (uint32_t k = 0; k < ref->strip_count; ++k)
      creases += ref->strips[k].crease;
    for (uint32_t l = 3; l <= TLOD_MAX_LEVEL; ++l)
      levels += ref->level_histogram[l];
  }
  CHECK_MSG(strips > 0 && levels > 0, "%s: the cameras made no strips (%u) or no level >= 3 (%u)", sh->name, strips,
            levels);
  CHECK_MSG(!sh->creases || creases > 0, "%s: a creased shape made no crease strip", sh->name);
  for (int b = 0; b < BUILDS; ++b) {
    tlod_scheduler_destroy(s[b]);
    fixture_free(&fx[b]);
    tlod_context_destroy(ctx[b]);
  }
}

TEST(test_builds_equal) {
  shape torus = shape_torus(120, 80), cube = shape_quad_sphere(56), creased = shape_creased_sphere(40);
  tlod_scheduler_desc d = {
      .policy = TLOD_POLICY_HYBRID, .morph = TLOD_MORPH_TIME, .morph_ms = 100, .max_level = 6, .epsilon_px = 0.25f};
  run_builds(&torus, 1.4, TLOD_SURFACE_PHONG, d);
  run_builds(&cube, 1.0, TLOD_SURFACE_PHONG, d);
  run_builds(&creased, 1.0, TLOD_SURFACE_PHONG, d);
  d.policy = TLOD_POLICY_ERROR, d.morph = TLOD_MORPH_CONTINUOUS;
  run_builds(&torus, 1.4, TLOD_SURFACE_PN, d);
  d.policy = TLOD_POLICY_SILHOUETTE, d.morph = TLOD_MORPH_NONE;
  run_builds(&cube, 1.0, TLOD_SURFACE_PHONG, d);
  shape_free(&torus);
  shape_free(&cube);
  shape_free(&creased);
}

/* A fresh scheduler's list for the same view and desc: what a kept or
 * rebuilt list must equal once the morphs are at rest. */
static bool same_as_fresh(const fixture* fx, tlod_scheduler_desc d, const tlod_view_desc* v, const tlod_draw_list* dl) {
  tlod_scheduler* fresh = scheduler_create(fx->ctx, fx->surf, fx->pat, d);
  const tlod_draw_list* ref = fresh ? plan(fx, fresh, v, 1, 0.0f) : NULL;
  bool same = ref && same_list(ref, dl, fx->mesh);
  tlod_scheduler_destroy(fresh);
  return same;
}

/* One frame after a change: a new generation, and (the morphs jumping at
 * once: dt far above morph_ms) the fresh scheduler's list. */
static void check_changed(const fixture* fx, tlod_scheduler* s, tlod_scheduler_desc fresh_desc, const tlod_view_desc* v,
                          uint64_t* g, const char* what) {
  uint64_t before = *g;
  const tlod_draw_list* dl = plan(fx, s, v, 1, 1e6f);
  CHECK(dl);
  *g = dl->generation;
  CHECK_MSG(dl->generation > before, "%s: generation %llu stayed", what, (unsigned long long)before);
  CHECK_MSG(same_as_fresh(fx, fresh_desc, v, dl), "%s: the list is not a fresh scheduler's", what);
}

/* Static frames until the generation stays; then it must keep staying,
 * with no stage run and the fresh scheduler's list. */
static void check_static(const fixture* fx, tlod_scheduler* s, tlod_scheduler_desc d, const tlod_view_desc* v,
                         uint64_t* gen, const char* what) {
  uint64_t g = 0;
  int frames = 0;
  for (const tlod_draw_list* dl; frames < 60 && (dl = plan(fx, s, v, 1, 25.0f)) && dl->generation != g; ++frames)
    g = dl->generation;
  *gen = g;
  CHECK_MSG(frames < 60, "%s: the generation never settled", what);
  for (int k = 0; k < 3; ++k) {
    const tlod_draw_list* dl = plan(fx, s, v, 1, 25.0f + (float)k);
    CHECK_MSG(dl && dl->generation == g, "%s: static frame %d made a new generation", what, k);
    double ms = 0;
    for (int st = 0; dl && st < TLOD_STAGE_NUM; ++st)
      ms += dl->stage_ms[st];
    CHECK_MSG(ms == 0.0, "%s: a kept list ran stages (%g ms)", what, ms);
    CHECK_MSG(dl && same_as_fresh(fx, d, v, dl), "%s: the kept list is not a fresh scheduler's", what);
  }
}

TEST(test_generation) {
  shape torus = shape_torus(60, 40);
  tlod_context* ctx = new_context(2, NULL, NULL);
  fixture fx;
  CHECK(ctx && fixture_make(&fx, ctx, &torus, TLOD_SURFACE_PHONG));
  tlod_scheduler_desc d = {.morph = TLOD_MORPH_TIME, .morph_ms = 100, .max_level = 6, .frame_time_target_ms = 16};
  tlod_scheduler* s = scheduler_create(ctx, fx.surf, fx.pat, d);
  CHECK(s);
  tlod_view_desc v = view_at(0, 1.8);
  uint64_t g = 0;
  check_static(&fx, s, d, &v, &g, "static camera");
  v.view[14] = nextafterf(v.view[14], INFINITY);
  check_changed(&fx, s, d, &v, &g, "camera moved by one ulp");
  check_static(&fx, s, d, &v, &g, "after the camera move");
  /* Positions rewritten as they were: the mesh generation still moves. */
  CHECK(tlod_mesh_update(fx.mesh, torus.positions, 0, NULL, 0) == TLOD_SUCCESS);
  check_changed(&fx, s, d, &v, &g, "mesh update");
  float* moved = malloc(sizeof(float) * 3 * torus.vertex_count);
  memcpy(moved, torus.positions, sizeof(float) * 3 * torus.vertex_count);
  moved[0] += 0.01f;
  CHECK(tlod_mesh_update(fx.mesh, moved, 0, NULL, 0) == TLOD_SUCCESS);
  check_changed(&fx, s, d, &v, &g, "mesh moved");
  uint32_t updated = 0;
  CHECK(tlod_surface_refresh(fx.surf, &updated) == TLOD_SUCCESS && updated > 0);
  check_changed(&fx, s, d, &v, &g, "surface refresh");
  check_static(&fx, s, d, &v, &g, "after the refresh");
  /* Frame-time control raises epsilon: a fresh scheduler at that epsilon. */
  tlod_frame_desc slow = {.views = &v, .view_count = 1, .dt_ms = 1e6f, .measured_frame_ms = 100};
  CHECK(scheduler_plan(ctx, s, &slow));
  const tlod_draw_list* dl = tlod_scheduler_draw_list(s, 0);
  CHECK_MSG(dl->generation > g, "epsilon raised: generation %llu stayed", (unsigned long long)g);
  tlod_scheduler_desc raised = d;
  raised.epsilon_px = dl->effective_epsilon;
  CHECK(dl->effective_epsilon > 0.5f && same_as_fresh(&fx, raised, &v, dl));
  free(moved);
  tlod_scheduler_destroy(s);
  fixture_free(&fx);
  tlod_context_destroy(ctx);
  shape_free(&torus);
}

/* Net count of directed edges u -> v minus v -> u over a triangle set, the
 * points welded by parameter (point r of a at r * (64 / na), of b at
 * j * (64 / nb)): a set that exactly fills the gap between the polylines
 * has net +-1 on their segments only, a's one way and b's the other. */
static bool fills_between(const uint32_t* tris, uint32_t count, uint32_t na, uint32_t nb) {
  static int net[65][65];
  memset(net, 0, sizeof net);
  for (uint32_t t = 0; t < count; ++t)
    for (int k = 0; k < 3; ++k) {
      uint32_t r = tris[3 * t + k], q = tris[3 * t + (k + 1) % 3];
      uint32_t u = r <= na ? r * (64 / na) : (r - na - 1) * (64 / nb),
               v = q <= na ? q * (64 / na) : (q - na - 1) * (64 / nb);
      net[u][v]++, net[v][u]--;
    }
  bool ok = true;
  for (uint32_t u = 0; u < 64 && ok; ++u)
    for (uint32_t v = u + 1; v <= 64 && ok; ++v) {
      bool on_a = u % (64 / na) == 0 && v == u + 64 / na, on_b = u % (64 / nb) == 0 && v == u + 64 / nb;
      int want = (on_a ? -1 : 0) + (on_b ? 1 : 0); /* a traversed backwards */
      ok = net[u][v] == want;
    }
  return ok;
}

/* The exact connection patterns: the full ones without the triangles with a
 * point of each side at the same parameter, |2^la - 2^lb| of them, still
 * filling the gap between the polylines exactly (as the full ones do). */
TEST(test_exact_connections) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  tlod_patterns* pat = NULL;
  CHECK(ctx && tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = 6}, &pat) == TLOD_SUCCESS);
  for (uint32_t la = 0; la <= 6; ++la)
    for (uint32_t lb = 0; lb <= 6; ++lb) {
      uint32_t na = 1u << la, nb = 1u << lb, nf = 0, ne = 0, kept = 0;
      const uint32_t *full = tlod_patterns_connection(pat, la, lb, &nf),
                     *ex = tlod_patterns_connection_exact(pat, la, lb, &ne);
      CHECK_MSG(ne == (na > nb ? na - nb : nb - na), "(%u, %u): %u exact triangles", la, lb, ne);
      CHECK_MSG(fills_between(full, nf, na, nb), "(%u, %u): the full pattern leaves a gap", la, lb);
      if (la != lb) CHECK_MSG(fills_between(ex, ne, na, nb), "(%u, %u): the exact pattern leaves a gap", la, lb);
      for (uint32_t t = 0; t < nf && kept < ne; ++t)
        kept += !memcmp(full + 3 * t, ex + 3 * kept, sizeof(uint32_t[3]));
      CHECK_MSG(kept == ne, "(%u, %u): exact is not a subsequence of the full pattern", la, lb);
    }
  tlod_draw_strip st = {.level_a = 2, .level_b = 4, .exact = true};
  uint32_t n = 99;
  CHECK(tlod_draw_strip_connection(pat, &st, &n) && n == 12);
  st.exact = false;
  CHECK(tlod_draw_strip_connection(pat, &st, &n) && n == 4 + 16 - 2);
  CHECK(!tlod_draw_strip_connection(pat, NULL, &n) && n == 0);
  st.level_b = 7;
  CHECK(!tlod_draw_strip_connection(pat, &st, &n) && n == 0);
  tlod_patterns_destroy(pat);
  tlod_context_destroy(ctx);
}

int main(void) {
  RUN(test_exact_connections);
  RUN(test_builds_equal);
  RUN(test_generation);
  TEST_END();
}
