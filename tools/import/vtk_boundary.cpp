// vtk_boundary.cpp -- the boundary of a volume mesh (docs/vtk.md section 4): every face of every
// volume cell is keyed by its sorted corner ids; a key seen once is a boundary face, twice an
// interior face (dropped), three or more times non-manifold (kept once). Each cell's faces are
// oriented by the sign of the cell's volume (divergence theorem over our face table), so an
// inverted cell still gives outward faces. Faces come out in cell order (deterministic).
// A linear cell with repeated corners (a hexahedron written for a wedge, pyramid or tetra) is
// the solid it collapses to: its faces lose repeated consecutive corners, and faces left with
// fewer than 3 corners vanish; its volume is the collapsed solid's, since the fan triangles of a
// collapsed face that repeat a corner contribute exactly 0.
#include "vtk_boundary.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "import_error.hpp"
#include "vtk_cells.hpp"

namespace tlod_import_detail {
namespace {

constexpr uint32_t kNone = TLOD_NO_NODE;

struct FaceRef {
  uint32_t cell;
  uint8_t face, flip, keep;
};

// A face's sorted corners packed into two words (a triangle's 4th corner is kNone), compared as
// one 128-bit number, then by reference so that runs list their faces in cell order.
struct FaceKey {
  uint64_t hi, lo;
  uint32_t ref;
  bool operator<(const FaceKey& o) const { return hi != o.hi ? hi < o.hi : lo != o.lo ? lo < o.lo : ref < o.ref; }
  bool same_face(const FaceKey& o) const { return hi == o.hi && lo == o.lo; }
};

int corner_count(const CellKind& k) {
  int n = 0;
  for (int f = 0; f < k.face_count; ++f)
    for (int i = 0; i < k.faces[f].size; ++i)
      n = std::max(n, k.faces[f].corner[i] + 1);
  return n;
}

bool repeats(const uint32_t* ids, int n) {
  for (int i = 1; i < n; ++i)
    for (int j = 0; j < i; ++j)
      if (ids[i] == ids[j]) return true;
  return false;
}

// A second-order cell must not repeat any of its nodes: a node on a corner would be a face node
// equal to a corner (core refuses it), and collapsed nodes no longer define an isoparametric map.
bool degenerate_second_order(const CellKind& k, const uint32_t* ids) {
  std::array<uint32_t, 32> s{};
  std::copy(ids, ids + k.nodes, s.begin());
  std::sort(s.begin(), s.begin() + k.nodes);
  return std::adjacent_find(s.begin(), s.begin() + k.nodes) != s.begin() + k.nodes;
}

// Face lc (n local corners) with repeated consecutive corners (cyclically) merged into out:
// the corner count left, or 0 when fewer than 3 are left or a corner still repeats (a face of
// no area, folded on itself).
int collapse_face(const uint32_t* id, const int* lc, int n, int* out) {
  int m = 0;
  for (int i = 0; i < n; ++i)
    if (id[lc[i]] != id[lc[(i + 1) % n]]) out[m++] = lc[i];
  for (int i = 1; i < m; ++i)
    for (int j = 0; j < i; ++j)
      if (id[out[i]] == id[out[j]]) return 0;
  return m < 3 ? 0 : m;
}

// Insertion sort of a face's n <= 4 corner ids (std::sort of a run of unknown length inside a
// 4-array trips GCC's -Warray-bounds).
void sort_corners(std::array<uint32_t, 4>& v, int n) {
  for (int i = 1; i < n && i < 4; ++i)
    for (int j = i; j > 0 && v[j - 1] > v[j]; --j)
      std::swap(v[j - 1], v[j]);
}

// A collapsed cell of no volume: |6V| within rounding of the cube of its extent.
bool flat(double v6, const uint32_t* ids, int corners, const double* p) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (int i = 0; i < corners; ++i)
    for (int a = 0; a < 3; ++a)
      lo[a] = std::min(lo[a], p[3 * size_t(ids[i]) + a]), hi[a] = std::max(hi[a], p[3 * size_t(ids[i]) + a]);
  const double ext = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  return !(std::fabs(v6) > 1e-12 * ext * ext * ext);
}

// Six times the signed volume of a cell, by the divergence theorem over its faces (fans),
// relative to its first corner so that large coordinates do not cancel.
double volume6(const CellKind& k, const uint32_t* ids, const double* p) {
  const double* o = p + 3 * size_t(ids[0]);
  double v = 0;
  for (int f = 0; f < k.face_count; ++f) {
    const CellFace& cf = k.faces[f];
    const double* a = p + 3 * size_t(ids[cf.corner[0]]);
    for (int i = 1; i + 1 < cf.size; ++i) {
      const double* b = p + 3 * size_t(ids[cf.corner[i]]);
      const double* c = p + 3 * size_t(ids[cf.corner[i + 1]]);
      const double ax = a[0] - o[0], ay = a[1] - o[1], az = a[2] - o[2];
      const double bx = b[0] - o[0], by = b[1] - o[1], bz = b[2] - o[2];
      const double cx = c[0] - o[0], cy = c[1] - o[1], cz = c[2] - o[2];
      v += ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx);
    }
  }
  return v;
}

class Extractor {
public:
  Extractor(const CellList& c, const double* p, const SurfaceHooks& h, Surface& o)
      : cells_(c), points_(p), hooks_(h), out_(o) {}

  void run() {
    collect();
    classify();
    emit();
  }

private:
  const CellList& cells_;
  const double* points_;
  const SurfaceHooks& hooks_;
  Surface& out_;
  std::vector<FaceRef> refs_;
  std::vector<FaceKey> keys_;
  std::array<const CellKind*, 256> kinds_{};
  std::array<int, 256> corners_{};

  const CellKind& kind(uint32_t cell) {
    const int t = cells_.types[cell];
    if (!kinds_[t]) {
      const CellKind* k = cell_kind(t);
      if (!k) fail(TLOD_ERROR_UNSUPPORTED, format("cell %u: unknown cell type %d", cell, t));
      kinds_[t] = k;
      corners_[t] = corner_count(*k);
    }
    return *kinds_[t];
  }

  uint32_t count(uint32_t cell) const { return uint32_t(cells_.offsets[cell + 1] - cells_.offsets[cell]); }
  const uint32_t* ids(uint32_t cell) const { return cells_.conn.data() + cells_.offsets[cell]; }

  void check(uint32_t cell, const CellKind& k) {
    if (k.role == CellRole::Unsupported)
      fail(TLOD_ERROR_UNSUPPORTED, format("cell %u (%s): unsupported cell type %d", cell, k.name, k.vtk_type));
    const uint32_t n = count(cell);
    if (k.nodes >= 0 && n != uint32_t(k.nodes))
      fail(TLOD_ERROR_INVALID_MESH, format("cell %u (%s): %u points, expected %d", cell, k.name, n, k.nodes));
  }

  // Pass 1: validate every cell; faces of volume cells, oriented, into refs_ and keys_.
  void collect() {
    size_t faces = 0;
    for (uint32_t c = 0; c < cells_.size(); ++c) {
      const CellKind& k = kind(c);
      check(c, k);
      out_.type_counts[k.vtk_type]++;
      if (k.role == CellRole::Volume) faces += size_t(k.face_count);
    }
    hooks_.take(faces * (sizeof(FaceRef) + 2 * sizeof(FaceKey)), "boundary extraction");
    refs_.reserve(faces);
    keys_.reserve(faces);
    for (uint32_t c = 0; c < cells_.size(); ++c) {
      if ((c & 0xffff) == 0) hooks_.progress(0.5 * c / double(cells_.size()));
      const CellKind& k = kind(c);
      if (k.role == CellRole::Volume) add_volume(c, k);
    }
  }

  // Corners of face f of cell c with repeats merged (collapse_face), into lc; their count or 0.
  int face_corners(uint32_t c, const CellKind& k, int f, int* lc) const {
    const CellFace& cf = k.faces[f];
    int given[4];
    std::copy(cf.corner, cf.corner + cf.size, given);
    return collapse_face(ids(c), given, cf.size, lc);
  }

  // A cell with repeated ids is kept when linear and what it collapses to is a solid.
  bool keep_volume(uint32_t c, const CellKind& k, double v6) {
    const uint32_t* id = ids(c);
    if (!repeats(id, corners_[k.vtk_type])) return true;
    int faces = 0, lc[4];
    for (int f = 0; f < k.face_count; ++f)
      faces += face_corners(c, k, f, lc) > 0;
    if (faces < 4 || flat(v6, id, corners_[k.vtk_type], points_)) {
      out_.degenerate_cells++;
      return false;
    }
    out_.cells_collapsed++;
    return true;
  }

  void add_volume(uint32_t c, const CellKind& k) {
    const uint32_t* id = ids(c);
    if (k.edge_node_count && degenerate_second_order(k, id)) {
      out_.degenerate_cells++;
      return;
    }
    const double v6 = volume6(k, id, points_);
    if (!keep_volume(c, k, v6)) return;
    out_.volume_cells++;
    const bool flip = v6 < 0;
    out_.cells_reoriented += flip;
    for (int f = 0; f < k.face_count; ++f) {
      int lc[4];
      const int n = face_corners(c, k, f, lc);
      if (n == 0) continue;
      std::array<uint32_t, 4> v{kNone, kNone, kNone, kNone};
      for (int i = 0; i < n; ++i)
        v[i] = id[lc[i]];
      sort_corners(v, n);
      keys_.push_back({uint64_t(v[0]) << 32 | v[1], uint64_t(v[2]) << 32 | v[3], uint32_t(refs_.size())});
      refs_.push_back({c, uint8_t(f), uint8_t(flip), 0});
    }
  }

  // Runs of equal keys: 1 boundary, 2 interior, 3+ non-manifold (the first kept).
  void classify() {
    std::sort(keys_.begin(), keys_.end());
    hooks_.progress(0.75);
    for (size_t i = 0; i < keys_.size();) {
      size_t j = i + 1;
      while (j < keys_.size() && keys_[j].same_face(keys_[i]))
        ++j;
      if (j - i == 2) out_.interior_faces++;
      if (j - i > 2) out_.non_manifold_faces++;
      if (j - i != 2) refs_[keys_[i].ref].keep = 1;
      i = j;
    }
    std::vector<FaceKey>().swap(keys_);
  }

  // One face: local corners lc (n of them), centre local node or -1.
  void face(uint32_t c, const CellKind& k, const int* lc, int n, int centre) {
    const uint32_t* id = ids(c);
    std::array<uint32_t, 5> nodes{kNone, kNone, kNone, kNone, kNone};
    bool curved = false;
    for (int e = 0; e < n; ++e) {
      out_.corners.push_back(id[lc[e]]);
      const int m = cell_edge_node(k, lc[e], lc[(e + 1) % n]);
      if (m >= 0) nodes[e] = id[m], curved = true;
    }
    if (centre >= 0) nodes[4] = id[centre], curved = true;
    out_.nodes.insert(out_.nodes.end(), nodes.begin(), nodes.end());
    out_.sizes.push_back(uint8_t(n));
    out_.second_order_faces += curved;
    (n == 3 ? out_.triangles : out_.quads)++;
  }

  // Face f as output: reversed when flip (same first corner), repeated corners merged.
  void table_face(uint32_t c, const CellKind& k, int f, bool flip) {
    const CellFace& cf = k.faces[f];
    int given[4], lc[4];
    for (int i = 0; i < cf.size; ++i)
      given[i] = cf.corner[flip && i ? cf.size - i : i];
    const int n = collapse_face(ids(c), given, cf.size, lc);
    if (n) face(c, k, lc, n, cf.centre);
  }

  void polygon(uint32_t c, const CellKind& k) {
    const int n = int(count(c));
    if (n < 3 || repeats(ids(c), n)) {
      out_.degenerate_cells++;
      return;
    }
    if (n <= 4) {
      const int lc[4] = {0, 1, 2, 3};
      return face(c, k, lc, n, -1);
    }
    out_.polygons_triangulated++;
    for (int i = 1; i + 1 < n; ++i) {
      const int lc[3] = {0, i, i + 1};
      face(c, k, lc, 3, -1);
    }
  }

  // Triangle i of a strip is (i, i+1, i+2), every other one reversed; the repeated-point
  // triangles strips use to turn corners are skipped.
  void strip(uint32_t c, const CellKind& k) {
    const uint32_t* id = ids(c);
    out_.strips_converted++;
    for (int i = 0; i + 2 < int(count(c)); ++i) {
      const int lc[3] = {i + (i & 1), i + 1 - (i & 1), i + 2};
      if (id[lc[0]] == id[lc[1]] || id[lc[1]] == id[lc[2]] || id[lc[0]] == id[lc[2]]) continue;
      face(c, k, lc, 3, -1);
    }
  }

  // A linear quad with a repeated corner is the triangle it collapses to.
  void surface_cell(uint32_t c, const CellKind& k) {
    const bool repeated = repeats(ids(c), k.faces[0].size);
    int lc[4];
    if (k.edge_node_count ? degenerate_second_order(k, ids(c)) : repeated && !face_corners(c, k, 0, lc)) {
      out_.degenerate_cells++;
      return;
    }
    out_.cells_collapsed += repeated;
    table_face(c, k, 0, false);
  }

  // Pass 2: faces in cell order.
  void emit() {
    size_t r = 0;
    for (uint32_t c = 0; c < cells_.size(); ++c) {
      if ((c & 0xffff) == 0) hooks_.progress(0.75 + 0.25 * c / double(cells_.size()));
      const CellKind& k = kind(c);
      switch (k.role) {
      case CellRole::Volume:
        for (; r < refs_.size() && refs_[r].cell == c; ++r)
          if (refs_[r].keep) table_face(c, k, refs_[r].face, refs_[r].flip);
        break;
      case CellRole::Surface:
        surface_cell(c, k);
        break;
      case CellRole::Polygon:
        polygon(c, k);
        break;
      case CellRole::Strip:
        strip(c, k);
        break;
      default:
        out_.cells_ignored++;
        break;
      }
    }
    hooks_.progress(1.0);
  }
};

} // namespace

void extract_surface(const CellList& cells, const double* points, const SurfaceHooks& hooks, Surface& out) {
  Extractor(cells, points, hooks, out).run();
}

} // namespace tlod_import_detail
