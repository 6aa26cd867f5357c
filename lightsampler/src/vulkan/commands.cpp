// Command recording, blocking submission, and GPU timestamps between passes.

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "vulkan/state.h"

namespace lightsampler::vk {

void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags src_stages, VkAccessFlags src_access,
                    VkPipelineStageFlags dst_stages, VkAccessFlags dst_access) {
  const VkMemoryBarrier barrier{.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                                .srcAccessMask = src_access,
                                .dstAccessMask = dst_access};
  vkCmdPipelineBarrier(cmd, src_stages, dst_stages, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

void Context::State::submit_and_wait(VkCommandBuffer cmd) {
  check(vkResetFences(device.handle, 1, &fence), "vkResetFences");
  device.submit(cmd, fence);
  check(vkWaitForFences(device.handle, 1, &fence, VK_TRUE, std::numeric_limits<std::uint64_t>::max()),
        "vkWaitForFences");
}

void Context::State::run_transfer(const std::function<void(VkCommandBuffer)>& record) {
  const VkCommandBufferBeginInfo begin{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                       .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
  check(vkBeginCommandBuffer(transfer_commands, &begin), "vkBeginCommandBuffer");
  record(transfer_commands);
  check(vkEndCommandBuffer(transfer_commands), "vkEndCommandBuffer");
  submit_and_wait(transfer_commands);
}

// Every Commands uses the same query slots (0 at begin(), then one per stamp). That is safe because
// each query is reset right before it is written and read back before submit() returns.
void Context::State::write_timestamp(VkCommandBuffer cmd, std::uint32_t slot) {
  if (device.timestamp_mask == 0) return;
  const std::uint32_t pool = slot / kQueriesPerPool, query = slot % kQueriesPerPool;
  while (query_pools.size() <= pool) {
    const VkQueryPoolCreateInfo info{.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
                                     .queryType = VK_QUERY_TYPE_TIMESTAMP,
                                     .queryCount = kQueriesPerPool};
    VkQueryPool created;
    check(vkCreateQueryPool(device.handle, &info, nullptr, &created), "vkCreateQueryPool");
    query_pools.push_back(created);
  }
  vkCmdResetQueryPool(cmd, query_pools[pool], query, 1);
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, query_pools[pool], query);
}

std::vector<std::uint64_t> Context::State::read_timestamps(std::uint32_t count) {
  std::vector<std::uint64_t> ticks(count);
  for (std::uint32_t first = 0; first < count; first += kQueriesPerPool) {
    const std::uint32_t n = std::min(count - first, kQueriesPerPool);
    check(vkGetQueryPoolResults(device.handle, query_pools[first / kQueriesPerPool], 0, n,
                                n * sizeof(std::uint64_t), ticks.data() + first, sizeof(std::uint64_t),
                                VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
          "vkGetQueryPoolResults");
  }
  return ticks;
}

Commands Context::begin() {
  State& s = *state_;
  Commands c;
  c.context_ = this;
  const VkCommandBufferAllocateInfo alloc{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                          .commandPool = s.command_pool,
                                          .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                          .commandBufferCount = 1};
  check(vkAllocateCommandBuffers(s.device.handle, &alloc, &c.cmd_), "vkAllocateCommandBuffers");
  const VkCommandBufferBeginInfo begin{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                       .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
  check(vkBeginCommandBuffer(c.cmd_, &begin), "vkBeginCommandBuffer");
  s.write_timestamp(c.cmd_, 0);
  return c;
}

std::vector<std::pair<std::string, double>> Context::submit(Commands& c) {
  if (c.cmd_ == VK_NULL_HANDLE || c.context_ != this)
    throw std::logic_error("Context::submit: these commands were not begun on this context, or were submitted");
  State& s = *state_;
  // Device writes become visible to the host, for buffers it reads through their mapping.
  memory_barrier(c.cmd_, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                 VK_ACCESS_HOST_READ_BIT);
  check(vkEndCommandBuffer(c.cmd_), "vkEndCommandBuffer");
  s.submit_and_wait(c.cmd_);

  std::vector<std::pair<std::string, double>> times;
  const std::uint32_t stamps = std::uint32_t(c.stamps_.size());
  const auto ticks = s.device.timestamp_mask != 0 ? s.read_timestamps(stamps + 1) : std::vector<std::uint64_t>();
  for (std::uint32_t i = 0; i < stamps; ++i) {
    const double ms = ticks.empty() ? std::nan("")
                                    : double((ticks[i + 1] - ticks[i]) & s.device.timestamp_mask) *
                                          s.device.capabilities.timestamp_period_ns * 1e-6;
    times.emplace_back(std::move(c.stamps_[i]), ms);
  }
  Commands finished(std::move(c));  // frees the command buffer
  return times;
}

Commands::Commands(Commands&& other) noexcept
    : cmd_(std::exchange(other.cmd_, VK_NULL_HANDLE)),
      stamps_(std::move(other.stamps_)),
      context_(std::exchange(other.context_, nullptr)) {}

Commands& Commands::operator=(Commands&& other) noexcept {
  if (this != &other) {
    Commands old(std::move(*this));  // freed at the end of this scope
    cmd_ = std::exchange(other.cmd_, VK_NULL_HANDLE);
    stamps_ = std::move(other.stamps_);
    context_ = std::exchange(other.context_, nullptr);
  }
  return *this;
}

Commands::~Commands() {
  if (cmd_ == VK_NULL_HANDLE) return;
  const Context::State& s = *context_->state_;
  vkFreeCommandBuffers(s.device.handle, s.command_pool, 1, &cmd_);
}

void Commands::dispatch(const ComputePipeline& p, const void* push, std::uint32_t push_size, std::uint32_t groups) {
  const std::uint32_t limit = context_->state_->device.capabilities.max_workgroup_count_x;
  if (groups > limit)
    throw std::invalid_argument("dispatch of " + std::to_string(groups) + " workgroups; the device allows " +
                                std::to_string(limit));
  bind(p, push, push_size);
  vkCmdDispatch(cmd_, groups, 1, 1);
}

void Commands::dispatch_indirect(const ComputePipeline& p, const void* push, std::uint32_t push_size,
                                 const Buffer& args, VkDeviceSize offset) {
  bind(p, push, push_size);
  vkCmdDispatchIndirect(cmd_, args.handle(), offset);
}

void Commands::bind(const ComputePipeline& p, const void* push, std::uint32_t push_size) {
  vkCmdBindPipeline(cmd_, VK_PIPELINE_BIND_POINT_COMPUTE, p.handle());
  if (push_size > 0) vkCmdPushConstants(cmd_, p.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, push_size, push);
}

void Commands::draw(const RasterPipeline& p, const void* push, std::uint32_t push_size, std::uint32_t width,
                    std::uint32_t height, std::uint32_t vertices) {
  const Context::State& s = *context_->state_;
  const VkRect2D area{{0, 0}, {width, height}};
  const VkRenderingInfo rendering{.sType = VK_STRUCTURE_TYPE_RENDERING_INFO, .renderArea = area, .layerCount = 1};
  s.device.begin_rendering(cmd_, &rendering);
  vkCmdBindPipeline(cmd_, VK_PIPELINE_BIND_POINT_GRAPHICS, p.handle());
  if (push_size > 0) vkCmdPushConstants(cmd_, p.layout(), p.push_stages_, 0, push_size, push);
  const VkViewport viewport{0.0f, 0.0f, float(width), float(height), 0.0f, 1.0f};
  vkCmdSetViewport(cmd_, 0, 1, &viewport);
  vkCmdSetScissor(cmd_, 0, 1, &area);
  vkCmdDraw(cmd_, vertices, 1, 0, 0);
  s.device.end_rendering(cmd_);
}

void Commands::fill(const Buffer& b, VkDeviceSize offset, VkDeviceSize size, std::uint32_t value) {
  if (size > 0) vkCmdFillBuffer(cmd_, b.handle(), offset, size, value);
}

void Commands::copy(const Buffer& from, VkDeviceSize from_offset, const Buffer& to, VkDeviceSize to_offset,
                    VkDeviceSize size) {
  if (size == 0) return;
  const VkBufferCopy region{.srcOffset = from_offset, .dstOffset = to_offset, .size = size};
  vkCmdCopyBuffer(cmd_, from.handle(), to.handle(), 1, &region);
}

void Commands::barrier() {
  memory_barrier(cmd_, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                 VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
}

void Commands::timestamp(std::string name) {
  stamps_.push_back(std::move(name));
  context_->state_->write_timestamp(cmd_, std::uint32_t(stamps_.size()));
}

}  // namespace lightsampler::vk
