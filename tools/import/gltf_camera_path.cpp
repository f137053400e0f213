// tlod tool -- cameras of a glTF file as `tlod play` camera paths: the node
// that carries camera N, its world transform (static parents), and the
// translation / rotation channels of the first animation that moves that
// node, sampled at the union of their keyframe times (linear and slerp, as
// glTF's LINEAR interpolation; STEP and CUBICSPLINE are sampled at their
// keys only). No exception leaves this file.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

#include "camera_path_json.h"
#include "gltf_load.hpp"
#include "import_error.hpp"

using tlod_import_detail::fail;
using tlod_import_detail::format;
using tlod_import_detail::ImportError;

namespace {

using Mat = std::array<double, 16>; // column-major

Mat identity() { return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; }

Mat mul(const Mat& a, const Mat& b) {
  Mat r{};
  for (int c = 0; c < 4; c++)
    for (int row = 0; row < 4; row++)
      for (int k = 0; k < 4; k++)
        r[c * 4 + row] += a[k * 4 + row] * b[c * 4 + k];
  return r;
}

Mat trs(const double t[3], const double q[4], const double s[3]) {
  double x = q[0], y = q[1], z = q[2], w = q[3];
  Mat m = {(1 - 2 * (y * y + z * z)) * s[0],
           (2 * (x * y + z * w)) * s[0],
           (2 * (x * z - y * w)) * s[0],
           0,
           (2 * (x * y - z * w)) * s[1],
           (1 - 2 * (x * x + z * z)) * s[1],
           (2 * (y * z + x * w)) * s[1],
           0,
           (2 * (x * z + y * w)) * s[2],
           (2 * (y * z - x * w)) * s[2],
           (1 - 2 * (x * x + y * y)) * s[2],
           0,
           t[0],
           t[1],
           t[2],
           1};
  return m;
}

struct Local {
  double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
  Mat matrix = identity();
  bool has_matrix = false;
};

// glTF rotations are unit quaternions; a non-unit one would scale the
// camera's frame (1e6 components put the target at infinity), so it is
// normalised, and one without a direction is refused naming `what`.
void make_unit(double q[4], const std::string& what) {
  double len = 0;
  for (int i = 0; i < 4; i++)
    len += q[i] * q[i];
  len = std::sqrt(len);
  if (!(len > 1e-12) || !std::isfinite(len)) fail(TLOD_ERROR_PARSE, what + ": rotation is not a usable quaternion");
  for (int i = 0; i < 4; i++)
    q[i] /= len;
}

Local local_of(const tinygltf::Model& m, size_t node) {
  const tinygltf::Node& n = m.nodes[node];
  Local l;
  if (n.matrix.size() == 16) {
    std::copy(n.matrix.begin(), n.matrix.end(), l.matrix.begin());
    l.has_matrix = true;
  }
  for (size_t i = 0; i < 3 && n.translation.size() == 3; i++)
    l.t[i] = n.translation[i];
  for (size_t i = 0; i < 4 && n.rotation.size() == 4; i++)
    l.q[i] = n.rotation[i];
  if (n.rotation.size() == 4) make_unit(l.q, format("nodes[%zu]", node));
  for (size_t i = 0; i < 3 && n.scale.size() == 3; i++)
    l.s[i] = n.scale[i];
  return l;
}

Mat matrix_of(const Local& l) { return l.has_matrix ? l.matrix : trs(l.t, l.q, l.s); }

struct Channel {
  std::vector<float> times, values;
  int components; // 3 translation, 4 rotation
};

// Value of a channel at time t: linear (slerp for rotations) between keys.
void sample(const Channel& c, double t, double* out) {
  size_t n = c.times.size(), k = 0;
  while (k + 1 < n && c.times[k + 1] <= t)
    k++;
  const float* a = &c.values[k * size_t(c.components)];
  if (k + 1 >= n || t <= c.times[0]) {
    for (int i = 0; i < c.components; i++)
      out[i] = a[i];
    return;
  }
  const float* b = &c.values[(k + 1) * size_t(c.components)];
  double u = (t - c.times[k]) / (c.times[k + 1] - c.times[k]);
  if (c.components == 3) {
    for (int i = 0; i < 3; i++)
      out[i] = a[i] + u * (b[i] - a[i]);
    return;
  }
  double d = 0;
  for (int i = 0; i < 4; i++)
    d += double(a[i]) * b[i];
  double sign = d < 0 ? -1.0 : 1.0, len = 0;
  for (int i = 0; i < 4; i++)
    out[i] = a[i] + u * (sign * b[i] - a[i]), len += out[i] * out[i];
  for (int i = 0; i < 4 && len > 0; i++)
    out[i] /= std::sqrt(len); // nlerp: close to slerp between dense keys
}

// Through the same hardened loader as the scene importer (gltf_load.hpp),
// with the same default memory budget.
void load_model(const char* path, _tlod_import_budget* budget, tinygltf::Model& model) {
  _tlod_import_job job{};
  job.path = job.name = path;
  job.budget = budget;
  char err[512];
  job.error = err;
  job.error_size = sizeof err;
  unsigned char* bytes = nullptr;
  size_t size = 0;
  // The message starts with the path, which the caller adds again: keep what follows it.
  if (_tlod_import_read_file(&job, &bytes, &size) != TLOD_SUCCESS)
    fail(TLOD_ERROR_IO, std::strlen(err) > std::strlen(path) + 2 ? err + std::strlen(path) + 2 : err);
  const std::unique_ptr<unsigned char, void (*)(void*)> hold(bytes, std::free);
  const std::string p = path;
  const size_t slash = p.rfind('/');
  const std::string folder = slash == std::string::npos ? "" : slash == 0 ? "/" : p.substr(0, slash);
  tlod_import_detail::OutputBase warnings;
  tlod_gltf::load(bytes, size, _tlod_str_ends_with_nocase(path, ".glb"), folder.c_str(), budget, model, warnings);
}

void build(const char* path, uint32_t camera, std::vector<camera_path_json_key>& keys) {
  _tlod_import_budget budget{_tlod_budget_default(0), 0, true};
  tinygltf::Model m;
  load_model(path, &budget, m);
  const tlod_gltf::Accessors acc(m, &budget);
  if (camera >= m.cameras.size())
    fail(TLOD_ERROR_INVALID_ARGUMENT, format("camera %u: the file has %zu cameras", camera, m.cameras.size()));
  const tinygltf::Camera& cam = m.cameras[camera];
  double fovy = cam.type == "perspective" ? cam.perspective.yfov * 180.0 / 3.14159265358979323846 : 45.0;
  std::vector<int> parent(m.nodes.size(), -1);
  int node = -1;
  for (size_t i = 0; i < m.nodes.size(); i++) {
    for (int c : m.nodes[i].children)
      if (c >= 0 && size_t(c) < m.nodes.size()) parent[size_t(c)] = int(i);
    if (m.nodes[i].camera == int(camera) && node < 0) node = int(i);
  }
  if (node < 0) fail(TLOD_ERROR_INVALID_ARGUMENT, format("camera %u is on no node", camera));
  Mat above = identity(); // static parents
  for (int p = parent[size_t(node)], guard = 0; p >= 0 && guard < 1024; p = parent[size_t(p)], guard++)
    above = mul(matrix_of(local_of(m, size_t(p))), above);
  Channel tr{{}, {}, 3}, rot{{}, {}, 4};
  for (const tinygltf::Animation& an : m.animations) {
    for (const tinygltf::AnimationChannel& ch : an.channels) {
      if (ch.target_node != node || ch.sampler < 0 || size_t(ch.sampler) >= an.samplers.size()) continue;
      const tinygltf::AnimationSampler& s = an.samplers[size_t(ch.sampler)];
      Channel* c = ch.target_path == "translation" ? &tr : ch.target_path == "rotation" ? &rot : nullptr;
      if (!c || !c->times.empty()) continue;
      c->times = acc.read_floats(s.input, "animation input", 1);
      c->values = acc.read_floats(s.output, "animation output", c->components);
      if (s.interpolation == "CUBICSPLINE") { // in-tangent, value, out-tangent per key: keep the values
        std::vector<float> v;
        for (size_t k = 0; k + 1 < c->values.size() / size_t(c->components) / 3 + 1; k++)
          for (int i = 0; i < c->components; i++)
            v.push_back(c->values[(3 * k + 1) * size_t(c->components) + size_t(i)]);
        c->values = v;
      }
      if (c->values.size() != c->times.size() * size_t(c->components))
        fail(TLOD_ERROR_PARSE, format("animation of camera node %d: %zu keys but %zu values", node, c->times.size(),
                                      c->values.size() / size_t(c->components)));
    }
    if (!tr.times.empty() || !rot.times.empty()) break; // the first animation that moves the camera
  }
  std::vector<double> times;
  for (float t : tr.times)
    times.push_back(t);
  for (float t : rot.times)
    times.push_back(t);
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  if (times.size() < 2) times = {0.0, 1.0}; // a still camera: one second of it
  acc.take(times.size(), 2 * sizeof(camera_path_json_key), "camera path keys");
  Local base = local_of(m, size_t(node));
  for (double t : times) {
    Local l = base;
    if (!tr.times.empty()) sample(tr, t, l.t), l.has_matrix = false;
    if (!rot.times.empty()) {
      sample(rot, t, l.q), l.has_matrix = false;
      make_unit(l.q, format("animation of camera node %d at t = %g", node, t));
    }
    Mat w = mul(above, matrix_of(l));
    camera_path_json_key k{};
    k.time = t;
    // glTF cameras look down their local -Z with +Y up.
    for (int i = 0; i < 3; i++) {
      k.eye[i] = w[12 + i];
      k.target[i] = w[12 + i] - w[8 + i];
      k.up[i] = w[4 + i];
    }
    k.fovy = fovy;
    keys.push_back(k);
  }
}

} // namespace

extern "C" bool gltf_camera_path_load(const char* path, uint32_t camera, camera_path_json_key** keys, uint32_t* count,
                                      char* error, size_t error_size) {
  *keys = nullptr;
  *count = 0;
  try {
    std::vector<camera_path_json_key> k;
    build(path, camera, k);
    *keys = static_cast<camera_path_json_key*>(std::malloc(sizeof(camera_path_json_key) * k.size()));
    if (!*keys) fail(TLOD_ERROR_OUT_OF_MEMORY, "out of memory");
    std::memcpy(*keys, k.data(), sizeof(camera_path_json_key) * k.size());
    *count = uint32_t(k.size());
    return true;
  } catch (const ImportError& e) {
    if (error && error_size) std::snprintf(error, error_size, "%s: %s", path, e.message.c_str());
  } catch (...) {
    if (error && error_size) std::snprintf(error, error_size, "%s: cannot read its cameras", path);
  }
  return false;
}
