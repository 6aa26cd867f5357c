// trs-render: renders a glTF scene lit by emissive textures and writes a linear EXR.
// Exit status: 0 success, 1 bad input or failed run, 2 bad command line, 130 interrupted by
// Ctrl-C (the image of the frames done is saved).

#include <csignal>

#include <atomic>
#include <chrono>
#include <iostream>
#include <new>
#include <optional>
#include <stdexcept>
#include <vector>

#include "scene_io/atomic_file.h"
#include "scene_io/file_error.h"
#include "scene_io/image_output.h"
#include "options.h"
#include "report.h"
#include "tracer/gltf_scene.h"
#include "tracer/renderer.h"

namespace trs {
namespace {

constexpr int kRunFailed = 1;
constexpr int kInterrupted = 130;  // 128 + SIGINT, as shells report it

std::atomic<bool> interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");

/// First Ctrl-C: finish the frames done and save them. A second one: the default action.
extern "C" void on_interrupt(int) {
  interrupted = true;
  std::signal(SIGINT, SIG_DFL);
}

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

/// The outputs of one image: the EXR, then what else the options ask for.
void write_outputs(const RenderOptions& options, std::int64_t frame, const tracer::RenderResult& result) {
  write_exr(output(options, options.out, frame), result.width, result.height, result.rgb.data());
  if (options.preview)
    write_png_preview(output(options, *options.preview, frame), result.width, result.height, result.rgb.data(),
                      options.exposure);
  if (options.variance) write_grey(output(options, *options.variance, frame), result, result.luminance_variance);
  if (options.emitter_mask) write_grey(output(options, *options.emitter_mask, frame), result, result.emitter_fraction);
}

void warn_about(const tracer::RenderResult& result) {
  if (result.invalid_paths > 0)
    std::cerr << "trs-render: warning: " << result.invalid_paths
              << " paths gave NaN or infinite radiance and count as black\n";
  for (const tracer::LightFrame& f : result.light_frames) {
    if (f.exhausted == 0) continue;
    std::cerr << "trs-render: warning: the light sampler gave up on some lights (rejection "
                 "limit); the image is biased\n";
    break;
  }
}

/// A deadline `seconds` after `start`.
std::chrono::steady_clock::time_point after(std::chrono::steady_clock::time_point start, double seconds) {
  return start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds));
}

tracer::Renderer make_renderer(const tracer::Scene& scene, const RenderOptions& options, std::int64_t frame) {
  try {
    return tracer::Renderer(scene, options.render, frame);
  } catch (const std::invalid_argument& e) {
    throw FileError(options.scene, e.what());
  }
}

int render_still(const RenderOptions& options, std::chrono::steady_clock::time_point start) {
  check_writable(options.out);
  for (const std::filesystem::path& path : outputs(options)) check_writable(path);
  std::optional<AtomicFile> stats;
  if (options.stats) stats.emplace(*options.stats);

  const tracer::Scene scene = tracer::load_gltf_scene(options.scene);
  tracer::Renderer renderer = make_renderer(scene, options, 0);
  if (options.time_seconds) renderer.set_deadline(after(start, *options.time_seconds));
  ProgressBar bar(options.progress, options.time_seconds);
  const tracer::RenderResult result =
      renderer.render([&](unsigned done, unsigned total) { bar.update(done, total); }, interrupted);
  bar.finish();
  std::signal(SIGINT, SIG_DFL);
  if (result.frames == 0) {
    std::cerr << "trs-render: interrupted before the first frame; nothing written\n";
    return kInterrupted;
  }
  write_outputs(options, 0, result);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (stats) {
    stats->write(stats_json(options, result, wall).dump(2) + "\n");
    stats->commit();
  }
  print_summary(std::cout, options.out, result, wall);
  warn_about(result);
  if (result.interrupted) {
    std::cerr << "trs-render: interrupted; saved " << result.frames << " spp\n";
    return kInterrupted;
  }
  return 0;
}

bool written(const RenderOptions& options, std::int64_t frame) {
  const auto paths = outputs(options);
  return std::all_of(paths.begin(), paths.end(),
                     [&](const std::filesystem::path& path) { return std::filesystem::exists(output(options, path, frame)); });
}

/// A sequence, frame by frame: each written whole as it is done. Ctrl-C finishes the frame under
/// way and stops; the frames written stay.
int render_sequence(const RenderOptions& options) {
  const FrameRange frames = *options.frames;
  std::vector<std::int64_t> todo;
  for (std::int64_t f = frames.first; f <= frames.last; ++f)
    if (!options.resume || !written(options, f)) todo.push_back(f);
  if (todo.size() < std::size_t(frames.count()))
    std::cout << frames.count() - std::int64_t(todo.size()) << " frames already written, " << todo.size() << " to render\n";
  if (todo.empty()) return 0;
  for (const std::int64_t f : todo)
    for (const std::filesystem::path& path : outputs(options)) check_writable(output(options, path, f));

  const tracer::Scene scene = tracer::load_gltf_scene(options.scene);
  std::optional<tracer::Renderer> renderer;
  // Every frame's samples count towards the bar; with a time budget, every frame's seconds.
  const unsigned spp = options.render.spp;
  ProgressBar bar(options.progress, options.time_seconds
                                        ? std::optional<double>(*options.time_seconds * double(todo.size()))
                                        : std::nullopt);
  const std::atomic<bool> never{false};  // the frame under way always finishes
  for (std::size_t i = 0; i < todo.size() && !interrupted; ++i) {
    const auto frame_start = std::chrono::steady_clock::now();
    SequenceFrame frame{todo[i], double(todo[i]) / options.render.fps, {}};
    if (renderer)
      frame.update = renderer->set_frame(frame.frame);
    else
      renderer.emplace(make_renderer(scene, options, frame.frame));
    renderer->set_deadline(options.time_seconds ? std::optional(after(frame_start, *options.time_seconds)) : std::nullopt);
    const auto done_before = unsigned(i) * spp;
    const tracer::RenderResult result = renderer->render(
        [&](unsigned done, unsigned) { bar.update(done_before + done, unsigned(todo.size()) * spp); }, never);
    write_outputs(options, frame.frame, result);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - frame_start).count();
    if (options.stats) {
      AtomicFile stats(output(options, *options.stats, frame.frame));
      stats.write(stats_json(options, result, wall, frame).dump(2) + "\n");
      stats.commit();
    }
    bar.finish();
    print_frame(std::cout, output(options, options.out, frame.frame), result, frame, wall);
    warn_about(result);
  }
  std::signal(SIGINT, SIG_DFL);
  if (interrupted) {
    std::cerr << "trs-render: interrupted; the frames written stay (--resume renders the rest)\n";
    return kInterrupted;
  }
  return 0;
}

/// A shell word: as it is when it is safe, in single quotes otherwise.
std::string quoted(const std::string& word) {
  if (!word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.,/:=%+@") ==
                           std::string::npos)
    return word;
  std::string out = "'";
  for (const char c : word) {
    if (c == '\'')
      out.append("'\\''");
    else
      out.push_back(c);
  }
  out.push_back('\'');
  return out;
}

/// --plan: the command line once per chunk of frames, with that chunk's --frames and without
/// --plan and --chunk.
int print_plan(const RenderOptions& options) {
  std::vector<std::string> kept;
  for (std::size_t i = 1; i < options.arguments.size(); ++i) {
    const std::string& a = options.arguments[i];
    if (a == "--plan" || a.starts_with("--chunk=") || a.starts_with("--frames=")) continue;
    if (a == "--chunk" || a == "--frames") {
      ++i;  // and its value
      continue;
    }
    kept.push_back(a);
  }
  const FrameRange frames = *options.frames;
  for (std::int64_t first = frames.first; first <= frames.last; first += *options.plan_chunk) {
    const std::int64_t last = std::min(frames.last, first + *options.plan_chunk - 1);
    std::cout << quoted(options.arguments[0]);
    for (const std::string& a : kept) std::cout << ' ' << quoted(a);
    std::cout << " --frames " << first << ':' << last << '\n';
  }
  return 0;
}

int run(const RenderOptions& options) {
  if (options.plan_chunk) return print_plan(options);
  const auto start = std::chrono::steady_clock::now();
  // From here on, Ctrl-C stops cleanly: temporaries are removed and what is done is saved.
  std::signal(SIGINT, on_interrupt);
  return options.frames ? render_sequence(options) : render_still(options, start);
}

}  // namespace
}  // namespace trs

int main(int argc, char** argv) {
  auto parsed = trs::parse_render_options(argc, argv);
  if (const int* status = std::get_if<int>(&parsed)) return *status;
  try {
    return trs::run(std::get<trs::RenderOptions>(parsed));
  } catch (const std::bad_alloc&) {
    std::cerr << "trs-render: error: out of memory\n";
  } catch (const std::exception& e) {
    std::cerr << "trs-render: error: " << e.what() << "\n";
  }
  return trs::kRunFailed;
}
