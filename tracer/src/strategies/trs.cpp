// `trs`: every pass of paths, lightsampler draws a fresh set of point lights with density proportional
// to the emitted luminance (Triangle Rejection Sampling), and a shading point connects to one
// of them, chosen uniformly.
//
// The estimator: a set of N lights drawn with intensity N_target p(x) (p = D / integral of D)
// and one of them picked uniformly gives E[N / N_target * f(x) / p(x)] = integral of f, exactly,
// N = 0 included. So the density it divides by is p(x) N_target / N, while MIS weighs with p(x),
// the density the set has in expectation.
//
// After drawing the set, a pass writes each light's record (LightPoint): position, normal,
// radiance and densities, so that a connection reads one line and no texture. The records are
// written on the CPU whatever the sampler's backend: the path tracer that reads them runs there,
// a light's 12-byte sample crosses the bus instead of its 64-byte record, and the refined
// sampler brings its lights back to the scene's triangles on the host just before.

#include <chrono>
#include <cstdlib>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include <sys/mman.h>
#include <tbb/parallel_for.h>

#include <lightsampler/random.h>

#include "strategies/strategies.h"
#include "tracer/strategy_registry.h"

namespace tracer {
namespace {

/// Memory in 2 MiB pages where the kernel has them: connections read the light records at
/// random, and with 4 KiB pages most of those reads would also miss the TLB.
template <class T>
struct HugePages {
  using value_type = T;
  static constexpr std::size_t kPage = std::size_t(2) << 20;
  HugePages() = default;
  template <class U>
  HugePages(const HugePages<U>&) {}
  T* allocate(std::size_t n) {
    const std::size_t bytes = (n * sizeof(T) + kPage - 1) / kPage * kPage;
    void* p = std::aligned_alloc(kPage, bytes);
    if (!p) throw std::bad_alloc();
    madvise(p, bytes, MADV_HUGEPAGE);  // advice only: without it, ordinary pages
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t) { std::free(p); }
  bool operator==(const HugePages&) const { return true; }
};

class TrsStrategy : public LightStrategy {
 public:
  TrsStrategy(Emitters& emitters, const StrategyOptions& options)
      : emitters_(emitters),
        sampler_(emitters.sampler()),
        target_(options.lights) {
    // Picking one light of the set takes 32 random bits.
    if (!(target_ >= 1.0 && target_ < 0x1p32))
      throw std::invalid_argument("trs takes 1 to 2^32 - 1 lights per pass");
  }

  std::string name() const override { return "trs"; }

  void begin_pass(std::uint64_t seed) override {
    lightsampler::FrameRequest request;
    request.seed = seed;
    request.target_count = target_;
    sampler_.generate(request, frame_);
    if (frame_.sample_count >= 0x1p32)
      throw std::runtime_error("the light sampler drew 2^32 lights or more in one pass");
    scale_ = frame_.sample_count > 0 ? float(target_ / double(frame_.sample_count)) : 0.0f;
    write_records();
  }

  std::optional<LightLiSample> sample(const LightRandom& random, const ShadingPoint& at) const override {
    if (records_.empty()) return std::nullopt;
    const LightPoint& s = records_[index(random[0])];
    // A refined sampler's light is brought back onto the texel it was drawn on; should rounding
    // still leave it on a texel without density, it carries nothing.
    if (!(s.mis_pdf > 0.0f)) return std::nullopt;
    return seen_from(emitters_, s, at);
  }

  void prefetch(const LightRandom& random) const override {
    if (!records_.empty()) __builtin_prefetch(&records_[index(random[0])]);
  }

  float pdf(std::uint32_t light, float b1, float b2, const ShadingPoint&) const override {
    return density(light, b1, b2);
  }

  LightPass last_pass() const override {
    return {frame_.total_ms, frame_.sample_count, frame_.candidates, frame_.exhausted, frame_.passes,
            records_ms_};
  }
  std::string device() const override { return std::string(lightsampler::to_string(sampler_.backend())) + ": " + sampler_.device(); }

 private:
  /// p(x) = D(x) / integral of D: the density the set has in expectation.
  float density(std::uint32_t light, float b1, float b2) const {
    const double total = emitters_.total_density();
    return total > 0.0 ? float(double(emitters_.density(light, b1, b2)) / total) : 0.0f;
  }

  /// Lemire's multiply-shift: a light of the set, uniform over n < 2^32 with a bias below
  /// n / 2^32.
  std::size_t index(std::uint32_t word) const {
    return std::size_t((std::uint64_t(word) * records_.size()) >> 32);
  }

  void write_records() {
    const auto start = std::chrono::steady_clock::now();
    const std::span<const lightsampler::Sample> samples = frame_.samples.span();
    // Room for a set somewhat larger than this one: the set's size varies from frame to frame,
    // and growing would copy records about to be overwritten and fault in fresh pages.
    if (frame_.sample_count > records_.capacity()) {
      records_ = {};
      records_.reserve(frame_.sample_count + frame_.sample_count / 8);
    }
    records_.resize(frame_.sample_count);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, records_.size(), 4096),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          const lightsampler::Sample& s = samples[i];
                          const float p = density(s.triangle, s.b1, s.b2);
                          records_[i] = light_point(emitters_, s.triangle, s.b1, s.b2, p * scale_, p);
                        }
                      });
    records_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }

  const Emitters& emitters_;
  lightsampler::Sampler& sampler_;
  double target_;
  lightsampler::Frame frame_;
  float scale_ = 0.0f;  ///< N_target / N
  std::vector<LightPoint, HugePages<LightPoint>> records_;  ///< one per light of the frame's set
  double records_ms_ = 0.0;
};

TRS_REGISTER_STRATEGY({.name = "trs",
                       .summary = "point lights drawn every frame by Triangle Rejection Sampling",
                       .make = [](const StrategyContext& c) { return std::make_unique<TrsStrategy>(c.emitters, c.options); },
                       .draws_point_lights = true});

}  // namespace

}  // namespace tracer
