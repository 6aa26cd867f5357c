#pragma once
// Directional albedos of the BSDF's glossy lobes, tabulated once per process by quadrature, for
// the layering that keeps the glTF material energy-conserving and reciprocal (Kulla and Conty
// 2017, "Revisiting Physically Based Shading at Imageworks", as glTF 2.0's Appendix B suggests):
//
//   E1(mu, r)  = the integral of a GGX reflection lobe's f |cos wi| over wi, Fresnel 1;
//   W(mu, r)   = the same weighted by Schlick's (1 - wo.h)^5, so that a lobe of Fresnel
//                F = f0 + (f90 - f0) (1 - wo.h)^5 reflects f0 (E1 - W) + f90 W;
//   Es(mu, r)  = the sheen lobe's (sheen.h), sheen colour white;
//
// mu the cosine of wo, r the perceptual roughness (GGX alpha = max(r^2, kMinAlpha)); and the
// cosine-weighted averages of E1 and W over mu, 2 times the integral of E mu dmu, of the tables
// as they interpolate. The mu axis is uniform in sqrt(mu): a smooth lobe's albedo drops within a
// cosine of about alpha of the horizon, where Smith's masking takes over.
//
// A surface point has one roughness per lobe: a Row fixes it once, and each lookup then
// interpolates along mu alone.

#include <array>

#include <glm/glm.hpp>

namespace tracer {

class AlbedoTables {
 public:
  static constexpr int kMu = 64;         ///< grid points in sqrt(mu), from 0 to 1
  static constexpr int kRoughness = 32;  ///< grid points in r, from 0 to 1

  /// The tables at one roughness, between two of their rows.
  template <class T>
  struct Row {
    const T* low;
    const T* high;
    float t;  ///< from low to high

    /// Linear in sqrt(mu), mu clamped to [0, 1].
    T at(float mu) const;
  };

  /// The tables, built on first use (thread-safe).
  static const AlbedoTables& get();

  /// E1 and W (x and y) of a GGX lobe of roughness r.
  Row<glm::vec2> ggx(float roughness) const { return row(ggx_.data(), roughness); }
  /// Es of a sheen of roughness r: a table of its own, built on first use (most scenes have no
  /// sheen, and its lobe is the costly one to integrate).
  static Row<float> sheen(float roughness);
  /// The cosine-weighted averages of E1 and W (x and y) at roughness r.
  glm::vec2 ggx_average(float roughness) const;

 private:
  AlbedoTables();
  template <class T>
  static Row<T> row(const T* table, float roughness);

  std::array<glm::vec2, kMu * kRoughness> ggx_{};  ///< [r][sqrt(mu)]: (E1, W)
  std::array<glm::vec2, kRoughness> ggx_average_{};
};

}  // namespace tracer
