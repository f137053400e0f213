/* fuzz_import.c -- one importer through tlod_import_file(): the input as a file whose
 * extension (TLOD_FUZZ_EXT, set per target by fuzz/CMakeLists.txt: ".gltf", ".glb", ".obj",
 * ".ply") picks the reader, then the header's contract on what came back. */
#include <stdlib.h>

#include "fuzz_common.h"
#include "import_contract.h"

#ifndef TLOD_FUZZ_EXT
#error "TLOD_FUZZ_EXT (the file extension that picks the importer) must be defined"
#endif

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const char* path = fuzz_input_file(TLOD_FUZZ_EXT, data, size);
  fuzz_import_and_check(path);
  return 0;
}
