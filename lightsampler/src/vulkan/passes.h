#pragma once
// The compiled passes of shaders/, and helpers to record them.

#include <cstdint>
#include <optional>
#include <vector>

#include "lightsampler/sampler.h"
#include "vulkan/context.h"
#include "vulkan/layouts.h"

namespace lightsampler::vk {

struct Pipelines {
  explicit Pipelines(Context& context);
  ComputePipeline rounding, scan_local, scan_add, realization_guide, realization_plan, realization, realization_exact, rejection_distribution, rejection, frs, naive_counting,
      naive_realization;
};

/// TRS's compute counting passes, specialized with an overlap formula (kOverlap: the closed form
/// of the sampler as designed, or the alternatives of the paper's Figure 11).
struct CountingPipelines {
  CountingPipelines(Context& context, Overlap overlap);
  ComputePipeline setup, cells, triangles;
};

/// The compute passes that reduce over subgroups before their atomics, specialized with or
/// without that reduction (kSubgroupReduction, the paper's "No Subgroup Reduction" ablation).
struct ReducingPipelines {
  ReducingPipelines(Context& context, bool subgroup_reduction);
  ComputePipeline counting_total, scan_unordered;
};

/// Workgroups for a grid-stride pass over `elements` (at least one, at most kMaxWorkgroups).
std::uint32_t workgroups_for(std::uint64_t elements);

/// Records an ordered inclusive scan of n uint64 values, recursing over block sums; keeps the
/// scratch buffers of every level between frames.
class OrderedScan {
 public:
  explicit OrderedScan(Context& context) : context_(context) {}
  void record(Commands& commands, const Pipelines& pipelines, VkDeviceAddress source,
              VkDeviceAddress result, std::uint64_t n, std::size_t level = 0);

 private:
  Buffer& scratch(std::vector<Buffer>& level_buffers, std::size_t level, std::uint64_t elements);
  Context& context_;
  std::vector<Buffer> block_sums_, scanned_sums_;
};

/// Records the single-pass ordered inclusive scan of n uint64 values (shaders/scan_lookback.comp),
/// whose total must be below 2^62. `polls`: reads of a predecessor's state before a workgroup
/// reduces that tile itself (0: it always does, which tests use). The pipeline is made on first
/// use; throws std::invalid_argument on a device without vulkanMemoryModel (and its device
/// scope, see Capabilities).
class LookbackScan {
 public:
  explicit LookbackScan(Context& context) : context_(context) {}
  void record(Commands& commands, VkDeviceAddress source, VkDeviceAddress result, std::uint64_t n,
              std::uint32_t polls = gpu::kLookbackPolls);

 private:
  Context& context_;
  std::optional<ComputePipeline> pipeline_;
  Buffer states_;  ///< the tile counter, then one state per tile
};

}  // namespace lightsampler::vk
