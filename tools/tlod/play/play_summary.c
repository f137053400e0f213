/* tlod play -- a run's figures summed up: distributions and means. */
#include "play_summary.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

/* Distribution of one field of every frame's digest (NaN when it cannot be read). */
static distribution distribution_of(const play_trace* t, size_t field) {
  uint32_t n = t->frame_count;
  distribution d = {NAN, NAN, NAN, NAN, NAN, NAN};
  double* v = malloc(sizeof(double) * n);
  if (!v || !play_trace_digest_field(t, field, v)) {
    free(v);
    return d;
  }
  d = distribution_sort(v, n);
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
  r->first_frame_ms = t->first_frame_ms;
}
