/*
 * vk_engine_test.c -- engine mode of the "vulkan" device (owned by the
 * Vulkan tests): the test is the engine. It makes its OWN VkInstance (with
 * the Khronos validation layer, synchronization validation on, and a
 * messenger counting errors and warnings), VkDevice (every feature the
 * physical device has), command pool and buffer, colour (R8G8B8A8_UNORM) and
 * depth (D32_SFLOAT) images, a classic VkRenderPass + VkFramebuffer and a
 * trivial pipeline of its own (engine.vert / engine.frag, compiled to
 * SPIR-V by glslangValidator at build time). No platform helper.
 *
 * One frame, in one command buffer inside one render pass instance:
 *   1. the engine draws a red triangle in the top-left corner;
 *   2. tesslod records an icosphere (PN) in the middle (device created with
 *      .vk.render_pass = the engine's, subpass 0);
 *   3. the engine rebinds its pipeline, viewport, scissor and push constants
 *      (tesslod/vulkan.h: left as tesslod set them) and draws a green
 *      triangle in the bottom-right corner;
 * then the colour image is copied to a host buffer, submitted, waited on.
 * The frame is recorded twice (the command buffer reset and reused).
 *
 * Checked, per pixel: the triangles' interiors are exactly red / green;
 * inside 0.9 x the sphere's projected silhouette radius (closed form:
 * tan(asin(r / d)) / tan(fovy / 2) in NDC for a unit sphere at distance d on
 * the axis) every pixel is tesslod's grey shading (r == g == b, not the
 * background); outside 1.1 x that radius and outside the triangles every
 * pixel is the clear colour; zero validation messages, counted after the
 * VkDevice is destroyed (leaks reported there).
 */
#define _POSIX_C_SOURCE 200809L /* dlopen */
#include <dlfcn.h>
#include <vulkan/vulkan.h>

#include "engine_frag_spv.h"
#include "engine_vert_spv.h"
#include "vk_test.h"

#define W 192
#define H 160
#define CAM_DIST 4.0
#define FOVY_DEG 45.0

static uint32_t s_messages;

static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                 VkDebugUtilsMessageTypeFlagsEXT type,
                                                 const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  (void)type, (void)user;
  if (severity & (VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT)) {
    s_messages++;
    fprintf(stderr, "validation: %s\n", data->pMessage);
  }
  return VK_FALSE;
}

/* ---- the engine ----------------------------------------------------------- */

typedef struct engine {
  VkInstance instance;
  VkDebugUtilsMessengerEXT messenger;
  VkPhysicalDevice gpu;
  VkDevice device;
  VkQueue queue;
  uint32_t family;
  bool host_query_reset;
  VkImage color, depth;
  VkDeviceMemory color_mem, depth_mem, readback_mem;
  VkImageView color_view, depth_view;
  VkBuffer readback;
  VkRenderPass pass;
  VkFramebuffer framebuffer;
  VkCommandPool pool;
  VkCommandBuffer cmd;
  VkFence fence;
  VkShaderModule vs, fs;
  VkPipelineLayout layout;
  VkPipeline pipeline;
} engine;

#define VK_OK(call, what)                                                                                              \
  do {                                                                                                                 \
    VkResult _r = (call);                                                                                              \
    CHECK_MSG(_r == VK_SUCCESS, "%s: VkResult %d", what, (int)_r);                                                     \
  } while (0)

/* The loader dlclose()s the driver and the layers in vkDestroyInstance;
 * what they keep in globals is then reported by LeakSanitizer from an
 * "<unknown module>" (docs/platform.md). An engine under ASan keeps them
 * mapped, as the platform does for its own instances. */
static void keep_drivers_loaded(void) {
  static const char* const libs[] = {"libvulkan_lvp.so", "libVkLayer_MESA_device_select.so",
                                     "libVkLayer_khronos_validation.so"};
  for (size_t i = 0; i < sizeof libs / sizeof libs[0]; ++i)
    (void)dlopen(libs[i], RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
}

/* VK_LAYER_KHRONOS_validation 1.3.239 itself leaks a few blocks per
 * instance (docs/platform.md); the platform names that module to
 * LeakSanitizer, and so does this engine, which does not link the
 * platform's Vulkan code. Nothing else is suppressed: a Vulkan object we
 * forget is the object tracker's error, counted. */
__attribute__((visibility("default"))) const char* __lsan_default_suppressions(void);
__attribute__((visibility("default"))) const char* __lsan_default_suppressions(void) {
  return "leak:libVkLayer_khronos_validation.so\n";
}

static void make_instance(engine* e) {
  keep_drivers_loaded();
  const char* layer = "VK_LAYER_KHRONOS_validation";
  const char* ext = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  VkValidationFeatureEnableEXT sync = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT features = {.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
                                      .enabledValidationFeatureCount = 1,
                                      .pEnabledValidationFeatures = &sync};
  VkDebugUtilsMessengerCreateInfoEXT mi = {.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
                                           .pNext = &features,
                                           .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                                              VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
                                           .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                                          VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                                          VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
                                           .pfnUserCallback = on_message};
  VkApplicationInfo app = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
                           .pApplicationName = "vk_engine_test",
                           .apiVersion = VK_API_VERSION_1_3};
  VkInstanceCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
                             .pNext = &mi,
                             .pApplicationInfo = &app,
                             .enabledLayerCount = 1,
                             .ppEnabledLayerNames = &layer,
                             .enabledExtensionCount = 1,
                             .ppEnabledExtensionNames = &ext};
  VK_OK(vkCreateInstance(&ci, NULL, &e->instance), "vkCreateInstance (validation layer + VK_EXT_debug_utils)");
  PFN_vkCreateDebugUtilsMessengerEXT create =
      (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(e->instance, "vkCreateDebugUtilsMessengerEXT");
  CHECK_MSG(create, "no vkCreateDebugUtilsMessengerEXT");
  mi.pNext = NULL;
  VK_OK(create(e->instance, &mi, NULL, &e->messenger), "vkCreateDebugUtilsMessengerEXT");
}

/* The first physical device with a graphics queue family. */
static void pick_gpu(engine* e) {
  VkPhysicalDevice gpus[8];
  uint32_t n = 8;
  VkResult r = vkEnumeratePhysicalDevices(e->instance, &n, gpus);
  CHECK_MSG((r == VK_SUCCESS || r == VK_INCOMPLETE) && n > 0, "no Vulkan physical device (VkResult %d)", (int)r);
  for (uint32_t g = 0; g < n; ++g) {
    VkQueueFamilyProperties fam[16];
    uint32_t nf = 16;
    vkGetPhysicalDeviceQueueFamilyProperties(gpus[g], &nf, fam);
    for (uint32_t f = 0; f < nf; ++f)
      if (fam[f].queueFlags & VK_QUEUE_GRAPHICS_BIT) {
        e->gpu = gpus[g], e->family = f;
        return;
      }
  }
  CHECK_MSG(false, "no physical device with a graphics queue");
}

/* A device with every feature the GPU has (an engine's usual choice). */
static void make_device(engine* e) {
  VkPhysicalDeviceVulkan13Features f13 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features f12 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
                                          .pNext = &f13};
  VkPhysicalDeviceVulkan11Features f11 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES,
                                          .pNext = &f12};
  VkPhysicalDeviceFeatures2 f = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &f11};
  vkGetPhysicalDeviceFeatures2(e->gpu, &f);
  e->host_query_reset = f12.hostQueryReset;
  float priority = 1.0f;
  VkDeviceQueueCreateInfo qi = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                .queueFamilyIndex = e->family,
                                .queueCount = 1,
                                .pQueuePriorities = &priority};
  VkDeviceCreateInfo ci = {
      .sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, .pNext = &f, .queueCreateInfoCount = 1, .pQueueCreateInfos = &qi};
  VK_OK(vkCreateDevice(e->gpu, &ci, NULL, &e->device), "vkCreateDevice");
  vkGetDeviceQueue(e->device, e->family, 0, &e->queue);
}

static uint32_t memory_type(const engine* e, uint32_t bits, VkMemoryPropertyFlags want) {
  VkPhysicalDeviceMemoryProperties mp;
  vkGetPhysicalDeviceMemoryProperties(e->gpu, &mp);
  for (uint32_t i = 0; i < mp.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & want) == want) return i;
  return UINT32_MAX;
}

static bool bind_memory(engine* e, VkMemoryRequirements req, VkMemoryPropertyFlags want, VkDeviceMemory* mem) {
  VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                             .allocationSize = req.size,
                             .memoryTypeIndex = memory_type(e, req.memoryTypeBits, want)};
  return ai.memoryTypeIndex != UINT32_MAX && vkAllocateMemory(e->device, &ai, NULL, mem) == VK_SUCCESS;
}

static void make_image(engine* e, VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect, VkImage* img,
                       VkDeviceMemory* mem, VkImageView* view) {
  VkImageCreateInfo ii = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
                          .imageType = VK_IMAGE_TYPE_2D,
                          .format = format,
                          .extent = {W, H, 1},
                          .mipLevels = 1,
                          .arrayLayers = 1,
                          .samples = VK_SAMPLE_COUNT_1_BIT,
                          .tiling = VK_IMAGE_TILING_OPTIMAL,
                          .usage = usage,
                          .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED};
  VK_OK(vkCreateImage(e->device, &ii, NULL, img), "vkCreateImage");
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(e->device, *img, &req);
  CHECK_MSG(bind_memory(e, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, mem), "image memory");
  VK_OK(vkBindImageMemory(e->device, *img, *mem, 0), "vkBindImageMemory");
  VkImageViewCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
                              .image = *img,
                              .viewType = VK_IMAGE_VIEW_TYPE_2D,
                              .format = format,
                              .subresourceRange = {aspect, 0, 1, 0, 1}};
  VK_OK(vkCreateImageView(e->device, &vi, NULL, view), "vkCreateImageView");
}

static void make_readback(engine* e) {
  VkBufferCreateInfo bi = {
      .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = 4 * W * H, .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT};
  VK_OK(vkCreateBuffer(e->device, &bi, NULL, &e->readback), "vkCreateBuffer (readback)");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(e->device, e->readback, &req);
  CHECK_MSG(
      bind_memory(e, req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, &e->readback_mem),
      "readback memory");
  VK_OK(vkBindBufferMemory(e->device, e->readback, e->readback_mem, 0), "vkBindBufferMemory");
}

/* Colour cleared and left TRANSFER_SRC for the copy; depth cleared. */
static void make_render_pass(engine* e) {
  VkAttachmentDescription att[2] = {{.format = VK_FORMAT_R8G8B8A8_UNORM,
                                     .samples = VK_SAMPLE_COUNT_1_BIT,
                                     .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR,
                                     .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
                                     .stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
                                     .stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
                                     .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
                                     .finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL},
                                    {.format = VK_FORMAT_D32_SFLOAT,
                                     .samples = VK_SAMPLE_COUNT_1_BIT,
                                     .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR,
                                     .storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
                                     .stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
                                     .stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
                                     .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
                                     .finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL}};
  VkAttachmentReference cref = {0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkAttachmentReference dref = {1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription sub = {.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS,
                              .colorAttachmentCount = 1,
                              .pColorAttachments = &cref,
                              .pDepthStencilAttachment = &dref};
  VkPipelineStageFlags att_stages = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                    VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                    VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  VkAccessFlags att_access = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                             VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_READ_BIT;
  VkSubpassDependency deps[2] = {{VK_SUBPASS_EXTERNAL, 0, att_stages | VK_PIPELINE_STAGE_TRANSFER_BIT, att_stages,
                                  VK_ACCESS_TRANSFER_READ_BIT | att_access, att_access, 0},
                                 {0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                                  VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                                  VK_ACCESS_TRANSFER_READ_BIT, 0}};
  VkRenderPassCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO,
                               .attachmentCount = 2,
                               .pAttachments = att,
                               .subpassCount = 1,
                               .pSubpasses = &sub,
                               .dependencyCount = 2,
                               .pDependencies = deps};
  VK_OK(vkCreateRenderPass(e->device, &ci, NULL, &e->pass), "vkCreateRenderPass");
  VkImageView views[2] = {e->color_view, e->depth_view};
  VkFramebufferCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO,
                                .renderPass = e->pass,
                                .attachmentCount = 2,
                                .pAttachments = views,
                                .width = W,
                                .height = H,
                                .layers = 1};
  VK_OK(vkCreateFramebuffer(e->device, &fi, NULL, &e->framebuffer), "vkCreateFramebuffer");
}

static VkShaderModule make_module(engine* e, const uint32_t* words, size_t bytes) {
  VkShaderModuleCreateInfo ci = {
      .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, .codeSize = bytes, .pCode = words};
  VkShaderModule m = VK_NULL_HANDLE;
  return vkCreateShaderModule(e->device, &ci, NULL, &m) == VK_SUCCESS ? m : VK_NULL_HANDLE;
}

typedef struct engine_push {
  float color[4], offset[2], scale[2];
} engine_push;

/* The engine's pipeline: no vertex input, no depth, no culling; viewport
 * and scissor dynamic. */
static void make_pipeline(engine* e) {
  e->vs = make_module(e, engine_vert_spv, sizeof engine_vert_spv);
  e->fs = make_module(e, engine_frag_spv, sizeof engine_frag_spv);
  CHECK_MSG(e->vs && e->fs, "engine shader modules");
  VkPushConstantRange range = {VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(engine_push)};
  VkPipelineLayoutCreateInfo li = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                   .pushConstantRangeCount = 1,
                                   .pPushConstantRanges = &range};
  VK_OK(vkCreatePipelineLayout(e->device, &li, NULL, &e->layout), "vkCreatePipelineLayout");
  VkPipelineShaderStageCreateInfo stages[2] = {{.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                                                .stage = VK_SHADER_STAGE_VERTEX_BIT,
                                                .module = e->vs,
                                                .pName = "main"},
                                               {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                                                .stage = VK_SHADER_STAGE_FRAGMENT_BIT,
                                                .module = e->fs,
                                                .pName = "main"}};
  VkPipelineVertexInputStateCreateInfo vin = {.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  VkPipelineInputAssemblyStateCreateInfo ia = {.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO,
                                               .topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST};
  VkPipelineViewportStateCreateInfo vp = {
      .sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO, .viewportCount = 1, .scissorCount = 1};
  VkPipelineRasterizationStateCreateInfo rs = {.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO,
                                               .polygonMode = VK_POLYGON_MODE_FILL,
                                               .cullMode = VK_CULL_MODE_NONE,
                                               .lineWidth = 1.0f};
  VkPipelineMultisampleStateCreateInfo ms = {.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO,
                                             .rasterizationSamples = VK_SAMPLE_COUNT_1_BIT};
  VkPipelineDepthStencilStateCreateInfo ds = {.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  VkPipelineColorBlendAttachmentState cb = {.colorWriteMask = 0xF};
  VkPipelineColorBlendStateCreateInfo blend = {
      .sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO, .attachmentCount = 1, .pAttachments = &cb};
  VkDynamicState dyn[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dy = {
      .sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO, .dynamicStateCount = 2, .pDynamicStates = dyn};
  VkGraphicsPipelineCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO,
                                     .stageCount = 2,
                                     .pStages = stages,
                                     .pVertexInputState = &vin,
                                     .pInputAssemblyState = &ia,
                                     .pViewportState = &vp,
                                     .pRasterizationState = &rs,
                                     .pMultisampleState = &ms,
                                     .pDepthStencilState = &ds,
                                     .pColorBlendState = &blend,
                                     .pDynamicState = &dy,
                                     .layout = e->layout,
                                     .renderPass = e->pass,
                                     .subpass = 0};
  VK_OK(vkCreateGraphicsPipelines(e->device, VK_NULL_HANDLE, 1, &pi, NULL, &e->pipeline), "engine pipeline");
}

static void make_commands(engine* e) {
  VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                .queueFamilyIndex = e->family};
  VK_OK(vkCreateCommandPool(e->device, &pi, NULL, &e->pool), "vkCreateCommandPool");
  VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                    .commandPool = e->pool,
                                    .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                    .commandBufferCount = 1};
  VK_OK(vkAllocateCommandBuffers(e->device, &ai, &e->cmd), "vkAllocateCommandBuffers");
  VkFenceCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VK_OK(vkCreateFence(e->device, &fi, NULL, &e->fence), "vkCreateFence");
}

static void engine_open(engine* e) {
  memset(e, 0, sizeof *e);
  CALL(make_instance(e));
  CALL(pick_gpu(e));
  CALL(make_device(e));
  CALL(make_image(e, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                  VK_IMAGE_ASPECT_COLOR_BIT, &e->color, &e->color_mem, &e->color_view));
  CALL(make_image(e, VK_FORMAT_D32_SFLOAT, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT,
                  &e->depth, &e->depth_mem, &e->depth_view));
  CALL(make_readback(e));
  CALL(make_render_pass(e));
  CALL(make_pipeline(e));
  CALL(make_commands(e));
}

static void engine_close(engine* e) {
  if (e->device) {
    vkDeviceWaitIdle(e->device);
    vkDestroyFence(e->device, e->fence, NULL);
    vkDestroyCommandPool(e->device, e->pool, NULL);
    vkDestroyPipeline(e->device, e->pipeline, NULL);
    vkDestroyPipelineLayout(e->device, e->layout, NULL);
    vkDestroyShaderModule(e->device, e->vs, NULL);
    vkDestroyShaderModule(e->device, e->fs, NULL);
    vkDestroyFramebuffer(e->device, e->framebuffer, NULL);
    vkDestroyRenderPass(e->device, e->pass, NULL);
    vkDestroyBuffer(e->device, e->readback, NULL);
    vkDestroyImageView(e->device, e->color_view, NULL);
    vkDestroyImageView(e->device, e->depth_view, NULL);
    vkDestroyImage(e->device, e->color, NULL);
    vkDestroyImage(e->device, e->depth, NULL);
    vkFreeMemory(e->device, e->color_mem, NULL);
    vkFreeMemory(e->device, e->depth_mem, NULL);
    vkFreeMemory(e->device, e->readback_mem, NULL);
    vkDestroyDevice(e->device, NULL);
  }
  PFN_vkDestroyDebugUtilsMessengerEXT destroy =
      e->instance
          ? (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(e->instance, "vkDestroyDebugUtilsMessengerEXT")
          : NULL;
  if (destroy && e->messenger) destroy(e->instance, e->messenger, NULL);
  if (e->instance) vkDestroyInstance(e->instance, NULL);
  memset(e, 0, sizeof *e);
}

/* ---- one frame --------------------------------------------------------------- */

/* The engine's own triangle: binds everything it needs (after tesslod too). */
static void engine_triangle(const engine* e, const float rgba[4], float ox, float oy, float sx, float sy) {
  vkCmdBindPipeline(e->cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, e->pipeline);
  VkViewport vp = {0, 0, W, H, 0, 1};
  VkRect2D sc = {{0, 0}, {W, H}};
  vkCmdSetViewport(e->cmd, 0, 1, &vp);
  vkCmdSetScissor(e->cmd, 0, 1, &sc);
  engine_push p = {{rgba[0], rgba[1], rgba[2], rgba[3]}, {ox, oy}, {sx, sy}};
  vkCmdPushConstants(e->cmd, e->layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof p, &p);
  vkCmdDraw(e->cmd, 3, 1, 0, 0);
}

static const float k_red[4] = {1, 0, 0, 1}, k_green[4] = {0, 1, 0, 1};

/* Records red triangle, tesslod's draw, green triangle, the copy. */
static void record_frame(engine* e, tlod_device* dev, tlod_context* ctx, tlod_draw_desc* desc) {
  VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                 .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
  VK_OK(vkResetCommandBuffer(e->cmd, 0), "vkResetCommandBuffer");
  VK_OK(vkBeginCommandBuffer(e->cmd, &bi), "vkBeginCommandBuffer");
  VkClearValue clear[2] = {{.color = {{vk_test_clear[0], vk_test_clear[1], vk_test_clear[2], 1}}},
                           {.depthStencil = {1.0f, 0}}};
  VkRenderPassBeginInfo rp = {.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO,
                              .renderPass = e->pass,
                              .framebuffer = e->framebuffer,
                              .renderArea = {{0, 0}, {W, H}},
                              .clearValueCount = 2,
                              .pClearValues = clear};
  vkCmdBeginRenderPass(e->cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
  engine_triangle(e, k_red, -1, -1, 0.5f, 0.5f); /* top-left corner (Vulkan NDC y = -1 at the top) */
  desc->vk.command_buffer = e->cmd;
  desc->vk.frame_index = 0;
  tlod_result r = tlod_device_draw(dev, desc);
  engine_triangle(e, k_green, 1, 1, -0.5f, -0.5f); /* bottom-right corner, after tesslod */
  vkCmdEndRenderPass(e->cmd);
  VkBufferImageCopy copy = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, .imageExtent = {W, H, 1}};
  vkCmdCopyImageToBuffer(e->cmd, e->color, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, e->readback, 1, &copy);
  VkBufferMemoryBarrier host = {.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER,
                                .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
                                .dstAccessMask = VK_ACCESS_HOST_READ_BIT,
                                .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                .buffer = e->readback,
                                .size = VK_WHOLE_SIZE};
  vkCmdPipelineBarrier(e->cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, NULL, 1, &host, 0,
                       NULL);
  VK_OK(vkEndCommandBuffer(e->cmd), "vkEndCommandBuffer");
  CHECK_MSG(r == TLOD_SUCCESS, "tlod_device_draw in the engine's render pass: %s: %s", tlod_result_string(r),
            tlod_context_last_error(ctx));
}

static void submit_and_read(engine* e, uint8_t* rgba) {
  VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &e->cmd};
  VK_OK(vkQueueSubmit(e->queue, 1, &si, e->fence), "vkQueueSubmit");
  VK_OK(vkWaitForFences(e->device, 1, &e->fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  VK_OK(vkResetFences(e->device, 1, &e->fence), "vkResetFences");
  void* mapped = NULL;
  VK_OK(vkMapMemory(e->device, e->readback_mem, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
  memcpy(rgba, mapped, 4 * W * H);
  vkUnmapMemory(e->device, e->readback_mem);
}

/* ---- checks ---------------------------------------------------------------- */

typedef struct pixel_counts {
  uint32_t red, green, object, background; /* pixels checked in each region */
  uint32_t wrong;                          /* of them, not what the region must show */
  int x, y;                                /* first wrong pixel */
  uint8_t got[4];
} pixel_counts;

/* Which region pixel (x, y) (row 0 = top) is safely inside: 'r', 'g',
 * 'o' (object), 'b' (background) or 0 (an edge band: not checked). */
static char region(uint32_t x, uint32_t y, double silhouette) {
  double nx = (x + 0.5) / W * 2.0 - 1.0, ny = (y + 0.5) / H * 2.0 - 1.0, margin = 0.05;
  /* red: (-1,-1) + s * (u, v), u, v >= 0, u + v <= 1, s = 0.5 */
  double ru = (nx + 1.0) / 0.5, rv = (ny + 1.0) / 0.5, gu = (1.0 - nx) / 0.5, gv = (1.0 - ny) / 0.5;
  if (ru > margin && rv > margin && ru + rv < 1.0 - 2 * margin) return 'r';
  if (gu > margin && gv > margin && gu + gv < 1.0 - 2 * margin) return 'g';
  if (ru + rv < 1.0 + 2 * margin || gu + gv < 1.0 + 2 * margin) return 0;
  double ax = nx * (double)W / H; /* aspect: x in units of the vertical NDC */
  double rr = sqrt(ax * ax + ny * ny);
  if (rr < 0.9 * silhouette) return 'o';
  if (rr > 1.1 * silhouette) return 'b';
  return 0;
}

static bool pixel_ok(char reg, const uint8_t* p) {
  switch (reg) {
  case 'r':
    return p[0] == 255 && p[1] == 0 && p[2] == 0;
  case 'g':
    return p[0] == 0 && p[1] == 255 && p[2] == 0;
  case 'o':
    return !is_background(p) && p[0] == p[1] && p[1] == p[2] && p[0] > 0;
  default:
    return is_background(p);
  }
}

static pixel_counts check_pixels(const uint8_t* rgba) {
  pixel_counts c;
  memset(&c, 0, sizeof c);
  c.x = c.y = -1;
  double silhouette = tan(asin(1.0 / CAM_DIST)) / tan(FOVY_DEG * SHAPES_PI / 360.0);
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      char reg = region(x, y, silhouette);
      if (!reg) continue;
      const uint8_t* p = rgba + 4 * ((size_t)y * W + x);
      c.red += reg == 'r', c.green += reg == 'g', c.object += reg == 'o', c.background += reg == 'b';
      if (pixel_ok(reg, p)) continue;
      if (c.wrong++ == 0) c.x = (int)x, c.y = (int)y, memcpy(c.got, p, 4);
    }
  return c;
}

/* ---- the test ------------------------------------------------------------------ */

typedef struct tlod_side {
  tlod_context* ctx;
  tlod_patterns* pat;
  tlod_device* dev;
  shape sph;
  fixture fx;
  tlod_scheduler* sch;
} tlod_side;

static void tlod_side_open(tlod_side* t, const engine* e) {
  memset(t, 0, sizeof *t);
  CHECK(tlod_context_create(&(tlod_context_desc){.thread_count = 2}, &t->ctx) == TLOD_SUCCESS);
  CHECK(t->pat = new_patterns(t->ctx, 4));
  tlod_device_vk_desc vk = {.instance = e->instance,
                            .physical_device = e->gpu,
                            .device = e->device,
                            .queue = e->queue,
                            .queue_family = e->family,
                            .frames_in_flight = 1,
                            .render_pass = (uint64_t)(uintptr_t)e->pass,
                            .subpass = 0,
                            .color_format = VK_FORMAT_R8G8B8A8_UNORM,
                            .depth_format = VK_FORMAT_D32_SFLOAT,
                            .host_query_reset = e->host_query_reset};
  CHECK_MSG(t->dev = new_vk_device(t->ctx, t->pat, "engine mode", vk), "tesslod device on the engine's VkDevice");
  t->sph = shape_icosphere(2);
  CHECK(fixture_make(&t->fx, t->ctx, &t->sph, TLOD_SURFACE_PN, t->pat, t->dev));
  CHECK(t->sch = new_scheduler(&t->fx, (tlod_scheduler_desc){.max_level = 4}));
}

static void tlod_side_close(tlod_side* t) {
  tlod_scheduler_destroy(t->sch);
  if (t->fx.mesh) fixture_free(&t->fx);
  shape_free(&t->sph);
  tlod_device_destroy(t->dev);
  tlod_patterns_destroy(t->pat);
  tlod_context_destroy(t->ctx);
  memset(t, 0, sizeof *t);
}

static void engine_frame(engine* e, tlod_side* t, uint8_t* rgba, int frame) {
  camera cam = camera_look(CAM_DIST * 0.6, -CAM_DIST * 0.8, 0.0, 0, 0, 0, FOVY_DEG, W, H);
  tlod_view_desc v = make_view(&cam);
  const tlod_draw_list* dl = plan(&t->fx, t->sch, &v, 16.0f);
  CHECK(dl);
  one_draw d;
  one_draw_make(&d, t->fx.ds, dl, &v);
  CALL(record_frame(e, t->dev, t->ctx, &d.desc));
  CALL(submit_and_read(e, rgba));
  pixel_counts c = check_pixels(rgba);
  printf("  frame %d: red %u, green %u, object %u, background %u pixels checked: %u wrong\n", frame, c.red, c.green,
         c.object, c.background, c.wrong);
  CHECK_MSG(c.red > 100 && c.green > 100 && c.object > 1000 && c.background > 1000, "regions too small");
  CHECK_MSG(c.wrong == 0, "frame %d: %u pixels wrong, first (%d, %d) (row 0 = top) = (%u, %u, %u, %u)", frame, c.wrong,
            c.x, c.y, c.got[0], c.got[1], c.got[2], c.got[3]);
}

TEST(test_engine_render_pass) {
  engine e;
  tlod_side t;
  memset(&t, 0, sizeof t);
  uint8_t* rgba = malloc(4 * W * H);
  int failed = _test_checks_failed;
  engine_open(&e);
  if (_test_checks_failed == failed) tlod_side_open(&t, &e);
  for (int f = 0; f < 2 && _test_checks_failed == failed && rgba; ++f)
    engine_frame(&e, &t, rgba, f);
  tlod_side_close(&t);
  engine_close(&e);
  free(rgba);
  CHECK_MSG(_test_checks_failed == failed, "see above");
  CHECK_MSG(s_messages == 0, "%u validation messages (printed above)", s_messages);
}

int main(void) {
  RUN(test_engine_render_pass);
  VK_TEST_END();
}
