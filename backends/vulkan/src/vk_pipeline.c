/* tesslod::vulkan -- shader modules and graphics pipelines. The GLSL is
 * backends/shaders, assembled exactly as the GL device assembles it, plus
 * TLOD_VULKAN 1 (the uniform block, push constants, gl_VertexIndex), and
 * compiled by glslang (vk_shader.c, with its SPIR-V disk cache). Modules of
 * the PLAIN variant are made at creation, FULL and MASK at the first item
 * that needs them; pipelines per (surface type, variant, kind, blend,
 * polygon mode) at their first draw, through an in-memory VkPipelineCache. */
#include <stdio.h>
#include <string.h>

#include "shader_sources.h"
#include "vk_internal.h"
#include "vk_shader.h"

static const VkDescriptorType binding_types[7] = {
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,         VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER_DYNAMIC,
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,         VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC,
    VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER};

tlod_result _tlod_vkb_pipelines_init(vk_pipelines* p) {
  VkDescriptorSetLayoutBinding b[7];
  for (uint32_t i = 0; i < 7; i++)
    b[i] = (VkDescriptorSetLayoutBinding){.binding = i,
                                          .descriptorType = binding_types[i],
                                          .descriptorCount = 1,
                                          .stageFlags = VK_SHADER_STAGE_ALL_GRAPHICS};
  VkDescriptorSetLayoutCreateInfo li = {
      .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO, .bindingCount = 7, .pBindings = b};
  VkResult r = vkCreateDescriptorSetLayout(p->device, &li, p->cb, &p->set_layout);
  VkPushConstantRange pc = {.stageFlags = VK_SHADER_STAGE_ALL_GRAPHICS, .size = sizeof(tlod_vk_push)};
  VkPipelineLayoutCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                   .setLayoutCount = 1,
                                   .pSetLayouts = &p->set_layout,
                                   .pushConstantRangeCount = 1,
                                   .pPushConstantRanges = &pc};
  if (r == VK_SUCCESS) r = vkCreatePipelineLayout(p->device, &pi, p->cb, &p->layout);
  VkPipelineCacheCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
  if (r == VK_SUCCESS) r = vkCreatePipelineCache(p->device, &ci, p->cb, &p->cache);
  if (r != VK_SUCCESS)
    return tlod_context_fail(p->ctx, TLOD_ERROR_BACKEND, "vulkan device '%s': pipeline layout: %s", p->label,
                             _tlod_vkb_result_name(r));
  return TLOD_SUCCESS;
}

static void destroy_module(vk_pipelines* p, VkShaderModule m) {
  if (m) vkDestroyShaderModule(p->device, m, p->cb);
}

static void destroy_modules(vk_pipelines* p, vk_modules* m) {
  destroy_module(p, m->pattern_vert);
  destroy_module(p, m->strip_vert);
  destroy_module(p, m->mesh_vert);
  for (int sh = 0; sh < 2; sh++) {
    destroy_module(p, m->tess_vert[sh]);
    destroy_module(p, m->tesc[sh]);
    destroy_module(p, m->tese[sh]);
  }
  memset(m, 0, sizeof(*m));
}

void _tlod_vkb_pipelines_destroy(vk_pipelines* p) {
  VkPipeline* all = &p->pipelines[0][0][0][0][0];
  for (size_t i = 0; i < sizeof(p->pipelines) / sizeof(VkPipeline); i++)
    if (all[i]) vkDestroyPipeline(p->device, all[i], p->cb);
  for (int t = 0; t < VK_TYPES; t++)
    for (int v = 0; v < VK_VARIANTS; v++)
      destroy_modules(p, &p->modules[t][v]);
  for (int v = 0; v < VK_VARIANTS; v++)
    destroy_module(p, p->frag[v]);
  if (p->cache) vkDestroyPipelineCache(p->device, p->cache, p->cb);
  if (p->layout) vkDestroyPipelineLayout(p->device, p->layout, p->cb);
  if (p->set_layout) vkDestroyDescriptorSetLayout(p->device, p->set_layout, p->cb);
}

/* ---- modules ----------------------------------------------------------------- */

/* One stage from its strings (shader_program.c's order and names). */
static tlod_result make_module(vk_pipelines* p, glslang_stage_t stage, const char* const* src, int count,
                               VkShaderModule* out) {
  const char* names[_TLOD_SHADER_STAGE_SOURCES];
  _tlod_shader_names(src, count, p->hook, names);
  uint32_t* words = NULL;
  size_t n = 0;
  tlod_result r = _tlod_vk_spirv(p->ctx, p->shader_cache, stage, src, names, count, &words, &n);
  if (r != TLOD_SUCCESS) return r;
  VkShaderModuleCreateInfo mi = {
      .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, .codeSize = n * sizeof(uint32_t), .pCode = words};
  VkResult vr = vkCreateShaderModule(p->device, &mi, p->cb, out);
  tlod_context_free(p->ctx, words);
  if (vr != VK_SUCCESS)
    return tlod_context_fail(p->ctx, TLOD_ERROR_BACKEND, "vulkan device '%s': %s: vkCreateShaderModule: %s", p->label,
                             names[count - 1], _tlod_vkb_result_name(vr));
  return TLOD_SUCCESS;
}

static tlod_result vertex_module(vk_pipelines* p, glslang_stage_t stage, const char* defines, int corners,
                                 tlod_surface_type type, bool last, const char* main_src, VkShaderModule* out) {
  const char* src[_TLOD_SHADER_STAGE_SOURCES];
  int n = _tlod_shader_vertex_side(src, defines, corners ? _tlod_shader_corners(corners) : NULL,
                                   _tlod_shader_surface(type), last, main_src);
  return make_module(p, stage, src, n, out);
}

static tlod_result build_tess(vk_pipelines* p, vk_modules* m, const char* defines, tlod_surface_type type) {
  tlod_result r = TLOD_SUCCESS;
  for (int sh = 0; sh < 2 && r == TLOD_SUCCESS; sh++) {
    int corners = sh ? 4 : 3;
    r = vertex_module(p, GLSLANG_STAGE_VERTEX, defines, corners, type, false, _tlod_shader_tess_vert,
                      &m->tess_vert[sh]);
    if (r == TLOD_SUCCESS)
      r = vertex_module(p, GLSLANG_STAGE_TESSCONTROL, defines, corners, type, false, _tlod_shader_tess_tesc,
                        &m->tesc[sh]);
    if (r == TLOD_SUCCESS)
      r = vertex_module(p, GLSLANG_STAGE_TESSEVALUATION, defines, corners, type, true, _tlod_shader_tess_tese,
                        &m->tese[sh]);
  }
  return r;
}

tlod_result _tlod_vkb_modules(vk_pipelines* p, tlod_surface_type type, int variant) {
  vk_modules* m = &p->modules[type][variant];
  if (m->built) return TLOD_SUCCESS;
  bool full = variant != VK_VARIANT_PLAIN;
  _tlod_shader_variant sv = {.vulkan = true,
                             .attribute_varyings = full && p->hook ? TLOD_SHADER_MAX_ATTRIBUTES : 0,
                             .texcoord = full,
                             .mask = variant == VK_VARIANT_MASK};
  char defines[_TLOD_SHADER_DEFINES_BYTES];
  _tlod_shader_defines(&sv, defines);
  tlod_result r =
      vertex_module(p, GLSLANG_STAGE_VERTEX, defines, 0, type, true, _tlod_shader_pattern_vert, &m->pattern_vert);
  if (r == TLOD_SUCCESS)
    r = vertex_module(p, GLSLANG_STAGE_VERTEX, defines, 0, type, true, _tlod_shader_strip_vert, &m->strip_vert);
  if (r == TLOD_SUCCESS && p->cpu_mesh && variant == VK_VARIANT_PLAIN)
    r = vertex_module(p, GLSLANG_STAGE_VERTEX, defines, 0, type, true, _tlod_shader_mesh_vert, &m->mesh_vert);
  const char* frag[_TLOD_SHADER_FRAGMENT_SOURCES];
  int nf = _tlod_shader_fragment(frag, defines, NULL, p->hook);
  if (r == TLOD_SUCCESS && !p->frag[variant]) r = make_module(p, GLSLANG_STAGE_FRAGMENT, frag, nf, &p->frag[variant]);
  if (r == TLOD_SUCCESS && p->hardware) r = build_tess(p, m, defines, type);
  if (r != TLOD_SUCCESS) {
    destroy_modules(p, m);
    return r;
  }
  m->built = true;
  return TLOD_SUCCESS;
}

/* ---- pipelines --------------------------------------------------------------- */

/* The fixed-function state every pipeline shares; what changes per item
 * (cull mode, depth writes, depth bias) is dynamic. */
typedef struct fixed_state {
  VkPipelineVertexInputStateCreateInfo vertex;
  VkVertexInputBindingDescription vb[2];
  VkVertexInputAttributeDescription va[2];
  VkPipelineInputAssemblyStateCreateInfo assembly;
  VkPipelineTessellationDomainOriginStateCreateInfo origin;
  VkPipelineTessellationStateCreateInfo tess;
  VkPipelineViewportStateCreateInfo viewport;
  VkPipelineRasterizationStateCreateInfo raster;
  VkPipelineMultisampleStateCreateInfo multisample;
  VkPipelineDepthStencilStateCreateInfo depth;
  VkPipelineColorBlendAttachmentState attachment;
  VkPipelineColorBlendStateCreateInfo blend;
  VkDynamicState dynamic_states[6];
  VkPipelineDynamicStateCreateInfo dynamic;
  VkPipelineRenderingCreateInfo rendering;
} fixed_state;

static bool has_stencil(VkFormat f) {
  return f == VK_FORMAT_D16_UNORM_S8_UINT || f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_D32_SFLOAT_S8_UINT;
}

static void vertex_input(fixed_state* f, int kind) {
  uint32_t inputs = kind == VK_KIND_STRIP ? 1u : kind == VK_KIND_MESH ? 2u : 0u;
  bool tess = kind == VK_KIND_TESS3 || kind == VK_KIND_TESS4;
  if (kind == VK_KIND_MESH) {
    /* positions at binding 0, normals at binding 1 (vk_draw.c binds both in the ring) */
    for (uint32_t b = 0; b < 2; b++) {
      f->vb[b] = (VkVertexInputBindingDescription){b, sizeof(float[3]), VK_VERTEX_INPUT_RATE_VERTEX};
      f->va[b] = (VkVertexInputAttributeDescription){b ? TLOD_ATTRIB_MESH_NORMAL : TLOD_ATTRIB_MESH_POSITION, b,
                                                     VK_FORMAT_R32G32B32_SFLOAT, 0};
    }
  } else {
    f->vb[0] = (VkVertexInputBindingDescription){0, sizeof(uint32_t[2]), VK_VERTEX_INPUT_RATE_VERTEX};
    f->va[0] = (VkVertexInputAttributeDescription){TLOD_ATTRIB_STRIP_REF, 0, VK_FORMAT_R32G32_UINT, 0};
  }
  f->vertex = (VkPipelineVertexInputStateCreateInfo){.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO,
                                                     .vertexBindingDescriptionCount = inputs,
                                                     .pVertexBindingDescriptions = f->vb,
                                                     .vertexAttributeDescriptionCount = inputs,
                                                     .pVertexAttributeDescriptions = f->va};
  f->assembly = (VkPipelineInputAssemblyStateCreateInfo){
      .sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO,
      .topology = tess ? VK_PRIMITIVE_TOPOLOGY_PATCH_LIST : VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST};
  /* GL's tessellation domain origin (Vulkan's default is the upper left):
   * the same (u, v) per tessellated point, so tess.tesc's outer levels and
   * tess.tese's ccw winding mean what they mean in GL. */
  f->origin = (VkPipelineTessellationDomainOriginStateCreateInfo){
      .sType = VK_STRUCTURE_TYPE_PIPELINE_TESSELLATION_DOMAIN_ORIGIN_STATE_CREATE_INFO,
      .domainOrigin = VK_TESSELLATION_DOMAIN_ORIGIN_LOWER_LEFT};
  f->tess = (VkPipelineTessellationStateCreateInfo){.sType = VK_STRUCTURE_TYPE_PIPELINE_TESSELLATION_STATE_CREATE_INFO,
                                                    .pNext = &f->origin,
                                                    .patchControlPoints = kind == VK_KIND_TESS4 ? 4u : 3u};
}

/* GL's state (gl_device.c): depth LESS, front face CCW (the negative-height
 * viewport keeps GL's winding), straight alpha (SRC_ALPHA, ONE_MINUS_SRC_ALPHA;
 * ONE, ONE_MINUS_SRC_ALPHA) with ADD. */
static void fixed(const vk_pipelines* p, fixed_state* f, int kind, bool blend, bool line) {
  memset(f, 0, sizeof(*f));
  vertex_input(f, kind);
  f->viewport = (VkPipelineViewportStateCreateInfo){
      .sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO, .viewportCount = 1, .scissorCount = 1};
  f->raster =
      (VkPipelineRasterizationStateCreateInfo){.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO,
                                               .polygonMode = line ? VK_POLYGON_MODE_LINE : VK_POLYGON_MODE_FILL,
                                               .frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE,
                                               .lineWidth = 1.0f};
  f->multisample = (VkPipelineMultisampleStateCreateInfo){
      .sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO, .rasterizationSamples = p->samples};
  f->depth =
      (VkPipelineDepthStencilStateCreateInfo){.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO,
                                              .depthTestEnable = VK_TRUE,
                                              .depthWriteEnable = VK_TRUE,
                                              .depthCompareOp = VK_COMPARE_OP_LESS};
  f->attachment =
      (VkPipelineColorBlendAttachmentState){.blendEnable = blend,
                                            .srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA,
                                            .dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA,
                                            .colorBlendOp = VK_BLEND_OP_ADD,
                                            .srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE,
                                            .dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA,
                                            .alphaBlendOp = VK_BLEND_OP_ADD,
                                            .colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                                              VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT};
  f->blend = (VkPipelineColorBlendStateCreateInfo){.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO,
                                                   .attachmentCount = 1,
                                                   .pAttachments = &f->attachment};
  const VkDynamicState ds[6] = {VK_DYNAMIC_STATE_VIEWPORT,          VK_DYNAMIC_STATE_SCISSOR,
                                VK_DYNAMIC_STATE_CULL_MODE,         VK_DYNAMIC_STATE_DEPTH_WRITE_ENABLE,
                                VK_DYNAMIC_STATE_DEPTH_BIAS_ENABLE, VK_DYNAMIC_STATE_DEPTH_BIAS};
  memcpy(f->dynamic_states, ds, sizeof(ds));
  f->dynamic = (VkPipelineDynamicStateCreateInfo){.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO,
                                                  .dynamicStateCount = 6,
                                                  .pDynamicStates = f->dynamic_states};
  f->rendering = (VkPipelineRenderingCreateInfo){
      .sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO,
      .colorAttachmentCount = 1,
      .pColorAttachmentFormats = &p->color_format,
      .depthAttachmentFormat = p->depth_format,
      .stencilAttachmentFormat = has_stencil(p->depth_format) ? p->depth_format : VK_FORMAT_UNDEFINED};
}

static int stages_of(const vk_modules* m, VkShaderModule frag, int kind, VkPipelineShaderStageCreateInfo st[4]) {
  VkShaderModule mods[4] = {0};
  VkShaderStageFlagBits bits[4] = {VK_SHADER_STAGE_VERTEX_BIT, VK_SHADER_STAGE_FRAGMENT_BIT, 0, 0};
  int n = 2;
  if (kind == VK_KIND_PATTERN || kind == VK_KIND_STRIP || kind == VK_KIND_MESH) {
    mods[0] = kind == VK_KIND_PATTERN ? m->pattern_vert : kind == VK_KIND_STRIP ? m->strip_vert : m->mesh_vert;
    mods[1] = frag;
  } else {
    int sh = kind == VK_KIND_TESS4;
    mods[0] = m->tess_vert[sh], mods[1] = m->tesc[sh], mods[2] = m->tese[sh], mods[3] = frag;
    bits[1] = VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT, bits[2] = VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT;
    bits[3] = VK_SHADER_STAGE_FRAGMENT_BIT;
    n = 4;
  }
  for (int i = 0; i < n; i++)
    st[i] = (VkPipelineShaderStageCreateInfo){.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                                              .stage = bits[i],
                                              .module = mods[i],
                                              .pName = "main"};
  return n;
}

tlod_result _tlod_vkb_pipeline(vk_pipelines* p, tlod_surface_type type, int variant, int kind, bool blend, bool line,
                               VkPipeline* out) {
  VkPipeline* slot = &p->pipelines[type][variant][kind][blend][line];
  if (*slot) {
    *out = *slot;
    return TLOD_SUCCESS;
  }
  tlod_result r = _tlod_vkb_modules(p, type, variant);
  if (r != TLOD_SUCCESS) return r;
  fixed_state f;
  fixed(p, &f, kind, blend, line);
  VkPipelineShaderStageCreateInfo st[4];
  VkGraphicsPipelineCreateInfo gi = {
      .sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO,
      .pNext = p->render_pass ? NULL : &f.rendering,
      .stageCount = (uint32_t)stages_of(&p->modules[type][variant], p->frag[variant], kind, st),
      .pStages = st,
      .pVertexInputState = &f.vertex,
      .pInputAssemblyState = &f.assembly,
      .pTessellationState = kind == VK_KIND_TESS3 || kind == VK_KIND_TESS4 ? &f.tess : NULL,
      .pViewportState = &f.viewport,
      .pRasterizationState = &f.raster,
      .pMultisampleState = &f.multisample,
      .pDepthStencilState = &f.depth,
      .pColorBlendState = &f.blend,
      .pDynamicState = &f.dynamic,
      .layout = p->layout,
      .renderPass = p->render_pass,
      .subpass = p->subpass};
  VkResult vr = vkCreateGraphicsPipelines(p->device, p->cache, 1, &gi, p->cb, slot);
  if (vr != VK_SUCCESS) {
    *slot = VK_NULL_HANDLE;
    return tlod_context_fail(p->ctx, TLOD_ERROR_BACKEND, "vulkan device '%s': %s pipeline (kind %d): %s", p->label,
                             tlod_surface_type_name(type), kind, _tlod_vkb_result_name(vr));
  }
  p->stats->vk.pipelines++;
  *out = *slot;
  return TLOD_SUCCESS;
}
