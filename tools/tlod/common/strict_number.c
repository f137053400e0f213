/* tlod -- strict number parsing (strict_number.h). */
#include "strict_number.h"

#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

static bool is_digit(char c) { return c >= '0' && c <= '9'; }

/* Where the number stops: the whole string (end NULL) or the caller's cursor. */
static number_status finish(const char* stop, const char** end) {
  if (end) {
    *end = stop;
    return NUMBER_OK;
  }
  return *stop ? NUMBER_SYNTAX : NUMBER_OK;
}

number_status number_parse_int(const char* text, const char** end, int64_t lo, int64_t hi, int64_t* out) {
  if (!text || !is_digit(text[text[0] == '-'])) return NUMBER_SYNTAX; /* no space, '+', or empty */
  char* stop = NULL;
  errno = 0;
  long long v = strtoll(text, &stop, 10);
  number_status s = finish(stop, end);
  if (s != NUMBER_OK) return s;
  if (errno == ERANGE || v < lo || v > hi) return NUMBER_RANGE;
  *out = v;
  return NUMBER_OK;
}

number_status number_parse_u32(const char* text, const char** end, uint32_t lo, uint32_t hi, uint32_t* out) {
  int64_t v = 0;
  number_status s = number_parse_int(text, end, lo, hi, &v);
  if (s == NUMBER_OK) *out = (uint32_t)v;
  return s;
}

/* Decimal syntax only: strtod would also take hex, inf, nan and spaces. */
static size_t decimal_span(const char* text) {
  size_t n = strspn(text, "0123456789+-.eE");
  return is_digit(text[text[0] == '-' || text[0] == '+']) || (text[0] == '.' && is_digit(text[1])) ||
                 ((text[0] == '-' || text[0] == '+') && text[1] == '.' && is_digit(text[2]))
             ? n
             : 0;
}

number_status number_parse_real(const char* text, const char** end, double lo, double hi, double* out) {
  size_t span = text ? decimal_span(text) : 0;
  if (!span) return NUMBER_SYNTAX;
  char* stop = NULL;
  errno = 0;
  double v = strtod(text, &stop);
  if (stop > text + span) return NUMBER_SYNTAX; /* "0x1p3": strtod read past the decimal characters */
  number_status s = finish(stop, end);
  if (s != NUMBER_OK) return s;
  if (!isfinite(v) || v < lo || v > hi) return NUMBER_RANGE;
  *out = v;
  return NUMBER_OK;
}
