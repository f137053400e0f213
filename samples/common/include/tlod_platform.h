/*
 * tlod_platform.h -- window / GL context glue for the samples, tools and GL
 * tests (target tlod_platform, alias tesslod::platform; not installed).
 *
 * WHAT IT DOES
 *   Gives a caller an OpenGL 4.5 core context, current on the calling thread,
 *   and a framebuffer to draw into:
 *     - headless (default): EGL on Mesa's surfaceless platform
 *       (EGL_MESA_platform_surfaceless), falling back to the EGL device
 *       platform (EGL_EXT_platform_device), with no window and no X server;
 *       the context has no default framebuffer, so the platform makes an FBO
 *       (RGBA8 colour + DEPTH24_STENCIL8, optionally multisampled) of the
 *       requested size and binds it;
 *     - window: a GLFW 3.3 window with a 4.5 core forward-compatible context
 *       (needs an X server: DISPLAY, e.g. under xvfb-run); draws go to the
 *       window's default framebuffer.
 *   Plus PNG screenshots (stb_image_write) and a monotonic clock.
 *
 * DOES NOT
 *   - load GL entry points: Linux links every GL 4.5 function directly
 *     (GL_GLEXT_PROTOTYPES, libOpenGL through glvnd);
 *   - handle input beyond the window's close button, or resizing (the
 *     framebuffer keeps the size it was created with);
 *   - belong to the tesslod libraries: backends receive the current context
 *     and never include this header (docs/style.md item 3).
 *
 * STEP BY STEP
 *   char err[256];
 *   tlod_platform* p = NULL;
 *   if (!tlod_platform_create(&(tlod_platform_desc){.width = 256, .height = 256}, &p, err, sizeof err))
 *     { fprintf(stderr, "%s\n", err); return 1; }   // e.g. "eglInitialize failed: EGL_NOT_INITIALIZED (0x3001)"
 *   tlod_platform_bind(p);                            // FBO (or window) + viewport
 *   ... draw with GL ...
 *   tlod_platform_read_rgba(p, pixels);               // width * height * 4 bytes, top row first
 *   tlod_png_write("shot.png", w, h, pixels, err, sizeof err);
 *   tlod_platform_destroy(p);
 *
 * ERRORS
 *   Every failure returns false and writes one line into the caller's error
 *   buffer naming the failing call and the EGL / GL / GLFW error, e.g.
 *   "eglCreateContext (GL 4.5 core) failed: EGL_BAD_MATCH (0x3009)" or
 *   "glfwInit failed: X11: The DISPLAY environment variable is missing".
 *   Nothing aborts.
 *
 * THREADING
 *   A platform is used by one thread. Creating and destroying platforms is
 *   not thread safe (EGL displays and GLFW are process-wide and reference
 *   counted here). Several platforms may live in one process; bind() makes
 *   the given one current.
 */
#ifndef TLOD_PLATFORM_H
#define TLOD_PLATFORM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct tlod_platform tlod_platform;

typedef struct tlod_platform_desc {
  uint32_t width, height; /* framebuffer size in pixels; 0 == 640 x 480 */
  bool window;            /* GLFW window (needs DISPLAY) instead of headless EGL */
  bool visible;           /* window mode: show the window (false: hidden window) */
  const char* title;      /* window mode; NULL == "tesslod" */
  uint32_t samples;       /* MSAA samples; 0 or 1 == none (headless: at most GL_MAX_SAMPLES) */
} tlod_platform_desc;

/* Creates the context (made current) and its framebuffer (bound, viewport
 * set). On failure *out is NULL and error (may be NULL) holds the reason.
 * desc may be NULL (headless 640 x 480). */
bool tlod_platform_create(const tlod_platform_desc* desc, tlod_platform** out, char* error, size_t error_size);
/* Destroys the framebuffer and the context (made current for that, then
 * released: no context is current afterwards). NULL is a no-op. */
void tlod_platform_destroy(tlod_platform* p);

/* One line: "EGL surfaceless, GL_RENDERER llvmpipe (...), GL_VERSION 4.5 (Core
 * Profile) Mesa 22.3.6, 256x256, samples 0". Returns buf. */
const char* tlod_platform_describe(const tlod_platform* p, char* buf, size_t size);

/* Makes the context current, binds its FBO (headless) or the default
 * framebuffer (window) for drawing and reading, and sets the viewport to the
 * whole framebuffer. */
void tlod_platform_bind(tlod_platform* p);
/* GL name of the framebuffer to draw into: the FBO (headless; the
 * multisampled one when samples > 1) or 0 (window). */
uint32_t tlod_platform_framebuffer(const tlod_platform* p);
void tlod_platform_size(const tlod_platform* p, uint32_t* width, uint32_t* height);

/* Reads the framebuffer (multisampled: resolved first; window: the back
 * buffer, so call it before tlod_platform_swap) into rgba, width * height * 4
 * bytes, TOP row first. Needs the context current. Saves and restores the
 * read framebuffer, pixel-pack buffer and pack alignment / row length. */
bool tlod_platform_read_rgba(tlod_platform* p, uint8_t* rgba);

/* Window mode: close requested (also polls events). Headless: false. */
bool tlod_platform_should_close(tlod_platform* p);
/* Window mode: swap buffers and poll events. Headless: no-op. */
void tlod_platform_swap(tlod_platform* p);

/* Monotonic clock, milliseconds (arbitrary origin). */
double tlod_platform_time_ms(void);
/* "GL_INVALID_OPERATION" etc. for a glGetError() value. */
const char* tlod_platform_gl_error_name(unsigned error);

/* Writes an 8-bit RGBA PNG (rows top first) to a temporary name next to
 * path, then renames it over path, so readers never see half a file. On
 * failure nothing is left behind and error holds the reason. */
bool tlod_png_write(const char* path, uint32_t width, uint32_t height, const uint8_t* rgba_top_first, char* error,
                    size_t error_size);

#ifdef __cplusplus
}
#endif
#endif
