// The Vulkan compute backend (`vulkan`).
//
// Kernels are the glsl-compute backend's (GLSLEmitter.cpp, Stage::Vulkan): one invocation per
// element, streams and arrays as storage buffers of descriptor set 0, the launch's uniforms in
// a read-only parameter buffer, discarded elements returning before they store, counts of the
// elements written and selected through atomics (one per subgroup where the device has
// ballots). glslang compiles the GLSL to SPIR-V 1.3 in-process and SPIRV-Tools validates it
// (SpirvCompiler.h); the device (VkContext.h) makes one compute pipeline per pass; the
// launcher (VkKernel.h) records, submits and waits.
//
// Strict kernels follow glsl-compute's rules (`precise` on every float, which glslang writes
// as SPIR-V NoContraction; constants in the parameter buffer so the driver cannot fold them;
// the division and square-root correction of DivSqrt.h where the device is not known exact;
// comparisons on bits except on NVIDIA) and add the SPV_KHR_float_controls execution modes the
// device offers for 32-bit floats (signed zeros, infinities and NaN preserved, denormals
// preserved, round to nearest even), through GL_EXT_spirv_intrinsics. Whether the device's
// arithmetic then keeps denormals is probed, as on glsl-compute.
//
// The disk cache keeps, per kernel, the passes' SPIR-V and the driver's pipeline cache data
// (vkGetPipelineCacheData), keyed by the device, its driver and pipelineCacheUUID, glslang's
// version and the source: a hit skips glslang and hands the driver its own cache back.
#include "VulkanBackend.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>

#include "../cache/DiskCache.h"
#include "../glsl/DivSqrt.h"
#include "../glsl/DriverProbes.h"
#include "../glsl/GLSLEmitter.h"
#include "../glsl/GLSession.h"
#include "SpirvCompiler.h"
#include "VkContext.h"
#include "VkKernel.h"
#include "VkMemory.h"
#include "rill/Error.h"
#include "rill/Stopwatch.h"
#include "rill/ir/FlushModel.h"

namespace rill::vk {

namespace {

// SPIR-V execution modes and capabilities of SPV_KHR_float_controls.
constexpr int kDenormPreserve = 4459, kDenormFlushToZero = 4460, kSignedZeroInfNanPreserve = 4461,
              kRoundingModeRTE = 4462;
constexpr int kCapDenormPreserve = 4464, kCapDenormFlushToZero = 4465,
              kCapSignedZeroInfNanPreserve = 4466, kCapRoundingModeRTE = 4467;

std::string execution_mode(int mode, int capability) {
  return "spirv_execution_mode(extensions = [\"SPV_KHR_float_controls\"], capabilities = [" +
         std::to_string(capability) + "], " + std::to_string(mode) + ", 32);\n";
}

// A compute pipeline (and its layout) over `bindings` storage buffers of set 0.
// `uniform_binding` (-1: none) is a uniform buffer.
void make_pipeline(Context& c, const std::vector<uint32_t>& spirv, int bindings,
                   VkPipelineCache cache, VulkanKernel::Pass& p, const std::string& what,
                   int uniform_binding = -1) {
  auto mi = make<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
  mi.codeSize = spirv.size() * 4;
  mi.pCode = spirv.data();
  check(c.api.vkCreateShaderModule(c.device, &mi, nullptr, &p.module),
        "creating the shader module of " + what);
  std::vector<VkDescriptorSetLayoutBinding> b(static_cast<size_t>(bindings));
  for (int i = 0; i < bindings; ++i)
    b[static_cast<size_t>(i)] = {static_cast<uint32_t>(i),
                                 i == uniform_binding ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER
                                                      : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  auto li =
      make<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
  li.bindingCount = static_cast<uint32_t>(b.size());
  li.pBindings = b.data();
  check(c.api.vkCreateDescriptorSetLayout(c.device, &li, nullptr, &p.set_layout),
        "creating the descriptor set layout of " + what);
  auto pl = make<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
  pl.setLayoutCount = 1;
  pl.pSetLayouts = &p.set_layout;
  check(c.api.vkCreatePipelineLayout(c.device, &pl, nullptr, &p.layout),
        "creating the pipeline layout of " + what);
  auto ci = make<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
  ci.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  ci.stage.module = p.module;
  ci.stage.pName = "main";
  ci.layout = p.layout;
  check(c.api.vkCreateComputePipelines(c.device, cache, 1, &ci, nullptr, &p.pipeline),
        "creating the compute pipeline of " + what + " (vkCreateComputePipelines)");
  p.bindings = bindings;
}

constexpr uint32_t kSpirvMagic = 0x07230203;

// Whether pipeline cache data (from the disk cache) has the header vkGetPipelineCacheData
// writes for this device: Vulkan asks for data that came from this device's driver, so data
// that does not (an entry forged or damaged past the checksum) is dropped here, and the
// pipelines are then made from the SPIR-V alone.
bool pipeline_cache_fits(const std::string& data, const DeviceInfo& d) {
  VkPipelineCacheHeaderVersionOne h{};
  if (data.size() < sizeof h) return false;
  std::memcpy(&h, data.data(), sizeof h);
  return h.headerSize >= sizeof h && h.headerSize <= data.size() &&
         h.headerVersion == VK_PIPELINE_CACHE_HEADER_VERSION_ONE && h.vendorID == d.vendor &&
         h.deviceID == d.device_id && hex(h.pipelineCacheUUID, VK_UUID_SIZE) == d.uuid;
}

// The disk cache's payload: the number of passes, each pass's SPIR-V (word count, words),
// then the driver's pipeline cache data to the end.
std::string pack(const std::vector<std::vector<uint32_t>>& modules, const std::string& cache) {
  std::string out;
  auto put = [&](const void* p, size_t n) { out.append(static_cast<const char*>(p), n); };
  const uint32_t n = static_cast<uint32_t>(modules.size());
  put(&n, 4);
  for (const auto& m : modules) {
    const uint32_t words = static_cast<uint32_t>(m.size());
    put(&words, 4);
    put(m.data(), m.size() * 4);
  }
  return out + cache;
}

// Unpacks pack()'s payload for `passes` passes; nullopt when it does not fit.
std::optional<std::pair<std::vector<std::vector<uint32_t>>, std::string>> unpack(
    const std::string& payload, size_t passes) {
  size_t at = 0;
  auto get = [&](void* p, size_t n) {
    if (payload.size() - at < n) return false;
    std::memcpy(p, payload.data() + at, n);
    at += n;
    return true;
  };
  uint32_t n = 0;
  if (!get(&n, 4) || n != passes) return std::nullopt;
  std::vector<std::vector<uint32_t>> modules(n);
  for (auto& m : modules) {
    uint32_t words = 0;
    if (!get(&words, 4) || words > (payload.size() - at) / 4 || words < 5) return std::nullopt;
    m.resize(words);
    get(m.data(), words * 4);
    if (m[0] != kSpirvMagic) return std::nullopt;  // a module's first word and header
  }
  return std::make_pair(std::move(modules), payload.substr(at));
}

class VulkanBackend : public Backend, public glsl::SessionOwner {
 public:
  ~VulkanBackend() override {
    glsl::forget_at_exit(this);
    shutdown();
  }

  std::string name() const override { return kName; }

  std::string unavailable_reason() const override {
    try {
      const_cast<VulkanBackend*>(this)->context();
      return {};
    } catch (const Error& e) {
      return e.what();
    }
  }

  bool runs_on_gpu() const override {
    if (!unavailable_reason().empty()) return false;
    const VkPhysicalDeviceType t = session_->context->info.type;
    return t == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU ||
           t == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU || t == VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU;
  }

  std::string driver_label() const override {
    if (!unavailable_reason().empty()) return {};
    const std::string& n = session_->context->info.name;
    return n.substr(0, n.find(" ("));
  }

  std::string description() const override {
    std::string why = unavailable_reason();
    if (!why.empty()) return std::string(kName) + ": unavailable: " + why;
    const DeviceInfo& d = session_->context->info;
    auto version = [](uint32_t v) {
      return std::to_string(VK_API_VERSION_MAJOR(v)) + "." +
             std::to_string(VK_API_VERSION_MINOR(v));
    };
    std::string modes;
    if (d.signed_zero_inf_nan) modes += "signed zeros/inf/NaN preserved, ";
    if (d.denorm_preserve) modes += "denormals preserved, ";
    if (d.rte) modes += "round to nearest even, ";
    modes = modes.empty() ? "none offered" : modes.substr(0, modes.size() - 2);
    return std::string(kName) + ": compute shaders (SPIR-V by " + spirv_compiler_version() + "); " +
           d.name + " (" + device_type_name(d.type) + "), " + d.driver + ", Vulkan " +
           version(d.api) + "; strict / and sqrt: " +
           glsl::divsqrt_description(rules_.divsqrt, rules_.fused_fma, rules_.lean) +
           ", comparisons: " + glsl::compare_name(rules_.native_compare) +
           "; float controls: " + modes + "; denormals: " + denormals_ + "; lane groups: " +
           (rules_.subgroups ? "subgroups of " + std::to_string(d.subgroup_size)
                             : std::string("one element") +
                                   (d.group_ops ? " (RILL_VULKAN_SUBGROUPS=off)"
                                                : " (the device lacks subgroup operations)")) +
           "; " + std::to_string(d.limits.maxPerStageDescriptorStorageBuffers) +
           " storage buffers; memory: " + memory_description(d) + "; parameters: " +
           (setup_.params_uniform ? "uniform buffer (RILL_VULKAN_PARAMS=uniform)"
                                  : "storage buffer") +
           "; validation: " + (session_->context->validation ? "on" : "off") +
           "; disk cache: SPIR-V and the driver's pipeline cache";
  }

  // Where streams live and how they move (RILL_VULKAN_MEMORY, VkContext.h).
  static std::string memory_description(const DeviceInfo& d) {
    const std::string mode =
        d.memory_mode == "auto" ? "" : "RILL_VULKAN_MEMORY=" + d.memory_mode + ": ";
    if (d.memory_mode == "mapped")
      return mode + "streams in " +
             (d.memory_device_local ? "device-local, host-visible" : "host-visible") +
             " memory, read through the mapping";
    return mode + "streams device-local, " +
           (d.streams_mapped ? "written through the mapping" : "written through a staging copy") +
           ", " +
           (d.streams_cached ? "read through the mapping (host-cached)"
                             : std::string("read through a staging copy (") +
                                   (d.readback_cached ? "host-cached" : "host-visible") + ")");
  }

  std::unique_ptr<CompiledKernel> compile(const ir::Function& f, const CompileOptions& o) override {
    std::lock_guard<std::recursive_mutex> lock(session_->mutex);
    Context& c = context();
    if (o.accuracy == Accuracy::Double)
      throw Error(std::string(kWho) +
                  ": accuracy mode 'double' is not supported (GLSL kernels compute in binary32)");
    // Bindings left for outputs after the inputs, the arrays, the counters, the mask and the
    // parameters; more outputs than that run in several passes.
    const int limit = static_cast<int>(std::min(c.info.limits.maxPerStageDescriptorStorageBuffers,
                                                c.info.limits.maxDescriptorSetStorageBuffers));
    const int fixed = static_cast<int>(f.inputs.size() + f.arrays.size()) + 3;
    const int group = limit - fixed;
    if (group < 1)
      throw Error(std::string(kWho) + ": kernel '" + f.name + "' reads " +
                  std::to_string(f.inputs.size()) + " input streams and " +
                  std::to_string(f.arrays.size()) + " arrays, but the device (" + c.info.name +
                  ") allows " + std::to_string(limit) +
                  " storage buffers per shader (maxPerStageDescriptorStorageBuffers), three of "
                  "which Rill needs for counts, masks and parameters");
    glsl::VulkanTarget target;
    target.ballot = c.info.ballot;
    target.params_uniform = setup_.params_uniform;
    if (o.accuracy != Accuracy::Fast) target.execution_modes = float_modes_;
    Stopwatch stage;
    double codegen_ms = 0, compile_ms = 0;
    // Strict kernels on a device that keeps some denormals: every arithmetic operation
    // flushes its operands and result in the kernel itself (rill/ir/FlushModel.h).
    ir::Function flushed;
    if (emulate_flush_ && o.accuracy != Accuracy::Fast) flushed = ir::flush_model(f);
    const ir::Function& g = emulate_flush_ && o.accuracy != Accuracy::Fast ? flushed : f;
    std::vector<VulkanKernel::Pass> passes;
    std::vector<std::string> sources;
    std::string source;
    for (size_t first = 0; first < std::max<size_t>(1, f.outputs.size());
         first += static_cast<size_t>(group)) {
      VulkanKernel::Pass p;
      for (size_t k = first; k < std::min(f.outputs.size(), first + static_cast<size_t>(group));
           ++k)
        p.outputs.push_back(static_cast<int>(k));
      glsl::GLSLShader shader =
          glsl::emit_glsl_compute(g, o.accuracy, p.outputs, passes.empty(), rules_,
                                  flushes_denormals_, setup_.local_size, &target, o.source_map);
      p.constants = std::move(shader.constants);
      p.bindings = fixed + static_cast<int>(p.outputs.size());
      source += shader.source;
      sources.push_back(std::move(shader.source));
      passes.push_back(std::move(p));
    }
    codegen_ms += stage.lap();
    // SPIR-V from the disk cache, or from glslang.
    const std::string key =
        "backend=vulkan\ndevice=" + c.info.name + "\ndriver=" + c.info.driver + " (" +
        std::to_string(c.info.driver_version) + ")\npipeline-cache=" + c.info.uuid +
        "\ncompiler=" + spirv_compiler_version() + "\n" + cache::source_line(source);
    std::optional<std::pair<std::vector<std::vector<uint32_t>>, std::string>> cached;
    if (auto payload = cache::load(kName, key)) {
      cached = unpack(*payload, passes.size());
      if (!cached) cache::remove(kName, key);
    }
    std::vector<std::vector<uint32_t>> modules;
    if (cached) {
      modules = std::move(cached->first);
    } else {
      for (size_t i = 0; i < passes.size(); ++i)
        modules.push_back(compile_compute_spirv(sources[i], f.name, setup_.params_uniform));
    }
    auto pci = make<VkPipelineCacheCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO);
    // An entry whose driver data does not fit is stored again with the driver's own.
    const bool fits = cached && pipeline_cache_fits(cached->second, c.info);
    if (fits) {
      pci.initialDataSize = cached->second.size();
      pci.pInitialData = cached->second.data();
    }
    VkPipelineCache pcache = VK_NULL_HANDLE;
    check(c.api.vkCreatePipelineCache(c.device, &pci, nullptr, &pcache),
          "creating a pipeline cache");
    VkDescriptorPool pool = VK_NULL_HANDLE;
    try {
      int descriptors = 0;
      for (size_t i = 0; i < passes.size(); ++i) {
        make_pipeline(
            c, modules[i], passes[i].bindings, pcache, passes[i], "kernel '" + f.name + "'",
            setup_.params_uniform ? glsl::compute_bindings(f, passes[i].outputs.size()).params
                                  : -1);
        descriptors += passes[i].bindings;
      }
      if (!fits) {
        size_t n = 0;
        std::string data;
        if (c.api.vkGetPipelineCacheData(c.device, pcache, &n, nullptr) == VK_SUCCESS) {
          data.resize(n);
          if (c.api.vkGetPipelineCacheData(c.device, pcache, &n, data.data()) != VK_SUCCESS) n = 0;
          data.resize(n);
        }
        cache::store(kName, key, pack(modules, data));
      }
      const uint32_t uniforms = setup_.params_uniform ? static_cast<uint32_t>(passes.size()) : 0;
      VkDescriptorPoolSize sizes[2] = {
          {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, static_cast<uint32_t>(descriptors) - uniforms},
          {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, uniforms}};
      auto di = make<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
      di.maxSets = static_cast<uint32_t>(passes.size());
      di.poolSizeCount = uniforms ? 2 : 1;
      di.pPoolSizes = sizes;
      check(c.api.vkCreateDescriptorPool(c.device, &di, nullptr, &pool),
            "creating a descriptor pool");
      for (auto& p : passes) {
        auto ai = make<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
        ai.descriptorPool = pool;
        ai.descriptorSetCount = 1;
        ai.pSetLayouts = &p.set_layout;
        check(c.api.vkAllocateDescriptorSets(c.device, &ai, &p.set), "allocating a descriptor set");
      }
      c.api.vkDestroyPipelineCache(c.device, pcache, nullptr);
      c.check_validation("compiling kernel '" + f.name + "'");
    } catch (...) {
      c.api.vkDestroyPipelineCache(c.device, pcache, nullptr);
      for (auto& p : passes) destroy_pass(c, p);
      if (pool) c.api.vkDestroyDescriptorPool(c.device, pool, nullptr);
      throw;
    }
    compile_ms += stage.lap();
    auto kernel = std::make_unique<VulkanKernel>(*this, session_, setup_, f, std::move(passes),
                                                 pool, std::move(source));
    kernel->set_origin(cached ? KernelOrigin::DiskCache : KernelOrigin::Built);
    kernel->set_build_times(codegen_ms, compile_ms);
    return kernel;
  }

  void read_back(const detail::Storage& s, uint32_t* host) override {
    std::lock_guard<std::recursive_mutex> lock(session_->mutex);
    vk::read_back(*this, session_, staging_, s, host);
  }

  // Frees the counter buffer and destroys the device and instance (at exit, before the
  // driver's own exit handlers; see glsl/GLSession.h for why).
  void shutdown() noexcept override {
    std::lock_guard<std::recursive_mutex> lock(session_->mutex);
    counter_.reset();
    staging_.up.reset();
    staging_.down.reset();
    session_->shut_down();
  }

 private:
  // The device, made at the first call; an Error on the way is kept for every later call.
  Context& context() {
    std::lock_guard<std::recursive_mutex> lock(session_->mutex);
    if (session_->context) return *session_->context;
    if (!init_error_.empty()) throw Error(init_error_);
    if (started_)
      throw Error(std::string(kWho) + ": the device was shut down (the process is exiting)");
    try {
      session_->context = std::make_unique<Context>();
      started_ = true;
      glsl::shut_down_at_exit(this);  // after the driver loaded: runs before its exit handlers
      set_up(*session_->context);
    } catch (const Error& e) {
      init_error_ = e.what();
      counter_.reset();
      session_->context.reset();
      throw;
    }
    return *session_->context;
  }

  void set_up(Context& c) {
    const DeviceInfo& d = c.info;
    rules_.divsqrt = glsl::divsqrt_mode(d.name);
    rules_.native_compare = glsl::native_compare_mode(d.name);
    rules_.loop_guard = glsl::loop_guard_mode(d.name);
    const int most = static_cast<int>(std::min<uint32_t>(d.limits.maxComputeWorkGroupInvocations,
                                                         d.limits.maxComputeWorkGroupSize[0]));
    if (const char* size = std::getenv("RILL_VULKAN_LOCAL_SIZE"))  // for measuring
      setup_.local_size = std::clamp(std::atoi(size), 1, most);
    setup_.local_size = std::min(setup_.local_size, most);
    setup_.loop_guard = rules_.loop_guard;
    // RILL_VULKAN_SUBGROUPS = on (default) | off: lane groups as subgroups where the device
    // has the operations, or a group of one (both pass the group tests).
    rules_.subgroups = d.group_ops;
    if (const char* g = std::getenv("RILL_VULKAN_SUBGROUPS"); g && *g) {
      const std::string v = g;
      if (v != "on" && v != "off")
        throw Error("RILL_VULKAN_SUBGROUPS='" + v + "' is not one of on, off");
      rules_.subgroups = rules_.subgroups && v == "on";
    }
    counter_ = make_buffer(session_, 16, "the launch counters");
    setup_.counter = counter_.get();
    setup_.staging = &staging_;
    // RILL_VULKAN_PARAMS = storage (default) | uniform: the launch parameters and strict
    // constants in a read-only storage buffer, or a uniform buffer (which drivers may keep in
    // a constant cache, as GL's uniforms), for measuring.
    if (const char* pu = std::getenv("RILL_VULKAN_PARAMS"); pu && *pu) {
      const std::string v = pu;
      if (v != "storage" && v != "uniform")
        throw Error("RILL_VULKAN_PARAMS='" + v + "' is not one of storage, uniform");
      if (v == "uniform" && !d.scalar_layout)
        throw Error(std::string(kWho) + ": RILL_VULKAN_PARAMS=uniform needs scalarBlockLayout " +
                    "(Vulkan 1.2), which " + d.name + " does not offer");
      setup_.params_uniform = v == "uniform";
    }
    choose_denormals(c);
    // The corrections' residual by one fma where the device's fma is fused (RILL_GLSL_FMA, else
    // probed as on the glsl backends); probed only where the corrections run.
    const std::optional<bool> fused = glsl::fused_fma_mode();
    rules_.fused_fma =
        fused ? *fused
              : glsl::divsqrt_corrects(rules_.divsqrt) &&
                    glsl::fma_probe_fused(run_probe(c, "rill_fma_probe", glsl::kFmaProbeBody,
                                                    glsl::fma_probe_data()));
    rules_.lean = glsl::lean_fused_mode();
    c.check_validation("setting up the device");
  }

  // The strict kernels' execution modes: signed zeros, infinities and NaN preserved and
  // round to nearest even where offered, plus `denorm_mode` (DenormPreserve,
  // DenormFlushToZero or none: 0), each where the device offers it.
  static std::string modes(const DeviceInfo& d, int denorm_mode) {
    std::string m;
    if (d.signed_zero_inf_nan)
      m += execution_mode(kSignedZeroInfNanPreserve, kCapSignedZeroInfNanPreserve);
    if (denorm_mode == kDenormPreserve) m += execution_mode(kDenormPreserve, kCapDenormPreserve);
    if (denorm_mode == kDenormFlushToZero)
      m += execution_mode(kDenormFlushToZero, kCapDenormFlushToZero);
    if (d.rte) m += execution_mode(kRoundingModeRTE, kCapRoundingModeRTE);
    return m.empty() ? m : "#extension GL_EXT_spirv_intrinsics : require\n" + m;
  }

  // What the device's arithmetic does with denormals under float_modes_: each probed
  // operation, and whether it kept them. A device may flush in some instructions and not in
  // others (NVIDIA's Vulkan driver without a denormal mode keeps them in mul and add but
  // flushes them in abs, min, comparisons and sqrt), so several are probed.
  struct DenormalProbe {
    std::vector<std::pair<std::string, bool>> ops;  // name, kept
    bool all(bool kept) const {
      return std::all_of(ops.begin(), ops.end(),
                         [kept](const auto& o) { return o.second == kept; });
    }
    // "mul, add keep them, min, lt, sqrt flush them", "all keep them"
    std::string text() const {
      if (all(true)) return "all keep them";
      if (all(false)) return "all flush them";
      std::string keep, flush;
      for (const auto& o : ops) {
        std::string& list = o.second ? keep : flush;
        list += (list.empty() ? "" : ", ") + o.first;
      }
      return keep + " keep them, " + flush + " flush them";
    }
  };
  DenormalProbe probe_denormals(Context& c) {
    const float d = std::numeric_limits<float>::denorm_min();
    const std::vector<float> out = run_probe(c, "rill_denormal_probe",
                                             "  precise float m = b.v[0] * b.v[1];\n"
                                             "  b.v[4] = m;\n"
                                             "  precise float a = b.v[0] + b.v[2];\n"
                                             "  b.v[5] = a;\n"
                                             "  b.v[6] = min(b.v[2], b.v[3]);\n"
                                             "  b.v[7] = b.v[2] < b.v[0] ? 1.0 : 0.0;\n"
                                             "  precise float r = sqrt(b.v[0]);\n"
                                             "  b.v[8] = r;\n",
                                             {d, 2.0f, 0.0f, -d, 0, 0, 0, 0, 0});
    // On bits: a host with denormals-are-zero set would read a kept one as zero.
    auto bits = [&](size_t i) {
      uint32_t b;
      std::memcpy(&b, &out[i], sizeof b);
      return b;
    };
    DenormalProbe p;
    p.ops = {{"mul", (bits(4) & 0x7fffffffu) != 0},
             {"add", (bits(5) & 0x7fffffffu) != 0},
             {"min", bits(6) == bits(3)},
             {"lt", out[7] == 1.0f},
             {"sqrt", (bits(8) & 0x7fffffffu) != 0}};
    return p;
  }

  // How strict kernels treat denormals (RILL_VULKAN_DENORMALS = auto | flush | emulate):
  // kept where every probed operation keeps them under DenormPreserve (where offered, else no
  // denormal mode); else flushed, by the device under DenormFlushToZero where every probed
  // operation then flushes them, else by the kernels themselves (emulate_flush_). `flush`
  // skips the first probe, `emulate` both. Flushed, comparisons treat denormals as zeros (as
  // on glsl-compute) and the conformance suite compares with the denormal rule.
  void choose_denormals(Context& c) {
    const DeviceInfo& d = c.info;
    std::string want = "auto";
    if (const char* e = std::getenv("RILL_VULKAN_DENORMALS"); e && *e) want = e;
    if (want != "auto" && want != "flush" && want != "emulate")
      throw Error("RILL_VULKAN_DENORMALS='" + want + "' is not one of auto, flush, emulate");
    const int keep_mode = d.denorm_preserve ? kDenormPreserve : 0;
    const std::string keep_name = d.denorm_preserve ? "DenormPreserve" : "no denormal mode";
    const std::string keep_modes = modes(d, keep_mode);
    float_modes_ = keep_modes;
    const DenormalProbe kept = probe_denormals(c);
    const std::string probed = "probed with " + keep_name + ": " + kept.text();
    emulate_flush_ = false;
    flushes_denormals_ = false;
    if (want == "auto" && kept.all(true)) {
      denormals_ = "kept (" + probed + ")";
      return;
    }
    const std::string forced = want == "auto" ? "" : "RILL_VULKAN_DENORMALS=" + want + "; ";
    flushes_denormals_ = true;
    if (want != "emulate" && d.denorm_flush) {
      float_modes_ = modes(d, kDenormFlushToZero);
      const DenormalProbe ftz = probe_denormals(c);
      if (ftz.all(false)) {
        denormals_ = "flushed by DenormFlushToZero (" + forced + probed +
                     "; with DenormFlushToZero: " + ftz.text() + ")";
        return;
      }
      denormals_ = "flushed by the kernels (" + forced + probed +
                   "; with DenormFlushToZero: " + ftz.text() + ")";
    } else {
      denormals_ = "flushed by the kernels (" + forced + probed +
                   (d.denorm_flush ? "" : "; DenormFlushToZero not offered") + ")";
    }
    // The kernels flush every operation's operands and results; the device's own arithmetic
    // runs as in the first probe (helpers' intermediate values then round as on the host).
    float_modes_ = keep_modes;
    emulate_flush_ = true;
  }

  // Runs `main_body` (GLSL statements over `buffer B { float v[]; } b`) in one invocation
  // under the strict kernels' execution modes, on `data`; returns the buffer afterwards.
  // `what` names the probe in errors. The glsl backends' probes (glsl/DriverProbes.h) in
  // Vulkan.
  std::vector<float> run_probe(Context& c, const std::string& what, const std::string& main_body,
                               std::vector<float> data) {
    const std::string glsl = "#version 450\n" + float_modes_ +
                             "layout(local_size_x = 1) in;\n"
                             "layout(std430, set = 0, binding = 0) buffer B { float v[]; } b;\n"
                             "void main() {\n" +
                             main_body + "}\n";
    const std::vector<uint32_t> spirv = compile_compute_spirv(glsl, what);
    VulkanKernel::Pass p;
    const size_t bytes = data.size() * sizeof(float);
    std::unique_ptr<Buffer> buf =
        make_buffer(session_, static_cast<int64_t>(bytes), "the probe " + what);
    std::memcpy(buf->mapped, data.data(), bytes);
    VkDescriptorPool pool = VK_NULL_HANDLE;
    try {
      make_pipeline(c, spirv, 1, VK_NULL_HANDLE, p, "the probe " + what);
      VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
      auto di = make<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
      di.maxSets = 1;
      di.poolSizeCount = 1;
      di.pPoolSizes = &size;
      check(c.api.vkCreateDescriptorPool(c.device, &di, nullptr, &pool),
            "creating a descriptor pool");
      auto ai = make<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
      ai.descriptorPool = pool;
      ai.descriptorSetCount = 1;
      ai.pSetLayouts = &p.set_layout;
      VkDescriptorSet set = VK_NULL_HANDLE;
      check(c.api.vkAllocateDescriptorSets(c.device, &ai, &set), "allocating a descriptor set");
      VkDescriptorBufferInfo bi{buf->buf, 0, VK_WHOLE_SIZE};
      auto w = make<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
      w.dstSet = set;
      w.descriptorCount = 1;
      w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
      w.pBufferInfo = &bi;
      c.api.vkUpdateDescriptorSets(c.device, 1, &w, 0, nullptr);
      auto begin = make<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
      begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
      check(c.api.vkResetCommandBuffer(c.commands, 0), "resetting the command buffer");
      check(c.api.vkBeginCommandBuffer(c.commands, &begin), "recording the probe " + what);
      c.api.vkCmdBindPipeline(c.commands, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipeline);
      c.api.vkCmdBindDescriptorSets(c.commands, VK_PIPELINE_BIND_POINT_COMPUTE, p.layout, 0, 1,
                                    &set, 0, nullptr);
      c.api.vkCmdDispatch(c.commands, 1, 1, 1);
      auto to_host = make<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
      to_host.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
      to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
      c.api.vkCmdPipelineBarrier(c.commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                                 VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0, nullptr, 0,
                                 nullptr);
      check(c.api.vkEndCommandBuffer(c.commands), "recording the probe " + what);
      c.submit_and_wait("running the probe " + what);
      std::memcpy(data.data(), buf->mapped, bytes);
    } catch (...) {
      destroy_pass(c, p);
      if (pool) c.api.vkDestroyDescriptorPool(c.device, pool, nullptr);
      throw;
    }
    destroy_pass(c, p);
    c.api.vkDestroyDescriptorPool(c.device, pool, nullptr);
    return data;
  }

  std::shared_ptr<Session> session_ = std::make_shared<Session>();
  std::string init_error_;
  bool started_ = false;
  glsl::DriverRules rules_;
  bool flushes_denormals_ = true;  // strict kernels flush denormals (choose_denormals())
  bool emulate_flush_ = false;     // ... in the kernels themselves (rill/ir/FlushModel.h)
  std::string denormals_;          // how, for description()
  std::string float_modes_;        // the strict kernels' execution-mode lines
  std::unique_ptr<Buffer> counter_;
  Staging staging_;
  LaunchSetup setup_;
};

}  // namespace

std::unique_ptr<Backend> make_backend() {
  return std::make_unique<VulkanBackend>();
}

std::vector<std::string> device_lines() {
  const DeviceListing l = list_devices();
  std::vector<std::string> lines;
  if (l.devices.empty()) return lines;
  lines.push_back("Vulkan devices (choose with RILL_VULKAN_DEVICE=N or a name fragment):");
  for (size_t i = 0; i < l.devices.size(); ++i) {
    const DeviceSummary& d = l.devices[i];
    std::string line = std::to_string(i) + "  " + d.name + "  " + device_type_name(d.type) +
                       "  Vulkan " + std::to_string(VK_API_VERSION_MAJOR(d.api)) + "." +
                       std::to_string(VK_API_VERSION_MINOR(d.api)) + "." +
                       std::to_string(VK_API_VERSION_PATCH(d.api));
    if (d.subgroup_size) line += "  subgroups of " + std::to_string(d.subgroup_size);
    if (static_cast<int>(i) == l.chosen) line += "  <- used: " + l.why;
    lines.push_back(line);
  }
  if (!l.error.empty()) lines.push_back("none used: " + l.error);
  return lines;
}

}  // namespace rill::vk
