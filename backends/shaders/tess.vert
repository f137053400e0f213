// Hardware tessellation path: one patch per instance of the draw list; the
// vertex shader only names the patch and the corner (u_first_instance,
// u_corners: uniforms.glsl).
layout(location = TLOD_LOCATION_TESS_INSTANCE) flat out uint vc_inst;
layout(location = TLOD_LOCATION_TESS_CORNER) flat out uint vc_corner;

void main() {
  vc_inst = u_first_instance + uint(TLOD_VERTEX_ID) / u_corners;
  vc_corner = uint(TLOD_VERTEX_ID) % u_corners;
}
