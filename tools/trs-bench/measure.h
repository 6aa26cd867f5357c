#pragma once
// Timing one benchmark case: warm-up frames, then timed frames with a new seed each, reduced to
// medians. Medians rather than means because the machines are shared: an interrupted frame is an
// outlier, not a signal.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "lightsampler/sampler.h"

namespace trs_bench {

struct MeasureSettings {
  int warmup = 1;
  int repeats = 5;
  /// Seconds a case may use: frames stop once it is spent (at least one timed frame is taken).
  double budget_s = 20;
  /// Replace the maps before every frame, as an animated texture would, so that every frame
  /// counts; otherwise only the first frame of a sampler counts (the counts are kept).
  bool recount = false;
};

struct Measurement {
  int runs = 0;                 ///< timed frames taken (fewer than asked when the budget ran out)
  double samples = 0;           ///< mean N over the timed frames
  double candidates = 0;        ///< mean candidates tried
  std::uint64_t exhausted = 0;  ///< samples that hit max_tries, over all timed frames
  std::string scan_used;
  std::vector<lightsampler::PassTime> pass_medians;  ///< in the order the passes ran
  double total_ms = 0;  ///< median of Frame::total_ms
  double wall_ms = 0;   ///< median time around generate(), as a caller sees it
  /// A method's set-up kept between frames (FRS), apart from the frames: its time and memory.
  double setup_ms = 0;
  std::uint64_t setup_bytes = 0;

  /// False for frames stopped before the realization (FrameRequest::realize off): N is known
  /// but no sample was drawn.
  bool realized() const { return candidates > 0; }
  double acceptance() const { return realized() ? samples / candidates : 0; }
  double samples_per_s() const {
    return realized() && total_ms > 0 ? samples / (total_ms * 1e-3) : 0;
  }
};

/// Runs `request` on `sampler`, writing into `frame` (reused so that buffers keep their
/// capacity). Frame k of the case gets seed first_seed + k. With settings.recount, `maps` are
/// handed to update_map before every frame.
Measurement measure(lightsampler::Sampler& sampler, lightsampler::Frame& frame,
                    lightsampler::FrameRequest request, std::uint64_t first_seed,
                    const MeasureSettings& settings, std::span<const lightsampler::DensityMapView> maps);

double median(std::vector<double> values);

}  // namespace trs_bench
