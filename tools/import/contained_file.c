/* contained_file.c -- reads a file a model names, under the containment rule of contained_file.h.
 * Owned by the import/export layer (tools/import/). */
#define _GNU_SOURCE /* realpath, O_CLOEXEC, O_NOCTTY */
#include "contained_file.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "tesslod/core.h"

static int _tlod_hex(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

bool _tlod_percent_decode(const char* ref, char* out, size_t out_size) {
  size_t n = 0;
  for (const char* p = ref; *p; ++p) {
    char c = *p;
    if (c == '%') {
      const int hi = _tlod_hex(p[1]), lo = hi < 0 ? -1 : _tlod_hex(p[2]);
      if (lo < 0 || (hi | lo) == 0) return false;
      c = (char)(hi * 16 + lo);
      p += 2;
    }
    if (n + 1 >= out_size) return false;
    out[n++] = c;
  }
  if (out_size == 0) return false;
  out[n] = 0;
  return true;
}

/* RFC 3986 scheme: ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":" before any '/'. */
static bool _tlod_has_scheme(const char* s) {
  if (!((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z'))) return false;
  for (const char* p = s + 1; *p && *p != '/'; ++p) {
    if (*p == ':') return true;
    const bool ok = (*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9') || *p == '+' ||
                    *p == '-' || *p == '.';
    if (!ok) return false;
  }
  return false;
}

/* Does the path, read component by component, climb above its start ("a/../../x")?
 * Checked before realpath so that a refusal does not depend on whether the
 * foreign file exists (which would let a model probe the file system). */
static bool _tlod_climbs_out(const char* s) {
  long depth = 0;
  while (*s) {
    const char* e = strchr(s, '/');
    const size_t n = e ? (size_t)(e - s) : strlen(s);
    if (n == 2 && s[0] == '.' && s[1] == '.') {
      if (--depth < 0) return true;
    } else if (n > 0 && !(n == 1 && s[0] == '.')) {
      depth++;
    }
    s += n + (e ? 1 : 0);
  }
  return false;
}

/* realpath(folder/name) inside realpath(folder): *resolved is malloc'ed. */
static _tlod_contained_status _tlod_resolve(const char* folder, const char* name, char** resolved) {
  *resolved = NULL;
  char* root = realpath(folder[0] ? folder : ".", NULL);
  if (!root) return _TLOD_CONTAINED_NOT_FOUND;
  const size_t root_len = strlen(root), name_len = strlen(name);
  char* joined = (char*)malloc(root_len + name_len + 2);
  if (!joined) {
    free(root);
    return _TLOD_CONTAINED_OUT_OF_MEMORY;
  }
  memcpy(joined, root, root_len);
  joined[root_len] = '/';
  memcpy(joined + root_len + 1, name, name_len + 1);
  char* real = realpath(joined, NULL);
  free(joined);
  _tlod_contained_status st = real ? _TLOD_CONTAINED_OK : _TLOD_CONTAINED_NOT_FOUND;
  /* Inside: root itself is a folder, so a file needs root + "/" as a prefix ("/" as root: any). */
  const size_t prefix = root_len == 1 ? 0 : root_len;
  if (real && !(strncmp(real, root, prefix) == 0 && real[prefix] == '/')) st = _TLOD_CONTAINED_OUTSIDE;
  free(root);
  if (st == _TLOD_CONTAINED_OK)
    *resolved = real;
  else
    free(real);
  return st;
}

/* Reads exactly size bytes of fd into a new buffer (+1 zero byte). */
static _tlod_contained_status _tlod_read_fd(int fd, size_t size, unsigned char** data) {
  unsigned char* buf = (unsigned char*)malloc(size + 1);
  if (!buf) return _TLOD_CONTAINED_OUT_OF_MEMORY;
  size_t got = 0;
  while (got < size) {
    const ssize_t n = read(fd, buf + got, size - got);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break; /* error, or the file shrank */
    got += (size_t)n;
  }
  char extra;
  if (got != size || read(fd, &extra, 1) != 0) { /* short, or the file grew */
    free(buf);
    return _TLOD_CONTAINED_READ_ERROR;
  }
  buf[size] = 0;
  *data = buf;
  return _TLOD_CONTAINED_OK;
}

/* A folder on the resolved path swapped for a symlink between realpath()
 * and open() would open a file elsewhere: the kernel's name for what was
 * opened must still be the resolved (inside) path. Without /proc this check
 * is skipped (docs/security.md). */
static bool _tlod_opened_as(int fd, const char* path) {
  char link[64], got[4096];
  snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
  const ssize_t n = readlink(link, got, sizeof got);
  if (n < 0) return true;
  return (size_t)n == strlen(path) && memcmp(got, path, (size_t)n) == 0;
}

static _tlod_contained_status _tlod_read_regular(const char* path, size_t max_bytes, unsigned char** data,
                                                 size_t* size) {
  /* O_NONBLOCK: opening a FIFO with no writer must not wait; fstat then refuses it. */
  const int fd = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) return _TLOD_CONTAINED_NOT_FOUND;
  struct stat sb;
  _tlod_contained_status st = _TLOD_CONTAINED_OK;
  if (!_tlod_opened_as(fd, path))
    st = _TLOD_CONTAINED_OUTSIDE;
  else if (fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode))
    st = _TLOD_CONTAINED_NOT_REGULAR;
  else if ((unsigned long long)sb.st_size > max_bytes)
    st = _TLOD_CONTAINED_TOO_LARGE;
  else
    st = _tlod_read_fd(fd, (size_t)sb.st_size, data);
  if (st == _TLOD_CONTAINED_OK) *size = (size_t)sb.st_size;
  close(fd);
  return st;
}

_tlod_contained_status _tlod_contained_read(const char* folder, const char* ref, size_t max_bytes, unsigned char** data,
                                            size_t* size) {
  *data = NULL;
  *size = 0;
  const size_t cap = strlen(ref) + 1;
  char* name = (char*)malloc(cap);
  if (!name) return _TLOD_CONTAINED_OUT_OF_MEMORY;
  _tlod_contained_status st = _TLOD_CONTAINED_OK;
  if (!_tlod_percent_decode(ref, name, cap))
    st = _TLOD_CONTAINED_BAD_ESCAPE;
  else if (name[0] == 0 || name[0] == '/' || _tlod_has_scheme(name) || _tlod_has_scheme(ref))
    st = _TLOD_CONTAINED_ABSOLUTE;
  else if (_tlod_climbs_out(name))
    st = _TLOD_CONTAINED_OUTSIDE;
  char* real = NULL;
  if (st == _TLOD_CONTAINED_OK) st = _tlod_resolve(folder, name, &real);
  free(name);
  if (st == _TLOD_CONTAINED_OK) st = _tlod_read_regular(real, max_bytes, data, size);
  free(real);
  return st;
}

const char* _tlod_contained_message(_tlod_contained_status status) {
  switch (status) {
  case _TLOD_CONTAINED_OK:
    return "read";
  case _TLOD_CONTAINED_BAD_ESCAPE:
    return "refused: malformed percent-encoding";
  case _TLOD_CONTAINED_ABSOLUTE:
    return "refused: not a relative reference (absolute path or scheme)";
  case _TLOD_CONTAINED_OUTSIDE:
    return "refused: outside the model's folder";
  case _TLOD_CONTAINED_NOT_FOUND:
    return "not found";
  case _TLOD_CONTAINED_NOT_REGULAR:
    return "refused: not a regular file";
  case _TLOD_CONTAINED_TOO_LARGE:
    return "refused: larger than the import's memory budget";
  case _TLOD_CONTAINED_READ_ERROR:
    return "cannot be read";
  case _TLOD_CONTAINED_OUT_OF_MEMORY:
    return "out of memory";
  }
  return "refused";
}

int _tlod_contained_result(_tlod_contained_status status) {
  switch (status) {
  case _TLOD_CONTAINED_TOO_LARGE:
  case _TLOD_CONTAINED_OUT_OF_MEMORY:
    return TLOD_ERROR_OUT_OF_MEMORY;
  case _TLOD_CONTAINED_BAD_ESCAPE:
    return TLOD_ERROR_PARSE;
  default:
    return TLOD_ERROR_IO;
  }
}
