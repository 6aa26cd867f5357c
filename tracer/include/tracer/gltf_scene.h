#pragma once
// Scenes from glTF 2.0 files (.gltf with its buffers and images, or .glb).

#include <filesystem>

#include "tracer/scene.h"

namespace tracer {

/// Loads the default scene: every triangle, strip and fan primitive in world space, the
/// metallic-roughness materials (with KHR_materials_emissive_strength) and their textures, and
/// the first camera of the node hierarchy.
///
/// - Normals: where no primitive has NORMAL, Mesh::normals stays empty (shading uses geometric
///   normals, as glTF asks: flat). Where some have, a primitive without gets flat normals: its
///   triangles get vertices of their own carrying the face normal.
/// - A primitive without a material gets glTF's default material, appended once after the
///   file's materials.
/// - Mirroring transforms (negative determinant) swap two corners of each triangle, so that the
///   front face stays counter-clockwise.
/// - Textures are decoded with scene_io's image codec (OpenImageIO, or stb_image and OpenEXR),
///   from their file or from the bytes embedded in the document; 8- and 16-bit colour textures
///   (base colour, emissive) from sRGB to linear, float ones as they are, metallic-roughness as
///   data. A texture used both as colour and as data is decoded once for each use. Only TEXCOORD_0 is read: a used texture on another set fails.
/// - The camera is the first node with a camera, depth first; it must be perspective.
///
/// Throws trs::FileError naming the file at fault (the glTF file, or a texture's own file) and
/// the problem.
Scene load_gltf_scene(const std::filesystem::path& file);

}  // namespace tracer
