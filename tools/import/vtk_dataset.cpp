// vtk_dataset.cpp -- points and cells of a VTK data set into plain arrays (vtk_dataset.hpp).
// VTK's legacy reader does not check that a cell's point ids exist, nor do we trust the XML
// reader to: every id is checked here, before the boundary extraction indexes points with it.
#include "vtk_dataset.hpp"

#include <cfloat>
#include <cmath>

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkIdList.h>
#include <vtkPointSet.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include "import_error.hpp"

namespace tlod_import_detail {
namespace {

// Ids fit our uint32 indices; more than this many points or cells is past the output limits anyway.
constexpr uint64_t kMaxCount = uint64_t(1) << 31;

void read_points(vtkDataSet* ds, const DatasetHooks& hooks, Dataset& out) {
  const vtkIdType n = ds->GetNumberOfPoints();
  if (n < 0 || uint64_t(n) > kMaxCount)
    fail(TLOD_ERROR_UNSUPPORTED, format("%lld points (at most 2^31)", (long long)n));
  hooks.take(size_t(n) * 24, "points");
  out.points.resize(size_t(n) * 3);
  vtkPointSet* ps = vtkPointSet::SafeDownCast(ds);
  vtkDataArray* data = ps && ps->GetPoints() ? ps->GetPoints()->GetData() : nullptr;
  for (vtkIdType i = 0; i < n; ++i) {
    double* p = &out.points[size_t(i) * 3];
    if (data)
      data->GetTuple(i, p);
    else
      ds->GetPoint(i, p);
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(p[k]) || std::fabs(p[k]) > FLT_MAX)
        fail(TLOD_ERROR_INVALID_MESH,
             format("point %lld: coordinate %c = %g is not a finite float", (long long)i, "xyz"[k], p[k]));
  }
}

void add_id(Dataset& out, uint64_t cell, vtkIdType id) {
  if (id < 0 || uint64_t(id) >= out.point_count())
    fail(TLOD_ERROR_INVALID_MESH, format("cell %llu: point id %lld out of range (%zu points)", (unsigned long long)cell,
                                         (long long)id, out.point_count()));
  out.cells.conn.push_back(uint32_t(id));
}

void end_cell(Dataset& out, int type) {
  out.cells.types.push_back(uint8_t(type));
  out.cells.offsets.push_back(out.cells.conn.size());
}

// VTK trusts a cell array's offsets (XML files and the 5.x legacy layout give them as data):
// they must start at 0, never decrease and end at the connectivity's size, or iterating the
// cells reads past the connectivity.
void check_offsets(vtkCellArray* a) {
  vtkDataArray* off = a->GetOffsetsArray();
  const vtkIdType n = a->GetNumberOfCells();
  if (!off || off->GetNumberOfTuples() != n + 1) fail(TLOD_ERROR_PARSE, "cell offsets: wrong count");
  double last = 0;
  for (vtkIdType i = 0; i <= n; ++i) {
    const double o = off->GetTuple1(i);
    if ((i == 0 && o != 0) || o < last)
      fail(TLOD_ERROR_PARSE,
           format("cell %lld: offset %.0f before the previous cell's %.0f", (long long)i - 1, o, last));
    last = o;
  }
  if (last != double(a->GetNumberOfConnectivityIds()))
    fail(TLOD_ERROR_PARSE, format("cell offsets end at %.0f, the connectivity holds %lld ids", last,
                                  (long long)a->GetNumberOfConnectivityIds()));
}

// Cells of one vtkCellArray; type_of(n) gives the VTK type of an n-point cell.
template <class TypeOf> void read_array(vtkCellArray* a, TypeOf type_of, Dataset& out) {
  if (!a) return;
  check_offsets(a);
  vtkIdType n;
  const vtkIdType* ids;
  auto it = vtk::TakeSmartPointer(a->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell()) {
    it->GetCurrentCell(n, ids);
    const uint64_t cell = out.cells.size();
    for (vtkIdType i = 0; i < n; ++i)
      add_id(out, cell, ids[i]);
    end_cell(out, type_of(n));
  }
}

void reserve_cells(const DatasetHooks& hooks, Dataset& out, uint64_t cells, uint64_t ids) {
  if (cells > kMaxCount || ids > (kMaxCount << 1))
    fail(TLOD_ERROR_UNSUPPORTED, format("%llu cells with %llu point ids (at most 2^31 cells)",
                                        (unsigned long long)cells, (unsigned long long)ids));
  hooks.take(size_t(cells) * 9 + size_t(ids) * 4, "cells");
  out.cells.types.reserve(size_t(cells));
  out.cells.offsets.reserve(size_t(cells) + 1);
  out.cells.conn.reserve(size_t(ids));
}

void read_poly(vtkPolyData* pd, const DatasetHooks& hooks, Dataset& out) {
  uint64_t cells = 0, ids = 0;
  for (vtkCellArray* a : {pd->GetVerts(), pd->GetLines(), pd->GetPolys(), pd->GetStrips()})
    if (a) cells += uint64_t(a->GetNumberOfCells()), ids += uint64_t(a->GetNumberOfConnectivityIds());
  reserve_cells(hooks, out, cells, ids);
  read_array(
      pd->GetVerts(), [](vtkIdType n) { return n == 1 ? 1 : 2; }, out);
  read_array(
      pd->GetLines(), [](vtkIdType n) { return n == 2 ? 3 : 4; }, out);
  read_array(
      pd->GetPolys(), [](vtkIdType n) { return n == 3   ? 5
                                               : n == 4 ? 9
                                                        : 7; }, out);
  read_array(
      pd->GetStrips(), [](vtkIdType) { return 6; }, out);
}

void read_grid(vtkUnstructuredGrid* ug, const DatasetHooks& hooks, Dataset& out) {
  vtkCellArray* a = ug->GetCells();
  vtkUnsignedCharArray* types = ug->GetCellTypesArray();
  const vtkIdType n = a ? a->GetNumberOfCells() : 0;
  if (n > 0 && (!types || types->GetNumberOfTuples() != n))
    fail(TLOD_ERROR_PARSE,
         format("%lld cells but %lld cell types", (long long)n, (long long)(types ? types->GetNumberOfTuples() : 0)));
  if (n == 0) return;
  reserve_cells(hooks, out, uint64_t(n), uint64_t(a->GetNumberOfConnectivityIds()));
  vtkIdType i = 0;
  read_array(
      a, [&](vtkIdType) { return int(types->GetValue(i++)); }, out);
}

// Structured and image data: VTK makes each cell on request.
void read_generic(vtkDataSet* ds, const DatasetHooks& hooks, Dataset& out) {
  const vtkIdType n = ds->GetNumberOfCells();
  reserve_cells(hooks, out, uint64_t(n), uint64_t(n) * 8);
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < n; ++c) {
    ds->GetCellPoints(c, ids);
    for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i)
      add_id(out, uint64_t(c), ids->GetId(i));
    end_cell(out, ds->GetCellType(c));
  }
}

} // namespace

void convert_dataset(vtkDataSet* ds, const DatasetHooks& hooks, Dataset& out) {
  read_points(ds, hooks, out);
  if (vtkUnstructuredGrid* ug = vtkUnstructuredGrid::SafeDownCast(ds))
    read_grid(ug, hooks, out);
  else if (vtkPolyData* pd = vtkPolyData::SafeDownCast(ds))
    read_poly(pd, hooks, out);
  else
    read_generic(ds, hooks, out);
}

} // namespace tlod_import_detail
