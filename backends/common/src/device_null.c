/* tesslod::backend -- the "null" device: draws nothing. The dispatch
 * validates its calls exactly as for the other backends and counts them;
 * its draws count what the draw lists would draw (pattern and strip
 * triangles and vertices), so code driving a device is testable without a
 * GPU. */
#include "device_internal.h"

typedef struct null_device {
  tlod_context* ctx;
  tlod_device_stats* stats;
} null_device;

static tlod_result null_create(tlod_context* ctx, const tlod_device_desc* desc, tlod_device_stats* stats,
                               void** state) {
  (void)desc;
  null_device* d = tlod_context_calloc(ctx, 1, sizeof(*d));
  if (!d) return tlod_context_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "null device: out of memory");
  d->ctx = ctx;
  d->stats = stats;
  *state = d;
  return TLOD_SUCCESS;
}

static void null_destroy(void* state) {
  null_device* d = state;
  tlod_context_free(d->ctx, d);
}

static tlod_result null_create_surface(void* state, const tlod_surface* surface, void** surface_state) {
  (void)state, (void)surface;
  *surface_state = NULL;
  return TLOD_SUCCESS;
}

static tlod_result null_update_surface(void* state, void* surface_state, const tlod_surface* surface) {
  (void)state, (void)surface_state, (void)surface;
  return TLOD_SUCCESS;
}

static void null_destroy_surface(void* state, void* surface_state) { (void)state, (void)surface_state; }

static tlod_result null_draw(void* state, const tlod_draw_desc* desc, const _tlod_draw_ref* refs,
                             tlod_draw_item_stats* item_stats) {
  null_device* d = state;
  double t0 = tlod_now_ms();
  uint64_t triangles = 0, vertices = 0;
  for (uint32_t k = 0; k < desc->item_count; k++) {
    const tlod_draw_list* dl = refs[k].item->draw_list;
    uint64_t v = 3 * dl->strip_triangles;
    for (uint32_t b = 0; b < dl->bucket_count; b++)
      v += (uint64_t)tlod_pattern_vertex_count(dl->buckets[b].shape, dl->buckets[b].level) * dl->buckets[b].count;
    item_stats[k] = (tlod_draw_item_stats){.triangles = dl->pattern_triangles + dl->strip_triangles, .vertices = v};
    triangles += item_stats[k].triangles;
    vertices += v;
  }
  d->stats->cpu_ms = d->stats->wall_ms = tlod_now_ms() - t0;
  d->stats->triangles = triangles;
  d->stats->vertices = vertices;
  d->stats->draw_calls = 0;
  return TLOD_SUCCESS;
}

static tlod_result null_read_image(void* state, uint32_t width, uint32_t height, uint8_t* rgba) {
  (void)width, (void)height, (void)rgba;
  null_device* d = state;
  return tlod_context_fail(d->ctx, TLOD_ERROR_UNSUPPORTED, "null device: it draws nothing and has no image");
}

const _tlod_device_vtbl _tlod_null_device_vtbl = {null_create,         null_destroy,         null_create_surface,
                                                  null_update_surface, null_destroy_surface, null_draw,
                                                  null_read_image};
