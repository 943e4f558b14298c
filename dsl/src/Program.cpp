#include "rill/Program.h"

#include "rill/ir/Hash.h"
#include "rill/ir/Printer.h"

namespace rill {

Program::Program(detail::CapturedProgram captured)
    : d_(std::make_shared<const detail::CapturedProgram>(std::move(captured))),
      hash_(ir::hash(*d_->fn)) {}

std::string Program::print() const { return ir::print(*d_->fn); }

}  // namespace rill
