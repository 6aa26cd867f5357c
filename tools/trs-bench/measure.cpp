#include "measure.h"

#include <algorithm>
#include <chrono>

namespace trs_bench {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Per-pass times of the timed frames, by pass in first-run order.
class PassSeries {
 public:
  void add(const std::vector<lightsampler::PassTime>& passes) {
    for (const auto& pass : passes) {
      auto it = std::find_if(series_.begin(), series_.end(),
                             [&](const auto& s) { return s.first == pass.pass; });
      if (it == series_.end()) it = series_.insert(series_.end(), {pass.pass, {}});
      it->second.push_back(pass.ms);
    }
  }

  std::vector<lightsampler::PassTime> medians() const {
    std::vector<lightsampler::PassTime> result;
    for (const auto& [pass, times] : series_) result.push_back({pass, median(times)});
    return result;
  }

 private:
  std::vector<std::pair<lightsampler::Pass, std::vector<double>>> series_;
};

}  // namespace

double median(std::vector<double> values) {
  if (values.empty()) return 0;
  const auto middle = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), middle, values.end());
  if (values.size() % 2) return *middle;
  return (*middle + *std::max_element(values.begin(), middle)) / 2;
}

Measurement measure(lightsampler::Sampler& sampler, lightsampler::Frame& frame,
                    lightsampler::FrameRequest request, std::uint64_t first_seed,
                    const MeasureSettings& settings, std::span<const lightsampler::DensityMapView> maps) {
  const auto start = Clock::now();
  const auto within_budget = [&] { return seconds_since(start) < settings.budget_s; };
  Measurement m;
  const auto generate = [&] {
    if (settings.recount)
      for (std::size_t i = 0; i < maps.size(); ++i) sampler.update_map(i, maps[i]);
    sampler.generate(request, frame);
    // A method's set-up (FRS's table): the distribution pass of the frame that built it.
    if (frame.setup_bytes == 0) return;
    m.setup_bytes = frame.setup_bytes;
    for (const lightsampler::PassTime& p : frame.passes)
      if (p.pass == lightsampler::Pass::distribution) m.setup_ms = p.ms;
  };

  // Warm-up: first touch of the frame's buffers, the thread pool, the caches.
  request.seed = first_seed;
  for (int i = 0; i < settings.warmup && within_budget(); ++i, ++request.seed) generate();

  PassSeries passes;
  std::vector<double> totals, walls;
  double samples = 0, candidates = 0;
  for (; m.runs < settings.repeats && (m.runs == 0 || within_budget()); ++m.runs, ++request.seed) {
    const auto frame_start = Clock::now();
    generate();
    walls.push_back(seconds_since(frame_start) * 1e3);
    totals.push_back(frame.total_ms);
    passes.add(frame.passes);
    samples += double(frame.sample_count);
    candidates += double(frame.candidates);
    m.exhausted += frame.exhausted;
  }
  m.samples = samples / m.runs;
  m.candidates = candidates / m.runs;
  m.scan_used = lightsampler::to_string(frame.scan_used);
  m.pass_medians = passes.medians();
  m.total_ms = median(totals);
  m.wall_ms = median(walls);
  return m;
}

}  // namespace trs_bench
