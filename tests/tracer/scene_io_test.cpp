// The tracer's scene input: glTF scenes written by each test into a fresh temporary directory
// (JSON with a .bin buffer, PNG and EXR textures), and the colour module.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene_io/color.h"
#include "scene_io/image_output.h"
#include "support/image_files.h"
#include "support/scratch_dir.h"
#include "tracer/gltf_scene.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kFloat = 5126, kUnsignedShort = 5123;

/// A glTF document under construction: its JSON and one binary buffer.
struct Gltf {
  json doc = {
      {"asset", {{"version", "2.0"}}}, {"scene", 0}, {"scenes", {{{"nodes", json::array()}}}}};
  std::string bin;

  int view(const void* data, std::size_t size) {
    bin.resize((bin.size() + 3) / 4 * 4, '\0');
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", size}});
    bin.append(static_cast<const char*>(data), size);
    return int(doc["bufferViews"].size()) - 1;
  }
  template <class T>
  int accessor(const std::vector<T>& values, int component_type, const char* type) {
    doc["accessors"].push_back({{"bufferView", view(values.data(), values.size() * sizeof(T))},
                                {"componentType", component_type},
                                {"type", type},
                                {"count", values.size()}});
    return int(doc["accessors"].size()) - 1;
  }
  /// A one-primitive mesh of the triangles `indices` over `positions`; `extra` adds to the
  /// primitive (attributes included).
  int mesh(const std::vector<glm::vec3>& positions, const std::vector<std::uint16_t>& indices,
           json extra = json::object()) {
    json primitive = {{"attributes", {{"POSITION", accessor(positions, kFloat, "VEC3")}}},
                      {"indices", accessor(indices, kUnsignedShort, "SCALAR")}};
    for (auto& [key, value] : extra.items()) {
      if (key == "attributes") {
        primitive["attributes"].update(value);
      } else {
        primitive[key] = value;
      }
    }
    doc["meshes"].push_back({{"primitives", {primitive}}});
    return int(doc["meshes"].size()) - 1;
  }
  int node(json node, bool root = true) {
    doc["nodes"].push_back(std::move(node));
    const int index = int(doc["nodes"].size()) - 1;
    if (root) doc["scenes"][0]["nodes"].push_back(index);
    return index;
  }
  fs::path write(const fs::path& directory, const std::string& name) {
    doc["buffers"] = {{{"uri", name + ".bin"}, {"byteLength", bin.size()}}};
    std::ofstream(directory / (name + ".bin"), std::ios::binary) << bin;
    std::ofstream(directory / (name + ".gltf")) << doc.dump(1);
    return directory / (name + ".gltf");
  }
};

std::string base64(const std::string& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t group = std::uint32_t(std::uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) group |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) group |= std::uint8_t(bytes[i + 2]);
    for (std::size_t k = 0; k < 4; ++k)
      text += i + k <= bytes.size() ? digits[(group >> (18 - 6 * k)) & 63] : '=';
  }
  return text;
}

const std::vector<glm::vec3> kTriangle = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};  // facing +z

void expect_near(glm::vec3 actual, glm::vec3 expected, float tolerance = 1e-5f) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(actual[k], expected[k], tolerance) << "component " << k;
}

using trs_test::expect_error;

class SceneIoTest : public trs_test::ScratchDirTest {};

constexpr double kHalfSqrt2 = 0.70710678118654752;

TEST_F(SceneIoTest, TransformsApplyToPositionsAndNormals) {
  Gltf gltf;
  const glm::vec3 diagonal = glm::normalize(glm::vec3(1, 1, 0));
  const int mesh =
      gltf.mesh({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {0, 1, 2},
                {{"attributes",
                  {{"NORMAL", gltf.accessor(std::vector<glm::vec3>{diagonal, {0, 0, 1}, {0, 0, 1}},
                                            kFloat, "VEC3")}}}});
  // Parent: translate and stretch x; child: 90 degrees about z.
  const int child =
      gltf.node({{"mesh", mesh}, {"rotation", {0, 0, kHalfSqrt2, kHalfSqrt2}}}, false);
  gltf.node({{"children", {child}}, {"translation", {10, 0, 0}}, {"scale", {2, 1, 1}}});
  gltf.node({{"mesh", mesh},
             {"translation", {1, 2, 3}},
             {"rotation", {0, 0, kHalfSqrt2, kHalfSqrt2}},
             {"scale", {2, 2, 2}}});
  const tracer::Scene scene = tracer::load_gltf_scene(gltf.write(dir_, "transforms"));
  const tracer::Mesh& m = scene.mesh;
  ASSERT_EQ(m.triangle_count(), 2u);
  ASSERT_EQ(m.positions.size(), 6u);
  ASSERT_EQ(m.normals.size(), 6u);
  // The chain first (document order), then T * R * S.
  expect_near(m.positions[m.indices[0]], {10, 1, 0});
  expect_near(m.positions[m.indices[1]], {8, 0, 0});
  expect_near(m.positions[m.indices[2]], {10, 0, 1});
  expect_near(m.positions[m.indices[3]], {1, 4, 3});
  expect_near(m.positions[m.indices[4]], {-1, 2, 3});
  expect_near(m.positions[m.indices[5]], {1, 2, 5});
  // Normals by the inverse transpose: (-1, 1, 0) after the rotation, x halved by the stretch.
  expect_near(m.normals[m.indices[0]], glm::normalize(glm::vec3(-0.5f, 1, 0)));
  expect_near(m.normals[m.indices[3]], glm::normalize(glm::vec3(-1, 1, 0)));
  expect_near(m.normals[m.indices[4]], {0, 0, 1});
  for (const glm::vec2& uv : m.uvs[0]) EXPECT_EQ(uv, glm::vec2(0.0f));
  // No materials in the file: one default, shared.
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(m.materials, (std::vector<std::uint32_t>{0, 0}));
  EXPECT_FALSE(scene.camera.has_value());
}

TEST_F(SceneIoTest, MirroredTransformKeepsTheFrontFace) {
  Gltf gltf;
  const int mesh = gltf.mesh(kTriangle, {0, 1, 2});
  gltf.node({{"mesh", mesh}, {"scale", {-1, 1, 1}}});
  gltf.node({{"mesh", mesh}, {"scale", {0, 0, 0}}});  // hidden: nothing to render
  const tracer::Mesh m = tracer::load_gltf_scene(gltf.write(dir_, "mirror")).mesh;
  ASSERT_EQ(m.triangle_count(), 1u);
  EXPECT_TRUE(m.normals.empty());  // no primitive has normals
  const glm::vec3 a = m.positions[m.indices[0]], b = m.positions[m.indices[1]],
                  c = m.positions[m.indices[2]];
  expect_near(glm::normalize(glm::cross(b - a, c - a)), {0, 0, 1});
}

TEST_F(SceneIoTest, PrimitiveWithoutNormalsGetsFaceNormalsBesideOneWithNormals) {
  Gltf gltf;
  const std::vector<glm::vec3> up(3, glm::vec3(0, 1, 0));
  gltf.node(
      {{"mesh", gltf.mesh(kTriangle, {0, 1, 2},
                          {{"attributes", {{"NORMAL", gltf.accessor(up, kFloat, "VEC3")}}}})}});
  gltf.node(
      {{"mesh", gltf.mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, {0, 1, 2, 2, 1, 3})}});
  const tracer::Mesh m = tracer::load_gltf_scene(gltf.write(dir_, "mixed")).mesh;
  ASSERT_EQ(m.triangle_count(), 3u);
  ASSERT_EQ(m.normals.size(), m.positions.size());
  EXPECT_EQ(m.positions.size(), 3u + 6u);
  for (std::size_t i = 3; i < 9; ++i) expect_near(m.normals[m.indices[i]], {0, 0, 1});
}

TEST_F(SceneIoTest, MaterialsAndTextures) {
  // Texel 0 is sRGB 128 everywhere; texel 1 tells channels apart.
  const std::vector<unsigned char> texels = {128, 128, 128, 255, 0, 64};
  trs::write_png(file("colour.png"), 2, 1, texels.data());
  const std::vector<float> float_texels = {0.5f, 0.5f, 0.5f, 2.0f, 0.0f, 0.25f};
  trs::write_exr(file("float.exr"), 2, 1, float_texels.data());
  std::ifstream png_file(file("colour.png"), std::ios::binary);
  const std::string png((std::istreambuf_iterator<char>(png_file)), {});

  Gltf gltf;
  gltf.doc["images"] = {
      {{"uri", "colour.png"}},
      {{"uri", "float.exr"}},
      {{"bufferView", gltf.view(png.data(), png.size())}, {"mimeType", "image/png"}},
      {{"uri", "data:image/png;base64," + base64(png)}}};
  gltf.doc["samplers"] = {{{"wrapS", 33071}, {"wrapT", 33648}, {"magFilter", 9728}}};
  gltf.doc["textures"] = {
      {{"source", 0}, {"sampler", 0}}, {{"source", 1}}, {{"source", 2}}, {{"source", 3}}};
  gltf.doc["materials"] = {
      {{"name", "lamp"},
       {"pbrMetallicRoughness",
        {{"baseColorFactor", {0.5, 0.25, 0.125, 0.3}},
         {"baseColorTexture", {{"index", 0}}},
         {"metallicFactor", 0.2},
         {"roughnessFactor", 0.7},
         {"metallicRoughnessTexture", {{"index", 0}}}}},
       {"emissiveFactor", {1, 0.5, 0}},
       {"emissiveTexture", {{"index", 1}}},
       {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 40}}}}},
       {"doubleSided", true}},
      {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 2}}}}},
       {"emissiveTexture", {{"index", 3}}}}};
  gltf.node({{"mesh", gltf.mesh(kTriangle, {0, 1, 2}, {{"material", 1}})}});
  gltf.node({{"mesh", gltf.mesh(kTriangle, {0, 1, 2}, {{"material", 0}})}});
  gltf.node({{"mesh", gltf.mesh(kTriangle, {0, 1, 2})}});
  const tracer::Scene scene = tracer::load_gltf_scene(gltf.write(dir_, "materials"));

  ASSERT_EQ(scene.materials.size(), 3u);  // the file's two and the default
  EXPECT_EQ(scene.mesh.materials, (std::vector<std::uint32_t>{1, 0, 2}));
  const tracer::Material& lamp = scene.materials[0];
  EXPECT_EQ(lamp.name, "lamp");
  expect_near(lamp.base_color, {0.5f, 0.25f, 0.125f});
  EXPECT_FLOAT_EQ(lamp.metallic, 0.2f);
  EXPECT_FLOAT_EQ(lamp.roughness, 0.7f);
  expect_near(lamp.emissive_factor, {1.0f, 0.5f, 0.0f});
  EXPECT_FLOAT_EQ(lamp.emissive_strength, 40.0f);
  EXPECT_TRUE(lamp.double_sided);
  EXPECT_TRUE(lamp.emissive());
  EXPECT_FALSE(scene.materials[2].emissive());
  EXPECT_FALSE(scene.materials[2].double_sided);

  ASSERT_EQ(scene.textures.size(), 5u);
  const tracer::Texture& base = scene.textures.at(std::size_t(lamp.base_color_texture.texture));
  const tracer::Texture& data = scene.textures.at(std::size_t(lamp.metallic_roughness_texture.texture));
  const tracer::Texture& emissive = scene.textures.at(std::size_t(lamp.emissive_texture.texture));
  const tracer::Texture& embedded =
      scene.textures.at(std::size_t(scene.materials[1].base_color_texture.texture));
  const tracer::Texture& data_uri =
      scene.textures.at(std::size_t(scene.materials[1].emissive_texture.texture));
  ASSERT_EQ(base.width, 2u);
  ASSERT_EQ(base.height, 1u);
  expect_near(base.texels[0], glm::vec3(0.21586f), 1e-4f);      // sRGB 128 decoded
  expect_near(base.texels[1], {1.0f, 0.0f, 0.05127f}, 1e-4f);   // 0.25 stored as 64
  expect_near(data.texels[0], glm::vec3(128 / 255.0f), 1e-6f);  // data: as stored
  expect_near(emissive.texels[1], {2.0f, 0.0f, 0.25f}, 0.0f);   // float: already linear
  expect_near(embedded.texels[0], base.texels[0], 0.0f);
  expect_near(data_uri.texels[1], base.texels[1], 0.0f);
  EXPECT_EQ(base.wrap_s, tracer::Wrap::clamp);
  EXPECT_EQ(base.wrap_t, tracer::Wrap::mirrored_repeat);
  EXPECT_TRUE(base.nearest);
  EXPECT_EQ(emissive.wrap_s, tracer::Wrap::repeat);
  EXPECT_EQ(emissive.wrap_t, tracer::Wrap::repeat);
  EXPECT_FALSE(emissive.nearest);
}

TEST_F(SceneIoTest, FirstCameraOfTheHierarchy) {
  Gltf gltf;
  gltf.doc["cameras"] = {
      {{"type", "perspective"},
       {"perspective", {{"yfov", 0.6}, {"aspectRatio", 1.5}, {"znear", 0.1}}}},
      {{"type", "perspective"}, {"perspective", {{"yfov", 0.9}, {"znear", 0.1}}}}};
  // 90 degrees about y turns -z (forward) into -x.
  const int eye = gltf.node({{"camera", 0}, {"rotation", {0, kHalfSqrt2, 0, kHalfSqrt2}}}, false);
  gltf.node({{"children", {eye}}, {"translation", {1, 2, 3}}});
  gltf.node({{"camera", 1}});
  gltf.node({{"mesh", gltf.mesh(kTriangle, {0, 1, 2})}});
  const tracer::Scene scene = tracer::load_gltf_scene(gltf.write(dir_, "camera"));
  ASSERT_TRUE(scene.camera.has_value());
  expect_near(scene.camera->position, {1, 2, 3});
  expect_near(scene.camera->forward, {-1, 0, 0});
  expect_near(scene.camera->up, {0, 1, 0});
  EXPECT_FLOAT_EQ(scene.camera->yfov, 0.6f);
  EXPECT_FLOAT_EQ(scene.camera->aspect, 1.5f);
}

// KHR_lights_punctual: placed by their nodes, shining down the node's -Z, candela and lux over
// 683 lm/W (Blender's importer), the spot's cones and the range as given.
TEST_F(SceneIoTest, PunctualLightsInTheRenderersUnits) {
  Gltf gltf;
  gltf.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  gltf.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "point"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 683.0}, {"range", 4.0}, {"name", "bulb"}},
      {{"type", "spot"}, {"intensity", 1366.0}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.5}}}},
      {{"type", "directional"}, {"intensity", 6830.0}}};
  gltf.node({{"mesh", gltf.mesh(kTriangle, {0, 1, 2})}});
  gltf.node({{"translation", {1, 2, 3}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  // 90 degrees about y turns -z into -x; the scale moves the spot but does not change it.
  gltf.node({{"translation", {0, 1, 0}}, {"rotation", {0, kHalfSqrt2, 0, kHalfSqrt2}}, {"scale", {2, 2, 2}},
             {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
  gltf.node({{"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
  const tracer::Scene scene = tracer::load_gltf_scene(gltf.write(dir_, "lights"));
  ASSERT_EQ(scene.lights.size(), 3u);
  const tracer::PunctualLight& point = scene.lights[0];
  EXPECT_EQ(point.kind, tracer::PunctualLight::Kind::point);
  EXPECT_EQ(point.name, "light 0 'bulb'");
  expect_near(point.position, {1, 2, 3});
  expect_near(point.intensity, {1.0f, 0.5f, 0.25f});
  EXPECT_FLOAT_EQ(point.range, 4.0f);
  const tracer::PunctualLight& spot = scene.lights[1];
  EXPECT_EQ(spot.kind, tracer::PunctualLight::Kind::spot);
  expect_near(spot.position, {0, 1, 0});
  expect_near(spot.direction, {-1, 0, 0});
  expect_near(spot.intensity, {2, 2, 2});
  EXPECT_FLOAT_EQ(spot.cos_inner, std::cos(0.2f));
  EXPECT_FLOAT_EQ(spot.cos_outer, std::cos(0.5f));
  const tracer::PunctualLight& sun = scene.lights[2];
  EXPECT_EQ(sun.kind, tracer::PunctualLight::Kind::directional);
  expect_near(sun.direction, {0, 0, -1});
  expect_near(sun.intensity, {10, 10, 10});

  gltf.doc["nodes"][3]["extensions"]["KHR_lights_punctual"]["light"] = 3;
  const fs::path absent = gltf.write(dir_, "absent-light");
  expect_error([&] { tracer::load_gltf_scene(absent); }, absent, "light 3 is not one of the file's 3 lights");
  gltf.doc["nodes"][3]["extensions"]["KHR_lights_punctual"]["light"] = 1;
  gltf.doc["extensions"]["KHR_lights_punctual"]["lights"][1]["spot"]["innerConeAngle"] = 0.6;
  const fs::path cones = gltf.write(dir_, "cones");
  expect_error([&] { tracer::load_gltf_scene(cones); }, cones, "light 1: the spot's cone angles");
}

// An extension the file requires and the renderer does not implement is refused by name; one it
// implements is not.
TEST_F(SceneIoTest, AlphaNormalMapsTextureTransformsAndUvSets) {
  const std::string png = trs_test::png_file(2, 1, 4, 8, {128, 128, 128, 255, 255, 0, 64, 51});
  std::ofstream(file("rgba.png"), std::ios::binary) << png;
  Gltf gltf;
  gltf.doc["extensionsUsed"] = {"KHR_texture_transform"};
  gltf.doc["extensionsRequired"] = {"KHR_texture_transform"};
  gltf.doc["images"] = {{{"uri", "rgba.png"}}};
  gltf.doc["textures"] = {{{"source", 0}}};
  const json quarter_turn = {{"KHR_texture_transform",
                              {{"offset", {0, 1}}, {"rotation", 1.5707963267948966}, {"scale", {0.5, 0.5}}, {"texCoord", 1}}}};
  gltf.doc["materials"] = {
      {{"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 0.8}}, {"baseColorTexture", {{"index", 0}}}}},
       {"alphaMode", "MASK"},
       {"alphaCutoff", 0.3},
       {"normalTexture", {{"index", 0}, {"scale", 0.5}, {"texCoord", 1}}},
       {"emissiveFactor", {1, 1, 1}},
       {"emissiveTexture", {{"index", 0}, {"extensions", quarter_turn}}}},
      {{"alphaMode", "BLEND"}}};
  const std::vector<glm::vec2> uv1 = {{0.25f, 0.5f}, {1, 0}, {0, 1}};
  const std::vector<glm::vec4> tangents = {{1, 0, 0, -1}, {1, 0, 0, -1}, {1, 0, 0, -1}};
  gltf.node({{"mesh", gltf.mesh(kTriangle, {0, 1, 2},
                                {{"material", 0},
                                 {"attributes", {{"TEXCOORD_1", gltf.accessor(uv1, kFloat, "VEC2")},
                                                 {"TANGENT", gltf.accessor(tangents, kFloat, "VEC4")}}}})}});
  gltf.node({{"mesh", gltf.mesh(kTriangle, {0, 1, 2}, {{"material", 1}})}});  // neither TEXCOORD_1 nor TANGENT
  const tracer::Scene scene = tracer::load_gltf_scene(gltf.write(dir_, "materials"));

  const tracer::Material& cutout = scene.materials[0];
  EXPECT_EQ(cutout.alpha_mode, tracer::AlphaMode::mask);
  EXPECT_FLOAT_EQ(cutout.alpha_cutoff, 0.3f);
  EXPECT_FLOAT_EQ(cutout.alpha, 0.8f);
  EXPECT_EQ(scene.materials[1].alpha_mode, tracer::AlphaMode::blend);
  const tracer::Texture& base = scene.textures.at(std::size_t(cutout.base_color_texture.texture));
  ASSERT_EQ(base.alpha.size(), 2u);  // as stored: alpha is never sRGB-encoded
  EXPECT_FLOAT_EQ(base.alpha[0], 1.0f);
  EXPECT_FLOAT_EQ(base.alpha[1], 0.2f);
  expect_near(base.texels[0], glm::vec3(0.21586f), 1e-4f);
  EXPECT_TRUE(scene.textures.at(std::size_t(cutout.emissive_texture.texture)).alpha.empty());

  EXPECT_EQ(cutout.normal_texture.uv_set, 1u);
  EXPECT_FLOAT_EQ(cutout.normal_scale, 0.5f);
  EXPECT_EQ(cutout.base_color_texture.uv_set, 0u);
  // The extension's own example: the lower-left quadrant, turned a quarter; its texCoord wins.
  const tracer::TextureRef& emission = cutout.emissive_texture;
  EXPECT_EQ(emission.uv_set, 1u);
  for (const auto& [from, to] : {std::pair{glm::vec2(0, 0), glm::vec2(0, 1)}, std::pair{glm::vec2(1, 0), glm::vec2(0, 0.5f)},
                                 std::pair{glm::vec2(0, 1), glm::vec2(0.5f, 1)}, std::pair{glm::vec2(1, 1), glm::vec2(0.5f, 0.5f)}}) {
    const glm::vec2 mapped = emission.transform(from);
    EXPECT_NEAR(mapped.x, to.x, 1e-6f);
    EXPECT_NEAR(mapped.y, to.y, 1e-6f);
  }

  ASSERT_EQ(scene.mesh.uvs[1].size(), 6u);  // (0, 0) for the primitive without a second set
  EXPECT_EQ(scene.mesh.uvs[1][0], uv1[0]);
  EXPECT_EQ(scene.mesh.uvs[1][5], glm::vec2(0.0f));
  ASSERT_EQ(scene.mesh.tangents.size(), 6u);  // none (zero) for the primitive without them
  EXPECT_EQ(scene.mesh.tangents[0], glm::vec4(1, 0, 0, -1));
  EXPECT_EQ(scene.mesh.tangents[3], glm::vec4(0.0f));
}

TEST_F(SceneIoTest, MaterialExtensionsAsTheirSpecificationsDefineThem) {
  // KHR_materials_specular, _ior, _transmission, _volume, _clearcoat and _sheen: every factor,
  // every texture with the channel its specification names (specular and sheen roughness in
  // alpha, kept as stored; colours decoded from sRGB), the defaults where a property is absent,
  // and a volume only where the thickness is non-zero.
  const std::string png = trs_test::png_file(1, 1, 4, 8, {255, 128, 64, 51});
  std::ofstream(file("rgba.png"), std::ios::binary) << png;
  Gltf gltf;
  gltf.doc["images"] = {{{"uri", "rgba.png"}}};
  gltf.doc["textures"] = {{{"source", 0}}};
  const json texture = {{"index", 0}};
  gltf.doc["materials"] = {
      {{"extensions",
        {{"KHR_materials_specular", {{"specularFactor", 0.5}, {"specularTexture", texture},
                                     {"specularColorFactor", {2, 1, 0.5}}, {"specularColorTexture", texture}}},
         {"KHR_materials_ior", {{"ior", 1.33}}},
         {"KHR_materials_transmission", {{"transmissionFactor", 0.75}, {"transmissionTexture", texture}}},
         {"KHR_materials_volume", {{"thicknessFactor", 0.1}, {"attenuationDistance", 2.5},
                                   {"attenuationColor", {0.5, 0.6, 0.7}}}},
         {"KHR_materials_clearcoat", {{"clearcoatFactor", 0.9}, {"clearcoatTexture", texture},
                                      {"clearcoatRoughnessFactor", 0.2}, {"clearcoatRoughnessTexture", texture},
                                      {"clearcoatNormalTexture", {{"index", 0}, {"scale", 0.25}}}}},
         {"KHR_materials_sheen", {{"sheenColorFactor", {0.1, 0.2, 0.3}}, {"sheenColorTexture", texture},
                                  {"sheenRoughnessFactor", 0.4}, {"sheenRoughnessTexture", texture}}}}}},
      {{"extensions", {{"KHR_materials_transmission", json::object()},
                       {"KHR_materials_volume", {{"thicknessFactor", 0}}},
                       {"KHR_materials_clearcoat", json::object()}, {"KHR_materials_sheen", json::object()}}}}};
  gltf.node({{"mesh", gltf.mesh(kTriangle, {0, 1, 2}, {{"material", 0}})}});
  gltf.node({{"mesh", gltf.mesh(kTriangle, {0, 1, 2}, {{"material", 1}})}});
  const tracer::Scene scene = tracer::load_gltf_scene(gltf.write(dir_, "extensions"));

  using Channel = tracer::ScalarInput::Channel;
  const tracer::Material& m = scene.materials[0];
  const auto texels = [&](const tracer::TextureRef& ref) { return scene.textures.at(std::size_t(ref.texture)); };
  EXPECT_FLOAT_EQ(m.specular.factor, 0.5f);
  EXPECT_EQ(m.specular.channel, Channel::alpha);
  ASSERT_EQ(texels(m.specular.texture).alpha.size(), 1u);
  EXPECT_FLOAT_EQ(texels(m.specular.texture).alpha[0], 0.2f);
  expect_near(m.specular_color.factor, {2, 1, 0.5});
  expect_near(texels(m.specular_color.texture).texels[0], {1.0f, 0.21586f, 0.05127f}, 1e-4f);  // sRGB decoded
  EXPECT_FLOAT_EQ(m.ior, 1.33f);
  EXPECT_FLOAT_EQ(m.transmission.factor, 0.75f);
  EXPECT_EQ(m.transmission.channel, Channel::r);
  expect_near(texels(m.transmission.texture).texels[0], {1.0f, 128 / 255.0f, 64 / 255.0f}, 1e-6f);  // data: as stored
  ASSERT_TRUE(m.volume.has_value());
  EXPECT_FLOAT_EQ(m.volume->attenuation_distance, 2.5f);
  expect_near(m.volume->attenuation_color, {0.5f, 0.6f, 0.7f});
  expect_near(m.volume->transmittance(5.0f), {0.25f, 0.36f, 0.49f});  // colour^(5 / 2.5)
  EXPECT_FLOAT_EQ(m.clearcoat.factor, 0.9f);
  EXPECT_EQ(m.clearcoat.channel, Channel::r);
  EXPECT_FLOAT_EQ(m.clearcoat_roughness.factor, 0.2f);
  EXPECT_EQ(m.clearcoat_roughness.channel, Channel::g);
  EXPECT_TRUE(m.clearcoat_normal_texture.present());
  EXPECT_FLOAT_EQ(m.clearcoat_normal_scale, 0.25f);
  expect_near(m.sheen_color.factor, {0.1f, 0.2f, 0.3f});
  expect_near(texels(m.sheen_color.texture).texels[0], {1.0f, 0.21586f, 0.05127f}, 1e-4f);
  EXPECT_FLOAT_EQ(m.sheen_roughness.factor, 0.4f);
  EXPECT_EQ(m.sheen_roughness.channel, Channel::alpha);

  const tracer::Material& defaults = scene.materials[1];
  EXPECT_FLOAT_EQ(defaults.specular.factor, 1.0f);
  EXPECT_FLOAT_EQ(defaults.ior, 1.5f);
  EXPECT_FLOAT_EQ(defaults.transmission.factor, 0.0f);
  EXPECT_FALSE(defaults.volume.has_value());  // thickness 0: thin-walled
  EXPECT_FLOAT_EQ(defaults.clearcoat.factor, 0.0f);
  EXPECT_FALSE(defaults.clearcoat_normal_texture.present());
  expect_near(defaults.sheen_color.factor, glm::vec3(0.0f));
}

TEST_F(SceneIoTest, MaterialExtensionValuesOutOfRangeAreRefused) {
  // Each refusal names the file, the material, the extension and the property.
  const std::vector<std::pair<json, std::string>> cases = {
      {{{"KHR_materials_ior", {{"ior", 0.5}}}}, "KHR_materials_ior: ior 0.500000 must be at least 1, or 0"},
      {{{"KHR_materials_transmission", {{"transmissionFactor", 1.5}}}}, "transmissionFactor 1.500000 is out of its range"},
      {{{"KHR_materials_specular", {{"specularColorFactor", {1, -1, 1}}}}}, "specularColorFactor must be three numbers"},
      {{{"KHR_materials_volume", {{"thicknessFactor", 1}, {"attenuationDistance", 0}}}}, "attenuationDistance must be positive"},
      {{{"KHR_materials_clearcoat", {{"clearcoatRoughnessFactor", -0.1}}}}, "clearcoatRoughnessFactor -0.100000 is out of its range"},
      {{{"KHR_materials_sheen", {{"sheenColorTexture", {{"texCoord", 0}}}}}}, "sheenColorTexture: index must be a texture"},
  };
  for (std::size_t k = 0; k < cases.size(); ++k) {
    Gltf gltf;
    gltf.doc["materials"] = {{{"name", "shade"}, {"extensions", cases[k].first}}};
    gltf.node({{"mesh", gltf.mesh(kTriangle, {0, 1, 2}, {{"material", 0}})}});
    const fs::path bad = gltf.write(dir_, "bad" + std::to_string(k));
    expect_error([&] { tracer::load_gltf_scene(bad); }, bad, "material 0 'shade' ");
    expect_error([&] { tracer::load_gltf_scene(bad); }, bad, cases[k].second);
  }
}

TEST_F(SceneIoTest, MirroringTurnsTheTangentsHandedness) {
  Gltf gltf;
  const std::vector<glm::vec4> tangents = {{0, 1, 0, 1}, {0, 1, 0, 1}, {0, 1, 0, 1}};
  gltf.node({{"mesh", gltf.mesh(kTriangle, {0, 1, 2}, {{"attributes", {{"TANGENT", gltf.accessor(tangents, kFloat, "VEC4")}}}})},
             {"scale", {-2, 1, 1}}});
  const tracer::Scene scene = tracer::load_gltf_scene(gltf.write(dir_, "mirrored"));
  ASSERT_EQ(scene.mesh.tangents.size(), 3u);
  EXPECT_EQ(scene.mesh.tangents[0], glm::vec4(0, 1, 0, -1));
}

TEST_F(SceneIoTest, RequiredExtensionsTheRendererLacksAreRefused) {
  // Every material extension the renderer implements may be required; one it lacks
  // (KHR_materials_iridescence) is refused, naming it.
  Gltf gltf;
  gltf.node({{"mesh", gltf.mesh(kTriangle, {0, 1, 2})}});
  const std::vector<std::string> implemented = {"KHR_lights_punctual", "KHR_materials_ior", "KHR_materials_specular",
                                                "KHR_materials_transmission", "KHR_materials_volume",
                                                "KHR_materials_clearcoat", "KHR_materials_sheen"};
  gltf.doc["extensionsUsed"] = implemented;
  gltf.doc["extensionsUsed"].push_back("KHR_materials_iridescence");
  gltf.doc["extensionsRequired"] = implemented;
  EXPECT_NO_THROW(tracer::load_gltf_scene(gltf.write(dir_, "implemented")));
  gltf.doc["extensionsRequired"].push_back("KHR_materials_iridescence");
  const fs::path lacking = gltf.write(dir_, "lacking");
  expect_error([&] { tracer::load_gltf_scene(lacking); }, lacking,
               "requires the extension KHR_materials_iridescence, which is not implemented");
}

TEST_F(SceneIoTest, ErrorsNameTheFileAtFault) {
  Gltf gltf;
  gltf.node({{"mesh", gltf.mesh(kTriangle, {0, 1, 2}, {{"material", 0}})}});
  gltf.doc["images"] = {{{"uri", "absent.png"}}};
  gltf.doc["textures"] = {{{"source", 0}}};
  gltf.doc["materials"] = {{{"emissiveTexture", {{"index", 0}}}}};
  expect_error([&] { tracer::load_gltf_scene(gltf.write(dir_, "missing")); }, file("absent.png"),
               "no such file");

  std::vector<float> texels(6, 0.5f);
  texels[4] = std::numeric_limits<float>::infinity();
  trs::write_exr(file("inf.exr"), 2, 1, texels.data());
  gltf.doc["images"][0]["uri"] = "inf.exr";
  expect_error([&] { tracer::load_gltf_scene(gltf.write(dir_, "inf")); }, file("inf.exr"),
               "not finite");

  gltf.doc["materials"][0]["emissiveTexture"]["texCoord"] = 2;
  const fs::path texcoord = gltf.write(dir_, "texcoord");
  expect_error([&] { tracer::load_gltf_scene(texcoord); }, texcoord, "TEXCOORD_2");
  gltf.doc["materials"][0]["emissiveTexture"]["texCoord"] = 0;
  gltf.doc["materials"][0]["alphaMode"] = "CUTOUT";
  const fs::path alpha_mode = gltf.write(dir_, "alpha-mode");
  expect_error([&] { tracer::load_gltf_scene(alpha_mode); }, alpha_mode, "unknown alphaMode 'CUTOUT'");
  gltf.doc.erase("materials");
  gltf.doc["meshes"][0]["primitives"][0].erase("material");

  gltf.doc["cameras"] = {{{"type", "orthographic"},
                          {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0}, {"zfar", 1}}}}};
  gltf.node({{"camera", 0}});
  const fs::path orthographic = gltf.write(dir_, "orthographic");
  expect_error([&] { tracer::load_gltf_scene(orthographic); }, orthographic,
               "orthographic cameras are not supported");
  gltf.doc["nodes"][1].erase("camera");

  Gltf range = gltf;
  range.mesh(kTriangle, {0, 1, 3});
  range.doc["nodes"][1]["mesh"] = 1;
  const fs::path out_of_range = range.write(dir_, "range");
  expect_error([&] { tracer::load_gltf_scene(out_of_range); }, out_of_range,
               "index 2 is 3, but the primitive has 3 vertices");

  gltf.doc["accessors"][0]["count"] = 1000;  // past the end of its buffer view
  const fs::path overrun = gltf.write(dir_, "overrun");
  expect_error([&] { tracer::load_gltf_scene(overrun); }, overrun, "extends past the end");

  std::ofstream(file("broken.gltf")) << R"({"asset": {"version": "2.0"}, "scenes": [)";
  expect_error([&] { tracer::load_gltf_scene(file("broken.gltf")); }, file("broken.gltf"),
               "malformed glTF");
  fs::remove(file("overrun.bin"));
  expect_error([&] { tracer::load_gltf_scene(overrun); }, overrun, "malformed glTF");
  expect_error([&] { tracer::load_gltf_scene(file("absent.gltf")); }, file("absent.gltf"),
               "no such file");
}

TEST(Color, SrgbRoundTripAndReferencePoints) {
  std::vector<float> values(100'001);  // pixels, and one value left over
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = 2.0f * float(i) / 100'000.0f;
  std::vector<float> round_trip = values;
  trs::linear_to_srgb(round_trip);
  trs::srgb_to_linear(round_trip);
  for (std::size_t i = 0; i < values.size(); ++i)
    ASSERT_NEAR(round_trip[i], values[i], 1e-6f + 1e-5f * values[i]) << i;

  std::vector<float> points = {0.5f, 128 / 255.0f, 0.04045f, 1.0f};
  trs::srgb_to_linear(points);
  EXPECT_NEAR(points[0], 0.214041f, 1e-5f);
  EXPECT_NEAR(points[1], 0.215861f, 1e-5f);
  EXPECT_NEAR(points[2], 0.0031308f, 1e-6f);
  EXPECT_NEAR(points[3], 1.0f, 1e-6f);
}

}  // namespace
