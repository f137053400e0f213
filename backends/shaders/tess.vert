// Hardware tessellation path: one patch per instance of the draw list; the
// vertex shader only names the patch and the corner.
uniform uint u_first_instance;
uniform uint u_corners;  // 3 or 4

flat out uint vc_inst;
flat out uint vc_corner;

void main() {
  vc_inst = u_first_instance + uint(gl_VertexID) / u_corners;
  vc_corner = uint(gl_VertexID) % u_corners;
}
