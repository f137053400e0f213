// Private to the C++ import shims: the part of the output both build (the
// arrays, the parts and the warnings) and how it reaches _tlod_import_data.
#ifndef TESSLOD_TOOLS_IMPORT_OUTPUT_HPP
#define TESSLOD_TOOLS_IMPORT_OUTPUT_HPP

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "import_internal.h"

namespace tlod_import_detail {

// A vertex attribute of the whole output (tlod_import_attribute), padded
// with its default for parts without it.
struct Attribute {
  std::string name;
  uint32_t components = 0;
  float fill = 0.0f; // COLOR_0: 1 (white, opaque)
  std::vector<float> data;
};

struct Image {
  tlod_import_image info{}; // rgba/encoded set by fill()
  std::vector<uint8_t> rgba, encoded;
};

struct Channel {
  tlod_import_channel info{};
  std::vector<float> times, values;
};

struct Animation {
  tlod_import_animation info{};
  std::vector<Channel> channels;
  std::vector<tlod_import_channel> flat; // made by fill()
};

struct Skin {
  tlod_import_skin info{};
  std::vector<uint32_t> joints;
  std::vector<float> inverse_bind;
};

struct OutputBase {
  std::vector<float> positions;
  std::vector<float> normals;
  std::vector<uint32_t> indices;
  std::vector<tlod_import_part> parts;
  bool any_normals = false;
  std::string warnings;
  uint32_t warning_count = 0;
  std::vector<Attribute> attributes;
  std::vector<uint16_t> joints; // empty: no part skinned
  std::vector<float> weights;
  uint32_t weights_renormalised = 0;
  std::vector<tlod_import_mesh> meshes;
  std::vector<tlod_import_node> nodes;
  std::vector<tlod_import_material> materials;
  std::vector<tlod_import_texture> textures;
  std::vector<Image> images;
  std::vector<Animation> animations;
  std::vector<Skin> skins;

  void warn(const std::string& w) {
    warnings += w;
    warnings += '\n';
    warning_count++;
  }

  // The attribute called name, made (zero/one-filled for the first vertices) on first use;
  // nullptr when TLOD_IMPORT_MAX_ATTRIBUTES are taken (a warning).
  Attribute* attribute(const std::string& name, uint32_t components, size_t first_vertex) {
    for (Attribute& a : attributes)
      if (a.name == name) return &a;
    if (attributes.size() == TLOD_IMPORT_MAX_ATTRIBUTES) {
      warn(name + ": more than " + std::to_string(TLOD_IMPORT_MAX_ATTRIBUTES) + " vertex attributes: ignored");
      return nullptr;
    }
    const float fill = name.rfind("COLOR_", 0) == 0 ? 1.0f : 0.0f;
    attributes.push_back({name, components, fill, std::vector<float>(first_vertex * components, fill)});
    return &attributes.back();
  }

  // Values of one part for attribute name (first_vertex: where the part starts).
  void add_attribute(const std::string& name, uint32_t components, size_t first_vertex, const std::vector<float>& v) {
    Attribute* a = attribute(name, components, first_vertex);
    if (!a) return;
    a->data.resize(first_vertex * components, a->fill);
    a->data.insert(a->data.end(), v.begin(), v.end());
  }

  // One part's JOINTS_0 / WEIGHTS_0 (4 per vertex).
  void add_skin_weights(size_t first_vertex, const std::vector<uint16_t>& j, const std::vector<float>& w) {
    joints.resize(first_vertex * 4, 0);
    weights.resize(first_vertex * 4, 0.0f);
    joints.insert(joints.end(), j.begin(), j.end());
    weights.insert(weights.end(), w.begin(), w.end());
  }

  // After each part: every attribute (and the skin arrays, if any) covers every vertex.
  void pad_attributes() {
    const size_t n = positions.size() / 3;
    for (Attribute& a : attributes)
      a.data.resize(n * a.components, a.fill);
    if (!joints.empty()) {
      joints.resize(n * 4, 0);
      weights.resize(n * 4, 0.0f);
    }
  }

  // Fills what OutputBase holds into d; the rest (faces, the importer's
  // own counts) is the importer's. The arrays d points to live in *this.
  void fill(_tlod_import_data& d) {
    d.vertex_count = uint32_t(positions.size() / 3);
    d.positions = positions.data();
    d.normals = any_normals ? normals.data() : nullptr;
    d.index_count = uint32_t(indices.size());
    d.indices = indices.data();
    d.part_count = uint32_t(parts.size());
    d.parts = parts.data();
    d.warnings = warnings.c_str();
    d.warning_count = warning_count;
    fill_scene(d);
  }

private:
  std::vector<tlod_import_attribute> flat_attributes_;
  std::vector<tlod_import_image> flat_images_;
  std::vector<tlod_import_animation> flat_animations_;
  std::vector<tlod_import_skin> flat_skins_;

  void fill_scene(_tlod_import_data& d) {
    pad_attributes();
    flat_attributes_.clear();
    for (Attribute& a : attributes) {
      tlod_import_attribute t{};
      std::snprintf(t.name, sizeof t.name, "%s", a.name.c_str());
      t.components = a.components;
      t.data = a.data.data();
      flat_attributes_.push_back(t);
    }
    d.attribute_count = uint32_t(flat_attributes_.size());
    d.attributes = flat_attributes_.data();
    d.joints = joints.empty() ? nullptr : joints.data();
    d.weights = joints.empty() ? nullptr : weights.data();
    d.weights_renormalised = weights_renormalised;
    d.mesh_count = uint32_t(meshes.size());
    d.meshes = meshes.data();
    d.node_count = uint32_t(nodes.size());
    d.nodes = nodes.data();
    d.material_count = uint32_t(materials.size());
    d.materials = materials.data();
    d.texture_count = uint32_t(textures.size());
    d.textures = textures.data();
    fill_images(d);
    fill_animations(d);
  }

  void fill_images(_tlod_import_data& d) {
    flat_images_.clear();
    for (Image& im : images) {
      tlod_import_image t = im.info;
      t.rgba = im.rgba.empty() ? nullptr : im.rgba.data();
      t.encoded = im.encoded.empty() ? nullptr : im.encoded.data();
      t.encoded_size = im.encoded.size();
      if (!t.rgba) t.width = t.height = 0;
      flat_images_.push_back(t);
    }
    d.image_count = uint32_t(flat_images_.size());
    d.images = flat_images_.data();
  }

  void fill_animations(_tlod_import_data& d) {
    flat_animations_.clear();
    for (Animation& an : animations) {
      an.flat.clear();
      for (Channel& c : an.channels) {
        tlod_import_channel t = c.info;
        t.key_count = uint32_t(c.times.size());
        t.times = c.times.data();
        t.values = c.values.data();
        an.flat.push_back(t);
      }
      tlod_import_animation t = an.info;
      t.channel_count = uint32_t(an.flat.size());
      t.channels = an.flat.data();
      flat_animations_.push_back(t);
    }
    d.animation_count = uint32_t(flat_animations_.size());
    d.animations = flat_animations_.data();
    flat_skins_.clear();
    for (Skin& s : skins) {
      tlod_import_skin t = s.info;
      t.joint_count = uint32_t(s.joints.size());
      t.joints = s.joints.data();
      t.inverse_bind = s.inverse_bind.data();
      flat_skins_.push_back(t);
    }
    d.skin_count = uint32_t(flat_skins_.size());
    d.skins = flat_skins_.data();
  }
};

} // namespace tlod_import_detail

#endif
