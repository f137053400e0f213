/* Unit tests of the lod module's names and defaults: the enum name tables
 * (tesslod/lod.h, tesslod/patterns.h), the desc defaults, and
 * TLOD_POLICY_FLAT (level 0 everywhere, no strips). Public API only. */
#include <stdint.h>

#include "shapes.h"
#include "tesslod/lod.h"
#include "test.h"
#include "test_names.h"

/* ------------------------------------------------------------------------ */
/* Enum names                                                               */
/* ------------------------------------------------------------------------ */

DEFINE_NAMES_CHECK(tlod_lod_policy, tlod_lod_policy, TLOD_LOD_POLICY_NAMES, TLOD_POLICY_NUM)
DEFINE_NAMES_CHECK(tlod_morph_mode, tlod_morph_mode, TLOD_MORPH_MODE_NAMES, TLOD_MORPH_NUM)
DEFINE_NAMES_CHECK(tlod_stage, tlod_stage, TLOD_STAGE_NAMES, TLOD_STAGE_NUM)
DEFINE_NAMES_CHECK(tlod_pattern_shape, tlod_pattern_shape, TLOD_PATTERN_SHAPE_NAMES, TLOD_PATTERN_SHAPE_NUM)

TEST(test_policy_and_morph_names) {
  /* Every value but DEFAULT has a table entry. */
  CALL(tlod_lod_policy_names_check(TLOD_POLICY_NUM - 1));
  CALL(tlod_morph_mode_names_check(TLOD_MORPH_NUM - 1));
  /* DEFAULT prints as what it resolves to; the tools' spellings. */
  CHECK(strcmp(tlod_lod_policy_name(TLOD_POLICY_DEFAULT), "hybrid") == 0);
  CHECK(strcmp(tlod_morph_mode_name(TLOD_MORPH_DEFAULT), "time") == 0);
  const char* policies[] = {"error", "silhouette", "hybrid", "uniform", "flat"};
  for (int p = 0; p < 5; p++)
    CHECK(strcmp(tlod_lod_policy_name((tlod_lod_policy)(TLOD_POLICY_ERROR + p)), policies[p]) == 0);
  CHECK(strcmp(tlod_morph_mode_name(TLOD_MORPH_CONTINUOUS), "continuous") == 0);
}

TEST(test_stage_and_shape_names) {
  /* No DEFAULT: every value has an entry. */
  CALL(tlod_stage_names_check(TLOD_STAGE_NUM));
  CALL(tlod_pattern_shape_names_check(TLOD_PATTERN_SHAPE_NUM));
  /* The spellings of the tools' stage columns, in enum order. */
  const char* stages[TLOD_STAGE_NUM] = {"silhouette", "metric", "levels", "morph", "strips"};
  for (int s = 0; s < TLOD_STAGE_NUM; s++)
    CHECK(strcmp(tlod_stage_name((tlod_stage)s), stages[s]) == 0);
  CHECK(strcmp(tlod_pattern_shape_name(TLOD_PATTERN_QUAD), "quad") == 0);
}

/* ------------------------------------------------------------------------ */
/* Scheduler fixtures                                                       */
/* ------------------------------------------------------------------------ */

typedef struct fixture {
  tlod_context* ctx;
  tlod_mesh* mesh;
  tlod_surface* surface;
  tlod_patterns* patterns;
} fixture;

static bool fixture_make(fixture* fx, shape s, tlod_surface_type type) {
  memset(fx, 0, sizeof *fx);
  tlod_context_create(&(tlod_context_desc){.thread_count = 2}, &fx->ctx);
  tlod_mesh_desc md = shape_mesh_desc(&s);
  bool ok = tlod_mesh_create(fx->ctx, &md, &fx->mesh) == TLOD_SUCCESS &&
            tlod_surface_create(fx->ctx, fx->mesh, &(tlod_surface_desc){.type = type}, &fx->surface) == TLOD_SUCCESS &&
            tlod_patterns_create(fx->ctx, &(tlod_patterns_desc){.max_level = 5}, &fx->patterns) == TLOD_SUCCESS;
  shape_free(&s);
  return ok;
}

static void fixture_free(fixture* fx) {
  tlod_patterns_destroy(fx->patterns);
  tlod_surface_destroy(fx->surface);
  tlod_mesh_destroy(fx->mesh);
  tlod_context_destroy(fx->ctx);
}

/* A camera on the +z axis at (x, 0, z) looking down -z: the view matrix is
 * a translation, the projection a 60 degree GL perspective. */
static tlod_view_desc axis_view(float x, float z) {
  tlod_view_desc v = {.viewport_width = 800, .viewport_height = 600};
  for (int k = 0; k < 4; k++)
    v.view[5 * k] = 1.0f;
  v.view[12] = -x, v.view[14] = -z;
  float f = 1.7320508f, n = 0.05f, far = 100.0f;
  v.proj[0] = f * 600.0f / 800.0f, v.proj[5] = f;
  v.proj[10] = (far + n) / (n - far), v.proj[11] = -1.0f, v.proj[14] = 2.0f * far * n / (n - far);
  return v;
}

static const tlod_draw_list* plan(tlod_scheduler* s, tlod_view_desc v) {
  tlod_frame_desc fr = {.views = &v, .view_count = 1, .dt_ms = 16.0f};
  return tlod_scheduler_update(s, &fr) == TLOD_SUCCESS ? tlod_scheduler_draw_list(s, 0) : NULL;
}

/* ------------------------------------------------------------------------ */
/* Defaults                                                                 */
/* ------------------------------------------------------------------------ */

TEST(test_desc_defaults) {
  fixture fx;
  CHECK(fixture_make(&fx, shape_icosphere(1), TLOD_SURFACE_PN));
  tlod_scheduler* s = NULL;
  CHECK(tlod_scheduler_create(fx.ctx, fx.surface, fx.patterns, &(tlod_scheduler_desc){0}, &s) == TLOD_SUCCESS);
  tlod_scheduler_desc d = tlod_scheduler_query_desc(s);
  CHECK(d.epsilon_px == 0.5f && d.max_level == 5 && d.policy == TLOD_POLICY_HYBRID && d.morph == TLOD_MORPH_TIME);
  CHECK(d.silhouette_depth == 32.0f && d.hybrid_relax == 16.0f && d.morph_ms == 200.0f);
  CHECK(d.triangle_budget == 0 && d.frame_time_target_ms == 0.0f && !d.no_frustum_cull);
  CHECK(strcmp(d.label, "scheduler") == 0);
  tlod_scheduler_destroy(s);
  /* Values that zero does not stand for are refused, naming the field. */
  tlod_scheduler_desc bad[] = {{.hybrid_relax = 0.5f},
                               {.epsilon_px = -1.0f},
                               {.morph_ms = -1.0f},
                               {.silhouette_depth = -2.0f},
                               {.policy = TLOD_POLICY_NUM}};
  const char* field[] = {"hybrid_relax", "epsilon_px", "morph_ms", "silhouette_depth", "policy"};
  for (int k = 0; k < 5; k++) {
    CHECK(tlod_scheduler_create(fx.ctx, fx.surface, fx.patterns, &bad[k], &s) == TLOD_ERROR_INVALID_ARGUMENT);
    CHECK_MSG(s == NULL && strstr(tlod_context_last_error(fx.ctx), field[k]), "%s", tlod_context_last_error(fx.ctx));
  }
  fixture_free(&fx);
}

/* ------------------------------------------------------------------------ */
/* TLOD_POLICY_FLAT                                                         */
/* ------------------------------------------------------------------------ */

/* Level 0 on every visible patch, exact vertices, no strip, level-0
 * buckets only, and the same culling and e_max as a refining policy. */
static void check_flat(const tlod_draw_list* flat, const tlod_draw_list* error, uint32_t* refined) {
  CHECK(flat && error && flat->patch_count == error->patch_count);
  CHECK(flat->strip_count == 0 && flat->strip_triangles == 0);
  uint32_t visible = 0;
  for (uint32_t f = 0; f < flat->patch_count; f++) {
    CHECK_MSG(flat->levels[f] == (error->levels[f] < 0 ? -1 : 0), "patch %u level %d", f, flat->levels[f]);
    CHECK(memcmp(&flat->e_max[f], &error->e_max[f], sizeof(float)) == 0);
    visible += flat->levels[f] == 0;
    *refined += error->levels[f] > 0;
  }
  CHECK(flat->instance_count == visible && flat->level_histogram[0] == visible && flat->culled == error->culled);
  for (uint32_t b = 0; b < flat->bucket_count; b++)
    CHECK(flat->buckets[b].level == 0);
  for (uint32_t i = 0; i < flat->instance_count; i++) {
    const tlod_draw_instance* in = &flat->instances[i];
    CHECK(in->level == 0 && in->morph == 1.0f);
  }
}

TEST(test_policy_flat) {
  struct {
    shape s;
    tlod_surface_type t;
  } cases[] = {{shape_icosphere(2), TLOD_SURFACE_PN},
               {shape_cube_soft(), TLOD_SURFACE_PN}, /* creases: strips at level 0 too, were they drawn */
               {shape_quad_sphere(3), TLOD_SURFACE_PHONG}};
  uint32_t refined = 0;
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    fixture fx;
    CHECK(fixture_make(&fx, cases[k].s, cases[k].t));
    /* Whatever epsilon, budget and max level ask for. */
    tlod_scheduler_desc fd = {.policy = TLOD_POLICY_FLAT, .epsilon_px = 1e-3f, .triangle_budget = 1, .max_level = 5};
    tlod_scheduler_desc ed = {.policy = TLOD_POLICY_ERROR, .epsilon_px = 1e-3f, .morph = TLOD_MORPH_NONE};
    tlod_scheduler *flat = NULL, *error = NULL;
    CHECK(tlod_scheduler_create(fx.ctx, fx.surface, fx.patterns, &fd, &flat) == TLOD_SUCCESS);
    CHECK(tlod_scheduler_create(fx.ctx, fx.surface, fx.patterns, &ed, &error) == TLOD_SUCCESS);
    const float cams[4][2] = {{0.0f, 4.0f}, {0.3f, 1.6f}, {2.5f, 2.0f}, {0.0f, 0.2f}};
    for (int c = 0; c < 4; c++) {
      const tlod_draw_list* a = plan(flat, axis_view(cams[c][0], cams[c][1]));
      const tlod_draw_list* b = plan(error, axis_view(cams[c][0], cams[c][1]));
      CHECK_MSG(a && b, "%s camera %d", tlod_context_last_error(fx.ctx), c);
      int before = _test_checks_failed;
      check_flat(a, b, &refined);
      CHECK_MSG(_test_checks_failed == before, "case %zu camera %d", k, c);
    }
    tlod_scheduler_destroy(flat);
    tlod_scheduler_destroy(error);
    fixture_free(&fx);
  }
  CHECK(refined > 0); /* the cameras do ask for refinement */
}

int main(void) {
  RUN(test_policy_and_morph_names);
  RUN(test_stage_and_shape_names);
  RUN(test_desc_defaults);
  RUN(test_policy_flat);
  TEST_END();
}
