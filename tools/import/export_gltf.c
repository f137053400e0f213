/* export_gltf.c -- the glTF 2.0 writer (.gltf and .glb) of a scene model
 * (export_internal.h): nodes, meshes, materials, textures, samplers and
 * images as JSON, then one binary buffer streamed in the same order as its
 * bufferViews were declared. Owned by the import/export layer.
 *
 * A hand writer rather than tinygltf's: it streams the geometry and images
 * into the file (tinygltf copies everything into its model first and then
 * into a std::string), stays C11 behind no C++ shim, and is the writer the
 * single-mesh export already had. "%.9g" round-trips floats exactly. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "export_gltf.h"

/* ------------------------------------------------------------------------ */
/* Buffer layout: per prim positions, normals, attributes, indices; then    */
/* the images (.glb). Every piece is a multiple of 4 bytes (images padded). */
/* ------------------------------------------------------------------------ */

static size_t _exp_prim_bytes(const tlod_export_mesh* m) {
  size_t bytes = (size_t)m->vertex_count * (m->normals ? 24 : 12) + (size_t)m->triangle_count * 12;
  for (uint32_t a = 0; a < m->attribute_count; ++a)
    bytes += (size_t)m->vertex_count * 4 * m->attributes[a].components;
  return bytes;
}

static size_t _exp_pad4(size_t n) { return (n + 3) & ~(size_t)3; }

static size_t _exp_buffer_bytes(const _exp_scene* sc, bool glb) {
  size_t total = 0;
  for (uint32_t p = 0; p < sc->prim_count; ++p)
    total += _exp_prim_bytes(sc->prims[p].mesh);
  for (uint32_t i = 0; glb && sc->source && i < sc->source->image_count; ++i)
    if (tlod_export_image_mime(&sc->source->images[i])) total += _exp_pad4(sc->source->images[i].encoded_size);
  return total;
}

/* ------------------------------------------------------------------------ */
/* bufferViews and accessors (one view per accessor, tight)                 */
/* ------------------------------------------------------------------------ */

static void _exp_view(_exp_text* t, size_t* offset, size_t length, int target, bool* first) {
  _exp_text_add(t, "%s{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu", *first ? "" : ",", *offset, length);
  if (target) _exp_text_add(t, ",\"target\":%d", target);
  _exp_text_add(t, "}");
  *offset += length, *first = false;
}

static void _exp_views(_exp_text* t, const _exp_scene* sc, bool glb) {
  size_t offset = 0;
  bool first = true;
  _exp_text_add(t, "\"bufferViews\":[");
  for (uint32_t p = 0; p < sc->prim_count; ++p) {
    const tlod_export_mesh* m = sc->prims[p].mesh;
    _exp_view(t, &offset, (size_t)m->vertex_count * 12, 34962, &first);
    if (m->normals) _exp_view(t, &offset, (size_t)m->vertex_count * 12, 34962, &first);
    for (uint32_t a = 0; a < m->attribute_count; ++a)
      _exp_view(t, &offset, (size_t)m->vertex_count * 4 * m->attributes[a].components, 34962, &first);
    _exp_view(t, &offset, (size_t)m->triangle_count * 12, 34963, &first);
  }
  for (uint32_t i = 0; glb && sc->source && i < sc->source->image_count; ++i) {
    const tlod_import_image* im = &sc->source->images[i];
    if (!tlod_export_image_mime(im)) continue;
    _exp_view(t, &offset, im->encoded_size, 0, &first);
    offset = _exp_pad4(offset);
  }
  _exp_text_add(t, "],");
}

/* POSITION min and max are required by glTF. */
static void _exp_bounds(const tlod_export_mesh* m, float lo[3], float hi[3]) {
  for (int c = 0; c < 3; ++c)
    lo[c] = hi[c] = m->positions[c];
  for (size_t i = 0; i < m->vertex_count; ++i)
    for (int c = 0; c < 3; ++c) {
      const float v = m->positions[3 * i + (size_t)c];
      lo[c] = v < lo[c] ? v : lo[c];
      hi[c] = v > hi[c] ? v : hi[c];
    }
}

static void _exp_accessor(_exp_text* t, uint32_t view, int type, size_t count, uint32_t components) {
  static const char* const names[] = {"SCALAR", "VEC2", "VEC3", "VEC4"};
  _exp_text_add(t, "%s{\"bufferView\":%u,\"componentType\":%d,\"count\":%zu,\"type\":\"%s\"}", view ? "," : "", view,
                type, count, names[components - 1]);
}

static void _exp_accessors(_exp_text* t, const _exp_scene* sc) {
  uint32_t view = 0;
  _exp_text_add(t, "\"accessors\":[");
  for (uint32_t p = 0; p < sc->prim_count; ++p) {
    const tlod_export_mesh* m = sc->prims[p].mesh;
    float lo[3], hi[3];
    _exp_bounds(m, lo, hi);
    _exp_text_add(t,
                  "%s{\"bufferView\":%u,\"componentType\":5126,\"count\":%u,\"type\":\"VEC3\","
                  "\"min\":[%.9g,%.9g,%.9g],\"max\":[%.9g,%.9g,%.9g]}",
                  view ? "," : "", view, m->vertex_count, (double)lo[0], (double)lo[1], (double)lo[2], (double)hi[0],
                  (double)hi[1], (double)hi[2]);
    ++view;
    if (m->normals) _exp_accessor(t, view++, 5126, m->vertex_count, 3);
    for (uint32_t a = 0; a < m->attribute_count; ++a)
      _exp_accessor(t, view++, 5126, m->vertex_count, m->attributes[a].components);
    _exp_accessor(t, view++, 5125, 3 * (size_t)m->triangle_count, 1);
  }
  _exp_text_add(t, "],");
}

/* ------------------------------------------------------------------------ */
/* meshes                                                                   */
/* ------------------------------------------------------------------------ */

/* *k: the prim's first accessor (POSITION); advanced past its last (indices). */
static void _exp_prim_json(_exp_text* t, const _exp_scene* sc, uint32_t p, uint32_t* next) {
  const tlod_export_mesh* m = sc->prims[p].mesh;
  uint32_t k = *next;
  _exp_text_add(t, "{\"attributes\":{\"POSITION\":%u", k++);
  if (m->normals) _exp_text_add(t, ",\"NORMAL\":%u", k++);
  for (uint32_t a = 0; a < m->attribute_count; ++a) {
    char name[48];
    _exp_attr_gltf_name(&m->attributes[a], a, name);
    _exp_text_add(t, ",");
    _exp_text_string(t, name, sizeof name);
    _exp_text_add(t, ":%u", k++);
  }
  _exp_text_add(t, "},\"indices\":%u,\"mode\":4", k);
  *next = k + 1;
  const uint32_t mat = sc->prims[p].material;
  if (sc->source && mat < sc->source->material_count) _exp_text_add(t, ",\"material\":%u", mat);
  _exp_text_add(t, "}");
}

/* Meshes hold the prims in order (mesh i's follow mesh i - 1's), so the
 * accessors, declared prim by prim, are numbered by one running count. */
static void _exp_meshes(_exp_text* t, const _exp_scene* sc) {
  uint32_t accessor = 0;
  _exp_text_add(t, "\"meshes\":[");
  for (uint32_t i = 0; i < sc->mesh_count; ++i) {
    const _exp_gltf_mesh* me = &sc->meshes[i];
    _exp_text_add(t, "%s{", i ? "," : "");
    if (me->name && me->name[0]) {
      char name[160];
      snprintf(name, sizeof name, "%.63s%s%.63s", me->name, me->suffix ? "@" : "", me->suffix ? me->suffix : "");
      _exp_text_add(t, "\"name\":");
      _exp_text_string(t, name, sizeof name);
      _exp_text_add(t, ",");
    }
    _exp_text_add(t, "\"primitives\":[");
    for (uint32_t p = 0; p < me->count; ++p) {
      if (p) _exp_text_add(t, ",");
      _exp_prim_json(t, sc, me->first + p, &accessor);
    }
    _exp_text_add(t, "]}");
  }
  _exp_text_add(t, "],");
}

/* ------------------------------------------------------------------------ */
/* binary                                                                   */
/* ------------------------------------------------------------------------ */

/* glTF requires unit normals and tangents with w = +-1; interpolation
 * shortens them, so they are renormalised on the way out. */
static void _exp_unit3(const float* in, float out[3]) {
  const float len = sqrtf(in[0] * in[0] + in[1] * in[1] + in[2] * in[2]);
  out[0] = in[0], out[1] = in[1], out[2] = in[2];
  if (fabsf(len - 1.0f) <= 1e-4f) return;
  if (len > 0.0f && isfinite(len))
    out[0] /= len, out[1] /= len, out[2] /= len;
  else
    out[0] = 0.0f, out[1] = 0.0f, out[2] = 1.0f;
}

static void _exp_floats(_exp_sink* s, const float* v, uint32_t n) {
  for (uint32_t c = 0; c < n; ++c)
    _exp_sink_u32(s, _exp_float_bits(v[c]));
}

static void _exp_attr_binary(_exp_sink* s, const tlod_export_attribute* a, uint32_t count) {
  const bool tangent = a->name && !strcmp(a->name, "TANGENT") && a->components == 4;
  for (uint32_t v = 0; v < count; ++v) {
    const float* x = _exp_attr_at(a, v);
    if (!tangent) {
      _exp_floats(s, x, a->components);
      continue;
    }
    float u[4];
    _exp_unit3(x, u);
    u[3] = x[3] < 0.0f ? -1.0f : 1.0f;
    _exp_floats(s, u, 4);
  }
}

static void _exp_prim_binary(_exp_sink* s, const tlod_export_mesh* m) {
  _exp_floats(s, m->positions, 3 * m->vertex_count);
  for (uint32_t v = 0; m->normals && v < m->vertex_count; ++v) {
    float n[3];
    _exp_unit3(m->normals + 3 * (size_t)v, n);
    _exp_floats(s, n, 3);
  }
  for (uint32_t a = 0; a < m->attribute_count; ++a)
    _exp_attr_binary(s, &m->attributes[a], m->vertex_count);
  for (size_t i = 0; i < 3 * (size_t)m->triangle_count; ++i)
    _exp_sink_u32(s, m->indices[i]);
}

static void _exp_binary(_exp_sink* s, const _exp_scene* sc, bool glb) {
  for (uint32_t p = 0; p < sc->prim_count; ++p)
    _exp_prim_binary(s, sc->prims[p].mesh);
  for (uint32_t i = 0; glb && sc->source && i < sc->source->image_count; ++i) {
    const tlod_import_image* im = &sc->source->images[i];
    if (!tlod_export_image_mime(im)) continue;
    static const unsigned char zeros[3] = {0};
    _exp_sink_put(s, im->encoded, im->encoded_size);
    _exp_sink_put(s, zeros, _exp_pad4(im->encoded_size) - im->encoded_size);
  }
  _exp_sink_end(s);
}

/* ------------------------------------------------------------------------ */
/* document                                                                 */
/* ------------------------------------------------------------------------ */

/* Everything but the buffers and images, which go last so that a .gltf's
 * base64 data can be streamed after the text. */
static void _exp_json(_exp_text* t, const _exp_scene* sc, bool glb) {
  _exp_text_add(t, "{\"asset\":{\"version\":\"2.0\",\"generator\":\"tesslod\"},");
  _exp_nodes_json(t, sc);
  _exp_meshes(t, sc);
  _exp_materials_json(t, sc);
  _exp_views(t, sc, glb);
  _exp_accessors(t, sc);
  _exp_text_add(t, "\"buffers\":[{\"byteLength\":%zu", _exp_buffer_bytes(sc, glb));
}

/* .gltf: the buffer, then every kept image, as streamed data URIs. */
static void _exp_gltf_tail(_exp_job* job, _exp_sink* s, const _exp_scene* sc) {
  _exp_printf(job, ",\"uri\":\"data:application/octet-stream;base64,");
  s->base64 = true;
  _exp_binary(s, sc, false);
  _exp_printf(job, "\"}]");
  uint32_t kept = 0;
  for (uint32_t i = 0; sc->source && i < sc->source->image_count; ++i) {
    const tlod_import_image* im = &sc->source->images[i];
    const char* mime = tlod_export_image_mime(im);
    if (!mime) continue;
    _exp_printf(job, "%s{\"mimeType\":\"%s\",\"uri\":\"data:%s;base64,", kept++ ? "," : ",\"images\":[", mime, mime);
    _exp_sink_put(s, im->encoded, im->encoded_size);
    _exp_sink_end(s);
    _exp_printf(job, "\"}");
  }
  _exp_printf(job, "%s}\n", kept ? "]" : "");
}

static tlod_result _exp_text_failed(_exp_job* job, _exp_text* t) {
  free(t->s);
  return _exp_fail(job, TLOD_ERROR_OUT_OF_MEMORY, "out of memory");
}

static void _exp_glb_chunk_header(_exp_job* job, size_t length, uint32_t type) {
  unsigned char h[8];
  _exp_put_u32(h, (uint32_t)length);
  _exp_put_u32(h + 4, type);
  _exp_write(job, h, 8);
}

static tlod_result _exp_glb(_exp_job* job, _exp_sink* s, const _exp_scene* sc, _exp_text* t) {
  _exp_text_add(t, "}]");
  _exp_glb_images_json(t, sc);
  _exp_text_add(t, "}");
  while (!t->failed && t->len % 4)
    _exp_text_add(t, " "); /* JSON chunk padding is spaces */
  if (t->failed) return _exp_text_failed(job, t);
  const size_t bin = _exp_buffer_bytes(sc, true);
  const size_t total = 12 + 8 + t->len + 8 + bin;
  if (total > 0xFFFFFFFFu) {
    free(t->s);
    return _exp_fail(job, TLOD_ERROR_UNSUPPORTED, "%zu bytes do not fit a GLB (4 GiB limit)", total);
  }
  unsigned char header[12] = {'g', 'l', 'T', 'F'};
  _exp_put_u32(header + 4, 2);
  _exp_put_u32(header + 8, (uint32_t)total);
  _exp_write(job, header, 12);
  _exp_glb_chunk_header(job, t->len, 0x4E4F534Au);
  _exp_write(job, t->s, t->len);
  free(t->s);
  _exp_glb_chunk_header(job, bin, 0x004E4942u);
  _exp_binary(s, sc, true);
  return TLOD_SUCCESS;
}

tlod_result _exp_gltf(_exp_job* job, _exp_sink* s, const _exp_scene* sc, bool glb) {
  _exp_text t = {0};
  _exp_json(&t, sc, glb);
  if (t.failed) return _exp_text_failed(job, &t);
  if (glb) return _exp_glb(job, s, sc, &t);
  _exp_write(job, t.s, t.len);
  free(t.s);
  _exp_gltf_tail(job, s, sc);
  return TLOD_SUCCESS;
}
