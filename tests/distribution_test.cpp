// Are the samples distributed in proportion to the density? Chi-square goodness of fit over
// (triangle, texel) cells, with expected counts computed independently of the sampler (polygon
// clipping, texel by texel: tests/support/polygon_clip.h).
//
// TRS: conditional on each triangle's count N_T (set by stochastic rounding, tested in
// rounding_test), the N_T samples of a triangle are i.i.d. with probability proportional to
// D(texel) Area(texel n T): one table per triangle, the statistics summed.
// Rejection sampling: the N samples are i.i.d. over all cells: one multinomial table.
//
// Hypothesis H0: the sampler draws from that distribution. Seeds fixed per scenario; family
// significance 0.01 with the Sidak correction over the scenarios; cells with expectation
// under 5 pooled; any sample in a zero-probability cell fails. Each test is shown to reject a
// deliberately wrong sampler.

#include <algorithm>
#include <map>
#include <vector>

#include <gtest/gtest.h>

#include "cpu/passes.h"
#include "lightsampler/sampler.h"
#include "lightsampler/triangle_map.h"
#include "sampler_fixtures.h"
#include "support/chi_square.h"
#include "support/polygon_clip.h"

using namespace lightsampler;

namespace {

constexpr double kFamilyAlpha = 0.01;
constexpr std::size_t kFamilySize = 6;  // 3 scenarios x 2 methods
const double kAlpha = trs_test::sidak_alpha(kFamilyAlpha, kFamilySize);

struct Scenario {
  const char* name;
  trs_test::Mesh mesh;
  trs_test::Map map;
  double target;
  std::uint64_t seed;
};

std::vector<Scenario> scenarios() {
  trs_test::Map clamped = trs_test::random_map(12, 10, 0.4, 22);
  clamped.addressing = Addressing::clamp;
  return {
      {"random triangles, sparse map, wrap beyond [0,1]", trs_test::random_triangles(30, -0.5f, 1.5f, 11),
       trs_test::random_map(12, 10, 0.4, 12), 300000, 101},
      {"random triangles, clamp beyond [0,1]", trs_test::random_triangles(30, -0.5f, 1.5f, 21), clamped,
       300000, 202},
      {"two large triangles over a fine sparse map", trs_test::quad(3, 1, 0, 0, 1, 1),
       trs_test::random_map(32, 32, 0.6, 32), 300000, 303},
  };
}

/// Cells of one triangle: texel (x, y) -> expected weight D(texel) * Area(texel n T_uv).
using Cells = std::map<std::pair<std::uint32_t, std::uint32_t>, double>;

std::vector<Cells> reference_cells(const Scenario& s) {
  const trs_test::Map& map = s.map;
  std::vector<Cells> cells(s.mesh.indices.size() / 3);
  for (std::size_t t = 0; t < cells.size(); ++t) {
    trs_test::Point p[3];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = s.mesh.indices[3 * t + k];
      p[k] = {double(s.mesh.uvs[2 * v]) * map.width, double(s.mesh.uvs[2 * v + 1]) * map.height};
    }
    for (const auto& texel : trs_test::texel_areas(p[0], p[1], p[2], map.width, map.height, map.addressing))
      cells[t][{texel.x, texel.y}] = double(map.texels[std::size_t(texel.y) * map.width + texel.x]) * texel.area;
  }
  return cells;
}

/// The texel a sample reads, computed as the sampler computes it (same float expression).
std::pair<std::uint32_t, std::uint32_t> texel_of(const Scenario& s, const cpu::TexelTriangle& t,
                                                 const Sample& sample) {
  const float x = t.origin[0] + sample.b1 * t.edge1[0] + sample.b2 * t.edge2[0];
  const float y = t.origin[1] + sample.b1 * t.edge1[1] + sample.b2 * t.edge2[1];
  return {cpu::address(std::int64_t(std::floor(x)), s.map.width, s.map.addressing),
          cpu::address(std::int64_t(std::floor(y)), s.map.height, s.map.addressing)};
}

std::vector<cpu::TexelTriangle> texel_triangles(const Scenario& s) {
  const cpu::DensityMap map{s.map.texels, s.map.width, s.map.height, s.map.addressing, s.map.scale};
  std::vector<cpu::TexelTriangle> out;
  for (const cpu::TriangleRecord& r : cpu::make_triangle_records(s.mesh.view(), 1))
    out.push_back(cpu::make_texel_triangle(r, {&map, 1}));
  return out;
}

/// Observed and expected counts of one table; expected scaled to `total`.
void add_table(const Cells& cells, const std::map<std::pair<std::uint32_t, std::uint32_t>, double>& observed,
               double total, std::vector<double>& obs, std::vector<double>& exp) {
  double weight = 0;
  for (const auto& [texel, w] : cells) weight += w;
  for (const auto& [texel, w] : cells) {
    const auto it = observed.find(texel);
    obs.push_back(it == observed.end() ? 0 : it->second);
    exp.push_back(weight > 0 ? total * w / weight : 0);
  }
  for (const auto& [texel, n] : observed)  // samples outside every overlapping texel
    if (!cells.count(texel)) {
      obs.push_back(n);
      exp.push_back(0);
    }
}

/// TRS: one table per triangle, conditional on its count.
trs_test::ChiSquareResult test_per_triangle(const Scenario& s, std::span<const Sample> samples) {
  const auto cells = reference_cells(s);
  const auto texel_tris = texel_triangles(s);
  std::vector<std::map<std::pair<std::uint32_t, std::uint32_t>, double>> observed(cells.size());
  for (const Sample& x : samples) observed[x.triangle][texel_of(s, texel_tris[x.triangle], x)] += 1;
  std::vector<trs_test::ChiSquareResult> parts;
  for (std::size_t t = 0; t < cells.size(); ++t) {
    double n = 0;
    for (const auto& [texel, c] : observed[t]) n += c;
    std::vector<double> obs, exp;
    add_table(cells[t], observed[t], n, obs, exp);
    parts.push_back(trs_test::chi_square_test(obs, exp));
  }
  return trs_test::combine_independent(parts);
}

/// Rejection sampling: one multinomial table over all (triangle, texel) cells.
trs_test::ChiSquareResult test_all_cells(const Scenario& s, std::span<const Sample> samples) {
  const auto cells = reference_cells(s);
  const auto texel_tris = texel_triangles(s);
  std::map<std::pair<std::uint64_t, std::uint64_t>, double> observed;
  for (const Sample& x : samples) {
    const auto texel = texel_of(s, texel_tris[x.triangle], x);
    observed[{x.triangle, (std::uint64_t(texel.first) << 32) | texel.second}] += 1;
  }
  // World area over UV area turns a texel-space weight into samples per triangle.
  Frame frame;
  const DensityMapView view = s.map.view();
  auto sampler = make_cpu_sampler(s.mesh.view(), {&view, 1});
  sampler->generate({.realize = false}, frame);
  double weight_total = 0;
  std::vector<double> tri_scale(cells.size());
  for (std::size_t t = 0; t < cells.size(); ++t) {
    double w = 0;
    for (const auto& [texel, c] : cells[t]) w += c;
    tri_scale[t] = w > 0 ? frame.expected_counts[t] / w : 0;
    weight_total += frame.expected_counts[t];
  }
  std::vector<double> obs, exp;
  for (std::size_t t = 0; t < cells.size(); ++t)
    for (const auto& [texel, w] : cells[t]) {
      const auto key = std::pair{std::uint64_t(t), (std::uint64_t(texel.first) << 32) | texel.second};
      const auto it = observed.find(key);
      obs.push_back(it == observed.end() ? 0 : it->second);
      exp.push_back(double(samples.size()) * w * tri_scale[t] / weight_total);
      if (it != observed.end()) observed.erase(it);
    }
  for (const auto& [key, n] : observed) {
    obs.push_back(n);
    exp.push_back(0);
  }
  return trs_test::chi_square_test(obs, exp);
}

Frame generate(const Scenario& s, Method method) {
  const DensityMapView view = s.map.view();
  auto sampler = make_cpu_sampler(s.mesh.view(), {&view, 1});
  Frame frame;
  sampler->generate({.seed = s.seed, .target_count = s.target, .method = method}, frame);
  for (const Sample& x : frame.samples)
    EXPECT_GT(sampler->density(x.triangle, x.b1, x.b2), 0.0f) << "a sample where the density is zero";
  return frame;
}

/// A wrong realization: the sqrt-free map misused (b2 = u1 (1 - u0) is not uniform on the
/// triangle: it crowds vertex 1).
void realize_with_wrong_map(const Scenario& s, const Frame& counted, Buffer<Sample>& samples) {
  const auto tris = texel_triangles(s);
  const cpu::DensityMap map{s.map.texels, s.map.width, s.map.height, s.map.addressing, s.map.scale};
  const PhiloxKey key = stream_key(s.seed, Stream::realization);
  samples.resize(counted.sample_count);
  std::uint64_t i = 0;
  for (std::size_t p = 0; p < counted.cdf.size(); ++p) {
    const std::uint32_t tri = counted.inverse_permutation[p];
    for (std::uint64_t rank = 0; rank < counted.counts[tri]; ++rank, ++i)
      for (std::uint32_t attempt = 0;; ++attempt) {
        const PhiloxCounter u = philox4x32({tri, std::uint32_t(rank), 0, attempt}, key);
        const float u0 = uniform_float(u[0]), u1 = uniform_float(u[1]);
        const Sample x{tri, u0, u1 * (1 - u0)};
        if (uniform_float(u[2]) * counted.max_density[tri] <
            cpu::texel_triangle_density(tris[tri], {&map, 1}, x.b1, x.b2)) {
          samples[i] = x;
          break;
        }
      }
  }
}

}  // namespace

TEST(Distribution, TrsMatchesTheDensity) {
  for (const Scenario& s : scenarios()) {
    const Frame frame = generate(s, Method::trs);
    const auto result = test_per_triangle(s, frame.samples.span());
    EXPECT_GT(result.dof, 100) << s.name << ": too few cells to have power";
    EXPECT_TRUE(result.passes(kAlpha)) << s.name << "\n" << result.describe();
  }
}

TEST(Distribution, RejectionSamplingMatchesTheDensity) {
  for (const Scenario& s : scenarios()) {
    const Frame frame = generate(s, Method::rejection);
    const auto result = test_all_cells(s, frame.samples.span());
    EXPECT_GT(result.dof, 100) << s.name;
    EXPECT_TRUE(result.passes(kAlpha)) << s.name << "\n" << result.describe();
  }
}

TEST(Distribution, RejectsTrsThatIgnoresTheMaxDensity) {
  // With a zero bound every candidate on a non-zero texel is accepted: uniform, not D-shaped.
  const Scenario s = scenarios()[0];
  Frame frame = generate(s, Method::trs);
  const auto tris = texel_triangles(s);
  const cpu::DensityMap map{s.map.texels, s.map.width, s.map.height, s.map.addressing, s.map.scale};
  const std::vector<float> no_bound(frame.max_density.size(), 0.0f);
  cpu::realize(tris, {&map, 1}, no_bound, frame.cdf.span(), frame.inverse_permutation.span(),
               stream_key(s.seed, Stream::realization), 1u << 20, frame.samples);
  EXPECT_FALSE(test_per_triangle(s, frame.samples.span()).passes(kAlpha));
}

TEST(Distribution, RejectsTrsWithANonUniformTriangleMap) {
  const Scenario s = scenarios()[2];
  Frame frame = generate(s, Method::trs);
  realize_with_wrong_map(s, frame, frame.samples);
  EXPECT_FALSE(test_per_triangle(s, frame.samples.span()).passes(kAlpha));
}

TEST(Distribution, RejectsRejectionSamplingWithTooLowABound) {
  // Half the true max: the brightest texels are accepted as often as dimmer ones.
  const Scenario s = scenarios()[0];
  Frame frame = generate(s, Method::rejection);
  const cpu::DensityMap map{s.map.texels, s.map.width, s.map.height, s.map.addressing, s.map.scale};
  Buffer<double> area_cdf;
  const auto records = cpu::make_triangle_records(s.mesh.view(), 1);
  const float bound = cpu::rejection_distribution(records, {&map, 1}, area_cdf);
  cpu::rejection_sample(texel_triangles(s), {&map, 1}, area_cdf.span(), 0.5f * bound, frame.sample_count,
                        stream_key(s.seed, Stream::rejection), 1u << 20, frame.samples);
  EXPECT_FALSE(test_all_cells(s, frame.samples.span()).passes(kAlpha));
}
