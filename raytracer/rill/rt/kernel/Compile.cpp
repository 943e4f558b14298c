// compile_for (Compile.h).
#include "rill/rt/kernel/Compile.h"

#include <stdexcept>

namespace rt {

using namespace rill;

void check_backend(const std::string& backend_name, Accuracy a) {
  Backend& be = backend(backend_name);
  if (std::string why = be.unavailable_reason(); !why.empty())
    throw std::runtime_error("backend " + backend_name + " cannot run here: " + why);
  if (!be.supports(a))
    throw std::runtime_error(std::string("backend ") + backend_name + " has no " +
                             accuracy_name(a) + " accuracy mode");
}

Kernel compile_for(const Program& program, const std::string& backend_name, Accuracy a) {
  check_backend(backend_name, a);
  CompileOptions opt;
  opt.accuracy = a;
  return compile(program, backend_name, opt);
}

}  // namespace rt
