#include "vulkan/passes.h"

#include <algorithm>
#include <array>
#include <stdexcept>

#include "spirv/counting_cells_comp.h"
#include "spirv/counting_setup_comp.h"
#include "spirv/counting_triangles_comp.h"
#include "spirv/frs_comp.h"
#include "spirv/naive_counting_comp.h"
#include "spirv/naive_realization_comp.h"
#include "spirv/realization_comp.h"
#include "spirv/realization_exact_comp.h"
#include "spirv/realization_guide_comp.h"
#include "spirv/realization_plan_comp.h"
#include "spirv/rejection_distribution_comp.h"
#include "spirv/rejection_comp.h"
#include "spirv/rounding_comp.h"
#include "spirv/scan_add_comp.h"
#include "spirv/scan_local_comp.h"
#include "spirv/scan_lookback_comp.h"
#include "spirv/scan_unordered_comp.h"
#include "spirv/counting_total_comp.h"

namespace lightsampler::vk {

Pipelines::Pipelines(Context& c)
    : rounding(c.create_compute(spirv::rounding_comp, sizeof(gpu::RoundingPush))),
      scan_local(c.create_compute(spirv::scan_local_comp, sizeof(gpu::ScanPush))),
      scan_add(c.create_compute(spirv::scan_add_comp, sizeof(gpu::ScanPush))),
      realization_guide(c.create_compute(spirv::realization_guide_comp, sizeof(gpu::RealizationPush))),
      realization_plan(c.create_compute(spirv::realization_plan_comp, sizeof(gpu::PlanPush))),
      realization(c.create_compute(spirv::realization_comp, sizeof(gpu::RealizationPush))),
      realization_exact(c.create_compute(spirv::realization_exact_comp, sizeof(gpu::RealizationPush))),
      rejection_distribution(c.create_compute(spirv::rejection_distribution_comp, sizeof(gpu::RejectionPush))),
      rejection(c.create_compute(spirv::rejection_comp, sizeof(gpu::RejectionPush))),
      frs(c.create_compute(spirv::frs_comp, sizeof(gpu::FrsPush))),
      naive_counting(c.create_compute(spirv::naive_counting_comp, sizeof(gpu::CountingPush))),
      naive_realization(c.create_compute(spirv::naive_realization_comp, sizeof(gpu::RealizationPush))) {}

namespace {
static_assert(std::uint32_t(Overlap::closed_form) == gpu::kOverlapClosedForm &&
              std::uint32_t(Overlap::clipping) == gpu::kOverlapClipping && std::uint32_t(Overlap::sdf) == gpu::kOverlapSdf);

/// Specialization constant 1 (kOverlap) after constant 0 (kSubgroupReduction, left as designed).
std::array<std::uint32_t, 2> overlap_constants(Overlap overlap) { return {1u, std::uint32_t(overlap)}; }
}  // namespace

CountingPipelines::CountingPipelines(Context& c, Overlap overlap) {
  const auto constants = overlap_constants(overlap);
  setup = c.create_compute(spirv::counting_setup_comp, sizeof(gpu::CountingPush), constants);
  cells = c.create_compute(spirv::counting_cells_comp, sizeof(gpu::CountingPush), constants);
  triangles = c.create_compute(spirv::counting_triangles_comp, sizeof(gpu::CountingPush), constants);
}

ReducingPipelines::ReducingPipelines(Context& c, bool subgroup_reduction) {
  const std::uint32_t constants[] = {subgroup_reduction};
  counting_total = c.create_compute(spirv::counting_total_comp, sizeof(gpu::CountingPush), constants);
  scan_unordered = c.create_compute(spirv::scan_unordered_comp, sizeof(gpu::ScanPush), constants);
}

std::uint32_t workgroups_for(std::uint64_t elements) {
  const std::uint64_t groups = (elements + gpu::kWorkgroupSize - 1) / gpu::kWorkgroupSize;
  return std::uint32_t(std::clamp<std::uint64_t>(groups, 1, gpu::kMaxWorkgroups));
}

Buffer& OrderedScan::scratch(std::vector<Buffer>& level_buffers, std::size_t level, std::uint64_t elements) {
  if (level_buffers.size() <= level) level_buffers.resize(level + 1);
  Buffer& b = level_buffers[level];
  if (!b || b.size() < elements * sizeof(std::uint64_t))
    b = context_.create_buffer(elements * sizeof(std::uint64_t));
  return b;
}

void OrderedScan::record(Commands& commands, const Pipelines& pipelines, VkDeviceAddress source,
                         VkDeviceAddress result, std::uint64_t n, std::size_t level) {
  if (n == 0) return;
  const std::uint64_t blocks = (n + gpu::kWorkgroupSize - 1) / gpu::kWorkgroupSize;
  // Addresses, not references: the recursion grows the scratch vectors.
  const VkDeviceAddress sums = scratch(block_sums_, level, blocks).address();
  gpu::ScanPush push{source, result, sums, 0, 0, n, 0, 0};
  commands.dispatch(pipelines.scan_local, &push, sizeof push,
                    std::uint32_t(std::min<std::uint64_t>(blocks, gpu::kMaxWorkgroups)));
  commands.barrier();
  if (blocks == 1) return;
  const VkDeviceAddress scanned = scratch(scanned_sums_, level, blocks).address();
  record(commands, pipelines, sums, scanned, blocks, level + 1);
  push.block_sums = scanned;
  commands.dispatch(pipelines.scan_add, &push, sizeof push, workgroups_for(n));
  commands.barrier();
}

void LookbackScan::record(Commands& commands, VkDeviceAddress source, VkDeviceAddress result, std::uint64_t n,
                          std::uint32_t polls) {
  if (!context_.capabilities().vulkan_memory_model)
    throw std::invalid_argument("the lookback scan needs vulkanMemoryModel and vulkanMemoryModelDeviceScope, which " +
                                context_.device_name() + " lacks; use the ordered scan");
  if (n == 0) return;
  if (!pipeline_) pipeline_ = context_.create_compute(spirv::scan_lookback_comp, sizeof(gpu::ScanPush));
  const std::uint64_t tiles = (n + gpu::kLookbackTile - 1) / gpu::kLookbackTile;
  const VkDeviceSize bytes = (tiles + 1) * sizeof(std::uint64_t);
  if (!states_ || states_.size() < bytes) states_ = context_.create_buffer(bytes);
  commands.fill(states_, 0, bytes, 0);  // tile counter and states start at zero
  commands.barrier();
  const gpu::ScanPush push{source, result, states_.address(), 0, 0, n, 0, polls};
  commands.dispatch(*pipeline_, &push, sizeof push, std::uint32_t(std::min<std::uint64_t>(tiles, gpu::kMaxWorkgroups)));
  commands.barrier();
}

}  // namespace lightsampler::vk
