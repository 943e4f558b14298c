// The vulkan backend's device: the instance, the physical device chosen (RILL_VULKAN_DEVICE),
// the logical device with one compute queue, what the device offers that kernels use
// (subgroup ballots, float controls, limits, timestamps, host-visible memory), and the
// validation layer's messages when it is on (RILL_VULKAN_VALIDATION, or the layer named in
// VK_INSTANCE_LAYERS): each becomes an Error at the end of the call that caused it.
//
// Nothing here assumes lavapipe: the device is chosen by type (a GPU before a CPU device)
// unless named, and every feature used is asked for first.
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "VkApi.h"

namespace rill::vk {

// What the chosen device offers, asked once.
struct DeviceInfo {
  std::string name;    // deviceName: "llvmpipe (LLVM 15.0.6, 256 bits)", "NVIDIA H200"
  std::string driver;  // driverName and driverInfo: "llvmpipe, Mesa 22.3.6 (LLVM 15.0.6)"
  std::string uuid;    // pipelineCacheUUID, in hex (keys of the disk cache)
  uint32_t api = 0, driver_version = 0, vendor = 0, device_id = 0;
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  VkPhysicalDeviceLimits limits{};
  bool ballot = false;         // subgroup ballots in compute shaders
  uint32_t subgroup_size = 1;  // lanes per subgroup
  // Basic, vote, ballot, arithmetic and shuffle subgroup operations in compute shaders: what
  // lane-group ops need (rill/Group.h).
  bool group_ops = false;
  // SPV_KHR_float_controls for 32-bit floats: what the device can be asked to keep.
  bool float_controls = false, denorm_preserve = false, signed_zero_inf_nan = false, rte = false;
  bool denorm_flush = false;   // shaderDenormFlushToZeroFloat32: DenormFlushToZero is offered
  bool scalar_layout = false;  // scalarBlockLayout (Vulkan 1.2), enabled where offered
  bool timestamps = false;     // the compute queue writes timestamps
  double timestamp_ns = 1;     // nanoseconds per tick
  // Parameters, counters, probes and upload staging: host-visible, coherent (device-local too
  // where such a heap is large).
  uint32_t memory_type = 0;
  bool memory_device_local = false;
  // Streams and arrays (RILL_VULKAN_MEMORY = auto | staged | mapped): device-local; mapped
  // where that memory is host-visible and coherent too (resizable BAR, integrated GPUs, CPU
  // devices) and not `staged`; read through the mapping only where it is also host-cached
  // (reads of write-combined BAR memory cross the bus uncached, word by word), else copied
  // to a host-cached staging buffer first. `mapped` keeps the streams in memory_type, read
  // through the mapping, as before (for measuring).
  std::string memory_mode = "auto";
  uint32_t stream_memory_type = 0;
  bool streams_mapped = false, streams_cached = false;
  // Read-back staging: host-visible, coherent, host-cached where there is such a type.
  uint32_t readback_memory_type = 0;
  bool readback_cached = false;
};

class Context {
 public:
  // Makes the instance and device; throws Error naming what is missing (the loader, a device,
  // a compute queue, Vulkan 1.1, the validation layer when asked for).
  Context();
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  Api api;
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t family = 0;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkCommandBuffer commands = VK_NULL_HANDLE;  // one launch's, recorded anew each time
  VkFence fence = VK_NULL_HANDLE;
  VkQueryPool timer = VK_NULL_HANDLE;  // two timestamps around a launch's dispatches
  DeviceInfo info;
  bool validation = false;  // the validation layer is on and reports here

  // Submits `commands` and waits for them.
  void submit_and_wait(const std::string& what);
  // Throws Error with the validation layer's messages since the last call, if any.
  void check_validation(const std::string& what);
  // Called by the layer (from any thread).
  void report(const std::string& message);

 private:
  void choose_device();
  void describe_device();
  void choose_stream_memory(const VkPhysicalDeviceMemoryProperties& mem);
  void make_device();
  void release() noexcept;  // destroys what exists, in reverse order

  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  std::mutex messages_mutex_;
  std::vector<std::string> messages_;
};

// Bytes in lower-case hex (pipelineCacheUUID in the disk cache's keys).
std::string hex(const uint8_t* bytes, size_t n);

// "cpu", "discrete GPU", ... for descriptions.
const char* device_type_name(VkPhysicalDeviceType t);

// The Vulkan devices the loader sees, for rill-info: each one's name, type, API version and
// subgroup size, which one the backend uses and why (RILL_VULKAN_DEVICE, or the type order).
struct DeviceSummary {
  std::string name;
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  uint32_t api = 0;
  uint32_t subgroup_size = 0;  // 0: not reported (a Vulkan 1.0 device)
};
struct DeviceListing {
  std::vector<DeviceSummary> devices;
  int chosen = -1;    // index into devices; -1 where none is usable
  std::string why;    // why that one ("the first discrete GPU", "RILL_VULKAN_DEVICE=1")
  std::string error;  // no loader, no driver, a bad RILL_VULKAN_DEVICE: the reason, else ""
};
// Lists through an instance of its own (no device is made); never throws.
DeviceListing list_devices();

}  // namespace rill::vk
