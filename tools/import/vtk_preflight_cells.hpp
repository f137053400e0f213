// Private to the VTK shim: the cell-offsets check of the XML pre-flight (vtk_preflight_xml.cpp,
// docs/vtk.md section 7). VTK sizes a cell block's connectivity by an offset before reading the
// connectivity, so no offset may be past the connectivity's own size. Which offset VTK picks
// depends on the piece's counts and the file's version; every offset is checked instead.
#ifndef TESSLOD_TOOLS_IMPORT_VTK_PREFLIGHT_CELLS_HPP
#define TESSLOD_TOOLS_IMPORT_VTK_PREFLIGHT_CELLS_HPP

#include <cstddef>
#include <cstdint>

namespace tlod_import_detail {

// A DataArray's part in a cell block, from its Name and type attributes.
struct CellArray {
  enum Role { kNone, kConnectivity, kOffsets } role = kNone;
  size_t size = 0; // bytes a value (1, 2, 4, 8)
  char kind = 0;   // 'i' signed, 'u' unsigned, 'f' floating point
};

// The role of the DataArray tag [b, e): connectivity or offsets of a numeric type, else kNone.
CellArray cell_array(const char* b, const char* e);

// Collects the connectivity and offsets arrays of one cell block (a piece's <Cells>, <Verts>,
// <Lines>, <Strips> or <Polys>) and, at its end, refuses an offset past the connectivity's size
// (the smallest, should a block hold two). Offsets are parsed as VTK's readers parse them; a
// negative or non-finite one is refused, and so are offsets without a numeric connectivity.
class CellBlocks {
public:
  // Connectivity array i holds ids values.
  void connectivity(uint64_t ids);
  // Offsets array i: its n binary values at q (big_endian: the file's byte order).
  void binary_offsets(uint64_t i, const unsigned char* q, uint64_t n, CellArray c, bool big_endian);
  // Offsets array i: its ASCII text [p, end) (up to the next '<').
  void ascii_offsets(uint64_t i, const char* p, const char* end, CellArray c);
  // The block ends (at any block or piece tag, and at the end of the XML).
  void end_block();

private:
  uint64_t ids_ = UINT64_MAX;  // smallest connectivity of the block (UINT64_MAX: none yet)
  uint64_t max_offset_ = 0;    // largest offset of the block
  uint64_t offsets_index_ = 0; // the DataArray it is in
  bool offsets_ = false;       // any offsets read in the block

  void offsets(uint64_t i, uint64_t max);
};

} // namespace tlod_import_detail

#endif
