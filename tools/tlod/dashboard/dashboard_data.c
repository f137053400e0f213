/* The page's JSON island (dashboard_data.h). */
#include "dashboard_data.h"

#include <stdlib.h>
#include <string.h>

#include "common/json_writer.h"
#include "common/run_compare.h"

/* Objects with their own chart line: more would not be readable. */
enum { DASHBOARD_OBJECT_LINES = 16 };

static void write_meta(json_writer* w, const run_meta* m) {
  const char* names[] = {"schema",   "tool",    "scene",  "path",    "mode",       "backend",
                         "renderer", "surface", "policy", "stopped", "debug_view", "field"};
  const char* values[] = {m->schema,   m->tool,    m->scene,  m->path,    m->mode,       m->backend,
                          m->renderer, m->surface, m->policy, m->stopped, m->debug_view, m->field};
  json_object_begin(w, "meta");
  for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
    json_string(w, names[i], values[i]);
  json_number(w, "epsilon_px", m->epsilon_px);
  json_number(w, "fps", m->fps);
  json_number(w, "wall_s", m->wall_s);
  json_int(w, "scene_budget", m->scene_budget);
  json_int(w, "width", m->width);
  json_int(w, "height", m->height);
  json_int(w, "frames_requested", m->frames_requested);
  json_int(w, "frames_completed", m->frames_completed);
  json_object_end(w);
}

static void write_numbers(json_writer* w, const char* key, const double* v, size_t n, size_t stride) {
  json_array_begin(w, key);
  for (size_t i = 0; i < n; i++)
    json_number(w, NULL, v[i * stride]);
  json_array_end(w);
}

static void write_columns(json_writer* w, const run* r) {
  json_object_begin(w, "columns");
  for (int c = 0; c < RUN_COLUMN_COUNT; c++)
    write_numbers(w, run_column_name(c), r->column[c], r->frame_count, 1);
  json_object_end(w);
}

/* Triangles per object and frame, the first DASHBOARD_OBJECT_LINES objects. */
static void write_objects(json_writer* w, const run* r) {
  json_array_begin(w, "objects");
  for (size_t i = 0; i < r->object_count; i++)
    json_string(w, NULL, r->objects[i].name);
  json_array_end(w);
  json_array_begin(w, "object_triangles");
  size_t lines = r->object_counts && r->object_count > 1 ? r->object_count : 0,
         stride = r->object_count * RUN_OBJECT_COLUMN_COUNT;
  for (size_t i = 0; i < lines && i < DASHBOARD_OBJECT_LINES; i++)
    write_numbers(w, NULL, r->object_counts + i * RUN_OBJECT_COLUMN_COUNT + RUN_OBJ_TRIANGLES, r->frame_count, stride);
  json_array_end(w);
}

static void write_screenshots(json_writer* w, const run* r, size_t* budget) {
  size_t omitted = 0;
  json_object_begin(w, "screenshots");
  for (size_t i = 0; i < r->frame_count; i++) {
    if (!r->screenshot[i][0]) continue;
    char* uri = dashboard_shot_uri(r->dir, r->screenshot[i], budget);
    char key[32];
    snprintf(key, sizeof key, "%.0f", r->column[RUN_COL_FRAME][i]);
    if (uri)
      json_string(w, key, uri);
    else
      omitted++;
    free(uri);
  }
  json_object_end(w);
  json_uint(w, "screenshots_omitted", omitted);
}

static void write_run(json_writer* w, const run* r, size_t* budget) {
  json_object_begin(w, NULL);
  json_string(w, "label", r->label);
  json_string(w, "dir", r->dir);
  json_string(w, "truncated", r->truncated_reason ? r->truncated_reason : "");
  json_string(w, "object_counts_note", r->object_counts_note ? r->object_counts_note : "");
  write_meta(w, &r->meta);
  write_objects(w, r);
  write_columns(w, r);
  write_screenshots(w, r, budget);
  json_object_end(w);
}

/* Every run against the first, as `tlod compare` computes it. */
static void write_comparisons(json_writer* w, const run_set* s) {
  json_array_begin(w, "comparisons");
  run_compare_limits limits = run_compare_default_limits();
  for (size_t i = 1; i < s->count; i++) {
    run_compare_side base = run_compare_side_of(&s->runs[0]), next = run_compare_side_of(&s->runs[i]);
    run_compare_result result;
    bool ok = run_compare(&base, &next, &limits, &result);
    json_object_begin(w, NULL);
    json_uint(w, "base", 0);
    json_uint(w, "run", i);
    json_string(w, "error", ok ? "" : result.error);
    if (ok) run_compare_json(w, "result", &result);
    json_object_end(w);
  }
  json_array_end(w);
}

bool dashboard_data_write(FILE* f, const run_set* runs, const dashboard_page_options* opt, char* err, size_t n) {
  json_writer w;
  size_t budget = opt->screenshot_bytes ? opt->screenshot_bytes : DASHBOARD_SCREENSHOT_BYTES;
  json_begin(&w, f);
  json_object_begin(&w, NULL);
  json_object_begin(&w, "config");
  json_string(&w, "title", opt->title ? opt->title : "tesslod dashboard");
  json_string(&w, "live", opt->live ? opt->live : "");
  json_object_end(&w);
  json_array_begin(&w, "runs");
  for (size_t i = 0; runs && i < runs->count; i++)
    write_run(&w, &runs->runs[i], &budget);
  json_array_end(&w);
  if (runs) write_comparisons(&w, runs);
  json_object_end(&w);
  return json_end(&w) ? true : (snprintf(err, n, "page: write failed"), false);
}
