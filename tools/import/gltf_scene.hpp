// gltf_scene.hpp -- the glTF scene beyond geometry, for the scene importer (private to tools/import/, C++17).
// Owned by the import/export layer. Nodes and their rest-pose matrices, materials and textures
// (gltf_scene.cpp), images (gltf_images.cpp), animations and skins (gltf_anim.cpp): each reads the
// loaded model through the hardened accessors (gltf_load.hpp) into the output's scene arrays and
// throws tlod_import_detail::ImportError naming the element at fault.
#ifndef TESSLOD_TOOLS_IMPORT_GLTF_SCENE_HPP
#define TESSLOD_TOOLS_IMPORT_GLTF_SCENE_HPP

#include <map>

#include "gltf_load.hpp"

namespace tlod_gltf {

// Column-major 4x4 in double, like glTF's node.matrix.
struct Mat4 {
  double m[16];
};

Mat4 identity();
bool is_identity(const Mat4& a);
Mat4 multiply(const Mat4& a, const Mat4& b);
double det3(const Mat4& a);
// A node's local matrix: its matrix, or T * R * S (rotation renormalised); throws naming the node.
Mat4 local_matrix(const tinygltf::Model& m, int node);

// Every node of the file (tlod_import_node, same indices) with parent and rest-pose world
// matrices; throws naming the node when the node graph is not a forest.
void read_nodes(const tinygltf::Model& m, tlod_import_detail::OutputBase& out);

// Every material and texture (same indices); a bad reference is a warning and reads as none.
// base_color_texcoord stays the glTF texCoord set until resolve_texcoords().
void read_materials(const tinygltf::Model& m, tlod_import_detail::OutputBase& out);

// After the geometry: base_color_texcoord from texCoord n to the index of attribute
// "TEXCOORD_n" (TLOD_IMPORT_NONE when no primitive had it).
void resolve_texcoords(tlod_import_detail::OutputBase& out);

// Bytes of images carried in data: URIs, by image index (captured while tinygltf parses).
using DataImages = std::map<int, std::vector<unsigned char>>;

// Every image (same indices): bytes from a bufferView, a data: URI or a file under the
// containment rule (folder NULL: refused), decoded to RGBA8 within the pixel limit and the
// budget. Anything missing, refused or undecodable is a warning naming the image; never throws
// for it.
void read_images(const tinygltf::Model& m, const Accessors& acc, const char* folder, _tlod_import_budget* budget,
                 const DataImages& data_images, tlod_import_detail::OutputBase& out);

// A primitive's vertex attributes besides POSITION and NORMAL (gltf_attributes.cpp).
struct Extras {
  struct Attr {
    std::string name;
    uint32_t components;
    std::vector<float> data;
  };
  std::vector<Attr> attributes; // TEXCOORD_0, TEXCOORD_1, COLOR_0 (always 4), TANGENT
  std::vector<uint16_t> joints; // JOINTS_0, 4 per vertex; empty: not skinned
  std::vector<float> weights;   // WEIGHTS_0, 4 per vertex, summing to 1
  uint32_t renormalised = 0;    // vertices whose weights were rescaled
};

// Reads them (their counts equal POSITION's, checked by the caller). A layout glTF does not allow for
// TEXCOORD/COLOR/TANGENT is a warning (attribute ignored); JOINTS_0 indices at or past joint_limit (the joint count of
// the skins the mesh is used with), negative, non-finite or badly normalised weights are errors naming the accessor.
Extras read_extras(const tinygltf::Model& m, const Accessors& acc, const tinygltf::Primitive& prim,
                   const std::string& where, uint32_t joint_limit, tlod_import_detail::OutputBase& out);

// Animations (translation, rotation, scale channels) and skins, checked (gltf_anim.cpp).
void read_animations(const tinygltf::Model& m, const Accessors& acc, tlod_import_detail::OutputBase& out);
void read_skins(const tinygltf::Model& m, const Accessors& acc, tlod_import_detail::OutputBase& out);

} // namespace tlod_gltf

#endif
