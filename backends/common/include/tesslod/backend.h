/*
 * tesslod/backend.h -- render devices (module tesslod::backend)
 *
 * WHAT IT DOES
 *   A device is one renderer, created once (sokol_gfx / bgfx shape): at
 *   creation it takes the refinement patterns and makes everything that is
 *   shared by all objects (GL: programs linked, pattern buffers uploaded,
 *   vertex arrays and queries made). Per object the caller creates a device
 *   surface (GL: the patch records and mesh attributes in storage buffers),
 *   updates it after tlod_surface_refresh(), and destroys it; images become
 *   device textures. One tlod_device_draw() draws a list of items (device
 *   surface, model matrix, the scheduler's draw list, a material: colour,
 *   base colour texture, alpha mode, culling) for one view; then the image
 *   can be read back and statistics queried. Backends are chosen by name at run time; tlod_backend_names()
 *   lists the ones this build has:
 *     "cpu"  the reference: realises each item's draw list as a mesh
 *            (tlod_cpu_device_mesh() below), draws no image;
 *     "gl"   OpenGL 4.5 core (when built with TLOD_BACKEND_GL; tesslod/gl.h);
 *     "vulkan" Vulkan 1.3 on the engine's device, recording into the
 *            engine's command buffer (when built with TLOD_BACKEND_VULKAN;
 *            tesslod/vulkan.h);
 *     "null" draws nothing, validates every call exactly like the others and
 *            counts them (tests of code that drives a device, without a GPU).
 *
 * DOES NOT
 *   - create windows or GL contexts: the GL device draws into the context
 *     current on the calling thread and into the framebuffer bound there (the
 *     engine's own). platform/ has a small EGL/GLFW platform module;
 *   - decide levels: the scheduler (tesslod/lod.h) does, one per object;
 *   - apply the model matrix to the level decisions: plan an item's draw list
 *     with view * model as the scheduler's view (the scheduler works in the
 *     surface's own space); the device uses the matrix to place the object;
 *   - clear the framebuffer or present it.
 *
 * STEP BY STEP
 *   1. make a context current (the engine's, or the platform/ glue's);
 *   2. tlod_device_create(ctx, &(tlod_device_desc){ .backend = "gl",
 *      .patterns = patterns }, &dev) once
 *      -> on failure tlod_context_last_error() says why (not in this build,
 *      no current context, GL version too low, shader build failed);
 *   3. per object: tlod_device_create_surface(dev, surface, &ds); after
 *      tlod_mesh_update() + tlod_surface_refresh():
 *      tlod_device_update_surface(dev, ds);
 *   4. every frame: tlod_scheduler_update() per object, then one
 *      tlod_device_draw(dev, &(tlod_draw_desc){ .items = items,
 *      .item_count = n, .view = ..., .proj = ..., .viewport = ... });
 *   5. optionally tlod_device_read_image(), tlod_device_query_stats();
 *   6. tlod_device_destroy_surface() per object, tlod_device_destroy_texture()
 *      per texture, tlod_device_destroy(dev) (which also destroys what is
 *      left), with the same GL context current.
 *   Wrong use (NULL desc, items NULL with a count, item_count 0, a surface
 *   of another device, a draw list that does not fit its surface or the
 *   device's patterns, a draw before any surface exists, an empty viewport)
 *   returns TLOD_ERROR_INVALID_ARGUMENT and the context's last error names
 *   the item: "tlod_device_draw: item 3: surface 'cow' belongs to another
 *   device". Nothing is drawn then.
 *
 * CONTRACT (the policy of tesslod/core.h; what this header checks)
 *   - NULL handles: create, update, draw and read calls return
 *     TLOD_ERROR_INVALID_ARGUMENT, destroy calls do nothing, queries return
 *     "" / zero / NULL; NULL out pointers and descs are refused by name.
 *   - A draw list "fits" when its patch count is the surface's, its level,
 *     instance, bucket and strip arrays are there for their counts, every
 *     level is -1 or one of the device's patterns, every instance names a
 *     patch of the surface at a level of the patterns, every bucket lies
 *     within the instances, and every strip names two patches, an edge of
 *     each and levels of the patterns. Any other list is refused naming the
 *     item and the patch, instance, bucket or strip. Matrices must be finite.
 *   - Item indices of the queries past the last draw: zero / NULL.
 *   Undefined: a tlod_surface destroyed before its device surface; the
 *   patterns destroyed before the device; "gl" calls without the device's GL
 *   context current.
 *
 * THREADING AND ALLOCATION
 *   A device and its surfaces belong to the thread of its context (and, for
 *   "gl", to the thread the GL context is current on). Every allocation goes
 *   through the context's allocator; staging arrays are grown, never shrunk,
 *   so a steady frame allocates nothing. The cpu device tessellates through
 *   the context's parallel-for.
 *
 * GL OBJECTS AND STATE
 *   The objects the "gl" device makes, and the state it saves and restores
 *   around a draw, are listed in tesslod/gl.h.
 *
 * PORTABILITY
 *   The pattern path needs only instancing and storage buffers (no
 *   tessellation stage), so the same shaders port to WebGPU, SDL GPU, sokol or
 *   bgfx. Buffer layouts and binding points are in one header shared by C and
 *   GLSL (backends/shaders/layout.h).
 */
#ifndef TESSLOD_BACKEND_H
#define TESSLOD_BACKEND_H

#include "tesslod/core.h"
#include "tesslod/lod.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct tlod_device tlod_device;
typedef struct tlod_device_surface tlod_device_surface;
typedef struct tlod_device_texture tlod_device_texture;

typedef enum tlod_debug_view {
  TLOD_DEBUG_NONE = 0,   /* shaded */
  TLOD_DEBUG_LEVELS,     /* colour by level */
  TLOD_DEBUG_SILHOUETTE, /* colour by silhouette depth */
  TLOD_DEBUG_STRIPS,     /* shaded, strips highlighted */
  TLOD_DEBUG_NUM,
  _TLOD_DEBUG_FORCE_U32 = 0x7FFFFFFF
} tlod_debug_view;

/* ------------------------------------------------------------------------ */
/* Device                                                                   */
/* ------------------------------------------------------------------------ */

/* Where the "gl" device evaluates the surfaces it draws. */
typedef enum tlod_gpu_eval {
  /* AUTO: OFF on a software rasteriser (GL_RENDERER naming llvmpipe,
   * softpipe or SwiftShader), where a vertex costs CPU time and each
   * pattern vertex's evaluation is that much work again; else ON. */
  TLOD_GPU_EVAL_DEFAULT = 0,
  TLOD_GPU_EVAL_ON,  /* patterns evaluated in the vertex shader (tesslod/gl.h) */
  TLOD_GPU_EVAL_OFF, /* CPU mesh: each item's draw list evaluated by tlod_cpu_tessellate_into
                        (welded, with normals), uploaded, one indexed draw; skipped while the
                        list, its surface and mesh are unchanged (tlod_device_stats.cpu_mesh) */
  TLOD_GPU_EVAL_NUM,
  _TLOD_GPU_EVAL_FORCE_U32 = 0x7FFFFFFF
} tlod_gpu_eval;

/* "default", "on", "off" (tlod_gpu_eval_from_name: also "auto" == DEFAULT);
 * "?" past the enum. */
TLOD_API const char* tlod_gpu_eval_name(tlod_gpu_eval e);
/* TLOD_GPU_EVAL_NUM for an unknown name or NULL. */
TLOD_API tlod_gpu_eval tlod_gpu_eval_from_name(const char* name);

/* Options of the "gl" device (ignored by the others). */
typedef struct tlod_device_gl_desc {
  /* Draw with GL_PATCHES and tessellation shaders instead of refinement
   * patterns, for comparison: outer levels per edge from both sides (no
   * strips), no geomorphs, and split-normal edges crack. Draws are batched
   * below 65,536 tessellated vertices (a Mesa limit, docs/platform.md section 1.2).
   * Links two more programs per surface type. */
  bool hardware_tessellation;
  /* Surface types the device links programs for, as a mask of
   * 1u << tlod_surface_type (FLAT, PHONG, PN, QUADRATIC; DEFAULT counts as
   * PHONG). 0 == all four; bits past TLOD_SURFACE_NUM are
   * TLOD_ERROR_INVALID_ARGUMENT. A device surface of a type outside the mask
   * is TLOD_ERROR_UNSUPPORTED. Each type costs two program links (four with
   * hardware_tessellation) at creation, none later: the default device
   * links 8 (16). */
  uint32_t surface_types;
  /* GLSL (version 450 core) defining `vec4 tlod_shade(tlod_fragment f)`,
   * the material of every item drawn by this device; NULL: the built-in
   * shading (tlod_draw_item). tlod_fragment and what the hook may use are
   * documented in tesslod/gl.h. Compiled into every program at creation: a
   * hook that does not compile is TLOD_ERROR_BACKEND, the last error
   * carrying the driver's log with the hook's own line numbers
   * ("fragment_hook:LINE"). Copied: need not outlive the call. */
  const char* fragment_hook;
  /* >= TLOD_GPU_EVAL_NUM is TLOD_ERROR_INVALID_ARGUMENT. With OFF (or AUTO
   * resolving to it), items whose fragments read a texture or (a hook)
   * attributes, MASK items and hardware_tessellation still draw with GPU
   * evaluation; the CPU mesh carries no level or strip per vertex (the
   * levels and strips debug views show level 0, no strip). */
  tlod_gpu_eval gpu_eval;
} tlod_device_gl_desc;

/* Options of the "vulkan" device (ignored by the others); tesslod/vulkan.h
 * lists what it creates, records and requires. Handles are the engine's and
 * are never destroyed by tesslod. Dispatchable handles as pointers,
 * non-dispatchable ones as uint64_t (VkRenderPass). */
typedef struct tlod_device_vk_desc {
  void* instance;        /* VkInstance; required */
  void* physical_device; /* VkPhysicalDevice; required */
  void* device;          /* VkDevice; required */
  void* queue;           /* VkQueue of queue_family; required. Used only inside tlod_device_create,
                            tlod_device_create_texture (one upload submit + fence wait each, never
                            in a frame); the engine must not use the queue concurrently with them */
  uint32_t queue_family;
  uint32_t frames_in_flight;    /* 0 == 2; 1..8: draws name a frame index below this */
  uint64_t render_pass;         /* VkRenderPass; 0 == dynamic rendering (Vulkan 1.3 dynamicRendering
                                   enabled) into colour_format + depth_format */
  uint32_t subpass;             /* with render_pass */
  uint32_t color_format;        /* VkFormat of colour attachment 0; required (also with render_pass:
                                   pipelines are made for it) */
  uint32_t depth_format;        /* VkFormat of the depth attachment; required (the device depth-tests) */
  uint32_t samples;             /* rasterization samples of the attachments; 0 == 1 */
  bool host_query_reset;        /* the device was created with hostQueryReset (Vulkan 1.2 feature):
                                   gpu_ms and vk.primitives are measured; false: gpu_ms stays < 0 */
  const char* shader_cache_dir; /* SPIR-V cache folder (created if missing); NULL == no disk cache */
  bool hardware_tessellation;   /* as tlod_device_gl_desc (needs the tessellationShader feature) */
  uint32_t surface_types;       /* as tlod_device_gl_desc */
  const char* fragment_hook;    /* as tlod_device_gl_desc: GLSL 450 defining vec4 tlod_shade(tlod_fragment f) */
  tlod_gpu_eval gpu_eval;       /* as tlod_device_gl_desc; AUTO: OFF on a VK_PHYSICAL_DEVICE_TYPE_CPU device
                                   (lavapipe); the CPU mesh goes through the frame's ring every draw */
} tlod_device_vk_desc;

typedef struct tlod_device_desc {
  const char* backend;           /* a name of tlod_backend_names(); NULL == "cpu" */
  const tlod_patterns* patterns; /* required; must outlive the device. Draw lists must come
                                    from schedulers on these patterns (or on ones with the same
                                    or a lower max level). */
  tlod_device_gl_desc gl;
  tlod_device_vk_desc vk;
  const char* label; /* names the device in messages; default: the backend name */
} tlod_device_desc;

/* The backends in this build, comma separated, in a fixed order
 * ("cpu,gl,null,vulkan"; gl and vulkan only when built). Asking tlod_device_create() for any other name is
 * TLOD_ERROR_UNSUPPORTED with a message listing these. */
TLOD_API const char* tlod_backend_names(void);
/* Creates a device: shared state made once (see WHAT IT DOES). */
TLOD_API tlod_result tlod_device_create(tlod_context* ctx, const tlod_device_desc* desc, tlod_device** out);
/* Destroys a device and any device surface and texture still made from
 * it; NULL is a no-op. */
TLOD_API void tlod_device_destroy(tlod_device* dev);
/* The backend's name ("gl"); "" for NULL. */
TLOD_API const char* tlod_device_backend(const tlod_device* dev);

/* ------------------------------------------------------------------------ */
/* Device surfaces                                                          */
/* ------------------------------------------------------------------------ */

/* Makes the device's copy of a surface (GL: its patch records in a storage
 * buffer). The surface must outlive the device surface. */
TLOD_API tlod_result tlod_device_create_surface(tlod_device* dev, const tlod_surface* surface,
                                                tlod_device_surface** out);
/* Uploads the surface again: its patch records and its mesh's attributes,
 * after tlod_mesh_update() + tlod_surface_refresh() and after
 * tlod_mesh_update_attribute() (a time series' field; no refresh needed for
 * attributes alone). Same patch count: topology never changes. */
TLOD_API tlod_result tlod_device_update_surface(tlod_device* dev, tlod_device_surface* ds);
/* NULL is a no-op. A device surface of another device is not destroyed (the
 * context's last error says so). */
TLOD_API void tlod_device_destroy_surface(tlod_device* dev, tlod_device_surface* ds);

/* ------------------------------------------------------------------------ */
/* Textures                                                                 */
/* ------------------------------------------------------------------------ */

typedef enum tlod_wrap {
  TLOD_WRAP_DEFAULT = 0, /* REPEAT (glTF's default) */
  TLOD_WRAP_REPEAT,
  TLOD_WRAP_CLAMP_TO_EDGE,
  TLOD_WRAP_MIRRORED_REPEAT,
  TLOD_WRAP_NUM,
  _TLOD_WRAP_FORCE_U32 = 0x7FFFFFFF
} tlod_wrap;

typedef enum tlod_filter {
  TLOD_FILTER_DEFAULT = 0, /* LINEAR (minification: linear between linear mipmaps) */
  TLOD_FILTER_NEAREST,     /* minification with mipmaps: nearest texel of the nearest mipmap */
  TLOD_FILTER_LINEAR,
  TLOD_FILTER_NUM,
  _TLOD_FILTER_FORCE_U32 = 0x7FFFFFFF
} tlod_filter;

#define TLOD_TEXTURE_MAX_SIZE 16384

/* An RGBA8 image for tlod_draw_item.base_color_texture. */
typedef struct tlod_texture_desc {
  uint32_t width, height; /* texels, 1..TLOD_TEXTURE_MAX_SIZE each */
  /* Required: width * height RGBA8 texels, TOP row first (as PNG and JPEG
   * decode), tightly packed; copied, need not outlive the call. Texture
   * coordinate (0, 0) is the top-left texel's corner, as in glTF. */
  const uint8_t* rgba8;
  bool srgb; /* sRGB-encoded colour (glTF base colour textures): decoded to linear when sampled */
  tlod_wrap wrap_s, wrap_t;
  tlod_filter min_filter, mag_filter;
  bool mipmaps_off;  /* default: a full mipmap chain, generated from rgba8 */
  const char* label; /* names the texture in messages; default "texture" */
} tlod_texture_desc;

/* Makes the device's copy of an image. Refused with
 * TLOD_ERROR_INVALID_ARGUMENT naming the field: NULL desc, out or rgba8, a
 * width or height of 0 or past TLOD_TEXTURE_MAX_SIZE, a wrap or filter
 * value >= its _NUM. "cpu" and "null" validate, count (stats.textures_*)
 * and keep nothing of the texels. A texture may be drawn by any number of
 * items; tlod_device_destroy() destroys the textures still made from the
 * device. */
TLOD_API tlod_result tlod_device_create_texture(tlod_device* dev, const tlod_texture_desc* desc,
                                                tlod_device_texture** out);
/* NULL is a no-op. A texture of another device is not destroyed (the
 * context's last error says so). */
TLOD_API void tlod_device_destroy_texture(tlod_device* dev, tlod_device_texture* tex);

/* ------------------------------------------------------------------------ */
/* Drawing                                                                  */
/* ------------------------------------------------------------------------ */

/* How an item's alpha is used (glTF alphaMode). */
typedef enum tlod_blend_mode {
  TLOD_BLEND_OPAQUE = 0, /* alpha ignored (written as the colour's alpha, as before) */
  TLOD_BLEND_MASK,       /* fragments of alpha < alpha_cutoff are discarded, the rest opaque */
  TLOD_BLEND_BLEND,      /* straight (not premultiplied) alpha over what is drawn: see tlod_device_draw */
  TLOD_BLEND_NUM,
  _TLOD_BLEND_FORCE_U32 = 0x7FFFFFFF
} tlod_blend_mode;

/* One object of a draw. */
typedef struct tlod_draw_item {
  const tlod_device_surface* surface; /* required, made on the device drawn with */
  const tlod_draw_list* draw_list;    /* required: a scheduler's list for this surface */
  /* Object to world, column-major 4x4; read only when has_model is true,
   * otherwise the identity (a zeroed item is drawn where its surface is,
   * never collapsed by an all-zero matrix). */
  float model[16];
  bool has_model;
  /* Base colour (RGBA, linear); read only when has_color is true, otherwise
   * light grey (0.8, 0.8, 0.8, 1). */
  float color[4];
  bool has_color;
  /* Optional, a texture of the device drawn with: its sample multiplies
   * color. Its coordinates are mesh attribute base_color_texcoord (the
   * attribute's first two components), which must exist and have at least
   * two components. */
  const tlod_device_texture* base_color_texture;
  uint32_t base_color_texcoord;
  tlod_blend_mode blend;
  /* MASK: read only when has_alpha_cutoff is true, otherwise 0.5; finite. */
  float alpha_cutoff;
  bool has_alpha_cutoff;
  /* true: back faces (clockwise in the window) are culled (glTF
   * doubleSided false). false (a zeroed item): both sides are drawn, back
   * faces shaded with the flipped normal. */
  bool cull_back_faces;
} tlod_draw_item;

typedef struct tlod_draw_vk_desc {
  void* command_buffer; /* VkCommandBuffer of the device, recording, inside the engine's rendering
                           (a render pass instance of desc.vk.render_pass / subpass, or dynamic
                           rendering with the device's formats); required for "vulkan" */
  uint32_t frame_index; /* < frames_in_flight: the upload ring this draw writes. The engine
                           guarantees the GPU has finished the last submitted draw with this index
                           (it waited on that frame's fence) */
} tlod_draw_vk_desc;

typedef struct tlod_draw_desc {
  const tlod_draw_item* items; /* required, item_count > 0; drawn in order */
  uint32_t item_count;
  float view[16], proj[16]; /* column-major world -> eye -> clip (the scheduler's view of the world) */
  uint32_t viewport[4];     /* x, y, width, height in the bound framebuffer; width, height > 0
                               (gl: y from the bottom; vulkan: from the top, Vulkan's origin) */
  /* World direction towards the light; (0, 0, 0) (no direction) == (0.3, 0.8, 0.5).
   * Normalised by the device. Shading (the built-in material; "gl": a
   * fragment hook replaces it): base * (0.15 + 0.85 * max(dot(n, l), 0)),
   * base = the item's colour times its texture sample (alpha likewise), n
   * the unit normal, flipped on back faces. */
  float light_dir[3];
  tlod_debug_view debug;
  bool wireframe; /* overlay edges */
  bool finish;    /* wait for the GPU and measure wall time (llvmpipe's timer queries miss most work);
                     ignored by "vulkan" (it submits nothing: wall_ms == cpu_ms, the recording time) */
  tlod_draw_vk_desc vk;
} tlod_draw_desc;

/* Draws every item for one view: first every item whose blend is not
 * TLOD_BLEND_BLEND, in item order, then the BLEND items farthest first (by
 * the eye-space depth of the model-transformed centre of their surface's
 * bounding box of patch spheres; equal depths keep item order) with depth
 * writes off (depth test on), blending straight alpha:
 * rgb = src.rgb * src.a + dst.rgb * (1 - src.a),
 * a = src.a + dst.a * (1 - src.a). GL: per item its patterns, then its
 * strips, then, with wireframe, its edges.
 * Besides the CONTRACT checks, an item is refused naming it when its
 * texture belongs to another device, its base_color_texcoord is not an
 * attribute of the surface's mesh with >= 2 components (checked only with a
 * texture), its blend is >= TLOD_BLEND_NUM or its alpha_cutoff (when
 * has_alpha_cutoff) is not finite. */
TLOD_API tlod_result tlod_device_draw(tlod_device* dev, const tlod_draw_desc* desc);
/* Reads width x height RGBA8 pixels at (0, 0) of the bound read framebuffer,
 * bottom row first. Devices without an image ("cpu", "null") and "vulkan"
 * (the image is the engine's; platform/ reads it back):
 * TLOD_ERROR_UNSUPPORTED. */
TLOD_API tlod_result tlod_device_read_image(tlod_device* dev, uint32_t width, uint32_t height, uint8_t* rgba);

/* ------------------------------------------------------------------------ */
/* Statistics                                                               */
/* ------------------------------------------------------------------------ */

/* "gl" only (zero elsewhere). */
typedef struct tlod_device_gl_stats {
  /* GL_PRIMITIVES_GENERATED of the draw gpu_ms belongs to (read late, like
   * it); 0 when none is ready. */
  uint64_t primitives_generated;
  uint32_t program_links;   /* since creation: a constant of the device's desc, plus as many again per
                               surface type the first time a textured (or, with a fragment hook,
                               attribute-reading) item of that type is drawn, and again at its first
                               MASK item (tesslod/gl.h, GL OBJECTS) */
  double mask_link_ms;      /* time in those later links, MASK and textured (inside the draws that
                               made them) */
  uint32_t pattern_uploads; /* pattern vertex + index buffer uploads since creation (1) */
  uint64_t pattern_bytes;   /* bytes of those uploads */
  uint64_t patch_bytes;     /* patch record bytes uploaded since creation (surface create + update) */
  uint64_t attribute_bytes; /* attribute bytes (TLOD_GL_BINDING_ATTRIBUTES) uploaded since creation; 16 per
                               upload of a mesh without attributes */
  double create_ms;         /* device creation: programs linked, patterns uploaded */
  double surface_upload_ms; /* since creation: time in surface create + update */
  uint32_t buffer_streams;  /* per-draw buffer uploads of the last draw (instances, strips, strip refs, strip
                               indices); 0 when its draw lists were those of the draw before */
} tlod_device_gl_stats;

/* "vulkan" only (zero elsewhere). */
typedef struct tlod_device_vk_stats {
  uint32_t shader_compiles;   /* since creation: stages compiled by glslang */
  uint32_t shader_cache_hits; /* stages loaded from shader_cache_dir */
  double shader_ms;           /* time in compiles + cache loads */
  uint32_t pipelines;         /* pipelines created since creation */
  double create_ms;
  uint64_t primitives;        /* pipeline statistics clipping invocations of the draw gpu_draw names */
  uint64_t upload_bytes;      /* bytes written into the frame's ring by the last draw */
  uint64_t ring_bytes;        /* capacity of all rings */
  uint32_t memory_blocks;     /* VkDeviceMemory allocations live */
  uint64_t memory_bytes;      /* their bytes */
  uint32_t descriptor_sets;   /* used by the last draw (one per item; kept per frame slot, allocated once) */
  uint32_t descriptor_writes; /* of those, written by the last draw: the ones whose surface, texture, ring or
                                 section sizes changed since the slot last used them */
} tlod_device_vk_stats;

typedef struct tlod_device_stats {
  /* The last draw. */
  double cpu_ms;      /* CPU time of the call (staging + commands) */
  double gpu_ms;      /* timer query of a draw a few draws back; < 0 when none is ready */
  uint64_t gpu_draw;  /* the draw gpu_ms measured, numbered as .draws (1 = the first); 0: none */
  double wall_ms;     /* wall clock of the call, including the finish when asked */
  uint64_t triangles; /* drawn (from the draw lists; cpu: realised) */
  uint64_t vertices;  /* shaded (pattern and strip vertices; cpu: realised) */
  uint32_t draw_calls;
  uint32_t items;
  /* Since creation (every backend, "null" included). */
  uint32_t surfaces_live;
  uint64_t surfaces_created, surfaces_destroyed, surface_updates;
  uint64_t draws, items_drawn, triangles_drawn;
  uint32_t textures_live;
  uint64_t textures_created, textures_destroyed, texture_bytes; /* bytes: width * height * 4 of those created */
  /* "gl" and "vulkan": the CPU-mesh mode (tlod_gpu_eval), whether the
   * device resolved to it, why, and the last draw's work in it. */
  bool cpu_mesh;
  char gpu_eval_reason[96];  /* e.g. "auto: GL_RENDERER llvmpipe (LLVM 15.0.6, 256 bits) is a software rasteriser" */
  uint32_t mesh_evaluations; /* items of the last draw evaluated and uploaded again (others reused theirs) */
  double mesh_eval_ms;       /* CPU time of those evaluations, last draw */
  uint64_t mesh_bytes;       /* vertex + index bytes uploaded by the last draw */
  tlod_device_gl_stats gl;
  tlod_device_vk_stats vk;
} tlod_device_stats;

/* Item k of the last draw. */
typedef struct tlod_draw_item_stats {
  uint64_t triangles; /* pattern + strip triangles drawn (gl hardware path: pattern only) */
  uint64_t vertices;
  uint32_t draw_calls;
  double cpu_ms; /* CPU time spent on this item (cpu: its tessellation) */
} tlod_draw_item_stats;

TLOD_API tlod_device_stats tlod_device_query_stats(const tlod_device* dev);
/* Zero for k >= the last draw's item count. */
TLOD_API tlod_draw_item_stats tlod_device_query_item_stats(const tlod_device* dev, uint32_t item);

/* ------------------------------------------------------------------------ */
/* "cpu" device only                                                        */
/* ------------------------------------------------------------------------ */

struct tlod_cpu_mesh; /* tesslod/cpu.h */

/* The mesh the "cpu" device realised for item k of its last draw (valid
 * until the next draw or destroy); NULL for other devices or k out of range. */
TLOD_API const struct tlod_cpu_mesh* tlod_cpu_device_mesh(const tlod_device* dev, uint32_t item);

#ifdef __cplusplus
}
#endif
#endif
