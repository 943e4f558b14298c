// GLSL to SPIR-V through glslang, validated by SPIRV-Tools (SpirvCompiler.h).
#include "SpirvCompiler.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <glslang/build_info.h>
#include <spirv-tools/libspirv.hpp>

#include <mutex>

#include "../codegen/SourceText.h"
#include "VkApi.h"
#include "rill/Error.h"

namespace rill::vk {

namespace {

// glslang's process-wide tables, made once and kept (FinalizeProcess would race other
// threads' compiles at exit).
void initialize_glslang() {
  static std::once_flag once;
  std::call_once(once, [] { glslang::InitializeProcess(); });
}

// The module without its OpName instructions (debug names, no meaning). glslang names every
// temporary it makes for a call's argument "param", and the validator's name mapper makes
// each repeated name unique by trying suffixes one after another: quadratic in the number of
// calls, minutes for a kernel of thousands of helper calls (a strict kernel that flushes
// denormals itself: VulkanBackend.cpp).
std::vector<uint32_t> without_names(const std::vector<uint32_t>& spirv) {
  constexpr uint32_t kHeaderWords = 5, kOpName = 5;
  if (spirv.size() < kHeaderWords) return spirv;
  std::vector<uint32_t> out(spirv.begin(), spirv.begin() + kHeaderWords);
  out.reserve(spirv.size());
  for (size_t i = kHeaderWords; i < spirv.size();) {
    const size_t words = spirv[i] >> 16;
    if (words == 0 || i + words > spirv.size()) return spirv;  // malformed: the validator says
    if ((spirv[i] & 0xffffu) != kOpName)
      out.insert(out.end(), spirv.begin() + static_cast<std::ptrdiff_t>(i),
                 spirv.begin() + static_cast<std::ptrdiff_t>(i + words));
    i += words;
  }
  return out;
}

}  // namespace

std::vector<uint32_t> compile_compute_spirv(const std::string& glsl, const std::string& kernel,
                                            bool scalar_layout) {
  initialize_glslang();
  auto fail = [&](const std::string& stage, const std::string& log) {
    return Error(std::string(kWho) + ": kernel '" + kernel + "' did not " + stage + ":\n" + log +
                 "\n" + codegen::numbered(glsl));
  };
  const char* text = glsl.c_str();
  glslang::TShader shader(EShLangCompute);
  shader.setStrings(&text, 1);
  shader.setEnvInput(glslang::EShSourceGlsl, EShLangCompute, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_1);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_3);
  const auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules);
  if (!shader.parse(GetDefaultResources(), 100, false, messages))
    throw fail("compile (glslang)", shader.getInfoLog());
  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(messages)) throw fail("link (glslang)", program.getInfoLog());
  std::vector<uint32_t> spirv;
  glslang::SpvOptions options;
  options.disableOptimizer = true;  // the driver optimizes; glslang's would only cost time
  glslang::GlslangToSpv(*program.getIntermediate(EShLangCompute), spirv, &options);
  spirv = without_names(spirv);
  spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_1);
  std::string log;
  tools.SetMessageConsumer(
      [&](spv_message_level_t, const char*, const spv_position_t& at, const char* message) {
        log += "word " + std::to_string(at.index) + ": " + message + "\n";
      });
  spvtools::ValidatorOptions options_v;
  options_v.SetScalarBlockLayout(scalar_layout);
  if (!tools.Validate(spirv.data(), spirv.size(), options_v))
    throw fail("validate (SPIRV-Tools)", log);
  return spirv;
}

std::string gl_compute_errors(const std::string& glsl) {
  initialize_glslang();
  const char* text = glsl.c_str();
  glslang::TShader shader(EShLangCompute);
  shader.setStrings(&text, 1);
  // No client: GLSL as OpenGL takes it (loose uniforms, no descriptor sets); #version decides.
  if (!shader.parse(GetDefaultResources(), 100, false, EShMsgDefault)) return shader.getInfoLog();
  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(EShMsgDefault)) return program.getInfoLog();
  return "";
}

std::string spirv_compiler_version() {
  return "glslang " + std::to_string(GLSLANG_VERSION_MAJOR) + "." +
         std::to_string(GLSLANG_VERSION_MINOR) + "." + std::to_string(GLSLANG_VERSION_PATCH);
}

}  // namespace rill::vk
