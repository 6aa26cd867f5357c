#pragma once
// Choosing a backend: the factory every caller uses, whatever backends the library was built
// with. The Vulkan backend is optional (CMake option LIGHTSAMPLER_VULKAN; a build with it
// defines LIGHTSAMPLER_HAS_VULKAN); without it, Backend::vulkan throws VulkanUnavailable and
// Backend::automatic gives the CPU backend.

#include <memory>
#include <span>
#include <stdexcept>
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

/// No suitable Vulkan device, or a library built without the Vulkan backend: the message says
/// which, and what is missing.
class VulkanUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The processor's model name (/proc/cpuinfo), the CPU backend's Sampler::device().
std::string cpu_device();

/// Whether this build of the library has the Vulkan backend.
bool has_vulkan_backend();

/// One line per Vulkan device: index, name, type, driver, and what it lacks if unsuitable. Empty when
/// Vulkan itself is unavailable, or the library was built without it.
std::vector<std::string> vulkan_devices();

struct SamplerOptions {
  Backend backend = Backend::automatic;
  CpuOptions cpu;
  VulkanOptions vulkan;
  /// Adaptive subdivision before sampling (refinement.h); off by default.
  Refinement refinement;
};

/// `automatic` takes the Vulkan backend when a suitable GPU exists (or a device is named by
/// VulkanOptions::device or LIGHTSAMPLER_VULKAN_DEVICE), else the CPU backend; `vulkan` throws
/// VulkanUnavailable rather than falling back. With a refinement, the backend samples the
/// refined mesh (make_refined_sampler).
std::unique_ptr<Sampler> make_sampler(const MeshView& mesh, std::span<const DensityMapView> maps,
                                      const SamplerOptions& options = {});

/// The floor under any frame of `count` samples on `backend` (cpu or vulkan, with `options`):
/// the time to write that many samples, by a kernel that writes each to device memory (Vulkan,
/// timed by GPU timestamps) or a parallel pass that writes them to host memory (CPU). The
/// median of `repeats` runs after an untimed one, in milliseconds. Throws as make_sampler does
/// when the backend cannot run, std::invalid_argument for Backend::automatic.
double sample_write_ms(Backend backend, const SamplerOptions& options, std::uint64_t count, int repeats = 5);

}  // namespace lightsampler
