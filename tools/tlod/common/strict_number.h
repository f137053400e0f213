/* Strict numbers for every value the tlod command reads from its arguments:
 * the whole text (or, for a field of a composite such as WxH, the text up to
 * its separator) must be a number, in range, finite. Nothing wraps: 4294967297
 * is out of range for a 32-bit field, "-1" for an unsigned one, and " 5",
 * "5x", "0x10", "1e999", "nan" are refused.
 *
 * Integers: an optional '-' then decimal digits (strtoll). Reals: decimal
 * (digits, one '.', an exponent; strtod), never hex, inf or nan. */
#ifndef TLOD_TOOLS_STRICT_NUMBER_H
#define TLOD_TOOLS_STRICT_NUMBER_H

#include <stdint.h>

typedef enum number_status {
  NUMBER_OK = 0,
  NUMBER_SYNTAX, /* not a number of the kind asked for */
  NUMBER_RANGE,  /* a number, outside [lo, hi] (or beyond what the type holds) */
} number_status;

/* Parses text as a whole number in [lo, hi]. With end NULL the whole string
 * must be the number; otherwise parsing stops after the digits and *end
 * points past them (the caller checks the separator). */
number_status number_parse_int(const char* text, const char** end, int64_t lo, int64_t hi, int64_t* out);
/* The same for a 32-bit unsigned field. */
number_status number_parse_u32(const char* text, const char** end, uint32_t lo, uint32_t hi, uint32_t* out);
/* A finite real in [lo, hi]; end as above. */
number_status number_parse_real(const char* text, const char** end, double lo, double hi, double* out);

#endif
