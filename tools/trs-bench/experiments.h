#pragma once
// The experiments, after the paper's Section 6: frame time against the sample count, TRS beside
// plain rejection sampling (Figure 8), and the unordered against the ordered scan across triangle
// counts (Figure 13).

#include <vector>

#include "density_maps.h"
#include "lightsampler/sampler.h"
#include "measure.h"
#include "meshes.h"
#include "report.h"

namespace trs_bench {

struct Inputs {
  std::vector<Mesh> meshes;
  std::vector<DensityMap> maps;
};

struct ExperimentSettings {
  std::vector<double> counts;  ///< target sample counts
  std::vector<lightsampler::Method> methods;
  unsigned threads = 0;  ///< 0: every hardware thread
  MeasureSettings measure;
  double scan_target = 1e6;  ///< target of the scan comparison's frames
};

/// Every mesh x map x count x method. A case whose frame time, extrapolated from the previous
/// count of its series, exceeds the budget is skipped and recorded with its estimate.
void run_sampling_experiment(const Inputs& inputs, const ExperimentSettings& settings,
                             lightsampler::Frame& frame, Recorder& recorder);

/// Every mesh x map with the unordered and the ordered scan, frames stopped after the scan.
void run_scan_experiment(const Inputs& inputs, const ExperimentSettings& settings,
                         lightsampler::Frame& frame, Recorder& recorder);

/// Why a measured case's output cannot be right (samples far from the target, samples that gave
/// up), or empty. A benchmark of wrong output measures nothing.
std::vector<std::string> sanity_problems(const std::vector<CaseResult>& results);

}  // namespace trs_bench
