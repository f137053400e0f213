/*
 * platform_vk.h -- private state of the Vulkan part of platform/, shared by
 * platform_vk_instance.c (instance, validation messenger, device),
 * platform_vk.c (attachments, frames, read-back) and platform_vk_window.c
 * (surface, swapchain, acquire / present).
 */
#ifndef TLOD_PLATFORM_VK_H
#define TLOD_PLATFORM_VK_H

#include <stdatomic.h>
#include <vulkan/vulkan.h>

#include "platform_internal.h"

#define VK_FRAMES 2
#define VK_MAX_SWAP_IMAGES 8

typedef struct vk_image {
  VkImage image;
  VkDeviceMemory memory;
  VkImageView view;
} vk_image;

typedef struct vk_frame {
  VkCommandBuffer cmd;
  VkFence fence;        /* created signalled: the first wait passes */
  VkSemaphore acquired; /* window: signalled by vkAcquireNextImageKHR */
  VkBuffer readback;    /* colour copy of this frame, host visible */
  VkDeviceMemory readback_memory;
  void* mapped;
} vk_frame;

struct _tlod_platform_vk {
  VkInstance instance;
  VkDebugUtilsMessengerEXT messenger;
  _Atomic uint64_t messages; /* validation warnings + errors on this platform */
  VkPhysicalDevice physical;
  VkPhysicalDeviceMemoryProperties memory;
  VkDevice device;
  VkQueue queue;
  uint32_t family;
  bool tessellation, host_query_reset;
  VkFormat color_format, depth_format;
  vk_image color, depth; /* color: headless only (window: the swapchain image) */
  VkCommandPool pool;
  vk_frame frames[VK_FRAMES];
  bool readback_coherent;
  uint64_t frame; /* frames begun */
  uint32_t slot;  /* frames[] of the frame being recorded / last ended */
  bool in_frame;  /* between begin_frame and end_frame */
  bool has_frame; /* frames[slot] holds a submitted frame read_rgba may read */
  /* window */
  VkSurfaceKHR surface;
  VkSwapchainKHR swapchain;
  uint32_t image_count, image; /* image: acquired index */
  VkImage images[VK_MAX_SWAP_IMAGES];
  VkImageView views[VK_MAX_SWAP_IMAGES];
  VkSemaphore rendered[VK_MAX_SWAP_IMAGES]; /* per image: the present waits on it */
  bool swap_readback;                       /* the swapchain has TRANSFER_SRC usage */
  bool recreate;                            /* out of date / suboptimal: recreate at the next begin_frame */
};

/* "VK_ERROR_DEVICE_LOST" etc. */
const char* _tlod_vk_result_name(VkResult r);
/* false and "<what> failed: VK_ERROR_... (n)" in error when r < 0. */
bool _tlod_vk_check(VkResult r, const char* what, char* error, size_t error_size);

/* platform_vk_instance.c: instance (+ messenger with desc->validation),
 * extensions of the window (GLFW's) when window is true. */
bool _tlod_vk_instance_create(tlod_platform* p, bool validation, char* error, size_t error_size);
/* The first physical device with a graphics queue (+ present support on
 * the surface when there is one) and Vulkan 1.3 dynamic rendering; the
 * device, queue, describe strings. */
bool _tlod_vk_device_create(tlod_platform* p, char* error, size_t error_size);
void _tlod_vk_instance_destroy(tlod_platform* p);

/* platform_vk.c: an image of format / usage / aspect with its memory and view. */
bool _tlod_vk_image_create(tlod_platform* p, vk_image* img, VkFormat format, VkImageUsageFlags usage,
                           VkImageAspectFlags aspect, uint32_t width, uint32_t height, char* error, size_t error_size);
void _tlod_vk_image_destroy(tlod_platform* p, vk_image* img);
/* The depth image and read-back buffers at p's size (window: after the
 * swapchain). */
bool _tlod_vk_size_objects_create(tlod_platform* p, char* error, size_t error_size);
void _tlod_vk_size_objects_destroy(tlod_platform* p);
VkImageAspectFlags _tlod_vk_depth_aspect(VkFormat format);

/* platform_vk_window.c */
bool _tlod_vk_surface_create(tlod_platform* p, char* error, size_t error_size);
bool _tlod_vk_swapchain_create(tlod_platform* p, char* error, size_t error_size);
void _tlod_vk_swapchain_destroy(tlod_platform* p, bool keep_handle);
/* begin_frame of a window: waits for a size, recreates, acquires. */
bool _tlod_vk_window_acquire(tlod_platform* p, char* error, size_t error_size);
/* end_frame of a window after the submit. */
bool _tlod_vk_window_present(tlod_platform* p, char* error, size_t error_size);

#endif
