/*
 * platform_vk_window.c -- the Vulkan window of platform/: the GLFW window's
 * surface, a FIFO swapchain (B8G8R8A8_UNORM when offered), its
 * re-creation (out of date, suboptimal, resized or minimised windows), and
 * acquire / present around a frame. The window itself is platform_glfw.c's.
 */
#define _POSIX_C_SOURCE 200809L

#define GLFW_INCLUDE_NONE
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "platform_vk.h"

bool _tlod_vk_surface_create(tlod_platform* p, char* error, size_t error_size) {
  VkResult r = glfwCreateWindowSurface(p->vk->instance, (GLFWwindow*)p->glfw_window, NULL, &p->vk->surface);
  return _tlod_vk_check(r, "glfwCreateWindowSurface", error, error_size);
}

void _tlod_vk_swapchain_destroy(tlod_platform* p, bool keep_handle) {
  _tlod_platform_vk* vk = p->vk;
  for (uint32_t i = 0; i < vk->image_count; ++i) {
    if (vk->views[i]) vkDestroyImageView(vk->device, vk->views[i], NULL);
    if (vk->rendered[i]) vkDestroySemaphore(vk->device, vk->rendered[i], NULL);
    vk->views[i] = VK_NULL_HANDLE;
    vk->rendered[i] = VK_NULL_HANDLE;
    vk->images[i] = VK_NULL_HANDLE;
  }
  vk->image_count = 0;
  if (!keep_handle && vk->swapchain) vkDestroySwapchainKHR(vk->device, vk->swapchain, NULL);
  if (!keep_handle) vk->swapchain = VK_NULL_HANDLE;
}

/* The format the swapchain keeps: the previous one (pipelines were made for
 * it), else B8G8R8A8_UNORM, else the first offered. */
static bool pick_surface_format(_tlod_platform_vk* vk, VkSurfaceFormatKHR* out, char* error, size_t error_size) {
  VkSurfaceFormatKHR formats[32];
  uint32_t n = 32;
  VkResult r = vkGetPhysicalDeviceSurfaceFormatsKHR(vk->physical, vk->surface, &n, formats);
  if (!_tlod_vk_check(r, "vkGetPhysicalDeviceSurfaceFormatsKHR", error, error_size)) return false;
  if (n == 0) {
    _tlod_platform_error(error, error_size, "vkGetPhysicalDeviceSurfaceFormatsKHR: the surface offers no format");
    return false;
  }
  VkFormat want = vk->color_format ? vk->color_format : VK_FORMAT_B8G8R8A8_UNORM;
  *out = formats[0];
  for (uint32_t i = 0; i < n; ++i)
    if (formats[i].format == want) *out = formats[i];
  if (vk->color_format && out->format != vk->color_format) {
    _tlod_platform_error(error, error_size, "swapchain re-creation: the surface no longer offers format %d",
                         (int)vk->color_format);
    return false;
  }
  return true;
}

/* The surface's capabilities once the window has a size (minimised: waits
 * for events). */
static bool wait_capabilities(tlod_platform* p, VkSurfaceCapabilitiesKHR* caps, VkExtent2D* extent, char* error,
                              size_t error_size) {
  _tlod_platform_vk* vk = p->vk;
  for (;;) {
    uint32_t w = 0, h = 0;
    if (!_tlod_platform_glfw_wait_size(p, &w, &h)) {
      _tlod_platform_error(error, error_size, "Vulkan window: closed while minimised");
      return false;
    }
    VkResult r = vkGetPhysicalDeviceSurfaceCapabilitiesKHR(vk->physical, vk->surface, caps);
    if (!_tlod_vk_check(r, "vkGetPhysicalDeviceSurfaceCapabilitiesKHR", error, error_size)) return false;
    *extent = caps->currentExtent.width != UINT32_MAX ? caps->currentExtent : (VkExtent2D){w, h};
    if (extent->width > 0 && extent->height > 0) return true;
    glfwWaitEvents();
  }
}

static VkCompositeAlphaFlagBitsKHR composite_alpha(VkCompositeAlphaFlagsKHR supported) {
  static const VkCompositeAlphaFlagBitsKHR order[] = {
      VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR, VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR, VK_COMPOSITE_ALPHA_PRE_MULTIPLIED_BIT_KHR,
      VK_COMPOSITE_ALPHA_POST_MULTIPLIED_BIT_KHR};
  for (size_t i = 0; i < sizeof order / sizeof order[0]; ++i)
    if (supported & order[i]) return order[i];
  return VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
}

static bool readable_format(VkFormat f) {
  return f == VK_FORMAT_B8G8R8A8_UNORM || f == VK_FORMAT_B8G8R8A8_SRGB || f == VK_FORMAT_R8G8B8A8_UNORM ||
         f == VK_FORMAT_R8G8B8A8_SRGB;
}

static bool create_handle(tlod_platform* p, const VkSurfaceCapabilitiesKHR* caps, VkExtent2D extent,
                          VkSurfaceFormatKHR format, char* error, size_t error_size) {
  _tlod_platform_vk* vk = p->vk;
  uint32_t count = caps->minImageCount + 1;
  if (caps->maxImageCount && count > caps->maxImageCount) count = caps->maxImageCount;
  vk->swap_readback = (caps->supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) && readable_format(format.format);
  VkSwapchainKHR old = vk->swapchain;
  VkSwapchainCreateInfoKHR info = {.sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR,
                                   .surface = vk->surface,
                                   .minImageCount = count,
                                   .imageFormat = format.format,
                                   .imageColorSpace = format.colorSpace,
                                   .imageExtent = extent,
                                   .imageArrayLayers = 1,
                                   .imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
                                                 (vk->swap_readback ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0),
                                   .imageSharingMode = VK_SHARING_MODE_EXCLUSIVE,
                                   .preTransform = caps->currentTransform,
                                   .compositeAlpha = composite_alpha(caps->supportedCompositeAlpha),
                                   .presentMode = VK_PRESENT_MODE_FIFO_KHR, /* always supported */
                                   .clipped = VK_TRUE,
                                   .oldSwapchain = old};
  VkResult r = vkCreateSwapchainKHR(vk->device, &info, NULL, &vk->swapchain);
  _tlod_vk_swapchain_destroy(p, true);
  if (old) vkDestroySwapchainKHR(vk->device, old, NULL);
  if (r < 0) vk->swapchain = VK_NULL_HANDLE;
  return _tlod_vk_check(r, "vkCreateSwapchainKHR (FIFO)", error, error_size);
}

static bool create_views(tlod_platform* p, char* error, size_t error_size) {
  _tlod_platform_vk* vk = p->vk;
  uint32_t n = 0;
  VkResult r = vkGetSwapchainImagesKHR(vk->device, vk->swapchain, &n, NULL);
  if (!_tlod_vk_check(r, "vkGetSwapchainImagesKHR", error, error_size)) return false;
  if (n > VK_MAX_SWAP_IMAGES) {
    _tlod_platform_error(error, error_size, "swapchain has %u images, at most %d are handled", n, VK_MAX_SWAP_IMAGES);
    return false;
  }
  r = vkGetSwapchainImagesKHR(vk->device, vk->swapchain, &n, vk->images);
  if (!_tlod_vk_check(r, "vkGetSwapchainImagesKHR", error, error_size)) return false;
  VkSemaphoreCreateInfo sem = {.sType = VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  for (uint32_t i = 0; i < n; ++i) {
    vk->image_count = i + 1; /* what exists so far is destroyed on failure */
    VkImageViewCreateInfo view = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
                                  .image = vk->images[i],
                                  .viewType = VK_IMAGE_VIEW_TYPE_2D,
                                  .format = vk->color_format,
                                  .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
    if (!_tlod_vk_check(vkCreateImageView(vk->device, &view, NULL, &vk->views[i]), "vkCreateImageView (swapchain)",
                        error, error_size) ||
        !_tlod_vk_check(vkCreateSemaphore(vk->device, &sem, NULL, &vk->rendered[i]), "vkCreateSemaphore", error,
                        error_size))
      return false;
  }
  return true;
}

bool _tlod_vk_swapchain_create(tlod_platform* p, char* error, size_t error_size) {
  _tlod_platform_vk* vk = p->vk;
  if (!_tlod_vk_check(vkDeviceWaitIdle(vk->device), "vkDeviceWaitIdle", error, error_size)) return false;
  VkSurfaceCapabilitiesKHR caps;
  VkExtent2D extent;
  VkSurfaceFormatKHR format;
  if (!wait_capabilities(p, &caps, &extent, error, error_size) || !pick_surface_format(vk, &format, error, error_size))
    return false;
  _tlod_vk_size_objects_destroy(p);
  vk->color_format = format.format;
  if (!create_handle(p, &caps, extent, format, error, error_size) || !create_views(p, error, error_size)) return false;
  p->width = extent.width;
  p->height = extent.height;
  vk->recreate = false;
  return _tlod_vk_size_objects_create(p, error, error_size);
}

bool _tlod_vk_window_acquire(tlod_platform* p, char* error, size_t error_size) {
  _tlod_platform_vk* vk = p->vk;
  int fw = 0, fh = 0;
  glfwGetFramebufferSize((GLFWwindow*)p->glfw_window, &fw, &fh);
  if ((uint32_t)fw != p->width || (uint32_t)fh != p->height) vk->recreate = true; /* resized or minimised */
  for (int attempt = 0; attempt < 2; ++attempt) {
    if ((vk->recreate || !vk->swapchain) && !_tlod_vk_swapchain_create(p, error, error_size)) return false;
    VkResult r = vkAcquireNextImageKHR(vk->device, vk->swapchain, UINT64_MAX, vk->frames[vk->slot].acquired,
                                       VK_NULL_HANDLE, &vk->image);
    if (r == VK_ERROR_OUT_OF_DATE_KHR) {
      vk->recreate = true;
      continue;
    }
    if (r == VK_SUBOPTIMAL_KHR) vk->recreate = true; /* usable now, recreated next frame */
    return _tlod_vk_check(r, "vkAcquireNextImageKHR", error, error_size);
  }
  _tlod_platform_error(error, error_size, "vkAcquireNextImageKHR: swapchain out of date right after re-creation");
  return false;
}

bool _tlod_vk_window_present(tlod_platform* p, char* error, size_t error_size) {
  _tlod_platform_vk* vk = p->vk;
  VkPresentInfoKHR info = {.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR,
                           .waitSemaphoreCount = 1,
                           .pWaitSemaphores = &vk->rendered[vk->image],
                           .swapchainCount = 1,
                           .pSwapchains = &vk->swapchain,
                           .pImageIndices = &vk->image};
  VkResult r = vkQueuePresentKHR(vk->queue, &info);
  if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) {
    vk->recreate = true; /* at the next begin_frame */
    return true;
  }
  return _tlod_vk_check(r, "vkQueuePresentKHR", error, error_size);
}
