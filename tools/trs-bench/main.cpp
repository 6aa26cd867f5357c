// trs-bench: Triangle Rejection Sampling against plain rejection sampling on generated meshes and
// density maps. Needs nothing but the lightsampler library, so that the same program runs on a
// machine without asset files or image libraries. See docs/benchmarks.md.

#include <algorithm>
#include <chrono>
#include <exception>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/build_commit.h"
#include "common/cli_options.h"
#include "experiments.h"

namespace {

using namespace trs_bench;

struct CommandLine {
  std::vector<std::string> meshes = {"grid:5k", "sphere:100k", "grid:2M"};
  std::vector<std::string> maps = {"smooth", "sparse", "hifreq"};
  std::uint32_t map_size = 2048;
  std::vector<std::string> methods = {"trs", "rs"};
  std::vector<std::string> backends = {"cpu"};
  std::vector<std::string> countings = {"auto", "raster", "compute"};
  std::vector<std::string> experiments = {"sampling", "scan"};
  std::string csv;
  ExperimentSettings settings;
};

/// --quick: a smoke run of a few seconds; options given explicitly still win.
void apply_quick(const CLI::App& app, CommandLine& cl) {
  if (!app.count("--meshes")) cl.meshes = {"grid:5k"};
  if (!app.count("--map-size")) cl.map_size = 256;
  if (!app.count("--counts")) cl.settings.counts = {1e3, 1e4, 1e5};
  if (!app.count("--repeats")) cl.settings.measure.repeats = 2;
  if (!app.count("--budget")) cl.settings.measure.budget_s = 2;
  if (!app.count("--scan-target")) cl.settings.scan_target = 1e4;
}

/// CLI11 validator: empty when `parse(text)` succeeds, else why not.
template <auto parse>
std::string check_spec(const std::string& text) {
  try {
    parse(text);
    return {};
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
}

bool contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

template <class F>
double seconds_of(F&& f) {
  const auto start = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Inputs generate_inputs(const CommandLine& cl) {
  Inputs inputs;
  for (const auto& spec : cl.meshes) {
    const double s = seconds_of([&] { inputs.meshes.push_back(make_mesh(parse_mesh_spec(spec))); });
    std::cout << "mesh " << spec << ": " << inputs.meshes.back().name << " with "
              << inputs.meshes.back().triangle_count() << " triangles (" << s << " s)\n";
  }
  for (const auto& spec : cl.maps) {
    const double s = seconds_of([&] { inputs.maps.push_back(make_map(parse_map_spec(spec), cl.map_size)); });
    const DensityMap& map = inputs.maps.back();
    std::cout << "map " << spec << ": " << map.width << "x" << map.height << ", "
              << 100 * map.coverage << "% of texels non-zero (" << s << " s)\n";
  }
  return inputs;
}

/// The backends as the experiments will see them, from one-triangle samplers; fails early (with
/// the reason) when a backend asked for is unavailable.
void print_backends(const ExperimentSettings& settings) {
  const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, uvs[] = {0, 0, 1, 0, 0, 1}, texel[] = {1};
  const std::uint32_t indices[] = {0, 1, 2};
  const lightsampler::DensityMapView map{texel, 1, 1};
  std::vector<lightsampler::Backend> shown;
  for (const Variant& v : settings.variants) {
    if (std::find(shown.begin(), shown.end(), v.backend) != shown.end()) continue;
    shown.push_back(v.backend);
    const auto sampler = lightsampler::make_sampler(
        {positions, uvs, indices, {}}, {&map, 1},
        {.backend = v.backend,
         .cpu = {settings.threads},
         .vulkan = {.device = settings.vulkan_device},
         .refinement = {}});
    std::cout << "backend " << lightsampler::to_string(sampler->backend()) << " on " << sampler->device();
    if (sampler->backend() == lightsampler::Backend::cpu)
      std::cout << ", " << lightsampler::worker_threads({settings.threads}) << " threads";
    std::cout << "\n";
  }
}

/// Backends x methods, and for Vulkan TRS each counting path.
std::vector<Variant> make_variants(const CommandLine& cl) {
  std::vector<Variant> variants;
  for (const auto& backend_name : cl.backends) {
    const bool vulkan = backend_name == "vulkan";
    const auto backend = vulkan ? lightsampler::Backend::vulkan : lightsampler::Backend::cpu;
    for (const auto& method_name : cl.methods) {
      const auto method = trs::named(lightsampler::kMethodNames, method_name);
      if (!vulkan || method != lightsampler::Method::trs) {
        variants.push_back({.backend = backend, .method = method, .counting = lightsampler::Counting::automatic});
        continue;
      }
      for (const auto& counting : cl.countings)
        variants.push_back({.backend = backend, .method = method, .counting = trs::named(lightsampler::kRequestableCountings, counting)});
    }
  }
  return variants;
}

int run(const CommandLine& cl) {
  ExperimentSettings settings = cl.settings;
  // Ascending, because skipping extrapolates from the smaller counts.
  std::sort(settings.counts.begin(), settings.counts.end());
  settings.variants = make_variants(cl);

  print_backends(settings);
  std::cout << "warm-up " << settings.measure.warmup << ", repeats " << settings.measure.repeats
            << " (medians), budget " << settings.measure.budget_s << " s per case\n";
  // The sliver experiment makes its own inputs.
  const bool own_inputs_only = cl.experiments == std::vector<std::string>{"sliver"};
  const Inputs inputs = own_inputs_only ? Inputs{} : generate_inputs(cl);

  lightsampler::Frame frame;
  Recorder recorder(std::cout, cl.csv);
  if (contains(cl.experiments, "sampling")) {
    run_sampling_experiment(inputs, settings, frame, recorder);
    print_speedups(std::cout, recorder.results());
  }
  if (contains(cl.experiments, "scan")) run_scan_experiment(inputs, settings, frame, recorder);
  if (contains(cl.experiments, "overlap")) run_overlap_experiment(inputs, settings, frame, recorder);
  if (contains(cl.experiments, "ablation")) run_ablation_experiment(inputs, settings, frame, recorder);
  if (contains(cl.experiments, "sliver")) run_sliver_experiment(settings, frame, recorder);
  if (!cl.csv.empty()) std::cout << "\nwrote " << cl.csv << "\n";

  const auto problems = sanity_problems(recorder.results());
  for (const auto& problem : problems) std::cerr << "trs-bench: wrong output: " << problem << "\n";
  return problems.empty() ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Benchmarks Triangle Rejection Sampling against plain rejection sampling on "
      "generated meshes and density maps; prints tables and writes CSV."};
  CommandLine cl;
  cl.settings.counts = {1e3, 1e4, 1e5, 1e6, 1e7, 1e8};
  bool quick = false;
  app.add_option("--counts", cl.settings.counts, "Target sample counts")
      ->delimiter(',')
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--meshes", cl.meshes,
                 "Meshes as KIND:TRIANGLES, KIND grid, sphere or torus, e.g. grid:100k,sphere:2M; "
                 "or file:PATH, the mesh of a dataset file (trs-dataset)")
      ->delimiter(',')
      ->check(check_spec<parse_mesh_spec>)
      ->capture_default_str();
  app.add_option("--maps", cl.maps,
                 "Density maps: " + map_kind_names() +
                     " (threshold:F: the fractal's brightest fraction F of texels; file:PATH: the "
                     "map of a dataset file)")
      ->delimiter(',')
      ->check(check_spec<parse_map_spec>)
      ->capture_default_str();
  app.add_option("--map-size", cl.map_size, "Width and height of the generated density maps, texels")
      ->check(CLI::Range(1u, 1u << 15))
      ->capture_default_str();
  app.add_option("--methods", cl.methods,
                 "Methods: trs (Triangle Rejection Sampling), rs (plain rejection sampling), "
                 "naive (naive triangle stratification), frs (fast rejection sampling)")
      ->delimiter(',')
      ->check(CLI::IsMember(trs::names(lightsampler::kMethodNames)))
      ->capture_default_str();
  app.add_option("--backends", cl.backends, "Backends: cpu, vulkan (side by side)")
      ->delimiter(',')
      ->check(CLI::IsMember({"cpu", "vulkan"}))
      ->capture_default_str();
  app.add_option("--counting", cl.countings,
                 "Counting paths of the Vulkan backend: auto (per-triangle for small triangles, "
                 "compute for large ones), raster, compute, per-triangle (the paper's naive ablation)")
      ->delimiter(',')
      ->check(CLI::IsMember(trs::names(lightsampler::kRequestableCountings)))
      ->capture_default_str();
  trs::add_refine_option(app, cl.settings.refinement);
  app.add_option("--device", cl.settings.vulkan_device,
                 "Vulkan device by index or name (also LIGHTSAMPLER_VULKAN_DEVICE)");
  app.add_option("--experiments", cl.experiments,
                 "sampling (time vs sample count), scan (scan orders), overlap (the overlap "
                 "formulas of TRS's counting), ablation (the sampler and one change at a time, "
                 "through the counts), sliver (one triangle whose lit texel overlaps it by 1e-2 "
                 "to 1e-6 of its area, beside the same triangle fully lit)")
      ->delimiter(',')
      ->check(CLI::IsMember({"sampling", "scan", "overlap", "ablation", "sliver"}))
      ->capture_default_str();
  app.add_option("--threads", cl.settings.threads, "Worker threads; 0: every hardware thread")
      ->capture_default_str();
  app.add_option("--repeats", cl.settings.measure.repeats, "Timed frames per case (median)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--warmup", cl.settings.measure.warmup, "Untimed frames before them")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--budget", cl.settings.measure.budget_s,
                 "Seconds per case: a case whose extrapolated frame time exceeds it is skipped, "
                 "and a case stops repeating once it has used it")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_flag("--recount", cl.settings.measure.recount,
               "Replace the maps before every frame (an animated texture): every frame counts. "
               "Without it a sampler counts once and keeps the counts");
  app.add_option("--scan-target", cl.settings.scan_target,
                 "Target sample count of the scan experiment")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--csv", cl.csv,
                 "Write the results as CSV to FILE (rewritten atomically after each case)");
  app.add_flag("--quick", quick, "Smoke run: grid:5k, 256x256 maps, counts 1e3..1e5, 2 repeats");
  bool list_devices = false;
  app.add_flag("--list-devices", list_devices,
               "Print the Vulkan devices (index, name, type, driver) and exit");
  app.set_version_flag("--version", std::string("trs-bench, commit ") + trs::build_commit(),
                       "Print the commit it was built from and exit");
  CLI11_PARSE(app, argc, argv);
  if (list_devices) {
    for (const auto& line : lightsampler::vulkan_devices()) std::cout << line << "\n";
    return 0;
  }
  if (quick) apply_quick(app, cl);
  // auto splits for the largest frames of the run: one subdivision serves every count.
  if (cl.settings.refinement.cost_model && !cl.settings.counts.empty())
    cl.settings.refinement.frame_samples = *std::max_element(cl.settings.counts.begin(), cl.settings.counts.end());

  try {
    return run(cl);
  } catch (const std::exception& e) {
    std::cerr << "trs-bench: " << e.what() << "\n";
    return 1;
  }
}
