#pragma once
// The compiled passes of shaders/, and helpers to record them.

#include <cstdint>
#include <vector>

#include "vulkan/context.h"
#include "vulkan/layouts.h"

namespace lightsampler::vk {

struct Pipelines {
  explicit Pipelines(Context& context);
  ComputePipeline counting_setup, counting_cells, counting_triangles, counting_total, rounding, scan_unordered,
      scan_local, scan_add, realization_plan, realization, rejection_distribution, rejection, frs, naive_counting,
      naive_realization;
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

}  // namespace lightsampler::vk
