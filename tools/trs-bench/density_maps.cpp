#include "density_maps.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "lightsampler/random.h"

namespace trs_bench {

namespace {

constexpr double kPi = std::numbers::pi;

/// Uniform in [0, 1) from a 64-bit hash: the same maps on every platform and standard library
/// (std::uniform_real_distribution is implementation-defined).
double unit_from_bits(std::uint64_t bits) { return double(bits >> 11) * 0x1p-53; }

/// SplitMix64: a sequence of well-mixed 64-bit values from one seed.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  double uniform() { return unit_from_bits(lightsampler::mix64(state_ += 0x9E3779B97F4A7C15ull)); }

 private:
  std::uint64_t state_;
};

constexpr std::uint64_t kSparseSeed = 0x5eed0001;
constexpr std::uint64_t kHifreqSeed = 0x5eed0002;
constexpr double kSparseCoverage = 0.015;

/// Lights the texels whose centres lie within `radius` of segment (x0,y0)-(x1,y1) at `value`
/// (max with what is there); returns how many texels it lit that were dark.
std::uint64_t draw_stroke(DensityMap& map, double x0, double y0, double x1, double y1,
                          double radius, float value) {
  const double dx = x1 - x0, dy = y1 - y0;
  const double length2 = std::max(dx * dx + dy * dy, 1e-12);
  const auto lo = [&](double a, double b) {
    return std::uint32_t(
        std::clamp(std::floor(std::min(a, b) - radius), 0.0, double(map.size - 1)));
  };
  const auto hi = [&](double a, double b) {
    return std::uint32_t(std::clamp(std::ceil(std::max(a, b) + radius), 0.0, double(map.size - 1)));
  };
  std::uint64_t lit = 0;
  for (std::uint32_t j = lo(y0, y1); j <= hi(y0, y1); ++j) {
    for (std::uint32_t i = lo(x0, x1); i <= hi(x0, x1); ++i) {
      const double px = i + 0.5 - x0, py = j + 0.5 - y0;
      const double t = std::clamp((px * dx + py * dy) / length2, 0.0, 1.0);
      const double ex = px - t * dx, ey = py - t * dy;
      if (ex * ex + ey * ey > radius * radius) continue;
      float& texel = map.texels[std::size_t(j) * map.size + i];
      if (texel == 0) ++lit;
      texel = std::max(texel, value);
    }
  }
  return lit;
}

}  // namespace

MapKind parse_map_kind(const std::string& name) {
  if (name == "smooth") return MapKind::smooth;
  if (name == "sparse") return MapKind::sparse;
  if (name == "hifreq") return MapKind::hifreq;
  throw std::invalid_argument("map '" + name + "': must be smooth, sparse or hifreq");
}

const char* to_string(MapKind kind) {
  switch (kind) {
    case MapKind::smooth:
      return "smooth";
    case MapKind::sparse:
      return "sparse";
    case MapKind::hifreq:
      return "hifreq";
  }
  return "?";
}

DensityMap make_smooth_map(std::uint32_t size) {
  DensityMap map{"smooth", size, std::vector<float>(std::size_t(size) * size)};
  for (std::uint32_t j = 0; j < size; ++j) {
    const double y = (j + 0.5) / size;
    for (std::uint32_t i = 0; i < size; ++i) {
      const double x = (i + 0.5) / size;
      const double wave = 0.55 + 0.45 * std::sin(2 * kPi * 2 * x) * std::sin(2 * kPi * 3 * y);
      map.texels[std::size_t(j) * size + i] = float((0.1 + 0.9 * x) * wave);
    }
  }
  return map;
}

DensityMap make_sparse_map(std::uint32_t size) {
  DensityMap map{"sparse", size, std::vector<float>(std::size_t(size) * size, 0.0f)};
  SplitMix64 random(kSparseSeed);
  // Stroke width scales with the map, so the coverage and look do not depend on the resolution.
  const double radius = std::max(0.75, size / 2048.0);
  const auto target = std::uint64_t(kSparseCoverage * double(size) * size);
  std::uint64_t lit = 0;
  while (lit < std::max<std::uint64_t>(target, 1)) {
    const double x0 = random.uniform() * size, y0 = random.uniform() * size;
    const double angle = random.uniform() * 2 * kPi;
    const double length = (0.03 + 0.17 * random.uniform()) * size;
    const double x1 = std::clamp(x0 + length * std::cos(angle), 0.0, size - 1e-6);
    const double y1 = std::clamp(y0 + length * std::sin(angle), 0.0, size - 1e-6);
    const auto brightness = float(0.3 + 0.7 * random.uniform());
    lit += draw_stroke(map, x0, y0, x1, y1, radius, brightness);
  }
  return map;
}

DensityMap make_hifreq_map(std::uint32_t size) {
  DensityMap map{"hifreq", size, std::vector<float>(std::size_t(size) * size)};
  for (std::uint32_t j = 0; j < size; ++j) {
    for (std::uint32_t i = 0; i < size; ++i) {
      const std::size_t index = std::size_t(j) * size + i;
      const double checker = (i + j) % 2 ? 1.0 : 0.1;
      const double noise = 0.5 + 0.5 * unit_from_bits(lightsampler::mix64(kHifreqSeed ^ index));
      map.texels[index] = float(checker * noise);
    }
  }
  return map;
}

DensityMap make_map(MapKind kind, std::uint32_t size) {
  switch (kind) {
    case MapKind::smooth:
      return make_smooth_map(size);
    case MapKind::sparse:
      return make_sparse_map(size);
    case MapKind::hifreq:
      return make_hifreq_map(size);
  }
  throw std::logic_error("unknown map kind");
}

double coverage(const DensityMap& map) {
  const auto lit =
      std::count_if(map.texels.begin(), map.texels.end(), [](float t) { return t > 0; });
  return double(lit) / double(map.texels.size());
}

}  // namespace trs_bench
