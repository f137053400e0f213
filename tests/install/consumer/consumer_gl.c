/* The GL part of the installed-package consumer (tests/install): a headless OpenGL 4.5 core context made
 * here with libEGL alone (Mesa's surfaceless platform, no window, no X server; the project's uninstalled
 * platform glue is not used), an FBO, and the installed "gl" backend drawing one scheduler frame of the
 * consumer's square. It checks that the backend is "gl", that the centre of the image is drawn (not the
 * clear colour) and that a corner outside the square is not. The backend calls are all in
 * draw_with_backend(), so a change of the backend API touches one function. */
#define GL_GLEXT_PROTOTYPES 1
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <GL/glext.h>
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <tesslod/backend.h>

#include "consumer_gl.h"

enum { W = 64, H = 64 };

typedef struct gl_target {
  EGLDisplay display;
  EGLContext context;
  GLuint fbo, color, depth;
} gl_target;

/* Mesa's driver keeps allocations in its globals and is unloaded at exit, which LeakSanitizer (the asan
 * build passes -fsanitize to this consumer) reports from an unnamed module: keep it mapped. */
static void keep_driver_loaded(void) {
  static const char* const libs[] = {"libEGL_mesa.so.0", "/usr/lib/x86_64-linux-gnu/dri/swrast_dri.so"};
  for (size_t i = 0; i < sizeof libs / sizeof libs[0]; ++i)
    (void)dlopen(libs[i], RTLD_NOW | RTLD_GLOBAL | RTLD_NODELETE);
}

static int gl_target_create(gl_target* t) {
  memset(t, 0, sizeof *t);
  keep_driver_loaded();
  PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
      (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
  if (!get_display) return fprintf(stderr, "consumer_gl: no eglGetPlatformDisplayEXT\n"), 0;
  t->display = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
  EGLint major = 0, minor = 0;
  if (t->display == EGL_NO_DISPLAY || !eglInitialize(t->display, &major, &minor))
    return fprintf(stderr, "consumer_gl: surfaceless EGL display: error 0x%x\n", (unsigned)eglGetError()), 0;
  if (!eglBindAPI(EGL_OPENGL_API)) return fprintf(stderr, "consumer_gl: eglBindAPI(EGL_OPENGL_API) failed\n"), 0;
  static const EGLint attribs[] = {
      EGL_CONTEXT_MAJOR_VERSION,           4,       EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK,
      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  t->context = eglCreateContext(t->display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
  if (t->context == EGL_NO_CONTEXT || !eglMakeCurrent(t->display, EGL_NO_SURFACE, EGL_NO_SURFACE, t->context))
    return fprintf(stderr, "consumer_gl: GL 4.5 core context: error 0x%x\n", (unsigned)eglGetError()), 0;
  glGenRenderbuffers(1, &t->color);
  glBindRenderbuffer(GL_RENDERBUFFER, t->color);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, W, H);
  glGenRenderbuffers(1, &t->depth);
  glBindRenderbuffer(GL_RENDERBUFFER, t->depth);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, W, H);
  glGenFramebuffers(1, &t->fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t->color);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, t->depth);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    return fprintf(stderr, "consumer_gl: framebuffer incomplete\n"), 0;
  glViewport(0, 0, W, H);
  glClearColor(0, 0, 0, 0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  printf("consumer_gl: EGL %d.%d surfaceless, %s, %s\n", (int)major, (int)minor, (const char*)glGetString(GL_RENDERER),
         (const char*)glGetString(GL_VERSION));
  return 1;
}

static void gl_target_destroy(gl_target* t) {
  if (t->context != EGL_NO_CONTEXT && t->context) {
    glDeleteFramebuffers(1, &t->fbo);
    glDeleteRenderbuffers(1, &t->color);
    glDeleteRenderbuffers(1, &t->depth);
    eglMakeCurrent(t->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(t->display, t->context);
  }
  if (t->display != EGL_NO_DISPLAY && t->display) eglTerminate(t->display);
}

/* Every call into tesslod's device API: create a "gl" device in the current context, make the
 * surface's device surface, draw the draw list into the bound framebuffer, read the image back
 * (bottom row first). 1 on success. */
static int draw_with_backend(tlod_context* ctx, const tlod_surface* surface, const tlod_patterns* patterns,
                             const tlod_draw_list* list, const float view[16], const float proj[16], uint8_t* rgba) {
  tlod_device* dev = NULL;
  tlod_result r = tlod_device_create(ctx, &(tlod_device_desc){.backend = "gl", .patterns = patterns}, &dev);
  if (r != TLOD_SUCCESS) {
    fprintf(stderr, "consumer_gl: tlod_device_create(gl): %s: %s\n", tlod_result_string(r),
            tlod_context_last_error(ctx));
    return 0;
  }
  int ok = strcmp(tlod_device_backend(dev), "gl") == 0;
  if (!ok) fprintf(stderr, "consumer_gl: backend '%s', expected 'gl'\n", tlod_device_backend(dev));
  tlod_device_surface* ds = NULL;
  if (ok && tlod_device_create_surface(dev, surface, &ds) != TLOD_SUCCESS)
    ok = 0, fprintf(stderr, "consumer_gl: tlod_device_create_surface: %s\n", tlod_context_last_error(ctx));
  tlod_draw_item item = {.surface = ds, .draw_list = list};
  tlod_draw_desc draw = {.items = &item, .item_count = 1, .viewport = {0, 0, W, H}, .finish = true};
  memcpy(draw.view, view, sizeof draw.view);
  memcpy(draw.proj, proj, sizeof draw.proj);
  if (ok && tlod_device_draw(dev, &draw) != TLOD_SUCCESS)
    ok = 0, fprintf(stderr, "consumer_gl: tlod_device_draw: %s\n", tlod_context_last_error(ctx));
  if (ok && tlod_device_read_image(dev, W, H, rgba) != TLOD_SUCCESS)
    ok = 0, fprintf(stderr, "consumer_gl: tlod_device_read_image: %s\n", tlod_context_last_error(ctx));
  tlod_device_destroy(dev); /* also destroys ds */
  return ok;
}

int consumer_gl(tlod_context* ctx, const tlod_surface* surface, const tlod_patterns* patterns) {
  /* Looking down -z at the unit square from (0.5, 0.5, 2); orthographic, x and y in [-1, 1]: the square
   * covers the middle half of the image. Column-major. */
  static const float view[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -0.5f, -0.5f, -2, 1};
  const float n = 0.1f, f = 10;
  const float proj[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -2 / (f - n), 0, 0, 0, -(f + n) / (f - n), 1};
  static uint8_t rgba[W * H * 4];
  gl_target t;
  int ok = gl_target_create(&t);
  tlod_scheduler* s = NULL;
  if (ok) {
    tlod_result r = tlod_scheduler_create(ctx, surface, patterns, &(tlod_scheduler_desc){0}, &s);
    tlod_view_desc v = {.viewport_width = W, .viewport_height = H};
    memcpy(v.view, view, sizeof v.view);
    memcpy(v.proj, proj, sizeof v.proj);
    if (r == TLOD_SUCCESS) r = tlod_scheduler_update(s, &(tlod_frame_desc){.views = &v, .view_count = 1});
    if (r != TLOD_SUCCESS) ok = 0, fprintf(stderr, "consumer_gl: scheduler: %s\n", tlod_context_last_error(ctx));
  }
  ok = ok && draw_with_backend(ctx, surface, patterns, tlod_scheduler_draw_list(s, 0), view, proj, rgba);
  if (ok) {
    const uint8_t* centre = rgba + ((H / 2) * W + W / 2) * 4;
    const uint8_t* corner = rgba + (2 * W + 2) * 4;
    uint32_t drawn = 0;
    for (uint32_t i = 0; i < W * H; i++)
      drawn += rgba[i * 4] || rgba[i * 4 + 1] || rgba[i * 4 + 2];
    ok = (centre[0] || centre[1] || centre[2]) && !(corner[0] || corner[1] || corner[2]) && drawn > 0;
    printf("consumer_gl: backend gl drew %u of %u pixels (centre %u,%u,%u; corner %u,%u,%u): %s\n", drawn, W * H,
           centre[0], centre[1], centre[2], corner[0], corner[1], corner[2], ok ? "OK" : "WRONG");
  }
  tlod_scheduler_destroy(s);
  gl_target_destroy(&t);
  return ok;
}
