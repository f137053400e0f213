/*
 * vtk_import_bench.c -- the scale measurement of VTK input (issue 14, BENCHMARKS.md) and its
 * small-size check.
 *   vtk_import_bench gen MODEL FILE writes a test mesh (.vtu by extension, else legacy binary
 *                                   .vtk): MODEL blockN is an N x N x N hexahedron block (unit cube;
 *                                   point fields temperature and displacement, cell field pressure;
 *                                   every fifth cell inverted), or box, sphere, cylinder, hex20,
 *                                   hex27, mixed, payload, pie (vtk_model.h)
 *   vtk_import_bench import FILE    imports it once and prints wall seconds, the importer's stage
 *                                   times (tlod_import_vtk_info), the boundary counts and the peak RSS
 *   vtk_import_bench check N WORK   gen + import in one run, exit 1 unless the boundary has 6 N^2
 *                                   quads, 0 triangles and the 6 N^2 + 2 points on it, every fifth
 *                                   cell was reoriented, every progress report is a named stage with
 *                                   a fraction in [0, 1], and the peak RSS stayed within 64 MiB + 8x
 *                                   the file (not under a sanitizer; the file is removed afterwards)
 * gen and import are separate processes so that the import's peak RSS is the import's own.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include "tlod_import.h"
#include "vtk_model.h"

/* A sanitizer's shadow memory makes the peak RSS meaningless: the bound is checked without one
 * (TLOD_TEST_SANITIZED: 1 in TLOD_SANITIZE builds, tests/vtk/CMakeLists.txt). */
#if defined(TLOD_TEST_SANITIZED) && TLOD_TEST_SANITIZED
#define RSS_CHECKED 0
#else
#define RSS_CHECKED 1
#endif

typedef struct progress_log {
  uint32_t calls, bad;
  double last;
  char stage[64];
} progress_log;

static void on_progress(void* user, const char* stage, double fraction) {
  progress_log* p = user;
  p->calls++;
  p->bad += !stage || !stage[0] || !(fraction >= 0 && fraction <= 1);
  p->last = fraction;
  snprintf(p->stage, sizeof p->stage, "%s", stage ? stage : "(null)");
}

/* The model a name stands for; false for an unknown name. */
static bool build(const char* name, vtk_model* m) {
  if (strncmp(name, "block", 5) == 0 && atoi(name + 5) > 0) {
    uint32_t n = (uint32_t)atoi(name + 5);
    vtk_build_box(m, n, n, n, 1, 1, 1);
  } else if (strcmp(name, "box") == 0) {
    vtk_build_box(m, 4, 3, 2, 2.0, 1.5, 1.0);
  } else if (strcmp(name, "sphere") == 0) {
    vtk_build_tet_sphere(m, 3, 1.0);
  } else if (strcmp(name, "cylinder") == 0) {
    vtk_build_hex_cylinder(m, 1, 2, 2);
  } else if (strcmp(name, "hex20") == 0 || strcmp(name, "hex27") == 0) {
    vtk_build_quadratic_pair(m, name[4] == '0' ? VTK_QUADRATIC_HEXAHEDRON : VTK_TRIQUADRATIC_HEXAHEDRON);
  } else if (strcmp(name, "mixed") == 0) {
    vtk_build_mixed(m);
  } else if (strcmp(name, "payload") == 0) {
    vtk_build_payload_box(m);
  } else if (strcmp(name, "pie") == 0) {
    vtk_build_collapsed_pie(m);
  } else {
    return false;
  }
  return true;
}

static int gen(const char* name, const char* path) {
  vtk_model m;
  if (!build(name, &m)) {
    fprintf(stderr, "vtk_import_bench: unknown model '%s'\n", name);
    return 2;
  }
  size_t len = strlen(path);
  bool xml = len > 4 && strcmp(path + len - 4, ".vtu") == 0;
  bool ok = vtk_model_write(&m, path, xml ? VTK_XML_ASCII : VTK_LEGACY_BINARY);
  printf("%s: %u cells, %u points, %u inverted\n", path, m.cell_count, m.point_count, m.inverted);
  vtk_model_free(&m);
  return ok ? 0 : 1;
}

static tlod_import_result* import(const char* path, progress_log* log) {
  char err[512];
  tlod_import_result* r = NULL;
  tlod_import_desc d = {.progress = on_progress, .progress_user = log};
  double t0 = tlod_now_ms();
  tlod_result res = tlod_import_file_desc(path, &d, &r, err, sizeof err);
  double t1 = tlod_now_ms();
  if (res != TLOD_SUCCESS) {
    fprintf(stderr, "%s: %s\n", tlod_result_string(res), err);
    return NULL;
  }
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  const tlod_import_vtk_info* v = r->vtk;
  printf("import %s: %.2f s wall, peak RSS %.0f MiB\n", path, (t1 - t0) / 1000, ru.ru_maxrss / 1024.0);
  if (v)
    printf("  %llu cells, %llu points -> %llu boundary quads, %llu triangles, %llu interior faces, %llu reoriented\n"
           "  stages: read %.0f ms, boundary %.0f ms (%.0f%%), fields %.0f ms; %u progress reports (last '%s' %.2f)\n",
           (unsigned long long)v->cells, (unsigned long long)v->points, (unsigned long long)v->boundary_quads,
           (unsigned long long)v->boundary_triangles, (unsigned long long)v->interior_faces,
           (unsigned long long)v->cells_reoriented, v->read_ms, v->boundary_ms, 100 * v->boundary_ms / (t1 - t0),
           v->fields_ms, log->calls, log->stage, log->last);
  return r;
}

static double peak_rss_bytes(void) {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss * 1024.0;
}

static int check(uint32_t n, const char* work) {
  char path[1024], name[32];
  snprintf(path, sizeof path, "%s/block%u.vtk", work, n);
  snprintf(name, sizeof name, "block%u", n);
  if (gen(name, path)) return 1;
  struct stat st;
  double file = stat(path, &st) == 0 ? (double)st.st_size : 0;
  progress_log log = {0};
  tlod_import_result* r = import(path, &log);
  remove(path);
  if (!r) return 1;
  const tlod_import_vtk_info* v = r->vtk;
  uint64_t cells = (uint64_t)n * n * n, quads = 6ull * n * n;
  bool ok = v && v->cells == cells && v->boundary_quads == quads && v->boundary_triangles == 0 &&
            r->face_count == quads && r->vertex_count == quads + 2 && v->cells_reoriented == (cells + 1) / 5 &&
            v->interior_faces == (6 * cells - quads) / 2 && log.bad == 0;
  tlod_import_free(r);
  double rss = peak_rss_bytes(), bound = 64.0 * 1024 * 1024 + 8 * file;
  printf("%s block counts and progress\n", ok ? "ok  " : "FAIL");
  bool rss_ok = !RSS_CHECKED || rss <= bound;
  printf("%s peak RSS %.0f MiB, bound %.0f MiB (64 MiB + 8x the file)%s\n", rss_ok ? "ok  " : "FAIL", rss / 1048576,
         bound / 1048576, RSS_CHECKED ? "" : ", not checked under a sanitizer");
  return ok && rss_ok ? 0 : 1;
}

int main(int argc, char** argv) {
  if (argc == 4 && strcmp(argv[1], "gen") == 0) return gen(argv[2], argv[3]);
  if (argc == 3 && strcmp(argv[1], "import") == 0) {
    progress_log log = {0};
    tlod_import_result* r = import(argv[2], &log);
    tlod_import_free(r);
    return r ? 0 : 1;
  }
  if (argc == 4 && strcmp(argv[1], "check") == 0) return check((uint32_t)atoi(argv[2]), argv[3]);
  fprintf(stderr, "usage: vtk_import_bench gen MODEL FILE | import FILE | check N WORK_DIR\n");
  return 2;
}
