// trs-sample: draws one frame of samples on a mesh with a density map and writes them as PLY.
// Exit status: 0 success, 1 bad input or failed run, 2 bad command line.

#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>

#include "scene_io/atomic_file.h"
#include "scene_io/density_io.h"
#include "scene_io/file_error.h"
#include "scene_io/mesh_io.h"
#include "scene_io/ply.h"
#include "lightsampler/sampler.h"
#include "options.h"
#include "report.h"

namespace trs {
namespace {

constexpr int kRunFailed = 1;

/// The library's exceptions say what is wrong ("mesh: ...", "density map 0: ..."), not which
/// file it came from: name the file here.
[[noreturn]] void rethrow_naming_inputs(const std::exception& e, const Options& options) {
  const std::string what = e.what();
  if (what.rfind("mesh", 0) == 0) throw FileError(options.mesh, what);
  if (what.rfind("density map", 0) == 0) throw FileError(options.density, what);
  throw std::runtime_error(options.mesh.string() + " with " + options.density.string() + ": " +
                           what);
}

std::string gib(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f GiB", bytes / double(1ull << 30));
  return text;
}

/// The best guess of how many samples the frame wanted when memory ran out.
std::string out_of_memory_message(const Options& options, const lightsampler::Frame& frame) {
  double samples = 0;
  if (options.target_count) {
    samples = *options.target_count;
  } else if (std::isfinite(frame.expected_total)) {  // the counting pass ran before the failure
    samples = frame.expected_total;
  }
  if (!(samples > 0)) return "out of memory";
  char count[32];
  std::snprintf(count, sizeof count, "%.3g", samples);
  return std::string("out of memory: ") + count + " samples need " +
         gib(samples * sizeof(lightsampler::Sample)) + " (" +
         std::to_string(sizeof(lightsampler::Sample)) + " bytes each)";
}

double milliseconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

std::unique_ptr<lightsampler::Sampler> make_sampler(const MeshData& mesh,
                                                    const lightsampler::DensityMapView& map,
                                                    const Options& options) {
  try {
    return lightsampler::make_sampler(mesh.view(), {&map, 1},
                                      {.backend = options.backend,
                                       .cpu = {.threads = options.threads},
                                       .vulkan = {.device = options.device},
                                       .refinement = options.refinement});
  } catch (const std::invalid_argument& e) {
    rethrow_naming_inputs(e, options);
  } catch (const std::length_error& e) {
    rethrow_naming_inputs(e, options);
  }
}

void generate(lightsampler::Sampler& sampler, const Options& options, lightsampler::Frame& frame) {
  lightsampler::FrameRequest request;
  request.seed = options.seed;
  request.target_count = options.target_count;
  request.method = options.method;
  request.scan = options.scan;
  request.overlap = options.overlap;
  request.exact_after = options.exact_after;
  request.vulkan.counting = options.counting;
  try {
    sampler.generate(request, frame);
  } catch (const std::bad_alloc&) {
    throw std::runtime_error(out_of_memory_message(options, frame));
  }
}

int run(const Options& options) {
  // Outputs first: a destination that cannot be written fails before minutes of work, and
  // until commit() neither file is touched.
  std::optional<AtomicFile> ply, stats;
  if (options.out) ply.emplace(*options.out);
  if (options.stats) stats.emplace(*options.stats);

  const MeshData mesh = load_mesh(options.mesh);
  const DensityMap map = load_density_map(options.density, options.map_encoding);
  const lightsampler::DensityMapView map_view = map.view(options.addressing, options.density_scale);
  const auto construction = std::chrono::steady_clock::now();
  const std::unique_ptr<lightsampler::Sampler> sampler = make_sampler(mesh, map_view, options);
  const double construction_ms = milliseconds_since(construction);
  lightsampler::Frame frame;
  generate(*sampler, options, frame);

  std::optional<double> write_ms;
  const RunReport report{options, mesh, map, *sampler, construction_ms, frame};
  if (ply) {
    const auto start = std::chrono::steady_clock::now();
    write_ply(*ply, mesh, frame.samples.span());
    write_ms = milliseconds_since(start);
  }
  if (stats) stats->write(stats_json(report).dump(2) + "\n");
  if (ply) ply->commit();
  if (stats) stats->commit();

  print_summary(std::cout, report, write_ms);
  if (frame.exhausted > 0) {
    std::cerr << "trs-sample: warning: " << frame.exhausted
              << " samples gave up after the maximum number of tries; the set is biased\n";
  }
  return 0;
}

}  // namespace
}  // namespace trs

int main(int argc, char** argv) {
  auto parsed = trs::parse_options(argc, argv);
  if (const int* status = std::get_if<int>(&parsed)) return *status;
  const trs::Options& options = std::get<trs::Options>(parsed);
  try {
    // Loading and writing run in parallel too, on no more threads than the sampler.
    tbb::task_arena arena(options.threads ? int(options.threads) : tbb::task_arena::automatic);
    return arena.execute([&] { return trs::run(options); });
  } catch (const std::bad_alloc&) {
    std::cerr << "trs-sample: error: out of memory\n";
  } catch (const std::exception& e) {
    std::cerr << "trs-sample: error: " << e.what() << "\n";
  }
  return trs::kRunFailed;
}
