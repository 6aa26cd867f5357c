#pragma once
// The experiments, after the paper's Section 6: frame time against the sample count, TRS beside
// the baselines (Figures 8 to 10), the triangle-texel overlap formulas (Figure 11), the scans
// across triangle counts (Figure 13), and the ablations of Figure 14; and the time of a sliver of
// density, the sparsity limit the paper names.

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
  lightsampler::Backend backend = lightsampler::Backend::cpu;
  lightsampler::Method method = lightsampler::Method::trs;
  lightsampler::Counting counting = lightsampler::Counting::automatic;  ///< the Vulkan counting path (TRS)
  lightsampler::ScanOrder scan = lightsampler::ScanOrder::automatic;
  lightsampler::Overlap overlap = lightsampler::Overlap::closed_form;
  bool subgroup_reduction = true;  ///< the Vulkan ablation switches (VulkanFrameOptions)
  bool inverse_cdf = false;
  std::uint32_t exact_after = lightsampler::FrameRequest{}.exact_after;  ///< TRS's rule on slivers
  /// The ablation this variant is ("full", "no-subgroup-reduction", ...); empty outside them.
  std::string ablation{};
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
  lightsampler::Refinement refinement = lightsampler::auto_refinement(0.0);
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

/// Every mesh x map x TRS variant with each overlap formula, frames that count (the maps
/// replaced before each) and stop after the scan: the counting pass is the comparison.
void run_overlap_experiment(const Inputs& inputs, const ExperimentSettings& settings,
                            lightsampler::Frame& frame, Recorder& recorder);

/// The sampler as designed ("full") and each version that differs from it by one change, on
/// every backend the variants use, through the counts as the sampling experiment; every frame
/// counts, as with an animated texture (the paper's setting).
void run_ablation_experiment(const Inputs& inputs, const ExperimentSettings& settings,
                             lightsampler::Frame& frame, Recorder& recorder);

/// A sliver of density: one triangle over an 8 x 8 map whose one lit texel it overlaps by a
/// fraction of its area, from 1e-2 down to 1e-6, beside the same triangle fully lit (the
/// ordinary triangle with the same N_T), through the counts. TRS on every backend the variants
/// use, unrefined, with exact draws after exact_after rejections in a row and, where plain
/// rejection can finish (fractions down to 1e-3), with the paper's rule (exact_after 0).
void run_sliver_experiment(const ExperimentSettings& settings, lightsampler::Frame& frame, Recorder& recorder);

/// The ablations that change something on `backend`, each named.
std::vector<Variant> ablation_variants(lightsampler::Backend backend);

/// Why a measured case's output cannot be right (samples far from the target, samples that gave
/// up), or empty. A benchmark of wrong output measures nothing.
std::vector<std::string> sanity_problems(const std::vector<CaseResult>& results);

}  // namespace trs_bench
