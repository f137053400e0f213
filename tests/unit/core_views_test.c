/* Unit tests of core's API for the layers above it (tesslod/core.h, "For the
 * layers above core"): mesh and surface views, patch records, grid
 * evaluation, grid point classification, enum names, context plumbing.
 * Public API only; every reference is computed here, independently of
 * core's code (brute force, Bernstein sums in double). */
#include <stdint.h>

#include "shapes.h"
#include "tesslod/core.h"
#include "test.h"
#include "test_context.h"
#include "test_names.h"

static bool bits_equal(const float* a, const float* b, size_t n) { return memcmp(a, b, n * sizeof(float)) == 0; }

/* A mesh and surface of a shape; NULL surface when creation failed. */
typedef struct fixture {
  tlod_context* ctx;
  shape shape;
  tlod_mesh* mesh;
  tlod_surface* surface;
} fixture;

static bool fixture_make(fixture* fx, shape s, tlod_surface_type type) {
  memset(fx, 0, sizeof *fx);
  fx->ctx = new_context(1, NULL, NULL);
  fx->shape = s;
  tlod_mesh_desc md = shape_mesh_desc(&s);
  if (tlod_mesh_create(fx->ctx, &md, &fx->mesh) != TLOD_SUCCESS) return false;
  return tlod_surface_create(fx->ctx, fx->mesh, &(tlod_surface_desc){.type = type}, &fx->surface) == TLOD_SUCCESS;
}

static void fixture_free(fixture* fx) {
  tlod_surface_destroy(fx->surface);
  tlod_mesh_destroy(fx->mesh);
  tlod_context_destroy(fx->ctx);
  shape_free(&fx->shape);
}

/* ------------------------------------------------------------------------ */
/* Mesh view                                                                */
/* ------------------------------------------------------------------------ */

static void check_mesh_view(const tlod_mesh* m) {
  tlod_mesh_view v = tlod_mesh_query_view(m);
  CHECK(v.vertex_count == tlod_mesh_vertex_count(m) && v.face_count == tlod_mesh_face_count(m));
  for (uint32_t i = 0; i < v.vertex_count; i++) {
    float p[3], n[3];
    tlod_mesh_vertex(m, i, p, n);
    CHECK_MSG(bits_equal(p, v.positions[i], 3) && bits_equal(n, v.normals[i], 3), "vertex %u", i);
    CHECK_MSG(v.weld_id[i] == tlod_mesh_vertex_weld_id(m, i) && v.weld_id[i] <= i, "vertex %u weld id", i);
  }
  for (uint32_t f = 0; f < v.face_count; f++) {
    uint32_t corners[4];
    uint32_t n = tlod_mesh_face_corners(m, f, corners);
    CHECK_MSG(n == v.face_corners[f] && memcmp(corners, v.faces[f], n * sizeof(uint32_t)) == 0, "face %u", f);
    CHECK(v.face_input_index[f] == tlod_mesh_face_input_index(m, f));
    for (uint32_t e = 0; e < n; e++) {
      tlod_edge_link a = tlod_mesh_edge_link(m, f, e), b = v.links[f][e];
      CHECK_MSG(a.face == b.face && a.edge == b.edge && a.smooth == b.smooth, "face %u edge %u", f, e);
    }
  }
}

TEST(test_mesh_view_matches_queries) {
  shape shapes[] = {shape_icosphere(2), shape_quad_sphere(3), shape_cube_soft(), shape_open_grid(4),
                    shape_seam_sphere(6, 8)};
  for (size_t k = 0; k < sizeof shapes / sizeof shapes[0]; k++) {
    fixture fx;
    bool ok = fixture_make(&fx, shapes[k], TLOD_SURFACE_FLAT);
    CHECK_MSG(ok, "%s", shapes[k].name);
    CALL(check_mesh_view(fx.mesh));
    /* After an update the positions change in place and the view shows them. */
    tlod_mesh_view before = tlod_mesh_query_view(fx.mesh);
    for (uint32_t i = 0; i < 3 * fx.shape.vertex_count; i++)
      fx.shape.positions[i] *= 1.5f;
    CHECK(tlod_mesh_update(fx.mesh, fx.shape.positions, 0, NULL, 0) == TLOD_SUCCESS);
    CALL(check_mesh_view(fx.mesh));
    CHECK(tlod_mesh_query_view(fx.mesh).faces == before.faces);
    fixture_free(&fx);
  }
}

/* ------------------------------------------------------------------------ */
/* Patch records                                                            */
/* ------------------------------------------------------------------------ */

static bool all_zero(const void* p, size_t bytes) {
  const unsigned char* c = p;
  for (size_t i = 0; i < bytes; i++)
    if (c[i]) return false;
  return true;
}

/* Corners, normals, weld ids, alphas, and zeros where the record is unused. */
static void check_record_corners(const tlod_surface* s, uint32_t f, const tlod_patch_record* r) {
  const tlod_mesh* m = tlod_surface_mesh(s);
  tlod_surface_view sv = tlod_surface_query_view(s);
  uint32_t corners[4], n = tlod_mesh_face_corners(m, f, corners);
  CHECK(r->info[0] == n && r->info[1] == 0 && r->info[2] == 0 && r->info[3] == 0);
  for (uint32_t c = 0; c < 4; c++) {
    if (c >= n) {
      CHECK(all_zero(r->corner[c], 16) && all_zero(r->normal[c], 16) && r->weld[c] == 0);
      continue;
    }
    float p[3], nn[3];
    tlod_mesh_vertex(m, corners[c], p, nn);
    CHECK_MSG(bits_equal(r->corner[c], p, 3) && bits_equal(r->normal[c], nn, 3), "patch %u corner %u", f, c);
    CHECK(r->corner[c][3] == sv.vertex_alpha[corners[c]] && r->normal[c][3] == 0.0f);
    CHECK(r->weld[c] == tlod_mesh_vertex_weld_id(m, corners[c]));
  }
  if (sv.type != TLOD_SURFACE_PN) CHECK(all_zero(r->pn_control, sizeof r->pn_control + sizeof r->pn_normal));
}

/* The PN triangle of a record at (u, v, w), as a Bernstein sum in double
 * (Vlachos et al. 2001): position and the quadratic normal field. */
static void pn_reference(const tlod_patch_record* r, double u, double v, double pos[3], double nrm[3]) {
  /* b300 b030 b003 b210 b120 b021 b012 b102 b201 b111 */
  double w = 1.0 - u - v;
  const double basis[10] = {u * u * u,     v * v * v,     w * w * w,     3 * u * u * v, 3 * u * v * v,
                            3 * v * v * w, 3 * v * w * w, 3 * u * w * w, 3 * u * u * w, 6 * u * v * w};
  /* n200 n020 n002 n110 n011 n101 */
  const double nb[6] = {u * u, v * v, w * w, u * v, v * w, u * w};
  for (int k = 0; k < 3; k++) {
    pos[k] = nrm[k] = 0.0;
    for (int b = 0; b < 10; b++)
      pos[k] += basis[b] * r->pn_control[b][k];
    for (int c = 0; c < 3; c++)
      nrm[k] += nb[c] * r->normal[c][k] + nb[3 + c] * r->pn_normal[c][k];
  }
  double len = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
  for (int k = 0; k < 3; k++)
    nrm[k] /= len;
}

static double max_diff(const float a[3], const double b[3]) {
  double d = 0.0;
  for (int k = 0; k < 3; k++)
    d = fmax(d, fabs((double)a[k] - b[k]));
  return d;
}

/* Corners and edge midpoints of a PN record against tlod_surface_eval. */
static void check_record_pn(const tlod_surface* s, uint32_t f, const tlod_patch_record* r) {
  static const double uv[6][2] = {{1, 0}, {0, 1}, {0, 0}, {0.5, 0.5}, {0, 0.5}, {0.5, 0}};
  CHECK(bits_equal(r->pn_control[0], r->corner[0], 3) && bits_equal(r->pn_control[1], r->corner[1], 3) &&
        bits_equal(r->pn_control[2], r->corner[2], 3));
  for (int k = 0; k < 6; k++) {
    double pos[3], nrm[3];
    pn_reference(r, uv[k][0], uv[k][1], pos, nrm);
    tlod_surface_point pt;
    tlod_surface_eval(s, f, (float)uv[k][0], (float)uv[k][1], &pt);
    CHECK_MSG(max_diff(pt.position, pos) < 1e-5, "patch %u point %d: position off by %g", f, k,
              max_diff(pt.position, pos));
    CHECK_MSG(max_diff(pt.normal, nrm) < 1e-5, "patch %u point %d: normal off by %g", f, k, max_diff(pt.normal, nrm));
  }
}

TEST(test_patch_records) {
  struct {
    shape s;
    tlod_surface_type t;
  } cases[] = {{shape_icosphere(1), TLOD_SURFACE_PN},
               {shape_cube_soft(), TLOD_SURFACE_PN},
               {shape_torus(8, 6), TLOD_SURFACE_PHONG},
               {shape_quad_sphere(2), TLOD_SURFACE_PHONG},
               {shape_quad_cube(), TLOD_SURFACE_FLAT}};
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    fixture fx;
    bool ok = fixture_make(&fx, cases[k].s, cases[k].t);
    CHECK_MSG(ok, "%s", cases[k].s.name);
    uint32_t n = tlod_surface_patch_count(fx.surface);
    tlod_patch_record* rec = calloc(n + 1, sizeof *rec);
    CHECK(tlod_surface_patch_records(fx.surface, 0, n, rec) == TLOD_SUCCESS);
    for (uint32_t f = 0; f < n; f++) {
      CALL(check_record_corners(fx.surface, f, &rec[f]));
      if (cases[k].t == TLOD_SURFACE_PN) CALL(check_record_pn(fx.surface, f, &rec[f]));
    }
    /* A sub-range gives the same records; past the end writes nothing. */
    tlod_patch_record one, guard;
    memset(&guard, 0xAB, sizeof guard);
    one = guard;
    CHECK(tlod_surface_patch_records(fx.surface, n - 1, 1, &one) == TLOD_SUCCESS);
    CHECK(memcmp(&one, &rec[n - 1], sizeof one) == 0);
    one = guard;
    CHECK(tlod_surface_patch_records(fx.surface, n, 1, &one) == TLOD_ERROR_INVALID_ARGUMENT);
    CHECK(memcmp(&one, &guard, sizeof one) == 0);
    free(rec);
    fixture_free(&fx);
  }
}

/* ------------------------------------------------------------------------ */
/* Grid point classification                                                */
/* ------------------------------------------------------------------------ */

/* Brute force from the corner weights (times 2^g): a corner has all the
 * weight, an edge point has none on the corners off the edge, and its
 * parameter is the weight of the edge's end corner. */
static uint32_t brute_kind(uint32_t corners, uint32_t nn, uint32_t i, uint32_t j, uint32_t* param) {
  uint32_t w[4];
  if (corners == 3) {
    w[0] = i, w[1] = j, w[2] = nn - i - j;
  } else {
    /* Bilinear weights times nn^2 of (0,0) (1,0) (1,1) (0,1). */
    w[0] = (nn - i) * (nn - j), w[1] = i * (nn - j), w[2] = i * j, w[3] = (nn - i) * j;
  }
  uint32_t full = corners == 3 ? nn : nn * nn;
  for (uint32_t c = 0; c < corners; c++)
    if (w[c] == full) return c;
  for (uint32_t e = 0; e < corners; e++) {
    uint32_t a = e, b = (e + 1) % corners, off = 0;
    for (uint32_t c = 0; c < corners; c++)
      if (c != a && c != b) off += w[c];
    if (off != 0) continue;
    *param = corners == 3 ? w[b] : w[b] / nn;
    return TLOD_GRID_EDGE + e;
  }
  return TLOD_GRID_INTERIOR;
}

TEST(test_grid_point_kind) {
  for (uint32_t corners = 3; corners <= 4; corners++) {
    for (uint32_t g = 0; g <= 5; g++) {
      uint32_t nn = 1u << g;
      for (uint32_t j = 0; j <= nn; j++) {
        for (uint32_t i = 0; i <= (corners == 3 ? nn - j : nn); i++) {
          uint32_t p1 = 12345, p2 = 12345;
          uint32_t k1 = tlod_grid_point_kind(corners, g, i, j, &p1), k2 = brute_kind(corners, nn, i, j, &p2);
          CHECK_MSG(k1 == k2 && p1 == p2, "%u corners, g %u, (%u, %u): kind %u param %u, expected %u %u", corners, g, i,
                    j, k1, p1, k2, p2);
        }
      }
    }
  }
}

/* ------------------------------------------------------------------------ */
/* Grid evaluation                                                          */
/* ------------------------------------------------------------------------ */

/* Every grid point of a patch on the 2^g grid, as uint16 pairs. */
static uint32_t grid_points(uint32_t corners, uint32_t g, uint16_t (*ij)[2]) {
  uint32_t nn = 1u << g, count = 0;
  for (uint32_t j = 0; j <= nn; j++)
    for (uint32_t i = 0; i <= (corners == 3 ? nn - j : nn); i++)
      ij[count][0] = (uint16_t)i, ij[count][1] = (uint16_t)j, count++;
  return count;
}

#define GRID_LOG2 3
#define GRID_MAX ((1 << GRID_LOG2) + 1) * ((1 << GRID_LOG2) + 1)

static void check_grid_equals_eval(const tlod_surface* s, uint32_t f, uint32_t corners) {
  uint16_t ij[GRID_MAX][2];
  float pos[GRID_MAX][3], nrm[GRID_MAX][3], only_pos[GRID_MAX][3];
  uint32_t count = grid_points(corners, GRID_LOG2, ij);
  tlod_surface_eval_grid(s, f, GRID_LOG2, &ij[0][0], sizeof ij[0], count, &pos[0][0], &nrm[0][0]);
  tlod_surface_eval_grid(s, f, GRID_LOG2, &ij[0][0], sizeof ij[0], count, &only_pos[0][0], NULL);
  CHECK(bits_equal(&pos[0][0], &only_pos[0][0], 3 * (size_t)count));
  float nn = (float)(1u << GRID_LOG2);
  for (uint32_t k = 0; k < count; k++) {
    tlod_surface_point pt;
    tlod_surface_eval(s, f, (float)ij[k][0] / nn, (float)ij[k][1] / nn, &pt);
    CHECK_MSG(bits_equal(pt.position, pos[k], 3) && bits_equal(pt.normal, nrm[k], 3), "patch %u point (%u, %u)", f,
              ij[k][0], ij[k][1]);
  }
}

/* Grid coordinates of the point at parameter p (end corner's weight times
 * nn) on edge e: the inverse of the classification. */
static void edge_ij(uint32_t corners, uint32_t nn, uint32_t e, uint32_t p, uint16_t out[2]) {
  /* (i0, di, j0, dj): i = i0 * nn + di * p, j = j0 * nn + dj * p. */
  static const int tri[3][4] = {{1, -1, 0, 1}, {0, 0, 1, -1}, {0, 1, 0, 0}};
  static const int quad[4][4] = {{0, 1, 0, 0}, {1, 0, 0, 1}, {1, -1, 1, 0}, {0, 0, 1, -1}};
  const int* r = corners == 3 ? tri[e] : quad[e];
  out[0] = (uint16_t)((int)(r[0] * (int)nn) + r[1] * (int)p);
  out[1] = (uint16_t)((int)(r[2] * (int)nn) + r[3] * (int)p);
}

/* Points on a smooth shared edge are bitwise equal from both patches. */
static void check_shared_edges(const tlod_surface* s, uint32_t* checked) {
  tlod_mesh_view m = tlod_mesh_query_view(tlod_surface_mesh(s));
  uint32_t nn = 1u << GRID_LOG2;
  for (uint32_t f = 0; f < m.face_count; f++) {
    for (uint32_t e = 0; e < m.face_corners[f]; e++) {
      tlod_edge_link l = m.links[f][e];
      if (l.face == UINT32_MAX || !l.smooth) continue;
      for (uint32_t p = 0; p <= nn; p++) {
        uint16_t a[2], b[2];
        uint32_t pa = 0, pb = 0;
        edge_ij(m.face_corners[f], nn, e, p, a);
        edge_ij(m.face_corners[l.face], nn, l.edge, nn - p, b);
        uint32_t ka = tlod_grid_point_kind(m.face_corners[f], GRID_LOG2, a[0], a[1], &pa);
        CHECK_MSG(ka < TLOD_GRID_EDGE ? p == 0 || p == nn : ka == TLOD_GRID_EDGE + e && pa == p, "edge_ij");
        uint32_t kb = tlod_grid_point_kind(m.face_corners[l.face], GRID_LOG2, b[0], b[1], &pb);
        CHECK_MSG(kb < TLOD_GRID_EDGE || (kb == TLOD_GRID_EDGE + l.edge && pb == nn - p), "edge_ij");
        float qa[3], qb[3], na[3], nb[3];
        tlod_surface_eval_grid(s, f, GRID_LOG2, a, sizeof a, 1, qa, na);
        tlod_surface_eval_grid(s, l.face, GRID_LOG2, b, sizeof b, 1, qb, nb);
        CHECK_MSG(bits_equal(qa, qb, 3) && bits_equal(na, nb, 3), "faces %u/%u edge %u/%u point %u", f, l.face, e,
                  l.edge, p);
        (*checked)++;
      }
    }
  }
}

TEST(test_eval_grid) {
  const tlod_surface_type types[3] = {TLOD_SURFACE_FLAT, TLOD_SURFACE_PHONG, TLOD_SURFACE_PN};
  for (int t = 0; t < 3; t++) {
    for (uint32_t corners = 3; corners <= 4; corners++) {
      if (types[t] == TLOD_SURFACE_PN && corners == 4) continue; /* PN has no quads */
      fixture fx;
      bool ok = fixture_make(&fx, corners == 3 ? shape_icosphere(2) : shape_quad_sphere(3), types[t]);
      CHECK_MSG(ok, "type %d, %u corners", types[t], corners);
      for (uint32_t f = 0; f < tlod_surface_patch_count(fx.surface); f++)
        CALL(check_grid_equals_eval(fx.surface, f, corners));
      uint32_t checked = 0;
      CALL(check_shared_edges(fx.surface, &checked));
      CHECK(checked > 0);
      fixture_free(&fx);
    }
  }
}

/* ------------------------------------------------------------------------ */
/* Enum names                                                               */
/* ------------------------------------------------------------------------ */

DEFINE_NAMES_CHECK(tlod_surface_type, tlod_surface_type, TLOD_SURFACE_TYPE_NAMES, TLOD_SURFACE_NUM)
DEFINE_NAMES_CHECK(tlod_shading_normal, tlod_shading_normal, TLOD_SHADING_NORMAL_NAMES, TLOD_SHADING_NORMAL_NUM)
DEFINE_NAMES_CHECK(tlod_alpha_mode, tlod_alpha_mode, TLOD_ALPHA_MODE_NAMES, TLOD_ALPHA_NUM)
DEFINE_NAMES_CHECK(tlod_normal_mode, tlod_normal_mode, TLOD_NORMAL_MODE_NAMES, TLOD_NORMALS_NUM)

/* Every value but DEFAULT has a table entry; DEFAULT prints as the value it
 * resolves to. */
TEST(test_enum_names) {
  CALL(tlod_surface_type_names_check(TLOD_SURFACE_NUM - 1));
  CALL(tlod_shading_normal_names_check(TLOD_SHADING_NORMAL_NUM - 1));
  CALL(tlod_alpha_mode_names_check(TLOD_ALPHA_NUM - 1));
  CALL(tlod_normal_mode_names_check(TLOD_NORMALS_NUM - 1));
  CHECK(strcmp(tlod_surface_type_name(TLOD_SURFACE_DEFAULT), "phong") == 0);
  CHECK(strcmp(tlod_shading_normal_name(TLOD_SHADING_NORMAL_DEFAULT), "interpolated") == 0);
  CHECK(strcmp(tlod_alpha_mode_name(TLOD_ALPHA_DEFAULT), "global") == 0);
  CHECK(strcmp(tlod_normal_mode_name(TLOD_NORMALS_DEFAULT), "keep") == 0);
  CHECK(strcmp(tlod_surface_type_name(TLOD_SURFACE_PN), "pn") == 0);
  CHECK(strcmp(tlod_alpha_mode_name(TLOD_ALPHA_PER_VERTEX), "per-vertex") == 0);
}

/* ------------------------------------------------------------------------ */
/* Context plumbing                                                         */
/* ------------------------------------------------------------------------ */

typedef struct hooks {
  long allocs, frees, parallel_calls;
  size_t last_size;
  int log_count;
  tlod_log_level last_level;
  char last_message[640];
} hooks;

static void* hook_alloc(size_t size, void* user) {
  hooks* h = user;
  h->allocs++;
  h->last_size = size;
  return malloc(size);
}

static void hook_free(void* ptr, void* user) {
  hooks* h = user;
  if (ptr) h->frees++;
  free(ptr);
}

static void hook_log(tlod_log_level level, const char* message, void* user) {
  hooks* h = user;
  h->log_count++;
  h->last_level = level;
  snprintf(h->last_message, sizeof h->last_message, "%s", message);
}

/* Runs the range in two chunks, the second on worker 1. */
static void hook_parallel_for(tlod_task_fn fn, void* data, uint32_t count, void* user) {
  hooks* h = user;
  h->parallel_calls++;
  fn(data, count / 2, count, 1);
  fn(data, 0, count / 2, 0);
}

static void mark_task(void* data, uint32_t begin, uint32_t end, uint32_t worker) {
  uint32_t* marks = data;
  for (uint32_t i = begin; i < end; i++)
    marks[i] += 1 + worker * 100;
}

TEST(test_context_plumbing) {
  hooks h = {0};
  tlod_context_desc d = {.allocator = {hook_alloc, hook_free, &h},
                         .logger = {hook_log, &h},
                         .parallel_for = {hook_parallel_for, 2, &h},
                         .label = "views"};
  tlod_context* ctx = NULL;
  CHECK(tlod_context_create(&d, &ctx) == TLOD_SUCCESS);
  long base = h.allocs;
  unsigned char* p = tlod_context_alloc(ctx, 40);
  CHECK(p && h.allocs == base + 1 && h.last_size == 40 && ((uintptr_t)p % 16) == 0);
  void* z = tlod_context_alloc(ctx, 0);
  CHECK(z && h.last_size == 1);
  uint32_t* c = tlod_context_calloc(ctx, 10, sizeof(uint32_t));
  CHECK(c && h.last_size == 40 && all_zero(c, 40));
  long before = h.allocs;
  CHECK(tlod_context_calloc(ctx, SIZE_MAX / 2, 4) == NULL && h.allocs == before); /* overflow: no call */
  tlod_context_free(ctx, p);
  tlod_context_free(ctx, z);
  tlod_context_free(ctx, c);
  tlod_context_free(ctx, NULL);
  CHECK(h.frees == 3);

  int logs = h.log_count;
  CHECK(tlod_context_fail(ctx, TLOD_ERROR_INVALID_MESH, "face %d: %s", 17, "bad") == TLOD_ERROR_INVALID_MESH);
  CHECK(strcmp(tlod_context_last_error(ctx), "face 17: bad") == 0);
  CHECK(h.log_count == logs + 1 && h.last_level == TLOD_LOG_ERROR);
  CHECK(strstr(h.last_message, "[views]") == h.last_message && strstr(h.last_message, "face 17: bad"));
  tlod_context_log(ctx, TLOD_LOG_INFO, "%u patches", 12u);
  CHECK(h.log_count == logs + 2 && h.last_level == TLOD_LOG_INFO && strcmp(h.last_message, "[views] 12 patches") == 0);

  uint32_t marks[9] = {0};
  CHECK(tlod_context_worker_count(ctx) == 2);
  tlod_context_parallel_for(ctx, mark_task, marks, 9);
  CHECK(h.parallel_calls == 1 && marks[0] == 1 && marks[3] == 1 && marks[4] == 101 && marks[8] == 101);
  tlod_context_parallel_for(ctx, mark_task, marks, 0); /* nothing to run: no call */
  CHECK(h.parallel_calls == 1);
  double t0 = tlod_now_ms(), t1 = tlod_now_ms();
  CHECK(t0 > 0.0 && t1 >= t0);
  tlod_context_destroy(ctx);
  CHECK(h.allocs == h.frees);
}

int main(void) {
  RUN(test_mesh_view_matches_queries);
  RUN(test_patch_records);
  RUN(test_grid_point_kind);
  RUN(test_eval_grid);
  RUN(test_enum_names);
  RUN(test_context_plumbing);
  TEST_END();
}
