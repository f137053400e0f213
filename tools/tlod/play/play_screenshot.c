/* tlod play -- screenshots: the last ended frame read back from the
 * platform (GL or Vulkan), with the field's legend when one is coloured, and written by the platform's PNG writer (an
 * atomic file: complete or not at all). */
#include <stdio.h>

#include "cli.h"
#include "field/field_legend.h"
#include "play_run.h"
#include "play_run_folder.h"

#if TLOD_HAS_GL || TLOD_HAS_VULKAN
#include "tlod_platform.h"

int play_screenshot(play_run* r, play_frame* fr, double run_start) {
  double t0 = cli_now_ms();
  snprintf(fr->screenshot, sizeof(fr->screenshot), "screenshots/frame_%05u.png", fr->frame);
  char path[PLAY_PATH_MAX + 64], err[PLAY_PATH_MAX + 512] = "cannot read the frame back";
  play_path_join(path, sizeof(path), r->run_dir, fr->screenshot);
  bool read = tlod_platform_read_rgba(r->platform, r->pixels);
  if (read && r->scene->field.on) field_legend_draw(&r->scene->field.sel, r->pixels, r->width, r->height);
  if (!read || !tlod_png_write(path, r->width, r->height, r->pixels, err, sizeof(err))) {
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
  return cli_error(CLI_FAILED, "screenshots need the GL or Vulkan backend");
}
#endif
