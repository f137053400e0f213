/* The NULL and contract policy of tesslod/core.h, checked as the header
 * states it (section CONTRACT): allocator hooks all-or-none, the position
 * limit at mesh create and update naming the vertex, range checks of every
 * entry point that takes a patch index or grid coordinates, and NULL
 * handles in every function. Public API only. */
#include <stdint.h>

#include "tesslod/core.h"
#include "test.h"
#include "test_context.h"

/* ------------------------------------------------------------------------ */
/* Fixtures                                                                 */
/* ------------------------------------------------------------------------ */

typedef struct log_capture {
  int count;
  char last[512];
} log_capture;

static void capture_log(tlod_log_level level, const char* message, void* user_data) {
  log_capture* c = user_data;
  if (level != TLOD_LOG_ERROR) return;
  c->count++;
  snprintf(c->last, sizeof(c->last), "%s", message);
}

/* One tetrahedron, closed; vertex 3 at (0, 0, top). */
static const uint32_t tet_indices[12] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3};

static void tet_positions(float scale, float out[12]) {
  const float p[12] = {1, 0, 0, -0.5f, 0.866f, 0, -0.5f, -0.866f, 0, 0, 0, 1};
  for (int i = 0; i < 12; i++)
    out[i] = p[i] * scale;
}

static tlod_mesh_desc tet_desc(const float* positions) {
  return (tlod_mesh_desc){.positions = positions, .vertex_count = 4, .indices = tet_indices, .index_count = 12};
}

static tlod_mesh* tet_mesh(tlod_context* ctx) {
  float p[12];
  tet_positions(1.0f, p);
  tlod_mesh_desc d = tet_desc(p);
  tlod_mesh* m = NULL;
  return tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS ? m : NULL;
}

/* ------------------------------------------------------------------------ */
/* Allocator hooks: both or neither                                         */
/* ------------------------------------------------------------------------ */

static tlod_result create_with_hooks(bool alloc, bool free_, log_capture* log, counting_allocator* counter) {
  tlod_context_desc d = {.thread_count = 1, .logger = {capture_log, log}};
  d.allocator.alloc_fn = alloc ? counting_alloc : NULL;
  d.allocator.free_fn = free_ ? counting_free : NULL;
  d.allocator.user_data = counter;
  tlod_context* ctx = (tlod_context*)(uintptr_t)1; /* must be reset to NULL */
  tlod_result r = tlod_context_create(&d, &ctx);
  if (r != TLOD_SUCCESS && ctx != NULL) return TLOD_RESULT_NUM;
  tlod_context_destroy(ctx);
  return r;
}

TEST(allocator_hooks_all_or_none) {
  counting_allocator counter = {.fail_at = -1};
  log_capture log = {0};
  CHECK(create_with_hooks(true, false, &log, &counter) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK_MSG(strstr(log.last, "allocator.free_fn") != NULL, "message: '%s'", log.last);
  CHECK(counter.calls == 0); /* refused before anything was allocated, by malloc or the hook */
  CHECK(create_with_hooks(false, true, &log, &counter) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK_MSG(strstr(log.last, "allocator.alloc_fn") != NULL, "message: '%s'", log.last);
  CHECK(log.count == 2);
  CHECK(create_with_hooks(true, true, &log, &counter) == TLOD_SUCCESS);
  CHECK(counter.allocs > 0 && counter.allocs == counter.frees);
  CHECK(create_with_hooks(false, false, &log, &counter) == TLOD_SUCCESS);
  CHECK(log.count == 2);
  /* Without a logger the refusal is still a refusal. */
  tlod_context_desc quiet = {.allocator = {.alloc_fn = counting_alloc, .user_data = &counter}};
  tlod_context* ctx = NULL;
  CHECK(tlod_context_create(&quiet, &ctx) == TLOD_ERROR_INVALID_ARGUMENT && ctx == NULL);
}

static void null_parallel_for(tlod_task_fn fn, void* task_data, uint32_t count, void* user_data) {
  (void)user_data;
  fn(task_data, 0, count, 0);
}

TEST(worker_count_bounded) {
  log_capture log = {0};
  tlod_context_desc d = {.logger = {capture_log, &log}, .parallel_for = {null_parallel_for, TLOD_MAX_WORKERS + 1}};
  tlod_context* ctx = (tlod_context*)(uintptr_t)1;
  CHECK(tlod_context_create(&d, &ctx) == TLOD_ERROR_INVALID_ARGUMENT && ctx == NULL);
  CHECK_MSG(strstr(log.last, "parallel_for.worker_count 1025") != NULL, "message: '%s'", log.last);
  d.parallel_for.worker_count = UINT32_MAX;
  CHECK(tlod_context_create(&d, &ctx) == TLOD_ERROR_INVALID_ARGUMENT && ctx == NULL);
  d.parallel_for.worker_count = TLOD_MAX_WORKERS;
  CHECK(tlod_context_create(&d, &ctx) == TLOD_SUCCESS);
  CHECK(tlod_context_worker_count(ctx) == TLOD_MAX_WORKERS);
  tlod_context_destroy(ctx);
}

TEST(context_create_out_of_memory) {
  counting_allocator counter = {.fail_at = 0};
  tlod_context_desc d = {.thread_count = 4, .allocator = {counting_alloc, counting_free, &counter}};
  for (long k = 0; k < 8; k++) {
    counter = (counting_allocator){.fail_at = k};
    tlod_context* ctx = NULL;
    tlod_result r = tlod_context_create(&d, &ctx);
    CHECK(r == TLOD_SUCCESS || (r == TLOD_ERROR_OUT_OF_MEMORY && ctx == NULL));
    tlod_context_destroy(ctx);
    CHECK_MSG(counter.allocs == counter.frees, "fail at %ld: %ld allocs, %ld frees", k, counter.allocs, counter.frees);
  }
}

/* ------------------------------------------------------------------------ */
/* Positions: finite and within TLOD_POSITION_LIMIT                         */
/* ------------------------------------------------------------------------ */

static tlod_result create_tet(tlod_context* ctx, const float* p) {
  tlod_mesh_desc d = tet_desc(p);
  tlod_mesh* m = (tlod_mesh*)(uintptr_t)1;
  tlod_result r = tlod_mesh_create(ctx, &d, &m);
  if (r != TLOD_SUCCESS && m != NULL) return TLOD_RESULT_NUM;
  tlod_mesh_destroy(m);
  return r;
}

TEST(position_limit_at_create) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(ctx);
  float p[12];
  tet_positions(TLOD_POSITION_LIMIT, p); /* every |x| <= the limit: accepted */
  CHECK_MSG(create_tet(ctx, p) == TLOD_SUCCESS, "%s", tlod_context_last_error(ctx));
  p[3 * 2 + 1] = -1.5e18f;
  CHECK(create_tet(ctx, p) == TLOD_ERROR_INVALID_MESH);
  const char* e = tlod_context_last_error(ctx);
  CHECK_MSG(strstr(e, "vertex 2: position.y") && strstr(e, "TLOD_POSITION_LIMIT"), "message: '%s'", e);
  p[3 * 2 + 1] = 3e38f; /* the example: NaN out of PN evaluation before */
  CHECK(create_tet(ctx, p) == TLOD_ERROR_INVALID_MESH);
  CHECK_MSG(strstr(tlod_context_last_error(ctx), "vertex 2: position.y"), "%s", tlod_context_last_error(ctx));
  p[3 * 2 + 1] = INFINITY;
  CHECK(create_tet(ctx, p) == TLOD_ERROR_INVALID_MESH);
  CHECK_MSG(strstr(tlod_context_last_error(ctx), "vertex 2: position.y is inf (not finite)"), "%s",
            tlod_context_last_error(ctx));
  tlod_context_destroy(ctx);
}

TEST(position_limit_at_update) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  tlod_mesh* m = tet_mesh(ctx);
  CHECK(m);
  float p[12], before[3], after[3];
  tet_positions(1.0f, p);
  p[3 * 3 + 2] = 2e18f;
  tlod_mesh_vertex(m, 3, before, NULL);
  CHECK(tlod_mesh_update(m, p, 0, NULL, 0) == TLOD_ERROR_INVALID_MESH);
  const char* e = tlod_context_last_error(ctx);
  CHECK_MSG(strstr(e, "update: vertex 3: position.z") && strstr(e, "TLOD_POSITION_LIMIT"), "message: '%s'", e);
  tlod_mesh_vertex(m, 3, after, NULL);
  CHECK(memcmp(before, after, sizeof(before)) == 0); /* a refused update changes nothing */
  p[3 * 3 + 2] = -TLOD_POSITION_LIMIT;
  CHECK_MSG(tlod_mesh_update(m, p, 0, NULL, 0) == TLOD_SUCCESS, "%s", tlod_context_last_error(ctx));
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* Patch indices and grid coordinates                                       */
/* ------------------------------------------------------------------------ */

static bool all_zero(const void* p, size_t n) {
  const unsigned char* b = p;
  for (size_t i = 0; i < n; i++)
    if (b[i]) return false;
  return true;
}

TEST(surface_eval_checks_its_arguments) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  tlod_mesh* m = tet_mesh(ctx);
  tlod_surface* s = NULL;
  CHECK(m && tlod_surface_create(ctx, m, &(tlod_surface_desc){.type = TLOD_SURFACE_PN}, &s) == TLOD_SUCCESS);
  tlod_surface_point pt;
  CHECK(tlod_surface_eval(s, 3, 0.25f, 0.25f, &pt) == TLOD_SUCCESS);
  CHECK(isfinite(pt.position[0]) && !all_zero(&pt, sizeof(pt)));
  const uint32_t bad_patches[] = {4, 5, 1u << 20, UINT32_MAX};
  for (size_t k = 0; k < sizeof(bad_patches) / sizeof(bad_patches[0]); k++) {
    memset(&pt, 0x7f, sizeof(pt));
    CHECK_MSG(tlod_surface_eval(s, bad_patches[k], 0.25f, 0.25f, &pt) == TLOD_ERROR_INVALID_ARGUMENT, "patch %u",
              bad_patches[k]);
    CHECK(all_zero(&pt, sizeof(pt)));
  }
  memset(&pt, 0x7f, sizeof(pt));
  CHECK(tlod_surface_eval(s, 0, NAN, 0.25f, &pt) == TLOD_ERROR_INVALID_ARGUMENT && all_zero(&pt, sizeof(pt)));
  CHECK(tlod_surface_eval(s, 0, 0.25f, INFINITY, &pt) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_surface_eval(NULL, 0, 0.25f, 0.25f, &pt) == TLOD_ERROR_INVALID_ARGUMENT && all_zero(&pt, sizeof(pt)));
  CHECK(tlod_surface_eval(s, 0, 0.25f, 0.25f, NULL) == TLOD_ERROR_INVALID_ARGUMENT);
  /* No last error: the call may run on many threads at once. */
  CHECK(tlod_context_last_error(ctx)[0] == '\0');
  tlod_surface_destroy(s);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

TEST(surface_eval_grid_checks_its_arguments) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  tlod_mesh* m = tet_mesh(ctx);
  tlod_surface* s = NULL;
  CHECK(m && tlod_surface_create(ctx, m, &(tlod_surface_desc){.type = TLOD_SURFACE_PHONG}, &s) == TLOD_SUCCESS);
  const uint16_t ij[4][2] = {{0, 0}, {1, 1}, {2, 0}, {0, 2}};
  float pos[12], nrm[12];
  CHECK(tlod_surface_eval_grid(s, 0, 1, &ij[0][0], sizeof(ij[0]), 4, pos, nrm) == TLOD_SUCCESS);
  for (int k = 0; k < 12; k++)
    CHECK(isfinite(pos[k]) && isfinite(nrm[k]));
  /* Each refused without writing a float. */
  const uint16_t off_tri[2][2] = {{1, 1}, {2, 1}}; /* i + j = 3 > 2 */
  struct {
    uint32_t patch, grid_log2;
    const uint16_t* ij;
    uint32_t count;
    float* positions;
  } bad[] = {
      {4, 1, &ij[0][0], 4, pos},
      {UINT32_MAX, 1, &ij[0][0], 4, pos},
      {0, TLOD_GRID_MAX_LOG2 + 1, &ij[0][0], 4, pos},
      {0, 40, &ij[0][0], 4, pos},
      {0, 1, &off_tri[0][0], 2, pos},
      {0, 0, &ij[0][0], 2, pos}, /* (1, 1) is off the grid of 2^0 */
      {0, 1, NULL, 4, pos},
      {0, 1, &ij[0][0], 4, NULL},
  };
  for (size_t k = 0; k < sizeof(bad) / sizeof(bad[0]); k++) {
    memset(pos, 0, sizeof(pos));
    tlod_result r = tlod_surface_eval_grid(s, bad[k].patch, bad[k].grid_log2, bad[k].ij, sizeof(ij[0]), bad[k].count,
                                           bad[k].positions, nrm);
    CHECK_MSG(r == TLOD_ERROR_INVALID_ARGUMENT, "case %zu: %s", k, tlod_result_string(r));
    CHECK_MSG(all_zero(pos, sizeof(pos)), "case %zu wrote positions", k);
  }
  CHECK(tlod_surface_eval_grid(NULL, 0, 1, &ij[0][0], sizeof(ij[0]), 4, pos, nrm) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_surface_eval_grid(s, 0, 1, NULL, 0, 0, NULL, NULL) == TLOD_SUCCESS); /* nothing to do */
  tlod_surface_destroy(s);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

TEST(grid_point_kind_off_the_grid) {
  uint32_t param = 12345;
  CHECK(tlod_grid_point_kind(3, 2, 4, 1, &param) == TLOD_GRID_OFF); /* i + j = 5 > 4 */
  CHECK(tlod_grid_point_kind(3, 2, UINT32_MAX, 1, &param) == TLOD_GRID_OFF);
  CHECK(tlod_grid_point_kind(4, 2, 5, 0, &param) == TLOD_GRID_OFF);
  CHECK(tlod_grid_point_kind(4, 2, 0, 5, &param) == TLOD_GRID_OFF);
  CHECK(tlod_grid_point_kind(3, 32, 0, 0, &param) == TLOD_GRID_OFF); /* the shift would be undefined */
  CHECK(tlod_grid_point_kind(3, TLOD_GRID_MAX_LOG2 + 1, 0, 0, &param) == TLOD_GRID_OFF);
  CHECK(tlod_grid_point_kind(5, 2, 0, 0, &param) == TLOD_GRID_OFF);
  CHECK(param == 12345);
  /* The largest grid still classifies. */
  CHECK(tlod_grid_point_kind(4, TLOD_GRID_MAX_LOG2, 1u << TLOD_GRID_MAX_LOG2, 0, &param) == 1u);
  CHECK(tlod_grid_point_kind(3, TLOD_GRID_MAX_LOG2, 1, 1, &param) == TLOD_GRID_INTERIOR);
}

TEST(indexed_queries_out_of_range) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  tlod_mesh* m = tet_mesh(ctx);
  tlod_surface* s = NULL;
  CHECK(m && tlod_surface_create(ctx, m, NULL, &s) == TLOD_SUCCESS);
  uint32_t corners[4] = {7, 7, 7, 7};
  float p[3] = {1, 1, 1}, n[3] = {1, 1, 1};
  CHECK(tlod_mesh_face_corners(m, 4, corners) == 0 && corners[0] == 7);
  CHECK(tlod_mesh_face_input_index(m, 4) == UINT32_MAX);
  CHECK(tlod_mesh_vertex_weld_id(m, 4) == UINT32_MAX);
  tlod_mesh_vertex(m, 4, p, n);
  CHECK(p[0] == 0 && n[0] == 0);
  CHECK(tlod_mesh_edge_link(m, 4, 0).face == UINT32_MAX && tlod_mesh_edge_link(m, 0, 3).face == UINT32_MAX);
  CHECK(tlod_mesh_query_finding(m, TLOD_MAX_FINDINGS).kind == TLOD_FINDING_NUM);
  tlod_patch_info info = tlod_surface_patch(s, 4);
  CHECK(all_zero(&info, sizeof(info)));
  tlod_patch_record rec[2];
  CHECK(tlod_surface_patch_records(s, 3, 2, rec) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_surface_patch_records(s, UINT32_MAX, 2, rec) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(tlod_context_last_error(ctx), "outside its 4 patches") != NULL);
  CHECK(tlod_surface_patch_records(s, 2, 2, rec) == TLOD_SUCCESS);
  tlod_surface_destroy(s);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* NULL handles: every function of tesslod/core.h                           */
/* ------------------------------------------------------------------------ */

static void count_task(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  uint32_t* sum = data;
  *sum += (end - begin) + worker * 1000u;
}

TEST(null_handles) {
  tlod_context* ctx = (tlod_context*)(uintptr_t)1;
  CHECK(tlod_context_create(NULL, NULL) == TLOD_ERROR_INVALID_ARGUMENT);
  tlod_context_destroy(NULL);
  CHECK(tlod_context_query_desc(NULL).allocator.alloc_fn == NULL);
  CHECK(strcmp(tlod_context_last_error(NULL), "") == 0);
  CHECK(tlod_context_alloc(NULL, 16) == NULL && tlod_context_calloc(NULL, 2, 8) == NULL);
  tlod_context_free(NULL, NULL);
  tlod_context_log(NULL, TLOD_LOG_ERROR, "dropped %d", 1);
  CHECK(tlod_context_fail(NULL, TLOD_ERROR_IO, "x") == TLOD_ERROR_IO);
  CHECK(tlod_context_worker_count(NULL) == 1);
  uint32_t sum = 0;
  tlod_context_parallel_for(NULL, count_task, &sum, 9);
  CHECK(sum == 9); /* on the caller, worker 0 */

  tlod_mesh* m = (tlod_mesh*)(uintptr_t)1;
  tlod_mesh_desc md = {0};
  CHECK(tlod_mesh_create(NULL, &md, &m) == TLOD_ERROR_INVALID_ARGUMENT && m == NULL);
  tlod_mesh_destroy(NULL);
  CHECK(tlod_mesh_query_info(NULL).face_count == 0);
  CHECK(tlod_mesh_query_finding(NULL, 0).kind == TLOD_FINDING_NUM);
  CHECK(tlod_mesh_face_count(NULL) == 0 && tlod_mesh_vertex_count(NULL) == 0);
  CHECK(tlod_mesh_face_input_index(NULL, 0) == UINT32_MAX && tlod_mesh_vertex_weld_id(NULL, 0) == UINT32_MAX);
  CHECK(tlod_mesh_face_corners(NULL, 0, NULL) == 0);
  tlod_mesh_vertex(NULL, 0, NULL, NULL);
  CHECK(tlod_mesh_edge_link(NULL, 0, 0).face == UINT32_MAX);
  CHECK(tlod_mesh_update(NULL, NULL, 0, NULL, 0) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_mesh_update_attribute(NULL, 0, NULL, 0) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_mesh_query_view(NULL).positions == NULL && tlod_mesh_query_view(NULL).face_nodes == NULL);

  tlod_surface* s = (tlod_surface*)(uintptr_t)1;
  CHECK(tlod_surface_create(NULL, NULL, NULL, &s) == TLOD_ERROR_INVALID_ARGUMENT && s == NULL);
  tlod_surface_destroy(NULL);
  CHECK(tlod_surface_query_desc(NULL).label == NULL);
  CHECK(tlod_surface_mesh(NULL) == NULL && tlod_surface_patch_count(NULL) == 0);
  CHECK(tlod_surface_patch(NULL, 0).corner_count == 0);
  uint32_t updated = 5;
  CHECK(tlod_surface_refresh(NULL, &updated) == TLOD_ERROR_INVALID_ARGUMENT && updated == 0);
  CHECK(tlod_surface_query_view(NULL).patches == NULL);
  CHECK(tlod_surface_patch_records(NULL, 0, 0, NULL) == TLOD_ERROR_INVALID_ARGUMENT);

  /* NULL out pointers and descs with a context: refused with a message. */
  ctx = new_context(1, NULL, NULL);
  CHECK(tlod_mesh_create(ctx, NULL, &m) == TLOD_ERROR_INVALID_ARGUMENT && m == NULL);
  CHECK(strstr(tlod_context_last_error(ctx), "desc is NULL"));
  CHECK(tlod_mesh_create(ctx, &md, NULL) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(tlod_context_last_error(ctx), "out is NULL"));
  CHECK(tlod_surface_create(ctx, NULL, NULL, &s) == TLOD_ERROR_INVALID_ARGUMENT && s == NULL);
  CHECK(strstr(tlod_context_last_error(ctx), "mesh is NULL"));
  CHECK(tlod_surface_create(ctx, NULL, NULL, NULL) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(tlod_context_last_error(ctx), "out is NULL"));
  tlod_context_destroy(ctx);
}

int main(void) {
  RUN(allocator_hooks_all_or_none);
  RUN(worker_count_bounded);
  RUN(context_create_out_of_memory);
  RUN(position_limit_at_create);
  RUN(position_limit_at_update);
  RUN(surface_eval_checks_its_arguments);
  RUN(surface_eval_grid_checks_its_arguments);
  RUN(grid_point_kind_off_the_grid);
  RUN(indexed_queries_out_of_range);
  RUN(null_handles);
  TEST_END();
}
