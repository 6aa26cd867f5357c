#pragma once
// The unit quad the command-line tests build their glTF files around.

#include <cstdint>
#include <cstring>
#include <string>

namespace trs_test {

/// A 1 x 1 quad in the z = 0 plane facing +z, UVs equal to its positions, as glTF buffer bytes:
/// 4 float positions (offset 0), 4 float UVs (offset 48), 6 uint16 indices (offset 80).
inline std::string quad_gltf_buffer() {
  const float positions[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const float uvs[8] = {0, 0, 1, 0, 1, 1, 0, 1};
  const std::uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
  std::string bytes(sizeof positions + sizeof uvs + sizeof indices, '\0');
  std::memcpy(bytes.data(), positions, sizeof positions);
  std::memcpy(bytes.data() + sizeof positions, uvs, sizeof uvs);
  std::memcpy(bytes.data() + sizeof positions + sizeof uvs, indices, sizeof indices);
  return bytes;
}

/// The glTF members that describe that buffer: "bufferViews" and "accessors" (POSITION 0,
/// TEXCOORD_0 1, indices 2), to close a document's top-level object.
inline const std::string kQuadGltfViews = R"("bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                  {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                  {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
    {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}])";

}  // namespace trs_test
