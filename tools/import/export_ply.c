/* export_ply.c -- one triangle mesh as binary little-endian PLY: x y z,
 * nx ny nz, u v (TEXCOORD_0 as it is: the importer reads PLY u v as stored,
 * so they round-trip bitwise), red green blue alpha (COLOR_0 as uchar).
 * Owned by the import/export layer (tools/import/). Floats are stored as
 * their bits: positions read back bit-exactly. */
#include <math.h>

#include "export_internal.h"

static unsigned char _exp_unorm8(float c) {
  const float v = roundf(c * 255.0f);
  return (unsigned char)(v < 0.0f ? 0.0f : v > 255.0f ? 255.0f : v);
}

static void _exp_ply_header(_exp_job* job, const tlod_export_mesh* m, bool uv, bool color) {
  _exp_printf(job,
              "ply\nformat binary_little_endian 1.0\ncomment tesslod export\nelement vertex %u\n"
              "property float x\nproperty float y\nproperty float z\n",
              m->vertex_count);
  if (m->normals) _exp_printf(job, "property float nx\nproperty float ny\nproperty float nz\n");
  if (uv) _exp_printf(job, "property float u\nproperty float v\n");
  if (color) _exp_printf(job, "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n");
  _exp_printf(job, "element face %u\nproperty list uchar uint vertex_indices\nend_header\n", m->triangle_count);
}

static void _exp_ply_vertex(_exp_sink* s, const tlod_export_mesh* m, uint32_t i, const tlod_export_attribute* uv,
                            const tlod_export_attribute* color) {
  for (int c = 0; c < 3; ++c)
    _exp_sink_u32(s, _exp_float_bits(m->positions[3 * (size_t)i + (size_t)c]));
  for (int c = 0; m->normals && c < 3; ++c)
    _exp_sink_u32(s, _exp_float_bits(m->normals[3 * (size_t)i + (size_t)c]));
  if (uv) {
    const float* t = _exp_attr_at(uv, i);
    _exp_sink_u32(s, _exp_float_bits(t[0]));
    _exp_sink_u32(s, _exp_float_bits(t[1]));
  }
  if (color) {
    const float* k = _exp_attr_at(color, i);
    unsigned char rgba[4] = {_exp_unorm8(k[0]), _exp_unorm8(k[1]), _exp_unorm8(k[2]),
                             color->components > 3 ? _exp_unorm8(k[3]) : 255};
    _exp_sink_put(s, rgba, 4);
  }
}

void _exp_ply(_exp_job* job, _exp_sink* s, const tlod_export_mesh* m) {
  const tlod_export_attribute* uv = _exp_find_attr(m, "TEXCOORD_0");
  const tlod_export_attribute* color = _exp_find_attr(m, "COLOR_0");
  if (uv && uv->components < 2) uv = NULL;
  if (color && color->components < 3) color = NULL;
  _exp_ply_header(job, m, uv != NULL, color != NULL);
  for (uint32_t i = 0; i < m->vertex_count; ++i)
    _exp_ply_vertex(s, m, i, uv, color);
  for (uint32_t t = 0; t < m->triangle_count; ++t) {
    const unsigned char three = 3;
    _exp_sink_put(s, &three, 1);
    for (int c = 0; c < 3; ++c)
      _exp_sink_u32(s, m->indices[3 * (size_t)t + (size_t)c]);
  }
  _exp_sink_end(s);
}
