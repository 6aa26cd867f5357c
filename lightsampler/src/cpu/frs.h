#pragma once
// Fast rejection sampling after Šik and Křivánek ("Fast Random Sampling of Triangular Meshes",
// 2013), a baseline of the paper's Section 6, on the CPU: a frame draws from the table of
// core/frs_table.h.

#include <cstdint>
#include <span>

#include "core/density.h"
#include "core/frs_table.h"
#include "core/geometry.h"
#include "cpu/passes.h"

namespace lightsampler::cpu {

/// `sample_count` samples by the table, brought back to the caller's triangles.
RealizationResult frs_sample(const core::FrsTable& table, std::span<const core::TexelTriangle> triangles,
                             std::span<const core::DensityMap> maps, std::uint64_t sample_count,
                             PhiloxKey key, std::uint32_t max_tries, Buffer<Sample>& samples);

}  // namespace lightsampler::cpu
