/*
 * platform_glfw.c -- window mode of the platform module, both APIs: a GLFW
 * 3.3 window with an OpenGL 4.5 core forward-compatible context, or a
 * GLFW_NO_API window whose Vulkan surface platform_vk_window.c makes (owned
 * by platform/).
 *
 * Based on docs/platform.md section 2: GLFW 3.3.8 is an X11 build
 * with no headless platform, so a window needs DISPLAY (Xvfb works); read
 * the back buffer before swapping.
 */
#define _POSIX_C_SOURCE 200809L

#include <stdlib.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "platform_internal.h"

/* GLFW is process-wide: initialised with the first window, terminated with
 * the last (not thread safe, like the rest of GLFW's window API). */
static int s_glfw_windows;

/* GLFW's last error as text. */
static const char* glfw_error_text(void) {
  const char* description = NULL;
  int code = glfwGetError(&description);
  return code == GLFW_NO_ERROR ? "no GLFW error reported" : description ? description : "unknown GLFW error";
}

static bool glfw_acquire(tlod_platform* p, char* error, size_t error_size) {
  const char* display = getenv("DISPLAY");
  if (!display || !display[0]) {
    _tlod_platform_error(error, error_size,
                         "GLFW window mode needs an X server: DISPLAY is not set (run under xvfb-run, or use the "
                         "headless mode)");
    return false;
  }
  if (s_glfw_windows == 0) {
    glfwGetError(NULL); /* forget errors of an earlier session */
    if (!glfwInit()) {
      _tlod_platform_error(error, error_size, "glfwInit failed: %s", glfw_error_text());
      return false;
    }
  }
  s_glfw_windows++;
  p->glfw_ref = true;
  return true;
}

static void window_hints(const tlod_platform_desc* desc, bool gl_context) {
  glfwDefaultWindowHints();
  if (gl_context) {
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_SAMPLES, desc->samples > 1 ? (int)desc->samples : 0);
  } else {
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  }
  glfwWindowHint(GLFW_VISIBLE, desc->visible ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE); /* the size changes only through tlod_platform_resize */
}

static void read_framebuffer_size(tlod_platform* p) {
  int fw = 0, fh = 0;
  glfwGetFramebufferSize((GLFWwindow*)p->glfw_window, &fw, &fh);
  if (fw > 0 && fh > 0) p->width = (uint32_t)fw, p->height = (uint32_t)fh;
}

bool _tlod_platform_glfw_create(tlod_platform* p, const tlod_platform_desc* desc, bool gl_context, char* error,
                                size_t error_size) {
  p->kind = gl_context ? "GLFW window" : "Vulkan window";
  if (!glfw_acquire(p, error, error_size)) return false;
  if (!gl_context && !glfwVulkanSupported()) {
    _tlod_platform_error(error, error_size, "glfwVulkanSupported: no Vulkan loader or surface extension: %s",
                         glfw_error_text());
    return false; /* tlod_platform_destroy() releases GLFW */
  }
  window_hints(desc, gl_context);
  GLFWwindow* w = glfwCreateWindow((int)p->width, (int)p->height, desc->title ? desc->title : "tesslod", NULL, NULL);
  if (!w) {
    _tlod_platform_error(error, error_size, "glfwCreateWindow (%ux%u, %s) failed: %s", p->width, p->height,
                         gl_context ? "GL 4.5 core forward-compatible" : "GLFW_NO_API", glfw_error_text());
    return false;
  }
  p->glfw_window = w;
  if (gl_context) glfwMakeContextCurrent(w);
  read_framebuffer_size(p);
  return true;
}

void _tlod_platform_glfw_destroy(tlod_platform* p) {
  if (p->glfw_window) {
    if (glfwGetCurrentContext() == (GLFWwindow*)p->glfw_window) glfwMakeContextCurrent(NULL);
    glfwDestroyWindow((GLFWwindow*)p->glfw_window);
    p->glfw_window = NULL;
  }
  if (p->glfw_ref) {
    p->glfw_ref = false;
    if (--s_glfw_windows == 0) glfwTerminate();
  }
}

void _tlod_platform_glfw_make_current(tlod_platform* p) {
  if (p->glfw_window && glfwGetCurrentContext() != (GLFWwindow*)p->glfw_window)
    glfwMakeContextCurrent((GLFWwindow*)p->glfw_window);
}

bool _tlod_platform_glfw_should_close(tlod_platform* p) {
  glfwPollEvents();
  return p->glfw_window && glfwWindowShouldClose((GLFWwindow*)p->glfw_window);
}

void _tlod_platform_glfw_swap(tlod_platform* p) {
  if (!p->glfw_window) return;
  if (p->api == TLOD_PLATFORM_GL) glfwSwapBuffers((GLFWwindow*)p->glfw_window);
  glfwPollEvents();
}

void _tlod_platform_glfw_resize(tlod_platform* p, uint32_t width, uint32_t height) {
  if (!p->glfw_window) return;
  glfwSetWindowSize((GLFWwindow*)p->glfw_window, (int)width, (int)height);
  glfwPollEvents(); /* let the X server's configure event arrive */
  p->width = width;
  p->height = height;
  read_framebuffer_size(p);
}

bool _tlod_platform_glfw_wait_size(tlod_platform* p, uint32_t* width, uint32_t* height) {
  GLFWwindow* w = (GLFWwindow*)p->glfw_window;
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(w, &fw, &fh);
  while ((fw <= 0 || fh <= 0) && !glfwWindowShouldClose(w)) {
    glfwWaitEvents();
    glfwGetFramebufferSize(w, &fw, &fh);
  }
  if (fw <= 0 || fh <= 0) return false;
  *width = (uint32_t)fw;
  *height = (uint32_t)fh;
  return true;
}
