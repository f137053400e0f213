// Private to the C++ import shims: the part of the output both build (the
// arrays, the parts and the warnings) and how it reaches _tlod_import_data.
#ifndef TESSLOD_TOOLS_IMPORT_OUTPUT_HPP
#define TESSLOD_TOOLS_IMPORT_OUTPUT_HPP

#include <cstdint>
#include <string>
#include <vector>

#include "import_internal.h"

namespace tlod_import_detail {

struct OutputBase {
  std::vector<float> positions;
  std::vector<float> normals;
  std::vector<uint32_t> indices;
  std::vector<tlod_import_part> parts;
  bool any_normals = false;
  std::string warnings;
  uint32_t warning_count = 0;

  void warn(const std::string& w) {
    warnings += w;
    warnings += '\n';
    warning_count++;
  }

  // Fills what OutputBase holds into d; the rest (faces, the importer's
  // own counts) is the importer's.
  void fill(_tlod_import_data& d) const {
    d.vertex_count = uint32_t(positions.size() / 3);
    d.positions = positions.data();
    d.normals = any_normals ? normals.data() : nullptr;
    d.index_count = uint32_t(indices.size());
    d.indices = indices.data();
    d.part_count = uint32_t(parts.size());
    d.parts = parts.data();
    d.warnings = warnings.c_str();
    d.warning_count = warning_count;
  }
};

} // namespace tlod_import_detail

#endif
