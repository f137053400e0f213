/* A tiny C11 test harness: one executable per module, one line per failed
 * check, and a closing "N passed, N failed" line. */
#ifndef TLOD_TEST_H
#define TLOD_TEST_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int _test_checks_failed;
static int _test_passed;
static int _test_failed;

#define TEST(name) static void name(void)

#define CHECK_MSG(cond, ...)                                                                                           \
  do {                                                                                                                 \
    if (!(cond)) {                                                                                                     \
      fprintf(stderr, "%s:%d: check failed: %s: ", __FILE__, __LINE__, #cond);                                         \
      fprintf(stderr, __VA_ARGS__);                                                                                    \
      fputc('\n', stderr);                                                                                             \
      _test_checks_failed++;                                                                                           \
      return;                                                                                                          \
    }                                                                                                                  \
  } while (0)

#define CHECK(cond) CHECK_MSG(cond, "%s", "")

/* Stops the calling test as soon as a helper's check failed. */
#define CALL(expr)                                                                                                     \
  do {                                                                                                                 \
    int _failed_before = _test_checks_failed;                                                                          \
    expr;                                                                                                              \
    if (_test_checks_failed != _failed_before) return;                                                                 \
  } while (0)

#define CHECK_NEAR(a, b, tol)                                                                                          \
  do {                                                                                                                 \
    double _a = (double)(a), _b = (double)(b), _t = (double)(tol);                                                     \
    CHECK_MSG(fabs(_a - _b) <= _t, "%s = %.9g, %s = %.9g, tolerance %.3g", #a, _a, #b, _b, _t);                        \
  } while (0)

#define RUN(name)                                                                                                      \
  do {                                                                                                                 \
    int _before = _test_checks_failed;                                                                                 \
    name();                                                                                                            \
    if (_test_checks_failed == _before) {                                                                              \
      _test_passed++;                                                                                                  \
      printf("ok   %s\n", #name);                                                                                      \
    } else {                                                                                                           \
      _test_failed++;                                                                                                  \
      printf("FAIL %s\n", #name);                                                                                      \
    }                                                                                                                  \
    fflush(stdout);                                                                                                    \
  } while (0)

#define TEST_END()                                                                                                     \
  do {                                                                                                                 \
    printf("%d passed, %d failed\n", _test_passed, _test_failed);                                                      \
    return _test_failed ? 1 : 0;                                                                                       \
  } while (0)

/* The whole file at path, NUL-terminated (malloc; free it); NULL when it cannot be opened. *size (may be NULL)
 * receives its length. */
static inline char* test_read_file(const char* path, size_t* size) {
  FILE* f = fopen(path, "rb");
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  char* s = n < 0 ? NULL : malloc((size_t)n + 1);
  if (s && fread(s, 1, (size_t)n, f) != (size_t)n) n = 0;
  if (s) s[n] = 0;
  fclose(f);
  if (size) *size = s ? (size_t)n : 0;
  return s;
}

#endif
