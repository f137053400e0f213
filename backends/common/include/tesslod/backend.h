/*
 * tesslod/backend.h -- the backend interface (module tesslod::backend)
 *
 * WHAT IT DOES
 *   One interface every renderer implements: create, upload a surface (its
 *   patches) and the refinement patterns, draw a scheduler's draw list for a
 *   camera, read back the image, report timings, destroy. Backends are chosen
 *   by name at run time: "cpu" (the reference: realises the draw list as a
 *   mesh, draws nothing), "gl" (OpenGL 4.5 core, when compiled in).
 *
 * DOES NOT
 *   - create windows or GL contexts: the GL backend draws into the context
 *     current on the calling thread and into the framebuffer bound there (the
 *     engine's own). samples/common has a small EGL/GLFW platform module;
 *   - decide levels: the scheduler (tesslod/lod.h) does.
 *
 * STEP BY STEP
 *   1. make a context current (engine, or samples/common platform);
 *   2. tlod_backend_create(ctx, &(tlod_backend_desc){ .name = "gl" }, &b)
 *      -> on failure tlod_context_last_error() says why (not compiled in, no
 *      current context, GL version too low, ...);
 *   3. tlod_backend_upload(b, surface, patterns) once, and again after
 *      tlod_surface_refresh();
 *   4. every frame: tlod_scheduler_update(), then
 *      tlod_backend_draw(b, &(tlod_backend_frame){ .draw_list = ..., ... });
 *   5. tlod_backend_destroy(b) with the same context current.
 *
 * GL STATE
 *   The GL backend saves and restores what it touches: current program,
 *   vertex array, array / element / shader-storage / uniform / draw-indirect
 *   buffer bindings, shader-storage binding points 0-3, polygon mode, cull
 *   face enable and mode, depth test enable and function, depth mask, blend
 *   enable, polygon offset fill enable and values, viewport. Everything else
 *   is left as the engine set it (the framebuffer it draws into included).
 *   While the engine has a GL_TIME_ELAPSED or GL_PRIMITIVES_GENERATED query
 *   active, the backend issues none of its own (gpu_ms then stays as it was).
 *
 * PORTABILITY
 *   The pattern path needs only instancing and storage buffers (no
 *   tessellation stage), so the same shaders port to WebGPU, SDL GPU, sokol or
 *   bgfx.
 */
#ifndef TESSLOD_BACKEND_H
#define TESSLOD_BACKEND_H

#include "tesslod/core.h"
#include "tesslod/lod.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct tlod_backend tlod_backend;

typedef enum tlod_debug_view {
  TLOD_DEBUG_NONE = 0,   /* shaded */
  TLOD_DEBUG_LEVELS,     /* colour by level */
  TLOD_DEBUG_SILHOUETTE, /* colour by silhouette depth */
  TLOD_DEBUG_STRIPS,     /* shaded, strips highlighted */
  TLOD_DEBUG_NUM,
  _TLOD_DEBUG_FORCE_U32 = 0x7FFFFFFF
} tlod_debug_view;

typedef struct tlod_backend_desc {
  const char* name; /* "cpu" or "gl"; NULL == "cpu" */
  /* gl: draw with GL_PATCHES and tessellation shaders instead of refinement
   * patterns, for comparison: outer levels per edge from both sides (no
   * strips), no geomorphs, and split-normal edges crack. Draws are batched
   * below 65,536 tessellated vertices (a Mesa limit, docs/platform.md section 1.2). */
  bool hardware_tessellation;
  const char* label;
} tlod_backend_desc;

typedef struct tlod_backend_frame {
  const tlod_draw_list* draw_list; /* from tlod_scheduler_draw_list() */
  float view[16], proj[16];        /* column-major, as given to the scheduler */
  uint32_t viewport[4];            /* x, y, width, height in the bound framebuffer */
  float light_dir[3];              /* view-independent world direction towards the light; 0 == (0.3, 0.8, 0.5) */
  float base_color[4];             /* 0 == light grey */
  tlod_debug_view debug;
  bool wireframe; /* overlay edges */
  bool finish;    /* wait for the GPU and measure wall time (llvmpipe's timer queries miss most work) */
} tlod_backend_frame;

typedef struct tlod_backend_timings {
  double cpu_ms;      /* CPU time of the last draw call (upload + commands) */
  double gpu_ms;      /* timer query of a frame a few frames back; < 0 when none is ready */
  double wall_ms;     /* wall clock of the last draw including a finish: llvmpipe's queries miss most work */
  uint64_t triangles; /* drawn by the last draw (from the draw list) */
  uint64_t vertices;  /* shaded by the last draw (pattern and strip vertices) */
  uint32_t draw_calls;
  /* GL_PRIMITIVES_GENERATED of the frame gpu_ms belongs to (read late, like
   * it); 0 when none is ready. */
  uint64_t primitives_generated;
} tlod_backend_timings;

/* Names compiled into this build, comma separated ("cpu,gl"). */
TLOD_API const char* tlod_backend_names(void);
TLOD_API tlod_result tlod_backend_create(tlod_context* ctx, const tlod_backend_desc* desc, tlod_backend** out);
TLOD_API void tlod_backend_destroy(tlod_backend* backend);
TLOD_API const char* tlod_backend_name(const tlod_backend* backend);
/* Uploads the patches of a surface and the patterns (both must outlive the backend's use of them). */
TLOD_API tlod_result tlod_backend_upload(tlod_backend* backend, const tlod_surface* surface,
                                         const tlod_patterns* patterns);
TLOD_API tlod_result tlod_backend_draw(tlod_backend* backend, const tlod_backend_frame* frame);
/* Reads width x height RGBA8 pixels from the bound framebuffer, bottom row first.
 * The cpu backend has no image: TLOD_ERROR_UNSUPPORTED. */
TLOD_API tlod_result tlod_backend_read_image(tlod_backend* backend, uint32_t width, uint32_t height, uint8_t* rgba);
TLOD_API tlod_backend_timings tlod_backend_query_timings(const tlod_backend* backend);
/* The cpu backend's realised mesh of the last draw (NULL for other backends). */
TLOD_API const struct tlod_cpu_mesh* tlod_backend_cpu_mesh(const tlod_backend* backend);

/* For backend authors: the vtable a backend fills in. */
typedef struct tlod_backend_vtbl {
  tlod_result (*create)(tlod_context* ctx, const tlod_backend_desc* desc, void** state);
  void (*destroy)(void* state);
  tlod_result (*upload)(void* state, const tlod_surface* surface, const tlod_patterns* patterns);
  tlod_result (*draw)(void* state, const tlod_backend_frame* frame);
  tlod_result (*read_image)(void* state, uint32_t width, uint32_t height, uint8_t* rgba);
  tlod_backend_timings (*timings)(const void* state);
} tlod_backend_vtbl;

#ifdef __cplusplus
}
#endif
#endif
