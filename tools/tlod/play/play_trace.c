/* tlod play -- the records of a playback: frames and per-object figures. */
#include "play_trace.h"

#include <stdlib.h>
#include <string.h>

play_frame* play_trace_add_frame(play_trace* t, play_object_stats** objects) {
  if (t->frame_count == t->capacity) {
    uint32_t cap = t->capacity ? 2 * t->capacity : 256;
    play_frame* f = realloc(t->frames, sizeof(play_frame) * cap);
    if (!f) return NULL;
    t->frames = f;
    play_object_stats* s = realloc(t->stats, sizeof(play_object_stats) * cap * (t->object_count ? t->object_count : 1));
    if (!s) return NULL;
    t->stats = s;
    t->capacity = cap;
  }
  play_frame* f = &t->frames[t->frame_count];
  memset(f, 0, sizeof(*f));
  f->frame = t->frame_count;
  *objects = &t->stats[(size_t)t->frame_count * t->object_count];
  memset(*objects, 0, sizeof(play_object_stats) * t->object_count);
  t->frame_count++;
  return f;
}

void play_trace_free(play_trace* t) {
  free(t->frames);
  free(t->stats);
  t->frames = NULL;
  t->stats = NULL;
  t->frame_count = t->capacity = 0;
}

const play_object_stats* play_trace_object(const play_trace* t, uint32_t frame, uint32_t object) {
  return &t->stats[(size_t)frame * t->object_count + object];
}

void play_frame_totals_of(const play_trace* t, uint32_t frame, play_frame_totals* o) {
  memset(o, 0, sizeof(*o));
  bool gpu = false;
  for (uint32_t i = 0; i < t->object_count; i++) {
    const play_object_stats* s = play_trace_object(t, frame, i);
    o->scheduler_ms += s->update_ms;
    for (int st = 0; st < TLOD_STAGE_NUM; st++)
      o->stage_ms[st] += s->stage_ms[st];
    o->backend_cpu_ms += s->backend_cpu_ms;
    o->backend_wall_ms += s->backend_wall_ms;
    if (s->backend_gpu_ms >= 0.0) o->backend_gpu_ms += s->backend_gpu_ms, gpu = true;
    o->patches += s->patches;
    o->culled += s->culled;
    o->instances += s->instances;
    o->strips += s->strips;
    o->draw_calls += s->draw_calls;
    o->pattern_triangles += s->pattern_triangles;
    o->strip_triangles += s->strip_triangles;
    o->drawn_triangles += s->drawn_triangles;
    for (int l = 0; l < PLAY_LEVELS; l++)
      o->level_histogram[l] += s->level_histogram[l];
    if (i == 0 || s->effective_epsilon > o->effective_epsilon) o->effective_epsilon = s->effective_epsilon;
  }
  if (!gpu) o->backend_gpu_ms = -1.0;
}
