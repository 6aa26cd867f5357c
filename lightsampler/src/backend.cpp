// Choosing a backend: Vulkan on a GPU where the library has it, the CPU otherwise.

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <vector>
#include <string>

#include "lightsampler/backend.h"

#include "cpu/passes.h"

#ifdef LIGHTSAMPLER_HAS_VULKAN
#include "lightsampler/vulkan.h"
#include "vulkan/context.h"
#include "vulkan/write_floor.h"
#endif

namespace lightsampler {

namespace {

#ifdef LIGHTSAMPLER_HAS_VULKAN

bool has_suitable_gpu() {
  for (const vk::DeviceInfo& d : vk::Context::devices())
    if (d.suitable && d.type != VK_PHYSICAL_DEVICE_TYPE_CPU) return true;
  return false;
}

std::unique_ptr<Sampler> make_backend(const MeshView& mesh, std::span<const DensityMapView> maps,
                                      const SamplerOptions& options) {
  switch (options.backend) {
    case Backend::cpu: return make_cpu_sampler(mesh, maps, options.cpu);
    case Backend::vulkan: return make_vulkan_sampler(mesh, maps, options.vulkan);
    case Backend::automatic:
      // A device asked for by name must be used; otherwise Vulkan only on a GPU, because a
      // software device (lavapipe) is slower than the native CPU backend.
      if (!options.vulkan.device.empty() || std::getenv("LIGHTSAMPLER_VULKAN_DEVICE"))
        return make_vulkan_sampler(mesh, maps, options.vulkan);
      if (has_suitable_gpu()) {
        try {
          return make_vulkan_sampler(mesh, maps, options.vulkan);
        } catch (const VulkanUnavailable&) {
        }
      }
      return make_cpu_sampler(mesh, maps, options.cpu);
  }
  return nullptr;
}

#else

VulkanUnavailable no_vulkan_backend() {
  return VulkanUnavailable("this build of lightsampler has no Vulkan backend (configured with LIGHTSAMPLER_VULKAN=OFF)");
}

std::unique_ptr<Sampler> make_backend(const MeshView& mesh, std::span<const DensityMapView> maps,
                                      const SamplerOptions& options) {
  if (options.backend == Backend::vulkan) throw no_vulkan_backend();
  return make_cpu_sampler(mesh, maps, options.cpu);
}

#endif

}  // namespace

bool has_vulkan_backend() {
#ifdef LIGHTSAMPLER_HAS_VULKAN
  return true;
#else
  return false;
#endif
}

std::vector<std::string> vulkan_devices() {
  std::vector<std::string> lines;
#ifdef LIGHTSAMPLER_HAS_VULKAN
  for (const vk::DeviceInfo& d : vk::Context::devices()) {
    std::string line = std::to_string(d.index) + ": " + d.name + " (" + vk::type_name(d.type);
    if (!d.driver.empty()) line += "; driver " + d.driver;
    line += d.suitable ? ")" : "; unsuitable: " + d.missing + ")";
    lines.push_back(line);
  }
#endif
  return lines;
}

std::unique_ptr<Sampler> make_sampler(const MeshView& mesh, std::span<const DensityMapView> maps,
                                      const SamplerOptions& options) {
  if (!(options.refinement.min_acceptance > 0.0f)) return make_backend(mesh, maps, options);
  return make_refined_sampler(mesh, maps, options.refinement,
                              [options](const MeshView& parts, std::span<const DensityMapView> m) {
                                return make_backend(parts, m, options);
                              });
}

double sample_write_ms(Backend backend, const SamplerOptions& options, std::uint64_t count, int repeats) {
  if (backend == Backend::automatic)
    throw std::invalid_argument("sample_write_ms: name the backend (cpu or vulkan), not automatic");
  if (repeats < 1) throw std::invalid_argument("sample_write_ms: repeats must be at least 1");
  std::vector<double> ms;
  if (backend == Backend::cpu) {
    ms = cpu::sample_write_ms(options.cpu, count, repeats + 1);
  } else {
#ifdef LIGHTSAMPLER_HAS_VULKAN
    ms = vk::sample_write_ms(options.vulkan, count, repeats + 1);
#else
    throw no_vulkan_backend();
#endif
  }
  ms.erase(ms.begin());  // the untimed run: first touches of the memory
  std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
  return ms[ms.size() / 2];
}

}  // namespace lightsampler
