#pragma once
// Internals of the Vulkan runtime shared by its source files: error checks, the instance, what a
// physical device offers, and the Context's state.

#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "vulkan/context.h"

namespace lightsampler::vk {

const char* result_name(VkResult result);
/// Throws Error("<call> failed: <VkResult name>") unless `result` is VK_SUCCESS.
void check(VkResult result, const char* call);

/// Validation warnings and errors; the debug callback may run on any thread.
class MessageLog {
 public:
  void add(std::string message);
  std::vector<std::string> snapshot() const;

 private:
  mutable std::mutex mutex_;
  std::vector<std::string> messages_;
};

/// The VkInstance, with the validation layer and a debug messenger feeding `log` when validation
/// is requested (by the caller or LIGHTSAMPLER_VULKAN_VALIDATION=1) and installed.
class Instance {
 public:
  /// Throws Unavailable when there is no Vulkan 1.2 loader or no driver.
  Instance(bool validation, MessageLog* log);
  ~Instance();
  Instance(const Instance&) = delete;
  Instance& operator=(const Instance&) = delete;

  VkInstance handle() const { return instance_; }
  std::uint32_t api_version() const { return api_version_; }
  bool validation() const { return messenger_ != VK_NULL_HANDLE; }

 private:
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  std::uint32_t api_version_ = 0;
};

/// What one physical device offers, queried once. Feature structs have their pNext cleared.
struct DeviceSurvey {
  VkPhysicalDevice handle = VK_NULL_HANDLE;
  DeviceInfo info;
  std::uint32_t api_version = 0;  ///< the lower of the device's and the instance's
  VkPhysicalDeviceProperties properties{};
  std::uint32_t subgroup_size = 0;
  VkDeviceSize max_buffer_size = 0;
  std::uint32_t queue_family = 0;
  bool graphics = false;  ///< the queue family also does graphics
  std::uint32_t timestamp_bits = 0;
  VkPhysicalDeviceFeatures features{};
  VkPhysicalDeviceVulkan12Features features12{};
  VkPhysicalDeviceShaderAtomicFloatFeaturesEXT atomic_float{};
  bool dynamic_rendering = false;
  bool dynamic_rendering_extension = false;  ///< through VK_KHR_dynamic_rendering (Vulkan 1.2)
  bool conservative_rasterization = false;
  std::string raster_missing;  ///< why raster pipelines cannot be made; empty if they can
};

std::vector<DeviceSurvey> survey_devices(const Instance& instance);
/// The device `request` names (an index or a case-insensitive name substring), or the best
/// suitable one when it is empty. Throws Unavailable saying what is missing or what exists.
const DeviceSurvey& select_device(const std::vector<DeviceSurvey>& devices, const std::string& request);

/// Owns the VkDevice; destroyed after every object made from it (see State's member order).
struct DeviceHandle {
  VkDevice handle = VK_NULL_HANDLE;
  DeviceHandle() = default;
  DeviceHandle(const DeviceHandle&) = delete;
  DeviceHandle& operator=(const DeviceHandle&) = delete;
  ~DeviceHandle();
};

struct Context::State {
  explicit State(bool validation) : instance(validation, &log) {}
  ~State();

  // Members are destroyed bottom-up: the staging buffer, then (in ~State) pools and the fence,
  // then the device, then the instance and its messenger, then the log it writes to.
  MessageLog log;
  Instance instance;
  DeviceHandle device;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  std::string name;
  Capabilities capabilities{};
  std::string raster_missing;
  std::uint32_t max_push_size = 0;
  VkPhysicalDeviceMemoryProperties memory{};
  VkQueue queue = VK_NULL_HANDLE;
  std::uint64_t timestamp_mask = 0;  ///< 0: the queue writes no timestamps
  PFN_vkCmdBeginRendering begin_rendering = nullptr;
  PFN_vkCmdEndRendering end_rendering = nullptr;
  VkCommandPool command_pool = VK_NULL_HANDLE;
  VkCommandBuffer transfer_commands = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  std::vector<VkQueryPool> query_pools;  ///< kQueriesPerPool timestamps each, added as needed
  Buffer staging;

  static constexpr std::uint32_t kQueriesPerPool = 64;

  void create_device(const DeviceSurvey& d);
  Buffer make_buffer(VkDeviceSize bytes, bool host_visible);
  /// The host-visible staging buffer, grown to at least `bytes`.
  const Buffer& staging_buffer(VkDeviceSize bytes);
  /// Submits `cmd` (ended) and waits for it.
  void submit_and_wait(VkCommandBuffer cmd);
  /// Records `record` into the transfer command buffer, submits it and waits.
  void run_transfer(const std::function<void(VkCommandBuffer)>& record);
  /// Resets and writes timestamp query `slot` (a no-op if the queue has no timestamps).
  void write_timestamp(VkCommandBuffer cmd, std::uint32_t slot);
  std::vector<std::uint64_t> read_timestamps(std::uint32_t count);
};

/// A memory dependency from `src` stages/accesses to `dst` ones, over all memory.
void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags src_stages, VkAccessFlags src_access,
                    VkPipelineStageFlags dst_stages, VkAccessFlags dst_access);

}  // namespace lightsampler::vk
