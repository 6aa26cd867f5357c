// glTF materials as the tracer renders them, on the analytic bench (quad_over_plane.h): alpha
// that cuts an emitter (MASK) or thins a surface (BLEND), an emissive texture read through
// KHR_texture_transform, and a normal map under a sun.
//
// Hypotheses: (1) the light sampler's density follows what the shader sees: no light sample
// lands on a texel that alpha cuts away (1e6 samples), and the samples of a transformed emissive
// texture follow the transformed image (chi-square, p >= 0.001, seed fixed); (2) every strategy
// stays unbiased: the radiance the plane reflects agrees with quadrature over what the shader
// sees, each channel within 4 standard errors plus 1e-4 relative (400 frames of 500 paths, seeds
// fixed, as analytic_test.cpp). Each check is also run against a deliberately wrong answer or
// sampler (the mask ignored, the transform ignored, the normal map's green read the other way)
// and must reject it, so that it can fail.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "support/chi_square.h"
#include "quad_over_plane.h"

namespace {

using namespace tracer;
using namespace trs_test;

// ---- alpha ----------------------------------------------------------------------------------

/// The texels of the emitter's alpha texture that MASK cuts away (alpha 0.1 < 0.5): a third.
bool cut(std::uint32_t i, std::uint32_t j) { return (i + 2 * j) % 3 == 0; }

/// A base colour texture the size of the emission, white, with alpha 0.1 on the cut texels and
/// 0.9 elsewhere; nearest, clamped, as the emission.
std::int32_t add_alpha_texture(Scene& scene) {
  Texture t;
  t.name = "alpha";
  t.width = kTexWidth;
  t.height = kTexHeight;
  t.wrap_s = t.wrap_t = Wrap::clamp;
  t.nearest = true;
  for (std::uint32_t j = 0; j < kTexHeight; ++j) {
    for (std::uint32_t i = 0; i < kTexWidth; ++i) {
      t.texels.push_back(glm::vec3(1.0f));
      t.alpha.push_back(cut(i, j) ? 0.1f : 0.9f);
    }
  }
  scene.textures.push_back(std::move(t));
  return std::int32_t(scene.textures.size() - 1);
}

void mask_the_emitter(Scene& scene) {
  Material& light = scene.materials[0];
  light.alpha_mode = AlphaMode::mask;
  light.base_color_texture.texture = add_alpha_texture(scene);
}

/// The light samples of one frame of 1e6 that land on a cut texel, by the sampler's own texel.
std::uint64_t samples_on_cut_texels(Emitters& emitters) {
  lightsampler::Frame frame;
  emitters.sampler().generate({.seed = 5, .target_count = 1e6}, frame);
  EXPECT_GT(frame.samples.size(), 900000u);
  std::uint64_t on_cut = 0;
  for (const lightsampler::Sample& s : frame.samples.span()) {
    const auto texel = emitters.sampler().maps().texel(s.triangle, s.b1, s.b2);
    if (texel && cut(texel->x, texel->y)) ++on_cut;
  }
  return on_cut;
}

/// Every strategy must agree with `expected` and, where given, miss `wrong`.
void expect_every_strategy(const QuadOverPlane& bench, const glm::dvec3& expected, const glm::dvec3* wrong,
                           const std::vector<std::string>& kinds = trs_test::every_strategy()) {
  for (const std::string& kind : kinds) {
    auto s = strategy(*bench.emitters, kind);
    const Estimate e = bench.run(*s, 21);
    EXPECT_TRUE(agrees(e, expected, kSigmas, kQuadratureSlack)) << kind << "\n" << describe(e, expected);
    if (wrong)
      EXPECT_FALSE(agrees(e, *wrong, kSigmas, kQuadratureSlack)) << kind << " agrees with a wrong answer";
  }
}

TEST(AlphaMask, NoLightSampleLandsOnACutTexel) {
  const QuadOverPlane masked(kCpuSampler, mask_the_emitter);
  EXPECT_EQ(samples_on_cut_texels(*masked.emitters), 0u);
  // The check fails where the density ignores the mask.
  const QuadOverPlane opaque(kCpuSampler, [](Scene& scene) {
    mask_the_emitter(scene);
    scene.materials[0].alpha_mode = AlphaMode::opaque;
  });
  EXPECT_GT(samples_on_cut_texels(*opaque.emitters), 1000u);
}

TEST(AlphaMask, EveryStrategyConvergesToTheQuadratureOverTheUncutTexels) {
  const QuadOverPlane bench(kCpuSampler, mask_the_emitter);
  const glm::dvec3 uncut = bench.integrate([&](double u, double v) {
    const auto i = std::uint32_t(u * kTexWidth), j = std::uint32_t(v * kTexHeight);
    return cut(i, j) ? glm::dvec3(0.0) : bench.radiance_at(i, j);
  }, kTexWidth, kTexHeight);
  const glm::dvec3 whole = bench.expected();
  expect_every_strategy(bench, uncut, &whole);
}

TEST(AlphaBlend, AHalfTransparentPaneBeforeTheLightPassesHalfItsLight) {
  const QuadOverPlane bench(kCpuSampler, [](Scene& scene) {
    Material pane = matte({0.5f, 0.5f, 0.5f});
    pane.alpha = 0.5f;
    pane.alpha_mode = AlphaMode::blend;
    const std::uint32_t m = add_material(scene, pane);
    add_quad(scene, {-1, -1, 0.6f}, {1, -1, 0.6f}, {1, 1, 0.6f}, {-1, 1, 0.6f}, m);
  });
  const glm::dvec3 half = 0.5 * bench.expected(), whole = bench.expected();
  expect_every_strategy(bench, half, &whole);
}

TEST(AlphaBlend, AHalfTransparentEmitterGivesHalfItsLight) {
  const QuadOverPlane bench(kCpuSampler, [](Scene& scene) {
    scene.materials[0].alpha = 0.5f;
    scene.materials[0].alpha_mode = AlphaMode::blend;
  });
  const glm::dvec3 half = 0.5 * bench.expected(), whole = bench.expected();
  expect_every_strategy(bench, half, &whole);
}

// ---- KHR_texture_transform ------------------------------------------------------------------

/// The extension's own example: the lower-left quadrant of the image, turned a quarter.
/// u' = cos(r) sx u + sin(r) sy v + ox, v' = -sin(r) sx u + cos(r) sy v + oy with r = pi / 2,
/// s = (0.5, 0.5), o = (0, 1): u' = v / 2, v' = 1 - u / 2.
glm::dvec2 transformed(double u, double v) { return {0.5 * v, 1.0 - 0.5 * u}; }

void transform_the_emission(Scene& scene) {
  // An image with no black texel, so that each of the region's 8 texels is a cell of the test.
  add_random_texture(scene, kTexWidth, kTexHeight, 0.0, 5);
  scene.textures[0] = std::move(scene.textures.back());
  scene.textures.pop_back();
  TextureRef& emission = scene.materials[0].emissive_texture;
  const float r = std::numbers::pi_v<float> / 2;
  emission.transform.linear = glm::mat2(0.5f * std::cos(r), -0.5f * std::sin(r), 0.5f * std::sin(r), 0.5f * std::cos(r));
  emission.transform.offset = glm::vec2(0.0f, 1.0f);
}

/// The texel the transformed image shows at the quad's (u, v).
glm::uvec2 transformed_texel(double u, double v) {
  const glm::dvec2 t = transformed(u, v);
  return {std::min(std::uint32_t(t.x * kTexWidth), kTexWidth - 1), std::min(std::uint32_t(t.y * kTexHeight), kTexHeight - 1)};
}

/// Chi-square of the light samples' texels against the transformed image: its region holds 4 x 2
/// texels, each the preimage of an eighth of the quad, so each is drawn in proportion to its
/// luminance.
ChiSquareResult transformed_image_test(Emitters& emitters, const QuadOverPlane& bench) {
  std::vector<double> observed(kTexWidth * kTexHeight, 0.0), expected(observed.size(), 0.0);
  // Each texel of the region seen at the centre of its preimage, a cell of a 2 x 4 grid.
  for (int a = 0; a < 2; ++a) {
    for (int b = 0; b < 4; ++b) {
      const glm::uvec2 texel = transformed_texel((a + 0.5) / 2, (b + 0.5) / 4);
      const glm::dvec3 le = bench.radiance_at(texel.x, texel.y);
      expected[texel.y * kTexWidth + texel.x] += 0.2126 * le.r + 0.7152 * le.g + 0.0722 * le.b;
    }
  }
  lightsampler::Frame frame;
  emitters.sampler().generate({.seed = 7, .target_count = 2e5}, frame);
  for (const lightsampler::Sample& s : frame.samples.span()) {
    const auto texel = emitters.sampler().maps().texel(s.triangle, s.b1, s.b2);
    if (texel) observed[texel->y * kTexWidth + texel->x] += 1.0;
  }
  double total = 0.0, weight = 0.0;
  for (double o : observed) total += o;
  for (double e : expected) weight += e;
  for (double& e : expected) e *= total / weight;
  return chi_square_test(observed, expected);
}

TEST(TextureTransform, LightSamplesFollowTheTransformedImage) {
  const QuadOverPlane bench(kCpuSampler, transform_the_emission);
  const ChiSquareResult result = transformed_image_test(*bench.emitters, bench);
  EXPECT_TRUE(result.passes(1e-3)) << result.describe();
  EXPECT_EQ(result.dof, 7.0);
  // The same test rejects samples of the image as it is, untransformed.
  const QuadOverPlane plain(kCpuSampler, [](Scene& scene) {
    transform_the_emission(scene);
    scene.materials[0].emissive_texture.transform = {};
  });
  EXPECT_FALSE(transformed_image_test(*plain.emitters, bench).passes(1e-3));
}

TEST(TextureTransform, EveryStrategyConvergesToTheQuadratureOfTheTransformedImage) {
  const QuadOverPlane bench(kCpuSampler, transform_the_emission);
  // Cells of a quarter in u and an eighth in v: the transformed texels' preimages are unions of them.
  const glm::dvec3 expected = bench.integrate([&](double u, double v) {
    const glm::uvec2 texel = transformed_texel(u, v);
    return bench.radiance_at(texel.x, texel.y);
  }, 4, 8);
  const glm::dvec3 plain = bench.expected();
  expect_every_strategy(bench, expected, &plain);
}

// ---- normal maps ----------------------------------------------------------------------------

/// The tangent-space normal the floor's map holds everywhere, and the sun.
const glm::vec3 kMapped{0.35f, -0.25f, 0.9f};
const glm::vec3 kTowardsSun = glm::normalize(glm::vec3(1.0f, 0.2f, 0.6f));
const glm::vec3 kSunIrradiance{0.6f, 0.5f, 0.4f};

/// The bench's quad dark, the floor normal-mapped (one texel holding kMapped as glTF stores it:
/// (n + 1) / 2), lit by a sun; `tangents`: the floor's vertices carry the file's tangents.
void normal_map_the_floor(Scene& scene, bool tangents) {
  scene.materials[0].emissive_factor = glm::vec3(0.0f);
  Texture t;
  t.name = "normal";
  t.width = t.height = 1;
  t.texels = {0.5f * (kMapped + 1.0f)};
  scene.textures.push_back(std::move(t));
  scene.materials[1].normal_texture.texture = std::int32_t(scene.textures.size() - 1);
  PunctualLight sun;
  sun.kind = PunctualLight::Kind::directional;
  sun.direction = -kTowardsSun;
  sun.intensity = kSunIrradiance;
  scene.lights = {sun};
  if (tangents) {
    // The quad's u runs along +x and its v along +y: tangent +x, and the bitangent (the map's +Y,
    // up the image, where v falls) -y = cross(n, t) w for w = -1.
    scene.mesh.tangents.assign(scene.mesh.positions.size(), glm::vec4(0.0f));
    for (std::size_t v = 4; v < 8; ++v) scene.mesh.tangents[v] = glm::vec4(1, 0, 0, -1);
  }
}

/// What the floor reflects towards the eye under the sun with shading normal `n`.
glm::dvec3 sunlit(const QuadOverPlane& bench, glm::vec3 n) {
  const Material& m = bench.scene.materials[1];
  const Bsdf bsdf({m.base_color, m.metallic, m.roughness}, n);
  return glm::dvec3(bsdf.eval(glm::normalize(bench.eye - bench.point), kTowardsSun)) * glm::dvec3(kSunIrradiance);
}

/// The floor's frame: tangent +x, bitangent -y, normal +z; the map's green read along `bitangent`.
glm::vec3 bent(glm::vec3 bitangent) {
  return glm::normalize(kMapped.x * glm::vec3(1, 0, 0) + kMapped.y * bitangent + kMapped.z * glm::vec3(0, 0, 1));
}

TEST(NormalMap, ASunOnANormalMappedFloorGivesTheBentNormalsAnswer) {
  for (const bool tangents : {false, true}) {
    const QuadOverPlane bench(kCpuSampler, [&](Scene& scene) { normal_map_the_floor(scene, tangents); });
    const glm::dvec3 expected = sunlit(bench, bent({0, -1, 0}));
    const glm::dvec3 green_flipped = sunlit(bench, bent({0, 1, 0}));
    const glm::dvec3 flat = sunlit(bench, {0, 0, 1});
    SCOPED_TRACE(tangents ? "the file's tangents" : "tangents from the UVs");
    expect_every_strategy(bench, expected, &green_flipped, {"uniform", "tree"});
    expect_every_strategy(bench, expected, &flat, {"trs"});
  }
}

// A map read through a UV set that no primitive has (every UV (0, 0), no tangent frame) leaves
// the normal as it is.
TEST(NormalMap, AMapThroughAnAbsentUvSetLeavesTheNormal) {
  const QuadOverPlane bench(kCpuSampler, [](Scene& scene) {
    normal_map_the_floor(scene, false);
    scene.materials[1].normal_texture.uv_set = 1;
  });
  ASSERT_TRUE(bench.scene.mesh.uvs[1].empty());
  const glm::dvec3 flat = sunlit(bench, {0, 0, 1}), mapped = sunlit(bench, bent({0, -1, 0}));
  expect_every_strategy(bench, flat, &mapped, {"uniform"});
}

}  // namespace
