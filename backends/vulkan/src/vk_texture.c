/* tesslod::vulkan -- textures: an optimal-tiling R8G8B8A8 image (UNORM or
 * SRGB), level 0 copied from a staging buffer, the mip chain made by
 * vkCmdBlitImage level to level, left in SHADER_READ_ONLY_OPTIMAL; one
 * sampler per texture with the desc's wrap modes and filters (as
 * gl_texture.c). Rows go in as given: row 0 (t = 0) is the image's top row,
 * so glTF coordinates sample unchanged. */
#include <string.h>

#include "vk_internal.h"

static VkSamplerAddressMode wrap_of(tlod_wrap w) {
  switch (w) {
  case TLOD_WRAP_CLAMP_TO_EDGE:
    return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  case TLOD_WRAP_MIRRORED_REPEAT:
    return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
  default:
    return VK_SAMPLER_ADDRESS_MODE_REPEAT;
  }
}

static uint32_t mip_levels(uint32_t w, uint32_t h) {
  uint32_t n = 1;
  for (uint32_t m = w > h ? w : h; m > 1; m >>= 1)
    n++;
  return n;
}

static void barrier(VkCommandBuffer cmd, VkImage image, uint32_t level, uint32_t count, VkImageLayout from,
                    VkImageLayout to, VkAccessFlags src, VkAccessFlags dst, VkPipelineStageFlags src_stage,
                    VkPipelineStageFlags dst_stage) {
  VkImageMemoryBarrier b = {.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER,
                            .srcAccessMask = src,
                            .dstAccessMask = dst,
                            .oldLayout = from,
                            .newLayout = to,
                            .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                            .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                            .image = image,
                            .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, level, count, 0, 1}};
  vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 0, NULL, 0, NULL, 1, &b);
}

/* Level l - 1 (TRANSFER_DST) becomes the source of level l, then shader-readable. */
static void record_mips(VkCommandBuffer cmd, VkImage image, uint32_t w, uint32_t h, uint32_t levels) {
  for (uint32_t l = 1; l < levels; l++) {
    barrier(cmd, image, l - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
            VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
            VK_PIPELINE_STAGE_TRANSFER_BIT);
    int32_t sw = (int32_t)(w >> (l - 1) ? w >> (l - 1) : 1), sh = (int32_t)(h >> (l - 1) ? h >> (l - 1) : 1);
    int32_t dw = sw > 1 ? sw / 2 : 1, dh = sh > 1 ? sh / 2 : 1;
    VkImageBlit blit = {.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, l - 1, 0, 1},
                        .srcOffsets = {{0, 0, 0}, {sw, sh, 1}},
                        .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, l, 0, 1},
                        .dstOffsets = {{0, 0, 0}, {dw, dh, 1}}};
    vkCmdBlitImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                   &blit, VK_FILTER_LINEAR);
    barrier(cmd, image, l - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
            VK_ACCESS_TRANSFER_READ_BIT, VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
            VK_PIPELINE_STAGE_ALL_GRAPHICS_BIT);
  }
  barrier(cmd, image, levels - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
          VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
          VK_PIPELINE_STAGE_ALL_GRAPHICS_BIT);
}

static VkResult upload(vk_memory* m, vk_upload* u, vk_texture* t, const tlod_texture_desc* desc, uint32_t levels) {
  VkDeviceSize bytes = 4ull * desc->width * desc->height;
  vk_buffer staging;
  VkResult r = _tlod_vkb_buffer_create(m, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, 1, &staging);
  if (r != VK_SUCCESS) return r;
  memcpy(staging.mem.mapped, desc->rgba8, (size_t)bytes);
  r = _tlod_vkb_upload_begin(u);
  if (r == VK_SUCCESS) {
    barrier(u->cmd, t->image, 0, levels, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
            VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
    VkBufferImageCopy copy = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                              .imageExtent = {desc->width, desc->height, 1}};
    vkCmdCopyBufferToImage(u->cmd, staging.buffer, t->image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
    record_mips(u->cmd, t->image, desc->width, desc->height, levels);
    r = _tlod_vkb_upload_submit(u);
  }
  _tlod_vkb_buffer_destroy(m, &staging);
  return r;
}

static VkResult make_image(vk_memory* m, vk_texture* t, VkFormat format, const tlod_texture_desc* desc,
                           uint32_t levels) {
  VkImageCreateInfo ii = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
                          .imageType = VK_IMAGE_TYPE_2D,
                          .format = format,
                          .extent = {desc->width, desc->height, 1},
                          .mipLevels = levels,
                          .arrayLayers = 1,
                          .samples = VK_SAMPLE_COUNT_1_BIT,
                          .tiling = VK_IMAGE_TILING_OPTIMAL,
                          .usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                                   VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                          .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED};
  VkResult r = vkCreateImage(m->device, &ii, m->cb, &t->image);
  if (r != VK_SUCCESS) return r;
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(m->device, t->image, &req);
  r = _tlod_vkb_memory_alloc(m, &req, VK_MEM_DEVICE | VK_MEM_OPTIMAL, &t->mem);
  if (r == VK_SUCCESS) r = vkBindImageMemory(m->device, t->image, t->mem.memory, t->mem.offset);
  VkImageViewCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
                              .image = t->image,
                              .viewType = VK_IMAGE_VIEW_TYPE_2D,
                              .format = format,
                              .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, levels, 0, 1}};
  if (r == VK_SUCCESS) r = vkCreateImageView(m->device, &vi, m->cb, &t->view);
  return r;
}

static VkResult make_sampler(vk_memory* m, vk_texture* t, const tlod_texture_desc* desc, uint32_t levels) {
  bool near_min = desc->min_filter == TLOD_FILTER_NEAREST, near_mag = desc->mag_filter == TLOD_FILTER_NEAREST;
  VkSamplerCreateInfo si = {.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
                            .magFilter = near_mag ? VK_FILTER_NEAREST : VK_FILTER_LINEAR,
                            .minFilter = near_min ? VK_FILTER_NEAREST : VK_FILTER_LINEAR,
                            .mipmapMode = near_min ? VK_SAMPLER_MIPMAP_MODE_NEAREST : VK_SAMPLER_MIPMAP_MODE_LINEAR,
                            .addressModeU = wrap_of(desc->wrap_s),
                            .addressModeV = wrap_of(desc->wrap_t),
                            .addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT,
                            .maxLod = (float)(levels - 1)};
  return vkCreateSampler(m->device, &si, m->cb, &t->sampler);
}

tlod_result _tlod_vkb_texture_create(tlod_context* ctx, vk_memory* m, vk_upload* u, VkPhysicalDevice pd,
                                     const tlod_texture_desc* desc, vk_texture** out) {
  VkFormat format = desc->srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
  uint32_t levels = desc->mipmaps_off ? 1 : mip_levels(desc->width, desc->height);
  VkFormatProperties fp;
  vkGetPhysicalDeviceFormatProperties(pd, format, &fp);
  VkFormatFeatureFlags need = VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
  if (levels > 1) need |= VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT;
  if ((fp.optimalTilingFeatures & need) != need)
    return tlod_context_fail(ctx, TLOD_ERROR_UNSUPPORTED,
                             "vulkan device: texture '%s': format %s lacks sampled linear filtering%s", desc->label,
                             desc->srgb ? "R8G8B8A8_SRGB" : "R8G8B8A8_UNORM", levels > 1 ? " or blits (mipmaps)" : "");
  vk_texture* t = tlod_context_calloc(ctx, 1, sizeof(*t));
  if (!t) return tlod_context_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "vulkan device: out of memory for a texture");
  VkResult r = make_image(m, t, format, desc, levels);
  if (r == VK_SUCCESS) r = upload(m, u, t, desc, levels);
  if (r == VK_SUCCESS) r = make_sampler(m, t, desc, levels);
  if (r != VK_SUCCESS) {
    _tlod_vkb_texture_destroy(ctx, m, t);
    return tlod_context_fail(ctx, r == VK_ERROR_OUT_OF_DEVICE_MEMORY ? TLOD_ERROR_OUT_OF_MEMORY : TLOD_ERROR_BACKEND,
                             "vulkan device: texture '%s' (%u x %u): %s", desc->label, desc->width, desc->height,
                             _tlod_vkb_result_name(r));
  }
  *out = t;
  return TLOD_SUCCESS;
}

void _tlod_vkb_texture_destroy(tlod_context* ctx, vk_memory* m, vk_texture* t) {
  if (t->sampler) vkDestroySampler(m->device, t->sampler, m->cb);
  if (t->view) vkDestroyImageView(m->device, t->view, m->cb);
  if (t->image) vkDestroyImage(m->device, t->image, m->cb);
  _tlod_vkb_memory_free(m, &t->mem);
  tlod_context_free(ctx, t);
}
