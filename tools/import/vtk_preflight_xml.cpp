// vtk_preflight_xml.cpp -- the binary headers of an XML VTK file's arrays, checked before VTK
// reads them (docs/vtk.md section 7). A binary or appended DataArray starts with a header
// (UInt32 or UInt64 words, the file's byte order) giving its byte count, or for compressed data
// [blocks, block size, last block size, compressed sizes...]; VTK allocates the uncompressed
// size it announces. That size must fit the remaining budget, and raw uncompressed data must
// fit the file. The header itself must lie inside the file.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <vtkLZ4DataCompressor.h>
#include <vtkLZMADataCompressor.h>
#include <vtkSmartPointer.h>
#include <vtkZLibDataCompressor.h>

#include "import_error.hpp"
#include "vtk_preflight.hpp"
#include "vtk_preflight_cells.hpp"

namespace tlod_import_detail {
namespace {

// VTK's reader of polyhedron faces (a .vtu's <Cells> arrays "faces" and "faceoffsets") leaks
// its arrays when they do not read or do not match, and walks the faces by counts it never
// checks (reads past them). We refuse polyhedra anyway (vtk_cells.cpp), so their faces are
// refused before VTK reads them.
void no_polyhedron_faces(const char* p, const char* end, uint64_t index) {
  std::string name;
  if (xml_attribute(p, end, "Name", &name) && (name == "faces" || name == "faceoffsets"))
    fail(TLOD_ERROR_UNSUPPORTED, format("DataArray %llu (%s): polyhedron faces are not read (polyhedron cells, "
                                        "type 42, are not supported)",
                                        (unsigned long long)index, name.c_str()));
}

int base64_value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  return c == '+' ? 62 : c == '/' ? 63 : -1;
}

// Decodes up to want bytes of base64 text at [p, end) (whitespace skipped) into out.
std::string base64_prefix(const char* p, const char* end, size_t want) {
  std::string out;
  uint32_t acc = 0;
  int bits = 0;
  for (; p < end && out.size() < want; ++p) {
    const int v = base64_value(*p);
    if (v < 0) {
      if (*p == '=' || *p == '<') break;
      continue;
    }
    acc = (acc << 6) | uint32_t(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(char((acc >> bits) & 0xff));
    }
  }
  return out;
}

// The first byte after n base64 characters (alphabet or '=') of [p, end), whitespace skipped.
const char* skip_base64(const char* p, const char* end, uint64_t n) {
  for (; p < end && n > 0; ++p)
    if (base64_value(*p) >= 0 || *p == '=') --n;
  return p;
}

// Inflates one block with the file's compressor (VTK's own classes, as its reader does); false
// when the compressor is not one VTK knows or the block does not inflate to exactly raw bytes.
bool inflate(const std::string& compressor, const unsigned char* src, size_t n, unsigned char* out, size_t raw) {
  vtkSmartPointer<vtkDataCompressor> c;
  if (compressor == "vtkZLibDataCompressor") c = vtkSmartPointer<vtkZLibDataCompressor>::New();
  if (compressor == "vtkLZ4DataCompressor") c = vtkSmartPointer<vtkLZ4DataCompressor>::New();
  if (compressor == "vtkLZMADataCompressor") c = vtkSmartPointer<vtkLZMADataCompressor>::New();
  return c && c->Uncompress(src, n, out, raw) == raw;
}

class XmlHeaders {
public:
  XmlHeaders(const char* data, size_t size, size_t room) : data_(data), end_(data + size), room_(room) {}

  // Tags are read only before <AppendedData>: its bytes are data, not XML (VTK's parser never
  // sees a tag in them), however much of them looks like a tag.
  void run() {
    const char* tag = static_cast<const char*>(memmem(data_, size_t(end_ - data_), "<AppendedData", 13));
    xml_end_ = tag ? tag : end_;
    no_hidden_markup();
    file_attributes();
    for (const char* p = data_; (p = static_cast<const char*>(memchr(p, '<', size_t(xml_end_ - p)))) != nullptr; ++p) {
      const char* close = static_cast<const char*>(memchr(p, '>', size_t(xml_end_ - p)));
      if (!close) break;
      if (is_tag(p, close, "DataArray")) array(p, close);
      for (const char* block : {"Piece", "Cells", "Verts", "Lines", "Strips", "Polys"})
        if (is_open_or_close(p, close, block)) blocks_.end_block();
      if (is_open_or_close(p, close, "Cells")) in_cells_ = p[1] != '/';
    }
    blocks_.end_block();
  }

private:
  const char* data_;
  const char* end_;
  const char* xml_end_ = nullptr; // <AppendedData, or end_
  size_t room_;
  size_t word_ = 4;
  bool big_endian_ = false, compressed_ = false, appended_base64_ = false;
  std::string compressor_;
  const char* appended_ = nullptr; // first byte after the '_' of <AppendedData>
  uint64_t index_ = 0;             // DataArray number, for messages
  bool in_cells_ = false;          // inside a piece's <Cells>
  CellBlocks blocks_;

  void file_attributes() {
    bool first = true; // the root element's attributes, not a later tag's
    xml_tags(data_, size_t(xml_end_ - data_), "VTKFile", [this, &first](const char* b, const char* e) {
      std::string v;
      if (!first) return;
      first = false;
      if (xml_attribute(b, e, "header_type", &v)) word_ = v == "UInt64" ? 8 : 4;
      if (xml_attribute(b, e, "byte_order", &v)) big_endian_ = v == "BigEndian";
      compressed_ = xml_attribute(b, e, "compressor", &v) && !v.empty();
      compressor_ = compressed_ ? v : std::string();
    });
    const char* tag = static_cast<const char*>(memmem(data_, size_t(end_ - data_), "<AppendedData", 13));
    if (!tag) return;
    const char* close = static_cast<const char*>(memchr(tag, '>', size_t(end_ - tag)));
    if (!close) return;
    std::string enc;
    appended_base64_ = xml_attribute(tag, close, "encoding", &enc) && enc == "base64";
    appended_ = appended_start(close + 1);
  }

  // Where VTK's reader starts the appended data: after the tag, spaces skipped, past the '_'
  // that must come next. VTK only warns when it is not a '_' and reads the data from that
  // character on, where every offset of ours would be off: refused.
  const char* appended_start(const char* p) const {
    while (p < end_ && is_space(*p))
      ++p;
    if (p < end_ && *p != '_')
      fail(TLOD_ERROR_PARSE, format("<AppendedData>: its data starts with byte 0x%02x, not the '_' it must start with",
                                    unsigned(static_cast<unsigned char>(*p))));
    return p < end_ ? p + 1 : nullptr;
  }

  // Comments, CDATA sections and processing instructions (but the <?xml?> declaration) are
  // refused before the data: VTK's XML parser skips them, this scan would read a DataArray or
  // an <AppendedData in one as real (and so check other arrays than VTK reads).
  void no_hidden_markup() const {
    static const char* const kinds[][2] = {
        {"<!--", "a comment"}, {"<![CDATA[", "a CDATA section"}, {"<!DOCTYPE", "a DOCTYPE"}};
    const size_t n = size_t(xml_end_ - data_);
    for (const auto& k : kinds)
      if (memmem(data_, n, k[0], strlen(k[0])))
        fail(TLOD_ERROR_PARSE, format("the XML holds %s: not read (VTK files have none)", k[1]));
    for (const char* q = data_; (q = static_cast<const char*>(memmem(q, size_t(xml_end_ - q), "<?", 2))) != nullptr;
         q += 2)
      if (q != data_ || size_t(xml_end_ - q) < 5 || memcmp(q, "<?xml", 5) != 0)
        fail(TLOD_ERROR_PARSE, "the XML holds a processing instruction: not read (VTK files have none)");
  }

  // Whether [p, close] is the tag <name ...>, <name> or <name/>.
  static bool is_tag(const char* p, const char* close, const char* name) {
    const size_t n = strlen(name);
    return size_t(close - p) > n && memcmp(p + 1, name, n) == 0 &&
           (is_space(p[n + 1]) || p[n + 1] == '/' || p[n + 1] == '>');
  }

  // Whether [p, close] opens or closes element name.
  static bool is_open_or_close(const char* p, const char* close, const char* name) {
    return is_tag(p, close, name) || (p[1] == '/' && is_tag(p + 1, close, name));
  }

  uint64_t word(const std::string& h, size_t i) const {
    uint64_t v = 0;
    for (size_t k = 0; k < word_; ++k) {
      const uint64_t byte = static_cast<unsigned char>(h[i * word_ + (big_endian_ ? k : word_ - 1 - k)]);
      v = v << 8 | byte;
    }
    return v;
  }

  // The header's first 3 words (compressed) or 1 (raw) at p; raw binary: also where data starts.
  std::string header(const char* p, bool base64, size_t words) const {
    const size_t want = words * word_;
    if (base64) return base64_prefix(p, end_, want);
    if (size_t(end_ - p) < want) return std::string();
    return std::string(p, want);
  }

  // An array is read as VTK reads it: appended when it has an offset (whatever its format says),
  // else binary when its format is "binary", else ASCII.
  void array(const char* b, const char* e) {
    const uint64_t i = index_++;
    if (in_cells_) no_polyhedron_faces(b, e, i);
    std::string fmt, off;
    xml_attribute(b, e, "format", &fmt);
    const bool appended = xml_attribute(b, e, "offset", &off);
    // VTK reports this too, but its unstructured-grid reader leaks the arrays it made.
    if (!appended && fmt == "appended")
      fail(TLOD_ERROR_PARSE, format("DataArray %llu: format appended, but no offset", (unsigned long long)i));
    if (!appended && fmt != "binary") return ascii_cells(i, b, e);
    const char* p = e + 1;
    bool base64 = true;
    if (appended) {
      char* stop = nullptr;
      if (!appended_)
        fail(TLOD_ERROR_PARSE,
             format("DataArray %llu: an appended offset, but no <AppendedData>", (unsigned long long)i));
      const unsigned long long o = strtoull(off.c_str(), &stop, 10);
      if (off.empty() || *stop || o > uint64_t(end_ - appended_))
        fail(TLOD_ERROR_PARSE,
             format("DataArray %llu: offset \"%.32s\" outside the appended data", (unsigned long long)i, off.c_str()));
      p = appended_ + o;
      base64 = appended_base64_;
    }
    const size_t words = compressed_ ? 3 : 1;
    const std::string h = header(p, base64, words);
    if (h.size() < words * word_)
      fail(TLOD_ERROR_PARSE, format("DataArray %llu: its data header runs past the file", (unsigned long long)i));
    cells(i, b, e, check(i, h, p, base64), p, base64);
  }

  // Cell blocks: a connectivity's size is its byte count (its header), the offsets are read
  // whole (decoded, every compressed block inflated: within the budget check() counted).
  void cells(uint64_t i, const char* b, const char* e, uint64_t bytes, const char* p, bool base64) {
    const CellArray c = cell_array(b, e);
    if (c.role == CellArray::kConnectivity) return blocks_.connectivity(bytes / c.size); // an empty one too
    if (c.role != CellArray::kOffsets) return;
    if (!compressed_ && !base64) // raw data, in the file (check())
      return blocks_.binary_offsets(i, reinterpret_cast<const unsigned char*>(p) + word_, bytes / c.size, c,
                                    big_endian_);
    std::vector<unsigned char> data;
    const bool ok = compressed_ ? inflated(p, base64, bytes, &data) : decoded(p, bytes, &data);
    // Compressed offsets the pre-flight cannot read are refused: VTK may still read a block it
    // cannot (a mangled base64 run), and would size the connectivity by a value nobody checked.
    if (!ok && compressed_)
      fail(TLOD_ERROR_PARSE,
           format("DataArray %llu (offsets): its compressed blocks do not read", (unsigned long long)i));
    if (!ok) return; // short uncompressed data: VTK's read fails
    blocks_.binary_offsets(i, data.data(), data.size() / c.size, c, big_endian_);
  }

  // The same for ASCII arrays (and formats VTK does not know, which it reads as ASCII): the
  // connectivity's size is its word count; the offsets are parsed as a C++ stream reads them.
  void ascii_cells(uint64_t i, const char* b, const char* e) {
    const CellArray c = cell_array(b, e);
    if (c.role == CellArray::kNone) return;
    const char* q = e[-1] == '/' ? e : e + 1; // <DataArray .../>: no text
    const char* stop = e[-1] == '/' ? e : static_cast<const char*>(memchr(q, '<', size_t(end_ - q)));
    const char* end = stop ? stop : end_;
    if (c.role == CellArray::kOffsets) return blocks_.ascii_offsets(i, q, end, c);
    uint64_t count = 0;
    for (; q < end; ++q)
      if (!is_space(*q) && (q == e + 1 || is_space(q[-1]))) ++count;
    blocks_.connectivity(count);
  }

  // The bytes of uncompressed base64 data at p (its header first); false if the file is short.
  bool decoded(const char* p, uint64_t bytes, std::vector<unsigned char>* out) const {
    const std::string all = base64_prefix(p, end_, word_ + bytes);
    if (all.size() < word_ + bytes) return false;
    out->assign(all.begin() + long(word_), all.end());
    return true;
  }

  // The bytes of compressed data at p: every block after the header (its own base64 run when
  // encoded), inflated with VTK's own compressor classes. False where VTK's read will fail
  // anyway (short data, a block that does not inflate).
  bool inflated(const char* p, bool base64, uint64_t bytes, std::vector<unsigned char>* out) const {
    const std::string h3 = header(p, base64, 3);
    const uint64_t blocks = word(h3, 0), block = word(h3, 1), last = word(h3, 2) ? word(h3, 2) : block;
    const std::string h = header(p, base64, 3 + blocks); // block_table(): in the file
    if (h.size() < (3 + blocks) * word_) return false;
    uint64_t total = 0;
    for (uint64_t k = 0; k < blocks; ++k)
      if (__builtin_add_overflow(total, word(h, 3 + k), &total)) return false;
    const uint64_t hb = (3 + blocks) * word_;
    const char* d = base64 ? skip_base64(p, end_, (hb + 2) / 3 * 4) : p + hb;
    const std::string dec = base64 ? base64_prefix(d, end_, total) : std::string();
    if ((base64 ? dec.size() : uint64_t(end_ - d)) < total) return false;
    const auto* src = reinterpret_cast<const unsigned char*>(base64 ? dec.data() : d);
    out->resize(bytes); // within the budget: check() counted it
    for (uint64_t k = 0, at = 0; k < blocks; at += word(h, 3 + k), ++k) {
      const uint64_t raw = k + 1 < blocks ? block : last;
      if (!inflate(compressor_, src + at, word(h, 3 + k), out->data() + k * block, raw)) return false;
    }
    return true;
  }

  // A compressed array's header lists every block's compressed size after its first 3 words, and
  // VTK allocates tables of that many blocks before reading them: the list must be in the file.
  void block_table(uint64_t i, uint64_t blocks, const char* p, bool base64) const {
    const uint64_t left = uint64_t(end_ - p), fits = (base64 ? left / 4 * 3 + 3 : left) / word_;
    if (blocks > fits || 3 + blocks > fits)
      fail(TLOD_ERROR_PARSE,
           format("DataArray %llu: its compression header lists %llu blocks, more than the file holds",
                  (unsigned long long)i, (unsigned long long)blocks));
    // VTK reads each block into a buffer of its compressed size: the blocks must be in the file.
    const std::string h = header(p, base64, 3 + blocks);
    uint64_t sum = 0;
    for (uint64_t k = 0; k < blocks && h.size() >= (3 + blocks) * word_; ++k)
      if (__builtin_add_overflow(sum, word(h, 3 + k), &sum) || sum > left)
        fail(TLOD_ERROR_PARSE, format("DataArray %llu: compressed block %llu runs past the end of the file",
                                      (unsigned long long)i, (unsigned long long)k));
  }

  // The uncompressed bytes the header at p announces, checked against the file and the budget.
  uint64_t check(uint64_t i, const std::string& h, const char* p, bool base64) {
    uint64_t bytes, tables = 0;
    if (!compressed_) {
      bytes = word(h, 0);
      if (!base64 && bytes > uint64_t(end_ - p) - word_)
        fail(TLOD_ERROR_PARSE,
             format("DataArray %llu: its header announces %llu bytes, the file has %llu left", (unsigned long long)i,
                    (unsigned long long)bytes, (unsigned long long)(end_ - p)));
    } else {
      const uint64_t blocks = word(h, 0), block = word(h, 1), last = word(h, 2);
      block_table(i, blocks, p, base64);
      // VTK divides offsets by the block size, inflates the last block into a buffer of one block,
      // and computes the total as blocks x block - (block - last): with no blocks, a last block
      // makes that wrap, and VTK reads a block it has no table for.
      if (blocks == 0 ? last != 0 : block == 0 || last > block)
        fail(TLOD_ERROR_PARSE,
             format(
                 "DataArray %llu: its compression header is inconsistent (%llu blocks of %llu bytes, the last of %llu)",
                 (unsigned long long)i, (unsigned long long)blocks, (unsigned long long)block,
                 (unsigned long long)last));
      tables = blocks * 16; // VTK's two per-block tables (blocks is at most the file's size)
      if ((blocks && __builtin_mul_overflow(blocks - 1, block, &bytes)) ||
          __builtin_add_overflow(blocks ? bytes : 0, last ? last : (blocks ? block : 0), &bytes))
        bytes = UINT64_MAX;
    }
    if (bytes > room_ || tables > room_ - bytes)
      fail(TLOD_ERROR_OUT_OF_MEMORY,
           format("DataArray %llu: its header announces %llu bytes, more than the import's memory budget (%zu "
                  "bytes; tlod_import_desc.memory_limit)",
                  (unsigned long long)i, (unsigned long long)(bytes > room_ ? bytes : bytes + tables), room_));
    return bytes;
  }
};

} // namespace

void preflight_xml_headers(const char* data, size_t size, size_t room) { XmlHeaders(data, size, room).run(); }

} // namespace tlod_import_detail
