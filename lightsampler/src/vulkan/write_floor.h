#pragma once
// The Vulkan backend's floor under realization (lightsampler::sample_write_ms).

#include <cstdint>
#include <vector>

#include "lightsampler/backend.h"

namespace lightsampler::vk {

/// GPU time of `runs` dispatches writing `count` samples to device memory, in milliseconds.
std::vector<double> sample_write_ms(const VulkanOptions& options, std::uint64_t count, int runs);

}  // namespace lightsampler::vk
