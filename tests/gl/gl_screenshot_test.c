/*
 * gl_screenshot_test.c -- screenshots of a rendered frame and the platform
 * module's failure paths (owned by the GL tests). Public API only.
 *
 *   - a GL-backend frame (160 x 120, not square, so width / height swaps
 *     show) read with tlod_platform_read_rgba (top row first) equals
 *     tlod_device_read_image (bottom row first) flipped, exactly;
 *   - tlod_png_write produces a valid PNG: the 8-byte signature, an IHDR
 *     chunk first with the width, height, bit depth 8 and colour type 6
 *     (RGBA), and stb_image decodes it back to the same bytes;
 *   - writing into a missing directory, or over a directory, fails with a
 *     message and leaves no file (no half-written target, no temp file);
 *     rewriting an existing file replaces it;
 *   - window mode without DISPLAY fails with a message naming DISPLAY, and
 *     headless creation still works afterwards.
 */
#define _POSIX_C_SOURCE 200809L

#include <dirent.h>
#include <stb_image.h>
#include <sys/stat.h>
#include <unistd.h>

#include "gl_test.h"

#define W 160
#define H 120

static uint32_t be32(const uint8_t* p) {
  return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | (uint32_t)p[3];
}

/* Reads up to size bytes of a file; returns the count (0 if missing). */
static size_t read_head(const char* path, uint8_t* buf, size_t size) {
  FILE* f = fopen(path, "rb");
  if (!f) return 0;
  size_t n = fread(buf, 1, size, f);
  fclose(f);
  return n;
}

/* Entries of dir other than . and .., names joined into list. */
static int list_dir(const char* dir, char* list, size_t size) {
  DIR* d = opendir(dir);
  int n = 0;
  list[0] = '\0';
  if (!d) return -1;
  struct dirent* e;
  while ((e = readdir(d)) != NULL) {
    if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) continue;
    n++;
    size_t used = strlen(list);
    snprintf(list + used, size - used, "%s%s", used ? ", " : "", e->d_name);
  }
  closedir(d);
  return n;
}

static void check_png(const char* path, uint32_t w, uint32_t h, const uint8_t* rgba) {
  uint8_t head[33];
  size_t n = read_head(path, head, sizeof head);
  static const uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  CHECK_MSG(n == sizeof head, "%s: only %zu bytes", path, n);
  CHECK_MSG(memcmp(head, signature, 8) == 0, "%s: bad PNG signature", path);
  CHECK_MSG(be32(head + 8) == 13 && memcmp(head + 12, "IHDR", 4) == 0, "%s: first chunk is not a 13-byte IHDR", path);
  CHECK_MSG(be32(head + 16) == w && be32(head + 20) == h, "%s: IHDR says %ux%u, expected %ux%u", path, be32(head + 16),
            be32(head + 20), w, h);
  CHECK_MSG(head[24] == 8 && head[25] == 6, "%s: bit depth %u colour type %u, expected 8 / 6 (RGBA)", path, head[24],
            head[25]);
  int dw = 0, dh = 0, comp = 0;
  uint8_t* decoded = stbi_load(path, &dw, &dh, &comp, 4);
  CHECK_MSG(decoded, "%s: stb_image cannot decode it: %s", path, stbi_failure_reason());
  bool same = dw == (int)w && dh == (int)h && comp == 4 && memcmp(decoded, rgba, (size_t)w * h * 4) == 0;
  stbi_image_free(decoded);
  CHECK_MSG(same, "%s: decoded %dx%d (%d channels) differs from the written pixels", path, dw, dh, comp);
}

TEST(test_screenshot) {
  gl_session gs;
  shape sph;
  fixture fx;
  tlod_scheduler* sch;
  CALL(sphere_scene_open(&gs, &sph, &fx, &sch, W, H, "gl_screenshot", TLOD_SURFACE_PN));
  uint32_t pw = 0, ph = 0;
  tlod_platform_size(gs.platform, &pw, &ph);
  CHECK(pw == W && ph == H && tlod_platform_framebuffer(gs.platform) != 0);
  tlod_result r;
  camera cam = camera_look(1.2, -2.6, 1.4, 0, 0, 0.2, 45, W, H);
  tlod_view_desc v = make_view(&cam);
  const tlod_draw_list* dl = plan(&fx, sch, &v, 0.0f);
  CHECK(dl);
  tlod_platform_bind(gs.platform);
  clear_frame(W, H);
  one_draw frame;
  one_draw_make(&frame, fx.ds, dl, &v);
  frame.desc.wireframe = true;
  CHECK(tlod_device_draw(gs.dev, &frame.desc) == TLOD_SUCCESS);

  uint8_t* top_first = malloc(4 * W * H);
  uint8_t* bottom_first = malloc(4 * W * H);
  CHECK(top_first && bottom_first);
  CHECK(tlod_platform_read_rgba(gs.platform, top_first));
  r = tlod_device_read_image(gs.dev, W, H, bottom_first);
  CHECK_MSG(r == TLOD_SUCCESS, "tlod_device_read_image: %s: %s", tlod_result_string(r),
            tlod_context_last_error(gs.ctx));
  uint32_t covered = 0, rows_differ = 0;
  for (uint32_t y = 0; y < H; ++y) {
    rows_differ += memcmp(top_first + (size_t)y * W * 4, bottom_first + (size_t)(H - 1 - y) * W * 4, W * 4) != 0;
    for (uint32_t x = 0; x < W; ++x)
      covered += !is_background(top_first + 4 * ((size_t)y * W + x));
  }
  printf("  frame %ux%u: %u pixels covered; gs.platform vs device read-back: %u rows differ\n", W, H, covered,
         rows_differ);
  CHECK_MSG(covered > 2000, "the frame has only %u covered pixels", covered);
  CHECK_MSG(rows_differ == 0, "%u rows differ between tlod_platform_read_rgba (flipped) and tlod_device_read_image",
            rows_differ);

  /* a scratch directory */
  const char* tmp = getenv("TMPDIR");
  char dir[512];
  snprintf(dir, sizeof dir, "%s/tlod_screenshot_XXXXXX", tmp && tmp[0] ? tmp : "/tmp");
  CHECK_MSG(mkdtemp(dir), "mkdtemp %s failed", dir);
  char path[640], list[1024];
  snprintf(path, sizeof path, "%s/frame.png", dir);
  char err[512] = "";
  bool ok = tlod_png_write(path, W, H, top_first, err, sizeof err);
  CHECK_MSG(ok, "tlod_png_write %s: %s", path, err);
  CALL(check_png(path, W, H, top_first));
  struct stat st;
  CHECK(stat(path, &st) == 0);
  printf("  %s: %lld bytes, valid PNG %ux%u RGBA, decodes to the same pixels\n", path, (long long)st.st_size, W, H);

  /* rewriting replaces the file */
  const uint8_t tiny[2 * 2 * 4] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128};
  ok = tlod_png_write(path, 2, 2, tiny, err, sizeof err);
  CHECK_MSG(ok, "rewriting %s: %s", path, err);
  CALL(check_png(path, 2, 2, tiny));

  /* a missing directory: clean failure, nothing left */
  char missing[700];
  snprintf(missing, sizeof missing, "%s/no/such/dir/frame.png", dir);
  err[0] = '\0';
  ok = tlod_png_write(missing, W, H, top_first, err, sizeof err);
  printf("  missing directory: \"%s\"\n", err);
  CHECK_MSG(!ok, "writing %s succeeded", missing);
  CHECK_MSG(err[0] != '\0', "no error message");
  CHECK_MSG(access(missing, F_OK) != 0, "%s exists after a failed write", missing);
  /* over a directory: the rename fails, the temp file must go */
  char subdir[700];
  snprintf(subdir, sizeof subdir, "%s/adir", dir);
  CHECK(mkdir(subdir, 0700) == 0);
  err[0] = '\0';
  ok = tlod_png_write(subdir, W, H, top_first, err, sizeof err);
  printf("  target is a directory: \"%s\"\n", err);
  CHECK_MSG(!ok && err[0], "writing over the directory %s succeeded", subdir);
  int entries = list_dir(dir, list, sizeof list);
  CHECK_MSG(entries == 2, "after the failed writes %s holds %d entries (%s), expected frame.png and adir", dir, entries,
            list);
  /* invalid arguments */
  CHECK(!tlod_png_write(path, 0, H, top_first, err, sizeof err) && err[0]);
  CHECK(!tlod_png_write(path, W, H, NULL, err, sizeof err) && err[0]);
  CHECK(!tlod_png_write(NULL, W, H, top_first, NULL, 0));
  CALL(check_png(path, 2, 2, tiny)); /* untouched by the failed calls */
  remove(path);
  rmdir(subdir);
  CHECK_MSG(rmdir(dir) == 0, "cannot remove %s", dir);

  free(top_first);
  free(bottom_first);
  sphere_scene_close(&gs, &sph, &fx, sch);
}

TEST(test_platform_errors) {
  char err[512] = "";
  /* window mode with no X server */
  char* display = getenv("DISPLAY");
  char saved[256] = "";
  if (display) snprintf(saved, sizeof saved, "%s", display);
  unsetenv("DISPLAY");
  tlod_platform* p = (tlod_platform*)1;
  bool ok = tlod_platform_create(&(tlod_platform_desc){.width = 64, .height = 64, .window = true}, &p, err, sizeof err);
  if (saved[0]) setenv("DISPLAY", saved, 1);
  printf("  window mode without DISPLAY: \"%s\"\n", err);
  CHECK_MSG(!ok && p == NULL, "window mode without DISPLAY succeeded");
  CHECK_MSG(strstr(err, "DISPLAY") != NULL, "the message does not name DISPLAY: %s", err);
  /* invalid requests */
  CHECK(!tlod_platform_create(NULL, NULL, err, sizeof err) && err[0]);
  ok = tlod_platform_create(&(tlod_platform_desc){.width = 64, .height = 64, .samples = 1000}, &p, err, sizeof err);
  printf("  1000 samples: \"%s\"\n", err);
  CHECK_MSG(!ok && p == NULL && strstr(err, "GL_MAX_SAMPLES"), "1000 samples: %s", err);
  /* headless still works, with and without MSAA, two at once */
  tlod_platform *a = NULL, *b = NULL;
  ok = tlod_platform_create(&(tlod_platform_desc){.width = 32, .height = 16}, &a, err, sizeof err);
  CHECK_MSG(ok, "headless after failures: %s", err);
  ok = tlod_platform_create(&(tlod_platform_desc){.width = 16, .height = 8, .samples = 4}, &b, err, sizeof err);
  CHECK_MSG(ok, "headless 4x MSAA: %s", err);
  char desc[320];
  printf("  %s\n", tlod_platform_describe(b, desc, sizeof desc));
  uint8_t px[32 * 16 * 4];
  /* a: top half red, bottom half green (GL rows are bottom first) */
  tlod_platform_bind(a);
  glClearColor(1, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, 0, 32, 8);
  glClearColor(0, 1, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
  tlod_platform_bind(b);
  glClearColor(0, 0, 1, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  CHECK(tlod_platform_read_rgba(b, px));
  CHECK_MSG(px[0] == 0 && px[1] == 0 && px[2] == 255 && px[4 * (16 * 8 - 1) + 2] == 255, "MSAA read-back wrong");
  tlod_platform_destroy(b);
  tlod_platform_bind(a);
  CHECK(tlod_platform_read_rgba(a, px));
  CHECK_MSG(px[0] == 255 && px[1] == 0, "top row is not red: %u %u %u", px[0], px[1], px[2]);
  CHECK_MSG(px[4 * 32 * 15 + 1] == 255 && px[4 * 32 * 15] == 0, "bottom row is not green");
  double t0 = tlod_platform_time_ms(), t1 = tlod_platform_time_ms();
  CHECK(t1 >= t0 && t0 > 0);
  CHECK(!tlod_platform_should_close(a));
  tlod_platform_swap(a); /* no-op headless */
  tlod_platform_destroy(a);
  tlod_platform_destroy(NULL);
}

int main(void) {
  RUN(test_platform_errors);
  RUN(test_screenshot);
  GL_TEST_END();
}
