// Emits a kernel as a C translation unit for the CPU backend (see CEmitter.cpp).
#pragma once

#include <string>

#include "rill/Backend.h"
#include "rill/ir/IR.h"

namespace rill::codegen {
class Dialect;
}

namespace rill::cpu {

// How the C is laid out: outline_min_cost 0 prints the kernel as one function; otherwise
// blocks costing at least that many are printed as functions of their own (Outline.h),
// spread over up to max_units translation units (C_UNITS_MARK below).
struct CLayout {
  size_t outline_min_cost = 0;
  int max_units = 1;
  size_t unit_cost = 3000;  // at most one unit per this much cost (Outline.h's measure)
  // Loop-free parts may be compiled at -O1 in units of their own (kColdUnitsMark).
  bool cold_units = false;
  // With #line directives naming the user's lines (codegen/SourceMap.h).
  bool source_map = false;
};
std::string emit_c(const ir::Function& optimized, Accuracy accuracy, const CLayout& layout = {});

// A source with outlined functions is one file that compiles as one translation unit, or
// as `units` of them, each with -DRILL_TU=k (k < units), linked together; the first line
// that starts with this mark says how many: "/* rill-units: N */". Returns 1 without it.
inline constexpr const char* kUnitsMark = "/* rill-units: ";
int c_units(const std::string& source);
// Of those units, the last ones that hold only outlined parts that run no loop
// (OutlinedPart::loops), compiled at -O1 instead of -O2: "/* rill-cold-units: K */" on the
// line after the units mark; 0 without it. Straight-line code runs once per call, so where
// a kernel's time goes (its loops: the grid walk) stays at -O2, and the compile of a large
// kernel's first image is shorter. -O1 and -O2 compute the same bits: strict kernels are
// compiled without FMA contraction, excess precision or fast math at every level.
inline constexpr const char* kColdUnitsMark = "/* rill-cold-units: ";
int c_cold_units(const std::string& source);

// Pieces every C translation unit of the CPU backends shares (the scalar one above and the
// lockstep one in simd/LockstepEmitter.h):
// the header comment, rill_real, the launch struct and the rill_* helpers;
std::string c_head(const ir::Function& f, Accuracy accuracy);
// the entry point's locals: in<k>/out<k> pointers, u<k>_<c> uniforms, arr<k> and shapes.
std::string c_entry_locals(const ir::Function& f, const codegen::Dialect& d);

}  // namespace rill::cpu
