// Registers the backends this build includes (see CMakeLists.txt: RILL_WITH_*).
#include "cpu/CpuBackend.h"
#include "rill/Backend.h"

namespace rill::detail {

void register_builtin_backends() {
  register_backend(cpu::make_backend());
}

}  // namespace rill::detail
