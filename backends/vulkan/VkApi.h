// The Vulkan API as the vulkan backend sees it: the loader (libvulkan.so.1) opened with dlopen
// at first use, so that a machine without it still runs every other backend and reports this
// one unavailable, and the functions of VkFunctions.def looked up through it; plus the error
// check every call goes through.
#pragma once

#define VK_NO_PROTOTYPES
#include <vulkan/vulkan.h>

#include <string>

namespace rill::vk {

// The backend in messages, and its name.
inline constexpr const char* kName = "vulkan";
inline constexpr const char* kWho = "vulkan backend";

struct Api {
  PFN_vkGetInstanceProcAddr vkGetInstanceProcAddr = nullptr;
  PFN_vkCreateInstance vkCreateInstance = nullptr;
  PFN_vkEnumerateInstanceVersion vkEnumerateInstanceVersion = nullptr;  // null: Vulkan 1.0
  PFN_vkEnumerateInstanceLayerProperties vkEnumerateInstanceLayerProperties = nullptr;
  PFN_vkEnumerateInstanceExtensionProperties vkEnumerateInstanceExtensionProperties = nullptr;
#define RILL_VK_INSTANCE(f) PFN_##f f = nullptr;
#define RILL_VK_DEVICE(f) PFN_##f f = nullptr;
#include "VkFunctions.def"
#undef RILL_VK_INSTANCE
#undef RILL_VK_DEVICE

  // Opens the loader ($RILL_VULKAN_LIBRARY, else libvulkan.so.1) and its global functions;
  // throws Error naming the library when it is missing.
  void load_loader();
  // The instance's functions (the debug-utils pair may stay null: only with validation).
  void load_instance(VkInstance instance);
  // The device's functions; throws Error naming a missing one.
  void load_device(VkDevice device);
};

// A Vulkan structure of type T, zeroed, with its sType (T{type} would leave -Wextra warning
// about every member it does not name).
template <class T>
T make(VkStructureType type) {
  T t{};
  t.sType = type;
  return t;
}

// "VK_ERROR_OUT_OF_DEVICE_MEMORY" for a result code.
const char* result_name(VkResult r);
// Throws Error("vulkan backend: <what> failed: VK_ERROR_...") unless r is VK_SUCCESS.
void check(VkResult r, const std::string& what);

}  // namespace rill::vk
