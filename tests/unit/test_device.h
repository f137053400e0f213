/*
 * test_device.h -- fixtures shared by the GPU device tests (tests/gl and
 * tests/vk), independent of the graphics API: cameras framing a
 * unit-radius-ish object, a shape's mesh + surface (+ device surface),
 * schedulers and one-frame plans, the CPU reference realisation, a one-item
 * draw desc and the tests' background colour. Header-only (every function
 * static); GL specifics stay in tests/gl/gl_test.h, Vulkan ones in
 * tests/vk/vk_test.h.
 */
#ifndef TLOD_TEST_DEVICE_H
#define TLOD_TEST_DEVICE_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "shapes.h"
#include "tesslod/backend.h"
#include "tesslod/cpu.h"
#include "tesslod/lod.h"
#include "test.h"
#include "test_camera.h"
#include "test_lod.h"

/* Like TEST_END, but a failed run exits with _Exit: the early returns of a
 * failed check leave objects behind, and LeakSanitizer's report of them
 * would only bury the message that matters. */
#define DEVICE_TEST_END()                                                                                              \
  do {                                                                                                                 \
    if (_test_failed) {                                                                                                \
      printf("%d passed, %d failed\n", _test_passed, _test_failed);                                                    \
      fflush(stdout);                                                                                                  \
      fflush(stderr);                                                                                                  \
      _Exit(1);                                                                                                        \
    }                                                                                                                  \
    TEST_END();                                                                                                        \
  } while (0)

/* ------------------------------------------------------------------------ */
/* Cameras (test_camera.h: double precision, stored as float)               */
/* ------------------------------------------------------------------------ */

/* Camera at eye looking at target; near / far hug a unit-radius-ish object
 * (24-bit depth keeps plenty of precision). */
static inline camera camera_look(double ex, double ey, double ez, double tx, double ty, double tz, double fovy_deg,
                                 uint32_t w, uint32_t h) {
  camera c = {.eye = {ex, ey, ez}, .target = {tx, ty, tz}, .up = {0, 0, 1}, .fovy = fovy_deg * SHAPES_PI / 180.0};
  double d[3] = {tx - ex, ty - ey, tz - ez};
  double dist = len3(d);
  shape_normalize3(d);
  if (fabs(d[2]) > 0.95) c.up[0] = 0, c.up[1] = 1, c.up[2] = 0;
  c.znear = dist > 3.0 ? dist - 2.5 : 0.05;
  c.zfar = dist + 3.0;
  c.width = w, c.height = h;
  c.aspect = (double)w / h;
  return c;
}

static inline void camera_print(const camera* c, char* buf, size_t size) {
  snprintf(buf, size, "eye (%.4f, %.4f, %.4f) target (%.4f, %.4f, %.4f) up (%.0f, %.0f, %.0f) fovy %.1f deg", c->eye[0],
           c->eye[1], c->eye[2], c->target[0], c->target[1], c->target[2], c->up[0], c->up[1], c->up[2],
           c->fovy * 180.0 / SHAPES_PI);
}

/* A random camera: 40% near (1.3-2.2 x the bounding radius), 30% far
 * (4-12), 30% grazing (near, aimed past the object so its silhouette
 * crosses the image at a steep angle). Always outside the object. */
static inline camera random_camera(shape_rng* rng, uint32_t w, uint32_t h) {
  double dir[3], off[3];
  shape_rng_direction(rng, dir);
  shape_rng_direction(rng, off);
  double u = shape_rng_unit(rng), dist, aim = 0.0;
  if (u < 0.4) {
    dist = shape_rng_range(rng, 1.9, 3.0);
  } else if (u < 0.7) {
    dist = shape_rng_range(rng, 4.0, 12.0);
  } else {
    dist = shape_rng_range(rng, 1.9, 2.6);
    aim = shape_rng_range(rng, 0.6, 1.1);
  }
  double fov = shape_rng_range(rng, 30.0, 75.0);
  return camera_look(dist * dir[0], dist * dir[1], dist * dir[2], aim * off[0], aim * off[1], aim * off[2], fov, w, h);
}

/* ------------------------------------------------------------------------ */
/* tesslod fixtures                                                         */
/* ------------------------------------------------------------------------ */

/* A shape's mesh and surface on patterns of the test's (a device is made
 * for one pattern set, so the fixtures of a test share it), and, with a
 * device, the surface's device surface. */
typedef struct fixture {
  tlod_context* ctx;
  tlod_mesh* mesh;
  tlod_surface* surf;
  const tlod_patterns* pat; /* borrowed */
  tlod_device* dev;
  tlod_device_surface* ds;
} fixture;

static inline void fixture_free(fixture* fx) {
  tlod_device_destroy_surface(fx->dev, fx->ds);
  tlod_surface_destroy(fx->surf);
  tlod_mesh_destroy(fx->mesh);
  fx->surf = NULL, fx->mesh = NULL, fx->pat = NULL, fx->ds = NULL, fx->dev = NULL;
}

/* A fixture of any mesh desc (attributes, say); dev may be NULL (no device surface). */
static inline bool fixture_make_desc(fixture* fx, tlod_context* ctx, const tlod_mesh_desc* md, tlod_surface_type type,
                                     const tlod_patterns* patterns, tlod_device* dev) {
  memset(fx, 0, sizeof *fx);
  fx->ctx = ctx;
  fx->pat = patterns;
  fx->dev = dev;
  tlod_result r = tlod_mesh_create(ctx, md, &fx->mesh);
  if (r == TLOD_SUCCESS)
    r = tlod_surface_create(ctx, fx->mesh, &(tlod_surface_desc){.type = type, .label = md->label}, &fx->surf);
  if (r == TLOD_SUCCESS && dev) r = tlod_device_create_surface(dev, fx->surf, &fx->ds);
  if (r != TLOD_SUCCESS) {
    fprintf(stderr, "fixture %s: %s: %s\n", md->label, tlod_result_string(r), tlod_context_last_error(ctx));
    fixture_free(fx);
    return false;
  }
  return true;
}

/* A shape's fixture; dev may be NULL (no device surface). */
static inline bool fixture_make(fixture* fx, tlod_context* ctx, const shape* s, tlod_surface_type type,
                                const tlod_patterns* patterns, tlod_device* dev) {
  tlod_mesh_desc md = shape_mesh_desc(s);
  return fixture_make_desc(fx, ctx, &md, type, patterns, dev);
}

/* shape_seam_sphere(nlat, nlon) with TEXCOORD_0 = lat-long UVs: vertex
 * (i, j) has (j / nlon, i / nlat) (v = 0 at the +z pole, glTF's top), so
 * the copied column and the pole copies are UV seams. desc points into the
 * struct: keep it where it is (do not copy it). */
typedef struct uv_sphere {
  shape sph;
  float* uv;
  tlod_attribute_desc attr;
  tlod_mesh_desc desc;
} uv_sphere;

static inline void uv_sphere_free(uv_sphere* u) {
  free(u->uv);
  shape_free(&u->sph);
  memset(u, 0, sizeof *u);
}

static inline bool uv_sphere_make(uv_sphere* u, uint32_t nlat, uint32_t nlon) {
  memset(u, 0, sizeof *u);
  u->sph = shape_seam_sphere(nlat, nlon);
  u->uv = malloc(sizeof(float) * 2 * (nlat + 1) * (nlon + 1));
  for (uint32_t i = 0; u->uv && i <= nlat; ++i)
    for (uint32_t j = 0; j <= nlon; ++j) {
      u->uv[2 * (i * (nlon + 1) + j)] = (float)j / (float)nlon;
      u->uv[2 * (i * (nlon + 1) + j) + 1] = (float)i / (float)nlat;
    }
  u->attr = (tlod_attribute_desc){.data = u->uv, .components = 2, .name = "TEXCOORD_0"};
  u->desc = shape_mesh_desc(&u->sph);
  u->desc.attributes = &u->attr;
  u->desc.attribute_count = 1;
  return u->uv != NULL;
}

/* The scheduler plans in an object's own space: its view is view * model
 * (column-major). */
static inline tlod_view_desc object_view(const tlod_view_desc* v, const float model[16]) {
  tlod_view_desc o = *v;
  for (int c = 0; c < 4; c++)
    for (int r = 0; r < 4; r++) {
      float s = 0.0f;
      for (int k = 0; k < 4; k++)
        s += v->view[k * 4 + r] * model[c * 4 + k];
      o.view[c * 4 + r] = s;
    }
  return o;
}

static inline tlod_scheduler* new_scheduler(const fixture* fx, tlod_scheduler_desc d) {
  return scheduler_create(fx->ctx, fx->surf, fx->pat, d);
}

/* One frame for one view; NULL on failure (reported). */
static inline const tlod_draw_list* plan(const fixture* fx, tlod_scheduler* s, const tlod_view_desc* v, float dt_ms) {
  tlod_frame_desc f = {.views = v, .view_count = 1, .dt_ms = dt_ms};
  return scheduler_plan(fx->ctx, s, &f);
}

/* The CPU reference realisation of a draw list (welded, with normals). */
static inline tlod_cpu_mesh* realise(const fixture* fx, const tlod_draw_list* dl) {
  tlod_cpu_tessellate_desc d = {.draw_list = dl};
  tlod_cpu_mesh* out = NULL;
  tlod_result r = tlod_cpu_tessellate(fx->ctx, fx->surf, fx->pat, &d, &out);
  if (r != TLOD_SUCCESS) {
    fprintf(stderr, "tlod_cpu_tessellate(draw_list): %s: %s\n", tlod_result_string(r),
            tlod_context_last_error(fx->ctx));
    return NULL;
  }
  return out;
}

/* A device of desc, or NULL with the reason printed (the GL and Vulkan
 * tests then FAIL, never skip). */
static inline tlod_device* new_device(tlod_context* ctx, const tlod_device_desc* desc) {
  tlod_device* dev = NULL;
  tlod_result r = tlod_device_create(ctx, desc, &dev);
  if (r != TLOD_SUCCESS)
    fprintf(stderr, "tlod_device_create(\"%s\"): %s: %s (this build has: %s)\n", desc->backend, tlod_result_string(r),
            tlod_context_last_error(ctx), tlod_backend_names());
  return dev;
}

static inline tlod_patterns* new_patterns(tlod_context* ctx, uint32_t max_level) {
  tlod_patterns* p = NULL;
  tlod_result r = tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = max_level}, &p);
  if (r != TLOD_SUCCESS)
    fprintf(stderr, "tlod_patterns_create: %s: %s\n", tlod_result_string(r), tlod_context_last_error(ctx));
  return p;
}

/* One item (identity model, default colour) for one view: desc.items points
 * at item, so keep the struct where it is (do not copy it). */
typedef struct one_draw {
  tlod_draw_item item;
  tlod_draw_desc desc;
} one_draw;

static inline void one_draw_make(one_draw* o, const tlod_device_surface* ds, const tlod_draw_list* dl,
                                 const tlod_view_desc* v) {
  memset(o, 0, sizeof *o);
  o->item.surface = ds;
  o->item.draw_list = dl;
  o->desc.items = &o->item;
  o->desc.item_count = 1;
  memcpy(o->desc.view, v->view, sizeof o->desc.view);
  memcpy(o->desc.proj, v->proj, sizeof o->desc.proj);
  o->desc.viewport[2] = v->viewport_width;
  o->desc.viewport[3] = v->viewport_height;
  o->desc.debug = TLOD_DEBUG_NONE;
}

/* ------------------------------------------------------------------------ */
/* Images                                                                   */
/* ------------------------------------------------------------------------ */

/* The clear colour of the GL tests: pure blue. Shaded pixels are grey
 * (r == g == b), so coverage is exact: not-background == covered. */
#define BG_R 0
#define BG_G 0
#define BG_B 255

static inline bool is_background(const uint8_t* px) { return px[0] == BG_R && px[1] == BG_G && px[2] == BG_B; }

/* ------------------------------------------------------------------------ */
/* Crack detection (tests/gl/gl_cracks_test.c, tests/vk/vk_cracks_test.c)   */
/* ------------------------------------------------------------------------ */

/* Background pixels of rgba (w x h) 4-connected to the border: reached[i]
 * = 1, else 0. queue: w * h entries of scratch. */
static inline void flood_background(const uint8_t* rgba, uint32_t w, uint32_t h, uint8_t* reached, uint32_t* queue) {
  memset(reached, 0, (size_t)w * h);
  uint32_t head = 0, tail = 0;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      if (x != 0 && y != 0 && x != w - 1 && y != h - 1) continue;
      uint32_t i = y * w + x;
      if (is_background(rgba + 4 * i) && !reached[i]) {
        reached[i] = 1;
        queue[tail++] = i;
      }
    }
  while (head < tail) {
    uint32_t i = queue[head++], x = i % w, y = i / w;
    uint32_t next[4] = {x > 0 ? i - 1 : i, x + 1 < w ? i + 1 : i, y > 0 ? i - w : i, y + 1 < h ? i + w : i};
    for (int k = 0; k < 4; ++k) {
      uint32_t j = next[k];
      if (!reached[j] && is_background(rgba + 4 * j)) {
        reached[j] = 1;
        queue[tail++] = j;
      }
    }
  }
}

/* The reference (ref_rgba, ref_stencil: 1 = front face) shows a front face
 * at (x, y) and its 8 neighbours. */
static inline bool reference_solid(const uint8_t* ref_rgba, const uint8_t* ref_stencil, uint32_t w, uint32_t h,
                                   uint32_t x, uint32_t y) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      int nx = (int)x + dx, ny = (int)y + dy;
      if (nx < 0 || ny < 0 || nx >= (int)w || ny >= (int)h) return false;
      size_t j = (size_t)ny * w + (size_t)nx;
      if (ref_stencil[j] != 1 || is_background(ref_rgba + 4 * j)) return false;
    }
  return true;
}

/* Eye-space distance of a window depth d (GL's [0, 1]) for the camera's
 * near / far. */
static inline double linear_depth(const camera* c, float d) {
  double z = 2.0 * (double)d - 1.0;
  return 2.0 * c->zfar * c->znear / (c->zfar + c->znear - z * (c->zfar - c->znear));
}

/* Coverage and colour differences of two images of one scene, where image b
 * is the reference: a pixel covered in only one image is "on the band" when
 * it, or one of its 8 neighbours, has the other coverage in b (a silhouette
 * moved by less than a pixel); colour is compared where both are covered. */
typedef struct compare_result {
  uint32_t covered_a, covered_b, covered_either, covered_both;
  uint32_t coverage_diff; /* covered in exactly one image */
  uint32_t off_band;      /* ... of which not on the reference's boundary band */
  int off_band_x, off_band_y;
  uint32_t colour_ok; /* both covered, max channel diff <= the tolerance */
  uint32_t max_colour_diff;
  double mean_colour_diff;
} compare_result;

/* a, b: RGBA, same layout (rows in any order, the same for both). */
static inline compare_result compare_images(const uint8_t* a, const uint8_t* b, uint32_t w, uint32_t h,
                                            uint32_t colour_tolerance) {
  compare_result r;
  memset(&r, 0, sizeof r);
  r.off_band_x = r.off_band_y = -1;
  double colour_sum = 0;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      size_t i = (size_t)y * w + x;
      bool ca = !is_background(a + 4 * i), cb = !is_background(b + 4 * i);
      r.covered_a += ca;
      r.covered_b += cb;
      r.covered_either += ca || cb;
      if (ca && cb) {
        r.covered_both++;
        uint32_t d = 0;
        for (int c = 0; c < 3; ++c) {
          int dc = abs((int)a[4 * i + c] - (int)b[4 * i + c]);
          if ((uint32_t)dc > d) d = (uint32_t)dc;
        }
        r.colour_ok += d <= colour_tolerance;
        if (d > r.max_colour_diff) r.max_colour_diff = d;
        colour_sum += d;
      }
      if (ca == cb) continue;
      r.coverage_diff++;
      bool band = false;
      for (int dy = -1; dy <= 1 && !band; ++dy)
        for (int dx = -1; dx <= 1 && !band; ++dx) {
          int nx = (int)x + dx, ny = (int)y + dy;
          if (nx < 0 || ny < 0 || nx >= (int)w || ny >= (int)h) continue;
          band = !is_background(b + 4 * ((size_t)ny * w + (size_t)nx)) != cb;
        }
      if (!band && r.off_band++ == 0) r.off_band_x = (int)x, r.off_band_y = (int)y;
    }
  r.mean_colour_diff = r.covered_both ? colour_sum / r.covered_both : 0;
  return r;
}

#endif
