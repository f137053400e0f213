/* tlod play -- trace.csv: one row of totals per frame. */
#include "play_trace_format.h"
#include "tool_names.h"

void trace_csv_head(FILE* f) {
  fputs("frame,time_s,frame_ms,scheduler_ms", f);
  for (int s = 0; s < TLOD_STAGE_NUM; s++)
    fprintf(f, ",%s_ms", tool_stage_name(s));
  fputs(",backend_cpu_ms,backend_gpu_ms,backend_wall_ms,screenshot_ms,patches,visible,culled,strips,"
        "pattern_triangles,strip_triangles,triangles,drawn_triangles,draw_calls,effective_epsilon",
        f);
  for (int l = 0; l < PLAY_LEVELS; l++)
    fprintf(f, ",level_%d", l);
  fputs(",eye_x,eye_y,eye_z,target_x,target_y,target_z,fovy\n", f);
}

void trace_csv_frames(FILE* f, const play_trace* t) {
  for (uint32_t n = 0; n < t->window_count; n++) {
    const play_frame* fr = &t->frames[n];
    play_frame_totals tot;
    play_frame_totals_of(t, n, &tot);
    fprintf(f, "%u,%.9g,%.6f,%.6f", fr->frame, fr->time_s, fr->frame_ms, tot.scheduler_ms);
    for (int s = 0; s < TLOD_STAGE_NUM; s++)
      fprintf(f, ",%.6f", tot.stage_ms[s]);
    fprintf(f, ",%.6f,%.6f,%.6f,%.6f,%u,%u,%u,%u,%llu,%llu,%llu,%llu,%u,%.9g", tot.backend_cpu_ms, tot.backend_gpu_ms,
            tot.backend_wall_ms, fr->screenshot_ms, tot.patches, tot.patches - tot.culled, tot.culled, tot.strips,
            (unsigned long long)tot.pattern_triangles, (unsigned long long)tot.strip_triangles,
            (unsigned long long)(tot.pattern_triangles + tot.strip_triangles), (unsigned long long)tot.drawn_triangles,
            tot.draw_calls, (double)tot.effective_epsilon);
    for (int l = 0; l < PLAY_LEVELS; l++)
      fprintf(f, ",%u", tot.level_histogram[l]);
    fprintf(f, ",%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", (double)fr->eye[0], (double)fr->eye[1], (double)fr->eye[2],
            (double)fr->target[0], (double)fr->target[1], (double)fr->target[2], (double)fr->fovy);
  }
}
