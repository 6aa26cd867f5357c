#pragma once
// A trs-render run as a function: a still or a sequence rendered and written as the options ask,
// for the command line and for Python (python/trs_render_module.cpp).

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <ostream>
#include <string>

#include <nlohmann/json.hpp>

#include "options.h"
#include "scene_io/display.h"
#include "tracer/renderer.h"

namespace trs {

/// Exit status of a run that failed, and of one stopped by `cancel` (128 + SIGINT, as shells
/// report Ctrl-C; trs-render exits with 128 + whichever signal stopped it).
inline constexpr int kRunFailed = 1;
inline constexpr int kInterrupted = 130;

/// What a run tells besides its summaries (trs-render prints it on standard error).
struct RunNote {
  enum class Kind {
    warning,      ///< about the image or the settings; the run goes on
    interrupted,  ///< what a run that `cancel` stopped has saved
  };
  Kind kind;
  std::string text;  ///< one sentence
};

/// A note as trs-render prints it, without the newline: "trs-render: warning: TEXT" or
/// "trs-render: TEXT".
std::string note_line(const RunNote& note);

/// Takes each note as it comes.
using NoteHandler = std::function<void(const RunNote&)>;

struct RunHooks {
  /// Once true, the pass under way is dropped: a still keeps the passes done; a sequence keeps
  /// the frames done and stops, the frame under way written under partial names with
  /// --save-partial, else dropped.
  const std::atomic<bool>& cancel;
  /// Summaries (trs-render's standard output).
  std::ostream& out;
  /// Warnings, and what an interrupted run saved: trs-render prints them, Python warns with them.
  NoteHandler note;
  /// Each image once it is done and written: its animation frame (0 for a still), the result
  /// and the stats JSON that --stats writes.
  std::function<void(std::int64_t, const tracer::RenderResult&, const nlohmann::json&)> on_image = {};
  /// After every pass (sample per pixel) rendered.
  std::function<void()> on_pass = {};
};

/// The preview's display transform that `options` ask for, a warning about it to `note`. Throws
/// FileError naming the config (scene_io/display.h).
DisplayEncoder display_encoder(const RenderOptions& options, const NoteHandler& note);

/// The scene the options name, its punctual lights left out with --no-punctual, its materials
/// made Lambertian with --diffuse-materials (their transmission kept). Throws FileError naming the file.
tracer::Scene load_scene(const RenderOptions& options);

/// The renderer of `scene` with the options' settings at animation frame `frame`, to `deadline`
/// where given (`auto`'s pilot weighs its rounds against the time left); a scene that cannot be
/// rendered so (its lights emit nothing, say) is a FileError naming options.scene.
tracer::Renderer make_renderer(const tracer::Scene& scene, const RenderOptions& options, std::int64_t frame,
                               std::optional<std::chrono::steady_clock::time_point> deadline = std::nullopt);

/// Renders what `options` ask (a still, or the frames of options.frames) from `start`, the
/// instant a time budget counts from, and writes each output that is set. Returns 0, or
/// kInterrupted when `cancel` stopped it. Throws FileError on bad input or an output that cannot
/// be written (before rendering, where it can tell).
int render(const RenderOptions& options, std::chrono::steady_clock::time_point start, const RunHooks& hooks);

}  // namespace trs
