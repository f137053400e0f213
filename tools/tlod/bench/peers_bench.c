/* tlod bench --peers -- tesslod and OpenSubdiv in one process, alternating
 * round by round on the same meshes, one thread each (thread CPU time,
 * min/median of --repeat after --warmup): preprocessing time and peak heap,
 * output vertices/s per level for positions (OpenSubdiv: PrimvarRefiner) and
 * positions + normals (its limit evaluation), static and deforming, and how
 * far each surface is from the input vertices and volume. */
#include <limits.h>
#include <malloc.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_peers.h"
#include "bench_stats.h"
#include "cli.h"
#include "peers.h"
#include "peers_osd.h"

/* Above this many output vertices a case is left out (both outputs and
 * OpenSubdiv's levels would take several GB). */
#define PEERS_MAX_OUTPUT 40000000.0

typedef struct peers_run {
  const bench_options* o;
  json_writer* json;
  FILE* csv;
  float* control; /* the deformed positions of a frame */
} peers_run;

typedef struct peers_case {
  const peers_mesh* m;
  uint32_t level;
  bool normals, deforming;
} peers_case;

typedef struct peers_pair {
  peers_ours ours;
  peers_osd* osd;
} peers_pair;

static const char* path_name(bool normals) { return normals ? "positions+normals" : "positions"; }

static void put_side(json_writer* j, const char* who, const double ms[2], uint64_t vertices) {
  char key[64];
  snprintf(key, sizeof(key), "%s_ms_min", who);
  json_number(j, key, ms[0]);
  snprintf(key, sizeof(key), "%s_ms_median", who);
  json_number(j, key, ms[1]);
  snprintf(key, sizeof(key), "%s_vertices", who);
  json_uint(j, key, vertices);
  snprintf(key, sizeof(key), "%s_vertices_per_s", who);
  json_number(j, key, vertices / (ms[0] * 1e-3));
}

static void report_case(peers_run* r, const peers_case* c, const double us[2], uint64_t uv, const double them[2],
                        uint64_t tv) {
  double ours_rate = uv / (us[0] * 1e-3), osd_rate = tv / (them[0] * 1e-3);
  const char* motion = c->deforming ? "deforming" : "static";
  printf("  L%u %-17s %-9s ours %8.2f Mvert/s (%9llu, %8.2f ms)  osd %8.2f Mvert/s (%9llu, %8.2f ms)  ours/osd %.2fx\n",
         c->level, path_name(c->normals), motion, ours_rate * 1e-6, (unsigned long long)uv, us[0], osd_rate * 1e-6,
         (unsigned long long)tv, them[0], ours_rate / osd_rate);
  if (r->csv)
    fprintf(r->csv, "evaluate,%s,%u,%u,%s,%s,%.4f,%.4f,%llu,%.4f,%.4f,%llu,%.4f\n", c->m->kind, c->m->face_count,
            c->level, path_name(c->normals), motion, us[0], us[1], (unsigned long long)uv, them[0], them[1],
            (unsigned long long)tv, ours_rate / osd_rate);
  if (!r->json) return;
  json_object_begin(r->json, motion);
  put_side(r->json, "ours", us, uv);
  put_side(r->json, "osd", them, tv);
  json_number(r->json, "ours_over_osd_rate", ours_rate / osd_rate);
  json_object_end(r->json);
}

/* One side's frame: ours (true) or OpenSubdiv's; false when ours failed. */
static bool frame(peers_run* r, const peers_case* c, peers_pair* p, bool ours, const float* control, double* ms,
                  uint64_t* vertices) {
  double t0 = peers_thread_ms();
  if (ours) {
    *vertices = peers_ours_evaluate(&p->ours, control, c->level, c->normals);
  } else {
    peers_osd_evaluate(p->osd, control ? control : c->m->positions, c->deforming);
    *vertices = peers_osd_output_count(p->osd);
  }
  *ms = peers_thread_ms() - t0;
  (void)r;
  return *vertices > 0;
}

/* Warm-up and repeats, who goes first alternating round by round. */
static int run_case(peers_run* r, const peers_case* c, peers_pair* p) {
  uint32_t n = r->o->warmup + r->o->repeat, k = 0;
  double* t = malloc(sizeof(double) * 2 * r->o->repeat);
  uint64_t v[2] = {0, 0};
  for (uint32_t i = 0; i < n && t; i++) {
    const float* control = NULL;
    if (c->deforming) {
      peers_mesh_deform(c->m, i, r->control);
      control = r->control;
    }
    double ms[2];
    for (uint32_t s = 0; s < 2; s++) {
      bool ours = (s + i) % 2 == 0;
      if (!frame(r, c, p, ours, control, &ms[ours ? 0 : 1], &v[ours ? 0 : 1])) {
        free(t);
        return cli_error(CLI_FAILED, "bench --peers: %s", tlod_context_last_error(p->ours.ctx));
      }
    }
    if (i >= r->o->warmup) t[k] = ms[0], t[r->o->repeat + k++] = ms[1];
  }
  if (!t) return cli_error(CLI_FAILED, "bench --peers: out of memory");
  double us[2], them[2];
  bench_min_median(t, r->o->repeat, 1.0, us);
  bench_min_median(t + r->o->repeat, r->o->repeat, 1.0, them);
  free(t);
  report_case(r, c, us, v[0], them, v[1]);
  return CLI_OK;
}

/* Preprocessing figures of one side, min and median: cold, warm, and (ours)
 * warm with the scheduler's error tables. */
enum { PREP_COLD, PREP_WARM, PREP_ADAPTIVE, PREP_WAYS };
typedef struct peers_prep {
  double ms[PREP_WAYS][2];
  uint64_t peak, adaptive_peak;
} peers_prep;

static void put_prep(json_writer* j, const char* who, const peers_prep* p, bool ours) {
  static const char* const names[PREP_WAYS] = {"", "warm_", "adaptive_"};
  char key[64];
  for (int w = 0; w < (ours ? PREP_WAYS : PREP_ADAPTIVE); w++) {
    snprintf(key, sizeof(key), "%s_%sms_min", who, names[w]);
    json_number(j, key, p->ms[w][0]);
    snprintf(key, sizeof(key), "%s_%sms_median", who, names[w]);
    json_number(j, key, p->ms[w][1]);
  }
  snprintf(key, sizeof(key), "%s_peak_bytes", who);
  json_uint(j, key, p->peak);
  if (ours) json_uint(j, "ours_adaptive_peak_bytes", p->adaptive_peak);
}

static void report_preprocess(peers_run* r, const peers_case* c, const peers_prep* us, const peers_prep* them) {
  printf("  L%u %-17s preprocess ours %8.2f ms (warm %7.2f, adaptive %7.2f) %6.2f MB  osd %8.2f ms (warm %7.2f) "
         "%8.2f MB  osd/ours time %.1fx (warm %.1fx, adaptive %.1fx) memory %.1fx\n",
         c->level, path_name(c->normals), us->ms[PREP_COLD][0], us->ms[PREP_WARM][0], us->ms[PREP_ADAPTIVE][0],
         us->peak * 1e-6, them->ms[PREP_COLD][0], them->ms[PREP_WARM][0], them->peak * 1e-6,
         them->ms[PREP_COLD][0] / us->ms[PREP_COLD][0], them->ms[PREP_WARM][0] / us->ms[PREP_WARM][0],
         them->ms[PREP_WARM][0] / us->ms[PREP_ADAPTIVE][0], (double)them->peak / us->peak);
  if (r->csv)
    fprintf(r->csv, "preprocess,%s,%u,%u,%s,-,%.4f,%.4f,%llu,%.4f,%.4f,%llu,%.4f\n", c->m->kind, c->m->face_count,
            c->level, path_name(c->normals), us->ms[PREP_COLD][0], us->ms[PREP_COLD][1], (unsigned long long)us->peak,
            them->ms[PREP_COLD][0], them->ms[PREP_COLD][1], (unsigned long long)them->peak,
            them->ms[PREP_COLD][0] / us->ms[PREP_COLD][0]);
  if (!r->json) return;
  json_object_begin(r->json, "preprocess");
  put_prep(r->json, "ours", us, true);
  put_prep(r->json, "osd", them, false);
  json_object_end(r->json);
}

static peers_osd* osd_create(const peers_case* c, double* ms, uint64_t* peak) {
  peers_osd_desc d = {c->m->positions,  c->m->vertex_count, c->m->indices, c->m->face_sizes,
                      c->m->face_count, c->level,           c->normals};
  char err[256];
  peers_osd_heap_reset_peak();
  uint64_t before = peers_osd_heap_now();
  double t0 = peers_thread_ms();
  peers_osd* o = peers_osd_create(&d, err, sizeof(err));
  *ms = peers_thread_ms() - t0;
  *peak = peers_osd_heap_peak() - before;
  if (!o) cli_error(CLI_FAILED, "bench --peers: %s", err);
  return o;
}

/* One side's preprocessing, timed cold, after the allocator gave its free
 * pages back (malloc_trim: every page touched for the first time, as when a
 * program loads its first mesh), then warm, just after the same
 * preprocessing was freed (the allocator keeps the pages: hold_freed_pages).
 * A uniform level needs no error bounds (TLOD_ERROR_TABLES_NONE, as
 * OpenSubdiv's refiner computes none); ours is timed a third time, warm, with
 * the MEASURED tables a scheduler's levels need. The last one is kept. */
static bool create_side(const peers_case* c, peers_pair* p, bool ours, double ms[PREP_WAYS], uint64_t peak[2]) {
  for (int w = 0; w < (ours ? PREP_WAYS : PREP_ADAPTIVE); w++) {
    if (w == PREP_COLD) malloc_trim(0);
    if (w != PREP_COLD && ours) peers_ours_destroy(&p->ours);
    if (w != PREP_COLD && !ours) peers_osd_destroy(p->osd), p->osd = NULL;
    tlod_error_tables tables = w == PREP_ADAPTIVE ? TLOD_ERROR_TABLES_MEASURED : TLOD_ERROR_TABLES_NONE;
    if (ours && !peers_ours_create(&p->ours, c->m, c->level, tables, &ms[w], &peak[w == PREP_ADAPTIVE]))
      return cli_error(CLI_FAILED, "bench --peers: %s", tlod_context_last_error(p->ours.ctx)), false;
    if (!ours && !(p->osd = osd_create(c, &ms[w], &peak[0]))) return false;
  }
  return true;
}

/* Both created --repeat times, who goes first alternating round by round;
 * the last pair is kept. t[side][way][round]. */
static int preprocess(peers_run* r, const peers_case* c, peers_pair* p) {
  uint32_t n = r->o->repeat;
  double* t = malloc(sizeof(double) * 2 * PREP_WAYS * n);
  peers_prep prep[2];
  memset(prep, 0, sizeof(prep));
  int rc = t ? CLI_OK : cli_error(CLI_FAILED, "bench --peers: out of memory");
  for (uint32_t i = 0; i < n && rc == CLI_OK; i++) {
    if (i) peers_ours_destroy(&p->ours), peers_osd_destroy(p->osd), p->osd = NULL;
    for (uint32_t s = 0; s < 2 && rc == CLI_OK; s++) {
      uint32_t side = (s + i) % 2; /* 0: ours */
      double ms[PREP_WAYS] = {0, 0, 0};
      uint64_t peak[2] = {0, 0};
      if (!create_side(c, p, side == 0, ms, peak)) rc = CLI_FAILED;
      prep[side].peak = peak[0], prep[side].adaptive_peak = peak[1];
      for (int w = 0; w < PREP_WAYS; w++)
        t[(side * PREP_WAYS + w) * n + i] = ms[w];
    }
  }
  for (uint32_t side = 0; side < 2 && rc == CLI_OK; side++)
    for (int w = 0; w < PREP_WAYS; w++)
      bench_min_median(t + (side * PREP_WAYS + w) * n, n, 1.0, prep[side].ms[w]);
  if (rc == CLI_OK) report_preprocess(r, c, &prep[0], &prep[1]);
  free(t);
  return rc;
}

typedef struct peers_accuracy {
  double ours_distance, osd_limit_distance, osd_refined_distance, ours_volume, osd_volume;
} peers_accuracy;

static void measure(const peers_case* c, peers_pair* p, peers_accuracy* a) {
  if (c->normals) {
    a->ours_distance = peers_ours_vertex_distance(&p->ours);
    const tlod_cpu_mesh* out = p->ours.out;
    a->ours_volume = peers_triangle_volume(out->positions, out->indices, out->triangle_count);
    a->osd_limit_distance = peers_osd_vertex_distance(p->osd, c->m->positions);
  } else {
    a->osd_refined_distance = peers_osd_vertex_distance(p->osd, c->m->positions);
    a->osd_volume = peers_osd_volume(p->osd);
  }
}

/* The surface again, with other error tables. */
static bool remake_surface(peers_ours* s, tlod_error_tables tables) {
  tlod_surface_destroy(s->surface);
  s->surface = NULL;
  tlod_surface_desc d = {.type = TLOD_SURFACE_PHONG, .error_tables = tables};
  return tlod_surface_create(s->ctx, s->mesh, &d, &s->surface) == TLOD_SUCCESS;
}

/* Thread CPU ns per face of tlod_mesh_update (normals recomputed) and
 * tlod_surface_refresh with the surface's tables: min over the frames. */
static bool time_refresh(peers_run* r, const peers_case* c, peers_ours* s, double* update_ns, double* refresh_ns) {
  *update_ns = *refresh_ns = INFINITY;
  for (uint32_t i = 0; i < r->o->warmup + r->o->repeat; i++) {
    peers_mesh_deform(c->m, i, r->control);
    double t0 = peers_thread_ms();
    if (tlod_mesh_update(s->mesh, r->control, 0, NULL, 0) != TLOD_SUCCESS) return false;
    double t1 = peers_thread_ms();
    if (tlod_surface_refresh(s->surface, NULL) != TLOD_SUCCESS) return false;
    double t2 = peers_thread_ms(), per = 1e6 / c->m->face_count;
    if (i < r->o->warmup) continue;
    *update_ns = fmin(*update_ns, (t1 - t0) * per);
    *refresh_ns = fmin(*refresh_ns, (t2 - t1) * per);
  }
  return true;
}

/* The deforming frames above use TLOD_ERROR_TABLES_NONE (uniform levels need
 * no bounds); what a CLOSED_FORM surface (a scheduler's ERROR/HYBRID
 * levels) would add, on one line. */
static int report_refresh(peers_run* r, const peers_case* c, peers_ours* s) {
  double upd, none, closed;
  if (!time_refresh(r, c, s, &upd, &none) || !remake_surface(s, TLOD_ERROR_TABLES_CLOSED_FORM) ||
      !time_refresh(r, c, s, &upd, &closed))
    return cli_error(CLI_FAILED, "bench --peers: %s", tlod_context_last_error(s->ctx));
  printf("  L%u deforming cost per face: tlod_mesh_update %.1f ns, tlod_surface_refresh NONE %.1f ns, CLOSED_FORM "
         "%.1f ns\n",
         c->level, upd, none, closed);
  if (!r->json) return CLI_OK;
  json_object_begin(r->json, "deforming_refresh_ns_per_face");
  json_number(r->json, "mesh_update", upd);
  json_number(r->json, "refresh_none", none);
  json_number(r->json, "refresh_closed_form", closed);
  json_object_end(r->json);
  return CLI_OK;
}

static int run_path(peers_run* r, const peers_mesh* m, uint32_t level, bool normals, peers_accuracy* a) {
  peers_case c = {m, level, normals, false};
  peers_pair p = {0};
  if (r->json) json_object_begin(r->json, path_name(normals));
  int rc = preprocess(r, &c, &p);
  if (rc == CLI_OK) rc = run_case(r, &c, &p);
  if (rc == CLI_OK) measure(&c, &p, a);
  /* Deforming at a uniform level: no error bounds to refresh. */
  if (rc == CLI_OK && !remake_surface(&p.ours, TLOD_ERROR_TABLES_NONE))
    rc = cli_error(CLI_FAILED, "bench --peers: %s", tlod_context_last_error(p.ours.ctx));
  c.deforming = true;
  if (rc == CLI_OK) rc = run_case(r, &c, &p);
  if (rc == CLI_OK && !normals) rc = report_refresh(r, &c, &p.ours);
  if (r->json) json_object_end(r->json);
  if (p.ours.ctx) peers_ours_destroy(&p.ours);
  if (p.osd) peers_osd_destroy(p.osd);
  return rc;
}

static void report_accuracy(peers_run* r, const peers_mesh* m, uint32_t level, const peers_accuracy* a) {
  double ours_dv = a->ours_volume / m->volume - 1.0, osd_dv = a->osd_volume / m->volume - 1.0;
  printf("  L%u input vertex to surface: ours %.3g, osd limit %.3g, osd level %u %.3g; volume change ours %+.4f%% "
         "osd level %u %+.4f%%\n",
         level, a->ours_distance, a->osd_limit_distance, level, a->osd_refined_distance, 100.0 * ours_dv, level,
         100.0 * osd_dv);
  if (!r->json) return;
  json_object_begin(r->json, "accuracy");
  json_number(r->json, "ours_vertex_distance", a->ours_distance);
  json_number(r->json, "osd_limit_vertex_distance", a->osd_limit_distance);
  json_number(r->json, "osd_refined_vertex_distance", a->osd_refined_distance);
  json_number(r->json, "ours_volume_change", ours_dv);
  json_number(r->json, "osd_volume_change", osd_dv);
  json_object_end(r->json);
}

static int run_level(peers_run* r, const peers_mesh* m, uint32_t level) {
  double out = (double)m->face_count * (double)(1u << (2 * level)) * (strcmp(m->kind, "triangle") ? 1.0 : 0.5);
  if (out > PEERS_MAX_OUTPUT) {
    printf("  L%u left out: about %.0fM output vertices (above %.0fM: several GB per side)\n", level, out * 1e-6,
           PEERS_MAX_OUTPUT * 1e-6);
    return CLI_OK;
  }
  peers_accuracy a = {0};
  if (r->json) {
    json_object_begin(r->json, NULL);
    json_string(r->json, "mesh", m->kind);
    json_uint(r->json, "faces", m->face_count);
    json_uint(r->json, "level", level);
  }
  int rc = run_path(r, m, level, false, &a);
  if (rc == CLI_OK) rc = run_path(r, m, level, true, &a);
  if (rc == CLI_OK) report_accuracy(r, m, level, &a);
  if (r->json) json_object_end(r->json);
  return rc;
}

static int run_mesh(peers_run* r, const char* kind, uint32_t faces) {
  peers_mesh m;
  if (!peers_mesh_make(kind, faces, &m)) return cli_error(CLI_FAILED, "bench --peers: out of memory");
  int rc = (r->control = malloc(sizeof(float) * 3 * (size_t)m.vertex_count)) ? CLI_OK : CLI_FAILED;
  printf("%s torus: %u faces, %u vertices (OpenSubdiv: %s)\n", kind, m.face_count, m.vertex_count,
         strcmp(kind, "triangle") ? "catmull-clark" : "loop");
  const bench_options* o = r->o;
  uint32_t count = o->peer_level_count ? o->peer_level_count : 4;
  for (uint32_t i = 0; i < count && rc == CLI_OK; i++)
    rc = run_level(r, &m, o->peer_level_count ? o->peer_levels[i] : i + 1);
  free(r->control);
  peers_mesh_free(&m);
  return rc;
}

/* glibc gives freed memory back to the system past a trim threshold and
 * serves blocks past a (moving) size from fresh mappings; with both fixed,
 * a warm preprocessing finds the pages its previous run freed, and a cold
 * one is made by malloc_trim. Blocks past 32 MB (glibc's largest threshold)
 * are still mapped afresh: the same for both sides. */
static void hold_freed_pages(void) {
  mallopt(M_TRIM_THRESHOLD, INT_MAX);
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
}

int bench_peers(const bench_options* o, json_writer* json, FILE* csv) {
  hold_freed_pages();
  static const char* const kinds[] = {"triangle", "quad", "mixed"};
  uint32_t sizes[2] = {100000, 1000000}, size_count = o->peer_faces ? 1 : 2;
  if (o->peer_faces) sizes[0] = o->peer_faces;
  printf("tlod bench --peers: tesslod %d.%d.%d (Phong) against OpenSubdiv %s, one thread each, thread CPU time, "
         "min/median of %u after %u warm-up\n",
         TLOD_VERSION / 1000, TLOD_VERSION / 100 % 10, TLOD_VERSION % 100, peers_osd_version(), o->repeat, o->warmup);
  if (csv)
    fprintf(csv, "stage,mesh,faces,level,output,motion,ours_ms_min,ours_ms_median,ours_count,osd_ms_min,"
                 "osd_ms_median,osd_count,ratio\n");
  peers_run r = {o, json, csv, NULL};
  if (json) {
    json_object_begin(json, "peers");
    json_string(json, "opensubdiv", peers_osd_version());
    json_uint(json, "tesslod", TLOD_VERSION);
    json_string(json, "timing", "thread CPU ms, one thread per library, min/median of repeats");
    json_array_begin(json, "cases");
  }
  int rc = CLI_OK;
  for (uint32_t s = 0; s < size_count && rc == CLI_OK; s++) {
    for (uint32_t k = 0; k < 3 && rc == CLI_OK; k++) {
      if (!o->peer_mesh || !strcmp(o->peer_mesh, kinds[k])) rc = run_mesh(&r, kinds[k], sizes[s]);
    }
  }
  if (json) json_array_end(json), json_object_end(json);
  return rc;
}
