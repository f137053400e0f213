/*
 * vtk_quadratic_test.c -- second-order cells end to end (issue 14): two 20-node (VTK type 25) and
 * two 27-node (type 29) hexahedra on a warped block, two 10-node tetrahedra (type 24) and two
 * 15-node wedges (type 26: 6-node triangle and 8-node quad faces), are
 * written as VTK files, imported, made a TLOD_SURFACE_QUADRATIC surface and tessellated; every
 * point at every level 0..6, from tlod_surface_eval_grid() and from the cpu tessellator's output
 * (vertex_patch, vertex_uv), must be the cell's isoparametric map evaluated here from the shape
 * functions (27: triquadratic Lagrange; 20: serendipity; 10: quadratic in the barycentrics; 15:
 * the quadratic wedge's, triangle x quadratic interval) at the
 * face's natural coordinates. Usage: vtk_quadratic_test WORK_DIR
 *
 * Tolerance: 8 float epsilons of the block's extent (the nodes are rounded to float first, so the
 * difference is the evaluation's rounding only).
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "tesslod/lod.h"
#include "test.h"
#include "vtk_test_util.h"

static const char* work = ".";

/* 1D quadratic Lagrange basis on the nodes 0, 1/2, 1. */
static double lagrange(double node, double t) {
  if (node == 0) return (1 - t) * (1 - 2 * t);
  if (node == 1) return t * (2 * t - 1);
  return 4 * t * (1 - t);
}

/* The 10-node tetrahedron's: corners L(2L - 1), edges 4 L_i L_j, L the barycentrics. */
static double tet_shape(uint32_t k, const double s[3]) {
  static const uint8_t edge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  const double L[4] = {1 - s[0] - s[1] - s[2], s[0], s[1], s[2]};
  return k < 4 ? L[k] * (2 * L[k] - 1) : 4 * L[edge[k - 4][0]] * L[edge[k - 4][1]];
}

/* The 15-node wedge's (z = 2t - 1; L the triangle's barycentrics): corners
 * L(2L - 1)(1 +- z)/2 - L(1 - z^2)/2, triangle edges 2 L_i L_j (1 +- z), vertical edges L (1 - z^2). */
static double wedge_shape(uint32_t k, const double s[3]) {
  static const uint8_t edge[3][2] = {{0, 1}, {1, 2}, {2, 0}};
  const double L[3] = {1 - s[0] - s[1], s[0], s[1]}, z = 2 * s[2] - 1;
  if (k < 6) {
    double l = L[k % 3], side = k < 3 ? 1 - z : 1 + z;
    return l * (2 * l - 1) * side / 2 - l * (1 - z * z) / 2;
  }
  if (k < 12) return 2 * L[edge[(k - 6) % 3][0]] * L[edge[(k - 6) % 3][1]] * (k < 9 ? 1 - z : 1 + z);
  return L[k - 12] * (1 - z * z);
}

static void node_coords(uint32_t nodes, uint32_t k, double out[3]) {
  if (nodes == 10)
    vtk_tet_node_coords(k, out);
  else if (nodes == 15)
    vtk_wedge_node_coords(k, out);
  else
    vtk_hex_node_coords(k, out);
}

static uint32_t cell_corners(uint32_t nodes) { return nodes == 10 ? 4 : nodes == 15 ? 6 : 8; }

/* Shape function of node k at natural coordinates s ([0,1]^3; tetrahedra: r, s, t >= 0, sum <= 1). */
static double shape(uint32_t nodes, uint32_t k, const double s[3]) {
  if (nodes == 10) return tet_shape(k, s);
  if (nodes == 15) return wedge_shape(k, s);
  double c[3];
  vtk_hex_node_coords(k, c);
  if (nodes == 27) return lagrange(c[0], s[0]) * lagrange(c[1], s[1]) * lagrange(c[2], s[2]);
  double x[3], xi[3]; /* serendipity in [-1, 1] */
  for (int a = 0; a < 3; ++a)
    x[a] = 2 * s[a] - 1, xi[a] = 2 * c[a] - 1;
  if (k < 8)
    return (1 + x[0] * xi[0]) * (1 + x[1] * xi[1]) * (1 + x[2] * xi[2]) *
           (x[0] * xi[0] + x[1] * xi[1] + x[2] * xi[2] - 2) / 8;
  double n = 0.25;
  for (int a = 0; a < 3; ++a)
    n *= xi[a] == 0 ? 1 - x[a] * x[a] : 1 + x[a] * xi[a];
  return n;
}

/* The cell's isoparametric map at s, from its float-rounded nodes. */
static void hex_map(const vtk_model* m, uint32_t cell, const double s[3], double out[3]) {
  uint32_t nodes = m->offsets[cell + 1] - m->offsets[cell];
  out[0] = out[1] = out[2] = 0;
  for (uint32_t k = 0; k < nodes; ++k) {
    double n = shape(nodes, k, s);
    const double* p = m->points + 3 * (size_t)m->conn[m->offsets[cell] + k];
    for (int a = 0; a < 3; ++a)
      out[a] += n * (float)p[a];
  }
}

/* A boundary patch as the test knows it: its cell and its corners' natural coordinates. */
typedef struct face_map {
  uint32_t cell, corners;
  double corner[4][3];
} face_map;

static bool find_face(const vtk_model* m, const tlod_mesh* mesh, uint32_t patch, face_map* fm) {
  uint32_t c[4], nc = tlod_mesh_face_corners(mesh, patch, c);
  for (uint32_t cell = 0; cell < m->cell_count; ++cell) {
    uint32_t found = 0, nodes = m->offsets[cell + 1] - m->offsets[cell], corners = cell_corners(nodes);
    for (uint32_t k = 0; k < nc; ++k) {
      float q[3], n[3];
      tlod_mesh_vertex(mesh, c[k], q, n);
      for (uint32_t h = 0; h < corners; ++h) {
        const double* p = m->points + 3 * (size_t)m->conn[m->offsets[cell] + h];
        if ((float)p[0] == q[0] && (float)p[1] == q[1] && (float)p[2] == q[2]) {
          node_coords(nodes, h, fm->corner[k]);
          found++;
          break;
        }
      }
    }
    if (found == nc) {
      fm->corners = nc;
      fm->cell = cell;
      return true;
    }
  }
  return false;
}

/* The expected point of patch (u, v) (core.h PARAMETERS): the natural coordinates are bilinear
 * (quads) or barycentric (triangles) in the corners'. */
static void expected(const vtk_model* m, const face_map* fm, double u, double v, double out[3]) {
  double s[3];
  for (int a = 0; a < 3; ++a)
    s[a] = fm->corners == 3 ? u * fm->corner[0][a] + v * fm->corner[1][a] + (1 - u - v) * fm->corner[2][a]
                            : (1 - u) * (1 - v) * fm->corner[0][a] + u * (1 - v) * fm->corner[1][a] +
                                  u * v * fm->corner[2][a] + (1 - u) * v * fm->corner[3][a];
  hex_map(m, fm->cell, s, out);
}

static double dist(const float* p, const double* q) {
  return sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
}

/* Largest |eval_grid - shape functions| over patch's full grid at level l. */
static double grid_error(const vtk_model* m, const tlod_surface* s, uint32_t patch, const face_map* fm, uint32_t l) {
  uint32_t n = 1u << l, count = 0;
  uint16_t* ij = malloc(2 * sizeof(uint16_t) * (n + 1) * (n + 1));
  float* pos = malloc(3 * sizeof(float) * (n + 1) * (n + 1));
  for (uint32_t j = 0; j <= n; ++j)
    for (uint32_t i = 0; i <= n && (fm->corners == 4 || i + j <= n); ++i, ++count)
      ij[2 * count] = (uint16_t)i, ij[2 * count + 1] = (uint16_t)j;
  double worst = INFINITY;
  if (tlod_surface_eval_grid(s, patch, l, ij, 2 * sizeof(uint16_t), count, pos, NULL) == TLOD_SUCCESS) {
    worst = 0;
    for (uint32_t k = 0; k < count; ++k) {
      double e[3];
      expected(m, fm, ij[2 * k] / (double)n, ij[2 * k + 1] / (double)n, e);
      worst = fmax(worst, dist(pos + 3 * k, e));
    }
  }
  free(ij);
  free(pos);
  return worst;
}

/* Largest |tessellated vertex - shape functions| of the cpu tessellator's no_weld output. */
static double tessellated_error(const vtk_model* m, tlod_context* ctx, const tlod_surface* s, const face_map* fm,
                                uint32_t l) {
  tlod_cpu_mesh* cm = vtk_test_tessellate(ctx, s, l, true);
  if (!cm) return INFINITY;
  double worst = 0;
  for (uint32_t v = 0; v < cm->vertex_count; ++v) {
    uint32_t p = cm->vertex_patch[v];
    if (p >= tlod_surface_patch_count(s)) continue;
    double e[3];
    expected(m, &fm[p], cm->vertex_uv[v][0], cm->vertex_uv[v][1], e);
    worst = fmax(worst, dist(cm->positions + 3 * (size_t)v, e));
  }
  tlod_cpu_mesh_destroy(ctx, cm);
  return worst;
}

/* How far the face bends away from its bilinear (flat) quad: the test must not be vacuous. */
static double bend(const vtk_model* m, const face_map* fm, const tlod_mesh* mesh, uint32_t patch) {
  uint32_t c[4], nc = tlod_mesh_face_corners(mesh, patch, c);
  float q[4][3], n[3];
  for (uint32_t k = 0; k < nc; ++k)
    tlod_mesh_vertex(mesh, c[k], q[k], n);
  double e[3], b[3] = {0, 0, 0}, mid = nc == 3 ? 1 / 3.0 : 0.5;
  expected(m, fm, mid, mid, e);
  for (int a = 0; a < 3; ++a)
    for (uint32_t k = 0; k < nc; ++k)
      b[a] += q[k][a] / nc;
  return sqrt((e[0] - b[0]) * (e[0] - b[0]) + (e[1] - b[1]) * (e[1] - b[1]) + (e[2] - b[2]) * (e[2] - b[2]));
}

/* A second-order pair sharing one face: its boundary triangles and quads by construction. */
typedef struct pair_case {
  uint8_t type;
  uint32_t nodes, tris, quads;
  const char* name;
  vtk_format format;
} pair_case;

static void check_import(const tlod_import_result* r, const pair_case* pc) {
  const tlod_import_vtk_info* v = r->vtk;
  CHECK_MSG(v && v->cells == 2 && v->boundary_quads == pc->quads && v->boundary_triangles == pc->tris &&
                v->interior_faces == 1 && v->second_order_faces == pc->tris + pc->quads,
            "%s: vtk info: cells %llu, %llu quads %llu triangles, %llu interior, %llu second-order", pc->name,
            v ? (unsigned long long)v->cells : 0ull, v ? (unsigned long long)v->boundary_quads : 0ull,
            v ? (unsigned long long)v->boundary_triangles : 0ull, v ? (unsigned long long)v->interior_faces : 0ull,
            v ? (unsigned long long)v->second_order_faces : 0ull);
  CHECK_MSG(r->face_nodes && r->face_count == pc->tris + pc->quads, "%s: face_nodes %p, %u faces", pc->name,
            (void*)r->face_nodes, r->face_count);
  for (uint32_t f = 0; f < r->face_count; ++f) {
    const uint32_t* fn = r->face_nodes + TLOD_FACE_NODES * (size_t)f;
    bool ok = true;
    for (uint32_t e = 0; e < (r->face_sizes ? r->face_sizes[f] : 3u); ++e)
      ok = ok && fn[e] < r->vertex_count;
    ok = ok && (pc->nodes == 27 ? fn[4] < r->vertex_count : fn[4] == TLOD_NO_NODE);
    CHECK_MSG(ok, "%s: face %u nodes %u %u %u %u %u", pc->name, f, fn[0], fn[1], fn[2], fn[3], fn[4]);
  }
}

/* Largest errors over levels 0..6 of every patch (eval_grid, tessellated) and the largest bend. */
static void measure_levels(const vtk_model* m, tlod_context* ctx, const tlod_mesh* mesh, const tlod_surface* s,
                           const face_map* fm, uint32_t faces, double out[3]) {
  out[0] = out[1] = out[2] = 0;
  for (uint32_t l = 0; l <= 6; ++l) {
    for (uint32_t p = 0; p < faces; ++p)
      out[0] = fmax(out[0], grid_error(m, s, p, &fm[p], l));
    out[1] = fmax(out[1], tessellated_error(m, ctx, s, fm, l));
  }
  for (uint32_t p = 0; p < faces; ++p)
    out[2] = fmax(out[2], bend(m, &fm[p], mesh, p));
}

static void quadratic_case(const pair_case* pc) {
  vtk_model m;
  const uint32_t faces = pc->tris + pc->quads;
  if (pc->nodes == 10)
    vtk_build_quadratic_tet_pair(&m);
  else if (pc->nodes == 15)
    vtk_build_quadratic_wedge_pair(&m);
  else
    vtk_build_quadratic_pair(&m, pc->type);
  tlod_import_result* r = vtk_test_write_import(&m, work, pc->name, pc->format);
  tlod_context* ctx = NULL;
  tlod_mesh* mesh = NULL;
  tlod_surface* s = NULL;
  face_map fm[10];
  bool ok = r && tlod_context_create(&(tlod_context_desc){.thread_count = 1}, &ctx) == TLOD_SUCCESS;
  if (ok) check_import(r, pc);
  if (ok) mesh = vtk_test_mesh(ctx, r, 45, 0);
  if (mesh) s = vtk_test_surface(ctx, mesh, TLOD_SURFACE_QUADRATIC);
  ok = s && tlod_surface_patch_count(s) == faces;
  for (uint32_t p = 0; ok && p < faces; ++p)
    ok = find_face(&m, mesh, p, &fm[p]);
  double e[3] = {0, 0, 0}; /* eval_grid, tessellated, bend */
  if (ok) measure_levels(&m, ctx, mesh, s, fm, faces, e);
  tlod_mesh_info info = mesh ? tlod_mesh_query_info(mesh) : (tlod_mesh_info){0};
  tlod_surface_destroy(s);
  tlod_mesh_destroy(mesh);
  tlod_context_destroy(ctx);
  tlod_import_free(r);
  vtk_model_free(&m);
  const double tol = 8 * FLT_EPSILON * 2.5; /* the warped block spans about 2.5 */
  printf("  %s: levels 0..6, largest |point - shape functions|: eval_grid %.3g, tessellated %.3g (tolerance %.3g); "
         "faces bend up to %.3f off their flat faces\n",
         pc->name, e[0], e[1], tol, e[2]);
  CHECK_MSG(ok, "%s: import, surface or face lookup failed (see above)", pc->name);
  CHECK_MSG(info.curved_faces == faces && info.closed, "%s: %u curved faces, closed %d", pc->name, info.curved_faces,
            info.closed);
  CHECK_MSG(e[0] <= tol && e[1] <= tol, "%s: quadratic surface off the element's faces by %.3g / %.3g", pc->name, e[0],
            e[1]);
  CHECK_MSG(e[2] > 0.05, "%s: the faces are hardly curved (%.3g): the test would prove nothing", pc->name, e[2]);
}

TEST(test_hex20) { quadratic_case(&(pair_case){VTK_QUADRATIC_HEXAHEDRON, 20, 0, 10, "hex20.vtk", VTK_LEGACY_ASCII}); }
TEST(test_hex27) { quadratic_case(&(pair_case){VTK_TRIQUADRATIC_HEXAHEDRON, 27, 0, 10, "hex27.vtu", VTK_XML_ASCII}); }
TEST(test_tet10) { quadratic_case(&(pair_case){VTK_QUADRATIC_TETRA, 10, 6, 0, "tet10.vtk", VTK_LEGACY_BINARY}); }
/* 2 x 2 triangles and 2 x 2 quads outside, the diagonal quad shared */
TEST(test_wedge15) { quadratic_case(&(pair_case){VTK_QUADRATIC_WEDGE, 15, 4, 4, "wedge15.vtu", VTK_XML_ASCII}); }

int main(int argc, char** argv) {
  if (argc > 1) work = argv[1];
  RUN(test_hex20);
  RUN(test_hex27);
  RUN(test_tet10);
  RUN(test_wedge15);
  TEST_END();
}
