/*
 * platform_internal.h -- private state shared by the files of platform/:
 * platform.c (the public entry points, dispatching on the API),
 * platform_egl.c (GL: headless EGL context, FBO, read-back), platform_glfw.c
 * (GLFW windows for both APIs) and platform_vk*.c (Vulkan, with its own
 * private header platform_vk.h). Not part of the samples' API.
 */
#ifndef TLOD_PLATFORM_INTERNAL_H
#define TLOD_PLATFORM_INTERNAL_H

#include <stdarg.h>

#include "tlod_platform.h"

typedef struct _tlod_platform_vk _tlod_platform_vk; /* platform_vk.h */

struct tlod_platform {
  tlod_platform_api api;
  uint32_t width, height; /* framebuffer size */
  uint32_t samples;       /* effective: 0 == single-sampled */
  bool window;
  const char* kind; /* "EGL surfaceless", "EGL device", "GLFW window", "Vulkan headless", "Vulkan window" */
  /* GL headless */
  void* egl_display;                /* EGLDisplay */
  void* egl_context;                /* EGLContext */
  uint32_t fbo, color_rb, depth_rb; /* draw target (multisampled when samples > 1) */
  uint32_t resolve_fbo, resolve_rb; /* samples > 1: single-sampled copy for read-back */
  /* window (both APIs) */
  void* glfw_window; /* GLFWwindow */
  bool glfw_ref;     /* holds one reference on glfwInit */
  /* Vulkan */
  _tlod_platform_vk* vk;
  char renderer[160], version[160]; /* for describe */
};

/* Writes a formatted one-line message into error (which may be NULL). */
void _tlod_platform_error(char* error, size_t error_size, const char* fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* GL mode (platform_egl.c): context (headless or through GLFW), framebuffer,
 * read-back. create fills everything but leaves p for tlod_platform_destroy
 * to free on failure. */
bool _tlod_platform_gl_create(tlod_platform* p, const tlod_platform_desc* desc, char* error, size_t error_size);
void _tlod_platform_gl_destroy(tlod_platform* p);
void _tlod_platform_gl_bind(tlod_platform* p);
void _tlod_platform_gl_clear(tlod_platform* p, const float rgba[4]);
bool _tlod_platform_gl_read_rgba(tlod_platform* p, uint8_t* rgba);
void _tlod_platform_gl_finish(tlod_platform* p);
bool _tlod_platform_gl_resize(tlod_platform* p, uint32_t width, uint32_t height, char* error, size_t error_size);

/* Windows (platform_glfw.c): gl_context true makes a GL 4.5 core context
 * (made current), false a GLFW_NO_API window for a Vulkan surface. Fills
 * width / height from the framebuffer. */
bool _tlod_platform_glfw_create(tlod_platform* p, const tlod_platform_desc* desc, bool gl_context, char* error,
                                size_t error_size);
void _tlod_platform_glfw_destroy(tlod_platform* p);
void _tlod_platform_glfw_make_current(tlod_platform* p);
bool _tlod_platform_glfw_should_close(tlod_platform* p);
void _tlod_platform_glfw_swap(tlod_platform* p); /* GL context: swap buffers; both: poll events */
/* Sets the window's size, then reads back the framebuffer size it got. */
void _tlod_platform_glfw_resize(tlod_platform* p, uint32_t width, uint32_t height);
/* The window's framebuffer size now; blocks in glfwWaitEvents while it is
 * 0 x 0 (minimised). False when the window was closed meanwhile. */
bool _tlod_platform_glfw_wait_size(tlod_platform* p, uint32_t* width, uint32_t* height);

/* Vulkan mode (platform_vk*.c). */
bool _tlod_platform_vk_create(tlod_platform* p, const tlod_platform_desc* desc, char* error, size_t error_size);
void _tlod_platform_vk_destroy(tlod_platform* p);
bool _tlod_platform_vk_begin_frame(tlod_platform* p, const float rgba[4], tlod_platform_frame* out, char* error,
                                   size_t error_size);
bool _tlod_platform_vk_end_frame(tlod_platform* p, double* submit_ms, char* error, size_t error_size);
bool _tlod_platform_vk_read_rgba(tlod_platform* p, uint8_t* rgba);
bool _tlod_platform_vk_finish(tlod_platform* p);
bool _tlod_platform_vk_resize(tlod_platform* p, uint32_t width, uint32_t height, char* error, size_t error_size);
bool _tlod_platform_vk_info(const tlod_platform* p, tlod_platform_vk* out);
uint64_t _tlod_platform_vk_messages(const tlod_platform* p); /* NULL: process total */

#endif
