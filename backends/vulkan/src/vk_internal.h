/* Private to tesslod::vulkan. */
#ifndef TESSLOD_VK_INTERNAL_H
#define TESSLOD_VK_INTERNAL_H

#include <vulkan/vulkan.h>

#include "device_mesh.h" /* CPU-mesh mode; device_stage.h */
#include "layout.h"      /* backends/shaders: bindings and buffer structs, shared with GLSL */
#include "tesslod/vulkan.h"

#if TLOD_VK_BINDING_PATCHES != TLOD_BINDING_PATCHES || TLOD_VK_BINDING_PATTERNS != TLOD_BINDING_PATTERN ||             \
    TLOD_VK_BINDING_INSTANCES != TLOD_BINDING_INSTANCES || TLOD_VK_BINDING_STRIPS != TLOD_BINDING_STRIPS ||            \
    TLOD_VK_BINDING_ATTRIBUTES != TLOD_BINDING_ATTRIBUTES
#error "tesslod/vulkan.h and backends/shaders/layout.h disagree on the bindings"
#endif
_Static_assert(sizeof(tlod_vk_uniforms) == 256 && sizeof(tlod_vk_push) == 16, "the Vulkan shader interface");

/* ---- host allocations (vk_alloc.c) ------------------------------------------ */

/* Vulkan's host allocations through the context's allocator (aligned). */
void _tlod_vkb_callbacks(tlod_context* ctx, VkAllocationCallbacks* out);

/* ---- device memory (vk_memory.c) ------------------------------------------- */

/* A few large VkDeviceMemory blocks, suballocated first fit with coalescing;
 * requests past a quarter block get a block of their own. */
typedef struct vk_block vk_block;
typedef struct vk_alloc {
  vk_block* block;
  VkDeviceMemory memory;
  VkDeviceSize offset, size;
  void* mapped; /* host-visible allocations: persistently mapped at offset */
} vk_alloc;

typedef struct vk_memory {
  tlod_context* ctx;
  VkDevice device;
  const VkAllocationCallbacks* cb;
  VkPhysicalDeviceMemoryProperties props;
  VkDeviceSize block_size;
  vk_block* blocks;
  uint32_t* live_blocks; /* stats.vk.memory_blocks */
  uint64_t* live_bytes;  /* stats.vk.memory_bytes */
} vk_memory;

enum { VK_MEM_DEVICE = 0, VK_MEM_HOST = 1 };
enum { VK_MEM_LINEAR = 0, VK_MEM_OPTIMAL = 2 }; /* images and buffers never share a block (granularity) */

VkResult _tlod_vkb_memory_alloc(vk_memory* m, const VkMemoryRequirements* req, int kind, vk_alloc* out);
void _tlod_vkb_memory_free(vk_memory* m, vk_alloc* a);
void _tlod_vkb_memory_destroy(vk_memory* m);

/* A buffer and its memory. */
typedef struct vk_buffer {
  VkBuffer buffer;
  vk_alloc mem;
  VkDeviceSize size;
} vk_buffer;

VkResult _tlod_vkb_buffer_create(vk_memory* m, VkDeviceSize size, VkBufferUsageFlags usage, int host, vk_buffer* out);
void _tlod_vkb_buffer_destroy(vk_memory* m, vk_buffer* b);

/* ---- one-time uploads (vk_upload.c): a submit + fence wait, never in a frame */

typedef struct vk_upload {
  VkDevice device;
  VkQueue queue;
  const VkAllocationCallbacks* cb;
  VkCommandPool pool;
  VkCommandBuffer cmd;
  VkFence fence;
} vk_upload;

VkResult _tlod_vkb_upload_init(vk_upload* u, VkDevice device, VkQueue queue, uint32_t family,
                               const VkAllocationCallbacks* cb);
void _tlod_vkb_upload_destroy(vk_upload* u);
VkResult _tlod_vkb_upload_begin(vk_upload* u);
/* Ends, submits, waits for its fence at most TLOD_VK_UPLOAD_TIMEOUT_NS
 * (VK_TIMEOUT past that: the caller's error names it). */
#define TLOD_VK_UPLOAD_TIMEOUT_NS 60000000000ull
VkResult _tlod_vkb_upload_submit(vk_upload* u);
/* Device-local buffer filled with data through a staging buffer. */
VkResult _tlod_vkb_buffer_upload(vk_memory* m, vk_upload* u, const void* data, VkDeviceSize size,
                                 VkBufferUsageFlags usage, vk_buffer* out);

/* ---- textures (vk_texture.c) ------------------------------------------------ */

typedef struct vk_texture {
  VkImage image;
  VkImageView view;
  VkSampler sampler;
  vk_alloc mem;
} vk_texture;

tlod_result _tlod_vkb_texture_create(tlod_context* ctx, vk_memory* m, vk_upload* u, VkPhysicalDevice pd,
                                     const tlod_texture_desc* desc, vk_texture** out);
void _tlod_vkb_texture_destroy(tlod_context* ctx, vk_memory* m, vk_texture* t);

/* ---- shaders and pipelines (vk_pipeline.c) ---------------------------------- */

enum { VK_TYPES = TLOD_SURFACE_NUM };
/* As gl_device.c: PLAIN (no texture coordinates, no attributes; made at
 * creation), FULL (texture, a hook's attributes), MASK (FULL + discard). */
enum { VK_VARIANT_PLAIN, VK_VARIANT_FULL, VK_VARIANT_MASK, VK_VARIANTS };
/* MESH: the CPU-mesh mode's mesh.vert (positions, normals as vertex input). */
enum { VK_KIND_PATTERN, VK_KIND_STRIP, VK_KIND_TESS3, VK_KIND_TESS4, VK_KIND_MESH, VK_KINDS };

typedef struct vk_modules {
  bool built;
  VkShaderModule pattern_vert, strip_vert, tess_vert[2], tesc[2], tese[2];
  VkShaderModule mesh_vert; /* PLAIN with cpu_mesh */
} vk_modules;

typedef struct vk_pipelines {
  tlod_context* ctx;
  VkDevice device;
  const VkAllocationCallbacks* cb;
  const char* label;
  tlod_device_stats* stats;
  VkDescriptorSetLayout set_layout;
  VkPipelineLayout layout;
  VkPipelineCache cache;
  VkRenderPass render_pass;
  uint32_t subpass;
  VkFormat color_format, depth_format;
  VkSampleCountFlagBits samples;
  bool hardware;
  bool cpu_mesh;      /* tlod_gpu_eval resolved to OFF: mesh.vert for the PLAIN variant */
  char* hook;         /* the desc's fragment hook, copied; NULL == material.glsl */
  void* shader_cache; /* vk_shader_cache (vk_shader.h) */
  vk_modules modules[VK_TYPES][VK_VARIANTS];
  VkShaderModule frag[VK_VARIANTS]; /* the fragment stage does not depend on the surface type */
  /* [type][variant][kind][blend][line] */
  VkPipeline pipelines[VK_TYPES][VK_VARIANTS][VK_KINDS][2][2];
} vk_pipelines;

/* The set layout and pipeline layout (the bindings of tesslod/vulkan.h). */
tlod_result _tlod_vkb_pipelines_init(vk_pipelines* p);
void _tlod_vkb_pipelines_destroy(vk_pipelines* p);
/* The shader modules of a surface type and variant, compiled (or loaded
 * from the SPIR-V cache) the first time. */
tlod_result _tlod_vkb_modules(vk_pipelines* p, tlod_surface_type type, int variant);
/* The pipeline of a key, made the first time (its modules built first). */
tlod_result _tlod_vkb_pipeline(vk_pipelines* p, tlod_surface_type type, int variant, int kind, bool blend, bool line,
                               VkPipeline* out);

/* ---- frames in flight (vk_frame.c) ------------------------------------------ */

/* What is destroyed once no frame recorded before it was retired can still
 * run: a ring that grew, a surface's buffers, a texture. */
typedef struct vk_retired {
  uint64_t serial; /* frames begun when it was retired */
  vk_buffer buffer;
  vk_texture* texture;
} vk_retired;

/* One frame index: its upload ring, descriptor pools and queries. */
/* What a descriptor set was last written with (vk_draw.c write_set): equal
 * keys, equal descriptors. `retired` is vk_frames.retired_serial: a handle
 * value may come back after its buffer or texture was retired. */
typedef struct vk_set_key {
  const void *surface, *texture;
  VkBuffer ring, patches, attrs;
  VkDeviceSize instance_bytes, strip_bytes, record_bytes, attribute_bytes;
  uint64_t retired;
} vk_set_key;

typedef struct vk_slot {
  vk_buffer ring;
  VkDeviceSize head;
  VkDescriptorPool* pools;
  uint32_t pool_count, pool_cap, pool_current;
  /* Descriptor sets kept across the slot's frames (its previous frame has
   * finished when it begins again): the draws of a frame take them in
   * order from set_used; one is written only when its key changed. */
  VkDescriptorSet* sets;
  vk_set_key* set_keys;
  uint32_t set_count, set_cap, set_used;
  VkQueryPool timestamps, statistics;
  bool queried;        /* this frame's queries are recorded */
  bool read;           /* ... and their results taken into the stats */
  uint64_t query_draw; /* the draw they measure (stats numbering) */
  uint64_t begun;      /* serial of this slot's last frame (0: none) */
} vk_slot;

typedef struct vk_frames {
  tlod_context* ctx;
  VkDevice device;
  const VkAllocationCallbacks* cb;
  vk_memory* memory;
  uint32_t count;
  vk_slot slots[TLOD_VK_MAX_FRAMES_IN_FLIGHT];
  uint64_t serial; /* frames begun */
  uint32_t current;
  bool started;
  vk_retired* retired;
  uint32_t retired_count, retired_cap;
  uint64_t retired_serial; /* grows with every retirement (vk_set_key.retired) */
  VkDescriptorSetLayout set_layout;
  bool queries;
  double timestamp_period; /* ns per tick */
  uint64_t timestamp_mask;
} vk_frames;

tlod_result _tlod_vkb_frames_init(vk_frames* f, bool queries, bool statistics);
void _tlod_vkb_frames_destroy(vk_frames* f);
/* A draw with frame index `index`: when it is not the previous draw's,
 * slot `index` begins a new frame (its previous one has finished: the
 * frame-index contract): queries, ring and pools reset, what was retired
 * before every other slot's last frame destroyed. */
void _tlod_vkb_frames_begin(vk_frames* f, uint32_t index);
/* The query results of every slot whose frame has run into stats (the
 * latest draw measured wins); tlod_device_query_stats() calls it. */
void _tlod_vkb_frames_poll(vk_frames* f, tlod_device_stats* stats);
/* `bytes` at an offset aligned to `align` in the current slot's ring
 * (grown, the old ring retired, when it does not fit). */
VkResult _tlod_vkb_ring_take(vk_frames* f, VkDeviceSize bytes, VkDeviceSize align, VkDeviceSize* offset,
                             tlod_device_stats* stats);
/* `count` descriptor sets of the set layout from the current slot's pools. */
/* count sets of the current slot for this draw, allocated only past the
 * ones its earlier frames made: *sets and *keys point at them (their keys
 * zero when new). */
VkResult _tlod_vkb_sets(vk_frames* f, uint32_t count, VkDescriptorSet** sets, vk_set_key** keys);
bool _tlod_vkb_retire_buffer(vk_frames* f, vk_buffer* b);
bool _tlod_vkb_retire_texture(vk_frames* f, vk_texture* t);

/* ---- the device (vk_device.c), surfaces (vk_surface.c), draws (vk_draw.c) -- */

typedef struct vk_device {
  tlod_context* ctx;
  char label[64];
  tlod_device_stats* stats;
  const tlod_patterns* patterns;
  uint32_t lmax;
  bool hardware, wireframe_ok; /* tessellationShader; fillModeNonSolid */
  VkInstance instance;
  VkPhysicalDevice physical;
  VkDevice device;
  VkAllocationCallbacks callbacks;
  VkPhysicalDeviceLimits limits;
  VkDeviceSize ring_align, uniform_stride;
  vk_memory memory;
  vk_upload upload;
  vk_pipelines pipelines;
  vk_frames frames;
  bool glslang;       /* glslang_initialize_process called */
  void* shader_cache; /* vk_shader_cache */
  vk_buffer pattern_vertices, pattern_indices;
  uint32_t index_first[2][TLOD_MAX_LEVEL + 1], index_count[2][TLOD_MAX_LEVEL + 1], shape_base[2];
  vk_texture* white; /* the sampler binding of untextured items */
  _tlod_stage st;
  tlod_vk_uniforms* uniforms; /* staging of the items' uniform blocks */
  uint32_t uniform_cap;
  VkDescriptorSet* sets;      /* this draw's, in the slot's cache (_tlod_vkb_sets) */
  bool cpu_mesh;              /* tlod_gpu_eval resolved to OFF: PLAIN items draw their CPU mesh */
  VkDeviceSize (*mesh_at)[2]; /* per item of the draw: ring offsets of its mesh's vertices, indices */
  uint32_t mesh_at_cap;
} vk_device;

/* A device surface: the patch records and attributes on the CPU, and one
 * host-visible copy of each per frame slot, refreshed at the slot's first
 * draw after an update (dirty: one bit per slot). */
typedef struct vk_surface {
  float center[3];
  tlod_surface_type type;
  uint32_t patch_count, attribute_count;
  const tlod_surface* surface;
  tlod_patch_record* records;
  size_t record_bytes;
  float (*attributes)[4];
  size_t attribute_bytes;
  vk_buffer patches[TLOD_VK_MAX_FRAMES_IN_FLIGHT], attrs[TLOD_VK_MAX_FRAMES_IN_FLIGHT];
  uint32_t dirty;
  _tlod_item_mesh mesh; /* CPU-mesh mode: evaluated again only when its list changed */
} vk_surface;

tlod_result _tlod_vkb_surface_create(void* state, const tlod_surface* s, void** surface_state);
tlod_result _tlod_vkb_surface_update(void* state, void* surface_state, const tlod_surface* s);
void _tlod_vkb_surface_destroy(void* state, void* surface_state);
/* Slot `slot`'s copy, refreshed when dirty (never in flight: the contract). */
VkResult _tlod_vkb_surface_sync(vk_device* d, vk_surface* vs, uint32_t slot);
/* stats.vk.shader_* from the shader cache's counters. */
void _tlod_vkb_shader_stats(vk_device* d);
tlod_result _tlod_vkb_draw(void* state, const tlod_draw_desc* desc, const _tlod_draw_ref* refs,
                           tlod_draw_item_stats* item_stats);

/* ---- helpers ---------------------------------------------------------------- */

/* Room for one more element in *arr (count used, *cap allocated; doubled
 * from first, contents kept), through ctx. */
static inline bool _tlod_vkb_room(const tlod_context* ctx, void** arr, uint32_t* cap, uint32_t count, uint32_t first,
                                  size_t elem) {
  if (count < *cap) return true;
  uint32_t n = *cap ? *cap * 2 : first;
  void* p = tlod_context_alloc(ctx, elem * n);
  if (!p) return false;
  if (count) memcpy(p, *arr, elem * count);
  tlod_context_free(ctx, *arr);
  *arr = p, *cap = n;
  return true;
}

static inline VkDeviceSize _tlod_vkb_align(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }

const char* _tlod_vkb_result_name(VkResult r);

#endif
