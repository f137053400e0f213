/*
 * platform_vk.c -- the Vulkan part of platform/, second half: creation and
 * destruction of the attachments, the 2 frames in flight (command buffer,
 * fence, read-back buffer each) and the whole platform. The instance and
 * device are platform_vk_instance.c's, the frame loop platform_vk_frame.c's,
 * the swapchain platform_vk_window.c's.
 */
#define _POSIX_C_SOURCE 200809L

#include <dlfcn.h>
#include <stdlib.h>
#include <string.h>

#include "platform_vk.h"

/* ------------------------------------------------------------------------ */
/* Memory, images, buffers                                                  */
/* ------------------------------------------------------------------------ */

/* A memory type of bits with all of `need`; UINT32_MAX when none. */
static uint32_t memory_type(const _tlod_platform_vk* vk, uint32_t bits, VkMemoryPropertyFlags need) {
  for (uint32_t i = 0; i < vk->memory.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (vk->memory.memoryTypes[i].propertyFlags & need) == need) return i;
  return UINT32_MAX;
}

static bool allocate(_tlod_platform_vk* vk, VkMemoryRequirements req, VkMemoryPropertyFlags need,
                     VkDeviceMemory* memory, const char* what, char* error, size_t error_size) {
  uint32_t type = memory_type(vk, req.memoryTypeBits, need);
  if (type == UINT32_MAX) {
    _tlod_platform_error(error, error_size, "%s: no memory type with properties 0x%x", what, (unsigned)need);
    return false;
  }
  VkMemoryAllocateInfo info = {
      .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size, .memoryTypeIndex = type};
  return _tlod_vk_check(vkAllocateMemory(vk->device, &info, NULL, memory), what, error, error_size);
}

VkImageAspectFlags _tlod_vk_depth_aspect(VkFormat format) {
  bool stencil = format == VK_FORMAT_D24_UNORM_S8_UINT || format == VK_FORMAT_D32_SFLOAT_S8_UINT ||
                 format == VK_FORMAT_D16_UNORM_S8_UINT;
  return VK_IMAGE_ASPECT_DEPTH_BIT | (stencil ? VK_IMAGE_ASPECT_STENCIL_BIT : 0);
}

bool _tlod_vk_image_create(tlod_platform* p, vk_image* img, VkFormat format, VkImageUsageFlags usage,
                           VkImageAspectFlags aspect, uint32_t width, uint32_t height, char* error, size_t error_size) {
  _tlod_platform_vk* vk = p->vk;
  VkImageCreateInfo info = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
                            .imageType = VK_IMAGE_TYPE_2D,
                            .format = format,
                            .extent = {width, height, 1},
                            .mipLevels = 1,
                            .arrayLayers = 1,
                            .samples = VK_SAMPLE_COUNT_1_BIT,
                            .tiling = VK_IMAGE_TILING_OPTIMAL,
                            .usage = usage,
                            .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED};
  if (!_tlod_vk_check(vkCreateImage(vk->device, &info, NULL, &img->image), "vkCreateImage", error, error_size))
    return false;
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(vk->device, img->image, &req);
  if (!allocate(vk, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, &img->memory, "vkAllocateMemory (image)", error,
                error_size) ||
      !_tlod_vk_check(vkBindImageMemory(vk->device, img->image, img->memory, 0), "vkBindImageMemory", error,
                      error_size))
    return false;
  VkImageViewCreateInfo view = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
                                .image = img->image,
                                .viewType = VK_IMAGE_VIEW_TYPE_2D,
                                .format = format,
                                .subresourceRange = {aspect, 0, 1, 0, 1}};
  return _tlod_vk_check(vkCreateImageView(vk->device, &view, NULL, &img->view), "vkCreateImageView", error, error_size);
}

void _tlod_vk_image_destroy(tlod_platform* p, vk_image* img) {
  VkDevice d = p->vk->device;
  if (img->view) vkDestroyImageView(d, img->view, NULL);
  if (img->image) vkDestroyImage(d, img->image, NULL);
  if (img->memory) vkFreeMemory(d, img->memory, NULL);
  *img = (vk_image){0};
}

/* frames[i]'s host-visible buffer for one colour copy, mapped. */
static bool readback_create(tlod_platform* p, vk_frame* f, char* error, size_t error_size) {
  _tlod_platform_vk* vk = p->vk;
  VkBufferCreateInfo info = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                             .size = (VkDeviceSize)p->width * p->height * 4,
                             .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                             .sharingMode = VK_SHARING_MODE_EXCLUSIVE};
  if (!_tlod_vk_check(vkCreateBuffer(vk->device, &info, NULL, &f->readback), "vkCreateBuffer (read-back)", error,
                      error_size))
    return false;
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(vk->device, f->readback, &req);
  const VkMemoryPropertyFlags coherent = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  vk->readback_coherent = memory_type(vk, req.memoryTypeBits, coherent) != UINT32_MAX;
  VkMemoryPropertyFlags need = vk->readback_coherent ? coherent : VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
  return allocate(vk, req, need, &f->readback_memory, "vkAllocateMemory (read-back)", error, error_size) &&
         _tlod_vk_check(vkBindBufferMemory(vk->device, f->readback, f->readback_memory, 0), "vkBindBufferMemory", error,
                        error_size) &&
         _tlod_vk_check(vkMapMemory(vk->device, f->readback_memory, 0, VK_WHOLE_SIZE, 0, &f->mapped), "vkMapMemory",
                        error, error_size);
}

static bool needs_readback(const tlod_platform* p) { return !p->window || p->vk->swap_readback; }

bool _tlod_vk_size_objects_create(tlod_platform* p, char* error, size_t error_size) {
  _tlod_platform_vk* vk = p->vk;
  if (!p->window && !_tlod_vk_image_create(p, &vk->color, vk->color_format,
                                           VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                           VK_IMAGE_ASPECT_COLOR_BIT, p->width, p->height, error, error_size))
    return false;
  if (!_tlod_vk_image_create(p, &vk->depth, vk->depth_format, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                             _tlod_vk_depth_aspect(vk->depth_format), p->width, p->height, error, error_size))
    return false;
  for (int i = 0; i < VK_FRAMES && needs_readback(p); ++i)
    if (!readback_create(p, &vk->frames[i], error, error_size)) return false;
  return true;
}

void _tlod_vk_size_objects_destroy(tlod_platform* p) {
  _tlod_platform_vk* vk = p->vk;
  _tlod_vk_image_destroy(p, &vk->color);
  _tlod_vk_image_destroy(p, &vk->depth);
  for (int i = 0; i < VK_FRAMES; ++i) {
    vk_frame* f = &vk->frames[i];
    if (f->readback) vkDestroyBuffer(vk->device, f->readback, NULL);
    if (f->readback_memory) vkFreeMemory(vk->device, f->readback_memory, NULL); /* unmaps */
    f->readback = VK_NULL_HANDLE;
    f->readback_memory = VK_NULL_HANDLE;
    f->mapped = NULL;
  }
  vk->has_frame = false;
}

/* ------------------------------------------------------------------------ */
/* Creation                                                                 */
/* ------------------------------------------------------------------------ */

static bool pick_formats(tlod_platform* p, char* error, size_t error_size) {
  _tlod_platform_vk* vk = p->vk;
  static const VkFormat depths[] = {VK_FORMAT_D32_SFLOAT, VK_FORMAT_D24_UNORM_S8_UINT, VK_FORMAT_D16_UNORM};
  vk->depth_format = VK_FORMAT_UNDEFINED;
  for (size_t i = 0; i < sizeof depths / sizeof depths[0] && !vk->depth_format; ++i) {
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(vk->physical, depths[i], &props);
    if (props.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) vk->depth_format = depths[i];
  }
  if (!vk->depth_format) {
    _tlod_platform_error(error, error_size, "Vulkan device: no depth attachment format (D32_SFLOAT, D24S8, D16)");
    return false;
  }
  if (p->window) return true; /* colour: the swapchain's */
  vk->color_format = VK_FORMAT_R8G8B8A8_UNORM;
  VkFormatProperties props;
  vkGetPhysicalDeviceFormatProperties(vk->physical, vk->color_format, &props);
  const VkFormatFeatureFlags need = VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
  if ((props.optimalTilingFeatures & need) == need) return true;
  _tlod_platform_error(error, error_size, "Vulkan device: R8G8B8A8_UNORM is no colour attachment / transfer source");
  return false;
}

static bool frames_create(tlod_platform* p, char* error, size_t error_size) {
  _tlod_platform_vk* vk = p->vk;
  VkCommandPoolCreateInfo pool = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                  .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                  .queueFamilyIndex = vk->family};
  if (!_tlod_vk_check(vkCreateCommandPool(vk->device, &pool, NULL, &vk->pool), "vkCreateCommandPool", error,
                      error_size))
    return false;
  VkFenceCreateInfo fence = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, .flags = VK_FENCE_CREATE_SIGNALED_BIT};
  VkSemaphoreCreateInfo sem = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  for (int i = 0; i < VK_FRAMES; ++i) {
    vk_frame* f = &vk->frames[i];
    VkCommandBufferAllocateInfo cmd = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                       .commandPool = vk->pool,
                                       .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                       .commandBufferCount = 1};
    if (!_tlod_vk_check(vkAllocateCommandBuffers(vk->device, &cmd, &f->cmd), "vkAllocateCommandBuffers", error,
                        error_size) ||
        !_tlod_vk_check(vkCreateFence(vk->device, &fence, NULL, &f->fence), "vkCreateFence", error, error_size))
      return false;
    if (p->window && !_tlod_vk_check(vkCreateSemaphore(vk->device, &sem, NULL, &f->acquired), "vkCreateSemaphore",
                                     error, error_size))
      return false;
  }
  return true;
}

static void frames_destroy(tlod_platform* p) {
  _tlod_platform_vk* vk = p->vk;
  for (int i = 0; i < VK_FRAMES; ++i) {
    vk_frame* f = &vk->frames[i];
    if (f->fence) vkDestroyFence(vk->device, f->fence, NULL);
    if (f->acquired) vkDestroySemaphore(vk->device, f->acquired, NULL);
    f->fence = VK_NULL_HANDLE;
    f->acquired = VK_NULL_HANDLE;
    f->cmd = VK_NULL_HANDLE; /* freed with the pool */
  }
  if (vk->pool) vkDestroyCommandPool(vk->device, vk->pool, NULL);
  vk->pool = VK_NULL_HANDLE;
}

/* The loader dlclose()s every driver (lavapipe and the Mesa drivers that
 * find no hardware here) and layer (validation, Mesa's device select) in
 * vkDestroyInstance; what they keep in globals (LLVM's, the C++ layer's)
 * is then reported by LeakSanitizer from an "<unknown module>" no
 * suppression can name, as platform_egl.c explains for the GL driver.
 * Keeping them mapped (RTLD_NODELETE) keeps those blocks reachable without
 * hiding a leak of ours. A missing library is ignored. */
static void keep_drivers_loaded(void) {
  static const char* const libs[] = {"libvulkan_lvp.so",
                                     "libvulkan_radeon.so",
                                     "libvulkan_intel.so",
                                     "libvulkan_intel_hasvk.so",
                                     "libVkLayer_MESA_device_select.so",
                                     "libVkLayer_khronos_validation.so"};
  for (size_t i = 0; i < sizeof libs / sizeof libs[0]; ++i)
    (void)dlopen(libs[i], RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
}

/* VK_LAYER_KHRONOS_validation 1.3.239 itself leaks two blocks (about 3 KB)
 * per instance, allocated inside the layer and reachable from nothing;
 * LeakSanitizer (ASan builds) reads this hook from the executable. It
 * names only that module: a Vulkan object we forget is reported by the
 * layer's object tracker as a validation error instead (counted). Unused
 * without LeakSanitizer. */
__attribute__((visibility("default"))) const char* __lsan_default_suppressions(void);
__attribute__((visibility("default"))) const char* __lsan_default_suppressions(void) {
  return "leak:libVkLayer_khronos_validation.so\n";
}

bool _tlod_platform_vk_create(tlod_platform* p, const tlod_platform_desc* d, char* error, size_t error_size) {
  keep_drivers_loaded();
  p->kind = d->window ? "Vulkan window" : "Vulkan headless";
  if (d->samples > 1) {
    _tlod_platform_error(error, error_size, "Vulkan platform: %u samples requested, only 1 is supported", d->samples);
    return false;
  }
  p->vk = calloc(1, sizeof *p->vk);
  if (!p->vk) {
    _tlod_platform_error(error, error_size, "Vulkan platform: out of memory");
    return false;
  }
  if (d->window && !_tlod_platform_glfw_create(p, d, false, error, error_size)) return false;
  if (!_tlod_vk_instance_create(p, d->validation, error, error_size)) return false;
  if (d->window && !_tlod_vk_surface_create(p, error, error_size)) return false;
  if (!_tlod_vk_device_create(p, error, error_size) || !pick_formats(p, error, error_size) ||
      !frames_create(p, error, error_size))
    return false;
  if (d->window) return _tlod_vk_swapchain_create(p, error, error_size); /* + size objects */
  return _tlod_vk_size_objects_create(p, error, error_size);
}

void _tlod_platform_vk_destroy(tlod_platform* p) {
  _tlod_platform_vk* vk = p->vk;
  if (vk) {
    if (vk->device) {
      vkDeviceWaitIdle(vk->device);
      _tlod_vk_size_objects_destroy(p);
      _tlod_vk_swapchain_destroy(p, false);
      frames_destroy(p);
    }
    _tlod_vk_instance_destroy(p);
  }
  if (p->window) _tlod_platform_glfw_destroy(p);
  free(vk);
  p->vk = NULL;
}

bool _tlod_platform_vk_info(const tlod_platform* p, tlod_platform_vk* out) {
  const _tlod_platform_vk* vk = p->vk;
  *out = (tlod_platform_vk){.instance = vk->instance,
                            .physical_device = vk->physical,
                            .device = vk->device,
                            .queue = vk->queue,
                            .queue_family = vk->family,
                            .color_format = (uint32_t)vk->color_format,
                            .depth_format = (uint32_t)vk->depth_format,
                            .frames_in_flight = VK_FRAMES,
                            .host_query_reset = vk->host_query_reset,
                            .tessellation = vk->tessellation};
  return true;
}
