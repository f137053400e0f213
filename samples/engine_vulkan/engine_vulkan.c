/*
 * engine_vulkan.c -- how an engine with its own Vulkan objects embeds tesslod.
 *
 *   engine_vulkan [-o out.png] [--frames N] [--size PIXELS] [--shader-cache DIR] [--validate]
 *
 * The engine owns the VkInstance, VkDevice, queue, render pass, images,
 * its pipeline and 2 frames in flight (a command buffer, a fence and a
 * read-back buffer each); no platform helper makes any of them. Per frame:
 * wait for the slot's fence (the frame two back), record into the slot's
 * command buffer: the render pass, the engine's floor, tesslod's sphere with
 * a fragment hook material (tlod_device_draw only records, with
 * .vk.frame_index = the slot: the frame-index contract of tesslod/vulkan.h),
 * the engine's overlay (it rebinds its pipeline: tesslod leaves its own
 * bound), the copy into the slot's read-back buffer; submit with the fence.
 * The camera moves every frame; the last frame is written as a PNG.
 * --validate enables VK_LAYER_KHRONOS_validation and counts its warnings and
 * errors through VK_EXT_debug_utils: any message fails the run.
 */
#define _POSIX_C_SOURCE 200809L /* dlopen */
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <vulkan/vulkan.h>

#include "engine_frag_spv.h"
#include "engine_vert_spv.h"
#include "sample_scene.h"
#include "tlod_platform.h" /* tlod_png_write only: no Vulkan help */

#define FRAMES_IN_FLIGHT 2
#define COLOR_FORMAT VK_FORMAT_R8G8B8A8_UNORM
#define DEPTH_FORMAT VK_FORMAT_D32_SFLOAT

typedef struct options {
  const char *out, *shader_cache;
  int frames;
  uint32_t size;
  bool validate;
} options;

typedef struct slot {
  VkCommandBuffer cmd;
  VkFence fence;
  VkBuffer readback;
  VkDeviceMemory readback_mem;
} slot;

typedef struct engine {
  uint32_t size;
  VkInstance instance;
  VkDebugUtilsMessengerEXT messenger;
  VkPhysicalDevice gpu;
  VkDevice device;
  VkQueue queue;
  uint32_t family;
  bool host_query_reset;
  VkImage color, depth;
  VkDeviceMemory color_mem, depth_mem;
  VkImageView color_view, depth_view;
  VkRenderPass pass;
  VkFramebuffer framebuffer;
  VkShaderModule vs, fs;
  VkPipelineLayout layout;
  VkPipeline pipeline;
  VkCommandPool pool;
  slot slots[FRAMES_IN_FLIGHT];
} engine;

#define VK_TRY(call)                                                                                                   \
  do {                                                                                                                 \
    VkResult r_ = (call);                                                                                              \
    if (r_ != VK_SUCCESS) {                                                                                            \
      fprintf(stderr, "engine_vulkan: %s failed: VkResult %d\n", #call, (int)r_);                                      \
      return false;                                                                                                    \
    }                                                                                                                  \
  } while (0)

static uint32_t s_validation_messages;

/* Counts what the validation layer finds (VALIDATION, PERFORMANCE) and any
 * error. A GENERAL warning is the loader's own notice, such as "env var
 * 'VK_INSTANCE_LAYERS' defined and adding layers": printed, not counted. */
static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                 VkDebugUtilsMessageTypeFlagsEXT type,
                                                 const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  (void)user;
  bool finding = (type & ~VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT) ||
                 (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT);
  s_validation_messages += finding;
  fprintf(stderr, "vulkan %s: %s\n", finding ? "validation" : "loader", data->pMessage);
  return VK_FALSE;
}

/* The loader unloads the driver and the layers in vkDestroyInstance, and
 * LeakSanitizer then cannot name what they kept (docs/platform.md; the
 * validation layer's own leaks are suppressed by tlod_platform, which this
 * sample links for tlod_png_write). Harmless outside sanitizer builds. */
static void keep_drivers_loaded(void) {
  static const char* const libs[] = {"libvulkan_lvp.so", "libVkLayer_MESA_device_select.so",
                                     "libVkLayer_khronos_validation.so"};
  for (size_t i = 0; i < sizeof libs / sizeof libs[0]; ++i)
    (void)dlopen(libs[i], RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
}

static bool parse_options(int argc, char** argv, options* o) {
  *o = (options){.out = "engine_vulkan.png", .frames = 4, .size = 256};
  for (int i = 1; i < argc; ++i) {
    bool has_value = i + 1 < argc;
    if (!strcmp(argv[i], "-o") && has_value)
      o->out = argv[++i];
    else if (!strcmp(argv[i], "--frames") && has_value) {
      if (!sample_parse_int("engine_vulkan", argv[i], argv[i + 1], 1, 1000000, &o->frames)) return false;
      ++i;
    } else if (!strcmp(argv[i], "--size") && has_value) {
      int size = 0;
      if (!sample_parse_int("engine_vulkan", argv[i], argv[i + 1], 16, 4096, &size)) return false;
      o->size = (uint32_t)size;
      ++i;
    } else if (!strcmp(argv[i], "--shader-cache") && has_value)
      o->shader_cache = argv[++i];
    else if (!strcmp(argv[i], "--validate"))
      o->validate = true;
    else {
      fprintf(stderr, "usage: engine_vulkan [-o out.png] [--frames N] [--size PIXELS] [--shader-cache DIR] "
                      "[--validate]\n");
      return false;
    }
  }
  return true;
}

/* ---- instance, device ------------------------------------------------- */

static VkDebugUtilsMessengerCreateInfoEXT messenger_info(void) {
  return (VkDebugUtilsMessengerCreateInfoEXT){.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
                                              .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                                                 VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
                                              .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                                             VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                                             VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
                                              .pfnUserCallback = on_message};
}

/* With validate: the Khronos layer with synchronization validation, and a
 * messenger (also chained into creation, so vkCreateInstance is checked). */
static bool make_instance(engine* e, bool validate) {
  keep_drivers_loaded();
  const char* layer = "VK_LAYER_KHRONOS_validation";
  const char* ext = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  VkValidationFeatureEnableEXT sync = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT features = {.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
                                      .enabledValidationFeatureCount = 1,
                                      .pEnabledValidationFeatures = &sync};
  VkDebugUtilsMessengerCreateInfoEXT mi = messenger_info();
  mi.pNext = &features;
  VkApplicationInfo app = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
                           .pApplicationName = "engine_vulkan",
                           .apiVersion = VK_API_VERSION_1_3};
  VkInstanceCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
                             .pNext = validate ? &mi : NULL,
                             .pApplicationInfo = &app,
                             .enabledLayerCount = validate,
                             .ppEnabledLayerNames = &layer,
                             .enabledExtensionCount = validate,
                             .ppEnabledExtensionNames = &ext};
  VK_TRY(vkCreateInstance(&ci, NULL, &e->instance));
  if (!validate) return true;
  PFN_vkCreateDebugUtilsMessengerEXT create =
      (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(e->instance, "vkCreateDebugUtilsMessengerEXT");
  mi = messenger_info();
  VK_TRY(create ? create(e->instance, &mi, NULL, &e->messenger) : VK_ERROR_EXTENSION_NOT_PRESENT);
  return true;
}

/* The first physical device with a graphics queue family. */
static bool pick_gpu(engine* e) {
  VkPhysicalDevice gpus[8];
  uint32_t n = 8;
  VkResult r = vkEnumeratePhysicalDevices(e->instance, &n, gpus);
  for (uint32_t g = 0; (r == VK_SUCCESS || r == VK_INCOMPLETE) && g < n; ++g) {
    VkQueueFamilyProperties fam[16];
    uint32_t nf = 16;
    vkGetPhysicalDeviceQueueFamilyProperties(gpus[g], &nf, fam);
    for (uint32_t f = 0; f < nf; ++f)
      if (fam[f].queueFlags & VK_QUEUE_GRAPHICS_BIT) {
        e->gpu = gpus[g], e->family = f;
        return true;
      }
  }
  fprintf(stderr, "engine_vulkan: no Vulkan device with a graphics queue (VkResult %d)\n", (int)r);
  return false;
}

/* Every feature the GPU has (tesslod needs dynamic rendering or a render
 * pass; it uses hostQueryReset and fillModeNonSolid when they are on). */
static bool make_device(engine* e) {
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
  VK_TRY(vkCreateDevice(e->gpu, &ci, NULL, &e->device));
  vkGetDeviceQueue(e->device, e->family, 0, &e->queue);
  return true;
}

/* ---- images, buffers, render pass ------------------------------------- */

static bool bind_memory(engine* e, VkMemoryRequirements req, VkMemoryPropertyFlags want, VkDeviceMemory* mem) {
  VkPhysicalDeviceMemoryProperties mp;
  vkGetPhysicalDeviceMemoryProperties(e->gpu, &mp);
  VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = req.size};
  for (ai.memoryTypeIndex = 0; ai.memoryTypeIndex < mp.memoryTypeCount; ++ai.memoryTypeIndex)
    if ((req.memoryTypeBits & (1u << ai.memoryTypeIndex)) &&
        (mp.memoryTypes[ai.memoryTypeIndex].propertyFlags & want) == want)
      return vkAllocateMemory(e->device, &ai, NULL, mem) == VK_SUCCESS;
  return false;
}

static bool make_image(engine* e, VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect, VkImage* img,
                       VkDeviceMemory* mem, VkImageView* view) {
  VkImageCreateInfo ii = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
                          .imageType = VK_IMAGE_TYPE_2D,
                          .format = format,
                          .extent = {e->size, e->size, 1},
                          .mipLevels = 1,
                          .arrayLayers = 1,
                          .samples = VK_SAMPLE_COUNT_1_BIT,
                          .tiling = VK_IMAGE_TILING_OPTIMAL,
                          .usage = usage};
  VK_TRY(vkCreateImage(e->device, &ii, NULL, img));
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(e->device, *img, &req);
  VK_TRY(bind_memory(e, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, mem) ? VK_SUCCESS : VK_ERROR_OUT_OF_DEVICE_MEMORY);
  VK_TRY(vkBindImageMemory(e->device, *img, *mem, 0));
  VkImageViewCreateInfo vi = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
                              .image = *img,
                              .viewType = VK_IMAGE_VIEW_TYPE_2D,
                              .format = format,
                              .subresourceRange = {aspect, 0, 1, 0, 1}};
  VK_TRY(vkCreateImageView(e->device, &vi, NULL, view));
  return true;
}

static bool make_readback(engine* e, slot* s) {
  VkBufferCreateInfo bi = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                           .size = 4 * (VkDeviceSize)e->size * e->size,
                           .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT};
  VK_TRY(vkCreateBuffer(e->device, &bi, NULL, &s->readback));
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(e->device, s->readback, &req);
  VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  VK_TRY(bind_memory(e, req, host, &s->readback_mem) ? VK_SUCCESS : VK_ERROR_OUT_OF_HOST_MEMORY);
  VK_TRY(vkBindBufferMemory(e->device, s->readback, s->readback_mem, 0));
  return true;
}

/* Colour cleared, stored and left TRANSFER_SRC for the copy; depth cleared.
 * The external dependencies order this frame's attachment writes after the
 * previous frame's (the images are shared by both slots) and the copy after
 * this frame's writes. */
static bool make_render_pass(engine* e) {
  VkAttachmentDescription att[2] = {{.format = COLOR_FORMAT,
                                     .samples = VK_SAMPLE_COUNT_1_BIT,
                                     .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR,
                                     .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
                                     .stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
                                     .stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
                                     .finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL},
                                    {.format = DEPTH_FORMAT,
                                     .samples = VK_SAMPLE_COUNT_1_BIT,
                                     .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR,
                                     .storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
                                     .stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
                                     .stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
                                     .finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL}};
  VkAttachmentReference cref = {0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkAttachmentReference dref = {1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription sub = {.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS,
                              .colorAttachmentCount = 1,
                              .pColorAttachments = &cref,
                              .pDepthStencilAttachment = &dref};
  VkPipelineStageFlags stages = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  VkAccessFlags access = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_COLOR_ATTACHMENT_READ_BIT |
                         VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
  VkSubpassDependency deps[2] = {{VK_SUBPASS_EXTERNAL, 0, stages | VK_PIPELINE_STAGE_TRANSFER_BIT, stages,
                                  VK_ACCESS_TRANSFER_READ_BIT | access, access, 0},
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
  VK_TRY(vkCreateRenderPass(e->device, &ci, NULL, &e->pass));
  VkImageView views[2] = {e->color_view, e->depth_view};
  VkFramebufferCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO,
                                .renderPass = e->pass,
                                .attachmentCount = 2,
                                .pAttachments = views,
                                .width = e->size,
                                .height = e->size,
                                .layers = 1};
  VK_TRY(vkCreateFramebuffer(e->device, &fi, NULL, &e->framebuffer));
  return true;
}

/* ---- the engine's pipeline -------------------------------------------- */

static bool make_module(engine* e, const uint32_t* words, size_t bytes, VkShaderModule* out) {
  VkShaderModuleCreateInfo ci = {
      .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, .codeSize = bytes, .pCode = words};
  VK_TRY(vkCreateShaderModule(e->device, &ci, NULL, out));
  return true;
}

/* No vertex input, depth or culling; viewport and scissor dynamic. */
static bool make_pipeline(engine* e) {
  if (!make_module(e, engine_vert_spv, sizeof engine_vert_spv, &e->vs) ||
      !make_module(e, engine_frag_spv, sizeof engine_frag_spv, &e->fs))
    return false;
  VkPushConstantRange range = {VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, 16};
  VkPipelineLayoutCreateInfo li = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                   .pushConstantRangeCount = 1,
                                   .pPushConstantRanges = &range};
  VK_TRY(vkCreatePipelineLayout(e->device, &li, NULL, &e->layout));
  VkPipelineShaderStageCreateInfo st[2] = {{.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
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
                                     .pStages = st,
                                     .pVertexInputState = &vin,
                                     .pInputAssemblyState = &ia,
                                     .pViewportState = &vp,
                                     .pRasterizationState = &rs,
                                     .pMultisampleState = &ms,
                                     .pDepthStencilState = &ds,
                                     .pColorBlendState = &blend,
                                     .pDynamicState = &dy,
                                     .layout = e->layout,
                                     .renderPass = e->pass};
  VK_TRY(vkCreateGraphicsPipelines(e->device, VK_NULL_HANDLE, 1, &pi, NULL, &e->pipeline));
  return true;
}

/* ---- frames in flight ------------------------------------------------- */

/* Fences start signalled: the first wait of each slot returns at once. */
static bool make_slots(engine* e) {
  VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                .queueFamilyIndex = e->family};
  VK_TRY(vkCreateCommandPool(e->device, &pi, NULL, &e->pool));
  for (int i = 0; i < FRAMES_IN_FLIGHT; ++i) {
    slot* s = &e->slots[i];
    VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                      .commandPool = e->pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                      .commandBufferCount = 1};
    VK_TRY(vkAllocateCommandBuffers(e->device, &ai, &s->cmd));
    VkFenceCreateInfo fi = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, .flags = VK_FENCE_CREATE_SIGNALED_BIT};
    VK_TRY(vkCreateFence(e->device, &fi, NULL, &s->fence));
    if (!make_readback(e, s)) return false;
  }
  return true;
}

static bool engine_open(engine* e, const options* o) {
  memset(e, 0, sizeof *e);
  e->size = o->size;
  VkImageUsageFlags color_use = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  return make_instance(e, o->validate) && pick_gpu(e) && make_device(e) &&
         make_image(e, COLOR_FORMAT, color_use, VK_IMAGE_ASPECT_COLOR_BIT, &e->color, &e->color_mem, &e->color_view) &&
         make_image(e, DEPTH_FORMAT, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT, &e->depth,
                    &e->depth_mem, &e->depth_view) &&
         make_render_pass(e) && make_pipeline(e) && make_slots(e);
}

/* vkDestroy* and vkFree* take VK_NULL_HANDLE: a half-made engine frees what it has. */
static void engine_close(engine* e) {
  if (e->device) {
    vkDeviceWaitIdle(e->device);
    for (int i = 0; i < FRAMES_IN_FLIGHT; ++i) {
      vkDestroyFence(e->device, e->slots[i].fence, NULL);
      vkDestroyBuffer(e->device, e->slots[i].readback, NULL);
      vkFreeMemory(e->device, e->slots[i].readback_mem, NULL);
    }
    vkDestroyCommandPool(e->device, e->pool, NULL);
    vkDestroyPipeline(e->device, e->pipeline, NULL);
    vkDestroyPipelineLayout(e->device, e->layout, NULL);
    vkDestroyShaderModule(e->device, e->vs, NULL);
    vkDestroyShaderModule(e->device, e->fs, NULL);
    vkDestroyFramebuffer(e->device, e->framebuffer, NULL);
    vkDestroyRenderPass(e->device, e->pass, NULL);
    vkDestroyImageView(e->device, e->color_view, NULL);
    vkDestroyImageView(e->device, e->depth_view, NULL);
    vkDestroyImage(e->device, e->color, NULL);
    vkDestroyImage(e->device, e->depth, NULL);
    vkFreeMemory(e->device, e->color_mem, NULL);
    vkFreeMemory(e->device, e->depth_mem, NULL);
    vkDestroyDevice(e->device, NULL);
  }
  PFN_vkDestroyDebugUtilsMessengerEXT destroy =
      e->messenger
          ? (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(e->instance, "vkDestroyDebugUtilsMessengerEXT")
          : NULL;
  if (destroy) destroy(e->instance, e->messenger, NULL);
  if (e->instance) vkDestroyInstance(e->instance, NULL);
}

/* ---- one frame -------------------------------------------------------- */

/* The engine's own draw: it binds all it needs, also after tesslod (which
 * leaves its pipeline, viewport, scissor and push constants bound). */
static void engine_draw(const engine* e, VkCommandBuffer cmd, uint32_t first, uint32_t count, const float rgba[4]) {
  VkViewport vp = {0, 0, (float)e->size, (float)e->size, 0, 1};
  VkRect2D sc = {{0, 0}, {e->size, e->size}};
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, e->pipeline);
  vkCmdSetViewport(cmd, 0, 1, &vp);
  vkCmdSetScissor(cmd, 0, 1, &sc);
  vkCmdPushConstants(cmd, e->layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, 16, rgba);
  vkCmdDraw(cmd, count, 1, first, 0);
}

static void record_copy(const engine* e, const slot* s) {
  VkBufferImageCopy copy = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                            .imageExtent = {e->size, e->size, 1}};
  vkCmdCopyImageToBuffer(s->cmd, e->color, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, s->readback, 1, &copy);
  VkBufferMemoryBarrier host = {.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER,
                                .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
                                .dstAccessMask = VK_ACCESS_HOST_READ_BIT,
                                .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                .buffer = s->readback,
                                .size = VK_WHOLE_SIZE};
  vkCmdPipelineBarrier(s->cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, NULL, 1, &host, 0,
                       NULL);
}

static const float floor_green[4] = {0.1f, 0.8f, 0.2f, 1}, overlay_red[4] = {0.9f, 0.1f, 0.1f, 1};

/* Records the frame into the slot's command buffer; tesslod draws with the
 * slot's index, whose previous frame the fence wait has seen finish. */
static bool record_frame(engine* e, uint32_t index, sample_scene* sc, tlod_draw_desc* draw) {
  slot* s = &e->slots[index];
  VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                 .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
  VK_TRY(vkResetCommandBuffer(s->cmd, 0));
  VK_TRY(vkBeginCommandBuffer(s->cmd, &bi));
  VkClearValue clear[2] = {{.color = {{0.08f, 0.08f, 0.1f, 1}}}, {.depthStencil = {1.0f, 0}}};
  VkRenderPassBeginInfo rp = {.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO,
                              .renderPass = e->pass,
                              .framebuffer = e->framebuffer,
                              .renderArea = {{0, 0}, {e->size, e->size}},
                              .clearValueCount = 2,
                              .pClearValues = clear};
  vkCmdBeginRenderPass(s->cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
  engine_draw(e, s->cmd, 0, 6, floor_green);
  draw->vk = (tlod_draw_vk_desc){.command_buffer = s->cmd, .frame_index = index};
  bool ok = sample_check(tlod_device_draw(sc->dev, draw), sc, "tlod_device_draw", "engine_vulkan");
  engine_draw(e, s->cmd, 6, 3, overlay_red);
  vkCmdEndRenderPass(s->cmd);
  record_copy(e, s);
  VK_TRY(vkEndCommandBuffer(s->cmd));
  return ok;
}

static bool frame(engine* e, sample_scene* sc, int number, uint64_t* triangles) {
  uint32_t index = (uint32_t)number % FRAMES_IN_FLIGHT;
  slot* s = &e->slots[index];
  VK_TRY(vkWaitForFences(e->device, 1, &s->fence, VK_TRUE, UINT64_MAX)); /* the frame two back is done */
  VK_TRY(vkResetFences(e->device, 1, &s->fence));
  tlod_view_desc v = sample_orbit_camera(0.4f * (float)number, 3.4f, 0.8f, e->size, e->size);
  tlod_draw_item item;
  tlod_draw_desc draw;
  if (!sample_scene_plan(sc, &v, 16.7f, &item, &draw, "engine_vulkan") || !record_frame(e, index, sc, &draw))
    return false;
  *triangles = tlod_device_query_stats(sc->dev).triangles;
  VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &s->cmd};
  VK_TRY(vkQueueSubmit(e->queue, 1, &si, s->fence));
  return true;
}

/* Waits for the last frame and writes its slot's read-back (top row first). */
static bool write_png(engine* e, int last, const char* path) {
  slot* s = &e->slots[(uint32_t)last % FRAMES_IN_FLIGHT];
  VK_TRY(vkWaitForFences(e->device, 1, &s->fence, VK_TRUE, UINT64_MAX));
  void* mapped = NULL;
  VK_TRY(vkMapMemory(e->device, s->readback_mem, 0, VK_WHOLE_SIZE, 0, &mapped));
  char err[256] = "";
  bool ok = tlod_png_write(path, e->size, e->size, mapped, err, sizeof err);
  vkUnmapMemory(e->device, s->readback_mem);
  if (!ok) fprintf(stderr, "engine_vulkan: %s\n", err);
  return ok;
}

static bool run(engine* e, const options* o, const sample_mesh* m) {
  tlod_device_vk_desc vk = {.instance = e->instance,
                            .physical_device = e->gpu,
                            .device = e->device,
                            .queue = e->queue,
                            .queue_family = e->family,
                            .frames_in_flight = FRAMES_IN_FLIGHT,
                            .render_pass = (uint64_t)(uintptr_t)e->pass,
                            .color_format = COLOR_FORMAT,
                            .depth_format = DEPTH_FORMAT,
                            .host_query_reset = e->host_query_reset,
                            .shader_cache_dir = o->shader_cache,
                            .surface_types = 1u << TLOD_SURFACE_PN,
                            .fragment_hook = sample_checker_hook};
  sample_scene sc;
  tlod_attribute_desc uv;
  tlod_mesh_desc md = sample_mesh_desc(m, &uv);
  bool ok = sample_scene_init(&sc, &md, (tlod_device_desc){.backend = "vulkan", .vk = vk}, "engine_vulkan");
  for (int f = 0; ok && f < o->frames; ++f) {
    uint64_t triangles = 0;
    ok = frame(e, &sc, f, &triangles);
    if (ok)
      printf("frame %d (slot %d): floor 2 + tesslod %llu + overlay 1 triangles\n", f, f % FRAMES_IN_FLIGHT,
             (unsigned long long)triangles);
  }
  ok = ok && write_png(e, o->frames - 1, o->out);
  if (ok) printf("wrote %s (%ux%u)\n", o->out, e->size, e->size);
  sample_scene_free(&sc); /* tlod_device_destroy waits for the device to be idle */
  return ok;
}

int main(int argc, char** argv) {
  options o;
  if (!parse_options(argc, argv, &o)) return 2;
  engine e;
  sample_mesh m = {0};
  bool ok = engine_open(&e, &o) && sample_sphere_make(&m, 6, 12) && run(&e, &o, &m);
  sample_mesh_free(&m);
  engine_close(&e);
  if (o.validate) printf("validation messages: %u\n", s_validation_messages);
  return ok && s_validation_messages == 0 ? 0 : 1;
}
