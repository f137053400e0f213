// gltf_accessor.cpp -- glTF accessors read after every range check (gltf_load.hpp), shared by
// the scene importer and the camera-path reader. Owned by the import/export layer.
//
// tinygltf checks none of this: that bufferViews fit their buffers, that
// accessors and their sparse parts fit their bufferViews, that sparse indices
// address elements. Sizes are compared in an order of tests that cannot
// overflow, and the arrays they size are taken from the import's budget first.
#include <cstring>

#include "gltf_load.hpp"

namespace tlod_gltf {

using tlod_import_detail::fail;
using tlod_import_detail::format;

void take(_tlod_import_budget* budget, size_t bytes, const std::string& what) {
  if (!_tlod_budget_take(budget, bytes))
    fail(TLOD_ERROR_OUT_OF_MEMORY, format("%s: needs %zu bytes, beyond the import's memory budget (%zu of %zu bytes "
                                          "used; tlod_import_desc.memory_limit)",
                                          what.c_str(), bytes, budget->used, budget->limit));
}

size_t mul(size_t a, size_t b, const std::string& what) {
  size_t r;
  if (!_tlod_size_mul(a, b, &r)) fail(TLOD_ERROR_PARSE, format("%s: %zu x %zu bytes overflows", what.c_str(), a, b));
  return r;
}

size_t mul_add(size_t a, size_t b, size_t c, const std::string& what) {
  size_t r;
  if (!_tlod_size_add(mul(a, b, what), c, &r))
    fail(TLOD_ERROR_PARSE, format("%s: %zu x %zu + %zu bytes overflows", what.c_str(), a, b, c));
  return r;
}

uint32_t load_u32(const unsigned char* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

float load_f32(const unsigned char* p) {
  const uint32_t u = load_u32(p);
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

namespace {

uint32_t load_index(const unsigned char* p, int component_type) {
  switch (component_type) {
  case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
    return p[0];
  case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
    return uint32_t(p[0]) | uint32_t(p[1]) << 8;
  default:
    return load_u32(p);
  }
}

bool is_index_type(int t) {
  return t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
         t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
}

} // namespace

size_t component_size(int type) {
  switch (type) {
  case TINYGLTF_COMPONENT_TYPE_BYTE:
  case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
    return 1;
  case TINYGLTF_COMPONENT_TYPE_SHORT:
  case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
    return 2;
  case TINYGLTF_COMPONENT_TYPE_INT:
  case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
  case TINYGLTF_COMPONENT_TYPE_FLOAT:
    return 4;
  case TINYGLTF_COMPONENT_TYPE_DOUBLE:
    return 8;
  default:
    return 0;
  }
}

const char* component_name(int type) {
  switch (type) {
  case TINYGLTF_COMPONENT_TYPE_BYTE:
    return "byte";
  case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
    return "unsigned byte";
  case TINYGLTF_COMPONENT_TYPE_SHORT:
    return "short";
  case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
    return "unsigned short";
  case TINYGLTF_COMPONENT_TYPE_INT:
    return "int";
  case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    return "unsigned int";
  case TINYGLTF_COMPONENT_TYPE_FLOAT:
    return "float";
  case TINYGLTF_COMPONENT_TYPE_DOUBLE:
    return "double";
  default:
    return "unknown";
  }
}

const char* type_name(int type) {
  switch (type) {
  case TINYGLTF_TYPE_SCALAR:
    return "SCALAR";
  case TINYGLTF_TYPE_VEC2:
    return "VEC2";
  case TINYGLTF_TYPE_VEC3:
    return "VEC3";
  case TINYGLTF_TYPE_VEC4:
    return "VEC4";
  case TINYGLTF_TYPE_MAT2:
    return "MAT2";
  case TINYGLTF_TYPE_MAT3:
    return "MAT3";
  case TINYGLTF_TYPE_MAT4:
    return "MAT4";
  default:
    return "unknown";
  }
}

void Accessors::check_ref(int index, const std::string& what) const {
  if (index < 0 || size_t(index) >= m_.accessors.size())
    fail(TLOD_ERROR_PARSE,
         format("%s: accessor %d does not exist (%zu accessors)", what.c_str(), index, m_.accessors.size()));
}

void Accessors::check_buffer_views() const {
  for (size_t i = 0; i < m_.bufferViews.size(); ++i)
    buffer_view(int(i), "");
}

void Accessors::take(size_t count, size_t element_bytes, const std::string& what) const {
  tlod_gltf::take(budget_, mul(count, element_bytes, what), what);
}

// what: the referrer for messages ("" for none).
const tinygltf::BufferView& Accessors::buffer_view(int index, const std::string& what) const {
  const std::string pre = what.empty() ? "" : what + ": ";
  if (index < 0 || size_t(index) >= m_.bufferViews.size())
    fail(TLOD_ERROR_PARSE,
         format("%sbufferView %d does not exist (%zu bufferViews)", pre.c_str(), index, m_.bufferViews.size()));
  const tinygltf::BufferView& bv = m_.bufferViews[size_t(index)];
  if (bv.buffer < 0 || size_t(bv.buffer) >= m_.buffers.size())
    fail(TLOD_ERROR_PARSE, format("%sbufferView %d: buffer %d does not exist (%zu buffers)", pre.c_str(), index,
                                  bv.buffer, m_.buffers.size()));
  const size_t size = m_.buffers[size_t(bv.buffer)].data.size();
  if (bv.byteOffset > size || bv.byteLength > size - bv.byteOffset)
    fail(TLOD_ERROR_PARSE, format("%sbufferView %d (offset %zu, length %zu) runs past the end of buffer %d "
                                  "(%zu bytes)",
                                  pre.c_str(), index, bv.byteOffset, bv.byteLength, bv.buffer, size));
  return bv;
}

const unsigned char* Accessors::view_bytes(int index, const std::string& what, size_t* size) const {
  const tinygltf::BufferView& bv = buffer_view(index, what);
  *size = bv.byteLength;
  return view_data(bv);
}

const unsigned char* Accessors::view_data(const tinygltf::BufferView& bv) const {
  return m_.buffers[size_t(bv.buffer)].data.data() + bv.byteOffset;
}

// byteOffset + stride * (count - 1) + element <= bufferView length, in an
// order of tests that cannot overflow.
Span Accessors::resolve(int index, const std::string& what, size_t element) const {
  const tinygltf::Accessor& a = m_.accessors[size_t(index)];
  Span s;
  s.count = a.count;
  if (a.bufferView < 0) {
    if (a.count > _TLOD_IMPORT_MAX_ZERO_FILLED)
      fail(TLOD_ERROR_UNSUPPORTED,
           format("%s: accessor %d has %zu elements and no bufferView", what.c_str(), index, a.count));
    return s; // zeros, possibly replaced by sparse values
  }
  const std::string w = format("%s: accessor %d", what.c_str(), index);
  const tinygltf::BufferView& bv = buffer_view(a.bufferView, w);
  s.stride = bv.byteStride ? bv.byteStride : element;
  if (s.stride < element)
    fail(TLOD_ERROR_PARSE, format("%s: bufferView %d byteStride %zu is less than the %zu-byte element", w.c_str(),
                                  a.bufferView, bv.byteStride, element));
  const size_t len = bv.byteLength;
  const bool fits = a.count == 0 || (a.byteOffset <= len && element <= len - a.byteOffset &&
                                     a.count - 1 <= (len - a.byteOffset - element) / s.stride);
  if (!fits)
    fail(TLOD_ERROR_PARSE, format("%s (offset %zu, %zu elements of %zu bytes, stride %zu) runs past the end of "
                                  "bufferView %d (%zu bytes)",
                                  w.c_str(), a.byteOffset, a.count, element, s.stride, a.bufferView, len));
  s.base = view_data(bv) + a.byteOffset;
  return s;
}

std::vector<float> Accessors::read_floats(int index, const std::string& what, int components) const {
  check_ref(index, what);
  const tinygltf::Accessor& a = m_.accessors[size_t(index)];
  // tinygltf's VEC2..VEC4 are 2..4, SCALAR is 64 + 1.
  const int type = components == 1 ? TINYGLTF_TYPE_SCALAR : components;
  if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || a.type != type)
    fail(TLOD_ERROR_UNSUPPORTED, format("%s: accessor %d is %s %s (float %s required)", what.c_str(), index,
                                        component_name(a.componentType), type_name(a.type), type_name(type)));
  return read_numbers(index, what, type);
}

namespace {

float load_number(const unsigned char* p, int component_type, bool normalized) {
  switch (component_type) {
  case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
    return normalized ? float(p[0]) / 255.0f : float(p[0]);
  case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
    return normalized ? float(load_index(p, component_type)) / 65535.0f : float(load_index(p, component_type));
  default:
    return load_f32(p);
  }
}

} // namespace

std::vector<float> Accessors::read_numbers(int index, const std::string& what, int type) const {
  check_ref(index, what);
  const tinygltf::Accessor& a = m_.accessors[size_t(index)];
  const int ct = a.componentType;
  const int nc_int = tinygltf::GetNumComponentsInType(uint32_t(type));
  if (a.type != type || nc_int <= 0 ||
      (ct != TINYGLTF_COMPONENT_TYPE_FLOAT && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
       ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT))
    fail(TLOD_ERROR_UNSUPPORTED, format("%s: accessor %d is %s %s (float, unsigned byte or short %s required)",
                                        what.c_str(), index, component_name(ct), type_name(a.type), type_name(type)));
  const size_t nc = size_t(nc_int), cs = component_size(ct);
  const Span s = resolve(index, what, cs * nc);
  take(s.count, 4 * nc, format("%s: accessor %d", what.c_str(), index));
  std::vector<float> out(s.count * nc, 0.0f);
  if (s.base)
    for (size_t i = 0; i < s.count; ++i)
      for (size_t c = 0; c < nc; ++c)
        out[i * nc + c] = load_number(s.base + i * s.stride + cs * c, ct, a.normalized);
  if (!a.sparse.isSparse) return out;
  const SparseSpans sp = resolve_sparse(index, what, cs * nc);
  for (size_t i = 0; i < sp.count; ++i) {
    const size_t t = sparse_target(sp, i, index, what);
    for (size_t c = 0; c < nc; ++c)
      out[t * nc + c] = load_number(sp.values + (i * nc + c) * cs, ct, a.normalized);
  }
  return out;
}

std::vector<uint32_t> Accessors::read_indices(int index, const std::string& what) const {
  const std::string w = what + ": indices";
  check_ref(index, w);
  const tinygltf::Accessor& a = m_.accessors[size_t(index)];
  if (a.type != TINYGLTF_TYPE_SCALAR || !is_index_type(a.componentType))
    fail(TLOD_ERROR_PARSE, format("%s: accessor %d is %s %s (unsigned byte/short/int SCALAR required)", w.c_str(),
                                  index, component_name(a.componentType), type_name(a.type)));
  const size_t cs = component_size(a.componentType);
  const Span s = resolve(index, w, cs);
  if (s.count > _TLOD_IMPORT_MAX_INDICES)
    fail(TLOD_ERROR_UNSUPPORTED, format("%s: accessor %d has %zu indices", w.c_str(), index, s.count));
  take(s.count, 4, format("%s: accessor %d", w.c_str(), index));
  std::vector<uint32_t> out(s.count, 0u);
  if (s.base)
    for (size_t i = 0; i < s.count; ++i)
      out[i] = load_index(s.base + i * s.stride, a.componentType);
  apply_sparse_indices(index, w, out);
  return out;
}

// Sparse substitution: both sparse arrays are tightly packed (glTF), and
// every sparse index must address an element of the accessor.
Accessors::SparseSpans Accessors::resolve_sparse(int index, const std::string& what, size_t element) const {
  const tinygltf::Accessor& a = m_.accessors[size_t(index)];
  const std::string w = format("%s: accessor %d: sparse", what.c_str(), index);
  const int n = a.sparse.count;
  if (n < 1 || size_t(n) > a.count)
    fail(TLOD_ERROR_PARSE, format("%s count %d out of range (accessor has %zu elements)", w.c_str(), n, a.count));
  const int it = a.sparse.indices.componentType;
  if (!is_index_type(it))
    fail(TLOD_ERROR_PARSE,
         format("%s indices are %s (unsigned byte/short/int required)", w.c_str(), component_name(it)));
  SparseSpans s{nullptr, nullptr, size_t(n), component_size(it), it};
  const int io = a.sparse.indices.byteOffset, vo = a.sparse.values.byteOffset;
  if (io < 0 || vo < 0) fail(TLOD_ERROR_PARSE, format("%s byteOffset is negative", w.c_str()));
  s.indices = sparse_range(a.sparse.indices.bufferView, size_t(io), mul(s.count, s.index_size, w), w + " indices");
  s.values = sparse_range(a.sparse.values.bufferView, size_t(vo), mul(s.count, element, w), w + " values");
  return s;
}

const unsigned char* Accessors::sparse_range(int view, size_t offset, size_t bytes, const std::string& what) const {
  const tinygltf::BufferView& bv = buffer_view(view, what);
  if (offset > bv.byteLength || bytes > bv.byteLength - offset)
    fail(TLOD_ERROR_PARSE, format("%s (offset %zu, %zu bytes) run past the end of bufferView %d (%zu bytes)",
                                  what.c_str(), offset, bytes, view, bv.byteLength));
  return view_data(bv) + offset;
}

size_t Accessors::sparse_target(const SparseSpans& s, size_t i, int index, const std::string& what) const {
  const size_t count = m_.accessors[size_t(index)].count;
  const uint32_t t = load_index(s.indices + i * s.index_size, s.index_type);
  if (t >= count)
    fail(TLOD_ERROR_PARSE, format("%s: accessor %d: sparse index %zu is %u, out of range (%zu elements)", what.c_str(),
                                  index, i, t, count));
  return t;
}

void Accessors::apply_sparse_indices(int index, const std::string& what, std::vector<uint32_t>& out) const {
  const tinygltf::Accessor& a = m_.accessors[size_t(index)];
  if (!a.sparse.isSparse) return;
  const size_t cs = component_size(a.componentType);
  const SparseSpans s = resolve_sparse(index, what, cs);
  for (size_t i = 0; i < s.count; ++i)
    out[sparse_target(s, i, index, what)] = load_index(s.values + i * cs, a.componentType);
}

} // namespace tlod_gltf
