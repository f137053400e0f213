/*
 * platform_glfw.c -- window mode of the platform module: a GLFW 3.3 window
 * with an OpenGL 4.5 core forward-compatible context (owned by
 * samples/common).
 *
 * Based on docs/platform.md section 2: GLFW 3.3.8 is an X11 build
 * with no headless platform, so a window needs DISPLAY (Xvfb works); read
 * the back buffer before swapping.
 */
#define _POSIX_C_SOURCE 200809L

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
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

bool _tlod_platform_glfw_create(tlod_platform* p, const tlod_platform_desc* desc, char* error, size_t error_size) {
  p->kind = "GLFW window";
  const char* display = getenv("DISPLAY");
  if (!display || !display[0]) {
    _tlod_platform_error(error, error_size,
                         "GLFW window mode needs an X server: DISPLAY is not set (run under xvfb-run, or use the "
                         "headless EGL mode)");
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
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_VISIBLE, desc->visible ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE); /* the framebuffer size is fixed at creation */
  glfwWindowHint(GLFW_SAMPLES, desc->samples > 1 ? (int)desc->samples : 0);
  GLFWwindow* w = glfwCreateWindow((int)p->width, (int)p->height, desc->title ? desc->title : "tesslod", NULL, NULL);
  if (!w) {
    _tlod_platform_error(error, error_size, "glfwCreateWindow (%ux%u, GL 4.5 core forward-compatible) failed: %s",
                         p->width, p->height, glfw_error_text());
    return false; /* tlod_platform_destroy() releases GLFW */
  }
  p->glfw_window = w;
  glfwMakeContextCurrent(w);
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(w, &fw, &fh);
  if (fw > 0 && fh > 0) p->width = (uint32_t)fw, p->height = (uint32_t)fh;
  GLint samples = 0;
  glGetIntegerv(GL_SAMPLES, &samples);
  p->samples = samples > 1 ? (uint32_t)samples : 0;
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
  glfwSwapBuffers((GLFWwindow*)p->glfw_window);
  glfwPollEvents();
}
