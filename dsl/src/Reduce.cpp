// Reductions (Reduce.h): a fixed tree of Rill kernels, each folding blocks of kReduceBlock
// elements that it gathers from the level before. Being ordinary kernels, they run on every
// backend and give the same bits wherever the kernels do.
#include "rill/Reduce.h"

#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <mutex>

#include "rill/ControlFlow.h"
#include "rill/Kernel.h"
#include "rill/Math.h"
#include "rill/Operators.h"
#include "rill/Parameters.h"

namespace rill::detail {

namespace {

const char* op_name(ReduceOp op) {
  switch (op) {
    case ReduceOp::Sum:
      return "sum";
    case ReduceOp::Min:
      return "minimum";
    case ReduceOp::Max:
      return "maximum";
    case ReduceOp::Count:
      return "count";
    case ReduceOp::Any:
      return "any";
    case ReduceOp::All:
      return "all";
  }
  return "?";
}

// count, any and all first turn each element into 0 or 1, then sum, max or min those.
bool reads_truth(ReduceOp op) {
  return op == ReduceOp::Count || op == ReduceOp::Any || op == ReduceOp::All;
}

template <class V>
V combine(ReduceOp op, const V& a, const V& b) {
  switch (op) {
    case ReduceOp::Sum:
    case ReduceOp::Count:
      return a + b;
    case ReduceOp::Min:
    case ReduceOp::All:
      return min(a, b);
    case ReduceOp::Max:
    case ReduceOp::Any:
      return max(a, b);
  }
  return a;
}

template <class V>
std::array<uint32_t, 4> identity(ReduceOp op) {
  using T = typename V::scalar_type;
  T v{};
  if (op == ReduceOp::Min)
    v = std::numeric_limits<T>::has_infinity ? std::numeric_limits<T>::infinity()
                                             : std::numeric_limits<T>::max();
  if (op == ReduceOp::Max)
    v = std::numeric_limits<T>::has_infinity ? -std::numeric_limits<T>::infinity()
                                             : std::numeric_limits<T>::min();
  if (op == ReduceOp::All) v = T(1);
  std::array<uint32_t, 4> out{};
  for (int c = 0; c < V::width; ++c) out[static_cast<size_t>(c)] = scalar_bits<T>(v);
  return out;
}

// One level: element j folds block j of `src` (len elements, or rows of len elements split
// into row_blocks blocks each for a 2D source).
template <class V>
Program level_program(ReduceOp op, const Stream<V>& src, bool two_d, bool map_truth,
                      const Uniform<Int>& len, const Uniform<Int>& row_blocks) {
  std::string name = std::string("rill_") + op_name(op) + "_" + V::type().str() +
                     (two_d ? "_rows" : "") + (map_truth ? "_first" : "");
  return program(name, [&] {
    Output<V> out("partial");
    Int j = element_index();
    Int bx = j, y = 0;
    if (two_d) {
      bx = j % row_blocks;
      y = j / row_blocks;
    }
    Int first = bx * kReduceBlock;
    auto at = [&](const Int& k) {
      V x = two_d ? src(k, y) : src[k];
      if constexpr (std::is_same_v<V, Int>)
        if (map_truth) x = select(x != 0, Int(1), Int(0));
      return x;
    };
    // A loop, not unrolled code: the fold is one dependency chain either way, and a short
    // kernel compiles quickly on every backend. The last block of a row may be short.
    Int here = min(len - first, Int(kReduceBlock));
    V acc = at(first);
    RILL_FOR(Int k = 1, k < here, k += 1) { acc = combine(op, acc, at(first + k)); }
    RILL_ENDFOR;
    out = acc;
  });
}

int64_t blocks(int64_t n) {
  return (n + kReduceBlock - 1) / kReduceBlock;
}

// The launches that reduce one stream with one op on one backend: the level kernels (bound
// to their partial streams) and the uniforms they read. A stream's shape never changes, so
// the chain built for it is reused by every later reduction of it: no capture, no hashing and
// no allocation per call.
struct Chain {
  std::mutex mutex;  // the partial streams are shared: one reduction of the chain at a time
  std::vector<std::unique_ptr<Uniform<Int>>> uniforms;
  std::vector<Kernel> levels;
  StreamRef last{nullptr};  // the one-element result
};

struct ChainKey {
  const StreamState* source;
  ReduceOp op;
  std::string backend;
  auto operator<=>(const ChainKey&) const = default;
};

struct ChainCache {
  std::mutex mutex;
  std::map<ChainKey, std::shared_ptr<Chain>> chains;
};

// The first level's program holds the source stream (as the array it gathers from). When
// that is the only reference left, the user has dropped the stream: its chain goes too.
bool source_dropped(const Chain& c) {
  return c.levels.front().program().captured().arrays.front().use_count() == 1;
}
ChainCache& chain_cache() {
  static ChainCache c;
  return c;
}

template <class V>
std::shared_ptr<Chain> build_chain(const StreamRef& s, ReduceOp op, const std::string& backend) {
  StreamState& st = s.state();
  CompileOptions options;
  options.accuracy = Accuracy::Strict;
  auto chain = std::make_shared<Chain>();
  Stream<V> src(s);
  // A 2D stream is gathered as s(x, y) even when it is one row high (a one-row tile).
  bool two_d = st.dims == 2;
  bool first_level = true;
  int64_t len = two_d ? st.width : st.count();
  int64_t count = two_d ? blocks(st.width) * st.height : blocks(len);
  for (;;) {
    auto& u_len = *chain->uniforms.emplace_back(
        std::make_unique<Uniform<Int>>(static_cast<int32_t>(len), "rill_len"));
    auto& u_row_blocks = *chain->uniforms.emplace_back(
        std::make_unique<Uniform<Int>>(static_cast<int32_t>(blocks(len)), "rill_row_blocks"));
    Program p = level_program(op, src, two_d, first_level && reads_truth(op), u_len, u_row_blocks);
    Stream<V> partial(count, "rill_partial");
    chain->levels.push_back(compile(p, backend, options));
    chain->levels.back().bind("partial", partial);
    if (count == 1) {
      chain->last = partial;
      return chain;
    }
    src = partial;
    two_d = false;
    first_level = false;
    len = count;
    count = blocks(len);
  }
}

template <class V>
std::array<uint32_t, 4> reduce_typed(const StreamRef& s, ReduceOp op, const std::string& backend) {
  StreamState& st = s.state();
  if (st.count() == 0) return identity<V>(op);
  if (st.width > std::numeric_limits<int32_t>::max() ||
      st.count() > std::numeric_limits<int32_t>::max())
    throw Error(std::string(op_name(op)) + " of stream '" + st.name +
                "': " + std::to_string(st.count()) + " elements; reductions take under 2^31");
  ChainCache& cache = chain_cache();
  const ChainKey key{&st, op, backend};
  std::shared_ptr<Chain> chain;
  {
    std::lock_guard<std::mutex> lock(cache.mutex);
    std::erase_if(cache.chains, [](const auto& e) { return source_dropped(*e.second); });
    auto it = cache.chains.find(key);
    if (it != cache.chains.end()) chain = it->second;  // alive, so the address is this stream's
  }
  if (!chain) {
    chain = build_chain<V>(s, op, backend);
    std::lock_guard<std::mutex> lock(cache.mutex);
    cache.chains[key] = chain;
  }
  std::lock_guard<std::mutex> lock(chain->mutex);
  for (Kernel& k : chain->levels) k.execute();
  std::array<uint32_t, 4> out{};
  const uint32_t* w = chain->last.state().host_data_for_read();
  for (int c = 0; c < V::width; ++c) out[static_cast<size_t>(c)] = w[c];
  return out;
}

}  // namespace

std::array<uint32_t, 4> reduce(const StreamRef& s, ReduceOp op, const std::string& backend_name) {
  StreamState& st = s.state();
  // The backend registry exists before the chain cache (statics die in reverse order), so
  // cached kernels and streams never outlive the backends they belong to.
  (void)backend(backend_name.empty() ? std::string("cpu") : backend_name);
  std::string where = backend_name;
  if (where.empty()) {
    // Where the newest copy is: reducing there moves only the result.
    Backend* owner = st.device_owner();
    where = owner && st.is_device_current(owner) ? owner->name() : "cpu";
  }
  const ir::Type t = st.type();
  if (reads_truth(op) && t != ir::int_type(1))
    throw Error(std::string(op_name(op)) + " of stream '" + st.name + "': needs a Stream<Int> " +
                "of truth values (0 is false), not a stream of " + t.str());
  if (t.kind == ir::ScalarKind::Float) {
    switch (t.width) {
      case 1:
        return reduce_typed<Float>(s, op, where);
      case 2:
        return reduce_typed<Float2>(s, op, where);
      case 3:
        return reduce_typed<Float3>(s, op, where);
      default:
        return reduce_typed<Float4>(s, op, where);
    }
  }
  switch (t.width) {
    case 1:
      return reduce_typed<Int>(s, op, where);
    case 2:
      return reduce_typed<Int2>(s, op, where);
    case 3:
      return reduce_typed<Int3>(s, op, where);
    default:
      return reduce_typed<Int4>(s, op, where);
  }
}

}  // namespace rill::detail
