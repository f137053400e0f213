#version 450
// vk_engine_test's own geometry: one triangle at a corner of the viewport,
// placed and coloured by push constants (the engine's draws, not tesslod's).
layout(push_constant) uniform EnginePush {
  vec4 color;
  vec2 offset;
  vec2 scale;
} pc;

const vec2 corners[3] = vec2[](vec2(0.0, 0.0), vec2(1.0, 0.0), vec2(0.0, 1.0));

void main() { gl_Position = vec4(pc.offset + pc.scale * corners[gl_VertexIndex], 0.5, 1.0); }
