#pragma once
// The punctual lights of a glTF document (KHR_lights_punctual; part of load_gltf_scene).

#include "scene_io/gltf_document.h"
#include "tracer/scene.h"

namespace tracer {

/// Lumens per watt: glTF's candela and lux over this are the renderer's W/sr and W/m^2, as
/// Blender's glTF importer converts them ("Standard" lighting mode).
inline constexpr double kLumensPerWatt = 683.0;

/// Appends a PunctualLight for every node of the default scene that places one.
void read_punctual_lights(const trs::gltf::Document& document, Scene& scene);

}  // namespace tracer
