// gltf_load.hpp -- the one hardened way into tinygltf (private to tools/import/, C++17).
// Owned by the import/export layer. Every glTF read in the project (the scene
// importer, the camera-path reader) goes through load() and reads accessors
// through Accessors, so every check lives in one place (docs/security.md):
//
//   load():      GLB header and chunk lengths against the file; JSON nesting
//                depth; integer fields strictly typed (gltf_validate.cpp);
//                external buffers read under the containment rule
//                (contained_file.h) and served to tinygltf from memory, so
//                tinygltf opens no file itself; images neither opened nor
//                decoded by tinygltf (gltf_images.cpp does, under the same rule);
//                tinygltf's memory estimated and taken from the budget before it
//                parses.
//   Accessors:   bufferViews inside their buffers, accessors (and sparse
//                parts) inside their views, every count x stride x size
//                overflow-checked and taken from the budget before the vector
//                it sizes is allocated.
//
// Errors are thrown as tlod_import_detail::ImportError ("<element>: <problem>";
// the caller adds the file name).
#ifndef TESSLOD_TOOLS_IMPORT_GLTF_LOAD_HPP
#define TESSLOD_TOOLS_IMPORT_GLTF_LOAD_HPP

#include <tiny_gltf.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "import_error.hpp"
#include "import_internal.h"
#include "import_output.hpp"

namespace tlod_gltf {

// Takes bytes from the budget or throws TLOD_ERROR_OUT_OF_MEMORY naming what.
void take(_tlod_import_budget* budget, size_t bytes, const std::string& what);
// a * b (+ c), or throws TLOD_ERROR_PARSE naming what when it does not fit size_t.
size_t mul(size_t a, size_t b, const std::string& what);
size_t mul_add(size_t a, size_t b, size_t c, const std::string& what);

// Parses file (size bytes: GLB if it starts with "glTF" or glb_name, else
// JSON) into model. folder: where external buffers resolve (NULL: refuse
// them). Warnings go to warnings.
// data_images: receives the bytes of images in data: URIs by image index (NULL: not kept).
void load(const unsigned char* file, size_t size, bool glb_name, const char* folder, _tlod_import_budget* budget,
          tinygltf::Model& model, tlod_import_detail::OutputBase& warnings,
          std::map<int, std::vector<unsigned char>>* data_images = nullptr);

// Integer fields, JSON shape (gltf_validate.cpp): throws on the first field
// that is not a non-negative integer; returns what tinygltf's model structs
// for the top-level arrays take and the external URIs.
struct JsonFacts {
  size_t estimate = 0;                  // bytes
  std::vector<std::string> buffer_uris; // external ones ("" for data: or none), per buffer
  std::vector<std::string> image_uris;  // external ones
};
JsonFacts validate_json(const unsigned char* json, size_t size);

// Little-endian loads through bytes: no alignment or aliasing assumptions.
uint32_t load_u32(const unsigned char* p);
float load_f32(const unsigned char* p);

size_t component_size(int type);
const char* component_name(int type);
const char* type_name(int type);

// An accessor's bytes after every range check: element i starts at
// base + i * stride. base == nullptr: no bufferView, all zeros (glTF rule).
struct Span {
  const unsigned char* base = nullptr;
  size_t stride = 0;
  size_t count = 0;
};

// Reads accessors of a loaded model; what names the referrer in messages
// ("mesh 0 primitive 1: POSITION").
class Accessors {
public:
  Accessors(const tinygltf::Model& model, _tlod_import_budget* budget) : m_(model), budget_(budget) {}

  const tinygltf::Model& model() const { return m_; }
  void check_ref(int index, const std::string& what) const;
  // The bytes of bufferView index after its range check (throws naming what).
  const unsigned char* view_bytes(int index, const std::string& what, size_t* size) const;
  // Every bufferView, used or not, inside its buffer.
  void check_buffer_views() const;
  // Float accessor of `components` per element (1 SCALAR, 3 VEC3, 4 VEC4), sparse applied.
  std::vector<float> read_floats(int index, const std::string& what, int components) const;
  // Accessor of `type` (TINYGLTF_TYPE_*) with float, unsigned byte or unsigned short
  // components as floats (normalised integers divided by 255 / 65535, others as their
  // value), sparse applied; any other layout throws TLOD_ERROR_UNSUPPORTED naming what.
  std::vector<float> read_numbers(int index, const std::string& what, int type) const;
  // Unsigned byte/short/int SCALAR accessor, sparse applied.
  std::vector<uint32_t> read_indices(int index, const std::string& what) const;
  // bytes of memory an array about to be made needs, from the budget.
  void take(size_t count, size_t element_bytes, const std::string& what) const;

private:
  struct SparseSpans {
    const unsigned char* indices;
    const unsigned char* values;
    size_t count, index_size;
    int index_type;
  };

  const tinygltf::BufferView& buffer_view(int index, const std::string& what) const;
  const unsigned char* view_data(const tinygltf::BufferView& bv) const;
  Span resolve(int index, const std::string& what, size_t element) const;
  SparseSpans resolve_sparse(int index, const std::string& what, size_t element) const;
  const unsigned char* sparse_range(int view, size_t offset, size_t bytes, const std::string& what) const;
  size_t sparse_target(const SparseSpans& s, size_t i, int index, const std::string& what) const;
  void apply_sparse_indices(int index, const std::string& what, std::vector<uint32_t>& out) const;

  const tinygltf::Model& m_;
  _tlod_import_budget* budget_;
};

} // namespace tlod_gltf

#endif
