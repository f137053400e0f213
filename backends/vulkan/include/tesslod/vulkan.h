/*
 * tesslod/vulkan.h -- the "vulkan" device (module tesslod::vulkan): what it
 * makes on an engine's Vulkan device and records into its command buffers.
 * The API is tesslod/backend.h (tlod_device_create with .backend = "vulkan"
 * and the desc's .vk); this header holds the Vulkan facts.
 *
 * (The full manual follows with the device; the binding layout below is the
 * interface shaders and engines code against.)
 */
#ifndef TESSLOD_VULKAN_H
#define TESSLOD_VULKAN_H

#include "tesslod/core.h"

/* Descriptor set 0 of every pipeline (the values of backends/shaders/layout.h). */
#define TLOD_VK_BINDING_PATCHES 0    /* STORAGE_BUFFER: tlod_patch_record per patch */
#define TLOD_VK_BINDING_PATTERNS 1   /* STORAGE_BUFFER: pattern vertices of both shapes */
#define TLOD_VK_BINDING_INSTANCES 2  /* STORAGE_BUFFER_DYNAMIC (frame ring): per visible patch */
#define TLOD_VK_BINDING_STRIPS 3     /* STORAGE_BUFFER_DYNAMIC (frame ring): per connection strip */
#define TLOD_VK_BINDING_ATTRIBUTES 4 /* STORAGE_BUFFER: vec4 mesh attributes per patch corner */
#define TLOD_VK_BINDING_UNIFORMS 5   /* UNIFORM_BUFFER_DYNAMIC (frame ring): tlod_vk_uniforms per item */
#define TLOD_VK_BINDING_BASE_COLOR 6 /* COMBINED_IMAGE_SAMPLER: the item's base colour texture */

/* Largest frames_in_flight of tlod_device_vk_desc. */
#define TLOD_VK_MAX_FRAMES_IN_FLIGHT 8

#endif
