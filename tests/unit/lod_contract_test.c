/* The NULL and contract policy of tesslod/lod.h and tesslod/patterns.h
 * (section CONTRACT of each, after tesslod/core.h): NULL handles in every
 * function, range checks of every index, level, shape and view argument,
 * the frame checks naming the view. Public API only. */
#include <stdint.h>

#include "shapes.h"
#include "tesslod/lod.h"
#include "test.h"
#include "test_camera.h"
#include "test_context.h"
#include "test_pipeline.h"

static const camera k_camera = {
    {0, -4, 1}, {0, 0, 0}, {0, 0, 1}, 1.0, 0, 4.0 / 3.0, 0.1, 20, false, 320, 240,
};

static bool fixture_make(test_pipeline* f) {
  return test_pipeline_make(f, shape_icosphere(1), 3, (tlod_scheduler_desc){0});
}

TEST(null_handles) {
  tlod_patterns* pat = (tlod_patterns*)(uintptr_t)1;
  CHECK(tlod_patterns_create(NULL, NULL, &pat) == TLOD_ERROR_INVALID_ARGUMENT && pat == NULL);
  tlod_patterns_destroy(NULL);
  uint32_t count = 7;
  CHECK(tlod_patterns_max_level(NULL) == 0);
  CHECK(tlod_patterns_vertices(NULL, TLOD_PATTERN_TRIANGLE, &count) == NULL && count == 0);
  count = 7;
  CHECK(tlod_patterns_indices(NULL, TLOD_PATTERN_QUAD, 0, &count) == NULL && count == 0);
  uint32_t edge[2] = {9, 9};
  CHECK(tlod_patterns_edge(NULL, TLOD_PATTERN_TRIANGLE, 0, 0, edge) == 0 && edge[0] == 9);
  size_t separate = 3;
  CHECK(tlod_patterns_memory(NULL, &separate) == 0 && separate == 0);
  count = 7;
  CHECK(tlod_patterns_connection(NULL, 0, 0, &count) == NULL && count == 0);

  tlod_scheduler* s = (tlod_scheduler*)(uintptr_t)1;
  CHECK(tlod_scheduler_create(NULL, NULL, NULL, NULL, &s) == TLOD_ERROR_INVALID_ARGUMENT && s == NULL);
  tlod_scheduler_destroy(NULL);
  tlod_scheduler_desc d = tlod_scheduler_query_desc(NULL);
  CHECK(d.epsilon_px == 0.0f && d.label == NULL);
  CHECK(tlod_scheduler_update(NULL, NULL) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_scheduler_draw_list(NULL, 0) == NULL);
  tlod_scheduler_reset(NULL);

  /* With a context, NULL out pointers and objects are refused with a message. */
  tlod_context* ctx = new_context(1, NULL, NULL);
  CHECK(tlod_patterns_create(ctx, NULL, NULL) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(tlod_context_last_error(ctx), "out is NULL"));
  CHECK(tlod_scheduler_create(ctx, NULL, NULL, NULL, &s) == TLOD_ERROR_INVALID_ARGUMENT && s == NULL);
  CHECK(strstr(tlod_context_last_error(ctx), "NULL argument"));
  tlod_context_destroy(ctx);
}

TEST(pattern_ranges) {
  test_pipeline f;
  CHECK(fixture_make(&f));
  tlod_patterns* pat = (tlod_patterns*)(uintptr_t)1;
  CHECK(tlod_patterns_create(f.ctx, &(tlod_patterns_desc){.max_level = TLOD_MAX_LEVEL + 1}, &pat) ==
            TLOD_ERROR_INVALID_ARGUMENT &&
        pat == NULL);
  CHECK(strstr(tlod_context_last_error(f.ctx), "max_level 11"));
  const tlod_pattern_shape bad_shape = (tlod_pattern_shape)2;
  uint32_t count = 7, out[16];
  CHECK(tlod_pattern_vertex_count(bad_shape, 0) == 0 && tlod_pattern_vertex_count(TLOD_PATTERN_QUAD, 11) == 0);
  CHECK(tlod_pattern_triangle_count(bad_shape, 0) == 0 && tlod_pattern_triangle_count(TLOD_PATTERN_QUAD, 11) == 0);
  CHECK(tlod_patterns_vertices(f.pat, bad_shape, &count) == NULL && count == 0);
  CHECK(tlod_patterns_indices(f.pat, TLOD_PATTERN_TRIANGLE, 4, &count) == NULL && count == 0);
  CHECK(tlod_patterns_indices(f.pat, bad_shape, 0, &count) == NULL);
  CHECK(tlod_patterns_edge(f.pat, TLOD_PATTERN_TRIANGLE, 1, 3, out) == 0); /* triangles have edges 0..2 */
  CHECK(tlod_patterns_edge(f.pat, TLOD_PATTERN_QUAD, 1, 3, out) == 3);
  CHECK(tlod_patterns_edge(f.pat, TLOD_PATTERN_QUAD, 4, 0, out) == 0);
  CHECK(tlod_patterns_edge(f.pat, TLOD_PATTERN_QUAD, 1, 0, NULL) == 0);
  CHECK(tlod_patterns_connection(f.pat, 4, 0, &count) == NULL && count == 0);
  CHECK(tlod_patterns_connection(f.pat, 0, UINT32_MAX, &count) == NULL);
  uint32_t param = 5;
  CHECK(tlod_pattern_vertex_kind(bad_shape, 3, 0, 0, &param) == TLOD_PATTERN_KIND_OFF);
  CHECK(tlod_pattern_vertex_kind(TLOD_PATTERN_TRIANGLE, 3, 8, 1, &param) == TLOD_PATTERN_KIND_OFF);
  CHECK(tlod_pattern_vertex_kind(TLOD_PATTERN_QUAD, 3, 8, 8, &param) == 2u && param == 5);
  test_pipeline_free(&f);
}

TEST(frame_checks_name_the_view) {
  test_pipeline f;
  CHECK(fixture_make(&f));
  tlod_view_desc views[2] = {make_view(&k_camera), make_view(&k_camera)};
  tlod_frame_desc fr = {.views = views, .view_count = 2};
  CHECK(tlod_scheduler_update(f.sched, &fr) == TLOD_SUCCESS);
  CHECK(tlod_scheduler_draw_list(f.sched, 1) != NULL && tlod_scheduler_draw_list(f.sched, 2) == NULL);
  CHECK(tlod_scheduler_draw_list(f.sched, UINT32_MAX) == NULL);
  views[1].viewport_height = 0;
  CHECK(tlod_scheduler_update(f.sched, &fr) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(tlod_context_last_error(f.ctx), "view 1:"));
  views[1] = make_view(&k_camera);
  views[1].proj[3] = NAN;
  CHECK(tlod_scheduler_update(f.sched, &fr) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(tlod_context_last_error(f.ctx), "view 1:"));
  fr.view_count = 0;
  CHECK(tlod_scheduler_update(f.sched, &fr) == TLOD_ERROR_INVALID_ARGUMENT);
  fr = (tlod_frame_desc){.views = views, .view_count = 1, .dt_ms = NAN};
  CHECK(tlod_scheduler_update(f.sched, &fr) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(tlod_context_last_error(f.ctx), "dt_ms"));
  CHECK(tlod_scheduler_update(f.sched, NULL) == TLOD_ERROR_INVALID_ARGUMENT);
  /* A scheduler whose max_level is past its patterns is refused. */
  tlod_scheduler* s = NULL;
  CHECK(tlod_scheduler_create(f.ctx, f.surf, f.pat, &(tlod_scheduler_desc){.max_level = 4}, &s) ==
        TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(tlod_context_last_error(f.ctx), "max_level is above"));
  tlod_scheduler_reset(f.sched);
  CHECK(tlod_scheduler_query_desc(f.sched).max_level == 3);
  test_pipeline_free(&f);
}

int main(void) {
  RUN(null_handles);
  RUN(pattern_ranges);
  RUN(frame_checks_name_the_view);
  TEST_END();
}
