/* tesslod::vulkan -- device memory: a few large VkDeviceMemory blocks per
 * memory type and kind, suballocated first fit; freed ranges coalesce with
 * their neighbours, and a block whose last range is freed is released.
 * Requests past a quarter block get a block of their own (dedicated), so
 * one big surface never fragments the shared blocks. Host-visible blocks
 * are mapped once, at allocation, and stay mapped (coherent memory: no
 * flushes). Why not VMA: docs/vulkan.md. */
#include <string.h>

#include "vk_internal.h"

typedef struct vk_range {
  VkDeviceSize offset, size;
} vk_range;

struct vk_block {
  VkDeviceMemory memory;
  VkDeviceSize size, used;
  uint32_t type;
  int kind;
  bool dedicated;
  void* mapped;
  vk_range* free; /* sorted by offset, never adjacent */
  uint32_t free_count, free_cap;
  vk_block* next;
};

static int find_type(const VkPhysicalDeviceMemoryProperties* p, uint32_t bits, VkMemoryPropertyFlags want) {
  for (uint32_t i = 0; i < p->memoryTypeCount; i++)
    if ((bits & (1u << i)) && (p->memoryTypes[i].propertyFlags & want) == want) return (int)i;
  return -1;
}

static int memory_type(const vk_memory* m, uint32_t bits, int kind) {
  if (kind & VK_MEM_HOST)
    return find_type(&m->props, bits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  int t = find_type(&m->props, bits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  return t >= 0 ? t : find_type(&m->props, bits, 0);
}

static VkResult block_create(vk_memory* m, VkDeviceSize size, uint32_t type, int kind, bool dedicated, vk_block** out) {
  vk_block* b = tlod_context_calloc(m->ctx, 1, sizeof(*b));
  if (!b || !_tlod_vkb_room(m->ctx, (void**)&b->free, &b->free_cap, 0, 8, sizeof(vk_range))) {
    tlod_context_free(m->ctx, b);
    return VK_ERROR_OUT_OF_HOST_MEMORY;
  }
  VkMemoryAllocateInfo ai = {
      .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = size, .memoryTypeIndex = type};
  VkResult r = vkAllocateMemory(m->device, &ai, m->cb, &b->memory);
  if (r == VK_SUCCESS && (kind & VK_MEM_HOST)) r = vkMapMemory(m->device, b->memory, 0, VK_WHOLE_SIZE, 0, &b->mapped);
  if (r != VK_SUCCESS) {
    if (b->memory) vkFreeMemory(m->device, b->memory, m->cb);
    tlod_context_free(m->ctx, b->free);
    tlod_context_free(m->ctx, b);
    return r;
  }
  b->size = size, b->type = type, b->kind = kind, b->dedicated = dedicated;
  b->free[0] = (vk_range){0, size};
  b->free_count = 1;
  b->next = m->blocks;
  m->blocks = b;
  (*m->live_blocks)++;
  *m->live_bytes += size;
  *out = b;
  return VK_SUCCESS;
}

static void block_destroy(vk_memory* m, vk_block* b) {
  for (vk_block** p = &m->blocks; *p; p = &(*p)->next) {
    if (*p == b) {
      *p = b->next;
      break;
    }
  }
  if (b->mapped) vkUnmapMemory(m->device, b->memory);
  vkFreeMemory(m->device, b->memory, m->cb);
  (*m->live_blocks)--;
  *m->live_bytes -= b->size;
  tlod_context_free(m->ctx, b->free);
  tlod_context_free(m->ctx, b);
}

/* First fit in b: the range's start aligned; what is left either side stays free. */
static bool block_take(vk_memory* m, vk_block* b, VkDeviceSize size, VkDeviceSize align, VkDeviceSize* offset) {
  for (uint32_t i = 0; i < b->free_count; i++) {
    vk_range f = b->free[i];
    VkDeviceSize start = _tlod_vkb_align(f.offset, align), end = start + size;
    if (end > f.offset + f.size) continue;
    bool before = start > f.offset, after = end < f.offset + f.size;
    if (before && after) { /* one range becomes two */
      if (!_tlod_vkb_room(m->ctx, (void**)&b->free, &b->free_cap, b->free_count, 8, sizeof(vk_range))) return false;
      memmove(&b->free[i + 2], &b->free[i + 1], sizeof(vk_range) * (b->free_count - i - 1));
      b->free_count++;
      b->free[i + 1] = (vk_range){end, f.offset + f.size - end};
      b->free[i].size = start - f.offset;
    } else if (before) {
      b->free[i].size = start - f.offset;
    } else if (after) {
      b->free[i] = (vk_range){end, f.offset + f.size - end};
    } else {
      memmove(&b->free[i], &b->free[i + 1], sizeof(vk_range) * (b->free_count - i - 1));
      b->free_count--;
    }
    b->used += size;
    *offset = start;
    return true;
  }
  return false;
}

/* Gives [offset, offset + size) back, merged with free neighbours. */
static bool block_give(vk_memory* m, vk_block* b, VkDeviceSize offset, VkDeviceSize size) {
  uint32_t i = 0;
  while (i < b->free_count && b->free[i].offset < offset)
    i++;
  bool left = i > 0 && b->free[i - 1].offset + b->free[i - 1].size == offset;
  bool right = i < b->free_count && offset + size == b->free[i].offset;
  b->used -= size;
  if (left && right) {
    b->free[i - 1].size += size + b->free[i].size;
    memmove(&b->free[i], &b->free[i + 1], sizeof(vk_range) * (b->free_count - i - 1));
    b->free_count--;
  } else if (left) {
    b->free[i - 1].size += size;
  } else if (right) {
    b->free[i].offset = offset, b->free[i].size += size;
  } else {
    /* Out of memory: the range is lost until the block goes, never used twice. */
    if (!_tlod_vkb_room(m->ctx, (void**)&b->free, &b->free_cap, b->free_count, 8, sizeof(vk_range))) return false;
    memmove(&b->free[i + 1], &b->free[i], sizeof(vk_range) * (b->free_count - i));
    b->free[i] = (vk_range){offset, size};
    b->free_count++;
  }
  return true;
}

VkResult _tlod_vkb_memory_alloc(vk_memory* m, const VkMemoryRequirements* req, int kind, vk_alloc* out) {
  memset(out, 0, sizeof(*out));
  int type = memory_type(m, req->memoryTypeBits, kind);
  if (type < 0) return VK_ERROR_FEATURE_NOT_PRESENT;
  VkDeviceSize align = req->alignment ? req->alignment : 1, offset = 0;
  vk_block* b = NULL;
  if (req->size > m->block_size / 4) {
    VkResult r = block_create(m, req->size, (uint32_t)type, kind, true, &b);
    if (r != VK_SUCCESS) return r;
    block_take(m, b, req->size, 1, &offset);
  } else {
    for (b = m->blocks; b; b = b->next)
      if (!b->dedicated && b->type == (uint32_t)type && b->kind == kind && block_take(m, b, req->size, align, &offset))
        break;
    if (!b) {
      VkResult r = block_create(m, m->block_size, (uint32_t)type, kind, false, &b);
      if (r != VK_SUCCESS) return r;
      block_take(m, b, req->size, align, &offset);
    }
  }
  *out = (vk_alloc){.block = b,
                    .memory = b->memory,
                    .offset = offset,
                    .size = req->size,
                    .mapped = b->mapped ? (char*)b->mapped + offset : NULL};
  return VK_SUCCESS;
}

void _tlod_vkb_memory_free(vk_memory* m, vk_alloc* a) {
  vk_block* b = a->block;
  if (!b) return;
  block_give(m, b, a->offset, a->size);
  if (b->used == 0) block_destroy(m, b);
  memset(a, 0, sizeof(*a));
}

void _tlod_vkb_memory_destroy(vk_memory* m) {
  while (m->blocks)
    block_destroy(m, m->blocks);
}

VkResult _tlod_vkb_buffer_create(vk_memory* m, VkDeviceSize size, VkBufferUsageFlags usage, int host, vk_buffer* out) {
  memset(out, 0, sizeof(*out));
  VkBufferCreateInfo bi = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                           .size = size,
                           .usage = usage,
                           .sharingMode = VK_SHARING_MODE_EXCLUSIVE};
  VkResult r = vkCreateBuffer(m->device, &bi, m->cb, &out->buffer);
  if (r != VK_SUCCESS) return r;
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(m->device, out->buffer, &req);
  r = _tlod_vkb_memory_alloc(m, &req, (host ? VK_MEM_HOST : VK_MEM_DEVICE) | VK_MEM_LINEAR, &out->mem);
  if (r == VK_SUCCESS) r = vkBindBufferMemory(m->device, out->buffer, out->mem.memory, out->mem.offset);
  if (r != VK_SUCCESS) {
    _tlod_vkb_buffer_destroy(m, out);
    return r;
  }
  out->size = size;
  return VK_SUCCESS;
}

void _tlod_vkb_buffer_destroy(vk_memory* m, vk_buffer* b) {
  if (b->buffer) vkDestroyBuffer(m->device, b->buffer, m->cb);
  _tlod_vkb_memory_free(m, &b->mem);
  memset(b, 0, sizeof(*b));
}
