/*
 * platform.c -- the public entry points of platform/: argument checks and
 * the dispatch to the GL part (platform_egl.c, platform_glfw.c; built with
 * TLOD_BACKEND_GL) or the Vulkan part (platform_vk*.c; built with
 * TLOD_BACKEND_VULKAN). Each part compiles alone: an API that is not built
 * is a creation error naming its CMake option.
 */
#define _POSIX_C_SOURCE 200809L

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "platform_internal.h"

#ifndef TLOD_PLATFORM_HAS_GL
#define TLOD_PLATFORM_HAS_GL 0
#endif
#ifndef TLOD_PLATFORM_HAS_VULKAN
#define TLOD_PLATFORM_HAS_VULKAN 0
#endif

void _tlod_platform_error(char* error, size_t error_size, const char* fmt, ...) {
  if (!error || error_size == 0) return;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(error, error_size, fmt, ap);
  va_end(ap);
}

static inline bool is_vk(const tlod_platform* p) { return TLOD_PLATFORM_HAS_VULKAN && p->api == TLOD_PLATFORM_VULKAN; }

/* The creation of one API, or the message saying it was not built. */
static bool create_api(tlod_platform* p, const tlod_platform_desc* d, char* error, size_t error_size) {
  if (d->api == TLOD_PLATFORM_VULKAN) {
#if TLOD_PLATFORM_HAS_VULKAN
    return _tlod_platform_vk_create(p, d, error, error_size);
#else
    _tlod_platform_error(error, error_size, "tlod_platform_create: Vulkan was not built (TLOD_BACKEND_VULKAN=OFF)");
    return false;
#endif
  }
  if (d->api != TLOD_PLATFORM_GL) {
    _tlod_platform_error(error, error_size, "tlod_platform_create: unknown api %d", (int)d->api);
    return false;
  }
#if TLOD_PLATFORM_HAS_GL
  return _tlod_platform_gl_create(p, d, error, error_size);
#else
  _tlod_platform_error(error, error_size, "tlod_platform_create: OpenGL was not built (TLOD_BACKEND_GL=OFF)");
  return false;
#endif
}

bool tlod_platform_create(const tlod_platform_desc* desc, tlod_platform** out, char* error, size_t error_size) {
  if (error && error_size) error[0] = '\0';
  if (!out) {
    _tlod_platform_error(error, error_size, "tlod_platform_create: out is NULL");
    return false;
  }
  *out = NULL;
  tlod_platform_desc d = desc ? *desc : (tlod_platform_desc){0};
  if (d.width == 0) d.width = 640;
  if (d.height == 0) d.height = 480;
  if (d.width > 16384 || d.height > 16384) {
    _tlod_platform_error(error, error_size, "tlod_platform_create: %ux%u is larger than 16384", d.width, d.height);
    return false;
  }
  tlod_platform* p = calloc(1, sizeof *p);
  if (!p) {
    _tlod_platform_error(error, error_size, "tlod_platform_create: out of memory");
    return false;
  }
  p->api = d.api;
  p->width = d.width;
  p->height = d.height;
  p->window = d.window;
  if (!create_api(p, &d, error, error_size)) {
    tlod_platform_destroy(p);
    return false;
  }
  *out = p;
  return true;
}

void tlod_platform_destroy(tlod_platform* p) {
  if (!p) return;
#if TLOD_PLATFORM_HAS_VULKAN
  if (p->api == TLOD_PLATFORM_VULKAN) _tlod_platform_vk_destroy(p);
#endif
#if TLOD_PLATFORM_HAS_GL
  if (p->api == TLOD_PLATFORM_GL) _tlod_platform_gl_destroy(p);
#endif
  free(p);
}

const char* tlod_platform_describe(const tlod_platform* p, char* buf, size_t size) {
  if (!buf || size == 0) return buf;
  if (!p) {
    snprintf(buf, size, "no platform");
  } else if (p->api == TLOD_PLATFORM_VULKAN) {
    snprintf(buf, size, "%s, %s, %s, %ux%u", p->kind, p->renderer, p->version, p->width, p->height);
  } else {
    snprintf(buf, size, "%s, GL_RENDERER %s, GL_VERSION %s, %ux%u, samples %u", p->kind, p->renderer, p->version,
             p->width, p->height, p->samples);
  }
  return buf;
}

void tlod_platform_bind(tlod_platform* p) {
#if TLOD_PLATFORM_HAS_GL
  if (p && p->api == TLOD_PLATFORM_GL) _tlod_platform_gl_bind(p);
#else
  (void)p;
#endif
}

uint32_t tlod_platform_framebuffer(const tlod_platform* p) {
  return p && p->api == TLOD_PLATFORM_GL && !p->window ? p->fbo : 0;
}

void tlod_platform_size(const tlod_platform* p, uint32_t* width, uint32_t* height) {
  if (width) *width = p ? p->width : 0;
  if (height) *height = p ? p->height : 0;
}

bool tlod_platform_vk_info(const tlod_platform* p, tlod_platform_vk* out) {
  if (out) memset(out, 0, sizeof *out);
#if TLOD_PLATFORM_HAS_VULKAN
  if (p && out && is_vk(p)) return _tlod_platform_vk_info(p, out);
#else
  (void)p;
#endif
  return false;
}

bool tlod_platform_begin_frame(tlod_platform* p, const float clear_rgba[4], tlod_platform_frame* out, char* error,
                               size_t error_size) {
  if (out) *out = (tlod_platform_frame){0};
  if (!p || !out) {
    _tlod_platform_error(error, error_size, "tlod_platform_begin_frame: platform or out is NULL");
    return false;
  }
  static const float black[4] = {0, 0, 0, 1};
  const float* rgba = clear_rgba ? clear_rgba : black;
#if TLOD_PLATFORM_HAS_VULKAN
  if (is_vk(p)) return _tlod_platform_vk_begin_frame(p, rgba, out, error, error_size);
#endif
#if TLOD_PLATFORM_HAS_GL
  _tlod_platform_gl_clear(p, rgba);
#endif
  return true;
}

bool tlod_platform_end_frame(tlod_platform* p, double* submit_ms, char* error, size_t error_size) {
  if (submit_ms) *submit_ms = 0;
  if (!p) {
    _tlod_platform_error(error, error_size, "tlod_platform_end_frame: platform is NULL");
    return false;
  }
#if TLOD_PLATFORM_HAS_VULKAN
  if (is_vk(p)) return _tlod_platform_vk_end_frame(p, submit_ms, error, error_size);
#endif
  return true;
}

double tlod_platform_finish(tlod_platform* p) {
  if (!p) return -1;
  double t0 = tlod_platform_time_ms();
#if TLOD_PLATFORM_HAS_VULKAN
  if (is_vk(p) && !_tlod_platform_vk_finish(p)) return -1;
#endif
#if TLOD_PLATFORM_HAS_GL
  if (p->api == TLOD_PLATFORM_GL) _tlod_platform_gl_finish(p);
#endif
  return tlod_platform_time_ms() - t0;
}

bool tlod_platform_resize(tlod_platform* p, uint32_t width, uint32_t height, char* error, size_t error_size) {
  if (!p || width == 0 || height == 0 || width > 16384 || height > 16384) {
    _tlod_platform_error(error, error_size, "tlod_platform_resize: %ux%u is not 1..16384 each (or no platform)", width,
                         height);
    return false;
  }
#if TLOD_PLATFORM_HAS_VULKAN
  if (is_vk(p)) return _tlod_platform_vk_resize(p, width, height, error, error_size);
#endif
#if TLOD_PLATFORM_HAS_GL
  return _tlod_platform_gl_resize(p, width, height, error, error_size);
#else
  return false;
#endif
}

uint64_t tlod_platform_validation_messages(const tlod_platform* p) {
#if TLOD_PLATFORM_HAS_VULKAN
  if (!p || is_vk(p)) return _tlod_platform_vk_messages(p);
#else
  (void)p;
#endif
  return 0;
}

bool tlod_platform_read_rgba(tlod_platform* p, uint8_t* rgba) {
  if (!p || !rgba) return false;
#if TLOD_PLATFORM_HAS_VULKAN
  if (is_vk(p)) return _tlod_platform_vk_read_rgba(p, rgba);
#endif
#if TLOD_PLATFORM_HAS_GL
  return _tlod_platform_gl_read_rgba(p, rgba);
#else
  return false;
#endif
}

bool tlod_platform_should_close(tlod_platform* p) { return p && p->window && _tlod_platform_glfw_should_close(p); }

void* tlod_platform_glfw_window(const tlod_platform* p) { return p && p->window ? p->glfw_window : NULL; }

void tlod_platform_swap(tlod_platform* p) {
  if (p && p->window) _tlod_platform_glfw_swap(p);
}

#if !TLOD_PLATFORM_HAS_GL
const char* tlod_platform_gl_error_name(unsigned e) {
  (void)e;
  return "GL not built";
}
#endif

double tlod_platform_time_ms(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}
