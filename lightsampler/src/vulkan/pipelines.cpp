// Compute and raster pipelines from embedded SPIR-V. Shaders reach memory through device addresses
// in their push constants, so layouts have no descriptor sets.

#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "vulkan/state.h"

namespace lightsampler::vk {

namespace {

// A shader module lives only until its pipeline is created.
class ShaderModule {
 public:
  ShaderModule(VkDevice device, std::span<const std::uint32_t> spirv) : device_(device) {
    if (spirv.empty()) throw std::invalid_argument("empty SPIR-V");
    const VkShaderModuleCreateInfo info{.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
                                        .codeSize = spirv.size_bytes(),
                                        .pCode = spirv.data()};
    check(vkCreateShaderModule(device, &info, nullptr, &module_), "vkCreateShaderModule");
  }
  ~ShaderModule() { vkDestroyShaderModule(device_, module_, nullptr); }
  ShaderModule(const ShaderModule&) = delete;
  ShaderModule& operator=(const ShaderModule&) = delete;
  VkShaderModule handle() const { return module_; }

 private:
  VkDevice device_;
  VkShaderModule module_ = VK_NULL_HANDLE;
};

void check_push_size(std::uint32_t push_size, std::uint32_t limit) {
  if (push_size % 4 != 0 || push_size > limit)
    throw std::invalid_argument("push constants of " + std::to_string(push_size) +
                                " bytes: must be a multiple of 4 and at most " + std::to_string(limit));
}

VkPipelineLayout make_layout(VkDevice device, VkShaderStageFlags stages, std::uint32_t push_size) {
  const VkPushConstantRange range{.stageFlags = stages, .offset = 0, .size = push_size};
  const VkPipelineLayoutCreateInfo info{.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                        .pushConstantRangeCount = push_size > 0 ? 1u : 0u,
                                        .pPushConstantRanges = &range};
  VkPipelineLayout layout;
  check(vkCreatePipelineLayout(device, &info, nullptr, &layout), "vkCreatePipelineLayout");
  return layout;
}

// Specialization constants 0, 1, ... of 32 bits each, as create_compute documents; the entries
// must outlive the pipeline's creation.
class Specialization {
 public:
  explicit Specialization(std::span<const std::uint32_t> values) {
    for (std::uint32_t i = 0; i < values.size(); ++i)
      entries_.push_back({.constantID = i, .offset = i * 4, .size = 4});
    info_ = {.mapEntryCount = std::uint32_t(entries_.size()),
             .pMapEntries = entries_.data(),
             .dataSize = values.size_bytes(),
             .pData = values.data()};
  }
  Specialization(const Specialization&) = delete;
  Specialization& operator=(const Specialization&) = delete;
  const VkSpecializationInfo* info() const { return entries_.empty() ? nullptr : &info_; }

 private:
  std::vector<VkSpecializationMapEntry> entries_;
  VkSpecializationInfo info_{};
};

VkPipelineShaderStageCreateInfo stage_info(VkShaderStageFlagBits stage, const ShaderModule& module,
                                           const Specialization& specialization) {
  return {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
          .stage = stage,
          .module = module.handle(),
          .pName = "main",
          .pSpecializationInfo = specialization.info()};
}

void destroy(VkDevice device, VkPipeline pipeline, VkPipelineLayout layout) {
  if (pipeline != VK_NULL_HANDLE) vkDestroyPipeline(device, pipeline, nullptr);
  if (layout != VK_NULL_HANDLE) vkDestroyPipelineLayout(device, layout, nullptr);
}

}  // namespace

ComputePipeline Context::create_compute(std::span<const std::uint32_t> spirv, std::uint32_t push_size,
                                        std::span<const std::uint32_t> specialization) {
  State& s = *state_;
  check_push_size(push_size, s.device.max_push_size);
  const ShaderModule module(s.device.handle, spirv);
  const Specialization constants(specialization);
  ComputePipeline p;
  p.device_ = s.device.handle;
  p.layout_ = make_layout(p.device_, VK_SHADER_STAGE_COMPUTE_BIT, push_size);
  const VkComputePipelineCreateInfo info{.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
                                         .stage = stage_info(VK_SHADER_STAGE_COMPUTE_BIT, module, constants),
                                         .layout = p.layout_};
  check(vkCreateComputePipelines(p.device_, VK_NULL_HANDLE, 1, &info, nullptr, &p.pipeline_),
        "vkCreateComputePipelines");
  return p;
}

RasterPipeline Context::create_raster(const RasterStages& stages, std::uint32_t push_size) {
  State& s = *state_;
  const Device& d = s.device;
  if (!d.raster_missing.empty()) throw Unavailable(d.name + " cannot rasterize: it lacks " + d.raster_missing);
  if (!stages.geometry.empty() && !d.capabilities.geometry_shader)
    throw Unavailable(d.name + " lacks geometryShader");
  if (stages.conservative && !d.capabilities.conservative_rasterization)
    throw Unavailable(d.name + " lacks VK_EXT_conservative_rasterization");
  check_push_size(push_size, s.device.max_push_size);

  const ShaderModule vertex(s.device.handle, stages.vertex);
  const Specialization constants(stages.specialization);
  std::vector<VkPipelineShaderStageCreateInfo> stage_infos{stage_info(VK_SHADER_STAGE_VERTEX_BIT, vertex, constants)};
  VkShaderStageFlags stage_flags = VK_SHADER_STAGE_VERTEX_BIT;
  std::optional<ShaderModule> geometry, fragment;
  if (!stages.geometry.empty()) {
    stage_infos.push_back(
        stage_info(VK_SHADER_STAGE_GEOMETRY_BIT, geometry.emplace(s.device.handle, stages.geometry), constants));
    stage_flags |= VK_SHADER_STAGE_GEOMETRY_BIT;
  }
  if (!stages.fragment.empty()) {
    stage_infos.push_back(
        stage_info(VK_SHADER_STAGE_FRAGMENT_BIT, fragment.emplace(s.device.handle, stages.fragment), constants));
    stage_flags |= VK_SHADER_STAGE_FRAGMENT_BIT;
  }

  RasterPipeline p;
  p.device_ = s.device.handle;
  p.push_stages_ = stage_flags;
  p.layout_ = make_layout(p.device_, stage_flags, push_size);

  const VkPipelineVertexInputStateCreateInfo vertex_input{
      .sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  const VkPipelineInputAssemblyStateCreateInfo assembly{
      .sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO,
      .topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST};
  const VkPipelineViewportStateCreateInfo viewport{.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO,
                                                   .viewportCount = 1,
                                                   .scissorCount = 1};
  // Overestimation covers every pixel a triangle touches, however little.
  const VkPipelineRasterizationConservativeStateCreateInfoEXT conservative{
      .sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_CONSERVATIVE_STATE_CREATE_INFO_EXT,
      .conservativeRasterizationMode = VK_CONSERVATIVE_RASTERIZATION_MODE_OVERESTIMATE_EXT,
      .extraPrimitiveOverestimationSize = 0.0f};
  const VkPipelineRasterizationStateCreateInfo rasterization{
      .sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO,
      .pNext = stages.conservative ? &conservative : nullptr,
      .polygonMode = VK_POLYGON_MODE_FILL,
      .cullMode = VK_CULL_MODE_NONE,
      .frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE,
      .lineWidth = 1.0f};
  const VkPipelineMultisampleStateCreateInfo multisample{
      .sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO,
      .rasterizationSamples = VK_SAMPLE_COUNT_1_BIT};
  const VkPipelineColorBlendStateCreateInfo blend{.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  const VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  const VkPipelineDynamicStateCreateInfo dynamic{.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO,
                                                 .dynamicStateCount = 2,
                                                 .pDynamicStates = dynamic_states};
  // Dynamic rendering with no attachments: fragments only have side effects through memory.
  const VkPipelineRenderingCreateInfo rendering{.sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  const VkGraphicsPipelineCreateInfo info{.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO,
                                          .pNext = &rendering,
                                          .stageCount = std::uint32_t(stage_infos.size()),
                                          .pStages = stage_infos.data(),
                                          .pVertexInputState = &vertex_input,
                                          .pInputAssemblyState = &assembly,
                                          .pViewportState = &viewport,
                                          .pRasterizationState = &rasterization,
                                          .pMultisampleState = &multisample,
                                          .pColorBlendState = &blend,
                                          .pDynamicState = &dynamic,
                                          .layout = p.layout_};
  check(vkCreateGraphicsPipelines(p.device_, VK_NULL_HANDLE, 1, &info, nullptr, &p.pipeline_),
        "vkCreateGraphicsPipelines");
  return p;
}

ComputePipeline::ComputePipeline(ComputePipeline&& other) noexcept
    : device_(std::exchange(other.device_, VK_NULL_HANDLE)),
      pipeline_(std::exchange(other.pipeline_, VK_NULL_HANDLE)),
      layout_(std::exchange(other.layout_, VK_NULL_HANDLE)) {}

ComputePipeline& ComputePipeline::operator=(ComputePipeline&& other) noexcept {
  if (this != &other) {
    ComputePipeline old(std::move(*this));  // destroyed at the end of this scope
    device_ = std::exchange(other.device_, VK_NULL_HANDLE);
    pipeline_ = std::exchange(other.pipeline_, VK_NULL_HANDLE);
    layout_ = std::exchange(other.layout_, VK_NULL_HANDLE);
  }
  return *this;
}

ComputePipeline::~ComputePipeline() { destroy(device_, pipeline_, layout_); }

RasterPipeline::RasterPipeline(RasterPipeline&& other) noexcept
    : device_(std::exchange(other.device_, VK_NULL_HANDLE)),
      pipeline_(std::exchange(other.pipeline_, VK_NULL_HANDLE)),
      layout_(std::exchange(other.layout_, VK_NULL_HANDLE)),
      push_stages_(std::exchange(other.push_stages_, 0)) {}

RasterPipeline& RasterPipeline::operator=(RasterPipeline&& other) noexcept {
  if (this != &other) {
    RasterPipeline old(std::move(*this));  // destroyed at the end of this scope
    device_ = std::exchange(other.device_, VK_NULL_HANDLE);
    pipeline_ = std::exchange(other.pipeline_, VK_NULL_HANDLE);
    layout_ = std::exchange(other.layout_, VK_NULL_HANDLE);
    push_stages_ = std::exchange(other.push_stages_, 0);
  }
  return *this;
}

RasterPipeline::~RasterPipeline() { destroy(device_, pipeline_, layout_); }

}  // namespace lightsampler::vk
