/* tlod -- option values: numbers, enums, the value after an option. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "tool_names.h"

bool cli_parse_float(const char* option, const char* text, double lo, double hi, float* out) {
  char* end = NULL;
  errno = 0;
  double v = text ? strtod(text, &end) : 0.0;
  if (!text || end == text || *end || errno || !isfinite(v) || v < lo || v > hi) {
    cli_error(CLI_USAGE, "%s: expected a number in [%g, %g], got '%s'", option, lo, hi, text ? text : "");
    return false;
  }
  *out = (float)v;
  return true;
}

bool cli_parse_uint(const char* option, const char* text, uint32_t lo, uint32_t hi, uint32_t* out) {
  char* end = NULL;
  errno = 0;
  unsigned long v = text && *text != '-' ? strtoul(text, &end, 10) : 0;
  if (!text || *text == '-' || end == text || *end || errno || v < lo || v > hi) {
    cli_error(CLI_USAGE, "%s: expected a whole number in [%u, %u], got '%s'", option, lo, hi, text ? text : "");
    return false;
  }
  *out = (uint32_t)v;
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
