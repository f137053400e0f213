/* tlod tessellate -- a cpu tessellation as an export mesh, attributes named
 * as the core mesh names them (no copies: the vec4 rows are strided). */
#ifndef TLOD_TOOLS_TESSELLATE_EXPORT_H
#define TLOD_TOOLS_TESSELLATE_EXPORT_H

#include "tesslod/cpu.h"
#include "tlod_import.h"

typedef struct tess_export {
  tlod_export_mesh mesh;
  tlod_attribute_info info[TLOD_MAX_ATTRIBUTES];
  tlod_export_attribute attributes[TLOD_MAX_ATTRIBUTES];
} tess_export;

/* Fills e from out (which must outlive it) and the mesh it came from. */
void tess_export_of(const tlod_cpu_mesh* out, const tlod_mesh* mesh, tess_export* e);

#endif
