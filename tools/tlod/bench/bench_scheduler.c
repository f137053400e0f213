/* tlod bench --suite scheduler -- time per frame of tlod_scheduler_update on
 * 10k, 100k and 1M patches (or --scheduler-mesh; demo:torus-NxM, Phong quads, levels 0-6), with a
 * refining camera just above the tube (bench_refine_view: levels 0-6,
 * contours, strips, culling), moving along the ring or still. Process CPU
 * time (every thread) beside wall time, min and median over the frames, the
 * stage split, the level histogram, the culled share and the strip
 * triangles (so a case that ends at level 0 everywhere shows), and the
 * memory bound of the bytes a frame must touch. */
#include <math.h>
#include <stdlib.h>

#include "bench_bandwidth.h"
#include "bench_lod.h"
#include "bench_report.h"
#include "bench_stats.h"

#define SCHED_W 1280
#define SCHED_H 720
#define SCHED_WARMUP 2
/* The still camera's warm-up ends when an update leaves the draw list's
 * generation as it was (time-based morphs converged: 200 ms per level at
 * 16.7 ms frames, up to 7 levels, ~84 frames), or after this many. */
#define SCHED_STILL_WARMUP_MAX 100
#define SCHED_MAX_LEVEL 6
/* The refining view's epsilon: Phong's error on a 1000x1000 torus is a few
 * thousandths of a pixel a metre away, so level 6 (error / 4^6) near the
 * eye needs a small epsilon; 0.5 px would end at level 0 everywhere. */
#define SCHED_EPSILON_PX 0.002f

typedef struct sched_case {
  const char* name;
  bool moving;
} sched_case;

static const sched_case k_cases[] = {{"refine-moving", true}, {"refine-static", false}};

/* Per frame the least bytes read: position and normal per vertex (24 B),
 * per patch its sphere, error bound and corner ids (16 + 4 + 16 B) and its
 * corner depths (16 B); written: depth per vertex (4 B), per patch level,
 * e_max, contour, target, continuous level, visibility (1+4+4+4+4+1 B)
 * and its 12 B draw instance. */
static void frame_bytes(uint32_t vertices, uint32_t patches, double* read, double* written) {
  *read = (double)vertices * 24.0 + (double)patches * (16.0 + 4.0 + 16.0 + 16.0);
  *written = (double)vertices * 4.0 + (double)patches * (18.0 + 12.0);
}

/* The scheduler's clusters (lod/src/scheduler_fast.h FAST_BLOCK, FAST_VCHUNK):
 * a culled block costs only its sphere test (40 B), a vertex chunk no
 * visible block reads costs nothing. */
#define SCHED_BLOCK 128u
#define SCHED_VCHUNK 256u

static bool block_visible(const tlod_draw_list* dl, uint32_t b) {
  for (uint32_t f = b * SCHED_BLOCK; f < dl->patch_count && f < (b + 1) * SCHED_BLOCK; f++)
    if (dl->levels[f] >= 0) return true;
  return false;
}

/* frame_bytes over what the last frame dl read: the patches of blocks with a
 * visible patch, the vertices of chunks such a block reads, the block tests. */
static void visible_bytes(const tlod_mesh* m, const tlod_draw_list* dl, double* read, double* written) {
  uint32_t nv = tlod_mesh_vertex_count(m), chunks = (nv + SCHED_VCHUNK - 1) / SCHED_VCHUNK;
  uint32_t blocks = (dl->patch_count + SCHED_BLOCK - 1) / SCHED_BLOCK, seen = 0, patches = 0;
  uint8_t* used = calloc(chunks + 1, 1);
  for (uint32_t b = 0; used && b < blocks; b++) {
    if (!block_visible(dl, b)) continue;
    for (uint32_t f = b * SCHED_BLOCK; f < dl->patch_count && f < (b + 1) * SCHED_BLOCK; f++, patches++) {
      uint32_t c[4], n = tlod_mesh_face_corners(m, f, c);
      for (uint32_t j = 0; j < n; j++)
        used[c[j] / SCHED_VCHUNK] = 1;
    }
  }
  for (uint32_t j = 0; used && j < chunks; j++)
    seen += used[j];
  uint32_t vertices = seen * SCHED_VCHUNK < nv ? seen * SCHED_VCHUNK : nv;
  free(used);
  frame_bytes(vertices, patches, read, written);
  *read += 40.0 * blocks;
}

typedef struct sched_figures {
  double wall[2], cpu[2];       /* min, median ms per frame */
  double caller[2];             /* the calling thread CPU, min and median ms */
  double stage[TLOD_STAGE_NUM]; /* median ms per stage */
  double bound_ms;
  double visible_read, visible_written; /* bytes of the last frame (visible_bytes) */
  double visible_bound_ms;
  uint32_t warmup;     /* frames before the timed ones */
  tlod_draw_list last; /* statistics of the last frame */
} sched_figures;

static void update(tlod_scheduler* sch, const sched_case* c, uint32_t k) {
  tlod_view_desc view;
  bench_refine_view(c->moving ? 0.003f * (float)k : 0.0f, SCHED_W, SCHED_H, &view);
  tlod_scheduler_update(sch, &(tlod_frame_desc){.views = &view, .view_count = 1, .dt_ms = 16.7f});
}

/* Warm-up frames; the still camera's run until its morphs have converged.
 * Returns how many ran. */
static uint32_t warm_up(tlod_scheduler* sch, const sched_case* c) {
  uint32_t k = 0;
  for (; k < SCHED_WARMUP; k++)
    update(sch, c, k);
  uint64_t gen = tlod_scheduler_draw_list(sch, 0)->generation;
  for (; !c->moving && k < SCHED_STILL_WARMUP_MAX; k++) {
    update(sch, c, k);
    uint64_t now = tlod_scheduler_draw_list(sch, 0)->generation;
    if (now == gen) break;
    gen = now;
  }
  return k;
}

static void time_frames(tlod_scheduler* sch, const sched_case* c, uint32_t frames, double* t, uint32_t* warmup) {
  *warmup = warm_up(sch, c);
  for (uint32_t k = *warmup; k < frames + *warmup; k++) {
    double w0 = cli_now_ms(), c0 = bench_cpu_ms(), h0 = bench_thread_cpu_ms();
    update(sch, c, k);
    double cpu = bench_cpu_ms() - c0, caller = bench_thread_cpu_ms() - h0, wall = cli_now_ms() - w0;
    uint32_t i = k - *warmup;
    t[i] = wall, t[frames + i] = cpu, t[2 * frames + i] = caller;
    for (int st = 0; st < TLOD_STAGE_NUM; st++)
      t[(3 + st) * frames + i] = tlod_scheduler_draw_list(sch, 0)->stage_ms[st];
  }
}

static int run_case(const bench_scene* s, const sched_case* c, uint32_t frames, sched_figures* f) {
  tlod_scheduler* sch = NULL;
  tlod_scheduler_desc d = {.epsilon_px = SCHED_EPSILON_PX, .max_level = SCHED_MAX_LEVEL};
  double* t = malloc(sizeof(double) * (3 + TLOD_STAGE_NUM) * frames);
  if (!t || tlod_scheduler_create(s->ctx, s->setup.surface, s->setup.patterns, &d, &sch) != TLOD_SUCCESS) {
    free(t);
    return cli_error(CLI_FAILED, "%s", t ? tlod_context_last_error(s->ctx) : "out of memory");
  }
  time_frames(sch, c, frames, t, &f->warmup);
  bench_min_median(t, frames, 1.0, f->wall);
  bench_min_median(t + frames, frames, 1.0, f->cpu);
  bench_min_median(t + 2 * frames, frames, 1.0, f->caller);
  for (int st = 0; st < TLOD_STAGE_NUM; st++) {
    double mm[2];
    bench_min_median(t + (3 + st) * frames, frames, 1.0, mm);
    f->stage[st] = mm[1];
  }
  f->last = *tlod_scheduler_draw_list(sch, 0);
  visible_bytes(s->setup.mesh, &f->last, &f->visible_read, &f->visible_written);
  tlod_scheduler_destroy(sch);
  free(t);
  return CLI_OK;
}

static void print_case(const char* in, const sched_case* c, uint32_t threads, const sched_figures* f) {
  const tlod_draw_list* dl = &f->last;
  /* A frame that touched next to nothing (a still camera's no-op update)
   * is not read against the bound of a frame that plans every patch. */
  char share[32] = "- (no-op frames)";
  if (f->cpu[1] > 0.01 * f->bound_ms) snprintf(share, sizeof(share), "%.0f%%", 100.0 * f->bound_ms / f->cpu[1]);
  printf("scheduler  %-20s %-13s T%-2u %8u patches  cpu min %8.3f median %8.3f ms | wall min %8.3f median %8.3f ms | "
         "caller thread cpu median %8.3f ms | bound %.3f cpu ms = %s of cpu median (visible blocks' bytes %.3f)\n",
         in, c->name, threads, dl->patch_count, f->cpu[0], f->cpu[1], f->wall[0], f->wall[1], f->caller[1], f->bound_ms,
         share, f->visible_bound_ms);
  printf("scheduler    after %u warm-up frames; stages median ms (wall):", f->warmup);
  for (int st = 0; st < TLOD_STAGE_NUM; st++)
    printf(" %s %.3f", tlod_stage_name((tlod_stage)st), f->stage[st]);
  printf(" | culled %.1f%% | levels", 100.0 * dl->culled / (dl->patch_count ? dl->patch_count : 1));
  for (int l = 0; l <= SCHED_MAX_LEVEL; l++)
    printf(" %u", dl->level_histogram[l]);
  printf(" | pattern tris %llu strip tris %llu (%.1f%%) strips %u\n", (unsigned long long)dl->pattern_triangles,
         (unsigned long long)dl->strip_triangles,
         100.0 * (double)dl->strip_triangles / (double)(dl->pattern_triangles ? dl->pattern_triangles : 1),
         dl->strip_count);
}

static void write_csv(FILE* csv, const char* in, const sched_case* c, uint32_t threads, const sched_figures* f) {
  const tlod_draw_list* dl = &f->last;
  fprintf(csv, "scheduler,%s,%s,%u,%u,%.4f,%.4f,%.4f,%.4f,%.4f,%u,%llu,%llu", in, c->name, threads, dl->patch_count,
          f->cpu[0], f->cpu[1], f->wall[0], f->wall[1], f->bound_ms, dl->culled,
          (unsigned long long)dl->pattern_triangles, (unsigned long long)dl->strip_triangles);
  for (int st = 0; st < TLOD_STAGE_NUM; st++)
    fprintf(csv, ",%.4f", f->stage[st]);
  for (int l = 0; l <= SCHED_MAX_LEVEL; l++)
    fprintf(csv, ",%u", dl->level_histogram[l]);
  fprintf(csv, "\n");
}

static void write_json(json_writer* w, const char* in, const sched_case* c, uint32_t threads, const sched_figures* f) {
  const tlod_draw_list* dl = &f->last;
  json_object_begin(w, NULL);
  json_string(w, "mesh", in);
  json_string(w, "camera", c->name);
  json_uint(w, "threads", threads);
  json_uint(w, "patches", dl->patch_count);
  json_uint(w, "warmup_frames", f->warmup);
  json_number(w, "cpu_min_ms", f->cpu[0]);
  json_number(w, "cpu_median_ms", f->cpu[1]);
  json_number(w, "wall_min_ms", f->wall[0]);
  json_number(w, "wall_median_ms", f->wall[1]);
  json_number(w, "caller_cpu_median_ms", f->caller[1]);
  json_number(w, "bound_ms", f->bound_ms);
  json_number(w, "visible_bound_ms", f->visible_bound_ms);
  json_object_begin(w, "stage_median_ms");
  for (int st = 0; st < TLOD_STAGE_NUM; st++)
    json_number(w, tlod_stage_name((tlod_stage)st), f->stage[st]);
  json_object_end(w);
  json_array_begin(w, "level_histogram");
  for (int l = 0; l <= SCHED_MAX_LEVEL; l++)
    json_uint(w, NULL, dl->level_histogram[l]);
  json_array_end(w);
  json_uint(w, "culled", dl->culled);
  json_uint(w, "pattern_triangles", dl->pattern_triangles);
  json_uint(w, "strip_triangles", dl->strip_triangles);
  json_object_end(w);
}

/* The headline figure: the moving refining camera on 2 threads. */
static void note_figure(bench_report* rep, const char* in, const sched_case* c, uint32_t threads,
                        const sched_figures* f) {
  if (!c->moving || threads != 2 || f->last.patch_count < rep->scheduler_patches) return;
  rep->scheduler_1m_ms = f->cpu[1] / 2.0;
  rep->scheduler_1m_cpu_ms = f->cpu[1];
  rep->scheduler_1m_wall_ms = f->wall[1];
  rep->scheduler_mesh = in;
  rep->scheduler_patches = f->last.patch_count;
}

static int mesh_cases(const char* in, uint32_t threads, const bench_lod_options* o, bench_report* rep, FILE* csv) {
  bench_scene s;
  int rc = bench_scene_load(in, threads, TLOD_SURFACE_PHONG, SCHED_MAX_LEVEL, &s);
  double read, written;
  frame_bytes(tlod_mesh_vertex_count(s.setup.mesh), tlod_surface_patch_count(s.setup.surface), &read, &written);
  for (size_t k = 0; rc == CLI_OK && k < sizeof k_cases / sizeof k_cases[0]; k++) {
    sched_figures f;
    rc = run_case(&s, &k_cases[k], o->frames, &f);
    if (rc != CLI_OK) break;
    f.bound_ms = bench_bound_ms(bench_bandwidth_rates(&rep->bw, threads), read, written);
    f.visible_bound_ms = bench_bound_ms(bench_bandwidth_rates(&rep->bw, threads), f.visible_read, f.visible_written);
    print_case(in, &k_cases[k], threads, &f);
    if (csv) write_csv(csv, in, &k_cases[k], threads, &f);
    if (rep->json) write_json(rep->json, in, &k_cases[k], threads, &f);
    note_figure(rep, in, &k_cases[k], threads, &f);
  }
  if (rc == CLI_OK) bench_scene_free(&s);
  return rc;
}

int bench_scheduler(const bench_lod_options* o, bench_report* rep, FILE* csv) {
  printf(
      "scheduler: Phong quads, %ux%u, epsilon %g px, HYBRID, TIME morphs, %u warm-up (still camera: until its morphs "
      "converged) + %u frames per case; cpu = "
      "process CPU time of every thread per frame, wall = wall clock; bound = bytes a frame must touch at the "
      "measured rates\n",
      SCHED_W, SCHED_H, (double)SCHED_EPSILON_PX, SCHED_WARMUP, o->frames);
  if (csv)
    fprintf(csv, "suite,mesh,camera,threads,patches,cpu_min_ms,cpu_median_ms,wall_min_ms,wall_median_ms,bound_ms,"
                 "culled,pattern_triangles,strip_triangles,silhouette_ms,metric_ms,levels_ms,morph_ms,strips_ms");
  for (int l = 0; csv && l <= SCHED_MAX_LEVEL; l++)
    fprintf(csv, ",l%d", l);
  if (csv) fprintf(csv, "\n");
  int rc = CLI_OK;
  if (rep->json) json_array_begin(rep->json, "scheduler");
  for (uint32_t m = 0; m < o->mesh_count && rc == CLI_OK; m++)
    for (uint32_t t = 0; t < o->thread_count && rc == CLI_OK; t++)
      rc = mesh_cases(o->meshes[m], o->threads[t], o, rep, csv);
  if (rep->json) json_array_end(rep->json);
  return rc;
}
