#pragma once
// The command line of trs-sample.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <variant>

#include "scene_io/density_io.h"
#include "lightsampler/mesh.h"
#include "lightsampler/sampler.h"
#include "lightsampler/backend.h"

namespace trs {

struct Options {
  std::filesystem::path mesh;
  std::filesystem::path density;
  std::optional<double> target_count;
  std::uint64_t seed = 0;
  float density_scale = 1.0f;
  lightsampler::Method method = lightsampler::Method::trs;
  unsigned threads = 0;
  lightsampler::Backend backend = lightsampler::Backend::automatic;
  std::string device;  ///< Vulkan device by index or name; empty: the default choice
  lightsampler::Refinement refinement = lightsampler::auto_refinement(0.0);  ///< --refine, auto by default
  lightsampler::Counting counting = lightsampler::Counting::automatic;
  lightsampler::ScanOrder scan = lightsampler::ScanOrder::automatic;
  lightsampler::Overlap overlap = lightsampler::Overlap::closed_form;
  std::uint32_t exact_after = lightsampler::FrameRequest{}.exact_after;
  lightsampler::Addressing addressing = lightsampler::Addressing::wrap;
  MapEncoding map_encoding = MapEncoding::automatic;
  std::optional<std::filesystem::path> out;
  std::optional<std::filesystem::path> stats;
};

/// Exit status of a command line that is wrong (as opposed to inputs that are).
inline constexpr int kUsageError = 2;

/// Parses the command line: the options, or the status to exit with at once (0 after --help,
/// kUsageError after a usage error, its message printed).
std::variant<Options, int> parse_options(int argc, char** argv);

}  // namespace trs
