#version 450
// engine_vulkan's own geometry: the push constant colour.
layout(push_constant) uniform EnginePush {
  vec4 color;
} pc;

layout(location = 0) out vec4 o_color;

void main() { o_color = pc.color; }
