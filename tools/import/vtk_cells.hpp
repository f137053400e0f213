// Private to the VTK shim (tools/import/vtk_*.cpp): what the importer knows about each VTK
// cell type -- its name, its node count, its faces and the second-order nodes on them. Our
// own tables (docs/vtk.md section 3), in VTK's node numbering; no VTK header is needed here,
// so the boundary extraction (vtk_boundary.cpp) is plain C++.
#ifndef TESSLOD_TOOLS_IMPORT_VTK_CELLS_HPP
#define TESSLOD_TOOLS_IMPORT_VTK_CELLS_HPP

#include <cstdint>

namespace tlod_import_detail {

enum class CellRole : uint8_t {
  Ignored,     // vertex, line, empty: no surface (counted in cells_ignored)
  Surface,     // a 2D cell: itself a face
  Polygon,     // n corners, fan-triangulated past 4
  Strip,       // triangle strip, converted to triangles
  Volume,      // a 3D cell: its faces go to the boundary extraction
  Unsupported, // refused naming the cell
};

// A face of a cell: 3 or 4 corners (local node indices) in the order that faces out of a
// cell of positive orientation; centre: the local index of its centre node (9-node quads), or -1.
struct CellFace {
  uint8_t size;
  int8_t corner[4];
  int8_t centre;
};

// A mid-edge node: local node `node` sits on the edge between local corners a and b.
struct EdgeNode {
  int8_t a, b, node;
};

struct CellKind {
  int vtk_type;
  const char* name; // "hexahedron", "quadratic tetra", ...
  CellRole role;
  int nodes; // node count the cell must have; -1: any (polygon, strip, poly vertex, poly line)
  int face_count;
  const CellFace* faces;
  int edge_node_count;
  const EdgeNode* edge_nodes;
};

// The kind of a VTK cell type id; for ids VTK defines but we do not read (polyhedron,
// Lagrange, Bezier, ...) a kind with role Unsupported and VTK's name; nullptr for ids VTK
// does not define.
const CellKind* cell_kind(int vtk_type);

// The local node on the edge between local corners a and b (either order), or -1.
int cell_edge_node(const CellKind& k, int a, int b);

} // namespace tlod_import_detail

#endif
