/* Unit tests of tlod_scheduler_update_group (tesslod/lod.h): several
 * schedulers, each with its own view, under one scene-wide triangle budget
 * with one shared effective epsilon. Public API only. The references are
 * lone schedulers: each at the even share of the budget (what the group
 * must beat for the near object), at the group's epsilon without a budget
 * (the same levels), and at a slightly smaller epsilon (which must not fit:
 * the search stops near the smallest epsilon that fits). */
#include <stdint.h>
#include <string.h>

#include "shapes.h"
#include "tesslod/lod.h"
#include "test.h"
#include "test_context.h"

#define OBJECTS 3

typedef struct fixture {
  tlod_context* ctx;
  tlod_mesh* mesh;
  tlod_surface* surface;
  tlod_patterns* patterns;
} fixture;

/* ctx: NULL for a default context of 2 threads; taken over either way. */
static bool fixture_make_in(fixture* fx, tlod_context* ctx) {
  memset(fx, 0, sizeof *fx);
  shape s = shape_icosphere(1);
  fx->ctx = ctx;
  if (!ctx) tlod_context_create(&(tlod_context_desc){.thread_count = 2}, &fx->ctx);
  tlod_mesh_desc md = shape_mesh_desc(&s);
  bool ok = tlod_mesh_create(fx->ctx, &md, &fx->mesh) == TLOD_SUCCESS &&
            tlod_surface_create(fx->ctx, fx->mesh, &(tlod_surface_desc){.type = TLOD_SURFACE_PN}, &fx->surface) ==
                TLOD_SUCCESS &&
            tlod_patterns_create(fx->ctx, &(tlod_patterns_desc){.max_level = 5}, &fx->patterns) == TLOD_SUCCESS;
  shape_free(&s);
  return ok;
}

static bool fixture_make(fixture* fx) { return fixture_make_in(fx, NULL); }

static void fixture_free(fixture* fx) {
  tlod_patterns_destroy(fx->patterns);
  tlod_surface_destroy(fx->surface);
  tlod_mesh_destroy(fx->mesh);
  tlod_context_destroy(fx->ctx);
}

/* A camera at (0, 0, z) looking down -z at the unit sphere: a 60 degree
 * GL perspective, 800 x 600. */
static tlod_view_desc axis_view(float z) {
  tlod_view_desc v = {.viewport_width = 800, .viewport_height = 600};
  for (int k = 0; k < 4; k++)
    v.view[5 * k] = 1.0f;
  v.view[14] = -z;
  float f = 1.7320508f, n = 0.05f, far = 100.0f;
  v.proj[0] = f * 600.0f / 800.0f, v.proj[5] = f;
  v.proj[10] = (far + n) / (n - far), v.proj[11] = -1.0f, v.proj[14] = 2.0f * far * n / (n - far);
  return v;
}

/* Near, middle and far objects. */
static const float distances[OBJECTS] = {1.6f, 4.0f, 12.0f};

static tlod_scheduler* make(const fixture* fx, float epsilon, uint32_t budget) {
  tlod_scheduler* s = NULL;
  tlod_scheduler_desc d = {
      .epsilon_px = epsilon, .policy = TLOD_POLICY_ERROR, .morph = TLOD_MORPH_NONE, .triangle_budget = budget};
  return tlod_scheduler_create(fx->ctx, fx->surface, fx->patterns, &d, &s) == TLOD_SUCCESS ? s : NULL;
}

static uint64_t triangles(const tlod_draw_list* dl) { return dl->pattern_triangles + dl->strip_triangles; }

/* Object k's frame; views[] must outlive it. */
static void frames_of(tlod_view_desc views[OBJECTS], tlod_frame_desc frames[OBJECTS]) {
  for (int k = 0; k < OBJECTS; k++) {
    views[k] = axis_view(distances[k]);
    frames[k] = (tlod_frame_desc){.views = &views[k], .view_count = 1, .dt_ms = 16.0f};
  }
}

/* Triangles of object k planned alone at (epsilon, budget). */
static uint64_t alone(const fixture* fx, int k, float epsilon, uint32_t budget, float* eff) {
  tlod_scheduler* s = make(fx, epsilon, budget);
  tlod_view_desc v = axis_view(distances[k]);
  tlod_frame_desc fr = {.views = &v, .view_count = 1, .dt_ms = 16.0f};
  uint64_t t = UINT64_MAX;
  if (s && tlod_scheduler_update(s, &fr) == TLOD_SUCCESS) {
    t = triangles(tlod_scheduler_draw_list(s, 0));
    if (eff) *eff = tlod_scheduler_draw_list(s, 0)->effective_epsilon;
  }
  tlod_scheduler_destroy(s);
  return t;
}

static void make_all(const fixture* fx, tlod_scheduler* s[OBJECTS]) {
  for (int k = 0; k < OBJECTS; k++)
    s[k] = make(fx, 0.5f, 0);
}

static void destroy_all(tlod_scheduler* s[OBJECTS]) {
  for (int k = 0; k < OBJECTS; k++)
    tlod_scheduler_destroy(s[k]);
}

/* Field by field: a strip has padding bytes. */
static bool same_strips(const tlod_draw_strip* a, const tlod_draw_strip* b, uint32_t n) {
  for (uint32_t i = 0; i < n; i++)
    if (a[i].patch_a != b[i].patch_a || a[i].patch_b != b[i].patch_b || a[i].edge_a != b[i].edge_a ||
        a[i].edge_b != b[i].edge_b || a[i].level_a != b[i].level_a || a[i].level_b != b[i].level_b ||
        a[i].crease != b[i].crease)
      return false;
  return true;
}

/* Bitwise equal draw lists (everything but the stage times). */
static bool same_list(const tlod_draw_list* a, const tlod_draw_list* b) {
  return a->patch_count == b->patch_count && !memcmp(a->levels, b->levels, a->patch_count) &&
         a->instance_count == b->instance_count &&
         !memcmp(a->instances, b->instances, sizeof(*a->instances) * a->instance_count) &&
         a->bucket_count == b->bucket_count && !memcmp(a->buckets, b->buckets, sizeof(*a->buckets) * a->bucket_count) &&
         a->strip_count == b->strip_count && same_strips(a->strips, b->strips, a->strip_count) &&
         a->pattern_triangles == b->pattern_triangles && a->strip_triangles == b->strip_triangles &&
         !memcmp(&a->effective_epsilon, &b->effective_epsilon, sizeof(float));
}

/* The group at budget against each scheduler updated alone without one. */
static void check_same_as_alone(const fixture* fx, uint32_t budget) {
  tlod_scheduler *g[OBJECTS], *a[OBJECTS];
  make_all(fx, g);
  make_all(fx, a);
  tlod_view_desc views[OBJECTS];
  tlod_frame_desc frames[OBJECTS];
  frames_of(views, frames);
  for (int frame = 0; frame < 2; frame++) {
    CHECK(tlod_scheduler_update_group(g, frames, OBJECTS, budget) == TLOD_SUCCESS);
    for (int k = 0; k < OBJECTS; k++) {
      CHECK(tlod_scheduler_update(a[k], &frames[k]) == TLOD_SUCCESS);
      const tlod_draw_list *x = tlod_scheduler_draw_list(g[k], 0), *y = tlod_scheduler_draw_list(a[k], 0);
      CHECK_MSG(same_list(x, y), "budget %u frame %d object %d: %llu/%llu triangles, epsilon %g/%g", budget, frame, k,
                (unsigned long long)triangles(x), (unsigned long long)triangles(y), (double)x->effective_epsilon,
                (double)y->effective_epsilon);
    }
  }
  destroy_all(g);
  destroy_all(a);
}

TEST(test_group_shares_by_error) {
  fixture fx;
  CHECK(fixture_make(&fx));
  uint64_t unconstrained = 0, free_k[OBJECTS];
  for (int k = 0; k < OBJECTS; k++)
    unconstrained += free_k[k] = alone(&fx, k, 0.5f, 0, NULL);
  CHECK_MSG(free_k[0] > free_k[1] && free_k[1] > free_k[2], "the near object needs the most: %llu %llu %llu",
            (unsigned long long)free_k[0], (unsigned long long)free_k[1], (unsigned long long)free_k[2]);
  uint32_t budget = (uint32_t)(unconstrained * 2 / 5);
  tlod_scheduler* g[OBJECTS];
  make_all(&fx, g);
  tlod_view_desc views[OBJECTS];
  tlod_frame_desc frames[OBJECTS];
  frames_of(views, frames);
  CHECK(tlod_scheduler_update_group(g, frames, OBJECTS, budget) == TLOD_SUCCESS);
  uint64_t total = 0, got[OBJECTS];
  float eps = tlod_scheduler_draw_list(g[0], 0)->effective_epsilon;
  for (int k = 0; k < OBJECTS; k++) {
    const tlod_draw_list* dl = tlod_scheduler_draw_list(g[k], 0);
    total += got[k] = triangles(dl);
    CHECK_MSG(dl->effective_epsilon == eps, "object %d: epsilon %g, object 0: %g", k, (double)dl->effective_epsilon,
              (double)eps);
  }
  CHECK_MSG(total <= budget, "%llu triangles over the budget %u", (unsigned long long)total, budget);
  CHECK(eps > 0.5f);
  /* An even split: each object alone at budget / count. The near object
   * gets more in the group, the far one less. */
  uint64_t even_near = alone(&fx, 0, 0.5f, budget / OBJECTS, NULL);
  uint64_t even_far = alone(&fx, OBJECTS - 1, 0.5f, budget / OBJECTS, NULL);
  CHECK_MSG(got[0] > even_near, "near: %llu in the group, %llu at an even split", (unsigned long long)got[0],
            (unsigned long long)even_near);
  CHECK_MSG(got[OBJECTS - 1] < even_far, "far: %llu in the group, %llu at an even split",
            (unsigned long long)got[OBJECTS - 1], (unsigned long long)even_far);
  /* The shared epsilon gives each object what it gets alone at that
   * epsilon. At the largest epsilon of the even split every object fits
   * its share, so the whole fits: the search stops at or below it. */
  float even_max = 0.0f;
  for (int k = 0; k < OBJECTS; k++) {
    CHECK_MSG(alone(&fx, k, eps, 0, NULL) == got[k], "object %d", k);
    float e = 0.0f;
    alone(&fx, k, 0.5f, budget / OBJECTS, &e);
    even_max = e > even_max ? e : even_max;
  }
  CHECK_MSG(eps <= even_max * 1.0001f, "group epsilon %g above the even split's largest %g", (double)eps,
            (double)even_max);
  destroy_all(g);
  fixture_free(&fx);
}

TEST(test_group_unconstrained) {
  fixture fx;
  CHECK(fixture_make(&fx));
  uint64_t unconstrained = 0;
  for (int k = 0; k < OBJECTS; k++)
    unconstrained += alone(&fx, k, 0.5f, 0, NULL);
  CALL(check_same_as_alone(&fx, 0)); /* 0: each alone */
  /* Far above what the unconstrained frame draws (the budget search counts
   * a strip on every edge whose blends differ, more than are drawn). */
  CALL(check_same_as_alone(&fx, (uint32_t)unconstrained * 16));
  fixture_free(&fx);
}

TEST(test_group_checks) {
  fixture fx;
  CHECK(fixture_make(&fx));
  tlod_scheduler* g[OBJECTS];
  make_all(&fx, g);
  tlod_view_desc views[OBJECTS];
  tlod_frame_desc frames[OBJECTS];
  frames_of(views, frames);
  CHECK(tlod_scheduler_update_group(NULL, NULL, 0, 100) == TLOD_SUCCESS);
  CHECK(tlod_scheduler_update_group(g, frames, 0, 100) == TLOD_SUCCESS);
  CHECK(tlod_scheduler_draw_list(g[0], 0) == NULL); /* count 0 updated nothing */
  CHECK(tlod_scheduler_update_group(NULL, frames, 2, 100) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_scheduler_update_group(g, NULL, 2, 100) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(tlod_context_last_error(fx.ctx), "NULL frames"));
  tlod_scheduler* twice[2] = {g[1], g[1]};
  CHECK(tlod_scheduler_update_group(twice, frames, 2, 100) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK_MSG(strstr(tlod_context_last_error(fx.ctx), "twice"), "%s", tlod_context_last_error(fx.ctx));
  tlod_scheduler* pair[2] = {g[2], g[1]}; /* the refusal left no mark behind: the same members are fine now */
  tlod_frame_desc pair_frames[2] = {frames[2], frames[1]};
  CHECK_MSG(tlod_scheduler_update_group(pair, pair_frames, 2, 100) == TLOD_SUCCESS, "%s",
            tlod_context_last_error(fx.ctx));
  CHECK(tlod_scheduler_update_group(pair, pair_frames, 2, 100) == TLOD_SUCCESS);
  tlod_scheduler* holed[2] = {g[0], NULL};
  CHECK(tlod_scheduler_update_group(holed, frames, 2, 100) == TLOD_ERROR_INVALID_ARGUMENT);
  tlod_frame_desc bad[2] = {frames[0], {.views = NULL}};
  CHECK(tlod_scheduler_update_group(g, bad, 2, 100) == TLOD_ERROR_INVALID_ARGUMENT);
  destroy_all(g);
  fixture_free(&fx);
}

/* The same draw lists on 2 threads and on a pool running chunks in
 * reverse; no allocation after the first group update. */
TEST(test_group_deterministic_no_alloc) {
  counting_allocator counter = {.fail_at = -1};
  reverse_pool pool = {0};
  fixture a, b;
  CHECK(fixture_make(&a));
  CHECK(fixture_make_in(&b, new_context(1, &counter, &pool)));
  tlod_scheduler *ga[OBJECTS], *gb[OBJECTS];
  make_all(&a, ga);
  make_all(&b, gb);
  tlod_view_desc views[OBJECTS];
  tlod_frame_desc frames[OBJECTS];
  frames_of(views, frames);
  long allocs = 0;
  for (int frame = 0; frame < 4; frame++) {
    views[0].view[14] -= 0.05f; /* the near object comes closer */
    CHECK(tlod_scheduler_update_group(ga, frames, OBJECTS, 700) == TLOD_SUCCESS);
    CHECK(tlod_scheduler_update_group(gb, frames, OBJECTS, 700) == TLOD_SUCCESS);
    for (int k = 0; k < OBJECTS; k++)
      CHECK_MSG(same_list(tlod_scheduler_draw_list(ga[k], 0), tlod_scheduler_draw_list(gb[k], 0)), "frame %d object %d",
                frame, k);
    CHECK(tlod_scheduler_draw_list(gb[0], 0)->effective_epsilon > 0.5f); /* the budget binds */
    if (frame == 0) allocs = counter.allocs;
  }
  CHECK_MSG(counter.allocs == allocs, "%ld allocations after the first frame", counter.allocs - allocs);
  CHECK(pool.calls > 0);
  destroy_all(ga);
  destroy_all(gb);
  fixture_free(&a);
  fixture_free(&b);
}

int main(void) {
  RUN(test_group_shares_by_error);
  RUN(test_group_unconstrained);
  RUN(test_group_checks);
  RUN(test_group_deterministic_no_alloc);
  TEST_END();
}
