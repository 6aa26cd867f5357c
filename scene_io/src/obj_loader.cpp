// Wavefront OBJ: positions and texture coordinates are indexed separately per face corner, so a
// vertex of the result is a unique (v, vt) pair. tinyobjloader parses without triangulating:
// it triangulates without checking indices (an out-of-range index would read out of bounds), so
// indices are checked here first and polygons triangulated by triangulate_polygon. It also reads
// a number it cannot parse ("nan", "inf", "1e999", "x") as 0 without a word, so the numbers of
// 'v' and 'vt' lines are checked here too.

#include <tiny_obj_loader.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <string_view>
#include <unordered_map>

#include "scene_io/file_error.h"
#include "scene_io/mesh_loaders.h"
#include "scene_io/polygon_triangulation.h"

namespace trs {
namespace {

std::string first_line(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
  return line;
}

/// Builds the unique (v, vt) vertices of the result, in order of first use.
class VertexTable {
 public:
  VertexTable(const std::filesystem::path& file, const tinyobj::attrib_t& attrib, MeshData& mesh)
      : file_(file), attrib_(attrib), mesh_(mesh) {}

  std::uint32_t vertex(int v, int vt) {
    const std::uint64_t key = (std::uint64_t(std::uint32_t(v)) << 32) | std::uint32_t(vt);
    const auto [it, inserted] = ids_.try_emplace(key, std::uint32_t(0));
    if (inserted) {
      if (mesh_.positions.size() / 3 >= std::numeric_limits<std::uint32_t>::max()) {
        throw FileError(file_, "more than 2^32 - 1 distinct (v, vt) vertices");
      }
      it->second = static_cast<std::uint32_t>(mesh_.positions.size() / 3);
      const float* p = &attrib_.vertices[3 * std::size_t(v)];
      mesh_.positions.insert(mesh_.positions.end(), p, p + 3);
      const float* t = &attrib_.texcoords[2 * std::size_t(vt)];
      mesh_.uvs.push_back(t[0]);
      mesh_.uvs.push_back(1.0f - t[1]);  // OBJ's v points up; the library's row 0 is at v = 0
    }
    return it->second;
  }

 private:
  const std::filesystem::path& file_;
  const tinyobj::attrib_t& attrib_;
  MeshData& mesh_;
  std::unordered_map<std::uint64_t, std::uint32_t> ids_;
};

/// Throws unless every corner of face `face_number` (1-based, over the whole file) names an
/// existing position and texture coordinate.
void check_face(const std::filesystem::path& file, const tinyobj::attrib_t& attrib,
                const tinyobj::index_t* corners, unsigned count, std::size_t face_number) {
  const auto position_count = attrib.vertices.size() / 3;
  const auto texcoord_count = attrib.texcoords.size() / 2;
  const std::string face = "face " + std::to_string(face_number);
  for (unsigned k = 0; k < count; ++k) {
    const tinyobj::index_t& c = corners[k];
    // tinyobjloader marks a missing index with -1 (a face without positions fails to parse),
    // and resolves a relative index that points before the first element to below 0.
    if (c.vertex_index < 0) {
      throw FileError(file,
                      face + " has a relative vertex index that points before the first vertex");
    }
    if (std::size_t(c.vertex_index) >= position_count) {
      throw FileError(file, face + " uses vertex " + std::to_string(c.vertex_index + 1L) +
                                ", but the file has " + std::to_string(position_count) +
                                " (out-of-range index; truncated file?)");
    }
    if (c.texcoord_index == -1)
      throw FileError(file, face + " has a corner without a texture coordinate");
    if (c.texcoord_index < 0) {
      throw FileError(
          file,
          face + " has a relative texture coordinate index that points before the first 'vt'");
    }
    if (std::size_t(c.texcoord_index) >= texcoord_count) {
      throw FileError(file, face + " uses texture coordinate " +
                                std::to_string(c.texcoord_index + 1L) + ", but the file has " +
                                std::to_string(texcoord_count) +
                                " (out-of-range index; truncated file?)");
    }
  }
}

/// Throws unless every field of every 'v' (position) and 'vt' (texture coordinate) line is a
/// finite number, naming the element, its 1-based index and the line.
void check_vertex_numbers(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::size_t line_number = 0, positions = 0, texcoords = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    std::string_view rest(line);
    rest.remove_prefix(std::min(rest.find_first_not_of(" \t"), rest.size()));
    const bool position = rest.starts_with("v ") || rest.starts_with("v\t");
    const bool texcoord = rest.starts_with("vt ") || rest.starts_with("vt\t");
    if (!position && !texcoord) continue;
    const std::string element = position ? "vertex " + std::to_string(++positions)
                                          : "texture coordinate " + std::to_string(++texcoords);
    rest.remove_prefix(position ? 1 : 2);
    for (;;) {
      const std::size_t start = rest.find_first_not_of(" \t\r");
      if (start == std::string_view::npos) break;
      rest.remove_prefix(start);
      const std::string_view field = rest.substr(0, rest.find_first_of(" \t\r"));
      // from_chars takes no leading '+', which OBJ writers may emit.
      const std::string_view digits = field.starts_with('+') ? field.substr(1) : field;
      double value = 0;
      const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
      if (error != std::errc() || end != digits.data() + digits.size() || !std::isfinite(value)) {
        throw FileError(file, element + " (line " + std::to_string(line_number) + "): '" +
                                  std::string(field) + "' is not a finite number");
      }
      rest.remove_prefix(field.size());
    }
  }
}

}  // namespace

MeshData load_obj(const std::filesystem::path& file) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(file.string(), config)) {
    throw FileError(file, "malformed OBJ: " + first_line(reader.Error()));
  }
  // Faces with fewer than 3 corners are dropped with only a warning; they mean a broken file
  // (typically one cut off in the middle of its last line).
  if (reader.Warning().find("Degenerated face") != std::string::npos) {
    throw FileError(file, "malformed OBJ: a face has fewer than 3 corners (truncated file?)");
  }
  check_vertex_numbers(file);
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  if (attrib.texcoords.empty()) throw FileError(file, "no texture coordinates (no 'vt' lines)");

  MeshData mesh;
  mesh.file = file;
  mesh.file_uv_origin = UvOrigin::bottom;
  VertexTable table(file, attrib, mesh);
  std::vector<lightsampler::Float3> polygon;
  std::size_t face_number = 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    std::size_t offset = 0;
    for (const unsigned char count : shape.mesh.num_face_vertices) {
      const tinyobj::index_t* corners = &shape.mesh.indices[offset];
      offset += count;
      check_face(file, attrib, corners, count, ++face_number);
      if (count == 3) {
        for (unsigned k = 0; k < 3; ++k) {
          mesh.indices.push_back(table.vertex(corners[k].vertex_index, corners[k].texcoord_index));
        }
        continue;
      }
      polygon.clear();
      for (unsigned k = 0; k < count; ++k) {
        const float* p = &attrib.vertices[3 * std::size_t(corners[k].vertex_index)];
        polygon.push_back({p[0], p[1], p[2]});
      }
      for (const auto& triangle : triangulate_polygon(polygon)) {
        for (const std::uint32_t k : triangle) {
          mesh.indices.push_back(table.vertex(corners[k].vertex_index, corners[k].texcoord_index));
        }
      }
    }
  }
  return mesh;
}

}  // namespace trs
