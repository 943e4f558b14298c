// The vulkan backend's instance, device and queue (VkContext.h).
#include "VkContext.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <utility>

#include "rill/Error.h"

namespace rill::vk {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string version_text(uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
         "." + std::to_string(VK_API_VERSION_PATCH(v));
}

// RILL_VULKAN_VALIDATION = 1|on: enable the validation layer in the instance. The layer may
// also come from VK_INSTANCE_LAYERS; either way its messages are reported.
bool validation_asked() {
  const char* v = std::getenv("RILL_VULKAN_VALIDATION");
  if (!v || !*v) return false;
  const std::string s = v;
  if (s == "1" || s == "on") return true;
  if (s == "0" || s == "off") return false;
  throw Error("RILL_VULKAN_VALIDATION='" + s + "' is not one of on, off, 1, 0");
}

bool layer_in_environment() {
  const char* v = std::getenv("VK_INSTANCE_LAYERS");
  return v && std::strstr(v, kValidationLayer) != nullptr;
}

VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                          VkDebugUtilsMessageTypeFlagsEXT,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data,
                                          void* context) {
  static_cast<Context*>(context)->report(data && data->pMessage ? data->pMessage : "(no text)");
  return VK_FALSE;
}

// The device RILL_VULKAN_DEVICE names (an index as rill-info lists them, or a fragment of the
// name, case-insensitive), else the first discrete GPU, else integrated, virtual, CPU, other;
// with the reason, for rill-info. Throws Error for a name or index that matches none.
std::pair<int, std::string> pick_device(const std::vector<VkPhysicalDeviceProperties>& props,
                                        const std::string& names) {
  const long n = static_cast<long>(props.size());
  const char* env = std::getenv("RILL_VULKAN_DEVICE");
  if (env && *env) {
    const std::string want = env;
    char* end = nullptr;
    const long index = std::strtol(env, &end, 10);
    if (end && *end == '\0') {
      if (index < 0 || index >= n)
        throw Error("RILL_VULKAN_DEVICE=" + want + ": there are " + std::to_string(n) +
                    " Vulkan devices (" + names + ")");
      return {static_cast<int>(index), "RILL_VULKAN_DEVICE=" + want};
    }
    for (long i = 0; i < n; ++i)
      if (lower(props[static_cast<size_t>(i)].deviceName).find(lower(want)) != std::string::npos)
        return {static_cast<int>(i),
                "RILL_VULKAN_DEVICE='" + want + "', the first name it matches"};
    throw Error("RILL_VULKAN_DEVICE='" + want + "' names none of the Vulkan devices (" + names +
                ")");
  }
  for (VkPhysicalDeviceType t :
       {VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU,
        VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU, VK_PHYSICAL_DEVICE_TYPE_CPU,
        VK_PHYSICAL_DEVICE_TYPE_OTHER})
    for (long i = 0; i < n; ++i)
      if (props[static_cast<size_t>(i)].deviceType == t)
        return {static_cast<int>(i),
                std::string("the first ") + device_type_name(t) + " (GPUs before CPU devices)"};
  return {0, "the first device"};
}

}  // namespace

std::string hex(const uint8_t* bytes, size_t n) {
  std::string out;
  char digits[3];
  for (size_t i = 0; i < n; ++i) {
    std::snprintf(digits, sizeof digits, "%02x", bytes[i]);
    out += digits;
  }
  return out;
}

const char* device_type_name(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return "CPU";
    default:
      return "other";
  }
}

Context::Context() {
  api.load_loader();
  uint32_t loader = VK_API_VERSION_1_0;
  if (api.vkEnumerateInstanceVersion) api.vkEnumerateInstanceVersion(&loader);
  if (loader < VK_API_VERSION_1_1)
    throw Error(std::string(kWho) + ": the Vulkan loader offers Vulkan " + version_text(loader) +
                "; Rill needs 1.1");
  validation = validation_asked() || layer_in_environment();
  std::vector<const char*> layers, extensions;
  if (validation) {
    uint32_t n = 0;
    api.vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> have(n);
    api.vkEnumerateInstanceLayerProperties(&n, have.data());
    const bool found = std::any_of(have.begin(), have.end(), [](const VkLayerProperties& l) {
      return std::strcmp(l.layerName, kValidationLayer) == 0;
    });
    if (!found)
      throw Error(std::string(kWho) +
                  ": validation was asked for (RILL_VULKAN_VALIDATION or "
                  "VK_INSTANCE_LAYERS) but the layer " +
                  kValidationLayer +
                  " is not installed (Debian: apt-get install vulkan-validationlayers)");
    if (validation_asked()) layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  auto app = make<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
  app.pApplicationName = "rill";
  app.pEngineName = "rill";
  app.apiVersion = VK_API_VERSION_1_2;  // the most Rill uses; a 1.1 device still serves
  auto ci = make<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
  ci.pApplicationInfo = &app;
  ci.enabledLayerCount = static_cast<uint32_t>(layers.size());
  ci.ppEnabledLayerNames = layers.data();
  ci.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  ci.ppEnabledExtensionNames = extensions.data();
  VkResult r = api.vkCreateInstance(&ci, nullptr, &instance);
  if (r == VK_ERROR_INCOMPATIBLE_DRIVER)
    throw Error(std::string(kWho) +
                ": no Vulkan driver (ICD) is installed or none loads (vkCreateInstance: "
                "VK_ERROR_INCOMPATIBLE_DRIVER); install one (Debian: mesa-vulkan-drivers) or "
                "check VK_ICD_FILENAMES / VK_DRIVER_FILES");
  check(r, "creating the Vulkan instance (vkCreateInstance)");
  try {
    api.load_instance(instance);
    if (validation) {
      if (!api.vkCreateDebugUtilsMessengerEXT)
        throw Error(std::string(kWho) + ": the instance lacks vkCreateDebugUtilsMessengerEXT");
      auto m = make<VkDebugUtilsMessengerCreateInfoEXT>(
          VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
      m.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                          VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
      m.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                      VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT;
      m.pfnUserCallback = on_message;
      m.pUserData = this;
      check(api.vkCreateDebugUtilsMessengerEXT(instance, &m, nullptr, &messenger_),
            "registering for validation messages");
    }
    choose_device();
    describe_device();
    make_device();
  } catch (...) {
    release();  // the destructor does not run for a constructor that throws
    throw;
  }
}

Context::~Context() {
  release();
}

void Context::release() noexcept {
  if (device) {
    api.vkDeviceWaitIdle(device);
    if (timer) api.vkDestroyQueryPool(device, timer, nullptr);
    if (fence) api.vkDestroyFence(device, fence, nullptr);
    if (pool) api.vkDestroyCommandPool(device, pool, nullptr);
    api.vkDestroyDevice(device, nullptr);
    device = VK_NULL_HANDLE;
  }
  if (messenger_ && api.vkDestroyDebugUtilsMessengerEXT)
    api.vkDestroyDebugUtilsMessengerEXT(instance, messenger_, nullptr);
  messenger_ = VK_NULL_HANDLE;
  if (instance) api.vkDestroyInstance(instance, nullptr);
  instance = VK_NULL_HANDLE;
}

// The device pick_device() names.
void Context::choose_device() {
  uint32_t n = 0;
  check(api.vkEnumeratePhysicalDevices(instance, &n, nullptr), "listing Vulkan devices");
  std::vector<VkPhysicalDevice> all(n);
  if (n) check(api.vkEnumeratePhysicalDevices(instance, &n, all.data()), "listing Vulkan devices");
  if (all.empty())
    throw Error(std::string(kWho) +
                ": the Vulkan loader found no device (no driver, or "
                "VK_ICD_FILENAMES / VK_DRIVER_FILES names none that loads)");
  std::vector<VkPhysicalDeviceProperties> props(n);
  std::string names;
  for (uint32_t i = 0; i < n; ++i) {
    api.vkGetPhysicalDeviceProperties(all[i], &props[i]);
    names += (i ? ", " : "") + std::to_string(i) + ": " + props[i].deviceName;
  }
  const int chosen = pick_device(props, names).first;
  physical = all[static_cast<size_t>(chosen)];
  const VkPhysicalDeviceProperties& p = props[static_cast<size_t>(chosen)];
  if (p.apiVersion < VK_API_VERSION_1_1)
    throw Error(std::string(kWho) + ": the Vulkan device '" + p.deviceName + "' offers Vulkan " +
                version_text(p.apiVersion) + "; Rill needs 1.1 (SPIR-V 1.3)");
}

void Context::describe_device() {
  auto sub = make<VkPhysicalDeviceSubgroupProperties>(
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES);
  auto drv =
      make<VkPhysicalDeviceDriverProperties>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES);
  auto fc = make<VkPhysicalDeviceFloatControlsProperties>(
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FLOAT_CONTROLS_PROPERTIES);
  auto p2 = make<VkPhysicalDeviceProperties2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2);
  // Driver and float-controls properties are Vulkan 1.2 (or their extensions): chained only
  // where the device has them.
  uint32_t n = 0;
  api.vkEnumerateDeviceExtensionProperties(physical, nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> ext(n);
  api.vkEnumerateDeviceExtensionProperties(physical, nullptr, &n, ext.data());
  auto has = [&](const char* e) {
    return std::any_of(ext.begin(), ext.end(), [&](const VkExtensionProperties& x) {
      return std::strcmp(x.extensionName, e) == 0;
    });
  };
  VkPhysicalDeviceProperties base{};
  api.vkGetPhysicalDeviceProperties(physical, &base);
  const bool v12 = base.apiVersion >= VK_API_VERSION_1_2;
  p2.pNext = &sub;
  void** tail = &sub.pNext;
  if (v12 || has(VK_KHR_DRIVER_PROPERTIES_EXTENSION_NAME)) {
    *tail = &drv;
    tail = &drv.pNext;
  }
  info.float_controls = v12 || has(VK_KHR_SHADER_FLOAT_CONTROLS_EXTENSION_NAME);
  if (info.float_controls) *tail = &fc;
  api.vkGetPhysicalDeviceProperties2(physical, &p2);
  const VkPhysicalDeviceProperties& p = p2.properties;
  info.name = p.deviceName;
  info.driver = drv.driverName[0] ? std::string(drv.driverName) + ", " + drv.driverInfo
                                  : "driver " + std::to_string(p.driverVersion);
  info.uuid = hex(p.pipelineCacheUUID, VK_UUID_SIZE);
  info.api = p.apiVersion;
  info.driver_version = p.driverVersion;
  info.vendor = p.vendorID;
  info.device_id = p.deviceID;
  info.type = p.deviceType;
  info.limits = p.limits;
  info.ballot = (sub.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) &&
                (sub.supportedOperations & VK_SUBGROUP_FEATURE_BALLOT_BIT) &&
                (sub.supportedOperations & VK_SUBGROUP_FEATURE_BASIC_BIT);
  info.subgroup_size = std::max<uint32_t>(1, sub.subgroupSize);
  const VkSubgroupFeatureFlags group_ops =
      VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_VOTE_BIT |
      VK_SUBGROUP_FEATURE_BALLOT_BIT | VK_SUBGROUP_FEATURE_ARITHMETIC_BIT |
      VK_SUBGROUP_FEATURE_SHUFFLE_BIT;
  info.group_ops = (sub.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) &&
                   (sub.supportedOperations & group_ops) == group_ops && sub.subgroupSize <= 128;
  if (info.float_controls) {
    info.denorm_preserve = fc.shaderDenormPreserveFloat32;
    info.denorm_flush = fc.shaderDenormFlushToZeroFloat32;
    info.signed_zero_inf_nan = fc.shaderSignedZeroInfNanPreserveFloat32;
    info.rte = fc.shaderRoundingModeRTEFloat32;
  }
  // Memory every buffer lives in: host-visible and coherent, so uploads and read-backs are
  // copies through a mapping. Device-local too where such a heap is large (resizable BAR,
  // integrated GPUs, CPU devices); a 256 MiB BAR window is not used for streams.
  VkPhysicalDeviceMemoryProperties mem{};
  api.vkGetPhysicalDeviceMemoryProperties(physical, &mem);
  const VkMemoryPropertyFlags host =
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  int best = -1;
  for (uint32_t i = 0; i < mem.memoryTypeCount; ++i) {
    const VkMemoryType& t = mem.memoryTypes[i];
    if ((t.propertyFlags & host) != host) continue;
    const bool local = (t.propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT) &&
                       mem.memoryHeaps[t.heapIndex].size > (uint64_t{1} << 30);
    if (best < 0 || (local && !info.memory_device_local)) {
      best = static_cast<int>(i);
      info.memory_device_local = local;
    }
  }
  if (best < 0)
    throw Error(std::string(kWho) + ": the Vulkan device '" + info.name +
                "' has no host-visible coherent memory type");
  info.memory_type = static_cast<uint32_t>(best);
  choose_stream_memory(mem);
}

void Context::choose_stream_memory(const VkPhysicalDeviceMemoryProperties& mem) {
  if (const char* m = std::getenv("RILL_VULKAN_MEMORY"); m && *m) info.memory_mode = m;
  const std::string& mode = info.memory_mode;
  if (mode != "auto" && mode != "staged" && mode != "mapped")
    throw Error("RILL_VULKAN_MEMORY='" + mode + "' is not one of auto, staged, mapped");
  const VkMemoryPropertyFlags host =
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  auto flags = [&](uint32_t i) { return mem.memoryTypes[i].propertyFlags; };
  auto large = [&](uint32_t i) {
    return mem.memoryHeaps[mem.memoryTypes[i].heapIndex].size > (uint64_t{1} << 30);
  };
  // Read-back staging: the first host-visible coherent type, a host-cached one before others.
  int readback = -1;
  for (uint32_t i = 0; i < mem.memoryTypeCount; ++i) {
    if ((flags(i) & host) != host) continue;
    const bool cached = flags(i) & VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
    if (readback < 0 || (cached && !info.readback_cached)) {
      readback = static_cast<int>(i);
      info.readback_cached = cached;
    }
  }
  info.readback_memory_type = static_cast<uint32_t>(readback);  // memory_type exists: >= 0
  // Streams: a device-local type on a large heap, one the host maps before one it does not
  // (unless staged); with none, memory_type.
  int streams = -1;
  bool mapped = false;
  for (uint32_t i = 0; i < mem.memoryTypeCount && mode != "mapped"; ++i) {
    if (!(flags(i) & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT) || !large(i)) continue;
    const bool m = mode == "auto" && (flags(i) & host) == host;
    if (streams < 0 || (m && !mapped)) {
      streams = static_cast<int>(i);
      mapped = m;
    }
  }
  if (streams < 0) {
    streams = static_cast<int>(info.memory_type);
    mapped = true;
  }
  info.stream_memory_type = static_cast<uint32_t>(streams);
  info.streams_mapped = mapped;
  // `mapped` reads through the mapping whatever the caching, as before.
  const bool cached = flags(info.stream_memory_type) & VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
  info.streams_cached = mapped && (cached || mode == "mapped");
}

void Context::make_device() {
  uint32_t n = 0;
  api.vkGetPhysicalDeviceQueueFamilyProperties(physical, &n, nullptr);
  std::vector<VkQueueFamilyProperties> families(n);
  api.vkGetPhysicalDeviceQueueFamilyProperties(physical, &n, families.data());
  int chosen = -1;
  for (uint32_t i = 0; i < n && chosen < 0; ++i)
    if (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) chosen = static_cast<int>(i);
  if (chosen < 0)
    throw Error(std::string(kWho) + ": the Vulkan device '" + info.name +
                "' has no queue family with compute (VK_QUEUE_COMPUTE_BIT)");
  family = static_cast<uint32_t>(chosen);
  info.timestamps = families[family].timestampValidBits > 0;
  info.timestamp_ns = info.limits.timestampPeriod;
  const float priority = 1.0f;
  auto q = make<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
  q.queueFamilyIndex = family;
  q.queueCount = 1;
  q.pQueuePriorities = &priority;
  // scalarBlockLayout, for parameters in a uniform buffer (RILL_VULKAN_PARAMS=uniform).
  auto scalar = make<VkPhysicalDeviceScalarBlockLayoutFeatures>(
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SCALAR_BLOCK_LAYOUT_FEATURES);
  if (info.api >= VK_API_VERSION_1_2) {
    auto f2 = make<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
    f2.pNext = &scalar;
    api.vkGetPhysicalDeviceFeatures2(physical, &f2);
    info.scalar_layout = scalar.scalarBlockLayout;
  }
  std::vector<const char*> extensions;
  if (info.float_controls && info.api < VK_API_VERSION_1_2)
    extensions.push_back(VK_KHR_SHADER_FLOAT_CONTROLS_EXTENSION_NAME);
  auto ci = make<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
  ci.queueCreateInfoCount = 1;
  ci.pQueueCreateInfos = &q;
  ci.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  ci.ppEnabledExtensionNames = extensions.data();
  if (info.scalar_layout) ci.pNext = &scalar;
  check(api.vkCreateDevice(physical, &ci, nullptr, &device),
        "creating the Vulkan device for '" + info.name + "' (vkCreateDevice)");
  api.load_device(device);
  api.vkGetDeviceQueue(device, family, 0, &queue);
  auto pc = make<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
  pc.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pc.queueFamilyIndex = family;
  check(api.vkCreateCommandPool(device, &pc, nullptr, &pool), "creating a command pool");
  auto ca = make<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
  ca.commandPool = pool;
  ca.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ca.commandBufferCount = 1;
  check(api.vkAllocateCommandBuffers(device, &ca, &commands), "allocating a command buffer");
  auto fi = make<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
  check(api.vkCreateFence(device, &fi, nullptr, &fence), "creating a fence");
  if (info.timestamps) {
    auto qi = make<VkQueryPoolCreateInfo>(VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO);
    qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
    qi.queryCount = 2;
    check(api.vkCreateQueryPool(device, &qi, nullptr, &timer), "creating a timestamp pool");
  }
}

void Context::submit_and_wait(const std::string& what) {
  auto si = make<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
  si.commandBufferCount = 1;
  si.pCommandBuffers = &commands;
  check(api.vkResetFences(device, 1, &fence), what + ": resetting the fence");
  check(api.vkQueueSubmit(queue, 1, &si, fence), what + ": vkQueueSubmit");
  check(api.vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), what + ": waiting");
}

void Context::report(const std::string& message) {
  std::lock_guard<std::mutex> lock(messages_mutex_);
  messages_.push_back(message);
}

void Context::check_validation(const std::string& what) {
  std::vector<std::string> m;
  {
    std::lock_guard<std::mutex> lock(messages_mutex_);
    m.swap(messages_);
  }
  if (m.empty()) return;
  std::string text = std::string(kWho) + ": the Vulkan validation layer reported " +
                     std::to_string(m.size()) + " message(s) while " + what + ":";
  for (const std::string& s : m) text += "\n  " + s;
  throw Error(text);
}

DeviceListing list_devices() {
  DeviceListing out;
  Api api;
  VkInstance instance = VK_NULL_HANDLE;
  try {
    api.load_loader();
    auto app = make<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    app.pApplicationName = "rill-info";
    app.apiVersion = VK_API_VERSION_1_2;
    auto ci = make<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    ci.pApplicationInfo = &app;
    check(api.vkCreateInstance(&ci, nullptr, &instance), "creating the Vulkan instance");
    api.load_instance(instance);
    uint32_t n = 0;
    check(api.vkEnumeratePhysicalDevices(instance, &n, nullptr), "listing Vulkan devices");
    std::vector<VkPhysicalDevice> all(n);
    if (n)
      check(api.vkEnumeratePhysicalDevices(instance, &n, all.data()), "listing Vulkan devices");
    std::vector<VkPhysicalDeviceProperties> props(n);
    std::string names;
    for (uint32_t i = 0; i < n; ++i) {
      VkPhysicalDeviceProperties& p = props[i];
      api.vkGetPhysicalDeviceProperties(all[i], &p);
      names += (i ? ", " : "") + std::to_string(i) + ": " + p.deviceName;
      DeviceSummary d;
      d.name = p.deviceName;
      d.type = p.deviceType;
      d.api = p.apiVersion;
      if (p.apiVersion >= VK_API_VERSION_1_1) {  // subgroup properties are Vulkan 1.1
        auto sub = make<VkPhysicalDeviceSubgroupProperties>(
            VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES);
        auto p2 = make<VkPhysicalDeviceProperties2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2);
        p2.pNext = &sub;
        api.vkGetPhysicalDeviceProperties2(all[i], &p2);
        d.subgroup_size = sub.subgroupSize;
      }
      out.devices.push_back(std::move(d));
    }
    if (n) {
      const std::pair<int, std::string> pick = pick_device(props, names);
      out.chosen = pick.first;
      out.why = pick.second;
    }
  } catch (const Error& e) {
    out.error = e.what();
  }
  if (instance) api.vkDestroyInstance(instance, nullptr);
  return out;
}

}  // namespace rill::vk
