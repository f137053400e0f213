/*
 * platform_egl.c -- the GL part of platform/: headless OpenGL 4.5 core
 * contexts through EGL (windows: platform_glfw.c), the framebuffer, clears,
 * resizes and read-back behind the public entry points of platform.c.
 *
 * Based on the measured recipe of docs/platform.md section 1:
 * eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA) (plain
 * eglGetDisplay fails without DISPLAY), EGL_KHR_no_config_context +
 * EGL_KHR_surfaceless_context, and a user FBO (RGBA8 + DEPTH24_STENCIL8).
 * The EGL device platform (EGL_EXT_platform_device) is the fallback.
 */
#define _POSIX_C_SOURCE 200809L

#define GL_GLEXT_PROTOTYPES 1
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <GL/glext.h>
#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

#include "platform_internal.h"

/* ------------------------------------------------------------------------ */
/* Errors                                                                   */
/* ------------------------------------------------------------------------ */

static const char* egl_error_name(EGLint e) {
  switch (e) {
  case EGL_SUCCESS:
    return "EGL_SUCCESS";
  case EGL_NOT_INITIALIZED:
    return "EGL_NOT_INITIALIZED";
  case EGL_BAD_ACCESS:
    return "EGL_BAD_ACCESS";
  case EGL_BAD_ALLOC:
    return "EGL_BAD_ALLOC";
  case EGL_BAD_ATTRIBUTE:
    return "EGL_BAD_ATTRIBUTE";
  case EGL_BAD_CONFIG:
    return "EGL_BAD_CONFIG";
  case EGL_BAD_CONTEXT:
    return "EGL_BAD_CONTEXT";
  case EGL_BAD_CURRENT_SURFACE:
    return "EGL_BAD_CURRENT_SURFACE";
  case EGL_BAD_DISPLAY:
    return "EGL_BAD_DISPLAY";
  case EGL_BAD_MATCH:
    return "EGL_BAD_MATCH";
  case EGL_BAD_NATIVE_PIXMAP:
    return "EGL_BAD_NATIVE_PIXMAP";
  case EGL_BAD_NATIVE_WINDOW:
    return "EGL_BAD_NATIVE_WINDOW";
  case EGL_BAD_PARAMETER:
    return "EGL_BAD_PARAMETER";
  case EGL_BAD_SURFACE:
    return "EGL_BAD_SURFACE";
  case EGL_CONTEXT_LOST:
    return "EGL_CONTEXT_LOST";
  default:
    return "unknown EGL error";
  }
}

const char* tlod_platform_gl_error_name(unsigned e) {
  switch (e) {
  case GL_NO_ERROR:
    return "GL_NO_ERROR";
  case GL_INVALID_ENUM:
    return "GL_INVALID_ENUM";
  case GL_INVALID_VALUE:
    return "GL_INVALID_VALUE";
  case GL_INVALID_OPERATION:
    return "GL_INVALID_OPERATION";
  case GL_INVALID_FRAMEBUFFER_OPERATION:
    return "GL_INVALID_FRAMEBUFFER_OPERATION";
  case GL_OUT_OF_MEMORY:
    return "GL_OUT_OF_MEMORY";
  case GL_STACK_UNDERFLOW:
    return "GL_STACK_UNDERFLOW";
  case GL_STACK_OVERFLOW:
    return "GL_STACK_OVERFLOW";
  case GL_FRAMEBUFFER_UNDEFINED:
    return "GL_FRAMEBUFFER_UNDEFINED";
  case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT:
    return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
  case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT:
    return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
  case GL_FRAMEBUFFER_UNSUPPORTED:
    return "GL_FRAMEBUFFER_UNSUPPORTED";
  case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE:
    return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
  default:
    return "unknown GL enum";
  }
}

/* Message of the failed EGL call `what`, with eglGetError(). */
static void egl_fail(char* error, size_t error_size, const char* what) {
  EGLint e = eglGetError();
  _tlod_platform_error(error, error_size, "%s failed: %s (0x%04X)", what, egl_error_name(e), (unsigned)e);
}

static bool has_extension(const char* list, const char* name) {
  if (!list) return false;
  size_t n = strlen(name);
  for (const char* s = list; (s = strstr(s, name)) != NULL; s += n)
    if ((s == list || s[-1] == ' ') && (s[n] == ' ' || s[n] == '\0')) return true;
  return false;
}

/* ------------------------------------------------------------------------ */
/* EGL displays: process-wide, so reference counted here                   */
/* ------------------------------------------------------------------------ */

/* eglTerminate is not reference counted (without EGL_KHR_display_reference):
 * terminating a display one platform used would destroy the contexts of
 * every other platform on it. */
#define MAX_DISPLAYS 8
static struct {
  EGLDisplay display;
  int refs;
} s_displays[MAX_DISPLAYS];

static bool display_acquire(EGLDisplay dpy, char* error, size_t error_size, const char* what) {
  for (int i = 0; i < MAX_DISPLAYS; ++i)
    if (s_displays[i].display == dpy && s_displays[i].refs > 0) {
      s_displays[i].refs++;
      return true;
    }
  EGLint major = 0, minor = 0;
  if (!eglInitialize(dpy, &major, &minor)) {
    char call[96];
    snprintf(call, sizeof call, "eglInitialize (%s)", what);
    egl_fail(error, error_size, call);
    return false;
  }
  for (int i = 0; i < MAX_DISPLAYS; ++i)
    if (s_displays[i].refs == 0) {
      s_displays[i].display = dpy;
      s_displays[i].refs = 1;
      return true;
    }
  eglTerminate(dpy);
  _tlod_platform_error(error, error_size, "too many EGL displays in use (%d)", MAX_DISPLAYS);
  return false;
}

static void display_release(EGLDisplay dpy) {
  for (int i = 0; i < MAX_DISPLAYS; ++i)
    if (s_displays[i].display == dpy && s_displays[i].refs > 0) {
      if (--s_displays[i].refs == 0) {
        eglTerminate(dpy);
        s_displays[i].display = EGL_NO_DISPLAY;
      }
      return;
    }
}

/* ------------------------------------------------------------------------ */
/* Headless context                                                         */
/* ------------------------------------------------------------------------ */

/* Context on an initialised display, made current with no surface. */
static bool egl_context(tlod_platform* p, EGLDisplay dpy, char* error, size_t error_size) {
  const char* ext = eglQueryString(dpy, EGL_EXTENSIONS);
  if (!has_extension(ext, "EGL_KHR_surfaceless_context")) {
    _tlod_platform_error(error, error_size, "EGL display (%s) lacks EGL_KHR_surfaceless_context", p->kind);
    return false;
  }
  EGLConfig config = EGL_NO_CONFIG_KHR;
  if (!has_extension(ext, "EGL_KHR_no_config_context") && !has_extension(ext, "EGL_MESA_configless_context")) {
    const EGLint want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLint n = 0;
    if (!eglChooseConfig(dpy, want, &config, 1, &n) || n < 1) {
      if (n < 1 && eglGetError() == EGL_SUCCESS)
        _tlod_platform_error(error, error_size, "eglChooseConfig (EGL_OPENGL_BIT) found no config");
      else
        egl_fail(error, error_size, "eglChooseConfig (EGL_OPENGL_BIT)");
      return false;
    }
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    egl_fail(error, error_size, "eglBindAPI(EGL_OPENGL_API)");
    return false;
  }
  const EGLint attribs[] = {
      EGL_CONTEXT_MAJOR_VERSION,           4,       EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK,
      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, attribs);
  if (ctx == EGL_NO_CONTEXT) {
    egl_fail(error, error_size, "eglCreateContext (GL 4.5 core)");
    return false;
  }
  if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
    egl_fail(error, error_size, "eglMakeCurrent (no surface)");
    eglDestroyContext(dpy, ctx);
    return false;
  }
  p->egl_display = dpy;
  p->egl_context = ctx;
  return true;
}

/* Surfaceless platform, then every EGL device. */
static bool egl_create(tlod_platform* p, char* error, size_t error_size) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display =
      (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
  if (!client || !has_extension(client, "EGL_EXT_platform_base") || !get_platform_display) {
    EGLint e = eglGetError();
    _tlod_platform_error(error, error_size,
                         "no headless EGL display: eglGetPlatformDisplayEXT unavailable (client extensions: \"%s\"; "
                         "eglGetError %s (0x%04X); is an EGL driver such as libegl-mesa0 installed?)",
                         client ? client : "", egl_error_name(e), (unsigned)e);
    return false;
  }
  char first[192] = "";
  if (has_extension(client, "EGL_MESA_platform_surfaceless")) {
    p->kind = "EGL surfaceless";
    EGLDisplay dpy = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (dpy == EGL_NO_DISPLAY) {
      egl_fail(first, sizeof first, "eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA)");
    } else if (display_acquire(dpy, first, sizeof first, "surfaceless")) {
      if (egl_context(p, dpy, first, sizeof first)) return true;
      display_release(dpy);
    }
  } else {
    snprintf(first, sizeof first, "no EGL_MESA_platform_surfaceless");
  }

  /* Fallback: the EGL device platform. */
  PFNEGLQUERYDEVICESEXTPROC query_devices = (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
  if (!has_extension(client, "EGL_EXT_platform_device") || !query_devices) {
    _tlod_platform_error(error, error_size, "%s; no EGL_EXT_platform_device fallback", first);
    return false;
  }
  EGLDeviceEXT devices[8];
  EGLint count = 0;
  if (!query_devices(8, devices, &count)) {
    char second[160];
    egl_fail(second, sizeof second, "eglQueryDevicesEXT");
    _tlod_platform_error(error, error_size, "%s; %s", first, second);
    return false;
  }
  char second[192] = "eglQueryDevicesEXT found no device";
  p->kind = "EGL device";
  for (EGLint d = 0; d < count; ++d) {
    EGLDisplay dpy = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[d], NULL);
    if (dpy == EGL_NO_DISPLAY) {
      egl_fail(second, sizeof second, "eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT)");
      continue;
    }
    if (!display_acquire(dpy, second, sizeof second, "device")) continue;
    if (egl_context(p, dpy, second, sizeof second)) return true;
    display_release(dpy);
  }
  _tlod_platform_error(error, error_size, "%s; fallback: %s", first, second);
  return false;
}

/* ------------------------------------------------------------------------ */
/* Framebuffer                                                              */
/* ------------------------------------------------------------------------ */

static bool make_fbo(GLuint* fbo, GLuint* color, GLuint* depth, uint32_t w, uint32_t h, GLsizei samples, char* error,
                     size_t error_size) {
  glGenFramebuffers(1, fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, *fbo);
  glGenRenderbuffers(1, color);
  glBindRenderbuffer(GL_RENDERBUFFER, *color);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, (GLsizei)w, (GLsizei)h);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, *color);
  if (depth) {
    glGenRenderbuffers(1, depth);
    glBindRenderbuffer(GL_RENDERBUFFER, *depth);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH24_STENCIL8, (GLsizei)w, (GLsizei)h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, *depth);
  }
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  GLenum err = glGetError();
  if (err != GL_NO_ERROR) {
    _tlod_platform_error(error, error_size, "glRenderbufferStorageMultisample (%ux%u, %d samples) failed: %s (0x%04X)",
                         w, h, (int)samples, tlod_platform_gl_error_name(err), (unsigned)err);
    return false;
  }
  GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    _tlod_platform_error(error, error_size, "glCheckFramebufferStatus (RGBA8 + DEPTH24_STENCIL8, %ux%u): %s (0x%04X)",
                         w, h, tlod_platform_gl_error_name(status), (unsigned)status);
    return false;
  }
  return true;
}

static bool headless_framebuffer(tlod_platform* p, uint32_t requested_samples, char* error, size_t error_size) {
  GLint max_size = 0, max_samples = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  if (p->width > (uint32_t)max_size || p->height > (uint32_t)max_size) {
    _tlod_platform_error(error, error_size, "framebuffer %ux%u exceeds GL_MAX_RENDERBUFFER_SIZE %d", p->width,
                         p->height, max_size);
    return false;
  }
  if (requested_samples > (uint32_t)max_samples) {
    _tlod_platform_error(error, error_size, "%u samples requested, GL_MAX_SAMPLES is %d", requested_samples,
                         max_samples);
    return false;
  }
  p->samples = requested_samples > 1 ? requested_samples : 0;
  if (!make_fbo(&p->fbo, &p->color_rb, &p->depth_rb, p->width, p->height, (GLsizei)p->samples, error, error_size))
    return false;
  if (p->samples && !make_fbo(&p->resolve_fbo, &p->resolve_rb, NULL, p->width, p->height, 0, error, error_size))
    return false;
  return true;
}

static void delete_framebuffers(tlod_platform* p) {
  GLuint fbos[2] = {p->fbo, p->resolve_fbo}, rbs[3] = {p->color_rb, p->depth_rb, p->resolve_rb};
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteFramebuffers(2, fbos);
  glDeleteRenderbuffers(3, rbs);
  p->fbo = p->resolve_fbo = p->color_rb = p->depth_rb = p->resolve_rb = 0;
}

/* ------------------------------------------------------------------------ */
/* Entry points of the GL part (platform.c dispatches to them)              */
/* ------------------------------------------------------------------------ */

static void make_current(tlod_platform* p) {
  if (p->window) {
    _tlod_platform_glfw_make_current(p);
  } else if (eglGetCurrentContext() != (EGLContext)p->egl_context) {
    eglMakeCurrent((EGLDisplay)p->egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, (EGLContext)p->egl_context);
  }
}

/* Mesa's swrast_dri.so keeps allocations in its globals and is dlclose()d
 * by eglTerminate / at exit; LeakSanitizer then reports them from an
 * "<unknown module>" no suppression can name (2 x 56 bytes per process).
 * Keeping the driver mapped (RTLD_NODELETE) keeps them reachable without
 * hiding any leak of ours. Missing libraries are ignored. */
static void keep_driver_loaded(void) {
  static const char* const libs[] = {"libEGL_mesa.so.0", "/usr/lib/x86_64-linux-gnu/dri/swrast_dri.so",
                                     "/usr/lib/dri/swrast_dri.so"};
  for (size_t i = 0; i < sizeof libs / sizeof libs[0]; ++i)
    (void)dlopen(libs[i], RTLD_NOW | RTLD_GLOBAL | RTLD_NODELETE);
}

static bool headless_create(tlod_platform* p, const tlod_platform_desc* d, char* error, size_t error_size) {
  if (!egl_create(p, error, error_size)) return false;
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major * 10 + minor < 45) {
    _tlod_platform_error(error, error_size, "%s context is GL %d.%d, 4.5 is needed", p->kind, major, minor);
    return false;
  }
  return headless_framebuffer(p, d->samples, error, error_size);
}

bool _tlod_platform_gl_create(tlod_platform* p, const tlod_platform_desc* d, char* error, size_t error_size) {
  keep_driver_loaded();
  if (d->window) {
    if (!_tlod_platform_glfw_create(p, d, true, error, error_size)) return false;
    GLint samples = 0;
    glGetIntegerv(GL_SAMPLES, &samples);
    p->samples = samples > 1 ? (uint32_t)samples : 0;
  } else if (!headless_create(p, d, error, error_size)) {
    return false;
  }
  const char* renderer = (const char*)glGetString(GL_RENDERER);
  const char* version = (const char*)glGetString(GL_VERSION);
  snprintf(p->renderer, sizeof p->renderer, "%s", renderer ? renderer : "?");
  snprintf(p->version, sizeof p->version, "%s", version ? version : "?");
  _tlod_platform_gl_bind(p);
  return true;
}

void _tlod_platform_gl_destroy(tlod_platform* p) {
  if (p->window) {
    _tlod_platform_glfw_destroy(p);
  } else if (p->egl_context) {
    EGLDisplay dpy = (EGLDisplay)p->egl_display;
    make_current(p);
    delete_framebuffers(p);
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, (EGLContext)p->egl_context);
    display_release(dpy);
    eglReleaseThread();
  }
}

void _tlod_platform_gl_bind(tlod_platform* p) {
  make_current(p);
  glBindFramebuffer(GL_FRAMEBUFFER, p->window ? 0 : p->fbo);
  glViewport(0, 0, (GLsizei)p->width, (GLsizei)p->height);
}

/* The clear writes every pixel: colour, depth and stencil masks are opened
 * for it and restored, the scissor test is off meanwhile. */
void _tlod_platform_gl_clear(tlod_platform* p, const float rgba[4]) {
  _tlod_platform_gl_bind(p);
  GLboolean color_mask[4], depth_mask = GL_TRUE, scissor = glIsEnabled(GL_SCISSOR_TEST);
  glGetBooleanv(GL_COLOR_WRITEMASK, color_mask);
  glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  glDisable(GL_SCISSOR_TEST);
  glClearColor(rgba[0], rgba[1], rgba[2], rgba[3]);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glColorMask(color_mask[0], color_mask[1], color_mask[2], color_mask[3]);
  glDepthMask(depth_mask);
  if (scissor) glEnable(GL_SCISSOR_TEST);
}

bool _tlod_platform_gl_resize(tlod_platform* p, uint32_t width, uint32_t height, char* error, size_t error_size) {
  if (p->window) {
    _tlod_platform_glfw_resize(p, width, height);
    _tlod_platform_gl_bind(p);
    return true;
  }
  make_current(p);
  delete_framebuffers(p);
  uint32_t old_w = p->width, old_h = p->height, samples = p->samples;
  p->width = width;
  p->height = height;
  if (!headless_framebuffer(p, samples, error, error_size)) {
    /* Keep a usable platform: the old size again (it worked before). */
    delete_framebuffers(p);
    p->width = old_w;
    p->height = old_h;
    (void)headless_framebuffer(p, samples, NULL, 0);
    _tlod_platform_gl_bind(p);
    return false;
  }
  _tlod_platform_gl_bind(p);
  return true;
}

void _tlod_platform_gl_finish(tlod_platform* p) {
  make_current(p);
  glFinish();
}

/* GL rows are bottom first: swap them in place. */
static void flip_rows(uint8_t* rgba, GLsizei w, GLsizei h) {
  size_t stride = (size_t)w * 4;
  uint8_t tmp[4096];
  for (GLsizei y = 0; y < h / 2; ++y) {
    uint8_t *a = rgba + (size_t)y * stride, *b = rgba + (size_t)(h - 1 - y) * stride;
    for (size_t off = 0; off < stride; off += sizeof tmp) {
      size_t n = stride - off < sizeof tmp ? stride - off : sizeof tmp;
      memcpy(tmp, a + off, n);
      memcpy(a + off, b + off, n);
      memcpy(b + off, tmp, n);
    }
  }
}

bool _tlod_platform_gl_read_rgba(tlod_platform* p, uint8_t* rgba) {
  GLint read_fbo = 0, draw_fbo = 0, pack_buffer = 0, alignment = 4, row_length = 0, skip_rows = 0, skip_pixels = 0;
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_fbo);
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_fbo);
  glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pack_buffer);
  glGetIntegerv(GL_PACK_ALIGNMENT, &alignment);
  glGetIntegerv(GL_PACK_ROW_LENGTH, &row_length);
  glGetIntegerv(GL_PACK_SKIP_ROWS, &skip_rows);
  glGetIntegerv(GL_PACK_SKIP_PIXELS, &skip_pixels);
  GLsizei w = (GLsizei)p->width, h = (GLsizei)p->height;
  GLint read_buffer = GL_BACK;
  bool ok = true;
  if (p->window) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glGetIntegerv(GL_READ_BUFFER, &read_buffer);
    glReadBuffer(GL_BACK);
  } else if (p->samples) {
    /* Resolve; the blit honours the scissor test, so switch it off. */
    GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST);
    glDisable(GL_SCISSOR_TEST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, p->fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, p->resolve_fbo);
    glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)draw_fbo);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, p->resolve_fbo);
    if (scissor) glEnable(GL_SCISSOR_TEST);
  } else {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, p->fbo);
  }
  if (glCheckFramebufferStatus(GL_READ_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) ok = false;
  if (ok) {
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    glPixelStorei(GL_PACK_SKIP_ROWS, 0);
    glPixelStorei(GL_PACK_SKIP_PIXELS, 0);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    flip_rows(rgba, w, h);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, (GLuint)pack_buffer);
    glPixelStorei(GL_PACK_ALIGNMENT, alignment);
    glPixelStorei(GL_PACK_ROW_LENGTH, row_length);
    glPixelStorei(GL_PACK_SKIP_ROWS, skip_rows);
    glPixelStorei(GL_PACK_SKIP_PIXELS, skip_pixels);
  }
  if (p->window) glReadBuffer((GLenum)read_buffer);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)read_fbo);
  return ok;
}
