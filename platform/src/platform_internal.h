/*
 * platform_internal.h -- private state shared by platform_egl.c (headless
 * EGL context, FBO, read-back, the public entry points) and platform_glfw.c
 * (window mode). Not part of the samples' API.
 */
#ifndef TLOD_PLATFORM_INTERNAL_H
#define TLOD_PLATFORM_INTERNAL_H

#include <stdarg.h>

#include "tlod_platform.h"

struct tlod_platform {
  uint32_t width, height; /* framebuffer size */
  uint32_t samples;       /* effective: 0 == single-sampled */
  bool window;
  const char* kind; /* "EGL surfaceless", "EGL device", "GLFW window" */
  /* headless */
  void* egl_display;                /* EGLDisplay */
  void* egl_context;                /* EGLContext */
  uint32_t fbo, color_rb, depth_rb; /* draw target (multisampled when samples > 1) */
  uint32_t resolve_fbo, resolve_rb; /* samples > 1: single-sampled copy for read-back */
  /* window */
  void* glfw_window; /* GLFWwindow */
  bool glfw_ref;     /* holds one reference on glfwInit */
  char renderer[160], version[160];
};

/* Writes a formatted one-line message into error (which may be NULL). */
void _tlod_platform_error(char* error, size_t error_size, const char* fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Window mode (platform_glfw.c): creates the window and context, makes it
 * current, fills width / height / samples. */
bool _tlod_platform_glfw_create(tlod_platform* p, const tlod_platform_desc* desc, char* error, size_t error_size);
void _tlod_platform_glfw_destroy(tlod_platform* p);
void _tlod_platform_glfw_make_current(tlod_platform* p);
bool _tlod_platform_glfw_should_close(tlod_platform* p);
void _tlod_platform_glfw_swap(tlod_platform* p);

#endif
