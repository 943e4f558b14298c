// Emits a kernel as GLSL 4.30, for either stage of the GLSL backends: a fragment shader (the
// thesis's stream model, backend `glsl`) or a compute shader (`glsl-compute`). The body, the
// helpers and the strict-mode rules are the same for both; the stages differ only in where
// elements, streams and arrays come from and go to (the Stage switches in GLSLDialect and
// the two emit_ functions at the end).
//
// Fragment stage: one fragment per stream element: the element index comes from gl_FragCoord over a
// texture laid out in rows of `rill_row` texels. Inputs, the outputs' previous values and
// arrays are textures read with texelFetch; outputs are render targets; RILL_DISCARD is
// `discard`, and the occlusion query counts what was written.
//
// Compute stage: one invocation per element, numbered from gl_GlobalInvocationID. Streams
// are shader storage buffers holding the host's words as they are (rill_in0.d[i * width +
// c]); arrays, and streams gathered from, are buffer textures read with texelFetch (one
// fetch per element, through the texture cache); RILL_DISCARD returns before the outputs
// are stored, and the elements written (and, in a masked launch, selected) are counted with
// atomics on a small storage buffer, one per subgroup where GL_KHR_shader_subgroup_ballot
// exists.
//
// The body is printed by the shared C-family printer (scalarized, like the C and OpenCL
// dialects); GLSL has its own bodies of the helpers (codegen/Helpers.cpp) because it has no
// casts or typedefs, and compares and selects floats through helpers in strict mode.
// In strict mode every float variable is `precise`, which forbids the compiler from fusing
// or reassociating the operations that compute it.
#include "GLSLEmitter.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "../codegen/CFamilyPrinter.h"
#include "../codegen/Helpers.h"
#include "../codegen/SourceMap.h"
#include "../codegen/SourceText.h"
#include "../codegen/Tiles.h"
#include "DivSqrt.h"

namespace rill::glsl {

using namespace ir;

namespace {

const char kComp[] = "xyzw";

class GLSLDialect : public codegen::Dialect {
 public:
  GLSLDialect(Accuracy a, Stage stage, const std::vector<int>& pass_outputs, bool loop_guard,
              bool subgroups = false)
      : strict_(a != Accuracy::Fast),
        stage_(stage),
        pass_outputs_(pass_outputs),
        loop_guard_(loop_guard),
        subgroups_(subgroups) {}

  // Lane-group ops as GL_KHR_shader_subgroup operations over the invocations that reach them
  // together (DriverRules::subgroups, both compute dialects), else a group of one. Inactive
  // invocations take no part in a subgroup operation, which gives the identities Group.h promises;
  // a broadcast from an inactive or out-of-range lane keeps the element's own value.
  std::string group(Op op, ScalarKind k, int c,
                    const std::vector<std::string>& args) const override {
    if (!subgroups_) return codegen::Dialect::group(op, k, c, args);
    switch (op) {
      case Op::GroupSize:
        return "int(gl_SubgroupSize)";
      case Op::LaneIndex:
        return "int(gl_SubgroupInvocationID)";
      case Op::GroupAny:
        return "subgroupAny(" + args[0] + ")";
      case Op::GroupAll:
        return "subgroupAll(" + args[0] + ")";
      case Op::GroupBallot:
        return "int(subgroupBallot(" + args[0] + ")[" + std::to_string(c) + "])";
      case Op::GroupCount:
        return "int(subgroupBallotBitCount(subgroupBallot(" + args[0] + ")))";
      case Op::GroupMin:
        return "subgroupMin(" + args[0] + ")";
      case Op::GroupMax:
        return "subgroupMax(" + args[0] + ")";
      case Op::GroupSum:
        return "subgroupAdd(" + args[0] + ")";
      case Op::GroupBroadcast: {
        const char* fn = k == ScalarKind::Float ? "rill_g_bcast_f"
                         : k == ScalarKind::Int ? "rill_g_bcast_i"
                                                : "rill_g_bcast_b";
        return std::string(fn) + "(" + args[0] + ", " + args[1] + ")";
      }
      default:
        break;
    }
    return codegen::Dialect::group(op, k, c, args);
  }

  // GLSL's #line takes a source-string number, not a file: the map is comments.
  std::string source_line(const SourceLoc& loc) const override {
    return codegen::kSourceComment +
           codegen::comment_safe(relative_path(loc.file) + ":" + std::to_string(loc.line));
  }
  bool source_line_renumbers() const override { return false; }

  // Strict: through rill_div_f, correctly rounded on every driver (DivSqrt.h).
  std::string float_div(const std::string& a, const std::string& b) const override {
    return strict_ ? "rill_div_f(" + a + ", " + b + ")" : "(" + a + " / " + b + ")";
  }

  // Float constants a strict kernel uses, in the order of rill_k[] (see literal()).
  mutable std::vector<uint32_t> constants;

  // Printing meets constants in the order C++ evaluates the printer's string expressions,
  // which differs between compilers; in ascending bits, rill_k[] is the same for every
  // build. The body is printed again after this.
  void sort_constants() const { std::sort(constants.begin(), constants.end()); }

  bool scalarize() const override { return true; }
  std::string scalar_type(ScalarKind k) const override {
    return k == ScalarKind::Float ? "float" : k == ScalarKind::Int ? "int" : "bool";
  }
  std::string vector_type(Type t) const override { return scalar_type(t.kind); }
  std::string literal(ScalarKind k, uint32_t bits) const override {
    char buf[48];
    switch (k) {
      case ScalarKind::Int:
        if (bits == 0x80000000u) return "int(0x80000000u)";
        return std::to_string(static_cast<int32_t>(bits));
      case ScalarKind::Bool:
        return bits ? "true" : "false";
      case ScalarKind::Float: {
        float v = std::bit_cast<float>(bits);
        if (strict_) {
          // Shader compilers fold some operations on literals even in `precise` code
          // (Mesa: x * 0.0 -> 0.0, 0.0 - x -> -x, x - (-0.0) -> x), which is wrong for
          // infinities, NaN and signed zeros. A constant read from a uniform cannot be
          // folded: every float constant of a strict kernel lives in rill_k[].
          size_t i = 0;
          while (i < constants.size() && constants[i] != bits) ++i;
          if (i == constants.size()) constants.push_back(bits);
          return "uintBitsToFloat(rill_k[" + std::to_string(i) + "])";
        }
        // Special and negative-zero values by their bits; others as the shortest decimal
        // that reads back to the same float.
        if (std::isnan(v) || std::isinf(v) || bits == 0x80000000u) {
          std::snprintf(buf, sizeof buf, "uintBitsToFloat(0x%08xu)", bits);
          return buf;
        }
        auto r = std::to_chars(buf, buf + sizeof buf, v);
        std::string s(buf, r.ptr);
        if (s.find_first_of(".e") == std::string::npos) s += ".0";
        return s;
      }
    }
    return "?";
  }
  std::string loop_header() const override { return "while (true)"; }
  // Compute: returning before the stores at the end of main leaves the outputs as they were.
  // With DriverRules::loop_guard, an element that ends here checks the loops first.
  std::string discard() const override {
    const std::string end = stage_ == Stage::Fragment ? "discard;" : "return;";
    return loop_guard_ ? "{ RILL_CHECK_LOOPS(); " + end + " }" : end;
  }
  std::string float_qualifier() const override { return strict_ ? "precise " : ""; }

  std::string initial_value(const Function& f, VarId v, int c) const override {
    const Variable& var = f.var(v);
    std::string comp = std::string(".") + kComp[c];
    switch (var.role) {
      case VarRole::Input:
        return "rill_in" + std::to_string(var.slot) + "_v" + comp;
      case VarRole::Output:
        // Only this pass's outputs read their previous values (the others are not stored).
        if (std::find(pass_outputs_.begin(), pass_outputs_.end(), var.slot) == pass_outputs_.end())
          return literal(var.type.kind, 0);
        return "rill_prev" + std::to_string(var.slot) + "_v" + comp;
      case VarRole::Uniform:
        return "u" + std::to_string(var.slot) + "_" + std::to_string(c);
      default:
        return literal(var.type.kind, 0);
    }
  }

  std::string gather(const Function& f, const Stmt& s, const std::vector<std::string>& index,
                     const std::vector<std::string>& dst) const override {
    std::string id = std::to_string(s.array);
    auto dim = [&](int d) { return "rill_shapes[" + std::to_string(s.array * 3 + d) + "]"; };
    const ArrayDecl& a = f.arrays[static_cast<size_t>(s.array)];
    // Each index mapped into its dimension under the array's boundary mode (see
    // codegen::boundary_index_helper), then linearized, x fastest.
    const std::string fn = "rill_" + codegen::boundary_index_helper(a.boundary);
    std::string lin = fn + "(" + index[0] + ", " + dim(0) + ")";
    if (index.size() > 1) lin += " + " + dim(0) + " * " + fn + "(" + index[1] + ", " + dim(1) + ")";
    if (index.size() > 2)
      lin += " + " + dim(0) + " * " + dim(1) + " * " + fn + "(" + index[2] + ", " + dim(2) + ")";
    const char* vec = a.elem.is_float() ? "vec4" : "ivec4";
    std::string out = "{\n  int g = " + lin + ";\n";
    if (stage_ == Stage::Fragment)  // rows of min(n, kTextureRow) texels: a shift and a mask
      out += "  " + std::string(vec) + " e = texelFetch(rill_arr" + id + ", ivec2(g & " +
             std::to_string(kTextureRow - 1) + ", g >> " + std::to_string(kTextureRowBits) +
             "), 0);\n";
    else if (stage_ == Stage::Compute)  // a buffer texture: element g is texel g
      out += "  " + std::string(vec) + " e = texelFetch(rill_arr" + id + ", g);\n";
    else {  // Vulkan: a storage buffer, element g is words g * width .. g * width + width - 1
      std::string words;
      const int w = a.elem.width;
      for (int c = 0; c < 4; ++c)
        words += (c ? ", " : "") + (c < w ? "rill_arr" + id + ".d[g * " + std::to_string(w) +
                                                " + " + std::to_string(c) + "]"
                                          : std::string(a.elem.is_float() ? "0.0" : "0"));
      out += "  " + std::string(vec) + " e = " + vec + "(" + words + ");\n";
    }
    const bool border = a.boundary == Boundary::Constant;
    if (border) {
      std::string inside;
      for (size_t d = 0; d < index.size(); ++d)
        inside += (d ? " && " : "") + std::string("rill_index_inside(") + index[d] + ", " +
                  dim(static_cast<int>(d)) + ")";
      out += "  bool rill_inside = " + inside + ";\n";
    }
    for (size_t c = 0; c < dst.size(); ++c) {
      std::string v = std::string("e.") + kComp[c];
      if (border) v = select(a.elem.kind, "rill_inside", v, literal(a.elem.kind, a.border.bits[c]));
      out += "  " + dst[c] + " = " + v + ";\n";
    }
    return out + "}\n";
  }

  std::string compare(ScalarKind k, const char* op, const std::string& a,
                      const std::string& b) const override {
    if (k != ScalarKind::Float || !strict_) return "(" + a + " " + op + " " + b + ")";
    std::string o = op;
    if (o == "<") return "rill_lt(" + a + ", " + b + ")";
    if (o == "<=") return "rill_le(" + a + ", " + b + ")";
    if (o == ">") return "rill_lt(" + b + ", " + a + ")";
    if (o == ">=") return "rill_le(" + b + ", " + a + ")";
    if (o == "==") return "rill_eq(" + a + ", " + b + ")";
    return "(!rill_eq(" + a + ", " + b + "))";
  }

  std::string select(ScalarKind k, const std::string& c, const std::string& a,
                     const std::string& b) const override {
    if (k == ScalarKind::Float) return "rill_sel_f(" + c + ", " + a + ", " + b + ")";
    return "(" + c + " ? " + a + " : " + b + ")";
  }

  std::string element_index() const override { return "rill_i"; }
  std::string element_coord(int c) const override {
    return c == 0 ? "(rill_i % rill_width)" : "(rill_i / rill_width)";
  }

 private:
  bool strict_;
  Stage stage_;
  std::vector<int> pass_outputs_;
  bool loop_guard_;
  bool subgroups_;
};

// group_broadcast's helpers under DriverRules::subgroups: the lane's x where that lane is
// active and in range, else the element's own (a shuffle from an inactive invocation is
// undefined, so its result is not used).
const char kSubgroupBroadcast[] = R"(#define RILL_G_BCAST(name, T) T name(T x, int lane) { \
  bool ok = lane >= 0 && lane < int(gl_SubgroupSize) && \
            subgroupBallotBitExtract(subgroupBallot(true), uint(lane)); \
  T v = subgroupShuffle(x, uint(clamp(lane, 0, int(gl_SubgroupSize) - 1))); \
  return ok ? v : x; }
RILL_G_BCAST(rill_g_bcast_f, float)
RILL_G_BCAST(rill_g_bcast_i, int)
RILL_G_BCAST(rill_g_bcast_b, bool)
)";

std::string sampler(ScalarKind k) {
  return k == ScalarKind::Float ? "sampler2D" : "isampler2D";
}
std::string vec4_of(ScalarKind k) {
  return k == ScalarKind::Float ? "vec4" : "ivec4";
}

}  // namespace

std::string vertex_shader() {
  // A triangle covering the viewport, from gl_VertexID alone (no vertex buffers).
  return "#version 430 core\n"
         "void main() {\n"
         "  vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - "
         "1.0);\n"
         "  gl_Position = vec4(p, 0.0, 1.0);\n"
         "}\n";
}

namespace {

// RILL_GLSL_PRAGMAS="a;b": `#pragma a`, `#pragma b` after the #extension lines, for measuring
// what a driver's pragmas (NVIDIA's optionNV) do to speed and bits; empty by default.
std::string measured_pragmas() {
  const char* env = std::getenv("RILL_GLSL_PRAGMAS");
  std::string out, v = env ? env : "";
  size_t start = 0;
  while (start < v.size()) {
    size_t end = v.find(';', start);
    if (end == std::string::npos) end = v.size();
    if (end > start) out += "#pragma " + v.substr(start, end - start) + "\n";
    start = end + 1;
  }
  return out;
}

// What both stages print the same way.
// `extensions`: #extension lines, which must precede everything but preprocessor lines.
// `vulkan`: GLSL 4.50 for glslang, where rill_one is a member of the parameter buffer.
std::string header(const Function& f, Accuracy accuracy, const char* stage,
                   const std::string& extensions = "", bool vulkan = false) {
  std::string src = std::string(vulkan ? "#version 450\n" : "#version 430 core\n") + extensions +
                    measured_pragmas() + "// Generated by Rill from kernel '" +
                    codegen::comment_safe(f.name) + "' (" + accuracy_name(accuracy) + ", " + stage +
                    " stage).\n";
  src += accuracy == Accuracy::Fast
             ? "#define RILL_PRECISE\n#define RILL_ONE 1.0\n#define RILL_ZERO_I 0\n"
             : "#define RILL_PRECISE precise\n#define RILL_ONE uintBitsToFloat(rill_one)\n"
               "#define RILL_ZERO_I int(rill_one ^ 0x3f800000u)\n";
  if (accuracy != Accuracy::Fast && !vulkan) src += "uniform uint rill_one;\n";
  return src;
}

// DriverRules::loop_guard's check, RILL_CHECK_LOOPS(), run where an element ends: llvmpipe
// counts the loop iterations of a batch of lanes against one limit, and once it is spent,
// ends every loop after its first pass through the loop's end (Mesa 22.3 measured: a loop
// that should run on then ran twice, its first iteration peeled off by the compiler). So a
// loop that must run four times (its trip count from a uniform, which the compiler cannot
// see through) falls short only where the kernel's loops were cut, and then sets `flag` to
// 1. (A kernel that leaves the limit fewer than four iterations is reported too.)
std::string loop_check(const std::string& flag) {
  return "#define RILL_CHECK_LOOPS() { int rill_laps = 0; int rill_want = min(rill_count, 1) + "
         "3; while (true) { rill_laps += 1; if (rill_laps == rill_want) break; } if (rill_laps < "
         "rill_want) " +
         flag + " = 1u; }\n";
}

// The launch's uniforms: strict constants, the kernel's uniform words, array shapes.
std::string uniform_declarations(const Function& f, const GLSLDialect& d) {
  std::string src;
  if (!d.constants.empty())
    src += "uniform uint rill_k[" + std::to_string(d.constants.size()) + "];\n";
  if (!f.uniforms.empty())
    src += "uniform uint rill_u[" + std::to_string(f.uniforms.size() * 4) + "];\n";
  if (!f.arrays.empty())
    src += "uniform int rill_shapes[" + std::to_string(f.arrays.size() * 3) + "];\n";
  src += "uniform int rill_count;\nuniform int rill_width;\n";
  return src;
}

// The Vulkan dialect's launch parameters: one read-only std430 storage buffer whose members
// are named as GL's uniforms, so the body reads them alike. std430 packs the arrays as the
// host's words (a uniform buffer's std140 would pad each element to 16 bytes, and push
// constants may be as small as 128 bytes).
std::string vulkan_params_block(const Function& f, const GLSLDialect& d, int binding,
                                bool uniform) {
  std::string src = std::string(uniform ? "layout(scalar, " : "layout(std430, ") +
                    "set = 0, binding = " + std::to_string(binding) +
                    (uniform ? ") uniform" : ") readonly buffer") +
                    " rill_params_b {\n  int rill_count; int rill_width; int "
                    "rill_tiled; int rill_nvalues; uint rill_one;\n  int rill_values[" +
                    std::to_string(kMaskValues) + "];\n";
  if (!d.constants.empty()) src += "  uint rill_k[" + std::to_string(d.constants.size()) + "];\n";
  if (!f.uniforms.empty()) src += "  uint rill_u[" + std::to_string(f.uniforms.size() * 4) + "];\n";
  if (!f.arrays.empty()) src += "  int rill_shapes[" + std::to_string(f.arrays.size() * 3) + "];\n";
  static_assert(kVulkanParamsHeader == 5 + kMaskValues);
  return src + "};\n";
}

// The prelude's helpers for kernel f: the table's (codegen/Helpers.cpp) under the driver's
// rules, then the on-demand ones f calls.
std::string helper_definitions(const Function& f, Accuracy accuracy, const DriverRules& rules,
                               bool flushes_denormals) {
  return std::string("#define RILL_NATIVE_COMPARE ") + (rules.native_compare ? "1" : "0") +
         "\n#define RILL_FLUSHES_DENORMALS " + (flushes_denormals ? "1" : "0") + "\n" +
         codegen::helper_bodies(
             codegen::Language::Glsl,
             accuracy == Accuracy::Fast
                 ? std::vector{codegen::Variant::Fast}
                 : divsqrt_variants(rules.divsqrt, rules.fused_fma, rules.lean)) +
         codegen::on_demand_bodies(codegen::Language::Glsl, f);
}

// The kernel's uniforms as named scalars, at the top of main.
std::string unpack_uniforms(const Function& f, const GLSLDialect& d) {
  std::string src;
  for (size_t i = 0; i < f.uniforms.size(); ++i) {
    const Variable& v = f.var(f.uniforms[i]);
    for (int c = 0; c < v.type.width; ++c) {
      std::string word = "rill_u[" + std::to_string(i * 4 + static_cast<size_t>(c)) + "]";
      std::string value = v.type.is_float() ? "uintBitsToFloat(" + word + ")"
                          : v.type.is_int() ? "int(" + word + ")"
                                            : "(" + word + " != 0u)";
      src += "  " + d.float_qualifier() + d.scalar_type(v.type.kind) + " u" + std::to_string(i) +
             "_" + std::to_string(c) + " = " + value + ";\n";
    }
  }
  return src;
}

// The final value of output o as a vec4 / ivec4 constructor's arguments.
std::string output_components(const Function& f, const codegen::CFamilyPrinter& p, int o) {
  VarId v = f.outputs[static_cast<size_t>(o)];
  const Variable& var = f.var(v);
  std::string parts;
  for (int c = 0; c < 4; ++c)
    parts +=
        (c ? ", " : "") +
        (c < var.type.width ? p.component(v, c) : std::string(var.type.is_float() ? "0.0" : "0"));
  return parts;
}

}  // namespace

GLSLShader emit_glsl(const Function& f, Accuracy accuracy, const std::vector<int>& outputs,
                     const DriverRules& rules, bool source_map) {
  GLSLDialect d(accuracy, Stage::Fragment, outputs, rules.loop_guard);
  codegen::CFamilyPrinter p(f, d, source_map);
  // The body first: printing it collects the constants that the declarations need; printed
  // again once they are in their own order.
  std::string body = p.declarations(1) + p.body(1);
  d.sort_constants();
  body = p.declarations(1) + p.body(1);
  std::string src = header(f, accuracy, "fragment");
  for (size_t i = 0; i < f.inputs.size(); ++i)
    src +=
        "uniform " + sampler(f.var(f.inputs[i]).type.kind) + " rill_in" + std::to_string(i) + ";\n";
  for (int o : outputs)
    src += "uniform " + sampler(f.var(f.outputs[static_cast<size_t>(o)]).type.kind) + " rill_prev" +
           std::to_string(o) + ";\n";
  for (size_t i = 0; i < f.arrays.size(); ++i)
    src += "uniform " + sampler(f.arrays[i].elem.kind) + " rill_arr" + std::to_string(i) + ";\n";
  src += uniform_declarations(f, d);
  src += "uniform int rill_row;\n";
  for (size_t k = 0; k < outputs.size(); ++k) {
    int o = outputs[k];
    src += "layout(location = " + std::to_string(k) + ") out " +
           vec4_of(f.var(f.outputs[static_cast<size_t>(o)]).type.kind) + " rill_out" +
           std::to_string(o) + ";\n";
  }
  if (rules.loop_guard)
    src += "layout(std430, binding = " + std::to_string(kGuardBinding) +
           ") buffer rill_guard_b { uint loops_cut; } rill_guard;\n" +
           loop_check("rill_guard.loops_cut");
  // Every driver's fragment stage that Rill has met flushes (NVIDIA, llvmpipe).
  src += helper_definitions(f, accuracy, rules, true);
  src += "\nvoid main() {\n";
  src += "  ivec2 rill_pos = ivec2(gl_FragCoord.xy);\n";
  src += "  int rill_i = rill_pos.y * rill_row + rill_pos.x;\n";
  src += "  if (rill_i >= rill_count) discard;  // padding after the last element\n";
  for (size_t i = 0; i < f.inputs.size(); ++i)
    src += "  " + vec4_of(f.var(f.inputs[i]).type.kind) + " rill_in" + std::to_string(i) +
           "_v = texelFetch(rill_in" + std::to_string(i) + ", rill_pos, 0);\n";
  for (int o : outputs)
    src += "  " + vec4_of(f.var(f.outputs[static_cast<size_t>(o)]).type.kind) + " rill_prev" +
           std::to_string(o) + "_v = texelFetch(rill_prev" + std::to_string(o) +
           ", rill_pos, 0);\n";
  src += unpack_uniforms(f, d);
  src += body;
  for (int o : outputs)
    src += "  rill_out" + std::to_string(o) + " = " +
           vec4_of(f.var(f.outputs[static_cast<size_t>(o)]).type.kind) + "(" +
           output_components(f, p, o) + ");\n";
  if (rules.loop_guard) src += "  RILL_CHECK_LOOPS();\n";
  src += "}\n";
  return GLSLShader{src, d.constants};
}

ComputeBindings compute_bindings(const Function& f, size_t pass_outputs) {
  ComputeBindings b;
  b.inputs = 0;
  b.outputs = static_cast<int>(f.inputs.size());
  b.counts = b.outputs + static_cast<int>(pass_outputs);
  b.mask = b.counts + 1;
  b.arrays = b.mask + 1;
  b.params = b.arrays + static_cast<int>(f.arrays.size());
  return b;
}

GLSLShader emit_glsl_compute(const Function& f, Accuracy accuracy, const std::vector<int>& outputs,
                             bool counts, const DriverRules& rules, bool flushes_denormals,
                             int local_size, const VulkanTarget* vulkan, bool source_map) {
  GLSLDialect d(accuracy, vulkan ? Stage::Vulkan : Stage::Compute, outputs, rules.loop_guard,
                rules.subgroups);
  codegen::CFamilyPrinter p(f, d, source_map);
  std::string body = p.declarations(1) + p.body(1);
  d.sort_constants();  // as in emit_glsl
  body = p.declarations(1) + p.body(1);
  const ComputeBindings bind = compute_bindings(f, outputs.size());
  // Counting one atomic per subgroup where the driver has ballots (NVIDIA, recent Mesa); an
  // extension the driver lacks is a warning, and its macro stays undefined. The lane-group
  // ops' extensions are required: rules.subgroups says the driver has them.
  // In Vulkan, a device without ballots gets no such extension (its module would need the
  // capability), and the float-controls execution modes follow.
  const std::string subgroups =
      "#extension GL_KHR_shader_subgroup_basic : enable\n"
      "#extension GL_KHR_shader_subgroup_ballot : enable\n";
  const std::string group_ops =
      "#extension GL_KHR_shader_subgroup_vote : require\n"
      "#extension GL_KHR_shader_subgroup_arithmetic : require\n"
      "#extension GL_KHR_shader_subgroup_shuffle : require\n";
  // Extensions before the execution modes, which are declarations.
  std::string src =
      vulkan
          ? header(f, accuracy, "compute, Vulkan",
                   (vulkan->ballot || rules.subgroups ? subgroups : "") +
                       (rules.subgroups ? group_ops : "") +
                       (vulkan->params_uniform ? "#extension GL_EXT_scalar_block_layout : require\n"
                                               : "") +
                       vulkan->execution_modes + "#define RILL_ABS_ON_BITS\n",
                   true)
          : header(f, accuracy, "compute", subgroups + (rules.subgroups ? group_ops : ""));
  src += "layout(local_size_x = " + std::to_string(local_size) + ") in;\n";
  const std::string set = vulkan ? "set = 0, " : "";
  auto block = [&](const std::string& name, int binding, ScalarKind k, bool readonly) {
    return "layout(std430, " + set + "binding = " + std::to_string(binding) + ") " +
           (readonly ? "readonly " : "") + "buffer " + name + "_b { " +
           (k == ScalarKind::Float ? "float" : "int") + " d[]; } " + name + ";\n";
  };
  for (size_t i = 0; i < f.inputs.size(); ++i)
    src += block("rill_in" + std::to_string(i), bind.inputs + static_cast<int>(i),
                 f.var(f.inputs[i]).type.kind, true);
  for (size_t k = 0; k < outputs.size(); ++k)
    src += block("rill_out" + std::to_string(outputs[k]), bind.outputs + static_cast<int>(k),
                 f.var(f.outputs[static_cast<size_t>(outputs[k])]).type.kind, false);
  src += "layout(std430, " + set + "binding = " + std::to_string(bind.counts) +
         ") buffer rill_counts_b { uint written; uint selected; uint loops_cut; } rill_counts;\n";
  if (rules.loop_guard) src += loop_check("rill_counts.loops_cut");
  src += block("rill_mask", bind.mask, ScalarKind::Int, true);
  if (vulkan) {
    for (size_t i = 0; i < f.arrays.size(); ++i)
      src += block("rill_arr" + std::to_string(i), bind.arrays + static_cast<int>(i),
                   f.arrays[i].elem.kind, true);
    src += vulkan_params_block(f, d, bind.params, vulkan->params_uniform);
  } else {
    for (size_t i = 0; i < f.arrays.size(); ++i)
      src += "layout(binding = " + std::to_string(i) + ") uniform " +
             (f.arrays[i].elem.is_float() ? "samplerBuffer" : "isamplerBuffer") + " rill_arr" +
             std::to_string(i) + ";\n";
    src += uniform_declarations(f, d);
    src += "uniform int rill_values[" + std::to_string(kMaskValues) +
           "];\nuniform int rill_nvalues;  // 0: no mask\n";
  }
  src += R"(#if defined(GL_KHR_shader_subgroup_ballot)
#define RILL_COUNT(field) { uvec4 rill_b = subgroupBallot(true); if (subgroupElect()) atomicAdd(rill_counts.field, subgroupBallotBitCount(rill_b)); }
#else
#define RILL_COUNT(field) atomicAdd(rill_counts.field, 1u)
#endif
)";
  if (!counts)
    src += "#undef RILL_COUNT\n#define RILL_COUNT(field)  // counted by the kernel's first pass\n";
  src += helper_definitions(f, accuracy, rules, flushes_denormals);
  if (rules.subgroups && body.find("rill_g_bcast_") != std::string::npos)
    src += kSubgroupBroadcast;  // only into kernels that broadcast
  if (!vulkan) src += "uniform int rill_tiled;\n";
  src += "\nvoid main() {\n";
  src +=
      "  int rill_i = int(gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * gl_WorkGroupSize.x) + "
      "gl_GlobalInvocationID.x);\n";
  // Tiled order for 2D launches (rill_tiled; codegen/Tiles.h).
  src += "  if (rill_tiled != 0)\n" +
         codegen::tiled_element("int", "rill_i", "rill_width", "return;", "  ");
  src += "  if (rill_i >= rill_count) return;  // past the last element\n";
  src +=
      "  if (rill_nvalues > 0) {  // a masked launch: only elements whose state is listed\n"
      "    int rill_state = rill_mask.d[rill_i];\n"
      "    bool rill_selected = false;\n"
      "    for (int k = 0; k < rill_nvalues; ++k) rill_selected = rill_selected || rill_state == "
      "rill_values[k];\n"
      "    if (!rill_selected) return;\n"
      "    RILL_COUNT(selected);\n"
      "  }\n";
  // The element's inputs and outputs' previous values, as the fragment stage's texel reads.
  auto load = [&](const std::string& buffer, const std::string& local, ir::Type t) {
    std::string parts;
    for (int c = 0; c < 4; ++c)
      parts += (c ? ", " : "") + (c < t.width ? buffer + ".d[rill_i * " + std::to_string(t.width) +
                                                    " + " + std::to_string(c) + "]"
                                              : std::string(t.is_float() ? "0.0" : "0"));
    return "  " + vec4_of(t.kind) + " " + local + " = " + vec4_of(t.kind) + "(" + parts + ");\n";
  };
  for (size_t i = 0; i < f.inputs.size(); ++i)
    src += load("rill_in" + std::to_string(i), "rill_in" + std::to_string(i) + "_v",
                f.var(f.inputs[i]).type);
  for (int o : outputs)
    src += load("rill_out" + std::to_string(o), "rill_prev" + std::to_string(o) + "_v",
                f.var(f.outputs[static_cast<size_t>(o)]).type);
  src += unpack_uniforms(f, d);
  src += body;
  // Reached only where the element was not discarded.
  for (int o : outputs) {
    const ir::Type t = f.var(f.outputs[static_cast<size_t>(o)]).type;
    const std::string v = "rill_v" + std::to_string(o);
    src += "  " + vec4_of(t.kind) + " " + v + " = " + vec4_of(t.kind) + "(" +
           output_components(f, p, o) + ");\n";
    for (int c = 0; c < t.width; ++c)
      src += "  rill_out" + std::to_string(o) + ".d[rill_i * " + std::to_string(t.width) + " + " +
             std::to_string(c) + "] = " + v + "." + kComp[c] + ";\n";
  }
  if (rules.loop_guard) src += "  RILL_CHECK_LOOPS();\n";
  src += "  RILL_COUNT(written);\n";
  src += "}\n";
  return GLSLShader{src, d.constants};
}

std::string glsl_helpers(const Function& f, Accuracy accuracy, const DriverRules& rules,
                         bool flushes_denormals) {
  return helper_definitions(f, accuracy, rules, flushes_denormals);
}

}  // namespace rill::glsl
