/* tesslod::lod -- the draw list's per-block kernels (scheduler_draw_list.c
 * runs them over the visible blocks of its chunks):
 *   strip_edges  per visible patch, which of its up edges (slots,
 *                scheduler_up_edges.c) need a connection strip: the
 *                neighbour visible, across a crease or at another drawn
 *                key (level and blend);
 *   count        drawn levels (-1 when culled), instances per bucket, the
 *                culled count and the e_max range;
 *   write        the instances at their buckets' next slots;
 *   strips       the strips strip_edges marked, in patch and edge order.
 *
 * One copy per SIMD level, chosen at create (the scalar one on the
 * reference path): the scalar loops; AVX2 and AVX-512 copies of the strip
 * test (8 or 16 patches a step, the neighbours' keys gathered, and their
 * visibility only where a key differs or a crease is crossed, 4 bytes at a
 * byte offset with the low byte kept: the array has 3 spare bytes);
 * AVX-512 copies of count, write and strips (16 patches or strips a step;
 * the lanes of one bucket compressed together and interleaved into
 * instances by permutes; a strip's four dwords transposed into its
 * record). Every copy gives bitwise the scalar results: integer and
 * compare work, the blends by the scalar expressions, the e_max range by
 * the scalar rule (first of equal zeros, NaN ignored).
 * lod_list_test checks each level against the oracle, lod_fast_test
 * against the reference path's scalar copies. */
#include <math.h>
#include <string.h>

#include "scheduler_frame.h"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

/* The continuous level as the list sees it: two patches draw the same
 * level and blend exactly when these are equal. Above 0 the drawn level
 * is l = ceil(c) and the blend c - (l - 1), exact (Sterbenz: l - 1 <= c
 * <= 2 (l - 1), or l - 1 == 0), so (l, blend) gives c back; at or below 0
 * (and NaN) every patch draws level 0 at blend 1. */
static float drawn_key(float c) { return c > 0.0f ? c : 0.0f; }

/* Buckets are ordered by shape, then level: bucket index shape * (lmax + 1) + level. */
static uint32_t bucket_of(const _tlod_list_in* in, uint32_t f, uint32_t level) {
  uint32_t shape = in->corners[f] == 4 ? TLOD_PATTERN_QUAD : TLOD_PATTERN_TRIANGLE;
  return shape * in->levels_n + level;
}

/* ---- scalar ---- */

/* The 4-bit strip mask of patch f over its first slots slots. */
static uint32_t patch_edges(const _tlod_list_in* in, uint32_t f, uint32_t slots) {
  float key = drawn_key(in->cont[f]);
  uint32_t mask = 0;
  for (uint32_t k = 0; k < slots; k++) {
    uint32_t s = in->slot[(size_t)k * in->patch_count + f], g = s & _TLOD_UP_FACE;
    uint32_t cross = (s >> 31) | (uint32_t)(drawn_key(in->cont[g]) != key);
    mask |= ((uint32_t)(in->visible[g] != 0) & cross) << k;
  }
  return in->visible[f] ? mask : 0u;
}

/* The bits set in a 4-bit mask. */
static uint32_t bits4(uint32_t mask) { return (UINT32_C(0x4332322132212110) >> (4u * mask)) & 0xFu; }

static uint32_t strip_edges_scalar(const _tlod_list_in* in, uint32_t begin, uint32_t end, uint32_t slots) {
  uint32_t count = 0;
  for (uint32_t f = begin; f < end; f++) {
    uint32_t mask = patch_edges(in, f, slots);
    in->edges[f] = (uint8_t)mask;
    count += bits4(mask);
  }
  return count;
}

/* Whether the 8 patches from f, all inside [f, end), are culled: a visible
 * block's culled patches skipped 8 at a time. */
static bool culled_8(const uint8_t* visible, uint32_t f, uint32_t end) {
  uint64_t w = 1;
  if (f % 8 == 0 && end - f >= 8) memcpy(&w, visible + f, 8);
  return w == 0;
}

/* The running e_max range: the scalar rule every copy follows (the first
 * of equal values kept, NaN never taken). */
static void tally_e(_tlod_list_tally* t, float e) {
  t->e_min = e < t->e_min ? e : t->e_min;
  t->e_max = e > t->e_max ? e : t->e_max;
}

/* Visible patches in runs of one bucket (neighbours mostly share one, and
 * a counts[b]++ per patch would wait on the last one's store). */
static void count_scalar(const _tlod_list_in* in, uint32_t begin, uint32_t end, uint32_t* counts, _tlod_list_tally* t) {
  uint32_t run_bucket = 0, run = 0;
  for (uint32_t f = begin; f < end; f++) {
    if (culled_8(in->visible, f, end)) {
      memset(in->levels + f, -1, 8);
      t->culled += 8, f += 7;
    } else if (!in->visible[f]) {
      in->levels[f] = -1;
      t->culled++;
    } else {
      uint32_t l = _tlod_drawn_level(in->cont[f]), b = bucket_of(in, f, l);
      in->levels[f] = (int8_t)l;
      if (b != run_bucket) counts[run_bucket] += run, run_bucket = b, run = 0;
      run++;
      tally_e(t, in->e_max[f]);
    }
  }
  counts[run_bucket] += run;
}

/* The current bucket's next instance kept as a pointer (slots[bucket]
 * stale until the bucket changes), as count_scalar's runs. */
static void write_scalar(const _tlod_list_in* in, uint32_t begin, uint32_t end, uint32_t* slots) {
  uint32_t bucket = 0;
  tlod_draw_instance* next = in->instances + slots[0];
  for (uint32_t f = begin; f < end; f++) {
    if (culled_8(in->visible, f, end)) {
      f += 7;
      continue;
    }
    if (!in->visible[f]) continue;
    uint32_t l = (uint32_t)in->levels[f], b = bucket_of(in, f, l);
    if (b != bucket) {
      slots[bucket] = (uint32_t)(next - in->instances);
      bucket = b, next = in->instances + slots[b];
    }
    *next++ = (tlod_draw_instance){.patch = f, .level = l, .morph = _tlod_morph_of(in->cont[f], l)};
  }
  slots[bucket] = (uint32_t)(next - in->instances);
}

/* The strip on up edge slot k of visible patch f, where strip_edges found
 * one (the neighbour visible, across a crease or at another level or
 * blend: see _tlod_strip_needed). Edges blend with their patch. */
static tlod_draw_strip strip_at(const _tlod_list_in* in, uint32_t f, uint32_t k) {
  uint32_t s = in->slot[(size_t)k * in->patch_count + f], g = s & _TLOD_UP_FACE;
  bool smooth = !(s & _TLOD_UP_CREASE);
  uint32_t l = (uint32_t)in->levels[f];
  float m = _tlod_morph_of(in->cont[f], l);
  float cg = in->cont[g];
  uint32_t lg = _tlod_drawn_level(cg);
  float mg = _tlod_morph_of(cg, lg);
  /* The coarser side's edge points are exact when its new vertices are at
   * rest: then the finer side has the same points (all of lower level). */
  bool exact = smooth && l != lg && (l < lg ? m : mg) == 1.0f;
  uint8_t ea = (uint8_t)(s >> _TLOD_UP_EDGE_SHIFT & 3u), eb = (uint8_t)(s >> _TLOD_UP_EDGE_B_SHIFT & 3u);
  return (tlod_draw_strip){f, g, ea, eb, (uint8_t)l, (uint8_t)lg, !smooth, exact};
}

/* The masks of patches [f, min(f + 8, end)) as one word, patch f + i's
 * in byte i (its bits 8 i to 8 i + 7). */
static uint64_t mask_word(const uint8_t* masks, uint32_t f, uint32_t end) {
  uint64_t w = 0;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
  if (end - f >= 8) {
    memcpy(&w, masks + f, 8);
    return w;
  }
#endif
  for (uint32_t i = 0; i < 8 && f + i < end; i++)
    w |= (uint64_t)masks[f + i] << (8 * i);
  return w;
}

/* The marked slots of patches [begin, end) in order: the slot masks of 8
 * patches as one word, bit 8 i + k for slot k of the i-th (slots are in
 * edge order), so its set bits in order are the strips in order (a culled
 * patch's mask is 0). Each as patch f and slot k into f[], k[]; returns
 * how many. */
static uint32_t marked_slots(const _tlod_list_in* in, uint32_t begin, uint32_t end, uint32_t* f, uint32_t* k) {
  uint32_t n = 0;
  for (uint32_t p = begin; p < end; p += 8)
    for (uint64_t w = mask_word(in->edges, p, end); w; w &= w - 1) {
      uint32_t bit = (uint32_t)__builtin_ctzll(w);
      f[n] = p + bit / 8, k[n++] = bit % 8;
    }
  return n;
}

/* The m strips of the marked slots (f[q], k[q]) into out. */
typedef void (*strips_of_fn)(const _tlod_list_in* in, const uint32_t* f, const uint32_t* k, uint32_t m,
                             tlod_draw_strip* out);

/* The strips of patches [begin, end) into out, a block at a time (f[] and
 * k[] hold one block's marked slots) by make; returns how many. */
static uint32_t strips_by_block(const _tlod_list_in* in, uint32_t begin, uint32_t end, tlod_draw_strip* out,
                                strips_of_fn make) {
  uint32_t f[FAST_BLOCK * _TLOD_UP_SLOTS], k[FAST_BLOCK * _TLOD_UP_SLOTS], n = 0;
  for (uint32_t b = begin; b < end; b += FAST_BLOCK) {
    uint32_t e = end - b < FAST_BLOCK ? end : b + FAST_BLOCK, m = marked_slots(in, b, e, f, k);
    make(in, f, k, m, out + n);
    n += m;
  }
  return n;
}

static void strips_of_scalar(const _tlod_list_in* in, const uint32_t* f, const uint32_t* k, uint32_t m,
                             tlod_draw_strip* out) {
  for (uint32_t q = 0; q < m; q++)
    out[q] = strip_at(in, f[q], k[q]);
}

static uint32_t strips_scalar(const _tlod_list_in* in, uint32_t begin, uint32_t end, tlod_draw_strip* out) {
  return strips_by_block(in, begin, end, out, strips_of_scalar);
}

#if defined(__x86_64__)
/* ---- AVX2: the strip test ---- */

#define AVX2_ATTR __attribute__((target("avx2")))
/* drawn_key: max returns its second operand for NaN and for two zeros. */
AVX2_ATTR static uint32_t strip_edges_avx2(const _tlod_list_in* in, uint32_t begin, uint32_t end, uint32_t slots) {
  const __m256 zero = _mm256_setzero_ps();
  const __m256i face = _mm256_set1_epi32((int)_TLOD_UP_FACE), low = _mm256_set1_epi32(0xFF);
  const __m256i none = _mm256_setzero_si256();
  __m256i count = _mm256_setzero_si256();
  uint32_t f = begin, lanes[8];
  for (; end - f >= 8; f += 8) {
    __m256 key = _mm256_max_ps(_mm256_loadu_ps(in->cont + f), zero);
    __m256i own = _mm256_cvtepu8_epi32(_mm_loadl_epi64((const __m128i*)(in->visible + f)));
    __m256i seen = _mm256_xor_si256(_mm256_cmpeq_epi32(own, none), _mm256_cmpeq_epi32(none, none));
    __m256i mask = none;
    for (uint32_t k = 0; k < slots; k++) {
      __m256i s = _mm256_loadu_si256((const __m256i*)(in->slot + (size_t)k * in->patch_count + f));
      __m256i g = _mm256_and_si256(s, face);
      __m256 other = _mm256_max_ps(_mm256_i32gather_ps(in->cont, g, 4), zero);
      __m256i cross =
          _mm256_or_si256(_mm256_srai_epi32(s, 31), _mm256_castps_si256(_mm256_cmp_ps(other, key, _CMP_NEQ_UQ)));
      cross = _mm256_and_si256(seen, cross);
      if (!_mm256_movemask_epi8(cross)) continue; /* as strip_edges_avx512 */
      __m256i vis = _mm256_and_si256(_mm256_i32gather_epi32((const int*)in->visible, g, 1), low);
      __m256i bit = _mm256_andnot_si256(_mm256_cmpeq_epi32(vis, none), cross);
      mask = _mm256_or_si256(mask, _mm256_and_si256(bit, _mm256_set1_epi32(1 << k)));
      count = _mm256_sub_epi32(count, bit);
    }
    _mm256_storeu_si256((__m256i*)lanes, mask);
    for (uint32_t q = 0; q < 8; q++)
      in->edges[f + q] = (uint8_t)lanes[q];
  }
  _mm256_storeu_si256((__m256i*)lanes, count);
  uint32_t total = 0;
  for (uint32_t q = 0; q < 8; q++)
    total += lanes[q];
  return total + strip_edges_scalar(in, f, end, slots);
}

/* ---- AVX-512 ---- */

#define AVX512_ATTR __attribute__((target("avx512f,avx512bw,avx512dq,avx512vl")))

AVX512_ATTR static uint32_t strip_edges_avx512(const _tlod_list_in* in, uint32_t begin, uint32_t end, uint32_t slots) {
  const __m512 zero = _mm512_setzero_ps();
  const __m512i face = _mm512_set1_epi32((int)_TLOD_UP_FACE), low = _mm512_set1_epi32(0xFF);
  const __m512i one = _mm512_set1_epi32(1);
  __m512i count = _mm512_setzero_si512();
  for (uint32_t k = 0; k < slots; k++) /* the block's slot lines asked for at once: the loop waits on them */
    for (uint32_t f = begin; f < end; f += 16)
      _mm_prefetch((const char*)(in->slot + (size_t)k * in->patch_count + f), _MM_HINT_T0);
  uint32_t f = begin;
  for (; end - f >= 16; f += 16) {
    __m512 key = _mm512_max_ps(_mm512_loadu_ps(in->cont + f), zero);
    __m128i own = _mm_loadu_si128((const __m128i*)(in->visible + f));
    __mmask16 seen = _mm_test_epi8_mask(own, own);
    __m512i mask = _mm512_setzero_si512();
    for (uint32_t k = 0; seen && k < slots; k++) {
      __m512i s = _mm512_loadu_si512(in->slot + (size_t)k * in->patch_count + f);
      __m512i g = _mm512_and_si512(s, face);
      __m512 other = _mm512_max_ps(_mm512_mask_i32gather_ps(zero, seen, g, in->cont, 4), zero);
      __mmask16 cross = seen & (_mm512_movepi32_mask(s) | _mm512_cmp_ps_mask(other, key, _CMP_NEQ_UQ));
      if (!cross) continue; /* most neighbours draw the same key: their visibility is not needed */
      __m512i vis = _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), cross, g, in->visible, 1);
      __mmask16 bit = _mm512_test_epi32_mask(vis, low) & cross;
      mask = _mm512_mask_or_epi32(mask, bit, mask, _mm512_set1_epi32(1 << k));
      count = _mm512_mask_add_epi32(count, bit, count, one);
    }
    _mm_storeu_si128((__m128i*)(in->edges + f), _mm512_cvtepi32_epi8(mask));
  }
  return (uint32_t)_mm512_reduce_add_epi32(count) + strip_edges_scalar(in, f, end, slots);
}

/* The set bits of a lane mask (no popcnt instruction assumed). */
static uint32_t bits16(uint32_t m) {
  m -= (m >> 1) & 0x5555u;
  m = (m & 0x3333u) + ((m >> 2) & 0x3333u);
  m = (m + (m >> 4)) & 0x0F0Fu;
  return (m + (m >> 8)) & 0x1Fu;
}

/* 16 patches from f: the visible lanes, their drawn levels and buckets. */
typedef struct lanes16 {
  __mmask16 seen;
  __m512i level, bucket;
} lanes16;

/* _tlod_drawn_level of 16 lanes: 0 unless c > 0, else i = (uint32_t)c, + 1 where (float)i < c. */
AVX512_ATTR static __m512i drawn_levels16(__m512 c) {
  __mmask16 up = _mm512_cmp_ps_mask(c, _mm512_setzero_ps(), _CMP_GT_OQ);
  __m512i i = _mm512_maskz_cvttps_epu32(up, c);
  __mmask16 below = _mm512_cmp_ps_mask(_mm512_cvtepu32_ps(i), c, _CMP_LT_OQ) & up;
  return _mm512_mask_add_epi32(i, below, i, _mm512_set1_epi32(1));
}

/* bucket_of of the 16 patches from f at levels level. */
AVX512_ATTR static __m512i buckets16(const _tlod_list_in* in, uint32_t f, __m512i level) {
  __m512i corners = _mm512_cvtepu8_epi32(_mm_loadu_si128((const __m128i*)(in->corners + f)));
  __mmask16 quad = _mm512_cmpeq_epi32_mask(corners, _mm512_set1_epi32(4));
  return _mm512_mask_add_epi32(level, quad, level, _mm512_set1_epi32((int)(TLOD_PATTERN_QUAD * in->levels_n)));
}

AVX512_ATTR static lanes16 lanes_at(const _tlod_list_in* in, uint32_t f) {
  __m128i own = _mm_loadu_si128((const __m128i*)(in->visible + f));
  __m512i level = drawn_levels16(_mm512_loadu_ps(in->cont + f));
  return (lanes16){_mm_test_epi8_mask(own, own), level, buckets16(in, f, level)};
}

/* The e_max range over lanes seen, as tally_e over them in lane order:
 * NaN lanes left out, the extremes found by reductions, and an extreme of
 * zero (either sign) taken from the first lane holding a zero. */
AVX512_ATTR static void tally_e16(_tlod_list_tally* t, __m512 e, __mmask16 seen) {
  __mmask16 valid = seen & _mm512_cmp_ps_mask(e, e, _CMP_ORD_Q);
  if (!valid) return;
  float lo = _mm512_reduce_min_ps(_mm512_mask_mov_ps(_mm512_set1_ps(INFINITY), valid, e));
  float hi = _mm512_reduce_max_ps(_mm512_mask_mov_ps(_mm512_setzero_ps(), valid, e));
  if (lo == 0.0f) {
    float z[16];
    _mm512_storeu_ps(z, e);
    lo = z[__builtin_ctz(valid & _mm512_cmp_ps_mask(e, _mm512_setzero_ps(), _CMP_EQ_OQ))];
  }
  tally_e(t, lo);
  tally_e(t, hi);
}

/* Instances per bucket of the lanes seen: one bucket a step. */
AVX512_ATTR static void count_buckets16(const lanes16* l, uint32_t* counts) {
  uint32_t b[16];
  _mm512_storeu_si512(b, l->bucket);
  for (__mmask16 left = l->seen; left;) {
    uint32_t bucket = b[__builtin_ctz(left)];
    __mmask16 same = left & _mm512_cmpeq_epi32_mask(l->bucket, _mm512_set1_epi32((int)bucket));
    counts[bucket] += bits16(same);
    left &= (__mmask16)~same;
  }
}

AVX512_ATTR static void count_avx512(const _tlod_list_in* in, uint32_t begin, uint32_t end, uint32_t* counts,
                                     _tlod_list_tally* t) {
  uint32_t f = begin;
  for (; end - f >= 16; f += 16) {
    lanes16 l = lanes_at(in, f);
    __m512i level = _mm512_mask_mov_epi32(_mm512_set1_epi32(-1), l.seen, l.level);
    _mm_storeu_si128((__m128i*)(in->levels + f), _mm512_cvtepi32_epi8(level));
    t->culled += 16 - bits16(l.seen);
    if (!l.seen) continue;
    count_buckets16(&l, counts);
    tally_e16(t, _mm512_loadu_ps(in->e_max + f), l.seen);
  }
  count_scalar(in, f, end, counts, t);
}

/* _tlod_morph_of of 16 lanes: 1 at level 0, else c - (level - 1) clamped to [0, 1]. */
AVX512_ATTR static __m512 morphs16(__m512 c, __m512i level) {
  __m512 one = _mm512_set1_ps(1.0f), zero = _mm512_setzero_ps();
  __m512 m = _mm512_sub_ps(c, _mm512_cvtepu32_ps(_mm512_sub_epi32(level, _mm512_set1_epi32(1))));
  m = _mm512_mask_mov_ps(m, _mm512_cmp_ps_mask(m, one, _CMP_GT_OQ), one);
  m = _mm512_mask_mov_ps(m, _mm512_cmp_ps_mask(m, zero, _CMP_LT_OQ), zero);
  return _mm512_mask_mov_ps(m, _mm512_cmpeq_epi32_mask(level, _mm512_setzero_si512()), one);
}

/* Instances {p[i], l[i], m[i]} for i < n at out: the three lane vectors
 * interleaved into 3 x 16 dwords (dword 3 i + field), by two-source
 * permutes of p and l and a masked permute of m, and stored up to 3 n.
 * Output vector o, lane j holds dword g = 16 o + j: instance g / 3, field
 * g mod 3 (k_from_pl: i from p or 16 + i from l; k_from_m: i; k_is_m:
 * the lanes of field 2). */
static const int32_t k_from_pl[3][16] = {{0, 16, 0, 1, 17, 1, 2, 18, 2, 3, 19, 3, 4, 20, 4, 5},
                                         {21, 5, 6, 22, 6, 7, 23, 7, 8, 24, 8, 9, 25, 9, 10, 26},
                                         {10, 11, 27, 11, 12, 28, 12, 13, 29, 13, 14, 30, 14, 15, 31, 15}};
static const int32_t k_from_m[3][16] = {{0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4, 4, 5},
                                        {5, 5, 6, 6, 6, 7, 7, 7, 8, 8, 8, 9, 9, 9, 10, 10},
                                        {10, 11, 11, 11, 12, 12, 12, 13, 13, 13, 14, 14, 14, 15, 15, 15}};
static const uint16_t k_is_m[3] = {0x4924, 0x2492, 0x9249};

AVX512_ATTR static void store_instances(tlod_draw_instance* out, uint32_t n, __m512i p, __m512i l, __m512i m) {
  _Static_assert(sizeof(tlod_draw_instance) == 12, "an instance is three dwords");
  int32_t* to = (int32_t*)(void*)out;
  for (uint32_t o = 0; o < 3 && 16 * o < 3 * n; o++) {
    __m512i v = _mm512_permutex2var_epi32(p, _mm512_loadu_si512(k_from_pl[o]), l);
    v = _mm512_mask_permutexvar_epi32(v, k_is_m[o], _mm512_loadu_si512(k_from_m[o]), m);
    uint32_t dwords = 3 * n - 16 * o;
    _mm512_mask_storeu_epi32(to + (size_t)16 * o, (__mmask16)(dwords >= 16 ? 0xFFFFu : (1u << dwords) - 1u), v);
  }
}

/* The lanes of one bucket at a time, compressed, then stored as instances. */
AVX512_ATTR static void write_avx512(const _tlod_list_in* in, uint32_t begin, uint32_t end, uint32_t* slots) {
  uint32_t f = begin;
  for (; end - f >= 16; f += 16) {
    __m128i lv = _mm_loadu_si128((const __m128i*)(in->levels + f));
    __mmask16 seen = _mm_cmpgt_epi8_mask(lv, _mm_set1_epi8(-1));
    if (!seen) continue;
    __m512i level = _mm512_cvtepi8_epi32(lv), bucket = buckets16(in, f, level);
    __m512 morph = morphs16(_mm512_loadu_ps(in->cont + f), level);
    __m512i patch = _mm512_add_epi32(_mm512_set1_epi32((int)f),
                                     _mm512_set_epi32(15, 14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0));
    uint32_t b[16];
    _mm512_storeu_si512(b, bucket);
    for (__mmask16 left = seen; left;) {
      uint32_t k = b[__builtin_ctz(left)], n;
      __mmask16 same = left & _mm512_cmpeq_epi32_mask(bucket, _mm512_set1_epi32((int)k));
      /* compressed in registers (Zen 4 microcodes the store form) */
      n = bits16(same);
      store_instances(in->instances + slots[k], n, _mm512_maskz_compress_epi32(same, patch),
                      _mm512_maskz_compress_epi32(same, level),
                      _mm512_castps_si512(_mm512_maskz_compress_ps(same, morph)));
      slots[k] += n;
      left &= (__mmask16)~same;
    }
  }
  write_scalar(in, f, end, slots);
}

/* Records {a[i], b[i], c[i], d[i]} for i < n (at most 16) at out: a 4 x 4
 * transpose within each 128-bit lane, then of the lanes, so that record i
 * is output vector i / 4, lane i % 4. */
AVX512_ATTR static void store_records(__m512i a, __m512i b, __m512i c, __m512i d, uint32_t n, void* out) {
  __m512i t0 = _mm512_unpacklo_epi32(a, b), t1 = _mm512_unpackhi_epi32(a, b);
  __m512i t2 = _mm512_unpacklo_epi32(c, d), t3 = _mm512_unpackhi_epi32(c, d);
  __m512i r0 = _mm512_unpacklo_epi64(t0, t2), r1 = _mm512_unpackhi_epi64(t0, t2);
  __m512i r2 = _mm512_unpacklo_epi64(t1, t3), r3 = _mm512_unpackhi_epi64(t1, t3);
  __m512i u0 = _mm512_shuffle_i32x4(r0, r1, 0x44), u1 = _mm512_shuffle_i32x4(r0, r1, 0xEE);
  __m512i u2 = _mm512_shuffle_i32x4(r2, r3, 0x44), u3 = _mm512_shuffle_i32x4(r2, r3, 0xEE);
  __m512i rec[4] = {_mm512_shuffle_i32x4(u0, u2, 0x88), _mm512_shuffle_i32x4(u0, u2, 0xDD),
                    _mm512_shuffle_i32x4(u1, u3, 0x88), _mm512_shuffle_i32x4(u1, u3, 0xDD)};
  int32_t* to = out;
  for (uint32_t v = 0; v < 4 && 4 * v < n; v++) {
    uint32_t records = n - 4 * v >= 4 ? 4 : n - 4 * v;
    _mm512_mask_storeu_epi32(to + (size_t)16 * v, (__mmask16)((1u << (4 * records)) - 1u), rec[v]);
  }
}

/* 16 strips from the marked slots (f[q], k[q]) into out: strip_at in
 * lanes (slots, continuous levels gathered), the four dwords of each strip
 * made in four vectors and transposed into 16-byte records (the padding
 * zero). */
AVX512_ATTR static void strips16(const _tlod_list_in* in, const uint32_t* f, const uint32_t* k, uint32_t n,
                                 tlod_draw_strip* out) {
  _Static_assert(sizeof(tlod_draw_strip) == 16, "a strip is four dwords");
  __mmask16 lanes = (__mmask16)(n >= 16 ? 0xFFFFu : (1u << n) - 1u);
  const __m512i three = _mm512_set1_epi32(3);
  __m512i pa = _mm512_maskz_loadu_epi32(lanes, f), kk = _mm512_maskz_loadu_epi32(lanes, k);
  __m512i at = _mm512_add_epi32(_mm512_mullo_epi32(kk, _mm512_set1_epi32((int)in->patch_count)), pa);
  __m512i s = _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), lanes, at, in->slot, 4);
  __m512i pb = _mm512_and_si512(s, _mm512_set1_epi32((int)_TLOD_UP_FACE));
  __m512 ca = _mm512_mask_i32gather_ps(_mm512_setzero_ps(), lanes, pa, in->cont, 4);
  __m512 cb = _mm512_mask_i32gather_ps(_mm512_setzero_ps(), lanes, pb, in->cont, 4);
  __m512i la = drawn_levels16(ca), lb = drawn_levels16(cb);
  __m512 ma = morphs16(ca, la), mb = morphs16(cb, lb);
  __mmask16 crease = _mm512_movepi32_mask(s);
  __m512 coarse = _mm512_mask_blend_ps(_mm512_cmplt_epu32_mask(la, lb), mb, ma);
  __mmask16 exact = (__mmask16)(~crease & _mm512_cmpneq_epi32_mask(la, lb) &
                                _mm512_cmp_ps_mask(coarse, _mm512_set1_ps(1.0f), _CMP_EQ_OQ));
  __m512i ea = _mm512_and_si512(_mm512_srli_epi32(s, _TLOD_UP_EDGE_SHIFT), three);
  __m512i eb = _mm512_and_si512(_mm512_srli_epi32(s, _TLOD_UP_EDGE_B_SHIFT), three);
  __m512i d2 = _mm512_or_si512(_mm512_or_si512(ea, _mm512_slli_epi32(eb, 8)),
                               _mm512_or_si512(_mm512_slli_epi32(la, 16), _mm512_slli_epi32(lb, 24)));
  __m512i d3 = _mm512_or_si512(_mm512_maskz_mov_epi32(crease, _mm512_set1_epi32(1)),
                               _mm512_maskz_mov_epi32(exact, _mm512_set1_epi32(0x100)));
  store_records(pa, pb, d2, d3, n, out);
}

AVX512_ATTR static void strips_of_avx512(const _tlod_list_in* in, const uint32_t* f, const uint32_t* k, uint32_t m,
                                         tlod_draw_strip* out) {
  for (uint32_t q = 0; q < m; q += 16)
    strips16(in, f + q, k + q, m - q, out + q);
}

static uint32_t strips_avx512(const _tlod_list_in* in, uint32_t begin, uint32_t end, tlod_draw_strip* out) {
  return strips_by_block(in, begin, end, out, strips_of_avx512);
}
#endif

_tlod_list_kernels _tlod_list_kernels_for(tlod_simd simd) {
#if defined(__x86_64__)
  if (simd == TLOD_SIMD_AVX512)
    return (_tlod_list_kernels){strip_edges_avx512, count_avx512, write_avx512, strips_avx512};
  if (simd == TLOD_SIMD_AVX2) return (_tlod_list_kernels){strip_edges_avx2, count_scalar, write_scalar, strips_scalar};
#else
  (void)simd;
#endif
  return (_tlod_list_kernels){strip_edges_scalar, count_scalar, write_scalar, strips_scalar};
}
