/* The NULL and contract policy of tesslod/backend.h (section CONTRACT, after
 * tesslod/core.h): NULL handles in every function, and the draw-list checks
 * of tlod_device_draw (every index a backend reads: instance patches and
 * levels, strip patches and edges, the arrays behind every count), on the
 * "null" and "cpu" backends. Public API only. */
#include <stdint.h>

#include "shapes.h"
#include "tesslod/backend.h"
#include "tesslod/cpu.h"
#include "test.h"
#include "test_camera.h"
#include "test_context.h"
#include "test_pipeline.h"

static const camera k_camera = {
    {0, -4, 1}, {0, 0, 0}, {0, 0, 1}, 1.0, 0, 4.0 / 3.0, 0.1, 20, false, 320, 240,
};

TEST(null_handles) {
  tlod_device* dev = (tlod_device*)(uintptr_t)1;
  CHECK(tlod_device_create(NULL, NULL, &dev) == TLOD_ERROR_INVALID_ARGUMENT && dev == NULL);
  tlod_device_destroy(NULL);
  CHECK(strcmp(tlod_device_backend(NULL), "") == 0);
  tlod_device_surface* ds = (tlod_device_surface*)(uintptr_t)1;
  CHECK(tlod_device_create_surface(NULL, NULL, &ds) == TLOD_ERROR_INVALID_ARGUMENT && ds == NULL);
  CHECK(tlod_device_update_surface(NULL, NULL) == TLOD_ERROR_INVALID_ARGUMENT);
  tlod_device_destroy_surface(NULL, NULL);
  CHECK(tlod_device_draw(NULL, NULL) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_device_read_image(NULL, 1, 1, NULL) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_device_query_stats(NULL).draws == 0 && tlod_device_query_stats(NULL).gpu_ms < 0);
  CHECK(tlod_device_query_item_stats(NULL, 0).triangles == 0);
  CHECK(tlod_cpu_device_mesh(NULL, 0) == NULL);
}

typedef struct fixture {
  test_pipeline p;
  const tlod_draw_list* dl;
  tlod_device* dev;
  tlod_device_surface* ds;
} fixture;

static void fixture_free(fixture* f) {
  tlod_device_destroy(f->dev);
  test_pipeline_free(&f->p);
}

/* A torus seen from k_camera: strips (levels differ) and instances. */
static bool fixture_make(fixture* f, const char* backend) {
  memset(f, 0, sizeof *f);
  tlod_view_desc v = make_view(&k_camera);
  test_pipeline* p = &f->p;
  bool ok = test_pipeline_make(p, shape_torus(12, 8), 4, (tlod_scheduler_desc){.epsilon_px = 0.2f}) &&
            tlod_scheduler_update(p->sched, &(tlod_frame_desc){.views = &v, .view_count = 1}) == TLOD_SUCCESS &&
            tlod_device_create(p->ctx, &(tlod_device_desc){.backend = backend, .patterns = p->pat}, &f->dev) ==
                TLOD_SUCCESS &&
            tlod_device_create_surface(f->dev, p->surf, &f->ds) == TLOD_SUCCESS;
  f->dl = ok ? tlod_scheduler_draw_list(p->sched, 0) : NULL;
  return f->dl && f->dl->strip_count > 0 && f->dl->instance_count > 0;
}

static tlod_result draw_with(fixture* f, const tlod_draw_list* dl) {
  tlod_draw_item item = {.surface = f->ds, .draw_list = dl};
  tlod_view_desc v = make_view(&k_camera);
  tlod_draw_desc d = {.items = &item, .item_count = 1, .viewport = {0, 0, 320, 240}};
  memcpy(d.view, v.view, sizeof d.view);
  memcpy(d.proj, v.proj, sizeof d.proj);
  return tlod_device_draw(f->dev, &d);
}

/* Each broken copy of a good draw list is refused naming what is wrong, and
 * nothing is drawn (the draw counter stays). */
static void check_draw_lists(const char* backend) {
  fixture f;
  CHECK_MSG(fixture_make(&f, backend), "%s fixture", backend);
  CHECK(draw_with(&f, f.dl) == TLOD_SUCCESS);
  uint64_t draws = tlod_device_query_stats(f.dev).draws;
  tlod_draw_instance inst[512];
  tlod_draw_strip strips[512];
  CHECK(f.dl->instance_count <= 512 && f.dl->strip_count <= 512);
  int8_t levels[4096];
  CHECK(f.dl->patch_count <= 4096);
  for (int c = 0; c < 9; c++) {
    tlod_draw_list dl = *f.dl;
    memcpy(inst, f.dl->instances, sizeof(*inst) * dl.instance_count);
    memcpy(strips, f.dl->strips, sizeof(*strips) * dl.strip_count);
    memcpy(levels, f.dl->levels, dl.patch_count);
    dl.instances = inst;
    dl.strips = strips;
    dl.levels = levels;
    const char* want = NULL;
    switch (c) {
    case 0:
      inst[0].patch = dl.patch_count, want = "instance 0 (patch";
      break;
    case 1:
      inst[dl.instance_count - 1].patch = UINT32_MAX, want = "instance";
      break;
    case 2:
      inst[0].level = 5, want = "instance 0 (patch";
      break;
    case 3:
      strips[0].edge_a = 3, want = "strip 0: edge 3";
      break; /* a triangle's edges are 0..2 */
    case 4:
      strips[0].edge_b = 200, want = "strip 0: edge";
      break;
    case 7:
      levels[1] = 5, want = "patch 1: level 5 outside [-1, 4]";
      break;
    case 8:
      levels[dl.patch_count - 1] = -2, want = "level -2";
      break;
    case 5:
      dl.levels = NULL, want = "draw list levels is NULL";
      break;
    default:
      dl.instances = NULL, want = "draw list instances is NULL";
      break;
    }
    tlod_result r = draw_with(&f, &dl);
    const char* e = tlod_context_last_error(f.p.ctx);
    CHECK_MSG(r == TLOD_ERROR_INVALID_ARGUMENT && strstr(e, want), "%s case %d: %s: '%s'", backend, c,
              tlod_result_string(r), e);
    CHECK(tlod_device_query_stats(f.dev).draws == draws);
  }
  fixture_free(&f);
}

TEST(draw_list_indices_checked) {
  CALL(check_draw_lists("null"));
  CALL(check_draw_lists("cpu"));
}

int main(void) {
  RUN(null_handles);
  RUN(draw_list_indices_checked);
  TEST_END();
}
