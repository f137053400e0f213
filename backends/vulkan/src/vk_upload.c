/* tesslod::vulkan -- one-time uploads at device and texture creation: one
 * command buffer recorded, submitted on the device's queue and waited for
 * with a fence (tesslod/vulkan.h: the queue is used only there, never in a
 * frame). */
#include <string.h>

#include "vk_internal.h"

VkResult _tlod_vkb_upload_init(vk_upload* u, VkDevice device, VkQueue queue, uint32_t family,
                               const VkAllocationCallbacks* cb) {
  memset(u, 0, sizeof(*u));
  u->device = device, u->queue = queue, u->cb = cb;
  VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                .flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT |
                                         VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                .queueFamilyIndex = family};
  VkResult r = vkCreateCommandPool(device, &pi, cb, &u->pool);
  VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                    .commandPool = u->pool,
                                    .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                    .commandBufferCount = 1};
  if (r == VK_SUCCESS) r = vkAllocateCommandBuffers(device, &ai, &u->cmd);
  VkFenceCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  if (r == VK_SUCCESS) r = vkCreateFence(device, &fi, cb, &u->fence);
  return r;
}

void _tlod_vkb_upload_destroy(vk_upload* u) {
  if (u->fence) vkDestroyFence(u->device, u->fence, u->cb);
  if (u->pool) vkDestroyCommandPool(u->device, u->pool, u->cb); /* frees u->cmd */
  memset(u, 0, sizeof(*u));
}

VkResult _tlod_vkb_upload_begin(vk_upload* u) {
  VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                 .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
  VkResult r = vkResetCommandBuffer(u->cmd, 0);
  return r == VK_SUCCESS ? vkBeginCommandBuffer(u->cmd, &bi) : r;
}

VkResult _tlod_vkb_upload_submit(vk_upload* u) {
  VkResult r = vkEndCommandBuffer(u->cmd);
  VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &u->cmd};
  if (r == VK_SUCCESS) r = vkResetFences(u->device, 1, &u->fence);
  if (r == VK_SUCCESS) r = vkQueueSubmit(u->queue, 1, &si, u->fence);
  if (r == VK_SUCCESS) r = vkWaitForFences(u->device, 1, &u->fence, VK_TRUE, UINT64_MAX);
  return r;
}

/* The copy is made visible to every shader read and index/vertex fetch of
 * later submissions (the fence wait orders the host; the barrier the device). */
VkResult _tlod_vkb_buffer_upload(vk_memory* m, vk_upload* u, const void* data, VkDeviceSize size,
                                 VkBufferUsageFlags usage, vk_buffer* out) {
  vk_buffer staging;
  VkResult r = _tlod_vkb_buffer_create(m, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, 1, &staging);
  if (r != VK_SUCCESS) return r;
  memcpy(staging.mem.mapped, data, (size_t)size);
  r = _tlod_vkb_buffer_create(m, size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, 0, out);
  if (r == VK_SUCCESS) r = _tlod_vkb_upload_begin(u);
  if (r == VK_SUCCESS) {
    vkCmdCopyBuffer(u->cmd, staging.buffer, out->buffer, 1, &(VkBufferCopy){.size = size});
    VkMemoryBarrier mb = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                          .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
                          .dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_INDEX_READ_BIT};
    vkCmdPipelineBarrier(u->cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_ALL_GRAPHICS_BIT, 0, 1, &mb, 0, NULL,
                         0, NULL);
    r = _tlod_vkb_upload_submit(u);
  }
  if (r != VK_SUCCESS) _tlod_vkb_buffer_destroy(m, out);
  _tlod_vkb_buffer_destroy(m, &staging);
  return r;
}
