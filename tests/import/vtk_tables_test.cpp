// vtk_tables_test.cpp -- our face tables (tools/import/vtk_cells.cpp) against VTK's own cells:
// for every volume type, each face of ours is VTK's face (same corner loop up to rotation, so the
// same orientation) and its mid-edge and centre nodes are the nodes VTK puts on that face; for
// 2D second-order types, each edge's node is VTK's. Owned by the import/export layer.
#include <vtkCell.h>
#include <vtkGenericCell.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPoints.h>

#include <cstdio>
#include <vector>

#include "vtk_cells.hpp"

using tlod_import_detail::cell_edge_node;
using tlod_import_detail::cell_kind;
using tlod_import_detail::CellKind;
using tlod_import_detail::CellRole;

static int g_failed = 0;

#define EXPECT(cond, ...)                                                                                              \
  do {                                                                                                                 \
    if (!(cond)) {                                                                                                     \
      std::fprintf(stderr, "%s:%d: ", __FILE__, __LINE__);                                                             \
      std::fprintf(stderr, __VA_ARGS__);                                                                               \
      std::fputc('\n', stderr);                                                                                        \
      g_failed++;                                                                                                      \
    }                                                                                                                  \
  } while (0)

static vtkCell* make(vtkGenericCell* g, int type, int nodes) {
  g->SetCellType(type);
  g->GetPointIds()->SetNumberOfIds(nodes);
  g->GetPoints()->SetNumberOfPoints(nodes);
  for (int i = 0; i < nodes; ++i) {
    g->GetPointIds()->SetId(i, i);
    g->GetPoints()->SetPoint(i, 0, 0, 0);
  }
  return g;
}

// VTK's face as a corner loop (a pixel's corners are 0 1 3 2 in loop order) and its other nodes.
static std::vector<int> loop_of(vtkCell* f, int corners) {
  std::vector<int> v;
  for (int i = 0; i < f->GetNumberOfPoints(); ++i)
    v.push_back(int(f->GetPointId(i)));
  if (f->GetCellType() == 8) std::swap(v[2], v[3]);
  v.resize(size_t(corners));
  return v;
}

static void check_volume(const CellKind& k) {
  vtkNew<vtkGenericCell> g;
  vtkCell* c = make(g, k.vtk_type, k.nodes);
  EXPECT(c->GetNumberOfFaces() == k.face_count, "%s: %d faces, VTK %d", k.name, k.face_count, c->GetNumberOfFaces());
  for (int f = 0; f < k.face_count && f < c->GetNumberOfFaces(); ++f) {
    vtkCell* vf = c->GetFace(f);
    const int n = k.faces[f].size;
    const std::vector<int> loop = loop_of(vf, n);
    int rot = -1;
    for (int r = 0; r < n; ++r)
      if (loop[size_t(r)] == k.faces[f].corner[0]) rot = r;
    bool same = rot >= 0;
    for (int i = 0; same && i < n; ++i)
      same = loop[size_t((rot + i) % n)] == k.faces[f].corner[i];
    EXPECT(same, "%s face %d: corners differ from VTK's", k.name, f);
    // VTK's second-order face: corners, then the node of each edge in loop order, then the
    // centre; a quadratic-linear quad (30) has nodes on its edges 0 and 2 only.
    for (int e = 0; same && e < n && vf->GetNumberOfPoints() > n; ++e) {
      const int ve = (e + rot) % n; // VTK's edge index for our edge e
      const int ours = cell_edge_node(k, k.faces[f].corner[e], k.faces[f].corner[(e + 1) % n]);
      const int slot = vf->GetCellType() == 30 ? (ve == 0 ? 4 : ve == 2 ? 5 : -1) : n + ve;
      const int theirs = slot >= 0 && slot < vf->GetNumberOfPoints() ? int(vf->GetPointId(slot)) : -1;
      EXPECT(ours == theirs, "%s face %d edge %d: node %d, VTK %d", k.name, f, e, ours, theirs);
    }
    const int centre = vf->GetNumberOfPoints() == 2 * n + 1 ? int(vf->GetPointId(2 * n)) : -1;
    EXPECT(k.faces[f].centre == centre, "%s face %d: centre %d, VTK %d", k.name, f, k.faces[f].centre, centre);
    if (vf->GetNumberOfPoints() == n)
      for (int e = 0; e < n; ++e)
        EXPECT(cell_edge_node(k, k.faces[f].corner[e], k.faces[f].corner[(e + 1) % n]) < 0, "%s: node on a linear face",
               k.name);
  }
}

static void check_surface(const CellKind& k) {
  vtkNew<vtkGenericCell> g;
  vtkCell* c = make(g, k.vtk_type, k.nodes);
  for (int e = 0; e < c->GetNumberOfEdges(); ++e) {
    vtkCell* ve = c->GetEdge(e);
    const int a = int(ve->GetPointId(0)), b = int(ve->GetPointId(1));
    const int theirs = ve->GetNumberOfPoints() > 2 ? int(ve->GetPointId(2)) : -1;
    EXPECT(cell_edge_node(k, a, b) == theirs, "%s edge %d-%d: node %d, VTK %d", k.name, a, b, cell_edge_node(k, a, b),
           theirs);
  }
}

int main() {
  int checked = 0;
  for (int t = 0; t < 100; ++t) {
    const CellKind* k = cell_kind(t);
    if (!k || k->nodes < 0) continue;
    if (k->role == CellRole::Volume) check_volume(*k), checked++;
    if (k->role == CellRole::Surface) check_surface(*k), checked++;
  }
  EXPECT(checked == 20, "%d cell types checked", checked);
  std::printf("%d cell types checked, %d failures\n", checked, g_failed);
  return g_failed ? 1 : 0;
}
