/* export_gltf.h -- the parts of the glTF writer (private to tools/import/):
 * export_gltf.c writes geometry and the document, export_gltf_scene.c the
 * scene objects (nodes, materials, textures, samplers, images). */
#ifndef TESSLOD_TOOLS_EXPORT_GLTF_H
#define TESSLOD_TOOLS_EXPORT_GLTF_H

#include "export_internal.h"

/* The glTF attribute name of attribute a (index for an unnamed one). */
void _exp_attr_gltf_name(const tlod_export_attribute* a, uint32_t index, char out[48]);
/* "scene", "scenes" and "nodes". */
void _exp_nodes_json(_exp_text* t, const _exp_scene* sc);
/* "materials", "textures" and "samplers" (nothing without a source). */
void _exp_materials_json(_exp_text* t, const _exp_scene* sc);
/* ",\"images\":[...]" of a .glb (bufferViews after the geometry's). */
void _exp_glb_images_json(_exp_text* t, const _exp_scene* sc);

#endif
