// obj_materials.cpp -- OBJ materials, their map_Kd textures and images (obj_materials.hpp).
// Owned by the import/export layer.
#include <cstdio>

#include "image_load.hpp"
#include "obj_materials.hpp"

namespace tlod_import_detail {

namespace {

// The image of a map_Kd reference, read once however many materials name it.
uint32_t texture_for(const std::string& ref, const char* folder, _tlod_import_budget* budget, OutputBase& out) {
  for (size_t i = 0; i < out.images.size(); ++i)
    if (ref == out.images[i].info.uri) return uint32_t(i);
  if (!_tlod_budget_take(budget, sizeof(Image) + sizeof(tlod_import_texture)))
    fail(TLOD_ERROR_OUT_OF_MEMORY, "materials exceed the import's memory budget (tlod_import_desc.memory_limit)");
  out.images.emplace_back();
  Image& im = out.images.back();
  std::snprintf(im.info.uri, sizeof im.info.uri, "%s", ref.c_str());
  try {
    image_read_file(folder, ref, budget, im);
    image_decode(budget, im);
  } catch (const ImportError& e) {
    out.warn(format("map_Kd '%.200s': %s: texture ignored", ref.c_str(), e.message.c_str()));
  }
  out.textures.push_back({uint32_t(out.images.size() - 1), 0, 0, 0, 0});
  return uint32_t(out.textures.size() - 1);
}

uint32_t texcoord_attribute(const OutputBase& out) {
  for (size_t a = 0; a < out.attributes.size(); ++a)
    if (out.attributes[a].name == "TEXCOORD_0") return uint32_t(a);
  return TLOD_IMPORT_NONE;
}

} // namespace

void read_obj_materials(const std::vector<tinyobj::material_t>& mats, const char* folder, _tlod_import_budget* budget,
                        OutputBase& out) {
  if (!_tlod_budget_take(budget, mats.size() * sizeof(tlod_import_material)))
    fail(TLOD_ERROR_OUT_OF_MEMORY, "materials exceed the import's memory budget (tlod_import_desc.memory_limit)");
  for (const tinyobj::material_t& m : mats) {
    tlod_import_material r{};
    std::snprintf(r.name, sizeof r.name, "%s", m.name.c_str());
    for (int i = 0; i < 3; ++i)
      r.base_color[i] = float(m.diffuse[i]);
    r.base_color[3] = float(m.dissolve);
    r.alpha_mode = m.dissolve < 1.0 ? TLOD_IMPORT_ALPHA_BLEND : TLOD_IMPORT_ALPHA_OPAQUE;
    r.alpha_cutoff = 0.5f;
    r.double_sided = true;
    r.metallic = 0.0f;
    r.roughness = 1.0f;
    r.base_color_texture = TLOD_IMPORT_NONE;
    r.base_color_texcoord = TLOD_IMPORT_NONE;
    if (!m.diffuse_texname.empty()) {
      r.base_color_texture = texture_for(m.diffuse_texname, folder, budget, out);
      r.base_color_texcoord = texcoord_attribute(out);
    }
    out.materials.push_back(r);
  }
}

} // namespace tlod_import_detail
