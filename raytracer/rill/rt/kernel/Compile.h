// Compiling the tracer's programs for a backend, with the errors a renderer's user needs:
// the backend cannot run here (and why), or it lacks the accuracy mode asked for.
#pragma once

#include <rill/rill.h>

#include <string>

namespace rt {

rill::Kernel compile_for(const rill::Program& program, const std::string& backend,
                         rill::Accuracy a);

}  // namespace rt
