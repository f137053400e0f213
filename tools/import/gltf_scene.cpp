// gltf_scene.cpp -- glTF nodes (rest pose), materials and textures for the scene importer (gltf_scene.hpp).
// Owned by the import/export layer.
#include <cmath>
#include <cstdio>
#include <cstring>

#include "gltf_scene.hpp"

namespace tlod_gltf {

using tlod_import_detail::fail;
using tlod_import_detail::format;
using tlod_import_detail::OutputBase;

Mat4 identity() {
  Mat4 r{};
  r.m[0] = r.m[5] = r.m[10] = r.m[15] = 1.0;
  return r;
}

bool is_identity(const Mat4& a) {
  const Mat4 i = identity();
  return std::memcmp(a.m, i.m, sizeof a.m) == 0;
}

Mat4 multiply(const Mat4& a, const Mat4& b) {
  Mat4 r{};
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) {
      double s = 0.0;
      for (int k = 0; k < 4; ++k)
        s += a.m[k * 4 + row] * b.m[c * 4 + k];
      r.m[c * 4 + row] = s;
    }
  return r;
}

namespace {

// Upper 3x3 entry at (row, col).
double at(const Mat4& a, int row, int col) { return a.m[col * 4 + row]; }

void check_size(int index, const char* what, size_t got, size_t want) {
  if (got != 0 && got != want)
    fail(TLOD_ERROR_PARSE, format("node %d: %s has %zu numbers (%zu expected)", index, what, got, want));
}

struct Trs {
  double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
};

// The node's TRS as written, rotation renormalised (a non-unit one would scale).
Trs node_trs(int index, const tinygltf::Node& n) {
  check_size(index, "translation", n.translation.size(), 3);
  check_size(index, "rotation", n.rotation.size(), 4);
  check_size(index, "scale", n.scale.size(), 3);
  Trs r;
  for (size_t i = 0; i < n.translation.size(); ++i)
    r.t[i] = n.translation[i];
  for (size_t i = 0; i < n.rotation.size(); ++i)
    r.q[i] = n.rotation[i];
  for (size_t i = 0; i < n.scale.size(); ++i)
    r.s[i] = n.scale[i];
  const double len = std::sqrt(r.q[0] * r.q[0] + r.q[1] * r.q[1] + r.q[2] * r.q[2] + r.q[3] * r.q[3]);
  if (!(len > 0.0) || !std::isfinite(len))
    fail(TLOD_ERROR_PARSE, format("node %d: rotation is not a unit quaternion", index));
  for (double& c : r.q)
    c /= len;
  return r;
}

// T * R * S with R from the unit quaternion.
Mat4 trs_matrix(const Trs& p) {
  const double x = p.q[0], y = p.q[1], z = p.q[2], w = p.q[3];
  const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                          {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                          {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
  Mat4 out = identity();
  for (int c = 0; c < 3; ++c)
    for (int row = 0; row < 3; ++row)
      out.m[c * 4 + row] = r[row][c] * p.s[c];
  for (int row = 0; row < 3; ++row)
    out.m[12 + row] = p.t[row];
  return out;
}

// Quaternion of a rotation matrix (Shepperd's method: the largest diagonal term first).
void quat_of(const double r[3][3], double q[4]) {
  const double tr = r[0][0] + r[1][1] + r[2][2];
  if (tr > 0) {
    const double s = 2 * std::sqrt(tr + 1);
    q[3] = s / 4, q[0] = (r[2][1] - r[1][2]) / s, q[1] = (r[0][2] - r[2][0]) / s, q[2] = (r[1][0] - r[0][1]) / s;
  } else if (r[0][0] > r[1][1] && r[0][0] > r[2][2]) {
    const double s = 2 * std::sqrt(1 + r[0][0] - r[1][1] - r[2][2]);
    q[3] = (r[2][1] - r[1][2]) / s, q[0] = s / 4, q[1] = (r[0][1] + r[1][0]) / s, q[2] = (r[0][2] + r[2][0]) / s;
  } else if (r[1][1] > r[2][2]) {
    const double s = 2 * std::sqrt(1 + r[1][1] - r[0][0] - r[2][2]);
    q[3] = (r[0][2] - r[2][0]) / s, q[0] = (r[0][1] + r[1][0]) / s, q[1] = s / 4, q[2] = (r[1][2] + r[2][1]) / s;
  } else {
    const double s = 2 * std::sqrt(1 + r[2][2] - r[0][0] - r[1][1]);
    q[3] = (r[1][0] - r[0][1]) / s, q[0] = (r[0][2] + r[2][0]) / s, q[1] = (r[1][2] + r[2][1]) / s, q[2] = s / 4;
  }
}

// TRS of a matrix node: exact for T * R * S matrices (a mirror goes into scale x); a
// sheared or singular matrix gets the nearest such reading, its `local` stays exact.
Trs decompose(const Mat4& a) {
  Trs p;
  double r[3][3];
  for (int c = 0; c < 3; ++c) {
    p.t[c] = a.m[12 + c];
    p.s[c] = std::sqrt(at(a, 0, c) * at(a, 0, c) + at(a, 1, c) * at(a, 1, c) + at(a, 2, c) * at(a, 2, c));
  }
  if (det3(a) < 0) p.s[0] = -p.s[0];
  for (int c = 0; c < 3; ++c)
    for (int row = 0; row < 3; ++row)
      r[row][c] = p.s[c] != 0 ? at(a, row, c) / p.s[c] : (row == c ? 1.0 : 0.0);
  quat_of(r, p.q);
  return p;
}

void store(const Mat4& m, float out[16]) {
  for (int i = 0; i < 16; ++i)
    out[i] = float(m.m[i]);
}

tlod_import_node make_node(const tinygltf::Model& m, int i, uint32_t parent) {
  const tinygltf::Node& n = m.nodes[size_t(i)];
  tlod_import_node r{};
  std::snprintf(r.name, sizeof r.name, "%s", n.name.c_str());
  r.parent = parent;
  r.mesh = n.mesh >= 0 && size_t(n.mesh) < m.meshes.size() ? uint32_t(n.mesh) : TLOD_IMPORT_NONE;
  r.skin = n.skin >= 0 && size_t(n.skin) < m.skins.size() ? uint32_t(n.skin) : TLOD_IMPORT_NONE;
  const Trs p = n.matrix.empty() ? node_trs(i, n) : decompose(local_matrix(m, i));
  for (int k = 0; k < 3; ++k)
    r.translation[k] = float(p.t[k]), r.scale[k] = float(p.s[k]);
  for (int k = 0; k < 4; ++k)
    r.rotation[k] = float(p.q[k]);
  store(local_matrix(m, i), r.local);
  return r;
}

// Parent of every node from the children lists; a second parent or a missing child is refused.
std::vector<uint32_t> parents_of(const tinygltf::Model& m) {
  std::vector<uint32_t> parent(m.nodes.size(), TLOD_IMPORT_NONE);
  for (size_t i = 0; i < m.nodes.size(); ++i)
    for (int c : m.nodes[i].children) {
      if (c < 0 || size_t(c) >= m.nodes.size())
        fail(TLOD_ERROR_PARSE, format("node %zu: child %d does not exist (%zu nodes)", i, c, m.nodes.size()));
      if (parent[size_t(c)] != TLOD_IMPORT_NONE || size_t(c) == i)
        fail(TLOD_ERROR_PARSE, format("node %d is reached twice (child of node %u and node %zu; the node hierarchy "
                                      "must be a tree)",
                                      c, parent[size_t(c)], i));
      parent[size_t(c)] = uint32_t(i);
    }
  return parent;
}

} // namespace

double det3(const Mat4& a) {
  return at(a, 0, 0) * (at(a, 1, 1) * at(a, 2, 2) - at(a, 1, 2) * at(a, 2, 1)) -
         at(a, 0, 1) * (at(a, 1, 0) * at(a, 2, 2) - at(a, 1, 2) * at(a, 2, 0)) +
         at(a, 0, 2) * (at(a, 1, 0) * at(a, 2, 1) - at(a, 1, 1) * at(a, 2, 0));
}

Mat4 local_matrix(const tinygltf::Model& m, int index) {
  const tinygltf::Node& n = m.nodes[size_t(index)];
  if (n.matrix.empty()) return trs_matrix(node_trs(index, n));
  if (n.matrix.size() != 16)
    fail(TLOD_ERROR_PARSE, format("node %d: matrix has %zu numbers (16 expected)", index, n.matrix.size()));
  Mat4 r{};
  for (int i = 0; i < 16; ++i)
    r.m[i] = n.matrix[size_t(i)];
  return r;
}

// Roots first, then children (explicit stack: a deep hierarchy must not overflow the C
// stack); a node never reached from a root is on a cycle.
void read_nodes(const tinygltf::Model& m, OutputBase& out) {
  const std::vector<uint32_t> parent = parents_of(m);
  out.nodes.resize(m.nodes.size());
  std::vector<Mat4> world(m.nodes.size());
  std::vector<char> done(m.nodes.size(), 0);
  std::vector<int> stack;
  for (size_t i = m.nodes.size(); i-- > 0;)
    if (parent[i] == TLOD_IMPORT_NONE) stack.push_back(int(i));
  while (!stack.empty()) {
    const int i = stack.back();
    stack.pop_back();
    const uint32_t p = parent[size_t(i)];
    world[size_t(i)] = p == TLOD_IMPORT_NONE ? local_matrix(m, i) : multiply(world[p], local_matrix(m, i));
    out.nodes[size_t(i)] = make_node(m, i, p);
    store(world[size_t(i)], out.nodes[size_t(i)].world);
    done[size_t(i)] = 1;
    for (size_t c = m.nodes[size_t(i)].children.size(); c-- > 0;)
      stack.push_back(m.nodes[size_t(i)].children[c]);
  }
  for (size_t i = 0; i < m.nodes.size(); ++i)
    if (!done[i])
      fail(TLOD_ERROR_PARSE, format("node %zu is on a cycle of children (the node hierarchy must be a tree)", i));
}

namespace {

tlod_import_alpha_mode alpha_mode(const tinygltf::Material& mat, size_t i, OutputBase& out) {
  if (mat.alphaMode.empty() || mat.alphaMode == "OPAQUE") return TLOD_IMPORT_ALPHA_OPAQUE;
  if (mat.alphaMode == "MASK") return TLOD_IMPORT_ALPHA_MASK;
  if (mat.alphaMode == "BLEND") return TLOD_IMPORT_ALPHA_BLEND;
  out.warn(
      format("material %zu: alphaMode '%.32s' is not OPAQUE, MASK or BLEND: OPAQUE used", i, mat.alphaMode.c_str()));
  return TLOD_IMPORT_ALPHA_OPAQUE;
}

// A factor of [0, 1] (glTF's range), clamped; a non-finite one: the glTF default 1.
float unit_factor(double f) { return std::isfinite(f) ? float(std::fmin(std::fmax(f, 0.0), 1.0)) : 1.0f; }

tlod_import_material make_material(const tinygltf::Model& m, size_t i, OutputBase& out) {
  const tinygltf::Material& mat = m.materials[i];
  tlod_import_material r{};
  std::snprintf(r.name, sizeof r.name, "%s", mat.name.c_str());
  const std::vector<double>& f = mat.pbrMetallicRoughness.baseColorFactor;
  for (int k = 0; k < 4; ++k)
    r.base_color[k] = f.size() == 4 ? float(f[size_t(k)]) : 1.0f;
  const tinygltf::TextureInfo& t = mat.pbrMetallicRoughness.baseColorTexture;
  r.base_color_texture = TLOD_IMPORT_NONE;
  r.base_color_texcoord = TLOD_IMPORT_NONE;
  if (t.index >= 0 && size_t(t.index) < m.textures.size()) {
    r.base_color_texture = uint32_t(t.index);
    r.base_color_texcoord = uint32_t(t.texCoord);
  } else if (t.index >= 0) {
    out.warn(format("material %zu: baseColorTexture %d does not exist (%zu textures): ignored", i, t.index,
                    m.textures.size()));
  }
  r.alpha_mode = alpha_mode(mat, i, out);
  r.alpha_cutoff = std::isfinite(mat.alphaCutoff) ? float(mat.alphaCutoff) : 0.5f;
  r.double_sided = mat.doubleSided;
  r.metallic = unit_factor(mat.pbrMetallicRoughness.metallicFactor);
  r.roughness = unit_factor(mat.pbrMetallicRoughness.roughnessFactor);
  return r;
}

// glTF sampler values are GL enums; tinygltf stores -1 for an unset filter.
int gl_value(int v) { return v > 0 ? v : 0; }

tlod_import_texture make_texture(const tinygltf::Model& m, size_t i, OutputBase& out) {
  const tinygltf::Texture& t = m.textures[i];
  tlod_import_texture r{TLOD_IMPORT_NONE, 0, 0, 0, 0};
  if (t.source >= 0 && size_t(t.source) < m.images.size())
    r.image = uint32_t(t.source);
  else if (t.source >= 0)
    out.warn(format("texture %zu: source image %d does not exist (%zu images): ignored", i, t.source, m.images.size()));
  if (t.sampler >= 0 && size_t(t.sampler) < m.samplers.size()) {
    const tinygltf::Sampler& s = m.samplers[size_t(t.sampler)];
    r.wrap_s = gl_value(s.wrapS), r.wrap_t = gl_value(s.wrapT);
    r.min_filter = gl_value(s.minFilter), r.mag_filter = gl_value(s.magFilter);
  } else if (t.sampler >= 0) {
    out.warn(format("texture %zu: sampler %d does not exist (%zu samplers): ignored", i, t.sampler, m.samplers.size()));
  }
  return r;
}

} // namespace

void read_materials(const tinygltf::Model& m, OutputBase& out) {
  for (size_t i = 0; i < m.materials.size(); ++i)
    out.materials.push_back(make_material(m, i, out));
  for (size_t i = 0; i < m.textures.size(); ++i)
    out.textures.push_back(make_texture(m, i, out));
}

void resolve_texcoords(OutputBase& out) {
  for (tlod_import_material& mat : out.materials) {
    if (mat.base_color_texcoord == TLOD_IMPORT_NONE) continue;
    const std::string name = "TEXCOORD_" + std::to_string(mat.base_color_texcoord);
    mat.base_color_texcoord = TLOD_IMPORT_NONE;
    for (size_t a = 0; a < out.attributes.size(); ++a)
      if (out.attributes[a].name == name) mat.base_color_texcoord = uint32_t(a);
  }
}

} // namespace tlod_gltf
