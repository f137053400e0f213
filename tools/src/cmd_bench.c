/* tlod bench -- preprocessing and CPU evaluation rates, with the ratios
 * that matter (Phong/flat, PN/flat, output bytes/s against this machine's
 * memory copy bandwidth) measured in one run. Warm-up, then timed repeats;
 * best, mean and worst are reported. */
#include <stdlib.h>
#include <string.h>

#include "bench_gl.h"
#include "bench_lod.h"
#include "cli.h"
#include "commands.h"
#include "tesslod/cpu.h"

typedef struct bench_options {
  const char* in;
  const char* csv;
  uint32_t levels[8], level_count;
  uint32_t threads[8], thread_count;
  uint32_t repeat, warmup, frames;
  const char* suite;
  const char* table1[16];
  uint32_t table1_count;
} bench_options;

typedef struct timing {
  double best, mean, worst;
} timing;

void bench_usage(FILE* f) {
  fprintf(f, "usage: tlod bench [IN] [options]\n"
             "Measures, on IN (default demo:torus-320x160, 102,400 triangles; quads are split):\n"
             "  preprocessing: mesh validation + adjacency + normals, and patch setup per surface (patches/s);\n"
             "  CPU evaluation: tlod_cpu_tessellate per surface, level and thread count (output vertices/s),\n"
             "  the Phong/flat and PN/flat time ratios, and output bytes/s against memcpy bandwidth.\n"
             "  --levels L,L       levels to evaluate (default 3,5)\n"
             "  --threads N,N      thread counts (default 1,2)\n"
             "  --repeat N         timed runs per case (default 3)\n"
             "  --warmup N         untimed runs first (default 1)\n"
             "  --csv FILE         also write one CSV row per case\n"
             "  --suite S          eval (default) | scheduler | table1 | gl | all\n"
             "                     scheduler: time per frame on 10k, 100k, 1M patches (torus), orbiting camera\n"
             "                     table1: Schwarz et al.'s Table 1 (PN, 1600x1144, 0.5 px): base, adaptive per\n"
             "                     policy, uniform at the worst patch's level, strip overhead\n"
             "                     gl: frame times (llvmpipe, wall clock): flat, adaptive, uniform, hardware\n"
             "                     tessellation per model; Phong against flat at equal triangles\n"
             "  --frames N         scheduler / gl frames per case (default 20)\n"
             "  --model IN         a table1 model (repeatable; default demo:cow)\n");
}

static bool parse_list(const char* option, const char* text, uint32_t lo, uint32_t hi, uint32_t* out, uint32_t* count) {
  char buf[128];
  snprintf(buf, sizeof(buf), "%s", text);
  *count = 0;
  for (char* tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
    if (*count == 8 || !cli_parse_uint(option, tok, lo, hi, &out[*count])) return false;
    (*count)++;
  }
  return *count > 0 || (cli_error(CLI_USAGE, "%s: empty list", option), false);
}

static int parse(int argc, char** argv, bench_options* o) {
  *o = (bench_options){.in = "demo:torus-320x160",
                       .levels = {3, 5},
                       .level_count = 2,
                       .threads = {1, 2},
                       .thread_count = 2,
                       .repeat = 3,
                       .warmup = 1,
                       .frames = 20,
                       .suite = "eval"};
  for (int i = 0; i < argc; i++) {
    const char* a = argv[i];
    const char* v = NULL;
    if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
      bench_usage(stdout);
      exit(0);
    } else if (!strcmp(a, "--levels")) {
      if (!(v = cli_value(argc, argv, &i)) || !parse_list(a, v, 0, TLOD_MAX_LEVEL, o->levels, &o->level_count))
        return CLI_USAGE;
    } else if (!strcmp(a, "--threads")) {
      if (!(v = cli_value(argc, argv, &i)) || !parse_list(a, v, 1, 64, o->threads, &o->thread_count)) return CLI_USAGE;
    } else if (!strcmp(a, "--repeat")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_uint(a, v, 1, 1000, &o->repeat)) return CLI_USAGE;
    } else if (!strcmp(a, "--warmup")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_uint(a, v, 0, 1000, &o->warmup)) return CLI_USAGE;
    } else if (!strcmp(a, "--suite")) {
      static const char* const suites[] = {"eval", "scheduler", "table1", "gl", "all", NULL};
      if (!(v = cli_value(argc, argv, &i)) || cli_parse_enum(a, v, suites) < 0) return CLI_USAGE;
      o->suite = v;
    } else if (!strcmp(a, "--frames")) {
      if (!(v = cli_value(argc, argv, &i)) || !cli_parse_uint(a, v, 1, 100000, &o->frames)) return CLI_USAGE;
    } else if (!strcmp(a, "--model")) {
      if (!(v = cli_value(argc, argv, &i))) return CLI_USAGE;
      if (o->table1_count == 16) return cli_error(CLI_USAGE, "--model: at most 16 models");
      o->table1[o->table1_count++] = v;
    } else if (!strcmp(a, "--csv")) {
      if (!(o->csv = cli_value(argc, argv, &i))) return CLI_USAGE;
    } else if (a[0] == '-' && a[1]) {
      return cli_error(CLI_USAGE, "bench: unknown option '%s' (see tlod bench --help)", a);
    } else {
      o->in = a;
    }
  }
  return CLI_OK;
}

static void add_sample(timing* t, double ms, uint32_t n) {
  if (n == 0) *t = (timing){ms, 0.0, ms};
  t->best = ms < t->best ? ms : t->best;
  t->worst = ms > t->worst ? ms : t->worst;
  t->mean += ms;
}

/* Best memcpy rate of a 256 MiB buffer, bytes copied per second. */
static double memcpy_bandwidth(void) {
  size_t bytes = (size_t)256 << 20;
  char* a = malloc(bytes);
  char* b = malloc(bytes);
  double best = 0.0;
  if (a && b) {
    memset(a, 1, bytes);
    memset(b, 2, bytes);
    for (int i = 0; i < 5; i++) {
      double t0 = cli_now_ms();
      memcpy(b, a, bytes);
      double dt = (cli_now_ms() - t0) * 1e-3;
      a[i] = b[bytes - 1 - (size_t)i];
      double rate = (double)bytes / dt;
      best = rate > best ? rate : best;
    }
  }
  free(a);
  free(b);
  return best;
}

static const char* const surface_names[] = {"flat", "phong", "pn"};

typedef struct bench_state {
  const bench_options* o;
  cli_mesh in;
  FILE* csv;
  double flat_ms; /* evaluation time of flat for the current level/threads */
  double bandwidth;
} bench_state;

static void report(bench_state* b, const char* stage, const char* surface, uint32_t level, uint32_t threads,
                   const timing* t, double items, const char* unit, double bytes) {
  double rate = items / (t->best * 1e-3);
  char ratio[32] = "";
  if (!strcmp(stage, "evaluate") && strcmp(surface, "flat") != 0 && b->flat_ms > 0)
    snprintf(ratio, sizeof(ratio), " %s/flat %.2fx", surface, t->best / b->flat_ms);
  char bw[64] = "";
  if (bytes > 0)
    snprintf(bw, sizeof(bw), " out %.2f GB/s = %.0f%% of memcpy", bytes / (t->best * 1e-3) * 1e-9,
             100.0 * bytes / (t->best * 1e-3) / b->bandwidth);
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
  report(b, "patches", surface_names[type - TLOD_SURFACE_FLAT], 0, tlod_context_query_desc(ctx).thread_count, &tm,
         tlod_mesh_face_count(mesh), "patch", 0);
  return CLI_OK;
}

static int bench_evaluate(bench_state* b, tlod_context* ctx, tlod_surface* s, const tlod_patterns* pat, uint32_t level,
                          tlod_surface_type type) {
  const bench_options* o = b->o;
  timing tm = {0};
  double vertices = 0, bytes = 0;
  /* One output reused run after run, as a per-frame caller would: the
   * figure is the steady state, not first-touch page faults. */
  tlod_cpu_mesh* out = NULL;
  if (tlod_cpu_tessellate(ctx, s, pat, &(tlod_cpu_tessellate_desc){.level = level}, &out) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "%s", tlod_context_last_error(ctx));
  for (uint32_t r = 0; r < o->warmup + o->repeat; r++) {
    double t0 = cli_now_ms();
    tlod_result res = tlod_cpu_tessellate_into(ctx, s, pat, &(tlod_cpu_tessellate_desc){.level = level}, out);
    double dt = cli_now_ms() - t0;
    if (res != TLOD_SUCCESS) {
      tlod_cpu_mesh_destroy(ctx, out);
      return cli_error(CLI_FAILED, "%s", tlod_context_last_error(ctx));
    }
    vertices = out->vertex_count;
    bytes = (double)out->vertex_count * 24.0 + (double)out->triangle_count * 16.0;
    if (r >= o->warmup) add_sample(&tm, dt, r - o->warmup);
  }
  tlod_cpu_mesh_destroy(ctx, out);
  tm.mean /= o->repeat;
  if (type == TLOD_SURFACE_FLAT) b->flat_ms = tm.best;
  report(b, "evaluate", surface_names[type - TLOD_SURFACE_FLAT], level, tlod_context_query_desc(ctx).thread_count, &tm,
         vertices, "vert", bytes);
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

static int run_lod_suites(const bench_options* o, double bandwidth, FILE* csv) {
  static const char* const default_models[] = {"demo:cow"};
  bench_lod_options lo = {o->threads, o->thread_count, o->frames, o->table1_count ? o->table1 : default_models,
                          o->table1_count ? o->table1_count : 1};
  bool all = !strcmp(o->suite, "all");
  int rc = CLI_OK;
  if (all || !strcmp(o->suite, "scheduler")) rc = bench_scheduler(&lo, bandwidth, csv);
  if (rc == CLI_OK && (all || !strcmp(o->suite, "table1"))) rc = bench_table1(&lo, csv);
  if (rc == CLI_OK && (all || !strcmp(o->suite, "gl"))) rc = bench_gl(lo.inputs, lo.input_count, o->frames, csv);
  return rc;
}

int cmd_bench(int argc, char** argv) {
  bench_options o;
  int rc = parse(argc, argv, &o);
  if (rc != CLI_OK) return rc;
  if (strcmp(o.suite, "eval") != 0 && strcmp(o.suite, "all") != 0) {
    FILE* csv = o.csv ? fopen(o.csv, "w") : NULL;
    if (o.csv && !csv) return cli_error(CLI_FAILED, "cannot write '%s'", o.csv);
    double bw = memcpy_bandwidth();
    printf("tlod bench --suite %s: memcpy %.2f GB/s\n", o.suite, bw * 1e-9);
    rc = run_lod_suites(&o, bw, csv);
    if (csv && fclose(csv) != 0 && rc == CLI_OK) rc = cli_error(CLI_FAILED, "cannot write '%s'", o.csv);
    return rc;
  }
  bench_state b = {.o = &o};
  if ((rc = cli_load(o.in, &b.in)) != CLI_OK || (rc = cli_split_quads(&b.in)) != CLI_OK) return rc;
  if (o.csv && !(b.csv = fopen(o.csv, "w"))) {
    cli_mesh_free(&b.in);
    return cli_error(CLI_FAILED, "cannot write '%s'", o.csv);
  }
  if (b.csv)
    fprintf(b.csv, "stage,surface,level,threads,best_ms,mean_ms,worst_ms,items,unit,rate_per_s,out_bytes_per_s\n");
  b.bandwidth = memcpy_bandwidth();
  printf("tlod bench: %s, %u triangles, %u vertices; memcpy %.2f GB/s (bytes copied per second, best of 5)\n", o.in,
         b.in.face_count, b.in.vertex_count, b.bandwidth * 1e-9);
  for (uint32_t i = 0; i < o.thread_count && rc == CLI_OK; i++)
    rc = bench_threads(&b, o.threads[i]);
  if (b.csv && fclose(b.csv) != 0 && rc == CLI_OK) rc = cli_error(CLI_FAILED, "cannot write '%s'", o.csv);
  cli_mesh_free(&b.in);
  return rc;
}
