/* vtk_collapsed_test.c -- collapsed (degenerate) linear cells through the VTK importer
 * (docs/vtk.md section 4): finite-element exporters write wedges, pyramids and tetrahedra as
 * hexahedra with repeated point ids, and triangles as quads with a repeated corner. Such cells
 * must give the faces of the solid they collapse to; cells collapsed flat are dropped.
 *
 * Expectations are the test's own: face counts of the solid each cell collapses to, volumes of
 * known solids (divergence theorem over the output), and closedness (every directed edge of the
 * output matched by its reverse exactly once). */
#include <stdint.h>

#include "test.h"
#include "tlod_import.h"

static char g_err[1024];
static const double kPi = 3.14159265358979323846;

static tlod_result import_text(const char* name, const char* text, tlod_import_result** r) {
  return tlod_import_memory(name, text, strlen(text), NULL, r, g_err, sizeof g_err);
}

static uint32_t face_size(const tlod_import_result* r, uint32_t f) { return r->face_sizes ? r->face_sizes[f] : 3; }

static uint32_t count_quads(const tlod_import_result* r) {
  uint32_t q = 0;
  for (uint32_t f = 0; f < r->face_count; ++f)
    q += face_size(r, f) == 4;
  return q;
}

/* Divergence-theorem volume of the output faces (fans): positive when they face out. */
static double surface_volume(const tlod_import_result* r) {
  double v = 0;
  size_t at = 0;
  for (uint32_t f = 0; f < r->face_count; ++f) {
    const uint32_t n = face_size(r, f);
    const float* a = r->positions + 3 * (size_t)r->indices[at];
    for (uint32_t i = 1; i + 1 < n; ++i) {
      const float* b = r->positions + 3 * (size_t)r->indices[at + i];
      const float* c = r->positions + 3 * (size_t)r->indices[at + i + 1];
      v += a[0] * ((double)b[1] * c[2] - (double)b[2] * c[1]) + a[1] * ((double)b[2] * c[0] - (double)b[0] * c[2]) +
           a[2] * ((double)b[0] * c[1] - (double)b[1] * c[0]);
    }
    at += n;
  }
  return v / 6;
}

/* Closed and consistently oriented: every directed edge appears once, and so does its reverse. */
static int closed(const tlod_import_result* r) {
  for (size_t e = 0; e < r->index_count; ++e) {
    uint32_t f = 0;
    size_t start = 0;
    while (start + face_size(r, f) <= e)
      start += face_size(r, f++);
    const uint32_t n = face_size(r, f), a = r->indices[e], b = r->indices[start + (e - start + 1) % n];
    int same = 0, reverse = 0;
    size_t at = 0;
    for (uint32_t g = 0; g < r->face_count; at += face_size(r, g++))
      for (uint32_t i = 0; i < face_size(r, g); ++i) {
        const uint32_t c = r->indices[at + i], d = r->indices[at + (i + 1) % face_size(r, g)];
        same += c == a && d == b;
        reverse += c == b && d == a;
      }
    if (same != 1 || reverse != 1) return 0;
  }
  return 1;
}

/* A legacy ASCII file: points (np x 3, x mirrored when mirror: inverts every cell), cells of
 * type `type` with `per` ids each (ids: cells x per). */
static void grid_file(char* out, size_t size, const double (*p)[3], int np, const int* ids, int cells, int per,
                      int type, int mirror) {
  int at = snprintf(out, size, "# vtk DataFile Version 3.0\ncollapsed\nASCII\nDATASET UNSTRUCTURED_GRID\n");
  at += snprintf(out + at, size - (size_t)at, "POINTS %d double\n", np);
  for (int i = 0; i < np; ++i)
    at += snprintf(out + at, size - (size_t)at, "%.17g %.17g %.17g\n", mirror ? -p[i][0] : p[i][0], p[i][1], p[i][2]);
  at += snprintf(out + at, size - (size_t)at, "CELLS %d %d\n", cells, cells * (per + 1));
  for (int c = 0; c < cells; ++c) {
    at += snprintf(out + at, size - (size_t)at, "%d", per);
    for (int i = 0; i < per; ++i)
      at += snprintf(out + at, size - (size_t)at, " %d", ids[c * per + i]);
    at += snprintf(out + at, size - (size_t)at, "\n");
  }
  at += snprintf(out + at, size - (size_t)at, "CELL_TYPES %d\n", cells);
  for (int c = 0; c < cells; ++c)
    at += snprintf(out + at, size - (size_t)at, "%d\n", type);
}

typedef struct expect {
  uint32_t tris, quads;
  double volume;
  uint64_t collapsed, degenerate;
} expect;

static void check_grid(const char* what, const char* text, const expect* e, int mirror) {
  tlod_import_result* r = NULL;
  CHECK_MSG(import_text("collapsed.vtk", text, &r) == TLOD_SUCCESS, "%s: %s", what, g_err);
  const uint32_t q = count_quads(r), t = r->face_count - q;
  const double vol = surface_volume(r);
  const int shut = closed(r);
  const uint64_t collapsed = r->vtk->cells_collapsed, degenerate = r->vtk->degenerate_cells;
  const uint64_t flipped = r->vtk->cells_reoriented, kept = r->vtk->volume_cells;
  tlod_import_free(r);
  CHECK_MSG(t == e->tris && q == e->quads, "%s: %u triangles, %u quads, expected %u, %u", what, t, q, e->tris,
            e->quads);
  CHECK_MSG(fabs(vol - e->volume) < 1e-6, "%s mirror %d: volume %.9g, expected %.9g (outward faces)", what, mirror, vol,
            e->volume);
  CHECK_MSG(shut, "%s: boundary not closed", what);
  CHECK_MSG(collapsed == e->collapsed && degenerate == e->degenerate, "%s: %llu collapsed, %llu degenerate", what,
            (unsigned long long)collapsed, (unsigned long long)degenerate);
  CHECK_MSG(flipped == (mirror ? kept : 0), "%s mirror %d: %llu of %llu reoriented", what, mirror,
            (unsigned long long)flipped, (unsigned long long)kept);
}

/* Cells of one type, upright and mirrored (inverted): the same faces, volume and closedness. */
static void check_both(const char* what, const double (*p)[3], int np, const int* ids, int cells, int per, int type,
                       const expect* e) {
  static char text[8192];
  for (int mirror = 0; mirror < 2; ++mirror) {
    grid_file(text, sizeof text, p, np, ids, cells, per, type, mirror);
    CALL(check_grid(what, text, e, mirror));
  }
}

/* Twelve hexahedra collapsed to wedges around the z axis (ids c k k+1 c, top the same), as FE
 * exporters write a pie: a closed 12-gon prism of 24 triangles and 12 quads, volume 12 * 1/4. */
TEST(collapsed_hex_wedge_ring_is_closed) {
  double p[26][3];
  int ids[12 * 8];
  for (int l = 0; l < 2; ++l) {
    p[13 * l][0] = p[13 * l][1] = 0, p[13 * l][2] = l;
    for (int k = 0; k < 12; ++k)
      p[13 * l + 1 + k][0] = cos(k * kPi / 6), p[13 * l + 1 + k][1] = sin(k * kPi / 6), p[13 * l + 1 + k][2] = l;
  }
  for (int k = 0; k < 12; ++k) {
    const int k1 = (k + 1) % 12, n[8] = {0, 1 + k, 1 + k1, 0, 13, 14 + k, 14 + k1, 13};
    memcpy(ids + 8 * k, n, sizeof n);
  }
  const expect e = {24, 12, 3.0, 12, 0};
  CALL(check_both("pie", (const double(*)[3])p, 26, ids, 12, 8, 12, &e));
}

static const double k_pyramid[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1}};
static const double k_tet[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

/* A hexahedron whose top face is one point: the pyramid (4 triangles, the base quad). */
TEST(hex_collapsed_to_pyramid) {
  const int ids[8] = {0, 1, 2, 3, 4, 4, 4, 4};
  const expect e = {4, 1, 1.0 / 3, 1, 0};
  CALL(check_both("hex as pyramid", k_pyramid, 5, ids, 1, 8, 12, &e));
}

/* A hexahedron as VTK-style exporters write a tetrahedron (ids 0 1 2 2 3 3 3 3). */
TEST(hex_collapsed_to_tet) {
  const int ids[8] = {0, 1, 2, 2, 3, 3, 3, 3};
  const expect e = {4, 0, 1.0 / 6, 1, 0};
  CALL(check_both("hex as tet", k_tet, 4, ids, 1, 8, 12, &e));
}

/* A wedge collapsed to a tetrahedron (ids 0 2 1 3 3 3): also a linear cell with repeats. */
TEST(wedge_collapsed_to_tet) {
  const int ids[6] = {0, 2, 1, 3, 3, 3};
  const expect e = {4, 0, 1.0 / 6, 1, 0};
  CALL(check_both("wedge as tet", k_tet, 4, ids, 1, 6, 13, &e));
}

/* Cells collapsed flat are dropped and counted, the tetrahedron next to them kept: a hex whose
 * top is its bottom (two opposite quads, volume 0), a hex whose 8 ids name 3 points, and a
 * hex-as-wedge whose top triangle lies in the bottom's plane. */
TEST(hex_collapsed_flat_is_dropped) {
  const double p[7][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {2, 0, 0}, {0, 2, 0}};
  const int ids[4 * 8] = {0, 1, 4, 2, 0, 1, 4, 2, /* top == bottom */
                          0, 1, 2, 2, 0, 1, 2, 2, /* 3 points */
                          0, 1, 4, 4, 5, 6, 2, 2, /* wedge with coplanar top */
                          0, 1, 2, 2, 3, 3, 3, 3};
  const expect e = {4, 0, 1.0 / 6, 1, 3};
  char text[4096];
  grid_file(text, sizeof text, p, 7, ids, 4, 8, 12, 0);
  CALL(check_grid("flat hexes", text, &e, 0));
}

/* A quad with a repeated corner is its triangle; one with two repeats has no area. */
TEST(quad_with_repeated_corner_is_a_triangle) {
  const double p[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const int ids[3 * 4] = {0, 1, 2, 2, 0, 2, 3, 3, 1, 1, 3, 3};
  char text[2048];
  grid_file(text, sizeof text, p, 4, ids, 3, 4, 9, 0);
  tlod_import_result* r = NULL;
  CHECK_MSG(import_text("quads.vtk", text, &r) == TLOD_SUCCESS, "%s", g_err);
  const uint32_t faces = r->face_count, quads = count_quads(r);
  const uint64_t collapsed = r->vtk->cells_collapsed, degenerate = r->vtk->degenerate_cells;
  const int order = faces == 2 && r->indices[0] == 0 && r->indices[1] == 1 && r->indices[2] == 2 &&
                    r->indices[3] == 0 && r->indices[4] == 2 && r->indices[5] == 3;
  tlod_import_free(r);
  CHECK_MSG(faces == 2 && quads == 0 && collapsed == 2 && degenerate == 1, "%u faces, %u quads, %llu/%llu", faces,
            quads, (unsigned long long)collapsed, (unsigned long long)degenerate);
  CHECK_MSG(order, "triangles keep the quad's corner order");
}

/* Second-order cells with a repeated node stay dropped: their node positions no longer define
 * an isoparametric map (docs/vtk.md section 4). */
TEST(second_order_collapsed_stays_dropped) {
  const char* text = "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n"
                     "0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 2 15\n3 0 1 2\n10 0 1 2 3 0 1 2 3 0 1\n"
                     "CELL_TYPES 2\n5\n24\n";
  tlod_import_result* r = NULL;
  CHECK_MSG(import_text("quadratic.vtk", text, &r) == TLOD_SUCCESS, "%s", g_err);
  const uint64_t collapsed = r->vtk->cells_collapsed, degenerate = r->vtk->degenerate_cells;
  const uint32_t faces = r->face_count;
  tlod_import_free(r);
  CHECK_MSG(faces == 1 && collapsed == 0 && degenerate == 1, "%u faces, %llu/%llu", faces,
            (unsigned long long)collapsed, (unsigned long long)degenerate);
}

int main(void) {
  RUN(collapsed_hex_wedge_ring_is_closed);
  RUN(hex_collapsed_to_pyramid);
  RUN(hex_collapsed_to_tet);
  RUN(wedge_collapsed_to_tet);
  RUN(hex_collapsed_flat_is_dropped);
  RUN(quad_with_repeated_corner_is_a_triangle);
  RUN(second_order_collapsed_stays_dropped);
  TEST_END();
}
