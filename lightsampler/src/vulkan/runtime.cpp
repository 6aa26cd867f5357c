// The process's Vulkan runtime: its one instance, and one logical device per physical device.

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "vulkan/state.h"

namespace lightsampler::vk {

namespace {
// Debug builds of the library run with the validation layer (when installed), as tests do.
#ifdef NDEBUG
constexpr bool kDebugBuild = false;
#else
constexpr bool kDebugBuild = true;
#endif

VkDeviceSize device_local_bytes(const VkPhysicalDeviceMemoryProperties& memory) {
  VkDeviceSize largest = 0;
  for (std::uint32_t i = 0; i < memory.memoryHeapCount; ++i)
    if (memory.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
      largest = std::max(largest, memory.memoryHeaps[i].size);
  return largest;
}

bool validation_from_environment() {
  const char* value = std::getenv("LIGHTSAMPLER_VULKAN_VALIDATION");
  return value && std::string(value) == "1";
}
}  // namespace

Device::Device(const DeviceSurvey& d) : physical(d.handle) {
  name = d.info.name;
  raster_missing = d.raster_missing;
  max_push_size = d.properties.limits.maxPushConstantsSize;
  vkGetPhysicalDeviceMemoryProperties(physical, &memory);
  // With the Vulkan memory model enabled, Device scope (which every other pass's atomics use)
  // needs vulkanMemoryModelDeviceScope: the lookback scan gets the model only with both.
  const bool memory_model = d.features12.vulkanMemoryModel && d.features12.vulkanMemoryModelDeviceScope;
  capabilities = {.subgroup_size = d.subgroup_size,
                  .conservative_rasterization = d.conservative_rasterization,
                  .timestamp_period_ns = d.properties.limits.timestampPeriod,
                  .max_workgroup_count_x = d.properties.limits.maxComputeWorkGroupCount[0],
                  .max_buffer_size = d.max_buffer_size,
                  .device_local_bytes = device_local_bytes(memory),
                  .sub_pixel_bits = d.properties.limits.subPixelPrecisionBits,
                  .raster = d.raster_missing.empty(),
                  .geometry_shader = d.raster_missing.empty() && d.features.geometryShader,
                  .vulkan_memory_model = memory_model};
  timestamp_mask = d.timestamp_bits >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << d.timestamp_bits) - 1;

  // Required features (checked by the survey), plus optional ones the passes use where present.
  VkPhysicalDeviceShaderAtomicFloatFeaturesEXT atomic_float{
      .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT,
      .shaderBufferFloat32Atomics = d.atomic_float.shaderBufferFloat32Atomics,
      .shaderBufferFloat32AtomicAdd = VK_TRUE,
      .shaderSharedFloat32Atomics = d.atomic_float.shaderSharedFloat32Atomics,
      .shaderSharedFloat32AtomicAdd = d.atomic_float.shaderSharedFloat32AtomicAdd};
  VkPhysicalDeviceDynamicRenderingFeatures dynamic_rendering{
      .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES,
      .pNext = &atomic_float,
      .dynamicRendering = VK_TRUE};
  VkPhysicalDeviceVulkan13Features features13{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES,
                                              .pNext = &atomic_float,
                                              .dynamicRendering = d.dynamic_rendering};
  const bool core13 = d.api_version >= VK_API_VERSION_1_3;
  VkPhysicalDeviceVulkan12Features features12{
      .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
      .pNext = core13 ? static_cast<void*>(&features13)
               : d.dynamic_rendering_extension ? static_cast<void*>(&dynamic_rendering)
                                               : static_cast<void*>(&atomic_float),
      .shaderBufferInt64Atomics = VK_TRUE,
      .shaderSharedInt64Atomics = d.features12.shaderSharedInt64Atomics,
      .shaderSubgroupExtendedTypes = d.features12.shaderSubgroupExtendedTypes,
      .bufferDeviceAddress = VK_TRUE,
      .vulkanMemoryModel = capabilities.vulkan_memory_model,
      .vulkanMemoryModelDeviceScope = capabilities.vulkan_memory_model};
  VkPhysicalDeviceFeatures2 features{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &features12};
  features.features.shaderInt64 = VK_TRUE;
  features.features.shaderFloat64 = d.features.shaderFloat64;
  features.features.geometryShader = d.features.geometryShader;
  features.features.fragmentStoresAndAtomics = d.features.fragmentStoresAndAtomics;
  features.features.vertexPipelineStoresAndAtomics = d.features.vertexPipelineStoresAndAtomics;

  std::vector<const char*> extensions{VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME};
  if (d.dynamic_rendering_extension) extensions.push_back(VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME);
  if (d.conservative_rasterization) extensions.push_back(VK_EXT_CONSERVATIVE_RASTERIZATION_EXTENSION_NAME);

  const float priority = 1.0f;
  const VkDeviceQueueCreateInfo queue_info{.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                           .queueFamilyIndex = d.queue_family,
                                           .queueCount = 1,
                                           .pQueuePriorities = &priority};
  const VkDeviceCreateInfo info{.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
                                .pNext = &features,
                                .queueCreateInfoCount = 1,
                                .pQueueCreateInfos = &queue_info,
                                .enabledExtensionCount = std::uint32_t(extensions.size()),
                                .ppEnabledExtensionNames = extensions.data()};
  check(vkCreateDevice(physical, &info, nullptr, &handle), "vkCreateDevice");
  queue_family = d.queue_family;
  vkGetDeviceQueue(handle, d.queue_family, 0, &queue_);
  if (d.dynamic_rendering) {
    const char* suffix = core13 ? "" : "KHR";
    begin_rendering = reinterpret_cast<PFN_vkCmdBeginRendering>(
        vkGetDeviceProcAddr(handle, (std::string("vkCmdBeginRendering") + suffix).c_str()));
    end_rendering = reinterpret_cast<PFN_vkCmdEndRendering>(
        vkGetDeviceProcAddr(handle, (std::string("vkCmdEndRendering") + suffix).c_str()));
  }
}

void Device::submit(VkCommandBuffer cmd, VkFence fence) {
  const VkSubmitInfo info{.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &cmd};
  const std::lock_guard lock(queue_mutex_);
  check(vkQueueSubmit(queue_, 1, &info, fence), "vkQueueSubmit");
}

Runtime::Runtime(bool validation) : instance_(validation, &log_), devices_(survey_devices(instance_)) {
  created_.resize(devices_.size());
}

Runtime& Runtime::get(bool validation) {
  static std::mutex mutex;
  static Runtime* runtime = nullptr;             // never destroyed: see the class comment
  static std::optional<std::string> unavailable;  // why Vulkan cannot be had, once found out
  const std::lock_guard lock(mutex);
  if (runtime) {
    static bool told = false;
    if (validation && !runtime->instance_.validation() && !told) {
      told = true;
      std::fprintf(stderr,
                   "lightsampler: Vulkan validation requested after the process's instance was created "
                   "without it; set LIGHTSAMPLER_VULKAN_VALIDATION=1 to have it from the start\n");
    }
    return *runtime;
  }
  if (unavailable) throw Unavailable(*unavailable);
  try {
    runtime = new Runtime(validation || kDebugBuild || validation_from_environment());
  } catch (const Unavailable& e) {
    unavailable = e.what();
    throw;
  }
  return *runtime;
}

Device& Runtime::device(const DeviceSurvey& survey) {
  const std::lock_guard lock(devices_mutex_);
  std::unique_ptr<Device>& d = created_.at(survey.info.index);
  if (!d) d = std::make_unique<Device>(survey);
  return *d;
}

}  // namespace lightsampler::vk
