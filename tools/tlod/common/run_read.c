/* Reading trace.json into a run (run_read.h): metadata, then the frames,
 * each frame's keys into the column arrays. */
#include "run_read.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "json_read.h"
#include "run_read_internal.h"

static const char* const column_names[RUN_COLUMN_COUNT] = {"frame",
                                                           "time_s",
                                                           "frame_ms",
                                                           "scheduler_ms",
                                                           "silhouette_ms",
                                                           "metric_ms",
                                                           "levels_ms",
                                                           "morph_ms",
                                                           "strips_ms",
                                                           "backend_cpu_ms",
                                                           "backend_gpu_ms",
                                                           "backend_wall_ms",
                                                           "screenshot_ms",
                                                           "patches",
                                                           "visible",
                                                           "culled",
                                                           "strips",
                                                           "pattern_triangles",
                                                           "strip_triangles",
                                                           "triangles",
                                                           "drawn_triangles",
                                                           "draw_calls",
                                                           "effective_epsilon",
                                                           "level_0",
                                                           "level_1",
                                                           "level_2",
                                                           "level_3",
                                                           "level_4",
                                                           "level_5",
                                                           "level_6",
                                                           "level_7",
                                                           "level_8",
                                                           "level_9",
                                                           "level_10",
                                                           "eye_x",
                                                           "eye_y",
                                                           "eye_z",
                                                           "target_x",
                                                           "target_y",
                                                           "target_z",
                                                           "fovy",
                                                           "anim_ms"};

const char* run_column_name(run_column c) { return c >= 0 && c < RUN_COLUMN_COUNT ? column_names[c] : ""; }

bool run_fail(char* err, size_t err_size, const char* fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(err, err_size, fmt, ap);
  va_end(ap);
  return false;
}

char* run_strdup(const char* s) {
  size_t n = strlen(s) + 1;
  char* d = malloc(n);
  return d ? memcpy(d, s, n) : NULL;
}

/* key of obj as a string into *out ("" when absent). */
static bool get_string(const json_value* obj, const char* key, char** out, const char* name, char* err,
                       size_t err_size) {
  const json_value* v = json_get(obj, key);
  if (v && v->type != JSON_STRING) return run_fail(err, err_size, "%s: %s: not a string", name, key);
  *out = run_strdup(v ? v->string : "");
  return *out ? true : run_fail(err, err_size, "%s: out of memory", name);
}

/* key of obj as a number into *out (fallback when absent or null). */
static bool get_number(const json_value* obj, const char* key, double fallback, double* out, const char* name,
                       char* err, size_t err_size) {
  const json_value* v = json_get(obj, key);
  *out = fallback;
  if (!v || v->type == JSON_NULL) return true;
  if (v->type != JSON_NUMBER) return run_fail(err, err_size, "%s: %s: not a number", name, key);
  *out = v->number;
  return true;
}

static bool get_int(const json_value* obj, const char* key, int64_t fallback, int64_t* out, const char* name, char* err,
                    size_t err_size) {
  double d;
  if (!get_number(obj, key, (double)fallback, &d, name, err, err_size)) return false;
  if (!(d >= -9e15 && d <= 9e15) || d != floor(d)) return run_fail(err, err_size, "%s: %s: not an integer", name, key);
  *out = (int64_t)d;
  return true;
}

static bool read_meta_strings(const json_value* root, run_meta* m, const char* name, char* err, size_t n) {
  return get_string(root, "tool", &m->tool, name, err, n) && get_string(root, "scene", &m->scene, name, err, n) &&
         get_string(root, "path", &m->path, name, err, n) && get_string(root, "mode", &m->mode, name, err, n) &&
         get_string(root, "backend", &m->backend, name, err, n) &&
         get_string(root, "renderer", &m->renderer, name, err, n) &&
         get_string(root, "surface", &m->surface, name, err, n) &&
         get_string(root, "policy", &m->policy, name, err, n) &&
         get_string(root, "stopped", &m->stopped, name, err, n) &&
         get_string(root, "debug_view", &m->debug_view, name, err, n) &&
         get_string(root, "field", &m->field, name, err, n);
}

static bool read_meta_numbers(const json_value* root, run_meta* m, const char* name, char* err, size_t n) {
  return get_number(root, "epsilon_px", 0, &m->epsilon_px, name, err, n) &&
         get_number(root, "fps", 0, &m->fps, name, err, n) &&
         get_number(root, "path_duration_s", 0, &m->path_duration_s, name, err, n) &&
         get_number(root, "wall_s", 0, &m->wall_s, name, err, n) &&
         get_int(root, "max_level", 0, &m->max_level, name, err, n) &&
         get_int(root, "scene_budget", 0, &m->scene_budget, name, err, n) &&
         get_int(root, "width", 0, &m->width, name, err, n) && get_int(root, "height", 0, &m->height, name, err, n) &&
         get_int(root, "screenshot_every", 0, &m->screenshot_every, name, err, n) &&
         get_int(root, "frames_requested", -1, &m->frames_requested, name, err, n) &&
         get_int(root, "frames_completed", -1, &m->frames_completed, name, err, n);
}

static bool read_objects(const json_value* root, run* r, const char* name, char* err, size_t n) {
  const json_value* list = json_get(root, "objects");
  if (!list) return true;
  if (list->type != JSON_ARRAY) return run_fail(err, n, "%s: objects: not an array", name);
  r->objects = calloc(list->count ? list->count : 1, sizeof *r->objects);
  if (!r->objects) return run_fail(err, n, "%s: out of memory", name);
  for (size_t i = 0; i < list->count; i++) {
    const json_value* o = &list->items[i];
    run_object* d = &r->objects[r->object_count++];
    char what[1280];
    snprintf(what, sizeof what, "%.1100s: objects[%zu]", name, i);
    if (o->type != JSON_OBJECT) return run_fail(err, n, "%s: not an object", what);
    if (!get_string(o, "name", &d->name, what, err, n) || !get_string(o, "source", &d->source, what, err, n) ||
        !get_int(o, "vertices", 0, &d->vertices, what, err, n) || !get_int(o, "faces", 0, &d->faces, what, err, n) ||
        !get_int(o, "patches", 0, &d->patches, what, err, n))
      return false;
  }
  return true;
}

/* An array of count numbers at key into out[0..count) (NaN when absent). */
static bool get_numbers(const json_value* obj, const char* key, double* out, size_t count, const char* name, char* err,
                        size_t n) {
  const json_value* v = json_get(obj, key);
  for (size_t i = 0; i < count; i++)
    out[i] = NAN;
  if (!v || v->type == JSON_NULL) return true;
  if (v->type != JSON_ARRAY || v->count != count)
    return run_fail(err, n, "%s: %s: not an array of %zu numbers", name, key, count);
  for (size_t i = 0; i < count; i++) {
    const json_value* x = &v->items[i];
    if (x->type != JSON_NUMBER && x->type != JSON_NULL)
      return run_fail(err, n, "%s: %s[%zu]: not a number", name, key, i);
    if (x->type == JSON_NUMBER) out[i] = x->number;
  }
  return true;
}

static bool read_stages(const json_value* f, double* row, const char* name, char* err, size_t n) {
  static const char* const stages[] = {"silhouette", "metric", "levels", "morph", "strips"};
  const json_value* s = json_get(f, "stage_ms");
  if (s && s->type != JSON_OBJECT && s->type != JSON_NULL) return run_fail(err, n, "%s: stage_ms: not an object", name);
  for (int i = 0; i < 5; i++) {
    char what[1280];
    snprintf(what, sizeof what, "%.1100s: stage_ms", name);
    if (!get_number(s, stages[i], NAN, &row[RUN_COL_SILHOUETTE_MS + i], what, err, n)) return false;
  }
  return true;
}

/* One frame record into row[RUN_COLUMN_COUNT] and its screenshot path. */
static bool read_frame(const json_value* f, double* row, char** shot, const char* name, char* err, size_t n) {
  if (f->type != JSON_OBJECT) return run_fail(err, n, "%s: not an object", name);
  for (int c = 0; c < RUN_COLUMN_COUNT; c++) {
    bool direct = c < RUN_COL_SILHOUETTE_MS || (c > RUN_COL_STRIPS_MS && c < RUN_COL_LEVEL_0) || c >= RUN_COL_FOVY;
    if (direct && !get_number(f, column_names[c], NAN, &row[c], name, err, n)) return false;
  }
  return read_stages(f, row, name, err, n) &&
         get_numbers(f, "level_histogram", row + RUN_COL_LEVEL_0, RUN_LEVELS, name, err, n) &&
         get_numbers(f, "eye", row + RUN_COL_EYE_X, 3, name, err, n) &&
         get_numbers(f, "target", row + RUN_COL_TARGET_X, 3, name, err, n) &&
         get_string(f, "screenshot", shot, name, err, n);
}

static bool alloc_frames(run* r, size_t count, const char* name, char* err, size_t n) {
  for (int c = 0; c < RUN_COLUMN_COUNT && count; c++) {
    if (!(r->column[c] = calloc(count, sizeof(double)))) return run_fail(err, n, "%s: out of memory", name);
  }
  r->screenshot = calloc(count ? count : 1, sizeof(char*));
  return r->screenshot ? true : run_fail(err, n, "%s: out of memory", name);
}

static bool read_frames(const json_value* root, run* r, const char* name, char* err, size_t n) {
  const json_value* list = json_get(root, "frames");
  if (!list) return alloc_frames(r, 0, name, err, n);
  if (list->type != JSON_ARRAY) return run_fail(err, n, "%s: frames: not an array", name);
  size_t complete = list->count;
  while (complete && !list->items[complete - 1].complete)
    complete--;
  if (!alloc_frames(r, complete, name, err, n)) return false;
  for (size_t i = 0; i < complete; i++) {
    double row[RUN_COLUMN_COUNT];
    char what[1280];
    snprintf(what, sizeof what, "%.1100s: frames[%zu]", name, i);
    r->frame_count++; /* first, so run_free frees a screenshot path read before an error */
    if (!read_frame(&list->items[i], row, &r->screenshot[i], what, err, n)) return false;
    for (int c = 0; c < RUN_COLUMN_COUNT; c++)
      r->column[c][i] = row[c];
  }
  return true;
}

static bool note_truncation(run* r, const char* name, char* err, size_t n) {
  char line[1200];
  /* The last frame's own number when it is one (a hostile trace may hold NaN or 1e300 there: converting
   * those is undefined), else its position. */
  double v = r->frame_count ? r->column[RUN_COL_FRAME][r->frame_count - 1] : 0.0;
  long long last = v >= 0.0 && v <= 9e15 ? (long long)v : (long long)r->frame_count - 1;
  if (r->frame_count)
    snprintf(line, sizeof line, "%s: truncated after frame %lld", name, last);
  else
    snprintf(line, sizeof line, "%s: truncated before its first frame", name);
  r->truncated = true;
  r->truncated_reason = run_strdup(line);
  return r->truncated_reason ? true : run_fail(err, n, "%s: out of memory", name);
}

static bool read_tree(const json_value* root, bool truncated, run* r, const char* name, char* err, size_t n) {
  if (root->type != JSON_OBJECT) return run_fail(err, n, "%s: not a JSON object", name);
  if (!get_string(root, "schema", &r->meta.schema, name, err, n)) return false;
  if (strcmp(r->meta.schema, RUN_TRACE_SCHEMA))
    return run_fail(err, n, "%s: schema '%.64s' is not %s", name, r->meta.schema, RUN_TRACE_SCHEMA);
  if (!read_meta_strings(root, &r->meta, name, err, n) || !read_meta_numbers(root, &r->meta, name, err, n) ||
      !read_objects(root, r, name, err, n) || !read_frames(root, r, name, err, n))
    return false;
  return !truncated || note_truncation(r, name, err, n);
}

bool run_read_trace_text(const char* name, const char* text, size_t size, run* out, char* err, size_t err_size) {
  memset(out, 0, sizeof *out);
  json_value* root = NULL;
  char why[160];
  json_read_status st = json_read(text, size, &root, why, sizeof why);
  if (st == JSON_READ_ERROR) return run_fail(err, err_size, "%s: not JSON: %s", name, why);
  bool ok = read_tree(root, st == JSON_READ_TRUNCATED, out, name, err, err_size);
  json_free(root);
  if (!ok) run_free(out);
  return ok;
}

static void free_meta(run_meta* m) {
  char** s[] = {&m->schema,   &m->tool,    &m->scene,  &m->path,    &m->mode,       &m->backend,
                &m->renderer, &m->surface, &m->policy, &m->stopped, &m->debug_view, &m->field};
  for (size_t i = 0; i < sizeof s / sizeof s[0]; i++)
    free(*s[i]);
}

void run_free(run* r) {
  if (!r) return;
  free_meta(&r->meta);
  for (size_t i = 0; i < r->object_count; i++)
    free(r->objects[i].name), free(r->objects[i].source);
  free(r->objects);
  for (int c = 0; c < RUN_COLUMN_COUNT; c++)
    free(r->column[c]);
  for (size_t i = 0; r->screenshot && i < r->frame_count; i++)
    free(r->screenshot[i]);
  free(r->screenshot);
  free(r->object_counts);
  free(r->object_counts_note);
  free(r->truncated_reason);
  free(r->dir);
  free(r->label);
  memset(r, 0, sizeof *r);
}
