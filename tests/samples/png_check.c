/*
 * png_check.c -- checks a sample's PNG for real content, independently of
 * the sample (stb_image decodes it; nothing of tesslod is linked).
 *
 *   png_check FILE [CHECK...]
 *     --color FX FY R G B   the pixel at (FX, FY) (fractions of width and
 *                           height, from the top left) is R G B within 40
 *                           per channel (the engine's own geometry; the
 *                           clear colour at a corner)
 *     --object FX FY R G B  the 5x5 box of pixels around (FX, FY) holds
 *                           no pixel within 40 of R G B (the background)
 *                           and has varying colours (shading, not a flat fill)
 *     --not FX FY R G B     the pixel at (FX, FY) is not within 40 of R G B
 *                           (a flat-shaded object over that background)
 *     --two-tone FX FY      in the central quarter box around (FX, FY),
 *                           over 5% of pixels are clearly blue (b > r + 60)
 *                           and over 5% clearly yellow-orange (r > b + 60):
 *                           the samples' checker material ran
 * Exit 0 when every check passes; each failure is printed.
 */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>

typedef struct image {
  unsigned char* px;
  int w, h;
} image;

static const unsigned char* at(const image* im, double fx, double fy) {
  int x = (int)(fx * (im->w - 1) + 0.5), y = (int)(fy * (im->h - 1) + 0.5);
  return im->px + 4 * ((size_t)y * (size_t)im->w + (size_t)x);
}

static bool near_rgb(const unsigned char* p, int r, int g, int b) {
  return abs(p[0] - r) <= 40 && abs(p[1] - g) <= 40 && abs(p[2] - b) <= 40;
}

static bool check_color(const image* im, double fx, double fy, int r, int g, int b) {
  const unsigned char* p = at(im, fx, fy);
  if (near_rgb(p, r, g, b)) return true;
  printf("FAIL --color %.2f %.2f: pixel is %d %d %d, want %d %d %d\n", fx, fy, p[0], p[1], p[2], r, g, b);
  return false;
}

static bool check_not(const image* im, double fx, double fy, int r, int g, int b) {
  const unsigned char* p = at(im, fx, fy);
  if (!near_rgb(p, r, g, b)) return true;
  printf("FAIL --not %.2f %.2f: pixel is %d %d %d, the colour it must not be\n", fx, fy, p[0], p[1], p[2]);
  return false;
}

static bool check_object(const image* im, double fx, double fy, int r, int g, int b) {
  int cx = (int)(fx * (im->w - 1)), cy = (int)(fy * (im->h - 1)), background = 0, lo = 255 * 3, hi = 0;
  for (int y = cy - 2; y <= cy + 2; ++y)
    for (int x = cx - 2; x <= cx + 2; ++x) {
      const unsigned char* p = im->px + 4 * ((size_t)y * (size_t)im->w + (size_t)x);
      int sum = p[0] + p[1] + p[2];
      background += near_rgb(p, r, g, b);
      lo = sum < lo ? sum : lo;
      hi = sum > hi ? sum : hi;
    }
  if (background == 0 && hi > lo) return true;
  printf("FAIL --object %.2f %.2f: %d of 25 pixels are background, brightness %d..%d\n", fx, fy, background, lo, hi);
  return false;
}

static bool check_two_tone(const image* im, double fx, double fy) {
  int cx = (int)(fx * im->w), cy = (int)(fy * im->h), hw = im->w / 8, hh = im->h / 8, blue = 0, warm = 0, n = 0;
  for (int y = cy - hh; y < cy + hh; ++y)
    for (int x = cx - hw; x < cx + hw; ++x, ++n) {
      const unsigned char* p = im->px + 4 * ((size_t)y * (size_t)im->w + (size_t)x);
      blue += p[2] > p[0] + 60;
      warm += p[0] > p[2] + 60;
    }
  if (blue * 20 > n && warm * 20 > n) return true;
  printf("FAIL --two-tone %.2f %.2f: %d blue and %d warm of %d pixels\n", fx, fy, blue, warm, n);
  return false;
}

static bool run_check(const image* im, char** a, int left, int* used) {
  bool is_color = !strcmp(a[0], "--color"), is_object = !strcmp(a[0], "--object"), is_not = !strcmp(a[0], "--not");
  if ((is_color || is_object || is_not) && left >= 6) {
    *used = 6;
    double fx = atof(a[1]), fy = atof(a[2]);
    int r = atoi(a[3]), g = atoi(a[4]), b = atoi(a[5]);
    if (is_not) return check_not(im, fx, fy, r, g, b);
    return is_color ? check_color(im, fx, fy, r, g, b) : check_object(im, fx, fy, r, g, b);
  }
  if (!strcmp(a[0], "--two-tone") && left >= 3) {
    *used = 3;
    return check_two_tone(im, atof(a[1]), atof(a[2]));
  }
  printf("FAIL: unknown or incomplete check '%s'\n", a[0]);
  *used = left;
  return false;
}

int main(int argc, char** argv) {
  if (argc < 3) {
    fprintf(stderr, "usage: png_check FILE CHECK...\n");
    return 2;
  }
  image im;
  int channels = 0;
  im.px = stbi_load(argv[1], &im.w, &im.h, &channels, 4);
  if (!im.px || im.w < 16 || im.h < 16) {
    printf("FAIL: %s: %s\n", argv[1], im.px ? "smaller than 16x16" : stbi_failure_reason());
    stbi_image_free(im.px);
    return 1;
  }
  int failures = 0, checks = 0;
  for (int i = 2; i < argc; ++checks) {
    int used = 1;
    failures += !run_check(&im, argv + i, argc - i, &used);
    i += used;
  }
  printf("%s: %dx%d, %d checks, %d failed\n", argv[1], im.w, im.h, checks, failures);
  stbi_image_free(im.px);
  return failures ? 1 : 0;
}
