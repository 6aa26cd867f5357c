// The CPU backend: the passes of cpu/passes.h strung together, timed, on a TBB arena of the
// requested size.

#include <algorithm>
#include <chrono>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <tbb/task_arena.h>

#include "core/counting.h"
#include "core/frame_policy.h"
#include "core/host_scene.h"
#include "core/validate.h"
#include "cpu/frs.h"
#include "cpu/passes.h"

namespace lightsampler {

std::string cpu_device() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
    }
  return "unknown CPU";
}

namespace {

// Elements per packed atomic in the unordered scan (the size of a GPU subgroup reduction).
constexpr std::size_t kScanBlock = 256;

class Stopwatch {
 public:
  double lap_ms() {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - last_).count();
    last_ = now;
    return ms;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

class CpuSampler final : public Sampler {
 public:
  CpuSampler(const MeshView& mesh, std::span<const DensityMapView> maps, const CpuOptions& options)
      : arena_(int(worker_threads(options))),
        device_(cpu_device()),
        scene_(arena_.execute([&] { return core::HostScene(mesh, maps); })),
        stale_(maps.size(), 0) {}

  Backend backend() const override { return Backend::cpu; }
  std::string device() const override { return device_; }
  std::uint64_t triangle_count() const override { return scene_.triangles().size(); }
  std::size_t map_count() const override { return scene_.maps().size(); }

  void update_map(std::size_t index, const DensityMapView& map) override {
    arena_.execute([&] { scene_.update_map(index, map); });
    stale_[index] = 1;
    frs_.reset();
  }

  MapQueries maps() const override { return MapQueries(scene_); }

  void use_counts(std::span<const double> expected_counts, std::span<const float> max_density) override {
    if (expected_counts.size() != triangle_count() || max_density.size() != triangle_count())
      throw std::invalid_argument("use_counts: " + std::to_string(expected_counts.size()) + " counts and " +
                                  std::to_string(max_density.size()) + " bounds for " +
                                  std::to_string(triangle_count()) + " triangles");
    expected_counts_.resize(expected_counts.size());
    max_density_.resize(max_density.size());
    std::copy(expected_counts.begin(), expected_counts.end(), expected_counts_.span().begin());
    std::copy(max_density.begin(), max_density.end(), max_density_.span().begin());
    expected_total_ = core::sum(expected_counts_.span());
    counted_ = CountingRule{false, Overlap::closed_form};
    std::fill(stale_.begin(), stale_.end(), 0);
  }

  void generate(const FrameRequest& request, Frame& frame) override {
    if (request.scan == ScanOrder::lookback)
      throw std::invalid_argument("the lookback scan runs on the Vulkan backend only");
    core::begin_frame(request, frame);
    Stopwatch total, pass;
    arena_.execute([&] {
      if (request.method == Method::rejection)
        generate_rejection(request, frame, pass);
      else if (request.method == Method::frs)
        generate_frs(request, frame, pass);
      else
        generate_stratified(request, frame, pass);
    });
    frame.total_ms = total.lap_ms();
  }

 private:
  /// How the counts in hand were made: naive stratification's clipping (every triangle at once),
  /// or TRS's counting with one overlap formula.
  struct CountingRule {
    bool naive;
    Overlap overlap;
    bool operator==(const CountingRule&) const = default;
  };

  /// N-bar_T and D_T^max change only through update_map: a frame recounts the triangles of the
  /// maps replaced since the last count, and copies the rest. A frame asking for another rule
  /// than the counts in hand were made by counts anew.
  void counting_pass(Frame& frame, Stopwatch& pass, CountingRule rule) {
    const bool stale = std::find(stale_.begin(), stale_.end(), 1) != stale_.end();
    const bool same_rule = counted_ == rule;
    const bool recount = !same_rule || stale;
    if (recount) {
      if (rule.naive)
        expected_total_ = cpu::naive_count(scene_.triangles(), scene_.texel_triangles(), scene_.maps(),
                                           expected_counts_, max_density_);
      else if (same_rule)
        expected_total_ = core::recount(scene_.triangles(), scene_.texel_triangles(), scene_.maps(), stale_,
                                        expected_counts_, max_density_, rule.overlap);
      else
        expected_total_ = core::count(scene_.triangles(), scene_.texel_triangles(), scene_.maps(),
                                      expected_counts_, max_density_, rule.overlap);
      counted_ = rule;
      std::fill(stale_.begin(), stale_.end(), 0);
    }
    core::validate_expected_total(expected_total_);
    copy(expected_counts_, frame.expected_counts);
    copy(max_density_, frame.max_density);
    frame.expected_total = expected_total_;
    frame.counting_used = recount ? std::optional(Counting::cpu) : std::nullopt;
    frame.passes.push_back({Pass::counting, pass.lap_ms()});
  }

  template <class T>
  static void copy(const Buffer<T>& from, Buffer<T>& to) {
    to.resize(from.size());
    std::copy(from.span().begin(), from.span().end(), to.span().begin());
  }

  /// Triangles as strata: TRS, or naive stratification (counting by clipping, realization
  /// texel piece by texel piece); rounding and the scan are the same.
  void generate_stratified(const FrameRequest& request, Frame& frame, Stopwatch& pass) {
    const bool naive = request.method == Method::naive;
    counting_pass(frame, pass, {naive, naive ? Overlap::closed_form : request.overlap});

    const double expected = frame.expected_total;
    const double scale = request.target_count ? (expected > 0 ? *request.target_count / expected : 0) : 1;
    frame.sample_count = cpu::round_counts(frame.expected_counts.span(), scale,
                                           stream_key(request.seed, Stream::rounding), frame.counts);
    frame.passes.push_back({Pass::rounding, pass.lap_ms()});

    // Automatic: ordered, which is faster on the CPU than contending for one atomic.
    frame.scan_used = core::choose_scan(request.scan, ScanOrder::ordered, frame.counts.size(), frame.sample_count);
    if (frame.scan_used == ScanOrder::unordered)
      cpu::unordered_scan(frame.counts.span(), kScanBlock, frame.cdf, frame.inverse_permutation);
    else
      cpu::ordered_scan(frame.counts.span(), frame.cdf, frame.inverse_permutation);
    frame.passes.push_back({Pass::scan, pass.lap_ms()});

    if (!request.realize) {
      frame.samples.resize(0);
      return;
    }
    const cpu::RealizationResult r =
        naive ? cpu::naive_realize(scene_.texel_triangles(), scene_.maps(), frame.cdf.span(),
                                   frame.inverse_permutation.span(), stream_key(request.seed, Stream::naive),
                                   request.max_tries, frame.samples)
              : cpu::realize(scene_.texel_triangles(), scene_.maps(), frame.max_density.span(), frame.cdf.span(),
                             frame.inverse_permutation.span(),
                             {stream_key(request.seed, Stream::realization), stream_key(request.seed, Stream::exact)},
                             {request.max_tries, request.exact_after}, frame.samples);
    frame.candidates = r.candidates;
    frame.exhausted = r.exhausted;
    frame.exact_draws = r.exact;
    frame.passes.push_back({Pass::realization, pass.lap_ms()});
  }

  /// Samplers over the whole mesh have no per-triangle counts, bounds or CDF.
  static void clear_triangle_outputs(Frame& frame) {
    for (auto* b : {&frame.counts, &frame.cdf}) b->resize(0);
    frame.inverse_permutation.resize(0);
    frame.expected_counts.resize(0);
    frame.max_density.resize(0);
  }

  void generate_rejection(const FrameRequest& request, Frame& frame, Stopwatch& pass) {
    clear_triangle_outputs(frame);
    double target;
    if (request.target_count) {
      target = *request.target_count;
    } else {
      counting_pass(frame, pass, {false, Overlap::closed_form});  // Algorithm 1 needs N: without a target it is N-bar
      target = frame.expected_total;
    }
    const float bound = cpu::rejection_distribution(scene_.triangles(), scene_.maps(), area_cdf_, area_guide_);
    frame.passes.push_back({Pass::distribution, pass.lap_ms()});

    const double total_area = area_cdf_.empty() ? 0.0 : area_cdf_[area_cdf_.size() - 1];
    frame.sample_count = core::rejection_sample_count(target, bound, total_area, request.seed);
    frame.scan_used = ScanOrder::ordered;
    if (!request.realize) {
      frame.samples.resize(0);
      return;
    }
    const cpu::RealizationResult r = cpu::rejection_sample(
        scene_.texel_triangles(), scene_.maps(), area_cdf_.span(), area_guide_, bound, frame.sample_count,
        stream_key(request.seed, Stream::rejection), request.max_tries, frame.samples);
    frame.candidates = r.candidates;
    frame.exhausted = r.exhausted;
    frame.passes.push_back({Pass::realization, pass.lap_ms()});
  }

  /// FRS: the table is built once, and again after update_map; a frame draws from it.
  void generate_frs(const FrameRequest& request, Frame& frame, Stopwatch& pass) {
    clear_triangle_outputs(frame);
    if (!frs_) {
      frs_ = core::frs_build(scene_.triangles(), scene_.texel_triangles(), scene_.maps());
      frame.passes.push_back({Pass::distribution, pass.lap_ms()});
    }
    frame.expected_total = frs_->expected_total;
    frame.setup_bytes = frs_->bytes();
    const double target = request.target_count.value_or(frs_->expected_total);
    frame.sample_count = core::rejection_sample_count(target, frs_->max_bound, frs_->total_area, request.seed);
    frame.scan_used = ScanOrder::ordered;
    if (!request.realize) {
      frame.samples.resize(0);
      return;
    }
    const cpu::RealizationResult r =
        cpu::frs_sample(*frs_, scene_.texel_triangles(), scene_.maps(), frame.sample_count,
                        stream_key(request.seed, Stream::frs), request.max_tries, frame.samples);
    frame.candidates = r.candidates;
    frame.exhausted = r.exhausted;
    frame.passes.push_back({Pass::realization, pass.lap_ms()});
  }

  tbb::task_arena arena_;
  std::string device_;
  core::HostScene scene_;
  std::optional<CountingRule> counted_;  ///< none before the first count
  std::vector<std::uint8_t> stale_;  ///< per map: replaced since the last count
  Buffer<double> expected_counts_;
  Buffer<float> max_density_;
  double expected_total_ = 0.0;
  std::optional<core::FrsTable> frs_;
  Buffer<double> area_cdf_;
  std::vector<std::uint32_t> area_guide_;
};

}  // namespace

std::unique_ptr<Sampler> make_cpu_sampler(const MeshView& mesh, std::span<const DensityMapView> maps,
                                          const CpuOptions& options) {
  return std::make_unique<CpuSampler>(mesh, maps, options);
}

}  // namespace lightsampler
