// gltf_images.cpp -- glTF images: their bytes (bufferView, data: URI, or a file under the
// containment rule) kept for re-export, and base colour images decoded (image_decode.h).
// Owned by the import/export layer. An image that is missing, refused or cannot be decoded
// costs its texture, never the model: a warning names it (by index and URI as written,
// never by what the URI resolved to).
#include <cstdio>

#include "gltf_scene.hpp"
#include "image_load.hpp"

namespace tlod_gltf {

using tlod_import_detail::fail;
using tlod_import_detail::format;
using tlod_import_detail::Image;
using tlod_import_detail::ImportError;
using tlod_import_detail::OutputBase;

namespace {

struct Context {
  const tinygltf::Model& m;
  const Accessors& acc;
  const char* folder;
  _tlod_import_budget* budget;
  const DataImages& data_images;
};

void read_bytes(const Context& c, size_t i, Image& im) {
  const tinygltf::Image& g = c.m.images[i];
  if (g.bufferView >= 0) {
    size_t size = 0;
    const unsigned char* p = c.acc.view_bytes(g.bufferView, "bufferView", &size);
    tlod_import_detail::image_keep_bytes(p, size, c.budget, im);
  } else if (!g.uri.empty()) {
    tlod_import_detail::image_read_file(c.folder, g.uri, c.budget, im);
  } else {
    const auto it = c.data_images.find(int(i));
    if (it == c.data_images.end()) fail(TLOD_ERROR_PARSE, "no image data (bufferView, uri or data: URI)");
    tlod_import_detail::image_keep_bytes(it->second.data(), it->second.size(), c.budget, im);
  }
}

// Images some material uses as its base colour: the ones decoded.
std::vector<char> base_colour_images(const OutputBase& out) {
  std::vector<char> used(out.images.size(), 0);
  for (const tlod_import_material& mat : out.materials)
    if (mat.base_color_texture != TLOD_IMPORT_NONE) {
      const uint32_t image = out.textures[mat.base_color_texture].image;
      if (image != TLOD_IMPORT_NONE) used[image] = 1;
    }
  return used;
}

void read_image(const Context& c, size_t i, bool wanted, Image& im, OutputBase& out) {
  const tinygltf::Image& g = c.m.images[i];
  std::snprintf(im.info.uri, sizeof im.info.uri, "%s", g.uri.c_str());
  std::snprintf(im.info.mime, sizeof im.info.mime, "%s", g.mimeType.c_str());
  try {
    read_bytes(c, i, im);
    if (wanted) tlod_import_detail::image_decode(c.budget, im);
  } catch (const ImportError& e) {
    const std::string name = g.uri.empty() ? "" : format(" '%.200s'", g.uri.c_str());
    out.warn(format("image %zu%s: %s: texture ignored", i, name.c_str(), e.message.c_str()));
  }
}

} // namespace

void read_images(const tinygltf::Model& m, const Accessors& acc, const char* folder, _tlod_import_budget* budget,
                 const DataImages& data_images, OutputBase& out) {
  const Context c{m, acc, folder, budget, data_images};
  acc.take(m.images.size(), sizeof(Image) + sizeof(tlod_import_image), "images");
  out.images.resize(m.images.size());
  const std::vector<char> wanted = base_colour_images(out);
  for (size_t i = 0; i < m.images.size(); ++i)
    read_image(c, i, wanted[i] != 0, out.images[i], out);
}

} // namespace tlod_gltf
