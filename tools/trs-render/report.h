#pragma once
// What trs-render tells: a progress bar while it renders, a summary at the end, a JSON file.

#include <chrono>
#include <optional>
#include <ostream>

#include <nlohmann/json.hpp>

#include "options.h"
#include "scene_io/display.h"
#include "tracer/renderer.h"

namespace trs {

/// A one-line bar redrawn in place on a terminal; nothing at all elsewhere (logs stay clean).
/// With a time budget, the bar fills with the time spent rather than the frames done.
class ProgressBar {
 public:
  explicit ProgressBar(bool enabled, std::optional<double> budget_seconds = {});
  void update(unsigned done, unsigned total);
  /// Ends the line, if one was drawn.
  void finish();

 private:
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
  std::optional<double> budget_;
};

/// Seconds from `start` to now.
double seconds_since(std::chrono::steady_clock::time_point start);

/// Mean over pixels of the per-sample luminance variance relative to the squared mean (plus
/// relMSE's guard against dark pixels, scene_io/relmse.h): the noise of one sample per pixel.
double relative_variance(const tracer::RenderResult& result);

/// One frame of a sequence: which, and what it took to change the emission to it.
struct SequenceFrame {
  std::int64_t frame = 0;
  double seconds = 0.0;  ///< into the animation
  tracer::EmissionUpdate update;
};

/// The stats JSON of a still, or of `frame` of a sequence; `preview` is the display transform of
/// the preview written, if any.
nlohmann::json stats_json(const RenderOptions& options, const tracer::RenderResult& result,
                          double wall_seconds, const std::optional<SequenceFrame>& frame = {},
                          const std::optional<DisplayEncoder>& preview = {});

/// The summary of a still, written to `image`.
void print_summary(std::ostream& out, const std::filesystem::path& image, const tracer::RenderResult& result,
                   double wall_seconds);

/// One line for a frame of a sequence.
void print_frame(std::ostream& out, const std::filesystem::path& image, const tracer::RenderResult& result,
                 const SequenceFrame& frame, double wall_seconds);

}  // namespace trs
