/* tesslod::backend -- the "null" device: draws nothing. The dispatch
 * validates its calls exactly as for the other backends and counts them;
 * its draws count what the draw lists would draw (pattern and strip
 * triangles and vertices), so code driving a device is testable without a
 * GPU. */
#include "device_internal.h"

typedef struct null_device {
  tlod_context* ctx;
} null_device;

static tlod_result null_create(tlod_context* ctx, const tlod_device_desc* desc, tlod_device_stats* stats,
                               void** state) {
  (void)desc, (void)stats;
  null_device* d = tlod_context_calloc(ctx, 1, sizeof(*d));
  if (!d) return tlod_context_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "null device: out of memory");
  d->ctx = ctx;
  *state = d;
  return TLOD_SUCCESS;
}

static void null_destroy(void* state) {
  null_device* d = state;
  tlod_context_free(d->ctx, d);
}

static tlod_result null_draw(void* state, const tlod_draw_desc* desc, const _tlod_draw_ref* refs,
                             tlod_draw_item_stats* item_stats) {
  (void)state;
  for (uint32_t k = 0; k < desc->item_count; k++) {
    const tlod_draw_list* dl = refs[k].item->draw_list;
    uint64_t v = 3 * dl->strip_triangles;
    for (uint32_t b = 0; b < dl->bucket_count; b++)
      v += (uint64_t)tlod_pattern_vertex_count(dl->buckets[b].shape, dl->buckets[b].level) * dl->buckets[b].count;
    item_stats[k] = (tlod_draw_item_stats){.triangles = dl->pattern_triangles + dl->strip_triangles, .vertices = v};
  }
  return TLOD_SUCCESS;
}

const _tlod_device_vtbl _tlod_null_device_vtbl = {
    .create = null_create, .destroy = null_destroy, .draw = null_draw, .times_draws = false};
