/*
 * vk_platform_test.c -- the platform helper's frame API (platform/,
 * tlod_platform.h) in both APIs, checked by reading pixels back. Public
 * API only (plus raw Vulkan calls recorded into the platform's command
 * buffer, as an engine would). FAILS (never skips) when a platform cannot
 * be created, with the platform's message.
 *
 *   - Vulkan headless with validation (synchronization validation on):
 *     describe / vk_info name the device, formats and 2 frames in flight;
 *     nothing to read before the first frame; a clear reads back as exact
 *     bytes; a clear rectangle over the top rows reads back in row 0 (top
 *     row first); 10 frames of different colours, each read right after
 *     its end_frame, give that frame's colour (never the other slot's) and
 *     frame_index alternates 0, 1; begin twice / end without begin /
 *     resize or finish inside a frame fail (with a message); resize then a frame reads back at the new size;
 *     zero validation messages, also over destruction (the object tracker
 *     reports leaks in vkDestroyDevice / vkDestroyInstance), and a
 *     command the layer must reject is printed and counted (so the zero
 *     means the layer ran);
 *   - the validation layer hidden (VK_LAYER_PATH to an empty folder):
 *     creation fails naming the package vulkan-validationlayers;
 *   - GL (when built): begin_frame clears to the colour, resize gives a
 *     new FBO of the new size, end_frame succeeds with submit_ms 0.
 */
#define _POSIX_C_SOURCE 200809L

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <vulkan/vulkan.h>

#include "test.h"
#include "tlod_platform.h"

#ifndef TLOD_TEST_HAS_GL
#define TLOD_TEST_HAS_GL 0
#endif

static char s_err[512];

static tlod_platform* vk_platform(uint32_t w, uint32_t h) {
  tlod_platform* p = NULL;
  tlod_platform_desc d = {.width = w, .height = h, .api = TLOD_PLATFORM_VULKAN, .validation = true};
  if (!tlod_platform_create(&d, &p, s_err, sizeof s_err)) fprintf(stderr, "no Vulkan platform: %s\n", s_err);
  return p;
}

/* Every pixel of a w x h read-back equals rgba; prints the first that does not. */
static bool all_pixels(const uint8_t* px, uint32_t w, uint32_t h, const uint8_t rgba[4], uint32_t y0, uint32_t y1) {
  for (uint32_t y = y0; y < y1; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const uint8_t* q = px + ((size_t)y * w + x) * 4;
      if (memcmp(q, rgba, 4) != 0) {
        fprintf(stderr, "pixel (%u, %u) = %u %u %u %u, want %u %u %u %u\n", x, y, q[0], q[1], q[2], q[3], rgba[0],
                rgba[1], rgba[2], rgba[3]);
        return false;
      }
    }
  (void)h;
  return true;
}

static void to_float(const uint8_t rgba[4], float out[4]) {
  for (int i = 0; i < 4; ++i)
    out[i] = (float)rgba[i] / 255.0f;
}

/* One frame cleared to rgba; with band_rows > 0 the top band_rows rows are
 * cleared to band inside the rendering (vkCmdClearAttachments). */
static bool vk_frame(tlod_platform* p, const uint8_t rgba[4], uint32_t band_rows, const uint8_t band[4],
                     uint32_t* index) {
  float clear[4];
  to_float(rgba, clear);
  tlod_platform_frame f;
  if (!tlod_platform_begin_frame(p, clear, &f, s_err, sizeof s_err) || !f.command_buffer) return false;
  if (band_rows) {
    uint32_t w, h;
    tlod_platform_size(p, &w, &h);
    VkClearAttachment a = {.aspectMask = VK_IMAGE_ASPECT_COLOR_BIT, .colorAttachment = 0};
    to_float(band, a.clearValue.color.float32);
    VkClearRect r = {.rect = {{0, 0}, {w, band_rows}}, .baseArrayLayer = 0, .layerCount = 1};
    vkCmdClearAttachments((VkCommandBuffer)f.command_buffer, 1, &a, 1, &r);
  }
  if (index) *index = f.frame_index;
  double ms = -1;
  if (!tlod_platform_end_frame(p, &ms, s_err, sizeof s_err)) return false;
  return ms >= 0;
}

TEST(vk_headless_describe_and_info) {
  tlod_platform* p = vk_platform(64, 48);
  CHECK_MSG(p, "%s", s_err);
  char buf[256];
  tlod_platform_describe(p, buf, sizeof buf);
  printf("  %s\n", buf);
  bool named = strstr(buf, "Vulkan headless, ") == buf && strstr(buf, "Vulkan 1.") && strstr(buf, ", 64x48");
  tlod_platform_vk vk;
  bool info = tlod_platform_vk_info(p, &vk);
  uint8_t px[64 * 48 * 4];
  bool early = tlod_platform_read_rgba(p, px);
  tlod_platform_destroy(p);
  CHECK_MSG(named, "%s", buf);
  CHECK(info && vk.instance && vk.physical_device && vk.device && vk.queue);
  CHECK(vk.color_format == VK_FORMAT_R8G8B8A8_UNORM && vk.depth_format == VK_FORMAT_D32_SFLOAT);
  CHECK(vk.frames_in_flight == 2 && vk.host_query_reset && vk.tessellation); /* lavapipe has both */
  CHECK_MSG(!early, "read_rgba before the first frame succeeded");
}

TEST(vk_headless_clear_band_and_frames) {
  tlod_platform* p = vk_platform(64, 48);
  CHECK_MSG(p, "%s", s_err);
  static uint8_t px[64 * 48 * 4];
  const uint8_t base[4] = {51, 102, 204, 255}, band[4] = {255, 0, 17, 128};
  bool ok = vk_frame(p, base, 5, band, NULL) && tlod_platform_read_rgba(p, px);
  bool top = ok && all_pixels(px, 64, 48, band, 0, 5), rest = ok && all_pixels(px, 64, 48, base, 5, 48);
  bool frames = true, alternate = true;
  for (uint32_t i = 0; i < 10 && frames; ++i) {
    const uint8_t c[4] = {(uint8_t)(i * 25), (uint8_t)(255 - i * 20), (uint8_t)(i * 7), 255};
    uint32_t index = 99;
    frames = vk_frame(p, c, 0, NULL, &index) && tlod_platform_read_rgba(p, px) && all_pixels(px, 64, 48, c, 0, 48);
    alternate = alternate && index == (i + 1) % 2; /* the band frame was index 0 */
  }
  uint64_t messages = tlod_platform_validation_messages(p);
  tlod_platform_destroy(p);
  CHECK_MSG(ok, "%s", s_err);
  CHECK_MSG(top && rest, "band of 5 top rows, then the clear colour");
  CHECK_MSG(frames, "%s", s_err);
  CHECK(alternate);
  CHECK_MSG(messages == 0, "%llu validation messages", (unsigned long long)messages);
}

TEST(vk_headless_misuse) {
  tlod_platform* p = vk_platform(8, 8);
  CHECK_MSG(p, "%s", s_err);
  tlod_platform_frame f;
  char e1[256] = "", e2[256] = "";
  bool first = tlod_platform_begin_frame(p, NULL, &f, s_err, sizeof s_err);
  bool second = tlod_platform_begin_frame(p, NULL, &f, e1, sizeof e1);
  bool resized = tlod_platform_resize(p, 16, 16, e2, sizeof e2); /* inside the frame */
  double inside = tlod_platform_finish(p);
  bool ended = tlod_platform_end_frame(p, NULL, s_err, sizeof s_err);
  double finished = tlod_platform_finish(p);
  bool again = tlod_platform_end_frame(p, NULL, s_err, sizeof s_err);
  uint64_t messages = tlod_platform_validation_messages(p);
  tlod_platform_destroy(p);
  CHECK(first && ended);
  CHECK_MSG(!second && strstr(e1, "not ended"), "%s", e1);
  CHECK_MSG(!resized && strstr(e2, "inside a frame"), "%s", e2);
  CHECK(!again);
  CHECK_MSG(inside < 0 && finished >= 0, "finish inside a frame %g, after %g", inside, finished);
  CHECK_MSG(messages == 0, "%llu validation messages", (unsigned long long)messages);
}

TEST(vk_headless_resize) {
  tlod_platform* p = vk_platform(32, 32);
  CHECK_MSG(p, "%s", s_err);
  static uint8_t px[80 * 20 * 4];
  const uint8_t a[4] = {10, 20, 30, 255}, b[4] = {200, 150, 100, 50}, band[4] = {0, 255, 0, 255};
  bool first = vk_frame(p, a, 0, NULL, NULL) && tlod_platform_read_rgba(p, px) && all_pixels(px, 32, 32, a, 0, 32);
  bool resized = tlod_platform_resize(p, 80, 20, s_err, sizeof s_err);
  uint32_t w = 0, h = 0;
  tlod_platform_size(p, &w, &h);
  bool stale = resized && tlod_platform_read_rgba(p, px); /* the old frame is gone */
  bool second = resized && vk_frame(p, b, 3, band, NULL) && tlod_platform_read_rgba(p, px) &&
                all_pixels(px, 80, 20, band, 0, 3) && all_pixels(px, 80, 20, b, 3, 20);
  uint64_t messages = tlod_platform_validation_messages(p);
  tlod_platform_destroy(p);
  CHECK_MSG(first, "%s", s_err);
  CHECK_MSG(resized && w == 80 && h == 20, "%s (size %ux%u)", s_err, w, h);
  CHECK_MSG(!stale, "read_rgba after resize returned the old frame");
  CHECK_MSG(second, "%s", s_err);
  CHECK_MSG(messages == 0, "%llu validation messages", (unsigned long long)messages);
}

/* Runs last among the Vulkan tests: every platform is destroyed by now. */
TEST(vk_no_messages_over_destruction) {
  uint64_t total = tlod_platform_validation_messages(NULL);
  CHECK_MSG(total == 0, "%llu validation messages in the process", (unsigned long long)total);
}

/* The zero counts above mean something: a command the layer must reject
 * (vkCmdSetViewport with no viewport) is printed and counted, on the
 * platform and in the process total. */
TEST(vk_validation_is_live) {
  tlod_platform* p = vk_platform(8, 8);
  CHECK_MSG(p, "%s", s_err);
  uint64_t before = tlod_platform_validation_messages(NULL);
  tlod_platform_frame f;
  bool ok = tlod_platform_begin_frame(p, NULL, &f, s_err, sizeof s_err);
  if (ok) vkCmdSetViewport((VkCommandBuffer)f.command_buffer, 0, 0, NULL);
  ok = ok && tlod_platform_end_frame(p, NULL, s_err, sizeof s_err);
  uint64_t mine = tlod_platform_validation_messages(p);
  tlod_platform_destroy(p);
  uint64_t after = tlod_platform_validation_messages(NULL);
  CHECK_MSG(ok, "%s", s_err);
  CHECK_MSG(mine >= 1 && after >= before + mine, "platform %llu, process %llu -> %llu", (unsigned long long)mine,
            (unsigned long long)before, (unsigned long long)after);
}

TEST(vk_missing_layer_names_package) {
  char* old = getenv("VK_LAYER_PATH") ? strdup(getenv("VK_LAYER_PATH")) : NULL;
  setenv("VK_LAYER_PATH", "/nonexistent-tesslod-layers", 1);
  tlod_platform* p = NULL;
  char err[512] = "";
  tlod_platform_desc d = {.width = 8, .height = 8, .api = TLOD_PLATFORM_VULKAN, .validation = true};
  bool made = tlod_platform_create(&d, &p, err, sizeof err);
  if (old)
    setenv("VK_LAYER_PATH", old, 1);
  else
    unsetenv("VK_LAYER_PATH");
  free(old);
  tlod_platform_destroy(p);
  CHECK_MSG(!made && !p, "created without the layer");
  CHECK_MSG(strstr(err, "VK_LAYER_KHRONOS_validation") && strstr(err, "vulkan-validationlayers"), "%s", err);
}

TEST(gl_begin_frame_clears_and_resizes) {
#if TLOD_TEST_HAS_GL
  tlod_platform* p = NULL;
  bool made = tlod_platform_create(&(tlod_platform_desc){.width = 16, .height = 16}, &p, s_err, sizeof s_err);
  CHECK_MSG(made, "no GL context: %s", s_err);
  static uint8_t px[16 * 16 * 4]; /* the larger of 16 x 16 and 20 x 10 */
  const uint8_t a[4] = {51, 102, 204, 255}, b[4] = {255, 0, 17, 128};
  float fa[4], fb[4];
  to_float(a, fa);
  to_float(b, fb);
  tlod_platform_frame f = {.command_buffer = &f, .frame_index = 7};
  double ms = -1;
  bool first = tlod_platform_begin_frame(p, fa, &f, s_err, sizeof s_err) && !f.command_buffer && f.frame_index == 0 &&
               tlod_platform_end_frame(p, &ms, s_err, sizeof s_err) && ms == 0 && tlod_platform_read_rgba(p, px) &&
               all_pixels(px, 16, 16, a, 0, 16);
  bool resized = tlod_platform_resize(p, 20, 10, s_err, sizeof s_err);
  uint32_t w = 0, h = 0;
  tlod_platform_size(p, &w, &h);
  bool second = resized && tlod_platform_begin_frame(p, fb, &f, s_err, sizeof s_err) &&
                tlod_platform_read_rgba(p, px) && all_pixels(px, 20, 10, b, 0, 10);
  bool finished = tlod_platform_finish(p) >= 0;
  bool no_vk = !tlod_platform_vk_info(p, &(tlod_platform_vk){0}) && tlod_platform_validation_messages(p) == 0;
  tlod_platform_destroy(p);
  CHECK_MSG(first, "%s", s_err);
  CHECK_MSG(resized && w == 20 && h == 10, "%s (size %ux%u)", s_err, w, h);
  CHECK_MSG(second, "%s", s_err);
  CHECK(no_vk && finished);
#else
  printf("  GL not built (TLOD_BACKEND_GL=OFF): the GL mode is not checked\n");
#endif
}

int main(void) {
  RUN(vk_headless_describe_and_info);
  RUN(vk_headless_clear_band_and_frames);
  RUN(vk_headless_misuse);
  RUN(vk_headless_resize);
  RUN(vk_no_messages_over_destruction);
  RUN(vk_validation_is_live);
  RUN(vk_missing_layer_names_package);
  RUN(gl_begin_frame_clears_and_resizes);
  if (_test_failed) {
    printf("%d passed, %d failed\n", _test_passed, _test_failed);
    fflush(stdout);
    _Exit(1); /* early returns leave objects behind: no LeakSanitizer noise over the message */
  }
  TEST_END();
}
