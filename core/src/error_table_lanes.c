/* tesslod::core -- Phong quad patches' bound and error table in lanes of
 * patches (error_table_lanes.inc, compiled per instruction set): the net,
 * its second-derivative maximum and the shared sample grid's cells were
 * 90% of a Phong quad surface's build. Bitwise the scalar path of phong.c
 * and error_table.c: same operations in the same order per lane, exact IEEE
 * division and sqrt, no contraction (-ffp-contract=off), the table's
 * rounding up included; only CLOSED_FORM's table is the scalar code's own
 * function, per patch. */
#include <math.h>
#include <string.h>

#include "error_table_lanes.h"

#define K (TLOD_ERROR_TABLE_LEVELS - 1)
_Static_assert(K == 2, "error_table_lanes.inc's table kernel holds 4^-l for l <= 3");
enum { L = _TLOD_QUAD_LANES, G = 2 << K, S = G + 1 };

typedef struct lanes_in {
  float p[4][3][L], n[4][3][L], alpha[4][L];
} lanes_in;

typedef struct lanes_out {
  double m[L], worst2[K + 1][L], slack[L], grid_max[L];
  float table[K + 3][L]; /* measured: error_table[0..K], error_tail, error_slack */
  float bound[L], center[3][L], radius[L];
} lanes_out;

typedef void (*quads_kernel)(const lanes_in* in, bool measured, lanes_out* out);

/* Inlined, so that the levels' constant steps unroll the sample loops. */
#if defined(__GNUC__)
#define INLINE inline __attribute__((always_inline))
#else
#define INLINE inline
#endif

#define KERNEL_FILE "error_table_lanes.inc"
#include "simd_instances.inc"
#undef KERNEL_FILE

static quads_kernel kernel_for(tlod_simd simd) {
#if defined(__x86_64__)
  if (simd == TLOD_SIMD_AVX512) return quads_avx512;
  if (simd == TLOD_SIMD_AVX2) return quads_avx2;
  if (simd == TLOD_SIMD_SSE2) return quads_sse2;
#else
  (void)simd;
#endif
  return quads_scalar;
}

/* Lanes past n repeat patch 0 (their results are dropped). */
static void load_lanes(const _tlod_corners* c, uint32_t n, lanes_in* in) {
  for (int l = 0; l < L; l++) {
    const _tlod_corners* x = &c[(uint32_t)l < n ? l : 0];
    for (int i = 0; i < 4; i++) {
      const float p[3] = {x->p[i].x, x->p[i].y, x->p[i].z}, m[3] = {x->nrm[i].x, x->nrm[i].y, x->nrm[i].z};
      for (int k = 0; k < 3; k++)
        in->p[i][k][l] = p[k], in->n[i][k][l] = m[k];
      in->alpha[i][l] = x->alpha[i];
    }
  }
}

void _tlod_phong_quads(tlod_simd simd, const _tlod_corners* c, uint32_t n, tlod_error_tables tables,
                       tlod_patch_info* const* info) {
  lanes_in in;
  lanes_out out;
  load_lanes(c, n, &in);
  bool measured = tables == TLOD_ERROR_TABLES_MEASURED;
  kernel_for(simd)(&in, measured, &out);
  for (uint32_t l = 0; l < n; l++) {
    tlod_patch_info* p = info[l];
    p->error_bound = p->d_max = out.bound[l];
    p->center[0] = out.center[0][l], p->center[1] = out.center[1][l], p->center[2] = out.center[2][l];
    p->radius = out.radius[l];
    if (tables == TLOD_ERROR_TABLES_CLOSED_FORM) _tlod_error_table_closed_slack(out.slack[l], p);
    if (!measured) continue;
    for (int lv = 0; lv <= K; lv++)
      p->error_table[lv] = out.table[lv][l];
    p->error_tail = out.table[K + 1][l], p->error_slack = out.table[K + 2][l];
  }
}
