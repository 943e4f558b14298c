// Lockstep SIMD C, for the simd backend: one kernel instance runs a group of RILL_W elements
// (lanes) at once, as in ISPC or a GPU's SIMT.
//
// The scalar C of CEmitter.cpp computes one element per iteration, so each branch the kernel
// takes is a branch the CPU must predict, and each loop runs once per element. Here the
// kernel is first lowered for lanes (passes::lower_lockstep: control flow becomes lane masks,
// assignments under a mask blend), then printed by the shared C-family printer through the
// lockstep dialect (VectorDialect.h): every variable component is a vector of lanes and every
// operation applies to all of them. This file adds the vector prelude and the entry point.
//
// Lanes that are off still compute values (which are then not kept), so every operation must
// be harmless on any input: the rill_* helpers already are (integer division by zero gives 0,
// conversions saturate, gathers clamp their indices and arrays are never empty). Each lane
// computes exactly the operations of the scalar code, in the same order and precision, so
// results are bit for bit those of emit_c().
// A group is RILL_W consecutive elements, or a tile of a 2D stream when the launch range is
// whole rows: RILL_W/2 x 2 at 8 lanes, 4 x 4 at 16 (the backend hands the lockstep kernel
// ranges of whole tile rows, cpu::lockstep_tile_rows; rill_next_group). A group shorter
// than RILL_W repeats its last element in the spare lanes and stores only the real ones.
#include "LockstepEmitter.h"

#include <string_view>

#include "../codegen/CFamilyPrinter.h"
#include "../codegen/Helpers.h"
#include "../codegen/SourceMap.h"
#include "../cpu/CEmitter.h"
#include "../cpu/HostKernel.h"
#include "VectorDialect.h"
#include "rill/ir/Visitor.h"
#include "rill/passes/Passes.h"

namespace rill::simd {

using cpu::c_entry_locals;
using cpu::c_head;

using namespace ir;

namespace {

// The vector frame, after c_head() (rill_real is float: the double mode has no lockstep
// form): vector types, broadcasts, loads, selections and gathers, before the helpers' vector
// bodies (lockstep_helpers()). rill_vi holds Int values and Bool lane masks (-1 true, 0 false).
const char* kVectorPrelude = R"(
typedef rill_real rill_vr __attribute__((vector_size(RILL_W * sizeof(rill_real))));
typedef int32_t rill_vi __attribute__((vector_size(RILL_W * 4)));
typedef uint32_t rill_vu __attribute__((vector_size(RILL_W * 4)));

/* Broadcasts are vector initializers (RILL_SPLAT(x) is {x, ..., x}, RILL_W times), not loops:
   a kernel holds thousands of them, and GCC spent over half of a ray tracer's compile time
   unrolling and folding one loop per broadcast. */
RILL_FN rill_vr rill_splat_r(rill_real x) { return (rill_vr)RILL_SPLAT(x); }
RILL_FN rill_vi rill_splat_i(int32_t x) { return (rill_vi)RILL_SPLAT(x); }
/* RILL_AVX2: 8 lanes in AVX2 registers, through the compiler's builtins (the same names in
   GCC 12+ and clang) rather than <immintrin.h>, whose 46,000 preprocessed lines took a third
   of a second to parse in every kernel. Without them the generic code below serves. */
#if defined(__AVX2__) && RILL_W == 8 && defined(__has_builtin)
#if __has_builtin(__builtin_shufflevector) && __has_builtin(__builtin_ia32_maskloadps) && \
    __has_builtin(__builtin_ia32_ptestz256) && __has_builtin(__builtin_ia32_roundps256) && \
    __has_builtin(__builtin_ia32_sqrtps256)
#define RILL_AVX2 1
typedef float rill_v4f __attribute__((vector_size(16)));
typedef float rill_v4f_u __attribute__((vector_size(16), aligned(4)));
typedef int32_t rill_v4i __attribute__((vector_size(16)));
typedef int32_t rill_v2i_u __attribute__((vector_size(8), aligned(4)));
typedef long long rill_v4q __attribute__((vector_size(32)));
#endif
#endif
/* RILL_AVX512: 16 lanes in AVX-512 registers (zmm), the simd backend's strict kernels where
   the CPU has AVX-512 F, VL, BW and DQ (SimdBackend.cpp). The builtins have the same names
   in GCC and clang. Without them (or at other widths) the generic code serves. */
#if defined(__AVX512F__) && RILL_W == 16 && defined(__has_builtin)
#if __has_builtin(__builtin_ia32_cmpd512_mask) && __has_builtin(__builtin_ia32_gathersiv16sf) && \
    __has_builtin(__builtin_ia32_gathersiv16si) && __has_builtin(__builtin_ia32_rndscaleps_mask)
#define RILL_AVX512 1
/* vrndscaleps and vsqrtps on all 16 lanes (rill_v_floor, rill_v_sqrt and kin), exact as
   their 8-lane AVX forms; the square root's builtin is named differently in GCC and clang.
   4 is _MM_FROUND_CUR_DIRECTION. */
#define RILL_ROUND16(a, imm) \
  __builtin_ia32_rndscaleps_mask((a), (imm), (a), (unsigned short)0xffff, 4)
#if __has_builtin(__builtin_ia32_sqrtps512_mask)
#define RILL_SQRT16(a) __builtin_ia32_sqrtps512_mask((a), (a), (unsigned short)0xffff, 4)
#else
#define RILL_SQRT16(a) __builtin_ia32_sqrtps512((a), 4)
#endif
#endif
#endif
/* Each lane's element of a stream: p[lane[l] * stride] (p points at the component). */
#if RILL_W == 8
RILL_FN rill_vr rill_lanes_r(const float* p, const int64_t* lane, int64_t n) {
  return (rill_vr){p[lane[0] * n], p[lane[1] * n], p[lane[2] * n], p[lane[3] * n],
                   p[lane[4] * n], p[lane[5] * n], p[lane[6] * n], p[lane[7] * n]};
}
RILL_FN rill_vi rill_lanes_i(const int32_t* p, const int64_t* lane, int64_t n) {
  return (rill_vi){p[lane[0] * n], p[lane[1] * n], p[lane[2] * n], p[lane[3] * n],
                   p[lane[4] * n], p[lane[5] * n], p[lane[6] * n], p[lane[7] * n]};
}
#elif RILL_W == 16
RILL_FN rill_vr rill_lanes_r(const float* p, const int64_t* lane, int64_t n) {
  return (rill_vr){p[lane[0] * n],  p[lane[1] * n],  p[lane[2] * n],  p[lane[3] * n],
                   p[lane[4] * n],  p[lane[5] * n],  p[lane[6] * n],  p[lane[7] * n],
                   p[lane[8] * n],  p[lane[9] * n],  p[lane[10] * n], p[lane[11] * n],
                   p[lane[12] * n], p[lane[13] * n], p[lane[14] * n], p[lane[15] * n]};
}
RILL_FN rill_vi rill_lanes_i(const int32_t* p, const int64_t* lane, int64_t n) {
  return (rill_vi){p[lane[0] * n],  p[lane[1] * n],  p[lane[2] * n],  p[lane[3] * n],
                   p[lane[4] * n],  p[lane[5] * n],  p[lane[6] * n],  p[lane[7] * n],
                   p[lane[8] * n],  p[lane[9] * n],  p[lane[10] * n], p[lane[11] * n],
                   p[lane[12] * n], p[lane[13] * n], p[lane[14] * n], p[lane[15] * n]};
}
#else
RILL_FN rill_vr rill_lanes_r(const float* p, const int64_t* lane, int64_t n) {
  rill_vr r; for (int l = 0; l < RILL_W; ++l) r[l] = p[lane[l] * n]; return r;
}
RILL_FN rill_vi rill_lanes_i(const int32_t* p, const int64_t* lane, int64_t n) {
  rill_vi r; for (int l = 0; l < RILL_W; ++l) r[l] = p[lane[l] * n]; return r;
}
#endif
#ifdef RILL_AVX2
RILL_FN int rill_any(rill_vi m) { return !__builtin_ia32_ptestz256((rill_v4q)m, (rill_v4q)m); }
#elif defined(RILL_AVX512)
/* vpcmpd into a mask register, compared with 0 (_mm512_cmpneq_epi32_mask). */
RILL_FN int rill_any(rill_vi m) {
  return __builtin_ia32_cmpd512_mask(m, (rill_vi){0}, 4, (unsigned short)0xffff) != 0;
}
#else
RILL_FN int rill_any(rill_vi m) {
  int32_t r = 0;
  for (int l = 0; l < RILL_W; ++l) r |= m[l];
  return r != 0;
}
#endif
/* The groups of a launch range [begin, end). A range of whole rows of a 2D stream goes in
   tiles of RILL_W/RILL_TILE_ROWS x RILL_TILE_ROWS elements (4 x 2 at 8 lanes, 4 x 4 at 16;
   rows taken from the range's first row; the last rows of a range, fewer than
   RILL_TILE_ROWS, in tiles of as many rows, a single row in runs of RILL_W): neighbouring
   pixels take similar paths through a kernel, and a tile's lanes lie closer together than
   RILL_W along one row, so they diverge less. Any other range goes in runs of RILL_W
   consecutive elements. The spare lanes of a short group repeat its last element; the return
   value is the group's element count, 0 after the last.
   A compacted launch (rill_run_list) goes instead through positions [begin, end) of a list of
   element indices, RILL_W at a time, so that its lanes run only the selected elements. */
typedef struct { int64_t next, end, width; int tiled; const int64_t* list; } rill_groups;
RILL_FN rill_groups rill_groups_of(const rill_launch* L, int64_t begin, int64_t end) {
  rill_groups g = {begin, end, L->width, 0, 0};
  g.tiled = RILL_W >= 4 && L->height >= 2 && L->width >= RILL_W / RILL_TILE_ROWS &&
            L->count == L->width * L->height && begin % L->width == 0 && end % L->width == 0;
  return g;
}
RILL_FN int rill_next_group(rill_groups* g, int64_t lane[RILL_W]) {
  if (g->next >= g->end) return 0;
  int n = 0;
  const int64_t x = g->next % g->width, row = g->next - x;
  const int64_t rows_left = (g->end - row) / g->width;
  const int64_t rows = rows_left < RILL_TILE_ROWS ? rows_left : RILL_TILE_ROWS;
  if (g->list) {
    n = g->end - g->next < RILL_W ? (int)(g->end - g->next) : RILL_W;
    for (int l = 0; l < n; ++l) lane[l] = g->list[g->next + l];
    g->next += n;
  } else if (g->tiled && rows >= 2) {
    const int64_t cols = g->width - x < RILL_W / rows ? g->width - x : RILL_W / rows;
    for (int64_t j = 0; j < rows; ++j)
      for (int64_t i = 0; i < cols; ++i) lane[n++] = row + j * g->width + x + i;
    g->next = x + cols < g->width ? g->next + cols : row + rows * g->width;
  } else {
    n = g->end - g->next < RILL_W ? (int)(g->end - g->next) : RILL_W;
    for (int l = 0; l < n; ++l) lane[l] = g->next + l;
    g->next += n;
  }
  for (int l = n; l < RILL_W; ++l) lane[l] = lane[n - 1];
  return n;
}

RILL_FN rill_vi rill_sel_i(rill_vi c, rill_vi a, rill_vi b) { return (a & c) | (b & ~c); }
RILL_FN rill_vr rill_sel_r(rill_vi c, rill_vr a, rill_vr b) {
  return (rill_vr)(((rill_vi)a & c) | ((rill_vi)b & ~c));
}
RILL_FN rill_vi rill_mask(rill_vi c) { return -(c != 0); }
#define RILL_CMP(x) __builtin_convertvector((x), rill_vi)

/* Gathers: each lane loads base[i]. With AVX2, one gather instruction (vgatherdps,
   vpgatherdd) per component: GCC compiled the scalar loads of a vector initializer or a
   per-lane loop into a loop through the stack, and the instruction measured 4-15% faster on
   the ray tracer's traversal (docs/benchmarks/2026-12-07-simd-gathers.md). The builtins'
   names differ between GCC and clang; without either, scalar loads (a vector initializer).
   Each lane reads exactly base[i[l]], as the scalar loads do. Compiling a kernel with
   -DRILL_NO_HW_GATHER (a RILL_CC wrapper) gives the earlier loads, to measure the two. */
#if defined(RILL_AVX2) && !defined(RILL_NO_HW_GATHER) /* RILL_AVX2: __has_builtin exists */
#if __has_builtin(__builtin_ia32_gathersiv8sf) && __has_builtin(__builtin_ia32_gathersiv8si)
#define RILL_HW_GATHER 1
#define RILL_GATHER_PS(base, i) \
  __builtin_ia32_gathersiv8sf((rill_vr){0}, (base), (i), (rill_vr)rill_splat_i(-1), 4)
#define RILL_GATHER_D(base, i) \
  __builtin_ia32_gathersiv8si((rill_vi){0}, (const int*)(base), (i), rill_splat_i(-1), 4)
#elif __has_builtin(__builtin_ia32_gatherd_ps256) && __has_builtin(__builtin_ia32_gatherd_d256)
#define RILL_HW_GATHER 1
#define RILL_GATHER_PS(base, i) \
  __builtin_ia32_gatherd_ps256((rill_vr){0}, (base), (i), (rill_vr)rill_splat_i(-1), 4)
#define RILL_GATHER_D(base, i) \
  __builtin_ia32_gatherd_d256((rill_vi){0}, (const int*)(base), (i), rill_splat_i(-1), 4)
#endif
#endif
/* 16 lanes: vgatherdps / vpgatherdd on zmm, all 16 lanes on (mask 0xffff); the same names in
   GCC and clang (RILL_AVX512 checked them). */
#if defined(RILL_AVX512) && !defined(RILL_NO_HW_GATHER)
#define RILL_HW_GATHER 1
#define RILL_GATHER_PS(base, i) \
  __builtin_ia32_gathersiv16sf((rill_vr){0}, (base), (i), (unsigned short)0xffff, 4)
#define RILL_GATHER_D(base, i) \
  __builtin_ia32_gathersiv16si((rill_vi){0}, (const int*)(base), (i), (unsigned short)0xffff, 4)
#endif
#ifdef RILL_HW_GATHER
/* Whether every lane has the same index (lanes that are off included: they may not, and then
   the gather runs). Where the lanes walk the same voxel, they load the same triangle ids and
   the same triangles: one load and a broadcast then, the same values. Measured for the int
   gathers and vec3 elements only (2026-12-07-simd-gathers.md): 1.3x on thesis B, within the
   noise on thesis C and the bunny, whose groups diverge more. -DRILL_NO_SAME_INDEX turns the
   test off, to measure it. */
#ifdef RILL_NO_SAME_INDEX
RILL_FN int rill_same_index(rill_vi i) { return 0; }
#else
RILL_FN int rill_same_index(rill_vi i) { return !rill_any(RILL_CMP(i != rill_splat_i(i[0]))); }
#endif
RILL_FN rill_vr rill_gather_r(const float* base, rill_vi i) { return RILL_GATHER_PS(base, i); }
RILL_FN rill_vi rill_gather_i(const int32_t* base, rill_vi i) {
  if (rill_same_index(i)) return rill_splat_i(base[i[0]]);
  return RILL_GATHER_D(base, i);
}
#elif RILL_W == 8
RILL_FN rill_vr rill_gather_r(const float* base, rill_vi i) {
  return (rill_vr){base[i[0]], base[i[1]], base[i[2]], base[i[3]], base[i[4]], base[i[5]], base[i[6]], base[i[7]]};
}
RILL_FN rill_vi rill_gather_i(const int32_t* base, rill_vi i) {
  return (rill_vi){base[i[0]], base[i[1]], base[i[2]], base[i[3]], base[i[4]], base[i[5]], base[i[6]], base[i[7]]};
}
#else
RILL_FN rill_vr rill_gather_r(const float* base, rill_vi i) {
  rill_vr r; for (int l = 0; l < RILL_W; ++l) r[l] = base[i[l]]; return r;
}
RILL_FN rill_vi rill_gather_i(const int32_t* base, rill_vi i) {
  rill_vi r; for (int l = 0; l < RILL_W; ++l) r[l] = base[i[l]]; return r;
}
#endif
#ifdef RILL_AVX2
/* Three or four consecutive floats per lane (a vec3/vec4 element): one 16-byte load per lane
   (masked to three floats for vec3, so the last element never reads past the array) and a
   transpose, instead of eight scalar loads per component. The shuffles are those of
   _mm256_insertf128_ps, _mm256_unpacklo/hi_ps and _mm256_shuffle_ps (0x44, 0xee). */
RILL_FN void rill_transpose_lanes(const rill_v4f q[8], rill_vr* x, rill_vr* y, rill_vr* z, rill_vr* w) {
  const rill_vr r0 = __builtin_shufflevector(q[0], q[4], 0, 1, 2, 3, 4, 5, 6, 7);
  const rill_vr r1 = __builtin_shufflevector(q[1], q[5], 0, 1, 2, 3, 4, 5, 6, 7);
  const rill_vr r2 = __builtin_shufflevector(q[2], q[6], 0, 1, 2, 3, 4, 5, 6, 7);
  const rill_vr r3 = __builtin_shufflevector(q[3], q[7], 0, 1, 2, 3, 4, 5, 6, 7);
  const rill_vr t0 = __builtin_shufflevector(r0, r1, 0, 8, 1, 9, 4, 12, 5, 13);
  const rill_vr t1 = __builtin_shufflevector(r2, r3, 0, 8, 1, 9, 4, 12, 5, 13);
  const rill_vr t2 = __builtin_shufflevector(r0, r1, 2, 10, 3, 11, 6, 14, 7, 15);
  const rill_vr t3 = __builtin_shufflevector(r2, r3, 2, 10, 3, 11, 6, 14, 7, 15);
  *x = __builtin_shufflevector(t0, t1, 0, 1, 8, 9, 4, 5, 12, 13);
  *y = __builtin_shufflevector(t0, t1, 2, 3, 10, 11, 6, 7, 14, 15);
  *z = __builtin_shufflevector(t2, t3, 0, 1, 8, 9, 4, 5, 12, 13);
  if (w) *w = __builtin_shufflevector(t2, t3, 2, 3, 10, 11, 6, 7, 14, 15);
}
#ifndef RILL_HW_GATHER
RILL_FN void rill_gather3_r(const float* base, rill_vi i, rill_vr* x, rill_vr* y, rill_vr* z) {
  const rill_v4i m = {-1, -1, -1, 0};
  rill_v4f q[8];
  for (int l = 0; l < 8; ++l) q[l] = __builtin_ia32_maskloadps((const rill_v4f*)(base + i[l]), m);
  rill_transpose_lanes(q, x, y, z, 0);
}
/* Two consecutive ints per lane (an ivec2 element): one 8-byte load per lane and a transpose
   (the shuffles of _mm_unpacklo_epi64, _mm256_insertf128_si256, _mm256_shuffle_ps 0x88/0xdd). */
RILL_FN void rill_gather2_i(const int32_t* base, rill_vi i, rill_vi* x, rill_vi* y) {
  rill_v2i_u q[8];
  for (int l = 0; l < 8; ++l) q[l] = *(const rill_v2i_u*)(base + i[l]);
  const rill_v4i a = __builtin_shufflevector(q[0], q[1], 0, 1, 2, 3);
  const rill_v4i b = __builtin_shufflevector(q[2], q[3], 0, 1, 2, 3);
  const rill_v4i c = __builtin_shufflevector(q[4], q[5], 0, 1, 2, 3);
  const rill_v4i d = __builtin_shufflevector(q[6], q[7], 0, 1, 2, 3);
  const rill_vi lo = __builtin_shufflevector(a, c, 0, 1, 2, 3, 4, 5, 6, 7);
  const rill_vi hi = __builtin_shufflevector(b, d, 0, 1, 2, 3, 4, 5, 6, 7);
  *x = __builtin_shufflevector(lo, hi, 0, 2, 8, 10, 4, 6, 12, 14);
  *y = __builtin_shufflevector(lo, hi, 1, 3, 9, 11, 5, 7, 13, 15);
}
#endif
RILL_FN void rill_gather4_r(const float* base, rill_vi i, rill_vr* x, rill_vr* y, rill_vr* z, rill_vr* w) {
  rill_v4f q[8];
  for (int l = 0; l < 8; ++l) q[l] = *(const rill_v4f_u*)(base + i[l]);
  rill_transpose_lanes(q, x, y, z, w);
}
#endif
#ifdef RILL_HW_GATHER
/* With gather instructions, a gather per component (measured faster than the load and
   transpose above for vec3; vec4 keeps the transpose at 8 lanes, unmeasured). */
RILL_FN void rill_gather3_r(const float* base, rill_vi i, rill_vr* x, rill_vr* y, rill_vr* z) {
  if (rill_same_index(i)) {
    const float* p = base + i[0];
    *x = rill_splat_r(p[0]);
    *y = rill_splat_r(p[1]);
    *z = rill_splat_r(p[2]);
    return;
  }
  *x = rill_gather_r(base, i);
  *y = rill_gather_r(base + 1, i);
  *z = rill_gather_r(base + 2, i);
}
RILL_FN void rill_gather2_i(const int32_t* base, rill_vi i, rill_vi* x, rill_vi* y) {
  *x = rill_gather_i(base, i);
  *y = rill_gather_i(base + 1, i);
}
#ifndef RILL_AVX2
/* 16 lanes: a gather per component for vec4 too (no transpose of 16 lanes). */
RILL_FN void rill_gather4_r(const float* base, rill_vi i, rill_vr* x, rill_vr* y, rill_vr* z, rill_vr* w) {
  *x = rill_gather_r(base, i);
  *y = rill_gather_r(base + 1, i);
  *z = rill_gather_r(base + 2, i);
  *w = rill_gather_r(base + 3, i);
}
#endif
#endif
#if defined(RILL_AVX2) || defined(RILL_HW_GATHER)
#define RILL_HAVE_GATHER34 1
#endif

/* The helpers without vector code run lane by lane through their scalar definitions. */
#define RILL_LANES1(name, R, A, fn) \
  RILL_FN R name(A a) { R r; for (int l = 0; l < RILL_W; ++l) r[l] = fn(a[l]); return r; }
#define RILL_LANES2(name, R, A, fn) \
  RILL_FN R name(A a, A b) { R r; for (int l = 0; l < RILL_W; ++l) r[l] = fn(a[l], b[l]); return r; }
)";

// The lane-group operations (VectorDialect::group): the group is the RILL_W lanes, and m
// the mask of the lanes taking part (-1 on, 0 off). Integer results are the same in any
// order, so the loops need no fixed tree. Only kernels that use them get them, so other
// kernels' source is unchanged.
const char* kGroupPrelude = R"(
RILL_FN uint32_t rill_g_bits(rill_vi x) {
  uint32_t b = 0;
  for (int l = 0; l < RILL_W; ++l) b |= (uint32_t)(x[l] != 0) << l;
  return b;
}
RILL_FN rill_vi rill_g_any(rill_vi x, rill_vi m) { return rill_splat_i(-rill_any(x & m)); }
RILL_FN rill_vi rill_g_all(rill_vi x, rill_vi m) { return rill_splat_i(rill_any(~x & m) - 1); }
RILL_FN rill_vi rill_g_ballot(rill_vi x, rill_vi m) {
  return rill_splat_i((int32_t)rill_g_bits(x & m));
}
RILL_FN rill_vi rill_g_count(rill_vi x, rill_vi m) {
  return rill_splat_i(__builtin_popcount(rill_g_bits(x & m)));
}
/* min and max: the best of the active lanes, from the identity. */
#define RILL_G_PICK(name, identity, better) \
  RILL_FN rill_vi name(rill_vi x, rill_vi m) { \
    int32_t r = identity; \
    for (int l = 0; l < RILL_W; ++l) if (m[l] && x[l] better r) r = x[l]; \
    return rill_splat_i(r); \
  }
RILL_G_PICK(rill_g_min, 2147483647, <)
RILL_G_PICK(rill_g_max, -2147483647 - 1, >)
RILL_FN rill_vi rill_g_sum(rill_vi x, rill_vi m) {
  uint32_t r = 0;
  for (int l = 0; l < RILL_W; ++l) r += (uint32_t)(x[l] & m[l]);
  return rill_splat_i((int32_t)r);
}
/* Lane `lane` of x where that lane is active, else the lane's own x. */
#define RILL_G_BCAST(name, V) \
  RILL_FN V name(V x, rill_vi lane, rill_vi m) { \
    V r; \
    for (int l = 0; l < RILL_W; ++l) { \
      const int32_t k = lane[l]; \
      r[l] = k >= 0 && k < RILL_W && m[k] ? x[k] : x[l]; \
    } \
    return r; \
  }
RILL_G_BCAST(rill_g_bcast_i, rill_vi)
RILL_G_BCAST(rill_g_bcast_r, rill_vr)
)";

bool uses_group_ops(const Function& f) {
  bool used = false;
  for_each_stmt(f.body, [&](const Stmt& s) {
    used = used || (s.kind == StmtKind::Assign && op_info(s.op).cls == OpClass::Group);
  });
  return used;
}

// For a helper without a lockstep body, RILL_LANES1/2(rill_v_NAME, result, operand,
// rill_NAME) when an op's HELPER form names it: lane by lane through its scalar definition.
std::string lane_wise(const codegen::Helper& h) {
  auto vtype = [](ScalarKind k) { return k == ScalarKind::Float ? "rill_vr" : "rill_vi"; };
  for (int o = 0; o < kOpCount; ++o) {
    const Op op = static_cast<Op>(o);
    const OpInfo& info = op_info(op);
    for (ScalarKind k : {ScalarKind::Float, ScalarKind::Int}) {
      const OpForm& form = info.form(k);
      if (form.kind != FormKind::Helper || form.text != std::string_view(h.name)) continue;
      std::vector<Type> args(static_cast<size_t>(info.arity), Type{k, 1});
      std::optional<Type> result = result_type(op, args, nullptr);
      if (!result || (info.arity != 1 && info.arity != 2))
        throw Error(std::string("internal: no lane-wise form for helper rill_") + h.name);
      return "RILL_LANES" + std::to_string(info.arity) + "(rill_v_" + h.name + ", " +
             vtype(result->kind) + ", " + vtype(k) + ", rill_" + h.name + ")\n";
    }
  }
  return "";  // not an op's helper (the frame's, or another dialect's)
}

// The lockstep bodies of the helper table (codegen/Helpers.cpp), and the lane-wise wrappers
// of those without one. The same for every kernel, so made once; the on-demand helpers a
// kernel calls follow (emit_c_lockstep).
const std::string& lockstep_helpers() {
  static const std::string text =
      codegen::helper_bodies(codegen::Language::Lockstep, {}, lane_wise);
  return text;
}

}  // namespace

std::string emit_c_lockstep(const Function& optimized, Accuracy accuracy, int lanes,
                            bool source_map) {
  if (accuracy == Accuracy::Double)
    throw Error(
        "lockstep C: the double mode has no lockstep form (the simd backend runs it as scalar C)");
  if (lanes < 2 || lanes > 16 || (lanes & (lanes - 1)))
    throw Error("lockstep C: lanes must be a power of two from 2 to 16, not " +
                std::to_string(lanes));
  const passes::LockstepFunction lowered = passes::lower_lockstep(optimized);
  const Function& f = lowered.f;
  VectorDialect d(accuracy, lanes);
  codegen::CFamilyPrinter p(f, d, source_map);
  std::string splat = "{x";
  for (int l = 1; l < lanes; ++l) splat += ", x";
  // Lockstep kernels keep hundreds of vector variables live across their loops, and GCC's
  // register allocation by loop regions took a quarter of a ray tracer kernel's compile; one
  // region compiled it 20% faster, with no measurable change in run time
  // (docs/benchmarks/2026-11-24-simd-compile.md). A pragma, since clang rejects the option
  // -fira-region=one and ignores GCC's pragmas; before any function, so all get it alike.
  std::string src =
      "#if defined(__GNUC__) && !defined(__clang__)\n"
      "#pragma GCC optimize(\"ira-region=one\")\n#endif\n";
  // The tile's rows (rill_next_group) as the host launcher cuts ranges (HostKernel.cpp);
  // overridable (-DRILL_TILE_ROWS=2 from a RILL_CC wrapper) to measure other tiles.
  src += "#define RILL_W " + std::to_string(lanes) +
         "\n#ifndef RILL_TILE_ROWS\n#define RILL_TILE_ROWS " +
         std::to_string(cpu::lockstep_tile_rows(lanes)) + "\n#endif\n#define RILL_SPLAT(x) " +
         splat + "}\n" + c_head(f, accuracy);
  src += kVectorPrelude;
  src += lockstep_helpers();
  src += codegen::on_demand_bodies(codegen::Language::Lockstep, f, lane_wise);
  const bool group = uses_group_ops(f);
  if (group) src += kGroupPrelude;
  // The kernel runs over groups of RILL_W elements: tiles of a 2D stream where they fit
  // (rill_next_group), or, for a compacted masked launch, the entries of a list of element
  // indices (rill_run_list, which HostKernel.cpp looks up). A kernel with group operations
  // has no list form: its groups' members are part of its results.
  src +=
      "\nstatic __attribute__((noinline)) int64_t rill_run_groups(const rill_launch* L, "
      "rill_groups rill_gs) {\n";
  src += c_entry_locals(f, codegen::CDialect(accuracy, ""));  // scalar locals
  src += "  int64_t rill_written = 0;\n";
  src += "  int64_t rill_lane[RILL_W];\n";
  src += "  int rill_n;\n";
  src += "  while ((rill_n = rill_next_group(&rill_gs, rill_lane)) > 0) {\n";
  if (group) {
    // The lanes of the group that hold a real element, and each lane's index.
    src += "    rill_vi rill_live, rill_lane_id;\n";
    src += "    for (int l = 0; l < RILL_W; ++l) {\n";
    src += "      rill_live[l] = l < rill_n ? -1 : 0;\n";
    src += "      rill_lane_id[l] = l;\n";
    src += "    }\n";
  }
  auto uses = [&](Op op) { return contains(f.body, op); };
  if (uses(Op::ElementIndex)) {
    src += "    rill_vi rill_element;\n";
    src += "    for (int l = 0; l < RILL_W; ++l) rill_element[l] = (int32_t)rill_lane[l];\n";
  }
  if (uses(Op::ElementCoord)) {
    src += "    rill_vi rill_coord_x, rill_coord_y;\n";
    src += "    for (int l = 0; l < RILL_W; ++l) {\n";
    src += "      rill_coord_x[l] = (int32_t)(rill_lane[l] % L->width);\n";
    src += "      rill_coord_y[l] = (int32_t)(rill_lane[l] / L->width);\n";
    src += "    }\n";
  }
  src += p.declarations(2);
  src += p.body(2);
  // Each real lane that is still alive stores its outputs.
  src += "    for (int l = 0; l < rill_n; ++l) {\n";
  if (lowered.alive != kNoVar)
    src += "      if (!" + f.var_name(lowered.alive) + "[l]) continue;\n";
  src += "      const int64_t rill_i = rill_lane[l];\n";
  for (size_t i = 0; i < f.outputs.size(); ++i) {
    VarId v = f.outputs[i];
    const Variable& var = f.var(v);
    for (int c = 0; c < var.type.width; ++c) {
      std::string value = p.component(v, c) + "[l]";
      if (var.type.is_float()) value = "rill_store_f(" + value + ")";
      src += "      out" + std::to_string(i) + "[rill_i * " + std::to_string(var.type.width) +
             " + " + std::to_string(c) + "] = " + value + ";\n";
    }
  }
  src += "      ++rill_written;\n    }\n  }\n  return rill_written;\n}\n";
  src += "\nint64_t rill_run(const rill_launch* L, int64_t rill_begin, int64_t rill_end) {\n";
  src += "  return rill_run_groups(L, rill_groups_of(L, rill_begin, rill_end));\n}\n";
  if (!group) {
    src +=
        "\nint64_t rill_run_list(const rill_launch* L, const int64_t* rill_list, "
        "int64_t rill_begin, int64_t rill_end) {\n";
    src += "  const rill_groups rill_gs = {rill_begin, rill_end, L->width, 0, rill_list};\n";
    src += "  return rill_run_groups(L, rill_gs);\n}\n";
  }
  return source_map ? codegen::finish_source_lines(src) : src;
}

}  // namespace rill::simd
