/* Private: Phong quad patches in lanes of patches (error_table_lanes.c), and
 * the scalar steps of error_table.c / phong.c the lanes share. */
#ifndef TESSLOD_ERROR_TABLE_LANES_H
#define TESSLOD_ERROR_TABLE_LANES_H

#include "surface_eval.h"

/* Patches per call. */
enum { _TLOD_QUAD_LANES = 8 };

/* For the n <= _TLOD_QUAD_LANES Phong quads c[0..n): info[i]->error_bound
 * and d_max as _tlod_quad_net + _tlod_quad_net_bound give them and, measured
 * true, the error table _tlod_error_table gives (with that net), bitwise, at
 * every instruction set. */
void _tlod_phong_quads(tlod_simd simd, const _tlod_corners* c, uint32_t n, bool measured, tlod_patch_info* const* info);

/* phong.c: the bound of a net whose _tlod_quad_net_m is m. */
float _tlod_quad_m_bound(double m, const _tlod_corners* c, float* d_max);
/* error_table.c: a Phong quad's table from its net's m and the squared
 * maxima worst2[l] of its shared sample grid's cells at level l. */
void _tlod_phong_quad_table_from(const _tlod_corners* c, double m, const double* worst2, tlod_patch_info* info);

#endif
