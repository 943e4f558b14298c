// A kernel's interface: stream inputs and outputs (declared inside a program) and uniforms
// (declared on the host, read by any program that uses them).
//
//   rill::Uniform<Float> gain(2.0f);               // host side; gain.set(3.0f) later
//   auto scale = rill::program("scale", [&] {
//     rill::Input<Float> x("x");                    // one element of the input stream
//     rill::Output<Float> y("y");                   // one element of the output stream
//     y = x * gain;
//   });
//
// Unnamed inputs and outputs are called in0, in1, ... and out0, out1, ...
// Inputs and outputs bind to streams by name (Kernel::bind, checked) or in declaration order
// (Kernel::inputs/outputs). Records (Record.h) declare one parameter per field. Every output must be written somewhere in the program. An output that
// is not written on some path keeps the value its stream already had.
#pragma once

#include <mutex>

#include "rill/Value.h"

namespace rill {

namespace detail {
// Host value of a uniform: the current bits, read at each launch.
struct UniformState {
  std::string name;
  ir::Type type;
  std::array<uint32_t, 4> bits{};
};
}  // namespace detail

template <class V>
class Input : public V {
 public:
  explicit Input(std::string name = {}, SourceLoc loc = RILL_HERE)
      : V(detail::new_var(V::type(), ir::VarRole::Input, std::move(name), loc),
          detail::AdoptTag{}) {}
  using V::operator=;
};

template <class V>
class Output : public V {
 public:
  explicit Output(std::string name = {}, SourceLoc loc = RILL_HERE)
      : V(detail::new_var(V::type(), ir::VarRole::Output, std::move(name), loc),
          detail::AdoptTag{}) {}
  using V::operator=;
  Output& operator=(const Output& o) {
    V::operator=(o);
    return *this;
  }
};

// A value set on the host and read by kernels; changing it needs no recompile.
template <class V>
class Uniform : public V {
 public:
  using host_type = typename V::host_type;

  explicit Uniform(const host_type& initial = host_type{}, std::string name = "uniform")
      : V(make_ref(std::move(name)), detail::AdoptTag{}) {
    set(initial);
  }
  Uniform(const Uniform&) = delete;
  Uniform& operator=(const Uniform&) = delete;

  void set(const host_type& v) {
    auto& st = *this->ref().uniform;
    if constexpr (V::width == 1) {
      st.bits[0] = detail::scalar_bits<typename V::scalar_type>(v);
    } else {
      for (int i = 0; i < V::width; ++i)
        st.bits[static_cast<size_t>(i)] = detail::scalar_bits<typename V::scalar_type>(v[i]);
    }
  }
  Uniform& operator=(const host_type& v) {
    set(v);
    return *this;
  }

 private:
  static detail::Ref make_ref(std::string name) {
    detail::Ref r;
    r.kind = detail::Ref::Kind::Uniform;
    r.uniform = std::make_shared<detail::UniformState>();
    r.uniform->name = std::move(name);
    r.uniform->type = V::type();
    return r;
  }
};

}  // namespace rill
