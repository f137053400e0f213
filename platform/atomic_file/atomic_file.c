/* atomic_file.c -- write to a unique temporary, rename when complete. */
#define _POSIX_C_SOURCE 200809L /* mkstemp, fdopen, fsync, fchmod */
#include <errno.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "tlod_atomic_file.h"

static bool fail(char* error, size_t error_size, int err, const char* fmt, const char* a, const char* b) {
  if (!error || !error_size) return false;
  int n = snprintf(error, error_size, fmt, a, b);
  if (n >= 0 && (size_t)n < error_size) snprintf(error + n, error_size - (size_t)n, ": %s", strerror(err ? err : EIO));
  return false;
}

/* mkstemp makes the file 0600: give it what fopen would (0666 less the umask). */
static int chmod_as_fopen(int fd) {
  mode_t mask = umask(0);
  umask(mask);
  return fchmod(fd, 0666 & ~mask);
}

/* The rename would replace a folder's entry or a device node (as root:
 * /dev/null, /dev/full): only a regular file or nothing may be there. */
static int target_error(const char* path) {
  struct stat st;
  if (lstat(path, &st) != 0 || S_ISREG(st.st_mode)) return 0;
  if (S_ISLNK(st.st_mode) && (stat(path, &st) != 0 || S_ISREG(st.st_mode))) return 0; /* the link is replaced */
  return S_ISDIR(st.st_mode) ? EISDIR : EINVAL;
}

bool tlod_atomic_file_begin(tlod_atomic_file* a, const char* path, char* error, size_t error_size) {
  memset(a, 0, sizeof(*a));
  int target = target_error(path);
  if (target == EISDIR) return fail(error, error_size, target, "cannot write '%s'%s", path, "");
  if (target && error && error_size) snprintf(error, error_size, "cannot write '%s': not a regular file", path);
  if (target) return false;
  size_t n = strlen(path);
  if (!(a->tmp = malloc(n + sizeof(".tmp.XXXXXX"))))
    return fail(error, error_size, ENOMEM, "cannot write '%s'", path, "");
  memcpy(a->tmp, path, n);
  memcpy(a->tmp + n, ".tmp.XXXXXX", sizeof(".tmp.XXXXXX"));
  int fd = mkstemp(a->tmp);
  int err = errno;
  if (fd >= 0 && (chmod_as_fopen(fd) != 0 || !(a->file = fdopen(fd, "wb")))) {
    err = errno;
    close(fd);
    unlink(a->tmp);
  }
  if (!a->file) {
    fail(error, error_size, err, "cannot create '%s'%s", a->tmp, "");
    free(a->tmp);
    memset(a, 0, sizeof(*a));
    return false;
  }
  a->path = path;
  setvbuf(a->file, NULL, _IOFBF, 1 << 16);
  return true;
}

/* Flush, sync and close; the errno of the first failure, or 0. */
static int close_checked(tlod_atomic_file* a) {
  int err = 0;
  if (fflush(a->file) != 0 || ferror(a->file)) err = errno ? errno : EIO;
  if (!err && a->sync && fsync(fileno(a->file)) != 0) err = errno;
  if (fclose(a->file) != 0 && !err) err = errno ? errno : EIO;
  a->file = NULL;
  return err;
}

static bool discard(tlod_atomic_file* a) {
  if (a->file) fclose(a->file);
  unlink(a->tmp);
  free(a->tmp);
  memset(a, 0, sizeof(*a));
  return false;
}

bool tlod_atomic_file_end(tlod_atomic_file* a, bool keep, char* error, size_t error_size) {
  if (!a->tmp) return false; /* begin failed */
  if (!keep) return discard(a);
  errno = 0;
  int err = close_checked(a);
  if (err) {
    fail(error, error_size, err, "cannot write '%s'%s", a->path, "");
    return discard(a);
  }
  if (rename(a->tmp, a->path) != 0) {
    fail(error, error_size, errno, "cannot rename '%s' to '%s'", a->tmp, a->path);
    return discard(a);
  }
  free(a->tmp);
  memset(a, 0, sizeof(*a));
  return true;
}

bool tlod_atomic_file_write(const char* path, tlod_atomic_file_fill fill, const void* data, char* error,
                            size_t error_size) {
  tlod_atomic_file a;
  if (!tlod_atomic_file_begin(&a, path, error, error_size)) return false;
  errno = 0;
  bool filled = fill(a.file, data);
  if (!filled) fail(error, error_size, errno, "cannot write '%s'%s", path, "");
  return tlod_atomic_file_end(&a, filled, error, error_size);
}
