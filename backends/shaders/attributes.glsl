// Mesh attributes at a surface point (after common.glsl): corners exact,
// edge points interpolated in the canonical edge direction (the same
// inputs and order on both sides of an edge, like positions), interior
// points with the corner weights of interior_point. Attributes are linear
// in the patch parameters, so geomorphs need nothing: the midpoint of the
// parents' values is the value at the vertex. u_attribute_count
// (uniforms.glsl): of the item's mesh, 0..TLOD_SHADER_MAX_ATTRIBUTES.

vec4 corner_attribute(uint patch_id, uint c, uint a) {
  return patch_attributes[(patch_id * 4u + c) * u_attribute_count + a];
}

// Attribute a at grid parameter num / N on edge e of patch P (its start corner at 0).
vec4 edge_attribute(uint patch_id, Patch P, uint e, uint num, uint a) {
  uint n = P.info.x, ca = e, cb = (e + 1u) % n;
  if (num == 0u) return corner_attribute(patch_id, ca, a);
  if (num == u_grid) return corner_attribute(patch_id, cb, a);
  precise float t = float(num) / float(u_grid);
  if (P.weld[ca] < P.weld[cb]) {
    precise vec4 r = corner_attribute(patch_id, ca, a) * (1.0 - t) + corner_attribute(patch_id, cb, a) * t;
    return r;
  }
  precise float s = 1.0 - t;
  precise vec4 r = corner_attribute(patch_id, cb, a) * (1.0 - s) + corner_attribute(patch_id, ca, a) * s;
  return r;
}

// Attribute a of a point given as pattern_point's kind (0-3 corner, 4-7
// edge at num, 8 interior at uv); (0, 0, 0, 0) for a >= u_attribute_count.
vec4 point_attribute(uint patch_id, Patch P, uint kind, uint num, vec2 uv, uint a) {
  if (a >= u_attribute_count) return vec4(0.0);
  if (kind < 4u) return corner_attribute(patch_id, kind, a);
  if (kind < 8u) return edge_attribute(patch_id, P, kind - 4u, num, a);
  float w[4];
  corner_weights(P.info.x, uv, w);
  vec4 x = vec4(0.0);
  for (uint c = 0u; c < P.info.x; c++) x += corner_attribute(patch_id, c, a) * w[c];
  return x;
}

// Every attribute of such a point; unused slots (0, 0, 0, 0).
void point_attributes(uint patch_id, Patch P, uint kind, uint num, vec2 uv,
                      out vec4 attr[TLOD_SHADER_MAX_ATTRIBUTES]) {
  for (uint a = 0u; a < uint(TLOD_SHADER_MAX_ATTRIBUTES); a++) attr[a] = point_attribute(patch_id, P, kind, num, uv, a);
}
