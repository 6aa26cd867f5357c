#include "core/geometry.h"

#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace lightsampler::core {

TriangleRecord make_triangle_record(const float (&positions)[3][3], const float (&uvs)[3][2], std::uint32_t map) {
  TriangleRecord r;
  double p[3][3];
  for (int k = 0; k < 3; ++k) {
    for (int a = 0; a < 3; ++a) p[k][a] = positions[k][a];
    r.uv[k][0] = uvs[k][0];
    r.uv[k][1] = uvs[k][1];
  }
  const double e1[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
  const double e2[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
  const double n3[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                        e1[0] * e2[1] - e1[1] * e2[0]};
  r.area = (0.5 * std::sqrt(n3[0] * n3[0] + n3[1] * n3[1] + n3[2] * n3[2]));
  r.map = map;
  return r;
}

std::vector<TriangleRecord> make_triangle_records(const MeshView& mesh, std::size_t map_count) {
  const std::size_t n = mesh.triangle_count();
  std::vector<TriangleRecord> records(n);
  // In parallel: meshes can be large, and every sampler's construction starts here.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t t = range.begin(); t != range.end(); ++t) {
      float positions[3][3], uvs[3][2];
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = mesh.indices[3 * t + k];
        for (int a = 0; a < 3; ++a) positions[k][a] = mesh.positions[3 * std::size_t(v) + a];
        for (int a = 0; a < 2; ++a) uvs[k][a] = mesh.uvs[2 * std::size_t(v) + a];
      }
      records[t] = make_triangle_record(positions, uvs, map_of_triangle(mesh, t, map_count));
    }
  });
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
