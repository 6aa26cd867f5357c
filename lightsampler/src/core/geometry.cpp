#include "core/geometry.h"

#include <cmath>

namespace lightsampler::core {

std::vector<TriangleRecord> make_triangle_records(const MeshView& mesh, std::size_t map_count) {
  const std::size_t n = mesh.triangle_count();
  std::vector<TriangleRecord> records(n);
  for (std::size_t t = 0; t < n; ++t) {
    TriangleRecord& r = records[t];
    double p[3][3];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh.indices[3 * t + k];
      for (int a = 0; a < 3; ++a) p[k][a] = mesh.positions[3 * std::size_t(v) + a];
      r.uv[k][0] = mesh.uvs[2 * std::size_t(v)];
      r.uv[k][1] = mesh.uvs[2 * std::size_t(v) + 1];
    }
    const double e1[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const double e2[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    const double n3[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                          e1[0] * e2[1] - e1[1] * e2[0]};
    r.area = (0.5 * std::sqrt(n3[0] * n3[0] + n3[1] * n3[1] + n3[2] * n3[2]));
    if (mesh.triangle_maps.empty())
      r.map = map_count > 0 ? 0u : kNoMap;
    else
      r.map = mesh.triangle_maps[t];
  }
  return records;
}

TexelTriangle make_texel_triangle(const TriangleRecord& t, std::span<const DensityMap> maps) {
  TexelTriangle out{};
  out.map = t.map;
  if (t.map == kNoMap) return out;
  const double w = maps[t.map].width, h = maps[t.map].height;
  const double x[3] = {t.uv[0][0] * w, t.uv[1][0] * w, t.uv[2][0] * w};
  const double y[3] = {t.uv[0][1] * h, t.uv[1][1] * h, t.uv[2][1] * h};
  const double e1[2] = {x[1] - x[0], y[1] - y[0]}, e2[2] = {x[2] - x[0], y[2] - y[0]};
  if (0.5 * std::abs(e1[0] * e2[1] - e1[1] * e2[0]) <= kDegenerateUvArea) {
    out.origin[0] = float((x[0] + x[1] + x[2]) / 3);
    out.origin[1] = float((y[0] + y[1] + y[2]) / 3);
    return out;
  }
  out.origin[0] = float(x[0]);
  out.origin[1] = float(y[0]);
  out.edge1[0] = float(e1[0]);
  out.edge1[1] = float(e1[1]);
  out.edge2[0] = float(e2[0]);
  out.edge2[1] = float(e2[1]);
  return out;
}

}  // namespace lightsampler::core
