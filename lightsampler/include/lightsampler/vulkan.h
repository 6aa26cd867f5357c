#pragma once
// The Vulkan backend, and choosing a backend.

#include <memory>
#include <stdexcept>
#include <span>
#include <string>
#include <vector>

#include "lightsampler/refinement.h"
#include "lightsampler/sampler.h"

namespace lightsampler {

struct VulkanOptions {
  /// Device by index or case-insensitive name substring; empty: LIGHTSAMPLER_VULKAN_DEVICE,
  /// else the best device (discrete GPU first).
  std::string device;
  /// Khronos validation layer, when installed; also on with LIGHTSAMPLER_VULKAN_VALIDATION=1 and
  /// in Debug builds of the library. It is set when the process's one Vulkan instance is made,
  /// by the first sampler: a later request cannot turn it on.
  bool validation = false;
};

/// The GPU backend. Samplers share the process's Vulkan instance and, per GPU, its device: both
/// are made on first use and kept until the process exits; a sampler owns only its buffers,
/// pipelines and command objects. Throws VulkanUnavailable when no suitable device exists (the
/// message says what is missing), std::invalid_argument / std::length_error on bad input as the
/// CPU backend.
std::unique_ptr<Sampler> make_vulkan_sampler(const MeshView& mesh, std::span<const DensityMapView> maps,
                                             const VulkanOptions& options = {});

class VulkanUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One line per Vulkan device: index, name, type, and what it lacks if unsuitable. Empty when
/// Vulkan itself is unavailable.
std::vector<std::string> vulkan_devices();

enum class Backend { automatic, cpu, vulkan };

struct SamplerOptions {
  Backend backend = Backend::automatic;
  CpuOptions cpu;
  VulkanOptions vulkan;
  /// Adaptive subdivision before sampling (refinement.h); off by default.
  Refinement refinement;
};

/// `automatic` takes the Vulkan backend when a suitable device exists, else the CPU backend;
/// `vulkan` throws VulkanUnavailable rather than falling back. With a refinement, the backend
/// samples the refined mesh (make_refined_sampler).
std::unique_ptr<Sampler> make_sampler(const MeshView& mesh, std::span<const DensityMapView> maps,
                                      const SamplerOptions& options = {});

const char* to_string(Backend backend);

}  // namespace lightsampler
