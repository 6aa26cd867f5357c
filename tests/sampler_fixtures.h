#pragma once
// Small meshes and maps shared by the tests, built in code so every case is visible in the test.

#include <cstdint>
#include <random>
#include <vector>

#include "lightsampler/mesh.h"

namespace trs_test {

/// A mesh that owns its arrays.
struct Mesh {
  std::vector<float> positions, uvs;
  std::vector<std::uint32_t> indices, triangle_maps;

  lightsampler::MeshView view() const { return {positions, uvs, indices, triangle_maps}; }

  void add_triangle(const float p[3][3], const float uv[3][2]) {
    for (int k = 0; k < 3; ++k) {
      indices.push_back(std::uint32_t(positions.size() / 3));
      positions.insert(positions.end(), p[k], p[k] + 3);
      uvs.insert(uvs.end(), uv[k], uv[k] + 2);
    }
  }
};

/// Axis-aligned quad in the z = 0 plane, [0, sx] x [0, sy], with UVs [u0, u1] x [v0, v1].
inline Mesh quad(float sx, float sy, float u0, float v0, float u1, float v1) {
  Mesh m;
  m.positions = {0, 0, 0, sx, 0, 0, sx, sy, 0, 0, sy, 0};
  m.uvs = {u0, v0, u1, v0, u1, v1, u0, v1};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

/// Random triangles with random world positions and UVs in [uv_lo, uv_hi]^2.
inline Mesh random_triangles(int count, float uv_lo, float uv_hi, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> pos(-1.0f, 1.0f), tex(uv_lo, uv_hi);
  Mesh m;
  for (int t = 0; t < count; ++t) {
    float p[3][3], uv[3][2];
    for (int k = 0; k < 3; ++k) {
      for (float& x : p[k]) x = pos(rng);
      for (float& x : uv[k]) x = tex(rng);
    }
    m.add_triangle(p, uv);
  }
  return m;
}

/// A map that owns its texels.
struct Map {
  std::vector<float> texels;
  std::uint32_t width, height;
  lightsampler::Addressing addressing = lightsampler::Addressing::wrap;
  float scale = 1.0f;

  lightsampler::DensityMapView view() const { return {texels, width, height, addressing, scale}; }
};

/// Random texels in [0, 1), a fraction of them zero (a sparse, structured-looking map).
inline Map random_map(std::uint32_t w, std::uint32_t h, double zero_fraction, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> value(0.0f, 1.0f);
  Map m{std::vector<float>(std::size_t(w) * h), w, h};
  for (float& t : m.texels) t = value(rng) < zero_fraction ? 0.0f : value(rng);
  return m;
}

}  // namespace trs_test
