/*
 * vk_window_test.c -- the platform helper's Vulkan window mode (GLFW
 * window, surface, FIFO swapchain), run under xvfb-run by ctest. Public API
 * only. FAILS (never skips) when the window cannot be made, with the
 * platform's message (e.g. DISPLAY not set).
 *
 *   - describe names "Vulkan window", vk_info gives the swapchain's format;
 *   - a cleared frame reads back (the swapchain image, copied in
 *     end_frame) as the exact clear colour in R, G, B, A order (the
 *     swapchain is B8G8R8A8 on lavapipe: the swizzle is checked);
 *   - resize gives a swapchain of the new size and exact pixels there;
 *   - the window resized behind the platform's back (Xlib, as a window
 *     manager or the user would): the next begin_frame recreates the
 *     swapchain at the new size (out of date / size changed), exact pixels;
 *   - 20 frames presented, the frame index alternating; zero validation
 *     messages, also over destruction.
 */
#define _POSIX_C_SOURCE 200809L

#include <X11/Xlib.h>
#include <stdint.h>
#include <string.h>
#include <vulkan/vulkan.h>

#include "test.h"
#include "tlod_platform.h"

static char s_err[512];

static bool frame_reads(tlod_platform* p, const uint8_t rgba[4], uint32_t* index) {
  float c[4];
  for (int i = 0; i < 4; ++i)
    c[i] = (float)rgba[i] / 255.0f;
  tlod_platform_frame f;
  if (!tlod_platform_begin_frame(p, c, &f, s_err, sizeof s_err)) return false;
  if (index) *index = f.frame_index;
  if (!tlod_platform_end_frame(p, NULL, s_err, sizeof s_err)) return false;
  uint32_t w, h;
  tlod_platform_size(p, &w, &h);
  uint8_t* px = malloc((size_t)w * h * 4);
  bool ok = px && tlod_platform_read_rgba(p, px);
  for (size_t i = 0; ok && i < (size_t)w * h; ++i)
    if (memcmp(px + i * 4, rgba, 4) != 0) {
      snprintf(s_err, sizeof s_err, "pixel %zu = %u %u %u %u", i, px[i * 4], px[i * 4 + 1], px[i * 4 + 2],
               px[i * 4 + 3]);
      ok = false;
    }
  free(px);
  tlod_platform_swap(p);
  return ok;
}

/* The X window titled name under w (depth first), or 0. */
static Window find_window(Display* d, Window w, const char* name) {
  char* title = NULL;
  if (XFetchName(d, w, &title) && title) {
    bool match = strcmp(title, name) == 0;
    XFree(title);
    if (match) return w;
  }
  Window root, parent, *kids = NULL, found = 0;
  unsigned n = 0;
  if (!XQueryTree(d, w, &root, &parent, &kids, &n)) return 0;
  for (unsigned i = 0; i < n && !found; ++i)
    found = find_window(d, kids[i], name);
  if (kids) XFree(kids);
  return found;
}

/* Resizes the window titled name through a connection of our own. */
static bool resize_from_outside(const char* name, unsigned w, unsigned h) {
  Display* d = XOpenDisplay(NULL);
  if (!d) return false;
  Window win = find_window(d, DefaultRootWindow(d), name);
  if (win) XResizeWindow(d, win, w, h);
  XSync(d, False);
  XCloseDisplay(d);
  return win != 0;
}

TEST(vk_window_frames_resize) {
  tlod_platform* p = NULL;
  tlod_platform_desc d = {
      .width = 96, .height = 64, .window = true, .api = TLOD_PLATFORM_VULKAN, .validation = true, .title = "vk test"};
  bool made = tlod_platform_create(&d, &p, s_err, sizeof s_err);
  CHECK_MSG(made, "no Vulkan window: %s", s_err);
  char buf[256];
  tlod_platform_describe(p, buf, sizeof buf);
  printf("  %s\n", buf);
  tlod_platform_vk vk;
  bool info = tlod_platform_vk_info(p, &vk);
  const uint8_t a[4] = {51, 102, 204, 255}, b[4] = {255, 17, 0, 255};
  bool first = frame_reads(p, a, NULL);
  bool resized = first && tlod_platform_resize(p, 120, 80, s_err, sizeof s_err);
  uint32_t w = 0, h = 0;
  tlod_platform_size(p, &w, &h);
  bool second = resized && frame_reads(p, b, NULL);
  bool frames = second, alternate = true;
  for (uint32_t i = 0; i < 20 && frames; ++i) {
    uint32_t index = 99;
    const uint8_t c[4] = {(uint8_t)(i * 12), 40, (uint8_t)(255 - i * 12), 255};
    frames = frame_reads(p, c, &index);
    alternate = alternate && index == i % 2;
  }
  bool outside = frames && resize_from_outside("vk test", 140, 90);
  const uint8_t c[4] = {9, 99, 199, 255};
  bool recreated = outside && frame_reads(p, c, NULL);
  uint32_t w2 = 0, h2 = 0;
  tlod_platform_size(p, &w2, &h2);
  bool closed = tlod_platform_should_close(p);
  uint64_t messages = tlod_platform_validation_messages(p);
  tlod_platform_destroy(p);
  uint64_t total = tlod_platform_validation_messages(NULL);
  CHECK_MSG(strstr(buf, "Vulkan window, ") == buf, "%s", buf);
  CHECK(info && vk.device && vk.frames_in_flight == 2 && vk.depth_format == VK_FORMAT_D32_SFLOAT);
  /* lavapipe's X11 surface: BGRA, so the exact RGBA read-backs below check the swizzle */
  CHECK_MSG(vk.color_format == VK_FORMAT_B8G8R8A8_UNORM, "swapchain format %u", vk.color_format);
  CHECK_MSG(first, "%s", s_err);
  CHECK_MSG(resized && w == 120 && h == 80, "%s (size %ux%u)", s_err, w, h);
  CHECK_MSG(second && frames, "%s", s_err);
  CHECK(alternate && !closed);
  CHECK_MSG(outside, "no X window titled \"vk test\"");
  CHECK_MSG(recreated && w2 == 140 && h2 == 90, "%s (size %ux%u after the outside resize)", s_err, w2, h2);
  CHECK_MSG(messages == 0 && total == 0, "%llu validation messages (%llu in the process)", (unsigned long long)messages,
            (unsigned long long)total);
}

int main(void) {
  RUN(vk_window_frames_resize);
  if (_test_failed) {
    printf("%d passed, %d failed\n", _test_passed, _test_failed);
    fflush(stdout);
    _Exit(1);
  }
  TEST_END();
}
