// Tessellation levels from the scheduler: inner 2^level, outer per edge the
// finer of the two sides' 2^level, so both sides of an edge generate the
// same points (no strips needed, but split normals still crack).
layout(vertices = TLOD_CORNERS) out;
layout(location = TLOD_LOCATION_TESS_INSTANCE) flat in uint vc_inst[];
layout(location = TLOD_LOCATION_TESS_CORNER) flat in uint vc_corner[];
layout(location = TLOD_LOCATION_TESS_INSTANCE) patch out uint tc_inst;

void main() {
  if (gl_InvocationID == 0) {
    Instance ins = instances[vc_inst[0]];
    tc_inst = vc_inst[0];
    float inner = float(1u << ins.level);
    gl_TessLevelInner[0] = inner;
    gl_TessLevelInner[1] = inner;
    for (uint e = 0u; e < uint(TLOD_CORNERS); e++) {
      uint l = (ins.edge_levels >> (8u * e)) & 255u;
      // GL numbers outer levels by the edge opposite a corner (triangles) or
      // by u/v sides (quads); map our edge e (corner e -> e+1) onto them.
#if TLOD_CORNERS == 3
      const uint outer_of_edge[3] = uint[3](2u, 0u, 1u);  // i->j is w = 0, j->k is u = 0, k->i is v = 0
#else
      const uint outer_of_edge[4] = uint[4](1u, 2u, 3u, 0u);  // v = 0, u = 1, v = 1, u = 0
#endif
      gl_TessLevelOuter[outer_of_edge[e]] = float(1u << l);
    }
  }
}
