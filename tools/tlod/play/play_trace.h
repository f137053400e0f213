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

#include "tesslod/backend.h"
#include "tesslod/lod.h"

/* Entries of every level histogram: levels 0..TLOD_MAX_LEVEL. */
#define PLAY_LEVELS (TLOD_MAX_LEVEL + 1)
#define PLAY_TRACE_SCHEMA "tlod-play-trace/2"
#define PLAY_SUMMARY_SCHEMA "tlod-play-summary/2"
/* Objects whose full per-frame records go into trace.json's frames (and
 * chrome_trace.json's events): the first 16. Every object's per-frame
 * counts go to objects.csv, one row per frame and object, so a frame of
 * trace.json stays the same size however many objects a scene has
 * (docs/play.md "objects.csv"). */
#define PLAY_TRACE_INLINE_OBJECTS 16u
/* Object records held in memory at most: the window holds fewer frames
 * when a scene has more than 64 objects. */
#define PLAY_TRACE_WINDOW_RECORDS 65536u

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
  double at_ms, frame_ms; /* start since the run started; animation + scheduler + draws, wall clock */
  double anim_ms;         /* node animation and skinning (play_scene_pose), wall clock; 0 when nothing moves */
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
  uint32_t surface; /* objects drawing one surface share it (glTF instances) */
  int64_t node;     /* glTF node index, -1: none */
  bool skinned;     /* skinned on the CPU every frame (its own surface) */
  bool textured;    /* draws a base colour texture */
} play_object_info;

/* Frames held in memory: when the window is full, its frames are appended
 * to the trace files' temporaries before the next frame, so a long run's
 * memory does not grow with its frames (docs/play.md, "Memory"). */
#define PLAY_TRACE_WINDOW 1024u

/* What the summary keeps of every frame (its percentiles need them all):
 * 40 bytes a frame, appended to an unlinked temporary file in the run
 * folder rather than kept in memory (play_trace_digests_open). */
typedef struct play_digest {
  double frame_ms, scheduler_ms, backend_cpu_ms, backend_wall_ms, triangles;
} play_digest;

/* Sums over every frame, for the summary's means. */
typedef struct play_sums {
  double stage_ms[TLOD_STAGE_NUM], pattern, strip, drawn, culled, epsilon, histogram[PLAY_LEVELS], gpu_ms;
  uint32_t gpu_frames;
} play_sums;

/* Resource use after frame 1, 10, 100, ... and the last (play_resources.c). */
#define PLAY_MAX_SAMPLES 9
typedef struct play_resources {
  uint32_t frame;                 /* frames played when sampled */
  uint64_t peak_rss_kib, rss_kib; /* VmHWM, VmRSS of /proc/self/status; 0: unknown */
  bool gl;                        /* the counts below were taken (gl backend) */
  uint32_t gl_buffers, gl_textures, gl_renderbuffers, gl_framebuffers, gl_vertex_arrays, gl_programs, gl_shaders,
      gl_queries;
} play_resources;

typedef struct play_trace_files play_trace_files; /* play_trace_files.c */

/* The result field coloured (tlod play --field); name NULL: none. */
typedef struct play_field_info {
  const char* name;  /* the array's name */
  const char* label; /* "stress", "displacement:magnitude", "velocity:1" */
  const char* units; /* "" none */
  int component;     /* -1: magnitude */
  double min, max;   /* the range on the colour map */
  const char* colormap;
  bool from_cells; /* cell data averaged to points */
  uint32_t steps;  /* of a time series, 0: one file */
} play_field_info;

/* One playback (one mode) and its settings. */
typedef struct play_trace {
  /* settings */
  const char* tool_version;
  const char* scene;
  const char* mode;    /* "adaptive", "uniform:3", "flat" */
  const char* backend; /* "cpu", "gl", "null" or "vulkan" */
  const char* renderer;
  const char* gpu_eval; /* gl: "on (why)" / "off (why)": where the surfaces were evaluated (--gpu-eval) */
  const char* surface;
  const char* policy;    /* adaptive: the policy; uniform / flat: "error" */
  float epsilon;         /* as given to the scheduler */
  uint32_t max_level;    /* scheduler max level */
  uint32_t scene_budget; /* --scene-budget in force (adaptive), 0 none */
  const char* path;      /* "orbit", ... or the file */
  double path_duration_s;
  bool loop;
  double fps;
  uint32_t width, height;
  uint32_t frames_requested;
  uint32_t screenshot_every;                          /* 0: none */
  const char* debug_view;                             /* --debug-view: "none", "levels", ... */
  uint32_t resize_frame, resize_width, resize_height; /* --resize-at; resize_width 0: none */
  bool validate;                                      /* --validate (vulkan) */
  const char* shader_cache;                           /* vulkan: the SPIR-V cache folder, "" none */
  const play_object_info* objects;
  uint32_t object_count;
  const char* animation; /* the animation played, "" none */
  double animation_duration_s;
  play_field_info field;
  const char* warnings; /* the importer's, newline-separated; "" none */
  uint32_t warning_count;
  /* results */
  const char* dir;      /* folder of this run's files, relative to the summary's folder ("." or the mode) */
  const char* stopped;  /* "completed", "interrupted" (SIGINT), "window closed", "error" */
  double wall_s;        /* whole playback, screenshots included */
  uint32_t frame_count; /* frames played (committed) */
  /* the window: frames window_first .. window_first + window_count - 1 */
  play_frame* frames;
  play_object_stats* stats; /* window_count * object_count, frame by frame */
  uint32_t window_first, window_count, capacity;
  FILE* digests; /* every frame's play_digest, in order; NULL before play_trace_digests_open */
  double first_frame_ms;
  play_sums sums;
  play_resources samples[PLAY_MAX_SAMPLES];
  uint32_t sample_count;
  play_trace_files* files; /* open from play_trace_files_open to _close */
  /* vulkan: the device's stats when the mode ended (shader figures since the
   * device was made: the session's), and the validation messages counted
   * by then (the session's; the last mode's include the device's shutdown) */
  tlod_device_vk_stats vk;
  uint64_t validation_messages;
} play_trace;

/* A zeroed slot for the next frame (and object_count zeroed object
 * records) at the end of the window; NULL when out of memory. The window
 * must not be full (play_trace_window_full: flush first). */
play_frame* play_trace_add_frame(play_trace* t, play_object_stats** objects);
/* The file of the frames' digests: an unlinked temporary in folder dir. */
bool play_trace_digests_open(play_trace* t, const char* dir, char* error, size_t error_size);
/* The slot becomes frame frame_count: summed up, digested and counted;
 * false when the digest cannot be written (the error is in errno). */
bool play_trace_commit_frame(play_trace* t);
/* Reads field (offsetof(play_digest, x)) of every frame's digest into v
 * (frame_count doubles); false on a read error. */
bool play_trace_digest_field(const play_trace* t, size_t field, double* v);
bool play_trace_window_full(const play_trace* t);
/* Frames the window holds: PLAY_TRACE_WINDOW, fewer for large scenes (at
 * most PLAY_TRACE_WINDOW_RECORDS object records), at least 1. */
uint32_t play_trace_window_frames(const play_trace* t);
/* Objects with records in trace.json's frames: min(count, PLAY_TRACE_INLINE_OBJECTS). */
uint32_t play_trace_inline_objects(const play_trace* t);
void play_trace_free(play_trace* t);
/* The figures of one object in window frame i. */
const play_object_stats* play_trace_object(const play_trace* t, uint32_t i, uint32_t object);
void play_frame_totals_of(const play_trace* t, uint32_t i, play_frame_totals* out);

/* The trace files of a run in folder dir: trace.json, trace.csv and
 * chrome_trace.json, each an atomic file (a unique temporary renamed when
 * complete). open writes their heads, flush appends the window's frames and
 * empties it, close (keep: flush, write the tails and rename; otherwise
 * discard) ends them. False with one line in error ("cannot write
 * 'DIR/trace.json': No space left on device"); after a false flush or close
 * nothing is left of the three. */
bool play_trace_files_open(play_trace* t, const char* dir, char* error, size_t error_size);
bool play_trace_files_flush(play_trace* t, char* error, size_t error_size);
bool play_trace_files_close(play_trace* t, bool keep, char* error, size_t error_size);

/* Samples this process's memory (and with gl the live GL objects) into the
 * trace's next sample (until PLAY_MAX_SAMPLES). */
void play_resources_sample(play_trace* t, bool gl);

/* The summary of runs (one per mode) as JSON and as the text printed at the
 * end; status "ok", or "failed" with the first error of the run. */
typedef struct play_outcome {
  const char* status;                   /* "ok" or "failed" */
  const char* error;                    /* the first error, "" when ok */
  const struct play_serve_stats* serve; /* --serve: the server's counts (play_serve.h); NULL: none */
} play_outcome;
bool play_write_summary_json(const play_trace* const* runs, uint32_t run_count, const char* out_dir,
                             const play_outcome* outcome, const char* path, char* error, size_t error_size);
bool play_write_summary_text(const play_trace* const* runs, uint32_t run_count, const char* out_dir, const char* path,
                             char* error, size_t error_size);
void play_print_summary(FILE* f, const play_trace* const* runs, uint32_t run_count, const char* out_dir);

#endif
