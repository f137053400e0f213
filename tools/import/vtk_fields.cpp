// vtk_fields.cpp -- point and cell data of a VTK data set as fields per point (docs/vtk.md
// section 5). Cell data is averaged onto the points: a point gets the mean of the values of
// every cell that lists it (each cell once per listing; points no cell lists get 0). Every
// value must be a finite float; an array whose tuple count is not the point (cell) count is
// refused, naming the array.
#include <cfloat>
#include <cmath>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>

#include "import_error.hpp"
#include "vtk_dataset.hpp"

namespace tlod_import_detail {
namespace {

const char* where(bool cells) { return cells ? "cell data" : "point data"; }

// The values of array a (tuples x comps), checked; false: skipped with a warning.
bool values(vtkAbstractArray* arr, bool cells, size_t tuples, const DatasetHooks& hooks, FieldData& f) {
  const std::string label = format("%s '%.64s'", where(cells), f.name.c_str());
  vtkDataArray* a = vtkDataArray::SafeDownCast(arr);
  if (!a) {
    hooks.warn(label + ": not a numeric array: skipped");
    return false;
  }
  const int comps = a->GetNumberOfComponents();
  if (comps < 1 || comps > TLOD_IMPORT_MAX_FIELD_COMPONENTS) {
    hooks.warn(format("%s: %d components (1..%d): skipped", label.c_str(), comps, TLOD_IMPORT_MAX_FIELD_COMPONENTS));
    return false;
  }
  if (uint64_t(a->GetNumberOfTuples()) != tuples)
    fail(TLOD_ERROR_INVALID_MESH, format("%s: %lld tuples for %zu %s", label.c_str(), (long long)a->GetNumberOfTuples(),
                                         tuples, cells ? "cells" : "points"));
  f.components = uint32_t(comps);
  hooks.take(tuples * size_t(comps) * 4, "fields");
  f.values.resize(tuples * size_t(comps));
  for (size_t t = 0; t < tuples; ++t)
    for (int c = 0; c < comps; ++c) {
      const double v = a->GetComponent(vtkIdType(t), c);
      if (!std::isfinite(v) || std::fabs(v) > FLT_MAX)
        fail(TLOD_ERROR_INVALID_MESH,
             format("%s: tuple %zu component %d: %g is not a finite float", label.c_str(), t, c, v));
      f.values[t * size_t(comps) + size_t(c)] = float(v);
    }
  return true;
}

// Cell values -> per point means (vtk_fields.cpp header comment).
void average_to_points(const CellList& cells, size_t points, const DatasetHooks& hooks, FieldData& f) {
  const size_t k = f.components;
  hooks.take(points * (k * 8 + 4), "cell data averaging");
  std::vector<double> sum(points * k, 0.0);
  std::vector<uint32_t> count(points, 0);
  for (size_t c = 0; c < cells.size(); ++c)
    for (uint64_t i = cells.offsets[c]; i < cells.offsets[c + 1]; ++i) {
      const uint32_t p = cells.conn[i];
      count[p]++;
      for (size_t j = 0; j < k; ++j)
        sum[p * k + j] += f.values[c * k + j];
    }
  f.values.assign(points * k, 0.0f);
  for (size_t p = 0; p < points; ++p)
    for (size_t j = 0; count[p] && j < k; ++j)
      f.values[p * k + j] = float(sum[p * k + j] / count[p]);
}

void read_set(vtkFieldData* data, bool cells, const DatasetHooks& hooks, Dataset& out) {
  if (!data) return;
  for (int i = 0; i < data->GetNumberOfArrays(); ++i) {
    vtkAbstractArray* arr = data->GetAbstractArray(i);
    if (!arr) continue;
    FieldData f;
    const char* name = arr->GetName();
    split_units(name && *name ? name : format("%s %d", where(cells), i), &f.name, &f.units);
    f.from_cells = cells;
    if (!values(arr, cells, cells ? out.cells.size() : out.point_count(), hooks, f)) continue;
    if (out.fields.size() == TLOD_IMPORT_MAX_FIELDS) {
      hooks.warn(
          format("%s '%.64s': more than %d fields: skipped", where(cells), f.name.c_str(), TLOD_IMPORT_MAX_FIELDS));
      continue;
    }
    if (cells) average_to_points(out.cells, out.point_count(), hooks, f);
    out.fields.push_back(std::move(f));
  }
}

} // namespace

void split_units(const std::string& full, std::string* name, std::string* units) {
  *name = full;
  units->clear();
  if (full.size() < 3) return;
  const char close = full.back();
  const char open = close == ']' ? '[' : close == ')' ? '(' : 0;
  const size_t at = open ? full.rfind(open) : std::string::npos;
  if (at == std::string::npos || at == 0) return;
  size_t end = at;
  while (end > 0 && full[end - 1] == ' ')
    --end;
  if (end == 0) return;
  *units = full.substr(at + 1, full.size() - at - 2);
  *name = full.substr(0, end);
}

void read_fields(vtkDataSet* ds, const DatasetHooks& hooks, Dataset& out) {
  read_set(ds->GetPointData(), false, hooks, out);
  read_set(ds->GetCellData(), true, hooks, out);
}

} // namespace tlod_import_detail
