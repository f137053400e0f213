/*
 * vk_gl_test.h -- what the Vulkan tests that compare with GL share
 * (vk_parity_test, vk_cracks_test): a GL platform (the GL device and
 * gl_test.h's independent reference renderer draw there) and a Vulkan
 * platform of the same size in one process, one tesslod context and one
 * pattern set. The Vulkan platform runs the validation layer (synchronization
 * validation on): the tests end with vk_check_no_messages(), so these
 * scenes are validated too and a Vulkan object tesslod forgets is the
 * object tracker's error. Built only with the GL backend
 * (tests/vk/CMakeLists.txt).
 */
#ifndef TLOD_VK_GL_TEST_H
#define TLOD_VK_GL_TEST_H

#include "gl_test.h"
#include "vk_test.h"

typedef struct vk_gl_env {
  tlod_platform *gl, *vk;
  ref_renderer ref;
  tlod_context* ctx;
  tlod_patterns* pat;
} vk_gl_env;

/* Closes what vk_gl_open made (also after a failed open); the devices on
 * it must be destroyed first. Waits for the Vulkan frames first. */
static inline void vk_gl_close(vk_gl_env* e) {
  if (e->vk) tlod_platform_finish(e->vk);
  if (e->gl) tlod_platform_bind(e->gl), ref_free(&e->ref);
  tlod_patterns_destroy(e->pat);
  tlod_context_destroy(e->ctx);
  if (e->vk) tlod_platform_destroy(e->vk);
  if (e->gl) tlod_platform_destroy(e->gl);
  memset(e, 0, sizeof *e);
}

/* false with the reason printed; the GL context is left current. */
static inline bool vk_gl_open(vk_gl_env* e, uint32_t w, uint32_t h, uint32_t max_level) {
  char err[512] = "";
  memset(e, 0, sizeof *e);
  e->gl = gl_test_platform(w, h, err, sizeof err);
  e->vk = e->gl ? vk_test_platform(w, h, true, err, sizeof err) : NULL;
  if (!e->vk) return false;
  tlod_platform_bind(e->gl);
  if (!ref_init(&e->ref)) return false;
  if (tlod_context_create(&(tlod_context_desc){.thread_count = 2}, &e->ctx) != TLOD_SUCCESS) return false;
  return (e->pat = new_patterns(e->ctx, max_level)) != NULL;
}

#endif
