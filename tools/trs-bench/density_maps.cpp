#include "density_maps.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "dataset_file.h"
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
constexpr std::uint64_t kFractalSeed = 0x5eed0003;
constexpr std::uint64_t kDotsSeed = 0x5eed0004;
constexpr std::uint64_t kTextSeed = 0x5eed0005;
constexpr double kSparseCoverage = 0.015;
constexpr double kDotsCoverage = 0.01;

DensityMap blank_map(std::string name, std::uint32_t size) {
  return {std::move(name), size, size, std::vector<float>(std::size_t(size) * size, 0.0f)};
}

/// Texels per texel of a 2048 map: features keep their look whatever the resolution.
double scale_of(std::uint32_t size) { return size / 2048.0; }

/// Lights the texels whose centres lie within `radius` of segment (x0,y0)-(x1,y1) at `value`
/// (max with what is there); returns how many texels it lit that were dark.
std::uint64_t draw_stroke(DensityMap& map, double x0, double y0, double x1, double y1,
                          double radius, float value) {
  const double dx = x1 - x0, dy = y1 - y0;
  const double length2 = std::max(dx * dx + dy * dy, 1e-12);
  const auto lo = [&](double a, double b) {
    return std::uint32_t(
        std::clamp(std::floor(std::min(a, b) - radius), 0.0, double(map.width - 1)));
  };
  const auto hi = [&](double a, double b) {
    return std::uint32_t(std::clamp(std::ceil(std::max(a, b) + radius), 0.0, double(map.width - 1)));
  };
  std::uint64_t lit = 0;
  for (std::uint32_t j = lo(y0, y1); j <= hi(y0, y1); ++j) {
    for (std::uint32_t i = lo(x0, x1); i <= hi(x0, x1); ++i) {
      const double px = i + 0.5 - x0, py = j + 0.5 - y0;
      const double t = std::clamp((px * dx + py * dy) / length2, 0.0, 1.0);
      const double ex = px - t * dx, ey = py - t * dy;
      if (ex * ex + ey * ey > radius * radius) continue;
      float& texel = map.texels[std::size_t(j) * map.width + i];
      if (texel == 0) ++lit;
      texel = std::max(texel, value);
    }
  }
  return lit;
}

/// A lattice value in [0, 1) of octave `octave`, wrapped to `cells` so that the noise tiles.
double lattice(std::uint32_t octave, std::uint32_t cells, std::int64_t x, std::int64_t y) {
  const auto wrap = [cells](std::int64_t a) { return std::uint64_t((a % cells + cells) % cells); };
  return unit_from_bits(lightsampler::mix64(kFractalSeed ^ (std::uint64_t(octave) << 56) ^
                                            (wrap(x) << 28) ^ wrap(y)));
}

/// Value noise with smoothstep interpolation, at (x, y) in [0, 1)^2, `cells` lattice cells across.
double value_noise(std::uint32_t octave, std::uint32_t cells, double x, double y) {
  const double fx = x * cells, fy = y * cells;
  const auto ix = std::int64_t(std::floor(fx)), iy = std::int64_t(std::floor(fy));
  const auto smooth = [](double t) { return t * t * (3 - 2 * t); };
  const double sx = smooth(fx - ix), sy = smooth(fy - iy);
  const auto mix = [](double a, double b, double t) { return a + (b - a) * t; };
  return mix(mix(lattice(octave, cells, ix, iy), lattice(octave, cells, ix + 1, iy), sx),
             mix(lattice(octave, cells, ix, iy + 1), lattice(octave, cells, ix + 1, iy + 1), sx),
             sy);
}

/// fBm: octaves of halving amplitude and doubling frequency, rescaled to [low, 1].
DensityMap fractal_map(std::string name, std::uint32_t size, double low) {
  DensityMap map = blank_map(std::move(name), size);
  std::vector<double> values(map.texels.size());
  for (std::uint32_t j = 0; j < size; ++j) {
    for (std::uint32_t i = 0; i < size; ++i) {
      const double x = (i + 0.5) / size, y = (j + 0.5) / size;
      double value = 0, amplitude = 1;
      for (std::uint32_t octave = 0; octave < 8; ++octave, amplitude *= 0.5)
        value += amplitude * value_noise(octave, 4u << octave, x, y);
      values[std::size_t(j) * size + i] = value;
    }
  }
  const auto [min, max] = std::minmax_element(values.begin(), values.end());
  const double range = std::max(*max - *min, 1e-300);
  for (std::size_t k = 0; k < values.size(); ++k)
    map.texels[k] = float(low + (1 - low) * (values[k] - *min) / range);
  return map;
}

std::string format_fraction(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", fraction);
  return text;
}

/// One glyph: 3 to 5 connected strokes walking a 3x4 lattice of points in the box at (x, y) of
/// size w x h, as a segment display draws characters.
void draw_glyph(DensityMap& map, SplitMix64& random, double x, double y, double w, double h,
                double radius, float value) {
  int column = int(random.uniform() * 3), row = int(random.uniform() * 4);
  const int strokes = 3 + int(random.uniform() * 3);
  for (int k = 0; k < strokes; ++k) {
    const int next_column = std::clamp(column + int(random.uniform() * 3) - 1, 0, 2);
    const int next_row = std::clamp(row + int(random.uniform() * 3) - 1, 0, 3);
    draw_stroke(map, x + w * column / 2, y + h * row / 3, x + w * next_column / 2,
                y + h * next_row / 3, radius, value);
    column = next_column;
    row = next_row;
  }
}

}  // namespace

MapSpec parse_map_spec(std::string_view text) {
  const std::string quoted = "map '" + std::string(text) + "': ";
  const auto colon = text.find(':');
  const std::string_view kind = text.substr(0, colon);
  const std::string_view argument =
      colon == std::string_view::npos ? std::string_view() : text.substr(colon + 1);
  MapSpec spec;
  if (kind == "threshold") {
    spec.kind = MapKind::threshold;
    const auto [end, error] =
        std::from_chars(argument.data(), argument.data() + argument.size(), spec.fraction);
    if (argument.empty() || error != std::errc() || end != argument.data() + argument.size() ||
        !(spec.fraction > 0 && spec.fraction <= 1))
      throw std::invalid_argument(quoted + "expected threshold:F with F in (0, 1], e.g. threshold:1e-3");
    return spec;
  }
  if (kind == "file") {
    if (argument.empty()) throw std::invalid_argument(quoted + "expected file:PATH");
    spec.kind = MapKind::file;
    spec.file = std::string(argument);
    return spec;
  }
  static const std::pair<const char*, MapKind> kNamed[] = {
      {"smooth", MapKind::smooth}, {"sparse", MapKind::sparse}, {"hifreq", MapKind::hifreq},
      {"fractal", MapKind::fractal}, {"dots", MapKind::dots},    {"stripes", MapKind::stripes},
      {"text", MapKind::text}};
  for (const auto& [name, named_kind] : kNamed) {
    if (text == name) {
      spec.kind = named_kind;
      return spec;
    }
  }
  throw std::invalid_argument(quoted + "must be one of " + map_kind_names());
}

std::string map_kind_names() {
  return "smooth, sparse, hifreq, fractal, dots, stripes, text, threshold:F, file:PATH";
}

DensityMap make_smooth_map(std::uint32_t size) {
  DensityMap map = blank_map("smooth", size);
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
  DensityMap map = blank_map("sparse", size);
  SplitMix64 random(kSparseSeed);
  // Stroke width scales with the map, so the coverage and look do not depend on the resolution.
  const double radius = std::max(0.75, scale_of(size));
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
  DensityMap map = blank_map("hifreq", size);
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

DensityMap make_fractal_map(std::uint32_t size) { return fractal_map("fractal", size, 0.02); }

DensityMap make_threshold_map(std::uint32_t size, double fraction) {
  DensityMap map = fractal_map("threshold:" + format_fraction(fraction), size, 0.02);
  const std::size_t texels = map.texels.size();
  const auto kept = std::clamp<std::size_t>(std::size_t(std::llround(fraction * double(texels))), 1, texels);
  std::vector<std::uint32_t> order(texels);
  std::iota(order.begin(), order.end(), 0u);
  // Brightest first, ties by index: exactly `kept` texels rank before the cut.
  const auto brighter = [&](std::uint32_t a, std::uint32_t b) {
    return map.texels[a] != map.texels[b] ? map.texels[a] > map.texels[b] : a < b;
  };
  std::nth_element(order.begin(), order.begin() + std::ptrdiff_t(kept - 1), order.end(), brighter);
  for (auto k = order.begin() + std::ptrdiff_t(kept); k != order.end(); ++k) map.texels[*k] = 0;
  return map;
}

DensityMap make_dots_map(std::uint32_t size) {
  DensityMap map = blank_map("dots", size);
  SplitMix64 random(kDotsSeed);
  const auto target = std::uint64_t(kDotsCoverage * double(size) * size);
  std::uint64_t lit = 0;
  while (lit < std::max<std::uint64_t>(target, 1)) {
    const double x = random.uniform() * size, y = random.uniform() * size;
    const double radius = std::max(0.75, (1 + 3 * random.uniform()) * scale_of(size));
    lit += draw_stroke(map, x, y, x, y, radius, float(0.3 + 0.7 * random.uniform()));
  }
  return map;
}

DensityMap make_stripes_map(std::uint32_t size) {
  DensityMap map = blank_map("stripes", size);
  for (std::uint32_t j = 0; j < size; ++j) {
    for (std::uint32_t i = 0; i < size; ++i) {
      // Four columns of diagonal bars, periods 64, 32, 16 and 8 texels at 2048 (4 at least,
      // so that bars stay bars at low resolution).
      const std::uint32_t column = 4 * i / size;
      const double period = std::max(4.0, (64 >> column) * scale_of(size));
      const double phase = (i + j + 1.0) / period;
      if (phase - std::floor(phase) < 0.3) map.texels[std::size_t(j) * size + i] = 1.0f;
    }
  }
  return map;
}

DensityMap make_text_map(std::uint32_t size) {
  DensityMap map = blank_map("text", size);
  SplitMix64 random(kTextSeed);
  const double line = size / 24.0, glyph_w = 0.45 * line, glyph_h = 0.7 * line;
  const double radius = std::max(0.75, 0.05 * line), margin = 0.05 * size;
  for (double y = margin; y + glyph_h < size - margin; y += line) {
    if (random.uniform() < 0.2) continue;  // a blank line between paragraphs
    const auto brightness = float(0.4 + 0.6 * random.uniform());
    const double end = size - margin - (0.3 * random.uniform()) * size;  // ragged right edge
    double x = margin;
    while (true) {
      const int letters = 2 + int(random.uniform() * 7);
      if (x + letters * 1.3 * glyph_w > end) break;
      for (int k = 0; k < letters; ++k, x += 1.3 * glyph_w)
        draw_glyph(map, random, x, y, glyph_w, glyph_h, radius, brightness);
      x += 1.3 * glyph_w;  // a space
    }
  }
  return map;
}

DensityMap make_map(const MapSpec& spec, std::uint32_t size) {
  DensityMap map;
  switch (spec.kind) {
    case MapKind::smooth: map = make_smooth_map(size); break;
    case MapKind::sparse: map = make_sparse_map(size); break;
    case MapKind::hifreq: map = make_hifreq_map(size); break;
    case MapKind::fractal: map = make_fractal_map(size); break;
    case MapKind::dots: map = make_dots_map(size); break;
    case MapKind::stripes: map = make_stripes_map(size); break;
    case MapKind::text: map = make_text_map(size); break;
    case MapKind::threshold: map = make_threshold_map(size, spec.fraction); break;
    case MapKind::file: map = read_dataset_map(spec.file); break;
  }
  const auto lit = std::count_if(map.texels.begin(), map.texels.end(), [](float t) { return t > 0; });
  map.coverage = double(lit) / double(map.texels.size());
  return map;
}

}  // namespace trs_bench
