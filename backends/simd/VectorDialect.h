// The lockstep dialect of C: how the shared C-family printer prints a kernel lowered by
// passes::lower_lockstep, for the simd backend.
//
// Every variable component is a vector of RILL_W lanes (GCC/Clang vector extensions, which
// compile to SSE/AVX): rill_vr for floats, rill_vi for ints and for bools, which are lane masks
// (-1 true, 0 false). Operators apply to all lanes at once; a HELPER form of Ops.def calls the
// helper's lane-wise twin rill_v_*; the conditions of ifs and loops test whether any lane has
// them (the lowered kernel's convention). Names follow the C dialect (CDialect.h), plus the
// group's lanes: rill_lane[] holds each lane's element, rill_element and rill_coord_x/y their
// index and coordinates.
#pragma once

#include "../codegen/CDialect.h"

namespace rill::simd {

class VectorDialect : public codegen::CDialect {
 public:
  VectorDialect(Accuracy a, int lanes) : CDialect(a, ""), lanes_(lanes) {}

  std::string scalar_type(ir::ScalarKind k) const override {
    return k == ir::ScalarKind::Float ? "rill_vr" : "rill_vi";
  }
  std::string vector_type(ir::Type t) const override { return scalar_type(t.kind); }
  // A constant in every lane.
  std::string literal(ir::ScalarKind k, uint32_t bits) const override {
    switch (k) {
      case ir::ScalarKind::Float:
        return "rill_splat_r(" + CDialect::literal(k, bits) + ")";
      case ir::ScalarKind::Int:
        return "rill_splat_i(" + CDialect::literal(k, bits) + ")";
      case ir::ScalarKind::Bool:
        return bits ? "rill_splat_i(-1)" : "rill_splat_i(0)";
    }
    return "?";
  }
  // Stream elements are loaded lane by lane (each lane's element of the group); uniforms are
  // the same in every lane.
  std::string initial_value(const ir::Function& f, ir::VarId v, int c) const override {
    const ir::Variable& var = f.var(v);
    const std::string lanes = var.type.is_float() ? "rill_lanes_r(" : "rill_lanes_i(";
    const std::string at =
        " + " + std::to_string(c) + ", rill_lane, " + std::to_string(var.type.width) + ")";
    switch (var.role) {
      case ir::VarRole::Input:
        return lanes + "in" + std::to_string(var.slot) + at;
      case ir::VarRole::Output:
        return lanes + "out" + std::to_string(var.slot) + at;
      case ir::VarRole::Uniform: {
        const std::string u = "u" + std::to_string(var.slot) + "_" + std::to_string(c);
        if (var.type.is_float()) return "rill_splat_r(" + u + ")";
        return "rill_splat_i(" + (var.type.is_bool() ? "-(" + u + " != 0)" : u) + ")";
      }
      default:
        return literal(var.type.kind, 0);
    }
  }
  std::string discard() const override {
    throw Error("internal: lockstep C prints lowered kernels, which have no discard");
  }

  std::string compare(ir::ScalarKind, const char* op, const std::string& a,
                      const std::string& b) const override {
    return "RILL_CMP(" + a + " " + op + " " + b + ")";
  }
  std::string select(ir::ScalarKind k, const std::string& c, const std::string& a,
                     const std::string& b) const override {
    return std::string(k == ir::ScalarKind::Float ? "rill_sel_r(" : "rill_sel_i(") + c + ", " + a +
           ", " + b + ")";
  }
  std::string helper(const std::string& name) const override { return "rill_v_" + name; }
  bool lane_masks() const override { return true; }
  std::string branch_condition(const std::string& c) const override {
    return "rill_any(" + c + ")";
  }
  // The group is the RILL_W lanes (docs/programming-model.md); the lanes taking part are
  // those of the op's mask operand (lower_lockstep appends it) that hold a real element
  // (rill_live: not the spare lanes of a short group). The rill_g_* functions are
  // LockstepEmitter.cpp's, emitted only for kernels that use them.
  std::string group(ir::Op op, ir::ScalarKind k, int c,
                    const std::vector<std::string>& args) const override {
    const std::string m = args.empty() ? "" : "(" + args.back() + " & rill_live)";
    switch (op) {
      case ir::Op::GroupSize:
        return "rill_splat_i(RILL_W)";
      case ir::Op::LaneIndex:
        return "rill_lane_id";
      case ir::Op::GroupAny:
        return "rill_g_any(" + args[0] + ", " + m + ")";
      case ir::Op::GroupAll:
        return "rill_g_all(" + args[0] + ", " + m + ")";
      case ir::Op::GroupBallot:  // at most 16 lanes: components 1..3 are 0
        return c == 0 ? "rill_g_ballot(" + args[0] + ", " + m + ")" : "rill_splat_i(0)";
      case ir::Op::GroupCount:
        return "rill_g_count(" + args[0] + ", " + m + ")";
      case ir::Op::GroupMin:
        return "rill_g_min(" + args[0] + ", " + m + ")";
      case ir::Op::GroupMax:
        return "rill_g_max(" + args[0] + ", " + m + ")";
      case ir::Op::GroupSum:
        return "rill_g_sum(" + args[0] + ", " + m + ")";
      case ir::Op::GroupBroadcast:
        return std::string(k == ir::ScalarKind::Float ? "rill_g_bcast_r(" : "rill_g_bcast_i(") +
               args[0] + ", " + args[1] + ", " + m + ")";
      default:
        break;
    }
    throw Error(std::string("internal: lockstep C has no form for ") + ir::op_name(op));
  }
  std::string element_index() const override { return "rill_element"; }
  std::string element_coord(int c) const override {
    return c == 0 ? "rill_coord_x" : "rill_coord_y";
  }

  // Each lane loads its own element at the scalar gather's clamped index. The index is
  // computed on vectors in 32 bits (the backend refuses arrays of 2^31 words or more, see
  // CpuBackend.cpp). A whole vec3/vec4/ivec2 element is loaded once per lane and transposed
  // (rill_gather3_r and kin: AVX2 at 8 lanes, gathers per component with AVX-512 at 16; the
  // prelude says which, RILL_HAVE_GATHER34); otherwise each component is a vector initializer from
  // scalar loads (rill_gather_r): writing lanes one by one to memory and reading the vector
  // back would stall on store forwarding.
  std::string gather(const ir::Function& f, const ir::Stmt& s,
                     const std::vector<std::string>& index,
                     const std::vector<std::string>& dst) const override {
    const ir::ArrayDecl& a = f.arrays.at(static_cast<size_t>(s.array));
    const std::string id = std::to_string(s.array), shape = "arr" + id + "_shape";
    // Each index mapped into its dimension under the array's boundary mode (CDialect's
    // gather says how; Constant also keeps a lane mask of the lanes whose indices are inside).
    const std::string fn = "rill_v_" + codegen::boundary_index_helper(a.boundary);
    auto clamped = [&](size_t d) {
      return fn + "(" + index[d] + ", " + shape + "[" + std::to_string(d) + "])";
    };
    std::string lin = clamped(0);
    if (index.size() > 1)
      lin = "rill_v_add_i(" + lin + ", rill_v_mul_i(rill_splat_i((int32_t)" + shape + "[0]), " +
            clamped(1) + "))";
    if (index.size() > 2)
      lin = "rill_v_add_i(" + lin + ", rill_v_mul_i(rill_splat_i((int32_t)(" + shape + "[0] * " +
            shape + "[1])), " + clamped(2) + "))";
    std::string out = "{\n  const rill_vi rill_g = rill_v_mul_i(" + lin + ", rill_splat_i(" +
                      std::to_string(a.elem.width) + "));\n";
    const bool border = a.boundary == ir::Boundary::Constant;
    if (border) {
      std::string inside;
      for (size_t d = 0; d < index.size(); ++d)
        inside += (d ? " & " : "") + std::string("rill_v_index_inside(") + index[d] + ", " + shape +
                  "[" + std::to_string(d) + "])";
      out += "  const rill_vi rill_inside = " + inside + ";\n";
    }
    const bool whole =
        (lanes_ == 8 || lanes_ == 16) && dst.size() >= 2 &&
        (a.elem.is_float() ? a.elem.width == 3 || a.elem.width == 4 : a.elem.width == 2);
    const std::string kind = a.elem.is_float() ? "_r" : "_i";
    if (whole) {
      const std::string vt = scalar_type(a.elem.kind);
      std::string q, fallback;
      for (int c = 0; c < a.elem.width; ++c) {
        std::string qc = "rill_q" + std::to_string(c);
        q += ", &" + qc;
        fallback += "  const " + vt + " " + qc + " = rill_gather" + kind + "(arr" + id + " + " +
                    std::to_string(c) + ", rill_g);\n";
      }
      out += "#ifdef RILL_HAVE_GATHER34\n";
      out += "  " + vt + " rill_q0, rill_q1, rill_q2, rill_q3;\n";
      out += "  rill_gather" + std::to_string(a.elem.width) + kind + "(arr" + id + ", rill_g" + q +
             ");\n";
      out += "#else\n" + fallback + "#endif\n";
    }
    for (size_t c = 0; c < dst.size(); ++c) {
      std::string v =
          whole ? "rill_q" + std::to_string(c)
                : "rill_gather" + kind + "(arr" + id + " + " + std::to_string(c) + ", rill_g)";
      if (border) v = select(a.elem.kind, "rill_inside", v, literal(a.elem.kind, a.border.bits[c]));
      out += "  " + dst[c] + " = " + v + ";\n";
    }
    return out + "}\n";
  }

 private:
  int lanes_;
};

}  // namespace rill::simd
