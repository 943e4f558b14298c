#include "rill/Program.h"

#include "rill/Parameters.h"
#include "rill/Reference.h"
#include "rill/Stopwatch.h"
#include "rill/Stream.h"
#include "rill/ir/Hash.h"
#include "rill/ir/Printer.h"

namespace rill {

Program::Program(detail::CapturedProgram captured) {
  Stopwatch hashing;  // hashing is the last step of capture: the caches need the key
  hash_ = ir::hash(*captured.fn);
  captured.capture_ms += hashing.ms();
  d_ = std::make_shared<const detail::CapturedProgram>(std::move(captured));
}

std::string Program::print() const { return ir::print(*d_->fn); }

std::string Program::print(const ir::PrintOptions& options) const {
  return ir::print(*d_->fn, options);
}

void Program::dump(std::ostream& os) const {
  os << *this;
}

std::ostream& operator<<(std::ostream& os, const Program& p) {
  if (!p.valid()) return os << "(empty program)\n";
  return os << p.print();
}

ir::InterpreterLaunch reference_launch(const Program& p) {
  ir::InterpreterLaunch l;
  for (const auto& u : p.captured().uniforms) l.uniforms.push_back(u->bits);
  for (const auto& a : p.captured().arrays) {
    ir::InterpreterArray ia;
    ia.data = a->host_data_for_read();
    for (int d = 0; d < 3; ++d) ia.shape[d] = a->shape[d];
    l.arrays.push_back(ia);
  }
  return l;
}

}  // namespace rill
