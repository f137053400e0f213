/* `tlod play` records and their files: the per-frame trace (trace_json.c,
 * trace_csv.c), the Chrome trace-event JSON (chrome_trace.c), and the
 * summary (summary_json.c, summary_text.c). Every file goes through
 * tlod_atomic_file: a unique temporary in its folder, renamed when complete.
 * The schemas are documented in docs/play.md. */
#ifndef TLOD_TOOLS_PLAY_TRACE_H
#define TLOD_TOOLS_PLAY_TRACE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "tesslod/lod.h"

/* Entries of every level histogram: levels 0..TLOD_MAX_LEVEL. */
#define PLAY_LEVELS (TLOD_MAX_LEVEL + 1)
#define PLAY_TRACE_SCHEMA "tlod-play-trace/1"
#define PLAY_SUMMARY_SCHEMA "tlod-play-summary/1"

/* One object of one frame. Times in ms; *_at_ms since the run started. */
typedef struct play_object_stats {
  double update_at_ms, update_ms; /* tlod_scheduler_update, wall clock */
  double stage_ms[TLOD_STAGE_NUM];
  double draw_at_ms, draw_ms; /* its share of the frame's tlod_device_draw, wall clock (play_loop.c) */
  double backend_cpu_ms, backend_gpu_ms, backend_wall_ms;
  uint32_t patches, culled, instances, strips, draw_calls;
  uint64_t pattern_triangles, strip_triangles, drawn_triangles;
  uint32_t level_histogram[PLAY_LEVELS];
  float effective_epsilon;
} play_object_stats;

typedef struct play_frame {
  uint32_t frame;
  double time_s;
  float eye[3], target[3], up[3], fovy, near_z, far_z;
  double at_ms, frame_ms; /* start since the run started; scheduler + draws, wall clock */
  double screenshot_at_ms, screenshot_ms;
  char screenshot[48]; /* "screenshots/frame_00025.png" or "" */
} play_frame;

/* Per-object totals of a frame (computed from its objects). */
typedef struct play_frame_totals {
  double scheduler_ms, stage_ms[TLOD_STAGE_NUM], backend_cpu_ms, backend_gpu_ms, backend_wall_ms;
  uint32_t patches, culled, instances, strips, draw_calls;
  uint64_t pattern_triangles, strip_triangles, drawn_triangles;
  uint32_t level_histogram[PLAY_LEVELS];
  float effective_epsilon;
} play_frame_totals;

typedef struct play_object_info {
  char name[64];
  char source[256];
  uint32_t vertices, faces, patches;
  float color[4];
} play_object_info;

/* One playback (one mode) and its settings. */
typedef struct play_trace {
  /* settings */
  const char* tool_version;
  const char* scene;
  const char* mode;    /* "adaptive", "uniform:3", "flat" */
  const char* backend; /* "cpu" or "gl" */
  const char* renderer;
  const char* surface;
  const char* policy; /* adaptive: the policy; uniform / flat: "error" */
  float epsilon;      /* as given to the scheduler */
  uint32_t max_level; /* scheduler max level */
  const char* path;   /* "orbit", ... or the file */
  double path_duration_s;
  bool loop;
  double fps;
  uint32_t width, height;
  uint32_t frames_requested;
  uint32_t screenshot_every; /* 0: none */
  const play_object_info* objects;
  uint32_t object_count;
  /* results */
  const char* dir;     /* folder of this run's files, relative to the summary's folder ("." or the mode) */
  const char* stopped; /* "completed", "interrupted" (SIGINT), "window closed", "error" */
  double wall_s;       /* whole playback, screenshots included */
  play_frame* frames;
  play_object_stats* stats; /* frame_count * object_count, frame by frame */
  uint32_t frame_count, capacity;
} play_trace;

/* Appends a frame (and object_count zeroed object records); NULL when out of memory. */
play_frame* play_trace_add_frame(play_trace* t, play_object_stats** objects);
void play_trace_free(play_trace* t);
/* The figures of one object in one frame. */
const play_object_stats* play_trace_object(const play_trace* t, uint32_t frame, uint32_t object);
void play_frame_totals_of(const play_trace* t, uint32_t frame, play_frame_totals* out);

/* Writers: false with one line in error when the file cannot be written
 * (then nothing is left under path). */
bool play_write_trace_json(const play_trace* t, const char* path, char* error, size_t error_size);
bool play_write_trace_csv(const play_trace* t, const char* path, char* error, size_t error_size);
bool play_write_chrome_trace(const play_trace* t, const char* path, char* error, size_t error_size);
/* The summary of runs (one per mode) as JSON and as the text printed at the end. */
bool play_write_summary_json(const play_trace* const* runs, uint32_t run_count, const char* out_dir, const char* path,
                             char* error, size_t error_size);
bool play_write_summary_text(const play_trace* const* runs, uint32_t run_count, const char* out_dir, const char* path,
                             char* error, size_t error_size);
void play_print_summary(FILE* f, const play_trace* const* runs, uint32_t run_count, const char* out_dir);

/* Nearest-rank percentile (p in [0, 100]) of n values; sorts a copy. */
double play_percentile(const double* values, uint32_t n, double p);

#endif
