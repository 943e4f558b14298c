// Lockstep SIMD C: one kernel instance runs a group of W elements at once.
//
// The scalar C of CEmitter.cpp computes one element per iteration, so each branch the kernel
// takes is a branch the CPU must predict, and each loop runs once per element. Here, as in
// ISPC or a GPU's SIMT, W elements (lanes) move through the kernel together:
//
// - Every variable component is a vector of W values (GCC/Clang vector extensions, which
//   compile to SSE/AVX), and every operation is applied to all lanes at once.
// - An `if` computes two lane masks, then runs each side only if some lane takes it, with
//   assignments inside blended under the mask (`x = mask ? new : x`, per lane).
// - A loop keeps a mask of lanes still looping and runs until it is empty; `break`,
//   `continue` and `discard` clear lanes from the masks, and the statements after a
//   statement that may have cleared lanes re-read the mask (see Lockstep::exits()).
// - A gather loads each lane's element; indices are clamped, so lanes that are off read
//   harmlessly (arrays are never empty).
//
// Lanes that are off still compute values (which are then not kept), so every operation
// must be harmless on any input: the rill_* helpers already are (integer division by zero
// gives 0, conversions saturate). Each lane computes exactly the operations of the scalar
// code, in the same order and precision, so results are bit for bit those of emit_c().
// A group is W consecutive elements, or a W/2 x 2 tile of a 2D stream when the launch range
// is whole rows (the backend hands the lockstep kernel ranges of row pairs; rill_next_group).
// A group shorter than W repeats its last element in the spare lanes and stores only the
// real ones.
#include "LockstepEmitter.h"

#include "../codegen/CDialect.h"
#include "CEmitter.h"
#include "rill/ir/Visitor.h"

namespace rill::cpu {

using namespace ir;

namespace {

// Vector types and the vector forms of the helpers, after c_head() (rill_real is float: the
// double mode has no lockstep form). rill_vi holds Int values and Bool lane masks (-1 true,
// 0 false).
const char* kVectorPrelude = R"(
typedef rill_real rill_vr __attribute__((vector_size(RILL_W * sizeof(rill_real))));
typedef int32_t rill_vi __attribute__((vector_size(RILL_W * 4)));
typedef uint32_t rill_vu __attribute__((vector_size(RILL_W * 4)));

RILL_FN rill_vr rill_splat_r(rill_real x) { rill_vr r; for (int l = 0; l < RILL_W; ++l) r[l] = x; return r; }
RILL_FN rill_vi rill_splat_i(int32_t x) { rill_vi r; for (int l = 0; l < RILL_W; ++l) r[l] = x; return r; }
#if defined(__AVX__) && RILL_W == 8
#include <immintrin.h>
RILL_FN int rill_any(rill_vi m) { return !_mm256_testz_si256((__m256i)m, (__m256i)m); }
#else
RILL_FN int rill_any(rill_vi m) {
  int32_t r = 0;
  for (int l = 0; l < RILL_W; ++l) r |= m[l];
  return r != 0;
}
#endif
/* The groups of a launch range [begin, end). A range of whole rows of a 2D stream goes in
   tiles of RILL_W/2 x 2 elements (rows paired from the range's first row, an odd last row in
   runs of RILL_W): neighbouring pixels take similar paths through a kernel, and a tile's
   lanes lie closer together than RILL_W along one row, so they diverge less. Any other
   range goes in runs of RILL_W consecutive elements. The spare lanes of a short group repeat
   its last element; the return value is the group's element count, 0 after the last. */
typedef struct { int64_t next, end, width; int tiled; } rill_groups;
RILL_FN rill_groups rill_groups_of(const rill_launch* L, int64_t begin, int64_t end) {
  rill_groups g = {begin, end, L->width, 0};
  g.tiled = RILL_W >= 4 && L->height >= 2 && L->width >= RILL_W / 2 &&
            L->count == L->width * L->height && begin % L->width == 0 && end % L->width == 0;
  return g;
}
RILL_FN int rill_next_group(rill_groups* g, int64_t lane[RILL_W]) {
  if (g->next >= g->end) return 0;
  int n = 0;
  const int64_t x = g->next % g->width, row = g->next - x;
  if (g->tiled && g->end - row >= 2 * g->width) {
    const int64_t cols = g->width - x < RILL_W / 2 ? g->width - x : RILL_W / 2;
    for (int j = 0; j < 2; ++j)
      for (int64_t i = 0; i < cols; ++i) lane[n++] = row + j * g->width + x + i;
    g->next = x + cols < g->width ? g->next + cols : row + 2 * g->width;
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
RILL_FN rill_vi rill_v_add_i(rill_vi a, rill_vi b) { return (rill_vi)((rill_vu)a + (rill_vu)b); }
RILL_FN rill_vi rill_v_sub_i(rill_vi a, rill_vi b) { return (rill_vi)((rill_vu)a - (rill_vu)b); }
RILL_FN rill_vi rill_v_mul_i(rill_vi a, rill_vi b) { return (rill_vi)((rill_vu)a * (rill_vu)b); }
RILL_FN rill_vi rill_v_neg_i(rill_vi a) { return (rill_vi)((rill_vu){} - (rill_vu)a); }
RILL_FN rill_vi rill_v_shl(rill_vi a, rill_vi b) { return (rill_vi)((rill_vu)a << (rill_vu)(b & 31)); }
RILL_FN rill_vi rill_v_shr(rill_vi a, rill_vi b) { return a >> (b & 31); }
RILL_FN rill_vi rill_v_min_i(rill_vi a, rill_vi b) { return rill_sel_i(RILL_CMP(b < a), b, a); }
RILL_FN rill_vi rill_v_max_i(rill_vi a, rill_vi b) { return rill_sel_i(RILL_CMP(a < b), b, a); }
RILL_FN rill_vr rill_v_min_f(rill_vr a, rill_vr b) { return rill_sel_r(RILL_CMP(b < a), b, a); }
RILL_FN rill_vr rill_v_max_f(rill_vr a, rill_vr b) { return rill_sel_r(RILL_CMP(a < b), b, a); }
RILL_FN rill_vr rill_v_abs_f(rill_vr a) { return (rill_vr)((rill_vi)a & 0x7fffffff); }
RILL_FN rill_vr rill_v_i2f(rill_vi a) { return __builtin_convertvector(a, rill_vr); }
RILL_FN rill_vi rill_v_fbits(rill_vr a) { return (rill_vi)a; }
RILL_FN rill_vr rill_v_ibits(rill_vi a) { return (rill_vr)a; }

/* Array index clamped into [0, n), n < 2^31 (see rill_clamp_index). */
RILL_FN rill_vi rill_v_clamp_index(rill_vi i, int64_t n) {
  return rill_v_min_i(rill_v_max_i(i, rill_splat_i(0)), rill_splat_i((int32_t)(n - 1)));
}
/* Gathers: each lane loads base[i]. Built from scalar loads (a vector initializer), which
   measured as fast as AVX2's microcoded gather instructions on the reference machine. */
#if RILL_W == 8
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
#if defined(__AVX2__) && RILL_W == 8
#include <immintrin.h>
/* Three or four consecutive floats per lane (a vec3/vec4 element): one 16-byte load per lane
   (masked to three floats for vec3, so the last element never reads past the array) and a
   transpose, instead of eight scalar loads per component. */
RILL_FN void rill_transpose_lanes(const __m128 q[8], rill_vr* x, rill_vr* y, rill_vr* z, rill_vr* w) {
  __m256 r0 = _mm256_insertf128_ps(_mm256_castps128_ps256(q[0]), q[4], 1);
  __m256 r1 = _mm256_insertf128_ps(_mm256_castps128_ps256(q[1]), q[5], 1);
  __m256 r2 = _mm256_insertf128_ps(_mm256_castps128_ps256(q[2]), q[6], 1);
  __m256 r3 = _mm256_insertf128_ps(_mm256_castps128_ps256(q[3]), q[7], 1);
  __m256 t0 = _mm256_unpacklo_ps(r0, r1), t1 = _mm256_unpacklo_ps(r2, r3);
  __m256 t2 = _mm256_unpackhi_ps(r0, r1), t3 = _mm256_unpackhi_ps(r2, r3);
  *x = (rill_vr)_mm256_shuffle_ps(t0, t1, 0x44);
  *y = (rill_vr)_mm256_shuffle_ps(t0, t1, 0xee);
  *z = (rill_vr)_mm256_shuffle_ps(t2, t3, 0x44);
  if (w) *w = (rill_vr)_mm256_shuffle_ps(t2, t3, 0xee);
}
RILL_FN void rill_gather3_r(const float* base, rill_vi i, rill_vr* x, rill_vr* y, rill_vr* z) {
  const __m128i m = _mm_setr_epi32(-1, -1, -1, 0);
  __m128 q[8];
  for (int l = 0; l < 8; ++l) q[l] = _mm_maskload_ps(base + i[l], m);
  rill_transpose_lanes(q, x, y, z, 0);
}
RILL_FN void rill_gather4_r(const float* base, rill_vi i, rill_vr* x, rill_vr* y, rill_vr* z, rill_vr* w) {
  __m128 q[8];
  for (int l = 0; l < 8; ++l) q[l] = _mm_loadu_ps(base + i[l]);
  rill_transpose_lanes(q, x, y, z, w);
}
/* Two consecutive ints per lane (an ivec2 element): one 8-byte load per lane and a transpose. */
RILL_FN void rill_gather2_i(const int32_t* base, rill_vi i, rill_vi* x, rill_vi* y) {
  __m128i q[8];
  for (int l = 0; l < 8; ++l) q[l] = _mm_loadl_epi64((const __m128i*)(base + i[l]));
  __m128i a = _mm_unpacklo_epi64(q[0], q[1]), b = _mm_unpacklo_epi64(q[2], q[3]);
  __m128i c = _mm_unpacklo_epi64(q[4], q[5]), d = _mm_unpacklo_epi64(q[6], q[7]);
  __m256 lo = _mm256_castsi256_ps(_mm256_insertf128_si256(_mm256_castsi128_si256(a), c, 1));
  __m256 hi = _mm256_castsi256_ps(_mm256_insertf128_si256(_mm256_castsi128_si256(b), d, 1));
  *x = (rill_vi)_mm256_castps_si256(_mm256_shuffle_ps(lo, hi, 0x88));
  *y = (rill_vi)_mm256_castps_si256(_mm256_shuffle_ps(lo, hi, 0xdd));
}
#define RILL_HAVE_GATHER34 1
#endif

/* The other helpers, lane by lane through their scalar definitions. */
#define RILL_LANES1(name, R, A, fn) \
  RILL_FN R name(A a) { R r; for (int l = 0; l < RILL_W; ++l) r[l] = fn(a[l]); return r; }
#define RILL_LANES2(name, R, A, fn) \
  RILL_FN R name(A a, A b) { R r; for (int l = 0; l < RILL_W; ++l) r[l] = fn(a[l], b[l]); return r; }
RILL_LANES2(rill_v_div_i, rill_vi, rill_vi, rill_div_i)
RILL_LANES2(rill_v_mod_i, rill_vi, rill_vi, rill_mod_i)
RILL_LANES1(rill_v_abs_i, rill_vi, rill_vi, rill_abs_i)
RILL_LANES1(rill_v_sign_i, rill_vi, rill_vi, rill_sign_i)
RILL_LANES1(rill_v_sign_f, rill_vr, rill_vr, rill_sign_f)
RILL_LANES2(rill_v_mod_f, rill_vr, rill_vr, rill_mod_f)
#if defined(__AVX2__) && RILL_W == 8
/* Exact in every mode, so the same bits as the scalar helpers (NaN, infinities, -0 included):
   rounding to an integer and the square root are correctly rounded instructions. Strict code
   would otherwise call floorf, ceilf and sqrtf lane by lane. */
RILL_FN rill_vr rill_v_floor(rill_vr a) {
  return (rill_vr)_mm256_round_ps((__m256)a, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
}
RILL_FN rill_vr rill_v_ceil(rill_vr a) {
  return (rill_vr)_mm256_round_ps((__m256)a, _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC);
}
RILL_FN rill_vr rill_v_sqrt(rill_vr a) { return (rill_vr)_mm256_sqrt_ps((__m256)a); }
#else
RILL_LANES1(rill_v_floor, rill_vr, rill_vr, rill_floor)
RILL_LANES1(rill_v_ceil, rill_vr, rill_vr, rill_ceil)
RILL_LANES1(rill_v_sqrt, rill_vr, rill_vr, rill_sqrt)
#endif
RILL_LANES1(rill_v_fract, rill_vr, rill_vr, rill_fract)
RILL_LANES1(rill_v_rsqrt, rill_vr, rill_vr, rill_rsqrt)
RILL_LANES1(rill_v_exp, rill_vr, rill_vr, rill_exp)
RILL_LANES1(rill_v_log, rill_vr, rill_vr, rill_log)
RILL_LANES1(rill_v_exp2, rill_vr, rill_vr, rill_exp2)
RILL_LANES1(rill_v_log2, rill_vr, rill_vr, rill_log2)
RILL_LANES1(rill_v_sin, rill_vr, rill_vr, rill_sin)
RILL_LANES1(rill_v_cos, rill_vr, rill_vr, rill_cos)
RILL_LANES1(rill_v_tan, rill_vr, rill_vr, rill_tan)
RILL_LANES1(rill_v_atan, rill_vr, rill_vr, rill_atan)
RILL_LANES2(rill_v_pow, rill_vr, rill_vr, rill_pow)
RILL_LANES2(rill_v_atan2, rill_vr, rill_vr, rill_atan2)
RILL_LANES1(rill_v_f2i, rill_vi, rill_vr, rill_f2i)
)";

std::string pad_of(int indent) {
  return std::string(static_cast<size_t>(indent) * 2, ' ');
}

std::string call(const std::string& fn, std::initializer_list<std::string> args) {
  std::string s = fn + "(";
  bool first = true;
  for (const auto& a : args) {
    if (!first) s += ", ";
    s += a;
    first = false;
  }
  return s + ")";
}

// Does b contain a break or continue of the loop it is in (not of a nested loop)?
bool exits_loop(const Block& b) {
  for (const Stmt& s : b) {
    if (s.kind == StmtKind::Break || s.kind == StmtKind::Continue) return true;
    if (s.kind == StmtKind::If && (exits_loop(s.then_body) || exits_loop(s.else_body))) return true;
  }
  return false;
}

bool has_continue(const Block& b) {
  for (const Stmt& s : b) {
    if (s.kind == StmtKind::Continue) return true;
    if (s.kind == StmtKind::If && (has_continue(s.then_body) || has_continue(s.else_body)))
      return true;
  }
  return false;
}

bool has_discard(const Block& b) {
  bool found = false;
  for_each_stmt(b, [&](const Stmt& s) { found = found || s.kind == StmtKind::Discard; });
  return found;
}

bool uses_op(const Block& b, Op op) {
  bool found = false;
  for_each_stmt(
      b, [&](const Stmt& s) { found = found || (s.kind == StmtKind::Assign && s.op == op); });
  return found;
}

// Variables whose lanes that are off may be overwritten: written by exactly one (whole)
// assignment and read only after it, in its block or inside what follows it there. Every
// read then runs for a subset of the lanes the assignment ran for (masks only narrow inside a
// block and its nested blocks), in the same loop iteration, so the value a lane that was off
// gets is never read, and the assignment can skip the blend with the old value.
std::vector<bool> unblended_vars(const Function& f) {
  std::vector<int> writes(f.vars.size(), 0);
  for_each_stmt(f.body, [&](const Stmt& s) {
    if (s.kind == StmtKind::Assign)
      writes[s.dst] += s.mask.full() || s.mask.count == f.var(s.dst).type.width ? 1 : 2;
  });
  std::vector<bool> ok(f.vars.size(), false);
  for (VarId v = 0; v < f.vars.size(); ++v) {
    VarRole r = f.vars[v].role;
    ok[v] = writes[v] == 1 && (r == VarRole::Temp || r == VarRole::Local);
  }
  // Walk in program order with the set of candidates assigned earlier in an enclosing block;
  // a read of a candidate outside that set disqualifies it.
  std::vector<bool> visible(f.vars.size(), false);
  auto read = [&](const Operand& o) {
    if (o.is_var() && !visible[o.var]) ok[o.var] = false;
  };
  // A loop's condition is read at the end of its condition block, by lanes that ran it; a
  // lane that did not is already off the loop mask, so a value it never got is harmless.
  auto walk = [&](auto& self, const Block& b, const Operand* read_at_end) -> void {
    std::vector<VarId> added;
    for (const Stmt& s : b) {
      for (const Operand& o : s.args) read(o);
      if (s.kind == StmtKind::If) read(s.cond);
      for (const Block* sub : {&s.then_body, &s.else_body, &s.body, &s.step})
        self(self, *sub, nullptr);
      if (s.kind == StmtKind::Loop) self(self, s.cond_body, &s.cond);
      if (s.kind == StmtKind::Assign && ok[s.dst] && !visible[s.dst]) {
        visible[s.dst] = true;
        added.push_back(s.dst);
      }
    }
    if (read_at_end) read(*read_at_end);
    for (VarId v : added) visible[v] = false;
  };
  walk(walk, f.body, nullptr);
  return ok;
}

// Prints the kernel body in lockstep form.
class Lockstep {
 public:
  Lockstep(const Function& f, const codegen::CDialect& d, int lanes)
      : f_(f),
        d_(d),
        lanes_(lanes),
        discards_(has_discard(f.body)),
        unblended_(unblended_vars(f)) {}

  bool discards() const { return discards_; }

  // Vector type of a variable's components.
  std::string vtype(ScalarKind k) const { return k == ScalarKind::Float ? "rill_vr" : "rill_vi"; }

  std::string component(VarId v, int c) const {
    std::string n = f_.var_name(v);
    return f_.var(v).type.width == 1 ? n : n + "_" + std::to_string(c);
  }

  // Component c of an operand, as a vector.
  std::string operand(const Operand& o, int c) const {
    if (o.is_var()) return component(o.var, o.component(c));
    uint32_t bits = o.value.bits[static_cast<size_t>(o.width() == 1 ? 0 : c)];
    switch (o.type.kind) {
      case ScalarKind::Float:
        return "rill_splat_r(" + d_.literal(ScalarKind::Float, bits) + ")";
      case ScalarKind::Int:
        return "rill_splat_i(" + d_.literal(ScalarKind::Int, bits) + ")";
      case ScalarKind::Bool:
        return bits ? "rill_splat_i(-1)" : "rill_splat_i(0)";
    }
    return "?";
  }

  // Component c of an operand, in lane `l` (a scalar).
  std::string operand_lane(const Operand& o, int c) const {
    if (o.is_const())
      return d_.literal(o.type.kind, o.value.bits[static_cast<size_t>(o.width() == 1 ? 0 : c)]);
    return component(o.var, o.component(c)) + "[l]";
  }

  // Every variable the body uses, as vectors with their initial values. Stream inputs and
  // outputs are read lane by lane; uniforms are broadcast; everything else starts at zero.
  std::string declarations(int indent) const {
    std::string out, pad = pad_of(indent), lanes;
    std::vector<bool> used(f_.vars.size(), false);
    for (VarId v : f_.inputs) used[v] = true;
    for (VarId v : f_.outputs) used[v] = true;
    for_each_operand(f_.body, [&](const Operand& o) {
      if (o.is_var()) used[o.var] = true;
    });
    for_each_stmt(f_.body, [&](const Stmt& s) {
      if (s.kind == StmtKind::Assign) used[s.dst] = true;
    });
    for (VarId v = 0; v < f_.vars.size(); ++v) {
      if (!used[v]) continue;
      const Variable& var = f_.vars[v];
      for (int c = 0; c < var.type.width; ++c) {
        std::string name = component(v, c), init = d_.initial_value(f_, v, c);
        if (var.role == VarRole::Input || var.role == VarRole::Output) {
          out += pad + vtype(var.type.kind) + " " + name + ";\n";
          lanes += pad + "  " + name + "[l] = " + init + ";\n";
        } else if (var.role == VarRole::Uniform) {
          std::string value = var.type.kind == ScalarKind::Bool ? "-(" + init + " != 0)" : init;
          out += pad + vtype(var.type.kind) + " " + name + " = " +
                 (var.type.is_float() ? "rill_splat_r(" : "rill_splat_i(") + value + ");\n";
        } else {
          out += pad + vtype(var.type.kind) + " " + name + " = " +
                 (var.type.is_float() ? "rill_splat_r(0)" : "rill_splat_i(0)") + ";\n";
        }
      }
    }
    if (!lanes.empty())
      out += pad + "for (int l = 0; l < RILL_W; ++l) {\n" + pad +
             "  const int64_t rill_i = rill_lane[l];\n" + lanes + pad + "}\n";
    return out;
  }

  // The body; the top-level mask is rill_alive if the kernel can discard, else none (every
  // lane runs every top-level statement).
  std::string body(int indent) {
    std::string out;
    std::string top = discards_ ? "rill_alive" : "";
    block(out, f_.body, top, top, indent);
    return out;
  }

 private:
  struct LoopMasks {
    std::string looping;  // lanes still in the loop
    std::string running;  // lanes running this iteration's body (looping minus continued)
  };

  std::string fresh(const char* prefix) { return prefix + std::to_string(next_++); }

  // May statement s turn lanes off for what follows it in its block?
  bool exits(const Stmt& s) const {
    switch (s.kind) {
      case StmtKind::Break:
      case StmtKind::Continue:
      case StmtKind::Discard:
        return true;
      case StmtKind::If:
        return exits_loop(s.then_body) || exits_loop(s.else_body) || has_discard(s.then_body) ||
               has_discard(s.else_body);
      case StmtKind::Loop:
        return has_discard(s.cond_body) || has_discard(s.body) || has_discard(s.step);
      case StmtKind::Assign:
        return false;
    }
    return false;
  }

  // mask: the variable holding the lanes this block runs for ("" = all lanes). live: the
  // mask that break, continue and discard clear lanes from, which is where the lanes still
  // running after such a statement are read back: a loop body's running lanes, a loop
  // condition's or step's looping lanes, the live lanes outside loops.
  void block(std::string& out, const Block& b, const std::string& mask, const std::string& live,
             int indent) {
    for (const Stmt& s : b) {
      stmt(out, s, mask, live, indent);
      if (exits(s) && !mask.empty() && mask != live)
        out += pad_of(indent) + mask + " &= " + live + ";\n";
    }
  }

  void stmt(std::string& out, const Stmt& s, const std::string& mask, const std::string& live,
            int indent) {
    std::string pad = pad_of(indent);
    auto in_mask = [&](const std::string& m) {
      return mask.empty() ? m : "(" + mask + " & " + m + ")";
    };
    switch (s.kind) {
      case StmtKind::Assign:
        if (s.op == Op::Gather)
          gather(out, s, mask, pad);
        else
          assign(out, s, mask, pad);
        return;
      case StmtKind::If: {
        std::string cond = operand(s.cond, 0);
        std::string then_mask = fresh("rill_m");
        out += pad + "{\n";
        out += pad + "  rill_vi " + then_mask + " = " + in_mask(cond) + ";\n";
        std::string else_mask;
        if (!s.else_body.empty()) {
          else_mask = fresh("rill_m");
          out += pad + "  rill_vi " + else_mask + " = " + in_mask("~" + cond) + ";\n";
        }
        out += pad + "  if (rill_any(" + then_mask + ")) {\n";
        block(out, s.then_body, then_mask, live, indent + 2);
        out += pad + "  }\n";
        if (!s.else_body.empty()) {
          out += pad + "  if (rill_any(" + else_mask + ")) {\n";
          block(out, s.else_body, else_mask, live, indent + 2);
          out += pad + "  }\n";
        }
        out += pad + "}\n";
        return;
      }
      case StmtKind::Loop: {
        LoopMasks m{fresh("rill_loop"), ""};
        bool continues = has_continue(s.body);
        m.running = continues ? fresh("rill_run") : m.looping;
        out += pad + "{\n";
        out += pad + "  rill_vi " + m.looping + " = " + (mask.empty() ? "rill_splat_i(-1)" : mask) +
               ";\n";
        if (continues) out += pad + "  rill_vi " + m.running + " = " + m.looping + ";\n";
        out += pad + "  " + d_.loop_header() + " {\n";
        loops_.push_back(m);
        std::string inner = pad + "    ";
        if (s.loop != LoopKind::DoUntil) {
          block(out, s.cond_body, m.looping, m.looping, indent + 2);
          out += inner + m.looping + " &= " + operand(s.cond, 0) + ";\n";
          out += inner + "if (!rill_any(" + m.looping + ")) break;\n";
        }
        if (continues) out += inner + m.running + " = " + m.looping + ";\n";
        block(out, s.body, m.running, m.running, indent + 2);
        block(out, s.step, m.looping, m.looping, indent + 2);
        if (s.loop == LoopKind::DoUntil) {
          block(out, s.cond_body, m.looping, m.looping, indent + 2);
          out += inner + m.looping + " &= ~" + operand(s.cond, 0) + ";\n";
        }
        out += inner + "if (!rill_any(" + m.looping + ")) break;\n";
        loops_.pop_back();
        out += pad + "  }\n";
        out += pad + "}\n";
        return;
      }
      case StmtKind::Break:
      case StmtKind::Continue:
      case StmtKind::Discard: {
        // Copy the leaving lanes first: `mask` may be one of the masks cleared below.
        out += pad + "{\n" + pad +
               "  const rill_vi rill_leaving = " + (mask.empty() ? "rill_splat_i(-1)" : mask) +
               ";\n";
        auto clear = [&](const std::string& m) { out += pad + "  " + m + " &= ~rill_leaving;\n"; };
        if (s.kind == StmtKind::Discard) {
          clear("rill_alive");
          for (const LoopMasks& l : loops_) {
            clear(l.looping);
            if (l.running != l.looping) clear(l.running);
          }
        } else {
          if (loops_.empty()) throw Error("internal: break or continue outside a loop");
          const LoopMasks& l = loops_.back();
          if (s.kind == StmtKind::Break) clear(l.looping);
          if (l.running != l.looping) clear(l.running);
        }
        out += pad + "}\n";
        return;
      }
    }
  }

  // `v` as the new value of `dst` (a component of s.dst) for the lanes in `mask`: the other
  // lanes keep their value, unless none of them can read it (see unblended_vars()).
  std::string blended(const Stmt& s, const std::string& mask, const std::string& dst,
                      const std::string& v) const {
    if (mask.empty() || unblended_[s.dst]) return v;
    return call(f_.var(s.dst).type.is_float() ? "rill_sel_r" : "rill_sel_i", {mask, v, dst});
  }

  void assign(std::string& out, const Stmt& s, const std::string& mask, const std::string& pad) {
    const Type dst_type = f_.var(s.dst).type;
    const int width = s.mask.full() ? dst_type.width : s.mask.count;
    auto dst_comp = [&](int c) {
      return s.mask.full() ? c : static_cast<int>(s.mask.comps[static_cast<size_t>(c)]);
    };
    std::vector<std::string> values;
    for (int c = 0; c < width; ++c) values.push_back(expr(s, c));
    auto blend = [&](const std::string& dst, const std::string& v) {
      return blended(s, mask, dst, v);
    };
    bool aliased = false;
    if (width > 1)
      for (const Operand& a : s.args) aliased = aliased || (a.is_var() && a.var == s.dst);
    if (!aliased) {
      for (int c = 0; c < width; ++c) {
        std::string dst = component(s.dst, dst_comp(c));
        out += pad + dst + " = " + blend(dst, values[static_cast<size_t>(c)]) + ";\n";
      }
      return;
    }
    out += pad + "{\n";
    for (int c = 0; c < width; ++c)
      out += pad + "  const " + vtype(dst_type.kind) + " r" + std::to_string(c) + " = " +
             values[static_cast<size_t>(c)] + ";\n";
    for (int c = 0; c < width; ++c) {
      std::string dst = component(s.dst, dst_comp(c));
      out += pad + "  " + dst + " = " + blend(dst, "r" + std::to_string(c)) + ";\n";
    }
    out += pad + "}\n";
  }

  // Each lane loads its own element at the scalar gather's clamped index. The index is
  // computed on vectors in 32 bits (the backend refuses arrays of 2^31 words or more, see
  // CpuBackend.cpp). A whole vec3/vec4/ivec2 element is loaded once per lane and transposed
  // (rill_gather3_r and kin, AVX2); otherwise each component is a vector initializer from
  // scalar loads (rill_gather_r): writing lanes one by one to memory and reading the vector
  // back would stall on store forwarding.
  void gather(std::string& out, const Stmt& s, const std::string& mask, const std::string& pad) {
    const ArrayDecl& a = f_.arrays.at(static_cast<size_t>(s.array));
    const Type dst_type = f_.var(s.dst).type;
    const int width = s.mask.full() ? dst_type.width : s.mask.count;
    const std::string id = std::to_string(s.array), shape = "arr" + id + "_shape";
    auto clamped = [&](size_t d) {
      return "rill_v_clamp_index(" + operand(s.args[d], 0) + ", " + shape + "[" +
             std::to_string(d) + "])";
    };
    std::string lin = clamped(0);
    if (s.args.size() > 1)
      lin = "rill_v_add_i(" + lin + ", rill_v_mul_i(rill_splat_i((int32_t)" + shape + "[0]), " +
            clamped(1) + "))";
    if (s.args.size() > 2)
      lin = "rill_v_add_i(" + lin + ", rill_v_mul_i(rill_splat_i((int32_t)(" + shape + "[0] * " +
            shape + "[1])), " + clamped(2) + "))";
    out += pad + "{\n";
    out += pad + "  const rill_vi rill_g = rill_v_mul_i(" + lin + ", rill_splat_i(" +
           std::to_string(a.elem.width) + "));\n";
    const bool whole =
        lanes_ == 8 && width >= 2 &&
        (a.elem.is_float() ? a.elem.width == 3 || a.elem.width == 4 : a.elem.width == 2);
    const std::string kind = a.elem.is_float() ? "_r" : "_i";
    if (whole) {
      const std::string vt = vtype(a.elem.kind);
      std::string q, fallback;
      for (int c = 0; c < a.elem.width; ++c) {
        std::string qc = "rill_q" + std::to_string(c);
        q += ", &" + qc;
        fallback += pad + "  const " + vt + " " + qc + " = rill_gather" + kind + "(arr" + id +
                    " + " + std::to_string(c) + ", rill_g);\n";
      }
      out += "#ifdef RILL_HAVE_GATHER34\n";
      out += pad + "  " + vt + " rill_q0, rill_q1, rill_q2, rill_q3;\n";
      out += pad + "  rill_gather" + std::to_string(a.elem.width) + kind + "(arr" + id +
             ", rill_g" + q + ");\n";
      out += "#else\n" + fallback + "#endif\n";
    }
    for (int c = 0; c < width; ++c) {
      std::string v =
          whole ? "rill_q" + std::to_string(c)
                : "rill_gather" + kind + "(arr" + id + " + " + std::to_string(c) + ", rill_g)";
      int dc = s.mask.full() ? c : s.mask.comps[static_cast<size_t>(c)];
      std::string dst = component(s.dst, dc);
      out += pad + "  " + dst + " = " + blended(s, mask, dst, v) + ";\n";
    }
    out += pad + "}\n";
  }

  std::string expr(const Stmt& s, int c) const {
    auto a = [&](size_t i) { return operand(s.args[i], c); };
    ScalarKind k = s.args.empty() ? ScalarKind::Int : s.args[0].type.kind;
    bool fl = k == ScalarKind::Float;
    auto bin = [&](const char* op) { return "(" + a(0) + " " + op + " " + a(1) + ")"; };
    auto cmp = [&](const char* op) { return "RILL_CMP(" + a(0) + " " + op + " " + a(1) + ")"; };
    if (std::string fn = codegen::helper_function(s.op, k); !fn.empty())
      return op_info(s.op).arity == 1 ? call("rill_v_" + fn, {a(0)})
                                      : call("rill_v_" + fn, {a(0), a(1)});
    switch (s.op) {
      case Op::Copy:
        return a(0);
      case Op::Neg:
        return fl ? "(-" + a(0) + ")" : call("rill_v_neg_i", {a(0)});
      case Op::Add:
        return fl ? bin("+") : call("rill_v_add_i", {a(0), a(1)});
      case Op::Sub:
        return fl ? bin("-") : call("rill_v_sub_i", {a(0), a(1)});
      case Op::Mul:
        return fl ? bin("*") : call("rill_v_mul_i", {a(0), a(1)});
      case Op::Div:
        return fl ? bin("/") : call("rill_v_div_i", {a(0), a(1)});
      case Op::BitAnd:
      case Op::And:
        return bin("&");
      case Op::BitOr:
      case Op::Or:
        return bin("|");
      case Op::BitXor:
        return bin("^");
      case Op::BitNot:
      case Op::Not:
        return "(~" + a(0) + ")";
      case Op::Lt:
        return cmp("<");
      case Op::Le:
        return cmp("<=");
      case Op::Gt:
        return cmp(">");
      case Op::Ge:
        return cmp(">=");
      case Op::Eq:
        return cmp("==");
      case Op::Ne:
        return cmp("!=");
      case Op::Select:
        return call(s.args[1].type.is_float() ? "rill_sel_r" : "rill_sel_i", {a(0), a(1), a(2)});
      case Op::IntToFloat:
        return call("rill_v_i2f", {a(0)});
      case Op::FloatToInt:
        return call("rill_v_f2i", {a(0)});
      case Op::FloatBitsToInt:
        return call("rill_v_fbits", {a(0)});
      case Op::IntBitsToFloat:
        return call("rill_v_ibits", {a(0)});
      case Op::Dot:
      case Op::Cross:
      case Op::Construct:
        return codegen::fixed_form_expr(s, c,
                                        [&](const Operand& o, int i) { return operand(o, i); });
      case Op::ElementIndex:
        return "rill_element";
      case Op::ElementCoord:
        return c == 0 ? "rill_coord_x" : "rill_coord_y";
      case Op::Gather:  // a statement of its own, not an expression
      default:          // the helper calls, handled above (helper_function)
        break;
    }
    throw Error(std::string("internal: no lockstep form for op ") + op_name(s.op));
  }

  const Function& f_;
  const codegen::CDialect& d_;
  int lanes_;
  bool discards_;
  std::vector<bool> unblended_;  // see unblended_vars()
  std::vector<LoopMasks> loops_;
  int next_ = 0;
};

}  // namespace

std::string emit_c_lockstep(const Function& f, Accuracy accuracy, int lanes) {
  if (accuracy == Accuracy::Double)
    throw Error(
        "lockstep C: the double mode has no lockstep form (the simd backend runs it as scalar C)");
  if (lanes < 2 || lanes > 16 || (lanes & (lanes - 1)))
    throw Error("lockstep C: lanes must be a power of two from 2 to 16, not " +
                std::to_string(lanes));
  codegen::CDialect d(accuracy, "", "L->width");
  Lockstep p(f, d, lanes);
  std::string src = "#define RILL_W " + std::to_string(lanes) + "\n" + c_head(f, accuracy);
  src += kVectorPrelude;
  src += "\nint64_t rill_run(const rill_launch* L, int64_t rill_begin, int64_t rill_end) {\n";
  src += c_entry_locals(f, d);
  src += "  int64_t rill_written = 0;\n";
  // Groups of RILL_W elements: tiles of a 2D stream where they fit (rill_next_group).
  src += "  rill_groups rill_gs = rill_groups_of(L, rill_begin, rill_end);\n";
  src += "  int64_t rill_lane[RILL_W];\n";
  src += "  int rill_n;\n";
  src += "  while ((rill_n = rill_next_group(&rill_gs, rill_lane)) > 0) {\n";
  if (uses_op(f.body, Op::ElementIndex)) {
    src += "    rill_vi rill_element;\n";
    src += "    for (int l = 0; l < RILL_W; ++l) rill_element[l] = (int32_t)rill_lane[l];\n";
  }
  if (uses_op(f.body, Op::ElementCoord)) {
    src += "    rill_vi rill_coord_x, rill_coord_y;\n";
    src += "    for (int l = 0; l < RILL_W; ++l) {\n";
    src += "      rill_coord_x[l] = (int32_t)(rill_lane[l] % L->width);\n";
    src += "      rill_coord_y[l] = (int32_t)(rill_lane[l] / L->width);\n";
    src += "    }\n";
  }
  if (p.discards()) src += "    rill_vi rill_alive = rill_splat_i(-1);\n";
  src += p.declarations(2);
  src += p.body(2);
  src += "    for (int l = 0; l < rill_n; ++l) {\n";
  if (p.discards()) src += "      if (!rill_alive[l]) continue;\n";
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
  return src;
}

}  // namespace rill::cpu
