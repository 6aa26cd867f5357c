#pragma once
// What trs-render tells: a progress bar while it renders, a summary at the end, a JSON file.

#include <chrono>
#include <optional>
#include <ostream>

#include <nlohmann/json.hpp>

#include "options.h"
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

/// Mean over pixels of the per-sample luminance variance relative to the squared mean (plus
/// 0.01, relMSE's usual guard against dark pixels): the noise of one sample per pixel.
double relative_variance(const tracer::RenderResult& result);

nlohmann::json stats_json(const RenderOptions& options, const tracer::RenderResult& result,
                          double wall_seconds);

void print_summary(std::ostream& out, const RenderOptions& options,
                   const tracer::RenderResult& result, double wall_seconds);

}  // namespace trs
