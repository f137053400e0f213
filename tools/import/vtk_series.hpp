// Private to the VTK shim: which files make up an import (docs/vtk.md section 2) -- the file
// itself, the pieces of a .pvtu, the steps of a .pvd, or the numbered files a '*' in the name
// stands for. Every file besides the model itself is a reference under the folder rule
// (contained_file.h), resolved against the model's folder.
#ifndef TESSLOD_TOOLS_IMPORT_VTK_SERIES_HPP
#define TESSLOD_TOOLS_IMPORT_VTK_SERIES_HPP

#include <string>
#include <vector>

#include "import_internal.h"

namespace tlod_import_detail {

struct StepRef {
  std::string ref; // relative to the model's folder, as written; "" for the model file itself
  float time;      // the .pvd's timestep; else the step's index
};

// The steps of a .pvd (its bytes): <DataSet timestep="T" file="F"/> in file order; a
// timestep given twice (several parts per step) is refused.
std::vector<StepRef> pvd_steps(const char* data, size_t size);

// The files FOLDER/PREFIX<digits>SUFFIX for a name PREFIX*SUFFIX, by increasing number.
std::vector<StepRef> numbered_steps(const char* folder, const std::string& pattern);

// The piece files of a .pvtu (its bytes), as references relative to the model's folder
// (a piece's Source is relative to the .pvtu, which is at ref `self`).
std::vector<std::string> pvtu_pieces(const char* data, size_t size, const std::string& self);

} // namespace tlod_import_detail

#endif
