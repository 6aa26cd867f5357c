#include "gltf_lights.h"

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

namespace tracer {
namespace {

using trs::gltf::Document;

/// The number `key` of `object`, or `fallback` where it is absent.
double number_or(const tinygltf::Value& object, const char* key, double fallback) {
  if (!object.Has(key)) return fallback;
  const tinygltf::Value& v = object.Get(key);
  return v.IsNumber() ? v.GetNumberAsDouble() : std::nan("");
}

/// The light node `node` places, its index checked; -1 where it places none.
int light_index(const Document& document, const tinygltf::Node& node, const std::string& what) {
  const auto extension = node.extensions.find("KHR_lights_punctual");
  if (extension == node.extensions.end()) return -1;
  const double index = number_or(extension->second, "light", std::nan(""));
  const std::size_t count = document.model().lights.size();
  if (!(index >= 0.0 && index < double(count) && index == std::floor(index))) {
    std::ostringstream text;
    text << what << ": KHR_lights_punctual light ";
    if (std::isnan(index))
      text << "(none given)";
    else
      text << index;
    text << " is not one of the file's " << count << " lights";
    document.fail(text.str());
  }
  return int(index);
}

PunctualLight::Kind kind_of(const Document& document, const tinygltf::Light& source, const std::string& what) {
  if (source.type == "point") return PunctualLight::Kind::point;
  if (source.type == "spot") return PunctualLight::Kind::spot;
  if (source.type == "directional") return PunctualLight::Kind::directional;
  document.fail(what + ": unknown type '" + source.type + "'");
}

glm::vec3 colour_of(const Document& document, const tinygltf::Light& source, const std::string& what) {
  if (source.color.empty()) return glm::vec3(1.0f);
  if (source.color.size() != 3) document.fail(what + ": color must have 3 components");
  const glm::dvec3 c(source.color[0], source.color[1], source.color[2]);
  if (!(c.r >= 0.0 && c.g >= 0.0 && c.b >= 0.0 && std::isfinite(c.r + c.g + c.b)))
    document.fail(what + ": color must be finite and non-negative");
  return glm::vec3(c);
}

/// The spot's cones (glTF: 0 <= inner < outer <= pi / 2).
void read_cones(const Document& document, const tinygltf::Light& source, const std::string& what,
                PunctualLight& light) {
  const double inner = source.spot.innerConeAngle, outer = source.spot.outerConeAngle;
  if (!(inner >= 0.0 && inner < outer && outer <= std::numbers::pi / 2))
    document.fail(what + ": the spot's cone angles must satisfy 0 <= inner < outer <= pi/2");
  light.cos_inner = float(std::cos(inner));
  light.cos_outer = float(std::cos(outer));
}

PunctualLight make_light(const Document& document, const tinygltf::Light& source, const glm::dmat4& world,
                         const std::string& what) {
  PunctualLight light;
  light.kind = kind_of(document, source, what);
  light.name = what;
  if (!(source.intensity >= 0.0 && std::isfinite(source.intensity)))
    document.fail(what + ": intensity must be finite and non-negative");
  light.intensity = glm::vec3(glm::dvec3(colour_of(document, source, what)) * (source.intensity / kLumensPerWatt));
  if (!(source.range >= 0.0 && std::isfinite(source.range)))
    document.fail(what + ": range must be positive where it is given");
  light.range = float(source.range);
  if (light.kind == PunctualLight::Kind::spot) read_cones(document, source, what, light);
  // Lights shine down their node's -Z; the node's scale moves them but does not change them.
  light.position = glm::vec3(world[3]);
  const glm::dvec3 down = glm::dvec3(world * glm::dvec4(0.0, 0.0, -1.0, 0.0));
  if (!(glm::length(down) > 0.0)) document.fail(what + ": its node is scaled to zero, so it points nowhere");
  light.direction = glm::vec3(glm::normalize(down));
  return light;
}

}  // namespace

void read_punctual_lights(const Document& document, Scene& scene) {
  const auto& lights = document.model().lights;
  document.for_each_node([&](int index, const tinygltf::Node& node, const glm::dmat4& world) {
    const int light = light_index(document, node, "node " + std::to_string(index));
    if (light < 0) return;
    const tinygltf::Light& source = lights[std::size_t(light)];
    const std::string what =
        "light " + std::to_string(light) + (source.name.empty() ? "" : " '" + source.name + "'");
    scene.lights.push_back(make_light(document, source, world, what));
  });
}

}  // namespace tracer
