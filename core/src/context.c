/* tesslod::core -- context: allocator, logger, errors, parallel-for. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime, sysconf */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "internal.h"

static void* default_alloc(size_t size, void* user_data) {
  (void)user_data;
  return malloc(size);
}

static void default_free(void* ptr, void* user_data) {
  (void)user_data;
  free(ptr);
}

const char* tlod_result_string(tlod_result result) {
  static const char* const names[TLOD_RESULT_NUM] = {
      "TLOD_SUCCESS",
      "TLOD_ERROR_INVALID_ARGUMENT",
      "TLOD_ERROR_OUT_OF_MEMORY",
      "TLOD_ERROR_INVALID_MESH",
      "TLOD_ERROR_UNSUPPORTED",
      "TLOD_ERROR_IO",
      "TLOD_ERROR_PARSE",
      "TLOD_ERROR_BACKEND",
  };
  if ((unsigned)result >= TLOD_RESULT_NUM) return "TLOD_ERROR_UNKNOWN";
  return names[result];
}

static uint32_t online_cpus(void) {
  long n = sysconf(_SC_NPROCESSORS_ONLN);
  if (n < 1) return 1;
  return n > 64 ? 64u : (uint32_t)n;
}

/* Resolves every default of the desc in one place. */
static tlod_context_desc context_desc_defaults(const tlod_context_desc* in) {
  tlod_context_desc d = in ? *in : (tlod_context_desc){0};
  /* Only both or neither reach here (check_desc). */
  if (!d.allocator.alloc_fn) {
    d.allocator.alloc_fn = default_alloc;
    d.allocator.free_fn = default_free;
    d.allocator.user_data = NULL;
  }
  if (d.parallel_for.func) {
    if (d.parallel_for.worker_count == 0) d.parallel_for.worker_count = 1;
    d.thread_count = d.parallel_for.worker_count;
  } else {
    if (d.thread_count == 0) d.thread_count = online_cpus();
    if (d.thread_count > 64) d.thread_count = 64;
  }
  if (!d.label) d.label = "tesslod";
  d.simd = _tlod_simd_resolve(d.simd);
  return d;
}

/* There is no context yet to hold a refusal: it goes to the desc's logger. */
static tlod_result refuse_desc(const tlod_context_desc* desc, const char* fmt, ...) _TLOD_PRINTF(2, 3);
static tlod_result refuse_desc(const tlod_context_desc* desc, const char* fmt, ...) {
  if (desc->logger.func) {
    char msg[256];
    int n = snprintf(msg, sizeof(msg), "[%.63s] tlod_context_create: ", desc->label ? desc->label : "tesslod");
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg + n, sizeof(msg) - (size_t)n, fmt, ap);
    va_end(ap);
    desc->logger.func(TLOD_LOG_ERROR, msg, desc->logger.user_data);
  }
  return TLOD_ERROR_INVALID_ARGUMENT;
}

/* One allocator hook without the other would pair the caller's memory with
 * malloc's; a worker count past TLOD_MAX_WORKERS would have every
 * parallel stage allocate per-worker scratch without a useful bound. */
static tlod_result check_desc(const tlod_context_desc* desc) {
  const tlod_allocator* a = &desc->allocator;
  if (!a->alloc_fn != !a->free_fn)
    return refuse_desc(desc, "allocator.%s is NULL but the other hook is set (give both hooks or neither)",
                       a->alloc_fn ? "free_fn" : "alloc_fn");
  if (desc->parallel_for.func && desc->parallel_for.worker_count > TLOD_MAX_WORKERS)
    return refuse_desc(desc, "parallel_for.worker_count %u is above TLOD_MAX_WORKERS (%u)",
                       desc->parallel_for.worker_count, (unsigned)TLOD_MAX_WORKERS);
  if ((unsigned)desc->simd >= TLOD_SIMD_NUM)
    return refuse_desc(desc, "simd %u is not a tlod_simd", (unsigned)desc->simd);
  return TLOD_SUCCESS;
}

tlod_result tlod_context_create(const tlod_context_desc* desc, tlod_context** out) {
  if (!out) return TLOD_ERROR_INVALID_ARGUMENT;
  *out = NULL;
  if (desc && check_desc(desc) != TLOD_SUCCESS) return TLOD_ERROR_INVALID_ARGUMENT;
  tlod_context_desc d = context_desc_defaults(desc);
  tlod_context* ctx = d.allocator.alloc_fn(sizeof(*ctx), d.allocator.user_data);
  if (!ctx) return TLOD_ERROR_OUT_OF_MEMORY;
  memset(ctx, 0, sizeof(*ctx));
  ctx->desc = d;
  snprintf(ctx->label, sizeof(ctx->label), "%s", d.label);
  ctx->desc.label = ctx->label;
  if (!d.parallel_for.func && d.thread_count > 1) {
    tlod_result r = _tlod_pool_create(ctx, d.thread_count, &ctx->pool);
    if (r != TLOD_SUCCESS) {
      d.allocator.free_fn(ctx, d.allocator.user_data);
      return r;
    }
  }
  *out = ctx;
  return TLOD_SUCCESS;
}

void tlod_context_destroy(tlod_context* ctx) {
  if (!ctx) return;
  if (ctx->pool) _tlod_pool_destroy(ctx, ctx->pool);
  ctx->desc.allocator.free_fn(ctx, ctx->desc.allocator.user_data);
}

tlod_context_desc tlod_context_query_desc(const tlod_context* ctx) { return ctx ? ctx->desc : (tlod_context_desc){0}; }

const char* tlod_context_last_error(const tlod_context* ctx) { return ctx ? ctx->last_error : ""; }

void* tlod_context_alloc(const tlod_context* ctx, size_t size) {
  if (!ctx) return NULL;
  if (size == 0) size = 1;
  return ctx->desc.allocator.alloc_fn(size, ctx->desc.allocator.user_data);
}

void* tlod_context_calloc(const tlod_context* ctx, size_t count, size_t size) {
  if (size != 0 && count > SIZE_MAX / size) return NULL;
  size_t bytes = count * size;
  void* p = _tlod_alloc(ctx, bytes);
  if (p) memset(p, 0, bytes > 0 ? bytes : 1);
  return p;
}

void tlod_context_free(const tlod_context* ctx, void* ptr) {
  if (ctx && ptr) ctx->desc.allocator.free_fn(ptr, ctx->desc.allocator.user_data);
}

static void vlog(const tlod_context* ctx, tlod_log_level level, const char* fmt, va_list ap) {
  if (!ctx || !ctx->desc.logger.func) return;
  char msg[640];
  int n = snprintf(msg, sizeof(msg), "[%s] ", ctx->label);
  if (n < 0) n = 0;
  vsnprintf(msg + n, sizeof(msg) - (size_t)n, fmt, ap);
  ctx->desc.logger.func(level, msg, ctx->desc.logger.user_data);
}

tlod_result tlod_context_fail(tlod_context* ctx, tlod_result result, const char* fmt, ...) {
  if (!ctx) return result;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(ctx->last_error, sizeof(ctx->last_error), fmt, ap);
  va_end(ap);
  _tlod_log(ctx, TLOD_LOG_ERROR, "%s: %s", tlod_result_string(result), ctx->last_error);
  return result;
}

void tlod_context_log(const tlod_context* ctx, tlod_log_level level, const char* fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vlog(ctx, level, fmt, ap);
  va_end(ap);
}

uint32_t tlod_context_worker_count(const tlod_context* ctx) { return ctx ? ctx->desc.thread_count : 1u; }

void tlod_context_parallel_for(const tlod_context* ctx, tlod_task_fn fn, void* data, uint32_t count) {
  if (count == 0) return;
  if (!ctx) {
    fn(data, 0, count, 0); /* no context: on the caller, as one worker */
  } else if (ctx->desc.parallel_for.func) {
    ctx->desc.parallel_for.func(fn, data, count, ctx->desc.parallel_for.user_data);
  } else if (ctx->pool) {
    _tlod_pool_run(ctx->pool, fn, data, count);
  } else {
    fn(data, 0, count, 0);
  }
}

double tlod_now_ms(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}
