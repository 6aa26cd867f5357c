#include "tracer/light.h"

#include <numbers>

#include "tracer/emitters.h"

namespace tracer {

Light::Kind Light::kind() const {
  if (index_ < emitters_->count()) return Kind::triangle;
  switch (emitters_->punctual()[index_ - emitters_->count()].kind) {
    case PunctualLight::Kind::point: return Kind::point;
    case PunctualLight::Kind::spot: return Kind::spot;
    case PunctualLight::Kind::directional: return Kind::directional;
  }
  return Kind::point;
}

double Light::power() const {
  const Emitters& e = *emitters_;
  if (index_ >= e.count()) return e.punctual().power(index_ - e.count());
  return std::numbers::pi * (e.two_sided(index_) ? 2.0 : 1.0) * e.light_density()[index_];
}

LightPoint Light::point(float b1, float b2, float pdf, float mis_pdf) const {
  const Emitters& e = *emitters_;
  const glm::vec3 radiance = e.emission(index_, b1, b2) * e.opacity(index_, b1, b2);
  return {e.position(index_, b1, b2), pdf, e.normal(index_), mis_pdf, radiance, index_, b1, b2, e.two_sided(index_)};
}

std::optional<LightLiSample> Light::sample_li(const LightPoint& point, const ShadingPoint& at) const {
  const glm::vec3 to_light = point.position - at.position;
  const float distance = glm::length(to_light);
  if (!(distance > 0.0f)) return std::nullopt;
  const glm::vec3 wi = to_light / distance;
  const float cos_light = glm::dot(-wi, point.normal);
  return LightLiSample{
      .li = point.radiance_towards(-wi) * emitters_->coat_transmittance(index_, point.b1, point.b2, -wi),
      .wi = wi,
      .distance = distance,
      .pdf = solid_angle_density(point.pdf, distance, cos_light),
      .mis_pdf = solid_angle_density(point.mis_pdf, distance, cos_light),
      .position = point.position,
      .normal = point.normal,
      .light = index_,
      .b1 = point.b1,
      .b2 = point.b2};
}

std::optional<LightLiSample> Light::sample_li(double pmf, const ShadingPoint& at) const {
  const std::uint32_t punctual = index_ - emitters_->count();
  const PunctualLi li = emitters_->punctual().li(punctual, at.position);
  if (!(li.li.r > 0.0f || li.li.g > 0.0f || li.li.b > 0.0f)) return std::nullopt;
  return LightLiSample{.li = li.li,
                       .wi = li.wi,
                       .distance = li.distance,
                       .pdf = float(pmf),
                       .mis_pdf = 0.0f,
                       .position = emitters_->punctual()[punctual].position,
                       .normal = glm::vec3(0.0f),
                       .light = index_,
                       .delta = true};
}

float Light::pdf_li(float area_density, glm::vec3 wo, float distance) const {
  return solid_angle_density(area_density, distance, glm::dot(wo, emitters_->normal(index_)));
}

}  // namespace tracer
