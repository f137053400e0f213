// vtk_cells.cpp -- our face tables of VTK's cell types (docs/vtk.md section 3). Faces list
// their corners so that they face out of a cell of VTK's positive orientation (the same
// order as VTK's own GetFaceArray(), which tests/import/vtk_tables_test.cpp checks); the
// boundary extraction does not rely on that: it orients each cell by its signed volume.
#include "vtk_cells.hpp"

namespace tlod_import_detail {
namespace {

constexpr CellFace kTri[] = {{3, {0, 1, 2, -1}, -1}};
constexpr CellFace kQuad[] = {{4, {0, 1, 2, 3}, -1}};
constexpr CellFace kBiQuad[] = {{4, {0, 1, 2, 3}, 8}};
constexpr CellFace kPixel[] = {{4, {0, 1, 3, 2}, -1}};

constexpr CellFace kTetFaces[] = {
    {3, {0, 1, 3, -1}, -1}, {3, {1, 2, 3, -1}, -1}, {3, {2, 0, 3, -1}, -1}, {3, {0, 2, 1, -1}, -1}};
constexpr CellFace kHexFaces[] = {{4, {0, 4, 7, 3}, -1}, {4, {1, 2, 6, 5}, -1}, {4, {0, 1, 5, 4}, -1},
                                  {4, {3, 7, 6, 2}, -1}, {4, {0, 3, 2, 1}, -1}, {4, {4, 5, 6, 7}, -1}};
// The 27-node hex: centre nodes 20..25 on the faces in this order (VTK's numbering).
constexpr CellFace kHex27Faces[] = {{4, {0, 4, 7, 3}, 20}, {4, {1, 2, 6, 5}, 21}, {4, {0, 1, 5, 4}, 22},
                                    {4, {3, 7, 6, 2}, 23}, {4, {0, 3, 2, 1}, 24}, {4, {4, 5, 6, 7}, 25}};
// The 24-node hex: centres on the four side faces only.
constexpr CellFace kHex24Faces[] = {{4, {0, 4, 7, 3}, 20}, {4, {1, 2, 6, 5}, 21}, {4, {0, 1, 5, 4}, 22},
                                    {4, {3, 7, 6, 2}, 23}, {4, {0, 3, 2, 1}, -1}, {4, {4, 5, 6, 7}, -1}};
// A voxel is a hex whose corners are numbered as a grid (x fastest): hex corner i = voxel node
// {0,1,3,2,4,5,7,6}[i], substituted into the hex faces.
constexpr CellFace kVoxelFaces[] = {{4, {0, 4, 6, 2}, -1}, {4, {1, 3, 7, 5}, -1}, {4, {0, 1, 5, 4}, -1},
                                    {4, {2, 6, 7, 3}, -1}, {4, {0, 2, 3, 1}, -1}, {4, {4, 5, 7, 6}, -1}};
constexpr CellFace kWedgeFaces[] = {{3, {0, 1, 2, -1}, -1},
                                    {3, {3, 5, 4, -1}, -1},
                                    {4, {0, 3, 4, 1}, -1},
                                    {4, {1, 4, 5, 2}, -1},
                                    {4, {2, 5, 3, 0}, -1}};
constexpr CellFace kWedge18Faces[] = {{3, {0, 1, 2, -1}, -1},
                                      {3, {3, 5, 4, -1}, -1},
                                      {4, {0, 3, 4, 1}, 15},
                                      {4, {1, 4, 5, 2}, 16},
                                      {4, {2, 5, 3, 0}, 17}};
constexpr CellFace kPyramidFaces[] = {{4, {0, 3, 2, 1}, -1},
                                      {3, {0, 1, 4, -1}, -1},
                                      {3, {1, 2, 4, -1}, -1},
                                      {3, {2, 3, 4, -1}, -1},
                                      {3, {3, 0, 4, -1}, -1}};

constexpr EdgeNode kTri6Edges[] = {{0, 1, 3}, {1, 2, 4}, {2, 0, 5}};
constexpr EdgeNode kQuad8Edges[] = {{0, 1, 4}, {1, 2, 5}, {2, 3, 6}, {3, 0, 7}};
constexpr EdgeNode kQuad6Edges[] = {{0, 1, 4}, {2, 3, 5}};
constexpr EdgeNode kTet10Edges[] = {{0, 1, 4}, {1, 2, 5}, {2, 0, 6}, {0, 3, 7}, {1, 3, 8}, {2, 3, 9}};
constexpr EdgeNode kHex20Edges[] = {{0, 1, 8},  {1, 2, 9},  {2, 3, 10}, {3, 0, 11}, {4, 5, 12}, {5, 6, 13},
                                    {6, 7, 14}, {7, 4, 15}, {0, 4, 16}, {1, 5, 17}, {2, 6, 18}, {3, 7, 19}};
constexpr EdgeNode kWedge15Edges[] = {{0, 1, 6},  {1, 2, 7},  {2, 0, 8},  {3, 4, 9}, {4, 5, 10},
                                      {5, 3, 11}, {0, 3, 12}, {1, 4, 13}, {2, 5, 14}};
constexpr EdgeNode kWedge12Edges[] = {{0, 1, 6}, {1, 2, 7}, {2, 0, 8}, {3, 4, 9}, {4, 5, 10}, {5, 3, 11}};
constexpr EdgeNode kPyramid13Edges[] = {{0, 1, 5}, {1, 2, 6},  {2, 3, 7},  {3, 0, 8},
                                        {0, 4, 9}, {1, 4, 10}, {2, 4, 11}, {3, 4, 12}};

template <class T, int N> constexpr int count(const T (&)[N]) { return N; }
#define TLOD_FACES(f) count(f), f
#define TLOD_EDGES(e) count(e), e

constexpr CellKind kKinds[] = {
    {0, "empty cell", CellRole::Ignored, 0, 0, nullptr, 0, nullptr},
    {1, "vertex", CellRole::Ignored, 1, 0, nullptr, 0, nullptr},
    {2, "poly vertex", CellRole::Ignored, -1, 0, nullptr, 0, nullptr},
    {3, "line", CellRole::Ignored, 2, 0, nullptr, 0, nullptr},
    {4, "poly line", CellRole::Ignored, -1, 0, nullptr, 0, nullptr},
    {5, "triangle", CellRole::Surface, 3, TLOD_FACES(kTri), 0, nullptr},
    {6, "triangle strip", CellRole::Strip, -1, 0, nullptr, 0, nullptr},
    {7, "polygon", CellRole::Polygon, -1, 0, nullptr, 0, nullptr},
    {8, "pixel", CellRole::Surface, 4, TLOD_FACES(kPixel), 0, nullptr},
    {9, "quad", CellRole::Surface, 4, TLOD_FACES(kQuad), 0, nullptr},
    {10, "tetra", CellRole::Volume, 4, TLOD_FACES(kTetFaces), 0, nullptr},
    {11, "voxel", CellRole::Volume, 8, TLOD_FACES(kVoxelFaces), 0, nullptr},
    {12, "hexahedron", CellRole::Volume, 8, TLOD_FACES(kHexFaces), 0, nullptr},
    {13, "wedge", CellRole::Volume, 6, TLOD_FACES(kWedgeFaces), 0, nullptr},
    {14, "pyramid", CellRole::Volume, 5, TLOD_FACES(kPyramidFaces), 0, nullptr},
    {15, "pentagonal prism", CellRole::Unsupported, 10, 0, nullptr, 0, nullptr},
    {16, "hexagonal prism", CellRole::Unsupported, 12, 0, nullptr, 0, nullptr},
    {21, "quadratic edge", CellRole::Ignored, 3, 0, nullptr, 0, nullptr},
    {22, "quadratic triangle", CellRole::Surface, 6, TLOD_FACES(kTri), TLOD_EDGES(kTri6Edges)},
    {23, "quadratic quad", CellRole::Surface, 8, TLOD_FACES(kQuad), TLOD_EDGES(kQuad8Edges)},
    {24, "quadratic tetra", CellRole::Volume, 10, TLOD_FACES(kTetFaces), TLOD_EDGES(kTet10Edges)},
    {25, "quadratic hexahedron", CellRole::Volume, 20, TLOD_FACES(kHexFaces), TLOD_EDGES(kHex20Edges)},
    {26, "quadratic wedge", CellRole::Volume, 15, TLOD_FACES(kWedgeFaces), TLOD_EDGES(kWedge15Edges)},
    {27, "quadratic pyramid", CellRole::Volume, 13, TLOD_FACES(kPyramidFaces), TLOD_EDGES(kPyramid13Edges)},
    {28, "biquadratic quad", CellRole::Surface, 9, TLOD_FACES(kBiQuad), TLOD_EDGES(kQuad8Edges)},
    {29, "triquadratic hexahedron", CellRole::Volume, 27, TLOD_FACES(kHex27Faces), TLOD_EDGES(kHex20Edges)},
    {30, "quadratic linear quad", CellRole::Surface, 6, TLOD_FACES(kQuad), TLOD_EDGES(kQuad6Edges)},
    {31, "quadratic linear wedge", CellRole::Volume, 12, TLOD_FACES(kWedgeFaces), TLOD_EDGES(kWedge12Edges)},
    {32, "biquadratic quadratic wedge", CellRole::Volume, 18, TLOD_FACES(kWedge18Faces), TLOD_EDGES(kWedge15Edges)},
    {33, "biquadratic quadratic hexahedron", CellRole::Volume, 24, TLOD_FACES(kHex24Faces), TLOD_EDGES(kHex20Edges)},
    // Not read: their faces are not triangles or quads of our surface types.
    {34, "biquadratic triangle", CellRole::Unsupported, 7, 0, nullptr, 0, nullptr},
    {35, "cubic line", CellRole::Ignored, 4, 0, nullptr, 0, nullptr},
    {36, "quadratic polygon", CellRole::Unsupported, -1, 0, nullptr, 0, nullptr},
    {37, "triquadratic pyramid", CellRole::Unsupported, 19, 0, nullptr, 0, nullptr},
    {41, "convex point set", CellRole::Unsupported, -1, 0, nullptr, 0, nullptr},
    {42, "polyhedron", CellRole::Unsupported, -1, 0, nullptr, 0, nullptr},
};

// VTK's other ids (parametric, higher-order, Lagrange, Bezier): refused by name.
const char* other_name(int t) {
  if (t >= 51 && t <= 56) return "parametric cell";
  if (t >= 60 && t <= 67) return "higher-order cell";
  if (t >= 68 && t <= 74) return "Lagrange cell";
  if (t >= 75 && t <= 81) return "Bezier cell";
  return nullptr;
}

} // namespace

const CellKind* cell_kind(int vtk_type) {
  for (const CellKind& k : kKinds)
    if (k.vtk_type == vtk_type) return &k;
  static thread_local CellKind other;
  const char* name = other_name(vtk_type);
  if (!name) return nullptr;
  other = {vtk_type, name, CellRole::Unsupported, -1, 0, nullptr, 0, nullptr};
  return &other;
}

int cell_edge_node(const CellKind& k, int a, int b) {
  for (int i = 0; i < k.edge_node_count; ++i) {
    const EdgeNode& e = k.edge_nodes[i];
    if ((e.a == a && e.b == b) || (e.a == b && e.b == a)) return e.node;
  }
  return -1;
}

} // namespace tlod_import_detail
