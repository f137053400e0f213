/* tlod play -- a run's figures summed up: distributions and means. */
#include "play_summary.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

static int compare_double(const void* a, const void* b) {
  double x = *(const double*)a, y = *(const double*)b;
  return x < y ? -1 : (x > y ? 1 : 0);
}

double play_percentile(const double* values, uint32_t n, double p) {
  if (!n) return 0.0;
  double* v = malloc(sizeof(double) * n);
  if (!v) return NAN;
  memcpy(v, values, sizeof(double) * n);
  qsort(v, n, sizeof(double), compare_double);
  double rank = ceil(p / 100.0 * n);
  uint32_t i = rank < 1.0 ? 0 : (uint32_t)rank - 1;
  double r = v[i < n ? i : n - 1];
  free(v);
  return r;
}

/* Distribution of one field of the digests (a copy: percentiles sort). */
static distribution distribution_of(const play_trace* t, size_t field) {
  distribution d = {0};
  uint32_t n = t->frame_count;
  double* v = n ? malloc(sizeof(double) * n) : NULL;
  if (!v) return d;
  for (uint32_t i = 0; i < n; i++)
    v[i] = *(const double*)((const char*)&t->digests[i] + field);
  d.min = d.max = v[0];
  for (uint32_t i = 0; i < n; i++) {
    d.mean += v[i];
    d.min = v[i] < d.min ? v[i] : d.min;
    d.max = v[i] > d.max ? v[i] : d.max;
  }
  d.mean /= n;
  d.p50 = play_percentile(v, n, 50);
  d.p95 = play_percentile(v, n, 95);
  d.p99 = play_percentile(v, n, 99);
  free(v);
  return d;
}

void play_summarize(const play_trace* t, run_summary* r) {
  memset(r, 0, sizeof(*r));
  uint32_t n = t->frame_count;
  const play_sums* s = &t->sums;
  r->frames = n;
  r->gpu_mean = s->gpu_frames ? s->gpu_ms / s->gpu_frames : -1.0;
  r->gpu_frames = s->gpu_frames;
  if (!n) return;
  for (int st = 0; st < TLOD_STAGE_NUM; st++)
    r->stage_mean[st] = s->stage_ms[st] / n;
  r->pattern_mean = s->pattern / n;
  r->strip_mean = s->strip / n;
  r->drawn_mean = s->drawn / n;
  r->culled_mean = s->culled / n;
  r->epsilon_mean = s->epsilon / n;
  for (int l = 0; l < PLAY_LEVELS; l++)
    r->histogram_mean[l] = s->histogram[l] / n;
  r->frame_ms = distribution_of(t, offsetof(play_digest, frame_ms));
  r->scheduler_ms = distribution_of(t, offsetof(play_digest, scheduler_ms));
  r->backend_cpu_ms = distribution_of(t, offsetof(play_digest, backend_cpu_ms));
  r->backend_wall_ms = distribution_of(t, offsetof(play_digest, backend_wall_ms));
  r->triangles = distribution_of(t, offsetof(play_digest, triangles));
  r->first_frame_ms = t->digests[0].frame_ms;
}
