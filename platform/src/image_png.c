/*
 * image_png.c -- PNG screenshots through stb_image_write (owned by platform/).
 *
 * The encoder is Debian's libstb (docs/platform.md section 6: libstb-dev ships
 * libstb.so with stbi_write_png*), so no STB_IMAGE_WRITE_IMPLEMENTATION is
 * compiled here and stb's code is not built with the project's sanitizers.
 * stbi_write_png_to_func streams into the atomic file writer's FILE, so every
 * failure (create, short write, close, rename) is reported with errno and
 * leaves nothing behind.
 */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include <stb_image_write.h>

#include "platform_internal.h"
#include "tlod_atomic_file.h"

/* Errors are sticky in the FILE and checked by tlod_atomic_file_end. */
static void png_sink_write(void* context, void* data, int size) {
  if (size > 0) fwrite(data, 1, (size_t)size, context);
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
  tlod_atomic_file a;
  if (!tlod_atomic_file_begin(&a, path, error, error_size)) return false;
  stbi_flip_vertically_on_write(0); /* libstb's process-wide flag: rows are given top first */
  errno = 0;
  bool encoded =
      stbi_write_png_to_func(png_sink_write, a.file, (int)width, (int)height, 4, rgba_top_first, (int)(width * 4)) != 0;
  /* The sink cannot return an error: read the write's errno (ENOSPC, EFBIG)
   * now, before closing the file replaces it. */
  const int write_errno = encoded && ferror(a.file) ? (errno ? errno : EIO) : 0;
  if (!encoded)
    _tlod_platform_error(error, error_size, "%s: PNG encoding (%ux%u) failed (out of memory?)", path, width, height);
  if (write_errno) {
    _tlod_platform_error(error, error_size, "cannot write '%s': %s", path, strerror(write_errno));
    return tlod_atomic_file_end(&a, false, NULL, 0);
  }
  return tlod_atomic_file_end(&a, encoded, error, error_size);
}
