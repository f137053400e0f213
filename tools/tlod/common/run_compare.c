/* Two play runs compared metric by metric (run_compare.h). Frame-time
 * percentiles come from common/distribution.h, as the play summary's do, so
 * a run compared with itself shows its summary's figures. */
#include "run_compare.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "distribution.h"

run_compare_limits run_compare_default_limits(void) {
  return (run_compare_limits){.max_p95_regression_pct = 10.0, .max_triangle_regression_pct = 0.0};
}

run_compare_side run_compare_side_of(const run* r) {
  return (run_compare_side){.dir = r->dir,
                            .scene = r->meta.scene,
                            .path = r->meta.path,
                            .mode = r->meta.mode,
                            .backend = r->meta.backend,
                            .debug_view = r->meta.debug_view,
                            .frames = (uint32_t)r->frame_count,
                            .frame_ms = r->column[RUN_COL_FRAME_MS],
                            .scheduler_ms = r->column[RUN_COL_SCHEDULER_MS],
                            .backend_cpu_ms = r->column[RUN_COL_BACKEND_CPU_MS],
                            .backend_wall_ms = r->column[RUN_COL_BACKEND_WALL_MS],
                            .triangles = r->column[RUN_COL_TRIANGLES]};
}

static double mean(const double* v, uint32_t n) {
  double s = 0.0;
  for (uint32_t i = 0; i < n; i++)
    s += v[i];
  return s / n;
}

/* The distribution of the first n values of v, on a sorted copy. */
static bool distribution_of(const double* v, uint32_t n, distribution* out) {
  double* sorted = malloc((size_t)n * sizeof(double));
  if (!sorted) return false;
  memcpy(sorted, v, (size_t)n * sizeof(double));
  *out = distribution_sort(sorted, n);
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

static const char* view_name(const char* v) { return v && v[0] ? v : "none"; }

/* A prefix compared; a debug view drawn in one run only (wireframe adds a
 * line pass: its frame times are not the shaded run's). */
static void notes(const run_compare_side* a, const run_compare_side* b, run_compare_result* out) {
  out->prefix = a->frames != b->frames;
  size_t at = 0;
  if (out->prefix)
    at = (size_t)snprintf(out->note, sizeof(out->note),
                          "note: the baseline holds %u frames and the new run %u: compared frames 0..%u\n", a->frames,
                          b->frames, out->frames - 1);
  if (strcmp(view_name(a->debug_view), view_name(b->debug_view)))
    snprintf(out->note + at, sizeof(out->note) - at,
             "note: debug views differ (baseline %s, new %s): frame times include the view's cost\n",
             view_name(a->debug_view), view_name(b->debug_view));
}

bool run_compare(const run_compare_side* base, const run_compare_side* next, const run_compare_limits* limits,
                 run_compare_result* out) {
  *out = (run_compare_result){0};
  if (mismatch(base, next, out)) return false;
  uint32_t n = base->frames < next->frames ? base->frames : next->frames;
  out->frames = n;
  notes(base, next, out);
  distribution a, b;
  if (!distribution_of(base->frame_ms, n, &a) || !distribution_of(next->frame_ms, n, &b)) {
    snprintf(out->error, sizeof(out->error), "out of memory sorting %u frame times", n);
    return false;
  }
  double p95 = limits->max_p95_regression_pct, tri = limits->max_triangle_regression_pct;
  run_compare_row* r = out->rows;
  r[0] = row("frame_ms p50", "ms", a.p50, b.p50, -1.0);
  r[1] = row("frame_ms p95", "ms", a.p95, b.p95, p95);
  r[2] = row("frame_ms p99", "ms", a.p99, b.p99, -1.0);
  r[3] = row("frame_ms max", "ms", a.max, b.max, -1.0);
  r[4] = row("frame_ms mean", "ms", a.mean, b.mean, -1.0);
  r[5] = row("scheduler_ms mean", "ms", mean(base->scheduler_ms, n), mean(next->scheduler_ms, n), -1.0);
  r[6] = row("backend_cpu_ms mean", "ms", mean(base->backend_cpu_ms, n), mean(next->backend_cpu_ms, n), -1.0);
  r[7] = row("backend_wall_ms mean", "ms", mean(base->backend_wall_ms, n), mean(next->backend_wall_ms, n), -1.0);
  r[8] = row("triangles mean", "", mean(base->triangles, n), mean(next->triangles, n), tri);
  for (int i = 0; i < RUN_COMPARE_ROWS; i++)
    out->regressions += r[i].regressed;
  return true;
}
