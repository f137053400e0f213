#version 450
// vk_engine_test's own geometry: the push constant colour.
layout(push_constant) uniform EnginePush {
  vec4 color;
  vec2 offset;
  vec2 scale;
} pc;

layout(location = 0) out vec4 o_color;

void main() { o_color = pc.color; }
