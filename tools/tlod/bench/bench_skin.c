/* tlod bench --suite skin -- what a skinned mesh costs per frame on the CPU
 * (docs/play.md "Skinning"): linear blend skinning (skin_apply),
 * tlod_mesh_update and tlod_surface_refresh, timed apart, on the generated
 * two-joint cylinder (skin_cylinder.h) at a few sizes and thread counts.
 * Every frame bends joint 1 to a new angle, so every vertex above the
 * lower third moves. Wall and process CPU time, min and median over the
 * repeats, in ms per frame per 10k skinned vertices. */
#include <math.h>
#include <stdlib.h>
#include <unistd.h>

#include "bench_eval.h"
#include "bench_stats.h"
#include "cli.h"
#include "common/skin_apply.h"
#include "common/skin_cylinder.h"

enum { STAGE_SKIN, STAGE_UPDATE, STAGE_REFRESH, STAGE_COUNT };

typedef struct skin_case {
  tlod_context* ctx;
  skin_cylinder_model m;
} skin_case;

static void case_free(skin_case* c) {
  skin_cylinder_model_free(&c->m);
  tlod_context_destroy(c->ctx);
}

static int case_make(uint32_t segments, uint32_t threads, skin_case* c) {
  *c = (skin_case){0};
  if (tlod_context_create(&(tlod_context_desc){.thread_count = threads, .label = "bench"}, &c->ctx) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "skin: cannot create a context");
  if (!skin_cylinder_model_create(c->ctx, segments, segments, 0.5f, 4.0f, &c->m)) {
    int rc = cli_error(CLI_FAILED, "skin: cannot set up the cylinder: %s", tlod_context_last_error(c->ctx));
    return case_free(c), rc;
  }
  return CLI_OK;
}

/* One frame at pose angle a; wall and CPU ms of each stage into t[stage]. */
static int run_frame(skin_case* c, double a, double wall[STAGE_COUNT], double cpu[STAGE_COUNT]) {
  float q[4] = {0.0f, 0.0f, (float)sin(0.5 * a), (float)cos(0.5 * a)}, mats[2][16];
  skin_cylinder_pose(&c->m.cyl, q, mats);
  skin_vertices sv = {c->m.cyl.vertex_count, c->m.cyl.positions, c->m.cyl.normals, c->m.cyl.joints, c->m.cyl.weights};
  double w0 = cli_now_ms(), c0 = bench_cpu_ms();
  skin_apply(c->ctx, &sv, 2, (const float(*)[16])mats, c->m.positions, c->m.normals);
  double w1 = cli_now_ms(), c1 = bench_cpu_ms();
  tlod_result r = tlod_mesh_update(c->m.mesh, c->m.positions, 0, c->m.normals, 0);
  double w2 = cli_now_ms(), c2 = bench_cpu_ms();
  if (r == TLOD_SUCCESS) r = tlod_surface_refresh(c->m.surface, NULL);
  double w3 = cli_now_ms(), c3 = bench_cpu_ms();
  wall[0] = w1 - w0, wall[1] = w2 - w1, wall[2] = w3 - w2;
  cpu[0] = c1 - c0, cpu[1] = c2 - c1, cpu[2] = c3 - c2;
  return r == TLOD_SUCCESS ? CLI_OK : cli_error(CLI_FAILED, "skin: %s", tlod_context_last_error(c->ctx));
}

static void report(const skin_case* c, uint32_t threads, uint32_t n, double* samples, FILE* csv) {
  static const char* const names[STAGE_COUNT] = {"skin", "mesh_update", "refresh"};
  double per10k = 1e4 / (double)c->m.cyl.vertex_count;
  printf("skin       %7u vertices %7u patches T%-2u", c->m.cyl.vertex_count, tlod_surface_patch_count(c->m.surface),
         threads);
  for (int s = 0; s < STAGE_COUNT; s++) {
    double wall[2], cpu[2];
    bench_min_median(samples + (size_t)(2 * s) * n, n, per10k, wall);
    bench_min_median(samples + (size_t)(2 * s + 1) * n, n, per10k, cpu);
    printf("  %s wall %.3f/%.3f cpu %.3f/%.3f", names[s], wall[0], wall[1], cpu[0], cpu[1]);
    if (csv)
      fprintf(csv, "skin,%u,%u,%s,%.5f,%.5f,%.5f,%.5f\n", c->m.cyl.vertex_count, threads, names[s], wall[0], wall[1],
              cpu[0], cpu[1]);
  }
  printf("\n");
}

static int skin_run(uint32_t segments, uint32_t threads, const bench_options* o, FILE* csv) {
  skin_case c;
  int rc = case_make(segments, threads, &c);
  double* samples = rc == CLI_OK ? malloc(sizeof(double) * 2 * STAGE_COUNT * o->repeat) : NULL;
  if (rc == CLI_OK && !samples) rc = cli_error(CLI_FAILED, "out of memory");
  for (uint32_t k = 0; rc == CLI_OK && k < o->warmup + o->repeat; k++) {
    double wall[STAGE_COUNT], cpu[STAGE_COUNT];
    rc = run_frame(&c, 0.1 + 0.05 * k, wall, cpu);
    for (int s = 0; rc == CLI_OK && k >= o->warmup && s < STAGE_COUNT; s++) {
      samples[(2 * s) * o->repeat + (k - o->warmup)] = wall[s];
      samples[(2 * s + 1) * o->repeat + (k - o->warmup)] = cpu[s];
    }
  }
  if (rc == CLI_OK) report(&c, threads, o->repeat, samples, csv);
  free(samples);
  case_free(&c);
  return rc;
}

/* The option's thread counts, plus the machine's when it is not among them. */
static uint32_t thread_counts(const bench_options* o, uint32_t out[9]) {
  long cpus = sysconf(_SC_NPROCESSORS_ONLN);
  uint32_t n = 0, machine = cpus > 0 && cpus <= 64 ? (uint32_t)cpus : 1;
  int seen = 0;
  for (uint32_t i = 0; i < o->thread_count; i++) {
    out[n++] = o->threads[i];
    seen |= o->threads[i] == machine;
  }
  if (!seen) out[n++] = machine;
  return n;
}

int bench_skin(const bench_options* o, FILE* csv) {
  static const uint32_t segments[] = {100, 200, 400}; /* 10k, 40k, 160k vertices */
  uint32_t threads[9], tn = thread_counts(o, threads);
  printf("tlod bench --suite skin: two-joint cylinder, ms per frame per 10k skinned vertices, min/median of %u "
         "frames after %u warm-up, wall and process CPU time\n",
         o->repeat, o->warmup);
  if (csv) fprintf(csv, "suite,vertices,threads,stage,wall_min,wall_median,cpu_min,cpu_median\n");
  int rc = CLI_OK;
  for (size_t s = 0; s < sizeof segments / sizeof segments[0] && rc == CLI_OK; s++)
    for (uint32_t t = 0; t < tn && rc == CLI_OK; t++)
      rc = skin_run(segments[s], threads[t], o, csv);
  return rc;
}
