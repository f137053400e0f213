/* tesslod::vulkan -- frames in flight. Each frame index has an upload ring
 * (host-visible, persistently mapped: instances, strips, strip references
 * and per-item uniforms of its draws), descriptor pools and two query
 * pools. A slot begins a new frame at the first draw naming its index after
 * a draw naming another one; by the frame-index contract the GPU has then
 * finished the slot's previous frame, so its ring, pools and queries are
 * free to reuse without any wait. Draws of one frame share its index and
 * append to its ring. What cannot be destroyed at once (a ring that grew,
 * a destroyed surface's buffers or texture) is retired with the number of
 * frames begun, and destroyed when every slot has begun a frame after that
 * (docs/vulkan.md: the sync argument). */
#include <string.h>

#include "vk_internal.h"

enum { POOL_SETS = 256, RING_MIN = 256 * 1024 };

static VkResult make_queries(vk_frames* f, vk_slot* s, bool statistics) {
  VkQueryPoolCreateInfo ti = {
      .sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO, .queryType = VK_QUERY_TYPE_TIMESTAMP, .queryCount = 2};
  VkResult r = vkCreateQueryPool(f->device, &ti, f->cb, &s->timestamps);
  if (r == VK_SUCCESS) vkResetQueryPool(f->device, s->timestamps, 0, 2);
  if (r != VK_SUCCESS || !statistics) return r;
  VkQueryPoolCreateInfo si = {.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
                              .queryType = VK_QUERY_TYPE_PIPELINE_STATISTICS,
                              .queryCount = 1,
                              .pipelineStatistics = VK_QUERY_PIPELINE_STATISTIC_CLIPPING_INVOCATIONS_BIT};
  r = vkCreateQueryPool(f->device, &si, f->cb, &s->statistics);
  if (r == VK_SUCCESS) vkResetQueryPool(f->device, s->statistics, 0, 1);
  return r;
}

tlod_result _tlod_vkb_frames_init(vk_frames* f, bool queries, bool statistics) {
  f->queries = queries;
  for (uint32_t i = 0; i < f->count && queries; i++) {
    VkResult r = make_queries(f, &f->slots[i], statistics);
    if (r != VK_SUCCESS)
      return tlod_context_fail(f->ctx, TLOD_ERROR_BACKEND, "vulkan device: query pools: %s", _tlod_vkb_result_name(r));
  }
  return TLOD_SUCCESS;
}

static void free_retired(vk_frames* f, vk_retired* r) {
  if (r->buffer.buffer) _tlod_vkb_buffer_destroy(f->memory, &r->buffer);
  if (r->texture) _tlod_vkb_texture_destroy(f->ctx, f->memory, r->texture);
}

void _tlod_vkb_frames_destroy(vk_frames* f) {
  for (uint32_t i = 0; i < f->count; i++) {
    vk_slot* s = &f->slots[i];
    _tlod_vkb_buffer_destroy(f->memory, &s->ring);
    for (uint32_t p = 0; p < s->pool_count; p++)
      vkDestroyDescriptorPool(f->device, s->pools[p], f->cb);
    tlod_context_free(f->ctx, s->pools);
    tlod_context_free(f->ctx, s->sets);
    tlod_context_free(f->ctx, s->set_keys);
    if (s->timestamps) vkDestroyQueryPool(f->device, s->timestamps, f->cb);
    if (s->statistics) vkDestroyQueryPool(f->device, s->statistics, f->cb);
  }
  for (uint32_t i = 0; i < f->retired_count; i++)
    free_retired(f, &f->retired[i]);
  tlod_context_free(f->ctx, f->retired);
}

/* A slot's queries, once its frame has run: read without waiting (a result
 * not yet available stays pending). Not in a draw: lavapipe answers
 * vkGetQueryPoolResults only after waiting for the device to be idle
 * (docs/vulkan.md), which in a draw would wait for the frame in flight. */
static bool read_queries(vk_frames* f, vk_slot* s, tlod_device_stats* stats) {
  uint64_t t[2] = {0, 0}, prims = 0;
  VkResult r =
      vkGetQueryPoolResults(f->device, s->timestamps, 0, 2, sizeof(t), t, sizeof(uint64_t), VK_QUERY_RESULT_64_BIT);
  if (r != VK_SUCCESS) return false;
  if (s->statistics && vkGetQueryPoolResults(f->device, s->statistics, 0, 1, sizeof(prims), &prims, sizeof(uint64_t),
                                             VK_QUERY_RESULT_64_BIT) != VK_SUCCESS)
    return false;
  if (s->query_draw > stats->gpu_draw) {
    stats->gpu_ms = (double)((t[1] - t[0]) & f->timestamp_mask) * f->timestamp_period * 1e-6;
    stats->gpu_draw = s->query_draw;
    stats->vk.primitives = prims;
  }
  return true;
}

void _tlod_vkb_frames_poll(vk_frames* f, tlod_device_stats* stats) {
  for (uint32_t k = 0; k < f->count; k++) {
    vk_slot* s = &f->slots[k];
    if (s->queried && !s->read) s->read = read_queries(f, s, stats);
  }
}

/* At the slot's new frame (its previous one has finished): the queries
 * are free to reset; a reading nobody polled is dropped. */
static void reset_queries(vk_frames* f, vk_slot* s) {
  if (!s->queried) return;
  vkResetQueryPool(f->device, s->timestamps, 0, 2);
  if (s->statistics) vkResetQueryPool(f->device, s->statistics, 0, 1);
  s->queried = s->read = false;
}

/* Retired before every slot's last frame began: no frame that can still
 * run was recorded with it. */
static void collect(vk_frames* f) {
  uint32_t kept = 0;
  for (uint32_t i = 0; i < f->retired_count; i++) {
    bool free = true;
    for (uint32_t k = 0; k < f->count; k++)
      free = free && (f->slots[k].begun == 0 || f->slots[k].begun > f->retired[i].serial);
    if (free)
      free_retired(f, &f->retired[i]);
    else
      f->retired[kept++] = f->retired[i];
  }
  f->retired_count = kept;
}

void _tlod_vkb_frames_begin(vk_frames* f, uint32_t index) {
  /* One slot: every draw is a frame of its own (nothing else tells frames apart). */
  if (f->started && index == f->current && f->count > 1) return;
  f->started = true;
  f->current = index;
  vk_slot* s = &f->slots[index];
  s->begun = ++f->serial;
  reset_queries(f, s);
  s->head = 0;
  s->set_used = 0; /* kept: written again only where their keys change */
  collect(f);
}

static bool push_retired(vk_frames* f, vk_retired r) {
  if (!_tlod_vkb_room(f->ctx, (void**)&f->retired, &f->retired_cap, f->retired_count, 16, sizeof(vk_retired)))
    return false;
  r.serial = f->serial;
  f->retired[f->retired_count++] = r;
  return true;
}

bool _tlod_vkb_retire_buffer(vk_frames* f, vk_buffer* b) {
  if (!b->buffer) return true;
  bool ok = push_retired(f, (vk_retired){.buffer = *b});
  f->retired_serial++;
  memset(b, 0, sizeof(*b));
  return ok;
}

bool _tlod_vkb_retire_texture(vk_frames* f, vk_texture* t) {
  f->retired_serial++;
  return push_retired(f, (vk_retired){.texture = t});
}

VkResult _tlod_vkb_ring_take(vk_frames* f, VkDeviceSize bytes, VkDeviceSize align, VkDeviceSize* offset,
                             tlod_device_stats* stats) {
  vk_slot* s = &f->slots[f->current];
  VkDeviceSize at = _tlod_vkb_align(s->head, align);
  if (!s->ring.buffer || at + bytes > s->ring.size) {
    VkDeviceSize cap = s->ring.size ? s->ring.size * 2 : RING_MIN;
    while (cap < bytes)
      cap *= 2;
    vk_buffer ring;
    VkResult r = _tlod_vkb_buffer_create(f->memory, cap,
                                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT |
                                             VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_INDEX_BUFFER_BIT,
                                         1, &ring);
    if (r != VK_SUCCESS) return r;
    stats->vk.ring_bytes += cap - s->ring.size;
    if (!_tlod_vkb_retire_buffer(f, &s->ring)) {
      _tlod_vkb_buffer_destroy(f->memory, &ring);
      return VK_ERROR_OUT_OF_HOST_MEMORY;
    }
    s->ring = ring;
    at = 0;
  }
  *offset = at;
  s->head = at + bytes;
  return VK_SUCCESS;
}

static VkResult add_pool(vk_frames* f, vk_slot* s) {
  if (!_tlod_vkb_room(f->ctx, (void**)&s->pools, &s->pool_cap, s->pool_count, 4, sizeof(VkDescriptorPool)))
    return VK_ERROR_OUT_OF_HOST_MEMORY;
  const VkDescriptorPoolSize sizes[4] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3 * POOL_SETS},
                                         {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC, 2 * POOL_SETS},
                                         {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, POOL_SETS},
                                         {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, POOL_SETS}};
  VkDescriptorPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
                                   .maxSets = POOL_SETS,
                                   .poolSizeCount = 4,
                                   .pPoolSizes = sizes};
  VkResult r = vkCreateDescriptorPool(f->device, &pi, f->cb, &s->pools[s->pool_count]);
  if (r == VK_SUCCESS) s->pool_count++;
  return r;
}

/* One more set into s->sets[i]. */
static VkResult allocate_set(vk_frames* f, vk_slot* s, VkDescriptorSet* out) {
  VkResult r = VK_ERROR_OUT_OF_POOL_MEMORY;
  while (r == VK_ERROR_OUT_OF_POOL_MEMORY || r == VK_ERROR_FRAGMENTED_POOL) {
    if (s->pool_current == s->pool_count) {
      VkResult a = add_pool(f, s);
      if (a != VK_SUCCESS) return a;
    }
    VkDescriptorSetAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                      .descriptorPool = s->pools[s->pool_current],
                                      .descriptorSetCount = 1,
                                      .pSetLayouts = &f->set_layout};
    r = vkAllocateDescriptorSets(f->device, &ai, out);
    if (r == VK_ERROR_OUT_OF_POOL_MEMORY || r == VK_ERROR_FRAGMENTED_POOL) s->pool_current++;
  }
  return r;
}

VkResult _tlod_vkb_sets(vk_frames* f, uint32_t count, VkDescriptorSet** sets, vk_set_key** keys) {
  vk_slot* s = &f->slots[f->current];
  uint32_t need = s->set_used + count;
  if (need > s->set_cap) {
    uint32_t cap = s->set_cap ? s->set_cap : 16;
    while (cap < need)
      cap *= 2;
    VkDescriptorSet* ns = tlod_context_alloc(f->ctx, sizeof(VkDescriptorSet) * cap);
    vk_set_key* nk = tlod_context_alloc(f->ctx, sizeof(vk_set_key) * cap);
    if (!ns || !nk) {
      tlod_context_free(f->ctx, ns);
      tlod_context_free(f->ctx, nk);
      return VK_ERROR_OUT_OF_HOST_MEMORY;
    }
    if (s->set_count) memcpy(ns, s->sets, sizeof(VkDescriptorSet) * s->set_count);
    if (s->set_count) memcpy(nk, s->set_keys, sizeof(vk_set_key) * s->set_count);
    tlod_context_free(f->ctx, s->sets);
    tlod_context_free(f->ctx, s->set_keys);
    s->sets = ns, s->set_keys = nk, s->set_cap = cap;
  }
  for (; s->set_count < need; s->set_count++) {
    VkResult r = allocate_set(f, s, &s->sets[s->set_count]);
    if (r != VK_SUCCESS) return r;
    memset(&s->set_keys[s->set_count], 0, sizeof(vk_set_key));
  }
  *sets = s->sets + s->set_used;
  *keys = s->set_keys + s->set_used;
  s->set_used = need;
  return VK_SUCCESS;
}
