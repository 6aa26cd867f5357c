#pragma once
// The Vulkan backend, in builds of the library with it (LIGHTSAMPLER_HAS_VULKAN). Callers that
// only choose a backend need lightsampler/backend.h.

#include <memory>
#include <span>

#include "lightsampler/backend.h"
#include "lightsampler/sampler.h"

namespace lightsampler {

/// The GPU backend. Samplers share the process's Vulkan instance and, per GPU, its device: both
/// are made on first use and kept until the process exits; a sampler owns only its buffers,
/// pipelines and command objects. Throws VulkanUnavailable when no suitable device exists (the
/// message says what is missing), std::invalid_argument / std::length_error on bad input as the
/// CPU backend.
std::unique_ptr<Sampler> make_vulkan_sampler(const MeshView& mesh, std::span<const DensityMapView> maps,
                                             const VulkanOptions& options = {});

}  // namespace lightsampler
