/* Folders the tools make (folder.h). */
#define _POSIX_C_SOURCE 200809L /* mkstemp */
#include "common/folder.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

bool tool_mkdir_p(const char* path) {
  char buf[4096];
  snprintf(buf, sizeof(buf), "%s", path);
  for (char* p = buf + 1; *p; p++) {
    if (*p != '/') continue;
    *p = '\0';
    if (mkdir(buf, 0777) != 0 && errno != EEXIST) return false;
    *p = '/';
  }
  if (mkdir(buf, 0777) != 0 && errno != EEXIST) return false;
  struct stat st;
  if (stat(buf, &st) != 0) return false;
  if (!S_ISDIR(st.st_mode)) errno = ENOTDIR;
  return S_ISDIR(st.st_mode);
}

bool tool_folder_writable(const char* path) {
  char name[4096];
  if (snprintf(name, sizeof(name), "%s/.tlod-write-test-XXXXXX", path) >= (int)sizeof(name)) {
    errno = ENAMETOOLONG;
    return false;
  }
  int fd = mkstemp(name);
  if (fd < 0) return false;
  close(fd);
  unlink(name);
  return true;
}

/* The default folder's name; false when neither variable is set. */
static bool default_cache_dir(char* buf, size_t size) {
  const char* xdg = getenv("XDG_CACHE_HOME");
  const char* home = getenv("HOME");
  int n = xdg && *xdg ? snprintf(buf, size, "%s/tesslod", xdg)
                      : (home && *home ? snprintf(buf, size, "%s/.cache/tesslod", home) : -1);
  return n > 0 && (size_t)n < size;
}

/* Made and writable, or the reason in why. */
static bool usable(const char* dir, char* why, size_t size) {
  if (!tool_mkdir_p(dir)) {
    snprintf(why, size, "cannot create folder '%s': %s", dir, strerror(errno));
    return false;
  }
  if (!tool_folder_writable(dir)) {
    snprintf(why, size, "cannot write in folder '%s': %s", dir, strerror(errno));
    return false;
  }
  return true;
}

bool tool_shader_cache_dir(const char* option, char* buf, size_t size, const char** dir, char* warning,
                           size_t warning_size, char* error, size_t error_size) {
  *dir = NULL;
  warning[0] = '\0';
  if (option && !strcmp(option, "off")) return true;
  if (option) {
    if (!usable(option, error, error_size)) return false;
    *dir = option;
    return true;
  }
  if (!default_cache_dir(buf, size)) {
    snprintf(warning, warning_size, "no shader cache: neither XDG_CACHE_HOME nor HOME is set");
    return true;
  }
  char why[4096 + 64];
  if (usable(buf, why, sizeof(why))) {
    *dir = buf;
  } else {
    snprintf(warning, warning_size, "no shader cache: %s", why);
  }
  return true;
}
