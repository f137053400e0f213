/* tlod play -- the run folder. */
#define _DEFAULT_SOURCE /* flock, localtime_r */
#include "play_run_folder.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "common/strict_number.h"

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

int play_make_run_folder(const play_options* o, char* out, size_t size, int* lock_fd) {
  if (o->out) {
    snprintf(out, size, "%s", o->out);
    size_t n = strlen(out);
    while (n > 1 && out[n - 1] == '/')
      out[--n] = '\0';
    if (!tool_mkdir_p(out)) return cli_error(CLI_FAILED, "--out: cannot create folder '%s': %s", out, strerror(errno));
    return *lock_fd >= 0 ? CLI_OK : play_lock_run_folder(out, lock_fd);
  }
  char stamp[32];
  time_t now = time(NULL);
  struct tm tm;
  localtime_r(&now, &tm);
  strftime(stamp, sizeof(stamp), "%Y%m%d-%H%M%S", &tm);
  if (!tool_mkdir_p("runs")) return cli_error(CLI_FAILED, "cannot create folder 'runs': %s", strerror(errno));
  for (int k = 1; k < 100; k++) {
    if (k == 1) {
      snprintf(out, size, "runs/%s", stamp);
    } else {
      snprintf(out, size, "runs/%s-%d", stamp, k);
    }
    if (mkdir(out, 0777) == 0) return play_lock_run_folder(out, lock_fd);
    if (errno != EEXIST) break;
  }
  return cli_error(CLI_FAILED, "cannot create a run folder under 'runs': %s", strerror(errno));
}

/* The holder's pid as it wrote it, or 0. */
static long holder_pid(int fd) {
  char buf[32] = "";
  static const char kPrefix[] = "tlod play pid ";
  ssize_t n = pread(fd, buf, sizeof(buf) - 1, 0);
  int64_t pid = 0;
  const char* end = NULL;
  if (n <= 0 || strncmp(buf, kPrefix, sizeof(kPrefix) - 1)) return 0;
  return number_parse_int(buf + sizeof(kPrefix) - 1, &end, 1, INT32_MAX, &pid) == NUMBER_OK ? (long)pid : 0;
}

static int lock_busy(const char* dir, int fd) {
  long pid = holder_pid(fd);
  close(fd);
  if (pid)
    return cli_error(CLI_FAILED,
                     "--out: folder '%s' is in use by another tlod (pid %ld holds %s/%s); one run per folder", dir, pid,
                     dir, PLAY_LOCK_FILE);
  return cli_error(CLI_FAILED, "--out: folder '%s' is in use by another process (it holds %s/%s); one run per folder",
                   dir, dir, PLAY_LOCK_FILE);
}

/* True when fd is still the file at path: the holder before us unlinks it as
 * it finishes, and a lock on the unlinked file would lock nothing. */
static bool still_linked(int fd, const char* path) {
  struct stat a, b;
  return fstat(fd, &a) == 0 && stat(path, &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

int play_lock_run_folder(const char* dir, int* lock_fd) {
  char path[PLAY_PATH_MAX + 64];
  if (!play_path_join(path, sizeof(path), dir, PLAY_LOCK_FILE))
    return cli_error(CLI_FAILED, "--out: folder name '%s' too long", dir);
  for (int attempt = 0; attempt < 16; attempt++) {
    int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd < 0) return cli_error(CLI_FAILED, "cannot create '%s': %s", path, strerror(errno));
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
      if (errno == EWOULDBLOCK) return lock_busy(dir, fd);
      int err = errno;
      close(fd);
      return cli_error(CLI_FAILED, "cannot lock '%s': %s", path, strerror(err));
    }
    if (!still_linked(fd, path)) {
      close(fd);
      continue;
    }
    char id[32];
    int n = snprintf(id, sizeof(id), "tlod play pid %ld\n", (long)getpid());
    if (ftruncate(fd, 0) != 0 || pwrite(fd, id, (size_t)n, 0) != n) { /* only the message needs it */
    }
    *lock_fd = fd;
    return CLI_OK;
  }
  return cli_error(CLI_FAILED, "cannot lock '%s': it keeps being replaced", path);
}

void play_unlock_run_folder(const char* dir, int lock_fd) {
  if (lock_fd < 0) return;
  char path[PLAY_PATH_MAX + 64];
  if (play_path_join(path, sizeof(path), dir, PLAY_LOCK_FILE)) unlink(path); /* while still holding it */
  close(lock_fd);
}
