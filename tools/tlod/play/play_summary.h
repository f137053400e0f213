/* tlod play -- the summary of runs (summary.json, summary.txt and the table
 * printed at the end). */
#ifndef TLOD_TOOLS_PLAY_SUMMARY_H
#define TLOD_TOOLS_PLAY_SUMMARY_H

#include "common/distribution.h"
#include "play_trace.h"

typedef struct run_summary {
  uint32_t frames;
  distribution frame_ms, scheduler_ms, backend_cpu_ms, backend_wall_ms, triangles;
  double gpu_mean; /* -1: no timer result */
  uint32_t gpu_frames;
  double stage_mean[TLOD_STAGE_NUM];
  double pattern_mean, strip_mean, drawn_mean, culled_mean, epsilon_mean;
  double histogram_mean[PLAY_LEVELS];
  double first_frame_ms;
} run_summary;

/* The runs a summary file is written for. */
typedef struct summary_job {
  const play_trace* const* runs;
  uint32_t run_count;
  const char* out_dir;
  const play_outcome* outcome; /* summary.json only */
} summary_job;

/* The figures of trace t summed up. */
void play_summarize(const play_trace* t, run_summary* r);

#endif
