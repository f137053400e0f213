/* tlod bench --suite build -- what the per-level error tables (issue #9)
 * cost at surface build: tlod_surface_create on one thread (context
 * thread_count 1, so process CPU time is the build's), the MEASURED tables
 * against CLOSED_FORM (error_bound * 4^-l, the build as it was before the
 * tables), per surface type; rounds interleave the two modes (alternating
 * which goes first) so machine noise hits both alike; min and median per
 * 100k patches, and the bytes per patch the tables take. */
#include <stdlib.h>
#include <string.h>

#include "bench_eval.h"
#include "bench_stats.h"
#include "cli.h"
#include "common/scene_setup.h"

typedef struct build_case {
  const char* name;
  tlod_surface_type type;
  tlod_alpha_mode alpha_mode;
} build_case;

static const build_case k_build_cases[] = {
    {"flat", TLOD_SURFACE_FLAT, TLOD_ALPHA_DEFAULT},
    {"phong", TLOD_SURFACE_PHONG, TLOD_ALPHA_DEFAULT}, /* one alpha, 0.75 */
    {"phong-pv", TLOD_SURFACE_PHONG, TLOD_ALPHA_PER_VERTEX},
    {"pn", TLOD_SURFACE_PN, TLOD_ALPHA_DEFAULT},
};

/* One build's CPU time in ms, or a negative value (error printed). */
static double time_build(tlod_context* ctx, const tlod_mesh* mesh, const tlod_surface_desc* d) {
  tlod_surface* s = NULL;
  double t0 = bench_cpu_ms();
  tlod_result r = tlod_surface_create(ctx, mesh, d, &s);
  double t = bench_cpu_ms() - t0;
  tlod_surface_destroy(s);
  return r == TLOD_SUCCESS ? t : (cli_error(CLI_FAILED, "%s", tlod_context_last_error(ctx)), -1.0);
}

/* Warm-up, then `repeat` rounds of one MEASURED and one CLOSED_FORM build
 * each; fig[mode] = {min, median} ms per 100k patches. */
static int run_case(tlod_context* ctx, const tlod_mesh* mesh, const build_case* c, const bench_options* o,
                    double fig[2][2]) {
  static const tlod_error_tables modes[2] = {TLOD_ERROR_TABLES_MEASURED, TLOD_ERROR_TABLES_CLOSED_FORM};
  double* t = malloc(sizeof(double) * 2 * o->repeat);
  if (!t) return cli_error(CLI_FAILED, "out of memory");
  for (uint32_t r = 0; r < o->warmup + o->repeat; r++) {
    for (int k = 0; k < 2; k++) {
      int m = (r % 2) ? 1 - k : k;
      tlod_surface_desc d = {.type = c->type, .alpha_mode = c->alpha_mode, .error_tables = modes[m]};
      double ms = time_build(ctx, mesh, &d);
      if (ms < 0.0) return free(t), CLI_FAILED;
      if (r >= o->warmup) t[m * o->repeat + (r - o->warmup)] = ms;
    }
  }
  double per100k = 1e5 / (double)tlod_mesh_face_count(mesh);
  bench_min_median(t, o->repeat, per100k, fig[0]);
  bench_min_median(t + o->repeat, o->repeat, per100k, fig[1]);
  free(t);
  return CLI_OK;
}

/* A deterministic alpha in [0.25, 1] per vertex (the PER_VERTEX case). */
static float* make_alphas(uint32_t n) {
  float* a = malloc(sizeof(float) * (n ? n : 1));
  uint64_t x = 0x9E3779B97F4A7C15ull;
  for (uint32_t v = 0; a && v < n; v++) {
    x = x * 6364136223846793005ull + 1442695040888963407ull;
    a[v] = 0.25f + 0.75f * (float)(x >> 40) / (float)(1u << 24);
  }
  return a;
}

static int make_mesh(tlod_context* ctx, const cli_mesh* m, const float* alphas, tlod_mesh** out) {
  tlod_mesh_desc d = {.positions = m->positions,
                      .normals = m->normals,
                      .alphas = alphas,
                      .vertex_count = m->vertex_count,
                      .indices = m->indices,
                      .index_count = m->index_count,
                      .face_type = TLOD_FACE_TRIANGLES,
                      .label = m->name};
  if (tlod_mesh_create(ctx, &d, out) != TLOD_SUCCESS) return cli_error(CLI_FAILED, "%s", tlod_context_last_error(ctx));
  return CLI_OK;
}

static void print_bytes(void) {
  size_t table = sizeof(((tlod_patch_info*)0)->error_table) + 2 * sizeof(float);
  printf("build      bytes per patch: tlod_patch_info %zu B, of which error_table[%d] + error_tail + error_slack %zu B "
         "(%zu B before issue #9); both modes store the same fields\n",
         sizeof(tlod_patch_info), TLOD_ERROR_TABLE_LEVELS, table, sizeof(tlod_patch_info) - table);
}

static int run_cases(tlod_context* ctx, const tlod_mesh* mesh, const bench_options* o, FILE* csv) {
  int rc = CLI_OK;
  for (size_t k = 0; k < sizeof k_build_cases / sizeof k_build_cases[0] && rc == CLI_OK; k++) {
    const build_case* c = &k_build_cases[k];
    double fig[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
    rc = run_case(ctx, mesh, c, o, fig);
    if (rc != CLI_OK) break;
    printf("build      %-8s T1  measured tables min %7.2f median %7.2f | closed form min %7.2f median %7.2f ms per "
           "100k patches | measured / closed form: min %.2fx, median %.2fx\n",
           c->name, fig[0][0], fig[0][1], fig[1][0], fig[1][1], fig[0][0] / fig[1][0], fig[0][1] / fig[1][1]);
    if (csv) fprintf(csv, "build,%s,%.4f,%.4f,%.4f,%.4f\n", c->name, fig[0][0], fig[0][1], fig[1][0], fig[1][1]);
  }
  return rc;
}

int bench_build(const bench_options* o, FILE* csv) {
  cli_mesh in;
  scene_setup_desc sd = {.input = o->in, .split_quads = true};
  int rc = scene_input_load(&sd, &in);
  if (rc != CLI_OK) return rc;
  float* alphas = make_alphas(in.vertex_count);
  tlod_context* ctx = NULL;
  tlod_mesh* mesh = NULL;
  if (!alphas || tlod_context_create(&(tlod_context_desc){.thread_count = 1, .label = "bench"}, &ctx) != TLOD_SUCCESS)
    rc = cli_error(CLI_FAILED, "cannot create a context");
  if (rc == CLI_OK) rc = make_mesh(ctx, &in, alphas, &mesh);
  if (rc == CLI_OK) {
    printf("tlod bench --suite build: %s, %u triangles, one thread, process CPU time of tlod_surface_create, %u "
           "warm-up + %u interleaved rounds\n",
           o->in, tlod_mesh_face_count(mesh), o->warmup, o->repeat);
    if (csv) fprintf(csv, "suite,surface,measured_min_ms,measured_median_ms,closed_min_ms,closed_median_ms\n");
    rc = run_cases(ctx, mesh, o, csv);
  }
  if (rc == CLI_OK) print_bytes();
  tlod_mesh_destroy(mesh);
  tlod_context_destroy(ctx);
  free(alphas);
  cli_mesh_free(&in);
  return rc;
}
