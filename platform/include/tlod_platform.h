/*
 * tlod_platform.h -- window / GPU context glue for the samples, tools and GPU
 * tests (target tlod_platform, alias tesslod::platform; not installed).
 *
 * WHAT IT DOES
 *   Gives a caller a GPU to draw with, in one of two APIs (desc.api):
 *
 *   OpenGL (TLOD_PLATFORM_GL, the zero default; built with TLOD_BACKEND_GL):
 *   an OpenGL 4.5 core context, current on the calling thread, and a
 *   framebuffer to draw into:
 *     - headless (default): EGL on Mesa's surfaceless platform
 *       (EGL_MESA_platform_surfaceless), falling back to the EGL device
 *       platform (EGL_EXT_platform_device), with no window and no X server;
 *       the context has no default framebuffer, so the platform makes an FBO
 *       (RGBA8 colour + DEPTH24_STENCIL8, optionally multisampled) of the
 *       requested size and binds it;
 *     - window: a GLFW 3.3 window with a 4.5 core forward-compatible context
 *       (needs an X server: DISPLAY, e.g. under xvfb-run); draws go to the
 *       window's default framebuffer.
 *
 *   Vulkan (TLOD_PLATFORM_VULKAN; built with TLOD_BACKEND_VULKAN): a
 *   Vulkan 1.3 instance, the first physical device with a graphics queue
 *   (the loader honours VK_DRIVER_FILES), a device with dynamicRendering and
 *   hostQueryReset (plus tessellationShader, fillModeNonSolid and
 *   pipelineStatisticsQuery when the device has them), one queue, and 2
 *   frames in flight (a command buffer and a fence each):
 *     - headless (default): offscreen colour VK_FORMAT_R8G8B8A8_UNORM and
 *       depth VK_FORMAT_D32_SFLOAT (else the first of D24_UNORM_S8_UINT /
 *       D16_UNORM with optimal-tiling attachment support) images; every
 *       frame's colour is copied into that frame's host-visible buffer;
 *     - window: a GLFW window (GLFW_NO_API) with a surface and a FIFO
 *       swapchain (B8G8R8A8_UNORM when offered, else the first format), a
 *       depth image of its size; the colour attachment is the acquired
 *       swapchain image. A swapchain that goes out of date (or suboptimal)
 *       is recreated at the next begin_frame; a minimised window (size 0)
 *       makes begin_frame wait for events.
 *   The caller records its draws into the frame's command buffer between
 *   tlod_platform_begin_frame and tlod_platform_end_frame, inside dynamic
 *   rendering of those attachments (tlod_platform_vk_info gives the handles
 *   and formats the tesslod "vulkan" device needs).
 *   With desc.validation: VK_LAYER_KHRONOS_validation with synchronization
 *   validation (best practices off), every warning and error printed to
 *   stderr as "vulkan validation: ..." and counted.
 *
 *   Plus PNG screenshots (stb_image_write) and a monotonic clock.
 *
 * DOES NOT
 *   - load GL entry points: Linux links every GL 4.5 function directly
 *     (GL_GLEXT_PROTOTYPES, libOpenGL through glvnd);
 *   - handle input beyond the window's close button (a window's size changes
 *     only through tlod_platform_resize): a caller reads keys and the mouse
 *     from GLFW itself, on tlod_platform_glfw_window;
 *   - use VkAllocationCallbacks or a memory suballocator (it is host glue,
 *     not library code: a handful of images and buffers);
 *   - wait for the GPU in a frame, except begin_frame's wait for the frame
 *     two frames back (its slot's fence) and read_rgba's wait for the last
 *     one; resize waits for the device to go idle;
 *   - belong to the tesslod libraries: backends receive the current context
 *     (GL) or the handles of tlod_platform_vk_info (Vulkan) and never include
 *     this header (CONVENTIONS.md layering).
 *
 * STEP BY STEP
 *   char err[256];
 *   tlod_platform* p = NULL;
 *   if (!tlod_platform_create(&(tlod_platform_desc){.width = 256, .height = 256}, &p, err, sizeof err))
 *     { fprintf(stderr, "%s\n", err); return 1; }   // e.g. "eglInitialize failed: EGL_NOT_INITIALIZED (0x3001)"
 *   tlod_platform_frame f;
 *   tlod_platform_begin_frame(p, (float[4]){0, 0, 0, 1}, &f, err, sizeof err);  // GL: bind + clear
 *   ... draw with GL, or record into f.command_buffer (Vulkan) ...
 *   tlod_platform_end_frame(p, NULL, err, sizeof err);  // Vulkan: submit (+ present)
 *   tlod_platform_read_rgba(p, pixels);               // width * height * 4 bytes, top row first
 *   tlod_png_write("shot.png", w, h, pixels, err, sizeof err);
 *   tlod_platform_destroy(p);
 *
 * ERRORS
 *   Every failure returns false and writes one line into the caller's error
 *   buffer naming the failing call and the EGL / GL / GLFW / VkResult error,
 *   e.g. "eglCreateContext (GL 4.5 core) failed: EGL_BAD_MATCH (0x3009)",
 *   "glfwInit failed: X11: The DISPLAY environment variable is missing" or
 *   "vkCreateInstance failed: VK_ERROR_LAYER_NOT_PRESENT (-6)". An API that
 *   was not built is an error naming the CMake option. Nothing aborts.
 *
 * THREADING
 *   A platform is used by one thread. Creating and destroying platforms is
 *   not thread safe (EGL displays and GLFW are process-wide and reference
 *   counted here). Several platforms may live in one process; bind() makes
 *   the given GL one current.
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

typedef enum tlod_platform_api { TLOD_PLATFORM_GL = 0, TLOD_PLATFORM_VULKAN = 1 } tlod_platform_api;

typedef struct tlod_platform_desc {
  uint32_t width, height; /* framebuffer size in pixels; 0 == 640 x 480 */
  bool window;            /* GLFW window (needs DISPLAY) instead of headless (EGL / offscreen images) */
  bool visible;           /* window mode: show the window (false: hidden window) */
  const char* title;      /* window mode; NULL == "tesslod" */
  uint32_t samples;       /* GL: MSAA samples; 0 or 1 == none (headless: at most GL_MAX_SAMPLES).
                             Vulkan: must be 0 or 1 (single-sampled attachments only) */
  tlod_platform_api api;  /* TLOD_PLATFORM_GL (zero default) or TLOD_PLATFORM_VULKAN */
  bool validation;        /* Vulkan: VK_LAYER_KHRONOS_validation with synchronization validation,
                             messages printed to stderr and counted; creation fails when the layer
                             is missing (Debian package vulkan-validationlayers). GL: ignored */
} tlod_platform_desc;

/* Creates the context (GL: made current) and its framebuffer (GL: bound,
 * viewport set). On failure *out is NULL and error (may be NULL) holds the
 * reason; a Vulkan platform's validation messages of a failed creation are
 * still counted by tlod_platform_validation_messages(NULL). desc may be NULL
 * (headless GL 640 x 480). */
bool tlod_platform_create(const tlod_platform_desc* desc, tlod_platform** out, char* error, size_t error_size);
/* GL: destroys the framebuffer and the context (made current for that, then
 * released: no context is current afterwards). Vulkan: waits for the device
 * to go idle, then destroys every object it made (what the validation layer
 * reports while destroying is counted by tlod_platform_validation_messages
 * (NULL)). NULL is a no-op. */
void tlod_platform_destroy(tlod_platform* p);

/* One line: "EGL surfaceless, GL_RENDERER llvmpipe (...), GL_VERSION 4.5 (Core
 * Profile) Mesa 22.3.6, 256x256, samples 0", or "Vulkan headless, llvmpipe
 * (LLVM 15.0.6, 256 bits), Vulkan 1.3.230, Mesa 22.3.6, 256x256" (Vulkan
 * window: "Vulkan window"). Returns buf. */
const char* tlod_platform_describe(const tlod_platform* p, char* buf, size_t size);

/* GL: makes the context current, binds its FBO (headless) or the default
 * framebuffer (window) for drawing and reading, and sets the viewport to the
 * whole framebuffer. Vulkan: no-op. */
void tlod_platform_bind(tlod_platform* p);
/* GL name of the framebuffer to draw into: the FBO (headless; the
 * multisampled one when samples > 1) or 0 (window, Vulkan). */
uint32_t tlod_platform_framebuffer(const tlod_platform* p);
/* Framebuffer size in pixels (Vulkan window: the swapchain's extent). */
void tlod_platform_size(const tlod_platform* p, uint32_t* width, uint32_t* height);

/* Vulkan: the handles and formats a "vulkan" device is created with.
 * Dispatchable handles as pointers; formats are VkFormat values. */
typedef struct tlod_platform_vk {
  void *instance, *physical_device, *device, *queue; /* VkInstance, VkPhysicalDevice, VkDevice, VkQueue */
  uint32_t queue_family;
  uint32_t color_format, depth_format; /* of the attachments begin_frame renders into */
  uint32_t frames_in_flight;           /* 2: tlod_platform_frame.frame_index is 0 or 1 */
  bool host_query_reset;               /* the device has hostQueryReset enabled (always, today) */
  bool tessellation;                   /* tessellationShader is enabled */
} tlod_platform_vk;
/* Fills *out for a Vulkan platform; false (and *out zeroed) for a GL one or
 * NULL. The handles stay valid until tlod_platform_destroy. */
bool tlod_platform_vk_info(const tlod_platform* p, tlod_platform_vk* out);

/* One frame: Vulkan's command buffer (VkCommandBuffer, recording, inside
 * dynamic rendering) and its slot; GL: NULL and 0. */
typedef struct tlod_platform_frame {
  void* command_buffer;
  uint32_t frame_index; /* < frames_in_flight; the GPU has finished the last frame with this index */
} tlod_platform_frame;

/* Starts a frame and clears colour to clear_rgba (NULL == 0, 0, 0, 1) and
 * depth to 1.
 * GL: tlod_platform_bind + glClear (colour, depth); *out = {NULL, 0}.
 * Vulkan: waits this slot's fence (the frame two frames back), window mode
 * first recreates an out-of-date swapchain (waiting for events while the
 * window is minimised) and acquires an image; resets and begins the slot's
 * command buffer, transitions the attachments and begins dynamic rendering
 * of colour + depth with clears. The viewport and scissor are not set.
 * Fails (false, error set) on a VkResult error or a begin_frame without
 * end_frame. */
bool tlod_platform_begin_frame(tlod_platform* p, const float clear_rgba[4], tlod_platform_frame* out, char* error,
                               size_t error_size);
/* GL: nothing (*submit_ms = 0). Vulkan: ends rendering, records the copy of
 * the colour image into the slot's read-back buffer (headless; window: when
 * the swapchain allows TRANSFER_SRC), ends and submits the command buffer
 * with the slot's fence (window: then presents; VK_ERROR_OUT_OF_DATE_KHR or
 * VK_SUBOPTIMAL_KHR marks the swapchain for recreation at the next
 * begin_frame). *submit_ms (may be NULL): milliseconds in vkQueueSubmit
 * (lavapipe queues the work for its own thread: see tlod_platform_finish). */
bool tlod_platform_end_frame(tlod_platform* p, double* submit_ms, char* error, size_t error_size);

/* Waits until the GPU has finished every frame submitted so far (GL:
 * glFinish; Vulkan: both slots' fences, no device idle) and returns the
 * milliseconds it waited, < 0 on failure. For measurements: lavapipe's
 * vkQueueSubmit returns before the work is done (docs/platform.md section
 * 3.1), so submit_ms alone is not the frame's GPU time. Not inside a
 * Vulkan frame. */
double tlod_platform_finish(tlod_platform* p);

/* Changes the framebuffer size (1..16384 each). GL headless: a new FBO;
 * window modes: the window is resized (Vulkan: the swapchain recreated
 * with the extent the surface reports). Vulkan waits for the device to go
 * idle (never call it per frame) and recreates the images and read-back
 * buffers; the previous frame can no longer be read. Not inside a frame. */
bool tlod_platform_resize(tlod_platform* p, uint32_t width, uint32_t height, char* error, size_t error_size);

/* Validation warnings + errors counted so far on p (0 for GL or without
 * desc.validation). NULL: the total of every platform of the process,
 * including destroyed ones and failed creations (so a test can check what
 * vkDestroyDevice reported). */
uint64_t tlod_platform_validation_messages(const tlod_platform* p);

/* Reads the last frame (GL: the framebuffer, multisampled: resolved first;
 * window: the back buffer, so call it before tlod_platform_swap. Vulkan: the
 * colour of the last ended frame, waiting for its fence; false before the
 * first frame, after a resize, or in window mode when the swapchain has no
 * TRANSFER_SRC usage) into rgba, width * height * 4 bytes R, G, B, A, TOP
 * row first. GL needs the context current, and saves and restores the read
 * framebuffer, pixel-pack buffer and pack alignment / row length. */
bool tlod_platform_read_rgba(tlod_platform* p, uint8_t* rgba);

/* Window mode: close requested (also polls events). Headless: false. */
bool tlod_platform_should_close(tlod_platform* p);
/* Window mode: GL swaps buffers and polls events; Vulkan polls events only
 * (end_frame presents). Headless: no-op. */
void tlod_platform_swap(tlod_platform* p);

/* Window mode: the GLFWwindow* (for the caller's own input callbacks and
 * polling; it must not destroy it or change its context or size). Headless
 * or NULL: NULL. */
void* tlod_platform_glfw_window(const tlod_platform* p);

/* Monotonic clock, milliseconds (arbitrary origin). */
double tlod_platform_time_ms(void);
/* "GL_INVALID_OPERATION" etc. for a glGetError() value ("GL not built"
 * without TLOD_BACKEND_GL). */
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
