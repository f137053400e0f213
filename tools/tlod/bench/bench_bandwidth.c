/* tlod bench -- memory read, write and copy rates on one and two threads,
 * through a context's own pool (the threads the cases run on). */
#include "bench_bandwidth.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_stats.h"
#include "cli.h"
#include "tesslod/core.h"

#define BW_CHUNKS 64u

typedef enum { BW_READ, BW_WRITE, BW_COPY } bw_kind;

typedef struct bw_task {
  bw_kind kind;
  size_t bytes; /* a multiple of 8 * BW_CHUNKS */
  uint64_t* src;
  uint64_t* dst;
  uint64_t sums[BW_CHUNKS];
} bw_task;

static void bw_chunk(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  (void)worker;
  bw_task* t = data;
  size_t words = t->bytes / 8 / BW_CHUNKS;
  for (uint32_t c = begin; c < end; c++) {
    uint64_t *s = t->src + c * words, *d = t->dst + c * words;
    if (t->kind == BW_WRITE) memset(d, (int)c, words * 8);
    if (t->kind == BW_COPY) memcpy(d, s, words * 8);
    if (t->kind != BW_READ) continue;
    uint64_t acc[8] = {0}; /* one cache line per step, 8 independent adds: the loads, not the adds, bound it */
    for (size_t i = 0; i < words; i += 8)
      for (int k = 0; k < 8; k++)
        acc[k] += s[i + k];
    uint64_t sum = 0;
    for (int k = 0; k < 8; k++)
      sum += acc[k];
    t->sums[c] = sum; /* kept: the loop cannot be elided */
  }
}

/* Best rate of 5 runs (copy: bytes copied): bytes per CPU-second of the
 * process (a stalled load keeps its thread running, so CPU time counts the
 * memory wait but not the time the host gave the core to another guest;
 * with T threads each CPU-second moved this much while they ran together)
 * and, for reference, bytes per wall-clock second. */
static void best_rate(tlod_context* ctx, bw_task* t, bw_kind kind, double* cpu_rate, double* wall_rate) {
  *cpu_rate = *wall_rate = 0.0;
  t->kind = kind;
  for (int i = 0; i < 5; i++) {
    double t0 = cli_now_ms(), c0 = bench_cpu_ms();
    tlod_context_parallel_for(ctx, bw_chunk, t, BW_CHUNKS);
    double wall = (cli_now_ms() - t0) * 1e-3, cpu = (bench_cpu_ms() - c0) * 1e-3;
    double rc = (double)t->bytes / cpu, rw = (double)t->bytes / wall;
    *cpu_rate = rc > *cpu_rate ? rc : *cpu_rate;
    *wall_rate = rw > *wall_rate ? rw : *wall_rate;
  }
}

static bool measure_threads(uint32_t threads, bw_task* t, bench_rates* r) {
  tlod_context* ctx = NULL;
  if (tlod_context_create(&(tlod_context_desc){.thread_count = threads, .label = "bandwidth"}, &ctx) != TLOD_SUCCESS)
    return false;
  best_rate(ctx, t, BW_READ, &r->read, &r->read_wall);
  best_rate(ctx, t, BW_WRITE, &r->write, &r->write_wall);
  best_rate(ctx, t, BW_COPY, &r->copy, &r->copy_wall);
  tlod_context_destroy(ctx);
  return true;
}

bool bench_bandwidth_measure(bench_bandwidth* out, uint32_t mib) {
  bw_task* t = calloc(1, sizeof(*t));
  size_t bytes = (size_t)mib << 20;
  out->mib = mib;
  bool ok = t && (t->src = malloc(bytes)) && (t->dst = malloc(bytes));
  if (ok) {
    t->bytes = bytes;
    memset(t->src, 1, bytes); /* touched: no page faults in the timed runs */
    memset(t->dst, 2, bytes);
  }
  for (uint32_t k = 0; ok && k < 2; k++)
    ok = measure_threads(k + 1, t, &out->rates[k]);
  if (t) free(t->src), free(t->dst);
  free(t);
  return ok;
}

const bench_rates* bench_bandwidth_rates(const bench_bandwidth* b, uint32_t threads) {
  return &b->rates[threads >= 2 ? 1 : 0];
}

double bench_bound_ms(const bench_rates* r, double bytes_read, double bytes_written) {
  return (bytes_read / r->read + bytes_written / r->write) * 1e3;
}

void bench_bandwidth_print(const bench_bandwidth* b) {
  for (int k = 0; k < 2; k++) {
    const bench_rates* r = &b->rates[k];
    printf("bandwidth  T%d  per CPU-second: read %6.2f GB  write %6.2f GB  copy %6.2f GB (bytes copied) | per wall "
           "second: read %6.2f write %6.2f copy %6.2f  [%u MiB buffers, best of 5]\n",
           k + 1, r->read * 1e-9, r->write * 1e-9, r->copy * 1e-9, r->read_wall * 1e-9, r->write_wall * 1e-9,
           r->copy_wall * 1e-9, b->mib);
  }
  printf("bandwidth  bound of a stage = bytes read / read rate + bytes written / write rate (rates per CPU-second at "
         "its thread count: the bound is CPU time, read against the stage's CPU time)\n");
}
