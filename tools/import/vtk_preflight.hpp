// Private to the VTK shim: checks on a file's bytes before a VTK reader sees them, so that a
// small file declaring huge counts fails with our message instead of making VTK allocate what
// it declares (docs/vtk.md section 7). Each throws ImportError naming the section at fault.
#ifndef TESSLOD_TOOLS_IMPORT_VTK_PREFLIGHT_HPP
#define TESSLOD_TOOLS_IMPORT_VTK_PREFLIGHT_HPP

#include <cstddef>
#include <functional>
#include <string>

namespace tlod_import_detail {

// Legacy .vtk: the header (version line, ASCII|BINARY, DATASET kind, returned lower-case in
// *dataset), then every count VTK would allocate for (POINTS, CELLS, CELL_TYPES, POLYGONS ...,
// POINT_DATA / CELL_DATA arrays, FIELD arrays, DIMENSIONS) against the bytes left in the file
// (each value takes at least 2 bytes in ASCII, its type's size in binary) and against room.
void preflight_legacy(const char* data, size_t size, size_t room, std::string* dataset);

// XML .vtu/.vtp: NumberOfPoints / NumberOfCells / NumberOfVerts|Lines|Strips|Polys of every
// Piece and NumberOfComponents of every DataArray, estimated in bytes against room (XML data
// may be compressed, so the file size bounds nothing).
void preflight_xml(const char* data, size_t size, size_t room);

// XML binary and appended arrays: the byte count each array's data header announces (the
// uncompressed size of compressed data) against room, raw data against the file
// (vtk_preflight_xml.cpp). preflight_xml() calls it.
void preflight_xml_headers(const char* data, size_t size, size_t room);

// STL: a binary file's triangle count against its size.
void preflight_stl(const char* data, size_t size);

// Whitespace as a C++ stream (and VTK's readers) skips it.
inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

// The value of attribute name (either quote) in the tag text [p, end); false when absent.
bool xml_attribute(const char* p, const char* end, const char* name, std::string* value);

// Calls each(tag_begin, tag_end) for every tag "<NAME ...>" of [data, data + size).
void xml_tags(const char* data, size_t size, const char* name,
              const std::function<void(const char* begin, const char* end)>& each);

} // namespace tlod_import_detail

#endif
