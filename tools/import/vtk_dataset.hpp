// Private to the VTK shim: a VTK data set as plain arrays -- its points (doubles, checked
// finite), its cells (CellList, ids checked in range) and its point and cell data (fields) --
// so that nothing after this step touches VTK (docs/vtk.md sections 4 and 5).
#ifndef TESSLOD_TOOLS_IMPORT_VTK_DATASET_HPP
#define TESSLOD_TOOLS_IMPORT_VTK_DATASET_HPP

#include <functional>
#include <string>
#include <vector>

#include <vtkDataSet.h>

#include "vtk_boundary.hpp"

namespace tlod_import_detail {

// One array of point or cell data, per point of the data set (cell data already averaged).
struct FieldData {
  std::string name, units; // "stress [MPa]" -> "stress", "MPa"
  uint32_t components = 0;
  bool from_cells = false;
  std::vector<float> values; // point_count x components
};

struct Dataset {
  std::vector<double> points; // 3 per point
  CellList cells;
  std::vector<FieldData> fields;
  size_t point_count() const { return points.size() / 3; }
};

struct DatasetHooks {
  std::function<void(size_t bytes, const char* what)> take; // the memory budget; throws
  std::function<void(const std::string&)> warn;
};

// Points and cells of ds into out (fields: read_fields). Throws ImportError naming the point, cell, array or tuple at
// fault.
void convert_dataset(vtkDataSet* ds, const DatasetHooks& hooks, Dataset& out);

// Point and cell data of ds into out.fields (vtk_fields.cpp); out.cells must be filled.
void read_fields(vtkDataSet* ds, const DatasetHooks& hooks, Dataset& out);

// "NAME [UNITS]" or "NAME (UNITS)" -> name, units; otherwise the whole name, "".
void split_units(const std::string& full, std::string* name, std::string* units);

} // namespace tlod_import_detail

#endif
