// The division and square-root rule of strict GLSL kernels (see DivSqrt.h for the method).
#include "DivSqrt.h"

#include <cstdlib>

#include "GLSession.h"
#include "rill/Error.h"

namespace rill::glsl {

const char* divsqrt_name(DivSqrt m) {
  switch (m) {
    case DivSqrt::Native:
      return "native";
    case DivSqrt::Corrected:
      return "corrected";
    case DivSqrt::Inexact:
      return "inexact";
    case DivSqrt::InexactCorrected:
      return "inexact-corrected";
  }
  return "?";
}

DivSqrt divsqrt_mode(const std::string& renderer) {
  const char* env = std::getenv("RILL_GLSL_DIVSQRT");
  std::string v = env ? env : "auto";
  if (v == "auto" || v.empty()) return is_llvmpipe(renderer) ? DivSqrt::Native : DivSqrt::Corrected;
  for (DivSqrt m :
       {DivSqrt::Native, DivSqrt::Corrected, DivSqrt::Inexact, DivSqrt::InexactCorrected})
    if (v == divsqrt_name(m)) return m;
  throw Error("RILL_GLSL_DIVSQRT='" + v +
              "' is not one of auto, native, corrected, inexact, inexact-corrected");
}

std::optional<bool> fused_fma_mode() {
  const char* env = std::getenv("RILL_GLSL_FMA");
  const std::string v = env ? env : "auto";
  if (v == "auto" || v.empty()) return std::nullopt;
  if (v == "fused") return true;
  if (v == "split") return false;
  throw Error("RILL_GLSL_FMA='" + v + "' is not one of auto, fused, split");
}

bool lean_fused_mode() {
  const char* env = std::getenv("RILL_GLSL_FUSED");
  const std::string v = env ? env : "lean";
  if (v == "lean" || v.empty()) return true;
  if (v == "residual") return false;
  throw Error("RILL_GLSL_FUSED='" + v + "' is not one of lean, residual");
}

bool divsqrt_corrects(DivSqrt m) {
  return m == DivSqrt::Corrected || m == DivSqrt::InexactCorrected;
}

std::vector<codegen::Variant> divsqrt_variants(DivSqrt m, bool fused_fma, bool lean) {
  using codegen::Variant;
  bool inexact = m == DivSqrt::Inexact || m == DivSqrt::InexactCorrected;
  if (!divsqrt_corrects(m))
    return {inexact ? Variant::InexactOps : Variant::DriverOps, Variant::Uncorrected};
  if (fused_fma && lean) return {inexact ? Variant::InexactOps : Variant::DriverOps, Variant::Lean};
  return {inexact ? Variant::InexactOps : Variant::DriverOps, Variant::Corrected,
          fused_fma ? Variant::FusedResidual : Variant::SplitResidual};
}

std::string divsqrt_description(DivSqrt m, bool fused_fma, bool lean) {
  std::string s = divsqrt_name(m);
  if (divsqrt_corrects(m))
    s += !fused_fma ? ", split residual" : lean ? ", fused lean" : ", fused residual";
  return s;
}

}  // namespace rill::glsl
