// Compiling the tracer's programs for a backend, with the errors a renderer's user needs:
// the backend cannot run here (and why), or it lacks the accuracy mode asked for (checked
// alone by the strategies that compile several kernels at once with compile_all).
#pragma once

#include <rill/rill.h>

#include <string>

namespace rt {

// Throws std::runtime_error where the backend cannot run here or has no accuracy mode a.
void check_backend(const std::string& backend, rill::Accuracy a);
// compile() after check_backend.
rill::Kernel compile_for(const rill::Program& program, const std::string& backend,
                         rill::Accuracy a);

}  // namespace rt
