/* tlod bench -- runs the suite of the options, with the CSV file (written
 * atomically: complete or not at all). */
#include <string.h>

#include "bench_eval.h"
#include "bench_gl.h"
#include "bench_lod.h"
#include "bench_options.h"
#include "bench_peers.h"
#include "cli.h"
#include "commands.h"
#include "common/folder.h"
#include "tlod_atomic_file.h"

static int run_lod_suites(const bench_options* o, const bench_gpu* gpu, FILE* csv) {
  static const char* const default_models[] = {"demo:cow"};
  bench_lod_options lo = {o->threads, o->thread_count, o->frames, o->table1_count ? o->table1 : default_models,
                          o->table1_count ? o->table1_count : 1};
  double bandwidth = bench_memcpy_bandwidth();
  printf("tlod bench --suite %s: memcpy %.2f GB/s\n", o->suite, bandwidth * 1e-9);
  bool all = !strcmp(o->suite, "all");
  int rc = CLI_OK;
  if (all || !strcmp(o->suite, "scheduler")) rc = bench_scheduler(&lo, bandwidth, csv);
  if (rc == CLI_OK && (all || !strcmp(o->suite, "table1"))) rc = bench_table1(&lo, csv);
  if (rc == CLI_OK && (all || !strcmp(o->suite, "gl"))) rc = bench_gl(gpu, lo.inputs, lo.input_count, o->frames, csv);
  if (rc == CLI_OK && (all || !strcmp(o->suite, "draw"))) rc = bench_draw(gpu, o->frames, csv);
  return rc;
}

/* "eval", "build" and "all" run on IN; the others are the scheduler suites. */
static int run_suite(const bench_options* o, const bench_gpu* gpu, FILE* csv) {
  bool all = !strcmp(o->suite, "all");
  if (!strcmp(o->suite, "build")) return bench_build(o, csv);
  if (!strcmp(o->suite, "skin")) return bench_skin(o, csv);
  if (!strcmp(o->suite, "objects")) return bench_objects(o, gpu, csv);
  if (!strcmp(o->suite, "vkstart")) return bench_vkstart(o->repeat, csv);
  if (strcmp(o->suite, "eval") != 0 && !all) return run_lod_suites(o, gpu, csv);
  int rc = bench_eval(o, csv);
  return rc == CLI_OK && all ? bench_build(o, csv) : rc;
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

/* --peers, with its JSON document when --json is given (written atomically). */
static int run_peers(const bench_options* o, FILE* csv) {
  char err[1024];
  tlod_atomic_file jf = {0};
  if (o->json && !tlod_atomic_file_begin(&jf, o->json, err, sizeof(err))) return cli_error(CLI_FAILED, "%s", err);
  json_writer w;
  if (o->json) json_begin(&w, jf.file), json_object_begin(&w, NULL);
  int rc = bench_peers(o, o->json ? &w : NULL, csv);
  if (o->json) {
    json_object_end(&w);
    bool written = json_end(&w);
    if (!tlod_atomic_file_end(&jf, rc == CLI_OK && written, err, sizeof(err)) && rc == CLI_OK)
      rc = cli_error(CLI_FAILED, "%s", err);
  }
  return rc;
}

int cmd_bench(int argc, char** argv) {
  bench_options o;
  int rc = bench_parse(argc, argv, &o);
  if (rc != CLI_OK) return rc;
  char err[1024], cache[4096];
  bench_gpu gpu;
  if ((rc = gpu_of(&o, cache, sizeof(cache), &gpu)) != CLI_OK) return rc;
  tlod_atomic_file csv = {0};
  if (o.csv && !tlod_atomic_file_begin(&csv, o.csv, err, sizeof(err))) return cli_error(CLI_FAILED, "%s", err);
  rc = o.peers ? run_peers(&o, csv.file) : run_suite(&o, &gpu, csv.file);
  if (o.csv && !tlod_atomic_file_end(&csv, rc == CLI_OK, err, sizeof(err)) && rc == CLI_OK)
    rc = cli_error(CLI_FAILED, "%s", err);
  return rc;
}
