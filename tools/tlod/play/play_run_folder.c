/* tlod play -- the run folder. */
#define _POSIX_C_SOURCE 200809L /* localtime_r */
#include "play_run_folder.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "cli.h"

bool play_path_join(char* buf, size_t size, const char* a, const char* b) {
  size_t na = strlen(a), nb = strlen(b);
  if (na + nb + 2 > size) {
    buf[0] = '\0';
    return false;
  }
  memmove(buf, a, na);
  buf[na] = '/';
  memcpy(buf + na + 1, b, nb + 1);
  return true;
}

bool play_mkdir_p(const char* path) {
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
  return stat(buf, &st) == 0 && S_ISDIR(st.st_mode);
}

int play_make_run_folder(const play_options* o, char* out, size_t size) {
  if (o->out) {
    snprintf(out, size, "%s", o->out);
    size_t n = strlen(out);
    while (n > 1 && out[n - 1] == '/')
      out[--n] = '\0';
    if (!play_mkdir_p(out)) return cli_error(CLI_FAILED, "--out: cannot create folder '%s': %s", out, strerror(errno));
    return CLI_OK;
  }
  char stamp[32];
  time_t now = time(NULL);
  struct tm tm;
  localtime_r(&now, &tm);
  strftime(stamp, sizeof(stamp), "%Y%m%d-%H%M%S", &tm);
  if (!play_mkdir_p("runs")) return cli_error(CLI_FAILED, "cannot create folder 'runs': %s", strerror(errno));
  for (int k = 1; k < 100; k++) {
    if (k == 1) {
      snprintf(out, size, "runs/%s", stamp);
    } else {
      snprintf(out, size, "runs/%s-%d", stamp, k);
    }
    if (mkdir(out, 0777) == 0) return CLI_OK;
    if (errno != EEXIST) break;
  }
  return cli_error(CLI_FAILED, "cannot create a run folder under 'runs': %s", strerror(errno));
}
