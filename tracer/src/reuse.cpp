#include "reuse.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

#include <lightsampler/random.h>

#include "luminance.h"
#include "resampling.h"

namespace tracer {
namespace {

/// `text` as a number in [least, most]; throws naming `name` otherwise.
double number_option(const std::string& name, const std::string& text, double least, double most) {
  std::size_t used = 0;
  double value = NAN;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
  }
  if (used != text.size() || !(value >= least && value <= most)) {
    char range[64];
    std::snprintf(range, sizeof range, "[%g, %g]", least, most);
    throw std::invalid_argument("restir: " + name + " takes a number in " + range + ", not " + text);
  }
  return value;
}

/// A candidate of step 1: a light sample and f Li over its density.
struct Candidate {
  LightLiSample light;
  glm::vec3 unshadowed;
};

/// Neighbours whose surfaces face more apart than this cosine, or lie further apart in distance
/// from the camera than this fraction, are not reused: their targets differ too much to help.
constexpr float kNormalCosine = 0.9f;
constexpr float kDistanceFraction = 0.1f;

}  // namespace

ReuseOptions reuse_options(const std::map<std::string, std::string>& parameters) {
  ReuseOptions o;
  for (const auto& [name, value] : parameters) {
    if (name == "neighbours") {
      o.neighbours = unsigned(number_option(name, value, 0, kMaxNeighbours));
      if (double(o.neighbours) != std::stod(value)) throw std::invalid_argument("restir: neighbours takes a whole number, not " + value);
    } else if (name == "radius") {
      o.radius = float(number_option(name, value, 1, 1024));
    } else if (name == "m-cap") {
      o.m_cap = float(number_option(name, value, 0, 1e6));
    } else if (name == "temporal") {
      if (value != "on" && value != "off") throw std::invalid_argument("restir: temporal takes on or off, not " + value);
      o.temporal = value == "on";
    } else if (name == "weights") {
      if (value == "pairwise") o.weights = ReuseOptions::Weights::pairwise;
      else if (value == "balance") o.weights = ReuseOptions::Weights::balance;
      else if (value == "uniform") o.weights = ReuseOptions::Weights::uniform;
      else throw std::invalid_argument("restir: weights takes pairwise, balance or uniform, not " + value);
    }
  }
  return o;
}

struct Reuse::Input {
  const Reservoir* reservoir;
  const PrimaryVertex* vertex;
  float M;  ///< its confidence, capped
};

Reuse::Reuse(const PathTracer& tracer, const Emitters& emitters, const LightStrategy& strategy,
             const ReuseOptions& options, unsigned width, unsigned height)
    : tracer_(tracer), emitters_(emitters), strategy_(strategy), options_(options), width_(width), height_(height) {
  const std::size_t pixels = std::size_t(width) * height;
  vertices_.resize(pixels);
  previous_vertices_.resize(pixels);
  temporal_.resize(pixels);
  final_.resize(pixels);
  previous_final_.resize(pixels);
}

void Reuse::reset() {
  for (auto& v : previous_vertices_) v.reset();
  for (auto& v : vertices_) v.reset();
}

void Reuse::begin_pass() {
  std::swap(vertices_, previous_vertices_);
  std::swap(final_, previous_final_);
}

std::optional<LightLiSample> Reuse::seen(const Sample& y, const ShadingPoint& at) const {
  const Light light = emitters_.light(y.point.light);
  std::optional<LightLiSample> s = y.punctual ? light.sample_li(1.0, at) : light.sample_li(y.point, at);
  if (!s || !(s->pdf > 0.0f)) return std::nullopt;
  return s;
}

float Reuse::target(const PrimaryVertex& v, const Sample& y, std::uint64_t& targets) const {
  ++targets;
  const std::optional<LightLiSample> s = seen(y, v.at);
  if (!s) return 0.0f;
  return luminance(tracer_.unshadowed(v, *s)) / s->pdf;
}

void Reuse::gather(std::uint32_t pixel, const Ray& ray, PathRandom& random, std::uint64_t& rays, ReuseWork& work) {
  std::optional<PrimaryVertex>& v = vertices_[pixel];
  v = tracer_.primary_vertex(ray, rays);
  ++work.reservoirs;
  Reservoir initial;
  initial.M = float(strategy_.candidates());
  if (!v) {
    temporal_[pixel] = initial;
    return;
  }
  work.candidates += strategy_.candidates();
  const std::optional<Resampled<Candidate>> chosen =
      resample<Candidate>(strategy_, random, v->at, [&](const LightLiSample& s) -> std::optional<Candidate> {
        const glm::vec3 f_li = tracer_.unshadowed(*v, s);
        if (!(s.pdf > 0.0f)) return std::nullopt;
        return Candidate{s, f_li / s.pdf};
      });
  if (chosen) {
    const LightLiSample& s = chosen->kept.light;
    Sample y;
    y.punctual = s.delta;
    y.point.light = s.light;
    if (!s.delta) y.point = emitters_.light(s.light).point(s.b1, s.b2, 1.0f, 1.0f);
    const float p = target(*v, y, work.targets);
    if (p > 0.0f) {
      initial.y = y;
      initial.target = p;
      // sum of w / M, w = p / q of each candidate: the kept one's times the resampling scale.
      initial.W = chosen->scale * luminance(chosen->kept.unshadowed) / p;
    }
  }
  const bool history = options_.temporal && previous_vertices_[pixel];
  if (!history) {
    temporal_[pixel] = initial;
    return;
  }
  const float cap = options_.m_cap * float(strategy_.candidates());
  const std::array<Input, 2> inputs{{{&initial, &*v, initial.M},
                                     {&previous_final_[pixel], &*previous_vertices_[pixel],
                                      std::min(previous_final_[pixel].M, cap)}}};
  temporal_[pixel] = combine(inputs, random, work.targets);
}

void Reuse::spatial(std::uint32_t pixel, PathRandom& random, ReuseWork& work) {
  const std::optional<PrimaryVertex>& v = vertices_[pixel];
  if (!v || options_.neighbours == 0) {
    final_[pixel] = temporal_[pixel];
    return;
  }
  std::array<Input, 1 + kMaxNeighbours> inputs;
  inputs[0] = {&temporal_[pixel], &*v, temporal_[pixel].M};
  std::size_t count = 1;
  const int x = int(pixel % width_), y = int(pixel / width_);
  for (unsigned k = 0; k < options_.neighbours; ++k) {
    const auto u = random.floats();
    const float r = options_.radius * std::sqrt(u[0]), phi = 2.0f * std::numbers::pi_v<float> * u[1];
    const int qx = x + int(std::lround(r * std::cos(phi))), qy = y + int(std::lround(r * std::sin(phi)));
    if (qx < 0 || qy < 0 || qx >= int(width_) || qy >= int(height_) || (qx == x && qy == y)) continue;
    const std::uint32_t q = std::uint32_t(qy) * width_ + std::uint32_t(qx);
    const std::optional<PrimaryVertex>& w = vertices_[q];
    if (!w || glm::dot(w->at.normal, v->at.normal) < kNormalCosine ||
        std::abs(w->distance - v->distance) > kDistanceFraction * v->distance)
      continue;
    // Other pixels' threads query this surface too: with its own wo, which its BSDF is prepared for.
    inputs[count++] = {&temporal_[q], &*w, temporal_[q].M};
  }
  final_[pixel] = combine({inputs.data(), count}, random, work.targets);
}

Reuse::Reservoir Reuse::combine(std::span<const Input> inputs, PathRandom& random, std::uint64_t& targets) const {
  const PrimaryVertex& here = *inputs[0].vertex;
  Reservoir out;
  float sum = 0.0f;
  for (const Input& in : inputs) out.M += in.M;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const Reservoir& r = *inputs[i].reservoir;
    if (!r.y || !(r.W > 0.0f)) continue;
    const float p = i == 0 ? r.target : target(here, *r.y, targets);
    if (!(p > 0.0f)) continue;
    const float w = weight(inputs, i, p, out.M, targets) * p * r.W;
    if (!(w > 0.0f) || !std::isfinite(w)) continue;
    sum += w;
    if (lightsampler::uniform_float(random.words()[0]) * sum < w) {
      out.y = r.y;
      out.target = p;
    }
  }
  out.W = out.y ? sum / out.target : 0.0f;
  return out;
}

float Reuse::weight(std::span<const Input> inputs, std::size_t i, float p_0, float total,
                    std::uint64_t& targets) const {
  switch (options_.weights) {
    case ReuseOptions::Weights::pairwise: return pairwise(inputs, i, p_0, total, targets);
    case ReuseOptions::Weights::balance: return balance(inputs, i, targets);
    case ReuseOptions::Weights::uniform: break;
  }
  return inputs[i].M / total;
}

float Reuse::pairwise(std::span<const Input> inputs, std::size_t i, float p_0, float total,
                      std::uint64_t& targets) const {
  const std::size_t n = inputs.size() - 1;
  if (n == 0) return 1.0f;
  const float own = inputs[0].M / float(n);  // the pixel's own confidence in each of its n pairs
  // Pair j's share of the weight, and its part of it for the sample held at j (or here).
  const auto pair = [&](std::size_t j, float p_j, bool theirs) {
    const float share = (inputs[j].M + own) / total, denominator = inputs[j].M * p_j + own * p_0;
    if (!(denominator > 0.0f)) return 0.0f;
    return share * (theirs ? inputs[j].M * p_j : own * p_0) / denominator;
  };
  if (i > 0) return pair(i, inputs[i].reservoir->target, true);
  const Sample& y = *inputs[0].reservoir->y;
  float m = 0.0f;
  for (std::size_t j = 1; j <= n; ++j) m += pair(j, target(*inputs[j].vertex, y, targets), false);
  return m;
}

float Reuse::balance(std::span<const Input> inputs, std::size_t i, std::uint64_t& targets) const {
  // The generalized balance heuristic over the inputs' domains: M_i p_i(y) / sum_j M_j p_j(y).
  const Reservoir& r = *inputs[i].reservoir;
  float denominator = 0.0f;
  for (std::size_t j = 0; j < inputs.size(); ++j)
    denominator += inputs[j].M * (j == i ? r.target : target(*inputs[j].vertex, *r.y, targets));
  return inputs[i].M * r.target / denominator;
}

PathTracer::FirstSurface Reuse::first_surface(std::uint32_t pixel) const {
  const Reservoir& r = final_[pixel];
  const std::optional<PrimaryVertex>& v = vertices_[pixel];
  if (!v) return {};
  PathTracer::FirstSurface first{v->hit, std::nullopt};
  if (!r.y || !(r.W > 0.0f)) return first;
  std::optional<LightLiSample>& s = first.light;
  s = seen(*r.y, v->at);
  if (!s) return first;
  // Its contribution f Li G W is f Li over this density in solid angle (1 / G: its unit density's).
  s->pdf /= r.W;
  if (!s->delta)
    s->mis_pdf = emitters_.light(s->light).pdf_li(strategy_.pdf(s->light, s->b1, s->b2, v->at), -s->wi, s->distance);
  return first;
}

}  // namespace tracer
