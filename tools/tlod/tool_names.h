/* The CLI's option lists for the library's enums, made from the library's
 * own name tables (TLOD_*_NAMES in tesslod/core.h and tesslod/lod.h), so
 * parsing and printing use one spelling. The lists are NULL-terminated, for
 * cli_parse_enum; entry e is the enum's first named value + e. */
#ifndef TLOD_TOOLS_TOOL_NAMES_H
#define TLOD_TOOLS_TOOL_NAMES_H

#include "tesslod/lod.h"

/* "flat", "phong", "pn", "quadratic": TLOD_SURFACE_FLAT + index. */
extern const char* const tool_surface_options[];
/* "auto", "flat", "phong", "pn", "quadratic": (tlod_surface_type)index, auto
 * being TLOD_SURFACE_DEFAULT (resolved per input by cli_resolve_surface). */
extern const char* const tool_surface_auto_options[];
/* "keep", "angle", "area": TLOD_NORMALS_KEEP + index. */
extern const char* const tool_normal_options[];
/* "error", "silhouette", "hybrid", "uniform", "flat": TLOD_POLICY_ERROR + index. */
extern const char* const tool_policy_options[];
/* The backends this build has (tlod_backend_names(): "cpu", "gl", "null"). */
const char* const* tool_backend_options(void);

/* The library's names ("phong" also for the default). */
const char* tool_surface_name(tlod_surface_type type);
const char* tool_policy_name(tlod_lod_policy policy);
const char* tool_stage_name(int stage);

#endif
