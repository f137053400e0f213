/* tlod play -- summary.json: every run (mode) summed up (schema
 * tlod-play-summary/1, docs/play.md). */
#include "common/lod_json.h"
#include "play_serve.h"
#include "play_summary.h"
#include "play_trace_format.h"
#include "tlod_atomic_file.h"
#include "tool_names.h"

static void json_distribution(json_writer* w, const char* key, const distribution* d) {
  json_object_begin(w, key);
  json_number(w, "mean", d->mean);
  json_number(w, "p50", d->p50);
  json_number(w, "p95", d->p95);
  json_number(w, "p99", d->p99);
  json_number(w, "max", d->max);
  json_number(w, "min", d->min);
  json_object_end(w);
}

/* Memory and GL objects after frame 1, 10, 100, ... and the last (soak tests). */
static void json_resources(json_writer* w, const play_trace* t) {
  json_array_begin(w, "resources");
  for (uint32_t k = 0; k < t->sample_count; k++) {
    const play_resources* r = &t->samples[k];
    json_object_begin(w, NULL);
    json_uint(w, "frame", r->frame);
    json_uint(w, "peak_rss_kib", r->peak_rss_kib);
    json_uint(w, "rss_kib", r->rss_kib);
    if (r->gl) {
      json_object_begin(w, "gl_objects");
      json_uint(w, "buffers", r->gl_buffers);
      json_uint(w, "textures", r->gl_textures);
      json_uint(w, "renderbuffers", r->gl_renderbuffers);
      json_uint(w, "framebuffers", r->gl_framebuffers);
      json_uint(w, "vertex_arrays", r->gl_vertex_arrays);
      json_uint(w, "programs", r->gl_programs);
      json_uint(w, "shaders", r->gl_shaders);
      json_uint(w, "queries", r->gl_queries);
      json_object_end(w);
    }
    json_object_end(w);
  }
  json_array_end(w);
}

/* vulkan: the device's shader, pipeline and memory figures at the mode's end (zero elsewhere). */
static void json_vk(json_writer* w, const tlod_device_vk_stats* vk) {
  json_object_begin(w, "vk");
  json_uint(w, "shader_compiles", vk->shader_compiles);
  json_uint(w, "shader_cache_hits", vk->shader_cache_hits);
  json_number(w, "shader_ms", vk->shader_ms);
  json_uint(w, "pipelines", vk->pipelines);
  json_number(w, "create_ms", vk->create_ms);
  json_uint(w, "memory_blocks", vk->memory_blocks);
  json_uint(w, "memory_bytes", vk->memory_bytes);
  json_uint(w, "ring_bytes", vk->ring_bytes);
  json_uint(w, "upload_bytes", vk->upload_bytes);
  json_uint(w, "descriptor_sets", vk->descriptor_sets);
  json_object_end(w);
}

/* --resize-at, --validate and the shader cache: the run's settings. */
static void json_gpu_settings(json_writer* w, const play_trace* t0, const play_trace* last) {
  json_object_begin(w, "resize_at"); /* width 0: none */
  json_uint(w, "frame", t0->resize_frame);
  json_uint(w, "width", t0->resize_width);
  json_uint(w, "height", t0->resize_height);
  json_object_end(w);
  json_bool(w, "validate", t0->validate);
  json_uint(w, "validation_messages", last->validation_messages);
  json_string(w, "shader_cache", t0->shader_cache ? t0->shader_cache : "");
}

/* --field: what was coloured and how (the dashboard's legend). */
static void json_field(json_writer* w, const play_field_info* f) {
  if (!f->name) return;
  json_object_begin(w, "field");
  json_string(w, "name", f->name);
  json_string(w, "label", f->label);
  json_string(w, "units", f->units);
  if (f->component < 0) {
    json_string(w, "component", "magnitude");
  } else {
    json_int(w, "component", f->component);
  }
  json_number(w, "min", f->min);
  json_number(w, "max", f->max);
  json_string(w, "colormap", f->colormap);
  json_bool(w, "from_cells", f->from_cells);
  json_uint(w, "steps", f->steps);
  json_object_end(w);
}

static bool summary_json(FILE* f, const void* data) {
  const summary_job* j = data;
  const play_trace* t0 = j->runs[0];
  json_writer w;
  json_begin(&w, f);
  json_object_begin(&w, NULL);
  json_string(&w, "schema", PLAY_SUMMARY_SCHEMA);
  json_string(&w, "status", j->outcome->status);
  json_string(&w, "error", j->outcome->error);
  if (j->outcome->serve) play_serve_stats_json(&w, "serve", j->outcome->serve);
  json_string(&w, "tool", t0->tool_version);
  json_string(&w, "scene", t0->scene);
  json_string(&w, "backend", t0->backend);
  json_string(&w, "renderer", t0->renderer);
  json_string(&w, "gpu_eval", t0->gpu_eval ? t0->gpu_eval : "");
  json_string(&w, "surface", t0->surface);
  json_string(&w, "path", t0->path);
  json_string(&w, "animation", t0->animation ? t0->animation : "");
  json_string(&w, "debug_view", t0->debug_view);
  json_field(&w, &t0->field);
  json_warnings(&w, t0->warnings, t0->warning_count);
  json_number(&w, "fps", t0->fps);
  json_uint(&w, "width", t0->width);
  json_uint(&w, "height", t0->height);
  json_gpu_settings(&w, t0, j->runs[j->run_count - 1]);
  json_string(&w, "out_dir", j->out_dir);
  json_array_begin(&w, "runs");
  run_summary base = {0};
  for (uint32_t k = 0; k < j->run_count; k++) {
    const play_trace* t = j->runs[k];
    run_summary r;
    play_summarize(t, &r);
    if (k == 0) base = r;
    json_object_begin(&w, NULL);
    json_string(&w, "mode", t->mode);
    json_string(&w, "dir", t->dir);
    json_string(&w, "policy", t->policy);
    json_number(&w, "epsilon_px", t->epsilon);
    json_uint(&w, "max_level", t->max_level);
    json_uint(&w, "scene_budget", t->scene_budget);
    json_uint(&w, "frames_requested", t->frames_requested);
    json_uint(&w, "frames", r.frames);
    json_string(&w, "stopped", t->stopped);
    json_number(&w, "wall_s", t->wall_s);
    json_distribution(&w, "frame_ms", &r.frame_ms);
    json_number(&w, "fps", r.frame_ms.mean > 0.0 ? 1000.0 / r.frame_ms.mean : 0.0);
    json_number(&w, "first_frame_ms", r.first_frame_ms);
    json_distribution(&w, "scheduler_ms", &r.scheduler_ms);
    json_stage_ms(&w, "stage_ms_mean", r.stage_mean);
    json_distribution(&w, "backend_cpu_ms", &r.backend_cpu_ms);
    json_distribution(&w, "backend_wall_ms", &r.backend_wall_ms);
    json_number(&w, "backend_gpu_ms_mean", r.gpu_mean);
    json_uint(&w, "backend_gpu_frames", r.gpu_frames);
    json_distribution(&w, "triangles", &r.triangles);
    json_number(&w, "pattern_triangles_mean", r.pattern_mean);
    json_number(&w, "strip_triangles_mean", r.strip_mean);
    json_number(&w, "drawn_triangles_mean", r.drawn_mean);
    json_number(&w, "culled_mean", r.culled_mean);
    json_number(&w, "effective_epsilon_mean", r.epsilon_mean);
    json_array_begin(&w, "level_histogram_mean");
    for (int l = 0; l < PLAY_LEVELS; l++)
      json_number(&w, NULL, r.histogram_mean[l]);
    json_array_end(&w);
    json_resources(&w, t);
    json_vk(&w, &t->vk); /* zero but for vulkan */
    json_uint(&w, "validation_messages", t->validation_messages);
    if (j->run_count > 1) {
      json_object_begin(&w, "relative_to_first");
      json_number(&w, "frame_ms_mean", base.frame_ms.mean > 0.0 ? r.frame_ms.mean / base.frame_ms.mean : 0.0);
      json_number(&w, "triangles_mean", base.triangles.mean > 0.0 ? r.triangles.mean / base.triangles.mean : 0.0);
      json_object_end(&w);
    }
    json_object_end(&w);
  }
  json_array_end(&w);
  json_object_end(&w);
  return json_end(&w);
}

bool play_write_summary_json(const play_trace* const* runs, uint32_t run_count, const char* out_dir,
                             const play_outcome* outcome, const char* path, char* error, size_t error_size) {
  summary_job j = {runs, run_count, out_dir, outcome};
  return tlod_atomic_file_write(path, summary_json, &j, error, error_size);
}
