// image_load.hpp -- an importer's image into tlod_import_detail::Image (private to tools/import/, C++17).
// Owned by the import/export layer. Shared by the glTF and OBJ readers: the file under the
// containment rule (contained_file.h), every copy from the memory budget, decoding through
// image_decode.h. Failures throw ImportError with a message that names no byte or size of
// what a reference resolved to; the readers turn them into warnings.
#ifndef TESSLOD_TOOLS_IMPORT_IMAGE_LOAD_HPP
#define TESSLOD_TOOLS_IMPORT_IMAGE_LOAD_HPP

#include "import_error.hpp"
#include "import_output.hpp"

namespace tlod_import_detail {

// ref (as written, percent-encoded) relative to folder (NULL: refused, memory import) into im.encoded.
void image_read_file(const char* folder, const std::string& ref, _tlod_import_budget* budget, Image& im);

// Bytes already in memory into im.encoded (from the budget).
void image_keep_bytes(const unsigned char* data, size_t size, _tlod_import_budget* budget, Image& im);

// Both set the MIME type from the signature when the file gave none.

// im.encoded to im.rgba, width, height.
void image_decode(_tlod_import_budget* budget, Image& im);

} // namespace tlod_import_detail

#endif
