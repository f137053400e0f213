/* The tools' names for the library's enums, all in one place (to be
 * replaced by the library's own name functions when core and lod have them).
 * The *_options lists are NULL-terminated, for cli_parse_enum. */
#ifndef TLOD_TOOLS_TOOL_NAMES_H
#define TLOD_TOOLS_TOOL_NAMES_H

#include "tesslod/lod.h"

/* "flat", "phong", "pn": TLOD_SURFACE_FLAT + index. (+ 1: phong | pn only.) */
extern const char* const tool_surface_options[];
/* "keep", "angle", "area": TLOD_NORMALS_KEEP + index. */
extern const char* const tool_normal_options[];
/* "error", "silhouette", "hybrid": TLOD_POLICY_ERROR + index. */
extern const char* const tool_policy_options[];
/* The backends this build has (tlod_backend_names(): "cpu", "gl", "null"). */
const char* const* tool_backend_options(void);

/* "flat", "phong" (also for the default), "pn". */
const char* tool_surface_name(tlod_surface_type type);
/* "error", "silhouette", "uniform", "hybrid" (also for the default). */
const char* tool_policy_name(tlod_lod_policy policy);
/* "silhouette", "metric", "levels", "morph", "strips". */
const char* tool_stage_name(int stage);

#endif
