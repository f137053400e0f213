// gltf_validate.cpp -- glTF JSON checked with nlohmann::json before tinygltf reads it (gltf_load.hpp).
// Owned by the import/export layer.
//
// tinygltf turns an integer field it cannot read (negative, fractional, a
// string: "byteOffset": -4, 1.5 or "8") into its default 0 without a word, so
// the importer would read the wrong bytes. Here every integer field the
// project reads or tinygltf indexes with must be a non-negative JSON integer
// (index fields also fit tinygltf's int), or the file is refused naming the
// field: "accessors[3].byteOffset: not a non-negative integer".
// The same pass measures the JSON for the memory estimate and collects the
// external URIs.
#include <nlohmann/json.hpp>

#include <climits>

#include "gltf_load.hpp"

namespace tlod_gltf {

using nlohmann::json;
using tlod_import_detail::fail;
using tlod_import_detail::format;

namespace {

enum Kind { kIndex, kSize }; // kIndex: tinygltf stores an int

struct Field {
  const char* array; // top-level array ("" for a top-level field)
  const char* path;  // '.'-separated members; "x[]" every element of array x, "*" every member
  Kind kind;
};

// Every integer field of glTF 2.0 that tinygltf parses into a struct the
// project reads (geometry, nodes, animations, skins, materials, samplers) or indexes with (images).
const Field kFields[] = {
    {"", "scene", kIndex},
    {"accessors", "bufferView", kIndex},
    {"accessors", "byteOffset", kSize},
    {"accessors", "componentType", kIndex},
    {"accessors", "count", kSize},
    {"accessors", "sparse.count", kIndex},
    {"accessors", "sparse.indices.bufferView", kIndex},
    {"accessors", "sparse.indices.byteOffset", kIndex},
    {"accessors", "sparse.indices.componentType", kIndex},
    {"accessors", "sparse.values.bufferView", kIndex},
    {"accessors", "sparse.values.byteOffset", kIndex},
    {"bufferViews", "buffer", kIndex},
    {"bufferViews", "byteOffset", kSize},
    {"bufferViews", "byteLength", kSize},
    {"bufferViews", "byteStride", kSize},
    {"bufferViews", "target", kIndex},
    {"buffers", "byteLength", kSize},
    {"images", "bufferView", kIndex},
    {"textures", "source", kIndex},
    {"materials", "pbrMetallicRoughness.baseColorTexture.index", kIndex},
    {"materials", "pbrMetallicRoughness.baseColorTexture.texCoord", kIndex},
    {"samplers", "magFilter", kIndex},
    {"samplers", "minFilter", kIndex},
    {"samplers", "wrapS", kIndex},
    {"samplers", "wrapT", kIndex},
    {"textures", "sampler", kIndex},
    {"nodes", "camera", kIndex},
    {"nodes", "mesh", kIndex},
    {"nodes", "skin", kIndex},
    {"nodes", "children[]", kIndex},
    {"scenes", "nodes[]", kIndex},
    {"meshes", "primitives[].indices", kIndex},
    {"meshes", "primitives[].material", kIndex},
    {"meshes", "primitives[].mode", kIndex},
    {"meshes", "primitives[].attributes.*", kIndex},
    {"meshes", "primitives[].targets[].*", kIndex},
    {"animations", "channels[].sampler", kIndex},
    {"animations", "channels[].target.node", kIndex},
    {"animations", "samplers[].input", kIndex},
    {"animations", "samplers[].output", kIndex},
    {"skins", "inverseBindMatrices", kIndex},
    {"skins", "skeleton", kIndex},
    {"skins", "joints[]", kIndex},
};

// tinygltf's struct per element of each top-level array, for the estimate.
struct ArraySize {
  const char* name;
  size_t bytes;
};
const ArraySize kArrays[] = {
    {"accessors", sizeof(tinygltf::Accessor)}, {"animations", sizeof(tinygltf::Animation)},
    {"buffers", sizeof(tinygltf::Buffer)},     {"bufferViews", sizeof(tinygltf::BufferView)},
    {"cameras", sizeof(tinygltf::Camera)},     {"images", sizeof(tinygltf::Image)},
    {"materials", sizeof(tinygltf::Material)}, {"meshes", sizeof(tinygltf::Mesh)},
    {"nodes", sizeof(tinygltf::Node)},         {"samplers", sizeof(tinygltf::Sampler)},
    {"scenes", sizeof(tinygltf::Scene)},       {"skins", sizeof(tinygltf::Skin)},
    {"textures", sizeof(tinygltf::Texture)},
};

[[noreturn]] void bad(const std::string& where, const char* problem) {
  fail(TLOD_ERROR_PARSE, format("%s: %s", where.c_str(), problem));
}

void check_integer(const json& v, const std::string& where, Kind kind) {
  if (!v.is_number_unsigned()) bad(where, "not a non-negative integer");
  if (kind == kIndex && v.get<uint64_t>() > uint64_t(INT_MAX)) bad(where, "larger than 2147483647");
}

// Walks path below v (where names v), checking every integer it reaches.
void check_path(const json& v, const std::string& path, const std::string& where, Kind kind) {
  const size_t dot = path.find('.');
  const std::string seg = path.substr(0, dot), rest = dot == std::string::npos ? "" : path.substr(dot + 1);
  if (!v.is_object()) bad(where, "not an object");
  auto recurse = [&](const json& child, const std::string& w) {
    if (rest.empty())
      check_integer(child, w, kind);
    else
      check_path(child, rest, w, kind);
  };
  if (seg == "*") {
    for (auto it = v.begin(); it != v.end(); ++it)
      recurse(it.value(), where + "." + it.key());
    return;
  }
  const bool each = seg.size() > 2 && seg.compare(seg.size() - 2, 2, "[]") == 0;
  const std::string name = each ? seg.substr(0, seg.size() - 2) : seg;
  const auto it = v.find(name);
  if (it == v.end()) return;
  const std::string w = where.empty() ? name : where + "." + name;
  if (!each) return recurse(*it, w);
  if (!it->is_array()) bad(w, "not an array");
  for (size_t i = 0; i < it->size(); ++i)
    recurse((*it)[i], format("%s[%zu]", w.c_str(), i));
}

void check_fields(const json& root) {
  if (!root.is_object()) bad("JSON", "the top level is not an object");
  for (const Field& f : kFields) {
    if (!f.array[0]) {
      check_path(root, f.path, "", f.kind);
      continue;
    }
    const auto a = root.find(f.array);
    if (a == root.end()) continue;
    if (!a->is_array()) bad(f.array, "not an array");
    for (size_t i = 0; i < a->size(); ++i)
      check_path((*a)[i], f.path, format("%s[%zu]", f.array, i), f.kind);
  }
}

// tinygltf's structs for the top-level arrays (the JSON trees and the
// strings are estimated from the pre-scan, gltf_load.cpp).
size_t estimate(const json& root) {
  size_t sum = 0;
  for (const ArraySize& a : kArrays) {
    const auto it = root.find(a.name);
    if (it != root.end() && it->is_array()) sum = mul_add(it->size(), a.bytes, sum, a.name);
  }
  return sum;
}

// The uri of each element of root[array] that tinygltf would open as a file.
std::vector<std::string> external_uris(const json& root, const char* array) {
  std::vector<std::string> uris;
  const auto a = root.find(array);
  if (a == root.end() || !a->is_array()) return uris;
  for (size_t i = 0; i < a->size(); ++i) {
    const json& e = (*a)[i];
    const auto u = e.find("uri");
    const bool external = u != e.end() && u->is_string() && !tinygltf::IsDataURI(u->get<std::string>());
    uris.push_back(external ? u->get<std::string>() : std::string());
  }
  return uris;
}

} // namespace

JsonFacts validate_json(const unsigned char* text, size_t size) {
  json root;
  try {
    root = json::parse(text, text + size);
  } catch (const json::exception& e) {
    fail(TLOD_ERROR_PARSE, format("glTF parse error: %s", e.what()));
  }
  check_fields(root);
  JsonFacts facts;
  facts.estimate = estimate(root);
  facts.buffer_uris = external_uris(root, "buffers");
  facts.image_uris = external_uris(root, "images");
  return facts;
}

} // namespace tlod_gltf
