// What each physical device offers, whether the sampler can run on it, and which one to use.

#include <algorithm>
#include <cctype>
#include <cstring>
#include <string>
#include <vector>

#include "vulkan/state.h"

namespace lightsampler::vk {

const char* type_name(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
  }
}

namespace {

int preference(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
  }
}

std::string join(const std::vector<std::string>& parts) {
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : ", ") + p;
  return out;
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::vector<VkExtensionProperties> device_extensions(VkPhysicalDevice device) {
  std::uint32_t count = 0;
  check(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr),
        "vkEnumerateDeviceExtensionProperties");
  std::vector<VkExtensionProperties> extensions(count);
  check(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data()),
        "vkEnumerateDeviceExtensionProperties");
  extensions.resize(count);
  return extensions;
}

bool has(const std::vector<VkExtensionProperties>& extensions, const char* name) {
  return std::any_of(extensions.begin(), extensions.end(),
                     [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

// One queue family for everything: compute and graphics if any family has both, else compute.
// False if no family computes.
bool pick_queue_family(DeviceSurvey& d) {
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(d.handle, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(d.handle, &count, families.data());
  bool found = false;
  for (std::uint32_t i = 0; i < count; ++i) {
    const VkQueueFlags flags = families[i].queueFlags;
    if (!(flags & VK_QUEUE_COMPUTE_BIT)) continue;
    const bool graphics = flags & VK_QUEUE_GRAPHICS_BIT;
    if (!found || (graphics && !d.graphics)) {
      d.queue_family = i;
      d.graphics = graphics;
      d.timestamp_bits = families[i].timestampValidBits;
      found = true;
    }
  }
  return found;
}

DeviceSurvey survey(VkPhysicalDevice handle, std::uint32_t index, std::uint32_t instance_api) {
  DeviceSurvey d;
  d.handle = handle;
  vkGetPhysicalDeviceProperties(handle, &d.properties);
  d.info = {d.properties.deviceName, d.properties.deviceType, index, false, {}, {}};
  d.api_version = std::min(d.properties.apiVersion, instance_api);
  if (d.api_version < VK_API_VERSION_1_2) {
    d.info.missing = "Vulkan 1.2 (it has " + std::to_string(VK_API_VERSION_MAJOR(d.api_version)) + "." +
                     std::to_string(VK_API_VERSION_MINOR(d.api_version)) + ")";
    return d;
  }
  const bool core13 = d.api_version >= VK_API_VERSION_1_3;
  const auto extensions = device_extensions(handle);
  const bool atomic_float = has(extensions, VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME);
  d.dynamic_rendering_extension = !core13 && has(extensions, VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME);
  const bool conservative = has(extensions, VK_EXT_CONSERVATIVE_RASTERIZATION_EXTENSION_NAME);

  // Properties: subgroups, and the largest allocation (1.1) and buffer (1.3) the device allows.
  VkPhysicalDeviceMaintenance4Properties maintenance4{
      .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_PROPERTIES};
  VkPhysicalDeviceMaintenance3Properties maintenance3{
      .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES,
      .pNext = core13 ? &maintenance4 : nullptr};
  VkPhysicalDeviceConservativeRasterizationPropertiesEXT conservative_properties{
      .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_CONSERVATIVE_RASTERIZATION_PROPERTIES_EXT,
      .pNext = &maintenance3};
  VkPhysicalDeviceDriverProperties driver{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES,
                                          .pNext = conservative ? static_cast<void*>(&conservative_properties)
                                                                : static_cast<void*>(&maintenance3)};
  VkPhysicalDeviceSubgroupProperties subgroup{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES,
                                              .pNext = &driver};
  VkPhysicalDeviceProperties2 properties2{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2,
                                          .pNext = &subgroup};
  vkGetPhysicalDeviceProperties2(handle, &properties2);
  d.subgroup_size = subgroup.subgroupSize;
  d.info.driver = std::string(driver.driverName) + (driver.driverInfo[0] ? " " : "") + driver.driverInfo;
  // Counting needs every touched texel, so also those of triangles that snap to zero area.
  d.conservative_rasterization = conservative && conservative_properties.degenerateTrianglesRasterized;
  d.max_buffer_size = maintenance3.maxMemoryAllocationSize;
  if (core13) d.max_buffer_size = std::min(d.max_buffer_size, maintenance4.maxBufferSize);

  // Features; each struct is chained only where its version or extension exists.
  VkPhysicalDeviceDynamicRenderingFeatures dynamic_rendering{
      .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES};
  VkPhysicalDeviceVulkan13Features features13{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  d.atomic_float.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT;
  d.features12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
  void* chain = nullptr;
  const auto link = [&chain](auto& s) {
    s.pNext = chain;
    chain = &s;
  };
  link(d.features12);
  if (core13) link(features13);
  if (d.dynamic_rendering_extension) link(dynamic_rendering);
  if (atomic_float) link(d.atomic_float);
  VkPhysicalDeviceFeatures2 features2{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = chain};
  vkGetPhysicalDeviceFeatures2(handle, &features2);
  d.features = features2.features;
  d.features12.pNext = nullptr;
  d.atomic_float.pNext = nullptr;
  d.dynamic_rendering = core13 ? features13.dynamicRendering : dynamic_rendering.dynamicRendering;

  std::vector<std::string> missing;
  if (!pick_queue_family(d)) missing.push_back("a compute queue");
  if (!d.features12.bufferDeviceAddress) missing.push_back("bufferDeviceAddress");
  if (!d.features.shaderInt64) missing.push_back("shaderInt64");
  if (!d.features12.shaderBufferInt64Atomics) missing.push_back("shaderBufferInt64Atomics");
  // Stochastic rounding and the area CDF are in double; 64-bit counts are reduced per subgroup.
  if (!d.features.shaderFloat64) missing.push_back("shaderFloat64");
  if (!d.features12.shaderSubgroupExtendedTypes) missing.push_back("shaderSubgroupExtendedTypes");
  if (!d.atomic_float.shaderBufferFloat32AtomicAdd)
    missing.push_back(atomic_float ? "shaderBufferFloat32AtomicAdd"
                                   : "shaderBufferFloat32AtomicAdd (VK_EXT_shader_atomic_float)");
  const VkSubgroupFeatureFlags subgroup_ops = VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_VOTE_BIT |
                                              VK_SUBGROUP_FEATURE_ARITHMETIC_BIT | VK_SUBGROUP_FEATURE_BALLOT_BIT;
  if ((subgroup.supportedOperations & subgroup_ops) != subgroup_ops ||
      !(subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT))
    missing.push_back("subgroup basic+vote+arithmetic+ballot operations in compute shaders");
  d.info.missing = join(missing);
  d.info.suitable = missing.empty();

  std::vector<std::string> raster_missing;
  if (!d.graphics) raster_missing.push_back("a graphics queue");
  if (!d.dynamic_rendering) raster_missing.push_back("dynamicRendering");
  if (!d.features.fragmentStoresAndAtomics) raster_missing.push_back("fragmentStoresAndAtomics");
  d.raster_missing = join(raster_missing);
  return d;
}

std::string describe(const DeviceSurvey& d) {
  return std::to_string(d.info.index) + ": \"" + d.info.name + "\" (" + type_name(d.info.type) + ", " +
         (d.info.suitable ? "suitable" : "lacks " + d.info.missing) + ")";
}

std::string describe_all(const std::vector<DeviceSurvey>& devices) {
  std::string out;
  for (const auto& d : devices) out += (out.empty() ? "" : "; ") + describe(d);
  return out;
}

// The most preferred suitable device among `candidates` (earliest on ties), or null.
const DeviceSurvey* best(const std::vector<const DeviceSurvey*>& candidates) {
  const DeviceSurvey* chosen = nullptr;
  for (const DeviceSurvey* d : candidates)
    if (d->info.suitable && (!chosen || preference(d->info.type) > preference(chosen->info.type)))
      chosen = d;
  return chosen;
}

}  // namespace

std::vector<DeviceSurvey> survey_devices(const Instance& instance) {
  std::uint32_t count = 0;
  check(vkEnumeratePhysicalDevices(instance.handle(), &count, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> handles(count);
  check(vkEnumeratePhysicalDevices(instance.handle(), &count, handles.data()), "vkEnumeratePhysicalDevices");
  std::vector<DeviceSurvey> devices;
  for (std::uint32_t i = 0; i < count; ++i) devices.push_back(survey(handles[i], i, instance.api_version()));
  return devices;
}

const DeviceSurvey& select_device(const std::vector<DeviceSurvey>& devices, const std::string& request) {
  if (devices.empty())
    throw Unavailable("no Vulkan device found (no driver reports one; on Debian a software device "
                      "comes with mesa-vulkan-drivers)");
  std::vector<const DeviceSurvey*> candidates;
  if (request.empty()) {
    for (const auto& d : devices) candidates.push_back(&d);
    if (const DeviceSurvey* d = best(candidates)) return *d;
    throw Unavailable("no suitable Vulkan device: " + describe_all(devices));
  }
  const bool is_index = std::all_of(request.begin(), request.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (is_index) {
    const unsigned long index = request.size() <= 9 ? std::stoul(request) : devices.size();
    if (index < devices.size()) candidates.push_back(&devices[index]);
  } else {
    for (const auto& d : devices)
      if (lower(d.info.name).find(lower(request)) != std::string::npos) candidates.push_back(&d);
  }
  if (candidates.empty())
    throw Unavailable("Vulkan device \"" + request + "\" not found; available devices: " + describe_all(devices));
  if (const DeviceSurvey* d = best(candidates)) return *d;
  throw Unavailable("Vulkan device " + describe(*candidates.front()) + " cannot run lightsampler");
}

std::vector<DeviceInfo> Context::devices() {
  try {
    std::vector<DeviceInfo> out;
    for (const auto& d : Runtime::get(false).devices()) out.push_back(d.info);
    return out;
  } catch (const Unavailable&) {
    return {};
  }
}

}  // namespace lightsampler::vk
