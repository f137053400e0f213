/* tlod bench -- runs the suite of the options, with the CSV and JSON files
 * (each written atomically: complete or not at all). */
#include <string.h>

#include "bench_eval.h"
#include "bench_gl.h"
#include "bench_lod.h"
#include "bench_options.h"
#include "bench_peers.h"
#include "bench_report.h"
#include "cli.h"
#include "commands.h"
#include "common/folder.h"
#include "tlod_atomic_file.h"

/* The three scenes of BENCHMARKS.md's Table 1. */
static const char* const k_table1_scenes[] = {"demo:cow", "tests/data/glTF-Sample-Models/Duck/glTF-Binary/Duck.glb",
                                              "tests/data/derived/fran_cut.obj"};

static int run_lod_suites(const bench_options* o, const bench_gpu* gpu, bench_report* rep, FILE* csv) {
  bool figures = !strcmp(o->suite, "figures");
  static const char* const default_models[] = {"demo:cow"};
  bench_lod_options lo = {.threads = o->threads,
                          .thread_count = o->thread_count,
                          .frames = o->frames,
                          .inputs = o->table1_count ? o->table1 : default_models,
                          .input_count = o->table1_count ? o->table1_count : 1};
  if (figures && !o->table1_count) lo.inputs = k_table1_scenes, lo.input_count = 3;
  static const char* const meshes[] = {"demo:torus-100x100", "demo:torus-320x320", "demo:torus-1000x1000"};
  lo.meshes = figures ? &o->scheduler_mesh : meshes, lo.mesh_count = figures ? 1 : 3;
  bool all = !strcmp(o->suite, "all");
  int rc = CLI_OK;
  if (all || figures || !strcmp(o->suite, "scheduler")) rc = bench_scheduler(&lo, rep, csv);
  if (rc == CLI_OK && (all || figures || !strcmp(o->suite, "table1"))) rc = bench_table1(&lo, rep, csv);
  uint32_t gpu_frames = o->frames_given ? o->frames : BENCH_GPU_FRAMES;
  if (rc == CLI_OK && (all || !strcmp(o->suite, "gl"))) rc = bench_gl(gpu, lo.inputs, lo.input_count, gpu_frames, csv);
  if (rc == CLI_OK && (all || !strcmp(o->suite, "draw"))) rc = bench_draw(gpu, gpu_frames, rep, csv);
  return rc;
}

/* bench_peers.h: without OpenSubdiv built in it says so and fails. */
static int run_peers(const bench_options* o, bench_report* rep, FILE* csv) { return bench_peers(o, rep->json, csv); }

/* "eval", "build" and "all" run on IN; "figures" runs eval at level 5 and
 * the scheduler suites; the others are the scheduler suites. */
static int run_suite(const bench_options* o, const bench_gpu* gpu, bench_report* rep, FILE* csv) {
  bool all = !strcmp(o->suite, "all");
  if (!strcmp(o->suite, "peers")) return run_peers(o, rep, csv);
  if (!strcmp(o->suite, "build")) return bench_build(o, csv);
  if (!strcmp(o->suite, "skin")) return bench_skin(o, csv);
  if (!strcmp(o->suite, "objects")) return bench_objects(o, gpu, csv);
  if (!strcmp(o->suite, "vkstart")) return bench_vkstart(o->repeat, csv);
  if (!strcmp(o->suite, "figures")) {
    bench_options eo = *o;
    eo.levels[0] = 5, eo.level_count = 1;
    int rc = bench_eval(&eo, rep, csv);
    return rc == CLI_OK ? run_lod_suites(o, gpu, rep, csv) : rc;
  }
  if (strcmp(o->suite, "eval") != 0 && !all) return run_lod_suites(o, gpu, rep, csv);
  int rc = bench_eval(o, rep, csv);
  if (rc == CLI_OK && all) rc = bench_build(o, csv);
  return rc == CLI_OK && all ? run_lod_suites(o, gpu, rep, csv) : rc;
}

/* vulkan: the shader cache folder (a given one must work; the default one
 * is left out with a warning when it cannot be had). */
static int gpu_of(const bench_options* o, char* buf, size_t size, bench_gpu* gpu) {
  *gpu = (bench_gpu){.backend = o->backend};
  if (strcmp(o->backend, "vulkan")) return CLI_OK;
  char warning[4200], err[4200];
  if (!tool_shader_cache_dir(o->shader_cache, buf, size, &gpu->shader_cache, warning, sizeof(warning), err,
                             sizeof(err)))
    return cli_error(CLI_FAILED, "--shader-cache: %s", err);
  if (warning[0]) fprintf(stderr, "tlod: warning: %s\n", warning);
  return CLI_OK;
}

/* The header, the suite and the figures; json (NULL: none) gets them all. */
static int run_reported(const bench_options* o, const bench_gpu* gpu, json_writer* json, FILE* csv) {
  bench_report rep;
  if (json) {
    json_object_begin(json, NULL);
    json_string(json, "suite", o->suite);
  }
  static const char* const reading_rates[] = {"eval", "scheduler", "figures", "all"};
  bool rates = false;
  for (size_t k = 0; k < sizeof reading_rates / sizeof reading_rates[0]; k++)
    rates = rates || !strcmp(o->suite, reading_rates[k]);
  int rc = bench_report_begin(&rep, json, rates ? o->bandwidth_mib : 0) ? CLI_OK : CLI_FAILED;
  if (rc == CLI_OK) rc = run_suite(o, gpu, &rep, csv);
  if (rc == CLI_OK) bench_report_end(&rep);
  if (json) json_object_end(json);
  return rc;
}

static int run_files(const bench_options* o, const bench_gpu* gpu) {
  char err[1024];
  tlod_atomic_file csv = {0}, js = {0};
  if (o->csv && !tlod_atomic_file_begin(&csv, o->csv, err, sizeof(err))) return cli_error(CLI_FAILED, "%s", err);
  if (o->json && !tlod_atomic_file_begin(&js, o->json, err, sizeof(err))) {
    if (o->csv) tlod_atomic_file_end(&csv, false, err, sizeof(err));
    return cli_error(CLI_FAILED, "--json: %s: %s", o->json, err);
  }
  json_writer w;
  if (o->json) json_begin(&w, js.file);
  int rc = run_reported(o, gpu, o->json ? &w : NULL, csv.file);
  if (o->json && rc == CLI_OK && !json_end(&w)) rc = cli_error(CLI_FAILED, "--json: %s: write failed", o->json);
  if (o->json && !tlod_atomic_file_end(&js, rc == CLI_OK, err, sizeof(err)) && rc == CLI_OK)
    rc = cli_error(CLI_FAILED, "--json: %s", err);
  if (o->csv && !tlod_atomic_file_end(&csv, rc == CLI_OK, err, sizeof(err)) && rc == CLI_OK)
    rc = cli_error(CLI_FAILED, "%s", err);
  return rc;
}

int cmd_bench(int argc, char** argv) {
  bench_options o;
  int rc = bench_parse(argc, argv, &o);
  if (rc != CLI_OK) return rc;
  char cache[4096];
  bench_gpu gpu;
  if ((rc = gpu_of(&o, cache, sizeof(cache), &gpu)) != CLI_OK) return rc;
  return run_files(&o, &gpu);
}
