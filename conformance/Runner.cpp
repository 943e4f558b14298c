// Runs cases on a backend and compares the results (see Conformance.h for the rules).
#include <rill/Reference.h>
#include <rill/ir/Interpreter.h>
#include <rill/passes/Passes.h>

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cstring>
#include <map>
#include <memory>

#include "Suite.h"

namespace rill::conformance {

namespace {

// ---- type-erased streams ----------------------------------------------------------------------

class AnyStream {
 public:
  virtual ~AnyStream() = default;
  virtual StreamRef ref() const = 0;
  virtual void upload(const Words& w) = 0;
  virtual Words download() const = 0;
};

template <class V>
class TypedStream : public AnyStream {
 public:
  TypedStream(int64_t w, int64_t h) : s_(w, h) {}
  StreamRef ref() const override { return s_; }
  void upload(const Words& w) override {
    std::vector<typename V::host_type> h(static_cast<size_t>(s_.size()));
    std::memcpy(h.data(), w.data(), w.size() * 4);
    s_.upload(h);
  }
  Words download() const override {
    auto h = s_.download();
    Words w(h.size() * V::width);
    std::memcpy(w.data(), h.data(), w.size() * 4);
    return w;
  }

 private:
  Stream<V> s_;
};

template <class T>
std::unique_ptr<AnyStream> make_typed(int width, int64_t w, int64_t h) {
  switch (width) {
    case 1:
      return std::make_unique<TypedStream<Value<T, 1>>>(w, h);
    case 2:
      return std::make_unique<TypedStream<Value<T, 2>>>(w, h);
    case 3:
      return std::make_unique<TypedStream<Value<T, 3>>>(w, h);
    default:
      return std::make_unique<TypedStream<Value<T, 4>>>(w, h);
  }
}

std::unique_ptr<AnyStream> make_stream(ir::Type t, int64_t w, int64_t h) {
  if (t.is_float()) return make_typed<float>(t.width, w, h);
  if (t.is_int()) return make_typed<int32_t>(t.width, w, h);
  throw Error("conformance: a stream of " + t.str() + " (streams hold Float or Int)");
}

// ---- running one program on a backend and on the interpreter ------------------------------

struct Launched {
  std::vector<Words> outputs;  // per launch, concatenated: outputs[launch * nout + o]
  std::vector<int64_t> written;
};

struct Shape {
  int64_t n = 0, width = 0, height = 1;
};

Launched run_backend(const Program& p, const std::string& backend, Accuracy a, const Shape& shape,
                     const std::vector<Words>& inputs, const std::vector<Words>& prefill,
                     const Case& c) {
  const ir::Function& f = p.ir();
  CompileOptions o;
  o.accuracy = a;
  Kernel k = compile(p, backend, o);
  std::vector<std::unique_ptr<AnyStream>> ins, outs;
  for (size_t i = 0; i < f.inputs.size(); ++i) {
    ins.push_back(make_stream(f.var(f.inputs[i]).type, shape.width, shape.height));
    ins.back()->upload(inputs[i]);
    k.bind(f.var(f.inputs[i]).name, ins.back()->ref());
  }
  for (size_t i = 0; i < f.outputs.size(); ++i) {
    outs.push_back(make_stream(f.var(f.outputs[i]).type, shape.width, shape.height));
    outs.back()->upload(prefill[i]);
    k.bind(f.var(f.outputs[i]).name, outs.back()->ref());
  }
  Launched r;
  for (int l = 0; l < c.launches; ++l) {
    if (c.set_launch) c.set_launch(l);
    r.written.push_back(k.execute());
    for (auto& s : outs) r.outputs.push_back(s->download());
  }
  return r;
}

// The reference: the program optimized as in strict mode, run by the interpreter; with
// `flushing`, under the flush-to-zero model of the denormal rule.
Launched run_interpreter(const Program& p, const Shape& shape, const std::vector<Words>& inputs,
                         const std::vector<Words>& prefill, const Case& c, bool flushing) {
  ir::Function f = passes::optimize(p.ir(), PassOptions{}, Accuracy::Strict);
  if (flushing) f = flush_model(f);
  std::vector<Words> outs = prefill;
  ir::InterpreterLaunch L = reference_launch(p);
  for (const Words& w : inputs) L.inputs.push_back(w.data());
  for (Words& w : outs) L.outputs.push_back(w.data());
  L.count = shape.n;
  L.width = shape.width;
  Launched r;
  for (int l = 0; l < c.launches; ++l) {
    if (c.set_launch) c.set_launch(l);
    L.uniforms = reference_launch(p).uniforms;  // as this launch set them
    r.written.push_back(ir::interpret(f, L));
    for (const Words& w : outs) r.outputs.push_back(w);
  }
  return r;
}

// Whether a program's elements depend on where they are (element_index / element_coord) or
// may discard: then the reference must run over the whole stream.
bool needs_whole_stream(const ir::Block& b) {
  for (const ir::Stmt& s : b) {
    if (s.kind == ir::StmtKind::Discard) return true;
    if (s.kind == ir::StmtKind::Assign &&
        (s.op == ir::Op::ElementIndex || s.op == ir::Op::ElementCoord))
      return true;
    if (needs_whole_stream(s.then_body) || needs_whole_stream(s.else_body) ||
        needs_whole_stream(s.cond_body) || needs_whole_stream(s.body) || needs_whole_stream(s.step))
      return true;
  }
  return false;
}

bool same(uint32_t got, uint32_t want, bool is_float, bool flush);

// The flush-to-zero model's reference, computed only for the elements where the backend
// differs from the plain reference (the others take the plain reference's values): the
// model's rewritten program is several times longer.
Launched model_reference(const Program& p, const Shape& shape, const std::vector<Words>& inputs,
                         const std::vector<Words>& prefill, const Case& c, const Launched& got,
                         const Launched& ref) {
  const ir::Function& f = p.ir();
  if (needs_whole_stream(f.body)) return run_interpreter(p, shape, inputs, prefill, c, true);
  const size_t nout = f.outputs.size();
  std::vector<int64_t> diff;
  for (int64_t e = 0; e < shape.n; ++e) {
    bool differs = false;
    for (size_t k = 0; k < got.outputs.size() && !differs; ++k) {
      const ir::Type t = f.var(f.outputs[k % nout]).type;
      for (int comp = 0; comp < t.width && !differs; ++comp) {
        size_t w = static_cast<size_t>(e * t.width + comp);
        differs = !same(got.outputs[k][w], ref.outputs[k][w], t.is_float(), true);
      }
    }
    if (differs) diff.push_back(e);
  }
  Launched model = ref;
  if (diff.empty()) return model;
  const int64_t m = static_cast<int64_t>(diff.size());
  auto compact = [&](const std::vector<Words>& all, const std::vector<ir::VarId>& vars) {
    std::vector<Words> out(all.size());
    for (size_t j = 0; j < all.size(); ++j) {
      const int w = f.var(vars[j]).type.width;
      for (int64_t e : diff)
        for (int comp = 0; comp < w; ++comp)
          out[j].push_back(all[j][static_cast<size_t>(e * w + comp)]);
    }
    return out;
  };
  Shape sub{m, m, 1};
  Launched part =
      run_interpreter(p, sub, compact(inputs, f.inputs), compact(prefill, f.outputs), c, true);
  for (size_t k = 0; k < model.outputs.size(); ++k) {
    const int w = f.var(f.outputs[k % nout]).type.width;
    for (int64_t i = 0; i < m; ++i)
      for (int comp = 0; comp < w; ++comp)
        model.outputs[k][static_cast<size_t>(diff[static_cast<size_t>(i)] * w + comp)] =
            part.outputs[k][static_cast<size_t>(i * w + comp)];
  }
  return model;
}

// ---- comparing ----------------------------------------------------------------------------------

// The denormal rule (docs/conformance.md): on a backend that flushes, denormals compare as
// zeros of their sign, and so may a result of +-FLT_MIN (whose exact value can lie below
// FLT_MIN: hardware that flushes detects tininess before rounding).
bool same(uint32_t got, uint32_t want, bool is_float, bool flush) {
  if (!is_float) return got == want;
  if (flush) {
    got = flush_bits(got);
    want = flush_bits(want);
    if ((want & 0x7fffffffu) == 0x00800000u && got == (want & 0x80000000u)) return true;
  }
  return got == want || (is_nan_bits(got) && is_nan_bits(want));
}

// Error of a float result against a double reference, with the denormal rule for backends
// that flush: a denormal result may be a zero, and a reference below FLT_MIN may be zero.
double measured_error(float got, double ref, double scale, bool flush) {
  double e = ulp_error(static_cast<double>(got), ref, scale);
  if (flush) {
    double g = static_cast<double>(float_of(flush_bits(bits_of(got))));
    double r = std::fabs(ref) < static_cast<double>(FLT_MIN) ? 0.0 : ref;
    e = std::min(e, ulp_error(g, r, scale));
  }
  return e;
}

// One table row while it is being filled.
struct Tally {
  std::string op, category;
  int64_t elements = 0, mismatches = 0, nan_bits = 0;
  double max_ulp = -1;
  double bound = -1;
  bool any_float = false;
  std::vector<std::string> examples;
  size_t max_examples = 2;
  std::string worst;  // the input with the largest error
  std::string error, skip;

  void error_at(double err, const std::function<std::string()>& describe) {
    if (err > max_ulp) {
      max_ulp = err;
      worst = describe();
    }
  }

  void example(const std::string& s) {
    if (examples.size() < max_examples) examples.push_back(s);
  }
};

class Rows {
 public:
  Tally& at(const std::string& op, const std::string& category) {
    auto it = index_.find(op);
    if (it != index_.end()) return rows_[it->second];
    index_[op] = rows_.size();
    rows_.push_back(Tally{});
    rows_.back().op = op;
    rows_.back().category = category;
    return rows_.back();
  }
  std::vector<Tally>& all() { return rows_; }

 private:
  std::vector<Tally> rows_;
  std::map<std::string, size_t> index_;
};

std::string describe_inputs(const Program& p, const std::vector<Words>& inputs, int64_t e) {
  const ir::Function& f = p.ir();
  std::string s;
  for (size_t j = 0; j < f.inputs.size(); ++j) {
    const ir::Type t = f.var(f.inputs[j]).type;
    if (j) s += ", ";
    s += f.var(f.inputs[j]).name + "=" +
         describe_words(t, &inputs[j][static_cast<size_t>(e * t.width)]);
  }
  return s;
}

std::string show_float(double v) {
  char buf[64];
  float f = static_cast<float>(v);
  std::snprintf(buf, sizeof buf, "%.9g [%08x]", v, bits_of(f));
  return buf;
}

struct Context {
  std::string backend;
  Accuracy accuracy;
  bool flush = false;
  std::string device;  // Backend::description(): picks the fast-mode bounds (Bounds.cpp)
};

// ---- operation cases --------------------------------------------------------------------------

// The fast mode's general domain (docs/accuracy.md): finite operands and a finite result,
// none of them nonzero below 2^-100 (a relaxed implementation may flush denormals anywhere,
// intermediate values included; 2^-100 leaves 26 binades of room above FLT_MIN).
constexpr double kFastTiny = 0x1p-100;
bool fast_value(double v) {
  return std::isfinite(v) && std::fabs(v) <= static_cast<double>(FLT_MAX) &&
         (v == 0 || std::fabs(v) >= kFastTiny);
}

void compare_checks(const Case& c, const Program& p, const Context& cx, const Shape& shape,
                    const std::vector<Words>& inputs, const Launched& got,
                    const Launched* strict_ref, const Launched* strict_daz, Rows& rows) {
  const ir::Function& f = p.ir();
  std::vector<ir::Type> in_types;
  for (ir::VarId v : f.inputs) in_types.push_back(f.var(v).type);
  const int64_t n = shape.n;
  for (const Check& ch : c.checks) {
    Tally& t = rows.at(ch.op, ch.category);
    const ir::Type ot = f.var(f.outputs[static_cast<size_t>(ch.output)]).type;
    const ir::Type st = ot.with_width(1);  // one component
    const bool is_float = ot.is_float();
    const bool exact = !is_float || exact_reference(ch.op);
    if (is_float) t.any_float = true;
    const Words& out = got.outputs[static_cast<size_t>(ch.output)];
    for (int64_t e = 0; e < n; ++e) {
      Elem el{&inputs, &in_types, e, false};
      Elem daz{&inputs, &in_types, e, true};
      bool fast_inputs = true;
      for (size_t j = 0; j < in_types.size(); ++j)
        if (in_types[j].is_float())
          for (int k = 0; k < in_types[j].width; ++k)
            if (!fast_value(el.d(static_cast<int>(j), k))) fast_inputs = false;
      for (int comp = 0; comp < ot.width; ++comp) {
        const size_t w = static_cast<size_t>(e * ot.width + comp);
        const uint32_t g = out[w];
        auto where = [&] {
          return ch.form + ": " + describe_inputs(p, inputs, e) +
                 (ot.width > 1 ? " [" + std::to_string(comp) + "]" : "") + " gives " +
                 describe_words(st, &g);
        };
        auto report = [&](const std::string& want) { t.example(where() + ", expected " + want); };
        const double r = ch.ref(el, comp);
        const bool in_domain =
            fast_inputs && fast_value(r) && (!ch.fast_domain || ch.fast_domain(el, comp));
        // The exact result where the reference is exact: the double result rounded once.
        auto host_bits = [&](double v) {
          return is_float ? bits_of(static_cast<float>(v))
                          : static_cast<uint32_t>(static_cast<int32_t>(v));
        };
        auto matches_host = [&] {
          if (same(g, host_bits(r), is_float, cx.flush)) return true;
          return cx.flush && same(g, host_bits(ch.ref(daz, comp)), is_float, true);
        };
        auto measure = [&](bool flush) {
          double s = ch.scale ? ch.scale(el, comp) : 0.0;
          double err = measured_error(float_of(g), r, s, flush);
          if (flush) {
            double sd = ch.scale ? ch.scale(daz, comp) : 0.0;
            err = std::min(err, measured_error(float_of(g), ch.ref(daz, comp), sd, true));
          }
          return err;
        };

        if (cx.accuracy == Accuracy::Strict) {
          // Bit for bit with the interpreter, and with the exact reference where there is one.
          const uint32_t want = strict_ref->outputs[static_cast<size_t>(ch.output)][w];
          bool ok = same(g, want, is_float, cx.flush);
          if (!ok && strict_daz)
            ok =
                same(g, strict_daz->outputs[static_cast<size_t>(ch.output)][w], is_float, cx.flush);
          ++t.elements;
          if (!ok) {
            ++t.mismatches;
            report(describe_words(st, &want) + " (interpreter)");
          } else if (exact && !matches_host()) {
            ++t.mismatches;
            uint32_t hb = host_bits(r);
            report(describe_words(st, &hb) +
                   " (exact reference; the interpreter agrees with the backend)");
          } else if (is_float && is_nan_bits(g) && g != want) {
            ++t.nan_bits;
          }
          // Informative: the strict result's error against the double reference.
          if (is_float && in_domain)
            t.error_at(measure(cx.flush),
                       [&] { return where() + ", double reference " + show_float(r); });
          continue;
        }
        if (cx.accuracy == Accuracy::Fast) {
          if (!is_float) {  // integer results: exact, for operands in the fast domain
            if (!fast_inputs) continue;
            ++t.elements;
            if (!matches_host()) {
              ++t.mismatches;
              report(std::to_string(static_cast<int64_t>(r)));
            }
            continue;
          }
          if (!in_domain) continue;
          double err = measure(true);
          ++t.elements;
          t.error_at(err, [&] { return where() + ", double reference " + show_float(r); });
          if (err > t.bound) {
            ++t.mismatches;
            report(show_float(r) + " (" + std::to_string(err) + " ulp)");
          }
          continue;
        }
        // Double: the double-precision result rounded once to float.
        ++t.elements;
        if (!is_float) {
          if (!matches_host()) {
            ++t.mismatches;
            report(std::to_string(static_cast<int64_t>(r)));
          }
          continue;
        }
        uint32_t want = host_bits(r);
        if (same(g, want, true, cx.flush)) {
          t.max_ulp = std::max(t.max_ulp, 0.0);
          continue;
        }
        double d = ulp_distance(float_of(cx.flush ? flush_bits(g) : g),
                                float_of(cx.flush ? flush_bits(want) : want));
        t.error_at(d, [&] { return where() + ", expected " + describe_words(st, &want); });
        if (d > t.bound || d == 0) {  // d == 0: the sign of a zero differs
          ++t.mismatches;
          report(describe_words(st, &want));
        }
      }
    }
  }
}

// ---- control programs and specials ---------------------------------------------------------

void compare_program(const Case& c, const Program& p, const Context& cx,
                     const std::vector<Words>& inputs, const Launched& got, const Launched& ref,
                     const Launched* daz, Tally& t) {
  const ir::Function& f = p.ir();
  const size_t nout = f.outputs.size();
  for (int l = 0; l < c.launches; ++l) {
    if (got.written[static_cast<size_t>(l)] != ref.written[static_cast<size_t>(l)]) {
      ++t.mismatches;
      t.example("launch " + std::to_string(l) + ": " +
                std::to_string(got.written[static_cast<size_t>(l)]) +
                " elements written, expected " +
                std::to_string(ref.written[static_cast<size_t>(l)]));
    }
    for (size_t o = 0; o < nout; ++o) {
      const ir::Type ot = f.var(f.outputs[o]).type;
      const Words& g = got.outputs[static_cast<size_t>(l) * nout + o];
      const Words& w = ref.outputs[static_cast<size_t>(l) * nout + o];
      for (size_t k = 0; k < g.size(); ++k) {
        ++t.elements;
        bool ok = same(g[k], w[k], ot.is_float(), cx.flush);
        if (!ok && daz)
          ok = same(g[k], daz->outputs[static_cast<size_t>(l) * nout + o][k], ot.is_float(),
                    cx.flush);
        if (!ok) {
          ++t.mismatches;
          int64_t e = static_cast<int64_t>(k) / ot.width;
          t.example("launch " + std::to_string(l) + ", " + f.var(f.outputs[o]).name + "[" +
                    std::to_string(e) + "] with " + describe_inputs(p, inputs, e) + ": " +
                    describe_words(ot, &g[static_cast<size_t>(e * ot.width)]) + ", expected " +
                    describe_words(ot, &w[static_cast<size_t>(e * ot.width)]));
        }
      }
    }
  }
}

void compare_specials(const Context& cx, const Launched& got, const Launched* interp, Rows& rows) {
  const auto& all = specials();
  for (size_t e = 0; e < all.size(); ++e) {
    const Special& s = all[e];
    Tally& t = rows.at("special: " + s.category, "special");
    t.max_examples = 100;  // every special that fails, by name
    if (cx.accuracy == Accuracy::Fast && s.category != "int") continue;  // finite math only
    if (cx.accuracy == Accuracy::Double && s.strict_only) continue;
    const int width = s.int_result ? 1 : s.width;
    for (int c = 0; c < width; ++c) {
      uint32_t want = s.expected[static_cast<size_t>(c)];
      auto pick = [&](const Launched& l) {
        return s.int_result ? l.outputs[1][e] : l.outputs[0][e * 4 + static_cast<size_t>(c)];
      };
      uint32_t g = pick(got);
      ++t.elements;
      if (!same(g, want, !s.int_result, cx.flush)) {
        ++t.mismatches;
        ir::Type ty = s.int_result ? ir::int_type(1) : ir::float_type(1);
        t.example(s.label + (width > 1 ? "[" + std::to_string(c) + "]" : "") + " gives " +
                  describe_words(ty, &g) + ", documented " + s.expected_text);
      }
      if (interp) {
        uint32_t ig = pick(*interp);
        if (!same(ig, want, !s.int_result, false)) {
          ++t.mismatches;
          ir::Type ty = s.int_result ? ir::int_type(1) : ir::float_type(1);
          t.example("reference interpreter: " + s.label + " gives " + describe_words(ty, &ig) +
                    ", documented " + s.expected_text);
        }
      }
    }
  }
}

// ---- the denormal probe ---------------------------------------------------------------------

struct Probe {
  bool flush = false;
  std::string text;
};

Probe probe_denormals(const std::string& backend, Accuracy a) {
  Program p = program("denormal_probe", [] {
    Input<Float> x("x");
    Input<Float> s("s");
    Output<Float> y("y");
    y = x * s;
  });
  CompileOptions o;
  o.accuracy = a;
  Kernel k = compile(p, backend, o);
  // denormal * 1 (is a denormal operand read as zero?), FLT_MIN * 0.5 (is a denormal result
  // flushed?), 1 * denormal.
  Stream<Float> x(std::vector<float>{float_of(0x000116c2u), FLT_MIN, 1.0f});
  Stream<Float> s(std::vector<float>{1.0f, 0.5f, float_of(0x000116c2u)});
  Stream<Float> y(3);
  k.inputs(x, s).outputs(y);
  k.execute();
  auto r = y.download();
  bool operands = bits_of(r[0]) == 0 || bits_of(r[2]) == 0;
  bool results = bits_of(r[1]) == 0;
  Probe pr;
  pr.flush = operands || results;
  pr.text = std::string("denormal operands ") + (operands ? "read as zero" : "kept") +
            ", denormal results " + (results ? "flushed to zero" : "kept");
  return pr;
}

uint64_t name_hash(const std::string& s) {
  uint64_t h = 1469598103934665603ull;
  for (char ch : s) h = (h ^ static_cast<uint8_t>(ch)) * 1099511628211ull;
  return h;
}

bool selected(const Options& o, const std::string& name) {
  if (!o.cases.empty() && std::find(o.cases.begin(), o.cases.end(), name) == o.cases.end())
    return false;
  if (o.filter.empty()) return true;
  for (const auto& f : o.filter)
    if (name.find(f) != std::string::npos) return true;
  return false;
}

void run_case(const Case& c, const Context& cx, const Options& o, Rows& rows, bool is_specials) {
  Program p;
  std::vector<std::string> ops;
  auto fail_all = [&](const std::string& msg) {
    if (c.exact_program) {
      rows.at(c.name, c.category).error = msg;
    } else if (is_specials) {
      for (const Special& s : specials()) rows.at("special: " + s.category, "special").error = msg;
    } else {
      for (const Check& ch : c.checks) rows.at(ch.op, ch.category).error = msg;
    }
  };
  try {
    p = c.build();
  } catch (const std::exception& e) {
    fail_all(std::string("program capture failed: ") + e.what());
    return;
  }
  const ir::Function& f = p.ir();
  Shape shape;
  shape.n = c.elements > 0 ? c.elements : o.elements;
  shape.width = c.width > 0 ? c.width : shape.n;
  shape.height = shape.n / shape.width;
  std::vector<ir::Type> in_types, out_types;
  for (ir::VarId v : f.inputs) in_types.push_back(f.var(v).type);
  for (ir::VarId v : f.outputs) out_types.push_back(f.var(v).type);
  Rng rng(o.seed ^ name_hash(c.name));
  std::vector<Words> inputs, prefill;
  if (c.generate)
    c.generate(rng, shape.n, in_types, inputs);
  else
    generate_inputs(rng, shape.n, in_types, c.domains, inputs);
  if (c.prefill) {
    c.prefill(shape.n, out_types, prefill);
  } else {
    for (const ir::Type& t : out_types)
      prefill.emplace_back(static_cast<size_t>(shape.n * t.width), 0u);
  }

  // Fast-mode and double-mode bounds of the rows this case feeds.
  if (!c.exact_program && !is_specials)
    for (const Check& ch : c.checks) {
      Tally& t = rows.at(ch.op, ch.category);
      t.bound = cx.accuracy == Accuracy::Fast     ? fast_bound(ch.op, cx.backend, cx.device)
                : cx.accuracy == Accuracy::Double ? double_bound(ch.op)
                                                  : -1;
    }

  Launched got;
  try {
    got = run_backend(p, cx.backend, cx.accuracy, shape, inputs, prefill, c);
  } catch (const std::exception& e) {
    fail_all(e.what());
    return;
  }
  const bool need_interp = c.exact_program || is_specials || cx.accuracy == Accuracy::Strict;
  Launched ref, daz;
  bool have_daz = false;
  if (need_interp) {
    try {
      ref = run_interpreter(p, shape, inputs, prefill, c, false);
      if (cx.flush) {
        daz = model_reference(p, shape, inputs, prefill, c, got, ref);
        have_daz = true;
      }
    } catch (const std::exception& e) {
      fail_all(std::string("reference interpreter: ") + e.what());
      return;
    }
  }
  if (is_specials) {
    compare_specials(cx, got, cx.accuracy == Accuracy::Strict ? &ref : nullptr, rows);
  } else if (c.exact_program) {
    compare_program(c, p, cx, inputs, got, ref, have_daz ? &daz : nullptr,
                    rows.at(c.name, c.category));
  } else {
    compare_checks(c, p, cx, shape, inputs, got, need_interp ? &ref : nullptr,
                   have_daz ? &daz : nullptr, rows);
  }
}

}  // namespace

const char* status_name(Status s) {
  switch (s) {
    case Status::Pass:
      return "pass";
    case Status::Fail:
      return "FAIL";
    case Status::Skip:
      return "skip";
    case Status::Error:
      return "ERROR";
  }
  return "?";
}

int Report::count(Status s) const {
  int k = 0;
  for (const Row& r : rows) k += r.status == s ? 1 : 0;
  return k;
}

std::vector<std::string> case_names() {
  std::vector<std::string> v;
  for (const Case& c : operation_cases()) v.push_back(c.name);
  for (const Case& c : control_cases()) v.push_back(c.name);
  v.push_back("specials");
  return v;
}

Report run(const std::string& backend_name, Accuracy a, const Options& o) {
  auto t0 = std::chrono::steady_clock::now();
  Report r;
  r.backend = backend_name;
  r.accuracy = accuracy_name(a);
  Backend* be = nullptr;
  for (Backend* b : backends())
    if (b->name() == backend_name) be = b;
  if (!be) {
    r.skipped = true;
    r.skip_reason = "this build has no backend named '" + backend_name + "'";
    return r;
  }
  r.skip_reason = be->unavailable_reason();
  if (!r.skip_reason.empty()) {
    r.skipped = true;
    return r;
  }
  r.device = be->description();
  if (!be->supports(a)) {
    r.skipped = true;
    r.skip_reason = "the backend has no " + std::string(accuracy_name(a)) + " mode" +
                    (a == Accuracy::Double ? " (no binary64 arithmetic)" : "");
    return r;
  }
  Context cx{backend_name, a, false, r.device};
  try {
    Probe pr = probe_denormals(backend_name, a);
    // Fast mode may flush denormals on any backend (relaxed math), whatever the probe saw.
    cx.flush = pr.flush || a == Accuracy::Fast;
    r.flushes_denormals = pr.flush;
    r.denormal_probe = pr.text;
  } catch (const std::exception& e) {
    r.denormal_probe = std::string("probe failed: ") + e.what();
  }

  Rows rows;
  if (o.operations)
    for (const Case& c : operation_cases())
      if (selected(o, c.name)) run_case(c, cx, o, rows, false);
  if (o.control)
    for (const Case& c : control_cases())
      if (selected(o, c.name)) run_case(c, cx, o, rows, false);
  if (o.specials && selected(o, "specials")) run_case(specials_case(), cx, o, rows, true);

  for (Tally& t : rows.all()) {
    Row row;
    row.op = t.op;
    row.category = t.category;
    row.backend = backend_name;
    row.accuracy = r.accuracy;
    row.elements = t.elements;
    row.mismatches = t.mismatches;
    row.max_ulp = t.any_float ? t.max_ulp : -1;
    row.bound = t.any_float ? t.bound : -1;
    row.nan_bits_differ = t.nan_bits;
    if (!t.error.empty()) {
      row.status = Status::Error;
      row.note = t.error;
    } else if (t.elements == 0) {
      row.status = Status::Skip;
      row.note = a == Accuracy::Fast ? "fast mode defines no result for these inputs (finite math)"
                                     : "nothing to compare";
    } else {
      row.status = t.mismatches ? Status::Fail : Status::Pass;
      for (size_t k = 0; k < t.examples.size(); ++k) row.note += (k ? "; " : "") + t.examples[k];
      if (!t.mismatches && t.nan_bits)
        row.note = std::to_string(t.nan_bits) +
                   " NaN results with other bits than the reference's (allowed)";
      if (t.max_ulp > 0 && !t.worst.empty())
        row.note =
            std::string("largest error: ") + t.worst + (row.note.empty() ? "" : "; ") + row.note;
    }
    r.rows.push_back(row);
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace rill::conformance
