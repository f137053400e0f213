/* The GPU target of play and bench (gpu_target.h). */
#include "common/gpu_target.h"

#include <stdio.h>
#include <string.h>

#if TLOD_HAS_GL || TLOD_HAS_VULKAN
#include "tlod_platform_device.h"
#endif

bool gpu_backend(const char* backend) { return backend && (!strcmp(backend, "gl") || !strcmp(backend, "vulkan")); }

#if TLOD_HAS_GL || TLOD_HAS_VULKAN
/* The build has the API the backend needs (the platform builds only those). */
static bool api_built(const char* backend, char* err, size_t err_size) {
  bool vk = !strcmp(backend, "vulkan");
  if (vk ? TLOD_HAS_VULKAN : TLOD_HAS_GL) return true;
  snprintf(err, err_size, "this build has no %s backend (TLOD_BACKEND_%s=OFF)", vk ? "Vulkan" : "GL",
           vk ? "VULKAN" : "GL");
  return false;
}

bool gpu_target_open(const gpu_target_desc* d, tlod_platform** out, char* err, size_t err_size) {
  *out = NULL;
  if (!api_built(d->backend, err, err_size)) return false;
  tlod_platform_desc pd = {.width = d->width,
                           .height = d->height,
                           .window = d->window,
                           .visible = d->window,
                           .title = d->title,
                           .api = strcmp(d->backend, "vulkan") ? TLOD_PLATFORM_GL : TLOD_PLATFORM_VULKAN,
                           .validation = d->validation};
  return tlod_platform_create(&pd, out, err, err_size);
}

void gpu_target_close(tlod_platform* p) { tlod_platform_destroy(p); }

void gpu_target_device_desc(const tlod_platform* p, const char* shader_cache_dir, bool hardware, tlod_device_desc* d) {
  tlod_platform_vk vk;
  tlod_device_vk_desc v = {.shader_cache_dir = shader_cache_dir,
                           .surface_types = d->gl.surface_types,
                           .fragment_hook = d->gl.fragment_hook,
                           .gpu_eval = d->gl.gpu_eval};
  if (!tlod_platform_vk_device_desc(p, &v) || !tlod_platform_vk_info(p, &vk)) return;
  v.hardware_tessellation = hardware && vk.tessellation;
  d->vk = v;
}

bool gpu_frame_begin(tlod_platform* p, const float clear_rgba[4], tlod_draw_desc* d, char* err, size_t err_size) {
  tlod_platform_frame f = {0};
  if (!tlod_platform_begin_frame(p, clear_rgba, &f, err, err_size)) return false;
  d->vk = (tlod_draw_vk_desc){.command_buffer = f.command_buffer, .frame_index = f.frame_index};
  return true;
}

bool gpu_frame_end(tlod_platform* p, bool finish, double* gpu_ms, char* err, size_t err_size) {
  *gpu_ms = 0.0;
  if (!tlod_platform_end_frame(p, gpu_ms, err, err_size)) return false;
  double waited = finish ? tlod_platform_finish(p) : 0.0;
  if (waited < 0.0) {
    snprintf(err, err_size, "waiting for the GPU to finish the frame failed");
    return false;
  }
  *gpu_ms += waited;
  return true;
}

uint64_t gpu_target_validation_messages(const tlod_platform* p) { return tlod_platform_validation_messages(p); }
#else
bool gpu_target_open(const gpu_target_desc* d, tlod_platform** out, char* err, size_t err_size) {
  *out = NULL;
  snprintf(err, err_size, "this build has no GPU backend (TLOD_BACKEND_GL=OFF, TLOD_BACKEND_VULKAN=OFF): no %s",
           d->backend);
  return false;
}

void gpu_target_close(tlod_platform* p) { (void)p; }

void gpu_target_device_desc(const tlod_platform* p, const char* shader_cache_dir, bool hardware, tlod_device_desc* d) {
  (void)p, (void)shader_cache_dir, (void)hardware, (void)d;
}

bool gpu_frame_begin(tlod_platform* p, const float clear_rgba[4], tlod_draw_desc* d, char* err, size_t err_size) {
  (void)p, (void)clear_rgba, (void)d;
  snprintf(err, err_size, "no GPU platform in this build");
  return false;
}

bool gpu_frame_end(tlod_platform* p, bool finish, double* gpu_ms, char* err, size_t err_size) {
  (void)p, (void)finish;
  *gpu_ms = 0.0;
  snprintf(err, err_size, "no GPU platform in this build");
  return false;
}

uint64_t gpu_target_validation_messages(const tlod_platform* p) {
  (void)p;
  return 0;
}
#endif
