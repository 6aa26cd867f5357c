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

}  // namespace trs_test
