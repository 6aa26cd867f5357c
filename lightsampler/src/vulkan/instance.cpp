// The Vulkan instance, the validation layer and its messages, and the error check every call uses.

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "vulkan/state.h"

namespace lightsampler::vk {

const char* result_name(VkResult result) {
  switch (result) {
#define LIGHTSAMPLER_RESULT(name) \
  case name: return #name;
    LIGHTSAMPLER_RESULT(VK_SUCCESS)
    LIGHTSAMPLER_RESULT(VK_NOT_READY)
    LIGHTSAMPLER_RESULT(VK_TIMEOUT)
    LIGHTSAMPLER_RESULT(VK_INCOMPLETE)
    LIGHTSAMPLER_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY)
    LIGHTSAMPLER_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    LIGHTSAMPLER_RESULT(VK_ERROR_INITIALIZATION_FAILED)
    LIGHTSAMPLER_RESULT(VK_ERROR_DEVICE_LOST)
    LIGHTSAMPLER_RESULT(VK_ERROR_MEMORY_MAP_FAILED)
    LIGHTSAMPLER_RESULT(VK_ERROR_LAYER_NOT_PRESENT)
    LIGHTSAMPLER_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT)
    LIGHTSAMPLER_RESULT(VK_ERROR_FEATURE_NOT_PRESENT)
    LIGHTSAMPLER_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER)
    LIGHTSAMPLER_RESULT(VK_ERROR_TOO_MANY_OBJECTS)
    LIGHTSAMPLER_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED)
    LIGHTSAMPLER_RESULT(VK_ERROR_FRAGMENTED_POOL)
    LIGHTSAMPLER_RESULT(VK_ERROR_UNKNOWN)
    LIGHTSAMPLER_RESULT(VK_ERROR_OUT_OF_POOL_MEMORY)
    LIGHTSAMPLER_RESULT(VK_ERROR_FRAGMENTATION)
    LIGHTSAMPLER_RESULT(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
    LIGHTSAMPLER_RESULT(VK_ERROR_INVALID_SHADER_NV)
#undef LIGHTSAMPLER_RESULT
    default: return "unknown VkResult";
  }
}

void check(VkResult result, const char* call) {
  if (result != VK_SUCCESS)
    throw Error(std::string(call) + " failed: " + result_name(result) + " (" +
                std::to_string(int(result)) + ")");
}

namespace {
std::atomic<std::size_t> process_message_count{0};
}  // namespace

std::size_t validation_message_count() { return process_message_count.load(); }

void MessageLog::add(std::string message) {
  process_message_count.fetch_add(1);
  const std::lock_guard lock(mutex_);
  messages_.push_back(std::move(message));
}

std::vector<std::string> MessageLog::snapshot() const {
  const std::lock_guard lock(mutex_);
  return messages_;
}

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                          VkDebugUtilsMessageTypeFlagsEXT,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data,
                                          void* log) {
  const char* level = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning";
  std::string message = std::string("Vulkan ") + level + ": " + (data->pMessage ? data->pMessage : "");
  std::fprintf(stderr, "lightsampler: %s\n", message.c_str());
  static_cast<MessageLog*>(log)->add(std::move(message));
  return VK_FALSE;  // never abort the call that triggered the message
}

bool layer_installed(const char* name) {
  std::uint32_t count = 0;
  check(vkEnumerateInstanceLayerProperties(&count, nullptr), "vkEnumerateInstanceLayerProperties");
  std::vector<VkLayerProperties> layers(count);
  check(vkEnumerateInstanceLayerProperties(&count, layers.data()), "vkEnumerateInstanceLayerProperties");
  return std::any_of(layers.begin(), layers.begin() + count,
                     [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

std::string version_string(std::uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v));
}

}  // namespace

Instance::Instance(bool validation, MessageLog* log) {
  std::uint32_t loader_version = 0;
  if (vkEnumerateInstanceVersion(&loader_version) != VK_SUCCESS || loader_version < VK_API_VERSION_1_2)
    throw Unavailable("the Vulkan loader supports Vulkan " + version_string(loader_version) +
                      "; lightsampler needs 1.2 or newer");
  // 1.3 brings dynamic rendering into core; a 1.2 device still works through the extension.
  api_version_ = std::min<std::uint32_t>(loader_version, VK_API_VERSION_1_3);

  if (validation && !layer_installed(kValidationLayer)) {
    std::fprintf(stderr,
                 "lightsampler: Vulkan validation requested but %s is not installed "
                 "(Debian: vulkan-validationlayers); running without it\n",
                 kValidationLayer);
    validation = false;
  }

  VkApplicationInfo app{.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
                        .pApplicationName = "lightsampler",
                        .pEngineName = "lightsampler",
                        .apiVersion = api_version_};
  VkDebugUtilsMessengerCreateInfoEXT messenger_info{
      .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
      .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                         VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
      .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
      .pfnUserCallback = on_message,
      .pUserData = log};
  const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  VkInstanceCreateInfo info{.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
                            // Chained, the messenger also hears vkCreateInstance and vkDestroyInstance.
                            .pNext = validation ? &messenger_info : nullptr,
                            .pApplicationInfo = &app,
                            .enabledLayerCount = validation ? 1u : 0u,
                            .ppEnabledLayerNames = &kValidationLayer,
                            .enabledExtensionCount = validation ? 1u : 0u,
                            .ppEnabledExtensionNames = &extension};
  if (const VkResult r = vkCreateInstance(&info, nullptr, &instance_); r != VK_SUCCESS)
    throw Unavailable(std::string("no usable Vulkan driver: vkCreateInstance failed: ") + result_name(r) +
                      (r == VK_ERROR_INCOMPATIBLE_DRIVER ? " (no Vulkan ICD found; on Debian a software "
                                                           "device comes with mesa-vulkan-drivers)"
                                                         : ""));
  if (validation) {
    const auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    const VkResult r = create(instance_, &messenger_info, nullptr, &messenger_);
    if (r != VK_SUCCESS) {
      vkDestroyInstance(instance_, nullptr);
      check(r, "vkCreateDebugUtilsMessengerEXT");
    }
  }
}

Instance::~Instance() {
  if (messenger_ != VK_NULL_HANDLE) {
    const auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(instance_, messenger_, nullptr);
  }
  if (instance_ != VK_NULL_HANDLE) vkDestroyInstance(instance_, nullptr);
}

}  // namespace lightsampler::vk
