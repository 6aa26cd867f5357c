#include "tracer/gltf_scene.h"

#include <array>
#include <chrono>
#include <cmath>
#include <glm/gtc/matrix_inverse.hpp>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "scene_io/gltf_document.h"
#include "scene_io/input_file.h"
#include "gltf_lights.h"
#include "gltf_materials.h"

namespace tracer {
namespace {

using trs::gltf::Document;

/// One primitive's vertices in world space, before they join the scene's mesh.
struct Vertices {
  std::vector<glm::vec3> positions;
  std::optional<std::vector<glm::vec3>> normals;
  std::array<std::vector<glm::vec2>, kUvSets> uvs;  ///< (0, 0) where the primitive has no such set
  std::optional<std::vector<glm::vec4>> tangents;
  std::vector<std::uint32_t> corners;  ///< 3 per triangle, into the vectors above
};

/// Which attributes some primitive of the scene has: the mesh then holds them for every vertex.
struct Attributes {
  bool normals = false;
  bool tangents = false;
  std::array<bool, kUvSets> uv_sets{};
};

std::string uv_set_name(std::size_t set) { return "TEXCOORD_" + std::to_string(set); }

template <class Vector>
void check_finite(const std::vector<Vector>& values, const Document& document,
                  const std::string& what) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    for (int k = 0; k < Vector::length(); ++k) {
      if (!std::isfinite(values[i][k]))
        document.fail(what + " " + std::to_string(i) + " is not finite");
    }
  }
}

Vertices world_vertices(const Document& document, const tinygltf::Primitive& primitive,
                        const glm::dmat4& world, const std::string& what) {
  Vertices v;
  v.positions = document.positions(primitive, what);
  const std::size_t count = v.positions.size();
  v.normals = document.vec3_attribute(primitive, "NORMAL", count, what);
  for (std::size_t set = 0; set < kUvSets; ++set) {
    v.uvs[set] = document.vec2_attribute(primitive, uv_set_name(set), count, what)
                     .value_or(std::vector<glm::vec2>(count, glm::vec2(0.0f)));
    check_finite(v.uvs[set], document, what + " " + uv_set_name(set));
  }
  v.tangents = document.vec4_attribute(primitive, "TANGENT", count, what);
  v.corners = document.triangles(primitive, count, what);
  check_finite(v.positions, document, what + " POSITION");

  for (glm::vec3& p : v.positions) p = glm::vec3(world * glm::dvec4(p, 1.0));
  const glm::dmat3 linear(world);
  if (v.normals) {
    check_finite(*v.normals, document, what + " NORMAL");
    const glm::dmat3 normal_matrix = glm::inverseTranspose(linear);  // linear is invertible
    for (std::size_t i = 0; i < v.normals->size(); ++i) {
      const glm::dvec3 normal = normal_matrix * glm::dvec3((*v.normals)[i]);
      if (glm::length(normal) == 0.0)
        document.fail(what + " NORMAL " + std::to_string(i) + " is zero");
      (*v.normals)[i] = glm::vec3(glm::normalize(normal));
    }
  }
  if (v.tangents) {
    check_finite(*v.tangents, document, what + " TANGENT");
    // A mirroring transform turns the bitangent, cross(normal, tangent) w, the other way.
    const float handedness = glm::determinant(linear) < 0.0 ? -1.0f : 1.0f;
    for (glm::vec4& t : *v.tangents) {
      const glm::dvec3 tangent = linear * glm::dvec3(t);
      // A zero tangent (a degenerate UV mapping) falls back to the UVs' own, as an absent one.
      t = glm::length(tangent) > 0.0 ? glm::vec4(glm::vec3(glm::normalize(tangent)), handedness * (t.w < 0.0f ? -1.0f : 1.0f))
                                     : glm::vec4(0.0f);
    }
  }
  if (glm::determinant(linear) < 0.0) {
    for (std::size_t t = 0; t < v.corners.size(); t += 3)
      std::swap(v.corners[t + 1], v.corners[t + 2]);
  }
  return v;
}

/// Gives each triangle vertices of its own carrying its face normal: flat shading for a
/// primitive without normals in a mesh that has them.
Vertices with_face_normals(const Vertices& shared) {
  Vertices flat;
  flat.normals.emplace();
  if (shared.tangents) flat.tangents.emplace();
  for (std::size_t t = 0; t < shared.corners.size(); t += 3) {
    const glm::vec3 a = shared.positions[shared.corners[t]];
    const glm::vec3 b = shared.positions[shared.corners[t + 1]];
    const glm::vec3 c = shared.positions[shared.corners[t + 2]];
    const glm::vec3 cross = glm::cross(b - a, c - a);
    const float length = glm::length(cross);
    // A degenerate triangle is never hit; any unit vector will do.
    const glm::vec3 normal = length > 0.0f ? cross / length : glm::vec3(0.0f, 0.0f, 1.0f);
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t corner = shared.corners[t + k];
      flat.corners.push_back(static_cast<std::uint32_t>(flat.positions.size()));
      flat.positions.push_back(shared.positions[corner]);
      for (std::size_t set = 0; set < kUvSets; ++set) flat.uvs[set].push_back(shared.uvs[set][corner]);
      if (shared.tangents) flat.tangents->push_back((*shared.tangents)[corner]);
      flat.normals->push_back(normal);
    }
  }
  return flat;
}

/// Appends `values`, or as many `fallback`s where there are none, to a mesh attribute that some
/// primitive has.
template <class T>
void append(std::vector<T>& attribute, bool scene_has, const std::vector<T>* values, std::size_t count,
            T fallback) {
  if (!scene_has) return;
  if (values)
    attribute.insert(attribute.end(), values->begin(), values->end());
  else
    attribute.insert(attribute.end(), count, fallback);
}

void read_geometry(const Document& document, Scene& scene) {
  Attributes any;
  document.for_each_triangle_primitive(
      [&](const tinygltf::Primitive& primitive, const glm::dmat4&, const std::string&) {
        any.normals = any.normals || primitive.attributes.contains("NORMAL");
        any.tangents = any.tangents || primitive.attributes.contains("TANGENT");
        for (std::size_t set = 0; set < kUvSets; ++set)
          any.uv_sets[set] = any.uv_sets[set] || primitive.attributes.contains(uv_set_name(set));
      });
  any.uv_sets[0] = true;  // TEXCOORD_0 is always there, (0, 0) where a primitive has none
  const std::size_t file_materials = document.model().materials.size();
  std::optional<std::uint32_t> default_material;
  Mesh& mesh = scene.mesh;
  document.for_each_triangle_primitive(
      [&](const tinygltf::Primitive& primitive, const glm::dmat4& world, const std::string& what) {
        // A node scaled to zero (a common way of hiding one) leaves nothing to render.
        if (glm::determinant(glm::dmat3(world)) == 0.0) return;
        if (primitive.material >= 0 && std::size_t(primitive.material) >= file_materials) {
          document.fail(what + " uses material " + std::to_string(primitive.material) +
                        ", which does not exist");
        }
        if (primitive.material < 0 && !default_material) {
          default_material = static_cast<std::uint32_t>(scene.materials.size());
          scene.materials.emplace_back().name = "default";
        }
        const auto material =
            primitive.material >= 0 ? std::uint32_t(primitive.material) : *default_material;

        Vertices v = world_vertices(document, primitive, world, what);
        if (any.normals && !v.normals) v = with_face_normals(v);
        const std::uint32_t base = document.vertex_base(mesh.positions.size(), v.positions.size());
        const std::size_t count = v.positions.size();
        mesh.positions.insert(mesh.positions.end(), v.positions.begin(), v.positions.end());
        append(mesh.normals, any.normals, v.normals ? &*v.normals : nullptr, count, glm::vec3(0.0f));
        append(mesh.tangents, any.tangents, v.tangents ? &*v.tangents : nullptr, count, glm::vec4(0.0f));
        for (std::size_t set = 0; set < kUvSets; ++set)
          append(mesh.uvs[set], any.uv_sets[set], &v.uvs[set], count, glm::vec2(0.0f));
        for (const std::uint32_t corner : v.corners) mesh.indices.push_back(base + corner);
        mesh.materials.insert(mesh.materials.end(), v.corners.size() / 3, material);
      });
}

std::optional<Camera> first_camera(const Document& document) {
  const auto& cameras = document.model().cameras;
  std::optional<Camera> camera;
  document.for_each_node([&](int index, const tinygltf::Node& node, const glm::dmat4& world) {
    if (camera || node.camera < 0) return;
    const std::string what =
        "camera " + std::to_string(node.camera) + " (node " + std::to_string(index) + ")";
    if (std::size_t(node.camera) >= cameras.size()) document.fail(what + " does not exist");
    const tinygltf::Camera& source = cameras[std::size_t(node.camera)];
    if (source.type == "orthographic")
      document.fail(what + ": orthographic cameras are not supported");
    const double yfov = source.perspective.yfov;
    if (source.type != "perspective") document.fail(what + ": unknown type '" + source.type + "'");
    if (!(yfov > 0.0 && yfov < std::numbers::pi))
      document.fail(what + ": yfov must lie between 0 and pi radians");
    // glTF cameras look down their local -Z with +Y up.
    const glm::dvec3 forward = glm::normalize(glm::dvec3(world * glm::dvec4(0, 0, -1, 0)));
    const glm::dvec3 up = glm::dvec3(world * glm::dvec4(0, 1, 0, 0));
    camera = Camera{.position = glm::vec3(world[3]),
                    .forward = glm::vec3(forward),
                    .up = glm::vec3(glm::normalize(up - glm::dot(up, forward) * forward)),
                    .yfov = float(yfov),
                    .aspect = float(source.perspective.aspectRatio)};
  });
  return camera;
}

}  // namespace

Scene load_gltf_scene(const std::filesystem::path& file) {
  const auto start = std::chrono::steady_clock::now();
  trs::check_input_file(file);
  const Document document(file);
  // Extensions the renderer reads; KHR_materials_variants leaves the default materials, which
  // are what it renders.
  document.require_only({"KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_animation_pointer",
                         "KHR_materials_variants", "KHR_texture_transform", "KHR_materials_ior",
                         "KHR_materials_specular", "KHR_materials_transmission", "KHR_materials_volume",
                         "KHR_materials_clearcoat", "KHR_materials_sheen"});
  Scene scene;
  scene.file = file;
  read_materials(document, scene);
  read_geometry(document, scene);
  read_punctual_lights(document, scene);
  scene.camera = first_camera(document);
  scene.load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return scene;
}

}  // namespace tracer
