#version 450
// engine_vulkan's own geometry (not tesslod's): vertices 0-5 the floor band
// along the bottom, 6-8 the overlay triangle top right, in Vulkan clip space
// (y down); the colour comes from push constants.
layout(push_constant) uniform EnginePush {
  vec4 color;
} pc;

const vec2 corners[9] = vec2[](vec2(-1.0, 1.0), vec2(1.0, 1.0), vec2(1.0, 0.6), vec2(-1.0, 1.0), vec2(1.0, 0.6),
                               vec2(-1.0, 0.6), vec2(0.6, -0.6), vec2(0.95, -0.6), vec2(0.95, -0.95));

void main() { gl_Position = vec4(corners[gl_VertexIndex], 0.5, 1.0); }
