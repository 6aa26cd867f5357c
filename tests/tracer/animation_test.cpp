// Emission that changes over time: image sequences and keyed factors (tracer/scene.h), the
// emitters moved from frame to frame (Emitters::set_frame), and the light strategies brought up
// to date (LightStrategy::emission_changed).
//
// Statistical check: the estimate after the change agrees with quadrature of the new emission,
// within 4 standard errors (400 frames of 500 paths, seed 2), for every strategy; and it is shown
// to fail on lights drawn from the old emission and weighed by the new.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "image_sequence.h"
#include "quad_over_plane.h"
#include "support/image_files.h"
#include "support/scratch_dir.h"
#include "tracer/gltf_scene.h"

namespace {

using namespace tracer;
using namespace trs_test;
namespace fs = std::filesystem;

TEST(Keyframes, InterpolateBetweenKeysAndHoldBeyondThem) {
  Keyframes keys{{1.0f, 2.0f, 4.0f}, {glm::vec3(0.0f), glm::vec3(2.0f), glm::vec3(1.0f)}, false};
  EXPECT_EQ(keys.at(0.0).x, 0.0f);
  EXPECT_EQ(keys.at(1.5).x, 1.0f);
  EXPECT_EQ(keys.at(3.0).x, 1.5f);
  EXPECT_EQ(keys.at(9.0).x, 1.0f);
  keys.step = true;
  EXPECT_EQ(keys.at(1.5).x, 0.0f);
  EXPECT_EQ(keys.at(2.0).x, 2.0f);
  EXPECT_EQ(keys.at(3.9).x, 2.0f);
}

/// Writes an 8-bit RGB PNG of random texels, black where `lit(i, j)` is false.
template <class Lit>
void write_png(const fs::path& file, int width, int height, std::uint64_t seed, Lit lit) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> value(20, 255);
  std::vector<std::uint16_t> samples;
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const bool on = lit(i, j);
      for (int c = 0; c < 3; ++c) samples.push_back(on ? std::uint16_t(value(rng)) : 0);
    }
  std::ofstream(file, std::ios::binary) << trs_test::png_file(width, height, 3, 8, samples);
}

/// Writes an 8-bit RGB PNG of random texels, `dark` of them black.
void write_random_png(const fs::path& file, int width, int height, double dark, std::uint64_t seed) {
  std::mt19937_64 rng(seed ^ 0x5eed);
  std::bernoulli_distribution black(dark);
  write_png(file, width, height, seed, [&](int, int) { return !black(rng); });
}

class Sequences : public trs_test::ScratchDirTest {};

// Moving to a frame gives what starting there gives: the same maps, integrals and samples.
TEST_F(Sequences, SetFrameIsStartingThere) {
  for (int f = 0; f < 3; ++f) write_random_png(file("f" + std::to_string(f) + ".png"), 8, 4, 0.3, 40 + f);
  Scene scene;
  Material light;
  light.emissive_factor = glm::vec3(1.0f);
  light.emissive_texture.texture = trs_test::add_random_texture(scene, 8, 4, 0.3, 1);
  scene.textures[0].frames = read_image_sequence(file("scene.gltf"), "f%d.png", 8, 4, "image 0");
  light.emissive_strength_keys = Keyframes{{0.0f, 1.0f}, {glm::vec3(2.0f), glm::vec3(5.0f)}, false};
  trs_test::add_quad(scene, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}, trs_test::add_material(scene, light));
  ASSERT_TRUE(scene.animated());

  Emitters moved(scene, trs_test::kCpuSampler, 0, 0.0);
  for (const auto& [frame, seconds] : {std::pair{1, 0.5}, std::pair{5, 0.7}, std::pair{5, 0.9}}) {
    const EmissionUpdate update = moved.set_frame(frame, seconds);
    EXPECT_TRUE(update.changed()) << frame;
    Emitters fresh(scene, trs_test::kCpuSampler, frame, seconds);
    EXPECT_EQ(moved.total_density(), fresh.total_density()) << frame;
    EXPECT_EQ(std::vector<double>(moved.light_density().begin(), moved.light_density().end()),
              std::vector<double>(fresh.light_density().begin(), fresh.light_density().end()));
    lightsampler::Frame a, b;
    moved.sampler().generate({.seed = 3, .target_count = 2000}, a);
    fresh.sampler().generate({.seed = 3, .target_count = 2000}, b);
    ASSERT_EQ(a.sample_count, b.sample_count);
    for (std::size_t i = 0; i < a.sample_count; ++i) {
      ASSERT_EQ(a.samples.span()[i].triangle, b.samples.span()[i].triangle);
      ASSERT_EQ(a.samples.span()[i].b1, b.samples.span()[i].b1);
    }
  }
  // Frames 7 and 8 both show the last image, and past 1 s the strength holds: nothing to do.
  EXPECT_TRUE(moved.set_frame(7, 2.0).changed());
  EXPECT_FALSE(moved.set_frame(8, 3.0).changed());
}

TEST_F(Sequences, BadSequencesAreRefusedNamingTheFileAndTheFrame) {
  const fs::path document = file("scene.gltf");
  for (int f : {0, 1, 3}) write_random_png(file("gap." + std::to_string(f) + ".png"), 4, 4, 0.0, f);
  trs_test::expect_error([&] { read_image_sequence(document, "gap.%d.png", 4, 4, "image 0"); }, document,
                         "frame 2 is missing (gap.2.png");
  write_random_png(file("size.0.png"), 4, 4, 0.0, 1);
  write_random_png(file("size.1.png"), 5, 4, 0.0, 2);
  trs_test::expect_error([&] { read_image_sequence(document, "size.%d.png", 4, 4, "image 0"); },
                         file("size.1.png"), "frame 1 of image 0 is 5 x 4");
  for (const char* pattern : {"f.png", "f%d%d.png", "f%s.png", "f%x.png"})
    trs_test::expect_error([&] { read_image_sequence(document, pattern, 4, 4, "image 0"); }, document,
                           "one integer conversion");
  trs_test::expect_error([&] { read_image_sequence(document, "none.%04d.png", 4, 4, "image 0"); }, document,
                         "no file matches it");
}

// The analytic bench (quad_over_plane.h) with its emitter playing two images, frame 1 lighting
// every texel and frame 0 only texels below the quad's diagonal: at frame 0 one of its two
// triangles carries nothing, so a strategy that kept frame 0's choice would never draw it. The
// strength is keyed 3 at 0 s, 7 at 1 s.
class ChangingEmission : public trs_test::ScratchDirTest {
 protected:
  void SetUp() override {
    ScratchDirTest::SetUp();
    // Texel (i, j) lies wholly in triangle 0 1 2 (u >= v) when i / 8 >= (j + 1) / 4.
    write_png(file("f0.png"), kTexWidth, kTexHeight, 50, [](int i, int j) { return i >= 2 * (j + 1); });
    write_png(file("f1.png"), kTexWidth, kTexHeight, 51, [](int, int) { return true; });
    Texture& texture = bench_.scene.textures[0];
    texture.frames = read_image_sequence(file("scene.gltf"), "f%d.png", kTexWidth, kTexHeight, "image 0");
    bench_.scene.materials[0].emissive_strength_keys =
        Keyframes{{0.0f, 1.0f}, {glm::vec3(3.0f), glm::vec3(7.0f)}, false};
    bench_.emitters = std::make_unique<Emitters>(bench_.scene, kCpuSampler, 0, 0.0);
    // The quadrature of frame 1, from a still scene that shows it.
    QuadOverPlane still;
    still.scene.textures[0].texels = read_sequence_frame(texture, 1);
    still.scene.materials[0].emissive_strength = 7.0f;
    expected_ = still.expected();
  }

  /// The estimate of a strategy built at frame 0, after the emission moved to frame 1 and the
  /// strategy was told.
  Estimate after_change(const StrategyOptions& o) {
    bench_.emitters->set_frame(0, 0.0);
    auto s = make_light_strategy(*bench_.emitters, o);
    if (!bench_.emitters->set_frame(1, 1.0).changed()) ADD_FAILURE() << "frame 1 changed nothing";
    s->emission_changed();
    return bench_.run(*s, 2);
  }

  QuadOverPlane bench_;
  glm::dvec3 expected_{0.0};
};

TEST_F(ChangingEmission, EveryStrategyConvergesToTheNewEmission) {
  for (const std::string& kind : trs_test::every_strategy()) {
    const Estimate e = after_change(options(kind));
    EXPECT_TRUE(agrees(e, expected_, kSigmas, kQuadratureSlack)) << kind << "\n" << describe(e, expected_);
  }
}

// What a strategy rebuilt for the new emission (power's table, the tree, the alias tables)
// is what a fresh build over it would be: the same draws and densities, bit for bit, seen from
// points above the emitter and beside it.
TEST_F(ChangingEmission, StrategiesAreThoseBuiltFreshForTheNewEmission) {
  std::mt19937_64 rng(12);
  for (const std::string& kind : trs_test::every_strategy()) {
    SCOPED_TRACE(kind);
    bench_.emitters->set_frame(0, 0.0);
    auto updated = make_light_strategy(*bench_.emitters, options(kind));
    bench_.emitters->set_frame(1, 1.0);
    updated->emission_changed();
    auto fresh = make_light_strategy(*bench_.emitters, options(kind));
    updated->begin_pass(3);
    fresh->begin_pass(3);
    for (int i = 0; i < 200; ++i) {
      const ShadingPoint at{{float(i % 7) * 0.3f - 1.0f, float(i % 5) * 0.2f - 0.4f, float(i % 3) * 0.4f},
                            {0.0f, 0.0f, 1.0f}};
      LightRandom random;
      for (std::uint32_t& word : random) word = std::uint32_t(rng());
      const auto a = updated->sample(random, at), b = fresh->sample(random, at);
      ASSERT_EQ(a.has_value(), b.has_value()) << i;
      if (!a) continue;
      ASSERT_EQ(a->light, b->light) << i;
      ASSERT_EQ(a->b1, b->b1) << i;
      ASSERT_EQ(a->pdf, b->pdf) << i;
      ASSERT_EQ(updated->pdf(a->light, a->b1, a->b2, at), fresh->pdf(a->light, a->b1, a->b2, at)) << i;
    }
  }
}

// Deliberately wrong: lights drawn as frame 0's emission would have them, weighed as frame 1's
// would, as a strategy half brought up to date would do. (One not told at all stays consistent
// with itself, and the BSDF's draws, weighed by MIS, cover what it no longer draws: only its
// variance suffers.)
TEST_F(ChangingEmission, TheCheckRejectsLightsDrawnFromTheOldEmission) {
  for (const std::string& kind : {"power", "texel"}) {
    bench_.emitters->set_frame(0, 0.0);
    auto before = make_light_strategy(*bench_.emitters, options(kind));
    bench_.emitters->set_frame(1, 1.0);
    DrawnByOneWeighedByAnother wrong(std::move(before), make_light_strategy(*bench_.emitters, options(kind)));
    const Estimate e = bench_.run(wrong, 2);
    EXPECT_FALSE(agrees(e, expected_, kSigmas, kQuadratureSlack)) << kind << "\n" << describe(e, expected_);
  }
}

// The shipped video wall: its clip is a sequence, its "on air" sign blinks by
// KHR_animation_pointer, keyed STEP on its emissive strength.
TEST(VideoWall, PlaysItsClipAndBlinksItsSign) {
  const Scene scene = load_gltf_scene(fs::path(TRS_SCENES_DIR) / "video-wall" / "video-wall.gltf");
  ASSERT_TRUE(scene.animated());
  const auto wall = std::find_if(scene.textures.begin(), scene.textures.end(),
                                 [](const Texture& t) { return t.frames.has_value(); });
  ASSERT_NE(wall, scene.textures.end());
  EXPECT_EQ(wall->frames->first, 0);
  EXPECT_EQ(wall->frames->last, 47);
  const auto sign = std::find_if(scene.materials.begin(), scene.materials.end(),
                                 [](const Material& m) { return m.emissive_strength_keys.has_value(); });
  ASSERT_NE(sign, scene.materials.end());
  EXPECT_TRUE(sign->emissive_strength_keys->step);
  EXPECT_EQ(sign->emissive_strength_at(0.25), 40.0f);
  EXPECT_EQ(sign->emissive_strength_at(0.75), 0.0f);
}

}  // namespace
