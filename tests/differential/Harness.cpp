#include "Harness.h"

#include <rill/Reference.h>
#include <rill/ir/Interpreter.h>
#include <rill/ir/Printer.h>
#include <rill/passes/Passes.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <sstream>

#include <sys/resource.h>

namespace rill::difftest {

std::string hex(uint64_t v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "0x%016llx", static_cast<unsigned long long>(v));
  return buf;
}

double cpu_seconds() {
  auto sec = [](const timeval& t) {
    return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_usec) * 1e-6;
  };
  rusage self{}, children{};
  getrusage(RUSAGE_SELF, &self);
  getrusage(RUSAGE_CHILDREN, &children);
  return sec(self.ru_utime) + sec(self.ru_stime) + sec(children.ru_utime) + sec(children.ru_stime);
}

std::string Target::name() const {
  return backend + (passes_off ? " (passes off)" : "");
}

std::string Stats::summary() const {
  char buf[512];
  std::snprintf(
      buf, sizeof buf,
      "%lld programs (%lld failed) in %lld kernels, %lld launches, %lld elements compared; "
      "denormal-tainted elements on flushing backends: %lld (%lld differed, excused); "
      "wall time: capture %.1f s, reference %.1f s, compile %.1f s, run %.1f s, shrink %.1f s",
      static_cast<long long>(programs), static_cast<long long>(failed),
      static_cast<long long>(kernels), static_cast<long long>(launches),
      static_cast<long long>(elements), static_cast<long long>(tainted),
      static_cast<long long>(excused), capture_s, reference_s, compile_s, run_s, shrink_s);
  return buf;
}

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

bool is_nan_word(uint32_t w) {
  return (w & 0x7fffffffu) > 0x7f800000u;
}
uint32_t flush_word(uint32_t w) {
  return (w & 0x7f800000u) == 0 ? (w & 0x80000000u) : w;
}
bool is_denormal_word(uint32_t w) {
  return (w & 0x7f800000u) == 0 && (w & 0x007fffffu) != 0;
}

// Float words match when equal after flushing denormals (on flushing backends), any NaN
// matching any NaN (payloads are unspecified); Int words match when equal.
bool same_word(uint32_t want, uint32_t got, bool is_float, bool ftz) {
  if (!is_float) return want == got;
  if (ftz) {
    want = flush_word(want);
    got = flush_word(got);
  }
  if (is_nan_word(want) && is_nan_word(got)) return true;
  return want == got;
}

struct Outcome {
  int64_t count = 0;
  std::array<std::vector<uint32_t>, kStreams> out;
};

// ---- denormal tracking -----------------------------------------------------------------------
//
// A backend that flushes denormals computes different bits wherever a denormal occurs, not
// only in the outputs: 1e-30f * 1e-10f * 1e30f is 1e-10 in binary32 but 0 after flushing the
// intermediate product. So for such backends the reference also reports, per element, whether
// its evaluation met a denormal anywhere; those elements are compared after flushing and a
// difference there is excused (and counted). Every other element must match bit for bit.
//
// The report comes from an instrumented copy of the reference IR: after every assignment of
// a float value (and for the intermediate values of dot, cross and float mod, and for
// denormal constants, inputs, uniforms and previous outputs) it ORs "is denormal" into a
// flag, written to an extra Int output. Discards become no-ops in the copy, so the flag also
// covers elements that discard (over-approximating after the discard).
class DenormalTracker {
 public:
  static ir::Function instrument(const ir::Function& src) {
    ir::Function f = src;
    DenormalTracker t(f);
    ir::Block body;
    body.push_back(ir::Stmt::assign(t.seen_, ir::Op::Copy,
                                    {ir::Operand::of_const(ir::Constant::of_bool(false))}));
    std::vector<ir::VarId> entry = f.inputs;
    entry.insert(entry.end(), f.uniforms.begin(), f.uniforms.end());
    entry.insert(entry.end(), f.outputs.begin(), f.outputs.end() - 1);
    for (ir::VarId v : entry)
      if (f.var(v).type.is_float()) t.check(body, ir::Operand::of_var(v, f.var(v).type));
    ir::Block rest = t.block(src.body);
    for (ir::Stmt& s : rest) body.push_back(std::move(s));
    body.push_back(ir::Stmt::assign(
        t.flag_, ir::Op::Select,
        {ir::Operand::of_var(t.seen_, ir::bool_type()), t.int_const(1, 1), t.int_const(0, 1)}));
    f.body = std::move(body);
    return f;
  }

 private:
  explicit DenormalTracker(ir::Function& f) : f_(f) {
    flag_ = f.add_var(ir::int_type(), ir::VarRole::Output, "denormal_seen");
    f.vars[flag_].slot = static_cast<int>(f.outputs.size());
    f.outputs.push_back(flag_);
    seen_ = f.add_var(ir::bool_type(), ir::VarRole::Local, "denormal_seen_b");
  }

  ir::Operand int_const(int32_t v, int w) const {
    ir::Constant c;
    c.type = ir::int_type(w);
    for (int i = 0; i < w; ++i) c.bits[static_cast<size_t>(i)] = static_cast<uint32_t>(v);
    return ir::Operand::of_const(c);
  }
  ir::Operand var(ir::VarId v) const { return ir::Operand::of_var(v, f_.var(v).type); }
  // Components `perm` of operand o (a swizzle of a swizzle, or of a constant).
  static ir::Operand swizzled(const ir::Operand& o, std::initializer_list<int> perm) {
    ir::Operand r = o;
    r.type.width = static_cast<uint8_t>(perm.size());
    size_t i = 0;
    for (int p : perm) {
      if (o.is_var())
        r.swizzle[i] = static_cast<uint8_t>(o.component(p));
      else
        r.value.bits[i] = o.value.bits[static_cast<size_t>(o.width() == 1 ? 0 : p)];
      ++i;
    }
    if (o.is_const()) r.value.type.width = r.type.width;
    return r;
  }
  ir::VarId emit(ir::Block& out, ir::Type t, ir::Op op, std::vector<ir::Operand> args) {
    ir::VarId v = f_.add_var(t);
    out.push_back(ir::Stmt::assign(v, op, std::move(args)));
    return v;
  }

  // seen |= any component of v is denormal: 0 < (bits & 0x7fffffff) < 0x00800000.
  void check(ir::Block& out, const ir::Operand& v) {
    int w = v.width();
    ir::VarId bits = emit(out, ir::int_type(w), ir::Op::FloatBitsToInt, {v});
    ir::VarId m = emit(out, ir::int_type(w), ir::Op::BitAnd, {var(bits), int_const(0x7fffffff, w)});
    ir::VarId small = emit(out, ir::bool_type(w), ir::Op::Lt, {var(m), int_const(0x00800000, w)});
    ir::VarId nonzero = emit(out, ir::bool_type(w), ir::Op::Ne, {var(m), int_const(0, w)});
    ir::VarId z = emit(out, ir::bool_type(w), ir::Op::And, {var(small), var(nonzero)});
    for (int c = 0; c < w; ++c)
      out.push_back(ir::Stmt::assign(seen_, ir::Op::Or,
                                     {ir::Operand::of_var(seen_, ir::bool_type()),
                                      ir::Operand::of_var(z, ir::ScalarKind::Bool, {c})}));
  }
  void mark(ir::Block& out) {
    out.push_back(ir::Stmt::assign(seen_, ir::Op::Copy,
                                   {ir::Operand::of_const(ir::Constant::of_bool(true))}));
  }

  void assign(ir::Block& out, const ir::Stmt& s) {
    for (const ir::Operand& a : s.args) {
      if (!a.is_const() || !a.type.is_float()) continue;
      bool den = false;
      for (int c = 0; c < a.width(); ++c)
        den = den || is_denormal_word(a.value.bits[static_cast<size_t>(c)]);
      if (den) mark(out);
    }
    const ir::Type dt = f_.var(s.dst).type;
    const int w = s.mask.full() ? dt.width : s.mask.count;
    if (s.op == ir::Op::Dot) {  // the products and partial sums
      const ir::Operand &a = s.args[0], &b = s.args[1];
      int n = std::max(a.width(), b.width());
      ir::VarId p = emit(out, ir::float_type(n), ir::Op::Mul, {a, b});
      check(out, var(p));
      ir::Operand acc = ir::Operand::of_var(p, ir::ScalarKind::Float, {0});
      for (int c = 1; c < n; ++c) {
        ir::VarId sum = emit(out, ir::float_type(), ir::Op::Add,
                             {acc, ir::Operand::of_var(p, ir::ScalarKind::Float, {c})});
        check(out, var(sum));
        acc = var(sum);
      }
    } else if (s.op == ir::Op::Cross) {  // a.yzx * b.zxy and a.zxy * b.yzx
      const ir::Operand &a = s.args[0], &b = s.args[1];
      ir::VarId p = emit(out, ir::float_type(3), ir::Op::Mul,
                         {swizzled(a, {1, 2, 0}), swizzled(b, {2, 0, 1})});
      ir::VarId q = emit(out, ir::float_type(3), ir::Op::Mul,
                         {swizzled(a, {2, 0, 1}), swizzled(b, {1, 2, 0})});
      check(out, var(p));
      check(out, var(q));
    } else if (s.op == ir::Op::Mod && dt.is_float()) {  // x - y * floor(x / y)
      const ir::Operand &a = s.args[0], &b = s.args[1];
      ir::VarId q = emit(out, ir::float_type(w), ir::Op::Div, {a, b});
      ir::VarId fl = emit(out, ir::float_type(w), ir::Op::Floor, {var(q)});
      ir::VarId m = emit(out, ir::float_type(w), ir::Op::Mul, {b, var(fl)});
      check(out, var(q));
      check(out, var(m));
    }
    out.push_back(s);
    if (!dt.is_float()) return;
    ir::Operand written = ir::Operand::of_var(s.dst, dt);
    if (!s.mask.full()) {
      written.type.width = s.mask.count;
      for (int i = 0; i < s.mask.count; ++i)
        written.swizzle[static_cast<size_t>(i)] = s.mask.comps[static_cast<size_t>(i)];
    }
    check(out, written);
  }

  ir::Block block(const ir::Block& in) {
    ir::Block out;
    for (const ir::Stmt& s : in) {
      switch (s.kind) {
        case ir::StmtKind::Assign:
          assign(out, s);
          break;
        case ir::StmtKind::If: {
          ir::Stmt c = s;
          c.then_body = block(s.then_body);
          c.else_body = block(s.else_body);
          out.push_back(std::move(c));
          break;
        }
        case ir::StmtKind::Loop: {
          ir::Stmt c = s;
          c.cond_body = block(s.cond_body);
          c.body = block(s.body);
          c.step = block(s.step);
          out.push_back(std::move(c));
          break;
        }
        case ir::StmtKind::Discard:
          break;
        default:
          out.push_back(s);
          break;
      }
    }
    return out;
  }

  ir::Function& f_;
  ir::VarId flag_ = ir::kNoVar, seen_ = ir::kNoVar;
};

// ---- running -----------------------------------------------------------------------------------

template <class H>
std::vector<H> to_host(const std::vector<uint32_t>& w) {
  std::vector<H> v(w.size() * 4 / sizeof(H));
  if (!v.empty()) std::memcpy(v.data(), w.data(), v.size() * sizeof(H));
  return v;
}
template <class V>
Stream<V> stream_of(const LaunchData& d, const std::vector<uint32_t>& w) {
  Stream<V> s = d.height > 1 ? Stream<V>(d.width, d.height) : Stream<V>(d.count);
  s.upload(to_host<typename V::host_type>(w));
  return s;
}
template <class V>
std::vector<uint32_t> words_of(const Stream<V>& s) {
  auto h = s.download();
  std::vector<uint32_t> w(h.size() * static_cast<size_t>(V::width));
  if (!w.empty()) std::memcpy(w.data(), h.data(), w.size() * 4);
  return w;
}

Outcome run_kernel(Kernel& k, const LaunchData& d) {
  auto f4 = stream_of<Float4>(d, d.in[0]);
  auto f3 = stream_of<Float3>(d, d.in[1]);
  auto f1 = stream_of<Float>(d, d.in[2]);
  auto i4 = stream_of<Int4>(d, d.in[3]);
  auto i2 = stream_of<Int2>(d, d.in[4]);
  Stream<Float4> of4 = d.alias ? f4 : stream_of<Float4>(d, d.out[0]);
  auto of3 = stream_of<Float3>(d, d.out[1]);
  auto of2 = stream_of<Float2>(d, d.out[2]);
  Stream<Int4> oi4 = d.alias ? i4 : stream_of<Int4>(d, d.out[3]);
  auto oi1 = stream_of<Int>(d, d.out[4]);
  k.inputs(f4, f3, f1, i4, i2).outputs(of4, of3, of2, oi4, oi1);
  Outcome o;
  o.count = k.execute();
  o.out[0] = words_of(of4);
  o.out[1] = words_of(of3);
  o.out[2] = words_of(of2);
  o.out[3] = words_of(oi4);
  o.out[4] = words_of(oi1);
  return o;
}

// Runs f (the program p optimized, or instrumented) in the reference interpreter. `flags`, if
// given, receives the instrumented function's extra output.
Outcome interpret(const ir::Function& f, const Program& p, const LaunchData& d,
                  std::vector<uint32_t>* flags) {
  ir::InterpreterLaunch l = reference_launch(p);
  Outcome o;
  o.out = d.out;
  for (int k = 0; k < kStreams; ++k) {
    l.inputs.push_back(d.in[static_cast<size_t>(k)].data());
    l.outputs.push_back(o.out[static_cast<size_t>(k)].data());
  }
  if (flags) {
    flags->assign(static_cast<size_t>(d.count), 0u);
    l.outputs.push_back(flags->data());
  }
  l.count = d.count;
  l.width = d.width;
  o.count = ir::interpret(f, l);
  return o;
}

std::string show_element(const std::vector<uint32_t>& w, int64_t e, int width, bool is_float) {
  std::string s = width > 1 ? "(" : "";
  for (int c = 0; c < width; ++c)
    s += (c ? ", " : "") + show_word(w[static_cast<size_t>(e * width + c)], is_float);
  return s + (width > 1 ? ")" : "");
}

// Everything element e of a launch read.
std::string describe_launch(const LaunchData& d, int64_t e) {
  std::ostringstream os;
  os << "    inputs:";
  for (int k = 0; k < kStreams; ++k)
    os << ' ' << kInName[static_cast<size_t>(k)] << '='
       << show_element(d.in[static_cast<size_t>(k)], e, kInWidth[static_cast<size_t>(k)],
                       kInFloat[static_cast<size_t>(k)]);
  os << "\n    previous outputs:";
  for (int k = 0; k < kStreams; ++k)
    os << ' ' << kOutName[static_cast<size_t>(k)] << '='
       << show_element(d.out[static_cast<size_t>(k)], e, kOutWidth[static_cast<size_t>(k)],
                       kOutFloat[static_cast<size_t>(k)]);
  os << (d.alias ? " (of4 and oi4 are the streams of f4 and i4: in place)" : "");
  auto fw = [](float f) { return show_word(std::bit_cast<uint32_t>(f), true); };
  auto iw = [](int32_t i) { return show_word(static_cast<uint32_t>(i), false); };
  os << "\n    uniforms: uf=" << fw(d.uf) << " uf4=(" << fw(d.uf4.x) << ", " << fw(d.uf4.y) << ", "
     << fw(d.uf4.z) << ", " << fw(d.uf4.w) << ") ui=" << iw(d.ui) << " ui3=(" << iw(d.ui3.x) << ", "
     << iw(d.ui3.y) << ", " << iw(d.ui3.z) << ")\n";
  static const char* names[] = {"af1", "af4", "af2d", "ai1", "ai2d"};
  for (int a = 0; a < kArrays; ++a) {
    const auto& shape = d.shape[static_cast<size_t>(a)];
    os << "    array " << names[a] << " [" << shape[0];
    if (kArrDims[static_cast<size_t>(a)] == 2) os << " x " << shape[1];
    os << "]:";
    for (int64_t i = 0; i < shape[0] * shape[1]; ++i)
      os << ' '
         << show_element(d.arr[static_cast<size_t>(a)], i, kArrWidth[static_cast<size_t>(a)],
                         kArrFloat[static_cast<size_t>(a)]);
    os << '\n';
  }
  return os.str();
}

// Compares a launch's results with the reference's; returns "" or what differs.
std::string compare(const Outcome& want, const Outcome& got, const LaunchData& d, bool ftz,
                    const std::vector<uint32_t>& flags, Stats& st) {
  int64_t tainted = 0;
  if (ftz)
    for (uint32_t f : flags) tainted += f != 0;
  st.tainted += tainted;
  st.elements += d.count;
  int64_t first = -1;
  for (int64_t e = 0; e < d.count && first < 0; ++e) {
    bool differs = false;
    for (int k = 0; k < kStreams; ++k) {
      int w = kOutWidth[static_cast<size_t>(k)];
      for (int c = 0; c < w; ++c) {
        size_t i = static_cast<size_t>(e * w + c);
        if (!same_word(want.out[static_cast<size_t>(k)][i], got.out[static_cast<size_t>(k)][i],
                       kOutFloat[static_cast<size_t>(k)], ftz))
          differs = true;
      }
    }
    if (!differs) continue;
    if (ftz && flags[static_cast<size_t>(e)]) {
      ++st.excused;
      continue;
    }
    first = e;
  }
  bool count_ok = ftz ? std::abs(want.count - got.count) <= tainted : want.count == got.count;
  if (first < 0 && count_ok) return {};
  std::ostringstream os;
  os << "  element counts from execute(): expected " << want.count << ", got " << got.count
     << (count_ok ? "" : "  <-- differ") << " (of " << d.count << " elements, shape " << d.width
     << " x " << d.height << ")\n";
  if (first < 0) {
    os << "  all outputs match";
    if (ftz && tainted)
      os << " (" << tainted << " elements met denormals, which this backend flushes)";
    os << '\n';
    return os.str();
  }
  os << "  first differing element: " << first << "\n";
  for (int k = 0; k < kStreams; ++k) {
    int w = kOutWidth[static_cast<size_t>(k)];
    bool f = kOutFloat[static_cast<size_t>(k)];
    std::string mark;
    for (int c = 0; c < w; ++c) {
      size_t i = static_cast<size_t>(first * w + c);
      if (!same_word(want.out[static_cast<size_t>(k)][i], got.out[static_cast<size_t>(k)][i], f,
                     ftz))
        mark += "xyzw"[c];
    }
    os << "    " << kOutName[static_cast<size_t>(k)] << ": expected "
       << show_element(want.out[static_cast<size_t>(k)], first, w, f) << ", got "
       << show_element(got.out[static_cast<size_t>(k)], first, w, f)
       << (mark.empty() ? "" : "  <-- differs in " + mark) << '\n';
  }
  os << describe_launch(d, first);
  if (ftz) os << "    (this backend flushes denormals; the reference met none for this element)\n";
  return os.str();
}

// The first program of `subs` for which `f` throws alone (0 if none does).
template <class F>
size_t locate(const std::vector<ProgramSpec>& subs, F f) {
  if (subs.size() == 1) return 0;
  for (size_t k = 0; k < subs.size(); ++k) {
    try {
      f(subs[k]);
    } catch (const std::exception&) {
      return k;
    }
  }
  return 0;
}

Failure failure(std::string kind, std::string target, size_t sub, std::string message) {
  return Failure{std::move(kind), std::move(target), sub, std::move(message)};
}

}  // namespace

// ---- probing -------------------------------------------------------------------------------

bool flushes_denormals(const std::string& backend) {
  static std::map<std::string, bool> known;
  auto it = known.find(backend);
  if (it != known.end()) return it->second;
  Program p = rill::program("denormal_probe", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x * 0.5f;
  });
  Kernel k = rill::compile(p, backend);
  float tiny = std::numeric_limits<float>::denorm_min();
  Stream<Float> in(std::vector<float>{std::numeric_limits<float>::min(), tiny * 4.0f});
  Stream<Float> out(2);
  k.inputs(in).outputs(out);
  k.execute();
  std::vector<float> v = out.download();
  bool ftz = v[0] == 0.0f || v[1] == 0.0f;
  known[backend] = ftz;
  return ftz;
}

// ---- one batch -----------------------------------------------------------------------------

std::vector<Failure> run_batch(const std::vector<ProgramSpec>& subs, const Options& opt,
                               Stats& st) {
  auto t = Clock::now();
  Program p;
  try {
    p = build_program(subs);
  } catch (const std::exception& e) {
    return {failure("capture", "reference",
                    locate(subs, [](const ProgramSpec& s) { build_program({s}); }),
                    std::string("  capturing the program threw: ") + e.what() + "\n")};
  }
  st.capture_s += seconds_since(t);
  if (opt.verbose) std::printf("%s\n", p.print().c_str());

  t = Clock::now();
  bool need_taint = false;
  for (const Target& tg : opt.targets) need_taint = need_taint || tg.ftz;
  ir::Function ref, ref_off, ref_lockstep, taint;
  try {
    ref = passes::optimize(p.ir(), PassOptions{}, Accuracy::Strict);
    if (opt.check_unoptimized)
      ref_off = passes::optimize(p.ir(), PassOptions{false, false, false, false}, Accuracy::Strict);
    if (opt.check_lockstep) {
      // Read as a scalar kernel, the lowered one computes what ref does once it drops the
      // lanes that are no longer alive.
      passes::LockstepFunction lowered = passes::lower_lockstep(ref);
      ref_lockstep = std::move(lowered.f);
      if (lowered.alive != ir::kNoVar) {
        ir::Stmt drop = ir::Stmt::make_if(ir::Operand::of_var(lowered.alive, ir::bool_type(1)));
        drop.else_body.push_back(ir::Stmt::make(ir::StmtKind::Discard));
        ref_lockstep.body.push_back(std::move(drop));
      }
    }
    if (need_taint) taint = DenormalTracker::instrument(ref);
  } catch (const std::exception& e) {
    size_t sub = locate(subs, [](const ProgramSpec& s) {
      passes::optimize(build_program({s}).ir(), PassOptions{}, Accuracy::Strict);
    });
    return {failure("optimize", "reference", sub,
                    std::string("  optimizing the program threw: ") + e.what() + "\n")};
  }
  st.reference_s += seconds_since(t);

  t = Clock::now();
  std::vector<Kernel> kernels;
  for (const Target& tg : opt.targets) {
    CompileOptions co;
    co.accuracy = Accuracy::Strict;
    if (tg.passes_off) co.passes = PassOptions{false, false, false, false};
    try {
      kernels.push_back(rill::compile(p, tg.backend, co));
    } catch (const std::exception& e) {
      return {failure(
          "compile", tg.name(), 0,
          std::string("  compiling the kernel (all its programs) threw: ") + e.what() + "\n")};
    }
  }
  st.compile_s += seconds_since(t);
  st.kernels += static_cast<int64_t>(kernels.size());

  // Program k of the batch: its first failure, if any.
  std::vector<uint32_t> flags;
  auto check = [&](size_t k) -> std::optional<Failure> {
    LaunchData d = make_launch_data(subs[k].seed, opt.denormals);
    apply_launch_data(d, subs.size() == 1 ? 0 : static_cast<int>(k));
    t = Clock::now();
    Outcome want;
    try {
      want = interpret(ref, p, d, nullptr);
      if (need_taint) interpret(taint, p, d, &flags);
      if (opt.check_unoptimized) {
        Outcome off = interpret(ref_off, p, d, nullptr);
        std::string diff = compare(want, off, d, false, flags, st);
        if (!diff.empty()) return failure("mismatch", "reference (passes off)", k, diff);
      }
      if (opt.check_lockstep) {
        Outcome lanes = interpret(ref_lockstep, p, d, nullptr);
        std::string diff = compare(want, lanes, d, false, flags, st);
        if (!diff.empty()) return failure("mismatch", "reference (lockstep lowering)", k, diff);
      }
    } catch (const std::exception& e) {
      return failure("interpret", "reference", k,
                     std::string("  the interpreter threw: ") + e.what() + "\n");
    }
    st.reference_s += seconds_since(t);
    for (size_t i = 0; i < opt.targets.size(); ++i) {
      const Target& tg = opt.targets[i];
      t = Clock::now();
      Outcome got;
      try {
        got = run_kernel(kernels[i], d);
      } catch (const std::exception& e) {
        return failure("run", tg.name(), k, std::string("  executing threw: ") + e.what() + "\n");
      }
      st.run_s += seconds_since(t);
      ++st.launches;
      std::string diff = compare(want, got, d, tg.ftz, flags, st);
      if (!diff.empty()) return failure("mismatch", tg.name(), k, diff);
    }
    return std::nullopt;
  };
  std::vector<Failure> failures;
  for (size_t k = 0; k < subs.size(); ++k) {
    ++st.programs;
    if (auto f = check(k)) {
      ++st.failed;
      failures.push_back(std::move(*f));
      if (opt.stop_at_first) break;
    }
  }
  return failures;
}

// ---- shrinking -----------------------------------------------------------------------------

namespace {

std::string id_list(const std::set<uint64_t>& s) {
  std::string r;
  for (uint64_t v : s) r += (r.empty() ? "" : ",") + hex(v);
  return r;
}

std::string repro_line(const std::vector<ProgramSpec>& subs, const std::string& filter) {
  std::string seeds, drop, leaf;
  std::set<uint64_t> dropped, leaves;
  for (const ProgramSpec& s : subs) {
    seeds += (seeds.empty() ? "" : ",") + hex(s.seed);
    dropped.insert(s.edits.dropped.begin(), s.edits.dropped.end());
    leaves.insert(s.edits.leaves.begin(), s.edits.leaves.end());
  }
  std::string line = "RILL_DIFF_SEED=" + seeds;
  if (!dropped.empty()) line += " RILL_DIFF_DROP=" + id_list(dropped);
  if (!leaves.empty()) line += " RILL_DIFF_LEAF=" + id_list(leaves);
  return line + " tests/differential/rill_differential_tests --gtest_filter='" + filter + "'";
}

std::string program_text(const std::vector<ProgramSpec>& subs) {
  try {
    return build_program(subs).print();
  } catch (const std::exception& e) {
    return std::string("(capture threw: ") + e.what() + ")\n";
  }
}

class Shrinker {
 public:
  Shrinker(const Options& opt, const Failure& goal, double seconds)
      : goal_(goal),
        deadline_(Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                     std::chrono::duration<double>(seconds))) {
    opt_ = opt;
    opt_.verbose = false;
    opt_.stop_at_first = true;
    opt_.targets.clear();
    for (const Target& t : opt.targets)
      if (t.name() == goal.target) opt_.targets.push_back(t);
    opt_.check_unoptimized = goal.target == "reference (passes off)";
    opt_.check_lockstep = goal.target == "reference (lockstep lowering)";
  }

  int attempts() const { return attempts_; }
  bool out_of_time() const { return Clock::now() > deadline_; }

  // Whether `c` still fails the same way; remembers the last such failure.
  bool fails(const std::vector<ProgramSpec>& c) {
    if (out_of_time()) return false;
    ++attempts_;
    Stats scratch;
    auto f = run_batch(c, opt_, scratch);
    rill::clear_kernel_cache();
    if (!f.empty() && f[0].same_as(goal_)) {
      last_ = f[0];
      return true;
    }
    return false;
  }
  const Failure& last() const { return last_; }

  std::vector<ProgramSpec> run(std::vector<ProgramSpec> cur) {
    last_ = goal_;
    // 1. The failing program alone, else as few programs of the batch as still fail.
    if (cur.size() > 1) {
      std::vector<ProgramSpec> alone = {cur[goal_.sub]};
      if (fails(alone)) {
        cur = alone;
      } else {
        std::set<uint64_t> removed;
        reduce(
            [&] {
              std::vector<uint64_t> ids;
              for (const ProgramSpec& s : cur) ids.push_back(s.seed);
              return ids;
            },
            [&](const std::set<uint64_t>& without) {
              std::vector<ProgramSpec> c;
              for (const ProgramSpec& s : cur)
                if (!without.count(s.seed)) c.push_back(s);
              if (c.empty() || !fails(c)) return false;
              cur = c;
              return true;
            });
      }
    }
    // 2. Statements, 3. expressions (replaced by leaves), then statements once more.
    for (int round = 0; round < 3; ++round) {
      bool exprs = round == 1;
      reduce(
          [&] {
            std::vector<GenTrace> traces;
            try {
              build_program(cur, &traces);
            } catch (const std::exception&) {
            }
            std::vector<uint64_t> ids;
            for (const GenTrace& t : traces)
              for (uint64_t id : exprs ? t.exprs : t.stmts) ids.push_back(id);
            return ids;
          },
          [&](const std::set<uint64_t>& chunk) {
            std::vector<ProgramSpec> c = cur;
            for (ProgramSpec& s : c)
              (exprs ? s.edits.leaves : s.edits.dropped).insert(chunk.begin(), chunk.end());
            if (!fails(c)) return false;
            cur = c;
            return true;
          });
    }
    return cur;
  }

 private:
  // Delta debugging: tries removing chunks of the current items (halves, quarters, ... single
  // items); `remove` applies a chunk and says whether the result still fails.
  void reduce(const std::function<std::vector<uint64_t>()>& items_now,
              const std::function<bool(const std::set<uint64_t>&)>& remove) {
    size_t n = 2;
    while (!out_of_time()) {
      std::vector<uint64_t> items = items_now();
      if (items.empty()) return;
      n = std::min(n, items.size());
      size_t chunk = (items.size() + n - 1) / n;
      bool progress = false;
      for (size_t start = 0; start < items.size() && !out_of_time(); start += chunk) {
        std::set<uint64_t> part(
            items.begin() + static_cast<std::ptrdiff_t>(start),
            items.begin() + static_cast<std::ptrdiff_t>(std::min(items.size(), start + chunk)));
        if (remove(part)) {
          progress = true;
          n = std::max<size_t>(n - 1, 2);
          break;
        }
      }
      if (!progress) {
        if (chunk == 1) return;
        n = std::min(n * 2, items.size());
      }
    }
  }

  Options opt_;
  Failure goal_, last_;
  Clock::time_point deadline_;
  int attempts_ = 0;
};

}  // namespace

std::string report_failure(const std::vector<ProgramSpec>& subs, const Failure& f,
                           const Options& opt, bool shrink, double shrink_seconds, Stats& stats,
                           const std::string& filter) {
  std::ostringstream os;
  const ProgramSpec& bad = subs[f.sub];
  os << "\n==== differential test failure: " << f.title() << " ====\n";
  os << "program seed " << hex(bad.seed) << " (program " << f.sub << " of a kernel of "
     << subs.size() << "; its launch data derives from the seed too)\n";
  os << "reproduce: " << repro_line({bad}, filter) << "\n";
  if (subs.size() > 1) os << "the whole kernel: " << repro_line(subs, filter) << "\n";
  os << f.message;
  os << "program (IR as captured, alone):\n" << program_text({bad});
  if (opt.targets.size() > 1 && f.target != "reference") {
    // Which of the other targets agree with the reference on this program alone.
    os << "this program alone on each target:\n";
    for (const Target& t : opt.targets) {
      Options one = opt;
      one.verbose = false;
      one.check_unoptimized = false;
      one.targets = {t};
      one.stop_at_first = true;
      Stats scratch;
      auto r = run_batch({bad}, one, scratch);
      rill::clear_kernel_cache();
      os << "  " << t.name() << ": " << (r.empty() ? "matches the reference" : r[0].kind) << '\n';
    }
  }
  if (!shrink) return os.str();

  auto t = Clock::now();
  Shrinker sh(opt, f, shrink_seconds);
  std::vector<ProgramSpec> min = sh.run(subs);
  stats.shrink_s += seconds_since(t);
  Program p;
  try {
    p = build_program(min);
  } catch (const std::exception&) {
  }
  os << "\n---- shrunk in " << sh.attempts() << " attempts (" << seconds_since(t) << " s"
     << (sh.out_of_time() ? ", stopped by the time limit" : "") << ") ----\n";
  os << "reproduce: " << repro_line(min, filter) << "\n";
  os << sh.last().message;
  if (p.valid()) {
    os << "program (" << ir::count_statements(p.ir().body) << " statements):\n" << p.print();
    try {
      ir::Function ref = passes::optimize(p.ir(), PassOptions{}, Accuracy::Strict);
      os << "reference IR (optimized, strict):\n" << ir::print(ref);
    } catch (const std::exception& e) {
      os << "(optimizing threw: " << e.what() << ")\n";
    }
    for (const Target& tg : opt.targets) {
      if (tg.name() != f.target) continue;
      try {
        CompileOptions co;
        if (tg.passes_off) co.passes = PassOptions{false, false, false, false};
        Kernel k = rill::compile(p, tg.backend, co);
        const std::string& src = k.source();
        if (std::count(src.begin(), src.end(), '\n') < 400)
          os << "generated " << tg.backend << " source:\n" << src << "\n";
      } catch (const std::exception& e) {
        os << "(compiling threw: " << e.what() << ")\n";
      }
    }
  } else {
    os << "program:\n" << program_text(min);
  }
  return os.str();
}

}  // namespace rill::difftest
