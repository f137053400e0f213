/* tlod bench --suite eval -- preprocessing and CPU evaluation rates, with
 * the ratios that matter (Phong/flat, PN/flat, output bytes/s against this
 * machine's memory copy bandwidth) measured in one run. Warm-up, then timed
 * repeats; best, mean and worst are reported. */
#include "bench_eval.h"

#include <stdlib.h>

#include "bench_report.h"
#include "bench_stats.h"

#include <string.h>

#include "cli.h"
#include "common/scene_setup.h"
#include "tesslod/cpu.h"
#include "tool_names.h"

typedef struct timing {
  double best, mean, worst;
} timing;

static void add_sample(timing* t, double ms, uint32_t n) {
  if (n == 0) *t = (timing){ms, 0.0, ms};
  t->best = ms < t->best ? ms : t->best;
  t->worst = ms > t->worst ? ms : t->worst;
  t->mean += ms;
}

typedef struct bench_state {
  const bench_options* o;
  cli_mesh in;
  FILE* csv;
  double flat_ms;    /* evaluation time of flat for the current level/threads */
  bench_report* rep; /* memory rates of this run, json, eval_bandwidth_fraction */
} bench_state;

static void report(bench_state* b, const char* stage, const char* surface, uint32_t level, uint32_t threads,
                   const timing* t, double items, const char* unit, double bytes) {
  double rate = items / (t->best * 1e-3);
  char ratio[32] = "";
  if (!strcmp(stage, "evaluate") && strcmp(surface, "flat") != 0 && b->flat_ms > 0)
    snprintf(ratio, sizeof(ratio), " %s/flat %.2fx", surface, t->best / b->flat_ms);
  char bw[64] = "";
  double copy = bench_bandwidth_rates(&b->rep->bw, threads)->copy_wall;
  if (bytes > 0)
    snprintf(bw, sizeof(bw), " out %.2f GB/s = %.0f%% of memcpy T%u (wall)", bytes / (t->best * 1e-3) * 1e-9,
             100.0 * bytes / (t->best * 1e-3) / copy, threads >= 2 ? 2 : 1);
  printf("%-10s %-6s L%-2u T%-2u best %9.2f ms mean %9.2f worst %9.2f  %8.2f M%s/s%s%s\n", stage, surface, level,
         threads, t->best, t->mean, t->worst, rate * 1e-6, unit, ratio, bw);
  if (b->csv)
    fprintf(b->csv, "%s,%s,%u,%u,%.4f,%.4f,%.4f,%.0f,%s,%.6g,%.6g\n", stage, surface, level, threads, t->best, t->mean,
            t->worst, items, unit, rate, bytes > 0 ? bytes / (t->best * 1e-3) : 0.0);
}

static int bench_preprocess(bench_state* b, tlod_context* ctx) {
  const bench_options* o = b->o;
  timing tm = {0};
  for (uint32_t r = 0; r < o->warmup + o->repeat; r++) {
    tlod_mesh* mesh = NULL;
    double t0 = cli_now_ms();
    if (cli_create_mesh(ctx, &b->in, TLOD_NORMALS_KEEP, 0.0f, &mesh) != CLI_OK) return CLI_FAILED;
    double dt = cli_now_ms() - t0;
    tlod_mesh_destroy(mesh);
    if (r >= o->warmup) add_sample(&tm, dt, r - o->warmup);
  }
  tm.mean /= o->repeat;
  report(b, "mesh", "-", 0, tlod_context_query_desc(ctx).thread_count, &tm, b->in.face_count, "face", 0);
  return CLI_OK;
}

static int bench_surface(bench_state* b, tlod_context* ctx, tlod_mesh* mesh, tlod_surface_type type,
                         tlod_surface** keep) {
  const bench_options* o = b->o;
  timing tm = {0};
  for (uint32_t r = 0; r < o->warmup + o->repeat; r++) {
    tlod_surface* s = NULL;
    double t0 = cli_now_ms();
    if (tlod_surface_create(ctx, mesh, &(tlod_surface_desc){.type = type}, &s) != TLOD_SUCCESS)
      return cli_error(CLI_FAILED, "%s", tlod_context_last_error(ctx));
    double dt = cli_now_ms() - t0;
    if (r + 1 == o->warmup + o->repeat) {
      *keep = s;
    } else {
      tlod_surface_destroy(s);
    }
    if (r >= o->warmup) add_sample(&tm, dt, r - o->warmup);
  }
  tm.mean /= o->repeat;
  report(b, "patches", tool_surface_name(type), 0, tlod_context_query_desc(ctx).thread_count, &tm,
         tlod_mesh_face_count(mesh), "patch", 0);
  return CLI_OK;
}

/* Output bytes per CPU-second of the process (the host's other load does
 * not count) against memcpy's bytes copied per CPU-second at T. */
static void report_cpu(bench_state* b, tlod_surface_type type, uint32_t level, uint32_t threads, double* cpu,
                       uint32_t n, double bytes) {
  double mm[2];
  bench_min_median(cpu, n, 1.0, mm);
  double rate = bytes / (mm[1] * 1e-3), copy = bench_bandwidth_rates(&b->rep->bw, threads)->copy;
  printf("evaluate   %-6s L%-2u T%-2u cpu min %9.2f median %9.2f ms  out %.2f GB per CPU-second (median) = %.0f%% of "
         "memcpy T%u\n",
         tool_surface_name(type), level, threads, mm[0], mm[1], rate * 1e-9, 100.0 * rate / copy, threads >= 2 ? 2 : 1);
  if (type == TLOD_SURFACE_PHONG && level == 5 && threads == 2) b->rep->eval_bandwidth_fraction = rate / copy;
  json_writer* w = b->rep->json;
  if (!w) return;
  json_object_begin(w, NULL);
  json_string(w, "surface", tool_surface_name(type));
  json_uint(w, "level", level);
  json_uint(w, "threads", threads);
  json_number(w, "cpu_min_ms", mm[0]);
  json_number(w, "cpu_median_ms", mm[1]);
  json_number(w, "output_bytes", bytes);
  json_number(w, "memcpy_fraction", rate / copy);
  json_object_end(w);
}

/* Every byte the evaluation writes: per vertex position, normal, patch and
 * (u, v); per triangle 3 indices and its patch (NULL arrays count nothing). */
static double output_bytes(const tlod_cpu_mesh* m) {
  double per_vertex = 12.0 + (m->normals ? 12.0 : 0.0) + (m->vertex_patch ? 4.0 : 0.0) + (m->vertex_uv ? 8.0 : 0.0);
  double per_triangle = 12.0 + (m->triangle_patch ? 4.0 : 0.0);
  return (double)m->vertex_count * per_vertex + (double)m->triangle_count * per_triangle;
}

static int bench_evaluate(bench_state* b, tlod_context* ctx, tlod_surface* s, const tlod_patterns* pat, uint32_t level,
                          tlod_surface_type type) {
  const bench_options* o = b->o;
  timing tm = {0};
  double* cpu = malloc(sizeof(double) * o->repeat);
  if (!cpu) return cli_error(CLI_FAILED, "out of memory");
  double vertices = 0, bytes = 0;
  /* One output reused run after run, as a per-frame caller would: the
   * figure is the steady state, not first-touch page faults. */
  tlod_cpu_mesh* out = NULL;
  if (tlod_cpu_tessellate(ctx, s, pat, &(tlod_cpu_tessellate_desc){.level = level}, &out) != TLOD_SUCCESS) {
    free(cpu);
    return cli_error(CLI_FAILED, "%s", tlod_context_last_error(ctx));
  }
  for (uint32_t r = 0; r < o->warmup + o->repeat; r++) {
    double t0 = cli_now_ms(), c0 = bench_cpu_ms();
    tlod_result res = tlod_cpu_tessellate_into(ctx, s, pat, &(tlod_cpu_tessellate_desc){.level = level}, out);
    double dt = cli_now_ms() - t0, dc = bench_cpu_ms() - c0;
    if (res != TLOD_SUCCESS) {
      tlod_cpu_mesh_destroy(ctx, out);
      free(cpu);
      return cli_error(CLI_FAILED, "%s", tlod_context_last_error(ctx));
    }
    vertices = out->vertex_count;
    bytes = output_bytes(out);
    if (r >= o->warmup) add_sample(&tm, dt, r - o->warmup), cpu[r - o->warmup] = dc;
  }
  tlod_cpu_mesh_destroy(ctx, out);
  tm.mean /= o->repeat;
  if (type == TLOD_SURFACE_FLAT) b->flat_ms = tm.best;
  uint32_t threads = tlod_context_query_desc(ctx).thread_count;
  report(b, "evaluate", tool_surface_name(type), level, threads, &tm, vertices, "vert", bytes);
  report_cpu(b, type, level, threads, cpu, o->repeat, bytes);
  free(cpu);
  return CLI_OK;
}

static int bench_threads(bench_state* b, uint32_t threads) {
  tlod_context* ctx = NULL;
  if (tlod_context_create(&(tlod_context_desc){.thread_count = threads, .label = "bench"}, &ctx) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "cannot create a context");
  tlod_mesh* mesh = NULL;
  tlod_surface* surfaces[3] = {0};
  tlod_patterns* pat = NULL;
  uint32_t max_level = 1;
  for (uint32_t i = 0; i < b->o->level_count; i++)
    max_level = b->o->levels[i] > max_level ? b->o->levels[i] : max_level;
  int rc = bench_preprocess(b, ctx);
  if (rc == CLI_OK) rc = cli_create_mesh(ctx, &b->in, TLOD_NORMALS_KEEP, 0.0f, &mesh);
  for (int k = 0; k < 3 && rc == CLI_OK; k++)
    rc = bench_surface(b, ctx, mesh, TLOD_SURFACE_FLAT + k, &surfaces[k]);
  if (rc == CLI_OK && tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = max_level}, &pat) != TLOD_SUCCESS)
    rc = cli_error(CLI_FAILED, "%s", tlod_context_last_error(ctx));
  for (uint32_t i = 0; i < b->o->level_count && rc == CLI_OK; i++) {
    for (int k = 0; k < 3 && rc == CLI_OK; k++)
      rc = bench_evaluate(b, ctx, surfaces[k], pat, b->o->levels[i], TLOD_SURFACE_FLAT + k);
  }
  tlod_patterns_destroy(pat);
  for (int k = 0; k < 3; k++)
    tlod_surface_destroy(surfaces[k]);
  tlod_mesh_destroy(mesh);
  tlod_context_destroy(ctx);
  return rc;
}

int bench_eval(const bench_options* o, bench_report* rep, FILE* csv) {
  bench_state b = {.o = o, .csv = csv, .rep = rep};
  scene_setup_desc d = {.input = o->in, .split_quads = true};
  int rc = scene_input_load(&d, &b.in);
  if (rc != CLI_OK) return rc;
  if (b.csv)
    fprintf(b.csv, "stage,surface,level,threads,best_ms,mean_ms,worst_ms,items,unit,rate_per_s,out_bytes_per_s\n");
  printf("tlod bench: %s, %u triangles, %u vertices; output bytes: 36 per vertex (position, normal, patch id, "
         "u v) + 16 per triangle (3 indices + patch id)\n",
         o->in, b.in.face_count, b.in.vertex_count);
  if (rep->json) json_array_begin(rep->json, "eval");
  for (uint32_t i = 0; i < o->thread_count && rc == CLI_OK; i++)
    rc = bench_threads(&b, o->threads[i]);
  if (rep->json) json_array_end(rep->json);
  cli_mesh_free(&b.in);
  return rc;
}
