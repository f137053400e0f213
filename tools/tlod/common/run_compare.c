/* Two play runs compared metric by metric (run_compare.h). Percentiles use
 * the nearest rank, as the play summary does (docs/play.md), so a run
 * compared with itself shows its summary's figures. */
#include "run_compare.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

run_compare_limits run_compare_default_limits(void) {
  return (run_compare_limits){.max_p95_regression_pct = 10.0, .max_triangle_regression_pct = 0.0};
}

run_compare_side run_compare_side_of(const run* r) {
  return (run_compare_side){.dir = r->dir,
                            .scene = r->meta.scene,
                            .path = r->meta.path,
                            .mode = r->meta.mode,
                            .backend = r->meta.backend,
                            .frames = (uint32_t)r->frame_count,
                            .frame_ms = r->column[RUN_COL_FRAME_MS],
                            .scheduler_ms = r->column[RUN_COL_SCHEDULER_MS],
                            .backend_cpu_ms = r->column[RUN_COL_BACKEND_CPU_MS],
                            .backend_wall_ms = r->column[RUN_COL_BACKEND_WALL_MS],
                            .triangles = r->column[RUN_COL_TRIANGLES]};
}

static int compare_doubles(const void* a, const void* b) {
  double x = *(const double*)a, y = *(const double*)b;
  return (x > y) - (x < y);
}

/* Nearest rank: the value at position ceil(p/100 * n) of sorted (1-based). */
static double nearest_rank(const double* sorted, uint32_t n, double p) {
  double rank = ceil(p / 100.0 * n);
  uint32_t k = rank < 1.0 ? 1 : (uint32_t)rank;
  return sorted[(k > n ? n : k) - 1];
}

static double mean(const double* v, uint32_t n) {
  double s = 0.0;
  for (uint32_t i = 0; i < n; i++)
    s += v[i];
  return s / n;
}

/* p50, p95, p99, max, mean of the first n frame times into out[5]. */
static bool frame_stats(const double* v, uint32_t n, double out[5]) {
  double* sorted = malloc((size_t)n * sizeof(double));
  if (!sorted) return false;
  memcpy(sorted, v, (size_t)n * sizeof(double));
  qsort(sorted, n, sizeof(double), compare_doubles);
  out[0] = nearest_rank(sorted, n, 50.0);
  out[1] = nearest_rank(sorted, n, 95.0);
  out[2] = nearest_rank(sorted, n, 99.0);
  out[3] = sorted[n - 1];
  out[4] = mean(v, n);
  free(sorted);
  return true;
}

static run_compare_row row(const char* metric, const char* unit, double base, double value, double limit_pct) {
  run_compare_row r = {.metric = metric, .unit = unit, .base = base, .value = value, .limit_pct = limit_pct};
  if (base != 0.0)
    r.ratio = value / base;
  else
    r.ratio = value == 0.0 ? 1.0 : INFINITY;
  r.change_pct = (r.ratio - 1.0) * 100.0;
  r.regressed = limit_pct >= 0.0 && r.change_pct > limit_pct;
  return r;
}

/* Why the runs cannot be compared, into out->error; false when they can. */
static bool mismatch(const run_compare_side* a, const run_compare_side* b, run_compare_result* out) {
  if (strcmp(a->scene, b->scene))
    snprintf(out->error, sizeof(out->error), "%s: scene '%s' differs from the baseline %s's '%s'", b->dir, b->scene,
             a->dir, a->scene);
  else if (strcmp(a->path, b->path))
    snprintf(out->error, sizeof(out->error), "%s: camera path '%s' differs from the baseline %s's '%s'", b->dir,
             b->path, a->dir, a->path);
  else if (!a->frames || !b->frames)
    snprintf(out->error, sizeof(out->error), "%s: no frames to compare", a->frames ? b->dir : a->dir);
  return out->error[0] != 0;
}

static void note_prefix(const run_compare_side* a, const run_compare_side* b, run_compare_result* out) {
  out->prefix = a->frames != b->frames;
  if (out->prefix)
    snprintf(out->note, sizeof(out->note),
             "note: the baseline holds %u frames and the new run %u: compared frames 0..%u", a->frames, b->frames,
             out->frames - 1);
}

bool run_compare(const run_compare_side* base, const run_compare_side* next, const run_compare_limits* limits,
                 run_compare_result* out) {
  *out = (run_compare_result){0};
  if (mismatch(base, next, out)) return false;
  uint32_t n = base->frames < next->frames ? base->frames : next->frames;
  out->frames = n;
  note_prefix(base, next, out);
  double a[5], b[5];
  if (!frame_stats(base->frame_ms, n, a) || !frame_stats(next->frame_ms, n, b)) {
    snprintf(out->error, sizeof(out->error), "out of memory sorting %u frame times", n);
    return false;
  }
  double p95 = limits->max_p95_regression_pct, tri = limits->max_triangle_regression_pct;
  run_compare_row* r = out->rows;
  r[0] = row("frame_ms p50", "ms", a[0], b[0], -1.0);
  r[1] = row("frame_ms p95", "ms", a[1], b[1], p95);
  r[2] = row("frame_ms p99", "ms", a[2], b[2], -1.0);
  r[3] = row("frame_ms max", "ms", a[3], b[3], -1.0);
  r[4] = row("frame_ms mean", "ms", a[4], b[4], -1.0);
  r[5] = row("scheduler_ms mean", "ms", mean(base->scheduler_ms, n), mean(next->scheduler_ms, n), -1.0);
  r[6] = row("backend_cpu_ms mean", "ms", mean(base->backend_cpu_ms, n), mean(next->backend_cpu_ms, n), -1.0);
  r[7] = row("backend_wall_ms mean", "ms", mean(base->backend_wall_ms, n), mean(next->backend_wall_ms, n), -1.0);
  r[8] = row("triangles mean", "", mean(base->triangles, n), mean(next->triangles, n), tri);
  for (int i = 0; i < RUN_COMPARE_ROWS; i++)
    out->regressions += r[i].regressed;
  return true;
}
