/* Private: Phong quad patches in lanes of patches (error_table_lanes.c), and
 * the scalar steps of error_table.c / phong.c the lanes share. */
#ifndef TESSLOD_ERROR_TABLE_LANES_H
#define TESSLOD_ERROR_TABLE_LANES_H

#include "surface_eval.h"

/* Patches per call: the float samples fill one AVX-512 register. */
enum { _TLOD_QUAD_LANES = 16 };

/* For the n <= _TLOD_QUAD_LANES Phong quads c[0..n): info[i]'s error_bound,
 * d_max and sphere as build_patch gives them (_tlod_quad_net,
 * _tlod_quad_net_bound, _tlod_sphere_of) and, for MEASURED and CLOSED_FORM
 * tables, the error table _tlod_error_table (with that net) or
 * _tlod_error_table_closed gives, bitwise, at every instruction set (other
 * modes: no table). */
void _tlod_phong_quads(tlod_simd simd, const _tlod_corners* c, uint32_t n, tlod_error_tables tables,
                       tlod_patch_info* const* info);

/* error_table.c: _tlod_error_table_closed without extra points, its slack given. */
void _tlod_error_table_closed_slack(double slack, tlod_patch_info* info);

#endif
