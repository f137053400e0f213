/* Private to tesslod::backend. */
#ifndef TESSLOD_BACKEND_INTERNAL_H
#define TESSLOD_BACKEND_INTERNAL_H

#include "internal.h"
#include "tesslod/backend.h"

extern const tlod_backend_vtbl _tlod_cpu_backend_vtbl;
struct tlod_cpu_mesh;
const struct tlod_cpu_mesh* _tlod_cpu_backend_mesh(const void* state);
#if TLOD_HAS_GL
extern const tlod_backend_vtbl _tlod_gl_vtbl;
#endif

#endif
