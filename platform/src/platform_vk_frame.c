/*
 * platform_vk_frame.c -- the Vulkan frame loop of platform/: begin_frame,
 * end_frame, read-back and resize over the objects of platform_vk.c.
 *
 * Synchronisation (the validation layer's synchronization validation
 * checks it): both slots share the colour (headless) and depth images, so
 * begin_frame orders its writes after every earlier frame's colour writes,
 * copy and depth writes with one pipeline barrier (queue submission order
 * makes that cover earlier submits); end_frame orders the copy after the
 * rendering and the host read after the copy; the host reads after the
 * slot's fence. Classic vkCmdPipelineBarrier: no synchronization2 needed.
 */
#define _POSIX_C_SOURCE 200809L

#include <string.h>

#include "platform_vk.h"

/* Fence waits are bounded: a lost device or a driver that never signals
 * fails the frame with VK_TIMEOUT instead of hanging the tool (lavapipe's
 * heaviest measured frame took under a second). */
#define FENCE_TIMEOUT_NS 60000000000ull

static VkImage color_image(const _tlod_platform_vk* vk, const tlod_platform* p) {
  return p->window ? vk->images[vk->image] : vk->color.image;
}

static VkImageView color_view(const _tlod_platform_vk* vk, const tlod_platform* p) {
  return p->window ? vk->views[vk->image] : vk->color.view;
}

static VkImageMemoryBarrier image_barrier(VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                                          VkImageLayout to, VkAccessFlags src, VkAccessFlags dst) {
  return (VkImageMemoryBarrier){.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER,
                                .srcAccessMask = src,
                                .dstAccessMask = dst,
                                .oldLayout = from,
                                .newLayout = to,
                                .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                .image = image,
                                .subresourceRange = {aspect, 0, 1, 0, 1}};
}

/* Both attachments from "anything earlier" to attachment layouts (their
 * contents are cleared, so UNDEFINED). */
static void attachments_barrier(tlod_platform* p, VkCommandBuffer cmd) {
  _tlod_platform_vk* vk = p->vk;
  const VkAccessFlags color_access = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  const VkAccessFlags depth_access =
      VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  VkImageMemoryBarrier b[2] = {image_barrier(color_image(vk, p), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                                             VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, 0, color_access),
                               image_barrier(vk->depth.image, _tlod_vk_depth_aspect(vk->depth_format),
                                             VK_IMAGE_LAYOUT_UNDEFINED,
                                             VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                                             VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, depth_access)};
  const VkPipelineStageFlags tests =
      VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  /* colour: the previous copy read it (headless) or the acquire semaphore
   * waited at COLOR_ATTACHMENT_OUTPUT (window); depth: earlier tests wrote it. */
  VkPipelineStageFlags src = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT | tests;
  vkCmdPipelineBarrier(cmd, src, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | tests, 0, 0, NULL, 0, NULL, 2, b);
}

static void begin_rendering(tlod_platform* p, VkCommandBuffer cmd, const float rgba[4]) {
  _tlod_platform_vk* vk = p->vk;
  VkRenderingAttachmentInfo color = {.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
                                     .imageView = color_view(vk, p),
                                     .imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                     .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR,
                                     .storeOp = VK_ATTACHMENT_STORE_OP_STORE};
  memcpy(color.clearValue.color.float32, rgba, 4 * sizeof(float));
  VkRenderingAttachmentInfo depth = {.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
                                     .imageView = vk->depth.view,
                                     .imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                                     .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR,
                                     .storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
                                     .clearValue.depthStencil = {1.0f, 0}};
  VkRenderingInfo info = {.sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
                          .renderArea = {{0, 0}, {p->width, p->height}},
                          .layerCount = 1,
                          .colorAttachmentCount = 1,
                          .pColorAttachments = &color,
                          .pDepthAttachment = &depth};
  vkCmdBeginRendering(cmd, &info);
}

bool _tlod_platform_vk_begin_frame(tlod_platform* p, const float rgba[4], tlod_platform_frame* out, char* error,
                                   size_t error_size) {
  _tlod_platform_vk* vk = p->vk;
  if (vk->in_frame) {
    _tlod_platform_error(error, error_size, "tlod_platform_begin_frame: the previous frame was not ended");
    return false;
  }
  uint32_t slot = (uint32_t)(vk->frame % VK_FRAMES);
  vk_frame* f = &vk->frames[slot];
  if (!_tlod_vk_check(vkWaitForFences(vk->device, 1, &f->fence, VK_TRUE, FENCE_TIMEOUT_NS), "vkWaitForFences", error,
                      error_size))
    return false;
  vk->slot = slot;
  vk->has_frame = false; /* this slot's read-back buffer is about to be rewritten */
  if (p->window && !_tlod_vk_window_acquire(p, error, error_size)) return false;
  VkCommandBufferBeginInfo begin = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                    .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
  if (!_tlod_vk_check(vkResetCommandBuffer(f->cmd, 0), "vkResetCommandBuffer", error, error_size) ||
      !_tlod_vk_check(vkBeginCommandBuffer(f->cmd, &begin), "vkBeginCommandBuffer", error, error_size))
    return false;
  attachments_barrier(p, f->cmd);
  begin_rendering(p, f->cmd, rgba);
  vk->in_frame = true;
  *out = (tlod_platform_frame){.command_buffer = f->cmd, .frame_index = slot};
  return true;
}

/* Colour -> TRANSFER_SRC, copy into the slot's buffer, buffer -> host. */
static void record_readback(tlod_platform* p, VkCommandBuffer cmd) {
  _tlod_platform_vk* vk = p->vk;
  vk_frame* f = &vk->frames[vk->slot];
  VkImageMemoryBarrier to_src = image_barrier(
      color_image(vk, p), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
      VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT);
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, NULL,
                       0, NULL, 1, &to_src);
  VkBufferImageCopy region = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                              .imageExtent = {p->width, p->height, 1}};
  vkCmdCopyImageToBuffer(cmd, color_image(vk, p), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, f->readback, 1, &region);
  VkBufferMemoryBarrier to_host = {.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER,
                                   .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
                                   .dstAccessMask = VK_ACCESS_HOST_READ_BIT,
                                   .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                   .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                   .buffer = f->readback,
                                   .size = VK_WHOLE_SIZE};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, NULL, 1, &to_host, 0,
                       NULL);
}

/* Window: the swapchain image to PRESENT_SRC (after the copy, if any). */
static void record_present_layout(tlod_platform* p, VkCommandBuffer cmd) {
  _tlod_platform_vk* vk = p->vk;
  bool copied = vk->swap_readback;
  VkImageMemoryBarrier b =
      image_barrier(color_image(vk, p), VK_IMAGE_ASPECT_COLOR_BIT,
                    copied ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                    VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, copied ? 0 : VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, 0);
  VkPipelineStageFlags src = copied ? VK_PIPELINE_STAGE_TRANSFER_BIT : VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  vkCmdPipelineBarrier(cmd, src, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0, 0, NULL, 0, NULL, 1, &b);
}

static bool submit(tlod_platform* p, vk_frame* f, double* submit_ms, char* error, size_t error_size) {
  _tlod_platform_vk* vk = p->vk;
  const VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  VkSubmitInfo info = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO,
                       .waitSemaphoreCount = p->window ? 1 : 0,
                       .pWaitSemaphores = &f->acquired,
                       .pWaitDstStageMask = &wait_stage,
                       .commandBufferCount = 1,
                       .pCommandBuffers = &f->cmd,
                       .signalSemaphoreCount = p->window ? 1 : 0,
                       .pSignalSemaphores = &vk->rendered[vk->image]};
  /* The fence is reset only here, right before the submit that signals it:
   * a frame that fails earlier leaves it signalled, so no later wait hangs. */
  if (!_tlod_vk_check(vkResetFences(vk->device, 1, &f->fence), "vkResetFences", error, error_size)) return false;
  double t0 = tlod_platform_time_ms();
  VkResult r = vkQueueSubmit(vk->queue, 1, &info, f->fence);
  if (submit_ms) *submit_ms = tlod_platform_time_ms() - t0;
  if (r < 0) (void)vkQueueSubmit(vk->queue, 0, NULL, f->fence); /* signal it anyway (or the device is lost) */
  return _tlod_vk_check(r, "vkQueueSubmit", error, error_size);
}

bool _tlod_platform_vk_end_frame(tlod_platform* p, double* submit_ms, char* error, size_t error_size) {
  _tlod_platform_vk* vk = p->vk;
  if (!vk->in_frame) {
    _tlod_platform_error(error, error_size, "tlod_platform_end_frame: no frame was begun");
    return false;
  }
  vk->in_frame = false;
  vk_frame* f = &vk->frames[vk->slot];
  vkCmdEndRendering(f->cmd);
  if (f->readback) record_readback(p, f->cmd); /* window: only with TRANSFER_SRC usage */
  if (p->window) record_present_layout(p, f->cmd);
  if (!_tlod_vk_check(vkEndCommandBuffer(f->cmd), "vkEndCommandBuffer", error, error_size) ||
      !submit(p, f, submit_ms, error, error_size))
    return false;
  vk->frame++;
  vk->has_frame = f->readback != VK_NULL_HANDLE;
  return !p->window || _tlod_vk_window_present(p, error, error_size);
}

bool _tlod_platform_vk_read_rgba(tlod_platform* p, uint8_t* rgba) {
  _tlod_platform_vk* vk = p->vk;
  if (!vk->has_frame || vk->in_frame) return false;
  vk_frame* f = &vk->frames[vk->slot];
  if (vkWaitForFences(vk->device, 1, &f->fence, VK_TRUE, FENCE_TIMEOUT_NS) != VK_SUCCESS) return false;
  if (!vk->readback_coherent) {
    VkMappedMemoryRange range = {
        .sType = VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, .memory = f->readback_memory, .size = VK_WHOLE_SIZE};
    if (vkInvalidateMappedMemoryRanges(vk->device, 1, &range) != VK_SUCCESS) return false;
  }
  size_t bytes = (size_t)p->width * p->height * 4;
  memcpy(rgba, f->mapped, bytes); /* image row 0 is the top row */
  bool bgra = vk->color_format == VK_FORMAT_B8G8R8A8_UNORM || vk->color_format == VK_FORMAT_B8G8R8A8_SRGB;
  for (size_t i = 0; bgra && i < bytes; i += 4) {
    uint8_t b = rgba[i];
    rgba[i] = rgba[i + 2];
    rgba[i + 2] = b;
  }
  return true;
}

bool _tlod_platform_vk_finish(tlod_platform* p) {
  _tlod_platform_vk* vk = p->vk;
  VkFence fences[VK_FRAMES];
  for (int i = 0; i < VK_FRAMES; ++i)
    fences[i] = vk->frames[i].fence;
  return !vk->in_frame && vkWaitForFences(vk->device, VK_FRAMES, fences, VK_TRUE, FENCE_TIMEOUT_NS) == VK_SUCCESS;
}

bool _tlod_platform_vk_resize(tlod_platform* p, uint32_t width, uint32_t height, char* error, size_t error_size) {
  _tlod_platform_vk* vk = p->vk;
  if (vk->in_frame) {
    _tlod_platform_error(error, error_size, "tlod_platform_resize: inside a frame (call it after end_frame)");
    return false;
  }
  if (!_tlod_vk_check(vkDeviceWaitIdle(vk->device), "vkDeviceWaitIdle", error, error_size)) return false;
  if (p->window) {
    _tlod_platform_glfw_resize(p, width, height);
    return _tlod_vk_swapchain_create(p, error, error_size);
  }
  _tlod_vk_size_objects_destroy(p);
  p->width = width;
  p->height = height;
  return _tlod_vk_size_objects_create(p, error, error_size);
}
