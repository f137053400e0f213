/* tesslod::vulkan -- device surfaces: the patch records and mesh attributes
 * kept on the CPU and copied into one host-visible storage buffer pair per
 * frame slot. tlod_device_update_surface() refreshes the CPU copy and marks
 * every slot dirty; a draw of frame index f copies into slot f's buffers
 * first when they are dirty. Slot f's buffers are read only by slot f's
 * frames, and the GPU has finished the last one when a draw names f again
 * (the frame-index contract), so no buffer in flight is ever written and
 * an update never waits. */
#include <string.h>

#include "vk_internal.h"

/* The records and attributes of s into the CPU copy (layouts of
 * TLOD_BINDING_PATCHES and TLOD_BINDING_ATTRIBUTES; one zero element of
 * each when there are none, a buffer is never empty). */
static tlod_result fill(vk_device* d, vk_surface* vs, const tlod_surface* s) {
  const tlod_mesh* mesh = tlod_surface_mesh(s);
  uint32_t n = vs->patch_count, count = tlod_mesh_attribute_count(mesh);
  size_t rec = sizeof(tlod_patch_record) * (n ? n : 1), attr = sizeof(float[4]) * ((size_t)n * 4u * count + 1u);
  if (rec != vs->record_bytes) {
    tlod_context_free(d->ctx, vs->records);
    vs->records = tlod_context_calloc(d->ctx, 1, rec);
    vs->record_bytes = vs->records ? rec : 0;
  }
  if (attr != vs->attribute_bytes) {
    tlod_context_free(d->ctx, vs->attributes);
    vs->attributes = tlod_context_calloc(d->ctx, 1, attr);
    vs->attribute_bytes = vs->attributes ? attr : 0;
  }
  if (!vs->records || !vs->attributes)
    return tlod_context_fail(d->ctx, TLOD_ERROR_OUT_OF_MEMORY, "vulkan device: out of memory for %u patches", n);
  tlod_result r = n ? tlod_surface_patch_records(s, 0, n, vs->records) : TLOD_SUCCESS;
  if (r == TLOD_SUCCESS && count) r = tlod_mesh_patch_attributes(mesh, 0, n, vs->attributes);
  if (r != TLOD_SUCCESS) return r;
  vs->attribute_count = count;
  _tlod_surface_center(s, vs->center);
  vs->dirty = (1u << d->frames.count) - 1u;
  return TLOD_SUCCESS;
}

static void free_surface(vk_device* d, vk_surface* vs) {
  for (uint32_t i = 0; i < TLOD_VK_MAX_FRAMES_IN_FLIGHT; i++) {
    /* Out of host memory for the list: destroying now is the only way left. */
    if (!_tlod_vkb_retire_buffer(&d->frames, &vs->patches[i])) _tlod_vkb_buffer_destroy(&d->memory, &vs->patches[i]);
    if (!_tlod_vkb_retire_buffer(&d->frames, &vs->attrs[i])) _tlod_vkb_buffer_destroy(&d->memory, &vs->attrs[i]);
  }
  tlod_context_free(d->ctx, vs->records);
  tlod_context_free(d->ctx, vs->attributes);
  _tlod_item_mesh_free(d->ctx, &vs->mesh);
  tlod_context_free(d->ctx, vs);
}

tlod_result _tlod_vkb_surface_create(void* state, const tlod_surface* s, void** surface_state) {
  vk_device* d = state;
  tlod_surface_view view = tlod_surface_query_view(s);
  if ((uint32_t)view.type >= VK_TYPES || !d->pipelines.modules[view.type][VK_VARIANT_PLAIN].built) {
    const char* label = tlod_surface_query_desc(s).label;
    return tlod_context_fail(d->ctx, TLOD_ERROR_UNSUPPORTED,
                             "vulkan device '%s': surface '%s' is %s, and the device has no shaders for it "
                             "(desc.vk.surface_types)",
                             d->label, label ? label : "surface", tlod_surface_type_name(view.type));
  }
  vk_surface* vs = tlod_context_calloc(d->ctx, 1, sizeof(*vs));
  if (!vs) return tlod_context_fail(d->ctx, TLOD_ERROR_OUT_OF_MEMORY, "vulkan device: out of memory");
  vs->type = view.type;
  vs->patch_count = view.patch_count;
  vs->surface = s;
  tlod_result r = fill(d, vs, s);
  if (r != TLOD_SUCCESS) {
    free_surface(d, vs);
    return r;
  }
  *surface_state = vs;
  return TLOD_SUCCESS;
}

tlod_result _tlod_vkb_surface_update(void* state, void* surface_state, const tlod_surface* s) {
  return fill(state, surface_state, s);
}

void _tlod_vkb_surface_destroy(void* state, void* surface_state) { free_surface(state, surface_state); }

/* b holds bytes of data (a larger buffer is made when it does not; the old
 * one retired: a draw earlier in this frame may read it). */
static VkResult copy_into(vk_device* d, vk_buffer* b, const void* data, size_t bytes) {
  if (b->size < bytes) {
    if (!_tlod_vkb_retire_buffer(&d->frames, b)) return VK_ERROR_OUT_OF_HOST_MEMORY;
    VkResult r = _tlod_vkb_buffer_create(&d->memory, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, 1, b);
    if (r != VK_SUCCESS) return r;
  }
  memcpy(b->mem.mapped, data, bytes);
  return VK_SUCCESS;
}

VkResult _tlod_vkb_surface_sync(vk_device* d, vk_surface* vs, uint32_t slot) {
  if (!(vs->dirty & (1u << slot))) return VK_SUCCESS;
  VkResult r = copy_into(d, &vs->patches[slot], vs->records, vs->record_bytes);
  if (r == VK_SUCCESS) r = copy_into(d, &vs->attrs[slot], vs->attributes, vs->attribute_bytes);
  if (r == VK_SUCCESS) vs->dirty &= ~(1u << slot);
  return r;
}
