/* tlod compare -- a baseline run against a new run, for CI: a table and an
 * exit code (docs/play.md "tlod compare"). The figures come from
 * common/run_compare.h, which the dashboard shows too. */
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "commands.h"
#include "common/run_compare.h"
#include "common/run_read.h"

/* Exit codes beside CLI_OK and CLI_USAGE: 1 is a regression, so a run
 * that cannot be compared (not a run, another scene or path) gets its own
 * code and a CI log tells the two apart. */
enum { COMPARE_REGRESSION = 1, COMPARE_CANNOT = 3 };

void compare_usage(FILE* f) {
  fprintf(f, "usage: tlod compare BASELINE_RUN NEW_RUN [--max-p95-regression PCT] [--max-triangle-regression PCT]\n"
             "Compares two tlod play run folders (same scene and camera path) over the frames both hold:\n"
             "frame time p50/p95/p99/max/mean, scheduler and backend means, mean triangles, with ratios.\n"
             "  --max-p95-regression PCT       frame_ms p95 may grow by at most PCT percent (default 10)\n"
             "  --max-triangle-regression PCT  mean triangles may grow by at most PCT percent (default 0)\n"
             "Exit: 0 within the limits, 1 a regression (named on stdout), 2 bad usage,\n"
             "3 the runs cannot be compared (not a run, scene or path differ).\n");
}

typedef struct compare_options {
  const char* dirs[2];
  int dir_count;
  run_compare_limits limits;
} compare_options;

static int parse_limit(const char* option, const char* v, double* out) {
  float pct = 0.0f;
  if (!v || !cli_parse_float(option, v, 0.0, 1e6, &pct)) return CLI_USAGE;
  *out = pct;
  return CLI_OK;
}

static int parse_argument(int argc, char** argv, int* i, compare_options* o) {
  const char* a = argv[*i];
  if (!strcmp(a, "--max-p95-regression"))
    return parse_limit(a, cli_value(argc, argv, i), &o->limits.max_p95_regression_pct);
  if (!strcmp(a, "--max-triangle-regression"))
    return parse_limit(a, cli_value(argc, argv, i), &o->limits.max_triangle_regression_pct);
  if (a[0] == '-' && a[1]) return cli_error(CLI_USAGE, "compare: unknown option '%s' (see tlod compare --help)", a);
  if (o->dir_count == 2) return cli_error(CLI_USAGE, "compare: unexpected argument '%s' (two runs: BASELINE NEW)", a);
  o->dirs[o->dir_count++] = a;
  return CLI_OK;
}

static int parse(int argc, char** argv, compare_options* o) {
  *o = (compare_options){.limits = run_compare_default_limits()};
  for (int i = 0; i < argc; i++) {
    if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) {
      compare_usage(stdout);
      exit(0);
    }
    int rc = parse_argument(argc, argv, &i, o);
    if (rc != CLI_OK) return rc;
  }
  if (o->dir_count != 2)
    return cli_error(CLI_USAGE, "compare: expected BASELINE_RUN and NEW_RUN (see tlod compare --help)");
  return CLI_OK;
}

/* One run folder into *out; a --compare parent (several modes) is refused
 * naming its modes' folders, since which of them is meant is a guess. */
static int load(const char* dir, run_set* set, const run** out) {
  char err[1024];
  if (!run_set_read(&dir, 1, set, err, sizeof(err))) return cli_error(COMPARE_CANNOT, "%s", err);
  if (set->count != 1)
    return cli_error(COMPARE_CANNOT, "%s: a --compare folder of %zu modes: name one of them (e.g. %s)", dir, set->count,
                     set->runs[0].dir);
  *out = &set->runs[0];
  if ((*out)->truncated)
    fprintf(stderr, "tlod: warning: %s (comparing the frames it holds)\n", (*out)->truncated_reason);
  return CLI_OK;
}

static int compare(const run* a, const run* b, const run_compare_limits* limits) {
  run_compare_side sa = run_compare_side_of(a), sb = run_compare_side_of(b);
  run_compare_result r;
  if (!run_compare(&sa, &sb, limits, &r)) return cli_error(COMPARE_CANNOT, "%s", r.error);
  run_compare_print(stdout, &sa, &sb, &r);
  return r.regressions ? COMPARE_REGRESSION : CLI_OK;
}

int cmd_compare(int argc, char** argv) {
  compare_options o;
  int rc = parse(argc, argv, &o);
  if (rc != CLI_OK) return rc;
  run_set sets[2] = {{0}, {0}};
  const run* runs[2] = {NULL, NULL};
  rc = load(o.dirs[0], &sets[0], &runs[0]);
  if (rc == CLI_OK) rc = load(o.dirs[1], &sets[1], &runs[1]);
  if (rc == CLI_OK) rc = compare(runs[0], runs[1], &o.limits);
  run_set_free(&sets[0]);
  run_set_free(&sets[1]);
  return rc;
}
