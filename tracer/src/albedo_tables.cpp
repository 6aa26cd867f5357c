#include "tracer/albedo_tables.h"

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
constexpr int kStrata = 16;

/// The cosine of grid point k of the mu axis; mu = 0 is taken a hair above, where wo still sees
/// the surface.
float grid_mu(int k) {
  const float x = float(k) / float(kMu - 1);
  return std::max(x * x, 1e-6f);
}

float grid_roughness(int j) { return float(j) / float(kRoughness - 1); }

glm::vec3 direction(float mu) { return {std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu}; }

/// Calls f(u1, u2) at the midpoints of kStrata x kStrata strata of the unit square.
template <class F>
void for_strata(F&& f) {
  for (int a = 0; a < kStrata; ++a)
    for (int b = 0; b < kStrata; ++b) f((float(a) + 0.5f) / kStrata, (float(b) + 0.5f) / kStrata);
}

/// 2 times the integral of E(mu) mu dmu over [0, 1] for the E of one table row, piecewise linear in
/// x = sqrt(mu): 4 times the integral of E(x) x^3 dx, of degree 4 on each interval, which 3-point
/// Gauss-Legendre integrates exactly.
glm::vec2 cosine_average(const glm::vec2* row) {
  constexpr double kNodes[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
  constexpr double kWeights[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  glm::dvec2 sum(0.0);
  for (int k = 0; k + 1 < kMu; ++k) {
    const double h = 1.0 / (kMu - 1), x0 = k * h;
    for (int g = 0; g < 3; ++g) {
      const double t = 0.5 * (kNodes[g] + 1.0), x = x0 + t * h;
      sum += kWeights[g] * 0.5 * h * glm::mix(glm::dvec2(row[k]), glm::dvec2(row[k + 1]), t) * (x * x * x);
    }
  }
  return glm::vec2(4.0 * sum);
}

}  // namespace

const AlbedoTables& AlbedoTables::get() {
  static const AlbedoTables tables;
  return tables;
}

AlbedoTables::AlbedoTables() {
  for (int j = 0; j < kRoughness; ++j) {
    const Ggx ggx{std::max(grid_roughness(j) * grid_roughness(j), kMinAlpha)};
    for (int k = 0; k < kMu; ++k) {
      const glm::vec3 wo = direction(grid_mu(k));
      // Visible normals, each reflection weighing G2 / G1(wo).
      glm::dvec2 sum(0.0);
      for_strata([&](float u1, float u2) {
        const glm::vec3 h = ggx.sample_visible(wo, u1, u2);
        const glm::vec3 wi = 2.0f * glm::dot(wo, h) * h - wo;
        if (!(wi.z > 0.0f)) return;
        const double weight = ggx.g2(wo, wi) / ggx.g1(wo);
        sum += weight * glm::dvec2(1.0, std::pow(1.0 - std::clamp(double(glm::dot(wo, h)), 0.0, 1.0), 5.0));
      });
      ggx_[j * kMu + k] = glm::vec2(sum / double(kStrata * kStrata));
    }
    ggx_average_[j] = cosine_average(&ggx_[j * kMu]);
  }
}

AlbedoTables::Row<float> AlbedoTables::sheen(float roughness) {
  static const std::array<float, kMu * kRoughness> table = [] {
    std::array<float, kMu * kRoughness> es{};
    for (int j = 0; j < kRoughness; ++j) {
      const Sheen sheen(grid_roughness(j));
      for (int k = 0; k < kMu; ++k) {
        const glm::vec3 wo = direction(grid_mu(k));
        // Cosine-weighted wi, each weighing pi f.
        double sum = 0.0;
        for_strata([&](float u1, float u2) {
          const float r = std::sqrt(u1), phi = 2.0f * std::numbers::pi_v<float> * u2;
          const glm::vec3 wi(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u1)));
          sum += std::numbers::pi * sheen.reflection(wo, wi) / std::max(wi.z, 1e-6f);
        });
        es[j * kMu + k] = float(std::min(sum / double(kStrata * kStrata), 1.0));
      }
    }
    return es;
  }();
  return row(table.data(), roughness);
}

template <class T>
AlbedoTables::Row<T> AlbedoTables::row(const T* table, float roughness) {
  const float y = std::clamp(roughness, 0.0f, 1.0f) * (kRoughness - 1);
  const int y0 = std::min(int(y), kRoughness - 2);
  return {table + y0 * kMu, table + (y0 + 1) * kMu, y - float(y0)};
}

template <class T>
T AlbedoTables::Row<T>::at(float mu) const {
  const float x = std::sqrt(std::clamp(mu, 0.0f, 1.0f)) * (kMu - 1);
  const int x0 = std::min(int(x), kMu - 2);
  const float fx = x - float(x0);
  const T a = low[x0] + (low[x0 + 1] - low[x0]) * fx;
  const T b = high[x0] + (high[x0 + 1] - high[x0]) * fx;
  return a + (b - a) * t;
}

template struct AlbedoTables::Row<glm::vec2>;
template struct AlbedoTables::Row<float>;
template AlbedoTables::Row<glm::vec2> AlbedoTables::row(const glm::vec2*, float);
template AlbedoTables::Row<float> AlbedoTables::row(const float*, float);

glm::vec2 AlbedoTables::ggx_average(float roughness) const {
  const float y = std::clamp(roughness, 0.0f, 1.0f) * (kRoughness - 1);
  const int y0 = std::min(int(y), kRoughness - 2);
  return glm::mix(ggx_average_[y0], ggx_average_[y0 + 1], y - float(y0));
}

}  // namespace tracer
