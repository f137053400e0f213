/*
 * tlod_platform_device.h -- the "vulkan" device's desc from a Vulkan
 * platform: the handles and formats tlod_platform_vk_info gives, in the
 * tlod_device_vk_desc fields that take them. Header-only (the platform
 * library does not link the backends); for tools and samples that use both.
 */
#ifndef TLOD_PLATFORM_DEVICE_H
#define TLOD_PLATFORM_DEVICE_H

#include "tesslod/backend.h"
#include "tlod_platform.h"

/* false (d untouched) for a GL platform or NULL; else sets instance,
 * physical_device, device, queue, queue_family, frames_in_flight,
 * color_format, depth_format and host_query_reset, and leaves the other
 * fields (shader cache, surface types, hook, gpu_eval ...) as they were. */
static inline bool tlod_platform_vk_device_desc(const tlod_platform* p, tlod_device_vk_desc* d) {
  tlod_platform_vk vk;
  if (!p || !tlod_platform_vk_info(p, &vk)) return false;
  d->instance = vk.instance;
  d->physical_device = vk.physical_device;
  d->device = vk.device;
  d->queue = vk.queue;
  d->queue_family = vk.queue_family;
  d->frames_in_flight = vk.frames_in_flight;
  d->color_format = vk.color_format;
  d->depth_format = vk.depth_format;
  d->host_query_reset = vk.host_query_reset;
  return true;
}

#endif
