// gltf_load.cpp -- the one hardened way into tinygltf (gltf_load.hpp): what is checked before
// tinygltf sees a byte, and the file-system callbacks it gets. Owned by the import/export layer.
//
// Order: GLB container against the file; a bracket scan of the JSON (depth,
// and its size for the memory estimate, taken from the budget); nlohmann
// pre-validation of integer fields (gltf_validate.cpp); external buffers read
// here under the containment rule (contained_file.h); only then tinygltf,
// whose file callbacks answer from those bytes and never touch the disk.
#include <cstring>
#include <map>
#include <set>

#include "contained_file.h"
#include "gltf_load.hpp"

namespace tlod_gltf {

using tlod_import_detail::fail;
using tlod_import_detail::format;

namespace {

// nlohmann::json and tinygltf's extras conversion recurse once per nesting
// level: "[[[[..." a few 10^5 deep overflows the stack. Real glTF nests
// about 8 deep; anything past kMaxJsonDepth is refused before parsing.
constexpr int kMaxJsonDepth = 256;

// Memory per JSON value: two nlohmann trees (ours, tinygltf's) with their
// map nodes and keys, and tinygltf's own copy (a tinygltf::Value in extras).
// Per string byte: both trees, the model, and a decoded copy (data: URIs).
constexpr size_t kBytesPerValue = 256;
constexpr size_t kBytesPerStringByte = 5;

struct JsonSize {
  size_t values = 1; // upper bound: one per '[', '{' and ','
  size_t string_bytes = 0;
};

JsonSize scan_json(const unsigned char* s, size_t n) {
  JsonSize js;
  int depth = 0;
  bool in_string = false;
  for (size_t i = 0; i < n; ++i) {
    const unsigned char c = s[i];
    if (in_string) {
      js.string_bytes++;
      if (c == '\\')
        ++i; // skip the escaped character
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      js.values++;
      if (++depth > kMaxJsonDepth)
        fail(TLOD_ERROR_UNSUPPORTED, format("JSON nested deeper than %d levels (byte %zu)", kMaxJsonDepth, i));
    } else if (c == ']' || c == '}') {
      --depth;
    } else if (c == ',') {
      js.values++;
    }
  }
  return js;
}

struct Glb {
  const unsigned char* json = nullptr;
  size_t json_size = 0, bin_size = 0;
};

// The GLB container, checked completely before tinygltf sees it (tinygltf
// 2.7 forgets the 8-byte chunk header when it bounds the BIN chunk).
Glb check_glb(const unsigned char* d, size_t size) {
  if (size < 12) fail(TLOD_ERROR_PARSE, format("truncated GLB header (%zu bytes, 12 needed)", size));
  if (std::memcmp(d, "glTF", 4) != 0) fail(TLOD_ERROR_PARSE, "not a GLB file (bad magic)");
  const uint32_t version = load_u32(d + 4), length = load_u32(d + 8);
  if (version != 2) fail(TLOD_ERROR_UNSUPPORTED, format("GLB version %u is not supported (2 expected)", version));
  if (length != size)
    fail(TLOD_ERROR_PARSE, format("GLB header length %u does not match the file size %zu", length, size));
  if (size < 20) fail(TLOD_ERROR_PARSE, "truncated GLB chunk header");
  const size_t json_len = load_u32(d + 12);
  if (load_u32(d + 16) != 0x4E4F534Au) fail(TLOD_ERROR_PARSE, "first GLB chunk is not JSON");
  if (json_len > size - 20)
    fail(TLOD_ERROR_PARSE, format("GLB JSON chunk (%zu bytes) runs past the end of the file", json_len));
  Glb g{d + 20, json_len, 0};
  const size_t rest = size - 20 - json_len;
  if (rest == 0) return g;
  if (rest < 8) fail(TLOD_ERROR_PARSE, "truncated GLB chunk header after the JSON chunk");
  g.bin_size = load_u32(d + 20 + json_len);
  if (load_u32(d + 24 + json_len) != 0x004E4942u) fail(TLOD_ERROR_UNSUPPORTED, "second GLB chunk is not BIN");
  if (g.bin_size > rest - 8)
    fail(TLOD_ERROR_PARSE, format("GLB BIN chunk (%zu bytes) runs past the end of the file", g.bin_size));
  return g;
}

// What tinygltf's file callbacks may hand out: external buffers read under
// the containment rule, keyed by the path tinygltf asks for; image URIs get
// one dummy byte (the no-op image loader ignores it), so no image is opened.
struct Files {
  std::map<std::string, std::vector<unsigned char>> buffers;
  std::set<std::string> images;
};

// tinygltf's own decoding of a URI before it asks for the file (dlib's
// urldecode: '+' is a space, "%XY" a byte, non-hex digits count as 0).
std::string tinygltf_key(const std::string& uri) {
  auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return 0;
  };
  std::string r;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '+') {
      r += ' ';
    } else if (uri[i] == '%' && uri.size() > i + 2) {
      r += char(hex(uri[i + 1]) << 4 | hex(uri[i + 2]));
      i += 2;
    } else {
      r += uri[i];
    }
  }
  return r;
}

void read_buffer(const char* folder, size_t i, const std::string& uri, _tlod_import_budget* budget, Files& files) {
  const std::string where = format("buffers[%zu].uri '%.200s'", i, uri.c_str());
  if (!folder) fail(TLOD_ERROR_IO, where + ": refused: an external file of a model imported from memory");
  const std::string key = tinygltf_key(uri);
  if (files.buffers.count(key)) return;
  unsigned char* data = nullptr;
  size_t size = 0;
  const _tlod_contained_status st =
      _tlod_contained_read(folder, uri.c_str(), _tlod_budget_file_limit(budget), &data, &size);
  if (st != _TLOD_CONTAINED_OK)
    fail(tlod_result(_tlod_contained_result(st)), where + ": " + _tlod_contained_message(st));
  _tlod_budget_add_input(budget, size);
  if (!_tlod_budget_take(budget, 2 * size)) {
    std::free(data);
    fail(TLOD_ERROR_OUT_OF_MEMORY, where + ": " + _tlod_contained_message(_TLOD_CONTAINED_TOO_LARGE));
  }
  try {
    files.buffers[key].assign(data, data + size);
  } catch (...) {
    std::free(data);
    throw;
  }
  std::free(data);
}

bool fs_exists(const std::string& path, void* user) {
  const Files* f = static_cast<const Files*>(user);
  return f->buffers.count(path) || f->images.count(path);
}

std::string fs_expand(const std::string& path, void*) { return path; }

bool fs_read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  const Files* f = static_cast<const Files*>(user);
  const auto it = f->buffers.find(path);
  if (it != f->buffers.end()) {
    *out = it->second;
    return true;
  }
  if (f->images.count(path)) {
    out->assign(1, 0);
    return true;
  }
  if (err) *err += "not available";
  return false;
}

bool fs_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is disabled";
  return false;
}

// tinygltf never decodes an image. The bytes of a data: URI image reach only this callback
// (tinygltf keeps no URI for them), so they are kept for gltf_images.cpp, within the budget
// (over it: not kept, which reads as a missing image). Files get a dummy byte, bufferViews are
// read by gltf_images.cpp itself.
struct ImageCapture {
  std::map<int, std::vector<unsigned char>>* images;
  _tlod_import_budget* budget;
};

bool capture_image(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
                   const unsigned char* bytes, int size, void* user) {
  const ImageCapture* c = static_cast<const ImageCapture*>(user);
  if (!c || !c->images || image->bufferView != -1 || !image->uri.empty() || size <= 0) return true;
  if (!_tlod_budget_take(c->budget, size_t(size))) return true;
  (*c->images)[index].assign(bytes, bytes + size);
  return true;
}

std::string one_line(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' '))
    s.pop_back();
  for (size_t i = 0; (i = s.find('\n', i)) != std::string::npos;)
    s.replace(i, 1, "; ");
  return s;
}

// Everything before tinygltf: returns the files its callbacks may hand out.
void prepare(const unsigned char* json, size_t json_size, const char* folder, _tlod_import_budget* budget,
             Files& files) {
  const JsonSize js = scan_json(json, json_size);
  take(budget, mul_add(js.values, kBytesPerValue, mul(js.string_bytes, kBytesPerStringByte, "JSON"), "JSON"),
       format("JSON (%zu values, %zu string bytes)", js.values, js.string_bytes));
  const JsonFacts facts = validate_json(json, json_size);
  take(budget, facts.estimate, "glTF model");
  for (size_t i = 0; i < facts.buffer_uris.size(); ++i)
    if (!facts.buffer_uris[i].empty()) read_buffer(folder, i, facts.buffer_uris[i], budget, files);
  for (const std::string& uri : facts.image_uris)
    if (!uri.empty()) files.images.insert(tinygltf_key(uri));
}

} // namespace

void load(const unsigned char* file, size_t size, bool glb_name, const char* folder, _tlod_import_budget* budget,
          tinygltf::Model& model, tlod_import_detail::OutputBase& warnings,
          std::map<int, std::vector<unsigned char>>* data_images) {
  if (size > 0xFFFFFFFFu) fail(TLOD_ERROR_UNSUPPORTED, "glTF file larger than 4 GiB");
  const bool glb = glb_name || (size >= 4 && std::memcmp(file, "glTF", 4) == 0);
  Files files;
  tinygltf::TinyGLTF loader;
  ImageCapture capture{data_images, budget};
  loader.SetImageLoader(capture_image, &capture);
  loader.SetFsCallbacks({fs_exists, fs_expand, fs_read, fs_write, &files});
  std::string err, warn;
  bool ok;
  if (glb) {
    const Glb g = check_glb(file, size);
    prepare(g.json, g.json_size, folder, budget, files);
    take(budget, g.bin_size, "GLB BIN chunk");
    ok = loader.LoadBinaryFromMemory(&model, &err, &warn, file, static_cast<unsigned int>(size), "");
  } else {
    size_t skip = 0;
    if (size >= 3 && std::memcmp(file, "\xEF\xBB\xBF", 3) == 0) {
      warnings.warn("UTF-8 byte order mark skipped (glTF JSON must not have one)");
      skip = 3;
    }
    prepare(file + skip, size - skip, folder, budget, files);
    ok = loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(file) + skip,
                                    static_cast<unsigned int>(size - skip), "");
  }
  if (!warn.empty()) warnings.warn("tinygltf: " + one_line(warn));
  if (!ok) fail(TLOD_ERROR_PARSE, "glTF parse error: " + one_line(err.empty() ? "unknown" : err));
}

} // namespace tlod_gltf
