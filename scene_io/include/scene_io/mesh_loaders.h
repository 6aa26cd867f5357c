#pragma once
// The per-format loaders behind load_mesh (internal to trs_tool_support). Each fills positions,
// UVs (library convention) and indices; load_mesh checks what is common to all formats.

#include <filesystem>
#include <optional>

#include "scene_io/mesh_io.h"

namespace trs {

MeshData load_obj(const std::filesystem::path& file);
/// `material`: only the primitives that use it.
MeshData load_gltf(const std::filesystem::path& file, std::optional<int> material = std::nullopt);

}  // namespace trs
