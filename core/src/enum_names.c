/* tesslod::core -- names of the public enums, from the one table per enum in
 * tesslod/core.h, for parsing and printing. */
#include <string.h>

#include "internal.h"

/* Generates NAME_name() and NAME_from_name() from TABLE; DEFAULT names its
 * resolved value. */
#define NAME_CASE(value, text)                                                                                         \
  case value:                                                                                                          \
    return text;
#define PARSE_ENTRY(value, text)                                                                                       \
  if (strcmp(name, text) == 0) return *out = value, true;
#define DEFINE_NAMES(fn, type, TABLE, default_value, resolved)                                                         \
  const char* fn##_name(type value) {                                                                                  \
    if (value == default_value) value = resolved;                                                                      \
    switch (value) { TABLE(NAME_CASE) default : return NULL; }                                                         \
  }                                                                                                                    \
  bool fn##_from_name(const char* name, type* out) {                                                                   \
    if (!name || !out) return false;                                                                                   \
    TABLE(PARSE_ENTRY)                                                                                                 \
    return false;                                                                                                      \
  }

DEFINE_NAMES(tlod_surface_type, tlod_surface_type, TLOD_SURFACE_TYPE_NAMES, TLOD_SURFACE_DEFAULT, TLOD_SURFACE_PHONG)
DEFINE_NAMES(tlod_shading_normal, tlod_shading_normal, TLOD_SHADING_NORMAL_NAMES, TLOD_SHADING_NORMAL_DEFAULT,
             TLOD_SHADING_NORMAL_INTERPOLATED)
DEFINE_NAMES(tlod_alpha_mode, tlod_alpha_mode, TLOD_ALPHA_MODE_NAMES, TLOD_ALPHA_DEFAULT, TLOD_ALPHA_GLOBAL)
DEFINE_NAMES(tlod_normal_mode, tlod_normal_mode, TLOD_NORMAL_MODE_NAMES, TLOD_NORMALS_DEFAULT, TLOD_NORMALS_KEEP)
DEFINE_NAMES(tlod_simd, tlod_simd, TLOD_SIMD_NAMES, TLOD_SIMD_DEFAULT, _tlod_simd_best())
