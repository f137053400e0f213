/* export_gltf_scene.c -- the scene objects of the glTF writer: nodes (names,
 * hierarchy, TRS or matrix), materials, textures, samplers and the .glb's
 * image entries. Owned by the import/export layer (tools/import/). Indices
 * of source objects are kept (materials, textures, samplers one per
 * texture); images without usable bytes are left out and renumbered. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "export_gltf.h"

const char* tlod_export_image_mime(const tlod_import_image* im) {
  static const unsigned char png[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  const unsigned char* b = im ? im->encoded : NULL;
  if (!b || im->encoded_size < 8) return NULL;
  if (!memcmp(b, png, 8)) return "image/png";
  if (b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) return "image/jpeg";
  return NULL;
}

/* Output index of source image i, or TLOD_IMPORT_NONE when left out. */
static uint32_t _exp_image_slot(const tlod_import_result* r, uint32_t i) {
  if (i >= r->image_count || !tlod_export_image_mime(&r->images[i])) return TLOD_IMPORT_NONE;
  uint32_t slot = 0;
  for (uint32_t k = 0; k < i; ++k)
    slot += tlod_export_image_mime(&r->images[k]) != NULL;
  return slot;
}

static bool _exp_digits(const char* s) {
  if (!*s) return false;
  for (; *s; ++s)
    if (*s < '0' || *s > '9') return false;
  return true;
}

/* glTF's own semantics with the component counts glTF allows them. */
static bool _exp_semantic(const char* name, uint32_t components) {
  if (!strncmp(name, "TEXCOORD_", 9)) return components == 2 && _exp_digits(name + 9);
  if (!strncmp(name, "COLOR_", 6)) return (components == 3 || components == 4) && _exp_digits(name + 6);
  return !strcmp(name, "TANGENT") && components == 4;
}

void _exp_attr_gltf_name(const tlod_export_attribute* a, uint32_t index, char out[48]) {
  if (!a->name || !a->name[0])
    snprintf(out, 48, "_ATTRIBUTE_%u", index);
  else if (a->name[0] == '_' || _exp_semantic(a->name, a->components))
    snprintf(out, 48, "%.47s", a->name);
  else
    snprintf(out, 48, "_%.46s", a->name);
}

/* ------------------------------------------------------------------------ */
/* nodes                                                                    */
/* ------------------------------------------------------------------------ */

static void _exp_trs_matrix(const tlod_import_node* n, float m[16]) {
  const float x = n->rotation[0], y = n->rotation[1], z = n->rotation[2], w = n->rotation[3];
  const float r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),
                      2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                      2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y)};
  memset(m, 0, 16 * sizeof(float));
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k)
      m[4 * c + k] = r[3 * c + k] * n->scale[c];
  for (int k = 0; k < 3; ++k)
    m[12 + k] = n->translation[k];
  m[15] = 1.0f;
}

/* True when the node's T, R, S give its local matrix (within 1e-6 relative). */
static bool _exp_trs_exact(const tlod_import_node* n) {
  float m[16];
  _exp_trs_matrix(n, m);
  for (int i = 0; i < 16; ++i)
    if (!(fabsf(m[i] - n->local[i]) <= 1e-6f * fmaxf(1.0f, fabsf(n->local[i])))) return false;
  return true;
}

static void _exp_floats_json(_exp_text* t, const char* key, const float* v, int n) {
  _exp_text_add(t, ",\"%s\":[", key);
  for (int i = 0; i < n; ++i)
    _exp_text_add(t, "%s%.9g", i ? "," : "", (double)v[i]);
  _exp_text_add(t, "]");
}

static void _exp_transform_json(_exp_text* t, const tlod_import_node* n) {
  static const float zero[3] = {0, 0, 0}, unit_q[4] = {0, 0, 0, 1}, one[3] = {1, 1, 1};
  if (!_exp_trs_exact(n)) {
    _exp_floats_json(t, "matrix", n->local, 16);
    return;
  }
  if (memcmp(n->translation, zero, sizeof zero)) _exp_floats_json(t, "translation", n->translation, 3);
  if (memcmp(n->rotation, unit_q, sizeof unit_q)) _exp_floats_json(t, "rotation", n->rotation, 4);
  if (memcmp(n->scale, one, sizeof one)) _exp_floats_json(t, "scale", n->scale, 3);
}

static void _exp_children_json(_exp_text* t, const tlod_import_result* r, uint32_t parent) {
  uint32_t count = 0;
  for (uint32_t c = 0; c < r->node_count; ++c) {
    if (r->nodes[c].parent != parent) continue;
    _exp_text_add(t, "%s%u", count++ ? "," : (parent == TLOD_IMPORT_NONE ? "" : ",\"children\":["), c);
  }
  if (count && parent != TLOD_IMPORT_NONE) _exp_text_add(t, "]");
}

static void _exp_node_json(_exp_text* t, const _exp_scene* sc, uint32_t i) {
  const tlod_import_node* n = &sc->source->nodes[i];
  _exp_text_add(t, "%s{\"name\":", i ? "," : "");
  _exp_text_string(t, n->name, sizeof n->name);
  _exp_children_json(t, sc->source, i);
  if (sc->node_mesh[i] != TLOD_IMPORT_NONE) _exp_text_add(t, ",\"mesh\":%u", sc->node_mesh[i]);
  _exp_transform_json(t, n);
  _exp_text_add(t, "}");
}

void _exp_nodes_json(_exp_text* t, const _exp_scene* sc) {
  if (!sc->source) {
    _exp_text_add(t, "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],");
    return;
  }
  _exp_text_add(t, "\"scene\":0,\"scenes\":[{\"nodes\":[");
  _exp_children_json(t, sc->source, TLOD_IMPORT_NONE);
  _exp_text_add(t, "]}],\"nodes\":[");
  for (uint32_t i = 0; i < sc->node_count; ++i)
    _exp_node_json(t, sc, i);
  _exp_text_add(t, "],");
}

/* ------------------------------------------------------------------------ */
/* materials, textures, samplers, images                                    */
/* ------------------------------------------------------------------------ */

/* The TEXCOORD set of the material's UVs, or -1 when it has none usable. */
static int _exp_texcoord_set(const tlod_import_result* r, const tlod_import_material* m) {
  if (m->base_color_texture >= r->texture_count || m->base_color_texcoord >= r->attribute_count) return -1;
  const char* name = r->attributes[m->base_color_texcoord].name;
  if (strncmp(name, "TEXCOORD_", 9) || !_exp_digits(name + 9) || strlen(name + 9) > 2) return -1;
  return atoi(name + 9);
}

/* A factor clamped to glTF's [0, 1]; non-finite: 1, glTF's default (the struct may come from a caller). */
static float _exp_unit(float f) { return isfinite(f) ? fminf(fmaxf(f, 0.0f), 1.0f) : 1.0f; }

static void _exp_material_json(_exp_text* t, const tlod_import_result* r, uint32_t i) {
  static const char* const modes[] = {"OPAQUE", "MASK", "BLEND"};
  const tlod_import_material* m = &r->materials[i];
  _exp_text_add(t, "%s{\"name\":", i ? "," : "");
  _exp_text_string(t, m->name, sizeof m->name);
  _exp_text_add(t, ",\"pbrMetallicRoughness\":{\"metallicFactor\":%.9g,\"roughnessFactor\":%.9g",
                (double)_exp_unit(m->metallic), (double)_exp_unit(m->roughness));
  _exp_floats_json(t, "baseColorFactor", m->base_color, 4);
  const int set = _exp_texcoord_set(r, m);
  if (set >= 0) _exp_text_add(t, ",\"baseColorTexture\":{\"index\":%u,\"texCoord\":%d}", m->base_color_texture, set);
  _exp_text_add(t, "}");
  if (m->alpha_mode == TLOD_IMPORT_ALPHA_MASK || m->alpha_mode == TLOD_IMPORT_ALPHA_BLEND)
    _exp_text_add(t, ",\"alphaMode\":\"%s\"", modes[m->alpha_mode]);
  if (m->alpha_mode == TLOD_IMPORT_ALPHA_MASK && isfinite(m->alpha_cutoff) && m->alpha_cutoff >= 0.0f)
    _exp_text_add(t, ",\"alphaCutoff\":%.9g", (double)m->alpha_cutoff);
  if (m->double_sided) _exp_text_add(t, ",\"doubleSided\":true");
  _exp_text_add(t, "}");
}

static bool _exp_gl_enum(int v, const int* allowed, int n) {
  for (int i = 0; i < n; ++i)
    if (v == allowed[i]) return true;
  return false;
}

static void _exp_sampler_json(_exp_text* t, const tlod_import_texture* x, uint32_t i) {
  static const int wraps[] = {33071, 33648, 10497}, mags[] = {9728, 9729},
                   mins[] = {9728, 9729, 9984, 9985, 9986, 9987};
  bool first = true;
  _exp_text_add(t, "%s{", i ? "," : "");
  const int v[4] = {x->mag_filter, x->min_filter, x->wrap_s, x->wrap_t};
  const char* const keys[4] = {"magFilter", "minFilter", "wrapS", "wrapT"};
  for (int k = 0; k < 4; ++k) {
    const bool ok = k == 0   ? _exp_gl_enum(v[k], mags, 2)
                    : k == 1 ? _exp_gl_enum(v[k], mins, 6)
                             : _exp_gl_enum(v[k], wraps, 3);
    if (!ok) continue;
    _exp_text_add(t, "%s\"%s\":%d", first ? "" : ",", keys[k], v[k]);
    first = false;
  }
  _exp_text_add(t, "}");
}

static void _exp_textures_json(_exp_text* t, const tlod_import_result* r) {
  _exp_text_add(t, "\"textures\":[");
  for (uint32_t i = 0; i < r->texture_count; ++i) {
    const uint32_t slot = _exp_image_slot(r, r->textures[i].image);
    _exp_text_add(t, "%s{\"sampler\":%u", i ? "," : "", i);
    if (slot != TLOD_IMPORT_NONE) _exp_text_add(t, ",\"source\":%u", slot);
    _exp_text_add(t, "}");
  }
  _exp_text_add(t, "],\"samplers\":[");
  for (uint32_t i = 0; i < r->texture_count; ++i)
    _exp_sampler_json(t, &r->textures[i], i);
  _exp_text_add(t, "],");
}

void _exp_materials_json(_exp_text* t, const _exp_scene* sc) {
  const tlod_import_result* r = sc->source;
  if (!r) return;
  if (r->material_count) {
    _exp_text_add(t, "\"materials\":[");
    for (uint32_t i = 0; i < r->material_count; ++i)
      _exp_material_json(t, r, i);
    _exp_text_add(t, "],");
  }
  if (r->texture_count) _exp_textures_json(t, r);
}

void _exp_glb_images_json(_exp_text* t, const _exp_scene* sc) {
  if (!sc->source) return;
  uint32_t view = 0, kept = 0;
  for (uint32_t p = 0; p < sc->prim_count; ++p)
    view += 2 + (sc->prims[p].mesh->normals != NULL) + sc->prims[p].mesh->attribute_count;
  for (uint32_t i = 0; i < sc->source->image_count; ++i) {
    const char* mime = tlod_export_image_mime(&sc->source->images[i]);
    if (!mime) continue;
    _exp_text_add(t, "%s{\"bufferView\":%u,\"mimeType\":\"%s\"}", kept ? "," : ",\"images\":[", view + kept, mime);
    ++kept;
  }
  if (kept) _exp_text_add(t, "]");
}
