#include "experiments.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace trs_bench {

namespace {

using lightsampler::FrameRequest;
using lightsampler::Method;
using lightsampler::Sampler;
using lightsampler::ScanOrder;

constexpr std::uint64_t kFirstSeed = 1;

std::unique_ptr<Sampler> make_sampler(const Mesh& mesh, const DensityMap& map, unsigned threads) {
  const lightsampler::DensityMapView view = map.view();
  return lightsampler::make_cpu_sampler(mesh.view(), {&view, 1}, {threads});
}

CaseResult describe_case(const char* experiment, const Mesh& mesh, const DensityMap& map,
                         const Sampler& sampler, const FrameRequest& request) {
  CaseResult r;
  r.experiment = experiment;
  r.mesh = mesh.name;
  r.triangles = mesh.triangle_count();
  r.map = map.name;
  r.map_size = map.size;
  r.method = lightsampler::to_string(request.method);
  r.scan = request.method == Method::trs ? lightsampler::to_string(request.scan) : "-";
  r.target = request.target_count.value_or(0);
  r.backend = sampler.backend();
  r.device = sampler.device();
  r.threads = sampler.threads();
  return r;
}

/// The last frame of one (mesh, map, method) series, to extrapolate the next count from: the
/// realization pass scales with the sample count, the other passes do not (they scale with the
/// mesh and the maps), so one point suffices whatever the step between counts.
struct SeriesTime {
  double target;
  double fixed_ms;
  double realization_ms;

  static SeriesTime of(double target, const Measurement& m) {
    double realization_ms = 0;
    for (const auto& pass : m.pass_medians)
      if (pass.name == "realization") realization_ms = pass.ms;
    return {target, std::max(m.total_ms - realization_ms, 0.0), realization_ms};
  }

  /// The estimate at another count, as a series point itself.
  SeriesTime at(double next_target) const {
    return {next_target, fixed_ms, realization_ms * next_target / target};
  }
  double total_ms() const { return fixed_ms + realization_ms; }
};

}  // namespace

void run_sampling_experiment(const Inputs& inputs, const ExperimentSettings& settings,
                             lightsampler::Frame& frame, Recorder& recorder) {
  for (const Mesh& mesh : inputs.meshes) {
    recorder.begin_section("Sample count: " + mesh.name + ", " +
                           std::to_string(mesh.triangle_count()) + " triangles");
    for (const DensityMap& map : inputs.maps) {
      const auto sampler = make_sampler(mesh, map, settings.threads);
      std::vector<std::optional<SeriesTime>> last(settings.methods.size());
      for (double target : settings.counts) {
        for (std::size_t k = 0; k < settings.methods.size(); ++k) {
          FrameRequest request;
          request.method = settings.methods[k];
          request.target_count = target;
          CaseResult result = describe_case("sampling", mesh, map, *sampler, request);
          const std::optional<SeriesTime> estimate =
              last[k] ? std::optional(last[k]->at(target)) : std::nullopt;
          if (estimate && estimate->total_ms() > settings.measure.budget_s * 1e3) {
            result.estimate_ms = estimate->total_ms();
            last[k] = estimate;
          } else {
            result.measured = measure(*sampler, frame, request, kFirstSeed, settings.measure);
            last[k] = SeriesTime::of(target, *result.measured);
            if (request.method == Method::trs) result.scan = result.measured->scan_used;
          }
          recorder.add(std::move(result));
        }
      }
    }
  }
}

void run_scan_experiment(const Inputs& inputs, const ExperimentSettings& settings,
                         lightsampler::Frame& frame, Recorder& recorder) {
  recorder.begin_section("Scan order (frames stop after the scan)");
  for (const Mesh& mesh : inputs.meshes) {
    for (const DensityMap& map : inputs.maps) {
      const auto sampler = make_sampler(mesh, map, settings.threads);
      for (ScanOrder scan : {ScanOrder::unordered, ScanOrder::ordered}) {
        FrameRequest request;
        request.target_count = settings.scan_target;
        request.scan = scan;
        request.realize = false;
        CaseResult result = describe_case("scan", mesh, map, *sampler, request);
        result.measured = measure(*sampler, frame, request, kFirstSeed, settings.measure);
        result.scan = result.measured->scan_used;
        recorder.add(std::move(result));
      }
    }
  }
}

std::vector<std::string> sanity_problems(const std::vector<CaseResult>& results) {
  std::vector<std::string> problems;
  for (const auto& r : results) {
    if (!r.measured) continue;
    const Measurement& m = *r.measured;
    const std::string where = r.experiment + " " + r.method + " " + r.mesh + " " +
                              std::to_string(r.triangles) + " " + r.map + " target " +
                              std::to_string(r.target) + ": ";
    // Stochastic rounding gives Var N <= target (one Bernoulli per triangle, each of variance at
    // most its expected count), so a mean N more than 6 sd away is a bug, not bad luck.
    if (std::abs(m.samples - r.target) > 6 * std::sqrt(r.target) + 1)
      problems.push_back(where + "mean sample count " + std::to_string(m.samples));
    if (m.exhausted > 0)
      problems.push_back(where + std::to_string(m.exhausted) + " samples reached max_tries");
  }
  return problems;
}

}  // namespace trs_bench
