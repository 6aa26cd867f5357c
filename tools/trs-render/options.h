#pragma once
// The command line of trs-render.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "scene_io/display.h"
#include "tracer/renderer.h"

namespace trs {

/// Animation frames first to last, inclusive.
struct FrameRange {
  std::int64_t first = 0;
  std::int64_t last = 0;
  std::int64_t count() const { return last - first + 1; }
};

/// --frames A:B: frames A to B, 0 <= A <= B, at most 12 digits each; none for any other text.
std::optional<FrameRange> parse_frame_range(const std::string& text);
/// The range as --frames takes it: A:B.
std::string to_string(const FrameRange& range);

struct RenderOptions {
  std::filesystem::path scene;
  /// With `frames`, every output path is a frame pattern (scene_io/frame_pattern.h) that output()
  /// formats.
  std::filesystem::path out;
  std::optional<std::filesystem::path> stats;
  std::optional<std::filesystem::path> preview;
  std::optional<std::filesystem::path> variance;
  std::optional<std::filesystem::path> emitter_mask;
  /// Render until this much wall time has passed since the start, set-up included.
  std::optional<double> time_seconds;
  float exposure = 0.0f;
  /// The preview's display transform: --ocio-config, else $OCIO (none: the sRGB curve).
  DisplayTransform preview_display;
  bool progress = true;  ///< a progress bar when standard error is a terminal
  bool punctual = true;  ///< render the scene's punctual lights (--no-punctual: its emission alone)
  /// --diffuse-materials: every surface a Lambertian of its base colour, its emission kept.
  bool diffuse_materials = false;
  tracer::RenderSettings render;
  /// A sequence: one image per animation frame (each with its own seeds; --spp and --time each).
  std::optional<FrameRange> frames;
  bool resume = false;  ///< skip the frames whose outputs are all written
  /// --save-partial: a sequence stopped by `cancel` writes the frame under way as it is, each
  /// output under partial_output()'s name.
  bool save_partial = false;
  /// --plan: print a command per chunk of this many frames instead of rendering.
  std::optional<std::int64_t> plan_chunk;
  /// --submit slurm: hand the frames to Slurm as one job array instead of rendering.
  struct Submission {
    std::int64_t chunk = 1;  ///< frames per array task
    std::vector<std::string> sbatch;  ///< --sbatch: sbatch's own options, split by split_shell_words()
    bool wait = false;       ///< --wait: block until the array ends
  };
  std::optional<Submission> submit;
  std::vector<std::string> arguments;  ///< the command line, for --plan and --submit
};

/// An output's path for animation frame `frame`: the pattern formatted with a sequence, the path
/// itself for a still.
std::filesystem::path output(const RenderOptions& options, const std::filesystem::path& path,
                             std::int64_t frame);

/// Where a sequence stopped by `cancel` writes `file` (an output() of the frame under way) with
/// --save-partial: ".partial" before its extension (f.0007.exr: f.0007.partial.exr), a name that
/// --resume does not take for the frame's.
std::filesystem::path partial_output(const std::filesystem::path& file);

/// Every output path that options ask for, `out` first (when set: Python's render() may write none).
std::vector<std::filesystem::path> outputs(const RenderOptions& options);

/// Whether every output of animation frame `frame` is there under its own name: a frame --resume
/// skips (partial outputs do not count).
bool frame_written(const RenderOptions& options, std::int64_t frame);

/// Exit status of a command line that is wrong (as opposed to inputs that are).
inline constexpr int kUsageError = 2;

/// Why a command line renders nothing: --help or --version, printed to standard output, or a
/// usage error.
struct NoRender {
  std::string error;  ///< the usage error, as trs-render prints it after "trs-render: error: "; empty for none
  bool see_help = false;  ///< trs-render follows the error with "Run with --help for more information."

  /// The status trs-render exits with: 0 after --help or --version, else kUsageError.
  int status() const { return error.empty() ? 0 : kUsageError; }
};

/// The options of `arguments` (the program's name first), or why they render nothing; without
/// `out_required`, --out may be left out (Python's render() returns the image).
std::variant<RenderOptions, NoRender> parse_render_arguments(const std::vector<std::string>& arguments,
                                                             bool out_required);

/// trs-render's command line: the options, or the status to exit with at once, a usage error
/// printed to standard error.
std::variant<RenderOptions, int> parse_render_options(int argc, char** argv);

}  // namespace trs
