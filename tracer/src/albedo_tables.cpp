#include "albedo_tables.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/glm.hpp>

#include "microfacet.h"
#include "sheen.h"

namespace tracer {
namespace {

constexpr int kMu = AlbedoTables::kMu, kRoughness = AlbedoTables::kRoughness;
/// Stratified draws per table entry, per axis.
constexpr int kStrata = 32;

/// The cosine of grid point k of the mu axis; mu = 0 is taken a hair above, where wo still sees
/// the surface.
float grid_mu(int k) {
  const float x = float(k) / float(kMu - 1);
  return std::max(x * x, 1e-6f);
}

glm::vec3 direction(float mu) { return {std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu}; }

/// 2 times the integral of E(mu) mu dmu over [0, 1] for the E of one table row, piecewise linear in
/// x = sqrt(mu): 4 times the integral of E(x) x^3 dx, of degree 4 on each interval, which 3-point
/// Gauss-Legendre integrates exactly.
float cosine_average(const float* row) {
  constexpr double kNodes[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
  constexpr double kWeights[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  double sum = 0;
  for (int k = 0; k + 1 < kMu; ++k) {
    const double h = 1.0 / (kMu - 1), x0 = k * h;
    for (int g = 0; g < 3; ++g) {
      const double t = 0.5 * (kNodes[g] + 1.0), x = x0 + t * h;
      sum += kWeights[g] * 0.5 * h * std::lerp(double(row[k]), double(row[k + 1]), t) * x * x * x;
    }
  }
  return float(4.0 * sum);
}

}  // namespace

const AlbedoTables& AlbedoTables::get() {
  static const AlbedoTables tables;
  return tables;
}

AlbedoTables::AlbedoTables() {
  for (int j = 0; j < kRoughness; ++j) {
    const float roughness = float(j) / float(kRoughness - 1);
    const Ggx ggx{std::max(roughness * roughness, kMinAlpha)};
    const Sheen sheen(roughness);
    for (int k = 0; k < kMu; ++k) {
      const glm::vec3 wo = direction(grid_mu(k));
      // GGX: visible normals, each reflection weighing G2 / G1(wo); sheen: cosine-weighted wi,
      // each weighing pi f. Midpoints of kStrata x kStrata strata.
      double e1 = 0, w = 0, es = 0;
      for (int a = 0; a < kStrata; ++a) {
        for (int b = 0; b < kStrata; ++b) {
          const float u1 = (float(a) + 0.5f) / kStrata, u2 = (float(b) + 0.5f) / kStrata;
          const glm::vec3 h = ggx.sample_visible(wo, u1, u2);
          const glm::vec3 wi = 2.0f * glm::dot(wo, h) * h - wo;
          if (wi.z > 0.0f) {
            const double weight = ggx.g2(wo, wi) / ggx.g1(wo);
            e1 += weight;
            w += weight * std::pow(1.0 - std::clamp(double(glm::dot(wo, h)), 0.0, 1.0), 5.0);
          }
          const float r = std::sqrt(u1), phi = 2.0f * std::numbers::pi_v<float> * u2;
          const glm::vec3 cosine(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u1)));
          es += std::numbers::pi * sheen.reflection(wo, cosine) / std::max(cosine.z, 1e-6f);
        }
      }
      const double n = double(kStrata) * kStrata;
      e1_[j * kMu + k] = float(e1 / n);
      w_[j * kMu + k] = float(w / n);
      sheen_[j * kMu + k] = float(std::min(es / n, 1.0));
    }
    e1_average_[j] = cosine_average(&e1_[j * kMu]);
    w_average_[j] = cosine_average(&w_[j * kMu]);
  }
}

float AlbedoTables::lookup(const Table& table, float mu, float roughness) {
  const float x = std::sqrt(std::clamp(mu, 0.0f, 1.0f)) * (kMu - 1);
  const float y = std::clamp(roughness, 0.0f, 1.0f) * (kRoughness - 1);
  const int x0 = std::min(int(x), kMu - 2), y0 = std::min(int(y), kRoughness - 2);
  const float fx = x - x0, fy = y - y0;
  const float* r0 = &table[y0 * kMu + x0];
  const float* r1 = r0 + kMu;
  return std::lerp(std::lerp(r0[0], r0[1], fx), std::lerp(r1[0], r1[1], fx), fy);
}

float AlbedoTables::lookup_average(const Averages& averages, float roughness) {
  const float y = std::clamp(roughness, 0.0f, 1.0f) * (kRoughness - 1);
  const int y0 = std::min(int(y), kRoughness - 2);
  return std::lerp(averages[y0], averages[y0 + 1], y - y0);
}

}  // namespace tracer
