/* The comparison of two runs as a text table (tlod compare) and as JSON
 * (the dashboard's table), from one run_compare_result. */
#include <math.h>

#include "run_compare.h"

static void print_limit(FILE* f, const run_compare_row* r) {
  if (r->limit_pct >= 0.0)
    fprintf(f, "  %+6.1f%%", r->limit_pct);
  else
    fprintf(f, "  %7s", "-");
}

static void print_row(FILE* f, const run_compare_row* r) {
  fprintf(f, "%-22s %12.3f %12.3f %8.3f %+8.1f%%", r->metric, r->base, r->value, r->ratio, r->change_pct);
  print_limit(f, r);
  fprintf(f, "%s\n", r->regressed ? "  REGRESSION" : "");
}

void run_compare_print(FILE* f, const run_compare_side* base, const run_compare_side* next,
                       const run_compare_result* r) {
  fprintf(f, "baseline: %s (%s, %s, %u frames)\n", base->dir, base->mode, base->backend, base->frames);
  fprintf(f, "new:      %s (%s, %s, %u frames)\n", next->dir, next->mode, next->backend, next->frames);
  fprintf(f, "scene %s, path %s, %u frames compared\n\n", base->scene, base->path, r->frames);
  fprintf(f, "%-22s %12s %12s %8s %9s  %7s\n", "metric", "baseline", "new", "ratio", "change", "limit");
  for (int i = 0; i < RUN_COMPARE_ROWS; i++)
    print_row(f, &r->rows[i]);
  if (r->note[0]) fprintf(f, "\n%s", r->note);
  for (int i = 0; i < RUN_COMPARE_ROWS; i++) {
    const run_compare_row* x = &r->rows[i];
    if (x->regressed)
      fprintf(f, "regression: %s %.3f%s -> %.3f%s (%+.1f%%, limit %+.1f%%)\n", x->metric, x->base, x->unit, x->value,
              x->unit, x->change_pct, x->limit_pct);
  }
}

void run_compare_json(json_writer* w, const char* key, const run_compare_result* r) {
  json_object_begin(w, key);
  json_uint(w, "frames", r->frames);
  json_bool(w, "prefix", r->prefix);
  json_string(w, "note", r->note);
  json_uint(w, "regressions", r->regressions);
  json_array_begin(w, "rows");
  for (int i = 0; i < RUN_COMPARE_ROWS; i++) {
    const run_compare_row* x = &r->rows[i];
    json_object_begin(w, NULL);
    json_string(w, "metric", x->metric);
    json_string(w, "unit", x->unit);
    json_number(w, "base", x->base);
    json_number(w, "new", x->value);
    json_number(w, "ratio", x->ratio);
    json_number(w, "change_pct", x->change_pct);
    json_number(w, "limit_pct", x->limit_pct);
    json_bool(w, "regressed", x->regressed);
    json_object_end(w);
  }
  json_array_end(w);
  json_object_end(w);
}
