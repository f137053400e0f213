/* Reading a `tlod play` run folder back (docs/play.md "Output files",
 * docs/dashboard.md "Reading runs"): the dashboard and `tlod compare` use it.
 *
 * WHAT IT DOES: loads DIR/trace.json (schema tlod-play-trace/2) into a run:
 * the metadata, one array per trace.csv column (the frame totals, level
 * histogram and camera), each frame's screenshot path, and, from
 * DIR/objects.csv when present, every object's counts every frame.
 * A `--compare` parent folder (no trace.json, one sub-folder per mode with
 * one) expands into its mode runs, sorted by folder name.
 *
 * TOLERANT: a trace cut short (a run killed mid-write, a disk that filled)
 * loads every complete frame; run.truncated is set and run.truncated_reason
 * says "DIR/trace.json: truncated after frame N" (N the last complete frame,
 * -1 when none). Keys it does not know are skipped; a key of the wrong type
 * is an error naming it. The JSON reader is our own small C parser
 * (common/json_read.h): it keeps what it parsed before the end of the text,
 * which nlohmann's DOM parser throws away, and needs no C++ shim.
 *
 * REFUSED (run_read returns false, err holds one line):
 *   "DIR: not a run (no trace.json)"
 *   "DIR/trace.json: schema 'x' is not tlod-play-trace/2"
 *   "DIR/trace.json: <key>: <problem>"   (wrong type, bad value)
 *   "DIR/trace.json: <problem>"          (not JSON, not an object, too big)
 * Bounds: trace.json at most RUN_READ_MAX_BYTES, nesting at most 64 deep;
 * objects.csv is read only while objects x frames x columns stays under
 * RUN_READ_MAX_OBJECT_VALUES (else run.object_counts is NULL and
 * run.object_counts_note says why).
 *
 * THREADING: no global state; runs are independent. */
#ifndef TLOD_TOOLS_RUN_READ_H
#define TLOD_TOOLS_RUN_READ_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define RUN_TRACE_SCHEMA "tlod-play-trace/2"
#define RUN_LEVELS 11
#define RUN_READ_MAX_BYTES (1024u * 1024u * 1024u)
#define RUN_READ_MAX_OBJECT_VALUES (16u * 1024u * 1024u)

/* The columns of trace.csv, in its order (run_column_name gives the header). */
typedef enum run_column {
  RUN_COL_FRAME,
  RUN_COL_TIME_S,
  RUN_COL_FRAME_MS,
  RUN_COL_SCHEDULER_MS,
  RUN_COL_SILHOUETTE_MS,
  RUN_COL_METRIC_MS,
  RUN_COL_LEVELS_MS,
  RUN_COL_MORPH_MS,
  RUN_COL_STRIPS_MS,
  RUN_COL_BACKEND_CPU_MS,
  RUN_COL_BACKEND_GPU_MS, /* -1: no GPU result that frame */
  RUN_COL_BACKEND_WALL_MS,
  RUN_COL_SCREENSHOT_MS,
  RUN_COL_PATCHES,
  RUN_COL_VISIBLE,
  RUN_COL_CULLED,
  RUN_COL_STRIPS,
  RUN_COL_PATTERN_TRIANGLES,
  RUN_COL_STRIP_TRIANGLES,
  RUN_COL_TRIANGLES,
  RUN_COL_DRAWN_TRIANGLES,
  RUN_COL_DRAW_CALLS,
  RUN_COL_EFFECTIVE_EPSILON,
  RUN_COL_LEVEL_0, /* RUN_COL_LEVEL_0 + l: visible patches at level l, l < RUN_LEVELS */
  RUN_COL_EYE_X = RUN_COL_LEVEL_0 + RUN_LEVELS,
  RUN_COL_EYE_Y,
  RUN_COL_EYE_Z,
  RUN_COL_TARGET_X,
  RUN_COL_TARGET_Y,
  RUN_COL_TARGET_Z,
  RUN_COL_FOVY,
  RUN_COL_ANIM_MS, /* trace.json only (not a trace.csv column) */
  RUN_COLUMN_COUNT
} run_column;

/* The trace.csv header name of c ("frame_ms", "level_3", ...; "anim_ms"). */
const char* run_column_name(run_column c);

/* The columns of objects.csv after `frame,object`, in its order. */
typedef enum run_object_column {
  RUN_OBJ_PATCHES,
  RUN_OBJ_VISIBLE,
  RUN_OBJ_CULLED,
  RUN_OBJ_STRIPS,
  RUN_OBJ_PATTERN_TRIANGLES,
  RUN_OBJ_STRIP_TRIANGLES,
  RUN_OBJ_TRIANGLES,
  RUN_OBJ_DRAWN_TRIANGLES,
  RUN_OBJ_DRAW_CALLS,
  RUN_OBJ_SCHEDULER_MS,
  RUN_OBJ_BACKEND_WALL_MS,
  RUN_OBJECT_COLUMN_COUNT
} run_object_column;

const char* run_object_column_name(run_object_column c);

typedef struct run_object {
  char* name;
  char* source;
  int64_t vertices, faces, patches;
} run_object;

/* Strings are never NULL ("" when trace.json lacks the key). */
typedef struct run_meta {
  char* schema;
  char* tool;
  char* scene;
  char* path;
  char* mode;
  char* backend;
  char* renderer;
  char* surface;
  char* policy;
  char* stopped;    /* "completed", "interrupted", ...; "" when truncated */
  char* debug_view; /* `tlod play --debug-view`; "" none */
  char* field;      /* `tlod play --field` in one line ("temperature [K] 0..250 viridis"); "" none */
  double epsilon_px, fps, path_duration_s, wall_s;
  int64_t max_level, scene_budget, width, height, screenshot_every;
  int64_t frames_requested, frames_completed; /* -1 when absent */
} run_meta;

typedef struct run {
  char* dir;   /* the folder read, as given (a mode run: PARENT/MODE) */
  char* label; /* short name for tables and legends: the mode, or dir's last part */
  run_meta meta;
  size_t object_count;
  run_object* objects;
  size_t frame_count;               /* complete frames read */
  double* column[RUN_COLUMN_COUNT]; /* column[c][i], frame i; NULL when frame_count is 0 */
  char** screenshot;                /* screenshot[i]: relative to dir, "" none */
  /* objects.csv: [(frame * object_count + object) * RUN_OBJECT_COLUMN_COUNT + col];
   * NULL when absent, unreadable or too big (object_counts_note says which). */
  double* object_counts;
  char* object_counts_note;
  bool truncated;
  char* truncated_reason; /* "DIR/trace.json: truncated after frame N"; NULL when not */
} run;

/* Reads the run in dir (not a --compare parent). False with a one-line
 * message in err (err_size > 0) and *out zeroed; on success free with run_free. */
bool run_read(const char* dir, run* out, char* err, size_t err_size);
/* The same on trace.json's text (name: how messages call the file; objects.csv
 * not read): the fuzz target's entry. */
bool run_read_trace_text(const char* name, const char* text, size_t size, run* out, char* err, size_t err_size);
/* Frees what run_read allocated; a zeroed run is fine. */
void run_free(run* r);

typedef struct run_set {
  size_t count;
  run* runs;
} run_set;

/* Reads every folder in dirs, expanding --compare parents; false at the first
 * error (message in err, nothing kept). Truncated runs load (see above). */
bool run_set_read(const char* const* dirs, size_t dir_count, run_set* out, char* err, size_t err_size);
void run_set_free(run_set* s);

#endif
