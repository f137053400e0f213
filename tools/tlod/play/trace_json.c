/* tlod play -- trace.json: the settings, every frame's figures, then the
 * results (schema tlod-play-trace/1, docs/play.md), written in pieces. */
#include <stdio.h>
#include <string.h>

#include "common/lod_json.h"
#include "play_trace_format.h"
#include "tlod_import.h"
#include "tool_names.h"

/* "warning_count" and "warnings": the importer's lines. */
void json_warnings(json_writer* w, const char* text, uint32_t count) {
  json_uint(w, "warning_count", count);
  json_array_begin(w, "warnings");
  for (const char* p = text ? text : ""; *p;) {
    const char* end = strchr(p, '\n');
    size_t n = end ? (size_t)(end - p) : strlen(p);
    char line[TLOD_IMPORT_WARNINGS_SIZE];
    snprintf(line, sizeof(line), "%.*s", (int)n, p);
    if (n) json_string(w, NULL, line);
    p += n + (end ? 1 : 0);
  }
  json_array_end(w);
}

static void json_vec(json_writer* w, const char* key, const float* v, int n) {
  json_array_begin(w, key);
  for (int i = 0; i < n; i++)
    json_number(w, NULL, v[i]);
  json_array_end(w);
}

/* --field in one line ("temperature [K] 0..250 viridis", the dashboard's
 * run line); no key without a field. */
static void json_field_line(json_writer* w, const play_field_info* f) {
  if (!f->name) return;
  char line[256];
  snprintf(line, sizeof(line), f->units[0] ? "%s [%s] %.6g..%.6g %s" : "%s%s %.6g..%.6g %s", f->label, f->units, f->min,
           f->max, f->colormap);
  json_string(w, "field", line);
}

/* The settings block of trace.json (also the live server's run.json). */
void trace_json_settings(json_writer* w, const play_trace* t) {
  json_string(w, "tool", t->tool_version);
  json_string(w, "scene", t->scene);
  json_string(w, "mode", t->mode);
  json_string(w, "backend", t->backend);
  json_string(w, "renderer", t->renderer);
  json_string(w, "gpu_eval", t->gpu_eval ? t->gpu_eval : "");
  json_string(w, "surface", t->surface);
  json_string(w, "policy", t->policy);
  json_number(w, "epsilon_px", t->epsilon);
  json_uint(w, "max_level", t->max_level);
  json_uint(w, "scene_budget", t->scene_budget);
  json_string(w, "path", t->path);
  json_number(w, "path_duration_s", t->path_duration_s);
  json_bool(w, "loop", t->loop);
  json_number(w, "fps", t->fps);
  json_number(w, "dt_ms", 1000.0 / t->fps);
  json_uint(w, "width", t->width);
  json_uint(w, "height", t->height);
  json_uint(w, "screenshot_every", t->screenshot_every);
  json_string(w, "debug_view", t->debug_view);
  json_field_line(w, &t->field);
  json_uint(w, "frames_requested", t->frames_requested);
  json_array_begin(w, "objects");
  for (uint32_t i = 0; i < t->object_count; i++) {
    const play_object_info* o = &t->objects[i];
    json_object_begin(w, NULL);
    json_string(w, "name", o->name);
    json_string(w, "source", o->source);
    json_uint(w, "vertices", o->vertices);
    json_uint(w, "faces", o->faces);
    json_uint(w, "patches", o->patches);
    json_vec(w, "color", o->color, 4);
    json_uint(w, "surface", o->surface);
    json_number(w, "node", (double)o->node);
    json_bool(w, "skinned", o->skinned);
    json_bool(w, "textured", o->textured);
    json_object_end(w);
  }
  json_array_end(w);
  json_uint(w, "objects_inline", play_trace_inline_objects(t));
  json_string(w, "object_counts_file", "objects.csv");
  json_string(w, "animation", t->animation ? t->animation : "");
  json_number(w, "animation_duration_s", t->animation_duration_s);
  json_warnings(w, t->warnings, t->warning_count);
}

void trace_json_head(json_writer* w, FILE* f, const play_trace* t) {
  json_begin(w, f);
  json_object_begin(w, NULL);
  json_string(w, "schema", PLAY_TRACE_SCHEMA);
  trace_json_settings(w, t);
  json_array_begin(w, "frames");
}

/* The per-object records of window frame n (the first objects_inline objects). */
static void json_frame_objects(json_writer* w, const play_trace* t, uint32_t n) {
  json_array_begin(w, "objects");
  for (uint32_t i = 0; i < play_trace_inline_objects(t); i++) {
    const play_object_stats* s = play_trace_object(t, n, i);
    json_object_begin(w, NULL);
    json_string(w, "name", t->objects[i].name);
    json_number(w, "scheduler_ms", s->update_ms);
    json_stage_ms(w, "stage_ms", s->stage_ms);
    json_number(w, "backend_cpu_ms", s->backend_cpu_ms);
    json_number(w, "backend_gpu_ms", s->backend_gpu_ms);
    json_number(w, "backend_wall_ms", s->backend_wall_ms);
    json_uint(w, "patches", s->patches);
    json_uint(w, "visible", s->patches - s->culled);
    json_uint(w, "culled", s->culled);
    json_uint(w, "strips", s->strips);
    json_uint(w, "pattern_triangles", s->pattern_triangles);
    json_uint(w, "strip_triangles", s->strip_triangles);
    json_uint(w, "triangles", s->pattern_triangles + s->strip_triangles);
    json_uint(w, "drawn_triangles", s->drawn_triangles);
    json_uint(w, "draw_calls", s->draw_calls);
    json_number(w, "effective_epsilon", s->effective_epsilon);
    json_level_histogram(w, "level_histogram", s->level_histogram, PLAY_LEVELS);
    json_object_end(w);
  }
  json_array_end(w);
}

void trace_json_frames(json_writer* w, const play_trace* t) {
  for (uint32_t n = 0; n < t->window_count; n++)
    trace_json_frame(w, t, n);
}

/* One record: also what the live server streams (play_serve_stream.c). */
void trace_json_frame(json_writer* w, const play_trace* t, uint32_t n) {
  const play_frame* fr = &t->frames[n];
  play_frame_totals tot;
  play_frame_totals_of(t, n, &tot);
  json_object_begin(w, NULL);
  json_uint(w, "frame", fr->frame);
  json_number(w, "time_s", fr->time_s);
  json_vec(w, "eye", fr->eye, 3);
  json_vec(w, "target", fr->target, 3);
  json_vec(w, "up", fr->up, 3);
  json_number(w, "fovy", fr->fovy);
  json_number(w, "near", fr->near_z);
  json_number(w, "far", fr->far_z);
  json_number(w, "frame_ms", fr->frame_ms);
  json_number(w, "anim_ms", fr->anim_ms);
  json_number(w, "scheduler_ms", tot.scheduler_ms);
  json_stage_ms(w, "stage_ms", tot.stage_ms);
  json_number(w, "backend_cpu_ms", tot.backend_cpu_ms);
  json_number(w, "backend_gpu_ms", tot.backend_gpu_ms);
  json_number(w, "backend_wall_ms", tot.backend_wall_ms);
  json_number(w, "screenshot_ms", fr->screenshot_ms);
  json_string(w, "screenshot", fr->screenshot);
  json_uint(w, "patches", tot.patches);
  json_uint(w, "visible", tot.patches - tot.culled);
  json_uint(w, "culled", tot.culled);
  json_uint(w, "strips", tot.strips);
  json_uint(w, "pattern_triangles", tot.pattern_triangles);
  json_uint(w, "strip_triangles", tot.strip_triangles);
  json_uint(w, "triangles", tot.pattern_triangles + tot.strip_triangles);
  json_uint(w, "drawn_triangles", tot.drawn_triangles);
  json_uint(w, "draw_calls", tot.draw_calls);
  json_number(w, "effective_epsilon", tot.effective_epsilon);
  json_level_histogram(w, "level_histogram", tot.level_histogram, PLAY_LEVELS);
  json_frame_objects(w, t, n);
  json_object_end(w);
}

/* The results come last: they are known only when the run ends. */
bool trace_json_tail(json_writer* w, const play_trace* t) {
  json_array_end(w);
  json_uint(w, "frames_completed", t->frame_count);
  json_string(w, "stopped", t->stopped);
  json_number(w, "wall_s", t->wall_s);
  json_object_end(w);
  return json_end(w);
}
