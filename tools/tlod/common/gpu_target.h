/* The GPU a "gl" or "vulkan" device draws on, for tlod play and tlod bench:
 * the platform (platform/tlod_platform.h: a GL context or a Vulkan device,
 * headless or a window) opened for the backend, the device desc's .vk taken
 * from it, and one frame through tlod_platform_begin_frame / end_frame for
 * both APIs (GL: bind + clear; Vulkan: the frame's command buffer inside
 * dynamic rendering, submitted at the end). A Vulkan platform that cannot
 * start is an error, never a fallback to another API. */
#ifndef TLOD_TOOLS_COMMON_GPU_TARGET_H
#define TLOD_TOOLS_COMMON_GPU_TARGET_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "tesslod/backend.h"

typedef struct tlod_platform tlod_platform;

typedef struct gpu_target_desc {
  const char* backend; /* "gl" or "vulkan" */
  uint32_t width, height;
  bool window;     /* a GLFW window (needs DISPLAY) instead of headless */
  bool validation; /* vulkan: the validation layer on (creation fails without it) */
  const char* title;
} gpu_target_desc;

/* True for the backends that draw through a platform: "gl", "vulkan". */
bool gpu_backend(const char* backend);
/* The platform for d->backend; false with the reason in err ("this build
 * has no Vulkan backend (TLOD_BACKEND_VULKAN=OFF)", or the platform's). */
bool gpu_target_open(const gpu_target_desc* d, tlod_platform** out, char* err, size_t err_size);
void gpu_target_close(tlod_platform* p);
/* d->vk from a Vulkan platform (its handles, formats, frames in flight,
 * host query reset; shader_cache_dir as given, NULL == no disk cache;
 * hardware tessellation only when asked for and the device has it). A GL
 * platform leaves d->vk zero. */
void gpu_target_device_desc(const tlod_platform* p, const char* shader_cache_dir, bool hardware, tlod_device_desc* d);
/* Begins a frame cleared to clear_rgba and fills d->vk from it. */
bool gpu_frame_begin(tlod_platform* p, const float clear_rgba[4], tlod_draw_desc* d, char* err, size_t err_size);
/* Ends it (Vulkan: submits). *gpu_ms: the time in the submit and, with
 * finish, the wait until the GPU has done the frame (tlod_platform_finish:
 * lavapipe's vkQueueSubmit returns before the work is done, so without it a
 * frame's wall time would miss its GPU work; GL: the draw's own finish has
 * waited, this adds about 0). */
bool gpu_frame_end(tlod_platform* p, bool finish, double* gpu_ms, char* err, size_t err_size);
/* Validation messages (errors + warnings) counted so far on p; 0 without
 * validation. NULL: every platform of the process, destroyed ones too (what
 * vkDestroyDevice reported at shutdown included). */
uint64_t gpu_target_validation_messages(const tlod_platform* p);

#endif
