/* tesslod::vulkan -- Vulkan's host allocations through the context's
 * allocator. The context gives no alignment guarantee past malloc's, and
 * Vulkan asks for any power of two: each block carries a header just below
 * the aligned pointer with the raw pointer and the size (for realloc). */
#include <string.h>

#include "vk_internal.h"

typedef struct vk_header {
  void* raw;
  size_t size;
} vk_header;

enum { HEADER = 16 };
_Static_assert(sizeof(vk_header) <= HEADER, "the header fits below the pointer");

static void* vk_alloc_fn(void* user, size_t size, size_t alignment, VkSystemAllocationScope scope) {
  (void)scope;
  const tlod_context* ctx = user;
  size_t align = alignment < HEADER ? HEADER : alignment;
  if (size > SIZE_MAX - align - HEADER) return NULL;
  char* raw = tlod_context_alloc(ctx, size + align + HEADER);
  if (!raw) return NULL;
  uintptr_t p = ((uintptr_t)raw + HEADER + align - 1) / align * align;
  vk_header* h = (vk_header*)(p - HEADER);
  h->raw = raw;
  h->size = size;
  return (void*)p;
}

static void vk_free_fn(void* user, void* mem) {
  if (!mem) return;
  const vk_header* h = (const vk_header*)((char*)mem - HEADER);
  tlod_context_free(user, h->raw);
}

static void* vk_realloc_fn(void* user, void* old, size_t size, size_t alignment, VkSystemAllocationScope scope) {
  if (!old) return vk_alloc_fn(user, size, alignment, scope);
  if (size == 0) {
    vk_free_fn(user, old);
    return NULL;
  }
  void* p = vk_alloc_fn(user, size, alignment, scope);
  if (!p) return NULL; /* the old block stays valid, as Vulkan requires */
  const vk_header* h = (const vk_header*)((char*)old - HEADER);
  memcpy(p, old, h->size < size ? h->size : size);
  vk_free_fn(user, old);
  return p;
}

void _tlod_vkb_callbacks(tlod_context* ctx, VkAllocationCallbacks* out) {
  *out = (VkAllocationCallbacks){
      .pUserData = ctx, .pfnAllocation = vk_alloc_fn, .pfnReallocation = vk_realloc_fn, .pfnFree = vk_free_fn};
}

const char* _tlod_vkb_result_name(VkResult r) {
  switch (r) {
  case VK_SUCCESS:
    return "VK_SUCCESS";
  case VK_ERROR_OUT_OF_HOST_MEMORY:
    return "VK_ERROR_OUT_OF_HOST_MEMORY";
  case VK_ERROR_OUT_OF_DEVICE_MEMORY:
    return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
  case VK_ERROR_DEVICE_LOST:
    return "VK_ERROR_DEVICE_LOST";
  case VK_ERROR_INITIALIZATION_FAILED:
    return "VK_ERROR_INITIALIZATION_FAILED";
  case VK_ERROR_FEATURE_NOT_PRESENT:
    return "VK_ERROR_FEATURE_NOT_PRESENT";
  case VK_ERROR_FORMAT_NOT_SUPPORTED:
    return "VK_ERROR_FORMAT_NOT_SUPPORTED";
  case VK_ERROR_OUT_OF_POOL_MEMORY:
    return "VK_ERROR_OUT_OF_POOL_MEMORY";
  case VK_ERROR_FRAGMENTED_POOL:
    return "VK_ERROR_FRAGMENTED_POOL";
  case VK_ERROR_INVALID_SHADER_NV:
    return "VK_ERROR_INVALID_SHADER_NV";
  default:
    return "VkResult error";
  }
}
