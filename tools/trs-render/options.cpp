#include "options.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdlib>
#include <initializer_list>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/build_commit.h"
#include "common/cli_options.h"
#include "scene_io/frame_pattern.h"
#include "scene_io/file_error.h"
#include "shell_words.h"
#include "tracer/strategy_registry.h"

namespace trs {
namespace {

constexpr const char* kAutoSummary = "the most efficient of power, trs and ris, by a pilot of a few passes on a grid of the pixels";

/// --strategy's help: every registered strategy (plugins loaded), then auto.
std::string strategy_help() {
  std::string help = "light sampling for next-event estimation:";
  for (const tracer::StrategyDefinition* s : tracer::registered_strategies())
    help += " " + s->name + " (" + s->summary + "),";
  return help + " auto (" + kAutoSummary + ")";
}

/// The names of the strategies ris can draw from, in the order of their names.
std::vector<std::string> resamplable_names() {
  std::vector<std::string> names;
  for (const tracer::StrategyDefinition* s : tracer::registered_strategies())
    if (tracer::resamplable(s->name)) names.push_back(s->name);
  return names;
}

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& n : names) text += (text.empty() ? "" : ", ") + n;
  return text;
}

/// Why --strategy-option's names are not all options of the strategy named or of the one that
/// draws its points; none if they are.
std::optional<std::string> undeclared_parameter(const tracer::StrategyOptions& options) {
  std::vector<std::string> declared;
  std::string owners = options.kind;
  for (const std::string& kind : {options.kind, tracer::source_kind(options)}) {
    if (const tracer::StrategyDefinition* s = tracer::find_strategy(kind))
      for (const tracer::StrategyParameter& p : s->parameters)
        if (std::find(declared.begin(), declared.end(), p.name) == declared.end()) declared.push_back(p.name);
    if (kind != options.kind) owners += " over " + kind;
  }
  for (const auto& [name, value] : options.parameters) {
    if (std::find(declared.begin(), declared.end(), name) == declared.end())
      return "--strategy-option " + name + ": strategy " + owners + " has " +
             (declared.empty() ? std::string("no options") : "the options " + joined(declared)) + ", not " + name;
  }
  return std::nullopt;
}

/// --strategy-option's help: the options of the strategies that have any.
std::string parameter_help() {
  std::string help = "NAME=VALUE: an option of the strategy (restir's, a plugin's), which reads it by name; repeatable";
  for (const tracer::StrategyDefinition* s : tracer::registered_strategies())
    for (const tracer::StrategyParameter& p : s->parameters) help += "; " + s->name + ": " + p.name + " (" + p.help + ")";
  return help;
}

/// The values of --plugin on a command line, so that their strategies are registered before the
/// options (and their help) are made; the settings file's are loaded once it is read.
std::vector<std::string> plugins_named(int argc, char** argv) {
  std::vector<std::string> plugins;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--plugin" && i + 1 < argc) plugins.emplace_back(argv[++i]);
    else if (a.starts_with("--plugin=")) plugins.push_back(a.substr(9));
  }
  return plugins;
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

/// A usage error found after parsing, as trs-render prints it after "trs-render: error: "; none
/// when the options agree.
using UsageError = std::optional<std::string>;

/// The first of `names` given though it means nothing unless `applies`: the error "NAME `why`".
UsageError misplaced(const CLI::App& app, std::initializer_list<const char*> names, bool applies, const char* why) {
  if (applies) return std::nullopt;
  for (const char* name : names)
    if (app.count(name) > 0) return std::string(name) + " " + why;
  return std::nullopt;
}

// The options by topic: each group adds its options to the parser, in the order the help lists
// them, and once the command line is parsed, fills in what they decide and checks them.

/// SCENE and --out; --settings, options from a file; --version.
void add_program_options(CLI::App& app, RenderOptions& options, bool out_required) {
  app.set_config("--settings", "", "settings file of `key = value` lines (TOML) with the long "
                                   "option names, e.g. spp = 64; the command line wins");
  app.config_formatter(std::make_shared<SettingsFile>());
  // A misspelt key would otherwise be dropped without a word, and the render not be the one asked for.
  app.allow_config_extras(CLI::config_extras_mode::error);
  app.set_version_flag("--version", std::string("trs-render, commit ") + trs::build_commit(), "print the commit it was built from and exit");
  app.add_option("SCENE", options.scene, "glTF 2.0 scene (.gltf, .glb)")->required();
  // An option given twice takes its last value, so that a script can override its own defaults.
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  app.add_option("--out", options.out, "linear float RGB OpenEXR image")->required(out_required);
}

/// --spp and --time: how long each image renders.
struct BudgetOptions {
  double time = 0.0;

  void add(CLI::App& app, tracer::RenderSettings& r) {
    app.add_option("--spp", r.spp, "samples per pixel: passes of one path per pixel")
        ->capture_default_str();
    app.add_option("--time", time,
                   "render passes until SECONDS of wall time have passed since the start, set-up "
                   "included (at least one pass); an explicit --spp then caps the passes")
        ->check(CLI::PositiveNumber & kFiniteNonNegative);
  }

  void finish(const CLI::App& app, RenderOptions& options) const {
    if (app.count("--time") == 0) return;
    options.time_seconds = time;
    // Only --spp on the command line caps a timed render; a settings file's spp is a default
    // that the time budget replaces.
    const std::vector<std::string>& arguments = options.arguments;
    const bool spp_on_command_line = std::any_of(arguments.begin() + 1, arguments.end(), [](const std::string& a) {
      return a == "--spp" || a.starts_with("--spp=");
    });
    if (!spp_on_command_line) options.render.spp = std::numeric_limits<unsigned>::max();
  }
};

/// --strategy and the options of particular strategies, --no-punctual and --diffuse-materials:
/// how next-event estimation samples the lights, which lights, and what they light.
struct LightOptions {
  std::string strategy = "auto", candidates_from = "trs", tree_importance = "pbrt", tree_power = "exact",
              lights = "auto";
  std::vector<std::string> plugins, parameters;

  void add(CLI::App& app, RenderOptions& options) {
    app.add_option("--strategy", strategy, strategy_help())->capture_default_str();
    app.add_option("--plugin", plugins,
                   "load the light strategies of a shared library built against the installed tracer "
                   "(examples/light_strategy); repeatable")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    app.add_option("--strategy-option", parameters, parameter_help())
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    app.add_flag_callback(
        "--list-strategies",
        [] {
          for (const tracer::StrategyDefinition* s : tracer::registered_strategies())
            std::cout << s->name << "\t" << s->summary << "\n";
          std::cout << tracer::kAutoStrategy << "\t" << kAutoSummary << "\n";
          throw CLI::Success();
        },
        "print the strategies --strategy takes (with the plugins' given before it), a name and a tab "
        "before each summary, and exit");
    app.add_option("--lights", lights,
                   "trs, ris: expected point lights drawn per frame (1e6 notation accepted; 64 bytes "
                   "each); auto: a quarter of the frame's next-event queries, width x height x max "
                   "depth")
        ->check(CLI::IsMember(std::vector<std::string>{"auto"}) | kFiniteNonNegative)
        ->capture_default_str();
    app.add_option("--candidates", options.render.strategy.candidates,
                   "ris: points resampled into each next-event connection")
        ->check(CLI::Range(1u, 1024u))
        ->capture_default_str();
    app.add_option("--candidates-from", candidates_from,
                   "ris: the strategy its candidates come from")
        ->capture_default_str();
    app.add_option("--tree-importance", tree_importance,
                   "tree, tree-texel: how a node's importance for a shading point is estimated: pbrt (pbrt-v4's), "
                   "or cycles (Cycles' lower and upper bounds, averaged)")
        ->check(CLI::IsMember(names(tracer::kTreeImportanceNames)))
        ->capture_default_str();
    app.add_option("--tree-power", tree_power,
                   "tree, tree-texel: each light's power: exact (its texels' integral), or image-mean (its area "
                   "times the mean of its whole emission map, as pbrt-v4 takes it)")
        ->check(CLI::IsMember(names(tracer::kTreePowerNames)))
        ->capture_default_str();
    app.add_flag("!--no-punctual", options.punctual,
                 "leave out the scene's punctual lights (KHR_lights_punctual): its emission alone");
    app.add_flag("--diffuse-materials", options.diffuse_materials,
                 "render every surface as a Lambertian of its base colour, emission and transmission kept: "
                 "lighting compared with other renderers");
  }

  UsageError finish(const CLI::App& app, RenderOptions& options) const {
    tracer::RenderSettings& r = options.render;
    try {
      for (const std::string& plugin : plugins) tracer::load_strategy_plugin(plugin);
    } catch (const FileError& error) {
      return error.what();
    }
    const std::vector<std::string> names = tracer::strategy_names(), sources = resamplable_names();
    if (std::find(names.begin(), names.end(), strategy) == names.end())
      return "--strategy: " + strategy + " not in {" + joined(names) + "}";
    if (std::find(sources.begin(), sources.end(), candidates_from) == sources.end())
      return "--candidates-from: " + candidates_from + " not in {" + joined(sources) + "}";
    r.strategy.kind = strategy;
    r.strategy.candidates_from = candidates_from;
    for (const std::string& p : parameters) {
      const std::size_t equals = p.find('=');
      if (equals == 0 || equals == std::string::npos) return "--strategy-option takes NAME=VALUE (" + p + ")";
      r.strategy.parameters[p.substr(0, equals)] = p.substr(equals + 1);
    }
    if (UsageError error = undeclared_parameter(r.strategy)) return error;
    const tracer::StrategyDefinition* definition = tracer::find_strategy(strategy);
    const bool resamples = (definition && definition->resamples) || strategy == tracer::kAutoStrategy;
    if (UsageError error = misplaced(app, {"--candidates", "--candidates-from"}, resamples,
                                     "belongs to --strategy ris and restir (and auto, where it chooses ris)"))
      return error;
    r.strategy.tree = {named(tracer::kTreeImportanceNames, tree_importance), named(tracer::kTreePowerNames, tree_power)};
    if (UsageError error = misplaced(app, {"--tree-importance", "--tree-power"}, tracer::picks_by_tree(r.strategy),
                                     "belongs to --strategy tree and tree-texel (or ris over them)"))
      return error;
    r.strategy.lights = lights == "auto" ? tracer::auto_lights(r.width, r.height, r.max_depth) : std::stod(lights);
    return std::nullopt;
  }
};

/// --seed, --width, --height, --max-depth, --threads: the image and its paths.
struct ImageOptions {
  void add(CLI::App& app, tracer::RenderSettings& r) {
    app.add_option("--seed", r.seed, "random seed of the paths and the light sets")
        ->capture_default_str();
    app.add_option("--width", r.width, "image width, pixels")->capture_default_str();
    app.add_option("--height", r.height, "image height, pixels")->capture_default_str();
    app.add_option("--max-depth", r.max_depth,
                   "most bounces of a path: 0 shows the emitters only, 1 is direct lighting")
        ->capture_default_str();
    app.add_option("--threads", r.threads, "worker threads; 0: all hardware threads")
        ->capture_default_str();
  }

  /// Before BudgetOptions, which lifts the cap of --spp under a time budget.
  UsageError finish(tracer::RenderSettings& r) const {
    if (r.width == 0 || r.height == 0 || r.spp == 0) return "--width, --height and --spp must be at least 1";
    return std::nullopt;
  }
};

/// --backend, --refine, --device: the light sampler.
struct LightSamplerOptions {
  std::string backend = "auto";

  void add(CLI::App& app, lightsampler::SamplerOptions& sampler) {
    app.add_option("--backend", backend,
                   "light sampler (the point lights of trs and ris, every strategy's light "
                   "integrals); auto: Vulkan on a GPU, else the native CPU backend")
        ->check(CLI::IsMember(names(lightsampler::kBackendNames)))
        ->capture_default_str();
    // Refined by the cost model by default: the same lights for less of the sampler's work, and
    // no split its frames cannot pay for (docs/benchmarks.md).
    sampler.refinement = lightsampler::auto_refinement(0.0);  // the lights a frame draws are filled in by the renderer
    add_refine_option(app, sampler.refinement);
    app.add_option("--device", sampler.vulkan.device,
                   "Vulkan device by index or name (also LIGHTSAMPLER_VULKAN_DEVICE)");
  }

  void finish(lightsampler::SamplerOptions& sampler) const { sampler.backend = named(lightsampler::kBackendNames, backend); }
};

/// --frames and --fps, and how a sequence runs: --resume, --save-partial, --plan, --submit, --chunk.
struct AnimationOptions {
  std::string frames;
  std::int64_t chunk = 1;
  bool plan = false;
  std::string submit, sbatch;
  RenderOptions::Submission submission;

  void add(CLI::App& app, RenderOptions& options) {
    app.add_option("--frames", frames,
                   "render animation frames A to B (A:B, inclusive), an image each: --out and the other "
                   "outputs are then frame patterns (out.%04d.exr), --spp and --time apply to each frame");
    app.add_option("--fps", options.render.fps, "animation frames per second (frame f is f / fps seconds in)")
        ->check(CLI::PositiveNumber & kFiniteNonNegative)
        ->capture_default_str();
    app.add_flag("--resume", options.resume, "--frames: skip the frames whose outputs are all there");
    app.add_flag("--save-partial", options.save_partial,
                 "--frames: when stopped (Ctrl-C, SIGTERM, SIGHUP), write the passes done of the frame under way, "
                 "each output with .partial before its extension (out.0007.partial.exr); --resume renders that "
                 "frame again");
    app.add_flag("--plan", plan,
                 "--frames: print one trs-render command per chunk of frames (for GNU parallel or a Slurm "
                 "array) and render nothing");
    app.add_option("--submit", submit,
                   "--frames: submit the frames to a scheduler as one job array, a task per chunk, each "
                   "the command --plan prints with --resume; print the job id and return (docs/cluster.md)")
        ->check(CLI::IsMember({"slurm"}));
    app.add_option("--sbatch", sbatch,
                   "--submit: options for sbatch ('--partition=gpu --gres=gpu:1'), split into words by the "
                   "shell's quotes and backslashes; nothing is expanded or run, so $, ` and unquoted ; | & < > ( ) "
                   "are refused");
    app.add_flag("--wait", submission.wait,
                 "--submit: wait for the job array to end; fail, naming the frames, if any task failed");
    app.add_option("--chunk", chunk, "--plan and --submit: frames per command")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
  }

  UsageError finish(const CLI::App& app, RenderOptions& options) const {
    if (!frames.empty()) {
      options.frames = parse_frame_range(frames);
      if (!options.frames) return "--frames takes A:B, frames 0 <= A <= B (" + frames + ")";
    }
    if (plan) options.plan_chunk = chunk;
    if (!submit.empty()) {
      options.submit = submission;
      options.submit->chunk = chunk;
      try {
        options.submit->sbatch = split_shell_words(sbatch);
      } catch (const ShellWordsError& e) {
        return std::string("--sbatch: ") + e.what();
      }
    }
    if (plan && options.submit) return "--plan and --submit are two ways to run the frames: give one";
    if (UsageError error = misplaced(app, {"--sbatch", "--wait"}, options.submit.has_value(), "belongs to --submit"))
      return error;
    if (UsageError error = misplaced(app, {"--resume", "--save-partial", "--plan", "--submit", "--chunk"},
                                     options.frames.has_value(), "belongs to --frames"))
      return error;
    return plan || options.submit ? control_character_in_values(app) : std::nullopt;
  }

  /// --plan and --submit write the command line's words into commands that sh reads a line at a
  /// time: the first option whose value holds a control character, named with it. (--sbatch's
  /// words go to sbatch alone, split by rules of their own.)
  static UsageError control_character_in_values(const CLI::App& app) {
    for (const CLI::Option* option : app.get_options()) {
      if (option->get_name() == "--sbatch") continue;
      for (const std::string& value : option->results())
        if (const std::optional<std::string> control = control_character(value))
          return option->get_name() + ": " + printable(value) + " holds " + *control +
                 ", which a command for a shell or a scheduler cannot hold safely";
    }
    return std::nullopt;
  }
};

/// --stats, --preview, --variance, --emitter-mask: what is written besides --out.
struct OutputOptions {
  std::string stats, preview, variance, emitter_mask;

  void add(CLI::App& app) {
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
  }

  /// After AnimationOptions: a sequence's outputs are frame patterns.
  UsageError finish(RenderOptions& options) const {
    if (!stats.empty()) options.stats = stats;
    if (!preview.empty()) options.preview = preview;
    if (!variance.empty()) options.variance = variance;
    if (!emitter_mask.empty()) options.emitter_mask = emitter_mask;
    if (!options.frames) return std::nullopt;
    for (const std::filesystem::path& path : outputs(options))
      if (!FramePattern::valid(path.filename().string()))
        return "with --frames, each output names its frame: " + path.string() +
               " needs one integer conversion in its file name (out.%04d.exr)";
    return std::nullopt;
  }
};

/// --exposure and the preview's display transform: --ocio-config, --ocio-colorspace, --display,
/// --view.
struct PreviewOptions {
  std::string ocio_config;

  void add(CLI::App& app, RenderOptions& options) {
    app.add_option("--exposure", options.exposure, "preview exposure, stops, applied before the display transform")
        ->capture_default_str();
    DisplayTransform& display = options.preview_display;
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
  }

  UsageError finish(const CLI::App& app, RenderOptions& options) const {
    DisplayTransform& display = options.preview_display;
    // As OpenColorIO reads $OCIO, an empty value is none.
    display.config = app.count("--ocio-config") > 0 ? ocio_config : environment_variable("OCIO");
    return misplaced(app, {"--ocio-colorspace", "--display", "--view"}, !display.config.empty(),
                     "needs an OpenColorIO config: --ocio-config or $OCIO");
  }
};

/// Runs the parser over the command line: none once it has filled the options, else why it
/// renders nothing (--help and --version are printed here).
std::optional<NoRender> run_parser(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    app.exit(e);  // prints the help
    return NoRender{};
  } catch (const CLI::CallForVersion& e) {
    std::cout << e.what() << "\n";
    return NoRender{};
  } catch (const CLI::Success&) {
    return NoRender{};
  } catch (const CLI::ConfigError& e) {
    // CLI11 names the key, not the file it came from.
    return NoRender{app.get_option("--settings")->as<std::string>() + ": " + e.what() +
                    " (settings are the long option names)"};
  } catch (const CLI::ParseError& e) {
    return NoRender{e.what(), true};
  }
  return std::nullopt;
}

std::variant<RenderOptions, NoRender> parse(int argc, char** argv, bool out_required) {
  try {
    for (const std::string& plugin : plugins_named(argc, argv)) tracer::load_strategy_plugin(plugin);
  } catch (const FileError& error) {
    return NoRender{error.what()};
  }
  CLI::App app(
      "Renders a glTF 2.0 scene lit by its emissive textures with a path tracer whose next-event "
      "estimation samples lights uniformly by area, by triangle power, by a light tree that weighs "
      "them for each shading point (tree), or from millions of point lights drawn every frame by "
      "Triangle Rejection Sampling, used as they are (trs) or resampled per shading point by their "
      "unshadowed contribution (ris).",
      "trs-render");
  RenderOptions options;
  add_program_options(app, options, out_required);
  BudgetOptions budget;
  budget.add(app, options.render);
  LightOptions lights;
  lights.add(app, options);
  ImageOptions image;
  image.add(app, options.render);
  LightSamplerOptions sampler;
  sampler.add(app, options.render.sampler);
  AnimationOptions animation;
  animation.add(app, options);
  OutputOptions outputs;
  outputs.add(app);
  PreviewOptions preview;
  preview.add(app, options);
  bool quiet = false;
  app.add_flag("--quiet", quiet, "no progress bar");

  if (std::optional<NoRender> stop = run_parser(app, argc, argv)) return *stop;
  options.arguments.assign(argv, argv + argc);
  options.progress = !quiet;
  sampler.finish(options.render.sampler);
  if (UsageError error = image.finish(options.render)) return NoRender{*error};
  budget.finish(app, options);
  if (UsageError error = lights.finish(app, options)) return NoRender{*error};
  if (UsageError error = animation.finish(app, options)) return NoRender{*error};
  if (UsageError error = preview.finish(app, options)) return NoRender{*error};
  if (UsageError error = outputs.finish(options)) return NoRender{*error};
  return options;
}

}  // namespace

std::optional<FrameRange> parse_frame_range(const std::string& text) {
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

std::string to_string(const FrameRange& range) { return std::to_string(range.first) + ":" + std::to_string(range.last); }

std::variant<RenderOptions, NoRender> parse_render_arguments(const std::vector<std::string>& arguments,
                                                             bool out_required) {
  std::vector<char*> argv;
  for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  return parse(int(arguments.size()), argv.data(), out_required);
}

std::variant<RenderOptions, int> parse_render_options(int argc, char** argv) {
  std::variant<RenderOptions, NoRender> parsed = parse(argc, argv, true);
  if (RenderOptions* options = std::get_if<RenderOptions>(&parsed)) return std::move(*options);
  const NoRender& stop = std::get<NoRender>(parsed);
  if (!stop.error.empty()) std::cerr << "trs-render: error: " << stop.error << "\n";
  if (stop.see_help) std::cerr << "Run with --help for more information.\n";
  return stop.status();
}

std::filesystem::path output(const RenderOptions& options, const std::filesystem::path& path, std::int64_t frame) {
  if (!options.frames || path.empty()) return path;
  return path.parent_path() / FramePattern(path.filename().string()).format(frame);
}

std::filesystem::path partial_output(const std::filesystem::path& file) {
  return file.parent_path() / (file.stem().string() + ".partial" + file.extension().string());
}

std::vector<std::filesystem::path> outputs(const RenderOptions& options) {
  std::vector<std::filesystem::path> paths;
  if (!options.out.empty()) paths.push_back(options.out);
  for (const auto* path : {&options.stats, &options.preview, &options.variance, &options.emitter_mask})
    if (*path) paths.push_back(**path);
  return paths;
}

bool frame_written(const RenderOptions& options, std::int64_t frame) {
  const std::vector<std::filesystem::path> paths = outputs(options);
  return std::all_of(paths.begin(), paths.end(), [&](const std::filesystem::path& path) {
    return std::filesystem::exists(output(options, path, frame));
  });
}

}  // namespace trs
