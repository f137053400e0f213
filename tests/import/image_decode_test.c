/* image_decode_test.c -- the PNG/JPEG decoders of the importers (tools/import/image_decode.h):
 * the size rule is applied from the header, against the pixel limit and the budget, before
 * any pixel memory exists (budget.used stays 0), truncated files fail cleanly, and what
 * decodes has the pixels its file was made from. Owned by the import/export layer. */
#define _POSIX_C_SOURCE 200809L /* setrlimit */
#include <stdint.h>
#include <sys/resource.h>
#include <zlib.h>

#include "image_decode.h"
#include "test.h"

static unsigned char* read_data(const char* rel, size_t* size) {
  char path[1024];
  snprintf(path, sizeof path, "%s/%s", TLOD_TEST_DATA_DIR, rel);
  FILE* f = fopen(path, "rb");
  if (!f) return NULL;
  unsigned char* d = malloc(1 << 20);
  *size = d ? fread(d, 1, 1 << 20, f) : 0;
  fclose(f);
  return d;
}

static void put_be32(unsigned char* p, uint32_t v) {
  p[0] = (unsigned char)(v >> 24), p[1] = (unsigned char)(v >> 16), p[2] = (unsigned char)(v >> 8);
  p[3] = (unsigned char)v;
}

/* The Duck's PNG with IHDR claiming w x h (CRC recomputed, so only the size is wrong). */
static unsigned char* png_claiming(uint32_t w, uint32_t h, size_t* size) {
  unsigned char* d = read_data("glTF-Sample-Models/Duck/glTF/DuckCM.png", size);
  if (!d) return NULL;
  put_be32(d + 16, w);
  put_be32(d + 20, h);
  put_be32(d + 29, (uint32_t)crc32(0, d + 12, 17)); /* over "IHDR" + 13 data bytes */
  return d;
}

/* A JPEG with its SOF marker claiming w x h (16-bit fields). */
static unsigned char* jpeg_claiming(const char* rel, uint16_t w, uint16_t h, size_t* size) {
  unsigned char* d = read_data(rel, size);
  for (size_t i = 2; d && i + 9 < *size; ++i)
    if (d[i] == 0xFF && (d[i + 1] == 0xC0 || d[i + 1] == 0xC2)) {
      d[i + 5] = (unsigned char)(h >> 8), d[i + 6] = (unsigned char)h;
      d[i + 7] = (unsigned char)(w >> 8), d[i + 8] = (unsigned char)w;
      return d;
    }
  return d;
}

static _tlod_image_status decode(const unsigned char* d, size_t n, size_t limit, _tlod_import_budget* b,
                                 _tlod_image* img) {
  *b = (_tlod_import_budget){limit, 0, false};
  char detail[128];
  return _tlod_image_decode(d, n, b, img, detail, sizeof detail);
}

TEST(png_past_the_pixel_limit_refused_before_allocating) {
  size_t n = 0;
  unsigned char* d = png_claiming(9000, 9000, &n); /* 81M pixels > 64M */
  CHECK(d != NULL);
  _tlod_import_budget b;
  _tlod_image img;
  CHECK(decode(d, n, (size_t)4 << 30, &b, &img) == _TLOD_IMAGE_TOO_LARGE);
  CHECK(img.rgba == NULL && b.used == 0);
  free(d);
}

/* The order of check and allocation: with the address space capped, a decoder that
 * allocated first would get NULL and report OUT_OF_MEMORY; one that checks the header
 * first reports TOO_LARGE. (Not under ASan, whose shadow memory needs the address space.) */
TEST(pixel_limit_checked_before_any_allocation) {
#if defined(__SANITIZE_ADDRESS__)
  return;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  return;
#endif
#endif
  size_t n = 0;
  unsigned char* png = png_claiming(9000, 9000, &n);
  size_t m = 0;
  unsigned char* jpg = jpeg_claiming("images/rgb16.jpg", 65000, 65000, &m);
  struct rlimit old;
  CHECK(png && jpg && getrlimit(RLIMIT_AS, &old) == 0);
  struct rlimit cap = old;
  cap.rlim_cur = (rlim_t)1 << 30; /* far below the 324 MB x 3 + 16 GB the claims would take */
  CHECK(setrlimit(RLIMIT_AS, &cap) == 0);
  _tlod_import_budget b;
  _tlod_image img;
  const _tlod_image_status a = decode(png, n, (size_t)64 << 30, &b, &img);
  const _tlod_image_status c = decode(jpg, m, (size_t)64 << 30, &b, &img);
  setrlimit(RLIMIT_AS, &old);
  CHECK_MSG(a == _TLOD_IMAGE_TOO_LARGE && c == _TLOD_IMAGE_TOO_LARGE, "png %d jpeg %d", (int)a, (int)c);
  free(png);
  free(jpg);
}

TEST(png_past_the_budget_refused_before_allocating) {
  size_t n = 0;
  unsigned char* d = png_claiming(512, 512, &n);
  _tlod_import_budget b;
  _tlod_image img;
  CHECK(decode(d, n, 512 * 512 * 4, &b, &img) == _TLOD_IMAGE_OVER_BUDGET); /* + rows, overhead */
  CHECK(img.rgba == NULL && b.used == 0);
  CHECK(decode(d, n, (size_t)64 << 20, &b, &img) == _TLOD_IMAGE_OK);
  CHECK(img.width == 512 && img.height == 512 && b.used >= 512 * 512 * 4);
  free(img.rgba);
  free(d);
}

TEST(jpeg_past_the_pixel_limit_and_budget_refused_before_allocating) {
  size_t n = 0;
  unsigned char* d = jpeg_claiming("images/rgb16.jpg", 65000, 65000, &n);
  _tlod_import_budget b;
  _tlod_image img;
  CHECK(decode(d, n, (size_t)4 << 30, &b, &img) == _TLOD_IMAGE_TOO_LARGE);
  CHECK(img.rgba == NULL && b.used == 0);
  free(d);
  /* Progressive: the coefficient buffers count too (16 x 8 x (4 + 6) bytes + overhead). */
  d = read_data("images/prog16x8.jpg", &n);
  CHECK(decode(d, n, ((size_t)1 << 20) + 16 * 8 * 4 + 16, &b, &img) == _TLOD_IMAGE_OVER_BUDGET && b.used == 0);
  CHECK(decode(d, n, (size_t)8 << 20, &b, &img) == _TLOD_IMAGE_OK && img.width == 16 && img.height == 8);
  free(img.rgba);
  free(d);
}

TEST(truncated_files_fail_without_pixels) {
  size_t n = 0;
  unsigned char* d = png_claiming(512, 512, &n);
  _tlod_import_budget b;
  _tlod_image img;
  CHECK(decode(d, n / 2, (size_t)64 << 20, &b, &img) == _TLOD_IMAGE_CORRUPT && img.rgba == NULL);
  free(d);
  d = read_data("images/rgb16.jpg", &n);
  CHECK(decode(d, n * 2 / 3, (size_t)64 << 20, &b, &img) == _TLOD_IMAGE_CORRUPT && img.rgba == NULL);
  CHECK(decode(d, 2, (size_t)64 << 20, &b, &img) == _TLOD_IMAGE_UNKNOWN_FORMAT);
  free(d);
}

/* fuzz_image: a zTXt chunk whose length field (925 MB) runs past the 123-byte file made
 * png_read_info allocate it. Refused by the chunk scan before libpng sees the file. */
TEST(chunk_length_past_the_end_refused_before_libpng) {
  size_t n = 0;
  unsigned char* d = read_data("fuzz/fuzz_image/ztxt_length_past_end.png", &n);
  CHECK(d != NULL && n == 123);
  _tlod_import_budget b = {(size_t)64 << 20, 0, false};
  _tlod_image img;
  char detail[128];
  CHECK(_tlod_image_decode(d, n, &b, &img, detail, sizeof detail) == _TLOD_IMAGE_CORRUPT && img.rgba == NULL);
  CHECK_MSG(strstr(detail, "runs past the end") != NULL && b.used == 0, "%s", detail);
  free(d);
}

/* The JPEG's source pattern (README in tests/data/images), within JPEG's loss. */
TEST(jpeg_pixels_match_their_source) {
  size_t n = 0;
  unsigned char* d = read_data("images/rgb16.jpg", &n);
  _tlod_image img;
  _tlod_import_budget b;
  CHECK(decode(d, n, (size_t)8 << 20, &b, &img) == _TLOD_IMAGE_OK && img.width == 16 && img.height == 16);
  int worst = 0;
  for (uint32_t y = 0; y < 16; y += 3)
    for (uint32_t x = 0; x < 16; x += 3)
      for (int c = 0; c < 3; ++c) {
        const int want = c == 0 ? (int)x * 16 : c == 1 ? (int)y * 16 : 128;
        const int got = img.rgba[(y * 16 + x) * 4 + (uint32_t)c];
        const int diff = abs(got - want);
        if (diff > worst) worst = diff;
      }
  CHECK_MSG(worst <= 12, "worst difference %d", worst);
  CHECK(img.rgba[3] == 255);
  free(img.rgba);
  free(d);
}

int main(void) {
  RUN(png_past_the_pixel_limit_refused_before_allocating);
  RUN(pixel_limit_checked_before_any_allocation);
  RUN(png_past_the_budget_refused_before_allocating);
  RUN(jpeg_past_the_pixel_limit_and_budget_refused_before_allocating);
  RUN(truncated_files_fail_without_pixels);
  RUN(chunk_length_past_the_end_refused_before_libpng);
  RUN(jpeg_pixels_match_their_source);
  TEST_END();
}
