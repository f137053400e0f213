/* tlod play -- summary.txt: the table printed at the end of a run. */
#include <string.h>

#include "play_summary.h"
#include "tlod_atomic_file.h"
#include "tool_names.h"

/* vulkan: shaders, pipelines and validation of the mode. */
static void print_vulkan(FILE* f, const play_trace* t) {
  if (strcmp(t->backend, "vulkan")) return;
  const tlod_device_vk_stats* vk = &t->vk;
  fprintf(f,
          "    vulkan: shader stages %u compiled, %u from the cache (%.2f ms), %u pipelines, device create %.2f ms\n",
          vk->shader_compiles, vk->shader_cache_hits, vk->shader_ms, vk->pipelines, vk->create_ms);
  if (t->validate) fprintf(f, "    validation: %llu messages\n", (unsigned long long)t->validation_messages);
}

void play_print_summary(FILE* f, const play_trace* const* runs, uint32_t run_count, const char* out_dir) {
  const play_trace* t0 = runs[0];
  fprintf(f, "tlod play: %s (", t0->scene);
  for (uint32_t i = 0; i < t0->object_count; i++)
    fprintf(f, "%s%s %u patches", i ? ", " : "", t0->objects[i].name, t0->objects[i].patches);
  fprintf(f, "), %s surface, path %s (%.3g s%s), %ux%u, %g fps fixed step\n", t0->surface, t0->path,
          t0->path_duration_s, t0->loop ? ", looped" : "", t0->width, t0->height, t0->fps);
  fprintf(f, "backend %s: %s\n", t0->backend, t0->renderer);
  if (t0->gpu_eval && *t0->gpu_eval) fprintf(f, "gpu eval: %s\n", t0->gpu_eval);
  if (t0->resize_width)
    fprintf(f, "resized to %ux%u before frame %u\n", t0->resize_width, t0->resize_height, t0->resize_frame);
  fprintf(f, "%-12s %11s | frame ms: %7s %7s %7s %7s %7s | %6s | %9s %9s | %10s\n", "mode", "frames", "mean", "p50",
          "p95", "p99", "max", "fps", "sched ms", "draw ms", "triangles");
  run_summary base = {0};
  for (uint32_t k = 0; k < run_count; k++) {
    const play_trace* t = runs[k];
    run_summary r;
    play_summarize(t, &r);
    if (k == 0) base = r;
    char frames[32];
    snprintf(frames, sizeof(frames), "%u/%u", r.frames, t->frames_requested);
    fprintf(f, "%-12s %11s | %9s %7.2f %7.2f %7.2f %7.2f %7.2f | %6.1f | %9.3f %9.3f | %10.0f\n", t->mode, frames, "",
            r.frame_ms.mean, r.frame_ms.p50, r.frame_ms.p95, r.frame_ms.p99, r.frame_ms.max,
            r.frame_ms.mean > 0.0 ? 1000.0 / r.frame_ms.mean : 0.0, r.scheduler_ms.mean, r.backend_wall_ms.mean,
            r.triangles.mean);
  }
  for (uint32_t k = 0; k < run_count; k++) {
    const play_trace* t = runs[k];
    run_summary r;
    play_summarize(t, &r);
    fprintf(f, "%s: ", t->mode);
    if (!strcmp(t->mode, "adaptive")) fprintf(f, "%s policy, epsilon %g px, ", t->policy, (double)t->epsilon);
    fprintf(f, "first frame %.2f ms; stages (mean ms):", r.first_frame_ms);
    for (int s = 0; s < TLOD_STAGE_NUM; s++)
      fprintf(f, " %s %.3f", tool_stage_name(s), r.stage_mean[s]);
    fprintf(f, "\n    backend (mean ms): cpu %.3f, wall %.3f, gpu ", r.backend_cpu_ms.mean, r.backend_wall_ms.mean);
    if (r.gpu_frames) {
      fprintf(f, "%.3f (%s)", r.gpu_mean,
              strcmp(t->backend, "vulkan") ? "timer query; misses most llvmpipe work" : "timestamp queries, read late");
    } else {
      fputs("n/a", f);
    }
    fprintf(f, "\n    triangles min %.0f max %.0f (strips %.1f%%), culled patches %.1f; patches per level (mean):",
            r.triangles.min, r.triangles.max, r.triangles.mean > 0.0 ? 100.0 * r.strip_mean / r.triangles.mean : 0.0,
            r.culled_mean);
    int last = 0;
    for (int l = 0; l < PLAY_LEVELS; l++)
      if (r.histogram_mean[l] > 0.0) last = l;
    for (int l = 0; l <= last; l++)
      fprintf(f, " %d:%.0f", l, r.histogram_mean[l]);
    fputc('\n', f);
    if (k > 0 && base.frame_ms.mean > 0.0 && base.triangles.mean > 0.0)
      fprintf(f, "    vs %s: frame time %.2fx, triangles %.2fx\n", runs[0]->mode, r.frame_ms.mean / base.frame_ms.mean,
              r.triangles.mean / base.triangles.mean);
    print_vulkan(f, t);
    if (strcmp(t->stopped, "completed")) fprintf(f, "    stopped early: %s\n", t->stopped);
  }
  if (run_count > 1) {
    fprintf(f, "output: %s/ (summary.json, summary.txt; per mode in", out_dir);
    for (uint32_t k = 0; k < run_count; k++)
      fprintf(f, " %s/", runs[k]->dir);
    fputs(": trace.json, trace.csv, chrome_trace.json", f);
  } else {
    fprintf(f, "output: %s/ (trace.json, trace.csv, chrome_trace.json, summary.json, summary.txt", out_dir);
  }
  fprintf(f, "%s)\n", t0->screenshot_every ? ", screenshots/" : "");
}

static bool summary_text(FILE* f, const void* data) {
  const summary_job* j = data;
  play_print_summary(f, j->runs, j->run_count, j->out_dir);
  return true;
}

bool play_write_summary_text(const play_trace* const* runs, uint32_t run_count, const char* out_dir, const char* path,
                             char* error, size_t error_size) {
  summary_job j = {runs, run_count, out_dir, NULL};
  return tlod_atomic_file_write(path, summary_text, &j, error, error_size);
}
