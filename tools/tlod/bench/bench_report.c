/* tlod bench -- the run's header (processor, SIMD level, memory rates) and
 * its headline figures, printed and written to the --json document. */
#include "bench_report.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "tesslod/core.h"

/* The value of "key<tabs>: value" in /proc/cpuinfo's first processor. */
static bool cpuinfo_value(const char* key, char* buf, size_t size) {
  FILE* f = fopen("/proc/cpuinfo", "r");
  char line[512];
  bool found = false;
  size_t n = strlen(key);
  while (f && !found && fgets(line, sizeof(line), f)) {
    char* colon = strchr(line, ':');
    if (strncmp(line, key, n) || !colon || (line[n] != '\t' && line[n] != ' ')) continue;
    snprintf(buf, size, "%s", colon + 2);
    buf[strcspn(buf, "\n")] = 0;
    found = true;
  }
  if (f) fclose(f);
  return found;
}

void bench_processor(char* buf, size_t size) {
  char name[256], family[32] = "?", model[32] = "?";
  if (!cpuinfo_value("model name", name, sizeof(name))) {
    snprintf(buf, size, "unknown");
    return;
  }
  cpuinfo_value("cpu family", family, sizeof(family));
  cpuinfo_value("model", model, sizeof(model));
  snprintf(buf, size, "%s (family %s model %s)", name, family, model);
}

static void write_rates(json_writer* w, const bench_bandwidth* b) {
  json_object_begin(w, "bandwidth");
  json_uint(w, "buffer_mib", b->mib);
  json_string(w, "bound", "bytes read / read rate + bytes written / write rate");
  json_string(w, "clock", "bytes per CPU-second of the process (the _wall keys: per wall-clock second)");
  static const char* const keys[2] = {"threads_1", "threads_2"};
  for (int k = 0; k < 2; k++) {
    json_object_begin(w, keys[k]);
    json_number(w, "read_bytes_per_s", b->rates[k].read);
    json_number(w, "write_bytes_per_s", b->rates[k].write);
    json_number(w, "copy_bytes_per_s", b->rates[k].copy);
    json_number(w, "read_bytes_per_s_wall", b->rates[k].read_wall);
    json_number(w, "write_bytes_per_s_wall", b->rates[k].write_wall);
    json_number(w, "copy_bytes_per_s_wall", b->rates[k].copy_wall);
    json_object_end(w);
  }
  json_object_end(w);
}

bool bench_report_begin(bench_report* r, json_writer* json, uint32_t bandwidth_mib) {
  *r = (bench_report){.json = json,
                      .scheduler_1m_ms = NAN,
                      .scheduler_1m_cpu_ms = NAN,
                      .scheduler_1m_wall_ms = NAN,
                      .eval_bandwidth_fraction = NAN,
                      .strip_triangle_overhead = NAN};
  tlod_context* ctx = NULL;
  if (tlod_context_create(&(tlod_context_desc){.label = "bench"}, &ctx) != TLOD_SUCCESS)
    return cli_error(CLI_FAILED, "cannot create a context"), false;
  const char* simd = tlod_simd_name(tlod_context_simd(ctx));
  tlod_context_destroy(ctx);
  if (bandwidth_mib && !bench_bandwidth_measure(&r->bw, bandwidth_mib))
    return cli_error(CLI_FAILED, "bandwidth: out of memory"), false;
  char cpu[320];
  bench_processor(cpu, sizeof(cpu));
  printf("processor  %s | SIMD level %s (tlod_context_simd)\n", cpu, simd);
  if (bandwidth_mib) bench_bandwidth_print(&r->bw);
  if (json) {
    json_string(json, "processor", cpu);
    json_string(json, "simd", simd);
    if (bandwidth_mib) write_rates(json, &r->bw);
  }
  return true;
}

void bench_report_end(const bench_report* r) {
  printf("figures    scheduler_1m_ms %.3f (%s, %u patches; cpu %.3f, wall median %.3f) | eval_bandwidth_fraction "
         "%.3f | strip_triangle_overhead %.4f   (nan: not measured by this suite)\n",
         r->scheduler_1m_ms, r->scheduler_mesh ? r->scheduler_mesh : "-", r->scheduler_patches, r->scheduler_1m_cpu_ms,
         r->scheduler_1m_wall_ms, r->eval_bandwidth_fraction, r->strip_triangle_overhead);
  json_writer* w = r->json;
  if (!w) return;
  json_number(w, "scheduler_1m_ms", r->scheduler_1m_ms);
  json_number(w, "scheduler_1m_cpu_ms", r->scheduler_1m_cpu_ms);
  json_number(w, "scheduler_1m_wall_ms", r->scheduler_1m_wall_ms);
  json_string(w, "scheduler_1m_mesh", r->scheduler_mesh ? r->scheduler_mesh : "");
  json_uint(w, "scheduler_1m_patches", r->scheduler_patches);
  json_number(w, "eval_bandwidth_fraction", r->eval_bandwidth_fraction);
  json_number(w, "strip_triangle_overhead", r->strip_triangle_overhead);
}
