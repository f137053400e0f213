/* Shared by the unit tests: tesslod contexts with the counting / failing
 * allocator of test_alloc.h and a parallel-for of the test's own that runs
 * chunks of TEST_POOL_CHUNK items (define it before the include; 7 by
 * default) in reverse order on 3 "workers". */
#ifndef TLOD_TEST_CONTEXT_H
#define TLOD_TEST_CONTEXT_H

#include <stdint.h>

#include "tesslod/core.h"
#include "test_alloc.h"

#ifndef TEST_POOL_CHUNK
#define TEST_POOL_CHUNK 7
#endif

typedef struct reverse_pool {
  long calls, chunks;
} reverse_pool;

static inline void reverse_parallel_for(tlod_task_fn fn, void* task_data, uint32_t count, void* user_data) {
  reverse_pool* pool = user_data;
  pool->calls++;
  const uint32_t chunk = TEST_POOL_CHUNK;
  uint32_t chunks = (count + chunk - 1) / chunk;
  for (uint32_t c = chunks; c-- > 0;) {
    uint32_t end = (c + 1) * chunk < count ? (c + 1) * chunk : count;
    pool->chunks++;
    fn(task_data, c * chunk, end, c % 3);
  }
}

/* counter and pool may be NULL (the default allocator / thread pool). */
static inline tlod_context* new_context(uint32_t threads, counting_allocator* counter, reverse_pool* pool) {
  tlod_context_desc desc = {.thread_count = threads};
  if (counter) {
    desc.allocator.alloc_fn = counting_alloc;
    desc.allocator.free_fn = counting_free;
    desc.allocator.user_data = counter;
  }
  if (pool) {
    desc.parallel_for.func = reverse_parallel_for;
    desc.parallel_for.worker_count = 3;
    desc.parallel_for.user_data = pool;
  }
  tlod_context* ctx = NULL;
  return tlod_context_create(&desc, &ctx) == TLOD_SUCCESS ? ctx : NULL;
}

#endif
