#include "meshes.h"

#include <charconv>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "dataset_file.h"

namespace trs_bench {

namespace {

constexpr double kPi = std::numbers::pi;

/// Monotone warp of [0,1] onto itself: slope varies between 1 - a and 1 + a over `periods` waves.
double warp(double x, double a, int periods) {
  return x - a * std::sin(2 * kPi * periods * x) / (2 * kPi * periods);
}

std::uint64_t parse_count(std::string_view text) {
  double multiplier = 1;
  if (!text.empty() && (text.back() == 'k' || text.back() == 'K')) multiplier = 1e3;
  if (!text.empty() && text.back() == 'M') multiplier = 1e6;
  if (multiplier != 1) text.remove_suffix(1);
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !(value * multiplier >= 1))
    throw std::invalid_argument("bad count");
  return static_cast<std::uint64_t>(std::llround(value * multiplier));
}

}  // namespace

MeshSpec parse_mesh_spec(std::string_view text) {
  const auto colon = text.find(':');
  const std::string_view kind = text.substr(0, colon);
  MeshSpec spec;
  if (kind == "file") {
    if (colon == std::string_view::npos || colon + 1 == text.size())
      throw std::invalid_argument("mesh '" + std::string(text) + "': expected file:PATH");
    spec.kind = MeshKind::file;
    spec.file = std::string(text.substr(colon + 1));
    return spec;
  }
  if (kind == "grid") {
    spec.kind = MeshKind::grid;
  } else if (kind == "sphere") {
    spec.kind = MeshKind::sphere;
  } else if (kind == "torus") {
    spec.kind = MeshKind::torus;
  } else {
    throw std::invalid_argument("mesh '" + std::string(text) +
                                "': kind must be grid, sphere, torus or file");
  }
  if (colon == std::string_view::npos)
    throw std::invalid_argument("mesh '" + std::string(text) +
                                "': expected KIND:COUNT, e.g. grid:100k");
  try {
    spec.triangles = parse_count(text.substr(colon + 1));
  } catch (const std::invalid_argument&) {
    throw std::invalid_argument(
        "mesh '" + std::string(text) +
        "': triangle count must be a positive number, optionally with k or M");
  }
  return spec;
}

Mesh make_warped_grid(std::uint64_t triangles) {
  // n x n quads, two triangles each.
  const auto n = std::max<std::uint32_t>(1, std::uint32_t(std::lround(std::sqrt(triangles / 2.0))));
  Mesh mesh;
  mesh.name = "grid";
  mesh.positions.reserve(3 * std::size_t(n + 1) * (n + 1));
  mesh.uvs.reserve(2 * std::size_t(n + 1) * (n + 1));
  for (std::uint32_t j = 0; j <= n; ++j) {
    for (std::uint32_t i = 0; i <= n; ++i) {
      const double s = double(i) / n, t = double(j) / n;
      // Separable warps (cell widths vary ~9x) plus a small shear so that edges are not all
      // axis-aligned in texel space. Both terms vanish on the border: UVs cover [0,1]^2 exactly,
      // and the slopes stay positive, so no triangle flips.
      const double u = warp(s, 0.8, 1) + 0.05 * std::sin(kPi * t) * s * (1 - s);
      const double v = warp(t, 0.8, 2) + 0.05 * std::sin(kPi * s) * t * (1 - t);
      mesh.uvs.insert(mesh.uvs.end(), {float(u), float(v)});
      // World space follows the unwarped grid, so world area per UV area varies across the mesh.
      const double height = 0.1 * std::sin(3 * kPi * s) * std::sin(2 * kPi * t);
      mesh.positions.insert(mesh.positions.end(), {float(2 * s), float(t), float(height)});
    }
  }
  mesh.indices.reserve(6 * std::size_t(n) * n);
  for (std::uint32_t j = 0; j < n; ++j) {
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t v00 = j * (n + 1) + i, v10 = v00 + 1, v01 = v00 + n + 1, v11 = v01 + 1;
      // Alternate the diagonal so that both triangle orientations occur.
      if ((i + j) % 2 == 0) {
        mesh.indices.insert(mesh.indices.end(), {v00, v10, v11, v00, v11, v01});
      } else {
        mesh.indices.insert(mesh.indices.end(), {v00, v10, v01, v10, v11, v01});
      }
    }
  }
  return mesh;
}

Mesh make_uv_sphere(std::uint64_t triangles) {
  // slices = 2 * stacks gives 2 * slices * (stacks - 1) = 4 * stacks * (stacks - 1) triangles.
  const auto stacks =
      std::max<std::uint32_t>(2, std::uint32_t(std::lround((1 + std::sqrt(1.0 + triangles)) / 2)));
  const std::uint32_t slices = 2 * stacks;
  const std::uint32_t columns = slices + 1;  // the seam column is duplicated for its u = 1
  Mesh mesh;
  mesh.name = "sphere";
  for (std::uint32_t j = 0; j <= stacks; ++j) {
    const double theta = kPi * j / stacks;
    for (std::uint32_t i = 0; i <= slices; ++i) {
      const double phi = 2 * kPi * i / slices;
      mesh.positions.insert(mesh.positions.end(),
                            {float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                             float(std::sin(theta) * std::sin(phi))});
      mesh.uvs.insert(mesh.uvs.end(), {float(double(i) / slices), float(double(j) / stacks)});
    }
  }
  const auto vertex = [columns](std::uint32_t i, std::uint32_t j) { return j * columns + i; };
  for (std::uint32_t j = 0; j < stacks; ++j) {
    for (std::uint32_t i = 0; i < slices; ++i) {
      const std::uint32_t a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i, j + 1),
                          d = vertex(i + 1, j + 1);
      // One triangle per slice at each pole, where a quad would have a zero-area half.
      if (j != 0) mesh.indices.insert(mesh.indices.end(), {a, c, b});
      if (j != stacks - 1) mesh.indices.insert(mesh.indices.end(), {b, c, d});
    }
  }
  return mesh;
}

Mesh make_displaced_torus(std::uint64_t triangles) {
  // 4 charts of n x n quads, two triangles each; a chart's vertices are its own (UV seams).
  const auto n = std::max<std::uint32_t>(1, std::uint32_t(std::lround(std::sqrt(triangles / 8.0))));
  constexpr double kMajor = 1, kMinor = 0.35, kGap = 0.02;
  Mesh mesh;
  mesh.name = "torus";
  for (std::uint32_t chart = 0; chart < 4; ++chart) {
    const auto base = std::uint32_t(mesh.positions.size() / 3);
    for (std::uint32_t j = 0; j <= n; ++j) {
      for (std::uint32_t i = 0; i <= n; ++i) {
        const double s = double(i) / n, t = double(j) / n;  // along the ring, around the tube
        const double phi = kPi / 2 * (chart + s), theta = 2 * kPi * t;
        const double r = kMinor * (1 + 0.15 * std::sin(5 * phi) * std::sin(3 * theta));
        const double ring = kMajor + r * std::cos(theta);
        mesh.positions.insert(mesh.positions.end(), {float(ring * std::cos(phi)),
                                                     float(r * std::sin(theta)),
                                                     float(ring * std::sin(phi))});
        // Chart 0 as it is, 1 turned, 2 mirrored, 3 turned and mirrored; each in its atlas tile.
        double a = chart % 2 ? t : s, b = chart % 2 ? s : t;
        if (chart >= 2) a = 1 - a;
        const double u = 0.5 * (chart % 2) + kGap + (0.5 - 2 * kGap) * a;
        const double v = 0.5 * (chart / 2) + kGap + (0.5 - 2 * kGap) * b;
        mesh.uvs.insert(mesh.uvs.end(), {float(u), float(v)});
      }
    }
    for (std::uint32_t j = 0; j < n; ++j) {
      for (std::uint32_t i = 0; i < n; ++i) {
        const std::uint32_t v00 = base + j * (n + 1) + i, v10 = v00 + 1, v01 = v00 + n + 1,
                            v11 = v01 + 1;
        mesh.indices.insert(mesh.indices.end(), {v00, v10, v11, v00, v11, v01});
      }
    }
  }
  return mesh;
}

Mesh make_mesh(const MeshSpec& spec) {
  switch (spec.kind) {
    case MeshKind::grid:
      return make_warped_grid(spec.triangles);
    case MeshKind::sphere:
      return make_uv_sphere(spec.triangles);
    case MeshKind::torus:
      return make_displaced_torus(spec.triangles);
    case MeshKind::file:
      return read_dataset_mesh(spec.file);
  }
  throw std::logic_error("unknown mesh kind");
}

}  // namespace trs_bench
