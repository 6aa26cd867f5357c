// End-to-end tests of the trs-render command line: the tool runs as a subprocess on the shipped
// neon-sign scene at tiny settings, or on small glTF files written by each test into a fresh
// temporary directory, and the tests read back its exit status, stderr and output files.

#include <gtest/gtest.h>
#include <signal.h>
#include <string.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "lightsampler/refinement.h"
#include "scene_io/image_output.h"
#include "support/environment.h"
#include "support/gltf_quad.h"
#include "support/image_files.h"
#include "support/ocio_config.h"
#include "support/subprocess.h"

namespace {

namespace fs = std::filesystem;
using trs_test::read_file;
using trs_test::RunResult;
using trs_test::write_file;

const fs::path kScene = fs::path(TRS_SCENES_DIR) / "neon-sign" / "neon-sign.gltf";
const fs::path kAnimated = fs::path(TRS_SCENES_DIR) / "video-wall" / "video-wall.gltf";
const std::vector<std::string> kStrategies = {"uniform", "power", "trs", "ris", "tree", "texel", "tree-texel"};

nlohmann::json read_json(const fs::path& file) { return nlohmann::json::parse(read_file(file)); }

/// A tiny render of `scene`: 16 x 9 pixels, 2 spp, 1000 lights, 2 bounces, 2 threads, no
/// progress bar. An option given again after these takes the later value.
std::vector<std::string> tiny(const fs::path& scene, std::vector<std::string> args) {
  args.insert(args.begin(), scene.string());
  for (const char* a : {"--width", "16", "--height", "9", "--spp", "2", "--lights", "1000",
                        "--max-depth", "2", "--threads", "2", "--quiet"})
    args.push_back(a);
  return args;
}

/// The quad's glTF document with one material, `material` its JSON object; `extra` are more
/// top-level members (textures, images), each followed by a comma.
std::string quad_gltf(const std::string& material, const std::string& extra = "") {
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2,
                              "material": 0}]}],
  "materials": [)" +
         material + "],\n  " + extra + R"(
  "buffers": [{"uri": "quad.bin", "byteLength": 92}],
  )" + trs_test::kQuadGltfViews + "}";
}

class RenderCliTest : public trs_test::ToolTest {
 protected:
  RenderCliTest() : ToolTest(TRS_RENDER_EXE) {}

  /// The user's OpenColorIO config would change the previews: the runs have none, unless a test
  /// sets one.
  trs_test::ScopedEnvironment ocio_{"OCIO", nullptr};

  fs::path write_quad_scene(const std::string& name, const std::string& material,
                            const std::string& extra = "") {
    write_file(file("quad.bin"), trs_test::quad_gltf_buffer());
    return write_text(name, quad_gltf(material, extra));
  }

  /// Outputs of every kind, for checking that a failed run leaves none behind.
  std::vector<std::string> all_outputs() const {
    return {"--out",     file("out.exr").string(),     "--stats",    file("out.json").string(),
            "--preview", file("out.png").string(), "--variance", file("var.exr").string()};
  }
};

/// The EXR, checked to have `width` x `height` finite non-negative pixels; nullopt (a test
/// failure recorded) if it cannot be read.
std::optional<trs::Image> read_render(const fs::path& exr, std::uint32_t width,
                                      std::uint32_t height) {
  trs::Image image;
  try {
    image = trs::read_exr(exr);
  } catch (const std::exception& e) {
    ADD_FAILURE() << e.what();
    return std::nullopt;
  }
  EXPECT_EQ(image.width, width) << exr;
  EXPECT_EQ(image.height, height) << exr;
  EXPECT_EQ(image.rgb.size(), 3 * std::size_t(image.width) * image.height) << exr;
  std::size_t bad = 0;
  for (const float v : image.rgb) bad += !(std::isfinite(v) && v >= 0.0f);
  EXPECT_EQ(bad, 0u) << exr << ": values not finite or negative";
  return image;
}

bool any_positive(const trs::Image& image) {
  for (const float v : image.rgb)
    if (v > 0.0f) return true;
  return false;
}

// 1. A good run of each strategy: the image, its preview, its variance and the statistics.
TEST_F(RenderCliTest, RendersEveryStrategy) {
  for (const std::string& strategy : kStrategies) {
    SCOPED_TRACE(strategy);
    const fs::path exr = file(strategy + ".exr"), json = file(strategy + ".json"),
                   png = file(strategy + ".png"), variance = file(strategy + "-var.exr");
    const RunResult result =
        run(tiny(kScene, {"--strategy", strategy, "--backend", "cpu", "--seed", "5", "--out",
                          exr.string(), "--stats", json.string(), "--preview", png.string(),
                          "--variance", variance.string()}));
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(result.err, "");

    const auto image = read_render(exr, 16, 9);
    ASSERT_TRUE(image);
    EXPECT_TRUE(any_positive(*image)) << "an all-black image";
    read_render(variance, 16, 9);
    try {
      const trs::Image preview = trs::read_image(png);
      EXPECT_EQ(preview.width, 16u);
      EXPECT_EQ(preview.height, 9u);
      EXPECT_TRUE(preview.integer);
    } catch (const std::exception& e) {
      ADD_FAILURE() << e.what();
    }

    const nlohmann::json stats = read_json(json);
    for (const char* key : {"settings", "passes", "interrupted", "wall_seconds", "paths_per_second",
                            "rays_per_second", "sampler_ms_per_pass", "relative_variance"}) {
      EXPECT_TRUE(stats.contains(key)) << key;
    }
    const nlohmann::json& settings = stats["settings"];
    EXPECT_EQ(settings["width"], 16);
    EXPECT_EQ(settings["height"], 9);
    EXPECT_EQ(settings["spp"], 2);
    EXPECT_EQ(settings["strategy"], strategy);
    EXPECT_EQ(settings["lights"], 1000.0);
    EXPECT_EQ(settings["seed"], 5);
    EXPECT_EQ(settings["max_depth"], 2);
    EXPECT_EQ(settings["threads"], 2);
    EXPECT_EQ(settings["backend"], "cpu");
    EXPECT_FLOAT_EQ(settings["refine"].get<float>(), lightsampler::kAutoMinAcceptance);
    EXPECT_EQ(settings["refine_rule"], "cost");
    EXPECT_EQ(stats["passes"], 2);
    EXPECT_EQ(stats["interrupted"], false);
    EXPECT_GT(stats["wall_seconds"].get<double>(), 0.0);
    EXPECT_GT(stats["paths_per_second"].get<double>(), 0.0);
    EXPECT_GT(stats["rays_per_second"].get<double>(), 0.0);
    const double relative_variance = stats["relative_variance"].get<double>();
    EXPECT_TRUE(std::isfinite(relative_variance) && relative_variance >= 0.0) << relative_variance;
    const double sampler_ms = stats["sampler_ms_per_pass"].get<double>();
    const bool point_lights = strategy == "trs" || strategy == "ris";
    if (point_lights)
      EXPECT_GT(sampler_ms, 0.0);
    else
      EXPECT_GE(sampler_ms, 0.0);
    EXPECT_EQ(stats["light_records_ms_per_pass"].get<double>() > 0.0, point_lights);
    if (strategy == "ris") {
      EXPECT_EQ(settings["candidates"], 4);
      EXPECT_EQ(settings["candidates_from"], "trs");
    } else {
      EXPECT_TRUE(settings["candidates"].is_null());
      EXPECT_TRUE(settings["candidates_from"].is_null());
    }
    const bool tree = strategy == "tree" || strategy == "tree-texel";
    if (tree) {
      EXPECT_EQ(settings["tree_importance"], "pbrt");
      EXPECT_EQ(settings["tree_power"], "exact");
    } else {
      EXPECT_TRUE(settings["tree_importance"].is_null());
      EXPECT_TRUE(settings["tree_power"].is_null());
    }
    if (tree || strategy == "texel") {
      EXPECT_GE(stats["light_structure"]["build_ms"].get<double>(), 0.0);
      EXPECT_GT(stats["light_structure"]["bytes"].get<double>(), 0.0);
    } else {
      EXPECT_TRUE(stats["light_structure"].is_null());
    }
  }
}

// The tree's options, and ris over the tree, which reports the tree's structure.
TEST_F(RenderCliTest, TreeOptions) {
  const fs::path settings = write_text("tree.toml", "tree-importance = \"cycles\"\ntree-power = \"image-mean\"\n");
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{"--strategy", "tree", "--settings", settings.string()},
        std::vector<std::string>{"--strategy", "ris", "--candidates-from", "tree", "--tree-importance", "cycles",
                                 "--tree-power", "image-mean"}}) {
    std::vector<std::string> args = {"--out", file("tree.exr").string(), "--stats", file("tree.json").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const RunResult result = run(tiny(kScene, args));
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_NE(result.out.find("light structure: built in"), std::string::npos) << result.out;
    const nlohmann::json stats = read_json(file("tree.json"));
    EXPECT_EQ(stats["settings"]["tree_importance"], "cycles");
    EXPECT_EQ(stats["settings"]["tree_power"], "image-mean");
    EXPECT_GT(stats["light_structure"]["bytes"].get<double>(), 0.0);
  }
}

// restir's options by --strategy-option: its reuse timed in the stats; a value it cannot take is
// refused, naming the option.
TEST_F(RenderCliTest, RestirOptions) {
  const RunResult result = run(tiny(kScene, {"--strategy", "restir", "--strategy-option", "temporal=on",
                                             "--strategy-option", "neighbours=2", "--out", file("restir.exr").string(),
                                             "--stats", file("restir.json").string()}));
  ASSERT_EQ(result.status, 0) << result.err;
  const nlohmann::json stats = read_json(file("restir.json"));
  EXPECT_EQ(stats["settings"]["strategy"], "restir");
  EXPECT_GE(stats["reuse_ms_per_pass"].get<double>(), 0.0);
  EXPECT_GT(stats["tracing_ms_per_pass"].get<double>(), 0.0);
  for (const std::string& bad : {"radius=0", "neighbours=2.5", "temporal=yes", "weights=none"}) {
    const RunResult refused = run(tiny(kScene, {"--strategy", "restir", "--strategy-option", bad, "--out",
                                                file("refused.exr").string()}));
    EXPECT_NE(refused.status, 0) << bad;
    EXPECT_NE(refused.err.find(bad.substr(0, bad.find('='))), std::string::npos) << refused.err;
  }
}

// A time budget: frames until that much wall time has passed since the start, set-up included;
// --spp on the command line caps them, a settings file's spp does not.
TEST_F(RenderCliTest, TimeBudgetRendersUntilItIsSpent) {
  const fs::path exr = file("timed.exr"), json = file("timed.json");
  const fs::path settings = write_text("render.toml", "spp = 2\n");
  const std::vector<std::string> args = {kScene.string(), "--settings", settings.string(), "--width", "32",
                                         "--height", "18", "--lights", "1000", "--max-depth", "2", "--threads",
                                         "2", "--quiet", "--time", "2", "--out", exr.string(), "--stats",
                                         json.string()};
  const auto start = std::chrono::steady_clock::now();
  const RunResult result = run(args);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_GE(seconds, 2.0);
  read_render(exr, 32, 18);
  const nlohmann::json stats = read_json(json);
  EXPECT_GT(stats["passes"].get<unsigned>(), 2u);
  EXPECT_EQ(stats["interrupted"], false);
  // The bound is on the tool's own clock, which leaves out loading its libraries and exiting:
  // those take longer under the sanitizers and on a loaded machine, whatever the budget.
  EXPECT_GE(stats["wall_seconds"].get<double>(), 2.0);
  EXPECT_LT(stats["wall_seconds"].get<double>(), 3.0) << "a frame of 32 x 18 pixels takes milliseconds";
  EXPECT_EQ(stats["settings"]["time"], 2.0);
  EXPECT_TRUE(stats["settings"]["spp"].is_null()) << "no cap on the frames";

  std::vector<std::string> capped = args;
  capped.insert(capped.end(), {"--time", "60", "--spp", "3"});
  const auto capped_start = std::chrono::steady_clock::now();
  ASSERT_EQ(run(capped).status, 0);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - capped_start).count(), 30.0);
  EXPECT_EQ(read_json(json)["passes"], 3);
  EXPECT_EQ(read_json(json)["settings"]["spp"], 3);
}

// The emitter mask: per pixel, the fraction of camera samples whose first hit is an emitter.
TEST_F(RenderCliTest, EmitterMaskIsTheFractionOfCameraSamplesOnAnEmitter) {
  const fs::path exr = file("out.exr"), mask = file("mask.exr");
  const RunResult result =
      run(tiny(kScene, {"--out", exr.string(), "--emitter-mask", mask.string(), "--spp", "4"}));
  ASSERT_EQ(result.status, 0) << result.err;
  const auto image = read_render(mask, 16, 9);
  ASSERT_TRUE(image);
  std::size_t on = 0, off = 0;
  for (std::size_t i = 0; i < image->rgb.size(); i += 3) {
    const float f = image->rgb[i];
    EXPECT_EQ(image->rgb[i + 1], f);
    EXPECT_EQ(image->rgb[i + 2], f);
    EXPECT_LE(f, 1.0f);
    EXPECT_EQ(f * 4, std::round(f * 4)) << "a count of 4 samples";
    (f > 0 ? on : off) += 1;
  }
  EXPECT_GT(on, 0u) << "the neon sign is in view";
  EXPECT_GT(off, 0u) << "so is the wall behind it";
}

// 2. A settings file gives defaults; the command line wins over it.
TEST_F(RenderCliTest, SettingsFileAndCommandLine) {
  const fs::path settings = write_text("render.toml", "# test settings\nwidth = 8\nspp = 3\n");
  const std::vector<std::string> base = {kScene.string(), "--settings", settings.string(),
                                         "--height", "9", "--lights", "1000", "--max-depth", "2",
                                         "--threads", "2", "--quiet"};

  std::vector<std::string> from_file = base;
  from_file.insert(from_file.end(), {"--out", file("file.exr").string(), "--stats",
                                     file("file.json").string()});
  RunResult result = run(from_file);
  ASSERT_EQ(result.status, 0) << result.err;
  read_render(file("file.exr"), 8, 9);
  nlohmann::json stats = read_json(file("file.json"));
  EXPECT_EQ(stats["settings"]["width"], 8);
  EXPECT_EQ(stats["settings"]["spp"], 3);
  EXPECT_EQ(stats["passes"], 3);

  std::vector<std::string> overridden = base;
  overridden.insert(overridden.end(), {"--width", "16", "--out", file("cli.exr").string(),
                                       "--stats", file("cli.json").string()});
  result = run(overridden);
  ASSERT_EQ(result.status, 0) << result.err;
  read_render(file("cli.exr"), 16, 9);
  stats = read_json(file("cli.json"));
  EXPECT_EQ(stats["settings"]["width"], 16);
  EXPECT_EQ(stats["settings"]["spp"], 3);  // still from the file
}

// A key that is no long option (a misspelt one) would change nothing without a word: refused,
// naming the file and the key.
TEST_F(RenderCliTest, SettingsFileWithAnUnknownKeyOrAKeyWithoutAValueIsRefused) {
  // The second, found by fuzzing: CLI11 handed `height` an empty list and read its first entry.
  for (const auto& [text, key] : {std::pair{"width = 8\nsamples = 64\n", "samples"},
                                  std::pair{"# a render\nheight = [e\n", "height"},
                                  std::pair{"height = []\n", "height"}}) {
    SCOPED_TRACE(text);
    const fs::path settings = write_text("render.toml", text);
    const RunResult result = run({kScene.string(), "--settings", settings.string(), "--out", file("out.exr").string()});
    EXPECT_EQ(result.status, 2) << result.err;
    EXPECT_NE(result.err.find("trs-render: error: " + settings.string()), std::string::npos) << result.err;
    EXPECT_NE(result.err.find(key), std::string::npos) << result.err;
    EXPECT_FALSE(fs::exists(file("out.exr")));
  }
}

// 3. The image depends on the seed, not on the number of threads.
TEST_F(RenderCliTest, SameSeedSameImageWithAnyThreadCount) {
  for (const std::string& strategy : kStrategies) {
    SCOPED_TRACE(strategy);
    std::vector<std::vector<float>> images;
    for (const char* threads : {"1", "2"}) {
      const fs::path exr = file(strategy + "-" + threads + ".exr");
      std::vector<std::string> args = tiny(kScene, {"--strategy", strategy, "--backend", "cpu",
                                                    "--seed", "11", "--out", exr.string()});
      args.push_back("--threads");  // the last --threads wins over tiny()'s
      args.push_back(threads);
      const RunResult result = run(args);
      ASSERT_EQ(result.status, 0) << result.err;
      const auto image = read_render(exr, 16, 9);
      ASSERT_TRUE(image);
      EXPECT_TRUE(any_positive(*image));
      images.push_back(image->rgb);
    }
    ASSERT_EQ(images[0].size(), images[1].size());
    EXPECT_EQ(std::memcmp(images[0].data(), images[1].data(), images[0].size() * sizeof(float)),
              0)
        << "1 and 2 threads give different images";
  }
}

// 4. Bad inputs: status 1, the file at fault named, no output written.
TEST_F(RenderCliTest, MissingScene) {
  const fs::path absent = file("absent.gltf");
  expect_failure_naming(tiny(absent, all_outputs()), absent);
}

TEST_F(RenderCliTest, MalformedGltf) {
  const fs::path broken =
      write_text("broken.gltf", R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [)");
  expect_failure_naming(tiny(broken, all_outputs()), broken);
}

// The control: the hand-written quad renders when its emission is a constant.
TEST_F(RenderCliTest, HandWrittenEmissiveQuadRenders) {
  const fs::path scene =
      write_quad_scene("glow.gltf", R"({"name": "glow", "emissiveFactor": [1, 1, 1]})");
  for (const std::string& strategy : kStrategies) {
    SCOPED_TRACE(strategy);
    const RunResult result =
        run(tiny(scene, {"--strategy", strategy, "--out", file("glow.exr").string()}));
    ASSERT_EQ(result.status, 0) << result.err;
    read_render(file("glow.exr"), 16, 9);
  }
}

// The set-up by part in the stats and the summary, and what `auto` chose and why: its pilot's
// measure of each strategy, the cheapest within 10% of the most efficient used. On the neon
// sign, whose strokes vary within its two triangles, drawing by the texels gains far more than
// it costs (not power); on a quad of flat emission the texel gain is exactly 1.
TEST_F(RenderCliTest, SetUpByPartAndTheStrategyAutoChose) {
  const fs::path flat = write_quad_scene("flat.gltf", R"({"name": "flat", "emissiveFactor": [1, 1, 1]})");
  for (const fs::path& scene : {kScene, flat}) {
    SCOPED_TRACE(scene.string());
    const RunResult result =
        run(tiny(scene, {"--strategy", "auto", "--out", file("auto.exr").string(), "--stats", file("auto.json").string()}));
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_NE(result.out.find("set-up's largest part: "), std::string::npos) << result.out;
    EXPECT_NE(result.out.find(std::string("strategy auto: ")), std::string::npos) << result.out;
    const nlohmann::json stats = read_json(file("auto.json"));
    const nlohmann::json& choice = stats["strategy_choice"];
    EXPECT_EQ(choice["asked"], "auto");
    EXPECT_EQ(stats["settings"]["strategy"], choice["used"]);
    // power, trs and ris on a grid; restir against ris on blocks where the render pays for them,
    // which this one, of 16 x 9 pixels, does not.
    EXPECT_EQ(choice["pilot_block_pixels"].get<unsigned>(), 0u);
    ASSERT_EQ(choice["pilot"].size(), 3u);
    std::string best;
    double most = 0.0;
    for (const nlohmann::json& m : choice["pilot"]) {
      EXPECT_GE(m["relative_variance"].get<double>(), 0.0);
      EXPECT_GE(m["relative_error"].get<double>(), 0.0);
      EXPECT_GT(m["cost"].get<double>(), 0.0);
      if (m["efficiency"].get<double>() > most) {
        most = m["efficiency"].get<double>();
        best = m["strategy"].get<std::string>();
      }
    }
    EXPECT_EQ(choice["most_efficient"], best);
    EXPECT_GE(choice["pilot_passes"].get<unsigned>(), 4u);
    EXPECT_GT(choice["pilot_pixels"].get<unsigned>(), 0u);
    // The cheapest within kCheaperMargin (tracer/light_strategy.h: 10%) of the most efficient.
    std::string cheapest;
    double cost = 0.0;
    for (const nlohmann::json& m : choice["pilot"])
      if (m["efficiency"].get<double>() >= 0.9 * most && (cheapest.empty() || m["cost"].get<double>() < cost)) {
        cheapest = m["strategy"].get<std::string>();
        cost = m["cost"].get<double>();
      }
    EXPECT_EQ(choice["used"], cheapest);
    const double gain = choice["texel_gain"].get<double>();
    if (scene == kScene) {
      EXPECT_NE(choice["used"], "power");
      EXPECT_GT(gain, 5.0);  // the strokes cover 4.8% of the sign's peak on average
    } else {
      EXPECT_NEAR(gain, 1.0, 1e-3);
    }
    EXPECT_FALSE(choice["reason"].get<std::string>().empty());
    double parts = 0.0;
    for (const char* part : {"loading", "texture_decoding", "bvh", "emission", "light_sampler", "subdivision",
                             "light_structure", "pilot", "first_pass"}) {
      ASSERT_TRUE(stats["setup_ms"].contains(part)) << part;
      EXPECT_GE(stats["setup_ms"][part].get<double>(), 0.0) << part;
      parts += stats["setup_ms"][part].get<double>();
    }
    EXPECT_GT(parts, 0.0);
    EXPECT_GE(stats["light_sampler_parts"].get<double>(), 1.0);
  }
  // A strategy named is no choice.
  ASSERT_EQ(run(tiny(flat, {"--strategy", "tree", "--out", file("tree.exr").string(), "--stats",
                            file("tree.json").string()})).status, 0);
  EXPECT_TRUE(read_json(file("tree.json"))["strategy_choice"].is_null());
}

TEST_F(RenderCliTest, MissingEmissiveTexture) {
  const fs::path scene = write_quad_scene(
      "textured.gltf",
      R"({"name": "sign", "emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 0}})",
      R"("textures": [{"source": 0}], "images": [{"uri": "missing.png"}],)");
  // The file at fault is the texture, resolved against the glTF's directory.
  expect_failure_naming(tiny(scene, all_outputs()), file("missing.png"));
}

TEST_F(RenderCliTest, SceneWithoutEmitters) {
  const fs::path scene = write_quad_scene(
      "dark.gltf", R"({"name": "grey", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1]}})");
  for (const std::string& strategy : kStrategies) {
    SCOPED_TRACE(strategy);
    std::vector<std::string> args = all_outputs();
    args.push_back("--strategy");
    args.push_back(strategy);
    expect_failure_naming(tiny(scene, args), scene);
  }
}

/// The quad's document with a node placing a punctual light `light` (its JSON object) at
/// (0.5, 0.5, 1), above the quad's centre; `required`: the document's extensionsRequired.
std::string lit_quad_gltf(const std::string& material, const std::string& light, const std::string& required) {
  std::string gltf = quad_gltf(material, R"("extensionsUsed": ["KHR_lights_punctual"],
  "extensionsRequired": )" + required + R"(,
  "extensions": {"KHR_lights_punctual": {"lights": [)" + light + "]}},");
  const std::string nodes = R"("scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],)";
  const std::string lit = R"("scenes": [{"nodes": [0, 1]}],
  "nodes": [{"mesh": 0}, {"translation": [0.5, 0.5, 1], "extensions": {"KHR_lights_punctual": {"light": 0}}}],)";
  return gltf.replace(gltf.find(nodes), nodes.size(), lit);
}

// A grey quad lit only by a point light: every strategy renders it, the stats count the light,
// and --no-punctual leaves a scene without lights, which is refused.
TEST_F(RenderCliTest, PunctualLightsRenderAndNoPunctualLeavesThemOut) {
  write_file(file("quad.bin"), trs_test::quad_gltf_buffer());
  const fs::path scene = write_text(
      "lamp.gltf", lit_quad_gltf(R"({"name": "grey", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1]}})",
                                 R"({"type": "point", "intensity": 683})", R"(["KHR_lights_punctual"])"));
  for (const std::string& strategy : kStrategies) {
    SCOPED_TRACE(strategy);
    const RunResult result = run(tiny(scene, {"--strategy", strategy, "--out", file("lamp.exr").string(), "--stats",
                                              file("lamp.json").string()}));
    ASSERT_EQ(result.status, 0) << result.err;
    const std::optional<trs::Image> image = read_render(file("lamp.exr"), 16, 9);
    ASSERT_TRUE(image);
    EXPECT_TRUE(any_positive(*image));
    EXPECT_EQ(read_json(file("lamp.json"))["punctual_lights"], 1);
    EXPECT_EQ(read_json(file("lamp.json"))["settings"]["punctual"], true);
  }
  std::vector<std::string> args = all_outputs();
  args.push_back("--no-punctual");
  expect_failure_naming(tiny(scene, args), scene);
}

// A file that requires an extension the renderer lacks is refused, naming the file and the
// extension, status 1.
TEST_F(RenderCliTest, ARequiredExtensionTheRendererLacksIsRefused) {
  write_file(file("quad.bin"), trs_test::quad_gltf_buffer());
  const fs::path scene =
      write_text("glass.gltf", lit_quad_gltf(R"({"name": "glow", "emissiveFactor": [1, 1, 1]})",
                                             R"({"type": "directional", "intensity": 683})",
                                             R"(["KHR_lights_punctual", "KHR_materials_anisotropy"])"));
  expect_failure_naming(tiny(scene, all_outputs()), scene);
  const RunResult result = run(tiny(scene, {"--out", file("glass.exr").string()}));
  EXPECT_NE(result.err.find("requires the extension KHR_materials_anisotropy, which is not implemented"),
            std::string::npos)
      << result.err;
}

// 5. Bad command lines: status 2, nothing written.
TEST_F(RenderCliTest, LightsAutoIsAQuarterOfTheQueriesAndTheDefault) {
  // 20 x 10 pixels, max depth 3: 600 next-event queries per frame, 150 lights.
  for (const bool given : {true, false}) {
    std::vector<std::string> args = {kScene.string(), "--width", "20", "--height", "10", "--spp", "1",
                                     "--max-depth", "3", "--threads", "2", "--quiet", "--out",
                                     file("out.exr").string(), "--stats", file("out.json").string()};
    if (given) args.insert(args.end(), {"--lights", "auto"});
    const RunResult result = run(args);
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(read_json(file("out.json"))["settings"]["lights"], 150.0) << "given: " << given;
  }
}

TEST_F(RenderCliTest, UsageErrorsExitWithTwo) {
  const std::set<std::string> before = listing();
  std::vector<std::string> no_samples = tiny(kScene, {"--out", file("out.exr").string()});
  no_samples.insert(no_samples.end(), {"--spp", "0"});  // after tiny()'s --spp: the last wins
  for (const std::vector<std::string>& args :
       {tiny(kScene, {"--strategy", "magic", "--out", file("out.exr").string()}), no_samples,
        tiny(kScene, {"--stats", file("out.json").string()}),
        tiny(kScene, {"--refine", "1.5", "--out", file("out.exr").string()}),
        tiny(kScene, {"--time", "0", "--out", file("out.exr").string()}),
        tiny(kScene, {"--time", "-1", "--out", file("out.exr").string()}),
        tiny(kScene, {"--strategy", "trs", "--candidates", "4", "--out", file("out.exr").string()}),
        tiny(kScene, {"--strategy", "ris", "--candidates", "0", "--out", file("out.exr").string()}),
        tiny(kScene, {"--strategy", "trs", "--candidates-from", "power", "--out", file("out.exr").string()}),
        tiny(kScene, {"--strategy", "ris", "--candidates-from", "ris", "--out", file("out.exr").string()}),
        tiny(kScene, {"--tree-importance", "cycles", "--out", file("out.exr").string()}),  // ris over trs
        tiny(kScene, {"--strategy", "ris", "--tree-power", "exact", "--out", file("out.exr").string()}),  // over trs
        tiny(kScene, {"--strategy", "tree", "--tree-importance", "exact", "--out", file("out.exr").string()}),
        tiny(kScene, {"--strategy", "tree", "--tree-power", "mean", "--out", file("out.exr").string()}),
        [&] {
          std::vector<std::string> bad_lights = tiny(kScene, {"--out", file("out.exr").string()});
          bad_lights.insert(bad_lights.end(), {"--lights", "many"});
          return bad_lights;
        }()}) {
    const RunResult result = run(args);
    EXPECT_EQ(result.status, 2) << result.err;
    EXPECT_NE(result.err.find("trs-render: error: "), std::string::npos) << result.err;
  }
  // --frames: a range A:B, outputs that are frame patterns, --plan and --resume with it.
  for (const std::vector<std::string>& args :
       {tiny(kAnimated, {"--frames", "0:2", "--out", file("out.exr").string()}),
        tiny(kAnimated, {"--frames", "0:2", "--out", file("out.%04d.exr").string(), "--stats", file("s.json").string()}),
        tiny(kAnimated, {"--frames", "0:2", "--out", file("out.%d%d.exr").string()}),
        tiny(kAnimated, {"--frames", "2:1", "--out", file("out.%04d.exr").string()}),
        tiny(kAnimated, {"--frames", "two", "--out", file("out.%04d.exr").string()}),
        tiny(kAnimated, {"--plan", "--out", file("out.exr").string()}),
        tiny(kAnimated, {"--resume", "--out", file("out.exr").string()}),
        tiny(kAnimated, {"--save-partial", "--out", file("out.exr").string()}),
        tiny(kAnimated, {"--submit", "slurm", "--out", file("out.exr").string()}),
        tiny(kAnimated, {"--frames", "0:2", "--submit", "pbs", "--out", file("out.%04d.exr").string()}),
        tiny(kAnimated, {"--frames", "0:2", "--wait", "--out", file("out.%04d.exr").string()}),
        tiny(kAnimated, {"--frames", "0:2", "--sbatch", "--hold", "--out", file("out.%04d.exr").string()}),
        tiny(kAnimated, {"--frames", "0:2", "--plan", "--submit", "slurm", "--out", file("out.%04d.exr").string()}),
        tiny(kAnimated, {"--frames", "0:2", "--plan", "--out", file("a\nb.%04d.exr").string()})}) {
    const RunResult result = run(args);
    EXPECT_EQ(result.status, 2) << result.err;
    EXPECT_NE(result.err.find("trs-render: error: "), std::string::npos) << result.err;
  }
  EXPECT_EQ(listing(), before);
}

/// A preview's bytes.
std::vector<int> preview_bytes(const fs::path& png) {
  std::vector<int> bytes;
  for (const float v : trs::read_image(png).rgb) bytes.push_back(int(std::lround(v * 255.0f)));
  return bytes;
}

/// The bytes of a preview of `exr` through `view` of its values times 2^exposure, clamped.
std::vector<int> expected_preview(const trs::Image& exr, float exposure, float (*view)(float)) {
  std::vector<int> bytes;
  for (const float v : exr.rgb) {
    const float shown = view(v * std::exp2(exposure));
    bytes.push_back(int(std::lround((shown > 0.0f ? std::min(shown, 1.0f) : 0.0f) * 255.0f)));
  }
  return bytes;
}

float raw_view(float v) { return v; }
float square_root_view(float v) { return std::sqrt(v); }

/// The colour settings of a stats file: config, colour space, display, view.
std::vector<nlohmann::json> colour_settings(const nlohmann::json& stats) {
  const nlohmann::json& s = stats["settings"];
  return {s["ocio_config"], s["ocio_colorspace"], s["display"], s["view"]};
}

// Without a config the preview is the sRGB curve, as written before configs were read: an empty
// --ocio-config turns $OCIO off, and $OCIO without a preview is not read at all.
TEST_F(RenderCliTest, WithoutAConfigThePreviewIsTheSrgbCurve) {
  const auto render = [&](std::vector<std::string> extra) {
    for (const char* a : {"--out", "out.exr", "--stats", "out.json"}) extra.push_back(a[0] == '-' ? a : file(a).string());
    const RunResult result = run(tiny(kScene, extra));
    EXPECT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(result.err, "");
  };
  render({"--preview", file("out.png").string(), "--exposure", "1.5"});
  const auto exr = read_render(file("out.exr"), 16, 9);
  ASSERT_TRUE(exr);
  trs::write_png_preview(file("expected.png"), 16, 9, exr->rgb.data(), 1.5f);
  EXPECT_EQ(read_file(file("out.png")), read_file(file("expected.png")));
  const std::vector<nlohmann::json> none(4, nullptr);
  EXPECT_EQ(colour_settings(read_json(file("out.json"))), none);

  ocio_.set(write_text("config.ocio", trs_test::ocio_config("lin_rec709")).c_str());
  render({"--preview", file("off.png").string(), "--exposure", "1.5", "--ocio-config", ""});
  EXPECT_EQ(read_file(file("off.png")), read_file(file("expected.png")));
  ocio_.set(file("absent.ocio").c_str());
  render({});
  EXPECT_EQ(colour_settings(read_json(file("out.json"))), none);
}

// $OCIO's config encodes the preview, exposure first; --ocio-config wins over it, from the
// command line or a settings file; the stats name the transform applied.
TEST_F(RenderCliTest, PreviewThroughTheOcioConfig) {
  const fs::path gamma = write_text("gamma.ocio", trs_test::ocio_config("Linear Rec.709 (sRGB)"));
  const fs::path linear = write_text("linear.ocio", trs_test::ocio_config("lin_rec709", "", true));
  ocio_.set(gamma.c_str());
  const auto render = [&](std::vector<std::string> extra) {
    for (const char* a : {"--out", "out.exr", "--stats", "out.json", "--preview", "out.png"})
      extra.push_back(a[0] == '-' ? a : file(a).string());
    const RunResult result = run(tiny(kScene, extra));
    EXPECT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(result.err, "");
    const auto exr = read_render(file("out.exr"), 16, 9);
    return exr ? *exr : trs::Image{};
  };
  trs::Image exr = render({"--exposure", "1"});
  EXPECT_EQ(preview_bytes(file("out.png")), expected_preview(exr, 1.0f, square_root_view));
  EXPECT_EQ(colour_settings(read_json(file("out.json"))),
            (std::vector<nlohmann::json>{gamma.string(), "Linear Rec.709 (sRGB)", "Gamma", "Square root"}));

  exr = render({"--ocio-config", linear.string()});
  EXPECT_EQ(preview_bytes(file("out.png")), expected_preview(exr, 0.0f, raw_view));
  EXPECT_EQ(colour_settings(read_json(file("out.json"))),
            (std::vector<nlohmann::json>{linear.string(), "lin_rec709", "Linear", "Raw"}));

  const fs::path settings =
      write_text("look.toml", "ocio-config = \"" + linear.string() + "\"\ndisplay = \"Gamma\"\nview = \"Square root\"\n");
  exr = render({"--settings", settings.string()});
  EXPECT_EQ(preview_bytes(file("out.png")), expected_preview(exr, 0.0f, square_root_view));
  EXPECT_EQ(colour_settings(read_json(file("out.json"))),
            (std::vector<nlohmann::json>{linear.string(), "lin_rec709", "Gamma", "Square root"}));
}

// Each frame of a sequence is previewed through the config.
TEST_F(RenderCliTest, SequencePreviewsThroughTheOcioConfig) {
  ocio_.set(write_text("config.ocio", trs_test::ocio_config("lin_rec709")).c_str());
  const RunResult result = run(tiny(kAnimated, {"--frames", "0:1", "--out", file("f.%d.exr").string(), "--preview",
                                                file("f.%d.png").string(), "--view", "Raw"}));
  ASSERT_EQ(result.status, 0) << result.err;
  for (const char* frame : {"0", "1"}) {
    const auto exr = read_render(file(std::string("f.") + frame + ".exr"), 16, 9);
    ASSERT_TRUE(exr);
    EXPECT_EQ(preview_bytes(file(std::string("f.") + frame + ".png")), expected_preview(*exr, 0.0f, raw_view));
  }
}

// A config without linear Rec. 709: its scene_linear role, with a warning that says how to name
// the renders' space.
TEST_F(RenderCliTest, ConfigWithoutLinearRec709Warns) {
  const fs::path config = write_text("config.ocio", trs_test::ocio_config("reference"));
  const RunResult result = run(tiny(kScene, {"--out", file("out.exr").string(), "--preview", file("out.png").string(),
                                             "--ocio-config", config.string()}));
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_NE(result.err.find("trs-render: warning: " + config.string() + ": no colour space for linear Rec. 709"),
            std::string::npos)
      << result.err;
  EXPECT_NE(result.err.find("--ocio-colorspace"), std::string::npos) << result.err;
}

// A display, view or colour space without a config ($OCIO is unset) is a usage error.
TEST_F(RenderCliTest, OcioNamesNeedAConfig) {
  const std::set<std::string> before = listing();
  for (const char* option : {"--display", "--view", "--ocio-colorspace"}) {
    const RunResult result = run(tiny(kScene, {option, "sRGB", "--out", file("out.exr").string(), "--preview",
                                               file("out.png").string()}));
    EXPECT_EQ(result.status, 2) << result.err;
    EXPECT_NE(result.err.find(std::string("trs-render: error: ") + option +
                              " needs an OpenColorIO config: --ocio-config or $OCIO"),
              std::string::npos)
        << result.err;
  }
  EXPECT_EQ(listing(), before);
}

// Names the config lacks, and a config that cannot be read: status 1 before any rendering, the
// config and the names it has in the message, nothing written.
TEST_F(RenderCliTest, BadOcioNamesAreRefused) {
  const fs::path config = write_text("config.ocio", trs_test::ocio_config("lin_rec709"));
  const std::set<std::string> before = listing();
  for (const auto& [extra, message] :
       {std::pair{std::vector<std::string>{"--display", "sRGB"}, "no display \"sRGB\" (its displays: \"Gamma\", \"Linear\")"},
        std::pair{std::vector<std::string>{"--display", "Linear", "--view", "Filmic"}, "no view \"Filmic\" (its views: \"Raw\")"},
        std::pair{std::vector<std::string>{"--ocio-colorspace", "ACES2065-1"},
                  "no colour space \"ACES2065-1\" (its colour spaces: \"lin_rec709\", \"ACEScg\", \"gamma 2\")"}}) {
    SCOPED_TRACE(message);
    std::vector<std::string> args = all_outputs();
    args.insert(args.end(), {"--ocio-config", config.string()});
    args.insert(args.end(), extra.begin(), extra.end());
    const RunResult result = run(tiny(kScene, args));
    EXPECT_EQ(result.status, 1) << result.err;
    EXPECT_NE(result.err.find("trs-render: error: " + config.string() + ": " + message), std::string::npos)
        << result.err;
    EXPECT_EQ(listing(), before);
  }
  ocio_.set(file("absent.ocio").c_str());
  expect_failure_naming(tiny(kScene, all_outputs()), file("absent.ocio"));
}

// 5b. Animation: a frame range, an image and statistics per frame.
TEST_F(RenderCliTest, FramesRenderAnImageAndStatisticsEach) {
  const RunResult result =
      run(tiny(kAnimated, {"--frames", "3:5", "--fps", "12", "--out", file("f.%04d.exr").string(), "--stats",
                           file("f.%04d.json").string(), "--preview", file("f.%02d.png").string()}));
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(listing(), (std::set<std::string>{"f.0003.exr", "f.0004.exr", "f.0005.exr", "f.0003.json", "f.0004.json",
                                              "f.0005.json", "f.03.png", "f.04.png", "f.05.png"}));
  for (int f = 3; f <= 5; ++f) {
    SCOPED_TRACE(f);
    read_render(file("f.000" + std::to_string(f) + ".exr"), 16, 9);
    const nlohmann::json stats = read_json(file("f.000" + std::to_string(f) + ".json"));
    EXPECT_EQ(stats["frame"], f);
    EXPECT_DOUBLE_EQ(stats["animation_seconds"].get<double>(), f / 12.0);
    EXPECT_EQ(stats["settings"]["frames"], "3:5");
    EXPECT_EQ(stats["settings"]["fps"], 12.0);
    EXPECT_EQ(stats["settings"]["out"], file("f.000" + std::to_string(f) + ".exr").string());
    for (const char* part : {"decode", "upload", "counting", "strategy"})
      EXPECT_GE(stats["emission_update_ms"][part].get<double>(), 0.0) << part;
  }
  // The clip's next image is decoded for every frame after the first.
  EXPECT_GT(read_json(file("f.0004.json"))["emission_update_ms"]["decode"].get<double>(), 0.0);
}

// A frame renders the same whatever range it is rendered in, so chunks of a plan make the same
// images as one run: frame 4 alone is frame 4 of 3:4, for every strategy. (On the CPU backend:
// the Vulkan one keeps the refinement of the range's first frame.)
TEST_F(RenderCliTest, AFrameRendersTheSameInAnyRange) {
  for (const std::string& strategy : kStrategies) {
    SCOPED_TRACE(strategy);
    for (const char* range : {"3:4", "4:4"})
      ASSERT_EQ(run(tiny(kAnimated, {"--strategy", strategy, "--backend", "cpu", "--frames", range, "--out",
                                     file(range[0] == '3' ? "seq.%d.exr" : "one.%d.exr").string()})).status, 0);
    const auto seq3 = read_render(file("seq.3.exr"), 16, 9), seq4 = read_render(file("seq.4.exr"), 16, 9),
               one4 = read_render(file("one.4.exr"), 16, 9);
    ASSERT_TRUE(seq3 && seq4 && one4);
    EXPECT_EQ(seq4->rgb, one4->rgb);
    EXPECT_NE(seq3->rgb, seq4->rgb);
  }
}

// The video wall's sign goes dark at frame 12 and lights again at frame 24 (its strength keyed 40,
// 0, 40): frame 24 after the dark frames renders as frame 24 alone, with every strategy and the
// tree's image-mean power, which follows the strength.
TEST_F(RenderCliTest, AStrengthThatGoesToZeroAndBackRendersAFrameTheSameInAnyRange) {
  std::vector<std::vector<std::string>> configs;
  for (const std::string& strategy : kStrategies) configs.push_back({"--strategy", strategy});
  for (const char* strategy : {"tree", "tree-texel"})
    configs.push_back({"--strategy", strategy, "--tree-power", "image-mean"});
  for (const std::vector<std::string>& config : configs) {
    SCOPED_TRACE(config[1] + (config.size() > 2 ? " " + config[3] : ""));
    for (const char* range : {"22:24", "24:24"}) {
      std::vector<std::string> args = config;
      for (const std::string a : {"--backend", "cpu", "--frames", range, "--out"}) args.push_back(a);
      args.push_back(file(range[1] == '2' ? "dark.%d.exr" : "lit.%d.exr").string());
      ASSERT_EQ(run(tiny(kAnimated, args)).status, 0);
    }
    const auto after_dark = read_render(file("dark.24.exr"), 16, 9), alone = read_render(file("lit.24.exr"), 16, 9);
    ASSERT_TRUE(after_dark && alone);
    EXPECT_EQ(after_dark->rgb, alone->rgb);
  }
}

TEST_F(RenderCliTest, ResumeRendersOnlyTheFramesNotAllThere) {
  ASSERT_EQ(run(tiny(kAnimated, {"--frames", "0:2", "--out", file("r.%d.exr").string(), "--stats",
                                 file("r.%d.json").string()})).status, 0);
  fs::remove(file("r.1.json"));  // frame 1 is missing an output; frame 0 is whole
  write_text("r.0.exr", "kept");
  const RunResult result = run(tiny(kAnimated, {"--frames", "0:3", "--resume", "--out", file("r.%d.exr").string(),
                                                "--stats", file("r.%d.json").string()}));
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(read_file(file("r.0.exr")), "kept");
  for (int f = 1; f <= 3; ++f) {
    read_render(file("r." + std::to_string(f) + ".exr"), 16, 9);
    EXPECT_EQ(read_json(file("r." + std::to_string(f) + ".json"))["frame"], f);
  }
}

TEST_F(RenderCliTest, PlanPrintsACommandPerChunkAndRendersNothing) {
  const std::set<std::string> before = listing();
  const RunResult result = run(tiny(kAnimated, {"--frames", "0:4", "--plan", "--chunk", "2", "--out",
                                                file("p.%04d.exr").string()}));
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(listing(), before);
  std::vector<std::string> lines;
  std::istringstream in(result.out);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 3u) << result.out;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string range = std::to_string(2 * i) + ":" + std::to_string(std::min<std::size_t>(2 * i + 1, 4));
    EXPECT_NE(lines[i].find("--frames " + range), std::string::npos) << lines[i];
    EXPECT_NE(lines[i].find(file("p.%04d.exr").string()), std::string::npos) << lines[i];
    EXPECT_EQ(lines[i].find("--plan"), std::string::npos) << lines[i];
  }
}

/// Slurm's sbatch, stood in for by tests/support/slurm/sbatch while this lives: first on the
/// PATH, it records each call in DIR, prints a job id as --parsable asks, and with --wait runs
/// the array's tasks itself (but task `skipped`).
class StandInSbatch {
 public:
  explicit StandInSbatch(const fs::path& dir, int skipped = -1)
      : dir_(dir),
        path_("PATH", (std::string(TRS_STAND_IN_SLURM) + ":" + std::getenv("PATH")).c_str()),
        record_("SBATCH_RECORD", dir.c_str()),
        skipped_("SBATCH_SKIPPED_TASK", std::to_string(skipped).c_str()) {
    fs::create_directories(dir);
  }

  std::size_t calls() const {
    std::size_t calls = 0;
    for (const auto& entry : fs::directory_iterator(dir_)) calls += entry.path().extension() == ".args";
    return calls;
  }
  /// The arguments of the last call, the batch script's path last.
  std::vector<std::string> args() const {
    std::vector<std::string> words;
    std::istringstream in(read_file(last(".args")));
    for (std::string word; std::getline(in, word, '\0');) words.push_back(word);
    return words;
  }
  std::string script() const { return read_file(last(".script")); }
  /// Runs the last batch script as Slurm runs an array's task `task`: sh, SLURM_ARRAY_TASK_ID set.
  RunResult run_task(int task) const {
    const trs_test::ScopedEnvironment id("SLURM_ARRAY_TASK_ID", std::to_string(task).c_str());
    const pid_t pid = trs_test::spawn_process({"/bin/sh", last(".script").string()}, dir_ / "task.out", dir_ / "task.err");
    return {trs_test::wait_process(pid), read_file(dir_ / "task.out"), read_file(dir_ / "task.err")};
  }

 private:
  fs::path last(const char* suffix) const { return dir_ / (std::to_string(calls() - 1) + suffix); }

  fs::path dir_;
  trs_test::ScopedEnvironment path_, record_, skipped_;
};

/// The regular files under `dir`, by their paths relative to it.
std::set<std::string> files_under(const fs::path& dir) {
  std::set<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file()) files.insert(fs::relative(entry.path(), dir).string());
  return files;
}

// --submit slurm: one array task per chunk, each the --plan command with --resume, run by this
// trs-render's absolute path; sbatch's options, then --sbatch's words, on its command line; the
// job id alone on standard output.
TEST_F(RenderCliTest, SubmitHandsTheChunksToSlurmAsOneArray) {
  const StandInSbatch sbatch(file("sbatch"));
  const RunResult result = run(tiny(kAnimated, {"--frames", "0:4", "--chunk", "2", "--submit", "slurm", "--sbatch",
                                                "--partition=gpu --time=10", "--out", file("s/f.%04d.exr").string()}));
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(result.out, "4242\n");
  EXPECT_NE(result.err.find("Slurm job 4242: frames 0:4 in 3 tasks"), std::string::npos) << result.err;
  std::vector<std::string> args = sbatch.args();
  ASSERT_FALSE(args.empty());
  EXPECT_EQ(fs::path(args.back()).parent_path(), file("s"));  // the batch script, beside the outputs
  args.pop_back();
  EXPECT_EQ(args, (std::vector<std::string>{"--parsable", "--job-name=trs-render", "--array=0-2",
                                            "--output=" + file("s").string() + "/trs-render-%A_%a.log",
                                            "--partition=gpu", "--time=10"}));
  const std::string script = sbatch.script();
  EXPECT_EQ(script.rfind("#!/bin/sh\ncase \"$SLURM_ARRAY_TASK_ID\" in\n", 0), 0u) << script;
  EXPECT_EQ(script.find("#SBATCH"), std::string::npos) << script;
  for (const char* range : {"0:1", "2:3", "4:4"})
    EXPECT_NE(script.find(" --resume --frames " + std::string(range) + " ;;"), std::string::npos) << script;
  EXPECT_NE(script.find(") exec /"), std::string::npos) << "not an absolute path: " << script;
  EXPECT_EQ(script.find("--submit"), std::string::npos) << script;
  EXPECT_EQ(script.find("--sbatch"), std::string::npos) << script;
  EXPECT_EQ(listing(), (std::set<std::string>{"s", "sbatch"}));  // the batch script is gone
}

// --sbatch's words reach sbatch without a shell: words that a shell would run something from are
// refused, naming the character, before anything runs; quoted words arrive whole, as they are.
TEST_F(RenderCliTest, SbatchWordsReachSbatchWithoutAShell) {
  const StandInSbatch sbatch(file("sbatch"));
  const std::string canary = file("pwned").string();
  const auto submit = [&](const std::string& words) {
    return run(tiny(kAnimated, {"--frames", "0:1", "--submit", "slurm", "--sbatch", words, "--out",
                                file("s/f.%04d.exr").string()}));
  };
  for (const auto& [words, named] : std::vector<std::pair<std::string, std::string>>{
           {"--partition=x; touch " + canary, "\";\" at character 14 is a shell operator"},
           {"--partition=x $(touch " + canary + ")", "\"$\" at character 15 would expand in a shell"},
           {"--partition=x `touch " + canary + "`", "\"`\" at character 15 would expand"},
           {"--partition=x | touch " + canary, "\"|\" at character 15 is a shell operator"},
           {"--partition=x && touch " + canary, "\"&\" at character 15"},
           {"--partition=x >" + canary, "\">\" at character 15"},
           {"--comment=\"$(touch " + canary + ")\"", "\"$\" at character 12"},
           {"--partition=x\ntouch " + canary, "a control character (newline) at character 14"},
           {"--comment='a", "\"'\" at character 11 opens a quote that is never closed"}}) {
    SCOPED_TRACE(words);
    const RunResult result = submit(words);
    EXPECT_EQ(result.status, 2) << result.err;
    EXPECT_NE(result.err.find("trs-render: error: --sbatch: " + named), std::string::npos) << result.err;
    EXPECT_EQ(listing(), std::set<std::string>{"sbatch"});  // no canary, no output folder
    EXPECT_EQ(sbatch.calls(), 0u);
  }
  const RunResult quoted = submit("--comment='a b' '--comment=$(touch " + canary + ")' --exclude=node[1-3] --comment=\\;");
  ASSERT_EQ(quoted.status, 0) << quoted.err;
  const std::vector<std::string> args = sbatch.args();
  ASSERT_GE(args.size(), 5u);
  EXPECT_EQ(std::vector<std::string>(args.end() - 5, args.end() - 1),
            (std::vector<std::string>{"--comment=a b", "--comment=$(touch " + canary + ")", "--exclude=node[1-3]",
                                      "--comment=;"}));
  EXPECT_EQ(listing(), (std::set<std::string>{"s", "sbatch"}));
}

// An output folder that a shell would read more into is quoted in the batch script: run by sh as
// Slurm runs a task, the task renders into that folder and creates nothing else. A control
// character in a path is refused, naming the option; a backslash in the folder too, which would
// give every task's log one name.
TEST_F(RenderCliTest, ABatchScriptHoldsAnyOutputFolderQuoted) {
  const StandInSbatch sbatch(file("sbatch"));
  const std::string canary = file("pwned").string();
  for (const std::string& folder : {std::string("it's \"quoted\""), "$(touch " + canary + ")", "`touch " + canary + "`",
                                    std::string("a b;c|d&e"), std::string("100%")}) {
    SCOPED_TRACE(folder);
    fs::remove_all(file("o"));
    const fs::path out = file("o") / folder / "f.%04d.exr";
    const RunResult submitted = run(tiny(kAnimated, {"--frames", "0:0", "--submit", "slurm", "--out", out.string()}));
    ASSERT_EQ(submitted.status, 0) << submitted.err;
    std::string pattern;  // sbatch's --output: Slurm reads % as a replacement symbol, %% as %
    for (const char c : out.parent_path().string()) pattern += c == '%' ? "%%" : std::string(1, c);
    const std::vector<std::string> args = sbatch.args();
    EXPECT_NE(std::find(args.begin(), args.end(), "--output=" + pattern + "/trs-render-%A_%a.log"), args.end());
    const RunResult task = sbatch.run_task(0);
    EXPECT_EQ(task.status, 0) << task.err;
    EXPECT_EQ(files_under(file("o")),
              std::set<std::string>{fs::relative(out.parent_path() / "f.0000.exr", file("o")).string()});
    EXPECT_EQ(listing(), (std::set<std::string>{"o", "sbatch"}));  // no canary
    read_render(out.parent_path() / "f.0000.exr", 16, 9);
  }
  fs::remove_all(file("o"));
  for (const auto& [option, path, named] : std::vector<std::tuple<std::string, std::string, std::string>>{
           {"--out", file("o/a\nb/f.%04d.exr").string(), "newline"},
           {"--stats", file("o/s\r.%04d.json").string(), "carriage return"}}) {
    std::vector<std::string> args = tiny(kAnimated, {"--frames", "0:0", "--submit", "slurm", option, path});
    if (option != "--out") args.insert(args.end(), {"--out", file("o/f.%04d.exr").string()});
    const RunResult refused = run(args);
    EXPECT_EQ(refused.status, 2) << refused.err;
    EXPECT_NE(refused.err.find("trs-render: error: " + option + ": \""), std::string::npos) << refused.err;
    EXPECT_NE(refused.err.find("holds a control character (" + named + ")"), std::string::npos) << refused.err;
  }
  const RunResult backslash = run(tiny(kAnimated, {"--frames", "0:0", "--submit", "slurm", "--out", file("o/a\\b/f.%04d.exr").string()}));
  EXPECT_EQ(backslash.status, 1) << backslash.err;
  EXPECT_NE(backslash.err.find("--out: the folder \"" + file("o/a\\b").string() + "\" holds a backslash"), std::string::npos)
      << backslash.err;
  EXPECT_EQ(listing(), std::set<std::string>{"sbatch"});
}

// --wait: the tasks' frames equal a render of the range here, bit for bit; a task that did not
// run fails the submission, which names its frames; submitted again, only those are rendered.
TEST_F(RenderCliTest, SubmitWaitRendersTheFramesAsHereAndNamesTheMissingOnes) {
  const std::vector<std::string> local = tiny(kAnimated, {"--frames", "0:3", "--out", file("here.%04d.exr").string()});
  ASSERT_EQ(run(local).status, 0);
  const std::vector<std::string> submit = tiny(kAnimated, {"--frames", "0:3", "--chunk", "2", "--submit", "slurm", "--wait",
                                                     "--out", file("s/f.%04d.exr").string()});
  {
    const StandInSbatch sbatch(file("sbatch"), 1);
    const RunResult failed = run(submit);
    EXPECT_EQ(failed.status, 1) << failed.err;
    EXPECT_NE(failed.err.find("task 1 left frames 2:3 unwritten"), std::string::npos) << failed.err;
  }
  const auto written = fs::last_write_time(file("s/f.0000.exr"));
  const StandInSbatch sbatch(file("sbatch"));
  const RunResult again = run(submit);
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_EQ(fs::last_write_time(file("s/f.0000.exr")), written);  // --resume: not rendered again
  for (const char* frame : {"0000", "0001", "0002", "0003"}) {
    const trs::Image here = trs::read_exr(file(std::string("here.") + frame + ".exr"));
    const trs::Image there = trs::read_exr(file(std::string("s/f.") + frame + ".exr"));
    EXPECT_EQ(here.rgb, there.rgb) << "frame " << frame;
  }
}

// A scene given by its bare file name, run from its own folder, finds its image sequence there
// (the folder of "clip.gltf" is empty, and the working directory is meant), still or animated.
TEST_F(RenderCliTest, ASceneNamedByItsBareFileNameFindsItsSequence) {
  write_file(file("clip.0.png"), trs_test::png_file(8, 8, 3, 8, std::vector<std::uint16_t>(8 * 8 * 3, 230)));
  write_file(file("clip.1.png"), trs_test::png_file(8, 8, 3, 8, std::vector<std::uint16_t>(8 * 8 * 3, 90)));
  write_quad_scene("clip.gltf", R"({"name": "screen", "emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 0}})",
                   R"("textures": [{"source": 0}], "images": [{"uri": "clip.0.png", "extras": {"frames": "clip.%d.png"}}],)");
  const fs::path before = fs::current_path();
  fs::current_path(file(""));
  const RunResult still = run(tiny("clip.gltf", {"--out", "still.exr"}));
  const RunResult animated = run(tiny("clip.gltf", {"--out", "clip.%d.exr", "--frames", "0:1"}));
  fs::current_path(before);
  EXPECT_EQ(still.status, 0) << still.err;
  EXPECT_EQ(animated.status, 0) << animated.err;
  EXPECT_TRUE(fs::exists(file("still.exr")));
  EXPECT_TRUE(fs::exists(file("clip.1.exr")));
}

// Each frame of a two-image sequence is the still render of that frame's image: bit for bit,
// frame f of a scene without animation rendered with the same seed stream; frame 0 is also the
// plain still render.
TEST_F(RenderCliTest, EachFrameIsTheStillRenderOfItsImage) {
  std::vector<std::uint16_t> bright(8 * 8 * 3, 230), pattern(8 * 8 * 3, 0);
  for (std::size_t i = 0; i < pattern.size(); i += 7) pattern[i] = 255;
  write_file(file("clip.0.png"), trs_test::png_file(8, 8, 3, 8, bright));
  write_file(file("clip.1.png"), trs_test::png_file(8, 8, 3, 8, pattern));
  const auto scene = [&](const std::string& name, const std::string& image) {
    return write_quad_scene(
        name, R"({"name": "screen", "emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 0}})",
        R"("textures": [{"source": 0}], "images": [)" + image + "],");
  };
  const fs::path animated = scene("clip.gltf", R"({"uri": "clip.0.png", "extras": {"frames": "clip.%d.png"}})");
  for (const std::string& strategy : kStrategies) {
    SCOPED_TRACE(strategy);
    const auto render = [&](const fs::path& gltf, const std::string& frames, const std::string& out) {
      std::vector<std::string> args = tiny(gltf, {"--strategy", strategy, "--backend", "cpu", "--out", file(out).string()});
      if (!frames.empty()) args.insert(args.end(), {"--frames", frames});
      const RunResult result = run(args);
      EXPECT_EQ(result.status, 0) << result.err;
      return read_render(file(frames.empty() ? out : std::string(out).replace(out.find("%d"), 2, frames.substr(0, 1))), 16, 9);
    };
    const auto frame0 = render(animated, "0:1", "anim.%d.exr");
    const auto frame1 = read_render(file("anim.1.exr"), 16, 9);
    const auto still0 = render(scene("still0.gltf", R"({"uri": "clip.0.png"})"), "", "still0.exr");
    const auto still1 = render(scene("still1.gltf", R"({"uri": "clip.1.png"})"), "1:1", "still1.%d.exr");
    ASSERT_TRUE(frame0 && frame1 && still0 && still1);
    EXPECT_EQ(frame0->rgb, still0->rgb);
    EXPECT_EQ(frame1->rgb, still1->rgb);
    EXPECT_NE(frame0->rgb, frame1->rgb);
  }
}

// A sequence with a frame that is not an image: the error names that file, and nothing is written.
TEST_F(RenderCliTest, ASequenceFrameThatIsNotAnImageIsNamed) {
  const std::vector<std::uint16_t> texels(4 * 4 * 3, 200);
  for (const char* name : {"poster.png", "clip.0.png"}) write_file(file(name), trs_test::png_file(4, 4, 3, 8, texels));
  write_text("clip.1.png", "not a png");
  const fs::path scene = write_quad_scene(
      "clip.gltf", R"({"name": "screen", "emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 0}})",
      R"("textures": [{"source": 0}], "images": [{"uri": "poster.png", "extras": {"frames": "clip.%d.png"}}],)");
  std::vector<std::string> args = tiny(scene, {"--frames", "0:1", "--out", file("clip.%d.exr").string()});
  expect_failure_naming(args, file("clip.1.png"));
}

enum class HandlerState { default_action, caught, exited };

/// Whether a running process has a handler installed for `signal`, from Linux's /proc.
HandlerState handler_state(pid_t pid, int signal) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("State:", 0) == 0 && line.find('Z') != std::string::npos)
      return HandlerState::exited;
    if (line.rfind("SigCgt:", 0) == 0) {
      const unsigned long long mask = std::stoull(line.substr(7), nullptr, 16);
      return mask & (1ull << (signal - 1)) ? HandlerState::caught : HandlerState::default_action;
    }
  }
  return HandlerState::exited;
}

/// Runs that a stop signal ends: SIGINT (Ctrl-C), SIGTERM (Slurm's time limit, scancel,
/// preemption) or SIGHUP.
class RenderCliStopTest : public RenderCliTest {
 protected:
  /// trs-render on `args`, sent `signal` once it has rendered for `rendering`: the handler is
  /// installed once the run starts (earlier, the signal just ends the process), and from then on a
  /// pass of these small images takes milliseconds. None (a failure recorded) if it never started.
  std::optional<RunResult> stopped(const std::vector<std::string>& args, int signal,
                                   std::chrono::milliseconds rendering) {
    const pid_t pid = start(args);
    if (pid <= 0) return std::nullopt;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    HandlerState state = HandlerState::default_action;
    while ((state = handler_state(pid, signal)) == HandlerState::default_action &&
           std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (state != HandlerState::caught) {
      ::kill(pid, SIGKILL);
      const RunResult failed = finish(pid);
      ADD_FAILURE() << "the render did not start: status " << failed.status << "\n" << failed.err;
      return std::nullopt;
    }
    std::this_thread::sleep_for(rendering);
    EXPECT_EQ(::kill(pid, signal), 0);
    return finish(pid);
  }
};

class RenderCliSignalTest : public RenderCliStopTest, public ::testing::WithParamInterface<int> {};

// 6. Ctrl-C, SIGTERM and SIGHUP: the passes done are saved with their stats, the run says it was
// interrupted, status 128 + the signal. A strategy named, so that the set-up is short: `auto`'s
// pilot for 100,000 passes weighs four strategies, seconds under the sanitizers, and a signal
// before the first pass saves nothing.
TEST_P(RenderCliSignalTest, SavesThePassesDone) {
  const int signal = GetParam();
  const fs::path exr = file("long.exr"), json = file("long.json");
  const std::optional<RunResult> result =
      stopped({kScene.string(), "--width", "64", "--height", "36", "--spp", "100000", "--lights", "1000",
               "--max-depth", "2", "--threads", "2", "--strategy", "trs", "--out", exr.string(), "--stats",
               json.string()},
              signal, std::chrono::milliseconds(1500));
  ASSERT_TRUE(result);
  EXPECT_EQ(result->status, 128 + signal) << result->err;
  EXPECT_NE(result->err.find("interrupted; saved "), std::string::npos) << result->err;
  EXPECT_EQ(listing(), (std::set<std::string>{"long.exr", "long.json"}));  // no temporaries
  const auto image = read_render(exr, 64, 36);
  ASSERT_TRUE(image);
  EXPECT_TRUE(any_positive(*image));
  const nlohmann::json stats = read_json(json);
  EXPECT_EQ(stats["interrupted"], true);
  const auto frames = stats["passes"].get<unsigned>();
  EXPECT_GE(frames, 1u);
  EXPECT_LE(frames, 99999u);
  EXPECT_EQ(stats["settings"]["spp"], 100000);
}

INSTANTIATE_TEST_SUITE_P(Signals, RenderCliSignalTest, ::testing::Values(SIGINT, SIGTERM, SIGHUP),
                         [](const ::testing::TestParamInfo<int>& info) { return std::string(sigabbrev_np(info.param)); });

// A sequence stopped in a frame keeps the frames written; the frame under way is dropped, or with
// --save-partial written under partial names with stats that say so. --resume renders that frame
// again and then removes its partial outputs.
TEST_F(RenderCliStopTest, ASequenceKeepsTheFrameUnderWayOnlyWithSavePartial) {
  const auto sequence = [&](const char* spp, const char* more) {
    std::vector<std::string> args =
        tiny(kAnimated, {"--frames", "0:1", "--out", file("f.%04d.exr").string(), "--stats",
                         file("f.%04d.json").string(), "--preview", file("f.%04d.png").string(), more});
    args.insert(args.end(), {"--spp", spp});  // after tiny()'s: the last wins
    return args;
  };
  const std::optional<RunResult> dropped = stopped(sequence("100000", "--quiet"), SIGTERM, std::chrono::milliseconds(1500));
  ASSERT_TRUE(dropped);
  EXPECT_EQ(dropped->status, 143) << dropped->err;
  EXPECT_NE(dropped->err.find("interrupted; frame 0 dropped (--save-partial keeps its passes)"), std::string::npos)
      << dropped->err;
  EXPECT_EQ(listing(), std::set<std::string>{});

  const std::optional<RunResult> kept = stopped(sequence("100000", "--save-partial"), SIGTERM, std::chrono::milliseconds(1500));
  ASSERT_TRUE(kept);
  EXPECT_EQ(kept->status, 143) << kept->err;
  EXPECT_NE(kept->err.find(" spp of frame 0 as " + file("f.0000.partial.exr").string()), std::string::npos) << kept->err;
  EXPECT_EQ(listing(), (std::set<std::string>{"f.0000.partial.exr", "f.0000.partial.json", "f.0000.partial.png"}));
  read_render(file("f.0000.partial.exr"), 16, 9);
  const nlohmann::json stats = read_json(file("f.0000.partial.json"));
  EXPECT_EQ(stats["interrupted"], true);
  EXPECT_EQ(stats["frame"], 0);
  EXPECT_GE(stats["passes"].get<unsigned>(), 1u);

  const RunResult resumed = run(sequence("2", "--resume"));
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  EXPECT_EQ(listing(), (std::set<std::string>{"f.0000.exr", "f.0000.json", "f.0000.png", "f.0001.exr", "f.0001.json",
                                              "f.0001.png"}));
  EXPECT_EQ(read_json(file("f.0000.json"))["interrupted"], false);
  EXPECT_EQ(read_json(file("f.0000.json"))["passes"], 2);
}

}  // namespace
