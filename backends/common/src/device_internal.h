/* Private to the backends: the table a backend fills in, called only by the
 * dispatch (device.c) after it has validated the call, and small helpers the
 * backends share (header-only: the gl library links below the dispatch). */
#ifndef TESSLOD_DEVICE_INTERNAL_H
#define TESSLOD_DEVICE_INTERNAL_H

#include <string.h>

#include "tesslod/backend.h"

/* A validated item: its surface, the backend's state of that surface. */
typedef struct _tlod_draw_ref {
  const tlod_draw_item* item;
  const tlod_surface* surface;
  void* surface_state;
  void* texture_state; /* the backend's state of item->base_color_texture; NULL without one */
} _tlod_draw_ref;

typedef struct _tlod_device_vtbl {
  /* stats lives as long as the device: the backend writes its .gl part
   * whenever it likes, and the last-draw fields in draw(). */
  tlod_result (*create)(tlod_context* ctx, const tlod_device_desc* desc, tlod_device_stats* stats, void** state);
  void (*destroy)(void* state);
  /* The three surface entries may be NULL: no state per surface (cpu, null). */
  tlod_result (*create_surface)(void* state, const tlod_surface* surface, void** surface_state);
  tlod_result (*update_surface)(void* state, void* surface_state, const tlod_surface* surface);
  void (*destroy_surface)(void* state, void* surface_state);
  /* item_stats has desc->item_count entries, zeroed; the backend fills
   * them, the dispatch sums them into the last-draw stats. */
  tlod_result (*draw)(void* state, const tlod_draw_desc* desc, const _tlod_draw_ref* refs,
                      tlod_draw_item_stats* item_stats);
  /* NULL: the device has no image (TLOD_ERROR_UNSUPPORTED). */
  tlod_result (*read_image)(void* state, uint32_t width, uint32_t height, uint8_t* rgba);
  /* false: the dispatch times draw() into cpu_ms and wall_ms; true: the
   * backend does (gl: cpu_ms without the finish, wall_ms with it). */
  bool times_draws;
  /* May be NULL: textures validated and counted, nothing kept (cpu, null).
   * desc is validated, its label resolved. */
  tlod_result (*create_texture)(void* state, const tlod_texture_desc* desc, void** texture_state);
  void (*destroy_texture)(void* state, void* texture_state);
  /* May be NULL: called by tlod_device_query_stats() to bring GPU readings
   * (gpu_ms, gpu_draw, ...) into stats (vulkan: its query results, read
   * there and not in a draw, where a driver may wait to answer). */
  void (*poll_stats)(void* state, tlod_device_stats* stats);
} _tlod_device_vtbl;

extern const _tlod_device_vtbl _tlod_cpu_device_vtbl;
extern const _tlod_device_vtbl _tlod_null_device_vtbl;
#if TLOD_HAS_GL
extern const _tlod_device_vtbl _tlod_gl_device_vtbl;
#endif
#if TLOD_HAS_VULKAN
extern const _tlod_device_vtbl _tlod_vk_device_vtbl;
#endif

const struct tlod_cpu_mesh* _tlod_cpu_device_mesh(const void* state, uint32_t item);

/* Per-item shading inputs, resolved once per item and draw. */
typedef struct _tlod_item_shading {
  float mvp[16];          /* proj * view * model */
  float model[16];        /* identity unless has_model */
  float normal_matrix[9]; /* inverse transpose of model's 3x3, column-major */
  float color[4];
} _tlod_item_shading;

/* out = a * b, column-major, summed in a fixed order (-ffp-contract=off). */
static inline void _tlod_mat4_mul(const float a[16], const float b[16], float out[16]) {
  for (int c = 0; c < 4; c++) {
    for (int r = 0; r < 4; r++) {
      float s = 0.0f;
      for (int k = 0; k < 4; k++)
        s += a[k * 4 + r] * b[c * 4 + k];
      out[c * 4 + r] = s;
    }
  }
}

/* With the identity model the product is exactly proj * view (x * 1 + y * 0
 * + ... is x, bitwise): an item without a model draws the same image as a
 * draw without models. */
static inline void _tlod_item_shading_of(const tlod_draw_desc* desc, const tlod_draw_item* item,
                                         _tlod_item_shading* out) {
  static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  static const float grey[4] = {0.8f, 0.8f, 0.8f, 1.0f};
  const float* m = item->has_model ? item->model : identity;
  float vp[16];
  _tlod_mat4_mul(desc->proj, desc->view, vp);
  _tlod_mat4_mul(vp, m, out->mvp);
  memcpy(out->model, m, sizeof(out->model));
  /* Inverse transpose of the upper 3x3: cofactors / determinant (the
   * identity gives the identity exactly; a singular matrix keeps its
   * cofactors, normals are normalised in the shader anyway). Rows of the
   * 3x3: (a b c) (d e f) (g h i). */
  float a = m[0], b = m[4], c = m[8], d = m[1], e = m[5], f = m[9], g = m[2], h = m[6], i = m[10];
  float cof[9] = {e * i - f * h,    -(d * i - f * g), d * h - e * g,    -(b * i - c * h), a * i - c * g,
                  -(a * h - b * g), b * f - c * e,    -(a * f - c * d), a * e - b * d};
  float det = a * cof[0] + b * cof[1] + c * cof[2];
  float inv = det != 0.0f ? 1.0f / det : 1.0f;
  for (int k = 0; k < 9; k++) /* column-major: element (row k % 3, column k / 3) */
    out->normal_matrix[k] = cof[(k % 3) * 3 + k / 3] * inv;
  memcpy(out->color, item->has_color ? item->color : grey, sizeof(out->color));
}

/* Grows *buf (elements of elem bytes; contents dropped) to hold need, through the context. */
static inline bool _tlod_device_grow(const tlod_context* ctx, void** buf, uint32_t* cap, uint32_t need, size_t elem) {
  if (need <= *cap && *buf) return true;
  uint32_t n = *cap ? *cap : 64;
  while (n < need)
    n *= 2;
  void* p = tlod_context_alloc(ctx, elem * n);
  if (!p) return false;
  tlod_context_free(ctx, *buf);
  *buf = p;
  *cap = n;
  return true;
}

#endif
