// gltf_import.cpp -- glTF 2.0 reader: a C shim over tinygltf (C++17, no exception leaves this file).
// Owned by the import/export layer (tools/import/).
//
// The file comes in through tlod_gltf::load and its accessors through
// tlod_gltf::Accessors (gltf_load.hpp: container, JSON, references, ranges,
// memory budget). tinygltf does not check that indices are in range, that
// node references exist or that the node graph is a tree, and it does not
// apply sparse accessors: that is done here, before any index is used.

#include <cerrno>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include "gltf_load.hpp"
#include "gltf_scene.hpp"
#include "import_error.hpp"
#include "import_internal.h"
#include "import_output.hpp"

namespace {

using tlod_import_detail::fail;
using tlod_import_detail::format;
using tlod_import_detail::ImportError;

using tlod_gltf::det3;
using tlod_gltf::identity;
using tlod_gltf::is_identity;
using tlod_gltf::Mat4;
using tlod_gltf::multiply;

// Upper 3x3 entry at (row, col).
double at(const Mat4& a, int row, int col) { return a.m[col * 4 + row]; }

// Normal matrix as the cofactor matrix times sign(det): it equals
// |det| * inverse-transpose, so the direction after renormalising is the
// same, and it still gives a usable normal when the matrix is singular.
void normal_matrix(const Mat4& a, double out[3][3]) {
  const double sign = det3(a) < 0.0 ? -1.0 : 1.0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const int r0 = (r + 1) % 3, r1 = (r + 2) % 3, c0 = (c + 1) % 3, c1 = (c + 2) % 3;
      out[r][c] = sign * (at(a, r0, c0) * at(a, r1, c1) - at(a, r0, c1) * at(a, r1, c0));
    }
}

// ---------------------------------------------------------------------------
// Output being built (normals are kept the size of positions).

struct Output : tlod_import_detail::OutputBase {
  uint32_t strips_fans_converted = 0;
  uint32_t primitives_skipped = 0;
};

// One mesh reached through the node hierarchy.
struct Instance {
  int node; // -1: mesh listed without nodes
  int mesh;
  Mat4 world;
};

// A primitive's data after reading, before it is appended.
struct PrimitiveData {
  std::vector<float> positions;
  std::vector<float> normals; // empty: none
  std::vector<uint32_t> triangles;
  tlod_gltf::Extras extras;
};

const char* mode_name(int mode) {
  static const char* const names[] = {"POINTS",    "LINES",          "LINE_LOOP",   "LINE_STRIP",
                                      "TRIANGLES", "TRIANGLE_STRIP", "TRIANGLE_FAN"};
  return mode >= 0 && mode <= 6 ? names[mode] : "unknown";
}

// ---------------------------------------------------------------------------

class Reader {
public:
  Reader(const tinygltf::Model& model, Output& out, _tlod_import_budget* budget, bool keep_scene)
      : m_(model), out_(out), acc_(model, budget), keep_scene_(keep_scene) {}

  void run() {
    check_required_extensions();
    acc_.check_buffer_views();
    joint_limits();
    acc_.take(m_.meshes.size(), sizeof(tlod_import_mesh), "meshes");
    for (size_t i = 0; i < m_.meshes.size(); ++i)
      out_.meshes.push_back(mesh_record(i));
    if (keep_scene_) {
      // Each mesh once, in mesh space: the nodes say where it goes.
      for (size_t i = 0; i < m_.meshes.size(); ++i)
        add_mesh_parts({-1, int(i), identity()});
    } else {
      for (const Instance& inst : collect_instances())
        add_mesh_parts(inst);
    }
    if (out_.parts.empty()) fail_nothing_imported();
    if (first_line_mode_ >= 0)
      out_.warn(format("%s: mode %d (%s) is not a surface: skipped (%u point/line primitive(s) "
                       "skipped in all)",
                       first_line_where_.c_str(), first_line_mode_, mode_name(first_line_mode_), lines_skipped_));
  }

private:
  const tinygltf::Model& m_;
  Output& out_;
  tlod_gltf::Accessors acc_;
  bool keep_scene_;
  std::vector<uint32_t> joint_limit_; // per mesh: fewest joints of a skin it is used with
  int first_line_mode_ = -1;          // first POINTS/LINES primitive seen, for the error
  std::string first_line_where_;
  uint32_t lines_skipped_ = 0;
  std::string first_skip_reason_;

  // -- scene graph ----------------------------------------------------------

  tlod_import_mesh mesh_record(size_t i) const {
    tlod_import_mesh r{};
    std::snprintf(r.name, sizeof r.name, "%s", m_.meshes[i].name.c_str());
    return r;
  }

  // JOINTS_0 of a mesh index the joints of every skin it is drawn with.
  void joint_limits() {
    joint_limit_.assign(m_.meshes.size(), 65536u);
    for (const tinygltf::Node& n : m_.nodes)
      if (n.skin >= 0 && n.mesh >= 0 && size_t(n.mesh) < m_.meshes.size()) {
        if (size_t(n.skin) >= m_.skins.size())
          fail(TLOD_ERROR_PARSE,
               format("node %d: skin %d does not exist (%zu skins)", int(&n - &m_.nodes[0]), n.skin, m_.skins.size()));
        const size_t j = m_.skins[size_t(n.skin)].joints.size();
        if (j < joint_limit_[size_t(n.mesh)]) joint_limit_[size_t(n.mesh)] = uint32_t(j);
      }
  }

  // The first instance of a mesh names its parts in meshes[] (flattened mode).
  void add_mesh_parts(const Instance& inst) {
    tlod_import_mesh& rec = out_.meshes[size_t(inst.mesh)];
    const size_t first = out_.parts.size();
    add_instance(inst);
    if (rec.part_count == 0) {
      rec.first_part = uint32_t(first);
      rec.part_count = uint32_t(out_.parts.size() - first);
    }
  }

  void check_required_extensions() const {
    for (const std::string& e : m_.extensionsRequired) {
      if (e == "KHR_draco_mesh_compression" || e == "EXT_meshopt_compression")
        fail(TLOD_ERROR_UNSUPPORTED, format("requires extension %s, which this importer does not support", e.c_str()));
    }
  }

  std::vector<int> root_nodes() const {
    if (!m_.scenes.empty()) {
      // tinygltf stores -1 when "scene" is absent: glTF says use scene 0 then.
      const int s = m_.defaultScene == -1 ? 0 : m_.defaultScene;
      if (s < 0 || size_t(s) >= m_.scenes.size())
        fail(TLOD_ERROR_PARSE, format("default scene %d does not exist (%zu scenes)", s, m_.scenes.size()));
      return m_.scenes[size_t(s)].nodes;
    }
    // No scenes: every node that is nobody's child.
    std::vector<char> is_child(m_.nodes.size(), 0);
    for (size_t i = 0; i < m_.nodes.size(); ++i)
      for (int c : m_.nodes[i].children)
        if (c >= 0 && size_t(c) < m_.nodes.size()) is_child[size_t(c)] = 1;
    std::vector<int> roots;
    for (size_t i = 0; i < m_.nodes.size(); ++i)
      if (!is_child[i]) roots.push_back(int(i));
    return roots;
  }

  // Depth-first with an explicit stack (a deep hierarchy must not overflow
  // the C stack); each node may be reached once, which also stops cycles and
  // exponential re-instancing through shared children.
  std::vector<Instance> collect_instances() const {
    std::vector<Instance> instances;
    if (m_.scenes.empty() && m_.nodes.empty()) {
      for (size_t i = 0; i < m_.meshes.size(); ++i)
        instances.push_back({-1, int(i), identity()});
      return instances;
    }
    struct Item {
      int node, parent;
      Mat4 world;
    };
    std::vector<Item> stack;
    const std::vector<int> roots = root_nodes();
    for (size_t i = roots.size(); i-- > 0;)
      stack.push_back({roots[i], -1, identity()});
    std::vector<char> visited(m_.nodes.size(), 0);
    while (!stack.empty()) {
      const Item item = stack.back();
      stack.pop_back();
      check_node_ref(item.node, item.parent);
      if (visited[size_t(item.node)])
        fail(TLOD_ERROR_PARSE, format("node %d is reached twice (the node hierarchy must be a tree)", item.node));
      visited[size_t(item.node)] = 1;
      const tinygltf::Node& n = m_.nodes[size_t(item.node)];
      const Mat4 world = multiply(item.world, tlod_gltf::local_matrix(m_, item.node));
      if (n.mesh != -1) instances.push_back(make_instance(item.node, world));
      for (size_t i = n.children.size(); i-- > 0;)
        stack.push_back({n.children[i], item.node, world});
    }
    return instances;
  }

  void check_node_ref(int node, int parent) const {
    if (node >= 0 && size_t(node) < m_.nodes.size()) return;
    if (parent < 0) fail(TLOD_ERROR_PARSE, format("scene node %d does not exist (%zu nodes)", node, m_.nodes.size()));
    fail(TLOD_ERROR_PARSE, format("node %d: child %d does not exist (%zu nodes)", parent, node, m_.nodes.size()));
  }

  Instance make_instance(int node, const Mat4& world) const {
    const tinygltf::Node& n = m_.nodes[size_t(node)];
    if (n.mesh < 0 || size_t(n.mesh) >= m_.meshes.size())
      fail(TLOD_ERROR_PARSE, format("node %d: mesh %d does not exist (%zu meshes)", node, n.mesh, m_.meshes.size()));
    if (n.skin >= 0 && !keep_scene_) {
      // glTF: a skinned mesh ignores its node's transform; without posing
      // the joints the mesh-space positions are the bind pose.
      out_.warn(format("node %d: skinned mesh %d imported in its bind pose", node, n.mesh));
      return {node, n.mesh, identity()};
    }
    return {node, n.mesh, world};
  }

  // -- primitives -----------------------------------------------------------

  void add_instance(const Instance& inst) {
    const tinygltf::Mesh& mesh = m_.meshes[size_t(inst.mesh)];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& prim = mesh.primitives[p];
      const std::string where = format("mesh %d primitive %zu", inst.mesh, p);
      if (prim.mode >= TINYGLTF_MODE_POINTS && prim.mode <= TINYGLTF_MODE_LINE_STRIP) {
        skip_line_primitive(where, prim.mode);
        continue;
      }
      if (prim.mode < TINYGLTF_MODE_TRIANGLES || prim.mode > TINYGLTF_MODE_TRIANGLE_FAN)
        fail(TLOD_ERROR_PARSE, format("%s: mode %d is not a glTF primitive mode", where.c_str(), prim.mode));
      add_primitive(inst, int(p), prim, where);
    }
  }

  void skip_line_primitive(const std::string& where, int mode) {
    if (first_line_mode_ < 0) {
      first_line_mode_ = mode;
      first_line_where_ = where;
    }
    lines_skipped_++;
    out_.primitives_skipped++;
  }

  void skip_primitive(const std::string& where, const char* reason) {
    const std::string w = format("%s: skipped: %s", where.c_str(), reason);
    if (first_skip_reason_.empty()) first_skip_reason_ = w;
    out_.warn(w);
    out_.primitives_skipped++;
  }

  // With nothing imported, the first warning (e.g. "BOM skipped") is often
  // the explanation: it goes into the message.
  [[noreturn]] void fail_nothing_imported() const {
    const std::string note = out_.warnings.empty() ? "" : "; " + out_.warnings.substr(0, out_.warnings.find('\n'));
    fail_nothing_imported_note(note);
  }

  [[noreturn]] void fail_nothing_imported_note(const std::string& note) const {
    if (first_line_mode_ >= 0)
      fail(TLOD_ERROR_UNSUPPORTED, format("%s: mode %d (%s) is not a surface, and the file has no triangle primitives",
                                          first_line_where_.c_str(), first_line_mode_, mode_name(first_line_mode_)));
    if (!first_skip_reason_.empty())
      fail(TLOD_ERROR_INVALID_MESH, format("no triangles to import (%s)", first_skip_reason_.c_str()));
    fail(TLOD_ERROR_INVALID_MESH, format("no triangle primitives to import (%zu meshes, %zu nodes, %zu scenes)%s",
                                         m_.meshes.size(), m_.nodes.size(), m_.scenes.size(), note.c_str()));
  }

  void add_primitive(const Instance& inst, int p, const tinygltf::Primitive& prim, const std::string& where) {
    const auto pos = prim.attributes.find("POSITION");
    if (pos == prim.attributes.end()) {
      skip_primitive(where, "no POSITION attribute");
      return;
    }
    const size_t vcount = check_attribute_counts(prim, where, pos->second);
    PrimitiveData data;
    data.positions = acc_.read_floats(pos->second, where + ": POSITION", 3);
    check_finite(data.positions, pos->second, where);
    data.normals = read_normals(prim, where, vcount);
    data.extras = tlod_gltf::read_extras(m_, acc_, prim, where, joint_limit_[size_t(inst.mesh)], out_);
    std::vector<uint32_t> idx = read_indices(prim, where, vcount);
    data.triangles = triangulate(prim.mode, std::move(idx), where);
    if (data.triangles.empty()) {
      skip_primitive(where, "no complete triangle");
      return;
    }
    append(inst, p, prim, data, where);
  }

  // glTF: every attribute of a primitive has the same count.
  size_t check_attribute_counts(const tinygltf::Primitive& prim, const std::string& where, int position) const {
    acc_.check_ref(position, where + ": POSITION");
    const size_t count = m_.accessors[size_t(position)].count;
    for (const auto& attr : prim.attributes) {
      acc_.check_ref(attr.second, where + ": " + attr.first);
      const size_t c = m_.accessors[size_t(attr.second)].count;
      if (c != count)
        fail(TLOD_ERROR_PARSE, format("%s: %s accessor %d has %zu elements, POSITION accessor %d has %zu",
                                      where.c_str(), attr.first.c_str(), attr.second, c, position, count));
    }
    if (count == 0) fail(TLOD_ERROR_PARSE, format("%s: POSITION accessor %d has no elements", where.c_str(), position));
    if (count > _TLOD_IMPORT_MAX_VERTICES)
      fail(TLOD_ERROR_UNSUPPORTED, format("%s: POSITION accessor %d has %zu elements (at most %zu)", where.c_str(),
                                          position, count, size_t(_TLOD_IMPORT_MAX_VERTICES)));
    return count;
  }

  void check_finite(const std::vector<float>& p, int accessor, const std::string& where) const {
    for (size_t i = 0; i < p.size(); i += 3)
      if (!std::isfinite(p[i]) || !std::isfinite(p[i + 1]) || !std::isfinite(p[i + 2]))
        fail(TLOD_ERROR_INVALID_MESH,
             format("%s: POSITION accessor %d element %zu is not finite (%g, %g, %g)", where.c_str(), accessor, i / 3,
                    double(p[i]), double(p[i + 1]), double(p[i + 2])));
  }

  std::vector<float> read_normals(const tinygltf::Primitive& prim, const std::string& where, size_t vcount) {
    const auto it = prim.attributes.find("NORMAL");
    if (it == prim.attributes.end()) return {};
    const tinygltf::Accessor& a = m_.accessors[size_t(it->second)];
    if (a.type != TINYGLTF_TYPE_VEC3 || a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
      // Normals can be recomputed, so a bad format costs shading, not the mesh.
      out_.warn(format("%s: NORMAL accessor %d is %s %s, not float VEC3: normals ignored", where.c_str(), it->second,
                       tlod_gltf::component_name(a.componentType), tlod_gltf::type_name(a.type)));
      return {};
    }
    std::vector<float> n = acc_.read_floats(it->second, where + ": NORMAL", 3);
    if (n.size() != vcount * 3) return {}; // cannot happen: counts were checked
    return n;
  }

  std::vector<uint32_t> read_indices(const tinygltf::Primitive& prim, const std::string& where, size_t vcount) const {
    std::vector<uint32_t> idx;
    if (prim.indices < 0) {
      acc_.take(vcount, 4, where + ": implicit indices");
      idx.resize(vcount);
      for (size_t i = 0; i < vcount; ++i)
        idx[i] = uint32_t(i);
      return idx;
    }
    idx = acc_.read_indices(prim.indices, where);
    for (size_t i = 0; i < idx.size(); ++i)
      if (idx[i] >= vcount)
        fail(TLOD_ERROR_INVALID_MESH,
             format("%s: indices accessor %d element %zu: index %u out of range (%zu vertices)", where.c_str(),
                    prim.indices, i, idx[i], vcount));
    return idx;
  }

  // TRIANGLES: whole triangles (trailing indices dropped with a warning);
  // STRIP and FAN: the glTF 2.0 spec's vertex order, which keeps winding.
  std::vector<uint32_t> triangulate(int mode, std::vector<uint32_t> idx, const std::string& where) {
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      if (idx.size() % 3 != 0) {
        out_.warn(format("%s: %zu indices is not a multiple of 3: last %zu dropped", where.c_str(), idx.size(),
                         idx.size() % 3));
        idx.resize(idx.size() - idx.size() % 3);
      }
      return idx;
    }
    out_.strips_fans_converted++;
    std::vector<uint32_t> tris;
    if (idx.size() < 3) return tris;
    acc_.take(idx.size() - 2, 12, where + ": triangles");
    tris.reserve((idx.size() - 2) * 3);
    for (size_t i = 0; i + 2 < idx.size(); ++i) {
      if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        const size_t odd = i % 2;
        tris.insert(tris.end(), {idx[i], idx[i + 1 + odd], idx[i + 2 - odd]});
      } else {
        tris.insert(tris.end(), {idx[i + 1], idx[i + 2], idx[0]});
      }
    }
    return tris;
  }

  // -- output ---------------------------------------------------------------

  void append(const Instance& inst, int p, const tinygltf::Primitive& prim, const PrimitiveData& d,
              const std::string& where) {
    const size_t first_vertex = out_.positions.size() / 3;
    const size_t vcount = d.positions.size() / 3;
    if (first_vertex + vcount > _TLOD_IMPORT_MAX_VERTICES ||
        out_.indices.size() + d.triangles.size() > _TLOD_IMPORT_MAX_INDICES)
      fail(TLOD_ERROR_UNSUPPORTED, format("%s: the scene has more than %zu vertices or %zu indices", where.c_str(),
                                          size_t(_TLOD_IMPORT_MAX_VERTICES), size_t(_TLOD_IMPORT_MAX_INDICES)));
    // Output arrays grow by doubling: what they hold, plus what they move.
    acc_.take(vcount, 3 * 24, where + ": output vertices");
    acc_.take(d.triangles.size(), 3 * 4, where + ": output indices");
    tlod_import_part part{};
    part_name(inst, p, part.name);
    part.first_vertex = uint32_t(first_vertex);
    part.vertex_count = uint32_t(vcount);
    part.first_face = uint32_t(out_.indices.size() / 3);
    part.face_count = uint32_t(d.triangles.size() / 3);
    part.had_normals = !d.normals.empty();
    part.mesh = uint32_t(inst.mesh);
    part.node = inst.node >= 0 ? uint32_t(inst.node) : TLOD_IMPORT_NONE;
    part.material =
        prim.material >= 0 && size_t(prim.material) < m_.materials.size() ? uint32_t(prim.material) : TLOD_IMPORT_NONE;
    base_color(prim, where, part.base_color);
    append_vertices(inst, d, where);
    append_triangles(inst, d.triangles, uint32_t(first_vertex));
    append_extras(d.extras, first_vertex, vcount, where);
    out_.parts.push_back(part);
  }

  // Attributes are per vertex, not per node: an instance copies them unchanged.
  void append_extras(const tlod_gltf::Extras& e, size_t first_vertex, size_t vcount, const std::string& where) {
    for (const tlod_gltf::Extras::Attr& a : e.attributes) {
      acc_.take(vcount, 8u * a.components, where + ": output " + a.name);
      out_.add_attribute(a.name, a.components, first_vertex, a.data);
    }
    if (!e.joints.empty()) {
      acc_.take(vcount, 2 * 24, where + ": output joints and weights");
      out_.add_skin_weights(first_vertex, e.joints, e.weights);
      out_.weights_renormalised += e.renormalised;
    }
    out_.pad_attributes();
  }

  void append_vertices(const Instance& inst, const PrimitiveData& d, const std::string& where) {
    if (is_identity(inst.world)) {
      // Bitwise pass-through: no rounding through double.
      out_.positions.insert(out_.positions.end(), d.positions.begin(), d.positions.end());
      if (d.normals.empty())
        out_.normals.resize(out_.positions.size(), 0.0f);
      else
        out_.normals.insert(out_.normals.end(), d.normals.begin(), d.normals.end());
    } else {
      transform_positions(inst.world, d.positions, where);
      transform_normals(inst.world, d.normals, d.positions.size());
    }
    if (!d.normals.empty()) out_.any_normals = true;
  }

  void transform_positions(const Mat4& w, const std::vector<float>& p, const std::string& where) {
    for (size_t i = 0; i < p.size(); i += 3) {
      const double x = p[i], y = p[i + 1], z = p[i + 2];
      for (int r = 0; r < 3; ++r) {
        const double v = w.m[r] * x + w.m[4 + r] * y + w.m[8 + r] * z + w.m[12 + r];
        const float f = float(v);
        if (!std::isfinite(f))
          fail(TLOD_ERROR_INVALID_MESH,
               format("%s: vertex %zu is not finite after the node transform", where.c_str(), i / 3));
        out_.positions.push_back(f);
      }
    }
  }

  void transform_normals(const Mat4& w, const std::vector<float>& n, size_t count) {
    if (n.empty()) {
      out_.normals.resize(out_.normals.size() + count, 0.0f);
      return;
    }
    double nm[3][3];
    normal_matrix(w, nm);
    for (size_t i = 0; i < n.size(); i += 3) {
      double v[3];
      for (int r = 0; r < 3; ++r)
        v[r] = nm[r][0] * n[i] + nm[r][1] * n[i + 1] + nm[r][2] * n[i + 2];
      const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      // Zero or non-finite: stored as zero, which core recomputes.
      const bool ok = len > 0.0 && std::isfinite(len);
      for (int r = 0; r < 3; ++r)
        out_.normals.push_back(ok ? float(v[r] / len) : 0.0f);
    }
  }

  // A mirroring transform turns counter-clockwise faces clockwise: swap two
  // corners to keep them front-facing.
  void append_triangles(const Instance& inst, const std::vector<uint32_t>& t, uint32_t base) {
    const bool flip = det3(inst.world) < 0.0;
    for (size_t i = 0; i < t.size(); i += 3) {
      out_.indices.push_back(base + t[i]);
      out_.indices.push_back(base + (flip ? t[i + 2] : t[i + 1]));
      out_.indices.push_back(base + (flip ? t[i + 1] : t[i + 2]));
    }
  }

  void part_name(const Instance& inst, int p, char name[64]) const {
    const tinygltf::Mesh& mesh = m_.meshes[size_t(inst.mesh)];
    std::string s;
    if (inst.node >= 0 && !m_.nodes[size_t(inst.node)].name.empty())
      s = m_.nodes[size_t(inst.node)].name;
    else if (!mesh.name.empty())
      s = mesh.name;
    else
      s = format("mesh %d", inst.mesh);
    if (mesh.primitives.size() > 1) s += format("/%d", p);
    std::snprintf(name, 64, "%s", s.c_str());
  }

  void base_color(const tinygltf::Primitive& prim, const std::string& where, float c[4]) {
    c[0] = c[1] = c[2] = c[3] = 1.0f;
    if (prim.material < 0) return;
    if (size_t(prim.material) >= m_.materials.size()) {
      out_.warn(format("%s: material %d does not exist: default colour used", where.c_str(), prim.material));
      return;
    }
    const std::vector<double>& f = m_.materials[size_t(prim.material)].pbrMetallicRoughness.baseColorFactor;
    if (f.size() == 4)
      for (int i = 0; i < 4; ++i)
        c[i] = float(f[size_t(i)]);
  }
};

// The base shape is imported; the caller is told which meshes lose their targets.
void warn_morph_targets(const tinygltf::Model& model, Output& out) {
  for (size_t i = 0; i < model.meshes.size(); ++i)
    for (const tinygltf::Primitive& prim : model.meshes[i].primitives)
      if (!prim.targets.empty()) {
        out.warn(
            format("mesh %zu '%.64s': morph targets ignored (base shape imported)", i, model.meshes[i].name.c_str()));
        break;
      }
}

// Everything besides geometry, after it (texture coordinates resolve against the attributes made).
void read_scene(const _tlod_import_job* job, const tinygltf::Model& model, const tlod_gltf::DataImages& images,
                Output& out) {
  const tlod_gltf::Accessors acc(model, job->budget);
  acc.take(model.nodes.size(), sizeof(tlod_import_node) + sizeof(Mat4) + 16, "nodes");
  tlod_gltf::read_nodes(model, out);
  acc.take(model.materials.size() + model.textures.size(), sizeof(tlod_import_material), "materials");
  tlod_gltf::read_materials(model, out);
  tlod_gltf::resolve_texcoords(out);
  tlod_gltf::read_skins(model, acc, out);
  tlod_gltf::read_animations(model, acc, out);
  tlod_gltf::read_images(model, acc, job->folder, job->budget, images, out);
}

tlod_result finish(const _tlod_import_job* job, Output& out) {
  _tlod_import_data d{};
  out.fill(d);
  d.face_count = uint32_t(out.indices.size() / 3);
  d.strips_fans_converted = out.strips_fans_converted;
  d.primitives_skipped = out.primitives_skipped;
  return _tlod_import_finish(job, &d);
}

tlod_result import_gltf(const _tlod_import_job* job) {
  unsigned char* bytes = nullptr;
  size_t size = 0;
  const tlod_result res = _tlod_import_read_file(job, &bytes, &size);
  if (res != TLOD_SUCCESS) return res;
  const std::unique_ptr<unsigned char, void (*)(void*)> file(bytes, std::free);
  Output out;
  tinygltf::Model model;
  tlod_gltf::DataImages images;
  tlod_gltf::load(bytes, size, _tlod_str_ends_with_nocase(job->path, ".glb"), job->folder, job->budget, model, out,
                  &images);
  warn_morph_targets(model, out);
  Reader(model, out, job->budget, job->keep_scene).run();
  if (out.weights_renormalised)
    out.warn(format("WEIGHTS_0: %u vertices' weights summed within 2e-2 of 1 and were renormalised",
                    out.weights_renormalised));
  read_scene(job, model, images, out);
  return finish(job, out);
}

} // namespace

extern "C" tlod_result _tlod_import_gltf(const _tlod_import_job* job) {
  return tlod_import_detail::guarded(job, "glTF", [job] { return import_gltf(job); });
}
