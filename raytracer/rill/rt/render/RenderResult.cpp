#include "rill/rt/render/RenderResult.h"

#include <utility>

namespace rt {

void add_stages(RenderResult& r, const rill::CompileInfo& k) {
  rill::CompileInfo& s = r.stages;
  if (r.kernels++ == 0) s.origin = k.origin;
  s.capture_ms += k.capture_ms;
  s.optimize_ms += k.optimize_ms;
  s.codegen_ms += k.codegen_ms;
  s.backend_compile_ms += k.backend_compile_ms;
  s.driver_finish_ms += k.driver_finish_ms;
  s.compile_ms += k.compile_ms;
  if (s.execution.empty()) s.execution = k.execution;
}

void move_aovs(RenderResult& from, RenderResult& to) {
  to.depth = std::move(from.depth);
  to.prim = std::move(from.prim);
  to.normal = std::move(from.normal);
  to.albedo = std::move(from.albedo);
}

}  // namespace rt
