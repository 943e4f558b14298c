// Source maps (backends/codegen/SourceMap.h): with CompileOptions::source_map the generated C,
// lockstep C and OpenCL C carry #line directives naming the user's lines, and GLSL comments;
// the map only adds lines, so the code is otherwise the same and computes the same bits on
// every backend; and a driver's message about a generated line is read back to the user's.
//
// Line numbers are the subject here: the kernel below takes __LINE__ on the line of its
// RILL_IF, which the statements inside the branch (made by operators) are near.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>

#include "BackendTest.h"
#include "codegen/SourceMap.h"
#include "cpu/CEmitter.h"
#include "rill/passes/Passes.h"
#include "simd/LockstepEmitter.h"
#ifdef RILL_HAVE_OPENCL
#include "opencl/OpenCLEmitter.h"
#endif
#ifdef RILL_HAVE_GLSL
#include "glsl/GLSLEmitter.h"
#endif

namespace rill::testing {
namespace {

namespace fs = std::filesystem;

#define EXPECT_HAS(text, sub) EXPECT_NE(std::string(text).find(sub), std::string::npos) << (text)

// The message of the rill::Error f throws ("" when it throws none).
template <class F>
std::string test_error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

int g_if_line = 0;  // the line of mapped_kernel()'s RILL_IF

// A kernel whose branch computes a constant found nowhere else in the generated code.
Program mapped_kernel() {
  return program("mapped", [] {
    Input<Int> x("x");
    Output<Int> y("y");
    Int t = x * 3;
    RILL_IF((g_if_line = __LINE__, x > 5)) {
      t = t + 987654;
    }
    RILL_ENDIF;
    y = t;
  });
}

std::string user_line(int line) {
  return relative_path(__FILE__) + ":" + std::to_string(line);
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string l;
  while (std::getline(in, l)) out.push_back(l);
  return out;
}

// The 1-based number of the first line of `text` containing `what` (0: none).
int line_containing(const std::string& text, const std::string& what) {
  const std::vector<std::string> lines = lines_of(text);
  for (size_t i = 0; i < lines.size(); ++i)
    if (lines[i].find(what) != std::string::npos) return static_cast<int>(i + 1);
  return 0;
}

// ---- the emitters, without a driver --------------------------------------------------------

struct Emitter {
  std::string name;
  bool directives;  // #line (else comments)
  std::function<std::string(const ir::Function&, bool)> emit;
};

std::vector<Emitter> emitters() {
  std::vector<Emitter> out = {
      {"C", true,
       [](const ir::Function& f, bool map) {
         cpu::CLayout layout;
         layout.source_map = map;
         return cpu::emit_c(f, Accuracy::Strict, layout);
       }},
      // Outlined into functions over two units (backends/cpu/Outline.h), as large kernels are.
      {"C, outlined", true,
       [](const ir::Function& f, bool map) {
         cpu::CLayout layout{
             .outline_min_cost = 1, .max_units = 2, .unit_cost = 1, .source_map = map};
         return cpu::emit_c(f, Accuracy::Strict, layout);
       }},
      {"lockstep C", true, [](const ir::Function& f, bool map) {
         return simd::emit_c_lockstep(f, Accuracy::Strict, simd::kLockstepLanes, map);
       }}};
#ifdef RILL_HAVE_OPENCL
  out.push_back({"OpenCL C", true, [](const ir::Function& f, bool map) {
                   return opencl::emit_opencl(f, Accuracy::Strict, map);
                 }});
#endif
#ifdef RILL_HAVE_GLSL
  out.push_back(
      {"GLSL fragment", false, [](const ir::Function& f, bool map) {
         return glsl::emit_glsl(f, Accuracy::Strict, {0}, glsl::DriverRules{}, map).source;
       }});
  out.push_back({"GLSL compute", false, [](const ir::Function& f, bool map) {
                   return glsl::emit_glsl_compute(f, Accuracy::Strict, {0}, true,
                                                  glsl::DriverRules{}, false, 64, nullptr, map)
                       .source;
                 }});
#endif
  return out;
}

ir::Function optimized(const Program& p) {
  return passes::optimize(p.ir(), PassOptions{}, Accuracy::Strict);
}

TEST(SourceMap, EachEmitterNamesTheUserLine) {
  const ir::Function f = optimized(mapped_kernel());
  const std::string directive =
      "#line " + std::to_string(g_if_line) + " \"" + relative_path(__FILE__) + "\"";
  const std::string comment = "// rill: " + user_line(g_if_line);
  for (const Emitter& e : emitters()) {
    const std::string plain = e.emit(f, false), mapped = e.emit(f, true);
    EXPECT_EQ(plain.find("#line"), std::string::npos) << e.name;
    EXPECT_EQ(plain.find("// rill: "), std::string::npos) << e.name;
    EXPECT_HAS(mapped, e.directives ? directive : comment) << e.name;
    if (e.directives) {
      EXPECT_EQ(mapped.find("// rill: "), std::string::npos) << e.name;
    }
  }
}

// The map adds whole lines and changes no other: without them the text is the plain one,
// line for line, and the line computing the branch's constant maps to the RILL_IF's line.
TEST(SourceMap, MapLinesAreOnlyAdded) {
  const ir::Function f = optimized(mapped_kernel());
  for (const Emitter& e : emitters()) {
    const std::string plain = e.emit(f, false), mapped = e.emit(f, true);
    const std::vector<std::string> table = codegen::user_lines(plain, mapped);
    ASSERT_EQ(table.size(), lines_of(plain).size()) << e.name << ": the map changed other lines";
    const int g = line_containing(plain, "987654");
    ASSERT_GT(g, 0) << e.name;
    EXPECT_EQ(table[static_cast<size_t>(g - 1)], user_line(g_if_line)) << e.name;
    // The kernel's interface, outside every statement, maps to nothing.
    EXPECT_EQ(table[0], "") << e.name;
  }
}

// After the statements, a #line directive gives back the generated text's own numbering:
// `#line K "generated"` stands on line K - 1.
TEST(SourceMap, DirectivesRestoreTheGeneratedNumbering) {
  const ir::Function f = optimized(mapped_kernel());
  const std::regex restore("^ *#line ([0-9]+) \"generated\"$");
  for (const Emitter& e : emitters()) {
    if (!e.directives) continue;
    const std::vector<std::string> lines = lines_of(e.emit(f, true));
    int restores = 0;
    for (size_t i = 0; i < lines.size(); ++i) {
      std::smatch m;
      if (!std::regex_match(lines[i], m, restore)) continue;
      ++restores;
      EXPECT_EQ(std::stoul(m[1].str()), i + 2) << e.name << ", line " << i + 1;
    }
    EXPECT_GE(restores, 1) << e.name;  // the body's at least (lockstep C has no nested block)
    for (const std::string& l : lines)
      EXPECT_EQ(l.find("rill-restore"), std::string::npos) << e.name;
  }
}

TEST(SourceMap, DriverMessagesAreReadBackToTheUserLine) {
  const ir::Function f = optimized(mapped_kernel());
  for (const Emitter& e : emitters()) {
    const std::string plain = e.emit(f, false);
    const int g = line_containing(plain, "987654");
    const std::string gen = std::to_string(g);
    // gcc, clang and PoCL: "file:line:column: "; Mesa: "0:line(column): ".
    const std::string message = e.directives ? "kernel.c:" + gen + ":9: error: made up\n"
                                             : "0:" + gen + "(9): error: made up\n";
    const std::string what = "driver rejected it:\n" + message + "generated source:\n" + plain;
    const std::string reported =
        codegen::with_user_lines(what, plain, [&] { return e.emit(f, true); });
    EXPECT_EQ(
        reported.rfind(user_line(g_if_line) + " (generated line " + gen + "): driver rejected", 0),
        0u)
        << e.name << ":\n"
        << reported.substr(0, 300);
    EXPECT_HAS(reported, "error: made up  [from " + user_line(g_if_line) + "]") << e.name;
    // A message naming no generated line of a statement stays as it was.
    const std::string other = "driver rejected it:\nkernel.c:1:1: error: made up\n";
    EXPECT_EQ(codegen::with_user_lines(other, plain, [&] { return e.emit(f, true); }), other);
  }
}

// ---- every backend ---------------------------------------------------------------------------

class SourceMapTest : public BackendTest {
 protected:
  Kernel compile_mapped(const Program& p, bool map) {
    CompileOptions o;
    o.source_map = map;
    return rill::compile(p, backend_name(), o);
  }
  // GLSL's backends (vulkan compiles GLSL too) carry comments, the others #line directives.
  bool directives() const {
    return backend_name().rfind("glsl", 0) != 0 && backend_name() != "vulkan";
  }
};

TEST_P(SourceMapTest, MappedKernelsComputeTheSameBits) {
  const Program p = mapped_kernel();
  std::vector<int32_t> xs;
  for (int i = -50; i < 50; ++i) xs.push_back(i * 7);
  Kernel plain = compile_mapped(p, false), mapped = compile_mapped(p, true);
  const std::vector<int32_t> a = run_kernel<Int>(plain, static_cast<int64_t>(xs.size()), xs);
  const std::vector<int32_t> b = run_kernel<Int>(mapped, static_cast<int64_t>(xs.size()), xs);
  std::vector<int32_t> want;
  for (int32_t x : xs) want.push_back(x > 5 ? x * 3 + 987654 : x * 3);
  EXPECT_EQ(a, want);
  EXPECT_EQ(b, want);
  const std::string marker =
      directives() ? "#line " + std::to_string(g_if_line) + " \"" + relative_path(__FILE__) + "\""
                   : "// rill: " + user_line(g_if_line);
  EXPECT_HAS(mapped.source(), marker);
  EXPECT_EQ(plain.source().find(marker), std::string::npos);
  EXPECT_EQ(plain.source().find("#line"), std::string::npos);
}

TEST_P(SourceMapTest, TheEnvironmentTurnsItOn) {
  ScopedEnv on("RILL_SOURCE_MAP", "1");
  Kernel k = compile(mapped_kernel());
  EXPECT_HAS(k.source(), directives() ? "#line " + std::to_string(g_if_line)
                                      : "// rill: " + user_line(g_if_line));
  ScopedEnv bad("RILL_SOURCE_MAP", "yes");
  EXPECT_HAS(test_error_of([&] { compile(mapped_kernel()); }),
             "RILL_SOURCE_MAP='yes' is not 0 or 1");
}

// The C compiler's error, end to end: a stand-in compiler (RILL_CC) rejects the line of the
// generated C that computes the branch's constant, as gcc would word it; the error names
// the user's line, with the generated one beside it.
TEST_P(SourceMapTest, ACompilerErrorNamesTheUserLine) {
  if (backend_name() != "cpu" && backend_name() != "simd")
    GTEST_SKIP() << "RILL_CC is the cpu and simd backends' compiler";
  const fs::path dir = fs::temp_directory_path() /
                       ("rill-sourcemap-test-" + std::to_string(getpid()) + "-" + backend_name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path cc = dir / "fake-cc";
  {
    std::ofstream script(cc);
    // The source file is the argument before the last ("... -o OUT SRC -lm").
    script << "#!/bin/sh\n"
              "prev=; last=; for a in \"$@\"; do prev=$last; last=$a; done\n"
              "n=$(grep -n 987654 \"$prev\" | head -n 1 | cut -d: -f1)\n"
              "echo \"$prev:$n:7: error: rejected by the test's compiler\"\n"
              "exit 1\n";
  }
  fs::permissions(cc, fs::perms::owner_all);
  std::string msg;
  {
    ScopedEnv compiler("RILL_CC", cc.string());
    ScopedEnv cache("RILL_CACHE_DIR", (dir / "cache").string());
    ScopedEnv no_profile("RILL_PROFILE_DIR", "");
    clear_kernel_cache();
    msg = test_error_of([&] { compile(mapped_kernel()); });
    clear_kernel_cache();
  }
  fs::remove_all(dir);
  EXPECT_EQ(msg.rfind(user_line(g_if_line) + " (generated line ", 0), 0u) << msg.substr(0, 400);
  EXPECT_HAS(msg, "error: rejected by the test's compiler  [from " + user_line(g_if_line) + "]");
}

RILL_BACKEND_TEST_SUITE(SourceMapTest);

}  // namespace
}  // namespace rill::testing
