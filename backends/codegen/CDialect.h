// The dialect shared by the C and OpenCL C emitters.
//
// Both print scalarized code (one variable per vector component) over the same naming
// convention, which their entry points set up: the element index is `rill_i`; input,
// output and array data are `in<k>`, `out<k>`, `arr<k>` (element-interleaved components)
// with `arr<k>_shape[3]`; uniform components are `u<k>_<c>`. They differ only in how an
// element is abandoned (a goto in C, a return in OpenCL) and where the domain width lives.
#pragma once

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "CFamilyPrinter.h"

namespace rill::codegen {

class CDialect : public Dialect {
 public:
  // discard: the statement that abandons an element; coord_x, coord_y: 64-bit expressions
  // for element_coord (the C loop keeps two counters in step with rill_i, where OpenCL
  // divides rill_i by the row length).
  CDialect(Accuracy a, std::string discard, std::string coord_x = "rill_x",
           std::string coord_y = "rill_y")
      : accuracy_(a),
        discard_(std::move(discard)),
        coord_x_(std::move(coord_x)),
        coord_y_(std::move(coord_y)) {}

  bool scalarize() const override { return true; }
  std::string scalar_type(ir::ScalarKind k) const override {
    switch (k) {
      case ir::ScalarKind::Float:
        return "rill_real";
      case ir::ScalarKind::Int:
        return "int32_t";
      case ir::ScalarKind::Bool:
        return "int";
    }
    return "?";
  }
  std::string vector_type(ir::Type t) const override { return scalar_type(t.kind); }
  std::string literal(ir::ScalarKind k, uint32_t bits) const override {
    switch (k) {
      case ir::ScalarKind::Int:
        if (bits == 0x80000000u) return "(-2147483647 - 1)";
        return std::to_string(static_cast<int32_t>(bits));
      case ir::ScalarKind::Bool:
        return bits ? "1" : "0";
      case ir::ScalarKind::Float: {
        float v = std::bit_cast<float>(bits);
        if (v != v || v == INFINITY || v == -INFINITY) {
          char buf[48];
          std::snprintf(buf, sizeof buf, "rill_word_f(0x%08xu)", bits);
          return buf;
        }
        // The shortest decimal that reads back as this float, with the f suffix: C compilers
        // round float literals correctly, so the value is exact (and widens exactly to
        // double in double mode).
        char buf[48];
        auto r = std::to_chars(buf, buf + sizeof buf, v);
        std::string s(buf, r.ptr);
        if (s.find_first_of(".e") == std::string::npos) s += ".0";
        // In double mode the constant is widened first, so that operations on constants
        // alone are evaluated in double like everything else.
        if (accuracy_ == Accuracy::Double) return "((rill_real)" + s + "f)";
        return s + "f";
      }
    }
    return "?";
  }
  std::string discard() const override { return discard_; }

  std::string initial_value(const ir::Function& f, ir::VarId v, int c) const override {
    const ir::Variable& var = f.var(v);
    int w = var.type.width;
    std::string at = "[rill_i * " + std::to_string(w) + " + " + std::to_string(c) + "]";
    switch (var.role) {
      case ir::VarRole::Input:
        return "in" + std::to_string(var.slot) + at;
      case ir::VarRole::Output:
        return "out" + std::to_string(var.slot) + at;
      case ir::VarRole::Uniform:
        return "u" + std::to_string(var.slot) + "_" + std::to_string(c);
      default:
        return literal(var.type.kind, 0);
    }
  }

  std::string gather(const ir::Function& f, const ir::Stmt& s,
                     const std::vector<std::string>& index,
                     const std::vector<std::string>& dst) const override {
    const ir::ArrayDecl& a = f.arrays.at(static_cast<size_t>(s.array));
    std::string id = std::to_string(s.array);
    std::string shape = "arr" + id + "_shape";
    // Map each index into its dimension under the array's boundary mode, then linearize (x
    // fastest), in 64 bits. A 1D clamped index is found in 32 bits (Helpers.cpp), against the
    // count the entry point declared (array_counts32).
    const std::string fn = "rill_" + boundary_index_helper(a.boundary);
    auto dim = [&](size_t d) { return shape + "[" + std::to_string(d) + "]"; };
    std::string lin = fn + "(" + index[0] + ", " + dim(0) + ")";
    if (index.size() == 1 && fn == "rill_clamp_index")
      lin = "(int64_t)rill_clamp_index32(" + index[0] + ", arr" + id + "_n32)";
    if (index.size() > 1) lin += " + " + dim(0) + " * " + fn + "(" + index[1] + ", " + dim(1) + ")";
    if (index.size() > 2)
      lin += " + " + dim(0) + " * " + dim(1) + " * " + fn + "(" + index[2] + ", " + dim(2) + ")";
    std::string out =
        "{\n  const int64_t g = (" + lin + ") * " + std::to_string(a.elem.width) + ";\n";
    const bool border = a.boundary == ir::Boundary::Constant;
    if (border) {
      std::string inside;
      for (size_t d = 0; d < index.size(); ++d)
        inside +=
            (d ? " && " : "") + std::string("rill_index_inside(") + index[d] + ", " + dim(d) + ")";
      out += "  const int rill_inside = " + inside + ";\n";
    }
    for (size_t c = 0; c < dst.size(); ++c) {
      std::string load = (a.elem.is_float() ? "(rill_real)" : "") + std::string("arr") + id +
                         "[g + " + std::to_string(c) + "]";
      if (border)
        load = select(a.elem.kind, "rill_inside", load, literal(a.elem.kind, a.border.bits[c]));
      out += "  " + dst[c] + " = " + load + ";\n";
    }
    return out + "}\n";
  }

  std::string element_index() const override { return "((int32_t)rill_i)"; }
  std::string element_coord(int c) const override {
    return "((int32_t)" + (c == 0 ? coord_x_ : coord_y_) + ")";
  }

 private:
  Accuracy accuracy_;
  std::string discard_, coord_x_, coord_y_;
};

// Statements both C-family entry points share, in the naming convention above.

// `const T u<k>_<c> = ...;` for every uniform component, from the 4-words-per-uniform table
// named `words` (L->uniforms in C, rill_uniforms in OpenCL).
inline std::string unpack_uniforms(const ir::Function& f, const Dialect& d,
                                   const std::string& words, const std::string& pad) {
  std::string out;
  for (size_t i = 0; i < f.uniforms.size(); ++i) {
    const ir::Variable& v = f.var(f.uniforms[i]);
    for (int c = 0; c < v.type.width; ++c) {
      std::string word = words + "[" + std::to_string(i * 4 + static_cast<size_t>(c)) + "]";
      std::string value = v.type.is_float() ? "rill_word_f(" + word + ")"
                                            : "(" + d.scalar_type(v.type.kind) + ")" + word;
      out += pad + "const " + d.scalar_type(v.type.kind) + " u" + std::to_string(i) + "_" +
             std::to_string(c) + " = " + value + ";\n";
    }
  }
  return out;
}

// `out<k>[rill_i * w + c] = ...;` for every output component (floats narrowed to binary32).
inline std::string store_outputs(const ir::Function& f, const CFamilyPrinter& p,
                                 const std::string& pad) {
  std::string out;
  for (size_t i = 0; i < f.outputs.size(); ++i) {
    ir::VarId v = f.outputs[i];
    const ir::Variable& var = f.var(v);
    for (int c = 0; c < var.type.width; ++c) {
      std::string value = p.component(v, c);
      if (var.type.is_float()) value = "rill_store_f(" + value + ")";
      out += pad + "out" + std::to_string(i) + "[rill_i * " + std::to_string(var.type.width) +
             " + " + std::to_string(c) + "] = " + value + ";\n";
    }
  }
  return out;
}

}  // namespace rill::codegen
