#pragma once
// The materials of a glTF document and the textures they use (part of load_gltf_scene).

#include "scene_io/gltf_document.h"
#include "tracer/scene.h"

namespace tracer {

/// Appends one Material per glTF material (so glTF's material indices stay valid) and the
/// textures they use, decoded to linear where they hold colour.
void read_materials(const trs::gltf::Document& document, Scene& scene);

}  // namespace tracer
