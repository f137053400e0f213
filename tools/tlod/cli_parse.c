/* tlod -- option values: numbers (common/strict_number.h), enums, the value after an option. */
#include <float.h>
#include <string.h>

#include "cli.h"
#include "common/strict_number.h"
#include "tool_names.h"

/* "<option>: <text>: <problem>", the one form of every number error. */
static bool number_error(const char* option, const char* text, const char* field, number_status s, const char* range) {
  if (s == NUMBER_SYNTAX) {
    cli_error(CLI_USAGE, "%s: %s: expected %s", option, text ? text : "", range);
  } else {
    cli_error(CLI_USAGE, "%s: %s: %s out of range %s", option, text ? text : "", field, range);
  }
  return false;
}

bool cli_parse_float(const char* option, const char* text, double lo, double hi, float* out) {
  double v = 0.0;
  number_status s = number_parse_real(text, NULL, lo, hi, &v);
  if (s == NUMBER_OK) {
    *out = (float)v;
    return true;
  }
  char range[96];
  snprintf(range, sizeof(range), s == NUMBER_SYNTAX ? "a number in [%g, %g]" : "[%g, %g]", lo, hi);
  return number_error(option, text, "value", s, range);
}

bool cli_parse_uint(const char* option, const char* text, uint32_t lo, uint32_t hi, uint32_t* out) {
  number_status s = number_parse_u32(text, NULL, lo, hi, out);
  if (s == NUMBER_OK) return true;
  char range[96];
  snprintf(range, sizeof(range), s == NUMBER_SYNTAX ? "a whole number in %u..%u" : "%u..%u", lo, hi);
  return number_error(option, text, "value", s, range);
}

bool cli_parse_size(const char* option, const char* text, uint32_t max, uint32_t* w, uint32_t* h) {
  const char* x = NULL;
  char range[64];
  snprintf(range, sizeof(range), "1..%u", max);
  number_status s = number_parse_u32(text, &x, 1, max, w);
  if (s == NUMBER_OK && *x != 'x') s = NUMBER_SYNTAX;
  if (s != NUMBER_OK) return number_error(option, text, "width", s, s == NUMBER_SYNTAX ? "WxH" : range);
  s = number_parse_u32(x + 1, NULL, 1, max, h);
  if (s != NUMBER_OK) return number_error(option, text, "height", s, s == NUMBER_SYNTAX ? "WxH" : range);
  return true;
}

bool cli_parse_vec3(const char* option, const char* text, float v[3]) {
  static const char* const axis[3] = {"x", "y", "z"};
  const char* at = text;
  for (int c = 0; c < 3; c++) {
    double d = 0.0;
    const char* stop = NULL;
    number_status s = number_parse_real(at, &stop, -FLT_MAX, FLT_MAX, &d);
    if (s == NUMBER_OK && *stop != (c < 2 ? ',' : '\0')) s = NUMBER_SYNTAX;
    if (s != NUMBER_OK) return number_error(option, text, axis[c], s, s == NUMBER_SYNTAX ? "X,Y,Z" : "of a float");
    v[c] = (float)d;
    at = stop + 1;
  }
  return true;
}

int cli_parse_enum(const char* option, const char* text, const char* const* names) {
  for (int i = 0; text && names[i]; i++) {
    if (!strcmp(text, names[i])) return i;
  }
  char list[256] = "";
  for (int i = 0; names[i]; i++) {
    strncat(list, i ? "|" : "", sizeof(list) - strlen(list) - 1);
    strncat(list, names[i], sizeof(list) - strlen(list) - 1);
  }
  cli_error(CLI_USAGE, "%s: expected %s, got '%s'", option, list, text ? text : "");
  return -1;
}

const char* cli_value(int argc, char** argv, int* i) {
  if (*i + 1 >= argc) {
    cli_error(CLI_USAGE, "%s needs a value", argv[*i]);
    return NULL;
  }
  return argv[++*i];
}

int cli_usage_unless(bool ok) { return ok ? CLI_OK : CLI_USAGE; }

int cli_parse_lod_option(int argc, char** argv, int* i, float* epsilon, tlod_lod_policy* policy, uint32_t* max_level) {
  const char* a = argv[*i];
  const char* v = NULL;
  int e;
  if (!strcmp(a, "--epsilon"))
    return cli_usage_unless((v = cli_value(argc, argv, i)) && cli_parse_float(a, v, 1e-6, 1e9, epsilon));
  if (!strcmp(a, "--policy")) {
    if (!(v = cli_value(argc, argv, i)) || (e = cli_parse_enum(a, v, tool_policy_options)) < 0) return CLI_USAGE;
    *policy = (tlod_lod_policy)(TLOD_POLICY_ERROR + e);
    return CLI_OK;
  }
  if (!strcmp(a, "--max-level"))
    return cli_usage_unless((v = cli_value(argc, argv, i)) && cli_parse_uint(a, v, 1, TLOD_MAX_LEVEL, max_level));
  return CLI_NOT_MINE;
}
