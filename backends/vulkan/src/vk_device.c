/* tesslod::vulkan -- the "vulkan" device: created on the engine's
 * VkDevice, it makes once what every draw shares (pattern buffers, the
 * descriptor set and pipeline layouts, the PLAIN shader modules, query
 * pools, a 1x1 white texture) and records draws into the engine's command
 * buffers (vk_draw.c). Every Vulkan object goes through VkAllocationCallbacks
 * routed to the context's allocator; device memory through vk_memory.c. */
#include <stdio.h>
#include <string.h>

#include "vk_internal.h"
#include "vk_shader.h"

/* ---- the desc and the physical device ---------------------------------------- */

static tlod_result check_desc(tlod_context* ctx, const tlod_device_desc* desc) {
  const tlod_device_vk_desc* v = &desc->vk;
  const char* missing = !v->instance          ? "instance"
                        : !v->physical_device ? "physical_device"
                        : !v->device          ? "device"
                        : !v->queue           ? "queue"
                        : !v->color_format    ? "color_format"
                        : !v->depth_format    ? "depth_format"
                                              : NULL;
  if (missing)
    return tlod_context_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT, "vulkan device '%s': desc.vk.%s is required",
                             desc->label, missing);
  if (v->frames_in_flight > TLOD_VK_MAX_FRAMES_IN_FLIGHT)
    return tlod_context_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT,
                             "vulkan device '%s': desc.vk.frames_in_flight %u outside [1, %u] (0 == 2)", desc->label,
                             v->frames_in_flight, TLOD_VK_MAX_FRAMES_IN_FLIGHT);
  uint32_t s = v->samples;
  if (s > 64 || (s & (s - 1)))
    return tlod_context_fail(ctx, TLOD_ERROR_INVALID_ARGUMENT,
                             "vulkan device '%s': desc.vk.samples %u is not a power of two up to 64 (0 == 1)",
                             desc->label, s);
  return TLOD_SUCCESS;
}

static tlod_result check_format(vk_device* d, uint32_t format, VkFormatFeatureFlags need, const char* field,
                                const char* what) {
  VkFormatProperties fp;
  vkGetPhysicalDeviceFormatProperties(d->physical, (VkFormat)format, &fp);
  if ((fp.optimalTilingFeatures & need) == need) return TLOD_SUCCESS;
  return tlod_context_fail(d->ctx, TLOD_ERROR_UNSUPPORTED, "vulkan device '%s': desc.vk.%s %u (VkFormat) is not %s",
                           d->label, field, format, what);
}

/* Vulkan 1.3 (dynamic cull mode, depth write and bias; dynamic rendering),
 * the features the desc asks for, the formats, the sample count. */
static tlod_result check_device(vk_device* d, const tlod_device_vk_desc* v) {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(d->physical, &props);
  if (props.apiVersion < VK_API_VERSION_1_3)
    return tlod_context_fail(d->ctx, TLOD_ERROR_UNSUPPORTED, "vulkan device '%s': %s supports Vulkan %u.%u (needs 1.3)",
                             d->label, props.deviceName, VK_API_VERSION_MAJOR(props.apiVersion),
                             VK_API_VERSION_MINOR(props.apiVersion));
  d->limits = props.limits;
  VkPhysicalDeviceFeatures f;
  vkGetPhysicalDeviceFeatures(d->physical, &f);
  if (v->hardware_tessellation && !f.tessellationShader)
    return tlod_context_fail(d->ctx, TLOD_ERROR_UNSUPPORTED,
                             "vulkan device '%s': desc.vk.hardware_tessellation needs the tessellationShader "
                             "feature, which %s lacks",
                             d->label, props.deviceName);
  d->wireframe_ok = f.fillModeNonSolid;
  bool software = props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU || _tlod_software_renderer(props.deviceName);
  d->cpu_mesh = d->pipelines.cpu_mesh = _tlod_resolve_gpu_eval(
      d->stats, v->gpu_eval, software, v->hardware_tessellation, "desc.vk.gpu_eval", props.deviceName);
  tlod_result r = check_format(d, v->color_format, VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT, "color_format",
                               "a blendable colour attachment");
  if (r == TLOD_SUCCESS)
    r = check_format(d, v->depth_format, VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT, "depth_format",
                     "a depth attachment");
  uint32_t samples = v->samples ? v->samples : 1;
  VkSampleCountFlags ok = props.limits.framebufferColorSampleCounts & props.limits.framebufferDepthSampleCounts;
  if (r == TLOD_SUCCESS && !(ok & samples))
    return tlod_context_fail(d->ctx, TLOD_ERROR_UNSUPPORTED,
                             "vulkan device '%s': desc.vk.samples %u not supported for colour and depth (mask 0x%x)",
                             d->label, samples, ok);
  return r;
}

/* Timestamps need valid bits on the queue family; statistics the feature. */
static void query_support(vk_device* d, const tlod_device_vk_desc* v, bool* timestamps, bool* statistics) {
  uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(d->physical, &n, NULL);
  VkQueueFamilyProperties qf[16];
  n = n > 16 ? 16 : n;
  vkGetPhysicalDeviceQueueFamilyProperties(d->physical, &n, qf);
  uint32_t bits = v->queue_family < n ? qf[v->queue_family].timestampValidBits : 0;
  VkPhysicalDeviceFeatures f;
  vkGetPhysicalDeviceFeatures(d->physical, &f);
  *timestamps = v->host_query_reset && bits > 0;
  *statistics = *timestamps && f.pipelineStatisticsQuery;
  d->frames.timestamp_mask = bits >= 64 ? ~0ull : (1ull << bits) - 1ull;
  d->frames.timestamp_period = d->limits.timestampPeriod;
}

/* ---- create and destroy ------------------------------------------------------ */

/* Frames the engine submitted may still read what is destroyed here: the
 * one wait of the device's life (tesslod/vulkan.h; never in a draw). */
static void vk_destroy(void* state) {
  vk_device* d = state;
  if (d->device) vkDeviceWaitIdle(d->device);
  _tlod_vkb_frames_destroy(&d->frames);
  _tlod_vkb_pipelines_destroy(&d->pipelines);
  if (d->white) _tlod_vkb_texture_destroy(d->ctx, &d->memory, d->white);
  _tlod_vkb_buffer_destroy(&d->memory, &d->pattern_vertices);
  _tlod_vkb_buffer_destroy(&d->memory, &d->pattern_indices);
  _tlod_vkb_upload_destroy(&d->upload);
  _tlod_vkb_memory_destroy(&d->memory);
  if (d->glslang) glslang_finalize_process();
  _tlod_stage_free(d->ctx, &d->st);
  tlod_context_free(d->ctx, d->uniforms);
  tlod_context_free(d->ctx, d->mesh_at);
  tlod_context_free(d->ctx, d->pipelines.hook);
  tlod_context_free(d->ctx, d->shader_cache);
  tlod_context_free(d->ctx, d);
}

static tlod_result upload_patterns(vk_device* d) {
  _tlod_pattern_data pd;
  VkResult r = VK_ERROR_OUT_OF_HOST_MEMORY;
  if (_tlod_pattern_data_make(d->ctx, d->patterns, &pd)) {
    memcpy(d->index_first, pd.index_first, sizeof(d->index_first));
    memcpy(d->index_count, pd.index_count, sizeof(d->index_count));
    memcpy(d->shape_base, pd.shape_base, sizeof(d->shape_base));
    r = _tlod_vkb_buffer_upload(&d->memory, &d->upload, pd.vertices, sizeof(tlod_gl_pattern_vertex) * pd.vertex_count,
                                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, &d->pattern_vertices);
    if (r == VK_SUCCESS)
      r = _tlod_vkb_buffer_upload(&d->memory, &d->upload, pd.indices, sizeof(uint32_t) * pd.index_total,
                                  VK_BUFFER_USAGE_INDEX_BUFFER_BIT, &d->pattern_indices);
  }
  _tlod_pattern_data_free(d->ctx, &pd);
  if (r == VK_SUCCESS) return TLOD_SUCCESS;
  return tlod_context_fail(d->ctx, r == VK_ERROR_OUT_OF_HOST_MEMORY ? TLOD_ERROR_OUT_OF_MEMORY : TLOD_ERROR_BACKEND,
                           "vulkan device '%s': pattern buffers: %s", d->label, _tlod_vkb_result_name(r));
}

static tlod_result make_white(vk_device* d) {
  static const uint8_t white[4] = {255, 255, 255, 255};
  tlod_texture_desc t = {.width = 1, .height = 1, .rgba8 = white, .mipmaps_off = true, .label = "white"};
  return _tlod_vkb_texture_create(d->ctx, &d->memory, &d->upload, d->physical, &t, &d->white);
}

/* The fields of the device from the desc (no Vulkan call yet). */
static tlod_result setup(vk_device* d, tlod_context* ctx, const tlod_device_desc* desc, tlod_device_stats* stats) {
  const tlod_device_vk_desc* v = &desc->vk;
  d->ctx = ctx;
  d->stats = stats;
  snprintf(d->label, sizeof(d->label), "%s", desc->label);
  d->patterns = desc->patterns;
  d->lmax = tlod_patterns_max_level(desc->patterns);
  d->hardware = d->st.hardware = v->hardware_tessellation;
  d->instance = v->instance;
  d->physical = v->physical_device;
  d->device = v->device;
  _tlod_vkb_callbacks(ctx, &d->callbacks);
  d->memory = (vk_memory){.ctx = ctx,
                          .device = d->device,
                          .cb = &d->callbacks,
                          .block_size = 16u << 20,
                          .live_blocks = &stats->vk.memory_blocks,
                          .live_bytes = &stats->vk.memory_bytes};
  vkGetPhysicalDeviceMemoryProperties(d->physical, &d->memory.props);
  /* The folder's name is copied after the struct: later draws compile the FULL and MASK variants. */
  size_t dir = v->shader_cache_dir ? strlen(v->shader_cache_dir) + 1 : 0;
  vk_shader_cache* cache = tlod_context_calloc(ctx, 1, sizeof(vk_shader_cache) + dir);
  d->shader_cache = cache;
  if (cache && dir) cache->dir = memcpy((char*)(cache + 1), v->shader_cache_dir, dir);
  size_t hook = v->fragment_hook ? strlen(v->fragment_hook) + 1 : 0;
  char* copy = hook ? tlod_context_alloc(ctx, hook) : NULL;
  if (copy) memcpy(copy, v->fragment_hook, hook);
  d->pipelines = (vk_pipelines){.ctx = ctx,
                                .device = d->device,
                                .cb = &d->callbacks,
                                .label = d->label,
                                .stats = stats,
                                .render_pass = (VkRenderPass)v->render_pass,
                                .subpass = v->subpass,
                                .color_format = (VkFormat)v->color_format,
                                .depth_format = (VkFormat)v->depth_format,
                                .samples = (VkSampleCountFlagBits)(v->samples ? v->samples : 1),
                                .hardware = d->hardware,
                                .hook = copy,
                                .shader_cache = cache};
  d->frames = (vk_frames){.ctx = ctx,
                          .device = d->device,
                          .cb = &d->callbacks,
                          .memory = &d->memory,
                          .count = v->frames_in_flight ? v->frames_in_flight : 2};
  if (!cache || (hook && !copy))
    return tlod_context_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "vulkan device: out of memory");
  return TLOD_SUCCESS;
}

/* Offsets into the ring: every section aligned for storage, uniform and
 * vertex use; one item's uniforms per uniform offset alignment. */
static void ring_layout(vk_device* d) {
  VkDeviceSize a = d->limits.minStorageBufferOffsetAlignment, u = d->limits.minUniformBufferOffsetAlignment;
  d->ring_align = a > u ? a : u;
  if (d->ring_align < 16) d->ring_align = 16;
  d->uniform_stride = _tlod_vkb_align(sizeof(tlod_vk_uniforms), u ? u : 1);
}

static tlod_result build(vk_device* d, const tlod_device_desc* desc) {
  const tlod_device_vk_desc* v = &desc->vk;
  tlod_result r = check_device(d, v);
  if (r != TLOD_SUCCESS) return r;
  ring_layout(d);
  bool timestamps, statistics;
  query_support(d, v, &timestamps, &statistics);
  VkResult vr = _tlod_vkb_upload_init(&d->upload, d->device, (VkQueue)v->queue, v->queue_family, &d->callbacks);
  if (vr != VK_SUCCESS)
    return tlod_context_fail(d->ctx, TLOD_ERROR_BACKEND, "vulkan device '%s': command pool / fence: %s", d->label,
                             _tlod_vkb_result_name(vr));
  r = upload_patterns(d);
  if (r == TLOD_SUCCESS) r = make_white(d);
  if (r == TLOD_SUCCESS) r = _tlod_vkb_pipelines_init(&d->pipelines);
  d->frames.set_layout = d->pipelines.set_layout;
  if (r == TLOD_SUCCESS) r = _tlod_vkb_frames_init(&d->frames, timestamps, statistics);
  d->glslang = r == TLOD_SUCCESS && glslang_initialize_process();
  if (r == TLOD_SUCCESS && !d->glslang)
    return tlod_context_fail(d->ctx, TLOD_ERROR_BACKEND, "vulkan device '%s': glslang_initialize_process failed",
                             d->label);
  uint32_t mask = v->surface_types ? v->surface_types : (1u << TLOD_SURFACE_NUM) - 1u;
  if (mask & (1u << TLOD_SURFACE_DEFAULT)) mask |= 1u << TLOD_SURFACE_PHONG;
  for (int t = 1; t < VK_TYPES && r == TLOD_SUCCESS; t++)
    if (mask & (1u << t)) r = _tlod_vkb_modules(&d->pipelines, (tlod_surface_type)t, VK_VARIANT_PLAIN);
  return r;
}

void _tlod_vkb_shader_stats(vk_device* d) {
  const vk_shader_cache* c = d->shader_cache;
  d->stats->vk.shader_compiles = c->compiles;
  d->stats->vk.shader_cache_hits = c->hits;
  d->stats->vk.shader_ms = c->ms;
}

static tlod_result vk_create(tlod_context* ctx, const tlod_device_desc* desc, tlod_device_stats* stats, void** state) {
  tlod_result r = check_desc(ctx, desc);
  if (r != TLOD_SUCCESS) return r;
  double t0 = tlod_now_ms();
  vk_device* d = tlod_context_calloc(ctx, 1, sizeof(*d));
  if (!d) return tlod_context_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "vulkan device: out of memory");
  r = setup(d, ctx, desc, stats);
  if (r == TLOD_SUCCESS) r = build(d, desc);
  if (d->shader_cache) _tlod_vkb_shader_stats(d);
  if (r != TLOD_SUCCESS) {
    vk_destroy(d);
    return r;
  }
  stats->vk.create_ms = tlod_now_ms() - t0;
  *state = d;
  return TLOD_SUCCESS;
}

/* ---- textures ------------------------------------------------------------------ */

static tlod_result vk_create_texture(void* state, const tlod_texture_desc* desc, void** texture_state) {
  vk_device* d = state;
  return _tlod_vkb_texture_create(d->ctx, &d->memory, &d->upload, d->physical, desc, (vk_texture**)texture_state);
}

/* A frame in flight may still sample it: destroyed once none can. */
static void vk_destroy_texture(void* state, void* texture_state) {
  vk_device* d = state;
  if (!_tlod_vkb_retire_texture(&d->frames, texture_state))
    _tlod_vkb_texture_destroy(d->ctx, &d->memory, texture_state);
}

static void vk_poll_stats(void* state, tlod_device_stats* stats) {
  vk_device* d = state;
  _tlod_vkb_frames_poll(&d->frames, stats);
}

const _tlod_device_vtbl _tlod_vk_device_vtbl = {.create = vk_create,
                                                .destroy = vk_destroy,
                                                .create_surface = _tlod_vkb_surface_create,
                                                .update_surface = _tlod_vkb_surface_update,
                                                .destroy_surface = _tlod_vkb_surface_destroy,
                                                .draw = _tlod_vkb_draw,
                                                .read_image = NULL,
                                                .times_draws = false,
                                                .create_texture = vk_create_texture,
                                                .destroy_texture = vk_destroy_texture,
                                                .poll_stats = vk_poll_stats};
