#pragma once
// The Vulkan runtime the GPU backend stands on: the process's one instance and one device per GPU,
// RAII resources, compute and raster pipelines built from embedded SPIR-V, command recording with
// GPU timestamps.
// Every buffer is reached from shaders by its device address (no descriptor sets).

#include <vulkan/vulkan.h>

#include "lightsampler/vulkan.h"

#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace lightsampler::vk {

/// No usable Vulkan device, or one lacks a required feature: the message names what is missing.
using Unavailable = lightsampler::VulkanUnavailable;

/// A Vulkan call failed: the message names the call and the VkResult.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct DeviceInfo {
  std::string name;
  VkPhysicalDeviceType type;
  std::uint32_t index;  ///< position in vkEnumeratePhysicalDevices
  bool suitable;        ///< has every feature the sampler needs
  std::string missing;  ///< what it lacks, when not suitable
  std::string driver;   ///< driver name and version, as the driver reports them (Vulkan 1.2)
};

/// "discrete GPU", "integrated GPU", "virtual GPU", "CPU" or "other".
const char* type_name(VkPhysicalDeviceType type);

struct ContextOptions {
  /// Device by name (case-insensitive substring) or index; empty: the environment variable
  /// LIGHTSAMPLER_VULKAN_DEVICE, else the best suitable device (discrete > integrated > virtual
  /// > cpu).
  std::string device;
  /// Khronos validation layer: on when requested by the process's first Context (or sampler),
  /// by LIGHTSAMPLER_VULKAN_VALIDATION=1 or in a Debug build, if installed. The instance is made
  /// once, so a later request cannot turn it on (it says so on stderr). Validation messages of severity warning or error are collected (see
  /// Context::validation_messages) and also printed to stderr.
  bool validation = false;
};

/// The device's capabilities the sampler adapts to.
struct Capabilities {
  std::uint32_t subgroup_size;
  /// VK_EXT_conservative_rasterization enabled (only where degenerate triangles rasterize too)
  bool conservative_rasterization;
  float timestamp_period_ns;
  std::uint32_t max_workgroup_count_x;
  VkDeviceSize max_buffer_size;     ///< largest single buffer we may create
  VkDeviceSize device_local_bytes;  ///< size of the largest device-local memory heap
  std::uint32_t sub_pixel_bits;     ///< precision of rasterized vertex positions
  bool raster;                      ///< create_raster works (graphics queue, dynamic rendering,
                                    ///< fragmentStoresAndAtomics)
  bool geometry_shader;             ///< raster pipelines may have a geometry stage
  bool vulkan_memory_model;         ///< vulkanMemoryModel and its device scope enabled (the
                                    ///< lookback scan needs them)
};

/// A device-local buffer with a device address; optionally host-visible (mapped).
class Buffer {
 public:
  Buffer() = default;
  Buffer(Buffer&&) noexcept;
  Buffer& operator=(Buffer&&) noexcept;
  ~Buffer();
  VkBuffer handle() const { return buffer_; }
  VkDeviceAddress address() const { return address_; }
  VkDeviceSize size() const { return size_; }  ///< as requested; 0 still has a valid address
  void* mapped() const { return mapped_; }  ///< null unless created host-visible
  explicit operator bool() const { return buffer_ != VK_NULL_HANDLE; }

 private:
  friend class Context;
  VkDevice device_ = VK_NULL_HANDLE;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceAddress address_ = 0;
  VkDeviceSize size_ = 0;
  void* mapped_ = nullptr;
};

/// A compute pipeline: one shader, push constants only.
class ComputePipeline {
 public:
  ComputePipeline() = default;
  ComputePipeline(ComputePipeline&&) noexcept;
  ComputePipeline& operator=(ComputePipeline&&) noexcept;
  ~ComputePipeline();
  VkPipeline handle() const { return pipeline_; }
  VkPipelineLayout layout() const { return layout_; }

 private:
  friend class Context;
  VkDevice device_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
};

/// A graphics pipeline rasterizing triangle lists without attachments (dynamic rendering,
/// dynamic viewport and scissor), push constants visible to every stage. Vertex input: none
/// (shaders fetch by gl_VertexIndex through device addresses). The geometry shader is optional;
/// conservative rasterization is enabled when `conservative` is true.
struct RasterStages {
  std::span<const std::uint32_t> vertex, geometry, fragment;  ///< geometry may be empty
  bool conservative = false;
  std::span<const std::uint32_t> specialization;  ///< of every stage, as for create_compute
};
class RasterPipeline {
 public:
  RasterPipeline() = default;
  RasterPipeline(RasterPipeline&&) noexcept;
  RasterPipeline& operator=(RasterPipeline&&) noexcept;
  ~RasterPipeline();
  VkPipeline handle() const { return pipeline_; }
  VkPipelineLayout layout() const { return layout_; }

 private:
  friend class Context;
  friend class Commands;
  VkDevice device_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkShaderStageFlags push_stages_ = 0;  ///< the stages the push-constant range names
};

class Context;

/// Records one command buffer; named timestamps are written between passes. Dropped without
/// Context::submit, nothing runs. Must not outlive its Context.
class Commands {
 public:
  Commands(Commands&&) noexcept;
  Commands& operator=(Commands&&) noexcept;
  ~Commands();

  /// Binds and dispatches `groups` workgroups in x (at most max_workgroup_count_x, else throws
  /// std::invalid_argument).
  void dispatch(const ComputePipeline& p, const void* push, std::uint32_t push_size, std::uint32_t groups);
  /// Dispatches the workgroup counts (x, y, z: three uint32) at byte `offset` of `args`, written
  /// on the device by an earlier pass (with a barrier between).
  void dispatch_indirect(const ComputePipeline& p, const void* push, std::uint32_t push_size, const Buffer& args,
                         VkDeviceSize offset);
  /// Begins dynamic rendering over a width x height area with no attachments, sets viewport
  /// and scissor to it, draws `vertices` vertices with the pipeline, ends rendering.
  void draw(const RasterPipeline& p, const void* push, std::uint32_t push_size, std::uint32_t width,
            std::uint32_t height, std::uint32_t vertices);
  /// Offset and size are multiples of 4 (vkCmdFillBuffer); size 0 records nothing.
  void fill(const Buffer& b, VkDeviceSize offset, VkDeviceSize size, std::uint32_t value);
  void copy(const Buffer& from, VkDeviceSize from_offset, const Buffer& to, VkDeviceSize to_offset,
            VkDeviceSize size);
  /// Full memory barrier between passes (shader writes and transfers -> shader reads, writes
  /// and transfers; all stages).
  void barrier();
  /// Writes a timestamp after all previous work; Context::submit returns the times between them.
  void timestamp(std::string name);

 private:
  friend class Context;
  Commands() = default;
  void bind(const ComputePipeline& p, const void* push, std::uint32_t push_size);
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  std::vector<std::string> stamps_;
  Context* context_ = nullptr;
};

/// Validation warnings and errors reported so far in the process (tests assert that it does not
/// grow).
std::size_t validation_message_count();

/// A user of the device: its command objects, timestamps and staging memory. Contexts share the
/// process's VkInstance and the VkDevice of their physical device, both created on first use and
/// kept until the process exits; destroying a Context frees only what it made. One thread at a
/// time per Context (validation_messages() excepted); several Contexts may be used from several
/// threads. Buffers, pipelines and Commands must be destroyed before their Context.

class Context {
 public:
  /// Throws Unavailable with a clear message (no loader, no device, device named but not found,
  /// or the chosen device lacks: Vulkan 1.2+, bufferDeviceAddress, shaderInt64,
  /// shaderBufferInt64Atomics, shaderBufferFloat32AtomicAdd, subgroup arithmetic+ballot+vote).
  static std::unique_ptr<Context> create(const ContextOptions& options = {});
  /// Every physical device with its suitability; empty if Vulkan itself is unavailable.
  static std::vector<DeviceInfo> devices();
  ~Context();

  const std::string& device_name() const;
  const Capabilities& capabilities() const;
  bool validation_enabled() const;
  /// Validation warnings and errors reported so far in the process.
  std::vector<std::string> validation_messages() const;

  /// Throws Error when the device cannot hold it (larger than max_buffer_size, out of memory).
  Buffer create_buffer(VkDeviceSize bytes, bool host_visible = false);
  /// Blocking transfers through a staging buffer (or directly when host-visible); a range
  /// outside the buffer throws std::out_of_range.
  void upload(const Buffer& to, VkDeviceSize offset, const void* data, VkDeviceSize bytes);
  void download(const Buffer& from, VkDeviceSize offset, void* data, VkDeviceSize bytes);

  /// push_size: bytes of push constants, a multiple of 4 within the device's limit (else
  /// std::invalid_argument). specialization[i]: the value of specialization constant i (32 bits;
  /// a bool is 0 or 1); constants the shader does not declare are ignored.
  ComputePipeline create_compute(std::span<const std::uint32_t> spirv, std::uint32_t push_size,
                                 std::span<const std::uint32_t> specialization = {});
  /// Throws Unavailable naming what is missing when !capabilities().raster, or when a geometry
  /// stage or conservative rasterization is asked for and the device lacks it.
  RasterPipeline create_raster(const RasterStages& stages, std::uint32_t push_size);

  /// Starts recording; submit() runs it and waits. Returns (name, milliseconds since the
  /// previous timestamp or the start) for each timestamp, from GPU timestamp queries (NaN if
  /// the queue has none).
  Commands begin();
  std::vector<std::pair<std::string, double>> submit(Commands& commands);

 private:
  Context() = default;
  struct State;
  std::unique_ptr<State> state_;
  friend class Commands;
};

}  // namespace lightsampler::vk
