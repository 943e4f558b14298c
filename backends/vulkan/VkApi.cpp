// The Vulkan loader opened at run time and the backend's function table (VkApi.h).
#include "VkApi.h"

#include <dlfcn.h>

#include <cstdlib>

#include "rill/Error.h"

namespace rill::vk {

void Api::load_loader() {
  const char* env = std::getenv("RILL_VULKAN_LIBRARY");
  const std::string lib = env && *env ? env : "libvulkan.so.1";
  // Never closed: the driver it loads registers exit handlers of its own.
  void* h = dlopen(lib.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!h) {
    const char* why = dlerror();
    throw Error(std::string(kWho) + ": cannot load the Vulkan loader " + lib + " (" +
                (why ? why : "not found") +
                "); install it (Debian: apt-get install libvulkan1 mesa-vulkan-drivers)");
  }
  vkGetInstanceProcAddr =
      reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(h, "vkGetInstanceProcAddr"));
  if (!vkGetInstanceProcAddr)
    throw Error(std::string(kWho) + ": " + lib + " has no vkGetInstanceProcAddr");
  auto global = [&](const char* name) { return vkGetInstanceProcAddr(nullptr, name); };
  vkCreateInstance = reinterpret_cast<PFN_vkCreateInstance>(global("vkCreateInstance"));
  vkEnumerateInstanceVersion =
      reinterpret_cast<PFN_vkEnumerateInstanceVersion>(global("vkEnumerateInstanceVersion"));
  vkEnumerateInstanceLayerProperties = reinterpret_cast<PFN_vkEnumerateInstanceLayerProperties>(
      global("vkEnumerateInstanceLayerProperties"));
  vkEnumerateInstanceExtensionProperties =
      reinterpret_cast<PFN_vkEnumerateInstanceExtensionProperties>(
          global("vkEnumerateInstanceExtensionProperties"));
  if (!vkCreateInstance || !vkEnumerateInstanceLayerProperties ||
      !vkEnumerateInstanceExtensionProperties)
    throw Error(std::string(kWho) + ": " + lib + " lacks the Vulkan 1.0 global functions");
}

void Api::load_instance(VkInstance instance) {
#define RILL_VK_INSTANCE(f) f = reinterpret_cast<PFN_##f>(vkGetInstanceProcAddr(instance, #f));
#define RILL_VK_DEVICE(f)
#include "VkFunctions.def"
#undef RILL_VK_INSTANCE
#undef RILL_VK_DEVICE
  // Vulkan 1.1 functions: an instance made for 1.1 has them.
  if (!vkEnumeratePhysicalDevices || !vkGetPhysicalDeviceProperties2 || !vkCreateDevice ||
      !vkGetDeviceProcAddr)
    throw Error(std::string(kWho) +
                ": the Vulkan instance lacks Vulkan 1.1 functions "
                "(vkGetPhysicalDeviceProperties2); the loader is too old");
}

void Api::load_device(VkDevice device) {
#define RILL_VK_INSTANCE(f)
#define RILL_VK_DEVICE(f)                                            \
  f = reinterpret_cast<PFN_##f>(vkGetDeviceProcAddr(device, #f));    \
  if (!f)                                                            \
    throw Error(std::string(kWho) + ": the Vulkan device has no " #f \
                                    " (a Vulkan 1.1 device function)");
#include "VkFunctions.def"
#undef RILL_VK_INSTANCE
#undef RILL_VK_DEVICE
}

const char* result_name(VkResult r) {
  switch (r) {
#define RILL_CASE(x) \
  case x:            \
    return #x;
    RILL_CASE(VK_SUCCESS)
    RILL_CASE(VK_NOT_READY)
    RILL_CASE(VK_TIMEOUT)
    RILL_CASE(VK_INCOMPLETE)
    RILL_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    RILL_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    RILL_CASE(VK_ERROR_INITIALIZATION_FAILED)
    RILL_CASE(VK_ERROR_DEVICE_LOST)
    RILL_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    RILL_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    RILL_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    RILL_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    RILL_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    RILL_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    RILL_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    RILL_CASE(VK_ERROR_FRAGMENTED_POOL)
    RILL_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
    RILL_CASE(VK_ERROR_INVALID_SHADER_NV)
    RILL_CASE(VK_PIPELINE_COMPILE_REQUIRED)
#undef RILL_CASE
    default:
      return "VK_ERROR_UNKNOWN";
  }
}

void check(VkResult r, const std::string& what) {
  if (r != VK_SUCCESS)
    throw Error(std::string(kWho) + ": " + what + " failed: " + result_name(r) + " (" +
                std::to_string(static_cast<int>(r)) + ")");
}

}  // namespace rill::vk
