/* fuzz_common.c -- the input as a file in a private folder, and the contract checks. */
#define _POSIX_C_SOURCE 200809L
#include "fuzz_common.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char g_dir[256];
static char g_path[320];

void fuzz_check(int ok, const char* what) {
  if (ok) return;
  fprintf(stderr, "fuzz_check: %s\n", what);
  abort();
}

const char* fuzz_base_name(const char* path) {
  const char* s = strrchr(path, '/');
  return s ? s + 1 : path;
}

void fuzz_check_error(const char* error, const char* file_name) {
  size_t n = strlen(file_name);
  fuzz_check(strncmp(error, file_name, n) == 0 && error[n] == ':' && error[n + 1] == ' ',
             "a failure's message does not start with '<file name>: '");
  fuzz_check(error[n + 2] != 0, "a failure's message is only the file name");
}

/* Removes the input file and the folder at exit (libFuzzer exits through exit()). */
static void remove_dir(void) {
  if (g_path[0]) unlink(g_path);
  if (g_dir[0]) rmdir(g_dir);
}

static void make_dir(void) {
  struct stat st;
  const char* base = getenv("TMPDIR");
  if (stat("/dev/shm", &st) == 0 && S_ISDIR(st.st_mode) && access("/dev/shm", W_OK) == 0) base = "/dev/shm";
  if (!base || !base[0]) base = "/tmp";
  snprintf(g_dir, sizeof g_dir, "%s/tlod-fuzz-XXXXXX", base);
  fuzz_check(mkdtemp(g_dir) != NULL, "cannot make the private temp folder");
  atexit(remove_dir);
}

const char* fuzz_input_file(const char* ext, const uint8_t* data, size_t size) {
  if (!g_dir[0]) make_dir();
  if (g_path[0]) unlink(g_path); /* the extension may differ from the last input's */
  snprintf(g_path, sizeof g_path, "%s/input%s", g_dir, ext);
  FILE* f = fopen(g_path, "wb");
  fuzz_check(f != NULL, "cannot create the input file");
  int ok = (size == 0 || fwrite(data, 1, size, f) == size);
  ok = (fclose(f) == 0) && ok;
  fuzz_check(ok, "cannot write the input file");
  return g_path;
}
