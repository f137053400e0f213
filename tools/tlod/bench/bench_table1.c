/* tlod bench --suite table1 -- the paper's Table 1 comparison (no
 * tessellation / adaptive / uniform at the worst patch's level) per policy,
 * with the strip overhead; the level rule of the per-level error tables
 * against the previous rule (error_bound 4^-l at the nearest depth, computed
 * here), and the surface build time per 100k patches. */
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "bench_lod.h"
#include "bench_report.h"
#include "tool_names.h"

/* Uniform tessellation at the finest level any visible patch needs. */
static uint64_t uniform_triangles(const bench_scene* s, const tlod_draw_list* dl, uint32_t level) {
  uint64_t tris = 0;
  for (uint32_t f = 0; f < dl->patch_count; f++) {
    uint32_t corners[4];
    if (dl->levels[f] < 0) continue;
    bool quad = tlod_mesh_face_corners(s->setup.mesh, f, corners) == 4;
    tris += tlod_pattern_triangle_count(quad ? TLOD_PATTERN_QUAD : TLOD_PATTERN_TRIANGLE, level);
  }
  return tris;
}

/* Patches the contour crosses: corner normals facing both ways. */
static bool on_contour(const tlod_mesh* mesh, uint32_t f, const float view[16]) {
  float eye[3];
  for (int i = 0; i < 3; i++)
    eye[i] = -(view[i * 4 + 0] * view[12] + view[i * 4 + 1] * view[13] + view[i * 4 + 2] * view[14]);
  uint32_t corners[4], n = tlod_mesh_face_corners(mesh, f, corners);
  bool front = false, back = false;
  for (uint32_t c = 0; c < n; c++) {
    float p[3], nrm[3];
    tlod_mesh_vertex(mesh, corners[c], p, nrm);
    float d = nrm[0] * (eye[0] - p[0]) + nrm[1] * (eye[1] - p[1]) + nrm[2] * (eye[2] - p[2]);
    front = front || d > 0.0f;
    back = back || d <= 0.0f;
  }
  return front && back;
}

/* The previous rule (before the per-level tables): e = error_bound * f / z,
 * z the sphere's nearest view depth clamped at the near plane (no off-axis
 * factor), level = the smallest l with 4^-l e <= eps (tlod_level_for_error). */
static uint32_t previous_level(const tlod_view_desc* v, const tlod_patch_info* in, float eps, uint32_t max_level) {
  const float *V = v->view, *P = v->proj;
  float scale;
  if (P[15] == 1.0f && P[11] == 0.0f) {
    scale = tlod_projection_scale(P, v->viewport_height, 1.0f);
  } else {
    float z = -(V[2] * in->center[0] + V[6] * in->center[1] + V[10] * in->center[2] + V[14]) - in->radius;
    float denom = P[10] - 1.0f, n = denom != 0.0f ? P[14] / denom : 0.0f;
    float zmin = n > 0.0f ? n : 1e-4f * in->radius;
    scale = tlod_projection_scale(P, v->viewport_height, z > zmin ? z : zmin);
  }
  return tlod_level_for_error(in->error_bound * scale, eps, max_level);
}

/* Pattern and strip triangles of the visible patches (levels[f] >= 0) at the
 * given levels, strips as the scheduler draws them without morphs: across
 * every edge between visible patches whose levels differ or that is a crease. */
static void count_frame(const bench_scene* s, const int8_t* levels, uint64_t* pattern, uint64_t* strips) {
  tlod_mesh_view m = tlod_mesh_query_view(s->setup.mesh);
  *pattern = *strips = 0;
  for (uint32_t f = 0; f < m.face_count; f++) {
    if (levels[f] < 0) continue;
    tlod_pattern_shape sh = m.face_corners[f] == 4 ? TLOD_PATTERN_QUAD : TLOD_PATTERN_TRIANGLE;
    *pattern += tlod_pattern_triangle_count(sh, (uint32_t)levels[f]);
    for (uint32_t e = 0; e < m.face_corners[f]; e++) {
      tlod_edge_link link = m.links[f][e];
      if (link.face == UINT32_MAX || link.face < f || levels[link.face] < 0) continue;
      if (link.smooth && levels[f] == levels[link.face]) continue;
      uint32_t n = 0;
      tlod_patterns_connection(s->setup.patterns, (uint32_t)levels[f], (uint32_t)levels[link.face], &n);
      *strips += n;
    }
  }
}

/* ------------------------------------------------------------------------ */
/* Measured on-screen error                                                 */
/* ------------------------------------------------------------------------ */

/* A world point to pixels with the view's matrices (column-major); false
 * behind the eye. */
static bool to_pixels(const tlod_view_desc* v, const double p[3], double px[2]) {
  double e[4], c[4];
  for (int r = 0; r < 4; r++)
    e[r] = v->view[r] * p[0] + v->view[4 + r] * p[1] + v->view[8 + r] * p[2] + v->view[12 + r];
  for (int r = 0; r < 4; r++)
    c[r] = v->proj[r] * e[0] + v->proj[4 + r] * e[1] + v->proj[8 + r] * e[2] + v->proj[12 + r] * e[3];
  if (!(c[3] > 1e-9)) return false;
  px[0] = (c[0] / c[3] * 0.5 + 0.5) * v->viewport_width;
  px[1] = (c[1] / c[3] * 0.5 + 0.5) * v->viewport_height;
  return true;
}

static void eval_point(const tlod_surface* s, uint32_t f, double u, double v, double out[3]) {
  tlod_surface_point pt;
  tlod_surface_eval(s, f, (float)u, (float)v, &pt);
  for (int c = 0; c < 3; c++)
    out[c] = pt.position[c];
}

/* max over a barycentric grid of d segments of one pattern triangle ((u, v)
 * corners c) of |pi(S) - pi(linear interpolation of the corner points)|, px. */
static double cell_screen_error(const tlod_surface* s, uint32_t f, const tlod_view_desc* v, const double c[3][2],
                                int d) {
  double p[3][3], worst = 0.0;
  for (int x = 0; x < 3; x++)
    eval_point(s, f, c[x][0], c[x][1], p[x]);
  for (int i = 0; i <= d; i++) {
    for (int j = 0; i + j <= d; j++) {
      if ((i == 0 && j == 0) || i == d || j == d) continue; /* the corners: 0 */
      double b1 = (double)i / d, b2 = (double)j / d, b0 = 1.0 - b1 - b2, q[3], a[3], pq[2], pa[2];
      eval_point(s, f, b0 * c[0][0] + b1 * c[1][0] + b2 * c[2][0], b0 * c[0][1] + b1 * c[1][1] + b2 * c[2][1], q);
      for (int k = 0; k < 3; k++)
        a[k] = b0 * p[0][k] + b1 * p[1][k] + b2 * p[2][k];
      if (!to_pixels(v, q, pq) || !to_pixels(v, a, pa)) continue;
      worst = fmax(worst, hypot(pq[0] - pa[0], pq[1] - pa[1]));
    }
  }
  return worst;
}

/* Samples per cell edge of the measurement. */
static int screen_error_segments(uint32_t level) { return level <= 2 ? 8 : level <= 4 ? 4 : 2; }

/* The worst measured on-screen error of patch f at level l over every
 * level-l pattern triangle (lod/src/pattern_refine.c's cells; quads split
 * along (a, b)-(a+1, b+1)). */
static double patch_screen_error(const tlod_surface* s, uint32_t f, uint32_t corners, const tlod_view_desc* v,
                                 uint32_t level) {
  int n = 1 << level, d = screen_error_segments(level);
  double h = 1.0 / n, worst = 0.0;
  for (int b = 0; b < n; b++) {
    for (int a = 0; a < (corners == 3 ? n - b : n); a++) {
      double A = a * h, B = b * h, A1 = (a + 1) * h, B1 = (b + 1) * h;
      if (corners == 3) {
        double lo[3][2] = {{A, B}, {A1, B}, {A, B1}};
        worst = fmax(worst, cell_screen_error(s, f, v, lo, d));
        if (a + b + 2 <= n) {
          double up[3][2] = {{A1, B}, {A1, B1}, {A, B1}};
          worst = fmax(worst, cell_screen_error(s, f, v, up, d));
        }
      } else {
        double t1[3][2] = {{A, B}, {A1, B}, {A1, B1}}, t2[3][2] = {{A, B}, {A1, B1}, {A, B1}};
        worst = fmax(worst, fmax(cell_screen_error(s, f, v, t1, d), cell_screen_error(s, f, v, t2, d)));
      }
    }
  }
  return worst;
}

/* Measured errors, per patch and level, computed on demand (NAN: not yet). */
typedef struct screen_errors {
  const bench_scene* s;
  const tlod_view_desc* view;
  uint32_t levels; /* lmax + 1 */
  double* e;       /* [patch][level] */
} screen_errors;

static double screen_error_at(screen_errors* se, uint32_t f, uint32_t level) {
  double* e = &se->e[(size_t)f * se->levels + level];
  if (isnan(*e)) {
    uint32_t corners[4], n = tlod_mesh_face_corners(se->s->setup.mesh, f, corners);
    *e = patch_screen_error(se->s->setup.surface, f, n, se->view, level);
  }
  return *e;
}

/* One rule's figures: pattern and strip triangles of the visible patches and
 * the worst measured error over the sampled ones (every stride-th visible). */
typedef struct rule_figures {
  uint64_t pattern, strips;
  uint32_t worst_level;
  double worst_px;
} rule_figures;

static rule_figures rule_measure(screen_errors* se, const int8_t* levels, uint32_t stride) {
  rule_figures r = {0};
  count_frame(se->s, levels, &r.pattern, &r.strips);
  uint32_t patches = tlod_surface_patch_count(se->s->setup.surface), visible = 0;
  for (uint32_t f = 0; f < patches; f++) {
    if (levels[f] < 0) continue;
    r.worst_level = (uint32_t)levels[f] > r.worst_level ? (uint32_t)levels[f] : r.worst_level;
    if (visible++ % stride) continue;
    r.worst_px = fmax(r.worst_px, screen_error_at(se, f, (uint32_t)levels[f]));
  }
  return r;
}

static void rule_print(const char* name, const rule_figures* r, const rule_figures* opt, float eps) {
  printf("table1err    %-34s pattern %8llu strips %7llu worst L%u | measured worst %7.3f px = %6.2f eps | pattern / "
         "optimum %5.2fx\n",
         name, (unsigned long long)r->pattern, (unsigned long long)r->strips, r->worst_level, r->worst_px,
         r->worst_px / eps, (double)r->pattern / (double)opt->pattern);
}

/* Best of 5 surface builds (the model's surface desc), ms per 100k patches. */
static double surface_build_ms_per_100k(const bench_scene* s) {
  tlod_surface_desc d = tlod_surface_query_desc(s->setup.surface);
  double best = INFINITY;
  for (int r = 0; r < 5; r++) {
    tlod_surface* surf = NULL;
    double t0 = cli_now_ms();
    if (tlod_surface_create(s->ctx, s->setup.mesh, &d, &surf) != TLOD_SUCCESS) return NAN;
    double t = cli_now_ms() - t0;
    tlod_surface_destroy(surf);
    best = t < best ? t : best;
  }
  return best * 1e5 / (double)tlod_surface_patch_count(s->setup.surface);
}

/* At one eps, per rule: pattern / strip triangles and the worst measured
 * on-screen error of the visible patches; the rules: the scheduler's draw
 * list (tables), the previous rule, the PN paper's (4^-l 9/4 d'_max, at the
 * previous rule's projection), uniform at the tables' worst level and at the
 * optimum's, and the per-camera optimum (per patch the smallest level whose
 * measured error is within eps). */
static int screen_error_comparison(const char* in, const bench_scene* s, const tlod_view_desc* view,
                                   const tlod_draw_list* dl, float eps, FILE* csv) {
  uint32_t patches = dl->patch_count, lmax = tlod_patterns_max_level(s->setup.patterns);
  bool pn = tlod_surface_query_desc(s->setup.surface).type == TLOD_SURFACE_PN;
  screen_errors se = {s, view, lmax + 1, malloc(sizeof(double) * patches * (lmax + 1))};
  int8_t* lv = malloc(patches + 1u);
  int8_t* opt = malloc(patches + 1u);
  if (!se.e || !lv || !opt) {
    free(se.e), free(lv), free(opt);
    return cli_error(CLI_FAILED, "out of memory");
  }
  for (size_t x = 0; x < (size_t)patches * (lmax + 1); x++)
    se.e[x] = NAN;
  double t0 = cli_now_ms();
  /* The optimum needs every visible patch; the other rules' worst errors are
   * taken over the same patches (no subsampling: stride 1). */
  const uint32_t stride = 1;
  uint32_t visible = 0;
  for (uint32_t f = 0; f < patches; f++) {
    opt[f] = -1;
    if (dl->levels[f] < 0) continue;
    visible++;
    uint32_t l = 0;
    while (l < lmax && screen_error_at(&se, f, l) > eps)
      l++;
    opt[f] = (int8_t)l;
  }
  rule_figures r_opt = rule_measure(&se, opt, stride), r_new = rule_measure(&se, dl->levels, stride), r_prev, r_pn;
  r_new.pattern = dl->pattern_triangles, r_new.strips = dl->strip_triangles;
  for (uint32_t f = 0; f < patches; f++) {
    lv[f] = -1;
    if (dl->levels[f] < 0) continue;
    tlod_patch_info info = tlod_surface_patch(s->setup.surface, f);
    lv[f] = (int8_t)previous_level(view, &info, eps, lmax);
  }
  r_prev = rule_measure(&se, lv, stride);
  for (uint32_t f = 0; pn && f < patches; f++) {
    lv[f] = -1;
    if (dl->levels[f] < 0) continue;
    tlod_patch_info info = tlod_surface_patch(s->setup.surface, f);
    info.error_bound = 2.25f * info.d_max; /* Schwarz et al.'s bound, at the previous rule's projection */
    lv[f] = (int8_t)previous_level(view, &info, eps, lmax);
  }
  if (pn) r_pn = rule_measure(&se, lv, stride);
  for (uint32_t f = 0; f < patches; f++)
    lv[f] = dl->levels[f] < 0 ? -1 : (int8_t)r_new.worst_level;
  rule_figures r_uni = rule_measure(&se, lv, stride);
  for (uint32_t f = 0; f < patches; f++)
    lv[f] = dl->levels[f] < 0 ? -1 : (int8_t)r_opt.worst_level;
  rule_figures r_uni_opt = rule_measure(&se, lv, stride);
  double ms = cli_now_ms() - t0;
  printf("table1err  %s: eps %.2f px, %u visible patches, measured: %s (all cells of the patch's level, %d/%d/%d "
         "samples per cell edge at L0-2/L3-4/L5+; %.0f ms)\n",
         in, (double)eps, visible, stride == 1 ? "every patch" : "a subsample", screen_error_segments(0),
         screen_error_segments(3), screen_error_segments(5), ms);
  rule_print("new rule (tables, scheduler)", &r_new, &r_opt, eps);
  rule_print("previous rule (error_bound 4^-l)", &r_prev, &r_opt, eps);
  if (pn)
    rule_print("PN paper (4^-l 9/4 d'_max)", &r_pn, &r_opt, eps);
  else
    printf("table1err    %-34s n/a (not a PN surface)\n", "PN paper (4^-l 9/4 d'_max)");
  char name[64];
  snprintf(name, sizeof name, "uniform L%u (tables' worst level)", r_new.worst_level);
  rule_print(name, &r_uni, &r_opt, eps);
  snprintf(name, sizeof name, "uniform L%u (optimum's worst level)", r_opt.worst_level);
  rule_print(name, &r_uni_opt, &r_opt, eps);
  rule_print("per-camera optimum (measured)", &r_opt, &r_opt, eps);
  printf("table1err    ratios: new / optimum pattern %.2fx (target <= 1.5x), previous / new pattern %.2fx (target >= "
         "3x)\n",
         (double)r_new.pattern / (double)r_opt.pattern, (double)r_prev.pattern / (double)r_new.pattern);
  if (csv) {
    const rule_figures* rs[] = {&r_new, &r_prev, pn ? &r_pn : NULL, &r_uni, &r_uni_opt, &r_opt};
    static const char* names[] = {"tables", "previous", "pn_paper", "uniform_tables", "uniform_optimum", "optimum"};
    for (int k = 0; k < 6; k++)
      if (rs[k])
        fprintf(csv, "table1err,%s,%s,%llu,%llu,%u,%.4f\n", in, names[k], (unsigned long long)rs[k]->pattern,
                (unsigned long long)rs[k]->strips, rs[k]->worst_level, rs[k]->worst_px);
  }
  free(se.e), free(lv), free(opt);
  return CLI_OK;
}

/* The previous rule against the tables' at the ERROR policy's visible set,
 * and uniform tessellation at the finest level the tables' rule needs. */
static int rule_comparison(const char* in, const bench_scene* s, const tlod_view_desc* view, const tlod_draw_list* dl,
                           uint32_t worst, FILE* csv) {
  uint32_t patches = dl->patch_count, lmax = tlod_patterns_max_level(s->setup.patterns), worst_prev = 0;
  int8_t* prev = malloc(patches + 1u);
  if (!prev) return cli_error(CLI_FAILED, "out of memory");
  for (uint32_t f = 0; f < patches; f++) {
    prev[f] = -1;
    if (dl->levels[f] < 0) continue;
    tlod_patch_info info = tlod_surface_patch(s->setup.surface, f);
    prev[f] = (int8_t)previous_level(view, &info, 0.5f, lmax);
    worst_prev = (uint32_t)prev[f] > worst_prev ? (uint32_t)prev[f] : worst_prev;
  }
  uint64_t prev_pat, prev_strip, uni_pat, uni_strip;
  int rc;
  count_frame(s, prev, &prev_pat, &prev_strip);
  for (uint32_t f = 0; f < patches; f++)
    prev[f] = dl->levels[f] < 0 ? -1 : (int8_t)worst;
  count_frame(s, prev, &uni_pat, &uni_strip);
  free(prev);
  rc = screen_error_comparison(in, s, view, dl, 0.5f, csv);
  if (rc != CLI_OK) return rc;
  double build = surface_build_ms_per_100k(s);
  printf("table1rule %-24s tables: pattern %8llu strips %7llu | previous rule (error_bound 4^-l): pattern %8llu strips "
         "%7llu (worst L%u) | pattern ratio %5.2fx, total %5.2fx | uniform L%u: pattern %9llu strips %6llu | surface "
         "build %.1f ms per 100k patches\n",
         in, (unsigned long long)dl->pattern_triangles, (unsigned long long)dl->strip_triangles,
         (unsigned long long)prev_pat, (unsigned long long)prev_strip, worst_prev,
         (double)prev_pat / (double)dl->pattern_triangles,
         (double)(prev_pat + prev_strip) / (double)(dl->pattern_triangles + dl->strip_triangles), worst,
         (unsigned long long)uni_pat, (unsigned long long)uni_strip, build);
  if (csv)
    fprintf(csv, "table1rule,%s,%llu,%llu,%llu,%llu,%u,%llu,%llu,%.3f\n", in, (unsigned long long)dl->pattern_triangles,
            (unsigned long long)dl->strip_triangles, (unsigned long long)prev_pat, (unsigned long long)prev_strip,
            worst, (unsigned long long)uni_pat, (unsigned long long)uni_strip, build);
  return CLI_OK;
}

/* HYBRID's strip / pattern triangles: the scene's entry in the JSON and the
 * worst scene's into strip_triangle_overhead. */
static void note_strips(bench_report* rep, const char* in, const tlod_draw_list* dl) {
  double share = (double)dl->strip_triangles / (double)(dl->pattern_triangles ? dl->pattern_triangles : 1);
  if (!(share <= rep->strip_triangle_overhead)) rep->strip_triangle_overhead = share; /* NAN: the first */
  if (!rep->json) return;
  json_object_begin(rep->json, NULL);
  json_string(rep->json, "model", in);
  json_uint(rep->json, "visible_patches", dl->patch_count - dl->culled);
  json_uint(rep->json, "pattern_triangles", dl->pattern_triangles);
  json_uint(rep->json, "strip_triangles", dl->strip_triangles);
  json_number(rep->json, "strip_over_pattern", share);
  json_object_end(rep->json);
}

static int table1_case(const char* in, double distance, bench_report* rep, FILE* csv) {
  bench_scene s;
  int rc = bench_scene_load(in, 0, TLOD_SURFACE_PN, 8, &s);
  if (rc != CLI_OK) return rc;
  tlod_view_desc view;
  bench_orbit_view(s.setup.mesh, 0.6f, (float)distance, 1600, 1144, &view);
  uint32_t worst = 0, patches = tlod_surface_patch_count(s.setup.surface);
  int8_t* error_levels = calloc(patches + 1u, 1);
  if (!error_levels) {
    bench_scene_free(&s);
    return cli_error(CLI_FAILED, "out of memory");
  }
  for (int p = TLOD_POLICY_ERROR; p <= TLOD_POLICY_HYBRID && rc == CLI_OK; p++) {
    tlod_scheduler* sch = NULL;
    /* The silhouette policy refines contours to its max level whatever the
     * error: cap it at the level the error rule needs, as uniform is. */
    tlod_scheduler_desc d = {.epsilon_px = 0.5f,
                             .policy = (tlod_lod_policy)p,
                             .morph = TLOD_MORPH_NONE,
                             .max_level = p == TLOD_POLICY_SILHOUETTE && worst ? worst : 0};
    if (tlod_scheduler_create(s.ctx, s.setup.surface, s.setup.patterns, &d, &sch) != TLOD_SUCCESS ||
        tlod_scheduler_update(sch, &(tlod_frame_desc){.views = &view, .view_count = 1}) != TLOD_SUCCESS) {
      rc = cli_error(CLI_FAILED, "%s", tlod_context_last_error(s.ctx));
      tlod_scheduler_destroy(sch);
      break;
    }
    const tlod_draw_list* dl = tlod_scheduler_draw_list(sch, 0);
    uint32_t visible = dl->patch_count - dl->culled;
    /* The uniform comparison uses the error rule's level for the worst patch. */
    if (p == TLOD_POLICY_ERROR)
      for (uint32_t f = 0; f < dl->patch_count; f++)
        if (dl->levels[f] >= 0 && (uint32_t)dl->levels[f] > worst) worst = (uint32_t)dl->levels[f];
    if (p == TLOD_POLICY_ERROR) rc = rule_comparison(in, &s, &view, dl, worst, csv);
    uint64_t adaptive = dl->pattern_triangles + dl->strip_triangles, uniform = uniform_triangles(&s, dl, worst);
    /* At contours the silhouette error must stay the error policy's. */
    uint32_t contour = 0, coarser = 0;
    for (uint32_t f = 0; f < patches; f++) {
      if (p == TLOD_POLICY_ERROR) error_levels[f] = dl->levels[f];
      if (dl->levels[f] < 0 || !on_contour(s.setup.mesh, f, view.view)) continue;
      contour++;
      coarser += dl->levels[f] < error_levels[f];
    }
    printf("table1     %-24s %-10s base %6u  adaptive %8llu (strips %5.1f%%)  uniform L%u %9llu  uniform/adaptive "
           "%5.2fx  contour patches %u, coarser than error policy %u\n",
           in, tool_policy_name((tlod_lod_policy)p), visible, (unsigned long long)adaptive,
           100.0 * (double)dl->strip_triangles / adaptive, worst, (unsigned long long)uniform,
           (double)uniform / (double)adaptive, contour, coarser);
    if (csv)
      fprintf(csv, "table1,%s,%s,%u,%llu,%llu,%u,%llu\n", in, tool_policy_name((tlod_lod_policy)p), visible,
              (unsigned long long)adaptive, (unsigned long long)dl->strip_triangles, worst,
              (unsigned long long)uniform);
    if (p == TLOD_POLICY_HYBRID) note_strips(rep, in, dl);
    tlod_scheduler_destroy(sch);
  }
  free(error_levels);
  bench_scene_free(&s);
  return rc;
}

int bench_table1(const bench_lod_options* o, bench_report* rep, FILE* csv) {
  int rc = CLI_OK;
  if (rep->json) json_array_begin(rep->json, "table1_hybrid");
  for (uint32_t i = 0; i < o->input_count && rc == CLI_OK; i++)
    rc = table1_case(o->inputs[i], 1.0, rep, csv);
  if (rep->json) json_array_end(rep->json);
  return rc;
}
