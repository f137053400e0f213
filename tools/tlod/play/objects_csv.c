/* tlod play -- objects.csv: every object's counts, one row per frame and
 * object (trace.json's frames carry the first PLAY_TRACE_INLINE_OBJECTS
 * objects only, so their size does not grow with the scene). */
#include "play_trace_format.h"

void objects_csv_head(FILE* f) {
  fputs("frame,object,patches,visible,culled,strips,pattern_triangles,strip_triangles,triangles,drawn_triangles,"
        "draw_calls,scheduler_ms,backend_wall_ms\n",
        f);
}

void objects_csv_frames(FILE* f, const play_trace* t) {
  for (uint32_t n = 0; n < t->window_count; n++)
    for (uint32_t i = 0; i < t->object_count; i++) {
      const play_object_stats* s = play_trace_object(t, n, i);
      fprintf(f, "%u,%u,%u,%u,%u,%u,%llu,%llu,%llu,%llu,%u,%.6f,%.6f\n", t->frames[n].frame, i, s->patches,
              s->patches - s->culled, s->culled, s->strips, (unsigned long long)s->pattern_triangles,
              (unsigned long long)s->strip_triangles, (unsigned long long)(s->pattern_triangles + s->strip_triangles),
              (unsigned long long)s->drawn_triangles, s->draw_calls, s->update_ms, s->backend_wall_ms);
    }
}
