#include "rill/rt/render/RenderResult.h"

#include <utility>

#include "rill/Stopwatch.h"
#include "rill/rt/render/OutputsInFlight.h"

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

void RenderResult::wait_outputs() {
  if (!in_flight) return;
  // Taken first: a read-back that fails is not waited for again.
  const std::shared_ptr<OutputsInFlight> f = std::move(in_flight);
  rill::Stopwatch waited;
  for (rill::ReadBack& read : f->reads) read.wait();
  if (f->rgb8_bytes) rgb8.resize(f->rgb8_bytes);  // the last group's padding cut off
  const double ms = waited.ms();
  times.read_back += ms;
  trace_ms += ms;
}

void move_aovs(RenderResult& from, RenderResult& to) {
  from.wait_outputs();  // reads in flight write into these vectors
  to.wait_outputs();
  to.depth = std::move(from.depth);
  to.prim = std::move(from.prim);
  to.normal = std::move(from.normal);
  to.albedo = std::move(from.albedo);
}

}  // namespace rt
