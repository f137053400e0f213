// vtk_preflight.cpp -- what a VTK file declares, checked before VTK allocates it (docs/vtk.md
// section 7). Legacy files are scanned word by word as VTK reads them (keywords matched
// case-insensitively by prefix, as vtkDataReader does), so a keyword VTK would act on is one we
// have checked; a keyword-like word inside binary data can only make the check stricter.
#include "vtk_preflight.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <strings.h>

#include "import_error.hpp"

namespace tlod_import_detail {
namespace {

// Whitespace-separated words of [p, end).
struct Words {
  const char* p;
  const char* end;

  bool next(const char** w, size_t* n) {
    while (p < end && is_space(*p))
      ++p;
    if (p == end) return false;
    *w = p;
    while (p < end && !is_space(*p) && p - *w < 255) // vtkDataReader::ReadString stops at 255 characters
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

  // The next word as a count VTK will allocate by: a C++ stream would take the digits of "9q" and
  // go on, so a word that is not wholly a non-negative integer ends the file here.
  uint64_t count(const char* what) {
    uint64_t v;
    if (!number(&v)) fail(TLOD_ERROR_PARSE, format("%s: expected a count (a non-negative integer)", what));
    return v;
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

// Widths that are not a byte count: bits packed 8 a byte; strings, each with its length first.
constexpr size_t kBit = SIZE_MAX - 1, kString = SIZE_MAX - 2;

// Bytes per value of a legacy type name in a binary file (or kBit, kString); 0: not a type name.
size_t type_size(const std::string& t) {
  static const struct {
    const char* name;
    size_t size;
  } kTypes[] = {{"unsigned_char", 1},  {"char", 1},         {"unsigned_short", 2}, {"short", 2},
                {"unsigned_int", 4},   {"int", 4},          {"unsigned_long", 8},  {"long", 8},
                {"float", 4},          {"double", 8},       {"vtkidtype", 4},      {"vtktypeint64", 8},
                {"vtktypeuint64", 8},  {"vtktypeint32", 4}, {"vtktypeuint32", 4},  {"vtktypeint8", 1},
                {"vtktypeuint8", 1},   {"vtktypeint16", 2}, {"vtktypeuint16", 2},  {"vtktypefloat32", 4},
                {"vtktypefloat64", 8}, {"signed_char", 1}};
  for (const auto& k : kTypes)
    if (t == k.name) return k.size;
  if (t == "bit") return kBit;
  if (t == "string" || t == "utf8_string") return kString;
  return 0; // not a type VTK reads
}

class Legacy {
public:
  Legacy(const char* d, size_t n, size_t room) : begin_(d), words_{d, d + n}, room_(room) {}

  void header(std::string* dataset) {
    const char* nl = static_cast<const char*>(memchr(begin_, '\n', size_t(words_.end - begin_)));
    if (size_t(words_.end - begin_) < 22 || strncmp(begin_, "# vtk DataFile Version", 22) != 0)
      fail(TLOD_ERROR_PARSE, "not a legacy VTK file (the first line must be '# vtk DataFile Version x.y')");
    const char* title = nl ? nl + 1 : words_.end;
    const char* tnl = static_cast<const char*>(memchr(title, '\n', size_t(words_.end - title)));
    if (!tnl) fail(TLOD_ERROR_PARSE, "truncated header (no title line)");
    words_.p = tnl + 1;
    // The version as vtkDataReader reads it: sscanf "%d.%d" after the 22-character prefix; when
    // that fails VTK takes version 0 (the classic layout), and so do we.
    char line[64] = {0};
    memcpy(line, begin_ + 22, std::min<size_t>(size_t((nl ? nl : words_.end) - begin_) - 22, sizeof line - 1));
    int major = 0, minor = 0;
    offsets_layout_ = sscanf(line, "%d.%d", &major, &minor) == 2 && major >= 5; // 5.x: CELLS n m, n = cells + 1
    const std::string mode = words_.word();
    if (mode != "ascii" && mode != "binary") fail(TLOD_ERROR_PARSE, "line 3: expected ASCII or BINARY");
    binary_ = mode == "binary";
    if (words_.word() != "dataset") fail(TLOD_ERROR_PARSE, "line 4: expected DATASET");
    *dataset = words_.word();
  }

  // Sections in order; each section's data is consumed exactly (ASCII: parsed; binary: skipped),
  // so every word between them must be a keyword VTK knows: VTK's
  // legacy readers leak what they read so far on "Unrecognized keyword" (LeakSanitizer).
  void body() {
    for (std::string w = words_.word(); !w.empty(); w = words_.word())
      if (!keyword(w))
        fail(TLOD_ERROR_PARSE, format("unknown keyword '%.24s' where a section should start", w.c_str()));
  }

private:
  const char* begin_;
  Words words_;
  size_t room_;
  bool binary_ = false;
  bool integer_ = false;     // the section being read holds integers (its type, or CELL_TYPES)
  bool after_array_ = false; // the last section was an array VTK reads with its METADATA (ReadArray)
  uint64_t tuples_ = 0;      // of the current POINT_DATA / CELL_DATA section
  bool offsets_layout_ = false;
  uint64_t offsets_ = 0, connectivity_ = 0;           // 5.x: the values of the OFFSETS and CONNECTIVITY blocks
  uint64_t points_ = UINT64_MAX, cells_ = UINT64_MAX; // as declared; UINT64_MAX: not yet

  // type_size() of a type name; also notes whether the type holds integers (ASCII check).
  size_t type(const std::string& t) {
    integer_ = t.find("int") != std::string::npos || t.find("char") != std::string::npos ||
               t.find("short") != std::string::npos || t.find("long") != std::string::npos || t == "vtkidtype" ||
               t == "bit";
    return type_size(t);
  }

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
    const uint64_t w = !binary_ ? 2 : width == kBit || width == kString ? 0 : width; // 0: checked by consume()
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
    const uint64_t n = words_.count(upper.c_str());
    if (upper == "POINTS") points_ = n;
    if (upper == "CELL_TYPES") agree("CELL_TYPES", n, "the cell count of CELLS", cells_);
    const size_t width = typed ? type(words_.word()) : (integer_ = true, 4);
    need(upper, n, per, width);
    consume(upper, n * per, width);
  }

  void cells(const std::string& upper) {
    const uint64_t n = words_.count(upper.c_str()), size = words_.count(upper.c_str());
    if (upper == "CELLS") cells_ = offsets_layout_ && n > 0 ? n - 1 : n;
    if (offsets_layout_) offsets_ = n, connectivity_ = size;
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
      for (uint64_t k = 0; !bin && k < count; ++k) { // ids, whole decimal words (as VTK's stream reads them)
        uint64_t id;
        if (!words_.number(&id))
          fail(TLOD_ERROR_PARSE, format("%s: cell %llu: point id %llu is not a non-negative integer", upper.c_str(),
                                        (unsigned long long)c, (unsigned long long)k));
      }
    }
    if (at != size)
      fail(TLOD_ERROR_PARSE, format("%s: %llu cells use %llu of the %llu values declared", upper.c_str(),
                                    (unsigned long long)n, (unsigned long long)at, (unsigned long long)size));
    if (bin) words_.p = std::min(words_.end, reinterpret_cast<const char*>(bin) + size * 4);
  }

  // 5.x: OFFSETS type / CONNECTIVITY type, then count values. In ASCII each must be an integer:
  // VTK's reader leaks its cell array when one is not (LeakSanitizer under fuzz_vtk).
  void block(const char* upper, uint64_t count) {
    const size_t width = type(words_.word());
    need(upper, count, 1, width);
    if (binary_) return consume(upper, count, width);
    for (uint64_t i = 0; i < count; ++i) {
      uint64_t v;
      if (!words_.number(&v))
        fail(TLOD_ERROR_PARSE, format("%s: value %llu is not a non-negative integer", upper, (unsigned long long)i));
    }
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
    const size_t width = type(words_.word());
    uint64_t comps = 1;
    if (upper == "SCALARS") {
      const char* save = words_.p;
      if (!words_.number(&comps)) comps = 1, words_.p = save;
      const char* before = words_.p;
      if (starts_with(words_.word(), "lookup_table"))
        words_.word(); // its table's name
      else
        words_.p = before;
    }
    need(upper, tuples_, per * comps, width);
    consume(upper, tuples_ * per * comps, width);
  }

  // FIELD NAME N, then N times: ARRAYNAME NCOMP NTUPLES TYPE followed by the data. The data is
  // skipped word by word in ASCII; in binary, the arrays' headers are found as the words follow.
  // VTK's legacy reader crashes (null read in ReadMeshSimple) on a FIELD it cannot read: every
  // array header must be there and well formed.
  void field() {
    words_.word();
    uint64_t n;
    if (!words_.number(&n)) fail(TLOD_ERROR_PARSE, "FIELD: expected its name and array count");
    for (uint64_t i = 0; i < n; ++i) {
      const char* w = nullptr;
      size_t len = 0;
      uint64_t comps, count;
      if (words_.next(&w, &len) && len == 10 && memcmp(w, "NULL_ARRAY", 10) == 0) continue; // vtkDataWriter's
      if (!len || !words_.number(&comps) || !words_.number(&count))
        fail(TLOD_ERROR_PARSE, format("FIELD array %llu: expected NAME COMPONENTS TUPLES TYPE", (unsigned long long)i));
      const std::string name(w, std::min<size_t>(len, 64));
      const size_t width = type(words_.word());
      need("FIELD array '" + name + "'", count, comps, width);
      consume("FIELD array '" + name + "'", comps * count, width);
      const char* after = words_.p; // an array may be followed by its METADATA (VTK reads it there)
      if (starts_with(words_.word(), "metadata"))
        metadata();
      else
        words_.p = after;
    }
  }

  // The data of a section: n values of width bytes (binary: skipped after the header line's end;
  // width 0: unknown, strict mode ends), or n ASCII numbers (parsed).
  void consume(const std::string& what, uint64_t n, size_t width) {
    // An unknown type, even of an empty array: VTK's FIELD reader dereferences the null array it gets.
    if (width == 0) fail(TLOD_ERROR_PARSE, what + ": not a type VTK reads");
    if (!binary_) return width == kString ? skip_values(n) : numbers(what, n);
    const char* nl = static_cast<const char*>(memchr(words_.p, '\n', size_t(words_.end - words_.p)));
    if (!nl) fail(TLOD_ERROR_PARSE, what + ": no data");
    words_.p = nl + 1;
    if (width == kString) return strings(what, n);
    const uint64_t bytes = width == kBit ? (n + 7) / 8 : n, size = width == kBit ? 1 : width;
    if (bytes > uint64_t(words_.end - words_.p) / size)
      fail(TLOD_ERROR_PARSE,
           format("%s: its %llu values run past the end of the file", what.c_str(), (unsigned long long)n));
    words_.p += bytes * size;
  }

  // Binary strings as vtkDataWriter writes them: a length (its top two bits give its size: 11 one
  // byte, 10 two, 01 four, 00 eight, big-endian) and the bytes.
  void strings(const std::string& what, uint64_t n) {
    const unsigned char* q = reinterpret_cast<const unsigned char*>(words_.p);
    const unsigned char* end = reinterpret_cast<const unsigned char*>(words_.end);
    for (uint64_t i = 0; i < n; ++i) {
      if (q >= end) fail(TLOD_ERROR_PARSE, format("%s: string %llu past the end", what.c_str(), (unsigned long long)i));
      const int tag = q[0] >> 6;
      const size_t k = tag == 3 ? 1 : tag == 2 ? 2 : tag == 1 ? 4 : 8;
      if (size_t(end - q) < k)
        fail(TLOD_ERROR_PARSE, format("%s: string %llu past the end", what.c_str(), (unsigned long long)i));
      uint64_t len = k == 8 ? 0 : q[0] & 0x3f;
      for (size_t b = 1; b < k; ++b)
        len = len << 8 | q[b];
      q += k;
      if (len > uint64_t(end - q))
        fail(TLOD_ERROR_PARSE,
             format("%s: string %llu runs past the end of the file", what.c_str(), (unsigned long long)i));
      q += len;
    }
    words_.p = reinterpret_cast<const char*>(q);
  }

  // ASCII: the next n words must be finite numbers. VTK's legacy reader leaks its arrays when
  // a value does not parse (LeakSanitizer under fuzz_vtk), so it never gets such a file.
  void numbers(const std::string& what, uint64_t n, bool text = false) {
    if (binary_ && !text) return;
    char buf[64];
    for (uint64_t i = 0; i < n; ++i) {
      const char* w;
      size_t len;
      if (!words_.next(&w, &len))
        fail(TLOD_ERROR_PARSE, format("%s: the file ends after %llu of its %llu values", what.c_str(),
                                      (unsigned long long)i, (unsigned long long)n));
      char* stop = nullptr;
      const size_t k = std::min(len, sizeof buf - 1);
      memcpy(buf, w, k);
      buf[k] = 0;
      // As C++ streams read them (VTK does): decimal only, the whole word, integers for integer types.
      const bool digits = strspn(buf, integer_ ? "0123456789+-" : "0123456789+-.eE") == len;
      const double v = strtod(buf, &stop);
      if (len >= sizeof buf || !digits || stop != buf + len || len == 0 || !std::isfinite(v))
        fail(TLOD_ERROR_PARSE, format("%s: value %llu '%.24s' is not a finite %s", what.c_str(), (unsigned long long)i,
                                      buf, integer_ ? "integer" : "number"));
    }
  }

  void skip_values(uint64_t n) {
    const char* w;
    size_t len;
    for (uint64_t i = 0; i < n && words_.next(&w, &len); ++i) {
    }
  }

  void dimensions() {
    const uint64_t d[3] = {words_.count("DIMENSIONS"), words_.count("DIMENSIONS"), words_.count("DIMENSIONS")};
    uint64_t pts, mem;
    if (__builtin_mul_overflow(d[0], d[1], &pts) || __builtin_mul_overflow(pts, d[2], &pts) ||
        __builtin_mul_overflow(pts, uint64_t(64), &mem) || mem > room_ || pts > (uint64_t(1) << 31))
      fail(TLOD_ERROR_OUT_OF_MEMORY,
           format("DIMENSIONS %llu %llu %llu: more points than the import's memory budget (%zu bytes)",
                  (unsigned long long)d[0], (unsigned long long)d[1], (unsigned long long)d[2], room_));
  }

  // Reads one section from its keyword w; false when w is not a keyword VTK knows.
  bool keyword(const std::string& w) {
    if (!strchr("pctlvxyzdsngfoam", w[0])) return false; // no keyword starts otherwise (most words of data)
    const bool after_array = after_array_;
    after_array_ = false;
    if (starts_with(w, "metadata")) return metadata_after(after_array), true;
    if (starts_with(w, "points")) return counted("POINTS", 3, true), after_array_ = true;
    for (const char* k : {"cells", "polygons", "triangle_strips", "lines", "vertices"})
      if (starts_with(w, k)) return cells(upper(k)), true;
    if (starts_with(w, "cell_types")) return counted("CELL_TYPES", 1, false), true;
    if (offsets_layout_ && starts_with(w, "offsets")) return block("OFFSETS", offsets_), after_array_ = true;
    if (offsets_layout_ && starts_with(w, "connectivity"))
      return block("CONNECTIVITY", connectivity_), after_array_ = true;
    if (starts_with(w, "x_coordinates") || starts_with(w, "y_coordinates") || starts_with(w, "z_coordinates"))
      return counted("COORDINATES", 1, true), after_array_ = true;
    if (starts_with(w, "dimensions")) return dimensions(), true;
    if (starts_with(w, "origin") || starts_with(w, "spacing") || starts_with(w, "aspect_ratio"))
      return integer_ = false, numbers(upper(w.c_str()), 3, true), true; // text even in binary files
    if (starts_with(w, "point_data") || starts_with(w, "cell_data")) return data_section(w), true;
    if (starts_with(w, "color_scalars")) return color_scalars(), true;
    static const struct {
      const char* word;
      const char* name;
      uint64_t per;
    } kArrays[] = {{"scalars", "SCALARS", 1},   {"vectors", "VECTORS", 3},      {"normals", "NORMALS", 3},
                   {"tensors6", "TENSORS6", 6}, {"tensors", "TENSORS", 9},      {"global_ids", "IDS", 1},
                   {"pedigree_ids", "IDS", 1},  {"edge_flags", "EDGE_FLAGS", 1}};
    for (const auto& a : kArrays)
      if (starts_with(w, a.word)) return array(a.name, a.per), after_array_ = true;
    if (starts_with(w, "texture_coordinates")) return texture_coordinates(), after_array_ = true;
    if (starts_with(w, "lookup_table")) return lookup_table(), true;
    if (starts_with(w, "field")) return field(), true;
    return false;
  }

  // A METADATA block is read only right after an array VTK reads with ReadArray (points,
  // coordinates, 5.x offsets and connectivity, attribute arrays, texture coordinates; FIELD
  // arrays read theirs in field()); after CELL_TYPES, classic cells, a lookup table or colour
  // scalars VTK's readers stop at "Unrecognized keyword" and leak what they read (a fuzz_vtk
  // finding: METADATA after CELL_TYPES).
  void metadata_after(bool after_array) {
    if (!after_array)
      fail(TLOD_ERROR_PARSE, "METADATA: not after an array VTK reads it with (VTK's reader would stop there)");
    metadata();
  }

  static std::string upper(const char* k) {
    std::string u(k);
    for (char& c : u)
      c = char(std::toupper(static_cast<unsigned char>(c)));
    return u;
  }

  void data_section(const std::string& w) {
    tuples_ = words_.count(w[0] == 'p' ? "POINT_DATA" : "CELL_DATA");
    if (w[0] == 'p')
      agree("POINT_DATA", tuples_, "POINTS", points_);
    else
      agree("CELL_DATA", tuples_, "the cell count of CELLS", cells_);
  }

  void color_scalars() {
    integer_ = false; // floats 0..1 in ASCII
    words_.word();
    const uint64_t n = words_.count("COLOR_SCALARS");
    need("COLOR_SCALARS", tuples_, n, 1);
    consume("COLOR_SCALARS", tuples_ * n, binary_ ? 1 : 4);
  }

  void texture_coordinates() {
    words_.word();
    const uint64_t dim = words_.count("TEXTURE_COORDINATES");
    const size_t width = type(words_.word());
    need("TEXTURE_COORDINATES", tuples_, dim, width);
    consume("TEXTURE_COORDINATES", tuples_ * dim, width);
  }

  // A standalone table: LOOKUP_TABLE NAME N, then N RGBA entries (bytes in binary).
  void lookup_table() {
    integer_ = false;
    words_.word();
    const uint64_t n = words_.count("LOOKUP_TABLE");
    need("LOOKUP_TABLE", n, 4, 1);
    consume("LOOKUP_TABLE", 4 * n, binary_ ? 1 : 4);
  }

  // METADATA: lines up to an empty one (vtkDataReader::ReadMetaData).
  void metadata() {
    for (const char* p = words_.p; p < words_.end; ++p) {
      const char* nl = static_cast<const char*>(memchr(p, '\n', size_t(words_.end - p)));
      if (!nl) break;
      const char* q = nl + 1;
      while (q < words_.end && (*q == ' ' || *q == '\t' || *q == '\r'))
        ++q;
      if (q < words_.end && *q == '\n' && p != words_.p) {
        words_.p = q + 1;
        return;
      }
      p = nl;
    }
    words_.p = words_.end;
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
  preflight_xml_headers(data, size, room);
  // Tags end where the appended (binary) data starts.
  const char* app = static_cast<const char*>(memmem(data, size, "<AppendedData", 13));
  const char* end = app ? app : data + size;
  uint64_t piece = 0, points = 0, cells = 0, bytes = 0;
  bool in_points = false; // the next DataArray holds a piece's points
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
    } else if (size_t(end - p) > 7 && memcmp(p, "<Points", 7) == 0) {
      in_points = true;
    } else if (size_t(end - p) > 10 && memcmp(p, "<DataArray", 10) == 0) {
      uint64_t comps = attribute_count(p, close, "NumberOfComponents", "DataArray", 0);
      const uint64_t tuples = attribute_count(p, close, "NumberOfTuples", "DataArray", 0);
      if (comps == 0) comps = 1;
      // VTK's XML readers leak the points they made when these are not xyz (LeakSanitizer).
      if (in_points && comps != 3)
        fail(TLOD_ERROR_PARSE, format("Piece %llu: Points: NumberOfComponents %llu (must be 3)",
                                      (unsigned long long)(piece ? piece - 1 : 0), (unsigned long long)comps));
      in_points = false;
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
  // vtkSTLReader decides by kwsys's DetectFileType: of the first 256 bytes, 5 % or more that are
  // not text (0x20..0x7f, tab, newline, return) make the file binary; an empty one is binary too.
  // The same rule here, so the count is checked whenever VTK will believe it.
  const size_t head = std::min<size_t>(size, 256);
  size_t text = 0;
  for (size_t i = 0; i < head; ++i) {
    const unsigned char c = static_cast<unsigned char>(data[i]);
    text += (c >= 0x20 && c <= 0x7f) || c == '\n' || c == '\r' || c == '\t';
  }
  const bool ascii = head > 0 && double(head - text) / double(head) < 0.05;
  if (ascii) return;
  if (size < 84) fail(TLOD_ERROR_PARSE, format("binary STL: %zu bytes, shorter than its 84-byte header", size));
  uint32_t n;
  memcpy(&n, data + 80, 4);
  if (uint64_t(n) * 50 + 84 > size)
    fail(TLOD_ERROR_PARSE, format("binary STL: declares %u triangles, the file holds %zu", n, (size - 84) / 50));
}

} // namespace tlod_import_detail
