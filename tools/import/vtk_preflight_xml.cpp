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

namespace tlod_import_detail {
namespace {

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
    file_attributes();
    xml_tags(data_, size_t(xml_end_ - data_), "DataArray", [this](const char* b, const char* e) { array(b, e); });
  }

private:
  const char* data_;
  const char* end_;
  const char* xml_end_ = nullptr; // <AppendedData, or end_
  size_t room_;
  size_t word_ = 4;
  bool big_endian_ = false, compressed_ = false, appended_base64_ = false;
  std::string compressor_;
  const char* appended_ = nullptr;     // first byte after the '_' of <AppendedData>
  uint64_t index_ = 0;                 // DataArray number, for messages
  uint64_t connectivity_ = UINT64_MAX; // ids of the last connectivity array (UINT64_MAX: none pending)
  uint64_t last_offset_ = UINT64_MAX;  // last value of the last offsets array (UINT64_MAX: none pending)
  uint64_t offsets_index_ = 0;         // its DataArray number

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
    const char* u = static_cast<const char*>(memchr(close, '_', size_t(end_ - close)));
    appended_ = u ? u + 1 : nullptr;
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

  // VTK sizes a cell array's connectivity by its last offset before reading the connectivity: a
  // last offset past the connectivity's own size (its header) would make VTK allocate it. The two
  // arrays of a block may come in either order; compressed data: the offsets' last block is
  // inflated to read it.
  void cells(uint64_t i, const char* b, const char* e, uint64_t bytes, const char* p, bool base64) {
    size_t size = 0;
    const int role = cell_role(b, e, &size);
    uint64_t v;
    if (role == kConnectivity) return pair(i, bytes / size, UINT64_MAX); // an empty one too
    if (role != kOffsets || bytes < size) return;
    // Compressed offsets the pre-flight cannot read are refused: VTK may still read a block it
    // cannot (a mangled base64 run), and would size the connectivity by a value nobody checked.
    if (compressed_ && !compressed_last(p, base64, size, &v))
      fail(TLOD_ERROR_PARSE,
           format("DataArray %llu (offsets): its last compressed block does not read", (unsigned long long)i));
    if (compressed_ || raw_last(p, base64, bytes, size, &v)) pair(i, UINT64_MAX, v);
  }

  // The same for ASCII arrays: the connectivity's size is its word count, the offsets' last
  // value its last word's digits (as a C++ stream reads them).
  void ascii_cells(uint64_t i, const char* b, const char* e) {
    size_t size = 0;
    const int role = cell_role(b, e, &size);
    if (role == kNone || e[-1] == '/') return role == kConnectivity ? pair(i, 0, UINT64_MAX) : void();
    const char* q = e + 1;
    const char* stop = static_cast<const char*>(memchr(q, '<', size_t(end_ - q)));
    const char* word = nullptr;
    uint64_t count = 0, v = 0;
    for (const char* end = stop ? stop : end_; q < end; ++q)
      if (!is_space(*q) && (q == e + 1 || is_space(q[-1]))) ++count, word = q;
    for (size_t k = 0; word && word + k < end_ && k < 19 && word[k] >= '0' && word[k] <= '9'; ++k)
      v = v * 10 + uint64_t(word[k] - '0');
    if (role == kConnectivity) return pair(i, count, UINT64_MAX);
    if (count > 0) pair(i, UINT64_MAX, v);
  }

  enum { kNone, kConnectivity, kOffsets };

  // Whether a DataArray is a cell block's connectivity or offsets (an integer array of 4 or 8
  // bytes a value: size), or neither.
  static int cell_role(const char* b, const char* e, size_t* size) {
    std::string name, type;
    if (!xml_attribute(b, e, "Name", &name) || (name != "offsets" && name != "connectivity")) return kNone;
    xml_attribute(b, e, "type", &type);
    *size = type == "Int64" || type == "UInt64" ? 8 : type == "Int32" || type == "UInt32" ? 4 : 0;
    if (*size == 0) return kNone;
    return name == "offsets" ? kOffsets : kConnectivity;
  }

  // One half of a block's pair (UINT64_MAX: the other half); checked once both are known.
  void pair(uint64_t i, uint64_t ids, uint64_t last) {
    if (ids != UINT64_MAX) connectivity_ = ids;
    if (last != UINT64_MAX) last_offset_ = last, offsets_index_ = i;
    if (connectivity_ == UINT64_MAX || last_offset_ == UINT64_MAX) return;
    if (last_offset_ > connectivity_)
      fail(TLOD_ERROR_PARSE, format("DataArray %llu (offsets): the last offset %llu is past the %llu connectivity ids",
                                    (unsigned long long)offsets_index_, (unsigned long long)last_offset_,
                                    (unsigned long long)connectivity_));
    connectivity_ = last_offset_ = UINT64_MAX;
  }

  // The value of size bytes at q in the file's byte order.
  uint64_t value(const char* q, size_t size) const {
    uint64_t v = 0;
    for (size_t k = 0; k < size; ++k)
      v = v << 8 | static_cast<unsigned char>(q[big_endian_ ? k : size - 1 - k]);
    return v;
  }

  // The last value of an uncompressed array of bytes at p (header first); false if cut short.
  bool raw_last(const char* p, bool base64, uint64_t bytes, size_t size, uint64_t* v) const {
    const std::string all = base64 ? base64_prefix(p, end_, word_ + bytes) : std::string();
    if (base64 && all.size() < word_ + bytes) return false;
    *v = value(base64 ? all.data() + word_ + bytes - size : p + word_ + bytes - size, size);
    return true;
  }

  // The last value of a compressed array at p: its last block, found after the header (its own
  // base64 run when encoded) and the blocks before it, inflated. False where VTK's read will
  // fail anyway (short data, a block that does not inflate) or the value spans two blocks.
  bool compressed_last(const char* p, bool base64, size_t size, uint64_t* v) const {
    const std::string h3 = header(p, base64, 3);
    const uint64_t blocks = word(h3, 0), raw = word(h3, 2) ? word(h3, 2) : word(h3, 1);
    const std::string h = header(p, base64, 3 + blocks); // block_table(): in the file
    if (blocks == 0 || raw < size || h.size() < (3 + blocks) * word_) return false;
    uint64_t at = 0;
    for (uint64_t k = 0; k + 1 < blocks; ++k)
      if (__builtin_add_overflow(at, word(h, 3 + k), &at)) return false;
    const uint64_t n = word(h, 2 + blocks), hb = (3 + blocks) * word_;
    const char* d = base64 ? skip_base64(p, end_, (hb + 2) / 3 * 4) : p + hb;
    const std::string dec = base64 ? base64_prefix(d, end_, at + n) : std::string();
    const uint64_t have = base64 ? dec.size() : uint64_t(end_ - d);
    if (at > have || n > have - at) return false;
    std::vector<unsigned char> out(raw); // within the budget: check() counted it
    const auto* src = reinterpret_cast<const unsigned char*>(base64 ? dec.data() : d) + at;
    if (!inflate(compressor_, src, n, out.data(), raw)) return false;
    *v = value(reinterpret_cast<const char*>(out.data()) + raw - size, size);
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
