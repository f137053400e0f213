/* fuzz_vtk.c -- the VTK importer (tools/import/vtk_*.cpp, docs/vtk.md) through tlod_import_file():
 * the first input byte picks the format (.vtk legacy, .vtu, .vtp, .stl, .pvd, .pvtu; low bits),
 * the rest is the file; then the header's contract on what came back. Files, not memory: STL is
 * read by VTK from its path, and the .pvd/.pvtu references resolve in the input's private folder
 * (fuzz_input_file), where nothing but the input is. */
#include "fuzz_common.h"
#include "import_contract.h"

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const char* const ext[8] = {".vtk", ".vtu", ".vtp", ".stl", ".vtk", ".vtu", ".pvd", ".pvtu"};
  if (size < 1) return 0;
  const char* path = fuzz_input_file(ext[data[0] & 7], data + 1, size - 1);
  fuzz_import_and_check(path);
  return 0;
}
