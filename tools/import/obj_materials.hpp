// obj_materials.hpp -- OBJ materials (mtllib, read by obj_import.cpp) into the result's materials,
// textures and images (private to tools/import/, C++17). Owned by the import/export layer.
#ifndef TESSLOD_TOOLS_IMPORT_OBJ_MATERIALS_HPP
#define TESSLOD_TOOLS_IMPORT_OBJ_MATERIALS_HPP

#include <tiny_obj_loader.h>

#include "import_output.hpp"

namespace tlod_import_detail {

// Kd and d as the base colour (d < 1: BLEND), map_Kd as a texture whose image is read
// relative to folder under the containment rule and decoded; an image that is missing,
// refused or undecodable is a warning naming the map_Kd reference. Materials are
// double-sided (OBJ says nothing about culling). Call after the geometry (the texture
// coordinates are TEXCOORD_0 when the file has vt).
void read_obj_materials(const std::vector<tinyobj::material_t>& mats, const char* folder, _tlod_import_budget* budget,
                        OutputBase& out);

} // namespace tlod_import_detail

#endif
