// The random program generator: C++ that calls the DSL with randomly chosen operations.
#include "Generator.h"

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <type_traits>

namespace rill::difftest {

int Rng::pick(std::initializer_list<int> weights) {
  int total = 0;
  for (int w : weights) total += w;
  int x = below(total);
  int i = 0;
  for (int w : weights) {
    if (x < w) return i;
    x -= w;
    ++i;
  }
  return i - 1;
}

Interface& Interface::get() {
  static Interface itf;
  return itf;
}

void Interface::release_device_copies() {
  for (detail::ArrayState* st : {af1.state().get(), af4.state().get(), af2d.state().get(),
                                 ai1.state().get(), ai2d.state().get()}) {
    st->release_device_copy();
  }
}

std::string show_word(uint32_t w, bool is_float) {
  char buf[64];
  if (is_float)
    std::snprintf(buf, sizeof buf, "%.9g (0x%08x)", static_cast<double>(std::bit_cast<float>(w)),
                  w);
  else
    std::snprintf(buf, sizeof buf, "%d (0x%08x)", static_cast<int32_t>(w), w);
  return buf;
}

namespace {

// ---- types chosen at run time ----------------------------------------------------------------

template <class T>
constexpr int kind_index() {
  if constexpr (std::is_same_v<T, float>)
    return 0;
  else if constexpr (std::is_same_v<T, int32_t>)
    return 1;
  else
    return 2;
}
template <class T, int N>
constexpr int type_index() {
  return kind_index<T>() * 4 + N - 1;
}
constexpr int kTypes = 12;

// Calls f.operator()<T, N>() for the type with index t.
template <class F>
void with_type(int t, F&& f) {
  switch (t) {
    case 0:
      f.template operator()<float, 1>();
      break;
    case 1:
      f.template operator()<float, 2>();
      break;
    case 2:
      f.template operator()<float, 3>();
      break;
    case 3:
      f.template operator()<float, 4>();
      break;
    case 4:
      f.template operator()<int32_t, 1>();
      break;
    case 5:
      f.template operator()<int32_t, 2>();
      break;
    case 6:
      f.template operator()<int32_t, 3>();
      break;
    case 7:
      f.template operator()<int32_t, 4>();
      break;
    case 8:
      f.template operator()<bool, 1>();
      break;
    case 9:
      f.template operator()<bool, 2>();
      break;
    case 10:
      f.template operator()<bool, 3>();
      break;
    default:
      f.template operator()<bool, 4>();
      break;
  }
}

// Calls f(std::integral_constant<int, w>{}) for a width chosen at run time.
template <class F>
decltype(auto) with_width(int w, F&& f) {
  switch (w) {
    case 1:
      return f(std::integral_constant<int, 1>{});
    case 2:
      return f(std::integral_constant<int, 2>{});
    case 3:
      return f(std::integral_constant<int, 3>{});
    default:
      return f(std::integral_constant<int, 4>{});
  }
}

using Comps = std::array<int, 4>;

// v(c0, ..., c{M-1}) as a fresh value.
template <int M, class T, int N>
Value<T, M> read_swizzle(const Value<T, N>& v, const Comps& c) {
  if constexpr (M == 1) {
    auto s = v(c[0]);
    return Value<T, M>(s.ref(), detail::AdoptTag{});
  } else if constexpr (M == 2) {
    auto s = v(c[0], c[1]);
    return Value<T, M>(s.ref(), detail::AdoptTag{});
  } else if constexpr (M == 3) {
    auto s = v(c[0], c[1], c[2]);
    return Value<T, M>(s.ref(), detail::AdoptTag{});
  } else {
    auto s = v(c[0], c[1], c[2], c[3]);
    return Value<T, M>(s.ref(), detail::AdoptTag{});
  }
}

// s += src, s -= src, s *= src or s /= src (op 1..4).
template <class Sw, class Src>
void compound(Sw& s, const Src& src, int op) {
  switch (op) {
    case 1:
      s += src;
      break;
    case 2:
      s -= src;
      break;
    case 3:
      s *= src;
      break;
    default:
      s /= src;
      break;
  }
}
// s = src, or a compound assignment for op 1..4.
template <class Sw, class Src>
void store(Sw& s, const Src& src, int op) {
  if constexpr (std::is_same_v<typename Sw::scalar_type, bool>) {
    s = src;
  } else {
    if (op == 0)
      s = src;
    else
      compound(s, src, op);
  }
}
template <int M, class T, int N>
void write_masked(const Value<T, N>& v, const Comps& c, const Value<T, M>& src, int op) {
  if constexpr (M == 1) {
    auto s = v(c[0]);
    store(s, src, op);
  } else if constexpr (M == 2) {
    auto s = v(c[0], c[1]);
    store(s, src, op);
  } else if constexpr (M == 3) {
    auto s = v(c[0], c[1], c[2]);
    store(s, src, op);
  } else {
    auto s = v(c[0], c[1], c[2], c[3]);
    store(s, src, op);
  }
}

// ---- constants -------------------------------------------------------------------------------

float pick_float(Rng& r) {
  using L = std::numeric_limits<float>;
  static const float table[] = {
      0.0f,           -0.0f,         1.0f,           -1.0f,       0.5f,          -0.5f,
      2.0f,           -2.0f,         3.0f,           0.25f,       10.0f,         -10.0f,
      100.0f,         1000.0f,       0.1f,           0.001f,      3.14159265f,   6.28318531f,
      1e10f,          -1e10f,        1e20f,          1e-20f,      1e30f,         -1e30f,
      1e38f,          L::max(),      -L::max(),      L::min(),    L::infinity(), -L::infinity(),
      L::quiet_NaN(), 2147483648.0f, -2147483904.0f, 16777216.0f, 8388607.5f,    0.49999997f,
      1.0000001f,     1e-40f,        127.0f,         128.0f,      88.7f,         -103.9f,
      6434.0f,        1e5f};
  int p = r.below(100);
  if (p < 45) return table[r.below(static_cast<int>(std::size(table)))];
  if (p < 75) return static_cast<float>(r.range(-16, 16)) * 0.5f;
  return static_cast<float>(r.below(20001)) / 1000.0f - 10.0f;
}

int32_t pick_int(Rng& r) {
  static const int32_t table[] = {0,
                                  1,
                                  -1,
                                  2,
                                  -2,
                                  3,
                                  4,
                                  5,
                                  7,
                                  8,
                                  15,
                                  16,
                                  31,
                                  32,
                                  33,
                                  -31,
                                  -32,
                                  -33,
                                  63,
                                  255,
                                  256,
                                  65535,
                                  65536,
                                  16777216,
                                  16777217,
                                  0x55555555,
                                  0x7f800000,
                                  0x7fc00000,
                                  0x00800000,
                                  0x3f800000,
                                  std::numeric_limits<int32_t>::max(),
                                  std::numeric_limits<int32_t>::min(),
                                  std::numeric_limits<int32_t>::min() + 1};
  int p = r.below(100);
  if (p < 40) return table[r.below(static_cast<int>(std::size(table)))];
  if (p < 85) return r.range(-10, 10);
  return static_cast<int32_t>(r.bits());
}

template <class T>
T host_scalar(Rng& r) {
  if constexpr (std::is_same_v<T, float>)
    return pick_float(r);
  else if constexpr (std::is_same_v<T, int32_t>)
    return pick_int(r);
  else
    return r.below(2) == 1;
}

// Bit patterns of NaNs become one canonical NaN: NaN payloads are not specified, so a kernel
// that exposes them (as_int) must not let them reach an output.
template <int N>
Value<int32_t, N> canonical_nan_bits(const Value<int32_t, N>& b) {
  Value<bool, N> nan = (b & 0x7fffffff) > 0x7f800000;
  return select(nan, Value<int32_t, N>(0x7fc00000), b);
}

// ---- the generator ---------------------------------------------------------------------------

struct Io {
  Value<float, 4>* f4;
  Value<float, 3>* f3;
  Value<float, 1>* f1;
  Value<int32_t, 4>* i4;
  Value<int32_t, 2>* i2;
  Value<float, 4>* of4;
  Value<float, 3>* of3;
  Value<float, 2>* of2;
  Value<int32_t, 4>* oi4;
  Value<int32_t, 1>* oi1;
};

class Generator {
 public:
  Generator(const ProgramSpec& spec, const Io& io, GenTrace* trace,
            std::array<bool, kStreams>& written)
      : spec_(spec), io_(io), trace_(trace), written_(written), itf_(Interface::get()) {}

  void run() {
    add(io_.f4, true);
    add(io_.f3, true);
    add(io_.f1, true);
    add(io_.i4, true);
    add(io_.i2, true);
    add(io_.of4, true, 0);
    add(io_.of3, true, 1);
    add(io_.of2, true, 2);
    add(io_.oi4, true, 3);
    add(io_.oi1, true, 4);
    add<float, 1>(&itf_.uf, false);
    add<float, 4>(&itf_.uf4, false);
    add<int32_t, 1>(&itf_.ui, false);
    add<int32_t, 3>(&itf_.ui3, false);
    Rng r(derive(spec_.seed, 1));
    int n = r.range(2, 6);
    block(derive(spec_.seed, 2), n, 0);
    int m = r.range(1, 2);  // an output write or two at the end
    for (int i = 0; i < m; ++i) {
      uint64_t id = derive(spec_.seed, 10 + static_cast<uint64_t>(i));
      if (!enter(id)) continue;
      Rng sr(id);
      assign(id, sr, true);
    }
  }

 private:
  struct Slot {
    void* v;
    bool writable;
    int output;  // which output, or -1
  };
  using Marks = std::array<size_t, kTypes>;

  // Variables declared inside a block go out of scope at its end, as in C++.
  class Scope {
   public:
    explicit Scope(Generator& g) : g_(g) {
      for (int t = 0; t < kTypes; ++t)
        m_[static_cast<size_t>(t)] = g.pools_[static_cast<size_t>(t)].size();
    }
    ~Scope() {
      for (int t = 0; t < kTypes; ++t)
        g_.pools_[static_cast<size_t>(t)].resize(m_[static_cast<size_t>(t)]);
    }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    Generator& g_;
    Marks m_;
  };

  template <class T, int N>
  void add(Value<T, N>* v, bool writable, int output = -1) {
    pools_[type_index<T, N>()].push_back(Slot{v, writable, output});
    const detail::Ref& ref = v->ref();
    slot_vars_.insert(ref.var);
  }
  // Whether e is a temporary of its own: moving it into a new variable must not make that
  // variable an alias of a slot (a uniform, which is read-only, or another variable, whose
  // writes it would share). fresh_ alone can be wrong: an operation may return an operand
  // as it is, and the shrinker's leaves are slots.
  template <class T, int N>
  bool own_temporary(const Value<T, N>& e) const {
    return e.ref().kind == detail::Ref::Kind::Var && !slot_vars_.count(e.ref().var);
  }
  template <class T, int N>
  static Value<T, N>& get(const Slot& s) {
    return *static_cast<Value<T, N>*>(s.v);
  }

  // Records a statement id; false if the shrinker dropped it.
  bool enter(uint64_t id) {
    if (spec_.edits.dropped.count(id)) return false;
    if (trace_) trace_->stmts.push_back(id);
    return true;
  }

  static int random_type(Rng& r) { return r.pick({45, 35, 20}) * 4 + r.range(1, 4) - 1; }

  static Comps random_comps(Rng& r, int from) {
    Comps c{};
    for (int& x : c) x = r.below(from);
    return c;
  }
  // m distinct components of n (a write mask).
  static Comps distinct_comps(Rng& r, int n, int m) {
    Comps all = {0, 1, 2, 3};
    for (int i = 0; i < m; ++i)
      std::swap(all[static_cast<size_t>(i)], all[static_cast<size_t>(r.range(i, n - 1))]);
    return all;
  }

  // ---- expressions ---------------------------------------------------------------------------

  template <class T, int N>
  Value<T, N> expr(uint64_t id, int depth) {
    Rng r(id);
    if (depth <= 0 || spec_.edits.leaves.count(id) || r.percent(20)) return leaf<T, N>(r);
    if (trace_) trace_->exprs.push_back(id);  // a node the shrinker may turn into a leaf
    Value<T, N> v = [&] {
      if constexpr (std::is_same_v<T, float>)
        return float_expr<N>(id, r, depth);
      else if constexpr (std::is_same_v<T, int32_t>)
        return int_expr<N>(id, r, depth);
      else
        return bool_expr<N>(id, r, depth);
    }();
    fresh_ = true;
    return v;
  }

  template <class T, int N>
  Value<T, N> leaf(Rng& r) {
    const auto& pool = pools_[type_index<T, N>()];
    int p = r.below(100);
    if (p < 55 && !pool.empty()) {
      // The variable itself (no copy): expression operands only read it.
      fresh_ = false;
      const Slot& s = pool[static_cast<size_t>(r.below(static_cast<int>(pool.size())))];
      return Value<T, N>(get<T, N>(s).ref(), detail::AdoptTag{});
    }
    fresh_ = true;
    if (p < 78) {
      int m = r.range(1, 4);
      const auto& other = pools_[static_cast<size_t>(kind_index<T>() * 4 + m - 1)];
      if (!other.empty()) {
        const Slot& s = other[static_cast<size_t>(r.below(static_cast<int>(other.size())))];
        Comps c = random_comps(r, m);
        return with_width(m, [&](auto mw) -> Value<T, N> {
          return read_swizzle<N>(get<T, decltype(mw)::value>(s), c);
        });
      }
    }
    if constexpr (std::is_same_v<T, int32_t> && N == 1) {
      if (p < 84) return element_index();
    }
    if constexpr (std::is_same_v<T, int32_t> && N == 2) {
      if (p < 84) return element_coord();
    }
    if constexpr (std::is_same_v<T, bool>) {
      if (p < 92) {
        auto a = leaf<float, N>(r);
        auto b = leaf<float, N>(r);
        fresh_ = true;
        return r.percent(50) ? Value<bool, N>(a < b) : Value<bool, N>(a >= b);
      }
    }
    return constant<T, N>(r);
  }

  template <class T, int N>
  Value<T, N> constant(Rng& r) {
    if constexpr (N == 1) {
      return Value<T, 1>(host_scalar<T>(r));
    } else {
      if (r.percent(50)) return Value<T, N>(host_scalar<T>(r));
      glm::vec<N, T, glm::defaultp> h;
      for (int i = 0; i < N; ++i) h[i] = host_scalar<T>(r);
      return Value<T, N>(h);
    }
  }

  // A binary operation f in one of its operand forms: value op value, value op host scalar,
  // host scalar op value, and for vectors the broadcasts vector op scalar, scalar op vector.
  template <class R, class T, int N, class F>
  Value<R, N> forms(uint64_t id, Rng& r, int d, F&& f) {
    int form = r.pick({50, 15, 10, N > 1 ? 15 : 0, N > 1 ? 10 : 0});
    if (form == 1) {
      auto a = expr<T, N>(derive(id, 0), d - 1);
      T c = host_scalar<T>(r);
      return f(a, c);
    }
    if (form == 2) {
      T c = host_scalar<T>(r);
      auto b = expr<T, N>(derive(id, 1), d - 1);
      return f(c, b);
    }
    if constexpr (N > 1) {
      if (form == 3) {
        auto a = expr<T, N>(derive(id, 0), d - 1);
        auto b = expr<T, 1>(derive(id, 1), d - 1);
        return f(a, b);
      }
      if (form == 4) {
        auto a = expr<T, 1>(derive(id, 0), d - 1);
        auto b = expr<T, N>(derive(id, 1), d - 1);
        return f(a, b);
      }
    }
    auto a = expr<T, N>(derive(id, 0), d - 1);
    auto b = expr<T, N>(derive(id, 1), d - 1);
    return f(a, b);
  }

  template <class T, int N>
  Value<T, N> select_expr(uint64_t id, Rng& r, int d) {
    int form = r.pick({70, 15, 15});
    if constexpr (N > 1) {
      if (r.percent(35)) {  // scalar condition choosing whole vectors
        auto c = expr<bool, 1>(derive(id, 0), d - 1);
        auto a = expr<T, N>(derive(id, 1), d - 1);
        auto b = expr<T, N>(derive(id, 2), d - 1);
        return rill::select(c, a, b);
      }
    }
    auto c = expr<bool, N>(derive(id, 0), d - 1);
    if (form == 1) {
      auto a = expr<T, N>(derive(id, 1), d - 1);
      return rill::select(c, a, host_scalar<T>(r));
    }
    if (form == 2) {
      T h = host_scalar<T>(r);
      auto b = expr<T, N>(derive(id, 2), d - 1);
      return rill::select(c, h, b);
    }
    auto a = expr<T, N>(derive(id, 1), d - 1);
    auto b = expr<T, N>(derive(id, 2), d - 1);
    return rill::select(c, a, b);
  }

  template <class T, int N>
  Value<T, N> swizzle_expr(uint64_t id, Rng& r, int d) {
    int m = r.range(1, 4);
    Comps c = random_comps(r, m);
    return with_width(m, [&](auto mw) -> Value<T, N> {
      auto e = expr<T, decltype(mw)::value>(derive(id, 0), d - 1);
      return read_swizzle<N>(e, c);
    });
  }

  // Vector constructors from parts (Float4(xy, z, 1.0f) and so on).
  template <class T, int N>
  Value<T, N> construct(uint64_t id, Rng& r, int d) {
    auto p1 = [&](int k) { return expr<T, 1>(derive(id, static_cast<uint64_t>(k)), d - 1); };
    auto p2 = [&](int k) { return expr<T, 2>(derive(id, static_cast<uint64_t>(k)), d - 1); };
    bool host_last = r.percent(30);
    if constexpr (N == 1) {
      return p1(0);
    } else if constexpr (N == 2) {
      auto a = p1(0);
      if (host_last) return Value<T, 2>(a, host_scalar<T>(r));
      auto b = p1(1);
      return Value<T, 2>(a, b);
    } else if constexpr (N == 3) {
      switch (r.below(3)) {
        case 0: {
          auto a = p1(0);
          auto b = p1(1);
          if (host_last) return Value<T, 3>(a, b, host_scalar<T>(r));
          auto c = p1(2);
          return Value<T, 3>(a, b, c);
        }
        case 1: {
          auto a = p2(0);
          if (host_last) return Value<T, 3>(a, host_scalar<T>(r));
          auto b = p1(1);
          return Value<T, 3>(a, b);
        }
        default: {
          auto a = p1(0);
          auto b = p2(1);
          return Value<T, 3>(a, b);
        }
      }
    } else {
      switch (r.below(6)) {
        case 0: {
          auto a = p1(0);
          auto b = p1(1);
          auto c = p1(2);
          if (host_last) return Value<T, 4>(a, b, c, host_scalar<T>(r));
          auto e = p1(3);
          return Value<T, 4>(a, b, c, e);
        }
        case 1: {
          auto a = p2(0);
          auto b = p2(1);
          return Value<T, 4>(a, b);
        }
        case 2: {
          auto a = expr<T, 3>(derive(id, 0), d - 1);
          if (host_last) return Value<T, 4>(a, host_scalar<T>(r));
          auto b = p1(1);
          return Value<T, 4>(a, b);
        }
        case 3: {
          auto a = p1(0);
          auto b = expr<T, 3>(derive(id, 1), d - 1);
          return Value<T, 4>(a, b);
        }
        case 4: {
          auto a = p2(0);
          auto b = p1(1);
          if (host_last) return Value<T, 4>(a, b, host_scalar<T>(r));
          auto c = p1(2);
          return Value<T, 4>(a, b, c);
        }
        default: {
          auto a = p1(0);
          auto b = p1(1);
          auto c = p2(2);
          return Value<T, 4>(a, b, c);
        }
      }
    }
  }

  // An array index: mostly near the array's range, sometimes far outside (clamped).
  Int index_expr(uint64_t id, int d) {
    Rng r(id);
    switch (r.pick({35, 15, 15, 20, 15})) {
      case 0: {
        Int e = expr<int32_t, 1>(derive(id, 0), d - 1);
        return (e & 7) - 2;
      }
      case 1: {
        Int e = expr<int32_t, 1>(derive(id, 0), d - 1);
        return e % 13;
      }
      case 2:
        return expr<int32_t, 1>(derive(id, 0), d - 1);
      case 3: {
        Float x = expr<float, 1>(derive(id, 0), d - 1);
        return to_int(x);
      }
      default:
        return Int(r.range(-3, 12));
    }
  }

  template <int N>
  Value<float, N> float_expr(uint64_t id, Rng& r, int d) {
    auto sub = [&](int k) { return expr<float, N>(derive(id, static_cast<uint64_t>(k)), d - 1); };
    // Transcendental functions become long routines in strict mode (one per component), so
    // they are rarer, and scalar or Float2 only: they dominate compile times otherwise.
    const int transcendental = N == 1 ? 3 : (N == 2 ? 1 : 0);
    switch (r.pick({20, 8, N == 1 ? 2 : 0, 12, transcendental, 4, 3, 6, 5, 2, 8, 5, 5, 3, 5})) {
      case 0:
        switch (r.below(4)) {
          case 0:
            return forms<float, float, N>(id, r, d,
                                          [](const auto& a, const auto& b) { return a + b; });
          case 1:
            return forms<float, float, N>(id, r, d,
                                          [](const auto& a, const auto& b) { return a - b; });
          case 2:
            return forms<float, float, N>(id, r, d,
                                          [](const auto& a, const auto& b) { return a * b; });
          default:
            return forms<float, float, N>(id, r, d,
                                          [](const auto& a, const auto& b) { return a / b; });
        }
      case 1:
        switch (r.below(3)) {
          case 0:
            return forms<float, float, N>(
                id, r, d, [](const auto& a, const auto& b) { return rill::min(a, b); });
          case 1:
            return forms<float, float, N>(
                id, r, d, [](const auto& a, const auto& b) { return rill::max(a, b); });
          default:
            return forms<float, float, N>(
                id, r, d, [](const auto& a, const auto& b) { return rill::mod(a, b); });
        }
      case 2:
        if (r.percent(50))
          return forms<float, float, N>(
              id, r, d, [](const auto& a, const auto& b) { return rill::pow(a, b); });
        return forms<float, float, N>(
            id, r, d, [](const auto& a, const auto& b) { return rill::atan2(a, b); });
      case 3: {
        auto a = sub(0);
        switch (r.below(8)) {
          case 0:
            return -a;
          case 1:
            return rill::abs(a);
          case 2:
            return rill::sign(a);
          case 3:  // one draw more, at the end: the node's other choices stay as they were
            return r.percent(50) ? rill::floor(a) : rill::trunc(a);
          case 4:
            return rill::ceil(a);
          case 5:
            return rill::fract(a);
          case 6:
            return rill::sqrt(a);
          default:
            return rill::rsqrt(a);
        }
      }
      case 4: {
        auto a = sub(0);
        switch (r.below(8)) {
          case 0:
            return rill::exp(a);
          case 1:
            return rill::log(a);
          case 2:
            return rill::exp2(a);
          case 3:
            return rill::log2(a);
          case 4:
            return rill::sin(a);
          case 5:
            return rill::cos(a);
          case 6:
            return rill::tan(a);
          default:
            return rill::atan(a);
        }
      }
      case 5: {
        auto x = sub(0);
        switch (r.below(3)) {
          case 0: {
            float lo = pick_float(r);
            float hi = pick_float(r);
            return rill::clamp(x, lo, hi);
          }
          case 1: {
            auto lo = expr<float, 1>(derive(id, 1), d - 1);
            auto hi = expr<float, 1>(derive(id, 2), d - 1);
            return rill::clamp(x, lo, hi);
          }
          default: {
            auto lo = sub(1);
            auto hi = sub(2);
            return rill::clamp(x, lo, hi);
          }
        }
      }
      case 6: {
        auto a = sub(0);
        switch (r.below(3)) {
          case 0: {
            auto b = sub(1);
            auto t = sub(2);
            return rill::lerp(a, b, t);
          }
          case 1: {
            auto b = sub(1);
            auto t = expr<float, 1>(derive(id, 2), d - 1);
            return rill::lerp(a, b, t);
          }
          default: {
            float b = pick_float(r);
            float t = pick_float(r);
            return rill::lerp(a, b, t);
          }
        }
      }
      case 7:
        return select_expr<float, N>(id, r, d);
      case 8:
        return to_float(expr<int32_t, N>(derive(id, 0), d - 1));
      case 9: {
        auto bits = expr<int32_t, N>(derive(id, 0), d - 1);
        if (r.percent(30)) return as_float(bits);  // small ints give denormals, others NaN...
        return as_float((bits & 0x807fffff) | 0x40000000);  // +-[2, 4)
      }
      case 10:
        return swizzle_expr<float, N>(id, r, d);
      case 11:
        return construct<float, N>(id, r, d);
      case 12:
        if constexpr (N == 1) {
          int m = r.range(1, 4);
          int which = r.below(3);
          return with_width(m, [&](auto mw) -> Value<float, 1> {
            constexpr int M = decltype(mw)::value;
            auto a = expr<float, M>(derive(id, 0), d - 1);
            if (which == 1) return rill::length(a);
            auto b = expr<float, M>(derive(id, 1), d - 1);
            return which == 0 ? rill::dot(a, b) : rill::distance(a, b);
          });
        } else if constexpr (N == 3) {
          auto a = sub(0);
          auto b = sub(1);
          return rill::cross(a, b);
        } else {
          auto a = sub(0);
          auto b = sub(1);
          return a * b;
        }
      case 13: {
        auto a = sub(0);
        switch (r.below(3)) {
          case 0:
            return rill::normalize(a);
          case 1: {
            auto n = sub(1);
            return rill::reflect(a, n);
          }
          default: {
            auto n = sub(1);
            auto eta = expr<float, 1>(derive(id, 2), d - 1);
            return rill::refract(a, n, eta);
          }
        }
      }
      default: {
        if constexpr (N == 1) {
          Int i = index_expr(derive(id, 0), d);
          return itf_.af1[i];
        } else if constexpr (N == 2) {
          Int x = index_expr(derive(id, 0), d);
          Int y = index_expr(derive(id, 1), d);
          return itf_.af2d(x, y);
        } else if constexpr (N == 3) {
          Int i = index_expr(derive(id, 0), d);
          Float4 g = itf_.af4[i];
          return read_swizzle<3>(g, random_comps(r, 4));
        } else {
          Int i = index_expr(derive(id, 0), d);
          return itf_.af4[i];
        }
      }
    }
  }

  template <int N>
  Value<int32_t, N> int_expr(uint64_t id, Rng& r, int d) {
    using V = Value<int32_t, N>;
    auto sub = [&](int k) { return expr<int32_t, N>(derive(id, static_cast<uint64_t>(k)), d - 1); };
    switch (r.pick({18, 6, 12, 5, 6, 3, 5, 6, 3, 8, 4, 6})) {
      case 0:
        switch (r.below(3)) {
          case 0:
            return forms<int32_t, int32_t, N>(id, r, d,
                                              [](const auto& a, const auto& b) { return a + b; });
          case 1:
            return forms<int32_t, int32_t, N>(id, r, d,
                                              [](const auto& a, const auto& b) { return a - b; });
          default:
            return forms<int32_t, int32_t, N>(id, r, d,
                                              [](const auto& a, const auto& b) { return a * b; });
        }
      case 1:
        if (r.percent(50))
          return forms<int32_t, int32_t, N>(id, r, d,
                                            [](const auto& a, const auto& b) { return a / b; });
        return forms<int32_t, int32_t, N>(id, r, d,
                                          [](const auto& a, const auto& b) { return a % b; });
      case 2:
        switch (r.below(5)) {
          case 0:
            return forms<int32_t, int32_t, N>(id, r, d,
                                              [](const auto& a, const auto& b) { return a & b; });
          case 1:
            return forms<int32_t, int32_t, N>(id, r, d,
                                              [](const auto& a, const auto& b) { return a | b; });
          case 2:
            return forms<int32_t, int32_t, N>(id, r, d,
                                              [](const auto& a, const auto& b) { return a ^ b; });
          case 3:
            return forms<int32_t, int32_t, N>(id, r, d,
                                              [](const auto& a, const auto& b) { return a << b; });
          default:
            return forms<int32_t, int32_t, N>(id, r, d,
                                              [](const auto& a, const auto& b) { return a >> b; });
        }
      case 3:
        if (r.percent(50))
          return forms<int32_t, int32_t, N>(
              id, r, d, [](const auto& a, const auto& b) { return rill::min(a, b); });
        return forms<int32_t, int32_t, N>(
            id, r, d, [](const auto& a, const auto& b) { return rill::max(a, b); });
      case 4: {
        auto a = sub(0);
        switch (r.below(4)) {
          case 0:
            return -a;
          case 1:
            return rill::abs(a);
          case 2:
            return rill::sign(a);
          default:
            return ~a;
        }
      }
      case 5: {
        auto x = sub(0);
        int32_t lo = pick_int(r);
        int32_t hi = pick_int(r);
        return rill::clamp(x, lo, hi);
      }
      case 6:
        return select_expr<int32_t, N>(id, r, d);
      case 7:
        return to_int(expr<float, N>(derive(id, 0), d - 1));
      case 8:
        return canonical_nan_bits(as_int(expr<float, N>(derive(id, 0), d - 1)));
      case 9:
        return swizzle_expr<int32_t, N>(id, r, d);
      case 10:
        return construct<int32_t, N>(id, r, d);
      default: {
        if constexpr (N == 1) {
          if (r.percent(30)) return element_index();
          Int i = index_expr(derive(id, 0), d);
          return itf_.ai1[i];
        } else if constexpr (N == 2) {
          if (r.percent(50)) return element_coord();
          Int i = index_expr(derive(id, 0), d);
          Int j = index_expr(derive(id, 1), d);
          Int3 g = itf_.ai2d(i, j);
          return read_swizzle<2>(g, random_comps(r, 3));
        } else {
          Int i = index_expr(derive(id, 0), d);
          Int j = index_expr(derive(id, 1), d);
          Int3 g = itf_.ai2d(i, j);
          if constexpr (N == 3)
            return g;
          else
            return read_swizzle<4>(g, random_comps(r, 3));
        }
      }
    }
    return V(0);
  }

  template <int N>
  Value<bool, N> bool_expr(uint64_t id, Rng& r, int d) {
    auto compare = [](int op) {
      return [op](const auto& a, const auto& b) {
        switch (op) {
          case 0:
            return a < b;
          case 1:
            return a <= b;
          case 2:
            return a > b;
          case 3:
            return a >= b;
          case 4:
            return a == b;
          default:
            return a != b;
        }
      };
    };
    switch (r.pick({25, 20, 5, 12, 6, 4, 6, 3, N == 1 ? 8 : 0})) {
      case 0:
        return forms<bool, float, N>(id, r, d, compare(r.below(6)));
      case 1:
        return forms<bool, int32_t, N>(id, r, d, compare(r.below(6)));
      case 2:
        if (r.percent(50))
          return forms<bool, bool, N>(id, r, d,
                                      [](const auto& a, const auto& b) { return a == b; });
        return forms<bool, bool, N>(id, r, d, [](const auto& a, const auto& b) { return a != b; });
      case 3:
        if (r.percent(50))
          return forms<bool, bool, N>(id, r, d,
                                      [](const auto& a, const auto& b) { return a && b; });
        return forms<bool, bool, N>(id, r, d, [](const auto& a, const auto& b) { return a || b; });
      case 4:
        return !expr<bool, N>(derive(id, 0), d - 1);
      case 5:
        return select_expr<bool, N>(id, r, d);
      case 6:
        return swizzle_expr<bool, N>(id, r, d);
      case 7:
        return construct<bool, N>(id, r, d);
      default: {
        if constexpr (N == 1) {
          int m = r.range(1, 4);
          bool any_of = r.percent(50);
          return with_width(m, [&](auto mw) -> Bool {
            auto b = expr<bool, decltype(mw)::value>(derive(id, 0), d - 1);
            return any_of ? rill::any(b) : rill::all(b);
          });
        } else {
          return expr<bool, N>(derive(id, 0), d - 1);
        }
      }
    }
  }

  // ---- statements ----------------------------------------------------------------------------

  void block(uint64_t id, int n, int depth) {
    for (int i = 0; i < n; ++i) stmt(derive(id, static_cast<uint64_t>(i)), depth);
  }

  void stmt(uint64_t id, int depth) {
    if (!enter(id)) return;
    Rng r(id);
    switch (r.pick({28, 22, 14, depth < 3 ? 12 : 0, depth < 3 && loop_depth_ < 2 ? 7 : 0,
                    loop_depth_ > 0 ? 6 : 0, 2})) {
      case 0:
        decl(id, r);
        break;
      case 1:
        assign(id, r, false);
        break;
      case 2:
        assign(id, r, true);
        break;
      case 3:
        if_stmt(id, r, depth);
        break;
      case 4:
        loop_stmt(id, r, depth);
        break;
      case 5:
        jump(id, r, depth);
        break;
      default:
        discard(id, r, depth);
        break;
    }
  }

  // The expression of statement `id`: usually its own, sometimes one generated earlier for the
  // same type, generated again (the same operations on mostly the same variables, maybe
  // modified since: common subexpressions, for the optimizer to get right).
  template <class T, int N>
  std::pair<uint64_t, int> expr_root(uint64_t id, Rng& r) {
    auto& recent = recent_[type_index<T, N>()];
    int depth = r.pick({15, 35, 35, 15});
    if (!recent.empty() && r.percent(15))
      return recent[static_cast<size_t>(r.below(static_cast<int>(recent.size())))];
    std::pair<uint64_t, int> root{derive(id, 100), depth};
    if (depth > 0) recent.push_back(root);
    return root;
  }

  // A new local variable: adopting a fresh temporary (Float a = x + y), a copy (Float a = b),
  // or default-initialized (zero) and then assigned.
  void decl(uint64_t id, Rng& r) {
    with_type(random_type(r), [&]<class T, int N>() {
      using V = Value<T, N>;
      auto [eid, depth] = expr_root<T, N>(id, r);
      int how = r.below(100);
      auto e = expr<T, N>(eid, depth);
      std::shared_ptr<V> v;
      if (how < 50 && fresh_ && own_temporary(e)) {
        v = std::make_shared<V>(std::move(e));
      } else if (how < 85) {
        v = std::make_shared<V>(static_cast<const V&>(e));
      } else {
        v = std::make_shared<V>();
        *v = e;
      }
      add<T, N>(v.get(), true);
      owned_.push_back(v);
    });
  }

  void assign(uint64_t id, Rng& r, bool to_output) {
    if (to_output) {
      int o = r.below(kStreams);
      written_[static_cast<size_t>(o)] = true;
      switch (o) {
        case 0:
          write(*io_.of4, id, r);
          break;
        case 1:
          write(*io_.of3, id, r);
          break;
        case 2:
          write(*io_.of2, id, r);
          break;
        case 3:
          write(*io_.oi4, id, r);
          break;
        default:
          write(*io_.oi1, id, r);
          break;
      }
      return;
    }
    int t = random_type(r);
    std::vector<const Slot*> targets;
    for (const Slot& s : pools_[static_cast<size_t>(t)])
      if (s.writable) targets.push_back(&s);
    if (targets.empty()) {
      decl(id, r);
      return;
    }
    Slot s = *targets[static_cast<size_t>(r.below(static_cast<int>(targets.size())))];
    if (s.output >= 0) written_[static_cast<size_t>(s.output)] = true;
    with_type(t, [&]<class T, int N>() { write(get<T, N>(s), id, r); });
  }

  // v = e, v op= e, v(mask) = e or v(mask) op= e.
  template <class T, int N>
  void write(Value<T, N>& v, uint64_t id, Rng& r) {
    constexpr bool numeric = !std::is_same_v<T, bool>;
    int depth = r.pick({15, 35, 35, 15});
    int form = r.pick({40, numeric ? 15 : 0, 35, numeric ? 10 : 0});
    int op = 1 + r.below(4);
    if (form == 0) {
      auto [eid, edepth] = expr_root<T, N>(id, r);
      auto e = expr<T, N>(eid, edepth);
      v = e;
    } else if (form == 1) {
      if constexpr (numeric) {
        if (N > 1 && r.percent(30)) {
          auto e = expr<T, 1>(derive(id, 100), depth);
          compound(v, e, op);
        } else {
          auto e = expr<T, N>(derive(id, 100), depth);
          compound(v, e, op);
        }
      }
    } else {
      int m = r.range(1, N);
      Comps c = distinct_comps(r, N, m);
      with_width(m, [&](auto mw) {
        constexpr int M = decltype(mw)::value;
        if constexpr (M <= N) {
          auto e = expr<T, M>(derive(id, 100), depth);
          write_masked<M>(v, c, e, form == 3 ? op : 0);
        }
      });
    }
  }

  Bool condition(uint64_t id, Rng& r) { return expr<bool, 1>(id, r.range(1, 2)); }

  void if_stmt(uint64_t id, Rng& r, int depth) {
    int shape = r.pick({30, 30, 15, 15, 10});
    std::array<int, 4> n{};
    for (int& k : n) k = r.range(1, 2);
    auto cond = [&](int k) { return condition(derive(id, 200 + static_cast<uint64_t>(k)), r); };
    auto body = [&](int k) {
      Scope s(*this);
      block(derive(id, 300 + static_cast<uint64_t>(k)), n[static_cast<size_t>(k)], depth + 1);
    };
    switch (shape) {
      case 0:
        RILL_IF(cond(0)) {
          body(0);
        }
        RILL_ENDIF;
        break;
      case 1:
        RILL_IF(cond(0)) {
          body(0);
        }
        RILL_ELSE {
          body(1);
        }
        RILL_ENDIF;
        break;
      case 2:
        RILL_IF(cond(0)) {
          body(0);
        }
        RILL_ELSE_IF(cond(1)) {
          body(1);
        }
        RILL_ENDIF;
        break;
      case 3:
        RILL_IF(cond(0)) {
          body(0);
        }
        RILL_ELSE_IF(cond(1)) {
          body(1);
        }
        RILL_ELSE {
          body(2);
        }
        RILL_ENDIF;
        break;
      default:
        RILL_IF(cond(0)) {
          body(0);
        }
        RILL_ELSE_IF(cond(1)) {
          body(1);
        }
        RILL_ELSE_IF(cond(2)) {
          body(2);
        }
        RILL_ELSE {
          body(3);
        }
        RILL_ENDIF;
        break;
    }
  }

  // An iteration bound in [-5, 6]: loops always terminate, after a data-dependent count.
  Int loop_bound(uint64_t id) {
    Rng r(id);
    switch (r.pick({35, 30, 20, 15})) {
      case 0:
        return Int(r.range(0, 5));
      case 1: {
        Int e = expr<int32_t, 1>(derive(id, 0), r.range(0, 2));
        return (e & 7) - 1;
      }
      case 2: {
        Int e = expr<int32_t, 1>(derive(id, 0), r.range(0, 2));
        return e % 6;
      }
      default: {
        Float x = expr<float, 1>(derive(id, 0), r.range(0, 2));
        return rill::clamp(to_int(x), -1, 6);
      }
    }
  }

  // The loop test `base`, sometimes combined with a random condition (evaluated, like the
  // whole test, in the loop's condition block).
  Bool loop_test(const Bool& base, bool extra, bool conj, uint64_t id, Rng& r) {
    if (!extra) return base;
    Bool c = condition(id, r);
    return conj ? Bool(base && c) : Bool(base || c);
  }

  void loop_stmt(uint64_t id, Rng& r, int depth) {
    int kind = r.pick({30, 25, 30, 15});
    int n = r.range(1, 3);
    bool extra = r.percent(40);
    uint64_t body_id = derive(id, 300);
    uint64_t cond_id = derive(id, 200);
    ++loop_depth_;
    switch (kind) {
      case 0: {  // while, counter incremented first thing in the body
        Int c = 0;
        Int bound = loop_bound(derive(id, 150));
        Scope s(*this);
        add<int32_t, 1>(&c, false);
        RILL_WHILE(loop_test(c < bound, extra, true, cond_id, r)) {
          c += 1;
          Scope inner(*this);
          block(body_id, n, depth + 1);
        }
        RILL_ENDWHILE;
        break;
      }
      case 1: {  // do-until
        Int c = 0;
        Int bound = loop_bound(derive(id, 150));
        Scope s(*this);
        add<int32_t, 1>(&c, false);
        RILL_DO {
          c += 1;
          Scope inner(*this);
          block(body_id, n, depth + 1);
        }
        RILL_UNTIL(loop_test(c >= bound, extra, false, cond_id, r));
        break;
      }
      case 2: {  // for over an Int, up or down
        int start = r.range(-2, 2);
        int step = r.range(1, 2);
        bool down = r.percent(30);
        Int bound = loop_bound(derive(id, 150));
        if (!down) {
          RILL_FOR(Int i = start, loop_test(i < bound, extra, true, cond_id, r), i += step) {
            Scope inner(*this);
            add<int32_t, 1>(&i, false);
            block(body_id, n, depth + 1);
          }
          RILL_ENDFOR;
        } else {
          RILL_FOR(Int i = bound, loop_test(i > start, extra, true, cond_id, r), i -= step) {
            Scope inner(*this);
            add<int32_t, 1>(&i, false);
            block(body_id, n, depth + 1);
          }
          RILL_ENDFOR;
        }
        break;
      }
      default: {  // for over a Float: -1, -0.5, ... while below a bound in [-2, 2]
        Float hi = rill::clamp(expr<float, 1>(derive(id, 150), r.range(0, 2)), -2.0f, 2.0f);
        RILL_FOR(Float x = -1.0f, loop_test(x < hi, extra, true, cond_id, r), x += 0.5f) {
          Scope inner(*this);
          add<float, 1>(&x, false);
          block(body_id, n, depth + 1);
        }
        RILL_ENDFOR;
        break;
      }
    }
    --loop_depth_;
  }

  void jump(uint64_t id, Rng& r, int depth) {
    bool brk = r.percent(50);
    if (depth > 0 && r.percent(20)) {  // unconditional: the rest of the block is dead
      if (brk)
        RILL_BREAK;
      else
        RILL_CONTINUE;
      return;
    }
    Bool c = condition(derive(id, 100), r);
    RILL_IF(c) {
      if (brk)
        RILL_BREAK;
      else
        RILL_CONTINUE;
    }
    RILL_ENDIF;
  }

  void discard(uint64_t id, Rng& r, int depth) {
    if (depth > 0 && r.percent(20)) {
      RILL_DISCARD;
      return;
    }
    Bool c = condition(derive(id, 100), r);
    RILL_IF(c) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
  }

  const ProgramSpec& spec_;
  const Io& io_;
  GenTrace* trace_;
  std::array<bool, kStreams>& written_;
  Interface& itf_;
  std::array<std::vector<Slot>, kTypes> pools_;
  std::array<std::vector<std::pair<uint64_t, int>>, kTypes> recent_;  // expression roots
  std::vector<std::shared_ptr<void>> owned_;
  int loop_depth_ = 0;
  bool fresh_ = false;  // whether the last expression is a fresh temporary (not a variable)
  std::set<ir::VarId> slot_vars_;  // the variables that slots are
};

}  // namespace

Program build_program(const std::vector<ProgramSpec>& subs, std::vector<GenTrace>* traces) {
  Interface& itf = Interface::get();
  if (traces) traces->assign(subs.size(), GenTrace{});
  return rill::program("differential", [&] {
    Input<Float4> f4("f4");
    Input<Float3> f3("f3");
    Input<Float> f1("f1");
    Input<Int4> i4("i4");
    Input<Int2> i2("i2");
    Output<Float4> of4("of4");
    Output<Float3> of3("of3");
    Output<Float2> of2("of2");
    Output<Int4> oi4("oi4");
    Output<Int> oi1("oi1");
    Io io{&f4, &f3, &f1, &i4, &i2, &of4, &of3, &of2, &oi4, &oi1};
    std::array<bool, kStreams> written{};
    auto generate = [&](size_t k) {
      Generator g(subs[k], io, traces ? &(*traces)[k] : nullptr, written);
      g.run();
    };
    if (subs.size() == 1) {
      generate(0);
    } else {
      // RILL_IF (which == 0) ... RILL_ELSE_IF (which == k) ... RILL_ENDIF, for a count known
      // only at run time: the calls the macros expand to.
      for (size_t k = 0; k < subs.size(); ++k) {
        if (k > 0) detail::begin_else_if(RILL_HERE);
        Bool is_k = itf.which == static_cast<int32_t>(k);
        detail::begin_if(is_k.operand(), RILL_HERE);
        generate(k);
      }
      detail::end_if(RILL_HERE);
    }
    // Every output must be written somewhere; those no program writes get a write that
    // never runs (which is never negative).
    if (!written[0] || !written[1] || !written[2] || !written[3] || !written[4]) {
      RILL_IF(itf.which < 0) {
        if (!written[0]) of4 = Float4(0.0f);
        if (!written[1]) of3 = Float3(0.0f);
        if (!written[2]) of2 = Float2(0.0f);
        if (!written[3]) oi4 = Int4(0);
        if (!written[4]) oi1 = 0;
      }
      RILL_ENDIF;
    }
  });
}

// ---- launch data -------------------------------------------------------------------------------

namespace {

uint32_t flush_denormal(uint32_t w) {
  return (w & 0x7f800000u) == 0 ? (w & 0x80000000u) : w;
}

uint32_t float_word(Rng& r, int profile, bool denormals) {
  using L = std::numeric_limits<float>;
  static const float hard[] = {
      0.0f,           -0.0f,          1.0f,          -1.0f,          0.5f,        -0.5f,
      2.0f,           L::max(),       -L::max(),     L::min(),       -L::min(),   L::infinity(),
      -L::infinity(), L::quiet_NaN(), 2147483648.0f, -2147483904.0f, 16777216.0f, 8388607.5f,
      0.49999997f,    1.0000001f,     1e30f,         -1e-30f,        88.7f,       -103.9f,
      3.14159265f,    1e10f};
  float f = 0.0f;
  uint32_t w = 0;
  bool raw = false;
  int p = r.below(100);
  // profile 0: tame values; 1: mixed; 2: wild bit patterns.
  const int halves = profile == 0 ? 50 : (profile == 1 ? 30 : 20);
  const int uniform = profile == 0 ? 40 : (profile == 1 ? 25 : 10);
  const int wide = profile == 0 ? 0 : (profile == 1 ? 20 : 30);
  const int hard_share = profile == 0 ? 10 : 15;
  const int denorm = denormals && profile > 0 ? 3 : 0;
  if (p < halves) {
    f = static_cast<float>(r.range(-16, 16)) * 0.5f;
  } else if ((p -= halves) < uniform) {
    f = static_cast<float>(static_cast<int>(r.bits() % 2000001u) - 1000000) *
        (profile == 0 ? 4e-6f : 1e-5f);
  } else if ((p -= uniform) < wide) {
    int e = profile == 1 ? r.range(-60, 60) : r.range(-126, 127);
    f = std::ldexp(1.0f + static_cast<float>(r.bits() >> 9) * 0x1p-23f, e) *
        (r.percent(50) ? 1.0f : -1.0f);
  } else if ((p -= wide) < hard_share) {
    f = hard[r.below(static_cast<int>(std::size(hard)))];
  } else if ((p -= hard_share) < denorm) {
    w = (r.bits() & 0x807fffffu) | 1u;
    raw = true;
  } else {
    w = r.bits();
    raw = true;
  }
  if (!raw) w = std::bit_cast<uint32_t>(f);
  return denormals ? w : flush_denormal(w);
}

uint32_t int_word(Rng& r, int profile) {
  static const int32_t hard[] = {0,
                                 1,
                                 -1,
                                 2,
                                 -2,
                                 31,
                                 32,
                                 33,
                                 -7,
                                 255,
                                 256,
                                 0x55555555,
                                 std::numeric_limits<int32_t>::max(),
                                 std::numeric_limits<int32_t>::min(),
                                 std::numeric_limits<int32_t>::min() + 1};
  int p = r.below(100);
  if (profile == 0) return static_cast<uint32_t>(p < 70 ? r.range(-10, 10) : r.range(-100, 100));
  if (p < 40) return static_cast<uint32_t>(r.range(-10, 10));
  if (p < 60) return static_cast<uint32_t>(r.range(-1000, 1000));
  if (p < 80) return static_cast<uint32_t>(hard[r.below(static_cast<int>(std::size(hard)))]);
  return r.bits();
}

std::vector<uint32_t> words(Rng& r, size_t n, bool is_float, int profile, bool denormals) {
  std::vector<uint32_t> v(n);
  for (uint32_t& w : v) w = is_float ? float_word(r, profile, denormals) : int_word(r, profile);
  return v;
}

template <class H>
std::vector<H> as_host(const std::vector<uint32_t>& w) {
  std::vector<H> v(w.size() * 4 / sizeof(H));
  if (!v.empty()) std::memcpy(v.data(), w.data(), v.size() * sizeof(H));
  return v;
}

}  // namespace

LaunchData make_launch_data(uint64_t seed, bool denormals) {
  Rng r(derive(seed, 0xda7a));
  LaunchData d;
  int profile = r.pick({30, 50, 20});
  // Sizes are never powers of two (nor 1): llvmpipe compiles a new variant of a shader for
  // every pattern of power-of-two texture sizes it meets, which costs as much as the compile.
  // Mostly one OpenCL work-group (64) or less; sometimes several, and several TBB ranges.
  static const int64_t counts[] = {5, 7, 13, 23, 37, 47, 61};
  static const int64_t shapes[][2] = {{5, 3}, {7, 3}, {6, 5}, {9, 7}, {19, 7}};
  int shape_kind = r.pick({70, 24, 6});
  if (shape_kind == 1) {
    const auto& s = shapes[r.below(5)];
    d.width = s[0];
    d.height = s[1];
  } else {
    d.width = shape_kind == 0 ? counts[r.below(7)] : (r.percent(65) ? 131 : 1031);
    d.height = 1;
  }
  d.count = d.width * d.height;
  size_t n = static_cast<size_t>(d.count);
  for (int k = 0; k < kStreams; ++k) {
    d.in[static_cast<size_t>(k)] =
        words(r, n * static_cast<size_t>(kInWidth[static_cast<size_t>(k)]),
              kInFloat[static_cast<size_t>(k)], profile, denormals);
    d.out[static_cast<size_t>(k)] =
        words(r, n * static_cast<size_t>(kOutWidth[static_cast<size_t>(k)]),
              kOutFloat[static_cast<size_t>(k)], profile, denormals);
  }
  d.alias = r.percent(15);
  if (d.alias) {
    d.in[0] = d.out[0];
    d.in[3] = d.out[3];
  }
  d.uf = std::bit_cast<float>(float_word(r, profile, denormals));
  for (int c = 0; c < 4; ++c) d.uf4[c] = std::bit_cast<float>(float_word(r, profile, denormals));
  d.ui = static_cast<int32_t>(int_word(r, profile));
  for (int c = 0; c < 3; ++c) d.ui3[c] = static_cast<int32_t>(int_word(r, profile));
  static const int64_t sizes[] = {3, 5, 6, 7, 9, 11};
  for (int a = 0; a < kArrays; ++a) {
    auto& shape = d.shape[static_cast<size_t>(a)];
    bool two_d = kArrDims[static_cast<size_t>(a)] == 2;
    shape[0] = two_d ? sizes[r.below(3)] : sizes[r.below(6)];
    shape[1] = two_d ? sizes[r.below(2)] : 1;
    d.arr[static_cast<size_t>(a)] =
        words(r, static_cast<size_t>(shape[0] * shape[1] * kArrWidth[static_cast<size_t>(a)]),
              kArrFloat[static_cast<size_t>(a)], profile, denormals);
  }
  return d;
}

void apply_launch_data(const LaunchData& d, int which) {
  Interface& itf = Interface::get();
  itf.which.set(which);
  itf.uf.set(d.uf);
  itf.uf4.set(d.uf4);
  itf.ui.set(d.ui);
  itf.ui3.set(d.ui3);
  auto load = [&](auto& array, int a, auto host_tag) {
    using H = decltype(host_tag);
    const auto& shape = d.shape[static_cast<size_t>(a)];
    if (kArrDims[static_cast<size_t>(a)] == 1)
      array.resize(shape[0]);
    else
      array.resize(shape[0], shape[1]);
    array.upload(as_host<H>(d.arr[static_cast<size_t>(a)]));
  };
  load(itf.af1, 0, float{});
  load(itf.af4, 1, glm::vec4{});
  load(itf.af2d, 2, glm::vec2{});
  load(itf.ai1, 3, int32_t{});
  load(itf.ai2d, 4, glm::ivec3{});
}

}  // namespace rill::difftest
