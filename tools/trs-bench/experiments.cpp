#include "experiments.h"

#include <map>
#include <utility>

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

namespace trs_bench {

namespace {

using lightsampler::FrameRequest;
using lightsampler::Counting;
using lightsampler::Method;
using lightsampler::Overlap;
using lightsampler::Pass;
using lightsampler::Sampler;
using lightsampler::ScanOrder;

constexpr std::uint64_t kFirstSeed = 1;

using lightsampler::Backend;

lightsampler::SamplerOptions sampler_options(Backend backend, const ExperimentSettings& settings) {
  return {.backend = backend,
          .cpu = {settings.threads},
          .vulkan = {.device = settings.vulkan_device},
          .refinement = settings.refinement};
}

std::unique_ptr<Sampler> make_sampler(const Mesh& mesh, const DensityMap& map, Backend backend,
                                      const ExperimentSettings& settings) {
  const lightsampler::DensityMapView view = map.view();
  return lightsampler::make_sampler(mesh.view(), {&view, 1}, sampler_options(backend, settings));
}

/// The floor under every frame: writing `target` samples on each backend the variants use, one
/// row per backend and count. Returns the floor of each (backend, count).
std::map<std::pair<Backend, double>, double> run_floors(const ExperimentSettings& settings, Recorder& recorder) {
  recorder.begin_section("Floor: the time to write N samples (x floor = 1)");
  std::map<std::pair<Backend, double>, double> floors;
  for (const Variant& v : settings.variants)
    for (double target : settings.counts) {
      if (floors.count({v.backend, target})) continue;
      const double ms = lightsampler::sample_write_ms(v.backend, sampler_options(v.backend, settings),
                                                      std::uint64_t(target), settings.measure.repeats);
      floors[{v.backend, target}] = ms;
      CaseResult r;
      r.experiment = "floor";
      const std::string none(1, '-');
      r.mesh = r.map = r.scan = r.overlap = none;
      r.method = "write";
      r.target = target;
      r.backend = lightsampler::to_string(v.backend);
      r.engine = v.backend == Backend::vulkan ? "vk" : "cpu";
      Measurement& m = r.measured.emplace();
      m.runs = settings.measure.repeats;
      m.samples = target;
      m.total_ms = m.wall_ms = ms;
      r.floor_ms = ms;
      recorder.add(std::move(r));
    }
  return floors;
}

/// One sampler per backend the variants use, for one (mesh, map).
struct Samplers {
  std::unique_ptr<Sampler> cpu, vulkan;

  Samplers(const Mesh& mesh, const DensityMap& map, const ExperimentSettings& settings) {
    for (const Variant& v : settings.variants) {
      auto& slot = v.backend == Backend::vulkan ? vulkan : cpu;
      if (!slot) slot = make_sampler(mesh, map, v.backend, settings);
    }
  }
  Sampler& of(const Variant& v) { return v.backend == Backend::vulkan ? *vulkan : *cpu; }
};

FrameRequest request_for(const Variant& v) {
  FrameRequest request;
  request.method = v.method;
  request.scan = v.scan;
  request.overlap = v.overlap;
  request.vulkan.counting = v.counting;
  request.vulkan.subgroup_reduction = v.subgroup_reduction;
  request.vulkan.inverse_cdf = v.inverse_cdf;
  request.exact_after = v.exact_after;
  request.vulkan.read_back = false;  // the Vulkan backend's outputs stay on the device
  return request;
}

/// The backends the variants use, in order of first use.
std::vector<Backend> backends_of(const std::vector<Variant>& variants) {
  std::vector<Backend> backends;
  for (const Variant& v : variants)
    if (std::find(backends.begin(), backends.end(), v.backend) == backends.end()) backends.push_back(v.backend);
  return backends;
}

CaseResult describe_case(const char* experiment, const Mesh& mesh, const DensityMap& map,
                         const Sampler& sampler, const FrameRequest& request, const std::string& engine,
                         const ExperimentSettings& settings) {
  CaseResult r;
  r.experiment = experiment;
  r.mesh = mesh.name;
  r.triangles = mesh.triangle_count();
  r.map = map.name;
  r.map_width = map.width;
  r.map_height = map.height;
  r.coverage = map.coverage;
  r.method = lightsampler::to_string(request.method);
  r.scan = request.method == Method::trs ? lightsampler::to_string(request.scan) : "-";
  r.overlap = request.method == Method::trs ? lightsampler::to_string(request.overlap) : "-";
  r.target = request.target_count.value_or(0);
  r.backend = lightsampler::to_string(sampler.backend());
  r.engine = engine;
  r.device = sampler.device();
  r.threads = sampler.backend() == Backend::cpu ? lightsampler::worker_threads({settings.threads}) : 0;
  r.refine = settings.refinement.min_acceptance;
  return r;
}

/// The frames of one (mesh, map, variant) series so far, to extrapolate the next count from.
/// A frame costs a fixed part (the passes before the scan: mesh and maps) plus a part
/// proportional to the sample count. With two points, an affine fit through their totals; with
/// one, its fixed passes stay and the rest scales. Times after the scan are not used one by
/// one: lavapipe misplaces them.
struct SeriesTime {
  struct Point {
    double target, total_ms, fixed_ms;
  };
  std::vector<Point> points;

  void add(double target, double total_ms, double fixed_ms) { points.push_back({target, total_ms, fixed_ms}); }

  static double fixed_ms_of(const Measurement& m) {
    double fixed = 0;
    for (const auto& pass : m.pass_medians)
      if (pass.pass == Pass::counting || pass.pass == Pass::rounding || pass.pass == Pass::distribution)
        fixed += pass.ms;
    return std::min(fixed, m.total_ms);
  }

  std::optional<double> estimate_ms(double target) const {
    if (points.empty()) return std::nullopt;
    const Point& last = points.back();
    if (points.size() == 1 || last.target == points[points.size() - 2].target)
      return last.fixed_ms + (last.total_ms - last.fixed_ms) * target / last.target;
    const Point& before = points[points.size() - 2];
    const double per_sample = std::max((last.total_ms - before.total_ms) / (last.target - before.target), 0.0);
    return last.total_ms + per_sample * (target - last.target);
  }
};

}  // namespace

namespace {

/// Every mesh x map x count x variant, as rows of `experiment` in sections named `title`. A case whose frame time,
/// extrapolated from the previous count of its series, exceeds the budget is skipped.
void run_count_series(const char* experiment, const char* title, const Inputs& inputs, const ExperimentSettings& settings,
                      const std::map<std::pair<Backend, double>, double>& floors, lightsampler::Frame& frame,
                      Recorder& recorder) {
  for (const Mesh& mesh : inputs.meshes) {
    recorder.begin_section(std::string(title) + ": " + mesh.name + ", " + std::to_string(mesh.triangle_count()) + " triangles");
    for (const DensityMap& map : inputs.maps) {
      Samplers samplers(mesh, map, settings);
      std::vector<SeriesTime> series(settings.variants.size());
      for (double target : settings.counts) {
        for (std::size_t k = 0; k < settings.variants.size(); ++k) {
          const Variant& variant = settings.variants[k];
          Sampler& sampler = samplers.of(variant);
          FrameRequest request = request_for(variant);
          request.target_count = target;
          CaseResult result = describe_case(experiment, mesh, map, sampler, request, variant.engine(), settings);
          result.variant = variant.ablation;
          if (const auto floor = floors.find({variant.backend, target}); floor != floors.end())
            result.floor_ms = floor->second;
          const std::optional<double> estimate = series[k].estimate_ms(target);
          if (estimate && *estimate > settings.measure.budget_s * 1e3) {
            result.estimate_ms = *estimate;
            series[k].add(target, *estimate, series[k].points.back().fixed_ms);
          } else {
            const lightsampler::DensityMapView view = map.view();
            result.measured = measure(sampler, frame, request, kFirstSeed, settings.measure, {&view, 1});
            series[k].add(target, result.measured->total_ms, SeriesTime::fixed_ms_of(*result.measured));
            if (request.method == Method::trs) result.scan = result.measured->scan_used;
          }
          recorder.add(std::move(result));
        }
      }
    }
  }
}

}  // namespace

void run_sampling_experiment(const Inputs& inputs, const ExperimentSettings& settings,
                             lightsampler::Frame& frame, Recorder& recorder) {
  run_count_series("sampling", "Sample count", inputs, settings, run_floors(settings, recorder), frame, recorder);
}

std::vector<Variant> ablation_variants(Backend backend) {
  const Variant full{.backend = backend, .method = Method::trs, .counting = Counting::automatic, .ablation = "full"};
  const auto with = [&](const char* name, auto change) {
    Variant v = full;
    v.ablation = name;
    change(v);
    return v;
  };
  std::vector<Variant> variants = {full};
  if (backend == Backend::vulkan) {
    variants.push_back(with("raster-counting", [](Variant& v) { v.counting = Counting::raster; }));
    variants.push_back(with("compute-counting", [](Variant& v) { v.counting = Counting::compute; }));
    variants.push_back(with("per-triangle-counting", [](Variant& v) { v.counting = Counting::per_triangle; }));
    variants.push_back(with("no-subgroup-reduction", [](Variant& v) { v.subgroup_reduction = false; }));
    variants.push_back(with("inverse-cdf", [](Variant& v) { v.inverse_cdf = true; }));
    variants.push_back(with("ordered-scan", [](Variant& v) { v.scan = ScanOrder::ordered; }));
    variants.push_back(with("lookback-scan", [](Variant& v) { v.scan = ScanOrder::lookback; }));
  } else {
    // The CPU backend's own choice is the ordered scan.
    variants.push_back(with("unordered-scan", [](Variant& v) { v.scan = ScanOrder::unordered; }));
  }
  variants.push_back(with("clipping-overlap", [](Variant& v) { v.overlap = Overlap::clipping; }));
  variants.push_back(with("sdf-overlap", [](Variant& v) { v.overlap = Overlap::sdf; }));
  variants.push_back(with("no-exact-draws", [](Variant& v) { v.exact_after = 0; }));
  return variants;
}

void run_ablation_experiment(const Inputs& inputs, const ExperimentSettings& settings,
                             lightsampler::Frame& frame, Recorder& recorder) {
  ExperimentSettings ablation = settings;
  ablation.variants.clear();
  for (Backend backend : backends_of(settings.variants))
    for (const Variant& v : ablation_variants(backend)) ablation.variants.push_back(v);
  ablation.measure.recount = true;
  run_count_series("ablation", "Ablation", inputs, ablation, {}, frame, recorder);
}

namespace {

/// One triangle, its texel-space corners (0, 0), (4 + d, 0) and (0, 4 + d) on an 8 x 8 map, and
/// the map: texel (2, 2) lit alone, which the triangle overlaps in a corner of legs d, a fraction
/// d^2 / (4 + d)^2 of its area; or, for fraction 0, every texel lit.
Inputs sliver_inputs(double fraction) {
  constexpr std::uint32_t kSize = 8;
  const double root = std::sqrt(fraction), d = 4.0 * root / (1.0 - root);
  const float corner = float((4.0 + d) / kSize);
  std::ostringstream name;
  name << "sliver:" << fraction;
  Mesh mesh{fraction > 0 ? name.str() : std::string("ordinary"),
            {0, 0, 0, 1, 0, 0, 0, 1, 0},
            {0, 0, corner, 0, 0, corner},
            {0, 1, 2}};
  DensityMap map{fraction > 0 ? "one-texel" : "uniform", kSize, kSize, std::vector<float>(kSize * kSize, 1.0f), 1.0};
  if (fraction > 0) {
    std::fill(map.texels.begin(), map.texels.end(), 0.0f);
    map.texels[2 * kSize + 2] = 1.0f;
    map.coverage = 1.0 / (kSize * kSize);
  }
  return {{std::move(mesh)}, {std::move(map)}};
}

}  // namespace

void run_sliver_experiment(const ExperimentSettings& settings, lightsampler::Frame& frame, Recorder& recorder) {
  ExperimentSettings sliver = settings;
  sliver.refinement = {};  // subdivision would split the triangle towards its lit texel
  for (double fraction : {0.0, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6}) {
    sliver.variants.clear();
    for (Backend backend : backends_of(settings.variants)) {
      const Variant exact{.backend = backend,
                          .ablation = "exact-after-" + std::to_string(lightsampler::FrameRequest{}.exact_after)};
      sliver.variants.push_back(exact);
      if (fraction == 0 || fraction >= 1e-3) {
        Variant paper = exact;
        paper.exact_after = 0;
        paper.ablation = "paper-rule";
        sliver.variants.push_back(paper);
      }
    }
    run_count_series("sliver", "Sliver of density", sliver_inputs(fraction), sliver, {}, frame, recorder);
  }
}

void run_overlap_experiment(const Inputs& inputs, const ExperimentSettings& settings,
                            lightsampler::Frame& frame, Recorder& recorder) {
  recorder.begin_section("Overlap formula (every frame counts; frames stop after the scan)");
  MeasureSettings counting_each_frame = settings.measure;
  counting_each_frame.recount = true;
  for (const Mesh& mesh : inputs.meshes)
    for (const DensityMap& map : inputs.maps) {
      Samplers samplers(mesh, map, settings);
      for (const Variant& variant : settings.variants) {
        if (variant.method != Method::trs) continue;
        for (Overlap overlap : {Overlap::closed_form, Overlap::clipping, Overlap::sdf}) {
          FrameRequest request = request_for(variant);
          request.overlap = overlap;
          request.target_count = settings.scan_target;
          request.realize = false;
          CaseResult result = describe_case("overlap", mesh, map, samplers.of(variant), request, variant.engine(), settings);
          const lightsampler::DensityMapView view = map.view();
          result.measured = measure(samplers.of(variant), frame, request, kFirstSeed, counting_each_frame, {&view, 1});
          result.scan = result.measured->scan_used;
          recorder.add(std::move(result));
        }
      }
    }
}

void run_scan_experiment(const Inputs& inputs, const ExperimentSettings& settings,
                         lightsampler::Frame& frame, Recorder& recorder) {
  recorder.begin_section("Scan order (frames stop after the scan)");
  for (const Mesh& mesh : inputs.meshes) {
    for (const DensityMap& map : inputs.maps) {
      Samplers samplers(mesh, map, settings);
      for (Sampler* sampler : {samplers.cpu.get(), samplers.vulkan.get()}) {
        if (!sampler) continue;
        std::vector<ScanOrder> scans{ScanOrder::unordered, ScanOrder::ordered};
        if (sampler->backend() == Backend::vulkan) scans.push_back(ScanOrder::lookback);  // GPU only
        for (ScanOrder scan : scans) {
          FrameRequest request;
          request.target_count = settings.scan_target;
          request.scan = scan;
          request.realize = false;
          request.vulkan.read_back = false;
          CaseResult result = describe_case("scan", mesh, map, *sampler, request,
                                            lightsampler::to_string(sampler->backend()), settings);
          const lightsampler::DensityMapView view = map.view();
          result.measured = measure(*sampler, frame, request, kFirstSeed, settings.measure, {&view, 1});
          result.scan = result.measured->scan_used;
          recorder.add(std::move(result));
        }
      }
    }
  }
}

std::string Variant::engine() const {
  if (backend != Backend::vulkan) return "cpu";
  if (method != Method::trs) return "vk";
  return std::string("vk/") + lightsampler::to_string(counting);
}

std::vector<std::string> sanity_problems(const std::vector<CaseResult>& results) {
  std::vector<std::string> problems;
  for (const auto& r : results) {
    if (!r.measured) continue;
    const Measurement& m = *r.measured;
    const std::string where = r.experiment + " " + r.engine + " " + r.method + " " + r.mesh + " " +
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
