#pragma once
// The experiments, after the paper's Section 6: frame time against the sample count, TRS beside
// plain rejection sampling (Figure 8), and the unordered against the ordered scan across triangle
// counts (Figure 13).

#include <string>
#include <vector>

#include "density_maps.h"
#include "lightsampler/sampler.h"
#include "lightsampler/backend.h"
#include "measure.h"
#include "meshes.h"
#include "report.h"

namespace trs_bench {

struct Inputs {
  std::vector<Mesh> meshes;
  std::vector<DensityMap> maps;
};

/// One way of sampling, compared side by side with the others on the same inputs.
struct Variant {
  lightsampler::Backend backend;    ///< cpu or vulkan
  lightsampler::Method method;
  lightsampler::Counting counting;  ///< the Vulkan backend's counting path (TRS)
  /// Backend and counting path as the tables show it: "cpu", "vk", "vk/auto", "vk/raster", "vk/compute", "vk/per-triangle".
  std::string engine() const;
};

struct ExperimentSettings {
  std::vector<double> counts;  ///< target sample counts
  std::vector<Variant> variants;
  std::string vulkan_device;  ///< empty: the default device
  unsigned threads = 0;  ///< 0: every hardware thread
  MeasureSettings measure;
  double scan_target = 1e6;  ///< target of the scan comparison's frames
  /// The samplers' adaptive subdivision: auto by default, 0 for the paper's sampler as it is.
  lightsampler::Refinement refinement{.min_acceptance = lightsampler::kAutoMinAcceptance};
};

/// Every mesh x map x count x variant. A case whose frame time, extrapolated from the previous
/// count of its series, exceeds the budget is skipped and recorded with its estimate. Vulkan
/// frames keep their outputs on the device (no readback): the sampler is timed, not the bus.
void run_sampling_experiment(const Inputs& inputs, const ExperimentSettings& settings,
                             lightsampler::Frame& frame, Recorder& recorder);

/// Every mesh x map x backend with the unordered and the ordered scan, frames stopped after the
/// scan.
void run_scan_experiment(const Inputs& inputs, const ExperimentSettings& settings,
                         lightsampler::Frame& frame, Recorder& recorder);

/// Why a measured case's output cannot be right (samples far from the target, samples that gave
/// up), or empty. A benchmark of wrong output measures nothing.
std::vector<std::string> sanity_problems(const std::vector<CaseResult>& results);

}  // namespace trs_bench
