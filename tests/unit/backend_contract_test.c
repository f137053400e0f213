/* The NULL and contract policy of tesslod/backend.h (section CONTRACT, after
 * tesslod/core.h): NULL handles in every function, the draw-list checks
 * of tlod_device_draw (every index a backend reads: instance patches and
 * levels, strip patches and edges, the arrays behind every count), the
 * texture desc checks and the material checks of draw items (texture of
 * another device, texcoord attribute, blend mode, cutoff), on the "null" and
 * "cpu" backends. Public API only. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

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
  tlod_device_texture* tex = (tlod_device_texture*)(uintptr_t)1;
  CHECK(tlod_device_create_texture(NULL, NULL, &tex) == TLOD_ERROR_INVALID_ARGUMENT && tex == NULL);
  tlod_device_destroy_texture(NULL, NULL);
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

static const uint8_t k_texels[4 * 4] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};

/* Every wrong field of a texture desc is refused naming it; nothing is
 * counted; good ones are counted, destroyed, and the device destroys those
 * left. */
static void check_textures(const char* backend) {
  fixture f;
  CHECK_MSG(fixture_make(&f, backend), "%s fixture", backend);
  const tlod_texture_desc good = {.width = 2, .height = 2, .rgba8 = k_texels, .label = "checker"};
  tlod_device_texture* t = NULL;
  CHECK(tlod_device_create_texture(f.dev, NULL, &t) == TLOD_ERROR_INVALID_ARGUMENT && !t);
  CHECK(strstr(tlod_context_last_error(f.p.ctx), "desc is NULL"));
  CHECK(tlod_device_create_texture(f.dev, &good, NULL) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(tlod_context_last_error(f.p.ctx), "out is NULL"));
  for (int c = 0; c < 8; c++) {
    tlod_texture_desc d = good;
    const char* want = NULL;
    switch (c) {
    case 0:
      d.rgba8 = NULL, want = "texture 'checker': rgba8 is NULL";
      break;
    case 1:
      d.width = 0, want = "width 0 outside [1, 16384]";
      break;
    case 2:
      d.height = TLOD_TEXTURE_MAX_SIZE + 1, want = "height 16385 outside";
      break;
    case 3:
      d.wrap_s = TLOD_WRAP_NUM, want = "wrap_s 4";
      break;
    case 4:
      d.wrap_t = (tlod_wrap)-1, want = "wrap_t";
      break;
    case 5:
      d.min_filter = TLOD_FILTER_NUM, want = "min_filter 3";
      break;
    case 6:
      d.mag_filter = (tlod_filter)77, want = "mag_filter 77";
      break;
    default:
      d.width = TLOD_TEXTURE_MAX_SIZE + 5, want = "width 16389";
      break;
    }
    tlod_result r = tlod_device_create_texture(f.dev, &d, &t);
    const char* e = tlod_context_last_error(f.p.ctx);
    CHECK_MSG(r == TLOD_ERROR_INVALID_ARGUMENT && !t && strstr(e, want), "%s case %d: %s: '%s'", backend, c,
              tlod_result_string(r), e);
  }
  CHECK(tlod_device_query_stats(f.dev).textures_created == 0);
  tlod_device_texture *a = NULL, *b = NULL;
  CHECK(tlod_device_create_texture(f.dev, &good, &a) == TLOD_SUCCESS && a);
  CHECK(tlod_device_create_texture(f.dev, &(tlod_texture_desc){.width = 1, .height = 1, .rgba8 = k_texels}, &b) ==
        TLOD_SUCCESS);
  tlod_device_stats st = tlod_device_query_stats(f.dev);
  CHECK(st.textures_live == 2 && st.textures_created == 2 && st.texture_bytes == 20);
  tlod_device_destroy_texture(f.dev, a);
  st = tlod_device_query_stats(f.dev);
  CHECK(st.textures_live == 1 && st.textures_destroyed == 1);
  /* b is left to tlod_device_destroy (ASan's leak check sees it freed) */
  fixture_free(&f);
}

TEST(textures_checked) {
  CALL(check_textures("null"));
  CALL(check_textures("cpu"));
}

/* A copy of the fixture's surface whose mesh has a 1-component and a
 * 2-component attribute (the draw list fits it: same shape). */
typedef struct attr_surface {
  tlod_mesh* mesh;
  tlod_surface* surf;
  tlod_device_surface* ds;
  float* data;
} attr_surface;

static bool attr_surface_make(attr_surface* a, fixture* f) {
  memset(a, 0, sizeof *a);
  uint32_t n = f->p.sh.vertex_count;
  a->data = calloc(3 * (size_t)n, sizeof(float));
  if (!a->data) return false;
  tlod_attribute_desc attrs[2] = {{.data = a->data, .components = 1, .name = "WEIGHT"},
                                  {.data = a->data + n, .components = 2, .name = "TEXCOORD_0"}};
  tlod_mesh_desc md = shape_mesh_desc(&f->p.sh);
  md.attributes = attrs;
  md.attribute_count = 2;
  return tlod_mesh_create(f->p.ctx, &md, &a->mesh) == TLOD_SUCCESS &&
         tlod_surface_create(f->p.ctx, a->mesh, &(tlod_surface_desc){.label = "uv_torus"}, &a->surf) == TLOD_SUCCESS &&
         tlod_device_create_surface(f->dev, a->surf, &a->ds) == TLOD_SUCCESS;
}

static void attr_surface_free(attr_surface* a, fixture* f) {
  tlod_device_destroy_surface(f->dev, a->ds);
  tlod_surface_destroy(a->surf);
  tlod_mesh_destroy(a->mesh);
  free(a->data);
}

/* Each wrong material of a good item is refused naming the item and what
 * is wrong, and nothing is drawn; the good textured item draws. */
static void check_materials(const char* backend) {
  fixture f, other;
  CHECK_MSG(fixture_make(&f, backend), "%s fixture", backend);
  CHECK_MSG(fixture_make(&other, backend), "%s second fixture", backend);
  attr_surface as;
  CHECK(attr_surface_make(&as, &f));
  const tlod_texture_desc td = {.width = 2, .height = 2, .rgba8 = k_texels, .label = "checker"};
  tlod_device_texture *mine = NULL, *theirs = NULL;
  CHECK(tlod_device_create_texture(f.dev, &td, &mine) == TLOD_SUCCESS);
  CHECK(tlod_device_create_texture(other.dev, &td, &theirs) == TLOD_SUCCESS);
  tlod_view_desc v = make_view(&k_camera);
  tlod_draw_item good = {.surface = as.ds, .draw_list = f.dl, .base_color_texture = mine, .base_color_texcoord = 1};
  tlod_draw_desc d = {.items = &good, .item_count = 1, .viewport = {0, 0, 320, 240}};
  memcpy(d.view, v.view, sizeof d.view);
  memcpy(d.proj, v.proj, sizeof d.proj);
  tlod_result r = tlod_device_draw(f.dev, &d);
  CHECK_MSG(r == TLOD_SUCCESS, "%s: good textured item: %s", tlod_result_string(r), tlod_context_last_error(f.p.ctx));
  uint64_t draws = tlod_device_query_stats(f.dev).draws;
  for (int c = 0; c < 7; c++) {
    tlod_draw_item it = good;
    const char* want = NULL;
    switch (c) {
    case 0:
      it.base_color_texture = theirs, want = "item 0: base_color_texture 'checker' belongs to another device";
      break;
    case 1:
      it.base_color_texcoord = 2, want = "base_color_texcoord 2 is not an attribute of surface 'uv_torus' (2";
      break;
    case 2:
      it.base_color_texcoord = 0, want = "base_color_texcoord 0 ('WEIGHT') of surface 'uv_torus' has 1 component";
      break;
    case 3:
      it.surface = f.ds, want = "is not an attribute of surface"; /* a mesh without attributes */
      break;
    case 4:
      it.blend = TLOD_BLEND_NUM, want = "item 0: blend 3 is not a tlod_blend_mode";
      break;
    case 5:
      it.has_alpha_cutoff = true, it.alpha_cutoff = NAN, want = "item 0: alpha_cutoff is not finite";
      break;
    default:
      it.has_alpha_cutoff = true, it.alpha_cutoff = INFINITY, want = "alpha_cutoff is not finite";
      break;
    }
    d.items = &it;
    r = tlod_device_draw(f.dev, &d);
    const char* e = tlod_context_last_error(f.p.ctx);
    CHECK_MSG(r == TLOD_ERROR_INVALID_ARGUMENT && strstr(e, want), "%s case %d: %s: '%s'", backend, c,
              tlod_result_string(r), e);
    CHECK(tlod_device_query_stats(f.dev).draws == draws);
  }
  /* a texcoord without a texture is not read: no check */
  tlod_draw_item plain = {.surface = f.ds, .draw_list = f.dl, .base_color_texcoord = 7, .blend = TLOD_BLEND_MASK};
  d.items = &plain;
  CHECK(tlod_device_draw(f.dev, &d) == TLOD_SUCCESS);
  tlod_device_destroy_texture(f.dev, theirs); /* refused: not destroyed, named */
  CHECK(strstr(tlod_context_last_error(f.p.ctx), "texture 'checker' belongs to another device"));
  CHECK(tlod_device_query_stats(other.dev).textures_live == 1);
  attr_surface_free(&as, &f);
  fixture_free(&other);
  fixture_free(&f);
}

TEST(materials_checked) {
  CALL(check_materials("null"));
  CALL(check_materials("cpu"));
}

int main(void) {
  RUN(null_handles);
  RUN(draw_list_indices_checked);
  RUN(textures_checked);
  RUN(materials_checked);
  TEST_END();
}
