/* vtk_models.c -- the builders of vtk_model.h: meshes whose boundary, area, volume, nodes and
 * fields the tests know by construction. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vtk_model.h"

/* VTK 9.1 vtkTriQuadraticHexahedron::GetParametricCoords() (0..19 also vtkQuadraticHexahedron's),
 * printed from the library: the header's prose lists the mid-face nodes in another order. */
static const double hex_nodes[27][3] = {
    {0, 0, 0},  {1, 0, 0},  {1, 1, 0},   {0, 1, 0},   {0, 0, 1},   {1, 0, 1},   {1, 1, 1},   {0, 1, 1},   {.5, 0, 0},
    {1, .5, 0}, {.5, 1, 0}, {0, .5, 0},  {.5, 0, 1},  {1, .5, 1},  {.5, 1, 1},  {0, .5, 1},  {0, 0, .5},  {1, 0, .5},
    {1, 1, .5}, {0, 1, .5}, {0, .5, .5}, {1, .5, .5}, {.5, 0, .5}, {.5, 1, .5}, {.5, .5, 0}, {.5, .5, 1}, {.5, .5, .5}};

void vtk_hex_node_coords(uint32_t k, double out[3]) { memcpy(out, hex_nodes[k < 27 ? k : 26], sizeof hex_nodes[0]); }

/* vtkQuadraticTetra::GetParametricCoords() */
static const double tet_nodes[10][3] = {{0, 0, 0},   {1, 0, 0},  {0, 1, 0},  {0, 0, 1},   {.5, 0, 0},
                                        {.5, .5, 0}, {0, .5, 0}, {0, 0, .5}, {.5, 0, .5}, {0, .5, .5}};

void vtk_tet_node_coords(uint32_t k, double out[3]) { memcpy(out, tet_nodes[k < 10 ? k : 9], sizeof tet_nodes[0]); }

/* vtkQuadraticWedge::GetParametricCoords() */
static const double wedge_nodes[15][3] = {{0, 0, 0},   {1, 0, 0},  {0, 1, 0},   {0, 0, 1},  {1, 0, 1},
                                          {0, 1, 1},   {.5, 0, 0}, {.5, .5, 0}, {0, .5, 0}, {.5, 0, 1},
                                          {.5, .5, 1}, {0, .5, 1}, {0, 0, .5},  {1, 0, .5}, {0, 1, .5}};

void vtk_wedge_node_coords(uint32_t k, double out[3]) {
  memcpy(out, wedge_nodes[k < 15 ? k : 14], sizeof wedge_nodes[0]);
}

/* A hexahedron from its bottom quad (counter-clockwise seen from the top) and top quad; inverted:
 * top and bottom swapped (negative orientation). */
static void hex_cell(vtk_model* m, const uint32_t bottom[4], const uint32_t top[4], bool inverted) {
  uint32_t n[8];
  memcpy(n, inverted ? top : bottom, sizeof(uint32_t) * 4);
  memcpy(n + 4, inverted ? bottom : top, sizeof(uint32_t) * 4);
  vtk_model_cell(m, VTK_HEXAHEDRON, n, 8);
  m->inverted += inverted;
}

/* ---- box ---- */

static void box_fields(vtk_model* m) {
  double* t = vtk_model_field_add(m, "temperature", 1, false);
  double* d = vtk_model_field_add(m, "displacement", 3, false);
  for (uint32_t p = 0; p < m->point_count; ++p) {
    const double* x = m->points + 3 * (size_t)p;
    t[p] = 100 + 10 * x[0] - 5 * x[1] + x[2] * x[2];
    d[3 * p] = x[0], d[3 * p + 1] = -2 * x[1], d[3 * p + 2] = x[2] / 2;
  }
  double* pr = vtk_model_field_add(m, "pressure", 1, true);
  for (uint32_t c = 0; c < m->cell_count; ++c)
    pr[c] = c;
}

void vtk_build_box(vtk_model* m, uint32_t nx, uint32_t ny, uint32_t nz, double a, double b, double c) {
  memset(m, 0, sizeof *m);
  for (uint32_t k = 0; k <= nz; ++k)
    for (uint32_t j = 0; j <= ny; ++j)
      for (uint32_t i = 0; i <= nx; ++i)
        vtk_model_point(m, a * i / nx, b * j / ny, c * k / nz);
#define P(i, j, k) ((i) + (nx + 1) * ((j) + (ny + 1) * (k)))
  for (uint32_t k = 0; k < nz; ++k)
    for (uint32_t j = 0; j < ny; ++j)
      for (uint32_t i = 0; i < nx; ++i) {
        uint32_t lo[4] = {P(i, j, k), P(i + 1, j, k), P(i + 1, j + 1, k), P(i, j + 1, k)};
        uint32_t hi[4] = {P(i, j, k + 1), P(i + 1, j, k + 1), P(i + 1, j + 1, k + 1), P(i, j + 1, k + 1)};
        hex_cell(m, lo, hi, m->cell_count % 5 == 4);
      }
#undef P
  box_fields(m);
}

void vtk_build_payload_box(vtk_model* m) {
  vtk_build_box(m, 1, 1, 1, 1, 1, 1);
  m->field_count = 0;
  for (int k = 0; k < 3; ++k)
    free(m->fields[k].data);
  double* f = vtk_model_field_add(m, "payload", 1, false);
  char text[64];
  memset(text, ' ', sizeof text);
  /* each 8 bytes start with a control, space or digit byte: finite doubles that are finite floats */
  memcpy(text, "\nPOINTS 999999999999     double\n", 32);
  for (int k = 0; k < 8; ++k) {
    uint64_t v = 0; /* legacy binary is big-endian: byte 0 of the text is the double's top byte */
    for (int b = 0; b < 8; ++b)
      v = v << 8 | (uint8_t)text[8 * k + b];
    memcpy(&f[k], &v, 8);
  }
}

void vtk_build_collapsed_pie(vtk_model* m) {
  memset(m, 0, sizeof *m);
  uint32_t c[2], p[2][12];
  for (int l = 0; l < 2; ++l) {
    c[l] = vtk_model_point(m, 0, 0, l);
    for (int k = 0; k < 12; ++k)
      p[l][k] = vtk_model_point(m, cos(k * M_PI / 6), sin(k * M_PI / 6), l);
  }
  for (int k = 0; k < 12; ++k) {
    int k1 = (k + 1) % 12;
    uint32_t n[8] = {c[0], p[0][k], p[0][k1], c[0], c[1], p[1][k], p[1][k1], c[1]};
    vtk_model_cell(m, VTK_HEXAHEDRON, n, 8);
  }
}

/* ---- tet sphere ---- */

typedef struct edge_map {
  uint64_t* keys;
  uint32_t* values;
  uint32_t capacity;
} edge_map;

/* The midpoint of edge (a, b) on the sphere, made once. */
static uint32_t midpoint(vtk_model* m, edge_map* em, uint32_t a, uint32_t b, double r) {
  uint64_t key = a < b ? ((uint64_t)a << 32 | b) : ((uint64_t)b << 32 | a);
  uint32_t h = (uint32_t)((key * 0x9E3779B97F4A7C15ull) >> 40) % em->capacity;
  while (em->keys[h] && em->keys[h] != key + 1)
    h = (h + 1) % em->capacity;
  if (em->keys[h]) return em->values[h];
  double p[3];
  for (int k = 0; k < 3; ++k)
    p[k] = (m->points[3 * a + k] + m->points[3 * b + k]) / 2;
  double l = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  em->keys[h] = key + 1;
  return em->values[h] = vtk_model_point(m, p[0] * r / l, p[1] * r / l, p[2] * r / l);
}

static uint32_t* subdivide(vtk_model* m, const uint32_t* tris, uint32_t n, double r) {
  edge_map em = {calloc(8 * (size_t)n, 8), calloc(8 * (size_t)n, 4), 8 * n};
  uint32_t* out = malloc(4 * 3 * sizeof(uint32_t) * n);
  for (uint32_t t = 0; t < n; ++t) {
    uint32_t a = tris[3 * t], b = tris[3 * t + 1], c = tris[3 * t + 2];
    uint32_t ab = midpoint(m, &em, a, b, r), bc = midpoint(m, &em, b, c, r), ca = midpoint(m, &em, c, a, r);
    uint32_t four[12] = {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca};
    memcpy(out + 12 * t, four, sizeof four);
  }
  free(em.keys);
  free(em.values);
  return out;
}

static uint32_t* icosphere(vtk_model* m, uint32_t subdivisions, double r, uint32_t* count) {
  const double g = (1 + sqrt(5.0)) / 2, l = sqrt(1 + g * g);
  const double v[12][3] = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                           {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  static const uint32_t f[60] = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                                 4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                                 6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
  for (int k = 0; k < 12; ++k)
    vtk_model_point(m, v[k][0] * r / l, v[k][1] * r / l, v[k][2] * r / l);
  uint32_t n = 20, *tris = malloc(sizeof f);
  memcpy(tris, f, sizeof f);
  for (uint32_t s = 0; s < subdivisions; ++s, n *= 4) {
    uint32_t* next = subdivide(m, tris, n, r);
    free(tris);
    tris = next;
  }
  *count = n;
  return tris;
}

/* True when triangle t of tris faces away from the origin. */
static bool outward(const vtk_model* m, const uint32_t* t) {
  const double *a = m->points + 3 * t[0], *b = m->points + 3 * t[1], *c = m->points + 3 * t[2];
  double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, f[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  double n[3] = {e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0]};
  return n[0] * a[0] + n[1] * a[1] + n[2] * a[2] > 0;
}

void vtk_build_tet_sphere(vtk_model* m, uint32_t subdivisions, double r) {
  memset(m, 0, sizeof *m);
  uint32_t n = 0, *tris = icosphere(m, subdivisions, r, &n);
  uint32_t centre = vtk_model_point(m, 0, 0, 0);
  for (uint32_t t = 0; t < n; ++t) {
    uint32_t* s = tris + 3 * t;
    if (!outward(m, s)) {
      uint32_t x = s[1];
      s[1] = s[2], s[2] = x;
    }
    /* positive: the base's right-hand normal points at the apex (the centre), i.e. inward */
    bool inverted = t % 2 == 1;
    uint32_t cell[4] = {s[0], inverted ? s[1] : s[2], inverted ? s[2] : s[1], centre};
    vtk_model_cell(m, VTK_TETRA, cell, 4);
    m->inverted += inverted;
  }
  free(tris);
}

/* ---- hex cylinder ---- */

/* One layer's 28 points at height z: the 4x4 inner grid (half side 0.45 R), then 12 on the circle. */
static uint32_t cylinder_layer(vtk_model* m, double R, double z) {
  uint32_t first = m->point_count;
  const double s = 0.45 * R;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i)
      vtk_model_point(m, -s + 2 * s * i / 3, -s + 2 * s * j / 3, z);
  for (int k = 0; k < 12; ++k) {
    double a = (225.0 + 30.0 * k) * M_PI / 180.0;
    vtk_model_point(m, R * cos(a), R * sin(a), z);
  }
  return first;
}

/* The inner grid's perimeter, counter-clockwise from (-s, -s): grid indices i + 4 j. */
static const uint32_t perimeter[12] = {0, 1, 2, 3, 7, 11, 15, 14, 13, 12, 8, 4};

void vtk_build_hex_cylinder(vtk_model* m, double R, double H, uint32_t layers) {
  memset(m, 0, sizeof *m);
  uint32_t base[64];
  for (uint32_t l = 0; l <= layers && l < 64; ++l)
    base[l] = cylinder_layer(m, R, H * l / layers);
  for (uint32_t l = 0; l < layers && l < 63; ++l) {
    uint32_t b = base[l], t = base[l + 1];
    for (uint32_t j = 0; j < 3; ++j)
      for (uint32_t i = 0; i < 3; ++i) {
        uint32_t q[4] = {i + 4 * j, i + 1 + 4 * j, i + 1 + 4 * (j + 1), i + 4 * (j + 1)};
        uint32_t lo[4] = {b + q[0], b + q[1], b + q[2], b + q[3]}, hi[4] = {t + q[0], t + q[1], t + q[2], t + q[3]};
        hex_cell(m, lo, hi, false);
      }
    for (uint32_t k = 0; k < 12; ++k) {
      uint32_t q[4] = {perimeter[k], 16 + k, 16 + (k + 1) % 12, perimeter[(k + 1) % 12]};
      uint32_t lo[4] = {b + q[0], b + q[1], b + q[2], b + q[3]}, hi[4] = {t + q[0], t + q[1], t + q[2], t + q[3]};
      hex_cell(m, lo, hi, false);
    }
  }
}

/* ---- quadratic pair ---- */

void vtk_warp(const double in[3], double out[3]) {
  const double x = in[0], y = in[1], z = in[2], sx = sin(M_PI * x / 2), sy = sin(M_PI * y);
  out[0] = x + 0.1 * y * z + 0.05 * sy;
  out[1] = y + 0.12 * sx * (1 + z);
  out[2] = z + 0.25 * sx * sy + 0.05 * x * y;
}

void vtk_build_quadratic_pair(vtk_model* m, uint8_t type) {
  memset(m, 0, sizeof *m);
  uint32_t grid[5][3][3];
  memset(grid, 0xff, sizeof grid);
  const uint32_t nodes = type == VTK_TRIQUADRATIC_HEXAHEDRON ? 27 : 20;
  for (uint32_t h = 0; h < 2; ++h) {
    uint32_t cell[27];
    for (uint32_t k = 0; k < nodes; ++k) {
      uint32_t i = 2 * h + (uint32_t)(2 * hex_nodes[k][0]), j = (uint32_t)(2 * hex_nodes[k][1]),
               l = (uint32_t)(2 * hex_nodes[k][2]);
      if (grid[i][j][l] == UINT32_MAX) {
        double p[3] = {i / 2.0, j / 2.0, l / 2.0}, w[3];
        vtk_warp(p, w);
        grid[i][j][l] = vtk_model_point(m, w[0], w[1], w[2]);
      }
      cell[k] = grid[i][j][l];
    }
    vtk_model_cell(m, type, cell, nodes);
  }
}

/* The point of m at warp(p) (made when absent; positions are multiples of 1/2, so exact). */
static uint32_t warped_at(vtk_model* m, double x, double y, double z) {
  double p[3] = {x, y, z}, w[3];
  vtk_warp(p, w);
  for (uint32_t k = 0; k < m->point_count; ++k)
    if (!memcmp(m->points + 3 * (size_t)k, w, sizeof w)) return k;
  return vtk_model_point(m, w[0], w[1], w[2]);
}

/* A cell of `count` nodes at natural coordinates nodes[k], placed by o + n0 A + n1 B + n2 C, warped. */
static void affine_cell(vtk_model* m, uint8_t type, const double (*nodes)[3], int count, const double o[3],
                        const double axes[3][3]) {
  uint32_t cell[27];
  for (int k = 0; k < count && k < 27; ++k) {
    double p[3];
    for (int a = 0; a < 3; ++a)
      p[a] = o[a] + nodes[k][0] * axes[0][a] + nodes[k][1] * axes[1][a] + nodes[k][2] * axes[2][a];
    cell[k] = warped_at(m, p[0], p[1], p[2]);
  }
  vtk_model_cell(m, type, cell, (uint32_t)count);
}

void vtk_build_quadratic_tet_pair(vtk_model* m) {
  memset(m, 0, sizeof *m);
  static const double o[2][3] = {{0, 0, 0}, {1, 0, 0}};
  static const double axes[2][3][3] = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{-1, 1, 0}, {-1, 0, 1}, {0, 1, 1}}};
  for (int t = 0; t < 2; ++t)
    affine_cell(m, VTK_QUADRATIC_TETRA, tet_nodes, 10, o[t], axes[t]);
}

void vtk_build_quadratic_wedge_pair(vtk_model* m) {
  memset(m, 0, sizeof *m);
  /* base corners 0, 1, 2 clockwise seen from +z (VTK's positive wedge), extruded by (0, 0, 1) */
  static const double o[2][3] = {{1, 0, 0}, {2, 0, 0}};
  static const double axes[2][3][3] = {{{0, 1, 0}, {1, 0, 0}, {0, 0, 1}}, {{-1, 1, 0}, {0, 1, 0}, {0, 0, 1}}};
  for (int w = 0; w < 2; ++w)
    affine_cell(m, VTK_QUADRATIC_WEDGE, wedge_nodes, 15, o[w], axes[w]);
}

void vtk_build_mixed_order(vtk_model* m) {
  vtk_build_quadratic_pair(m, VTK_QUADRATIC_HEXAHEDRON);
  uint32_t lo[4] = {warped_at(m, 2, 0, 0), warped_at(m, 3, 0, 0), warped_at(m, 3, 1, 0), warped_at(m, 2, 1, 0)};
  uint32_t hi[4] = {warped_at(m, 2, 0, 1), warped_at(m, 3, 0, 1), warped_at(m, 3, 1, 1), warped_at(m, 2, 1, 1)};
  hex_cell(m, lo, hi, false);
}

/* ---- mixed ---- */

/* The corner (x, y, z) of the unit cubes along x (x 0..4, y and z 0..1). */
#define MC(x, y, z) ((uint32_t)(4 * (x) + 2 * (y) + (z)))

/* Cube [x, x + 1]'s six faces, each counter-clockwise seen from outside (VTK's hexahedron faces). */
static void cube_faces(uint32_t x, uint32_t out[6][4]) {
  const uint32_t h[8] = {MC(x, 0, 0), MC(x + 1, 0, 0), MC(x + 1, 1, 0), MC(x, 1, 0),
                         MC(x, 0, 1), MC(x + 1, 0, 1), MC(x + 1, 1, 1), MC(x, 1, 1)};
  static const uint8_t f[6][4] = {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}};
  for (int k = 0; k < 6; ++k)
    for (int c = 0; c < 4; ++c)
      out[k][c] = h[f[k][c]];
}

/* A pyramid on an outward face (so its base is the reversed face, normal towards the apex). */
static void pyramid_on(vtk_model* m, const uint32_t face[4], uint32_t apex) {
  uint32_t p[5] = {face[3], face[2], face[1], face[0], apex};
  vtk_model_cell(m, VTK_PYRAMID, p, 5);
}

static void tets_on(vtk_model* m, const uint32_t q[4], uint32_t apex) {
  uint32_t a[4] = {q[0], q[2], q[1], apex}, b[4] = {q[0], q[3], q[2], apex};
  vtk_model_cell(m, VTK_TETRA, a, 4);
  vtk_model_cell(m, VTK_TETRA, b, 4);
}

void vtk_build_mixed(vtk_model* m) {
  memset(m, 0, sizeof *m);
  for (uint32_t x = 0; x <= 4; ++x)
    for (uint32_t y = 0; y <= 1; ++y)
      for (uint32_t z = 0; z <= 1; ++z)
        vtk_model_point(m, x, y, z);
  uint32_t c1 = vtk_model_point(m, 2.5, 0.5, 0.5), c2 = vtk_model_point(m, 3.5, 0.5, 0.5);
  uint32_t lo[4] = {MC(0, 0, 0), MC(1, 0, 0), MC(1, 1, 0), MC(0, 1, 0)};
  uint32_t hi[4] = {MC(0, 0, 1), MC(1, 0, 1), MC(1, 1, 1), MC(0, 1, 1)};
  hex_cell(m, lo, hi, false);
  /* [1,2] split by the plane x + y = 2 into two wedges. VTK's positive wedge has its base (0, 1, 2)
   * facing away from (3, 4, 5) (vtkWedge.h; vtkCellValidator agrees), unlike its parametric
   * coordinates: the triangles are clockwise seen from the top (+z). */
  uint32_t w1[6] = {MC(1, 0, 0), MC(1, 1, 0), MC(2, 0, 0), MC(1, 0, 1), MC(1, 1, 1), MC(2, 0, 1)};
  uint32_t w2[6] = {MC(2, 0, 0), MC(1, 1, 0), MC(2, 1, 0), MC(2, 0, 1), MC(1, 1, 1), MC(2, 1, 1)};
  vtk_model_cell(m, VTK_WEDGE, w1, 6);
  vtk_model_cell(m, VTK_WEDGE, w2, 6);
  uint32_t f[6][4];
  cube_faces(2, f);
  for (int k = 0; k < 6; ++k)
    pyramid_on(m, f[k], c1);
  cube_faces(3, f);
  pyramid_on(m, f[0], c2); /* x = 3: against the x+ pyramid of the cube before */
  for (int k = 1; k < 6; ++k)
    tets_on(m, f[k], c2);
}
