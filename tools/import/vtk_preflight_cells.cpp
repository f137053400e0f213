// vtk_preflight_cells.cpp -- offsets against connectivity, before VTK reads either
// (vtk_preflight_cells.hpp).
#include "vtk_preflight_cells.hpp"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>

#include "import_error.hpp"
#include "vtk_preflight.hpp"

namespace tlod_import_detail {
namespace {

// Offsets at or past this are past any connectivity the budget allows.
constexpr double kHuge = 9.0e18;

[[noreturn]] void not_a_count(uint64_t i, const char* what) {
  fail(TLOD_ERROR_PARSE, format("DataArray %llu (offsets): an offset is %s", (unsigned long long)i, what));
}

// The value of size bytes at q (big_endian or little), as a count; fails when it is not one.
uint64_t binary_value(uint64_t i, const unsigned char* q, CellArray c, bool big_endian) {
  if (c.size == 0 || c.size > 8) return 0; // not a cell array (callers pass only those)
  uint64_t bits = 0;
  for (size_t k = 0; k < c.size; ++k)
    bits = bits << 8 | q[big_endian ? k : c.size - 1 - k];
  if (c.kind == 'u') return bits;
  if (c.kind == 'i') {
    const uint64_t sign = uint64_t(1) << (8 * c.size - 1);
    if (bits & sign) not_a_count(i, "negative");
    return bits;
  }
  double d;
  if (c.size == 4) {
    float f;
    const uint32_t b32 = uint32_t(bits);
    memcpy(&f, &b32, 4);
    d = f;
  } else {
    memcpy(&d, &bits, 8);
  }
  if (!(d >= 0) || !std::isfinite(d)) not_a_count(i, "negative or not a finite number");
  return d >= kHuge ? uint64_t(kHuge) : uint64_t(d); // VTK converts by truncation
}

// An ASCII word as a C++ stream reads a value of c's kind (its longest valid prefix); a word
// with no such prefix ends VTK's read, and so the values that count.
bool ascii_value(uint64_t i, const char* w, size_t n, CellArray c, uint64_t* v) {
  char text[64];
  const size_t len = n < sizeof text - 1 ? n : sizeof text - 1;
  memcpy(text, w, len);
  text[len] = '\0';
  char* stop = nullptr;
  const double d = c.kind == 'f' ? strtod(text, &stop) : double(strtoll(text, &stop, 10));
  if (stop == text) return false;
  if (!(d >= 0) || !std::isfinite(d)) not_a_count(i, "negative or not a finite number");
  // strtoll saturates where a stream fails, which can only raise the bound.
  *v = d >= kHuge ? uint64_t(kHuge) : uint64_t(d);
  return true;
}

} // namespace

CellArray cell_array(const char* b, const char* e) {
  static const struct {
    const char* type;
    size_t size;
    char kind;
  } k[] = {{"Int8", 1, 'i'},   {"UInt8", 1, 'u'}, {"Int16", 2, 'i'},  {"UInt16", 2, 'u'},  {"Int32", 4, 'i'},
           {"UInt32", 4, 'u'}, {"Int64", 8, 'i'}, {"UInt64", 8, 'u'}, {"Float32", 4, 'f'}, {"Float64", 8, 'f'}};
  std::string name, type;
  CellArray c;
  if (!xml_attribute(b, e, "Name", &name) || (name != "offsets" && name != "connectivity")) return c;
  xml_attribute(b, e, "type", &type);
  for (const auto& t : k)
    if (type == t.type) c.size = t.size, c.kind = t.kind;
  if (c.size) c.role = name == "offsets" ? CellArray::kOffsets : CellArray::kConnectivity;
  return c;
}

void CellBlocks::connectivity(uint64_t ids) { ids_ = ids < ids_ ? ids : ids_; }

void CellBlocks::binary_offsets(uint64_t i, const unsigned char* q, uint64_t n, CellArray c, bool big_endian) {
  uint64_t max = 0;
  for (uint64_t k = 0; k < n; ++k) {
    const uint64_t v = binary_value(i, q + k * c.size, c, big_endian);
    max = v > max ? v : max;
  }
  offsets(i, max);
}

void CellBlocks::ascii_offsets(uint64_t i, const char* p, const char* end, CellArray c) {
  uint64_t max = 0, v = 0;
  while (p < end) {
    while (p < end && is_space(*p))
      ++p;
    const char* w = p;
    while (p < end && !is_space(*p))
      ++p;
    if (p == w || !ascii_value(i, w, size_t(p - w), c, &v)) break;
    max = v > max ? v : max;
  }
  offsets(i, max);
}

void CellBlocks::offsets(uint64_t i, uint64_t max) {
  if (!offsets_ || max > max_offset_) max_offset_ = max, offsets_index_ = i;
  offsets_ = true;
}

void CellBlocks::end_block() {
  const uint64_t ids = ids_ == UINT64_MAX ? 0 : ids_; // no connectivity: VTK reads none
  if (offsets_ && max_offset_ > ids)
    fail(TLOD_ERROR_PARSE,
         format("DataArray %llu (offsets): the offset %llu is past the %llu connectivity ids",
                (unsigned long long)offsets_index_, (unsigned long long)max_offset_, (unsigned long long)ids));
  *this = CellBlocks();
}

} // namespace tlod_import_detail
