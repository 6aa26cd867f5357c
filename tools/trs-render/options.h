#pragma once
// The command line of trs-render.

#include <filesystem>
#include <optional>
#include <variant>

#include "tracer/renderer.h"

namespace trs {

struct RenderOptions {
  std::filesystem::path scene;
  std::filesystem::path out;
  std::optional<std::filesystem::path> stats;
  std::optional<std::filesystem::path> preview;
  std::optional<std::filesystem::path> variance;
  std::optional<std::filesystem::path> emitter_mask;
  /// Render until this much wall time has passed since the start, set-up included.
  std::optional<double> time_seconds;
  float exposure = 0.0f;
  bool progress = true;  ///< a progress bar when standard error is a terminal
  tracer::RenderSettings render;
};

/// Exit status of a command line that is wrong (as opposed to inputs that are).
inline constexpr int kUsageError = 2;

/// The options, or the status to exit with at once (0 after --help or --version, kUsageError after a usage
/// error, its message printed).
std::variant<RenderOptions, int> parse_render_options(int argc, char** argv);

}  // namespace trs
