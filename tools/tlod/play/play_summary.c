/* tlod play -- a run's figures summed up: distributions and means. */
#include "play_summary.h"

#include <math.h>
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

static distribution distribution_of(const double* v, uint32_t n) {
  distribution d = {0};
  if (!n) return d;
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
  return d;
}

void play_summarize(const play_trace* t, run_summary* r) {
  memset(r, 0, sizeof(*r));
  uint32_t n = t->frame_count;
  r->frames = n;
  r->gpu_mean = -1.0;
  if (!n) return;
  double* v[5];
  for (int k = 0; k < 5; k++)
    v[k] = calloc(n, sizeof(double));
  if (!v[0] || !v[1] || !v[2] || !v[3] || !v[4]) {
    for (int k = 0; k < 5; k++)
      free(v[k]);
    return;
  }
  double gpu = 0.0;
  for (uint32_t i = 0; i < n; i++) {
    play_frame_totals tot;
    play_frame_totals_of(t, i, &tot);
    v[0][i] = t->frames[i].frame_ms;
    v[1][i] = tot.scheduler_ms;
    v[2][i] = tot.backend_cpu_ms;
    v[3][i] = tot.backend_wall_ms;
    v[4][i] = (double)(tot.pattern_triangles + tot.strip_triangles);
    if (tot.backend_gpu_ms >= 0.0) gpu += tot.backend_gpu_ms, r->gpu_frames++;
    for (int s = 0; s < TLOD_STAGE_NUM; s++)
      r->stage_mean[s] += tot.stage_ms[s] / n;
    r->pattern_mean += (double)tot.pattern_triangles / n;
    r->strip_mean += (double)tot.strip_triangles / n;
    r->drawn_mean += (double)tot.drawn_triangles / n;
    r->culled_mean += (double)tot.culled / n;
    r->epsilon_mean += (double)tot.effective_epsilon / n;
    for (int l = 0; l < PLAY_LEVELS; l++)
      r->histogram_mean[l] += (double)tot.level_histogram[l] / n;
  }
  if (r->gpu_frames) r->gpu_mean = gpu / r->gpu_frames;
  r->frame_ms = distribution_of(v[0], n);
  r->scheduler_ms = distribution_of(v[1], n);
  r->backend_cpu_ms = distribution_of(v[2], n);
  r->backend_wall_ms = distribution_of(v[3], n);
  r->triangles = distribution_of(v[4], n);
  r->first_frame_ms = t->frames[0].frame_ms;
  for (int k = 0; k < 5; k++)
    free(v[k]);
}
