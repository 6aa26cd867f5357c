#include "options.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "common/build_commit.h"
#include "common/cli_options.h"
#include "scene_io/frame_pattern.h"

namespace trs {
namespace {

const std::map<std::string, tracer::StrategyKind> kStrategies = {
    {"uniform", tracer::StrategyKind::uniform},
    {"power", tracer::StrategyKind::power},
    {"trs", tracer::StrategyKind::trs},
    {"ris", tracer::StrategyKind::ris},
    {"tree", tracer::StrategyKind::tree},
    {"texel", tracer::StrategyKind::texel},
    {"tree-texel", tracer::StrategyKind::tree_texel},
    {"auto", tracer::StrategyKind::automatic}};

const std::map<std::string, tracer::TreeImportance> kTreeImportances = {
    {"pbrt", tracer::TreeImportance::pbrt}, {"cycles", tracer::TreeImportance::cycles}};

const std::map<std::string, tracer::TreePower> kTreePowers = {
    {"exact", tracer::TreePower::exact}, {"image-mean", tracer::TreePower::image_mean}};

/// "A:B" with 0 <= A <= B.
std::optional<FrameRange> parse_frames(const std::string& text) {
  const std::size_t colon = text.find(':');
  if (colon == std::string::npos) return std::nullopt;
  FrameRange range;
  for (auto [part, value] : {std::pair{text.substr(0, colon), &range.first}, std::pair{text.substr(colon + 1), &range.last}}) {
    if (part.empty() || part.size() > 12 || !std::all_of(part.begin(), part.end(), [](char c) { return c >= '0' && c <= '9'; }))
      return std::nullopt;
    *value = std::stoll(part);
  }
  if (range.first > range.last) return std::nullopt;
  return range;
}

std::vector<std::string> resamplable_names() {
  std::vector<std::string> result;
  for (const auto& [name, kind] : kStrategies)
    if (tracer::resamplable(kind)) result.push_back(name);
  return result;
}

/// The settings file as CLI11 reads TOML, but a key without a value (`height = []`) is refused:
/// CLI11 would hand the option an empty list, which its conversions index all the same.
class SettingsFile : public CLI::ConfigTOML {
 public:
  std::vector<CLI::ConfigItem> from_config(std::istream& input) const override {
    std::vector<CLI::ConfigItem> items = CLI::ConfigTOML::from_config(input);
    for (const CLI::ConfigItem& item : items)
      if (item.inputs.empty() && item.name != "++" && item.name != "--")  // not a section's start or end
        throw CLI::ConfigError(item.fullname() + ": no value");
    return items;
  }
};

std::string environment_variable(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "";
}

}  // namespace

std::variant<RenderOptions, int> parse_render_options(int argc, char** argv) {
  return parse_render_options(argc, argv, std::cerr, true);
}

std::variant<RenderOptions, int> parse_render_options(const std::vector<std::string>& arguments,
                                                      std::ostream& errors, bool out_required) {
  std::vector<char*> argv;
  for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  return parse_render_options(int(arguments.size()), argv.data(), errors, out_required);
}

std::variant<RenderOptions, int> parse_render_options(int argc, char** argv, std::ostream& errors, bool out_required) {
  CLI::App app(
      "Renders a glTF 2.0 scene lit by its emissive textures with a path tracer whose next-event "
      "estimation samples lights uniformly by area, by triangle power, by a light tree that weighs "
      "them for each shading point (tree), or from millions of point lights drawn every frame by "
      "Triangle Rejection Sampling, used as they are (trs) or resampled per shading point by their "
      "unshadowed contribution (ris).",
      "trs-render");
  RenderOptions options;
  tracer::RenderSettings& r = options.render;
  std::string strategy = "auto", candidates_from = "trs", tree_importance = "pbrt", tree_power = "exact",
              backend = "auto", lights = "auto", out, stats, preview, variance, emitter_mask;
  double time = 0.0;
  bool quiet = false;

  app.set_config("--settings", "", "settings file of `key = value` lines (TOML) with the long "
                                   "option names, e.g. spp = 64; the command line wins");
  app.config_formatter(std::make_shared<SettingsFile>());
  // A misspelt key would otherwise be dropped without a word, and the render not be the one asked for.
  app.allow_config_extras(CLI::config_extras_mode::error);
  app.set_version_flag("--version", std::string("trs-render, commit ") + trs::build_commit(), "print the commit it was built from and exit");
  app.add_option("SCENE", options.scene, "glTF 2.0 scene (.gltf, .glb)")->required();
  // An option given twice takes its last value, so that a script can override its own defaults.
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  app.add_option("--out", out, "linear float RGB OpenEXR image")->required(out_required);
  app.add_option("--spp", r.spp, "samples per pixel: frames of one path per pixel")
      ->capture_default_str();
  app.add_option("--time", time,
                 "render frames until SECONDS of wall time have passed since the start, set-up "
                 "included (at least one frame); an explicit --spp then caps the frames")
      ->check(CLI::PositiveNumber & kFiniteNonNegative);
  app.add_option("--strategy", strategy, "light sampling for next-event estimation")
      ->check(CLI::IsMember(names(kStrategies)))
      ->capture_default_str();
  app.add_option("--lights", lights,
                 "trs, ris: expected point lights drawn per frame (1e6 notation accepted; 64 bytes "
                 "each); auto: a quarter of the frame's next-event queries, width x height x max "
                 "depth")
      ->check(CLI::IsMember(std::vector<std::string>{"auto"}) | kFiniteNonNegative)
      ->capture_default_str();
  app.add_option("--candidates", r.strategy.candidates,
                 "ris: points resampled into each next-event connection")
      ->check(CLI::Range(1u, 1024u))
      ->capture_default_str();
  app.add_option("--candidates-from", candidates_from,
                 "ris: the strategy its candidates come from")
      ->check(CLI::IsMember(resamplable_names()))
      ->capture_default_str();
  app.add_option("--tree-importance", tree_importance,
                 "tree, tree-texel: how a node's importance for a shading point is estimated: pbrt (pbrt-v4's), "
                 "or cycles (Cycles' lower and upper bounds, averaged)")
      ->check(CLI::IsMember(names(kTreeImportances)))
      ->capture_default_str();
  app.add_option("--tree-power", tree_power,
                 "tree, tree-texel: each light's power: exact (its texels' integral), or image-mean (its area "
                 "times the mean of its whole emission map, as pbrt-v4 takes it)")
      ->check(CLI::IsMember(names(kTreePowers)))
      ->capture_default_str();
  app.add_option("--seed", r.seed, "random seed of the paths and the light sets")
      ->capture_default_str();
  app.add_option("--width", r.width, "image width, pixels")->capture_default_str();
  app.add_option("--height", r.height, "image height, pixels")->capture_default_str();
  app.add_option("--max-depth", r.max_depth,
                 "most bounces of a path: 0 shows the emitters only, 1 is direct lighting")
      ->capture_default_str();
  app.add_option("--threads", r.threads, "worker threads; 0: all hardware threads")
      ->capture_default_str();
  app.add_option("--backend", backend,
                 "light sampler (the point lights of trs and ris, every strategy's light "
                 "integrals); auto: Vulkan on a GPU, else the native CPU backend")
      ->check(CLI::IsMember(names(kBackends)))
      ->capture_default_str();
  // Refined by the cost model by default: the same lights for less of the sampler's work, and
  // no split its frames cannot pay for (docs/benchmarks.md).
  r.sampler.refinement = lightsampler::auto_refinement(0.0);  // the lights a frame draws are filled in by the renderer
  add_refine_option(app, r.sampler.refinement);
  app.add_option("--device", r.sampler.vulkan.device,
                 "Vulkan device by index or name (also LIGHTSAMPLER_VULKAN_DEVICE)");
  std::string frames;
  std::int64_t chunk = 1;
  bool plan = false;
  app.add_option("--frames", frames,
                 "render animation frames A to B (A:B, inclusive), an image each: --out and the other "
                 "outputs are then frame patterns (out.%04d.exr), --spp and --time apply to each frame");
  app.add_option("--fps", r.fps, "animation frames per second (frame f is f / fps seconds in)")
      ->check(CLI::PositiveNumber & kFiniteNonNegative)
      ->capture_default_str();
  app.add_flag("--resume", options.resume, "--frames: skip the frames whose outputs are all there");
  app.add_flag("--plan", plan,
               "--frames: print one trs-render command per chunk of frames (for GNU parallel or a Slurm "
               "array) and render nothing");
  app.add_option("--chunk", chunk, "--plan: frames per command")->check(CLI::PositiveNumber)->capture_default_str();
  app.add_option("--stats", stats, "JSON summary of the run");
  app.add_option("--preview", preview,
                 "8-bit PNG preview of the image: sRGB-encoded, or through an OpenColorIO display and "
                 "view (--ocio-config)");
  app.add_option("--variance", variance,
                 "OpenEXR of each pixel's per-sample luminance variance (all three channels), "
                 "for noise studies and noise-aware image comparison (trs-imgdiff)");
  app.add_option("--emitter-mask", emitter_mask,
                 "OpenEXR of each pixel's fraction of camera samples whose first hit is an emitter "
                 "(all three channels): pixels whose noise is the pixel footprint over an emitter, "
                 "the same for every light strategy, to leave out of noise figures");
  app.add_option("--exposure", options.exposure, "preview exposure, stops, applied before the display transform")
      ->capture_default_str();
  DisplayTransform& display = options.preview_display;
  std::string ocio_config;
  app.add_option("--ocio-config", ocio_config,
                 "OpenColorIO config of the preview's display transform (default: $OCIO; a built-in "
                 "config's ocio:// URI needs OpenColorIO 2.2); without one, or empty, the sRGB curve");
  app.add_option("--ocio-colorspace", display.colorspace,
                 "the renders' colour space in the config (default: its linear Rec. 709 space by its usual "
                 "names, lin_rec709 and others, else its scene_linear role)");
  app.add_option("--display", display.display, "the preview's display in the config (default: its default display)");
  app.add_option("--view", display.view,
                 "the preview's view of the display, e.g. a filmic or ACES view that does not clip highlights "
                 "(default: the display's default view)");
  app.add_flag("--quiet", quiet, "no progress bar");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    std::cout << e.what() << "\n";
    return 0;
  } catch (const CLI::ConfigError& e) {
    // CLI11 names the key, not the file it came from.
    errors << "trs-render: error: " << app.get_option("--settings")->as<std::string>() << ": " << e.what()
              << " (settings are the long option names)\n";
    return kUsageError;
  } catch (const CLI::ParseError& e) {
    errors << "trs-render: error: " << e.what() << "\nRun with --help for more information.\n";
    return kUsageError;
  }
  if (r.width == 0 || r.height == 0 || r.spp == 0) {
    errors << "trs-render: error: --width, --height and --spp must be at least 1\n";
    return kUsageError;
  }
  if (app.count("--time") > 0) {
    options.time_seconds = time;
    // Only --spp on the command line caps a timed render; a settings file's spp is a default
    // that the time budget replaces.
    const bool spp_on_command_line = std::any_of(argv + 1, argv + argc, [](const char* a) {
      return std::string_view(a) == "--spp" || std::string_view(a).starts_with("--spp=");
    });
    if (!spp_on_command_line) r.spp = std::numeric_limits<unsigned>::max();
  }
  r.strategy.kind = kStrategies.at(strategy);
  r.strategy.candidates_from = kStrategies.at(candidates_from);
  for (const char* option : {"--candidates", "--candidates-from"}) {
    if (app.count(option) > 0 && r.strategy.kind != tracer::StrategyKind::ris &&
        r.strategy.kind != tracer::StrategyKind::automatic) {
      errors << "trs-render: error: " << option << " belongs to --strategy ris (and auto, where it chooses ris)\n";
      return kUsageError;
    }
  }
  r.strategy.tree = {kTreeImportances.at(tree_importance), kTreePowers.at(tree_power)};
  for (const char* option : {"--tree-importance", "--tree-power"}) {
    if (app.count(option) > 0 && !tracer::picks_by_tree(r.strategy)) {
      errors << "trs-render: error: " << option << " belongs to --strategy tree and tree-texel (or ris over them)\n";
      return kUsageError;
    }
  }
  if (!frames.empty()) {
    const auto range = parse_frames(frames);
    if (!range) {
      errors << "trs-render: error: --frames takes A:B, frames 0 <= A <= B (" << frames << ")\n";
      return kUsageError;
    }
    options.frames = range;
  }
  for (const char* option : {"--resume", "--plan", "--chunk"}) {
    if (app.count(option) > 0 && !options.frames) {
      errors << "trs-render: error: " << option << " belongs to --frames\n";
      return kUsageError;
    }
  }
  // As OpenColorIO reads $OCIO, an empty value is none.
  display.config = app.count("--ocio-config") > 0 ? ocio_config : environment_variable("OCIO");
  for (const char* option : {"--ocio-colorspace", "--display", "--view"}) {
    if (app.count(option) > 0 && display.config.empty()) {
      errors << "trs-render: error: " << option << " needs an OpenColorIO config: --ocio-config or $OCIO\n";
      return kUsageError;
    }
  }
  if (plan) options.plan_chunk = chunk;
  options.arguments.assign(argv, argv + argc);
  r.strategy.lights = lights == "auto" ? tracer::auto_lights(r.width, r.height, r.max_depth) : std::stod(lights);
  r.sampler.backend = kBackends.at(backend);
  r.strategy.seed = r.seed;
  options.out = out;
  if (!stats.empty()) options.stats = stats;
  if (!preview.empty()) options.preview = preview;
  if (!variance.empty()) options.variance = variance;
  if (!emitter_mask.empty()) options.emitter_mask = emitter_mask;
  options.progress = !quiet;
  if (options.frames) {
    for (const std::filesystem::path& path : outputs(options)) {
      if (FramePattern::valid(path.filename().string())) continue;
      errors << "trs-render: error: with --frames, each output names its frame: " << path.string()
                << " needs one integer conversion in its file name (out.%04d.exr)\n";
      return kUsageError;
    }
  }
  return options;
}

std::filesystem::path output(const RenderOptions& options, const std::filesystem::path& path, std::int64_t frame) {
  if (!options.frames || path.empty()) return path;
  return path.parent_path() / FramePattern(path.filename().string()).format(frame);
}

std::vector<std::filesystem::path> outputs(const RenderOptions& options) {
  std::vector<std::filesystem::path> paths;
  if (!options.out.empty()) paths.push_back(options.out);
  for (const auto* path : {&options.stats, &options.preview, &options.variance, &options.emitter_mask})
    if (*path) paths.push_back(**path);
  return paths;
}

}  // namespace trs
