// Private to the VTK shim: the surface of a cell list -- the boundary faces of its volume
// cells, facing out, and its 2D cells as they are (docs/vtk.md sections 3 and 4). Plain C++
// over our cell tables (vtk_cells.hpp): no VTK type crosses this header.
#ifndef TESSLOD_TOOLS_IMPORT_VTK_BOUNDARY_HPP
#define TESSLOD_TOOLS_IMPORT_VTK_BOUNDARY_HPP

#include <cstdint>
#include <functional>
#include <vector>

namespace tlod_import_detail {

// Cells as VTK stores them: cell i has type types[i] and the point ids
// conn[offsets[i] .. offsets[i + 1]), each < point_count (checked by whoever filled it).
struct CellList {
  std::vector<uint8_t> types;
  std::vector<uint64_t> offsets{0};
  std::vector<uint32_t> conn;
  size_t size() const { return types.size(); }
};

struct Surface {
  std::vector<uint32_t> corners; // point ids, sizes[f] per face
  std::vector<uint8_t> sizes;    // 3 or 4
  std::vector<uint32_t> nodes;   // TLOD_FACE_NODES per face: point ids or TLOD_NO_NODE
  std::vector<uint64_t> type_counts = std::vector<uint64_t>(256, 0);
  uint64_t volume_cells = 0, triangles = 0, quads = 0, second_order_faces = 0, interior_faces = 0;
  uint64_t non_manifold_faces = 0, cells_reoriented = 0, degenerate_cells = 0, polygons_triangulated = 0;
  uint64_t strips_converted = 0, cells_ignored = 0, cells_collapsed = 0;
};

// What extract_surface() asks of its caller: take bytes from the memory budget (throws
// when over it, naming what), report progress 0..1.
struct SurfaceHooks {
  std::function<void(size_t bytes, const char* what)> take;
  std::function<void(double fraction)> progress;
};

// Fills out from cells (points: 3 doubles per point id). Throws ImportError naming the cell
// ("cell 17 (polyhedron): unsupported cell type 42") for a type we do not read or a cell
// with the wrong number of points.
void extract_surface(const CellList& cells, const double* points, const SurfaceHooks& hooks, Surface& out);

} // namespace tlod_import_detail

#endif
