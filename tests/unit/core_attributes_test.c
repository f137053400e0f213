/*
 * core_attributes_test.c -- vertex attributes through tessellation (issue
 * 11): validation, storage and the mesh view, per-patch corner data, seam
 * flags, grid evaluation against an independent evaluation written here,
 * bitwise agreement along shared edges, and the CPU tessellator's attribute,
 * patch and (u, v) output. Reads private state: none (public API only).
 *
 * Tolerances: interpolated values against the independent evaluation (in
 * double) within 4 float ulps of the largest corner magnitude; everything
 * along shared edges, at corners and at welded seams is compared bitwise.
 */
#include <stdint.h>
#include <stdio.h>

#include "shapes.h"
#include "tesslod/cpu.h"
#include "tesslod/lod.h"
#include "test.h"
#include "test_camera.h"
#include "test_context.h"

#define MAX_LEVEL 6

/* ------------------------------------------------------------------------ */
/* Fixtures                                                                 */
/* ------------------------------------------------------------------------ */

/* Smooth functions of the position: every copy of a position gets the same
 * values, so only the shape's own seams (none, or the seam sphere's) split. */
static void smooth_values(const float p[3], float uv[2], float color[4], float* scalar) {
  uv[0] = 0.5f + 0.5f * p[0];
  uv[1] = 0.25f * p[1] - 0.125f * p[2];
  color[0] = p[0] * p[1];
  color[1] = 1.0f - p[2];
  color[2] = 0.3f + p[0] - p[1];
  color[3] = 0.75f;
  *scalar = 3.0f * p[2] + p[0];
}

/* Three attributes of 2, 4 and 1 components; the scalar in a strided array
 * (8 bytes a vertex) to exercise strides. */
typedef struct attr_data {
  float* uv;
  float* color;
  float* scalar; /* stride 8 */
  tlod_attribute_desc desc[3];
} attr_data;

static void attr_data_free(attr_data* a) {
  free(a->uv);
  free(a->color);
  free(a->scalar);
  memset(a, 0, sizeof(*a));
}

static attr_data attr_data_smooth(const shape* s) {
  attr_data a = {0};
  a.uv = calloc(2 * (size_t)s->vertex_count + 1, sizeof(float));
  a.color = calloc(4 * (size_t)s->vertex_count + 1, sizeof(float));
  a.scalar = calloc(2 * (size_t)s->vertex_count + 1, sizeof(float));
  for (uint32_t v = 0; v < s->vertex_count; v++)
    smooth_values(s->positions + 3 * v, a.uv + 2 * v, a.color + 4 * v, a.scalar + 2 * v);
  a.desc[0] = (tlod_attribute_desc){.data = a.uv, .components = 2, .name = "TEXCOORD_0"};
  a.desc[1] = (tlod_attribute_desc){.data = a.color, .components = 4, .name = "COLOR_0"};
  a.desc[2] = (tlod_attribute_desc){.data = a.scalar, .components = 1, .stride = 8, .name = "stress"};
  return a;
}

/* The seam sphere's own UVs: u = column / nlon (the seam column copies
 * column 0's position with u = 1), v = ring / nlat; poles: one copy per
 * column, each its own u. */
static float* seam_sphere_uv(uint32_t nlat, uint32_t nlon) {
  uint32_t cols = nlon + 1;
  float* uv = calloc(2 * (size_t)(nlat + 1) * cols, sizeof(float));
  for (uint32_t i = 0; i <= nlat; i++)
    for (uint32_t j = 0; j <= nlon; j++) {
      uv[2 * (i * cols + j)] = (float)j / (float)nlon;
      uv[2 * (i * cols + j) + 1] = (float)i / (float)nlat;
    }
  return uv;
}

static tlod_mesh* make_mesh(tlod_context* ctx, const shape* s, const tlod_attribute_desc* attrs, uint32_t count) {
  tlod_mesh_desc d = shape_mesh_desc(s);
  d.attributes = attrs;
  d.attribute_count = count;
  tlod_mesh* m = NULL;
  tlod_result r = tlod_mesh_create(ctx, &d, &m);
  if (r != TLOD_SUCCESS)
    fprintf(stderr, "tlod_mesh_create: %s: %s\n", tlod_result_string(r), tlod_context_last_error(ctx));
  return m;
}

/* ------------------------------------------------------------------------ */
/* (d) Validation                                                           */
/* ------------------------------------------------------------------------ */

/* Creation refused with `result`, the message containing `needle`, and
 * every allocation given back. */
static void check_refused(const shape* s, const tlod_attribute_desc* attrs, uint32_t count, tlod_result result,
                          const char* needle) {
  counting_allocator counter = {.fail_at = -1};
  tlod_context* ctx = new_context(1, &counter, NULL);
  CHECK(ctx);
  long allocs_before = counter.allocs - counter.frees;
  tlod_mesh_desc d = shape_mesh_desc(s);
  d.attributes = attrs;
  d.attribute_count = count;
  tlod_mesh* m = (tlod_mesh*)(uintptr_t)1;
  tlod_result r = tlod_mesh_create(ctx, &d, &m);
  const char* msg = tlod_context_last_error(ctx);
  bool found = strstr(msg, needle) != NULL;
  long leaked = counter.allocs - counter.frees - allocs_before;
  tlod_context_destroy(ctx);
  CHECK_MSG(r == result && m == NULL, "%s instead of %s", tlod_result_string(r), tlod_result_string(result));
  CHECK_MSG(found, "message '%s' does not name '%s'", msg, needle);
  CHECK_MSG(leaked == 0, "%ld allocations kept by a refused mesh", leaked);
}

TEST(validation_names_the_attribute) {
  shape s = shape_icosphere(0);
  attr_data a = attr_data_smooth(&s);
  tlod_attribute_desc bad[TLOD_MAX_ATTRIBUTES + 1];
  for (uint32_t k = 0; k <= TLOD_MAX_ATTRIBUTES; k++)
    bad[k] = a.desc[k % 3];
  CALL(check_refused(&s, bad, TLOD_MAX_ATTRIBUTES + 1, TLOD_ERROR_INVALID_ARGUMENT, "attribute_count 9 (at most 8)"));
  CALL(check_refused(&s, NULL, 1, TLOD_ERROR_INVALID_ARGUMENT, "attributes is NULL"));
  memcpy(bad, a.desc, sizeof(a.desc));
  bad[1].components = 5;
  CALL(check_refused(&s, bad, 3, TLOD_ERROR_INVALID_ARGUMENT, "attribute 1 'COLOR_0': components 5 (1..4)"));
  bad[1].components = 0;
  CALL(check_refused(&s, bad, 3, TLOD_ERROR_INVALID_ARGUMENT, "attribute 1 'COLOR_0': components 0 (1..4)"));
  memcpy(bad, a.desc, sizeof(a.desc));
  bad[2].data = NULL;
  CALL(check_refused(&s, bad, 3, TLOD_ERROR_INVALID_ARGUMENT, "attribute 2 'stress': data is NULL"));
  memcpy(bad, a.desc, sizeof(a.desc));
  bad[0].stride = 7;
  CALL(check_refused(&s, bad, 3, TLOD_ERROR_INVALID_ARGUMENT, "attribute 0 'TEXCOORD_0': stride 7 bytes"));
  memcpy(bad, a.desc, sizeof(a.desc));
  bad[1].name = NULL;
  bad[1].components = 9;
  CALL(check_refused(&s, bad, 3, TLOD_ERROR_INVALID_ARGUMENT, "attribute 1: components 9"));
  memcpy(bad, a.desc, sizeof(a.desc));
  a.color[4 * 7 + 2] = NAN;
  CALL(check_refused(&s, bad, 3, TLOD_ERROR_INVALID_MESH, "vertex 7: attribute 1 'COLOR_0'.z is nan"));
  a.color[4 * 7 + 2] = 0.0f;
  a.uv[2 * 11 + 1] = INFINITY;
  CALL(check_refused(&s, bad, 3, TLOD_ERROR_INVALID_MESH, "vertex 11: attribute 0 'TEXCOORD_0'.y is inf"));
  attr_data_free(&a);
  shape_free(&s);
}

/* Every allocation failure of a mesh with attributes is refused cleanly. */
TEST(out_of_memory_frees_everything) {
  shape s = shape_icosphere(1);
  attr_data a = attr_data_smooth(&s);
  for (long fail = 0; fail < 64; fail++) {
    counting_allocator counter = {.fail_at = -1};
    tlod_context* ctx = new_context(1, &counter, NULL);
    CHECK(ctx);
    long live_before = counter.allocs - counter.frees;
    counter.fail_at = counter.calls + fail;
    tlod_mesh_desc d = shape_mesh_desc(&s);
    d.attributes = a.desc;
    d.attribute_count = 3;
    tlod_mesh* m = NULL;
    tlod_result r = tlod_mesh_create(ctx, &d, &m);
    tlod_mesh_destroy(m);
    long live = counter.allocs - counter.frees - live_before;
    tlod_context_destroy(ctx);
    CHECK_MSG(r == TLOD_SUCCESS || r == TLOD_ERROR_OUT_OF_MEMORY, "failure %ld: %s", fail, tlod_result_string(r));
    CHECK_MSG(live == 0, "failure %ld: %ld allocations kept", fail, live);
    if (r == TLOD_SUCCESS) break;
  }
  attr_data_free(&a);
  shape_free(&s);
}

/* ------------------------------------------------------------------------ */
/* Storage, view, patch corners, seam flags                                 */
/* ------------------------------------------------------------------------ */

TEST(view_and_patch_attributes_copy_the_input) {
  shape s = shape_icosphere(1);
  attr_data a = attr_data_smooth(&s);
  tlod_context* ctx = new_context(1, NULL, NULL);
  tlod_mesh* m = make_mesh(ctx, &s, a.desc, 3);
  CHECK(m);
  CHECK(tlod_mesh_attribute_count(m) == 3);
  tlod_attribute_info info = tlod_mesh_query_attribute(m, 1);
  CHECK(strcmp(info.name, "COLOR_0") == 0 && info.components == 4);
  info = tlod_mesh_query_attribute(m, 3);
  CHECK(info.name[0] == 0 && info.components == 0);
  tlod_mesh_view view = tlod_mesh_query_view(m);
  CHECK(view.attribute_count == 3 && view.attributes);
  for (uint32_t v = 0; v < view.vertex_count; v++) {
    const float* uv = view.attributes[v * 3 + 0];
    const float* col = view.attributes[v * 3 + 1];
    const float* sc = view.attributes[v * 3 + 2];
    CHECK(uv[0] == a.uv[2 * v] && uv[1] == a.uv[2 * v + 1] && uv[2] == 0.0f && uv[3] == 1.0f);
    CHECK(!memcmp(col, a.color + 4 * v, 16));
    CHECK(sc[0] == a.scalar[2 * v] && sc[1] == 0.0f && sc[2] == 0.0f && sc[3] == 1.0f);
  }
  uint32_t faces = view.face_count;
  float(*corners)[4] = calloc((size_t)faces * 4 * 3, sizeof(*corners));
  CHECK(tlod_mesh_patch_attributes(m, 0, faces, corners) == TLOD_SUCCESS);
  for (uint32_t f = 0; f < faces; f++)
    for (uint32_t c = 0; c < 4; c++)
      for (uint32_t k = 0; k < 3; k++) {
        const float* got = corners[(f * 4 + c) * 3 + k];
        static const float zero[4] = {0};
        const float* want = c < 3 ? view.attributes[view.faces[f][c] * 3 + k] : zero;
        CHECK_MSG(!memcmp(got, want, 16), "patch %u corner %u attribute %u", f, c, k);
      }
  CHECK(tlod_mesh_patch_attributes(m, faces, 1, corners) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(strstr(tlod_context_last_error(ctx), "patch attributes") != NULL);
  CHECK(tlod_mesh_patch_attributes(m, 0, 1, NULL) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_mesh_patch_attributes(NULL, 0, 0, corners) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_mesh_query_info(m).attribute_seam_edges == 0);
  CHECK(tlod_mesh_attribute_count(NULL) == 0 && tlod_mesh_query_attribute(NULL, 0).components == 0);
  /* An update moves the geometry and leaves the attributes as they are. */
  float(*before)[4] = malloc(sizeof(*before) * 3 * view.vertex_count);
  memcpy(before, view.attributes, sizeof(*before) * 3 * view.vertex_count);
  float* moved = malloc(sizeof(float) * 3 * s.vertex_count);
  for (uint32_t k = 0; k < 3 * s.vertex_count; k++)
    moved[k] = 2.0f * s.positions[k];
  CHECK(tlod_mesh_update(m, moved, 0, NULL, 0) == TLOD_SUCCESS);
  view = tlod_mesh_query_view(m);
  CHECK(!memcmp(before, view.attributes, sizeof(*before) * 3 * view.vertex_count));
  free(moved);
  free(before);
  free(corners);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
  attr_data_free(&a);
  shape_free(&s);
}

/* The seam sphere's seam column and pole fans are seams (smooth, split UVs);
 * no other edge is. Counted independently from the shape's layout. */
TEST(seam_flags_follow_split_attributes) {
  const uint32_t nlat = 6, nlon = 8;
  shape s = shape_seam_sphere(nlat, nlon);
  float* uv = seam_sphere_uv(nlat, nlon);
  tlod_attribute_desc ad = {.data = uv, .components = 2, .name = "TEXCOORD_0"};
  tlod_context* ctx = new_context(1, NULL, NULL);
  tlod_mesh* m = make_mesh(ctx, &s, &ad, 1);
  CHECK(m);
  tlod_mesh_info info = tlod_mesh_query_info(m);
  /* Seam column: nlat edges, the two at the poles counted with the poles;
   * each pole: nlon edges between its fan triangles. */
  uint32_t expected = nlat - 2 + 2 * nlon;
  CHECK_MSG(info.attribute_seam_edges == expected, "%u seam edges, expected %u", info.attribute_seam_edges, expected);
  CHECK(info.crease_edges == 0 && info.closed);
  tlod_mesh_view view = tlod_mesh_query_view(m);
  uint32_t flagged = 0;
  for (uint32_t f = 0; f < view.face_count; f++)
    for (uint32_t e = 0; e < view.face_corners[f]; e++) {
      tlod_edge_link l = view.links[f][e];
      CHECK(l.smooth);
      flagged += l.seam;
      CHECK(l.seam == view.links[l.face][l.edge].seam);
    }
  CHECK(flagged == 2 * expected);
  /* Without attributes the same mesh has no seam. */
  tlod_mesh* plain = make_mesh(ctx, &s, NULL, 0);
  CHECK(plain && tlod_mesh_query_info(plain).attribute_seam_edges == 0);
  CHECK(tlod_mesh_query_view(plain).attributes == NULL);
  tlod_mesh_destroy(plain);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
  free(uv);
  shape_free(&s);
}

/* ------------------------------------------------------------------------ */
/* (a) Bitwise agreement along shared edges, (b) values at pattern vertices */
/* ------------------------------------------------------------------------ */

/* Grid point of edge e at end-corner weight q (over nn), as
 * tlod_grid_point_kind() classifies it (core.h). */
static void edge_ij(uint32_t corners, uint32_t e, uint32_t nn, uint32_t q, uint16_t ij[2]) {
  static const int tri[3][4] = {{1, -1, 0, 1}, {0, 0, 1, -1}, {0, 1, 0, 0}}; /* i = a + b q, j = c + d q (over nn) */
  static const int quad[4][4] = {{0, 1, 0, 0}, {1, 0, 0, 1}, {1, -1, 1, 0}, {0, 0, 1, -1}};
  const int* r = corners == 3 ? tri[e] : quad[e];
  ij[0] = (uint16_t)((int)nn * r[0] + r[1] * (int)q);
  ij[1] = (uint16_t)((int)nn * r[2] + r[3] * (int)q);
}

/* Edge points of patch f's edge e at grid level g: out[q] for end weight q. */
static bool eval_edge(const tlod_mesh* m, uint32_t f, uint32_t e, uint32_t g, float (*out)[4]) {
  uint32_t nn = 1u << g, corners = tlod_mesh_face_corners(m, f, NULL);
  uint16_t ij[(1u << 5) + 1][2];
  for (uint32_t q = 0; q <= nn; q++)
    edge_ij(corners, e, nn, q, ij[q]);
  return tlod_mesh_eval_attributes_grid(m, f, g, &ij[0][0], sizeof(ij[0]), nn + 1, out) == TLOD_SUCCESS;
}

/* Over every linked edge at levels 0..5: non-seam edges give bitwise equal
 * values at each edge point on both sides (point q on f is point nn - q on
 * the neighbour); counts the seam edges whose sides differ. */
static void check_shared_edges(const tlod_mesh* m, uint32_t* compared, uint32_t* differing_seams) {
  tlod_mesh_view view = tlod_mesh_query_view(m);
  uint32_t na = view.attribute_count;
  float(*a)[4] = calloc(((1u << 5) + 1) * (size_t)na, sizeof(*a));
  float(*b)[4] = calloc(((1u << 5) + 1) * (size_t)na, sizeof(*b));
  for (uint32_t g = 0; g <= 5; g++)
    for (uint32_t f = 0; f < view.face_count; f++)
      for (uint32_t e = 0; e < view.face_corners[f]; e++) {
        tlod_edge_link l = view.links[f][e];
        if (l.face == UINT32_MAX || l.face < f) continue;
        uint32_t nn = 1u << g;
        CHECK_MSG(eval_edge(m, f, e, g, a) && eval_edge(m, l.face, l.edge, g, b), "patch %u edge %u", f, e);
        bool equal = true;
        for (uint32_t q = 0; q <= nn; q++)
          equal = equal && !memcmp(a[q * na], b[(nn - q) * na], sizeof(*a) * na);
        if (l.seam) {
          *differing_seams += !equal && g == 0;
          continue;
        }
        CHECK_MSG(equal, "level %u: patch %u edge %u and patch %u edge %u differ", g, f, e, l.face, l.edge);
        (*compared)++;
      }
  free(a);
  free(b);
}

static void shared_edges_case(const shape* s, bool seam_uv, uint32_t nlat, uint32_t nlon) {
  attr_data a = attr_data_smooth(s);
  float* uv = seam_uv ? seam_sphere_uv(nlat, nlon) : NULL;
  if (uv) a.desc[0].data = uv;
  tlod_context* ctx = new_context(1, NULL, NULL);
  tlod_mesh* m = make_mesh(ctx, s, a.desc, 3);
  CHECK(m);
  uint32_t compared = 0, differing = 0, seams = tlod_mesh_query_info(m).attribute_seam_edges;
  check_shared_edges(m, &compared, &differing);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
  free(uv);
  attr_data_free(&a);
  CHECK_MSG(compared > 0, "%s: no shared edge compared", s->name);
  CHECK_MSG(differing == seams, "%s: %u of %u seams differ", s->name, differing, seams);
}

TEST(shared_edges_are_bitwise_equal) {
  shape shapes[4] = {shape_icosphere(2), shape_quad_sphere(3), shape_cube_split(), shape_torus(7, 5)};
  for (int k = 0; k < 4; k++) {
    CALL(shared_edges_case(&shapes[k], false, 0, 0));
    shape_free(&shapes[k]);
  }
  shape seam = shape_seam_sphere(6, 8);
  CALL(shared_edges_case(&seam, true, 6, 8));
  shape_free(&seam);
}

/* The interpolation written out in double: barycentric u, v, w on corners
 * 0, 1, 2 of a triangle, bilinear on a quad (core.h PARAMETERS). */
static double expected_value(const tlod_mesh_view* v, uint32_t f, uint32_t attr, int c, double u, double w) {
  const uint32_t* face = v->faces[f];
  uint32_t na = v->attribute_count;
  double x[4];
  for (uint32_t i = 0; i < v->face_corners[f]; i++)
    x[i] = v->attributes[face[i] * na + attr][c];
  if (v->face_corners[f] == 3) return u * x[0] + w * x[1] + (1.0 - u - w) * x[2];
  return (1 - u) * (1 - w) * x[0] + u * (1 - w) * x[1] + u * w * x[2] + (1 - u) * w * x[3];
}

static void check_pattern_values(const tlod_mesh* m, const tlod_patterns* pat) {
  tlod_mesh_view view = tlod_mesh_query_view(m);
  uint32_t na = view.attribute_count, lmax = tlod_patterns_max_level(pat);
  for (uint32_t f = 0; f < view.face_count; f++) {
    tlod_pattern_shape sh = view.face_corners[f] == 4 ? TLOD_PATTERN_QUAD : TLOD_PATTERN_TRIANGLE;
    uint32_t count;
    const tlod_pattern_vertex* pv = tlod_patterns_vertices(pat, sh, &count);
    float(*out)[4] = calloc((size_t)count * na, sizeof(*out));
    CHECK(tlod_mesh_eval_attributes_grid(m, f, lmax, &pv[0].i, sizeof(*pv), count, out) == TLOD_SUCCESS);
    for (uint32_t x = 0; x < count; x++)
      for (uint32_t k = 0; k < na; k++) {
        uint32_t param, kind = tlod_grid_point_kind(view.face_corners[f], lmax, pv[x].i, pv[x].j, &param);
        if (kind < TLOD_GRID_EDGE) {
          CHECK_MSG(!memcmp(out[x * na + k], view.attributes[view.faces[f][kind] * na + k], 16), "corner not exact");
          continue;
        }
        double scale = 0;
        for (uint32_t i = 0; i < view.face_corners[f]; i++)
          for (int c = 0; c < 4; c++)
            scale = fmax(scale, fabs(view.attributes[view.faces[f][i] * na + k][c]));
        for (int c = 0; c < 4; c++) {
          double want = expected_value(&view, f, k, c, (double)pv[x].i / (1 << lmax), (double)pv[x].j / (1 << lmax));
          CHECK_MSG(fabs(out[x * na + k][c] - want) <= 4 * scale * 0x1p-24,
                    "patch %u vertex %u attribute %u.%d: %.9g, expected %.9g", f, x, k, c, (double)out[x * na + k][c],
                    want);
        }
      }
    free(out);
  }
}

TEST(pattern_values_match_the_corner_weights) {
  tlod_context* ctx = new_context(1, NULL, NULL);
  tlod_patterns* pat = NULL;
  CHECK(tlod_patterns_create(ctx, &(tlod_patterns_desc){.max_level = 4}, &pat) == TLOD_SUCCESS);
  shape shapes[2] = {shape_icosphere(1), shape_quad_sphere(2)};
  for (int k = 0; k < 2; k++) {
    attr_data a = attr_data_smooth(&shapes[k]);
    tlod_mesh* m = make_mesh(ctx, &shapes[k], a.desc, 3);
    CHECK(m);
    CALL(check_pattern_values(m, pat));
    tlod_mesh_destroy(m);
    attr_data_free(&a);
    shape_free(&shapes[k]);
  }
  tlod_patterns_destroy(pat);
  tlod_context_destroy(ctx);
}

TEST(eval_grid_checks_its_arguments) {
  shape s = shape_icosphere(0);
  attr_data a = attr_data_smooth(&s);
  tlod_context* ctx = new_context(1, NULL, NULL);
  tlod_mesh* m = make_mesh(ctx, &s, a.desc, 3);
  tlod_mesh* plain = make_mesh(ctx, &s, NULL, 0);
  CHECK(m && plain);
  uint16_t ij[2][2] = {{1, 1}, {3, 2}}; /* the second is off a level-2 triangle grid */
  float out[2 * 3][4], sentinel[2 * 3][4];
  memset(out, 0x5a, sizeof(out));
  memcpy(sentinel, out, sizeof(out));
  CHECK(tlod_mesh_eval_attributes_grid(m, 0, 2, &ij[0][0], 4, 2, out) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_mesh_eval_attributes_grid(m, 20, 2, &ij[0][0], 4, 1, out) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_mesh_eval_attributes_grid(m, 0, 16, &ij[0][0], 4, 1, out) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_mesh_eval_attributes_grid(m, 0, 2, NULL, 4, 1, out) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_mesh_eval_attributes_grid(m, 0, 2, &ij[0][0], 4, 1, NULL) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_mesh_eval_attributes_grid(NULL, 0, 2, &ij[0][0], 4, 1, out) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(!memcmp(out, sentinel, sizeof(out)));
  CHECK(tlod_mesh_eval_attributes_grid(plain, 0, 2, &ij[0][0], 4, 1, NULL) == TLOD_SUCCESS);
  CHECK(tlod_mesh_eval_attributes_grid(plain, 0, 2, &ij[0][0], 4, 2, NULL) == TLOD_ERROR_INVALID_ARGUMENT);
  CHECK(tlod_mesh_eval_attributes_grid(m, 0, 2, &ij[0][0], 4, 1, out) == TLOD_SUCCESS);
  tlod_mesh_destroy(plain);
  tlod_mesh_destroy(m);
  tlod_context_destroy(ctx);
  attr_data_free(&a);
  shape_free(&s);
}

/* ------------------------------------------------------------------------ */
/* CPU tessellator: (c) UV seams, (e) vertex_patch / vertex_uv              */
/* ------------------------------------------------------------------------ */

typedef struct cpu_fixture {
  tlod_context* ctx;
  tlod_mesh* mesh;
  tlod_surface* surf;
  tlod_patterns* pat;
} cpu_fixture;

static void cpu_fixture_free(cpu_fixture* fx) {
  tlod_surface_destroy(fx->surf);
  tlod_mesh_destroy(fx->mesh);
  tlod_patterns_destroy(fx->pat);
  tlod_context_destroy(fx->ctx);
  memset(fx, 0, sizeof(*fx));
}

static bool cpu_fixture_make(cpu_fixture* fx, const shape* s, const tlod_attribute_desc* attrs, uint32_t count,
                             tlod_surface_type type) {
  memset(fx, 0, sizeof(*fx));
  fx->ctx = new_context(2, NULL, NULL);
  fx->mesh = make_mesh(fx->ctx, s, attrs, count);
  tlod_result r = fx->mesh ? TLOD_SUCCESS : TLOD_ERROR_INVALID_MESH;
  if (r == TLOD_SUCCESS) r = tlod_surface_create(fx->ctx, fx->mesh, &(tlod_surface_desc){.type = type}, &fx->surf);
  if (r == TLOD_SUCCESS) r = tlod_patterns_create(fx->ctx, &(tlod_patterns_desc){.max_level = MAX_LEVEL}, &fx->pat);
  if (r != TLOD_SUCCESS) {
    fprintf(stderr, "fixture %s: %s: %s\n", s->name, tlod_result_string(r), tlod_context_last_error(fx->ctx));
    cpu_fixture_free(fx);
    return false;
  }
  return true;
}

static tlod_cpu_mesh* cpu_run(const cpu_fixture* fx, uint32_t level, const int8_t* levels, bool no_weld) {
  tlod_cpu_tessellate_desc d = {.level = level, .levels = levels, .no_weld = no_weld};
  tlod_cpu_mesh* out = NULL;
  tlod_result r = tlod_cpu_tessellate(fx->ctx, fx->surf, fx->pat, &d, &out);
  if (r != TLOD_SUCCESS)
    fprintf(stderr, "tlod_cpu_tessellate: %s: %s\n", tlod_result_string(r), tlod_context_last_error(fx->ctx));
  return out;
}

static int8_t* random_levels(uint32_t patches, uint64_t seed) {
  shape_rng rng = {seed};
  int8_t* l = malloc(patches + 1);
  for (uint32_t p = 0; p < patches; p++)
    l[p] = (int8_t)(shape_rng_next(&rng) % (MAX_LEVEL + 1));
  return l;
}

/* No triangle spans the seam: its corners' u all on one side (the seam's
 * sides are u 0 and u 1). */
static void check_no_span(const tlod_cpu_mesh* o, const char* what) {
  CHECK(o->attribute_count == 1 && o->attributes && o->vertex_patch && o->vertex_uv);
  for (uint32_t k = 0; k < o->triangle_count; k++) {
    float lo = 2, hi = -2;
    for (int c = 0; c < 3; c++) {
      float u = o->attributes[o->indices[3 * k + c]][0];
      lo = fminf(lo, u), hi = fmaxf(hi, u);
    }
    CHECK_MSG(hi - lo < 0.5f, "%s: triangle %u (patch %d) spans the seam: u %g..%g", what, k, (int)o->triangle_patch[k],
              (double)lo, (double)hi);
  }
}

/* Closed after welding by exact position; no triangle spans the seam (its
 * corners' u all on one side: the seam's sides are u 0 and u 1); every
 * output position on the seam meridian (y == 0, x > 0) carries both u 0 and
 * a u near 1 (each side kept its own vertex; towards a pole the u 1 side
 * blends with the pole copy of the last column). With different levels a
 * finer side's extra points belong to it alone (the strip carries its
 * attributes), so the last check is made at one level. */
static void check_seam_output(const tlod_cpu_mesh* o, const char* what, bool one_level) {
  char why[160];
  CHECK_MSG(shape_closed_manifold(o->positions, o->vertex_count, o->indices, o->triangle_count, o->triangle_patch, why,
                                  sizeof(why)),
            "%s: %s", what, why);
  CALL(check_no_span(o, what));
  uint32_t on_seam = 0;
  for (uint32_t v = 0; one_level && v < o->vertex_count; v++) {
    const float* p = o->positions + 3 * v;
    if (p[1] != 0.0f || !(p[0] > 0.0f)) continue;
    bool zero = false, one = false;
    for (uint32_t w = 0; w < o->vertex_count; w++) {
      if (memcmp(o->positions + 3 * w, p, 12) != 0) continue;
      zero = zero || o->attributes[w][0] == 0.0f;
      one = one || o->attributes[w][0] > 0.75f; /* 1, or towards a pole copy of the last column */
    }
    CHECK_MSG(zero && one, "%s: seam vertex %u (%g, %g, %g) lacks u %s", what, v, (double)p[0], (double)p[1],
              (double)p[2], zero ? "near 1" : "0");
    on_seam++;
  }
  CHECK_MSG(on_seam > 0 || !one_level, "%s: no output vertex on the seam", what);
}

TEST(uv_seam_stays_closed_with_both_uvs) {
  const uint32_t nlat = 4, nlon = 6;
  shape s = shape_seam_sphere(nlat, nlon);
  float* uv = seam_sphere_uv(nlat, nlon);
  tlod_attribute_desc ad = {.data = uv, .components = 2, .name = "TEXCOORD_0"};
  tlod_surface_type types[2] = {TLOD_SURFACE_PHONG, TLOD_SURFACE_PN};
  for (int ty = 0; ty < 2; ty++) {
    cpu_fixture fx;
    CHECK(cpu_fixture_make(&fx, &s, &ad, 1, types[ty]));
    char what[64];
    for (uint32_t level = 0; level <= MAX_LEVEL; level++) {
      tlod_cpu_mesh* o = cpu_run(&fx, level, NULL, false);
      CHECK(o);
      snprintf(what, sizeof(what), "type %d level %u", ty, level);
      CALL(check_seam_output(o, what, true));
      CHECK_MSG(o->strips == 0, "%s: %u strips on a mesh without creases at one level", what, o->strips);
      tlod_cpu_mesh_destroy(fx.ctx, o);
    }
    for (uint64_t seed = 1; seed <= 4; seed++) {
      int8_t* levels = random_levels(tlod_mesh_face_count(fx.mesh), seed);
      tlod_cpu_mesh* o = cpu_run(&fx, 0, levels, false);
      free(levels);
      CHECK(o);
      snprintf(what, sizeof(what), "type %d random levels %llu", ty, (unsigned long long)seed);
      CALL(check_seam_output(o, what, false));
      tlod_cpu_mesh_destroy(fx.ctx, o);
    }
    cpu_fixture_free(&fx);
  }
  free(uv);
  shape_free(&s);
}

/* A scheduler's draw lists (levels per patch, geomorph blends, its strips)
 * on the seam sphere, the camera moving in: closed while nothing is culled,
 * and no triangle spans the seam. */
TEST(uv_seam_through_draw_lists) {
  const uint32_t nlat = 6, nlon = 10;
  shape s = shape_seam_sphere(nlat, nlon);
  float* uv = seam_sphere_uv(nlat, nlon);
  tlod_attribute_desc ad = {.data = uv, .components = 2, .name = "TEXCOORD_0"};
  cpu_fixture fx;
  CHECK(cpu_fixture_make(&fx, &s, &ad, 1, TLOD_SURFACE_PHONG));
  tlod_scheduler* sched = NULL;
  CHECK(tlod_scheduler_create(fx.ctx, fx.surf, fx.pat, &(tlod_scheduler_desc){.epsilon_px = 0.3f}, &sched) ==
        TLOD_SUCCESS);
  tlod_cpu_mesh* o = tlod_context_calloc(fx.ctx, 1, sizeof(*o));
  uint32_t strips = 0, culled = 0;
  for (int frame = 0; frame < 12; frame++) {
    double d = 6.0 - 0.4 * frame;
    camera cam = {.eye = {d, -0.4 * d, 0.3 * d},
                  .up = {0, 0, 1},
                  .fovy = 0.9,
                  .aspect = 1.0,
                  .znear = 0.01,
                  .zfar = 100,
                  .width = 400,
                  .height = 400};
    tlod_view_desc view = make_view(&cam);
    CHECK(tlod_scheduler_update(sched, &(tlod_frame_desc){.views = &view, .view_count = 1, .dt_ms = 40}) ==
          TLOD_SUCCESS);
    const tlod_draw_list* dl = tlod_scheduler_draw_list(sched, 0);
    tlod_cpu_tessellate_desc td = {.draw_list = dl};
    CHECK(tlod_cpu_tessellate_into(fx.ctx, fx.surf, fx.pat, &td, o) == TLOD_SUCCESS);
    char what[64];
    snprintf(what, sizeof(what), "frame %d", frame);
    if (dl->culled == 0) {
      CALL(check_seam_output(o, what, false));
    } else {
      CALL(check_no_span(o, what));
    }
    culled += dl->culled > 0;
    strips += o->strip_triangles;
  }
  CHECK_MSG(strips > 0, "no strip drawn: the draw lists did not exercise strips");
  CHECK_MSG(culled < 12, "every frame culled something: closedness never checked");
  tlod_cpu_mesh_destroy(fx.ctx, o);
  tlod_scheduler_destroy(sched);
  cpu_fixture_free(&fx);
  free(uv);
  shape_free(&s);
}

/* Every output vertex: tlod_surface_eval() at (vertex_patch, vertex_uv)
 * gives its position bitwise, and the attributes evaluated there are its
 * attributes bitwise (a mesh without seams has no strip vertices). */
static void check_vertex_origin(const cpu_fixture* fx, const tlod_cpu_mesh* o, const char* what) {
  uint32_t na = o->attribute_count;
  CHECK(na == 3);
  for (uint32_t v = 0; v < o->vertex_count; v++) {
    uint32_t f = o->vertex_patch[v];
    CHECK_MSG(f < tlod_mesh_face_count(fx->mesh), "%s: vertex %u: patch %u", what, v, f);
    float u = o->vertex_uv[v][0], w = o->vertex_uv[v][1];
    tlod_surface_point pt;
    CHECK(tlod_surface_eval(fx->surf, f, u, w, &pt) == TLOD_SUCCESS);
    CHECK_MSG(!memcmp(pt.position, o->positions + 3 * v, 12),
              "%s: vertex %u (patch %u, %g, %g): (%.9g %.9g %.9g) vs (%.9g %.9g %.9g)", what, v, f, (double)u,
              (double)w, (double)pt.position[0], (double)pt.position[1], (double)pt.position[2],
              (double)o->positions[3 * v], (double)o->positions[3 * v + 1], (double)o->positions[3 * v + 2]);
    uint16_t ij[2] = {(uint16_t)(u * (1 << MAX_LEVEL)), (uint16_t)(w * (1 << MAX_LEVEL))};
    float want[3][4];
    CHECK(tlod_mesh_eval_attributes_grid(fx->mesh, f, MAX_LEVEL, ij, 4, 1, want) == TLOD_SUCCESS);
    CHECK_MSG(!memcmp(want, o->attributes[v * na], sizeof(want)), "%s: vertex %u attributes", what, v);
  }
}

TEST(vertex_patch_and_uv_reproduce_the_vertex) {
  shape shapes[3] = {shape_icosphere(1), shape_quad_sphere(2), shape_cube_split()};
  for (int k = 0; k < 3; k++) {
    attr_data a = attr_data_smooth(&shapes[k]);
    cpu_fixture fx;
    CHECK(cpu_fixture_make(&fx, &shapes[k], a.desc, 3, TLOD_SURFACE_PHONG));
    int8_t* levels = random_levels(tlod_mesh_face_count(fx.mesh), 7 + (uint64_t)k);
    for (int mode = 0; mode < 3; mode++) {
      tlod_cpu_mesh* o = cpu_run(&fx, 3, mode == 2 ? levels : NULL, mode == 1);
      CHECK(o);
      char what[64];
      snprintf(what, sizeof(what), "%s mode %d", shapes[k].name, mode);
      CALL(check_vertex_origin(&fx, o, what));
      tlod_cpu_mesh_destroy(fx.ctx, o);
    }
    free(levels);
    cpu_fixture_free(&fx);
    attr_data_free(&a);
    shape_free(&shapes[k]);
  }
}

/* A mesh without attributes: no attribute array; a reused mesh follows the
 * attribute count of each call. */
TEST(attribute_arrays_follow_the_mesh) {
  shape s = shape_icosphere(1);
  attr_data a = attr_data_smooth(&s);
  cpu_fixture with, without;
  CHECK(cpu_fixture_make(&with, &s, a.desc, 3, TLOD_SURFACE_PHONG));
  CHECK(cpu_fixture_make(&without, &s, NULL, 0, TLOD_SURFACE_PHONG));
  tlod_cpu_mesh* o = cpu_run(&without, 2, NULL, false);
  CHECK(o && o->attribute_count == 0 && o->attributes == NULL && o->vertex_patch && o->vertex_uv);
  tlod_cpu_mesh_destroy(without.ctx, o);
  o = cpu_run(&with, 1, NULL, false);
  CHECK(o && o->attribute_count == 3 && o->attributes);
  tlod_cpu_tessellate_desc d = {.level = 3};
  CHECK(tlod_cpu_tessellate_into(with.ctx, with.surf, with.pat, &d, o) == TLOD_SUCCESS);
  CALL(check_vertex_origin(&with, o, "reused"));
  tlod_cpu_mesh_destroy(with.ctx, o);
  cpu_fixture_free(&with);
  cpu_fixture_free(&without);
  attr_data_free(&a);
  shape_free(&s);
}

int main(void) {
  RUN(uv_seam_stays_closed_with_both_uvs);
  RUN(uv_seam_through_draw_lists);
  RUN(vertex_patch_and_uv_reproduce_the_vertex);
  RUN(attribute_arrays_follow_the_mesh);

  RUN(shared_edges_are_bitwise_equal);
  RUN(pattern_values_match_the_corner_weights);
  RUN(eval_grid_checks_its_arguments);

  RUN(validation_names_the_attribute);
  RUN(out_of_memory_frees_everything);
  RUN(view_and_patch_attributes_copy_the_input);
  RUN(seam_flags_follow_split_attributes);
  TEST_END();
}
