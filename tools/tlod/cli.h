/* Plumbing every tlod command shares: exit codes, one-line errors, option
 * parsing and the clock. */
#ifndef TLOD_TOOLS_CLI_H
#define TLOD_TOOLS_CLI_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "tesslod/lod.h"

enum { CLI_OK = 0, CLI_FAILED = 1, CLI_USAGE = 2 };

/* Prints "tlod: error: ..." to stderr; returns code. */
int cli_error(int code, const char* fmt, ...) __attribute__((format(printf, 2, 3)));
/* The message of the last cli_error ("" before the first). */
const char* cli_last_error(void);

/* Parses a whole string as a number in [lo, hi] (common/strict_number.h:
 * nothing wraps, no trailing text, finite); false with one error line
 * "<option>: <text>: <problem>" printed otherwise, e.g.
 * "--size: 4294967297x720: width out of range 1..16384". */
bool cli_parse_float(const char* option, const char* text, double lo, double hi, float* out);
bool cli_parse_uint(const char* option, const char* text, uint32_t lo, uint32_t hi, uint32_t* out);
/* "WxH", each in 1..max. */
bool cli_parse_size(const char* option, const char* text, uint32_t max, uint32_t* w, uint32_t* h);
/* "X,Y,Z", each a finite number that fits a float. */
bool cli_parse_vec3(const char* option, const char* text, float v[3]);
/* Index of text in names (NULL-terminated), or -1 with an error printed. */
int cli_parse_enum(const char* option, const char* text, const char* const* names);
/* The value of an option that takes one: argv[*i + 1]; advances *i. */
const char* cli_value(int argc, char** argv, int* i);

/* Option parsers of one command answer CLI_OK, CLI_USAGE (error printed) or
 * CLI_NOT_MINE (not one of theirs: the next parser tries). */
enum { CLI_NOT_MINE = -1 };
/* CLI_OK when ok, else CLI_USAGE (the parser printed the error). */
int cli_usage_unless(bool ok);
/* The scheduler options tessellate and play share: --epsilon PX, --policy P,
 * --max-level L at argv[*i]. */
int cli_parse_lod_option(int argc, char** argv, int* i, float* epsilon, tlod_lod_policy* policy, uint32_t* max_level);

/* Monotonic clock in milliseconds (arbitrary origin). */
double cli_now_ms(void);

#endif
