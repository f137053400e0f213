/* tlod play -- trace, CSV, Chrome trace-event and summary writers. */
#include "play_trace.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "json_writer.h"

static const char* const stage_names[TLOD_STAGE_NUM] = {"silhouette", "metric", "levels", "morph", "strips"};

/* ---- records ------------------------------------------------------------- */

play_frame* play_trace_add_frame(play_trace* t, play_object_stats** objects) {
  if (t->frame_count == t->capacity) {
    uint32_t cap = t->capacity ? 2 * t->capacity : 256;
    play_frame* f = realloc(t->frames, sizeof(play_frame) * cap);
    if (!f) return NULL;
    t->frames = f;
    play_object_stats* s = realloc(t->stats, sizeof(play_object_stats) * cap * (t->object_count ? t->object_count : 1));
    if (!s) return NULL;
    t->stats = s;
    t->capacity = cap;
  }
  play_frame* f = &t->frames[t->frame_count];
  memset(f, 0, sizeof(*f));
  f->frame = t->frame_count;
  *objects = &t->stats[(size_t)t->frame_count * t->object_count];
  memset(*objects, 0, sizeof(play_object_stats) * t->object_count);
  t->frame_count++;
  return f;
}

void play_trace_free(play_trace* t) {
  free(t->frames);
  free(t->stats);
  t->frames = NULL;
  t->stats = NULL;
  t->frame_count = t->capacity = 0;
}

static const play_object_stats* object_stats(const play_trace* t, uint32_t frame, uint32_t object) {
  return &t->stats[(size_t)frame * t->object_count + object];
}

void play_frame_totals_of(const play_trace* t, uint32_t frame, play_frame_totals* o) {
  memset(o, 0, sizeof(*o));
  bool gpu = false;
  for (uint32_t i = 0; i < t->object_count; i++) {
    const play_object_stats* s = object_stats(t, frame, i);
    o->scheduler_ms += s->update_ms;
    for (int st = 0; st < TLOD_STAGE_NUM; st++)
      o->stage_ms[st] += s->stage_ms[st];
    o->backend_cpu_ms += s->backend_cpu_ms;
    o->backend_wall_ms += s->backend_wall_ms;
    if (s->backend_gpu_ms >= 0.0) o->backend_gpu_ms += s->backend_gpu_ms, gpu = true;
    o->patches += s->patches;
    o->culled += s->culled;
    o->instances += s->instances;
    o->strips += s->strips;
    o->draw_calls += s->draw_calls;
    o->pattern_triangles += s->pattern_triangles;
    o->strip_triangles += s->strip_triangles;
    o->drawn_triangles += s->drawn_triangles;
    for (int l = 0; l < PLAY_LEVELS; l++)
      o->level_histogram[l] += s->level_histogram[l];
    if (i == 0 || s->effective_epsilon > o->effective_epsilon) o->effective_epsilon = s->effective_epsilon;
  }
  if (!gpu) o->backend_gpu_ms = -1.0;
}

/* ---- files --------------------------------------------------------------- */

typedef bool (*write_fn)(FILE* f, const void* data);

/* Writes path.tmp, then renames it over path; nothing is left behind on failure. */
static bool write_atomic(const char* path, write_fn fn, const void* data, char* error, size_t error_size) {
  char tmp[4200];
  snprintf(tmp, sizeof(tmp), "%s.tmp", path);
  FILE* f = fopen(tmp, "w");
  if (!f) {
    snprintf(error, error_size, "cannot write '%s': %s", tmp, strerror(errno));
    return false;
  }
  static char buffer[1 << 16];
  setvbuf(f, buffer, _IOFBF, sizeof(buffer));
  bool ok = fn(f, data);
  ok = !ferror(f) && ok;
  int saved = errno;
  ok = fclose(f) == 0 && ok;
  if (!ok) {
    remove(tmp);
    snprintf(error, error_size, "cannot write '%s': %s", path, strerror(saved ? saved : EIO));
    return false;
  }
  if (rename(tmp, path) != 0) {
    snprintf(error, error_size, "cannot rename '%s' to '%s': %s", tmp, path, strerror(errno));
    remove(tmp);
    return false;
  }
  return true;
}

static void json_vec(json_writer* w, const char* key, const float* v, int n) {
  json_array_begin(w, key);
  for (int i = 0; i < n; i++)
    json_number(w, NULL, v[i]);
  json_array_end(w);
}

static void json_histogram(json_writer* w, const uint32_t* h) {
  json_array_begin(w, "level_histogram");
  for (int l = 0; l < PLAY_LEVELS; l++)
    json_uint(w, NULL, h[l]);
  json_array_end(w);
}

static void json_stages(json_writer* w, const double* ms) {
  json_object_begin(w, "stage_ms");
  for (int s = 0; s < TLOD_STAGE_NUM; s++)
    json_number(w, stage_names[s], ms[s]);
  json_object_end(w);
}

/* The settings block shared by trace.json (and the summary's runs). */
static void json_settings(json_writer* w, const play_trace* t) {
  json_string(w, "tool", t->tool_version);
  json_string(w, "scene", t->scene);
  json_string(w, "mode", t->mode);
  json_string(w, "backend", t->backend);
  json_string(w, "renderer", t->renderer);
  json_string(w, "surface", t->surface);
  json_string(w, "policy", t->policy);
  json_number(w, "epsilon_px", t->epsilon);
  json_uint(w, "max_level", t->max_level);
  json_string(w, "path", t->path);
  json_number(w, "path_duration_s", t->path_duration_s);
  json_bool(w, "loop", t->loop);
  json_number(w, "fps", t->fps);
  json_number(w, "dt_ms", 1000.0 / t->fps);
  json_uint(w, "width", t->width);
  json_uint(w, "height", t->height);
  json_uint(w, "screenshot_every", t->screenshot_every);
  json_uint(w, "frames_requested", t->frames_requested);
  json_uint(w, "frames_completed", t->frame_count);
  json_string(w, "stopped", t->stopped);
  json_number(w, "wall_s", t->wall_s);
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
    json_object_end(w);
  }
  json_array_end(w);
}

static bool trace_json(FILE* f, const void* data) {
  const play_trace* t = data;
  json_writer w;
  json_begin(&w, f);
  json_object_begin(&w, NULL);
  json_string(&w, "schema", PLAY_TRACE_SCHEMA);
  json_settings(&w, t);
  json_array_begin(&w, "frames");
  for (uint32_t n = 0; n < t->frame_count; n++) {
    const play_frame* fr = &t->frames[n];
    play_frame_totals tot;
    play_frame_totals_of(t, n, &tot);
    json_object_begin(&w, NULL);
    json_uint(&w, "frame", fr->frame);
    json_number(&w, "time_s", fr->time_s);
    json_vec(&w, "eye", fr->eye, 3);
    json_vec(&w, "target", fr->target, 3);
    json_vec(&w, "up", fr->up, 3);
    json_number(&w, "fovy", fr->fovy);
    json_number(&w, "near", fr->near_z);
    json_number(&w, "far", fr->far_z);
    json_number(&w, "frame_ms", fr->frame_ms);
    json_number(&w, "scheduler_ms", tot.scheduler_ms);
    json_stages(&w, tot.stage_ms);
    json_number(&w, "backend_cpu_ms", tot.backend_cpu_ms);
    json_number(&w, "backend_gpu_ms", tot.backend_gpu_ms);
    json_number(&w, "backend_wall_ms", tot.backend_wall_ms);
    json_number(&w, "screenshot_ms", fr->screenshot_ms);
    json_string(&w, "screenshot", fr->screenshot);
    json_uint(&w, "patches", tot.patches);
    json_uint(&w, "visible", tot.patches - tot.culled);
    json_uint(&w, "culled", tot.culled);
    json_uint(&w, "strips", tot.strips);
    json_uint(&w, "pattern_triangles", tot.pattern_triangles);
    json_uint(&w, "strip_triangles", tot.strip_triangles);
    json_uint(&w, "triangles", tot.pattern_triangles + tot.strip_triangles);
    json_uint(&w, "drawn_triangles", tot.drawn_triangles);
    json_uint(&w, "draw_calls", tot.draw_calls);
    json_number(&w, "effective_epsilon", tot.effective_epsilon);
    json_histogram(&w, tot.level_histogram);
    json_array_begin(&w, "objects");
    for (uint32_t i = 0; i < t->object_count; i++) {
      const play_object_stats* s = object_stats(t, n, i);
      json_object_begin(&w, NULL);
      json_string(&w, "name", t->objects[i].name);
      json_number(&w, "scheduler_ms", s->update_ms);
      json_stages(&w, s->stage_ms);
      json_number(&w, "backend_cpu_ms", s->backend_cpu_ms);
      json_number(&w, "backend_gpu_ms", s->backend_gpu_ms);
      json_number(&w, "backend_wall_ms", s->backend_wall_ms);
      json_uint(&w, "patches", s->patches);
      json_uint(&w, "visible", s->patches - s->culled);
      json_uint(&w, "culled", s->culled);
      json_uint(&w, "strips", s->strips);
      json_uint(&w, "pattern_triangles", s->pattern_triangles);
      json_uint(&w, "strip_triangles", s->strip_triangles);
      json_uint(&w, "triangles", s->pattern_triangles + s->strip_triangles);
      json_uint(&w, "drawn_triangles", s->drawn_triangles);
      json_uint(&w, "draw_calls", s->draw_calls);
      json_number(&w, "effective_epsilon", s->effective_epsilon);
      json_histogram(&w, s->level_histogram);
      json_object_end(&w);
    }
    json_array_end(&w);
    json_object_end(&w);
  }
  json_array_end(&w);
  json_object_end(&w);
  return json_end(&w);
}

bool play_write_trace_json(const play_trace* t, const char* path, char* error, size_t error_size) {
  return write_atomic(path, trace_json, t, error, error_size);
}

static bool trace_csv(FILE* f, const void* data) {
  const play_trace* t = data;
  fputs("frame,time_s,frame_ms,scheduler_ms", f);
  for (int s = 0; s < TLOD_STAGE_NUM; s++)
    fprintf(f, ",%s_ms", stage_names[s]);
  fputs(",backend_cpu_ms,backend_gpu_ms,backend_wall_ms,screenshot_ms,patches,visible,culled,strips,"
        "pattern_triangles,strip_triangles,triangles,drawn_triangles,draw_calls,effective_epsilon",
        f);
  for (int l = 0; l < PLAY_LEVELS; l++)
    fprintf(f, ",level_%d", l);
  fputs(",eye_x,eye_y,eye_z,target_x,target_y,target_z,fovy\n", f);
  for (uint32_t n = 0; n < t->frame_count; n++) {
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
  return true;
}

bool play_write_trace_csv(const play_trace* t, const char* path, char* error, size_t error_size) {
  return write_atomic(path, trace_csv, t, error, error_size);
}

/* JSON string with the few escapes object names can need. */
static void put_json_string(FILE* f, const char* s) {
  fputc('"', f);
  for (; *s; s++) {
    unsigned char c = (unsigned char)*s;
    if (c == '"' || c == '\\') {
      fprintf(f, "\\%c", c);
    } else if (c < 0x20) {
      fprintf(f, "\\u%04x", c);
    } else {
      fputc(c, f);
    }
  }
  fputc('"', f);
}

/* One complete ("X") event; args_fmt is the inside of the args object. */
static void chrome_event(FILE* f, bool* first, const char* name, const char* object, const char* cat, double at_ms,
                         double dur_ms, const char* args) {
  fputs(*first ? "\n  " : ",\n  ", f);
  *first = false;
  fputs("{\"name\": ", f);
  if (object) {
    char buf[160];
    snprintf(buf, sizeof(buf), "%s %s", name, object);
    put_json_string(f, buf);
  } else {
    put_json_string(f, name);
  }
  fprintf(f, ", \"cat\": \"%s\", \"ph\": \"X\", \"ts\": %.3f, \"dur\": %.3f, \"pid\": 1, \"tid\": 1, \"args\": {%s}}",
          cat, at_ms * 1e3, (dur_ms > 0.0 ? dur_ms : 0.0) * 1e3, args);
}

static bool chrome_trace(FILE* f, const void* data) {
  const play_trace* t = data;
  bool first = true;
  fputs("{\"displayTimeUnit\": \"ms\", \"traceEvents\": [", f);
  for (uint32_t n = 0; n < t->frame_count; n++) {
    const play_frame* fr = &t->frames[n];
    play_frame_totals tot;
    play_frame_totals_of(t, n, &tot);
    char args[512];
    snprintf(args, sizeof(args), "\"frame\": %u, \"time_s\": %.9g, \"triangles\": %llu, \"culled\": %u", fr->frame,
             fr->time_s, (unsigned long long)(tot.pattern_triangles + tot.strip_triangles), tot.culled);
    chrome_event(f, &first, "frame", NULL, "frame", fr->at_ms, fr->frame_ms, args);
    for (uint32_t i = 0; i < t->object_count; i++) {
      const play_object_stats* s = object_stats(t, n, i);
      const char* name = t->objects[i].name;
      snprintf(args, sizeof(args),
               "\"frame\": %u, \"patches\": %u, \"culled\": %u, \"strips\": %u, \"effective_epsilon\": %.9g", fr->frame,
               s->patches, s->culled, s->strips, (double)s->effective_epsilon);
      chrome_event(f, &first, "scheduler_update", name, "scheduler", s->update_at_ms, s->update_ms, args);
      /* The scheduler reports stage durations: laid out back to back from the update's start. */
      double at = s->update_at_ms;
      for (int st = 0; st < TLOD_STAGE_NUM; st++) {
        snprintf(args, sizeof(args), "\"frame\": %u", fr->frame);
        chrome_event(f, &first, stage_names[st], name, "scheduler", at, s->stage_ms[st], args);
        at += s->stage_ms[st];
      }
    }
    for (uint32_t i = 0; i < t->object_count; i++) {
      const play_object_stats* s = object_stats(t, n, i);
      snprintf(args, sizeof(args),
               "\"frame\": %u, \"backend\": \"%s\", \"cpu_ms\": %.6f, \"gpu_ms\": %.6f, \"wall_ms\": %.6f, "
               "\"triangles\": %llu, \"draw_calls\": %u",
               fr->frame, t->backend, s->backend_cpu_ms, s->backend_gpu_ms, s->backend_wall_ms,
               (unsigned long long)s->drawn_triangles, s->draw_calls);
      chrome_event(f, &first, "backend_draw", t->objects[i].name, "backend", s->draw_at_ms, s->draw_ms, args);
    }
    if (fr->screenshot[0]) {
      snprintf(args, sizeof(args), "\"frame\": %u, \"file\": \"%s\"", fr->frame, fr->screenshot);
      chrome_event(f, &first, "screenshot", NULL, "io", fr->screenshot_at_ms, fr->screenshot_ms, args);
    }
  }
  fputs("\n], \"otherData\": {", f);
  fputs("\"tool\": ", f);
  put_json_string(f, t->tool_version);
  fputs(", \"scene\": ", f);
  put_json_string(f, t->scene);
  fputs(", \"mode\": ", f);
  put_json_string(f, t->mode);
  fputs(", \"backend\": ", f);
  put_json_string(f, t->backend);
  fputs(", \"renderer\": ", f);
  put_json_string(f, t->renderer);
  fprintf(f, ", \"frames\": %u}}\n", t->frame_count);
  return true;
}

bool play_write_chrome_trace(const play_trace* t, const char* path, char* error, size_t error_size) {
  return write_atomic(path, chrome_trace, t, error, error_size);
}

/* ---- summary ------------------------------------------------------------- */

static int compare_double(const void* a, const void* b) {
  double x = *(const double*)a, y = *(const double*)b;
  return x < y ? -1 : (x > y ? 1 : 0);
}

double play_percentile(const double* values, uint32_t n, double p) {
  if (!n) return 0.0;
  double* v = malloc(sizeof(double) * n);
  if (!v) return NAN;
  memcpy(v, values, sizeof(double) * n);
  qsort(v, n, sizeof(double), compare_double);
  double rank = ceil(p / 100.0 * n);
  uint32_t i = rank < 1.0 ? 0 : (uint32_t)rank - 1;
  double r = v[i < n ? i : n - 1];
  free(v);
  return r;
}

typedef struct distribution {
  double mean, p50, p95, p99, max, min;
} distribution;

static distribution distribution_of(const double* v, uint32_t n) {
  distribution d = {0};
  if (!n) return d;
  d.min = d.max = v[0];
  for (uint32_t i = 0; i < n; i++) {
    d.mean += v[i];
    d.min = v[i] < d.min ? v[i] : d.min;
    d.max = v[i] > d.max ? v[i] : d.max;
  }
  d.mean /= n;
  d.p50 = play_percentile(v, n, 50);
  d.p95 = play_percentile(v, n, 95);
  d.p99 = play_percentile(v, n, 99);
  return d;
}

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

static void summarize(const play_trace* t, run_summary* r) {
  memset(r, 0, sizeof(*r));
  uint32_t n = t->frame_count;
  r->frames = n;
  r->gpu_mean = -1.0;
  if (!n) return;
  double* v[5];
  for (int k = 0; k < 5; k++)
    v[k] = calloc(n, sizeof(double));
  if (!v[0] || !v[1] || !v[2] || !v[3] || !v[4]) {
    for (int k = 0; k < 5; k++)
      free(v[k]);
    return;
  }
  double gpu = 0.0;
  for (uint32_t i = 0; i < n; i++) {
    play_frame_totals tot;
    play_frame_totals_of(t, i, &tot);
    v[0][i] = t->frames[i].frame_ms;
    v[1][i] = tot.scheduler_ms;
    v[2][i] = tot.backend_cpu_ms;
    v[3][i] = tot.backend_wall_ms;
    v[4][i] = (double)(tot.pattern_triangles + tot.strip_triangles);
    if (tot.backend_gpu_ms >= 0.0) gpu += tot.backend_gpu_ms, r->gpu_frames++;
    for (int s = 0; s < TLOD_STAGE_NUM; s++)
      r->stage_mean[s] += tot.stage_ms[s] / n;
    r->pattern_mean += (double)tot.pattern_triangles / n;
    r->strip_mean += (double)tot.strip_triangles / n;
    r->drawn_mean += (double)tot.drawn_triangles / n;
    r->culled_mean += (double)tot.culled / n;
    r->epsilon_mean += (double)tot.effective_epsilon / n;
    for (int l = 0; l < PLAY_LEVELS; l++)
      r->histogram_mean[l] += (double)tot.level_histogram[l] / n;
  }
  if (r->gpu_frames) r->gpu_mean = gpu / r->gpu_frames;
  r->frame_ms = distribution_of(v[0], n);
  r->scheduler_ms = distribution_of(v[1], n);
  r->backend_cpu_ms = distribution_of(v[2], n);
  r->backend_wall_ms = distribution_of(v[3], n);
  r->triangles = distribution_of(v[4], n);
  r->first_frame_ms = t->frames[0].frame_ms;
  for (int k = 0; k < 5; k++)
    free(v[k]);
}

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

typedef struct summary_job {
  const play_trace* const* runs;
  uint32_t run_count;
  const char* out_dir;
} summary_job;

static bool summary_json(FILE* f, const void* data) {
  const summary_job* j = data;
  const play_trace* t0 = j->runs[0];
  json_writer w;
  json_begin(&w, f);
  json_object_begin(&w, NULL);
  json_string(&w, "schema", PLAY_SUMMARY_SCHEMA);
  json_string(&w, "tool", t0->tool_version);
  json_string(&w, "scene", t0->scene);
  json_string(&w, "backend", t0->backend);
  json_string(&w, "renderer", t0->renderer);
  json_string(&w, "surface", t0->surface);
  json_string(&w, "path", t0->path);
  json_number(&w, "fps", t0->fps);
  json_uint(&w, "width", t0->width);
  json_uint(&w, "height", t0->height);
  json_string(&w, "out_dir", j->out_dir);
  json_array_begin(&w, "runs");
  run_summary base = {0};
  for (uint32_t k = 0; k < j->run_count; k++) {
    const play_trace* t = j->runs[k];
    run_summary r;
    summarize(t, &r);
    if (k == 0) base = r;
    json_object_begin(&w, NULL);
    json_string(&w, "mode", t->mode);
    json_string(&w, "dir", t->dir);
    json_string(&w, "policy", t->policy);
    json_number(&w, "epsilon_px", t->epsilon);
    json_uint(&w, "max_level", t->max_level);
    json_uint(&w, "frames_requested", t->frames_requested);
    json_uint(&w, "frames", r.frames);
    json_string(&w, "stopped", t->stopped);
    json_number(&w, "wall_s", t->wall_s);
    json_distribution(&w, "frame_ms", &r.frame_ms);
    json_number(&w, "fps", r.frame_ms.mean > 0.0 ? 1000.0 / r.frame_ms.mean : 0.0);
    json_number(&w, "first_frame_ms", r.first_frame_ms);
    json_distribution(&w, "scheduler_ms", &r.scheduler_ms);
    json_object_begin(&w, "stage_ms_mean");
    for (int s = 0; s < TLOD_STAGE_NUM; s++)
      json_number(&w, stage_names[s], r.stage_mean[s]);
    json_object_end(&w);
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

bool play_write_summary_json(const play_trace* const* runs, uint32_t run_count, const char* out_dir, const char* path,
                             char* error, size_t error_size) {
  summary_job j = {runs, run_count, out_dir};
  return write_atomic(path, summary_json, &j, error, error_size);
}

void play_print_summary(FILE* f, const play_trace* const* runs, uint32_t run_count, const char* out_dir) {
  const play_trace* t0 = runs[0];
  fprintf(f, "tlod play: %s (", t0->scene);
  for (uint32_t i = 0; i < t0->object_count; i++)
    fprintf(f, "%s%s %u patches", i ? ", " : "", t0->objects[i].name, t0->objects[i].patches);
  fprintf(f, "), %s surface, path %s (%.3g s%s), %ux%u, %g fps fixed step\n", t0->surface, t0->path,
          t0->path_duration_s, t0->loop ? ", looped" : "", t0->width, t0->height, t0->fps);
  fprintf(f, "backend %s: %s\n", t0->backend, t0->renderer);
  fprintf(f, "%-12s %11s | frame ms: %7s %7s %7s %7s %7s | %6s | %9s %9s | %10s\n", "mode", "frames", "mean", "p50",
          "p95", "p99", "max", "fps", "sched ms", "draw ms", "triangles");
  run_summary base = {0};
  for (uint32_t k = 0; k < run_count; k++) {
    const play_trace* t = runs[k];
    run_summary r;
    summarize(t, &r);
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
    summarize(t, &r);
    fprintf(f, "%s: ", t->mode);
    if (!strcmp(t->mode, "adaptive")) fprintf(f, "%s policy, epsilon %g px, ", t->policy, (double)t->epsilon);
    fprintf(f, "first frame %.2f ms; stages (mean ms):", r.first_frame_ms);
    for (int s = 0; s < TLOD_STAGE_NUM; s++)
      fprintf(f, " %s %.3f", stage_names[s], r.stage_mean[s]);
    fprintf(f, "\n    backend (mean ms): cpu %.3f, wall %.3f, gpu ", r.backend_cpu_ms.mean, r.backend_wall_ms.mean);
    if (r.gpu_frames) {
      fprintf(f, "%.3f (timer query; misses most llvmpipe work)", r.gpu_mean);
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
  summary_job j = {runs, run_count, out_dir};
  return write_atomic(path, summary_text, &j, error, error_size);
}
