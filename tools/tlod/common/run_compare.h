/* The comparison of two play runs (a baseline and a new run): the one
 * function behind `tlod compare` and the dashboard's comparison table, so
 * both show the same figures.
 *
 * WHAT IT DOES: over the frames both runs hold (the common prefix, see
 * frames below), computes per metric the baseline's and the new run's value,
 * their ratio new / base and the change in percent; checks two limits: frame
 * time p95 and mean triangles may grow by at most their percentage. Scene
 * and path must match; mode, backend and debug view may differ (the last
 * with a note: a debug view costs frame time).
 * DOES NOT: read files (the caller fills run_compare_side from its loaded
 * run, common/run_read.h), allocate beyond a scratch copy for sorting, or
 * print unless asked (run_compare_print, run_compare_json).
 * STEP BY STEP: fill two sides; run_compare(); if result.error[0], the runs
 * cannot be compared (scene or path differ, no frames); else print or show
 * the rows; result.regressions > 0 means a limit was passed.
 * THREADING: none; pure over the caller's arrays. */
#ifndef TLOD_TOOLS_RUN_COMPARE_H
#define TLOD_TOOLS_RUN_COMPARE_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "json_writer.h"
#include "run_read.h"

/* One run as the comparison sees it: views into the caller's per-frame
 * arrays (frames entries each, milliseconds and triangles as in
 * trace.csv). Strings are NUL-terminated; none may be NULL. */
typedef struct run_compare_side {
  const char* dir;        /* the run folder, for messages */
  const char* scene;      /* trace.json "scene" */
  const char* path;       /* trace.json "path" */
  const char* mode;       /* trace.json "mode" (may differ: adaptive vs uniform is a fair question) */
  const char* backend;    /* trace.json "backend" (may differ: gl vs vulkan) */
  const char* debug_view; /* trace.json "debug_view" (NULL or "" read as "none"); may differ, with a note */
  uint32_t frames;
  const double* frame_ms;
  const double* scheduler_ms;
  const double* backend_cpu_ms;
  const double* backend_wall_ms;
  const double* triangles; /* planned: pattern + strip triangles */
} run_compare_side;

/* The side of a loaded run (views into r, valid while r is). */
run_compare_side run_compare_side_of(const run* r);

/* Percentages the new run may be worse by; negative: not checked. */
typedef struct run_compare_limits {
  double max_p95_regression_pct;      /* frame_ms p95 */
  double max_triangle_regression_pct; /* triangles mean */
} run_compare_limits;

/* The defaults of `tlod compare`: p95 10% (frame times on a shared
 * machine vary by that much between identical runs), triangles 0% (they are
 * repeatable exactly: any growth is a change). */
run_compare_limits run_compare_default_limits(void);

enum { RUN_COMPARE_ROWS = 9 };

typedef struct run_compare_row {
  const char* metric; /* "frame_ms p95", "triangles mean", ... */
  const char* unit;   /* "ms" or "" */
  double base, value; /* baseline, new */
  double ratio;       /* value / base; 1 when both are 0, INFINITY when only base is 0 */
  double change_pct;  /* (ratio - 1) * 100 */
  double limit_pct;   /* the limit checked on this row, negative: none */
  bool regressed;     /* limit_pct >= 0 and change_pct > limit_pct */
} run_compare_row;

typedef struct run_compare_result {
  uint32_t frames; /* frames compared: the smaller count */
  bool prefix;     /* the runs hold different counts: only the first `frames` were compared */
  run_compare_row rows[RUN_COMPARE_ROWS];
  uint32_t regressions; /* rows regressed */
  char note[512];       /* "" or notes, one a line: only a prefix compared; the debug views differ */
  char error[512]; /* "" or why the runs cannot be compared ("NEW: scene 'x' differs from the baseline BASE's 'y'") */
} run_compare_result;

/* Compares base and next under limits into *out. Returns false (and
 * out->error set) when the runs cannot be compared: scene or path differ,
 * either has no frames, or out of memory for the sorting copy. */
bool run_compare(const run_compare_side* base, const run_compare_side* next, const run_compare_limits* limits,
                 run_compare_result* out);

/* The table `tlod compare` prints: one line per row (metric, baseline,
 * new, ratio, change, limit, "REGRESSION" when regressed), the note, then
 * one line per regression naming the metric, both values and the limit. */
void run_compare_print(FILE* f, const run_compare_side* base, const run_compare_side* next,
                       const run_compare_result* r);

/* The result as a JSON object under key (NULL inside an array):
 * {"frames", "prefix", "note", "regressions", "rows": [{"metric", "unit",
 * "base", "new", "ratio", "change_pct", "limit_pct", "regressed"}]}; a
 * ratio that is not finite is written as null. */
void run_compare_json(json_writer* w, const char* key, const run_compare_result* r);

#endif
