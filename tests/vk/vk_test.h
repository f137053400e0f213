/*
 * vk_test.h -- shared fixtures of the Vulkan tests (tests/vk/<name>_test.c):
 * a headless Vulkan platform from platform/ (lavapipe on the CI machine),
 * "vulkan" devices on it, sessions, and one recorded-submitted-read-back
 * frame. The API-independent fixtures (cameras, tesslod fixtures, one-item
 * draws, image comparison) are tests/unit/test_device.h. Header-only.
 *
 * Vulkan tests FAIL (never skip) when no Vulkan device can be created: the
 * platform's reason is printed.
 */
#ifndef TLOD_VK_TEST_H
#define TLOD_VK_TEST_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test.h"
#include "test_device.h"
#include "tlod_platform.h"

#define VK_TEST_END() DEVICE_TEST_END()

/* The tests' clear colour: pure blue (test_device.h's background). */
static const float vk_test_clear[4] = {BG_R / 255.0f, BG_G / 255.0f, BG_B / 255.0f, 1.0f};

/* ------------------------------------------------------------------------ */
/* Platform and devices                                                     */
/* ------------------------------------------------------------------------ */

/* Headless Vulkan platform of w x h (validation: the Khronos layer with
 * synchronization validation, messages counted), or NULL with the reason
 * printed. */
static inline tlod_platform* vk_test_platform(uint32_t w, uint32_t h, bool validation, char* error, size_t error_size) {
  tlod_platform* p = NULL;
  tlod_platform_desc d = {.width = w, .height = h, .api = TLOD_PLATFORM_VULKAN, .validation = validation};
  if (!tlod_platform_create(&d, &p, error, error_size)) {
    fprintf(stderr, "no Vulkan device: %s\n", error);
    return NULL;
  }
  static bool described;
  if (!described) {
    char buf[320];
    printf("  %s\n", tlod_platform_describe(p, buf, sizeof buf));
    described = true;
  }
  return p;
}

/* The "vulkan" device options for the platform's device, formats and
 * features; the caller adds hardware_tessellation, cache folder, hook. */
static inline tlod_device_vk_desc vk_desc_of(const tlod_platform* p) {
  tlod_platform_vk info;
  memset(&info, 0, sizeof info);
  tlod_device_vk_desc vk;
  memset(&vk, 0, sizeof vk);
  if (!tlod_platform_vk_info(p, &info)) return vk;
  vk.instance = info.instance;
  vk.physical_device = info.physical_device;
  vk.device = info.device;
  vk.queue = info.queue;
  vk.queue_family = info.queue_family;
  vk.frames_in_flight = info.frames_in_flight;
  vk.color_format = info.color_format;
  vk.depth_format = info.depth_format;
  vk.host_query_reset = info.host_query_reset;
  return vk;
}

/* A "vulkan" device, or NULL with the reason printed. */
static inline tlod_device* new_vk_device(tlod_context* ctx, const tlod_patterns* patterns, const char* label,
                                         tlod_device_vk_desc vk) {
  /* The Vulkan tests are of the vertex-shader path: AUTO (the CPU mesh on
   * lavapipe) is ON unless a test asks for OFF. */
  if (vk.gpu_eval == TLOD_GPU_EVAL_DEFAULT) vk.gpu_eval = TLOD_GPU_EVAL_ON;
  return new_device(ctx, &(tlod_device_desc){.backend = "vulkan", .patterns = patterns, .vk = vk, .label = label});
}

/* What a Vulkan device test starts with: a headless platform, a tesslod
 * context, patterns and a "vulkan" device on them. */
typedef struct vk_session {
  tlod_platform* platform;
  tlod_context* ctx;
  tlod_patterns* pat;
  tlod_device* dev;
  uint32_t w, h;
} vk_session;

/* The engine's duty before destroying tesslod objects: the GPU is done with
 * every frame that used them (tesslod never waits). */
static inline void vk_session_close(vk_session* s) {
  if (s->platform) tlod_platform_finish(s->platform);
  tlod_device_destroy(s->dev);
  tlod_patterns_destroy(s->pat);
  tlod_context_destroy(s->ctx);
  if (s->platform) tlod_platform_destroy(s->platform);
  memset(s, 0, sizeof *s);
}

/* false with the reason printed (Vulkan tests then FAIL, never skip).
 * options: the device options beyond the platform's (vk_desc_of fills the
 * handles and formats over whatever options holds there). */
static inline bool vk_session_open(vk_session* s, uint32_t w, uint32_t h, uint32_t max_level, const char* label,
                                   bool validation, tlod_device_vk_desc options) {
  char err[512] = "";
  memset(s, 0, sizeof *s);
  s->w = w, s->h = h;
  s->platform = vk_test_platform(w, h, validation, err, sizeof err);
  if (!s->platform) return false;
  tlod_device_vk_desc vk = vk_desc_of(s->platform);
  vk.hardware_tessellation = options.hardware_tessellation;
  vk.shader_cache_dir = options.shader_cache_dir;
  vk.surface_types = options.surface_types;
  vk.fragment_hook = options.fragment_hook;
  if (tlod_context_create(&(tlod_context_desc){.thread_count = 2}, &s->ctx) != TLOD_SUCCESS ||
      !(s->pat = new_patterns(s->ctx, max_level)) || !(s->dev = new_vk_device(s->ctx, s->pat, label, vk))) {
    vk_session_close(s);
    return false;
  }
  return true;
}

/* ------------------------------------------------------------------------ */
/* Frames                                                                   */
/* ------------------------------------------------------------------------ */

/* Opens a platform frame cleared to the background and points desc.vk at
 * its command buffer; false with the reason printed. */
static inline bool vk_frame_begin(tlod_platform* p, tlod_draw_desc* desc) {
  char err[512] = "";
  tlod_platform_frame f;
  memset(&f, 0, sizeof f);
  if (!tlod_platform_begin_frame(p, vk_test_clear, &f, err, sizeof err)) {
    fprintf(stderr, "tlod_platform_begin_frame: %s\n", err);
    return false;
  }
  desc->vk.command_buffer = f.command_buffer;
  desc->vk.frame_index = f.frame_index;
  return true;
}

/* Ends and submits the frame; rgba (may be NULL) receives its image, top
 * row first (waits for it). */
static inline bool vk_frame_end(tlod_platform* p, uint8_t* rgba) {
  char err[512] = "";
  if (!tlod_platform_end_frame(p, NULL, err, sizeof err)) {
    fprintf(stderr, "tlod_platform_end_frame: %s\n", err);
    return false;
  }
  if (rgba && !tlod_platform_read_rgba(p, rgba)) {
    fprintf(stderr, "tlod_platform_read_rgba failed\n");
    return false;
  }
  return true;
}

/* One whole frame of one draw desc on dev; false with the reason printed.
 * The frame is ended even when the draw fails (the command buffer stays
 * valid: a refused draw records nothing). */
static inline bool vk_draw_frame(tlod_platform* p, tlod_device* dev, tlod_context* ctx, tlod_draw_desc* desc,
                                 uint8_t* rgba) {
  if (!vk_frame_begin(p, desc)) return false;
  tlod_result r = tlod_device_draw(dev, desc);
  if (r != TLOD_SUCCESS)
    fprintf(stderr, "tlod_device_draw(\"vulkan\"): %s: %s\n", tlod_result_string(r), tlod_context_last_error(ctx));
  return vk_frame_end(p, rgba) && r == TLOD_SUCCESS;
}

/* No validation message in this process so far (platforms destroyed
 * included: the object tracker's leak reports at vkDestroyDevice count). */
static inline void vk_check_no_messages(void) {
  uint64_t n = tlod_platform_validation_messages(NULL);
  CHECK_MSG(n == 0, "%llu validation messages in this process (printed above)", (unsigned long long)n);
}

/* Pixels of an image that are not the background. */
static inline uint32_t covered_pixels(const uint8_t* rgba, uint32_t w, uint32_t h) {
  uint32_t n = 0;
  for (uint32_t i = 0; i < w * h; ++i)
    n += !is_background(rgba + 4 * i);
  return n;
}

#endif
