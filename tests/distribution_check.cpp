#include "distribution_check.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "support/polygon_clip.h"

namespace trs_test {

using namespace lightsampler;


std::vector<Scenario> scenarios() {
  Map clamped = random_map(12, 10, 0.4, 22);
  clamped.addressing = Addressing::clamp;
  return {
      {"random triangles, sparse map, wrap beyond [0,1]", random_triangles(30, -0.5f, 1.5f, 11),
       random_map(12, 10, 0.4, 12), 300000, 101},
      {"random triangles, clamp beyond [0,1]", random_triangles(30, -0.5f, 1.5f, 21), clamped,
       300000, 202},
      {"two large triangles over a fine sparse map", quad(3, 1, 0, 0, 1, 1),
       random_map(32, 32, 0.6, 32), 300000, 303},
  };
}

std::size_t distribution_family_size() {
  const std::size_t per_scenario = scenarios().size();
  std::size_t size = 0;
  for (const FamilyMember& m : kDistributionFamily) size += m.per_scenario ? per_scenario : 1;
  return size;
}

/// Cells of one triangle: texel (x, y) -> expected weight D(texel) * Area(texel n T_uv).
using Cells = std::map<std::pair<std::uint32_t, std::uint32_t>, double>;

std::vector<Cells> reference_cells(const Scenario& s) {
  const Map& map = s.map;
  std::vector<Cells> cells(s.mesh.indices.size() / 3);
  for (std::size_t t = 0; t < cells.size(); ++t) {
    Point p[3];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = s.mesh.indices[3 * t + k];
      p[k] = {double(s.mesh.uvs[2 * v]) * map.width, double(s.mesh.uvs[2 * v + 1]) * map.height};
    }
    for (const auto& texel : texel_areas(p[0], p[1], p[2], map.width, map.height, map.addressing))
      cells[t][{texel.x, texel.y}] = double(map.texels[std::size_t(texel.y) * map.width + texel.x]) * texel.area;
  }
  return cells;
}

/// The texel a sample reads, computed as the sampler computes it (same float expression).
std::pair<std::uint32_t, std::uint32_t> texel_of(const Scenario& s, const core::TexelTriangle& t,
                                                 const Sample& sample) {
  const float x = t.origin[0] + sample.b1 * t.edge1[0] + sample.b2 * t.edge2[0];
  const float y = t.origin[1] + sample.b1 * t.edge1[1] + sample.b2 * t.edge2[1];
  return {core::address(std::int64_t(std::floor(x)), s.map.width, s.map.addressing),
          core::address(std::int64_t(std::floor(y)), s.map.height, s.map.addressing)};
}

std::vector<core::TexelTriangle> texel_triangles(const Scenario& s) {
  const core::DensityMap map{s.map.texels, s.map.width, s.map.height, s.map.addressing, s.map.scale};
  std::vector<core::TexelTriangle> out;
  for (const core::TriangleRecord& r : core::make_triangle_records(s.mesh.view(), 1))
    out.push_back(core::make_texel_triangle(r, {&map, 1}));
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
ChiSquareResult test_per_triangle(const Scenario& s, std::span<const Sample> samples) {
  const auto cells = reference_cells(s);
  const auto texel_tris = texel_triangles(s);
  std::vector<std::map<std::pair<std::uint32_t, std::uint32_t>, double>> observed(cells.size());
  for (const Sample& x : samples) observed[x.triangle][texel_of(s, texel_tris[x.triangle], x)] += 1;
  std::vector<ChiSquareResult> parts;
  for (std::size_t t = 0; t < cells.size(); ++t) {
    double n = 0;
    for (const auto& [texel, c] : observed[t]) n += c;
    std::vector<double> obs, exp;
    add_table(cells[t], observed[t], n, obs, exp);
    parts.push_back(chi_square_test(obs, exp));
  }
  return combine_independent(parts);
}

/// Rejection sampling: one multinomial table over all (triangle, texel) cells.
ChiSquareResult test_all_cells(const Scenario& s, std::span<const Sample> samples) {
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
  return chi_square_test(obs, exp);
}

}  // namespace trs_test
