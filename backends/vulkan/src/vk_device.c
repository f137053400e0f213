/* tesslod::vulkan -- the "vulkan" device (stub: validates its desc; the
 * device follows). */
#include <stdio.h>

#include <vulkan/vulkan.h>

#include "device_internal.h"
#include "tesslod/vulkan.h"

static tlod_result vk_create(tlod_context* ctx, const tlod_device_desc* desc, tlod_device_stats* stats, void** state) {
  (void)stats, (void)state;
  const tlod_device_vk_desc* v = &desc->vk;
  const char* missing = !v->instance          ? "instance"
                        : !v->physical_device ? "physical_device"
                        : !v->device          ? "device"
                        : !v->queue           ? "queue"
                        : !v->color_format    ? "color_format"
                        : !v->depth_format    ? "depth_format"
                                              : NULL;
  if (missing)
    return tlod_context_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "vulkan device '%s': desc.vk.%s is required",
                             desc->label, missing);
  return tlod_context_fail(ctx, TLOD_ERROR_UNSUPPORTED, "vulkan device '%s': not implemented yet", desc->label);
}

static void vk_destroy(void* state) { (void)state; }

static tlod_result vk_draw(void* state, const tlod_draw_desc* desc, const _tlod_draw_ref* refs,
                           tlod_draw_item_stats* item_stats) {
  (void)state, (void)desc, (void)refs, (void)item_stats;
  return TLOD_ERROR_UNSUPPORTED;
}

const _tlod_device_vtbl _tlod_vk_device_vtbl = {
    .create = vk_create, .destroy = vk_destroy, .draw = vk_draw, .times_draws = true};
