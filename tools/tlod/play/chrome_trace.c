/* tlod play -- chrome_trace.json: Chrome trace-event JSON (about:tracing,
 * Perfetto) of frames, scheduler stages, backend draws and screenshots. */
#include <stdio.h>

#include "common/json_writer.h"
#include "play_trace_format.h"
#include "tool_names.h"

static void chrome_event(FILE* f, bool* first, const char* name, const char* object, const char* cat, double at_ms,
                         double dur_ms, const char* args) {
  fputs(*first ? "\n  " : ",\n  ", f);
  *first = false;
  fputs("{\"name\": ", f);
  if (object) {
    char buf[160];
    snprintf(buf, sizeof(buf), "%s %s", name, object);
    json_put_string(f, buf);
  } else {
    json_put_string(f, name);
  }
  fprintf(f, ", \"cat\": \"%s\", \"ph\": \"X\", \"ts\": %.3f, \"dur\": %.3f, \"pid\": 1, \"tid\": 1, \"args\": {%s}}",
          cat, at_ms * 1e3, (dur_ms > 0.0 ? dur_ms : 0.0) * 1e3, args);
}

void chrome_trace_head(FILE* f) { fputs("{\"displayTimeUnit\": \"ms\", \"traceEvents\": [", f); }

void chrome_trace_frames(FILE* f, const play_trace* t, bool* first) {
  for (uint32_t n = 0; n < t->window_count; n++) {
    const play_frame* fr = &t->frames[n];
    play_frame_totals tot;
    play_frame_totals_of(t, n, &tot);
    char args[512];
    snprintf(args, sizeof(args), "\"frame\": %u, \"time_s\": %.9g, \"triangles\": %llu, \"culled\": %u", fr->frame,
             fr->time_s, (unsigned long long)(tot.pattern_triangles + tot.strip_triangles), tot.culled);
    chrome_event(f, first, "frame", NULL, "frame", fr->at_ms, fr->frame_ms, args);
    for (uint32_t i = 0; i < play_trace_inline_objects(t); i++) {
      const play_object_stats* s = play_trace_object(t, n, i);
      const char* name = t->objects[i].name;
      snprintf(args, sizeof(args),
               "\"frame\": %u, \"patches\": %u, \"culled\": %u, \"strips\": %u, \"effective_epsilon\": %.9g", fr->frame,
               s->patches, s->culled, s->strips, (double)s->effective_epsilon);
      chrome_event(f, first, "scheduler_update", name, "scheduler", s->update_at_ms, s->update_ms, args);
      /* The scheduler reports stage durations: laid out back to back from the update's start. */
      double at = s->update_at_ms;
      for (int st = 0; st < TLOD_STAGE_NUM; st++) {
        snprintf(args, sizeof(args), "\"frame\": %u", fr->frame);
        chrome_event(f, first, tool_stage_name(st), name, "scheduler", at, s->stage_ms[st], args);
        at += s->stage_ms[st];
      }
    }
    for (uint32_t i = 0; i < play_trace_inline_objects(t); i++) {
      const play_object_stats* s = play_trace_object(t, n, i);
      snprintf(args, sizeof(args),
               "\"frame\": %u, \"backend\": \"%s\", \"cpu_ms\": %.6f, \"gpu_ms\": %.6f, \"wall_ms\": %.6f, "
               "\"triangles\": %llu, \"draw_calls\": %u",
               fr->frame, t->backend, s->backend_cpu_ms, s->backend_gpu_ms, s->backend_wall_ms,
               (unsigned long long)s->drawn_triangles, s->draw_calls);
      chrome_event(f, first, "backend_draw", t->objects[i].name, "backend", s->draw_at_ms, s->draw_ms, args);
    }
    if (fr->screenshot[0]) {
      snprintf(args, sizeof(args), "\"frame\": %u, \"file\": \"%s\"", fr->frame, fr->screenshot);
      chrome_event(f, first, "screenshot", NULL, "io", fr->screenshot_at_ms, fr->screenshot_ms, args);
    }
  }
}

void chrome_trace_tail(FILE* f, const play_trace* t) {
  fputs("\n], \"otherData\": {", f);
  fputs("\"tool\": ", f);
  json_put_string(f, t->tool_version);
  fputs(", \"scene\": ", f);
  json_put_string(f, t->scene);
  fputs(", \"mode\": ", f);
  json_put_string(f, t->mode);
  fputs(", \"backend\": ", f);
  json_put_string(f, t->backend);
  fputs(", \"renderer\": ", f);
  json_put_string(f, t->renderer);
  fprintf(f, ", \"frames\": %u}}\n", t->frame_count);
}
