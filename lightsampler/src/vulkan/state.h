#pragma once
// Internals of the Vulkan runtime shared by its source files: error checks, the instance, what a
// physical device offers, and the Context's state.

#include <functional>
#include <memory>
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

/// The logical device of one physical device, shared by every Context of the process: created
/// on first use and kept until exit, like the instance. Immutable once made, but for the queue,
/// which `submit` serializes (vkQueueSubmit needs the queue externally synchronized).
struct Device {
  explicit Device(const DeviceSurvey& d);
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  VkDevice handle = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  std::string name;
  Capabilities capabilities{};
  std::string raster_missing;
  std::uint32_t max_push_size = 0;
  std::uint32_t queue_family = 0;
  VkPhysicalDeviceMemoryProperties memory{};
  std::uint64_t timestamp_mask = 0;  ///< 0: the queue writes no timestamps
  PFN_vkCmdBeginRendering begin_rendering = nullptr;
  PFN_vkCmdEndRendering end_rendering = nullptr;

  /// Submits `cmd` (ended), signalling `fence` when done.
  void submit(VkCommandBuffer cmd, VkFence fence);

 private:
  VkQueue queue_ = VK_NULL_HANDLE;
  std::mutex queue_mutex_;
};

/// The process's Vulkan: one instance and one logical device per physical device, made on first
/// use and never destroyed. A driver need not survive being loaded again (NVIDIA's fails after
/// about 14 instances in one process), and objects of a long-lived program may outlive any scope
/// that could own them. Thread-safe.
class Runtime {
 public:
  /// The runtime, created by the first call with validation if that call or
  /// LIGHTSAMPLER_VULKAN_VALIDATION=1 or a Debug build asks for it; later requests cannot turn
  /// it on. Throws Unavailable (every call, without retrying) when there is no usable loader
  /// or driver.
  static Runtime& get(bool validation);

  const Instance& instance() const { return instance_; }
  const std::vector<DeviceSurvey>& devices() const { return devices_; }
  /// The device for `survey` (one of devices()), created on first use.
  Device& device(const DeviceSurvey& survey);
  MessageLog& log() { return log_; }

 private:
  explicit Runtime(bool validation);
  MessageLog log_;
  Instance instance_;
  std::vector<DeviceSurvey> devices_;
  std::mutex devices_mutex_;
  std::vector<std::unique_ptr<Device>> created_;  ///< by physical device index
};

/// What one Context owns on the shared device: its command pool and buffers, fence, timestamp
/// queries and staging memory. Destroying it frees them and nothing else.
struct Context::State {
  explicit State(Device& d);
  ~State();

  Device& device;
  VkCommandPool command_pool = VK_NULL_HANDLE;
  VkCommandBuffer transfer_commands = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  std::vector<VkQueryPool> query_pools;  ///< kQueriesPerPool timestamps each, added as needed
  Buffer staging;

  static constexpr std::uint32_t kQueriesPerPool = 64;

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
