// Private to the VTK shim: VTK's readers run on bytes we read ourselves (the memory budget and
// the folder rule apply before VTK sees anything), each with its errors and warnings captured
// into our one message (docs/vtk.md section 6), after the pre-flight checks of vtk_preflight.cpp.
#ifndef TESSLOD_TOOLS_IMPORT_VTK_READ_HPP
#define TESSLOD_TOOLS_IMPORT_VTK_READ_HPP

#include <cstddef>
#include <functional>
#include <string>

#include <vtkDataSet.h>
#include <vtkSmartPointer.h>

namespace tlod_import_detail {

enum class VtkFormat { Legacy, Vtu, Vtp, Stl };

// One file to read. data/size: its bytes (always read by us first); file_path: where VTK may
// open it itself (STL only: VTK's STL reader takes no bytes), else nullptr.
struct VtkSource {
  std::string name; // for messages: the file name as given or as referenced
  VtkFormat format;
  const char* data;
  size_t size;
  const char* file_path;
};

// Reads src with VTK's reader for its format, after the pre-flight checks against budget_room
// (bytes the import may still allocate). warn receives VTK's warnings (one line each); VTK's
// errors fail the read (TLOD_ERROR_PARSE, "VTK: <what VTK said>"). progress: 0..1.
vtkSmartPointer<vtkDataSet> read_vtk(const VtkSource& src, size_t budget_room,
                                     const std::function<void(const std::string&)>& warn,
                                     const std::function<void(double)>& progress);

// The format of a file name by its extension (.vtk .vtu .vtp .stl); false for others.
bool vtk_format_of(const std::string& name, VtkFormat* out);

} // namespace tlod_import_detail

#endif
