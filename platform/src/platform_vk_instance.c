/*
 * platform_vk_instance.c -- the Vulkan part of platform/, first half: the
 * instance (Vulkan 1.3; with validation: VK_LAYER_KHRONOS_validation,
 * synchronization validation, a debug-utils messenger that prints and
 * counts), the physical device and the logical device with its queue.
 * docs/platform.md section 3 has the measured lavapipe facts this relies on.
 */
#define _POSIX_C_SOURCE 200809L

#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "platform_vk.h"

#define VALIDATION_LAYER "VK_LAYER_KHRONOS_validation"
#define MAX_EXTENSIONS 16

/* Every platform's messages, also those of destroyed ones (platform.c). */
static _Atomic uint64_t s_messages_total; /* atomic: a driver thread may report too */

const char* _tlod_vk_result_name(VkResult r) {
  switch (r) {
#define NAME(x)                                                                                                        \
  case x:                                                                                                              \
    return #x
    NAME(VK_SUCCESS);
    NAME(VK_NOT_READY);
    NAME(VK_TIMEOUT);
    NAME(VK_INCOMPLETE);
    NAME(VK_SUBOPTIMAL_KHR);
    NAME(VK_ERROR_OUT_OF_HOST_MEMORY);
    NAME(VK_ERROR_OUT_OF_DEVICE_MEMORY);
    NAME(VK_ERROR_INITIALIZATION_FAILED);
    NAME(VK_ERROR_DEVICE_LOST);
    NAME(VK_ERROR_MEMORY_MAP_FAILED);
    NAME(VK_ERROR_LAYER_NOT_PRESENT);
    NAME(VK_ERROR_EXTENSION_NOT_PRESENT);
    NAME(VK_ERROR_FEATURE_NOT_PRESENT);
    NAME(VK_ERROR_INCOMPATIBLE_DRIVER);
    NAME(VK_ERROR_TOO_MANY_OBJECTS);
    NAME(VK_ERROR_FORMAT_NOT_SUPPORTED);
    NAME(VK_ERROR_SURFACE_LOST_KHR);
    NAME(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR);
    NAME(VK_ERROR_OUT_OF_DATE_KHR);
#undef NAME
  default:
    return "unknown VkResult";
  }
}

bool _tlod_vk_check(VkResult r, const char* what, char* error, size_t error_size) {
  if (r >= 0) return true;
  _tlod_platform_error(error, error_size, "%s failed: %s (%d)", what, _tlod_vk_result_name(r), (int)r);
  return false;
}

/* Prints and counts warnings and errors (the messenger is created for no
 * other severities). */
static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                 VkDebugUtilsMessageTypeFlagsEXT types,
                                                 const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  (void)types;
  _tlod_platform_vk* vk = user;
  vk->messages++;
  s_messages_total++;
  const char* level = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning";
  fprintf(stderr, "vulkan validation: %s: %s\n", level, data && data->pMessage ? data->pMessage : "(no message)");
  return VK_FALSE;
}

uint64_t _tlod_platform_vk_messages(const tlod_platform* p) {
  return p ? (p->vk ? p->vk->messages : 0) : s_messages_total;
}

static bool has_layer(const char* name) {
  uint32_t n = 0;
  if (vkEnumerateInstanceLayerProperties(&n, NULL) != VK_SUCCESS || n == 0) return false;
  VkLayerProperties* layers = calloc(n, sizeof *layers);
  bool found = false;
  if (layers && vkEnumerateInstanceLayerProperties(&n, layers) >= 0)
    for (uint32_t i = 0; i < n && !found; ++i)
      found = strcmp(layers[i].layerName, name) == 0;
  free(layers);
  return found;
}

static bool has_instance_extension(const char* layer, const char* name) {
  uint32_t n = 0;
  if (vkEnumerateInstanceExtensionProperties(layer, &n, NULL) != VK_SUCCESS || n == 0) return false;
  VkExtensionProperties* ext = calloc(n, sizeof *ext);
  bool found = false;
  if (ext && vkEnumerateInstanceExtensionProperties(layer, &n, ext) >= 0)
    for (uint32_t i = 0; i < n && !found; ++i)
      found = strcmp(ext[i].extensionName, name) == 0;
  free(ext);
  return found;
}

/* Window: the surface extensions GLFW needs. */
static bool window_extensions(const char** names, uint32_t* count, char* error, size_t error_size) {
  uint32_t n = 0;
  const char** glfw = glfwGetRequiredInstanceExtensions(&n);
  if (!glfw || n == 0 || n + *count > MAX_EXTENSIONS) {
    _tlod_platform_error(error, error_size, "glfwGetRequiredInstanceExtensions: no Vulkan surface extensions");
    return false;
  }
  for (uint32_t i = 0; i < n; ++i)
    names[(*count)++] = glfw[i];
  return true;
}

static bool check_loader_version(char* error, size_t error_size) {
  uint32_t version = VK_API_VERSION_1_0;
  (void)vkEnumerateInstanceVersion(&version);
  if (version >= VK_API_VERSION_1_3) return true;
  _tlod_platform_error(error, error_size, "Vulkan loader is %u.%u, Vulkan 1.3 is needed (Debian package libvulkan1)",
                       VK_API_VERSION_MAJOR(version), VK_API_VERSION_MINOR(version));
  return false;
}

static VkDebugUtilsMessengerCreateInfoEXT messenger_info(_tlod_platform_vk* vk) {
  return (VkDebugUtilsMessengerCreateInfoEXT){.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
                                              .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                                                 VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
                                              .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                                             VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                                             VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
                                              .pfnUserCallback = on_message,
                                              .pUserData = vk};
}

static bool create_messenger(_tlod_platform_vk* vk, char* error, size_t error_size) {
  PFN_vkCreateDebugUtilsMessengerEXT create =
      (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(vk->instance, "vkCreateDebugUtilsMessengerEXT");
  if (!create) {
    _tlod_platform_error(error, error_size, "vkGetInstanceProcAddr: no vkCreateDebugUtilsMessengerEXT");
    return false;
  }
  VkDebugUtilsMessengerCreateInfoEXT info = messenger_info(vk);
  return _tlod_vk_check(create(vk->instance, &info, NULL, &vk->messenger), "vkCreateDebugUtilsMessengerEXT", error,
                        error_size);
}

bool _tlod_vk_instance_create(tlod_platform* p, bool validation, char* error, size_t error_size) {
  _tlod_platform_vk* vk = p->vk;
  if (!check_loader_version(error, error_size)) return false;
  const char* extensions[MAX_EXTENSIONS];
  uint32_t n_ext = 0;
  if (p->window && !window_extensions(extensions, &n_ext, error, error_size)) return false;
  const char* layers[1] = {VALIDATION_LAYER};
  /* Synchronization validation on, best practices (not listed) off. */
  static const VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkDebugUtilsMessengerCreateInfoEXT messenger = messenger_info(vk);
  VkValidationFeaturesEXT features = {.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
                                      .pNext = &messenger,
                                      .enabledValidationFeatureCount = 1,
                                      .pEnabledValidationFeatures = enables};
  if (validation) {
    if (!has_layer(VALIDATION_LAYER)) {
      _tlod_platform_error(error, error_size,
                           "Vulkan validation requested but the layer " VALIDATION_LAYER
                           " is not installed (Debian package vulkan-validationlayers)");
      return false;
    }
    extensions[n_ext++] = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    if (!has_instance_extension(VALIDATION_LAYER, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME)) {
      _tlod_platform_error(error, error_size,
                           "Vulkan validation: the layer " VALIDATION_LAYER
                           " lacks " VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME
                           " (synchronization validation); vulkan-validationlayers 1.3.239 has it");
      return false;
    }
    extensions[n_ext++] = VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME;
  }
  VkApplicationInfo app = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
                           .pApplicationName = "tesslod",
                           .pEngineName = "tesslod",
                           .apiVersion = VK_API_VERSION_1_3};
  VkInstanceCreateInfo info = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
                               .pNext = validation ? &features : NULL,
                               .pApplicationInfo = &app,
                               .enabledLayerCount = validation ? 1 : 0,
                               .ppEnabledLayerNames = layers,
                               .enabledExtensionCount = n_ext,
                               .ppEnabledExtensionNames = extensions};
  if (!_tlod_vk_check(vkCreateInstance(&info, NULL, &vk->instance), "vkCreateInstance (Vulkan 1.3)", error, error_size))
    return false;
  return !validation || create_messenger(vk, error, error_size);
}

/* ------------------------------------------------------------------------ */
/* Physical device and device                                               */
/* ------------------------------------------------------------------------ */

typedef struct device_features {
  VkPhysicalDeviceFeatures2 f2;
  VkPhysicalDeviceVulkan12Features f12;
  VkPhysicalDeviceVulkan13Features f13;
} device_features;

static void chain_features(device_features* f) {
  memset(f, 0, sizeof *f);
  f->f2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
  f->f12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
  f->f13.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES;
  f->f2.pNext = &f->f12;
  f->f12.pNext = &f->f13;
}

static bool has_device_extension(VkPhysicalDevice pd, const char* name) {
  uint32_t n = 0;
  if (vkEnumerateDeviceExtensionProperties(pd, NULL, &n, NULL) != VK_SUCCESS || n == 0) return false;
  VkExtensionProperties* ext = calloc(n, sizeof *ext);
  bool found = false;
  if (ext && vkEnumerateDeviceExtensionProperties(pd, NULL, &n, ext) >= 0)
    for (uint32_t i = 0; i < n && !found; ++i)
      found = strcmp(ext[i].extensionName, name) == 0;
  free(ext);
  return found;
}

/* A graphics queue family of pd (that can present to the surface, if any);
 * UINT32_MAX when none. */
static uint32_t graphics_family(const tlod_platform* p, VkPhysicalDevice pd) {
  uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, NULL);
  VkQueueFamilyProperties props[16];
  if (n > 16) n = 16;
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, props);
  for (uint32_t i = 0; i < n; ++i) {
    if (!(props[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) || props[i].queueCount == 0) continue;
    VkBool32 present = VK_TRUE;
    if (p->vk->surface) vkGetPhysicalDeviceSurfaceSupportKHR(pd, i, p->vk->surface, &present);
    if (present) return i;
  }
  return UINT32_MAX;
}

/* Why pd cannot be used (NULL: it can), with its queue family. */
static const char* unusable(const tlod_platform* p, VkPhysicalDevice pd, uint32_t* family) {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(pd, &props);
  if (props.apiVersion < VK_API_VERSION_1_3) return "Vulkan 1.3 is not supported";
  device_features f;
  chain_features(&f);
  vkGetPhysicalDeviceFeatures2(pd, &f.f2);
  if (!f.f13.dynamicRendering) return "no dynamicRendering";
  if (p->window && !has_device_extension(pd, VK_KHR_SWAPCHAIN_EXTENSION_NAME)) return "no VK_KHR_swapchain";
  *family = graphics_family(p, pd);
  if (*family == UINT32_MAX) return p->window ? "no graphics queue that presents to the window" : "no graphics queue";
  return NULL;
}

static bool pick_physical_device(tlod_platform* p, char* error, size_t error_size) {
  _tlod_platform_vk* vk = p->vk;
  VkPhysicalDevice devices[16];
  uint32_t n = 16;
  VkResult r = vkEnumeratePhysicalDevices(vk->instance, &n, devices);
  if (!_tlod_vk_check(r, "vkEnumeratePhysicalDevices", error, error_size)) return false;
  char why[256] = "no Vulkan device (is mesa-vulkan-drivers installed? VK_DRIVER_FILES names the driver)";
  for (uint32_t i = 0; i < n; ++i) {
    const char* reason = unusable(p, devices[i], &vk->family);
    if (!reason) {
      vk->physical = devices[i];
      return true;
    }
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(devices[i], &props);
    snprintf(why, sizeof why, "Vulkan device %u (%.120s): %s", i, props.deviceName, reason);
  }
  _tlod_platform_error(error, error_size, "no usable Vulkan device: %s", why);
  return false;
}

/* Enables what the "vulkan" device needs from what pd has. */
static void wanted_features(const device_features* have, device_features* want) {
  chain_features(want);
  const VkPhysicalDeviceFeatures* h = &have->f2.features;
  VkPhysicalDeviceFeatures* w = &want->f2.features;
  w->tessellationShader = h->tessellationShader;
  w->fillModeNonSolid = h->fillModeNonSolid;
  w->pipelineStatisticsQuery = h->pipelineStatisticsQuery;
  w->multiDrawIndirect = h->multiDrawIndirect;
  w->drawIndirectFirstInstance = h->drawIndirectFirstInstance;
  w->samplerAnisotropy = h->samplerAnisotropy;
  want->f12.hostQueryReset = have->f12.hostQueryReset;
  want->f13.dynamicRendering = VK_TRUE;
  want->f13.synchronization2 = have->f13.synchronization2;
}

static void describe_device(tlod_platform* p) {
  VkPhysicalDeviceVulkan12Properties p12 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_PROPERTIES};
  VkPhysicalDeviceProperties2 props = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &p12};
  vkGetPhysicalDeviceProperties2(p->vk->physical, &props);
  uint32_t v = props.properties.apiVersion;
  /* driverInfo is "Mesa 22.3.6 (LLVM 15.0.6)": the part before " (". */
  char driver[VK_MAX_DRIVER_INFO_SIZE];
  snprintf(driver, sizeof driver, "%s", p12.driverInfo[0] ? p12.driverInfo : p12.driverName);
  char* paren = strstr(driver, " (");
  if (paren) *paren = '\0';
  snprintf(p->renderer, sizeof p->renderer, "%.159s", props.properties.deviceName);
  snprintf(p->version, sizeof p->version, "Vulkan %u.%u.%u, %.100s", VK_API_VERSION_MAJOR(v), VK_API_VERSION_MINOR(v),
           VK_API_VERSION_PATCH(v), driver);
}

bool _tlod_vk_device_create(tlod_platform* p, char* error, size_t error_size) {
  _tlod_platform_vk* vk = p->vk;
  if (!pick_physical_device(p, error, error_size)) return false;
  vkGetPhysicalDeviceMemoryProperties(vk->physical, &vk->memory);
  device_features have, want;
  chain_features(&have);
  vkGetPhysicalDeviceFeatures2(vk->physical, &have.f2);
  wanted_features(&have, &want);
  vk->tessellation = want.f2.features.tessellationShader;
  vk->host_query_reset = want.f12.hostQueryReset;
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                   .queueFamilyIndex = vk->family,
                                   .queueCount = 1,
                                   .pQueuePriorities = &priority};
  const char* extensions[1] = {VK_KHR_SWAPCHAIN_EXTENSION_NAME};
  VkDeviceCreateInfo info = {.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
                             .pNext = &want.f2,
                             .queueCreateInfoCount = 1,
                             .pQueueCreateInfos = &queue,
                             .enabledExtensionCount = p->window ? 1 : 0,
                             .ppEnabledExtensionNames = extensions};
  if (!_tlod_vk_check(vkCreateDevice(vk->physical, &info, NULL, &vk->device), "vkCreateDevice", error, error_size))
    return false;
  vkGetDeviceQueue(vk->device, vk->family, 0, &vk->queue);
  describe_device(p);
  return true;
}

void _tlod_vk_instance_destroy(tlod_platform* p) {
  _tlod_platform_vk* vk = p->vk;
  if (vk->device) vkDestroyDevice(vk->device, NULL);
  vk->device = VK_NULL_HANDLE;
  if (vk->surface) vkDestroySurfaceKHR(vk->instance, vk->surface, NULL);
  vk->surface = VK_NULL_HANDLE;
  if (vk->messenger) {
    PFN_vkDestroyDebugUtilsMessengerEXT destroy =
        (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(vk->instance, "vkDestroyDebugUtilsMessengerEXT");
    if (destroy) destroy(vk->instance, vk->messenger, NULL);
    vk->messenger = VK_NULL_HANDLE;
  }
  if (vk->instance) vkDestroyInstance(vk->instance, NULL);
  vk->instance = VK_NULL_HANDLE;
}
