/* Unit tests of the mesh module: validation, repairs, welding, adjacency,
 * normals, creases, updates, allocation failures.
 * Public API only: a mesh's alphas are read through a PER_VERTEX surface's
 * view (tlod_surface_query_view().vertex_alpha). */
#include <math.h>
#include <stdint.h>

#include "tesslod/core.h"
#include "test.h"
#include "test_context.h"

#define PI 3.14159265358979323846

/* ------------------------------------------------------------------------ */
/* Fixtures                                                                 */
/* ------------------------------------------------------------------------ */

/* An allocator that counts, and fails once its budget is spent (test_alloc.h
 * fails the k-th call instead). */
typedef struct counting {
  long budget; /* allocations left; < 0: unlimited */
  size_t allocs, frees;
} counting;

static void* budget_alloc(size_t size, void* user) {
  counting* c = user;
  if (c->budget == 0) return NULL;
  if (c->budget > 0) c->budget--;
  c->allocs++;
  return malloc(size);
}

static void budget_free(void* ptr, void* user) {
  counting* c = user;
  if (ptr) c->frees++;
  free(ptr);
}

/* Log capture: the last message containing a marker. */
typedef struct log_capture {
  char last[640];
  int count;
} log_capture;

static void capture_log(tlod_log_level level, const char* message, void* user) {
  (void)level;
  log_capture* c = user;
  c->count++;
  if (strstr(message, "appended")) snprintf(c->last, sizeof(c->last), "%s", message);
}

/* The mesh's (clamped) per-vertex alphas, as a PER_VERTEX Phong surface
 * uses them, copied into out[vertex_count]; false when the mesh has none. */
static bool mesh_alphas(tlod_context* ctx, const tlod_mesh* m, float* out) {
  tlod_surface* s = NULL;
  tlod_surface_desc d = {.type = TLOD_SURFACE_PHONG, .alpha_mode = TLOD_ALPHA_PER_VERTEX};
  if (tlod_surface_create(ctx, m, &d, &s) != TLOD_SUCCESS) return false;
  memcpy(out, tlod_surface_query_view(s).vertex_alpha, sizeof(float) * tlod_mesh_vertex_count(m));
  tlod_surface_destroy(s);
  return true;
}

/* Cube [-1, 1]^3, vertex x + 2y + 4z, faces counter-clockwise seen from
 * outside, each quad (a, b, c, d) split as (a, b, c), (a, c, d). */
static const uint32_t cube_quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                          {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
static const float cube_face_normal[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};

static void cube_position(uint32_t v, float out[3]) {
  out[0] = (v & 1) ? 1.0f : -1.0f;
  out[1] = (v & 2) ? 1.0f : -1.0f;
  out[2] = (v & 4) ? 1.0f : -1.0f;
}

/* 8 shared vertices, 12 triangles. */
typedef struct shared_cube {
  float pos[8][3];
  uint32_t idx[36];
} shared_cube;

static void make_shared_cube(shared_cube* c) {
  for (uint32_t v = 0; v < 8; v++)
    cube_position(v, c->pos[v]);
  for (uint32_t f = 0; f < 6; f++) {
    const uint32_t* q = cube_quads[f];
    uint32_t t[6] = {q[0], q[1], q[2], q[0], q[2], q[3]};
    memcpy(&c->idx[f * 6], t, sizeof(t));
  }
}

static tlod_mesh_desc shared_cube_desc(const shared_cube* c) {
  return (tlod_mesh_desc){
      .positions = &c->pos[0][0], .vertex_count = 8, .indices = c->idx, .index_count = 36, .label = "cube"};
}

/* 24 vertices with split face normals, like glTF's Box. */
typedef struct split_cube {
  float pos[24][3];
  float nrm[24][3];
  uint32_t idx[36];
} split_cube;

static void make_split_cube(split_cube* c) {
  for (uint32_t f = 0; f < 6; f++) {
    for (uint32_t i = 0; i < 4; i++) {
      cube_position(cube_quads[f][i], c->pos[f * 4 + i]);
      memcpy(c->nrm[f * 4 + i], cube_face_normal[f], sizeof(c->nrm[0]));
    }
    uint32_t b = f * 4, t[6] = {b, b + 1, b + 2, b, b + 2, b + 3};
    memcpy(&c->idx[f * 6], t, sizeof(t));
  }
}

static tlod_mesh_desc split_cube_desc(const split_cube* c) {
  return (tlod_mesh_desc){.positions = &c->pos[0][0],
                          .normals = &c->nrm[0][0],
                          .vertex_count = 24,
                          .indices = c->idx,
                          .index_count = 36,
                          .label = "box"};
}

/* Flat grid of w x h quads in z = 0, as quads or as triangles. */
typedef struct grid {
  uint32_t w, h, vertex_count, index_count;
  float* pos;
  uint32_t* idx;
} grid;

static void make_grid(grid* g, uint32_t w, uint32_t h, bool triangles) {
  g->w = w;
  g->h = h;
  g->vertex_count = (w + 1) * (h + 1);
  g->index_count = w * h * (triangles ? 6 : 4);
  g->pos = malloc(sizeof(float) * 3 * g->vertex_count);
  g->idx = malloc(sizeof(uint32_t) * g->index_count);
  for (uint32_t y = 0; y <= h; y++)
    for (uint32_t x = 0; x <= w; x++) {
      float* p = &g->pos[(size_t)3 * (y * (w + 1) + x)];
      p[0] = (float)x;
      p[1] = (float)y;
      p[2] = 0.0f;
    }
  uint32_t* o = g->idx;
  for (uint32_t y = 0; y < h; y++)
    for (uint32_t x = 0; x < w; x++) {
      uint32_t a = y * (w + 1) + x, b = a + 1, c = a + w + 2, d = a + w + 1;
      if (triangles) {
        uint32_t t[6] = {a, b, c, a, c, d};
        memcpy(o, t, sizeof(t));
        o += 6;
      } else {
        uint32_t q[4] = {a, b, c, d};
        memcpy(o, q, sizeof(q));
        o += 4;
      }
    }
}

static void free_grid(grid* g) {
  free(g->pos);
  free(g->idx);
}

static double length3f(const float n[3]) {
  return sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
}

static bool has_finding(const tlod_mesh* m, tlod_finding_kind kind, uint32_t element) {
  tlod_mesh_info info = tlod_mesh_query_info(m);
  for (uint32_t i = 0; i < info.finding_count; i++) {
    tlod_finding f = tlod_mesh_query_finding(m, i);
    if (f.kind == kind && f.element == element) return true;
  }
  return false;
}

/* ------------------------------------------------------------------------ */
/* Topology                                                                 */
/* ------------------------------------------------------------------------ */

TEST(shared_cube_is_closed) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  shared_cube c;
  make_shared_cube(&c);
  tlod_mesh_desc d = shared_cube_desc(&c);
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  tlod_mesh_info info = tlod_mesh_query_info(m);
  CHECK(info.face_count == 12 && info.triangle_count == 12 && info.quad_count == 0);
  CHECK(info.welded_vertex_count == 8);
  CHECK_MSG(info.edge_count == 18, "edges %u", info.edge_count);
  CHECK(info.boundary_edges == 0);
  CHECK(info.non_manifold_edges == 0);
  CHECK_MSG(info.crease_edges == 0, "creases %u", info.crease_edges);
  CHECK(info.closed);
  CHECK(info.normals_computed == 8 && info.normals_repaired == 0);
  CHECK(info.finding_count == 0);
  CHECK(tlod_mesh_vertex_count(m) == 8);
  for (int i = 0; i < 3; i++) {
    CHECK(info.bbox_min[i] == -1.0f);
    CHECK(info.bbox_max[i] == 1.0f);
  }
  /* Every link is symmetric and smooth. */
  for (uint32_t f = 0; f < 12; f++)
    for (uint32_t e = 0; e < 3; e++) {
      tlod_edge_link l = tlod_mesh_edge_link(m, f, e);
      CHECK(l.face < 12 && l.smooth);
      tlod_edge_link back = tlod_mesh_edge_link(m, l.face, l.edge);
      CHECK(back.face == f && back.edge == e);
    }
  tlod_edge_link none = tlod_mesh_edge_link(m, 0, 3);
  CHECK(none.face == UINT32_MAX && !none.smooth);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

TEST(split_cube_welds_and_creases) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  split_cube c;
  make_split_cube(&c);
  tlod_mesh_desc d = split_cube_desc(&c);
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  tlod_mesh_info info = tlod_mesh_query_info(m);
  CHECK_MSG(info.welded_vertex_count == 8, "welded %u", info.welded_vertex_count);
  CHECK(info.edge_count == 18);
  CHECK(info.boundary_edges == 0 && info.non_manifold_edges == 0);
  CHECK(info.closed);
  CHECK_MSG(info.crease_edges == 12, "creases %u", info.crease_edges);
  CHECK(info.normals_computed == 0 && info.normals_repaired == 0);
  CHECK(tlod_mesh_vertex_count(m) == 24);
  /* weld id: smallest vertex with the same position. */
  for (uint32_t v = 0; v < 24; v++) {
    uint32_t w = tlod_mesh_vertex_weld_id(m, v);
    CHECK(w <= v && memcmp(c.pos[w], c.pos[v], sizeof(c.pos[v])) == 0);
    for (uint32_t u = 0; u < w; u++)
      CHECK(memcmp(c.pos[u], c.pos[v], sizeof(c.pos[v])) != 0);
  }
  /* The diagonal inside a face: triangle (a, b, c) edge 2 meets (a, c, d) edge 0. */
  for (uint32_t f = 0; f < 6; f++) {
    tlod_edge_link l = tlod_mesh_edge_link(m, 2 * f, 2);
    CHECK(l.face == 2 * f + 1 && l.edge == 0 && l.smooth);
    tlod_edge_link side = tlod_mesh_edge_link(m, 2 * f, 0);
    CHECK(side.face != UINT32_MAX && !side.smooth);
  }
  /* Given normals are kept (and were already unit). */
  float p[3], n[3];
  tlod_mesh_vertex(m, 5, p, n);
  CHECK(memcmp(n, c.nrm[5], sizeof(n)) == 0 && memcmp(p, c.pos[5], sizeof(p)) == 0);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

TEST(open_grid_boundary) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  for (int tri = 0; tri < 2; tri++) {
    grid g;
    make_grid(&g, 3, 4, tri);
    tlod_mesh_desc d = {.positions = g.pos,
                        .vertex_count = g.vertex_count,
                        .indices = g.idx,
                        .index_count = g.index_count,
                        .face_type = tri ? TLOD_FACE_TRIANGLES : TLOD_FACE_QUADS};
    tlod_mesh* m = NULL;
    tlod_result r = tlod_mesh_create(ctx, &d, &m);
    free_grid(&g);
    CHECK(r == TLOD_SUCCESS);
    tlod_mesh_info info = tlod_mesh_query_info(m);
    uint32_t edges = 3 * 5 + 4 * 4 + (tri ? 12 : 0);
    CHECK_MSG(info.boundary_edges == 14, "boundary %u", info.boundary_edges);
    CHECK_MSG(info.edge_count == edges, "edges %u, want %u", info.edge_count, edges);
    CHECK(!info.closed && info.non_manifold_edges == 0 && info.crease_edges == 0);
    CHECK(info.quad_count == (tri ? 0u : 12u) && info.triangle_count == (tri ? 24u : 0u));
    CHECK(info.finding_count == 14);
    for (uint32_t i = 0; i < info.finding_count; i++)
      CHECK(tlod_mesh_query_finding(m, i).kind == TLOD_FINDING_BOUNDARY_EDGE);
    /* Flat grid: every computed normal is +z. */
    float n[3];
    tlod_mesh_vertex(m, 7, NULL, n);
    CHECK(n[0] == 0.0f && n[1] == 0.0f && n[2] == 1.0f);
    tlod_mesh_destroy(m);
  }
  tlod_context_destroy(ctx);
}

TEST(findings_past_the_limit_are_counted) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  grid g;
  make_grid(&g, 40, 30, false);
  tlod_mesh_desc d = {.positions = g.pos,
                      .vertex_count = g.vertex_count,
                      .indices = g.idx,
                      .index_count = g.index_count,
                      .face_type = TLOD_FACE_QUADS};
  tlod_mesh* m = NULL;
  tlod_result r = tlod_mesh_create(ctx, &d, &m);
  free_grid(&g);
  CHECK(r == TLOD_SUCCESS);
  tlod_mesh_info info = tlod_mesh_query_info(m);
  CHECK(info.boundary_edges == 140);
  CHECK(info.finding_count == TLOD_MAX_FINDINGS);
  CHECK_MSG(info.findings_dropped == 140 - TLOD_MAX_FINDINGS, "dropped %u", info.findings_dropped);
  CHECK(tlod_mesh_query_finding(m, TLOD_MAX_FINDINGS).kind == TLOD_FINDING_NUM);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

TEST(non_manifold_edges) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  float pos[5][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  /* Three triangles on edge (0, 1). */
  uint32_t fan[9] = {0, 1, 2, 1, 0, 3, 1, 0, 4};
  tlod_mesh_desc d = {.positions = &pos[0][0], .vertex_count = 5, .indices = fan, .index_count = 9};
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  tlod_mesh_info info = tlod_mesh_query_info(m);
  CHECK_MSG(info.non_manifold_edges == 1, "non-manifold %u", info.non_manifold_edges);
  CHECK(!info.closed);
  CHECK(info.edge_count == 7 && info.boundary_edges == 6);
  CHECK(has_finding(m, TLOD_FINDING_NON_MANIFOLD_EDGE, 0));
  CHECK(tlod_mesh_edge_link(m, 0, 0).face == UINT32_MAX);
  CHECK(tlod_mesh_edge_link(m, 1, 0).face == UINT32_MAX);
  tlod_mesh_destroy(m);

  /* Two triangles on one edge, same direction: orientation flips. */
  uint32_t flip[6] = {0, 1, 2, 0, 1, 3};
  d.indices = flip;
  d.index_count = 6;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  info = tlod_mesh_query_info(m);
  CHECK(info.non_manifold_edges == 1 && info.boundary_edges == 4 && !info.closed);
  CHECK(tlod_mesh_edge_link(m, 0, 0).face == UINT32_MAX);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

TEST(mixed_faces) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  float pos[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}};
  uint32_t idx[7] = {0, 1, 2, 3, 1, 4, 2};
  uint8_t sizes[2] = {4, 3};
  tlod_mesh_desc d = {.positions = &pos[0][0],
                      .vertex_count = 5,
                      .indices = idx,
                      .index_count = 7,
                      .face_type = TLOD_FACE_MIXED,
                      .face_sizes = sizes,
                      .face_count = 2};
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  tlod_mesh_info info = tlod_mesh_query_info(m);
  CHECK(info.quad_count == 1 && info.triangle_count == 1);
  CHECK(info.edge_count == 6 && info.boundary_edges == 5);
  uint32_t corners[4];
  CHECK(tlod_mesh_face_corners(m, 0, corners) == 4 && corners[3] == 3);
  CHECK(tlod_mesh_face_corners(m, 1, corners) == 3 && corners[0] == 1 && corners[2] == 2);
  tlod_edge_link l = tlod_mesh_edge_link(m, 0, 1); /* quad edge 1 -> 2 */
  CHECK(l.face == 1 && l.edge == 2 && l.smooth);
  tlod_mesh_destroy(m);

  sizes[1] = 5;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_ERROR_INVALID_MESH && m == NULL);
  CHECK(strstr(tlod_context_last_error(ctx), "face 1") != NULL);
  sizes[1] = 3;
  d.index_count = 8;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_ERROR_INVALID_MESH);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* Validation                                                               */
/* ------------------------------------------------------------------------ */

TEST(index_out_of_range) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  float pos[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  uint32_t idx[6] = {0, 1, 2, 1, 3, 4096};
  tlod_mesh_desc d = {.positions = &pos[0][0], .vertex_count = 4, .indices = idx, .index_count = 6, .label = "duck"};
  tlod_mesh* m = (tlod_mesh*)&d; /* must be reset */
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_ERROR_INVALID_MESH);
  CHECK(m == NULL);
  const char* e = tlod_context_last_error(ctx);
  CHECK_MSG(strstr(e, "face 1") && strstr(e, "4096") && strstr(e, "'duck'") && strstr(e, "(4 vertices)") &&
                strstr(e, "indices 3..5"),
            "message: %s", e);
  tlod_context_destroy(ctx);
}

TEST(nan_position) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  float pos[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, NAN, 0}, {1, 1, 0}};
  uint32_t idx[6] = {0, 1, 3, 0, 3, 2};
  tlod_mesh_desc d = {.positions = &pos[0][0], .vertex_count = 4, .indices = idx, .index_count = 6};
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_ERROR_INVALID_MESH && m == NULL);
  const char* e = tlod_context_last_error(ctx);
  CHECK_MSG(strstr(e, "vertex 2") && strstr(e, "position.y"), "message: %s", e);
  pos[2][1] = 1.0f;
  pos[3][2] = -INFINITY;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_ERROR_INVALID_MESH);
  e = tlod_context_last_error(ctx);
  CHECK_MSG(strstr(e, "vertex 3") && strstr(e, "position.z"), "message: %s", e);
  pos[3][2] = 0.0f;
  float alphas[4] = {0, 0, NAN, 0};
  d.alphas = alphas;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_ERROR_INVALID_MESH);
  e = tlod_context_last_error(ctx);
  CHECK_MSG(strstr(e, "vertex 2") && strstr(e, "alpha"), "message: %s", e);
  tlod_context_destroy(ctx);
}

TEST(wrong_api_use) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  shared_cube c;
  make_shared_cube(&c);
  tlod_mesh_desc good = shared_cube_desc(&c);
  tlod_mesh* m = (tlod_mesh*)&good;
  CHECK(tlod_mesh_create(NULL, &good, &m) == TLOD_ERROR_INVALID_ARGUMENT && m == NULL);
  CHECK(tlod_mesh_create(ctx, NULL, &m) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(tlod_context_last_error(ctx), "desc") != NULL);
  CHECK(tlod_mesh_create(ctx, &good, NULL) == TLOD_ERROR_INVALID_ARGUMENT);

  tlod_mesh_desc d = good;
  d.face_type = (tlod_face_type)99;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(tlod_context_last_error(ctx), "face_type") != NULL);
  d = good;
  d.normal_mode = (tlod_normal_mode)7;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_ERROR_INVALID_ARGUMENT);
  d = good;
  d.position_stride = 8;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(tlod_context_last_error(ctx), "position_stride") != NULL);
  d = good;
  d.positions = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_ERROR_INVALID_ARGUMENT);
  d = good;
  d.indices = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_ERROR_INVALID_ARGUMENT);
  d = good;
  d.index_count = 0;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_ERROR_INVALID_ARGUMENT);
  d = good;
  d.crease_angle_deg = -1.0f;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_ERROR_INVALID_ARGUMENT);
  d = good;
  d.weld_epsilon = NAN;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_ERROR_INVALID_ARGUMENT);
  d = good;
  d.face_type = TLOD_FACE_MIXED;
  d.face_count = 0;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_ERROR_INVALID_ARGUMENT);
  /* Data, not API use: a bad index count is an invalid mesh. */
  d = good;
  d.index_count = 35;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_ERROR_INVALID_MESH);
  CHECK(strstr(tlod_context_last_error(ctx), "multiple of 3") != NULL);
  d = good;
  d.face_type = TLOD_FACE_QUADS;
  d.index_count = 34;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_ERROR_INVALID_MESH);
  CHECK(m == NULL);
  CHECK(tlod_mesh_update(NULL, NULL, 0, NULL, 0) == TLOD_ERROR_INVALID_ARGUMENT);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* Repairs                                                                  */
/* ------------------------------------------------------------------------ */

TEST(degenerate_faces_dropped) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  float pos[6][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  /* 0 ok, 1 repeated index, 2 collinear, 3 ok, 4 two corners at one position. */
  uint32_t idx[15] = {0, 1, 2, 0, 0, 1, 0, 1, 3, 1, 4, 2, 1, 5, 2};
  tlod_mesh_desc d = {.positions = &pos[0][0], .vertex_count = 6, .indices = idx, .index_count = 15};
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  tlod_mesh_info info = tlod_mesh_query_info(m);
  CHECK_MSG(info.degenerate_faces_dropped == 3, "dropped %u", info.degenerate_faces_dropped);
  CHECK(info.input_face_count == 5 && info.face_count == 2 && tlod_mesh_face_count(m) == 2);
  CHECK(tlod_mesh_face_input_index(m, 0) == 0);
  CHECK(tlod_mesh_face_input_index(m, 1) == 3);
  CHECK(tlod_mesh_face_input_index(m, 2) == UINT32_MAX);
  uint32_t corners[4];
  CHECK(tlod_mesh_face_corners(m, 1, corners) == 3);
  CHECK(corners[0] == 1 && corners[1] == 4 && corners[2] == 2);
  CHECK(has_finding(m, TLOD_FINDING_DEGENERATE_FACE, 1));
  CHECK(has_finding(m, TLOD_FINDING_DEGENERATE_FACE, 2));
  CHECK(has_finding(m, TLOD_FINDING_DEGENERATE_FACE, 4));
  /* Vertices 3 and 5 were only used by dropped faces. */
  CHECK(info.unused_vertices == 2);
  CHECK(has_finding(m, TLOD_FINDING_UNUSED_VERTEX, 3));
  CHECK(has_finding(m, TLOD_FINDING_UNUSED_VERTEX, 5));
  CHECK(info.bbox_max[0] == 1.0f); /* vertex 3 (x = 2) is unused */
  tlod_mesh_destroy(m);

  /* Nothing left: an invalid mesh. */
  uint32_t bad[6] = {0, 0, 1, 0, 1, 3};
  d.indices = bad;
  d.index_count = 6;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_ERROR_INVALID_MESH && m == NULL);
  const char* e = tlod_context_last_error(ctx);
  CHECK_MSG(strstr(e, "all 2 faces are degenerate") != NULL, "message: %s", e);
  tlod_context_destroy(ctx);
}

TEST(quad_with_one_flat_half_is_kept) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  /* Corners 0, 1, 2 are collinear: (0, 1, 2) is flat, (0, 2, 3) is not. */
  float pos[5][3] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {1, 1, 0}, {3, 0, 0}};
  uint32_t idx[8] = {0, 1, 2, 3, 0, 1, 2, 4};
  tlod_mesh_desc d = {
      .positions = &pos[0][0], .vertex_count = 5, .indices = idx, .index_count = 8, .face_type = TLOD_FACE_QUADS};
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  tlod_mesh_info info = tlod_mesh_query_info(m);
  CHECK(info.face_count == 1 && info.quad_count == 1 && info.degenerate_faces_dropped == 1);
  CHECK(has_finding(m, TLOD_FINDING_DEGENERATE_FACE, 1));
  float n[3];
  tlod_mesh_vertex(m, 3, NULL, n);
  CHECK_NEAR(n[2], 1.0, 1e-6);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

/* Octahedron, outward counter-clockwise faces. */
static const float octa_pos[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
static const uint32_t octa_idx[24] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};

TEST(bad_normals_repaired) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  float nrm[6][3];
  memcpy(nrm, octa_pos, sizeof(nrm));
  nrm[0][0] = 0.0f; /* zero-length */
  nrm[3][1] = NAN;  /* not finite */
  nrm[4][2] = 5.0f; /* valid, not unit */
  tlod_mesh_desc d = {
      .positions = &octa_pos[0][0], .normals = &nrm[0][0], .vertex_count = 6, .indices = octa_idx, .index_count = 24};
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  tlod_mesh_info info = tlod_mesh_query_info(m);
  CHECK_MSG(info.normals_repaired == 2, "repaired %u", info.normals_repaired);
  CHECK(info.normals_computed == 0);
  CHECK(info.closed && info.edge_count == 12);
  CHECK(has_finding(m, TLOD_FINDING_NORMAL_REPAIRED, 0));
  CHECK(has_finding(m, TLOD_FINDING_NORMAL_REPAIRED, 3));
  for (uint32_t v = 0; v < 6; v++) {
    float p[3], n[3];
    tlod_mesh_vertex(m, v, p, n);
    CHECK_NEAR(length3f(n), 1.0, 1e-6);
    /* Outward: along the position for this symmetric shape. */
    double dot = (double)n[0] * p[0] + (double)n[1] * p[1] + (double)n[2] * p[2];
    CHECK_MSG(dot > 0.999999, "vertex %u: n . p = %g", v, dot);
  }
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

TEST(alphas_clamped) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  float alphas[6] = {-0.5f, 0.25f, 2.0f, 1.0f, 0.0f, 0.75f};
  tlod_mesh_desc d = {
      .positions = &octa_pos[0][0], .alphas = alphas, .vertex_count = 6, .indices = octa_idx, .index_count = 24};
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  float got[6];
  CHECK(mesh_alphas(ctx, m, got));
  CHECK(got[0] == 0.0f && got[1] == 0.25f && got[2] == 1.0f);
  CHECK(got[5] == 0.75f);
  tlod_mesh_info info = tlod_mesh_query_info(m);
  CHECK(info.finding_count == 2);
  CHECK(has_finding(m, TLOD_FINDING_ALPHA_CLAMPED, 0));
  CHECK(has_finding(m, TLOD_FINDING_ALPHA_CLAMPED, 2));
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

TEST(unused_vertex_counted) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  float pos[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {100, 100, 100}};
  uint32_t idx[3] = {0, 1, 2};
  tlod_mesh_desc d = {.positions = &pos[0][0], .vertex_count = 4, .indices = idx, .index_count = 3};
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  tlod_mesh_info info = tlod_mesh_query_info(m);
  CHECK(info.unused_vertices == 1 && has_finding(m, TLOD_FINDING_UNUSED_VERTEX, 3));
  CHECK(info.bbox_max[0] == 1.0f && info.bbox_max[2] == 0.0f);
  CHECK(info.boundary_edges == 3);
  float n[3];
  tlod_mesh_vertex(m, 3, NULL, n);
  CHECK_NEAR(length3f(n), 1.0, 1e-6);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

/* The box as the face corners give it, in face order, the first of equal
 * values kept (the sign of a zero bound depends on it). */
static bool bbox_is_corners_box(const tlod_mesh* m) {
  tlod_mesh_view v = tlod_mesh_query_view(m);
  float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (uint32_t f = 0; f < v.face_count; f++)
    for (uint32_t i = 0; i < v.face_corners[f]; i++)
      for (int c = 0; c < 3; c++) {
        float x = v.positions[v.faces[f][i]][c];
        lo[c] = x < lo[c] ? x : lo[c], hi[c] = x > hi[c] ? x : hi[c];
      }
  tlod_mesh_info info = tlod_mesh_query_info(m);
  return memcmp(lo, info.bbox_min, sizeof(lo)) == 0 && memcmp(hi, info.bbox_max, sizeof(hi)) == 0;
}

/* tlod_mesh_create takes the box from the vertices when every one is a
 * corner: bitwise the corners' box, a zero bound's sign included (-0 is
 * the first in face order here, +0 the first in vertex order). */
TEST(bbox_matches_the_corners) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  enum { N = 300 };
  static float pos[N][3];
  static uint32_t idx[N];
  uint32_t r = 12345;
  for (uint32_t i = 0; i < N; i++) {
    for (int c = 0; c < 3; c++)
      r = r * 1664525u + 1013904223u, pos[i][c] = (float)(r >> 8) * 0x1p-22f - 2.0f;
    idx[i] = (i * 7u) % N; /* every vertex a corner, out of vertex order */
  }
  tlod_mesh* m = NULL;
  tlod_mesh_desc d = {.positions = &pos[0][0], .vertex_count = N, .indices = idx, .index_count = N};
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  CHECK(tlod_mesh_query_info(m).unused_vertices == 0 && bbox_is_corners_box(m));
  tlod_mesh_destroy(m);
  float zp[4][3] = {{0.0f, 0.0f, 0.0f}, {-0.0f, 1.0f, 0.0f}, {1.0f, 0.0f, 1.0f}, {1.0f, 1.0f, 1.0f}};
  uint32_t zi[6] = {1, 2, 3, 0, 2, 1};
  d = (tlod_mesh_desc){.positions = &zp[0][0], .vertex_count = 4, .indices = zi, .index_count = 6};
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  CHECK(bbox_is_corners_box(m) && signbit(tlod_mesh_query_info(m).bbox_min[0]));
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* Welding                                                                  */
/* ------------------------------------------------------------------------ */

TEST(weld_epsilon_and_signed_zero) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  /* Two triangles on edge (1, 2) / (3, 4); the copies are a hair off. */
  float pos[6][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 1.000001f, 0}, {1.000001f, 0, 0}, {1, 1, 0}};
  uint32_t idx[6] = {0, 1, 2, 3, 4, 5};
  tlod_mesh_desc d = {.positions = &pos[0][0], .vertex_count = 6, .indices = idx, .index_count = 6};
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  tlod_mesh_info info = tlod_mesh_query_info(m);
  CHECK(info.welded_vertex_count == 6 && info.edge_count == 6 && info.boundary_edges == 6);
  tlod_mesh_destroy(m);

  d.weld_epsilon = 1e-5f;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  info = tlod_mesh_query_info(m);
  CHECK_MSG(info.welded_vertex_count == 4, "welded %u", info.welded_vertex_count);
  CHECK(tlod_mesh_vertex_weld_id(m, 3) == 2 && tlod_mesh_vertex_weld_id(m, 4) == 1);
  CHECK(info.edge_count == 5 && info.boundary_edges == 4);
  /* Linked, but positions differ bitwise: the sides cannot agree exactly. */
  tlod_edge_link l = tlod_mesh_edge_link(m, 0, 1);
  CHECK(l.face == 1 && l.edge == 0 && !l.smooth);
  CHECK(info.crease_edges == 1);
  tlod_mesh_destroy(m);

  /* Exactly eps apart (both exact in float) still welds: "within eps". */
  float bpos[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1.25f, 0, 0}};
  uint32_t bidx[3] = {0, 1, 2};
  tlod_mesh_desc bd = {
      .positions = &bpos[0][0], .vertex_count = 4, .indices = bidx, .index_count = 3, .weld_epsilon = 0.25f};
  CHECK(tlod_mesh_create(ctx, &bd, &m) == TLOD_SUCCESS);
  CHECK(tlod_mesh_vertex_weld_id(m, 3) == 1);
  tlod_mesh_destroy(m);
  bd.weld_epsilon = 0.2499f;
  CHECK(tlod_mesh_create(ctx, &bd, &m) == TLOD_SUCCESS);
  CHECK(tlod_mesh_vertex_weld_id(m, 3) == 3);
  tlod_mesh_destroy(m);

  /* -0.0 and +0.0 weld by default; vertices 0 and 3 differ only there. */
  float zpos[5][3] = {{0, 0, -0.0f}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}, {-1, 1, 0}};
  uint32_t zidx[6] = {0, 1, 2, 3, 2, 4};
  tlod_mesh_desc zd = {.positions = &zpos[0][0], .vertex_count = 5, .indices = zidx, .index_count = 6};
  CHECK(tlod_mesh_create(ctx, &zd, &m) == TLOD_SUCCESS);
  CHECK(tlod_mesh_vertex_weld_id(m, 3) == 0);
  info = tlod_mesh_query_info(m);
  CHECK(info.welded_vertex_count == 4 && info.edge_count == 5 && info.boundary_edges == 4);
  l = tlod_mesh_edge_link(m, 0, 2); /* 2 -> 0 meets 3 -> 2 */
  CHECK(l.face == 1 && l.edge == 0);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

static uint32_t lcg_next(uint32_t* s) {
  *s = *s * 1664525u + 1013904223u;
  return *s >> 8;
}

/* Clusters of jittered copies (within 0.8 eps of each other), shuffled,
 * against the definition: each vertex welds to the smallest earlier
 * representative within eps per coordinate. Jitter spans cell boundaries
 * on every side, so every neighbour cell the search looks at is used. With
 * a large eps the clusters overlap and the tie-break is tested too. */
enum { WELD_BASES = 400, WELD_N = WELD_BASES * 3 };

static uint32_t brute_force_weld(float (*pos)[3], float eps, uint32_t* want) {
  uint32_t reps = 0;
  for (uint32_t v = 0; v < WELD_N; v++) {
    want[v] = v;
    for (uint32_t r = 0; r < v; r++) {
      if (want[r] != r) continue;
      bool near = true;
      for (int c = 0; c < 3; c++)
        near = near && fabs((double)pos[r][c] - pos[v][c]) <= eps;
      if (near) {
        want[v] = r;
        break;
      }
    }
    reps += want[v] == v;
  }
  return reps;
}

/* Fisher-Yates over n points. */
static void shuffle_points(float (*pos)[3], uint32_t n, uint32_t* seed) {
  for (uint32_t i = n - 1; i > 0; i--) {
    uint32_t j = lcg_next(seed) % (i + 1);
    float t[3];
    memcpy(t, pos[i], sizeof(t));
    memcpy(pos[i], pos[j], sizeof(t));
    memcpy(pos[j], t, sizeof(t));
  }
}

static void make_weld_cloud(float (*pos)[3], float jitter) {
  uint32_t seed = 12345;
  for (uint32_t i = 0; i < WELD_N; i++) {
    uint32_t b = i % WELD_BASES;
    float base[3] = {(float)(b % 8) * 0.37f, (float)(b / 8 % 8) * 0.41f, (float)(b / 64) * 0.43f};
    for (int c = 0; c < 3; c++)
      pos[i][c] = base[c] + ((float)(lcg_next(&seed) % 2001) / 1000.0f - 1.0f) * jitter;
  }
  shuffle_points(pos, WELD_N, &seed);
}

TEST(weld_epsilon_matches_brute_force) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  static float pos[WELD_N][3];
  static uint32_t want[WELD_N];
  const float eps_list[2] = {0.01f, 0.4f}; /* 0.4: x neighbours (0.37 apart) overlap */
  for (int k = 0; k < 2; k++) {
    float eps = eps_list[k];
    make_weld_cloud(pos, 0.4f * (k == 0 ? eps : 0.01f));
    uint32_t reps = brute_force_weld(pos, eps, want);
    if (k == 0)
      CHECK(reps == WELD_BASES);
    else
      CHECK(reps > 1 && reps < WELD_BASES);
    /* A single face at the cloud's corners; the rest is unused, and welded
     * all the same. */
    float corner[3][3] = {{-1, -1, -1}, {9, -1, -1}, {-1, 9, -1}};
    memcpy(pos[0], corner[0], sizeof(corner[0]));
    memcpy(pos[1], corner[1], sizeof(corner[1]));
    memcpy(pos[2], corner[2], sizeof(corner[2]));
    reps = brute_force_weld(pos, eps, want);
    uint32_t idx[3] = {0, 1, 2};
    tlod_mesh_desc d = {
        .positions = &pos[0][0], .vertex_count = WELD_N, .indices = idx, .index_count = 3, .weld_epsilon = eps};
    tlod_mesh* m = NULL;
    CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
    CHECK(tlod_mesh_query_info(m).welded_vertex_count == reps);
    for (uint32_t v = 0; v < WELD_N; v++)
      CHECK_MSG(tlod_mesh_vertex_weld_id(m, v) == want[v], "eps %g vertex %u: %u, want %u", (double)eps, v,
                tlod_mesh_vertex_weld_id(m, v), want[v]);
    tlod_mesh_destroy(m);
  }
  tlod_context_destroy(ctx);
}

/* Exact welding against sorting in the test: each vertex welds to the
 * smallest vertex with an equal position (== : -0.0 and +0.0 alike). Half a
 * million vertices drawn from about 230k distinct positions, shuffled, some
 * zeros negated: positions held by one to several vertices, and (with a
 * 32-bit sort key) a handful of distinct positions whose keys collide. */
enum { EXACT_N = 1 << 19, EXACT_BASES = 1 << 18 };

static float (*exact_pos)[3];

static int exact_cmp(const void* pa, const void* pb) {
  uint32_t a = *(const uint32_t*)pa, b = *(const uint32_t*)pb;
  for (int c = 0; c < 3; c++) {
    float x = exact_pos[a][c], y = exact_pos[b][c];
    if (x != y) return x < y ? -1 : 1;
  }
  return a < b ? -1 : (a > b);
}

static uint32_t sort_weld(float (*pos)[3], uint32_t* order, uint32_t* want) {
  exact_pos = pos;
  for (uint32_t v = 0; v < EXACT_N; v++)
    order[v] = v;
  qsort(order, EXACT_N, sizeof(*order), exact_cmp);
  uint32_t reps = 0;
  for (uint32_t i = 0, first = 0; i < EXACT_N; i++) {
    bool same = true;
    for (int c = 0; c < 3; c++)
      same = same && pos[order[first]][c] == pos[order[i]][c];
    if (!same) first = i;
    want[order[i]] = order[first];
    reps += first == i;
  }
  return reps;
}

static void make_exact_cloud(float (*pos)[3]) {
  uint32_t seed = 777;
  for (uint32_t i = 0; i < EXACT_N; i++) {
    uint32_t b = i < EXACT_BASES ? i : lcg_next(&seed) % EXACT_BASES;
    uint32_t h = b * 2654435761u;
    for (int c = 0; c < 3; c++) {
      float x = (float)((h >> (c * 7)) % 97) * 0.25f - 12.0f; /* 0.0 exactly at 48 */
      pos[i][c] = x == 0.0f && (lcg_next(&seed) & 1) ? -0.0f : x;
    }
    pos[i][0] += (float)(b % 4096) * 0x1p-10f;
  }
  shuffle_points(pos, EXACT_N, &seed);
}

TEST(weld_exact_matches_sorting) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  static float pos[EXACT_N][3];
  static uint32_t want[EXACT_N], order[EXACT_N];
  make_exact_cloud(pos);
  float corner[3][3] = {{-100, -100, -100}, {100, -100, -100}, {-100, 100, -100}};
  memcpy(pos[0], corner[0], sizeof(corner));
  uint32_t reps = sort_weld(pos, order, want), idx[3] = {0, 1, 2};
  CHECK_MSG(reps > EXACT_BASES / 2 && reps < EXACT_N - EXACT_N / 8, "distinct %u", reps);
  tlod_mesh_desc d = {.positions = &pos[0][0], .vertex_count = EXACT_N, .indices = idx, .index_count = 3};
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  CHECK_MSG(tlod_mesh_query_info(m).welded_vertex_count == reps, "welded %u, want %u",
            tlod_mesh_query_info(m).welded_vertex_count, reps);
  uint32_t wrong = 0;
  for (uint32_t v = 0; v < EXACT_N; v++)
    wrong += tlod_mesh_vertex_weld_id(m, v) != want[v];
  CHECK_MSG(wrong == 0, "%u vertices weld elsewhere", wrong);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* Normals                                                                  */
/* ------------------------------------------------------------------------ */

/* Vertex 1 = (1, -1, -1) of the triangulated cube: the +x face gives it two
 * 45-degree corners, -y and -z one 90-degree corner each. Angle weights
 * see three right angles, area weights see twice the area on +x. */
TEST(angle_weighted_cube_corner) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  shared_cube c;
  make_shared_cube(&c);
  tlod_mesh_desc d = shared_cube_desc(&c);
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  float n[3];
  tlod_mesh_vertex(m, 1, NULL, n);
  double s = 1.0 / sqrt(3.0);
  CHECK_NEAR(n[0], s, 1e-6);
  CHECK_NEAR(n[1], -s, 1e-6);
  CHECK_NEAR(n[2], -s, 1e-6);
  /* And every corner of the cube points along its diagonal. */
  for (uint32_t v = 0; v < 8; v++) {
    tlod_mesh_vertex(m, v, NULL, n);
    for (int i = 0; i < 3; i++)
      CHECK_NEAR(n[i], c.pos[v][i] * s, 1e-6);
  }
  tlod_mesh_destroy(m);

  d.normal_mode = TLOD_NORMALS_AREA;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  tlod_mesh_vertex(m, 1, NULL, n);
  double a = 1.0 / sqrt(6.0);
  CHECK_NEAR(n[0], 2 * a, 1e-6);
  CHECK_NEAR(n[1], -a, 1e-6);
  CHECK_NEAR(n[2], -a, 1e-6);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

TEST(recompute_modes_ignore_given_normals) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  split_cube c;
  make_split_cube(&c);
  tlod_mesh_desc d = split_cube_desc(&c);
  d.normal_mode = TLOD_NORMALS_ANGLE;
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  tlod_mesh_info info = tlod_mesh_query_info(m);
  CHECK(info.normals_computed == 24);
  /* Accumulated per welded position: every copy of a corner agrees. */
  for (uint32_t v = 0; v < 24; v++) {
    float n[3], w[3];
    tlod_mesh_vertex(m, v, NULL, n);
    tlod_mesh_vertex(m, tlod_mesh_vertex_weld_id(m, v), NULL, w);
    CHECK(memcmp(n, w, sizeof(n)) == 0);
    CHECK_NEAR(n[0] * c.pos[v][0] + n[1] * c.pos[v][1] + n[2] * c.pos[v][2], sqrt(3.0), 1e-5);
  }
  /* Seam duplicates now agree: every edge is smooth. */
  CHECK_MSG(info.crease_edges == 0, "creases %u", info.crease_edges);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

TEST(quad_normals) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  /* A non-planar quad: the diagonals' cross product is the normal. */
  float pos[4][3] = {{0, 0, 0}, {1, 0, 0.25f}, {1, 1, 0}, {0, 1, 0.25f}};
  uint32_t idx[4] = {0, 1, 2, 3};
  tlod_mesh_desc d = {
      .positions = &pos[0][0], .vertex_count = 4, .indices = idx, .index_count = 4, .face_type = TLOD_FACE_QUADS};
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  /* (1, 1, 0) x (-1, 1, 0) = (0, 0, 2). */
  for (uint32_t v = 0; v < 4; v++) {
    float n[3];
    tlod_mesh_vertex(m, v, NULL, n);
    CHECK(n[0] == 0.0f && n[1] == 0.0f && n[2] == 1.0f);
  }
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

TEST(crease_angle_splits_shared_cube) {
  log_capture log = {0};
  tlod_context* ctx = NULL;
  tlod_context_create(&(tlod_context_desc){.thread_count = 1, .logger = {.func = capture_log, .user_data = &log}},
                      &ctx);
  shared_cube c;
  make_shared_cube(&c);
  tlod_mesh_desc d = shared_cube_desc(&c);
  d.crease_angle_deg = 30.0f;
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  tlod_mesh_info info = tlod_mesh_query_info(m);
  /* Each corner is on three faces: three normals, two split vertices. */
  CHECK_MSG(tlod_mesh_vertex_count(m) == 24, "vertices %u", tlod_mesh_vertex_count(m));
  CHECK(info.input_vertex_count == 8 && info.normals_computed == 8);
  CHECK(info.welded_vertex_count == 8 && info.closed && info.edge_count == 18);
  CHECK_MSG(info.crease_edges == 12, "creases %u", info.crease_edges);
  CHECK(strstr(log.last, "16 vertices appended") != NULL);
  for (uint32_t f = 0; f < 12; f++) {
    uint32_t corners[4];
    CHECK(tlod_mesh_face_corners(m, f, corners) == 3);
    for (uint32_t i = 0; i < 3; i++) {
      float p[3], n[3];
      tlod_mesh_vertex(m, corners[i], p, n);
      CHECK(memcmp(n, cube_face_normal[f / 2], sizeof(n)) == 0);
      /* A split vertex keeps its source's position and welded id. */
      uint32_t w = tlod_mesh_vertex_weld_id(m, corners[i]);
      CHECK(w < 8 && memcmp(p, c.pos[w], sizeof(p)) == 0);
    }
  }
  tlod_mesh_destroy(m);

  /* Above 90 degrees the cube is smooth again. */
  d.crease_angle_deg = 100.0f;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  CHECK(tlod_mesh_vertex_count(m) == 8 && tlod_mesh_query_info(m).crease_edges == 0);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

TEST(crease_angle_keeps_smooth_regions) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  /* A gentle fold (10 degrees) in a grid stays smooth at 30 degrees. */
  grid g;
  make_grid(&g, 4, 2, true);
  for (uint32_t v = 0; v < g.vertex_count; v++)
    if (g.pos[3 * v] > 2.0f) g.pos[3 * v + 2] = (g.pos[3 * v] - 2.0f) * (float)tan(10.0 * PI / 180.0);
  tlod_mesh_desc d = {.positions = g.pos,
                      .vertex_count = g.vertex_count,
                      .indices = g.idx,
                      .index_count = g.index_count,
                      .crease_angle_deg = 30.0f};
  tlod_mesh* m = NULL;
  tlod_result r = tlod_mesh_create(ctx, &d, &m);
  CHECK(r == TLOD_SUCCESS);
  CHECK(tlod_mesh_vertex_count(m) == g.vertex_count);
  CHECK(tlod_mesh_query_info(m).crease_edges == 0);
  tlod_mesh_destroy(m);
  free_grid(&g);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* Strides                                                                  */
/* ------------------------------------------------------------------------ */

static bool same_info(const tlod_mesh_info* a, const tlod_mesh_info* b) {
  return a->input_vertex_count == b->input_vertex_count && a->face_count == b->face_count &&
         a->welded_vertex_count == b->welded_vertex_count && a->edge_count == b->edge_count &&
         a->boundary_edges == b->boundary_edges && a->crease_edges == b->crease_edges &&
         a->normals_repaired == b->normals_repaired && a->finding_count == b->finding_count && a->closed == b->closed &&
         memcmp(a->bbox_min, b->bbox_min, sizeof(a->bbox_min)) == 0 &&
         memcmp(a->bbox_max, b->bbox_max, sizeof(a->bbox_max)) == 0;
}

TEST(strides_match_tight_arrays) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  split_cube c;
  make_split_cube(&c);
  c.nrm[3][0] = c.nrm[3][1] = c.nrm[3][2] = 0.0f; /* a repair, to compare too */
  struct {
    float p[3], n[3];
  } inter[24];
  struct {
    float a;
    float pad;
  } alpha_inter[24];
  float alphas[24];
  for (uint32_t v = 0; v < 24; v++) {
    memcpy(inter[v].p, c.pos[v], sizeof(inter[v].p));
    memcpy(inter[v].n, c.nrm[v], sizeof(inter[v].n));
    alphas[v] = alpha_inter[v].a = (float)v / 23.0f;
    alpha_inter[v].pad = NAN; /* never read */
  }
  CHECK(sizeof(inter[0]) == 24);
  tlod_mesh_desc tight = split_cube_desc(&c);
  tight.alphas = alphas;
  tlod_mesh_desc strided = tight;
  strided.positions = inter[0].p;
  strided.normals = inter[0].n;
  strided.position_stride = strided.normal_stride = 24;
  strided.alphas = &alpha_inter[0].a;
  strided.alpha_stride = 8;
  tlod_mesh *a = NULL, *b = NULL;
  CHECK(tlod_mesh_create(ctx, &tight, &a) == TLOD_SUCCESS);
  CHECK(tlod_mesh_create(ctx, &strided, &b) == TLOD_SUCCESS);
  tlod_mesh_info ia = tlod_mesh_query_info(a), ib = tlod_mesh_query_info(b);
  CHECK(same_info(&ia, &ib) && ia.normals_repaired == 1);
  CHECK(tlod_mesh_vertex_count(a) == tlod_mesh_vertex_count(b) && tlod_mesh_vertex_count(a) <= 48);
  float alpha_a[48], alpha_b[48];
  CHECK(mesh_alphas(ctx, a, alpha_a) && mesh_alphas(ctx, b, alpha_b));
  for (uint32_t v = 0; v < tlod_mesh_vertex_count(a); v++) {
    float pa[3], na[3], pb[3], nb[3];
    tlod_mesh_vertex(a, v, pa, na);
    tlod_mesh_vertex(b, v, pb, nb);
    CHECK(memcmp(pa, pb, sizeof(pa)) == 0 && memcmp(na, nb, sizeof(na)) == 0);
    CHECK(alpha_a[v] == alpha_b[v]);
  }
  for (uint32_t f = 0; f < 12; f++)
    for (uint32_t e = 0; e < 3; e++) {
      tlod_edge_link la = tlod_mesh_edge_link(a, f, e), lb = tlod_mesh_edge_link(b, f, e);
      CHECK(la.face == lb.face && la.edge == lb.edge && la.smooth == lb.smooth);
    }
  tlod_mesh_destroy(a);
  tlod_mesh_destroy(b);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* Updates                                                                  */
/* ------------------------------------------------------------------------ */

TEST(update_positions_recomputes_normals) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  shared_cube c;
  make_shared_cube(&c);
  tlod_mesh_desc d = shared_cube_desc(&c);
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  /* Pull one corner in: its normal and its neighbours' change, and equal
   * those of a mesh created from the new positions, bitwise. */
  float before7[3];
  tlod_mesh_vertex(m, 7, NULL, before7);
  float moved[8][3];
  memcpy(moved, c.pos, sizeof(moved));
  moved[7][0] = 0.5f;
  moved[7][1] = 1.5f;
  CHECK(tlod_mesh_update(m, &moved[0][0], 0, NULL, 0) == TLOD_SUCCESS);
  float p[3], n[3];
  tlod_mesh_vertex(m, 7, p, n);
  CHECK(p[0] == 0.5f && p[1] == 1.5f);
  CHECK(memcmp(n, before7, sizeof(n)) != 0);
  tlod_mesh_desc fresh_desc = d;
  fresh_desc.positions = &moved[0][0];
  tlod_mesh* fresh = NULL;
  CHECK(tlod_mesh_create(ctx, &fresh_desc, &fresh) == TLOD_SUCCESS);
  for (uint32_t v = 0; v < 8; v++) {
    float a[3], b[3];
    tlod_mesh_vertex(m, v, NULL, a);
    tlod_mesh_vertex(fresh, v, NULL, b);
    CHECK_MSG(memcmp(a, b, sizeof(a)) == 0, "vertex %u", v);
  }
  tlod_mesh_destroy(fresh);
  tlod_mesh_info info = tlod_mesh_query_info(m);
  CHECK(info.bbox_max[1] == 1.5f && info.bbox_min[0] == -1.0f);

  /* A NaN is refused and the mesh is left alone. */
  float before[3];
  tlod_mesh_vertex(m, 7, before, NULL);
  moved[7][0] = 9.0f;
  moved[2][1] = NAN;
  CHECK(tlod_mesh_update(m, &moved[0][0], 12, NULL, 0) == TLOD_ERROR_INVALID_MESH);
  CHECK(strstr(tlod_context_last_error(ctx), "vertex 2") != NULL);
  tlod_mesh_vertex(m, 7, p, NULL);
  CHECK(memcmp(p, before, sizeof(p)) == 0);
  CHECK(tlod_mesh_update(m, &moved[0][0], 4, NULL, 0) == TLOD_ERROR_INVALID_ARGUMENT);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

TEST(update_normals_refreshes_smooth_flags) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  split_cube c;
  make_split_cube(&c);
  tlod_mesh_desc d = split_cube_desc(&c);
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  CHECK(tlod_mesh_query_info(m).crease_edges == 12);
  uint64_t smooth_gen = tlod_mesh_query_view(m).smooth_generation;
  /* Interleaved normals, all the same: every edge becomes smooth. */
  float normals[24][6] = {{0}};
  for (uint32_t v = 0; v < 24; v++) {
    normals[v][0] = normals[v][1] = 0.0f;
    normals[v][2] = 2.0f;
  }
  CHECK(tlod_mesh_update(m, NULL, 0, &normals[0][0], 24) == TLOD_SUCCESS);
  CHECK_MSG(tlod_mesh_query_info(m).crease_edges == 0, "creases %u", tlod_mesh_query_info(m).crease_edges);
  /* The flags moved: a new smooth generation; the same normals again move
   * nothing: the same smooth generation, a new mesh generation. */
  tlod_mesh_view before = tlod_mesh_query_view(m);
  CHECK(before.smooth_generation == smooth_gen + 1);
  CHECK(tlod_mesh_update(m, NULL, 0, &normals[0][0], 24) == TLOD_SUCCESS);
  CHECK(tlod_mesh_query_view(m).smooth_generation == before.smooth_generation);
  CHECK(tlod_mesh_query_view(m).generation == before.generation + 1);
  float n[3];
  tlod_mesh_vertex(m, 11, NULL, n);
  CHECK(n[0] == 0.0f && n[1] == 0.0f && n[2] == 1.0f);
  CHECK(tlod_mesh_edge_link(m, 0, 0).smooth);
  /* A zero normal cannot be repaired in an update: refused, nothing moves. */
  normals[4][2] = 0.0f;
  normals[5][2] = -1.0f;
  CHECK(tlod_mesh_update(m, NULL, 0, &normals[0][0], 24) == TLOD_ERROR_INVALID_MESH);
  tlod_mesh_vertex(m, 5, NULL, n);
  CHECK(n[2] == 1.0f);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

TEST(update_moves_crease_splits) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  shared_cube c;
  make_shared_cube(&c);
  tlod_mesh_desc d = shared_cube_desc(&c);
  d.crease_angle_deg = 30.0f;
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  uint32_t n = tlod_mesh_vertex_count(m);
  CHECK(n == 24);
  float before[24][3];
  for (uint32_t v = 0; v < n; v++)
    tlod_mesh_vertex(m, v, NULL, before[v]);
  float moved[8][3];
  for (uint32_t v = 0; v < 8; v++)
    for (int i = 0; i < 3; i++)
      moved[v][i] = c.pos[v][i] + (float)(i + 1);
  CHECK(tlod_mesh_update(m, &moved[0][0], 0, NULL, 0) == TLOD_SUCCESS);
  for (uint32_t v = 0; v < n; v++) {
    float p[3], nn[3];
    tlod_mesh_vertex(m, v, p, nn);
    uint32_t w = tlod_mesh_vertex_weld_id(m, v);
    CHECK_MSG(memcmp(p, moved[w], sizeof(p)) == 0, "vertex %u", v);
    /* A translation keeps every normal, bitwise. */
    CHECK_MSG(memcmp(nn, before[v], sizeof(nn)) == 0, "vertex %u", v);
  }
  CHECK(tlod_mesh_query_info(m).crease_edges == 12);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

/* ------------------------------------------------------------------------ */
/* Allocation                                                               */
/* ------------------------------------------------------------------------ */

/* Five crease-split cubes (80 splits: the split lists grow), alphas, a
 * repaired normal and a degenerate face: most allocation paths. */
typedef struct busy_mesh {
  float pos[40][3];
  float nrm[40][3];
  float alpha[40];
  uint32_t idx[5 * 36 + 3];
} busy_mesh;

static tlod_mesh_desc make_busy(busy_mesh* b) {
  shared_cube c;
  make_shared_cube(&c);
  for (uint32_t k = 0; k < 5; k++) {
    for (uint32_t v = 0; v < 8; v++) {
      for (int i = 0; i < 3; i++)
        b->pos[k * 8 + v][i] = c.pos[v][i] + 3.0f * (float)k;
      b->alpha[k * 8 + v] = 0.5f;
    }
    for (uint32_t i = 0; i < 36; i++)
      b->idx[k * 36 + i] = c.idx[i] + k * 8;
  }
  b->idx[180] = b->idx[181] = 0;
  b->idx[182] = 1;
  return (tlod_mesh_desc){.positions = &b->pos[0][0],
                          .alphas = b->alpha,
                          .vertex_count = 40,
                          .indices = b->idx,
                          .index_count = 183,
                          .crease_angle_deg = 30.0f,
                          .label = "busy"};
}

TEST(allocator_balanced) {
  counting cnt = {.budget = -1};
  tlod_context* ctx = NULL;
  tlod_context_desc cd = {.thread_count = 1, .allocator = {budget_alloc, budget_free, &cnt}};
  CHECK(tlod_context_create(&cd, &ctx) == TLOD_SUCCESS);
  size_t a0 = cnt.allocs, f0 = cnt.frees;
  busy_mesh b;
  tlod_mesh_desc d = make_busy(&b);
  tlod_mesh* m = NULL;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  CHECK(tlod_mesh_vertex_count(m) == 40 + 5 * 16);
  CHECK(tlod_mesh_query_info(m).degenerate_faces_dropped == 1);
  CHECK(cnt.allocs > a0);
  CHECK(tlod_mesh_update(m, &b.pos[0][0], 0, NULL, 0) == TLOD_SUCCESS);
  tlod_mesh_destroy(m);
  CHECK_MSG(cnt.allocs - a0 == cnt.frees - f0, "allocs %zu frees %zu", cnt.allocs - a0, cnt.frees - f0);
  /* A rejected mesh allocates nothing. */
  d.vertex_count = 2;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_ERROR_INVALID_MESH);
  CHECK(cnt.allocs - a0 == cnt.frees - f0);
  tlod_context_destroy(ctx);
  CHECK(cnt.allocs == cnt.frees);
}

TEST(allocation_failures) {
  counting cnt = {.budget = -1};
  tlod_context* ctx = NULL;
  tlod_context_desc cd = {.thread_count = 1, .allocator = {budget_alloc, budget_free, &cnt}};
  CHECK(tlod_context_create(&cd, &ctx) == TLOD_SUCCESS);
  busy_mesh b;
  tlod_mesh_desc d = make_busy(&b);
  tlod_mesh* m = NULL;
  size_t a0 = cnt.allocs;
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  long total = (long)(cnt.allocs - a0);
  tlod_mesh_destroy(m);
  CHECK(total > 10);
  for (long n = 0; n <= total; n++) {
    size_t allocs = cnt.allocs, frees = cnt.frees;
    cnt.budget = n;
    m = (tlod_mesh*)&d;
    tlod_result r = tlod_mesh_create(ctx, &d, &m);
    cnt.budget = -1;
    if (n < total) {
      CHECK_MSG(r == TLOD_ERROR_OUT_OF_MEMORY, "budget %ld: %s", n, tlod_result_string(r));
      CHECK(m == NULL);
      CHECK(strstr(tlod_context_last_error(ctx), "out of memory") != NULL);
    } else {
      CHECK_MSG(r == TLOD_SUCCESS, "budget %ld: %s", n, tlod_result_string(r));
      tlod_mesh_destroy(m);
    }
    CHECK_MSG(cnt.allocs - allocs == cnt.frees - frees, "budget %ld leaks", n);
  }

  /* An update that runs out of memory leaves the mesh as it was. */
  CHECK(tlod_mesh_create(ctx, &d, &m) == TLOD_SUCCESS);
  float moved[40][3];
  for (uint32_t v = 0; v < 40; v++)
    for (int i = 0; i < 3; i++)
      moved[v][i] = b.pos[v][i] * 2.0f;
  float p0[3], n0[3];
  tlod_mesh_vertex(m, 45, p0, n0);
  bool succeeded = false;
  for (long n = 0; n < 64 && !succeeded; n++) {
    size_t allocs = cnt.allocs, frees = cnt.frees;
    cnt.budget = n;
    tlod_result r = tlod_mesh_update(m, &moved[0][0], 0, NULL, 0);
    cnt.budget = -1;
    CHECK(cnt.allocs - allocs == cnt.frees - frees);
    if (r == TLOD_SUCCESS) {
      succeeded = true;
      break;
    }
    CHECK(r == TLOD_ERROR_OUT_OF_MEMORY);
    float p[3], nn[3];
    tlod_mesh_vertex(m, 45, p, nn);
    CHECK(memcmp(p, p0, sizeof(p)) == 0 && memcmp(nn, n0, sizeof(nn)) == 0);
  }
  CHECK(succeeded);
  float p[3];
  tlod_mesh_vertex(m, 45, p, NULL);
  CHECK(p[0] == 2.0f * p0[0]);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
  CHECK(cnt.allocs == cnt.frees);
}

/* ------------------------------------------------------------------------ */
/* Scale                                                                    */
/* ------------------------------------------------------------------------ */

TEST(million_triangles) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  grid g;
  make_grid(&g, 1000, 500, true); /* 1,000,000 triangles */
  tlod_mesh_desc d = {
      .positions = g.pos, .vertex_count = g.vertex_count, .indices = g.idx, .index_count = g.index_count};
  tlod_mesh* m = NULL;
  tlod_result r = tlod_mesh_create(ctx, &d, &m);
  free_grid(&g);
  CHECK(r == TLOD_SUCCESS);
  tlod_mesh_info info = tlod_mesh_query_info(m);
  CHECK(info.face_count == 1000000);
  CHECK(info.boundary_edges == 2 * (1000 + 500));
  CHECK(info.edge_count == 1000 * 501 + 1001 * 500 + 500000);
  CHECK(info.welded_vertex_count == 1001 * 501);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
}

int main(void) {
  RUN(shared_cube_is_closed);
  RUN(split_cube_welds_and_creases);
  RUN(open_grid_boundary);
  RUN(findings_past_the_limit_are_counted);
  RUN(non_manifold_edges);
  RUN(mixed_faces);
  RUN(index_out_of_range);
  RUN(nan_position);
  RUN(wrong_api_use);
  RUN(degenerate_faces_dropped);
  RUN(quad_with_one_flat_half_is_kept);
  RUN(bad_normals_repaired);
  RUN(alphas_clamped);
  RUN(unused_vertex_counted);
  RUN(bbox_matches_the_corners);
  RUN(weld_epsilon_and_signed_zero);
  RUN(weld_epsilon_matches_brute_force);
  RUN(weld_exact_matches_sorting);
  RUN(angle_weighted_cube_corner);
  RUN(recompute_modes_ignore_given_normals);
  RUN(quad_normals);
  RUN(crease_angle_splits_shared_cube);
  RUN(crease_angle_keeps_smooth_regions);
  RUN(strides_match_tight_arrays);
  RUN(update_positions_recomputes_normals);
  RUN(update_normals_refreshes_smooth_flags);
  RUN(update_moves_crease_splits);
  RUN(allocator_balanced);
  RUN(allocation_failures);
  RUN(million_triangles);
  TEST_END();
}
