// vtk_xml_reader.cpp -- the test behind RepairedXmlReader's leak repair (vtk_xml_reader.hpp).
#include "vtk_xml_reader.hpp"

#include <cstring>

namespace tlod_import_detail {

bool is_orphan_cell_types(vtkXMLDataElement* da, vtkAbstractArray* array) {
  const char* name = da->GetAttribute("Name");
  vtkXMLDataElement* parent = da->GetParent();
  return array && array->GetReferenceCount() == 1 && name && std::strcmp(name, "types") == 0 && parent &&
         parent->GetName() && std::strcmp(parent->GetName(), "Cells") == 0;
}

} // namespace tlod_import_detail
