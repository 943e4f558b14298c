// Stand-in data for a warm-up launch (see WarmUpLaunch.h).
#include "WarmUpLaunch.h"

namespace rill {

WarmUpLaunch::WarmUpLaunch(const ir::Function& f) {
  auto stream = [&](ir::VarId v) {
    streams_.push_back(std::make_unique<detail::StreamState>());
    detail::init_stream(*streams_.back(), f.var(v).type, 1, 1, 1, "warm-up " + f.var(v).name);
    return streams_.back().get();
  };
  for (ir::VarId v : f.inputs) args_.inputs.push_back(stream(v));
  for (ir::VarId v : f.outputs) args_.outputs.push_back(stream(v));
  for (ir::VarId v : f.uniforms) {
    uniforms_.push_back(std::make_unique<detail::UniformState>());
    uniforms_.back()->name = f.var(v).name;
    uniforms_.back()->type = f.var(v).type;
    args_.uniforms.push_back(uniforms_.back().get());
  }
  for (const ir::ArrayDecl& decl : f.arrays) {
    arrays_.push_back(std::make_unique<detail::ArrayState>());
    detail::ArrayState& a = *arrays_.back();
    a.init(decl.elem, 1);
    a.name = "warm-up " + decl.name;
    a.dims = decl.dims;
    a.shape[0] = a.shape[1] = a.shape[2] = 1;
    args_.arrays.push_back(&a);
  }
  args_.count = 0;
  args_.width = args_.height = 1;
  args_.warm_up = true;
}

}  // namespace rill
