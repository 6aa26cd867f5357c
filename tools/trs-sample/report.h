#pragma once
// What trs-sample tells about a run: a JSON summary for scripts, a short text for people.

#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>

#include "scene_io/density_io.h"
#include "scene_io/mesh_io.h"
#include "lightsampler/sampler.h"
#include "options.h"

namespace trs {

struct RunReport {
  const Options& options;
  const MeshData& mesh;
  const DensityMap& map;
  const lightsampler::Sampler& sampler;
  double construction_ms;  ///< building the sampler, its subdivision (sampler.setup()) included
  const lightsampler::Frame& frame;
};

/// The --stats document: inputs, settings, counts, and milliseconds per pass.
nlohmann::ordered_json stats_json(const RunReport& run);

/// A few lines for the terminal; `write_ms` is the time spent writing --out, if it was given.
void print_summary(std::ostream& out, const RunReport& run, std::optional<double> write_ms);

}  // namespace trs
