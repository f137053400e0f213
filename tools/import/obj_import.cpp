// obj_import.cpp -- Wavefront OBJ reader: a C shim over tinyobjloader (C++17, no exception leaves this file).
// Owned by the import/export layer (tools/import/).
//
// tinyobjloader is lenient where a mesh tool must not be: it reads "nan" or
// "1.0abc" as a number without complaint (0 and 1), ignores unknown lines,
// drops faces with fewer than 3 corners, stores a 256-corner face as 0
// corners, and only warns about out-of-range indices. So a strict line
// scan runs first: it checks every statement, number and index and names
// the line at fault; only text that passed is handed to tinyobjloader, and
// its output is checked once more against the scan before any index is
// used.
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <new>
#include <sstream>
#include <string>
#include <vector>

#include "contained_file.h"
#include "import_error.hpp"
#include "import_internal.h"
#include "import_output.hpp"
#include "obj_materials.hpp"

namespace {

using tlod_import_detail::fail;
using tlod_import_detail::format;
using tlod_import_detail::ImportError;

// tinyobjloader's num_face_vertices is an unsigned char.
constexpr size_t kMaxCorners = 255;
// A 255-corner "v/vt/vn" face fits in 10 KB; a longer line is not OBJ, and
// splitting it into words could take gigabytes.
constexpr size_t kMaxLine = size_t(1) << 20;

// ---------------------------------------------------------------------------
// The strict scan.

// An index written before what it refers to existed; checked at the end.
struct ForwardRef {
  size_t line;
  long value;
  int kind; // 0 v, 1 vt, 2 vn
};

struct Scan {
  size_t counts[3] = {0, 0, 0}; // v, vt, vn
  std::vector<size_t> face_lines;
  std::vector<size_t> face_corners;
  std::vector<ForwardRef> forward;
  std::string text; // what tinyobjloader reads: same lines, ignored ones blanked
  size_t ignored_elements = 0, first_ignored_line = 0;
  std::string first_ignored;
};

const char* const kKindName[3] = {"vertex", "texture coordinate", "normal"};
const char* const kKindStatement[3] = {"v", "vt", "vn"};

// Statements that describe no polygon: dropped with one warning.
bool is_ignored_statement(const std::string& k) {
  static const char* const list[] = {
      "l",        "p",    "vp",     "t",      "vw",         "cstype",    "deg",   "bmat",  "step", "curv",  "curv2",
      "surf",     "parm", "trim",   "hole",   "scrv",       "sp",        "end",   "con",   "mg",   "bevel", "c_interp",
      "d_interp", "lod",  "usemap", "maplib", "shadow_obj", "trace_obj", "ctech", "stech", "call", "csh"};
  for (const char* s : list)
    if (k == s) return true;
  return false;
}

// Statements tinyobjloader handles and that need no check here.
bool is_passed_statement(const std::string& k) {
  return k == "o" || k == "g" || k == "s" || k == "usemtl" || k == "mtllib";
}

std::vector<std::string> split_ws(const std::string& s) {
  std::vector<std::string> out;
  size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t'))
      ++i;
    size_t j = i;
    while (j < s.size() && s[j] != ' ' && s[j] != '\t')
      ++j;
    if (j > i) out.push_back(s.substr(i, j - i));
    i = j;
  }
  return out;
}

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// The number grammar tinyobjloader parses completely:
// [+-] (digits [. digits*] | . digits) [(e|E) [+-] digits]. Anything it
// would cut short ("1.0abc", "nan", "0x10") is rejected here.
bool is_obj_number(const std::string& s) {
  size_t i = 0;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  size_t digits = 0;
  while (i < s.size() && is_digit(s[i]))
    ++i, ++digits;
  if (i < s.size() && s[i] == '.') {
    ++i;
    while (i < s.size() && is_digit(s[i]))
      ++i, ++digits;
  }
  if (digits == 0) return false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    size_t exp_digits = 0;
    while (i < s.size() && is_digit(s[i]))
      ++i, ++exp_digits;
    if (exp_digits == 0) return false;
  }
  return i == s.size();
}

// tinyobjloader accumulates an exponent's digits in an int: "0e2147483649"
// overflows it (undefined behaviour). Floats need at most 2 exponent digits;
// one with more than 4 significant digits (past leading zeros) is refused.
constexpr size_t kMaxExponentDigits = 4;

// Does the number-like token s (starts with a digit, sign or '.') have an
// exponent longer than kMaxExponentDigits?
bool long_exponent(const std::string& s) {
  const size_t e = s.find_first_of("eE");
  if (e == std::string::npos) return false;
  size_t i = e + 1;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  while (i < s.size() && s[i] == '0')
    ++i;
  size_t digits = 0;
  while (i < s.size() && is_digit(s[i]))
    ++i, ++digits;
  return digits > kMaxExponentDigits;
}

bool number_like(const std::string& s) {
  return !s.empty() && (is_digit(s[0]) || s[0] == '+' || s[0] == '-' || s[0] == '.');
}

// Every number-like word of a material file, before tinyobjloader parses it.
void check_mtl_exponents(const std::string& text, const std::string& id) {
  size_t line = 0;
  for (size_t i = 0; i < text.size();) {
    size_t j = text.find_first_of("\r\n", i);
    if (j == std::string::npos) j = text.size();
    line++;
    for (const std::string& w : split_ws(text.substr(i, j - i)))
      if (number_like(w) && long_exponent(w))
        fail(TLOD_ERROR_PARSE,
             format("mtllib '%.200s': line %zu: '%.40s': exponent out of range", id.c_str(), line, w.c_str()));
    i = j + 1;
  }
}

class Scanner {
public:
  Scan run(const char* data, size_t size) {
    size_t i = 0;
    while (i < size) {
      size_t j = i;
      while (j < size && data[j] != '\n' && data[j] != '\r')
        ++j;
      line_++;
      if (j - i > kMaxLine) error(format("longer than %zu bytes", kMaxLine));
      scan_line(std::string(data + i, j - i));
      // Line ends as tinyobjloader splits them: \n, \r\n or a lone \r.
      if (j < size && data[j] == '\r' && j + 1 < size && data[j + 1] == '\n') ++j;
      i = j + 1;
    }
    check_forward_refs();
    return std::move(scan_);
  }

private:
  Scan scan_;
  size_t line_ = 0;

  [[noreturn]] void error(const std::string& what) const {
    fail(TLOD_ERROR_PARSE, format("line %zu: %s", line_, what.c_str()));
  }

  void keep(const std::string& line) {
    scan_.text += line;
    scan_.text += '\n';
  }

  void scan_line(const std::string& line) {
    if (line.find('\0') != std::string::npos) error("NUL byte (binary data in a text file?)");
    const std::vector<std::string> tok = split_ws(line);
    if (tok.empty() || tok[0][0] == '#') return keep(line);
    const std::string& k = tok[0];
    if (k == "v")
      numbers(tok, 3, 7, 0);
    else if (k == "vt")
      numbers(tok, 1, 3, 1);
    else if (k == "vn")
      numbers(tok, 3, 3, 2);
    else if (k == "f")
      face(tok);
    else if (is_ignored_statement(k))
      return ignore(k);
    else if (!is_passed_statement(k))
      error(format("unknown statement '%.40s'", k.c_str()));
    keep(line);
  }

  void ignore(const std::string& k) {
    if (scan_.ignored_elements++ == 0) {
      scan_.first_ignored = k;
      scan_.first_ignored_line = line_;
    }
    keep("");
  }

  void numbers(const std::vector<std::string>& tok, size_t min, size_t max, int kind) {
    const size_t n = tok.size() - 1;
    if (n < min || n > max) error(format("'%s' needs %zu to %zu numbers, has %zu", kKindStatement[kind], min, max, n));
    for (size_t t = 1; t < tok.size(); ++t) {
      if (!is_obj_number(tok[t])) error(format("'%.40s' is not a number", tok[t].c_str()));
      if (long_exponent(tok[t])) error(format("'%.40s': exponent out of range", tok[t].c_str()));
      // Finite as a float, since the mesh stores floats: 1e39 is rejected too.
      const float f = std::strtof(tok[t].c_str(), nullptr);
      if (!std::isfinite(f)) error(format("'%.40s' is not a finite float", tok[t].c_str()));
    }
    scan_.counts[kind]++;
  }

  void face(const std::vector<std::string>& tok) {
    const size_t n = tok.size() - 1;
    if (n < 3) error(format("face has %zu corner%s (at least 3 needed)", n, n == 1 ? "" : "s"));
    if (n > kMaxCorners) error(format("face has %zu corners (at most %zu supported)", n, kMaxCorners));
    for (size_t t = 1; t < tok.size(); ++t)
      corner(tok[t]);
    scan_.face_lines.push_back(line_);
    scan_.face_corners.push_back(n);
  }

  // v, v/vt, v//vn or v/vt/vn.
  void corner(const std::string& c) {
    std::vector<std::string> parts;
    size_t start = 0;
    for (size_t s; (s = c.find('/', start)) != std::string::npos; start = s + 1)
      parts.push_back(c.substr(start, s - start));
    parts.push_back(c.substr(start));
    const bool ok = parts.size() <= 3 && !parts[0].empty() && !(parts.size() == 2 && parts[1].empty()) &&
                    !(parts.size() == 3 && parts[2].empty());
    if (!ok) error(format("face corner '%.40s' is not v, v/vt, v//vn or v/vt/vn", c.c_str()));
    for (size_t p = 0; p < parts.size(); ++p)
      if (!parts[p].empty()) index(parts[p], int(p == 0 ? 0 : p == 1 ? 1 : 2));
  }

  void index(const std::string& s, int kind) {
    size_t i = (s[0] == '+' || s[0] == '-') ? 1 : 0;
    if (i == s.size() || s.size() > 11) error(format("bad %s index '%.40s'", kKindName[kind], s.c_str()));
    for (; i < s.size(); ++i)
      if (!is_digit(s[i])) error(format("bad %s index '%.40s'", kKindName[kind], s.c_str()));
    const long v = std::strtol(s.c_str(), nullptr, 10);
    const size_t have = scan_.counts[kind];
    if (v == 0) error(format("%s index 0 (OBJ indices start at 1)", kKindName[kind]));
    if (v > 2147483647L || v < -2147483647L) error(format("%s index %ld out of range", kKindName[kind], v));
    if (v < 0 && size_t(-v) > have)
      fail(TLOD_ERROR_INVALID_MESH, format("line %zu: relative %s index %ld reaches before the first '%s' (%zu so far)",
                                           line_, kKindName[kind], v, kKindStatement[kind], have));
    if (v > 0 && size_t(v) > have) scan_.forward.push_back({line_, v, kind});
  }

  // Forward references are legal in tinyobjloader (resolved at the end).
  void check_forward_refs() const {
    for (const ForwardRef& r : scan_.forward)
      if (size_t(r.value) > scan_.counts[r.kind])
        fail(TLOD_ERROR_INVALID_MESH, format("line %zu: %s index %ld out of range (%zu '%s' in the file)", r.line,
                                             kKindName[r.kind], r.value, scan_.counts[r.kind], kKindStatement[r.kind]));
  }
};

// ---------------------------------------------------------------------------
// Output.

struct Output : tlod_import_detail::OutputBase {
  std::vector<uint8_t> face_sizes;
  bool any_quads = false;
  uint32_t polygons_triangulated = 0;
};

class Builder {
public:
  Builder(const tinyobj::attrib_t& a, const std::vector<tinyobj::material_t>& mats, const Scan& scan, Output& out)
      : a_(a), mats_(mats), scan_(scan), out_(out) {}

  void run(const std::vector<tinyobj::shape_t>& shapes) {
    check_counts();
    for (size_t s = 0; s < shapes.size(); ++s)
      add_shape(shapes[s], s);
    if (face_ != scan_.face_lines.size())
      fail(TLOD_ERROR_PARSE,
           format("internal: tinyobjloader returned %zu faces, the scan found %zu", face_, scan_.face_lines.size()));
  }

private:
  const tinyobj::attrib_t& a_;
  const std::vector<tinyobj::material_t>& mats_;
  const Scan& scan_;
  Output& out_;
  // An output vertex: (v, vn + 1, vt + 1), so a vertex without vn or vt is 0 there.
  struct Key {
    uint32_t v, n, t;
    bool operator<(const Key& o) const { return v != o.v ? v < o.v : n != o.n ? n < o.n : t < o.t; }
    bool operator==(const Key& o) const { return v == o.v && n == o.n && t == o.t; }
  };

  size_t face_ = 0;       // faces before the current shape = index into the scan
  std::vector<Key> keys_; // sorted distinct keys of the current part

  static Key key(const tinyobj::index_t& c) {
    return {uint32_t(c.vertex_index), uint32_t(c.normal_index + 1), uint32_t(c.texcoord_index + 1)};
  }

  void check_counts() const {
    if (a_.vertices.size() != scan_.counts[0] * 3 || a_.normals.size() != scan_.counts[2] * 3 ||
        a_.texcoords.size() != scan_.counts[1] * 2)
      fail(TLOD_ERROR_PARSE, format("internal: tinyobjloader read %zu v, %zu vt and %zu vn, the scan %zu, %zu and %zu",
                                    a_.vertices.size() / 3, a_.texcoords.size() / 2, a_.normals.size() / 3,
                                    scan_.counts[0], scan_.counts[1], scan_.counts[2]));
  }

  std::string where(const tinyobj::shape_t& sh, size_t s, size_t f) const {
    const size_t k = face_ + f;
    const size_t line = k < scan_.face_lines.size() ? scan_.face_lines[k] : 0;
    return format("shape %zu '%.40s' face %zu (line %zu)", s, sh.name.c_str(), f, line);
  }

  void add_shape(const tinyobj::shape_t& sh, size_t s) {
    const tinyobj::mesh_t& m = sh.mesh;
    if (m.num_face_vertices.empty()) return;
    check_faces(sh, s);
    tlod_import_part part{};
    std::snprintf(part.name, sizeof part.name, "%s", sh.name.empty() ? "default" : sh.name.c_str());
    part.first_vertex = uint32_t(out_.positions.size() / 3);
    part.first_face = uint32_t(out_.face_sizes.size());
    base_color(m, part.base_color);
    part.material = material_of(m);
    make_vertices(sh, s, part.had_normals);
    size_t offset = 0;
    for (size_t f = 0; f < m.num_face_vertices.size(); ++f) {
      add_face(&m.indices[offset], m.num_face_vertices[f], part.first_vertex);
      offset += m.num_face_vertices[f];
    }
    face_ += m.num_face_vertices.size();
    part.vertex_count = uint32_t(out_.positions.size() / 3) - part.first_vertex;
    part.face_count = uint32_t(out_.face_sizes.size()) - part.first_face;
    out_.parts.push_back(part);
  }

  // Every face against the scan, every index against the arrays: nothing
  // tinyobjloader returned is used before this.
  void check_faces(const tinyobj::shape_t& sh, size_t s) const {
    const tinyobj::mesh_t& m = sh.mesh;
    const size_t nv = a_.vertices.size() / 3, nn = a_.normals.size() / 3, nt = a_.texcoords.size() / 2;
    size_t offset = 0;
    for (size_t f = 0; f < m.num_face_vertices.size(); ++f) {
      const size_t n = m.num_face_vertices[f], k = face_ + f;
      if (k >= scan_.face_corners.size() || scan_.face_corners[k] != n || offset + n > m.indices.size())
        fail(TLOD_ERROR_PARSE, "internal: " + where(sh, s, f) + ": corners disagree with the scan");
      for (size_t i = offset; i < offset + n; ++i) {
        const tinyobj::index_t& c = m.indices[i];
        if (c.vertex_index < 0 || size_t(c.vertex_index) >= nv)
          fail(TLOD_ERROR_INVALID_MESH, format("%s: vertex index %d out of range (%zu vertices)",
                                               where(sh, s, f).c_str(), c.vertex_index + 1, nv));
        if (c.normal_index < -1 || (c.normal_index >= 0 && size_t(c.normal_index) >= nn))
          fail(TLOD_ERROR_INVALID_MESH, format("%s: normal index %d out of range (%zu normals)",
                                               where(sh, s, f).c_str(), c.normal_index + 1, nn));
        if (c.texcoord_index < -1 || (c.texcoord_index >= 0 && size_t(c.texcoord_index) >= nt))
          fail(TLOD_ERROR_INVALID_MESH, format("%s: texture coordinate index %d out of range (%zu vt)",
                                               where(sh, s, f).c_str(), c.texcoord_index + 1, nt));
      }
      offset += n;
    }
  }

  // One output vertex per distinct (v, vn, vt) of the part, ordered by v,
  // vn, vt: an OBJ whose faces use every v (as tlod_export_file writes them)
  // comes back in its own vertex order.
  void make_vertices(const tinyobj::shape_t& sh, size_t s, bool& had_normals) {
    keys_.clear();
    for (const tinyobj::index_t& c : sh.mesh.indices)
      keys_.push_back(key(c));
    std::sort(keys_.begin(), keys_.end());
    keys_.erase(std::unique(keys_.begin(), keys_.end()), keys_.end());
    if (out_.positions.size() / 3 + keys_.size() > _TLOD_IMPORT_MAX_VERTICES)
      fail(TLOD_ERROR_UNSUPPORTED, format("more than %zu vertices", size_t(_TLOD_IMPORT_MAX_VERTICES)));
    const size_t first = out_.positions.size() / 3;
    std::vector<float> uv;
    for (const Key& k : keys_) {
      const size_t v = k.v;
      const long n = long(k.n) - 1;
      const float* p = &a_.vertices[3 * v];
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
        fail(TLOD_ERROR_INVALID_MESH, format("shape %zu '%.40s': vertex %zu is not finite", s, sh.name.c_str(), v + 1));
      out_.positions.insert(out_.positions.end(), p, p + 3);
      if (n >= 0) {
        const float* q = &a_.normals[3 * size_t(n)];
        out_.normals.insert(out_.normals.end(), q, q + 3);
        had_normals = out_.any_normals = true;
      } else {
        out_.normals.insert(out_.normals.end(), 3, 0.0f);
      }
      add_texcoord(k, s, sh, uv);
    }
    if (a_.texcoords.empty()) return;
    out_.add_attribute("TEXCOORD_0", 2, first, uv);
    out_.pad_attributes();
  }

  // OBJ's vt origin is bottom-left, glTF's (and the result's) top-left: v' = 1 - v.
  // A corner without vt gets (0, 0).
  void add_texcoord(const Key& k, size_t s, const tinyobj::shape_t& sh, std::vector<float>& uv) const {
    if (a_.texcoords.empty()) return;
    float u = 0.0f, v = 0.0f;
    if (k.t > 0) {
      u = a_.texcoords[2 * (k.t - 1)];
      v = 1.0f - a_.texcoords[2 * (k.t - 1) + 1];
    }
    if (!std::isfinite(u) || !std::isfinite(v))
      fail(TLOD_ERROR_INVALID_MESH,
           format("shape %zu '%.40s': texture coordinate %u is not finite", s, sh.name.c_str(), k.t));
    uv.push_back(u);
    uv.push_back(v);
  }

  uint32_t vertex_id(const tinyobj::index_t& c, uint32_t first) const {
    const auto it = std::lower_bound(keys_.begin(), keys_.end(), key(c));
    return first + uint32_t(it - keys_.begin());
  }

  void add_face(const tinyobj::index_t* c, size_t n, uint32_t first) {
    uint32_t v[kMaxCorners];
    for (size_t i = 0; i < n; ++i)
      v[i] = vertex_id(c[i], first);
    if (out_.indices.size() + 3 * n > _TLOD_IMPORT_MAX_INDICES)
      fail(TLOD_ERROR_UNSUPPORTED, format("more than %zu indices", size_t(_TLOD_IMPORT_MAX_INDICES)));
    if (n <= 4) {
      out_.indices.insert(out_.indices.end(), v, v + n);
      out_.face_sizes.push_back(uint8_t(n));
      if (n == 4) out_.any_quads = true;
      return;
    }
    // Fan from corner 0: exact for convex polygons, which is what OBJ
    // exporters write; the triangles keep the polygon's winding.
    for (size_t i = 1; i + 1 < n; ++i) {
      out_.indices.insert(out_.indices.end(), {v[0], v[i], v[i + 1]});
      out_.face_sizes.push_back(3);
    }
    out_.polygons_triangulated++;
  }

  uint32_t material_of(const tinyobj::mesh_t& m) const {
    if (m.material_ids.empty()) return TLOD_IMPORT_NONE;
    const int id = m.material_ids[0];
    return id >= 0 && size_t(id) < mats_.size() ? uint32_t(id) : TLOD_IMPORT_NONE;
  }

  // The part's first face decides its colour (a part is one o/g group).
  void base_color(const tinyobj::mesh_t& m, float c[4]) const {
    c[0] = c[1] = c[2] = c[3] = 1.0f;
    if (m.material_ids.empty()) return;
    const int id = m.material_ids[0];
    if (id < 0 || size_t(id) >= mats_.size()) return;
    for (int i = 0; i < 3; ++i)
      c[i] = float(mats_[size_t(id)].diffuse[i]);
    c[3] = float(mats_[size_t(id)].dissolve);
  }
};

// Material files are read here under the containment rule
// (contained_file.h), within the budget, and handed to tinyobjloader's
// LoadMtl as text: its own reader opens whatever path a file names and reads
// it whole (think "mtllib /dev/zero", a FIFO, or "../../secret"). A missing
// file is a warning (default colour); a refused one fails the import after
// LoadObj returns (no exception is thrown through tinyobjloader).
class MaterialReader final : public tinyobj::MaterialReader {
public:
  MaterialReader(const char* folder, _tlod_import_budget* budget) : folder_(folder), budget_(budget) {}

  bool operator()(const std::string& id, std::vector<tinyobj::material_t>* materials, std::map<std::string, int>* map,
                  std::string* warn, std::string* err) override {
    if (refused_.code != TLOD_SUCCESS) return false;
    std::string text;
    try {
      if (!read(id, &text)) {
        if (warn) *warn += "material file '" + id + "' not found: default colour used\n";
        return false;
      }
      check_mtl_exponents(text, id);
    } catch (const ImportError& e) {
      refused_ = e;
      return false;
    }
    std::istringstream in(text);
    tinyobj::LoadMtl(map, materials, &in, warn, err);
    return true;
  }

  // The first refusal, if any (code TLOD_SUCCESS: none).
  const ImportError& refused() const { return refused_; }

private:
  const char* folder_;
  _tlod_import_budget* budget_;
  ImportError refused_{TLOD_SUCCESS, ""};

  // false: not found; throws on a refusal.
  bool read(const std::string& id, std::string* out) const {
    const std::string where = format("mtllib '%.200s'", id.c_str());
    if (!folder_) fail(TLOD_ERROR_IO, where + ": refused: an external file of a model imported from memory");
    const size_t room = budget_->limit > budget_->used ? budget_->limit - budget_->used : 0;
    unsigned char* data = nullptr;
    size_t size = 0;
    const _tlod_contained_status st = _tlod_contained_read(folder_, id.c_str(), room / 3, &data, &size);
    if (st == _TLOD_CONTAINED_NOT_FOUND) return false;
    if (st != _TLOD_CONTAINED_OK)
      fail(st == _TLOD_CONTAINED_TOO_LARGE ? TLOD_ERROR_OUT_OF_MEMORY : TLOD_ERROR_IO,
           where + ": " + _tlod_contained_message(st));
    // Ours, the string, the stream's copy.
    const bool ok = _tlod_budget_take(budget_, 3 * size);
    if (ok) out->assign(reinterpret_cast<const char*>(data), size);
    std::free(data);
    if (!ok) fail(TLOD_ERROR_OUT_OF_MEMORY, where + ": " + _tlod_contained_message(_TLOD_CONTAINED_TOO_LARGE));
    return true;
  }
};

std::string one_line(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ' || s.back() == '.'))
    s.pop_back();
  for (size_t i = 0; (i = s.find('\n', i)) != std::string::npos;)
    s.replace(i, 1, "; ");
  return s;
}

tlod_result finish(const _tlod_import_job* job, Output& out) {
  _tlod_import_data d{};
  out.fill(d);
  d.face_count = uint32_t(out.face_sizes.size());
  d.face_sizes = out.any_quads ? out.face_sizes.data() : nullptr;
  d.polygons_triangulated = out.polygons_triangulated;
  return _tlod_import_finish(job, &d);
}

// What tinyobjloader and the builder allocate, from the scan's counts, taken
// from the budget before either runs (the file is only text: a few bytes
// per corner become tens of bytes, but never more than this).
void take_estimate(_tlod_import_budget* budget, const Scan& scan) {
  size_t corners = 0;
  for (size_t c : scan.face_corners)
    corners += c;
  // Per v: position + colour, twice (growth); vt, vn likewise; per corner: tinyobj's
  // index, our sort key, an output vertex (position, normal: up to 3x for growth),
  // fan indices; per face: its size, material and smoothing ids.
  const double bytes = double(scan.counts[0]) * 48 + double(scan.counts[1]) * 16 + double(scan.counts[2]) * 24 +
                       double(corners) * 160 + double(scan.face_lines.size()) * 24 + double(scan.text.size()) * 2;
  if (bytes >= double(SIZE_MAX) || !_tlod_budget_take(budget, size_t(bytes)))
    fail(TLOD_ERROR_OUT_OF_MEMORY, format("%zu vertices and %zu face corners: need about %.0f bytes, beyond the "
                                          "import's memory budget (%zu bytes; tlod_import_desc.memory_limit)",
                                          scan.counts[0], corners, bytes, budget->limit));
}

tlod_result import_obj(const _tlod_import_job* job) {
  unsigned char* bytes = nullptr;
  size_t size = 0;
  const tlod_result res = _tlod_import_read_file(job, &bytes, &size);
  if (res != TLOD_SUCCESS) return res;
  Scan scan;
  try {
    scan = Scanner().run(reinterpret_cast<const char*>(bytes), size);
  } catch (...) {
    std::free(bytes);
    throw;
  }
  std::free(bytes);
  if (scan.face_lines.empty())
    fail(TLOD_ERROR_INVALID_MESH,
         format("no faces (%zu vertices, %zu ignored elements)", scan.counts[0], scan.ignored_elements));
  take_estimate(job->budget, scan);
  Output out;
  if (scan.ignored_elements)
    out.warn(format("line %zu: '%s' and %zu other non-polygon statement(s) ignored", scan.first_ignored_line,
                    scan.first_ignored.c_str(), scan.ignored_elements - 1));
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  std::istringstream in(scan.text);
  MaterialReader mtl(job->folder, job->budget);
  const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, &mtl,
                                   /*triangulate=*/false, /*default_vcols_fallback=*/false);
  if (mtl.refused().code != TLOD_SUCCESS) throw mtl.refused();
  if (!ok) fail(TLOD_ERROR_PARSE, "tinyobjloader: " + one_line(err));
  if (!warn.empty()) out.warn("tinyobjloader: " + one_line(warn));
  Builder(attrib, materials, scan, out).run(shapes);
  tlod_import_detail::read_obj_materials(materials, job->folder, job->budget, out);
  return finish(job, out);
}

} // namespace

extern "C" tlod_result _tlod_import_obj(const _tlod_import_job* job) {
  return tlod_import_detail::guarded(job, "OBJ", [job] { return import_obj(job); });
}
