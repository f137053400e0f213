/* objects.csv into run.object_counts (run_read.h): optional, so any problem
 * leaves the counts out with a note instead of failing the run. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "run_read_internal.h"

static const char* const object_column_names[RUN_OBJECT_COLUMN_COUNT] = {
    "patches",   "visible",         "culled",     "strips",       "pattern_triangles", "strip_triangles",
    "triangles", "drawn_triangles", "draw_calls", "scheduler_ms", "backend_wall_ms"};

const char* run_object_column_name(run_object_column c) {
  return c >= 0 && c < RUN_OBJECT_COLUMN_COUNT ? object_column_names[c] : "";
}

static bool header_ok(const char* line) {
  char want[512] = "frame,object";
  for (int c = 0; c < RUN_OBJECT_COLUMN_COUNT; c++)
    strcat(strcat(want, ","), object_column_names[c]);
  return !strncmp(line, want, strlen(want)) && strchr("\r\n", line[strlen(want)]);
}

/* One data row into counts; false when it is malformed or out of range. */
static bool parse_row(char* line, run* r, double* counts) {
  double v[2 + RUN_OBJECT_COLUMN_COUNT];
  char* p = line;
  for (int i = 0; i < 2 + RUN_OBJECT_COLUMN_COUNT; i++) {
    char* end;
    v[i] = strtod(p, &end);
    if (end == p || (*end != (i + 1 < 2 + RUN_OBJECT_COLUMN_COUNT ? ',' : *end))) return false;
    p = end + 1;
  }
  if (!(v[0] >= 0 && v[1] >= 0 && v[1] < (double)r->object_count)) return false;
  if (v[0] >= (double)r->frame_count) return true; /* past a truncated trace's frames */
  double* dst = counts + ((size_t)v[0] * r->object_count + (size_t)v[1]) * RUN_OBJECT_COLUMN_COUNT;
  memcpy(dst, v + 2, sizeof(double) * RUN_OBJECT_COLUMN_COUNT);
  return true;
}

static void note(run* r, const char* what) {
  char line[1200];
  snprintf(line, sizeof line, "%s/objects.csv: %s", r->dir, what);
  free(r->object_counts_note);
  r->object_counts_note = run_strdup(line);
}

static bool read_rows(FILE* f, run* r, double* counts) {
  char line[1024];
  if (!fgets(line, sizeof line, f) || !header_ok(line)) return note(r, "unexpected header"), false;
  for (long n = 2; fgets(line, sizeof line, f); n++) {
    if (!parse_row(line, r, counts)) {
      char what[64];
      snprintf(what, sizeof what, "line %ld: not a row of counts", n);
      return note(r, what), false;
    }
  }
  return true;
}

void run_read_object_counts(run* r) {
  size_t cells = r->frame_count * r->object_count;
  if (!cells) return;
  if (cells > RUN_READ_MAX_OBJECT_VALUES / RUN_OBJECT_COLUMN_COUNT) return note(r, "too many objects x frames to load");
  size_t n = strlen(r->dir) + 16;
  char* path = malloc(n);
  FILE* f = path ? (snprintf(path, n, "%s/objects.csv", r->dir), fopen(path, "r")) : NULL;
  free(path);
  if (!f) return note(r, "absent");
  double* counts = malloc(cells * RUN_OBJECT_COLUMN_COUNT * sizeof *counts);
  for (size_t i = 0; counts && i < cells * RUN_OBJECT_COLUMN_COUNT; i++)
    counts[i] = NAN;
  if (counts && read_rows(f, r, counts))
    r->object_counts = counts;
  else
    free(counts);
  if (!counts) note(r, "out of memory");
  fclose(f);
}
