/* Deforming meshes (issue 15): tlod_mesh_update's recomputed normals
 * against an independent double-precision angle- (and area-) weighted
 * normal, updates and refreshes that allocate only the first time,
 * TLOD_ERROR_TABLES_NONE (no bounds, a sphere that still holds the patch,
 * refreshed like a fresh build) and the scheduler's refusal of it for the
 * policies that need bounds. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "tesslod/core.h"
#include "tesslod/lod.h"
#include "test.h"
#include "test_context.h"

/* A bumpy open grid, N x N cells; every third cell two triangles (one of
 * them with a corner near pi when squashed), the rest quads. */
#define N 9
#define NV ((N + 1) * (N + 1))

typedef struct grid {
  float pos[NV][3];
  uint32_t idx[N * N * 6];
  uint8_t sizes[N * N * 2];
  uint32_t index_count, face_count;
} grid;

static void grid_shape(grid* g, float phase) {
  for (uint32_t j = 0; j <= N; j++)
    for (uint32_t i = 0; i <= N; i++) {
      float* p = g->pos[j * (N + 1) + i];
      /* Uneven spacing in x (thin cells, wide angles) and a wave in z. */
      p[0] = (float)i + 0.35f * sinf(1.7f * (float)j + phase) - (i == 4 ? 0.45f : 0.0f);
      p[1] = (float)j + 0.2f * cosf(2.3f * (float)i);
      p[2] = 0.6f * sinf(0.9f * (float)i + phase) * cosf(0.7f * (float)j - phase);
    }
}

static void grid_make(grid* g) {
  memset(g, 0, sizeof(*g));
  grid_shape(g, 0.0f);
  for (uint32_t j = 0; j < N; j++)
    for (uint32_t i = 0; i < N; i++) {
      uint32_t a = j * (N + 1) + i, b = a + 1, c = a + N + 2, d = a + N + 1;
      if ((i + j) % 3 == 0) {
        uint32_t t[6] = {a, b, c, a, c, d};
        memcpy(g->idx + g->index_count, t, sizeof(t));
        g->index_count += 6;
        g->sizes[g->face_count++] = 3;
        g->sizes[g->face_count++] = 3;
      } else {
        uint32_t q[4] = {a, b, c, d};
        memcpy(g->idx + g->index_count, q, sizeof(q));
        g->index_count += 4;
        g->sizes[g->face_count++] = 4;
      }
    }
}

static tlod_mesh_desc grid_desc(const grid* g, tlod_normal_mode mode) {
  return (tlod_mesh_desc){.positions = &g->pos[0][0],
                          .vertex_count = NV,
                          .indices = g->idx,
                          .index_count = g->index_count,
                          .face_type = TLOD_FACE_MIXED,
                          .face_sizes = g->sizes,
                          .face_count = g->face_count,
                          .normal_mode = mode,
                          .label = "grid"};
}

/* ---- The oracle: straight from the definition, libm atan2, in double ---- */

static void d_sub(const float* a, const float* b, double o[3]) {
  for (int k = 0; k < 3; k++)
    o[k] = (double)a[k] - (double)b[k];
}
static void d_cross(const double a[3], const double b[3], double o[3]) {
  o[0] = a[1] * b[2] - a[2] * b[1];
  o[1] = a[2] * b[0] - a[0] * b[2];
  o[2] = a[0] * b[1] - a[1] * b[0];
}
static double d_len(const double a[3]) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

/* Twice the area vector: triangles the edges' cross product, quads the
 * diagonals' (tesslod/core.h: a quad's normal). */
static void oracle_face_normal(const grid* g, const uint32_t* c, uint32_t k, double n[3]) {
  double a[3], b[3];
  d_sub(g->pos[c[k == 4 ? 2 : 1]], g->pos[c[0]], a);
  d_sub(g->pos[c[k == 4 ? 3 : 2]], g->pos[c[k == 4 ? 1 : 0]], b);
  d_cross(a, b, n);
}

static void oracle_normals(const grid* g, bool area, double out[NV][3]) {
  memset(out, 0, sizeof(double) * NV * 3);
  const uint32_t* c = g->idx;
  for (uint32_t f = 0; f < g->face_count; c += g->sizes[f++]) {
    uint32_t k = g->sizes[f];
    double n[3];
    oracle_face_normal(g, c, k, n);
    double len = d_len(n);
    for (uint32_t i = 0; i < k; i++) {
      double a[3], b[3], x[3];
      d_sub(g->pos[c[(i + 1) % k]], g->pos[c[i]], a);
      d_sub(g->pos[c[(i + k - 1) % k]], g->pos[c[i]], b);
      d_cross(a, b, x);
      double w = area ? 0.5 * len : atan2(d_len(x), a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
      for (int d = 0; d < 3; d++)
        out[c[i]][d] += w * n[d] / len;
    }
  }
  for (uint32_t v = 0; v < NV; v++) {
    double len = d_len(out[v]);
    for (int d = 0; d < 3; d++)
      out[v][d] /= len;
  }
}

/* Every vertex's normal within float rounding of the oracle's; returns the
 * largest difference seen. */
static double normals_error(const tlod_mesh* m, const grid* g, bool area) {
  double ref[NV][3], worst = 0.0;
  oracle_normals(g, area, ref);
  for (uint32_t v = 0; v < NV; v++) {
    float n[3];
    tlod_mesh_vertex(m, v, NULL, n);
    for (int d = 0; d < 3; d++)
      worst = fmax(worst, fabs((double)n[d] - ref[v][d]));
  }
  return worst;
}

static void check_normals(tlod_normal_mode mode) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  grid g;
  grid_make(&g);
  tlod_mesh_desc d = grid_desc(&g, mode);
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  bool area = mode == TLOD_NORMALS_AREA;
  /* Float output of unit vectors: a few 2^-24 of rounding. */
  double tol = 4.0 * 0x1p-24;
  double e = normals_error(m, &g, area);
  CHECK_MSG(e <= tol, "created: %.3g", e);
  /* The other weighting is far off: the check can tell them apart. */
  CHECK(normals_error(m, &g, !area) > 100.0 * tol);
  for (int frame = 1; frame <= 3; frame++) {
    grid_shape(&g, 0.8f * (float)frame);
    CHECK(tlod_mesh_update(m, &g.pos[0][0], 0, NULL, 0) == TLOD_SUCCESS);
    e = normals_error(m, &g, area);
    CHECK_MSG(e <= tol, "frame %d: %.3g", frame, e);
  }
  /* An update reproduces a fresh creation from the same positions, bitwise. */
  tlod_mesh* fresh = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &fresh) == TLOD_SUCCESS);
  for (uint32_t v = 0; v < NV; v++) {
    float a[3], b[3];
    tlod_mesh_vertex(m, v, NULL, a);
    tlod_mesh_vertex(fresh, v, NULL, b);
    CHECK_MSG(memcmp(a, b, sizeof(a)) == 0, "vertex %u", v);
  }
  tlod_mesh_destroy(fresh);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

TEST(angle_normals_match_double_oracle) { check_normals(TLOD_NORMALS_ANGLE); }
TEST(area_normals_match_double_oracle) { check_normals(TLOD_NORMALS_AREA); }

/* Corners at nearly 0 and nearly pi (a sliver triangle), where an angle by
 * acos would lose its digits: the normal still matches the oracle. */
TEST(sliver_angles_match_double_oracle) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  grid g;
  grid_make(&g);
  /* Triangle (0, 1, N + 2) of the first cell: vertex 1 just off the middle
   * of the other two (an angle near pi there, near 0 at the others). */
  const float* a = g.pos[0];
  const float* c = g.pos[N + 2];
  for (int k = 0; k < 3; k++)
    g.pos[1][k] = 0.5f * (a[k] + c[k]);
  g.pos[1][0] += 1e-3f;
  g.pos[1][1] -= 1e-3f;
  tlod_mesh_desc d = grid_desc(&g, TLOD_NORMALS_ANGLE);
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  double e = normals_error(m, &g, false);
  CHECK_MSG(e <= 4.0 * 0x1p-24, "%.3g", e);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

/* The corner angles run in lanes per instruction set: every level the
 * processor has gives bitwise the scalar normals, created and updated. */
TEST(normals_bitwise_at_every_simd_level) {
  grid g;
  grid_make(&g);
  float ref[NV][3], got[NV][3];
  for (int level = TLOD_SIMD_SCALAR; level < TLOD_SIMD_NUM; level++) {
    tlod_context* ctx = NULL;
    tlod_context_desc cd = {.thread_count = 1, .simd = (tlod_simd)level};
    CHECK(tlod_context_create(&cd, &ctx) == TLOD_SUCCESS);
    grid_shape(&g, 0.0f);
    tlod_mesh_desc d = grid_desc(&g, TLOD_NORMALS_ANGLE);
    tlod_mesh* m = NULL;
    CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
    grid_shape(&g, 1.3f);
    CHECK(tlod_mesh_update(m, &g.pos[0][0], 0, NULL, 0) == TLOD_SUCCESS);
    for (uint32_t v = 0; v < NV; v++)
      tlod_mesh_vertex(m, v, NULL, level == TLOD_SIMD_SCALAR ? ref[v] : got[v]);
    if (level != TLOD_SIMD_SCALAR)
      CHECK_MSG(memcmp(ref, got, sizeof(ref)) == 0, "%s", tlod_simd_name(tlod_context_simd(ctx)));
    tlod_mesh_destroy(m);
    tlod_context_destroy(ctx);
  }
}

/* ---- No allocation per frame ---- */

TEST(updates_and_refreshes_allocate_once) {
  counting_allocator counter = {.fail_at = -1};
  tlod_context* ctx = new_context(1, &counter, NULL);
  grid g;
  grid_make(&g);
  tlod_mesh_desc d = grid_desc(&g, TLOD_NORMALS_ANGLE);
  tlod_mesh* m = NULL;
  tlod_surface* s = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  tlod_surface_desc sd = {.type = TLOD_SURFACE_PHONG, .error_tables = TLOD_ERROR_TABLES_NONE};
  CHECK(tlod_surface_create(ctx, m, &sd, &s) == TLOD_SUCCESS);
  long allocs = 0;
  for (int frame = 1; frame <= 4; frame++) {
    grid_shape(&g, 0.5f * (float)frame);
    uint32_t updated = 0;
    CHECK(tlod_mesh_update(m, &g.pos[0][0], 0, NULL, 0) == TLOD_SUCCESS);
    CHECK(tlod_surface_refresh(s, &updated) == TLOD_SUCCESS);
    CHECK(updated == g.face_count);
    if (frame == 1) allocs = counter.allocs;
    CHECK_MSG(counter.allocs == allocs, "frame %d: %ld allocations, %ld after the first", frame, counter.allocs,
              allocs);
  }
  /* An unchanged mesh rebuilds nothing. */
  uint32_t updated = 1;
  CHECK(tlod_mesh_update(m, &g.pos[0][0], 0, NULL, 0) == TLOD_SUCCESS);
  CHECK(tlod_surface_refresh(s, &updated) == TLOD_SUCCESS && updated == 0);
  tlod_surface_destroy(s);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
  CHECK(counter.allocs == counter.frees);
}

/* The first update's scratch failing leaves the mesh as it was. */
TEST(first_update_out_of_memory_leaves_mesh) {
  counting_allocator counter = {.fail_at = -1};
  tlod_context* ctx = new_context(1, &counter, NULL);
  grid g;
  grid_make(&g);
  tlod_mesh_desc d = grid_desc(&g, TLOD_NORMALS_ANGLE);
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  float before[NV][3], after[NV][3];
  for (uint32_t v = 0; v < NV; v++)
    tlod_mesh_vertex(m, v, before[v], NULL);
  counter.fail_at = counter.calls;
  grid_shape(&g, 1.0f);
  CHECK(tlod_mesh_update(m, &g.pos[0][0], 0, NULL, 0) == TLOD_ERROR_OUT_OF_MEMORY);
  for (uint32_t v = 0; v < NV; v++)
    tlod_mesh_vertex(m, v, after[v], NULL);
  CHECK(memcmp(before, after, sizeof(before)) == 0);
  counter.fail_at = -1;
  CHECK(tlod_mesh_update(m, &g.pos[0][0], 0, NULL, 0) == TLOD_SUCCESS);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
  CHECK(counter.allocs == counter.frees);
}

/* ---- TLOD_ERROR_TABLES_NONE ---- */

static tlod_surface* make_surface(tlod_context* ctx, const tlod_mesh* m, tlod_error_tables tables, float alpha) {
  tlod_surface_desc sd = {
      .type = TLOD_SURFACE_PHONG, .alpha_mode = TLOD_ALPHA_GLOBAL, .alpha = alpha, .error_tables = tables};
  tlod_surface* s = NULL;
  return tlod_surface_create(ctx, m, &sd, &s) == TLOD_SUCCESS ? s : NULL;
}

/* Every evaluated point of every patch within its sphere; returns the
 * largest distance / radius. */
static double sphere_fill(const tlod_surface* s) {
  double worst = 0.0;
  for (uint32_t p = 0; p < tlod_surface_patch_count(s); p++) {
    tlod_patch_info info = tlod_surface_patch(s, p);
    for (int i = 0; i <= 16; i++)
      for (int j = 0; j <= 16; j++) {
        float u = (float)i / 16.0f, v = (float)j / 16.0f;
        if (info.corner_count == 3 && u + v > 1.0f) continue;
        tlod_surface_point pt;
        if (tlod_surface_eval(s, p, u, v, &pt) != TLOD_SUCCESS) return INFINITY;
        double d[3] = {pt.position[0] - (double)info.center[0], pt.position[1] - (double)info.center[1],
                       pt.position[2] - (double)info.center[2]};
        worst = fmax(worst, d_len(d) / info.radius);
      }
  }
  return worst;
}

TEST(none_tables_unknown_bounds_valid_sphere) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  grid g;
  grid_make(&g);
  tlod_mesh_desc d = grid_desc(&g, TLOD_NORMALS_ANGLE);
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  const float alphas[] = {0.75f, 1.0f, 0.0f};
  for (int a = 0; a < 3; a++) {
    tlod_surface* s = make_surface(ctx, m, TLOD_ERROR_TABLES_NONE, alphas[a]);
    tlod_surface* closed = make_surface(ctx, m, TLOD_ERROR_TABLES_CLOSED_FORM, alphas[a]);
    CHECK(s && closed);
    for (uint32_t p = 0; p < tlod_surface_patch_count(s); p++) {
      tlod_patch_info info = tlod_surface_patch(s, p);
      for (uint32_t l = 0; l <= 10; l++)
        CHECK_MSG(isinf(tlod_patch_error_bound(&info, l)), "patch %u level %u", p, l);
      CHECK(isinf(info.error_bound));
      /* The same centre as the closed-form sphere (the corners' mean). */
      tlod_patch_info c = tlod_surface_patch(closed, p);
      CHECK(memcmp(info.center, c.center, sizeof(c.center)) == 0);
    }
    /* The cheap sphere holds the patch; and is not absurdly loose: the
     * patch reaches most of it. */
    double fill = sphere_fill(s);
    CHECK_MSG(fill <= 1.0 && fill > 0.5, "alpha %g: %.6f", (double)alphas[a], fill);
    tlod_surface_destroy(closed);
    tlod_surface_destroy(s);
  }
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

/* A refresh after updates gives bitwise the patches of a fresh surface. */
static void check_refresh_equals_fresh(tlod_error_tables tables) {
  reverse_pool pool = {0};
  tlod_context* ctx = new_context(3, NULL, &pool);
  grid g;
  grid_make(&g);
  tlod_mesh_desc d = grid_desc(&g, TLOD_NORMALS_ANGLE);
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  tlod_surface* s = make_surface(ctx, m, tables, 0.75f);
  CHECK(s != NULL);
  for (int frame = 1; frame <= 2; frame++) {
    grid_shape(&g, 0.6f * (float)frame);
    CHECK(tlod_mesh_update(m, &g.pos[0][0], 0, NULL, 0) == TLOD_SUCCESS);
    CHECK(tlod_surface_refresh(s, NULL) == TLOD_SUCCESS);
  }
  tlod_surface* fresh = make_surface(ctx, m, tables, 0.75f);
  CHECK(fresh != NULL);
  for (uint32_t p = 0; p < tlod_surface_patch_count(s); p++) {
    tlod_patch_info a = tlod_surface_patch(s, p), b = tlod_surface_patch(fresh, p);
    CHECK_MSG(memcmp(&a, &b, sizeof(a)) == 0, "patch %u", p);
  }
  tlod_surface_destroy(fresh);
  tlod_surface_destroy(s);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

TEST(refresh_none_equals_fresh) { check_refresh_equals_fresh(TLOD_ERROR_TABLES_NONE); }
TEST(refresh_closed_form_equals_fresh) { check_refresh_equals_fresh(TLOD_ERROR_TABLES_CLOSED_FORM); }
TEST(refresh_measured_equals_fresh) { check_refresh_equals_fresh(TLOD_ERROR_TABLES_MEASURED); }

/* The sphere of a Phong patch without tables, as docs/design.md states it:
 * centre the corners' float mean (summed in corner order, times 1/n),
 * radius (the largest corner distance + grow) (1 + 1e-5), grow = a_max D
 * (n - 1) / n (1 + 2^-20) + 1e-6 extent, D = max |(p_y - p_x).n_x|, in
 * double. Written out here as the independent reference. */
static void none_sphere(const tlod_mesh_view* v, float alpha, uint32_t f, float center[3], float* radius) {
  uint32_t n = v->face_corners[f];
  const float(*p)[3] = v->positions;
  const uint32_t* c = v->faces[f];
  float m[3];
  for (int k = 0; k < 3; k++) {
    m[k] = p[c[0]][k];
    for (uint32_t i = 1; i < n; i++)
      m[k] += p[c[i]][k];
    center[k] = m[k] * (1.0f / (float)n);
  }
  float r2 = 0.0f;
  double dmax = 0.0, extent2 = 0.0;
  for (uint32_t x = 0; x < n; x++) {
    float d[3] = {p[c[x]][0] - center[0], p[c[x]][1] - center[1], p[c[x]][2] - center[2]};
    r2 = fmaxf(r2, d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    double q[3] = {(double)p[c[x]][0] - p[c[0]][0], (double)p[c[x]][1] - p[c[0]][1], (double)p[c[x]][2] - p[c[0]][2]};
    extent2 = fmax(extent2, q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    for (uint32_t y = 0; y < n; y++) {
      double e = 0.0;
      for (int k = 0; k < 3; k++)
        e += ((double)p[c[y]][k] - p[c[x]][k]) * v->normals[c[x]][k];
      dmax = fmax(dmax, fabs(e));
    }
  }
  double grow = alpha * dmax * (double)(n - 1) / (double)n * (1.0 + 0x1p-20) + 1e-6 * sqrt(extent2);
  *radius = (sqrtf(r2) + (float)grow) * (1.0f + 1e-5f);
}

static void check_none_spheres(tlod_context* ctx, const tlod_surface* s, const tlod_mesh* m, float alpha,
                               const char* when) {
  tlod_mesh_view v = tlod_mesh_query_view(m);
  for (uint32_t f = 0; f < v.face_count; f++) {
    tlod_patch_info info = tlod_surface_patch(s, f);
    float center[3], radius;
    none_sphere(&v, alpha, f, center, &radius);
    CHECK_MSG(memcmp(info.center, center, sizeof(center)) == 0 && memcmp(&info.radius, &radius, sizeof(float)) == 0,
              "%s, %s, alpha %g: patch %u sphere (%.9g %.9g %.9g) r %.9g, expected (%.9g %.9g %.9g) r %.9g", when,
              tlod_simd_name(tlod_context_simd(ctx)), (double)alpha, f, (double)info.center[0], (double)info.center[1],
              (double)info.center[2], (double)info.radius, (double)center[0], (double)center[1], (double)center[2],
              (double)radius);
    CHECK(info.corner_count == v.face_corners[f] && isinf(info.error_bound) && isinf(info.d_max));
  }
}

/* A NONE surface's spheres are made in lanes of patches (surface_spheres.c),
 * at creation and on a refresh: bitwise the rule above, at every
 * instruction set this processor has; one thread, so a block holds all of
 * the grid's triangles or quads (the lanes and their remainder); three
 * alphas. */
TEST(none_spheres_bitwise_at_every_simd_level) {
  const float alphas[] = {0.75f, 1.0f, 0.0f};
  for (int level = TLOD_SIMD_SCALAR; level < TLOD_SIMD_NUM; level++) {
    tlod_context* ctx = NULL;
    tlod_context_desc cd = {.thread_count = 1, .simd = (tlod_simd)level};
    CHECK(tlod_context_create(&cd, &ctx) == TLOD_SUCCESS);
    if (tlod_context_simd(ctx) != (tlod_simd)level) { /* this processor lacks it */
      tlod_context_destroy(ctx);
      break;
    }
    for (int a = 0; a < 3; a++) {
      grid g;
      grid_make(&g);
      tlod_mesh_desc d = grid_desc(&g, TLOD_NORMALS_ANGLE);
      tlod_mesh* m = NULL;
      CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
      tlod_surface* s = make_surface(ctx, m, TLOD_ERROR_TABLES_NONE, alphas[a]);
      CHECK(s != NULL);
      check_none_spheres(ctx, s, m, alphas[a], "created");
      grid_shape(&g, 1.1f);
      uint32_t updated = 0;
      CHECK(tlod_mesh_update(m, &g.pos[0][0], 0, NULL, 0) == TLOD_SUCCESS);
      CHECK(tlod_surface_refresh(s, &updated) == TLOD_SUCCESS);
      CHECK(updated == tlod_surface_patch_count(s)); /* the wave moves every vertex */
      check_none_spheres(ctx, s, m, alphas[a], "refreshed");
      tlod_surface_destroy(s);
      tlod_mesh_destroy(m);
    }
    tlod_context_destroy(ctx);
  }
}

TEST(scheduler_refuses_none_for_error_policies) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  grid g;
  grid_make(&g);
  tlod_mesh_desc d = grid_desc(&g, TLOD_NORMALS_ANGLE);
  tlod_mesh* m = NULL;
  tlod_patterns* pat = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  CHECK(tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = 3}, &pat) == TLOD_SUCCESS);
  tlod_surface* s = make_surface(ctx, m, TLOD_ERROR_TABLES_NONE, 0.75f);
  CHECK(s != NULL);
  const tlod_lod_policy refused[] = {TLOD_POLICY_DEFAULT, TLOD_POLICY_ERROR, TLOD_POLICY_HYBRID};
  for (int i = 0; i < 3; i++) {
    tlod_scheduler* sch = NULL;
    tlod_scheduler_desc sd = {.policy = refused[i]};
    CHECK(tlod_scheduler_create(ctx, s, pat, &sd, &sch) == TLOD_ERROR_INVALID_ARGUMENT && sch == NULL);
    CHECK(strstr(tlod_context_last_error(ctx), "TLOD_ERROR_TABLES_NONE") != NULL);
  }
  const tlod_lod_policy accepted[] = {TLOD_POLICY_UNIFORM, TLOD_POLICY_SILHOUETTE, TLOD_POLICY_FLAT};
  for (int i = 0; i < 3; i++) {
    tlod_scheduler* sch = NULL;
    tlod_scheduler_desc sd = {.policy = accepted[i]};
    CHECK(tlod_scheduler_create(ctx, s, pat, &sd, &sch) == TLOD_SUCCESS);
    tlod_scheduler_destroy(sch);
  }
  tlod_surface_destroy(s);
  tlod_patterns_destroy(pat);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

int main(void) {
  RUN(angle_normals_match_double_oracle);
  RUN(area_normals_match_double_oracle);
  RUN(sliver_angles_match_double_oracle);
  RUN(normals_bitwise_at_every_simd_level);
  RUN(updates_and_refreshes_allocate_once);
  RUN(first_update_out_of_memory_leaves_mesh);
  RUN(none_tables_unknown_bounds_valid_sphere);
  RUN(refresh_none_equals_fresh);
  RUN(none_spheres_bitwise_at_every_simd_level);
  RUN(refresh_closed_form_equals_fresh);
  RUN(refresh_measured_equals_fresh);
  RUN(scheduler_refuses_none_for_error_policies);
  TEST_END();
}
