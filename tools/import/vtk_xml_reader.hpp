// Private to the VTK shim: the .vtu and .vtp readers we use, VTK's own with three of their
// error paths repaired (docs/vtk.md section 7). All three are reached by files that are merely
// truncated, and none can be ruled out by looking at the bytes first: whether VTK can read an
// array's values (ASCII, base64, raw, compressed) is only known by reading them.
//   - A piece without <PointData> whose cell data does not read: VTK's error message names the
//     <PointData> element, which is null (SEGV, VTK 9.1 to at least 9.4). An absent <PointData>
//     is replaced by an empty one, which VTK reads as the same thing.
//   - A point data array that is not numeric (a String array) and does not read: VTK's message
//     names it through GetArray(), which is null for it (SEGV). ReadArrayValues reports that
//     failure itself, as an error the import fails on (vtk_read.cpp), and tells VTK it read.
//   - A .vtu piece whose cell "types" array does not read: VTK returns without deleting the array
//     it made for it (a leak). ReadArrayValues deletes it there: VTK calls it with that fresh
//     array, holds it nowhere else, and uses nothing of it after the failure.
// The readers keep VTK's class names (no vtkTypeMacro), so VTK's messages read as before.
#ifndef TESSLOD_TOOLS_IMPORT_VTK_XML_READER_HPP
#define TESSLOD_TOOLS_IMPORT_VTK_XML_READER_HPP

#include <vtkAbstractArray.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>

namespace tlod_import_detail {

// Whether da is a piece's cell types array (<Cells><DataArray Name="types">) in an array only
// VTK's local pointer holds. A "types" array of <CellData> belongs to the output: left alone.
bool is_orphan_cell_types(vtkXMLDataElement* da, vtkAbstractArray* array);

template <class Reader> class RepairedXmlReader : public Reader {
public:
  static RepairedXmlReader* New() {
    auto* r = new RepairedXmlReader;
    r->InitializeObjectBase();
    return r;
  }

protected:
  RepairedXmlReader() { no_point_data_->SetName("PointData"); }

  using Reader::ReadPiece;
  int ReadPiece(vtkXMLDataElement* piece) override {
    const int ok = Reader::ReadPiece(piece);
    if (!this->PointDataElements[this->Piece]) this->PointDataElements[this->Piece] = no_point_data_;
    return ok;
  }

  int ReadArrayValues(vtkXMLDataElement* da, vtkIdType arrayIndex, vtkAbstractArray* array, vtkIdType startIndex,
                      vtkIdType numValues, typename Reader::FieldType type = Reader::OTHER) override {
    const int ok = Reader::ReadArrayValues(da, arrayIndex, array, startIndex, numValues, type);
    if (ok) return ok;
    if (is_orphan_cell_types(da, array)) array->Delete();
    if (type == Reader::POINT_DATA && !vtkArrayDownCast<vtkDataArray>(array)) {
      const char* name = da->GetAttribute("Name");
      vtkErrorMacro("Cannot read point data array \"" << (name ? name : "") << "\" in piece " << this->Piece
                                                      << ": the data array may be too short.");
      return 1;
    }
    return ok;
  }

private:
  vtkNew<vtkXMLDataElement> no_point_data_;
};

using GridReader = RepairedXmlReader<vtkXMLUnstructuredGridReader>;
using PolyReader = RepairedXmlReader<vtkXMLPolyDataReader>;

} // namespace tlod_import_detail

#endif
