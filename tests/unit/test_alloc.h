/* Shared by the unit tests: an allocator that counts calls and can fail on
 * the k-th (or every call from the k-th on), to prove every allocation goes
 * through the context's hooks and every error path frees what it took. */
#ifndef TLOD_TEST_ALLOC_H
#define TLOD_TEST_ALLOC_H

#include <stdbool.h>
#include <stdlib.h>

typedef struct counting_allocator {
  long calls, allocs, frees, failed;
  long fail_at; /* -1: never */
  bool fail_all;
} counting_allocator;

static void* counting_alloc(size_t size, void* user_data) {
  counting_allocator* c = user_data;
  long call = c->calls++;
  if (c->fail_at >= 0 && (call == c->fail_at || (c->fail_all && call > c->fail_at))) {
    c->failed++;
    return NULL;
  }
  void* p = malloc(size ? size : 1);
  if (p) c->allocs++;
  return p;
}

static void counting_free(void* ptr, void* user_data) {
  counting_allocator* c = user_data;
  if (ptr) c->frees++;
  free(ptr);
}

#endif
