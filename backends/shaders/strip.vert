// Connection strips: each vertex names a strip and a point of its pattern
// (r <= 2^la: point r of a's edge polyline; else point r - 2^la - 1 of b's,
// given in a's direction). Points are evaluated exactly as the patches' own
// edge vertices, geomorph included, so strip and patch meet bitwise.
layout(location = TLOD_ATTRIB_STRIP_REF) in uvec2 a_ref;  // strip, point

layout(location = TLOD_LOCATION_NORMAL) out vec3 v_normal;
layout(location = TLOD_LOCATION_WORLD) out vec3 v_world;
layout(location = TLOD_LOCATION_LEVEL) flat out uint v_level;
layout(location = TLOD_LOCATION_STRIP) flat out uint v_strip;

// Point i of the level-l polyline on edge e of P, with e's blend a.
void polyline_point(Patch P, uint e, uint l, uint i, float a, out vec3 pos, out vec3 nrm) {
  uint shift = u_max_level - l;
  patch_edge_point(P, e, i << shift, pos, nrm);
  if ((i & 1u) == 1u && l > 0u && a < 1.0) {
    vec3 p0, n0, p1, n1;
    patch_edge_point(P, e, (i - 1u) << shift, p0, n0);
    patch_edge_point(P, e, (i + 1u) << shift, p1, n1);
    morph_point(a, p0, n0, p1, n1, pos, nrm);
  }
}

void main() {
  Strip S = strips[a_ref.x];
  uint la = S.levels & 255u, lb = S.levels >> 8, ea = S.edges & 255u, eb = S.edges >> 8;
  uint na = 1u << la, nb = 1u << lb, r = a_ref.y;
  vec3 pos, nrm;
  if (r <= na) {
    polyline_point(patches[S.patch_a], ea, la, r, S.morph.x, pos, nrm);
    v_level = la;
  } else {
    polyline_point(patches[S.patch_b], eb, lb, nb - (r - na - 1u), S.morph.y, pos, nrm);
    v_level = lb;
  }
  // Every point takes side a's attributes at the same edge point (b's
  // point r - na - 1 of nb, in a's direction), as the cpu tessellator does:
  // no strip smears the two sides of an attribute seam.
  uint num = r <= na ? r << (u_max_level - la) : (r - na - 1u) << (u_max_level - lb);
  write_varyings(S.patch_a, patches[S.patch_a], 4u + ea, num, vec2(0.0));
  v_normal = world_normal(nrm);
  v_world = world_position(pos);
  v_strip = 1u;
  gl_Position = u_view_proj * vec4(pos, 1.0);
}
