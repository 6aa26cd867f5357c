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

#include <array>

namespace tracer {

class AlbedoTables {
 public:
  static constexpr int kMu = 64;         ///< grid points in sqrt(mu), from 0 to 1
  static constexpr int kRoughness = 32;  ///< grid points in r, from 0 to 1

  /// The tables, built on first use (thread-safe).
  static const AlbedoTables& get();

  float e1(float mu, float roughness) const { return lookup(e1_, mu, roughness); }
  float w(float mu, float roughness) const { return lookup(w_, mu, roughness); }
  float sheen(float mu, float roughness) const { return lookup(sheen_, mu, roughness); }
  float e1_average(float roughness) const { return lookup_average(e1_average_, roughness); }
  float w_average(float roughness) const { return lookup_average(w_average_, roughness); }

 private:
  using Table = std::array<float, kMu * kRoughness>;  ///< [r][sqrt(mu)]
  using Averages = std::array<float, kRoughness>;

  AlbedoTables();
  /// Bilinear in (sqrt(mu), r), both clamped to [0, 1].
  static float lookup(const Table& table, float mu, float roughness);
  static float lookup_average(const Averages& averages, float roughness);

  Table e1_{}, w_{}, sheen_{};
  Averages e1_average_{}, w_average_{};
};

}  // namespace tracer
