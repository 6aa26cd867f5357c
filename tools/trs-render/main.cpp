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

int run(const RenderOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  // From here on, Ctrl-C stops cleanly: temporaries are removed and what is done is saved.
  std::signal(SIGINT, on_interrupt);
  check_writable(options.out);
  if (options.preview) check_writable(*options.preview);
  if (options.variance) check_writable(*options.variance);
  if (options.emitter_mask) check_writable(*options.emitter_mask);
  std::optional<AtomicFile> stats;
  if (options.stats) stats.emplace(*options.stats);

  const tracer::Scene scene = tracer::load_gltf_scene(options.scene);
  tracer::RenderSettings settings = options.render;
  if (options.time_seconds)
    settings.deadline = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                    std::chrono::duration<double>(*options.time_seconds));
  std::optional<tracer::Renderer> renderer;
  try {
    renderer.emplace(scene, settings);
  } catch (const std::invalid_argument& e) {
    throw FileError(options.scene, e.what());
  }
  ProgressBar bar(options.progress, options.time_seconds);
  const tracer::RenderResult result =
      renderer->render([&](unsigned done, unsigned total) { bar.update(done, total); }, interrupted);
  bar.finish();
  std::signal(SIGINT, SIG_DFL);
  if (result.frames == 0) {
    std::cerr << "trs-render: interrupted before the first frame; nothing written\n";
    return kInterrupted;
  }

  write_exr(options.out, result.width, result.height, result.rgb.data());
  if (options.preview)
    write_png_preview(*options.preview, result.width, result.height, result.rgb.data(),
                      options.exposure);
  if (options.variance) write_grey(*options.variance, result, result.luminance_variance);
  if (options.emitter_mask) write_grey(*options.emitter_mask, result, result.emitter_fraction);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (stats) {
    stats->write(stats_json(options, result, wall).dump(2) + "\n");
    stats->commit();
  }
  print_summary(std::cout, options, result, wall);
  if (result.invalid_paths > 0)
    std::cerr << "trs-render: warning: " << result.invalid_paths
              << " paths gave NaN or infinite radiance and count as black\n";
  for (const tracer::LightFrame& f : result.light_frames) {
    if (f.exhausted == 0) continue;
    std::cerr << "trs-render: warning: the light sampler gave up on some lights (rejection "
                 "limit); the image is biased\n";
    break;
  }
  if (result.interrupted) {
    std::cerr << "trs-render: interrupted; saved " << result.frames << " spp\n";
    return kInterrupted;
  }
  return 0;
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
