// vtk_preflight.cpp -- what a VTK file declares, checked before VTK allocates it (docs/vtk.md
// section 7). Legacy files are scanned word by word as VTK reads them (keywords matched
// case-insensitively by prefix, as vtkDataReader does), so a keyword VTK would act on is one we
// have checked; a keyword-like word inside binary data can only make the check stricter.
#include "vtk_preflight.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <strings.h>

#include "import_error.hpp"

namespace tlod_import_detail {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

// Whitespace-separated words of [p, end).
struct Words {
  const char* p;
  const char* end;

  bool next(const char** w, size_t* n) {
    while (p < end && is_space(*p))
      ++p;
    if (p == end) return false;
    *w = p;
    while (p < end && !is_space(*p))
      ++p;
    *n = size_t(p - *w);
    return true;
  }

  // The next word as a non-negative integer; false (and the word consumed) if it is not one.
  bool number(uint64_t* v) {
    const char* w;
    size_t n;
    if (!next(&w, &n) || n > 19) return false;
    uint64_t x = 0;
    for (size_t i = 0; i < n; ++i) {
      if (w[i] < '0' || w[i] > '9') return false;
      x = x * 10 + uint64_t(w[i] - '0');
    }
    *v = x;
    return true;
  }

  // The next word, lower-case (its first 24 characters); "" at the end. Words that cannot be
  // keywords (not starting with a letter: numbers, binary data) come back as "0" unread.
  std::string word() {
    const char* w;
    size_t n;
    if (!next(&w, &n)) return "";
    if (!std::isalpha(static_cast<unsigned char>(w[0]))) return "0";
    std::string s(w, std::min<size_t>(n, 24));
    for (char& c : s)
      c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
  }
};

bool starts_with(const std::string& s, const char* prefix) { return s.compare(0, strlen(prefix), prefix) == 0; }

// Bytes per value of a legacy type name in a binary file; 0: not a type name.
size_t type_size(const std::string& t) {
  static const struct {
    const char* name;
    size_t size;
  } kTypes[] = {{"bit", 1},
                {"unsigned_char", 1},
                {"char", 1},
                {"unsigned_short", 2},
                {"short", 2},
                {"unsigned_int", 4},
                {"int", 4},
                {"unsigned_long", 8},
                {"long", 8},
                {"float", 4},
                {"double", 8},
                {"vtkidtype", 4},
                {"vtktypeint64", 8},
                {"vtktypeuint64", 8},
                {"vtktypeint32", 4},
                {"vtktypeuint32", 4},
                {"vtktypeint8", 1},
                {"vtktypeuint8", 1},
                {"vtktypeint16", 2},
                {"vtktypeuint16", 2},
                {"vtktypefloat32", 4},
                {"vtktypefloat64", 8},
                {"signed_char", 1},
                {"string", 1}};
  for (const auto& k : kTypes)
    if (t == k.name) return k.size;
  return 0;
}

class Legacy {
public:
  Legacy(const char* d, size_t n, size_t room) : begin_(d), words_{d, d + n}, room_(room) {}

  void header(std::string* dataset) {
    const char* nl = static_cast<const char*>(memchr(begin_, '\n', size_t(words_.end - begin_)));
    if (size_t(words_.end - begin_) < 14 || strncasecmp(begin_, "# vtk DataFile", 14) != 0)
      fail(TLOD_ERROR_PARSE, "not a legacy VTK file (the first line must be '# vtk DataFile Version x.y')");
    const char* title = nl ? nl + 1 : words_.end;
    const char* tnl = static_cast<const char*>(memchr(title, '\n', size_t(words_.end - title)));
    if (!tnl) fail(TLOD_ERROR_PARSE, "truncated header (no title line)");
    words_.p = tnl + 1;
    const char* v = begin_ + 14;
    while (v < nl && !(*v >= '0' && *v <= '9'))
      ++v;
    offsets_layout_ = v < nl && atoi(v) >= 5; // 5.x: CELLS n m counts n = cells + 1 offsets
    const std::string mode = words_.word();
    if (mode != "ascii" && mode != "binary") fail(TLOD_ERROR_PARSE, "line 3: expected ASCII or BINARY");
    binary_ = mode == "binary";
    if (words_.word() != "dataset") fail(TLOD_ERROR_PARSE, "line 4: expected DATASET");
    *dataset = words_.word();
  }

  void body() {
    for (std::string w = words_.word(); !w.empty(); w = words_.word())
      keyword(w);
  }

private:
  const char* begin_;
  Words words_;
  size_t room_;
  bool binary_ = false;
  uint64_t tuples_ = 0; // of the current POINT_DATA / CELL_DATA section
  bool offsets_layout_ = false;
  uint64_t points_ = UINT64_MAX, cells_ = UINT64_MAX; // as declared; UINT64_MAX: not yet

  // VTK sizes one array by one declaration and fills it by another: they must agree.
  void agree(const char* what, uint64_t n, const char* other, uint64_t m) {
    if (m != UINT64_MAX && n != m)
      fail(TLOD_ERROR_PARSE,
           format("%s %llu disagrees with %s %llu", what, (unsigned long long)n, other, (unsigned long long)m));
  }

  // values of width bytes (binary) must fit the rest of the file, and 8 bytes each the budget.
  void need(const std::string& what, uint64_t count, uint64_t per, size_t width) {
    uint64_t values, bytes, mem;
    const uint64_t left = uint64_t(words_.end - words_.p);
    const uint64_t w = binary_ ? (width ? width : 1) : 2;
    if (__builtin_mul_overflow(count, per, &values) || __builtin_mul_overflow(values, w, &bytes) ||
        (bytes > 0 && bytes - (binary_ ? 0 : 1) > left))
      fail(TLOD_ERROR_PARSE,
           format("%s: declares %llu x %llu values, more than the %llu bytes left in the file", what.c_str(),
                  (unsigned long long)count, (unsigned long long)per, (unsigned long long)left));
    if (__builtin_mul_overflow(values, uint64_t(8), &mem) || mem > room_)
      fail(TLOD_ERROR_OUT_OF_MEMORY,
           format("%s: %llu values exceed the import's memory budget (%zu bytes; tlod_import_desc.memory_limit)",
                  what.c_str(), (unsigned long long)values, room_));
  }

  void counted(const std::string& upper, uint64_t per, bool typed) {
    uint64_t n;
    if (!words_.number(&n)) return;
    if (upper == "POINTS") points_ = n;
    if (upper == "CELL_TYPES") agree("CELL_TYPES", n, "the cell count of CELLS", cells_);
    const size_t width = typed ? type_size(words_.word()) : 4;
    need(upper, n, per, width);
  }

  void cells(const std::string& upper) {
    uint64_t n, size;
    if (!words_.number(&n) || !words_.number(&size)) return;
    if (upper == "CELLS") cells_ = offsets_layout_ && n > 0 ? n - 1 : n;
    need(upper, size, 1, 4);
    need(upper, n, 1, 1);
    if (!offsets_layout_) walk_cells(upper, n, size);
  }

  // The classic layout: n cells as "count id id ..." in size values. VTK walks the counts
  // without checking them against size (vtkCellArray::AppendLegacyFormat reads past its
  // buffer on a count too large), so the walk is done here first: every count must fit.
  void walk_cells(const std::string& upper, uint64_t n, uint64_t size) {
    uint64_t at = 0;
    const unsigned char* bin = nullptr;
    if (binary_) {
      const char* nl = static_cast<const char*>(memchr(words_.p, '\n', size_t(words_.end - words_.p)));
      if (!nl) fail(TLOD_ERROR_PARSE, upper + ": no data");
      bin = reinterpret_cast<const unsigned char*>(nl + 1);
    }
    for (uint64_t c = 0; c < n; ++c) {
      uint64_t count;
      if (at >= size || !value(bin, at, &count) || count > size - at - 1)
        fail(TLOD_ERROR_PARSE, format("%s: cell %llu: its point count runs past the %llu values declared",
                                      upper.c_str(), (unsigned long long)c, (unsigned long long)size));
      at += 1 + count;
      if (!bin) skip_values(count);
    }
    if (at != size)
      fail(TLOD_ERROR_PARSE, format("%s: %llu cells use %llu of the %llu values declared", upper.c_str(),
                                    (unsigned long long)n, (unsigned long long)at, (unsigned long long)size));
    if (bin) words_.p = std::min(words_.end, reinterpret_cast<const char*>(bin) + size * 4);
  }

  // Value at of a cell list: binary big-endian int32 (bin), else the next ASCII word.
  bool value(const unsigned char* bin, uint64_t at, uint64_t* v) {
    if (!bin) return words_.number(v);
    const unsigned char* q = bin + at * 4;
    if (q + 4 > reinterpret_cast<const unsigned char*>(words_.end)) return false;
    const int32_t x = int32_t(uint32_t(q[0]) << 24 | uint32_t(q[1]) << 16 | uint32_t(q[2]) << 8 | q[3]);
    *v = uint64_t(x < 0 ? 0 : x);
    return x >= 0;
  }

  // NAME TYPE (per tuple: per values) for SCALARS (NAME TYPE [NCOMP]), VECTORS, TENSORS ...
  void array(const std::string& upper, uint64_t per) {
    words_.word(); // name
    const size_t width = type_size(words_.word());
    uint64_t comps = 1;
    if (upper == "SCALARS") {
      const char* save = words_.p;
      if (!words_.number(&comps)) comps = 1, words_.p = save;
    }
    need(upper, tuples_, per * comps, width);
  }

  // FIELD NAME N, then N times: ARRAYNAME NCOMP NTUPLES TYPE followed by the data. The data is
  // skipped word by word in ASCII; in binary, the arrays' headers are found as the words follow.
  void field() {
    words_.word();
    uint64_t n;
    if (!words_.number(&n)) return;
    for (uint64_t i = 0; i < n; ++i) {
      const char* w;
      size_t len;
      if (!words_.next(&w, &len)) return;
      const std::string name(w, std::min<size_t>(len, 64));
      uint64_t comps, count;
      if (!words_.number(&comps) || !words_.number(&count)) return;
      const size_t width = type_size(words_.word());
      need("FIELD array '" + name + "'", count, comps, width);
      if (binary_) return; // data follows as bytes: the scan continues word by word
      skip_values(comps * count);
    }
  }

  void skip_values(uint64_t n) {
    const char* w;
    size_t len;
    for (uint64_t i = 0; i < n && words_.next(&w, &len); ++i) {
    }
  }

  void dimensions() {
    uint64_t d[3];
    if (!words_.number(&d[0]) || !words_.number(&d[1]) || !words_.number(&d[2])) return;
    uint64_t pts, mem;
    if (__builtin_mul_overflow(d[0], d[1], &pts) || __builtin_mul_overflow(pts, d[2], &pts) ||
        __builtin_mul_overflow(pts, uint64_t(64), &mem) || mem > room_ || pts > (uint64_t(1) << 31))
      fail(TLOD_ERROR_OUT_OF_MEMORY,
           format("DIMENSIONS %llu %llu %llu: more points than the import's memory budget (%zu bytes)",
                  (unsigned long long)d[0], (unsigned long long)d[1], (unsigned long long)d[2], room_));
  }

  void keyword(const std::string& w) {
    if (!strchr("pctlvxyzdsngf", w[0])) return; // no keyword starts otherwise (most words of data)
    if (starts_with(w, "points")) return counted("POINTS", 3, true);
    if (starts_with(w, "cells")) return cells("CELLS");
    if (starts_with(w, "polygons")) return cells("POLYGONS");
    if (starts_with(w, "triangle_strips")) return cells("TRIANGLE_STRIPS");
    if (starts_with(w, "lines")) return cells("LINES");
    if (starts_with(w, "vertices")) return cells("VERTICES");
    if (starts_with(w, "cell_types")) return counted("CELL_TYPES", 1, false);
    if (starts_with(w, "x_coordinates") || starts_with(w, "y_coordinates") || starts_with(w, "z_coordinates"))
      return counted("COORDINATES", 1, true);
    if (starts_with(w, "dimensions")) return dimensions();
    if (starts_with(w, "point_data") || starts_with(w, "cell_data")) {
      if (!words_.number(&tuples_)) tuples_ = 0;
      if (w[0] == 'p')
        agree("POINT_DATA", tuples_, "POINTS", points_);
      else
        agree("CELL_DATA", tuples_, "the cell count of CELLS", cells_);
      return;
    }
    if (starts_with(w, "color_scalars")) {
      words_.word();
      uint64_t n;
      if (words_.number(&n)) need("COLOR_SCALARS", tuples_, n, 1);
      return;
    }
    if (starts_with(w, "scalars")) return array("SCALARS", 1);
    if (starts_with(w, "vectors")) return array("VECTORS", 3);
    if (starts_with(w, "normals")) return array("NORMALS", 3);
    if (starts_with(w, "tensors6")) return array("TENSORS6", 6);
    if (starts_with(w, "tensors")) return array("TENSORS", 9);
    if (starts_with(w, "global_ids") || starts_with(w, "pedigree_ids")) return array("IDS", 1);
    if (starts_with(w, "texture_coordinates")) {
      words_.word();
      uint64_t dim;
      if (words_.number(&dim)) need("TEXTURE_COORDINATES", tuples_, dim, type_size(words_.word()));
      return;
    }
    if (starts_with(w, "lookup_table")) {
      words_.word();
      const char* save = words_.p;
      uint64_t n;
      if (words_.number(&n))
        need("LOOKUP_TABLE", n, 4, 1);
      else
        words_.p = save;
      return;
    }
    if (starts_with(w, "field")) return field();
  }
};

} // namespace

bool xml_attribute(const char* p, const char* end, const char* name, std::string* value) {
  const size_t n = strlen(name);
  for (const char* q = p; q + n < end; ++q) {
    if (memcmp(q, name, n) != 0 || (q > p && !is_space(q[-1]))) continue;
    const char* r = q + n;
    while (r < end && is_space(*r))
      ++r;
    if (r == end || *r != '=') continue;
    ++r;
    while (r < end && is_space(*r))
      ++r;
    if (r == end || (*r != '"' && *r != '\'')) continue;
    const char* close = static_cast<const char*>(memchr(r + 1, *r, size_t(end - r - 1)));
    if (!close) return false;
    value->assign(r + 1, close);
    return true;
  }
  return false;
}

void xml_tags(const char* data, size_t size, const char* name,
              const std::function<void(const char* begin, const char* end)>& each) {
  const char* end = data + size;
  const size_t n = strlen(name);
  for (const char* p = data; (p = static_cast<const char*>(memchr(p, '<', size_t(end - p)))) != nullptr; ++p) {
    const char* close = static_cast<const char*>(memchr(p, '>', size_t(end - p)));
    if (!close) return;
    if (size_t(close - p) > n + 1 && memcmp(p + 1, name, n) == 0 && (is_space(p[n + 1]) || p[n + 1] == '/'))
      each(p, close);
  }
}

namespace {

uint64_t attribute_count(const char* p, const char* end, const char* name, const char* tag, uint64_t index) {
  std::string v;
  if (!xml_attribute(p, end, name, &v)) return 0;
  char* stop = nullptr;
  errno = 0;
  const long long x = strtoll(v.c_str(), &stop, 10);
  if (v.empty() || *stop || x < 0 || errno)
    fail(TLOD_ERROR_PARSE,
         format("%s %llu: %s=\"%.32s\" is not a count", tag, (unsigned long long)index, name, v.c_str()));
  return uint64_t(x);
}

} // namespace

void preflight_legacy(const char* data, size_t size, size_t room, std::string* dataset) {
  Legacy l(data, size, room);
  l.header(dataset);
  l.body();
}

void preflight_xml(const char* data, size_t size, size_t room) {
  const char* end = data + size;
  uint64_t piece = 0, points = 0, cells = 0, bytes = 0;
  for (const char* p = data; (p = static_cast<const char*>(memchr(p, '<', size_t(end - p)))) != nullptr; ++p) {
    const char* close = static_cast<const char*>(memchr(p, '>', size_t(end - p)));
    if (!close) break;
    if (size_t(end - p) > 6 && memcmp(p, "<Piece", 6) == 0 && is_space(p[6])) {
      points = attribute_count(p, close, "NumberOfPoints", "Piece", piece);
      cells = attribute_count(p, close, "NumberOfCells", "Piece", piece);
      for (const char* k : {"NumberOfVerts", "NumberOfLines", "NumberOfStrips", "NumberOfPolys"})
        cells += attribute_count(p, close, k, "Piece", piece);
      if (points > (uint64_t(1) << 40) || cells > (uint64_t(1) << 40))
        fail(TLOD_ERROR_OUT_OF_MEMORY,
             format("Piece %llu: %llu points, %llu cells: past any budget", (unsigned long long)piece,
                    (unsigned long long)points, (unsigned long long)cells));
      bytes += points * 24 + cells * 80; // coordinates; about 8 ids, offset and type per cell
      piece++;
    } else if (size_t(end - p) > 10 && memcmp(p, "<DataArray", 10) == 0) {
      uint64_t comps = attribute_count(p, close, "NumberOfComponents", "DataArray", 0);
      const uint64_t tuples = attribute_count(p, close, "NumberOfTuples", "DataArray", 0);
      if (comps == 0) comps = 1;
      if (comps > 4096)
        fail(TLOD_ERROR_UNSUPPORTED,
             format("DataArray: NumberOfComponents %llu (at most 4096)", (unsigned long long)comps));
      const uint64_t n = tuples > std::max(points, cells) ? tuples : std::max(points, cells);
      if (n > (uint64_t(1) << 40)) fail(TLOD_ERROR_OUT_OF_MEMORY, "DataArray: NumberOfTuples past any budget");
      bytes += comps * n * 8;
    }
    if (bytes > room)
      fail(TLOD_ERROR_OUT_OF_MEMORY,
           format("Piece %llu: its declared points, cells and arrays exceed the import's memory budget (%zu bytes; "
                  "tlod_import_desc.memory_limit)",
                  (unsigned long long)(piece ? piece - 1 : 0), room));
  }
}

void preflight_stl(const char* data, size_t size) {
  const bool ascii = size >= 5 && strncasecmp(data, "solid", 5) == 0 && memchr(data, 0, size) == nullptr;
  if (ascii) return;
  if (size < 84) fail(TLOD_ERROR_PARSE, format("binary STL: %zu bytes, shorter than its 84-byte header", size));
  uint32_t n;
  memcpy(&n, data + 80, 4);
  if (uint64_t(n) * 50 + 84 > size)
    fail(TLOD_ERROR_PARSE, format("binary STL: declares %u triangles, the file holds %zu", n, (size - 84) / 50));
}

} // namespace tlod_import_detail
