/* replay_main.c -- a libFuzzer target without libFuzzer: main() runs LLVMFuzzerTestOneInput
 * once on every file named on the command line, and on every regular file directly inside a
 * named folder (sub-folders are skipped). The ctest tests fuzz_replay_<target> run it over the
 * target's seed corpus (fuzz/seeds.py: tests/data, the seeds, every reproducer saved in
 * tests/data/fuzz/<target>); a crash or a broken contract (abort) fails the test, under the
 * asan preset a sanitizer report too.
 * Usage: <target>_replay PATH...   Prints "replayed N inputs"; exits 1 when a file cannot be
 * read or N is 0. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fuzz_common.h"

static int replay_file(const char* path) {
  FILE* f = fopen(path, "rb");
  if (!f) {
    fprintf(stderr, "replay: cannot open %s\n", path);
    return -1;
  }
  size_t cap = 1 << 16, len = 0, got;
  unsigned char* buf = malloc(cap);
  while (buf && (got = fread(buf + len, 1, cap - len, f)) > 0) {
    len += got;
    if (len < cap) continue;
    unsigned char* grown = realloc(buf, cap * 2);
    if (!grown) free(buf);
    buf = grown;
    cap *= 2;
  }
  fclose(f);
  fuzz_check(buf != NULL, "replay: out of memory");
  fprintf(stderr, "replay: %s (%zu bytes)\n", path, len);
  LLVMFuzzerTestOneInput(buf, len);
  free(buf);
  return 1;
}

static int compare_names(const void* a, const void* b) { return strcmp(*(char* const*)a, *(char* const*)b); }

/* The regular files directly in dir, in name order (a stable log). */
static int replay_dir(const char* dir) {
  DIR* d = opendir(dir);
  if (!d) return replay_file(dir);
  char* names[4096];
  size_t n = 0;
  struct dirent* e;
  while ((e = readdir(d)) != NULL && n < sizeof names / sizeof names[0]) {
    char path[4096];
    struct stat st;
    snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
    if (stat(path, &st) == 0 && S_ISREG(st.st_mode)) names[n++] = strdup(path);
  }
  closedir(d);
  qsort(names, n, sizeof names[0], compare_names);
  int count = 0;
  for (size_t i = 0; i < n; ++i) {
    int r = replay_file(names[i]);
    count = (r < 0 || count < 0) ? -1 : count + r;
    free(names[i]);
  }
  return count;
}

int main(int argc, char** argv) {
  int total = 0;
  for (int i = 1; i < argc; ++i) {
    struct stat st;
    if (stat(argv[i], &st) != 0) continue; /* a target without reproducers yet */
    int r = S_ISDIR(st.st_mode) ? replay_dir(argv[i]) : replay_file(argv[i]);
    if (r < 0) return 1;
    total += r;
  }
  printf("replayed %d inputs\n", total);
  return total > 0 ? 0 : 1;
}
