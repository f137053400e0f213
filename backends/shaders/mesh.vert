// CPU-mesh mode (tlod_gpu_eval OFF): the draw list evaluated on the CPU
// (tlod_cpu_tessellate_into: the patterns, geomorphs and strips of the
// draw list, welded), drawn as one indexed mesh; this stage only places
// it. Levels and strips are not carried per vertex: the levels and strips
// debug views show level 0 and no strip.
layout(location = TLOD_ATTRIB_MESH_POSITION) in vec3 a_position;
layout(location = TLOD_ATTRIB_MESH_NORMAL) in vec3 a_normal;

layout(location = TLOD_LOCATION_NORMAL) out vec3 v_normal;
layout(location = TLOD_LOCATION_WORLD) out vec3 v_world;
layout(location = TLOD_LOCATION_LEVEL) flat out uint v_level;
layout(location = TLOD_LOCATION_STRIP) flat out uint v_strip;

void main() {
  v_normal = world_normal(a_normal);
  v_world = world_position(a_position);
  v_level = 0u;
  v_strip = 0u;
  gl_Position = u_view_proj * vec4(a_position, 1.0);
}
