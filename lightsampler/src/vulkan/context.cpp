// The Context: device creation, buffers with device addresses, and blocking transfers.

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include "vulkan/state.h"

namespace lightsampler::vk {

namespace {

// Transfers larger than this go through the staging buffer in pieces, so it stays small.
constexpr VkDeviceSize kStagingBytes = VkDeviceSize(64) << 20;
// Every buffer has at least this many bytes, so that even an empty one has a valid address.
constexpr VkDeviceSize kMinBufferBytes = 16;

std::string environment(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "";
}

// The first memory type allowed by `type_bits` with `required` and `preferred` flags, else the
// first with `required` ones.
std::uint32_t memory_type(const VkPhysicalDeviceMemoryProperties& memory, std::uint32_t type_bits,
                          VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred) {
  for (const VkMemoryPropertyFlags flags : {required | preferred, required})
    for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i)
      if ((type_bits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & flags) == flags) return i;
  throw Error("no Vulkan memory type is " +
              std::string(required & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT ? "host-visible and coherent"
                                                                         : "usable for a storage buffer"));
}

void check_range(const Buffer& b, VkDeviceSize offset, VkDeviceSize bytes, const char* what) {
  if (offset > b.size() || bytes > b.size() - offset)
    throw std::out_of_range(std::string(what) + ": bytes [" + std::to_string(offset) + ", " +
                            std::to_string(offset + bytes) + ") outside a buffer of " +
                            std::to_string(b.size()) + " bytes");
}

}  // namespace

Context::State::State(Device& d) : device(d) {
  // Resettable buffers: the transfer buffer is re-recorded for every upload and download.
  const VkCommandPoolCreateInfo pool_info{.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                          .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                          .queueFamilyIndex = d.queue_family};
  check(vkCreateCommandPool(d.handle, &pool_info, nullptr, &command_pool), "vkCreateCommandPool");
  const VkCommandBufferAllocateInfo alloc{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                          .commandPool = command_pool,
                                          .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                          .commandBufferCount = 1};
  check(vkAllocateCommandBuffers(d.handle, &alloc, &transfer_commands), "vkAllocateCommandBuffers");
  const VkFenceCreateInfo fence_info{.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  check(vkCreateFence(d.handle, &fence_info, nullptr, &fence), "vkCreateFence");
}

// Every submission of this context has been waited for: nothing of it is still running.
Context::State::~State() {
  for (VkQueryPool pool : query_pools) vkDestroyQueryPool(device.handle, pool, nullptr);
  if (fence != VK_NULL_HANDLE) vkDestroyFence(device.handle, fence, nullptr);
  if (command_pool != VK_NULL_HANDLE) vkDestroyCommandPool(device.handle, command_pool, nullptr);
}

Buffer Context::State::make_buffer(VkDeviceSize bytes, bool host_visible) {
  if (bytes > device.capabilities.max_buffer_size)
    throw Error("a buffer of " + std::to_string(bytes) + " bytes exceeds the largest " + device.name +
                " allows (" + std::to_string(device.capabilities.max_buffer_size) + " bytes)");
  Buffer b;
  b.device_ = device.handle;
  b.size_ = bytes;
  const VkBufferCreateInfo info{.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                                .size = std::max(bytes, kMinBufferBytes),
                                .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                                         VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                         VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                         VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                                .sharingMode = VK_SHARING_MODE_EXCLUSIVE};
  check(vkCreateBuffer(device.handle, &info, nullptr, &b.buffer_), "vkCreateBuffer");

  VkMemoryRequirements requirements;
  vkGetBufferMemoryRequirements(device.handle, b.buffer_, &requirements);
  // Host-visible buffers are mostly read back by the host: cached memory makes that fast.
  const std::uint32_t type =
      host_visible ? memory_type(device.memory, requirements.memoryTypeBits,
                                 VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                                 VK_MEMORY_PROPERTY_HOST_CACHED_BIT)
                   : memory_type(device.memory, requirements.memoryTypeBits, 0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  const VkMemoryAllocateFlagsInfo flags{.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO,
                                        .flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT};
  const VkMemoryAllocateInfo alloc{.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                                   .pNext = &flags,
                                   .allocationSize = requirements.size,
                                   .memoryTypeIndex = type};
  if (const VkResult r = vkAllocateMemory(device.handle, &alloc, nullptr, &b.memory_); r != VK_SUCCESS)
    throw Error("vkAllocateMemory of " + std::to_string(requirements.size) + " bytes (" +
                (host_visible ? "host-visible" : "device-local") + ") failed: " + result_name(r));
  check(vkBindBufferMemory(device.handle, b.buffer_, b.memory_, 0), "vkBindBufferMemory");
  if (host_visible) check(vkMapMemory(device.handle, b.memory_, 0, VK_WHOLE_SIZE, 0, &b.mapped_), "vkMapMemory");
  const VkBufferDeviceAddressInfo address{.sType = VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO,
                                          .buffer = b.buffer_};
  b.address_ = vkGetBufferDeviceAddress(device.handle, &address);
  return b;
}

const Buffer& Context::State::staging_buffer(VkDeviceSize bytes) {
  if (staging.size() < bytes) {
    staging = Buffer();  // free the smaller one before allocating
    staging = make_buffer(bytes, true);
  }
  return staging;
}

std::unique_ptr<Context> Context::create(const ContextOptions& options) {
  std::unique_ptr<Context> context(new Context);
  Runtime& runtime = Runtime::get(options.validation);
  const std::string request =
      options.device.empty() ? environment("LIGHTSAMPLER_VULKAN_DEVICE") : options.device;
  context->state_ = std::make_unique<State>(runtime.device(select_device(runtime.devices(), request)));
  return context;
}

Context::~Context() = default;

const std::string& Context::device_name() const { return state_->device.name; }
const Capabilities& Context::capabilities() const { return state_->device.capabilities; }
// A Context exists, so the runtime does: get() returns it.
bool Context::validation_enabled() const { return Runtime::get(false).instance().validation(); }
std::vector<std::string> Context::validation_messages() const { return Runtime::get(false).log().snapshot(); }

Buffer Context::create_buffer(VkDeviceSize bytes, bool host_visible) {
  return state_->make_buffer(bytes, host_visible);
}

void Context::upload(const Buffer& to, VkDeviceSize offset, const void* data, VkDeviceSize bytes) {
  check_range(to, offset, bytes, "upload");
  if (bytes == 0) return;
  const auto* source = static_cast<const std::byte*>(data);
  if (to.mapped()) {  // every submission has completed: the host may write directly
    std::memcpy(static_cast<std::byte*>(to.mapped()) + offset, source, bytes);
    return;
  }
  State& s = *state_;
  for (VkDeviceSize done = 0; done < bytes;) {
    const VkDeviceSize chunk = std::min(bytes - done, kStagingBytes);
    const Buffer& staging = s.staging_buffer(std::min(bytes, kStagingBytes));
    std::memcpy(staging.mapped(), source + done, chunk);
    s.run_transfer([&](VkCommandBuffer cmd) {
      // Earlier shader writes to the range land before the copy; the copy before later passes.
      memory_barrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                     VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
      const VkBufferCopy region{.srcOffset = 0, .dstOffset = offset + done, .size = chunk};
      vkCmdCopyBuffer(cmd, staging.handle(), to.handle(), 1, &region);
      memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                     VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
    });
    done += chunk;
  }
}

void Context::download(const Buffer& from, VkDeviceSize offset, void* data, VkDeviceSize bytes) {
  check_range(from, offset, bytes, "download");
  if (bytes == 0) return;
  auto* target = static_cast<std::byte*>(data);
  if (from.mapped()) {  // submit() ends with a barrier that makes device writes host-visible
    std::memcpy(target, static_cast<const std::byte*>(from.mapped()) + offset, bytes);
    return;
  }
  State& s = *state_;
  for (VkDeviceSize done = 0; done < bytes;) {
    const VkDeviceSize chunk = std::min(bytes - done, kStagingBytes);
    const Buffer& staging = s.staging_buffer(std::min(bytes, kStagingBytes));
    s.run_transfer([&](VkCommandBuffer cmd) {
      memory_barrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                     VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT);
      const VkBufferCopy region{.srcOffset = offset + done, .dstOffset = 0, .size = chunk};
      vkCmdCopyBuffer(cmd, from.handle(), staging.handle(), 1, &region);
      memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                     VK_ACCESS_HOST_READ_BIT);
    });
    std::memcpy(target + done, staging.mapped(), chunk);
    done += chunk;
  }
}

Buffer::Buffer(Buffer&& other) noexcept
    : device_(std::exchange(other.device_, VK_NULL_HANDLE)),
      buffer_(std::exchange(other.buffer_, VK_NULL_HANDLE)),
      memory_(std::exchange(other.memory_, VK_NULL_HANDLE)),
      address_(std::exchange(other.address_, 0)),
      size_(std::exchange(other.size_, 0)),
      mapped_(std::exchange(other.mapped_, nullptr)) {}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    Buffer old(std::move(*this));  // freed at the end of this scope
    device_ = std::exchange(other.device_, VK_NULL_HANDLE);
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    address_ = std::exchange(other.address_, 0);
    size_ = std::exchange(other.size_, 0);
    mapped_ = std::exchange(other.mapped_, nullptr);
  }
  return *this;
}

Buffer::~Buffer() {
  // Freeing the memory also unmaps it.
  if (buffer_ != VK_NULL_HANDLE) vkDestroyBuffer(device_, buffer_, nullptr);
  if (memory_ != VK_NULL_HANDLE) vkFreeMemory(device_, memory_, nullptr);
}

}  // namespace lightsampler::vk
