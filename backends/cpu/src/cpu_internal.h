/* Private to tesslod::cpu. */
#ifndef TESSLOD_CPU_INTERNAL_H
#define TESSLOD_CPU_INTERNAL_H

#include "tesslod/cpu.h"

/* Zips two polylines that run the same way between the same end points into
 * a strip (DESIGN.md "Strips in practice"). ta[0..na] and tb[0..nb] are
 * their points' integer parameters, ascending, ta[0] == tb[0] and
 * ta[na] == tb[nb]. Writes up to na + nb triangles as point references:
 * r <= na is a[r], otherwise b[r - na - 1]. Triangles are oriented so that
 * a is traversed backwards (a is the boundary of a face on the strip's
 * left). Returns the triangle count. */
uint32_t _tlod_zip_polylines(const uint32_t* ta, uint32_t na, const uint32_t* tb, uint32_t nb, uint32_t (*out)[3]);

#endif
