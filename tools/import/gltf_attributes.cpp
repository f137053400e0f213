// gltf_attributes.cpp -- a glTF primitive's texture coordinates, colours, tangents and skin
// weights, read and checked (gltf_scene.hpp). Owned by the import/export layer.
#include <cmath>
#include <cstring>

#include "gltf_scene.hpp"

namespace tlod_gltf {

using tlod_import_detail::fail;
using tlod_import_detail::format;
using tlod_import_detail::OutputBase;

namespace {

// Weights within this of 1 in sum are rescaled to 1; further off the vertex is refused.
constexpr double kWeightSumTolerance = 2e-2;
// Sums closer to 1 than this are float rounding, left as stored.
constexpr double kWeightSumExact = 1e-5;

struct Wanted {
  const char* name;
  uint32_t components; // in the output
  int types[2];        // accepted accessor types (0: none)
};

const Wanted kAttributes[] = {{"TEXCOORD_0", 2, {TINYGLTF_TYPE_VEC2, 0}},
                              {"TEXCOORD_1", 2, {TINYGLTF_TYPE_VEC2, 0}},
                              {"COLOR_0", 4, {TINYGLTF_TYPE_VEC4, TINYGLTF_TYPE_VEC3}},
                              {"TANGENT", 4, {TINYGLTF_TYPE_VEC4, 0}}};

// glTF allows float or normalised unsigned integers for these (TANGENT: float only).
bool layout_ok(const tinygltf::Accessor& a, const Wanted& w) {
  if (a.type != w.types[0] && a.type != w.types[1]) return false;
  if (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) return true;
  const bool small = a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                     a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  return small && a.normalized && std::strcmp(w.name, "TANGENT") != 0;
}

// VEC3 colours get alpha 1.
std::vector<float> widen(std::vector<float> v, size_t from, size_t to) {
  if (from == to) return v;
  std::vector<float> r(v.size() / from * to, 1.0f);
  for (size_t i = 0; i < v.size() / from; ++i)
    for (size_t c = 0; c < from; ++c)
      r[i * to + c] = v[i * from + c];
  return r;
}

void read_attribute(const tinygltf::Model& m, const Accessors& acc, const tinygltf::Primitive& prim,
                    const std::string& where, const Wanted& w, Extras& e, OutputBase& out) {
  const auto it = prim.attributes.find(w.name);
  if (it == prim.attributes.end()) return;
  const tinygltf::Accessor& a = m.accessors[size_t(it->second)];
  if (!layout_ok(a, w)) {
    out.warn(format("%s: %s accessor %d is %s%s %s, which glTF does not allow: ignored", where.c_str(), w.name,
                    it->second, a.normalized ? "normalized " : "", component_name(a.componentType), type_name(a.type)));
    return;
  }
  std::vector<float> v = acc.read_numbers(it->second, where + ": " + w.name, a.type);
  const size_t nc = size_t(tinygltf::GetNumComponentsInType(uint32_t(a.type)));
  for (size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]))
      fail(TLOD_ERROR_INVALID_MESH,
           format("%s: %s accessor %d element %zu is not finite", where.c_str(), w.name, it->second, i / nc));
  e.attributes.push_back({w.name, w.components, widen(std::move(v), nc, w.components)});
}

void read_joints(const tinygltf::Model& m, const Accessors& acc, int index, const std::string& where,
                 uint32_t joint_limit, Extras& e) {
  const tinygltf::Accessor& a = m.accessors[size_t(index)];
  if (a.type != TINYGLTF_TYPE_VEC4 || a.normalized ||
      (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
       a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT))
    fail(TLOD_ERROR_UNSUPPORTED, format("%s: JOINTS_0 accessor %d is %s %s (unsigned byte or short VEC4 required)",
                                        where.c_str(), index, component_name(a.componentType), type_name(a.type)));
  const std::vector<float> j = acc.read_numbers(index, where + ": JOINTS_0", TINYGLTF_TYPE_VEC4);
  acc.take(j.size(), 2, where + ": JOINTS_0");
  e.joints.resize(j.size());
  for (size_t i = 0; i < j.size(); ++i) {
    if (j[i] >= float(joint_limit))
      fail(TLOD_ERROR_INVALID_MESH,
           format("%s: JOINTS_0 accessor %d element %zu: joint %u out of range (the skin has %u joints)", where.c_str(),
                  index, i / 4, unsigned(j[i]), joint_limit));
    e.joints[i] = uint16_t(j[i]);
  }
}

// Negative, non-finite or far from summing to 1: refused; near 1: rescaled.
void check_weights(std::vector<float>& w, int index, const std::string& where, Extras& e) {
  for (size_t v = 0; v < w.size() / 4; ++v) {
    double sum = 0.0;
    for (size_t c = 0; c < 4; ++c) {
      const float x = w[v * 4 + c];
      if (!std::isfinite(x) || x < 0.0f)
        fail(TLOD_ERROR_INVALID_MESH, format("%s: WEIGHTS_0 accessor %d element %zu: weight %g is negative or not "
                                             "finite",
                                             where.c_str(), index, v, double(x)));
      sum += x;
    }
    if (std::fabs(sum - 1.0) > kWeightSumTolerance)
      fail(TLOD_ERROR_INVALID_MESH, format("%s: WEIGHTS_0 accessor %d element %zu: weights sum to %g (1 expected)",
                                           where.c_str(), index, v, sum));
    if (std::fabs(sum - 1.0) <= kWeightSumExact) continue;
    for (size_t c = 0; c < 4; ++c)
      w[v * 4 + c] = float(w[v * 4 + c] / sum);
    e.renormalised++;
  }
}

void read_weights(const tinygltf::Model& m, const Accessors& acc, int index, const std::string& where, Extras& e) {
  const tinygltf::Accessor& a = m.accessors[size_t(index)];
  if (a.type != TINYGLTF_TYPE_VEC4 || (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !a.normalized))
    fail(TLOD_ERROR_UNSUPPORTED,
         format("%s: WEIGHTS_0 accessor %d is %s %s (float or normalized unsigned byte/short VEC4 required)",
                where.c_str(), index, component_name(a.componentType), type_name(a.type)));
  e.weights = acc.read_numbers(index, where + ": WEIGHTS_0", TINYGLTF_TYPE_VEC4);
  check_weights(e.weights, index, where, e);
}

} // namespace

Extras read_extras(const tinygltf::Model& m, const Accessors& acc, const tinygltf::Primitive& prim,
                   const std::string& where, uint32_t joint_limit, OutputBase& out) {
  Extras e;
  for (const Wanted& w : kAttributes)
    read_attribute(m, acc, prim, where, w, e, out);
  const auto j = prim.attributes.find("JOINTS_0");
  const auto w = prim.attributes.find("WEIGHTS_0");
  if ((j == prim.attributes.end()) != (w == prim.attributes.end()))
    fail(TLOD_ERROR_PARSE, format("%s: JOINTS_0 and WEIGHTS_0 must come together", where.c_str()));
  if (j == prim.attributes.end()) return e;
  read_joints(m, acc, j->second, where, joint_limit, e);
  read_weights(m, acc, w->second, where, e);
  return e;
}

} // namespace tlod_gltf
