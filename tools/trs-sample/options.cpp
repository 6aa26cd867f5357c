#include "options.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <string>

#include "common/cli_options.h"

namespace trs {
namespace {

constexpr lightsampler::EnumName<MapEncoding> kEncodings[] = {
    {MapEncoding::automatic, "auto"}, {MapEncoding::srgb, "srgb"}, {MapEncoding::linear, "linear"}};

}  // namespace

std::variant<Options, int> parse_options(int argc, char** argv) {
  CLI::App app(
      "Draws random points on a triangle mesh, distributed in proportion to a density map "
      "(samples per unit of world area) mapped onto it by its UVs, with Triangle Rejection "
      "Sampling.",
      "trs-sample");
  Options options;
  double count = 0, scale = 1;
  std::string method = "trs", backend = "auto", counting = "auto", scan = "auto", overlap = "closed-form",
              address = "wrap",
              encoding = "auto";
  std::string out, stats;

  app.add_option("MESH", options.mesh, "Wavefront OBJ or glTF 2.0 (.gltf, .glb) mesh with UVs")
      ->required();
  app.add_option("DENSITY", options.density,
                 "density map (EXR, HDR, PNG, JPEG, ...); colour maps give their luminance")
      ->required();
  app.add_option("--count", count,
                 "target sample count N_target (1e8 notation accepted); without it the count "
                 "is the integral of the density, N-bar")
      ->check(kFiniteNonNegative);
  app.add_option("--seed", options.seed, "random seed")->capture_default_str();
  app.add_option("--density-scale", scale, "multiplies every texel of the map")
      ->check(kFiniteNonNegative)
      ->capture_default_str();
  app.add_option("--method", method,
                 "Triangle Rejection Sampling, plain rejection sampling, naive triangle "
                 "stratification or fast rejection sampling (FRS)")
      ->check(CLI::IsMember(names(lightsampler::kMethodNames)))
      ->capture_default_str();
  app.add_option("--threads", options.threads, "worker threads; 0: all hardware threads")
      ->capture_default_str();
  app.add_option("--backend", backend,
                 "sampler backend; auto: Vulkan on a GPU, else the native CPU backend")
      ->check(CLI::IsMember(names(lightsampler::kBackendNames)))
      ->capture_default_str();
  app.add_option("--device", options.device,
                 "Vulkan device by index or name (also LIGHTSAMPLER_VULKAN_DEVICE); implies Vulkan "
                 "with --backend auto");
  app.add_option("--counting", counting,
                 "Vulkan counting pass: raster (the paper's UV rasterization), compute (balanced), "
                 "or per-triangle (the paper's naive ablation)")
      ->check(CLI::IsMember(names(lightsampler::kRequestableCountings)))
      ->capture_default_str();
  add_refine_option(app, options.refinement);
  app.add_option("--scan", scan,
                 "cumulative sum of the per-triangle counts (lookback: decoupled look-back, Vulkan only)")
      ->check(CLI::IsMember(names(lightsampler::kScanOrderNames)))
      ->capture_default_str();
  app.add_option("--overlap", overlap,
                 "triangle-texel overlap of TRS's counting: the closed form, polygon clipping, or the "
                 "paper's Eq. 6 SDF approximation (biased; for experiments)")
      ->check(CLI::IsMember(names(lightsampler::kOverlapNames)))
      ->capture_default_str();
  app.add_option("--exact-after", options.exact_after,
                 "TRS: rejections in a row after which the rest of a segment is drawn exactly from "
                 "its triangle's texel pieces (bounds the time of slivers of density); 0: never, "
                 "the paper's rule")
      ->capture_default_str();
  app.add_option("--address", address, "what UVs outside [0, 1] read")
      ->check(CLI::IsMember(names(lightsampler::kAddressingNames)))
      ->capture_default_str();
  app.add_option("--map-encoding", encoding,
                 "transfer function of the map's values; auto: 8/16-bit images are sRGB unless "
                 "their metadata says linear, float images are linear")
      ->check(CLI::IsMember(names(kEncodings)))
      ->capture_default_str();
  app.add_option("--out", out, "PLY file of the samples; without it nothing is written");
  app.add_option("--stats", stats, "JSON summary of the run");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "trs-sample: error: " << e.what() << "\nRun with --help for more information.\n";
    return kUsageError;
  }

  if (app.count("--count")) options.target_count = count;
  // auto splits for the frame asked for; without a target the acceptance rules decide.
  if (options.refinement.cost_model) options.refinement.frame_samples = options.target_count.value_or(0.0);
  options.density_scale = static_cast<float>(scale);
  if (!std::isfinite(options.density_scale)) {
    std::cerr << "trs-sample: error: --density-scale " << scale << " does not fit a float\n";
    return kUsageError;
  }
  // The names were checked by IsMember.
  options.method = named(lightsampler::kMethodNames, method);
  options.backend = named(lightsampler::kBackendNames, backend);
  options.counting = named(lightsampler::kRequestableCountings, counting);
  options.scan = named(lightsampler::kScanOrderNames, scan);
  options.overlap = named(lightsampler::kOverlapNames, overlap);
  options.addressing = named(lightsampler::kAddressingNames, address);
  options.map_encoding = named(kEncodings, encoding);
  if (!out.empty()) options.out = out;
  if (!stats.empty()) options.stats = stats;
  return options;
}

}  // namespace trs
