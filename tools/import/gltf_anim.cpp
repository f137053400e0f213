// gltf_anim.cpp -- glTF animations (node translation / rotation / scale channels) and skins,
// checked before anyone samples them (gltf_scene.hpp). Owned by the import/export layer.
#include <cmath>
#include <cstdio>

#include "gltf_scene.hpp"

namespace tlod_gltf {

using tlod_import_detail::Animation;
using tlod_import_detail::Channel;
using tlod_import_detail::fail;
using tlod_import_detail::format;
using tlod_import_detail::OutputBase;
using tlod_import_detail::Skin;

namespace {

// An inverse bind matrix whose determinant is this small against the product of its column
// lengths (Hadamard's bound: 1 for a rotation, 0 when singular) cannot be inverted usefully.
constexpr double kMinRelativeDet = 1e-6;

void check_finite(const std::vector<float>& v, int accessor, const std::string& what) {
  for (size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]))
      fail(TLOD_ERROR_INVALID_MESH, format("%s: accessor %d value %zu is not finite", what.c_str(), accessor, i));
}

std::vector<float> read_times(const Accessors& acc, int input, const std::string& what) {
  const std::vector<float> t = acc.read_floats(input, what + ": input", 1);
  if (t.empty()) fail(TLOD_ERROR_PARSE, format("%s: input accessor %d has no keys", what.c_str(), input));
  for (size_t i = 0; i < t.size(); ++i) {
    if (!std::isfinite(t[i]))
      fail(TLOD_ERROR_INVALID_MESH,
           format("%s: input accessor %d key %zu: time %g is not finite", what.c_str(), input, i, double(t[i])));
    if (i > 0 && !(t[i] > t[i - 1]))
      fail(TLOD_ERROR_INVALID_MESH, format("%s: input accessor %d key %zu: time %g does not increase (key %zu: %g)",
                                           what.c_str(), input, i, double(t[i]), i - 1, double(t[i - 1])));
  }
  return t;
}

bool parse_path(const std::string& p, tlod_import_anim_path* out) {
  if (p == "translation")
    *out = TLOD_IMPORT_PATH_TRANSLATION;
  else if (p == "rotation")
    *out = TLOD_IMPORT_PATH_ROTATION;
  else if (p == "scale")
    *out = TLOD_IMPORT_PATH_SCALE;
  else
    return false;
  return true;
}

tlod_import_interp parse_interp(const std::string& s, const std::string& what) {
  if (s.empty() || s == "LINEAR") return TLOD_IMPORT_INTERP_LINEAR;
  if (s == "STEP") return TLOD_IMPORT_INTERP_STEP;
  if (s == "CUBICSPLINE") return TLOD_IMPORT_INTERP_CUBICSPLINE;
  fail(TLOD_ERROR_PARSE,
       format("%s: interpolation '%.32s' is not STEP, LINEAR or CUBICSPLINE", what.c_str(), s.c_str()));
}

const tinygltf::AnimationSampler& sampler_of(const tinygltf::Animation& an, int s, const std::string& what) {
  if (s < 0 || size_t(s) >= an.samplers.size())
    fail(TLOD_ERROR_PARSE, format("%s: sampler %d does not exist (%zu samplers)", what.c_str(), s, an.samplers.size()));
  return an.samplers[size_t(s)];
}

Channel read_channel(const tinygltf::Model& m, const Accessors& acc, const tinygltf::Animation& an,
                     const tinygltf::AnimationChannel& ch, tlod_import_anim_path path, const std::string& what) {
  if (ch.target_node < 0 || size_t(ch.target_node) >= m.nodes.size())
    fail(TLOD_ERROR_PARSE,
         format("%s: target node %d does not exist (%zu nodes)", what.c_str(), ch.target_node, m.nodes.size()));
  const tinygltf::AnimationSampler& s = sampler_of(an, ch.sampler, what);
  const std::string sw = format("%s: sampler %d", what.c_str(), ch.sampler);
  Channel c;
  c.info.node = uint32_t(ch.target_node);
  c.info.path = path;
  c.info.interp = parse_interp(s.interpolation, sw);
  c.times = read_times(acc, s.input, sw);
  const int n = path == TLOD_IMPORT_PATH_ROTATION ? 4 : 3;
  c.values = acc.read_floats(s.output, sw + ": output", n);
  check_finite(c.values, s.output, sw + ": output");
  const size_t per_key = size_t(n) * (c.info.interp == TLOD_IMPORT_INTERP_CUBICSPLINE ? 3 : 1);
  if (c.values.size() != c.times.size() * per_key)
    fail(TLOD_ERROR_PARSE, format("%s: output accessor %d has %zu values, %zu keys need %zu", sw.c_str(), s.output,
                                  c.values.size() / size_t(n), c.times.size(), c.times.size() * per_key / size_t(n)));
  c.info.key_count = uint32_t(c.times.size());
  return c;
}

Animation read_animation(const tinygltf::Model& m, const Accessors& acc, size_t i, OutputBase& out) {
  const tinygltf::Animation& an = m.animations[i];
  Animation a;
  std::snprintf(a.info.name, sizeof a.info.name, "%s", an.name.c_str());
  bool warned = false;
  for (size_t k = 0; k < an.channels.size(); ++k) {
    const std::string what = format("animation %zu channel %zu", i, k);
    tlod_import_anim_path path;
    if (parse_path(an.channels[k].target_path, &path)) {
      a.channels.push_back(read_channel(m, acc, an, an.channels[k], path, what));
    } else if (an.channels[k].target_path == "weights") {
      if (!warned) out.warn(what + ": morph target animation ignored");
      warned = true;
    } else {
      fail(TLOD_ERROR_PARSE, format("%s: target path '%.32s' is not translation, rotation, scale or weights",
                                    what.c_str(), an.channels[k].target_path.c_str()));
    }
  }
  return a;
}

// Determinant of a column-major 4x4 by cofactors along the first column.
double det4(const float* a) {
  auto m = [a](int r, int c) { return double(a[c * 4 + r]); };
  double d = 0.0;
  for (int r = 0; r < 4; ++r) {
    const int r0 = r == 0 ? 1 : 0, r1 = r <= 1 ? 2 : 1, r2 = r <= 2 ? 3 : 2;
    const double minor = m(r0, 1) * (m(r1, 2) * m(r2, 3) - m(r1, 3) * m(r2, 2)) -
                         m(r0, 2) * (m(r1, 1) * m(r2, 3) - m(r1, 3) * m(r2, 1)) +
                         m(r0, 3) * (m(r1, 1) * m(r2, 2) - m(r1, 2) * m(r2, 1));
    d += (r % 2 ? -1.0 : 1.0) * m(r, 0) * minor;
  }
  return d;
}

bool invertible(const float* a) {
  double bound = 1.0;
  for (int c = 0; c < 4; ++c) {
    double len = 0.0;
    for (int r = 0; r < 4; ++r)
      len += double(a[c * 4 + r]) * double(a[c * 4 + r]);
    bound *= std::sqrt(len);
  }
  const double d = std::fabs(det4(a));
  return std::isfinite(d) && bound > 0.0 && d > kMinRelativeDet * bound;
}

std::vector<float> inverse_binds(const Accessors& acc, const tinygltf::Skin& s, size_t i) {
  const size_t n = s.joints.size();
  std::vector<float> ib;
  if (s.inverseBindMatrices < 0) {
    acc.take(n, 64, format("skin %zu: inverse bind matrices", i));
    ib.assign(n * 16, 0.0f);
    for (size_t j = 0; j < n; ++j)
      ib[j * 16] = ib[j * 16 + 5] = ib[j * 16 + 10] = ib[j * 16 + 15] = 1.0f;
    return ib;
  }
  const std::string what = format("skin %zu: inverseBindMatrices", i);
  acc.check_ref(s.inverseBindMatrices, what);
  const int ct = acc.model().accessors[size_t(s.inverseBindMatrices)].componentType;
  if (ct != TINYGLTF_COMPONENT_TYPE_FLOAT)
    fail(TLOD_ERROR_UNSUPPORTED, format("%s: accessor %d is %s (float MAT4 required)", what.c_str(),
                                        s.inverseBindMatrices, component_name(ct)));
  ib = acc.read_numbers(s.inverseBindMatrices, what, TINYGLTF_TYPE_MAT4);
  if (ib.size() != n * 16)
    fail(TLOD_ERROR_PARSE, format("%s: accessor %d has %zu matrices for %zu joints", what.c_str(),
                                  s.inverseBindMatrices, ib.size() / 16, n));
  for (size_t j = 0; j < n; ++j)
    if (!invertible(&ib[j * 16]))
      fail(TLOD_ERROR_INVALID_MESH, format("%s: accessor %d matrix %zu (joint node %d) is not invertible or not finite",
                                           what.c_str(), s.inverseBindMatrices, j, s.joints[j]));
  return ib;
}

} // namespace

void read_animations(const tinygltf::Model& m, const Accessors& acc, OutputBase& out) {
  acc.take(m.animations.size(), sizeof(Animation) + sizeof(tlod_import_animation), "animations");
  for (size_t i = 0; i < m.animations.size(); ++i) {
    acc.take(m.animations[i].channels.size(), 2 * sizeof(Channel), format("animation %zu", i));
    out.animations.push_back(read_animation(m, acc, i, out));
  }
}

void read_skins(const tinygltf::Model& m, const Accessors& acc, OutputBase& out) {
  acc.take(m.skins.size(), sizeof(Skin) + sizeof(tlod_import_skin), "skins");
  for (size_t i = 0; i < m.skins.size(); ++i) {
    const tinygltf::Skin& s = m.skins[i];
    if (s.joints.empty()) fail(TLOD_ERROR_PARSE, format("skin %zu: no joints", i));
    Skin k;
    std::snprintf(k.info.name, sizeof k.info.name, "%s", s.name.c_str());
    acc.take(s.joints.size(), 4, format("skin %zu: joints", i));
    for (int j : s.joints) {
      if (j < 0 || size_t(j) >= m.nodes.size())
        fail(TLOD_ERROR_PARSE, format("skin %zu: joint node %d does not exist (%zu nodes)", i, j, m.nodes.size()));
      k.joints.push_back(uint32_t(j));
    }
    k.inverse_bind = inverse_binds(acc, s, i);
    out.skins.push_back(std::move(k));
  }
}

} // namespace tlod_gltf
