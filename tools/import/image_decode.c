/* image_decode.c -- format sniffing, the shared size rule and messages of the image decoders
 * (image_decode.h). Owned by the import/export layer. */
#include <string.h>

#include "image_decode.h"

const char* _tlod_image_sniff(const unsigned char* data, size_t size) {
  if (size >= 8 && memcmp(data, "\x89PNG\r\n\x1a\n", 8) == 0) return "image/png";
  if (size >= 3 && data[0] == 0xFF && data[1] == 0xD8 && data[2] == 0xFF) return "image/jpeg";
  return NULL;
}

_tlod_image_status _tlod_image_decode(const unsigned char* data, size_t size, _tlod_import_budget* budget,
                                      _tlod_image* out, char* detail, size_t detail_size) {
  memset(out, 0, sizeof *out);
  if (detail && detail_size) detail[0] = 0;
  const char* mime = _tlod_image_sniff(data, size);
  if (!mime) return _TLOD_IMAGE_UNKNOWN_FORMAT;
  if (mime[6] == 'p') return _tlod_png_decode(data, size, budget, out, detail, detail_size);
  return _tlod_jpeg_decode(data, size, budget, out, detail, detail_size);
}

_tlod_image_status _tlod_image_reserve(uint32_t width, uint32_t height, size_t bytes_per_pixel, size_t extra,
                                       _tlod_import_budget* budget) {
  if (width == 0 || height == 0) return _TLOD_IMAGE_CORRUPT;
  if ((uint64_t)width * height > TLOD_IMPORT_MAX_IMAGE_PIXELS) return _TLOD_IMAGE_TOO_LARGE;
  size_t bytes;
  if (!_tlod_size_mul((size_t)width * height, bytes_per_pixel, &bytes) || !_tlod_size_add(bytes, extra, &bytes) ||
      !_tlod_budget_take(budget, bytes))
    return _TLOD_IMAGE_OVER_BUDGET;
  return _TLOD_IMAGE_OK;
}

const char* _tlod_image_message(_tlod_image_status status) {
  switch (status) {
  case _TLOD_IMAGE_OK:
    return "decoded";
  case _TLOD_IMAGE_UNKNOWN_FORMAT:
    return "not a PNG or JPEG image";
  case _TLOD_IMAGE_CORRUPT:
    return "cannot be decoded";
  case _TLOD_IMAGE_TOO_LARGE:
    return "larger than the image pixel limit (TLOD_IMPORT_MAX_IMAGE_PIXELS)";
  case _TLOD_IMAGE_OVER_BUDGET:
    return "its decoded size exceeds the import's memory budget (tlod_import_desc.memory_limit)";
  default:
    return "out of memory";
  }
}
