/* tesslod::core -- the built-in worker pool behind _tlod_parallel_for.
 * Workers pull fixed-size chunks from an atomic counter; the caller works
 * too, as worker 0. Which worker runs a chunk never changes a result: tasks
 * write only to their own range. */
#include <pthread.h>
#include <stdatomic.h>

#include "internal.h"

struct _tlod_pool {
  uint32_t thread_count; /* including the caller */
  pthread_t* threads;
  pthread_mutex_t lock;
  pthread_cond_t wake, done;
  uint64_t generation; /* bumped per job */
  uint32_t busy;       /* workers still on the current job */
  bool quit;
  /* current job */
  tlod_task_fn fn;
  void* data;
  uint32_t count, chunk;
  atomic_uint next;
};

typedef struct worker_arg {
  _tlod_pool* pool;
  uint32_t id;
} worker_arg;

static void run_chunks(_tlod_pool* p, uint32_t worker) {
  for (;;) {
    uint32_t begin = atomic_fetch_add(&p->next, p->chunk);
    if (begin >= p->count) return;
    uint32_t end = p->count - begin < p->chunk ? p->count : begin + p->chunk;
    p->fn(p->data, begin, end, worker);
  }
}

static void* worker_main(void* arg) {
  worker_arg a = *(worker_arg*)arg;
  _tlod_pool* p = a.pool;
  uint64_t seen = 0;
  pthread_mutex_lock(&p->lock);
  for (;;) {
    while (!p->quit && p->generation == seen)
      pthread_cond_wait(&p->wake, &p->lock);
    if (p->quit) break;
    seen = p->generation;
    pthread_mutex_unlock(&p->lock);
    run_chunks(p, a.id);
    pthread_mutex_lock(&p->lock);
    if (--p->busy == 0) pthread_cond_signal(&p->done);
  }
  pthread_mutex_unlock(&p->lock);
  return NULL;
}

/* The worker args must outlive thread start-up; they live after the pool. */
tlod_result _tlod_pool_create(tlod_context* ctx, uint32_t threads, _tlod_pool** out) {
  *out = NULL;
  size_t bytes = sizeof(_tlod_pool) + sizeof(worker_arg) * threads;
  _tlod_pool* p = _tlod_calloc(ctx, 1, bytes);
  if (!p) return _tlod_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "thread pool: out of memory");
  p->threads = _tlod_calloc(ctx, threads, sizeof(pthread_t));
  if (!p->threads) {
    _tlod_free(ctx, p);
    return _tlod_fail(ctx, TLOD_ERROR_OUT_OF_MEMORY, "thread pool: out of memory");
  }
  pthread_mutex_init(&p->lock, NULL);
  pthread_cond_init(&p->wake, NULL);
  pthread_cond_init(&p->done, NULL);
  worker_arg* args = (worker_arg*)(p + 1);
  p->thread_count = 1;
  for (uint32_t i = 1; i < threads; i++) {
    args[i] = (worker_arg){p, i};
    if (pthread_create(&p->threads[i], NULL, worker_main, &args[i]) != 0) break;
    p->thread_count = i + 1;
  }
  *out = p;
  return TLOD_SUCCESS;
}

void _tlod_pool_destroy(tlod_context* ctx, _tlod_pool* p) {
  pthread_mutex_lock(&p->lock);
  p->quit = true;
  pthread_cond_broadcast(&p->wake);
  pthread_mutex_unlock(&p->lock);
  for (uint32_t i = 1; i < p->thread_count; i++)
    pthread_join(p->threads[i], NULL);
  pthread_cond_destroy(&p->done);
  pthread_cond_destroy(&p->wake);
  pthread_mutex_destroy(&p->lock);
  _tlod_free(ctx, p->threads);
  _tlod_free(ctx, p);
}

void _tlod_pool_run(_tlod_pool* p, tlod_task_fn fn, void* data, uint32_t count) {
  /* ~8 chunks per thread balances uneven patches without contention. */
  uint32_t chunk = count / (p->thread_count * 8u);
  pthread_mutex_lock(&p->lock);
  p->fn = fn;
  p->data = data;
  p->count = count;
  p->chunk = chunk ? chunk : 1;
  atomic_store(&p->next, 0);
  p->busy = p->thread_count - 1;
  p->generation++;
  pthread_cond_broadcast(&p->wake);
  pthread_mutex_unlock(&p->lock);
  run_chunks(p, 0);
  pthread_mutex_lock(&p->lock);
  while (p->busy > 0)
    pthread_cond_wait(&p->done, &p->lock);
  pthread_mutex_unlock(&p->lock);
}
