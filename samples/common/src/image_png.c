/*
 * image_png.c -- PNG screenshots through stb_image_write (owned by
 * samples/common).
 *
 * The encoder is Debian's libstb (docs/platform.md section 6: libstb-dev ships
 * libstb.so with stbi_write_png*), so no STB_IMAGE_WRITE_IMPLEMENTATION is
 * compiled here and stb's code is not built with the project's sanitizers.
 * stbi_write_png_to_func streams into a FILE* we own, so every failure
 * (open, short write, close, rename) is reported with errno.
 */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include <stb_image_write.h>

#include "platform_internal.h"

typedef struct png_sink {
  FILE* file;
  int error; /* errno of the first failed write, 0 if none */
} png_sink;

static void png_sink_write(void* context, void* data, int size) {
  png_sink* s = context;
  if (s->error || size <= 0) return;
  if (fwrite(data, 1, (size_t)size, s->file) != (size_t)size) s->error = errno ? errno : EIO;
}

bool tlod_png_write(const char* path, uint32_t width, uint32_t height, const uint8_t* rgba_top_first, char* error,
                    size_t error_size) {
  if (error && error_size) error[0] = '\0';
  if (!path || !path[0] || !rgba_top_first) {
    _tlod_platform_error(error, error_size, "tlod_png_write: %s is NULL or empty", !rgba_top_first ? "rgba" : "path");
    return false;
  }
  if (width == 0 || height == 0 || width > 1u << 20 || height > 1u << 20 || (uint64_t)width * 4 > 0x7FFFFFFF) {
    _tlod_platform_error(error, error_size, "tlod_png_write %s: invalid size %ux%u", path, width, height);
    return false;
  }
  char tmp[4096];
  int n = snprintf(tmp, sizeof tmp, "%s.tmp%ld", path, (long)getpid());
  if (n < 0 || (size_t)n >= sizeof tmp) {
    _tlod_platform_error(error, error_size, "tlod_png_write: path too long (%zu bytes)", strlen(path));
    return false;
  }
  png_sink sink = {fopen(tmp, "wb"), 0};
  if (!sink.file) {
    _tlod_platform_error(error, error_size, "cannot create %s: %s", tmp, strerror(errno));
    return false;
  }
  errno = 0;
  stbi_flip_vertically_on_write(0); /* libstb's process-wide flag: rows are given top first */
  int encoded =
      stbi_write_png_to_func(png_sink_write, &sink, (int)width, (int)height, 4, rgba_top_first, (int)(width * 4));
  int close_error = fclose(sink.file) != 0 ? errno : 0;
  if (!encoded || sink.error || close_error) {
    if (!encoded)
      _tlod_platform_error(error, error_size, "stbi_write_png_to_func (%ux%u) failed (out of memory?)", width, height);
    else
      _tlod_platform_error(error, error_size, "cannot write %s: %s", tmp,
                           strerror(sink.error ? sink.error : close_error));
    remove(tmp);
    return false;
  }
  if (rename(tmp, path) != 0) {
    _tlod_platform_error(error, error_size, "cannot rename %s to %s: %s", tmp, path, strerror(errno));
    remove(tmp);
    return false;
  }
  return true;
}
