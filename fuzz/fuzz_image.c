/* fuzz_image.c -- the image decoders (tools/import/image_decode.h): the input is an image file;
 * its signature picks _tlod_png_decode or _tlod_jpeg_decode (anything else goes through the
 * dispatcher, which must refuse it). Contract: a status the header lists; on success
 * width x height within TLOD_IMPORT_MAX_IMAGE_PIXELS, taken from the budget, every pixel
 * byte readable (ASan); on failure no pixels and nothing leaked. */
#include <stdlib.h>

#include "fuzz_common.h"
#include "image_decode.h"

/* Small enough that libFuzzer's -malloc_limit_mb is never what stops a decode: the
 * budget must refuse first. */
#define FUZZ_IMAGE_BUDGET ((size_t)256 << 20)

static _tlod_image_status decode(const uint8_t* data, size_t size, _tlod_import_budget* b, _tlod_image* img) {
  char detail[128];
  const char* mime = _tlod_image_sniff(data, size);
  if (!mime) {
    const _tlod_image_status st = _tlod_image_decode(data, size, b, img, detail, sizeof detail);
    fuzz_check(st == _TLOD_IMAGE_UNKNOWN_FORMAT, "an input without a signature is refused as unknown");
    return st;
  }
  if (mime[6] == 'p') return _tlod_png_decode(data, size, b, img, detail, sizeof detail);
  return _tlod_jpeg_decode(data, size, b, img, detail, sizeof detail);
}

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  _tlod_import_budget budget = {FUZZ_IMAGE_BUDGET, 0, false};
  _tlod_image img = {0, 0, NULL};
  const _tlod_image_status st = decode(data, size, &budget, &img);
  fuzz_check(st >= _TLOD_IMAGE_OK && st <= _TLOD_IMAGE_OUT_OF_MEMORY, "status listed in image_decode.h");
  fuzz_check(budget.used <= budget.limit, "budget respected");
  if (st != _TLOD_IMAGE_OK) {
    fuzz_check(img.rgba == NULL, "no pixels on failure");
    return 0;
  }
  fuzz_check(img.rgba && img.width > 0 && img.height > 0, "pixels on success");
  fuzz_check((uint64_t)img.width * img.height <= TLOD_IMPORT_MAX_IMAGE_PIXELS, "within the pixel limit");
  fuzz_check((size_t)img.width * img.height * 4 <= budget.used, "pixels taken from the budget");
  unsigned sum = 0;
  for (size_t i = 0; i < (size_t)img.width * img.height * 4; ++i)
    sum += img.rgba[i];
  fuzz_check(sum != 0xFFFFFFFFu || img.width, "every pixel byte readable");
  free(img.rgba);
  return 0;
}
