/* tlod play -- the records of a playback: a window of frames with their
 * per-object figures, and what the summary keeps of every frame. */
#define _POSIX_C_SOURCE 200809L /* mkstemp, fdopen */
#include "play_trace.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "play_run_folder.h"

/* Room for one more frame in the window (at most PLAY_TRACE_WINDOW). */
static bool reserve_window(play_trace* t) {
  if (t->window_count < t->capacity) return true;
  uint32_t cap = t->capacity ? 2 * t->capacity : 64, most = play_trace_window_frames(t);
  cap = cap > most ? most : cap;
  play_frame* f = realloc(t->frames, sizeof(play_frame) * cap);
  if (!f) return false;
  t->frames = f;
  play_object_stats* s = realloc(t->stats, sizeof(play_object_stats) * cap * (t->object_count ? t->object_count : 1));
  if (!s) return false;
  t->stats = s;
  t->capacity = cap;
  return true;
}

play_frame* play_trace_add_frame(play_trace* t, play_object_stats** objects) {
  if (play_trace_window_full(t) || !reserve_window(t)) return NULL;
  play_frame* f = &t->frames[t->window_count];
  memset(f, 0, sizeof(*f));
  f->frame = t->frame_count;
  *objects = &t->stats[(size_t)t->window_count * t->object_count];
  memset(*objects, 0, sizeof(play_object_stats) * t->object_count);
  return f;
}

static void add_sums(play_sums* s, const play_frame_totals* tot) {
  for (int st = 0; st < TLOD_STAGE_NUM; st++)
    s->stage_ms[st] += tot->stage_ms[st];
  s->pattern += (double)tot->pattern_triangles;
  s->strip += (double)tot->strip_triangles;
  s->drawn += (double)tot->drawn_triangles;
  s->culled += tot->culled;
  s->epsilon += tot->effective_epsilon;
  for (int l = 0; l < PLAY_LEVELS; l++)
    s->histogram[l] += tot->level_histogram[l];
  if (tot->backend_gpu_ms >= 0.0) s->gpu_ms += tot->backend_gpu_ms, s->gpu_frames++;
}

bool play_trace_digests_open(play_trace* t, const char* dir, char* error, size_t error_size) {
  char path[PLAY_PATH_MAX + 64];
  play_path_join(path, sizeof(path), dir, ".digests.XXXXXX");
  int fd = mkstemp(path);
  if (fd >= 0) unlink(path); /* gone with the process, whatever happens */
  if (fd < 0 || !(t->digests = fdopen(fd, "w+b"))) {
    snprintf(error, error_size, "cannot create '%s': %s", path, strerror(errno));
    if (fd >= 0) close(fd);
    return false;
  }
  return true;
}

bool play_trace_commit_frame(play_trace* t) {
  play_frame_totals tot;
  play_frame_totals_of(t, t->window_count, &tot);
  play_digest d = {.frame_ms = t->frames[t->window_count].frame_ms,
                   .scheduler_ms = tot.scheduler_ms,
                   .backend_cpu_ms = tot.backend_cpu_ms,
                   .backend_wall_ms = tot.backend_wall_ms,
                   .triangles = (double)(tot.pattern_triangles + tot.strip_triangles)};
  errno = 0;
  if (fwrite(&d, sizeof(d), 1, t->digests) != 1) return false;
  if (!t->frame_count) t->first_frame_ms = d.frame_ms;
  add_sums(&t->sums, &tot);
  t->frame_count++;
  t->window_count++;
  return true;
}

bool play_trace_digest_field(const play_trace* t, size_t field, double* v) {
  if (!t->digests || fflush(t->digests) != 0 || fseek(t->digests, 0, SEEK_SET) != 0) return false;
  play_digest chunk[256];
  for (uint32_t i = 0; i < t->frame_count;) {
    uint32_t want = t->frame_count - i < 256 ? t->frame_count - i : 256;
    if (fread(chunk, sizeof(play_digest), want, t->digests) != want) return false;
    for (uint32_t k = 0; k < want; k++)
      memcpy(&v[i + k], (const char*)&chunk[k] + field, sizeof(double));
    i += want;
  }
  return fseek(t->digests, 0, SEEK_END) == 0; /* further frames append */
}

uint32_t play_trace_window_frames(const play_trace* t) {
  uint32_t n = t->object_count ? PLAY_TRACE_WINDOW_RECORDS / t->object_count : PLAY_TRACE_WINDOW;
  return n < 1 ? 1 : n > PLAY_TRACE_WINDOW ? PLAY_TRACE_WINDOW : n;
}

uint32_t play_trace_inline_objects(const play_trace* t) {
  return t->object_count < PLAY_TRACE_INLINE_OBJECTS ? t->object_count : PLAY_TRACE_INLINE_OBJECTS;
}

bool play_trace_window_full(const play_trace* t) { return t->window_count >= play_trace_window_frames(t); }

void play_trace_free(play_trace* t) {
  if (t->files) play_trace_files_close(t, false, NULL, 0);
  free(t->frames);
  free(t->stats);
  if (t->digests) fclose(t->digests);
  t->frames = NULL;
  t->stats = NULL;
  t->digests = NULL;
  t->frame_count = t->window_count = t->capacity = 0;
}

const play_object_stats* play_trace_object(const play_trace* t, uint32_t i, uint32_t object) {
  return &t->stats[(size_t)i * t->object_count + object];
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
