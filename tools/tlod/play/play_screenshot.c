/* tlod play -- screenshots: the frame read back from GL, encoded as PNG by
 * Debian's libstb into an atomic file (complete or not at all). */
#include <stdio.h>

#include "cli.h"
#include "play_run.h"
#include "play_run_folder.h"

#if TLOD_HAS_GL
#include <stb_image_write.h>

#include "tlod_atomic_file.h"
#include "tlod_platform.h"

static void png_sink(void* context, void* data, int size) {
  if (size > 0) fwrite(data, 1, (size_t)size, context); /* errors are sticky: checked at the end */
}

/* 8-bit RGBA, rows top first. */
static bool png_write(const char* path, uint32_t w, uint32_t h, const uint8_t* rgba, char* err, size_t err_size) {
  tlod_atomic_file a;
  if (!tlod_atomic_file_begin(&a, path, err, err_size)) return false;
  stbi_flip_vertically_on_write(0); /* libstb's process-wide flag */
  bool encoded = stbi_write_png_to_func(png_sink, a.file, (int)w, (int)h, 4, rgba, (int)(w * 4)) != 0;
  if (!encoded) snprintf(err, err_size, "%s: PNG encoding (%ux%u) failed (out of memory?)", path, w, h);
  return tlod_atomic_file_end(&a, encoded, err, err_size);
}

int play_screenshot(play_run* r, play_frame* fr, double run_start) {
  double t0 = cli_now_ms();
  snprintf(fr->screenshot, sizeof(fr->screenshot), "screenshots/frame_%05u.png", fr->frame);
  char path[PLAY_PATH_MAX + 64], err[PLAY_PATH_MAX + 512] = "cannot read the frame back";
  play_path_join(path, sizeof(path), r->run_dir, fr->screenshot);
  if (!tlod_platform_read_rgba(r->platform, r->pixels) ||
      !png_write(path, r->o->width, r->o->height, r->pixels, err, sizeof(err))) {
    fr->screenshot[0] = '\0';
    return cli_error(CLI_FAILED, "screenshot of frame %u: %s", fr->frame, err);
  }
  fr->screenshot_at_ms = t0 - run_start;
  fr->screenshot_ms = cli_now_ms() - t0;
  return CLI_OK;
}
#else
int play_screenshot(play_run* r, play_frame* fr, double run_start) {
  (void)r, (void)fr, (void)run_start;
  return cli_error(CLI_FAILED, "screenshots need the GL backend");
}
#endif
