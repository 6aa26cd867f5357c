#include "run.h"

#include <algorithm>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "report.h"
#include "scene_io/atomic_file.h"
#include "scene_io/display.h"
#include "scene_io/file_error.h"
#include "scene_io/image_output.h"
#include "tracer/gltf_scene.h"

namespace trs {
namespace {

/// One value per pixel (a variance, a fraction) as a grey RGB image.
void write_grey(const std::filesystem::path& file, const tracer::RenderResult& result,
                const std::vector<float>& values) {
  std::vector<float> grey;
  grey.reserve(3 * values.size());
  for (const float v : values) grey.insert(grey.end(), {v, v, v});
  write_exr(file, result.width, result.height, grey.data());
}

/// Fails before the render on an output that cannot be created, rather than after it.
void check_writable(const std::filesystem::path& file) { AtomicFile probe(file); }

/// The preview's display transform, when there is a preview: set up before the render, so that a
/// config that cannot be read, or a name it lacks, fails the run before any work.
std::optional<DisplayEncoder> preview_encoder(const RenderOptions& options, const NoteHandler& note) {
  if (!options.preview) return std::nullopt;
  return display_encoder(options, note);
}

/// The file of output `path` for animation frame `frame`; under partial_output()'s name for a
/// frame cut short.
std::filesystem::path frame_file(const RenderOptions& options, const std::filesystem::path& path, std::int64_t frame,
                                 bool partial) {
  const std::filesystem::path file = output(options, path, frame);
  return partial ? partial_output(file) : file;
}

/// The outputs of one image but the stats: the EXR, then what else the options ask for (a
/// preview, encoded by `display`); `partial` for a frame cut short.
void write_outputs(const RenderOptions& options, const std::optional<DisplayEncoder>& display, std::int64_t frame,
                   const tracer::RenderResult& result, bool partial = false) {
  const auto file = [&](const std::filesystem::path& path) { return frame_file(options, path, frame, partial); };
  if (!options.out.empty()) write_exr(file(options.out), result.width, result.height, result.rgb.data());
  if (options.preview)
    write_png_preview(file(*options.preview), result.width, result.height, result.rgb.data(), options.exposure,
                      *display);
  if (options.variance) write_grey(file(*options.variance), result, result.luminance_variance);
  if (options.emitter_mask) write_grey(file(*options.emitter_mask), result, result.emitter_fraction);
}

void warn_about(const NoteHandler& note, const tracer::RenderResult& result) {
  if (result.invalid_paths > 0)
    note({RunNote::Kind::warning,
          std::to_string(result.invalid_paths) + " paths gave NaN or infinite radiance and count as black"});
  const auto exhausted = [](const tracer::LightPass& f) { return f.exhausted > 0; };
  if (std::any_of(result.light_passes.begin(), result.light_passes.end(), exhausted))
    note({RunNote::Kind::warning, "the light sampler gave up on some lights (rejection limit); the image is biased"});
}

/// A deadline `seconds` after `start`.
std::chrono::steady_clock::time_point after(std::chrono::steady_clock::time_point start, double seconds) {
  return start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds));
}

int render_still(const RenderOptions& options, std::chrono::steady_clock::time_point start, const RunHooks& hooks) {
  for (const std::filesystem::path& path : outputs(options)) check_writable(path);
  std::optional<AtomicFile> stats;
  if (options.stats) stats.emplace(*options.stats);
  const std::optional<DisplayEncoder> display = preview_encoder(options, hooks.note);

  const tracer::Scene scene = load_scene(options);
  tracer::Renderer renderer =
      make_renderer(scene, options, 0, options.time_seconds ? std::optional(after(start, *options.time_seconds)) : std::nullopt);
  ProgressBar bar(options.progress, options.time_seconds);
  const tracer::RenderResult result = renderer.render(
      [&](unsigned done, unsigned total) {
        bar.update(done, total);
        if (hooks.on_pass) hooks.on_pass();
      },
      hooks.cancel);
  bar.finish();
  if (result.passes == 0) {
    hooks.note({RunNote::Kind::interrupted, "interrupted before the first frame; nothing written"});
    return kInterrupted;
  }
  write_outputs(options, display, 0, result);
  const double wall = seconds_since(start);
  const nlohmann::json summary = stats_json(options, result, wall, {}, display);
  if (stats) {
    stats->write(summary.dump(2) + "\n");
    stats->commit();
  }
  print_summary(hooks.out, options.out, result, wall);
  warn_about(hooks.note, result);
  if (hooks.on_image) hooks.on_image(0, result, summary);
  if (result.interrupted) {
    hooks.note({RunNote::Kind::interrupted, "interrupted; saved " + std::to_string(result.passes) + " spp"});
    return kInterrupted;
  }
  return 0;
}

/// A frame of a sequence written, its stats too, and its line printed: under partial names for
/// one cut short. Returns its stats.
nlohmann::json write_frame(const RenderOptions& options, const std::optional<DisplayEncoder>& display,
                           const SequenceFrame& frame, const tracer::RenderResult& result,
                           std::chrono::steady_clock::time_point frame_start, bool partial, std::ostream& out) {
  write_outputs(options, display, frame.frame, result, partial);
  const double wall = seconds_since(frame_start);
  const nlohmann::json summary = stats_json(options, result, wall, frame, display);
  if (options.stats) {
    AtomicFile stats(frame_file(options, *options.stats, frame.frame, partial));
    stats.write(summary.dump(2) + "\n");
    stats.commit();
  }
  print_frame(out, frame_file(options, options.out, frame.frame, partial), result, frame, wall);
  return summary;
}

/// Once a frame is written whole, what an earlier run stopped in it left under partial names
/// goes. One that cannot be removed stays: it is never taken for the frame.
void remove_partial_outputs(const RenderOptions& options, std::int64_t frame) {
  for (const std::filesystem::path& path : outputs(options)) {
    std::error_code ignored;
    std::filesystem::remove(frame_file(options, path, frame, true), ignored);
  }
}

/// A sequence stopped by `cancel` in `frame`, `result` its passes done: written under partial
/// names with --save-partial (once it has a pass and an output), else dropped.
int stop_in_frame(const RenderOptions& options, const std::optional<DisplayEncoder>& display,
                  const SequenceFrame& frame, const tracer::RenderResult& result,
                  std::chrono::steady_clock::time_point frame_start, const RunHooks& hooks) {
  const std::string f = std::to_string(frame.frame);
  const std::vector<std::filesystem::path> paths = outputs(options);
  if (!options.save_partial || result.passes == 0 || paths.empty()) {
    const char* why = !options.save_partial ? " (--save-partial keeps its passes)" : " before its first pass";
    hooks.note({RunNote::Kind::interrupted, "interrupted; frame " + f + " dropped" + why +
                                                ", the frames written stay (--resume renders the rest)"});
    return kInterrupted;
  }
  write_frame(options, display, frame, result, frame_start, true, hooks.out);
  hooks.note({RunNote::Kind::interrupted,
              "interrupted; saved " + std::to_string(result.passes) + " spp of frame " + f + " as " +
                  frame_file(options, paths.front(), frame.frame, true).string() +
                  ", the frames written stay (--resume renders the rest, that frame included)"});
  return kInterrupted;
}

/// A sequence, frame by frame: each written whole as it is done. `cancel` stops the frame under
/// way (a time limit's SIGTERM leaves little time); the frames written stay.
int render_sequence(const RenderOptions& options, const RunHooks& hooks) {
  const FrameRange frames = *options.frames;
  std::vector<std::int64_t> todo;
  for (std::int64_t f = frames.first; f <= frames.last; ++f)
    if (!options.resume || !frame_written(options, f)) todo.push_back(f);
  if (todo.size() < std::size_t(frames.count()))
    hooks.out << frames.count() - std::int64_t(todo.size()) << " frames already written, " << todo.size() << " to render\n";
  if (todo.empty()) return 0;
  for (const std::int64_t f : todo)
    for (const std::filesystem::path& path : outputs(options)) check_writable(output(options, path, f));
  const std::optional<DisplayEncoder> display = preview_encoder(options, hooks.note);

  const tracer::Scene scene = load_scene(options);
  std::optional<tracer::Renderer> renderer;
  // Every frame's samples count towards the bar; with a time budget, every frame's seconds.
  const unsigned spp = options.render.spp;
  ProgressBar bar(options.progress, options.time_seconds
                                        ? std::optional<double>(*options.time_seconds * double(todo.size()))
                                        : std::nullopt);
  for (std::size_t i = 0; i < todo.size() && !hooks.cancel; ++i) {
    const auto frame_start = std::chrono::steady_clock::now();
    SequenceFrame frame{todo[i], tracer::animation_seconds(todo[i], options.render.fps), {}};
    const auto deadline = options.time_seconds ? std::optional(after(frame_start, *options.time_seconds)) : std::nullopt;
    if (renderer) {
      renderer->set_deadline(deadline);  // before the frame: a new emission chooses `auto`'s strategy again
      frame.update = renderer->set_frame(frame.frame);
    } else {
      renderer.emplace(make_renderer(scene, options, frame.frame, deadline));
    }
    const auto done_before = unsigned(i) * spp;
    const tracer::RenderResult result = renderer->render(
        [&](unsigned done, unsigned) {
          bar.update(done_before + done, unsigned(todo.size()) * spp);
          if (hooks.on_pass) hooks.on_pass();
        },
        hooks.cancel);
    bar.finish();
    if (result.interrupted) return stop_in_frame(options, display, frame, result, frame_start, hooks);
    const nlohmann::json summary = write_frame(options, display, frame, result, frame_start, false, hooks.out);
    remove_partial_outputs(options, frame.frame);
    warn_about(hooks.note, result);
    if (hooks.on_image) hooks.on_image(frame.frame, result, summary);
  }
  if (hooks.cancel) {
    hooks.note({RunNote::Kind::interrupted, "interrupted; the frames written stay (--resume renders the rest)"});
    return kInterrupted;
  }
  return 0;
}

}  // namespace

tracer::Scene load_scene(const RenderOptions& options) {
  tracer::Scene scene = tracer::load_gltf_scene(options.scene);
  if (!options.punctual) scene.lights.clear();
  if (options.diffuse_materials) {
    // No specular layer, coat or sheen: a Lambertian of the base colour beside the material's
    // transmission, whose roughness the metallic-roughness texture still gives.
    for (tracer::Material& m : scene.materials) {
      m.metallic = 0.0f;
      m.specular = {0.0f, {}, tracer::ScalarInput::Channel::alpha};
      m.clearcoat = {};
      m.sheen_color = {};
    }
  }
  return scene;
}

tracer::Renderer make_renderer(const tracer::Scene& scene, const RenderOptions& options, std::int64_t frame,
                               std::optional<std::chrono::steady_clock::time_point> deadline) {
  tracer::RenderSettings settings = options.render;
  settings.deadline = deadline;
  try {
    return tracer::Renderer(scene, settings, frame);
  } catch (const std::invalid_argument& e) {
    throw FileError(options.scene, e.what());
  }
}

std::string note_line(const RunNote& note) {
  return (note.kind == RunNote::Kind::warning ? "trs-render: warning: " : "trs-render: ") + note.text;
}

DisplayEncoder display_encoder(const RenderOptions& options, const NoteHandler& note) {
  DisplayEncoder display(options.preview_display);
  if (!display.warning().empty())
    note({RunNote::Kind::warning, display.warning() + " (--ocio-colorspace names the renders' space)"});
  return display;
}

int render(const RenderOptions& options, std::chrono::steady_clock::time_point start, const RunHooks& hooks) {
  return options.frames ? render_sequence(options, hooks) : render_still(options, start, hooks);
}

}  // namespace trs
