// End-to-end tests of the trs-sample command line: the tool runs as a subprocess on small inputs
// written by each test into a fresh temporary directory (meshes by hand, images with
// support/image_files.h), and the tests read back its exit status, stdout, stderr and output
// files.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "lightsampler/refinement.h"
#include "support/gltf_quad.h"
#include "support/image_files.h"
#include "support/subprocess.h"

namespace {

namespace fs = std::filesystem;
using trs_test::read_file;
using trs_test::RunResult;
using trs_test::write_file;

struct PlySample {
  float x, y, z, u, v;
  std::uint32_t triangle;
  float b1, b2;
};
static_assert(sizeof(PlySample) == 32);

struct PlyFile {
  std::string header;
  std::vector<PlySample> samples;
};

PlyFile read_ply(const fs::path& file) {
  const std::string bytes = read_file(file);
  const std::string end = "end_header\n";
  const std::size_t header_end = bytes.find(end);
  PlyFile ply;
  if (header_end == std::string::npos) return ply;
  ply.header = bytes.substr(0, header_end + end.size());
  const std::size_t body = bytes.size() - ply.header.size();
  ply.samples.resize(body / sizeof(PlySample));
  std::memcpy(ply.samples.data(), bytes.data() + ply.header.size(),
              ply.samples.size() * sizeof(PlySample));
  return ply;
}

std::string expected_ply_header(std::uint64_t count, bool obj_convention) {
  return std::string("ply\n") +
         "format binary_little_endian 1.0\n"
         "comment samples of trs-sample; uv: v = 0 at the image's " +
         (obj_convention ? "bottom row (OBJ convention)" : "top row (glTF convention)") +
         "\n"
         "element vertex " +
         std::to_string(count) +
         "\n"
         "property float x\n"
         "property float y\n"
         "property float z\n"
         "property float u\n"
         "property float v\n"
         "property uint triangle\n"
         "property float b1\n"
         "property float b2\n"
         "end_header\n";
}

// A unit quad in the z = 0 plane whose UVs equal its (x, y) positions.
const char* kQuadObj =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "f 1/1 2/2 3/3 4/4\n";

/// The quad's glTF document, its node translated by (10, 0, 0); `buffer` is the buffer object.
std::string quad_gltf_json(const std::string& buffer) {
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0, "translation": [10, 0, 0]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2}]}],
  "buffers": [)" +
         buffer + R"(],
  )" + trs_test::kQuadGltfViews + "}";
}

/// A binary glTF: header, JSON chunk (padded with spaces), BIN chunk (padded with zeros).
std::string make_glb(std::string json, std::string bin) {
  json.resize((json.size() + 3) / 4 * 4, ' ');
  bin.resize((bin.size() + 3) / 4 * 4, '\0');
  auto u32 = [](std::uint32_t value) {
    return std::string(reinterpret_cast<const char*>(&value), 4);
  };
  const auto total = std::uint32_t(12 + 8 + json.size() + 8 + bin.size());
  return "glTF" + u32(2) + u32(total) + u32(std::uint32_t(json.size())) + "JSON" + json +
         u32(std::uint32_t(bin.size())) + std::string("BIN\0", 4) + bin;
}

/// Every run gets `--threads 2`.
class CliTest : public trs_test::ToolTest {
 protected:
  CliTest() : ToolTest(TRS_SAMPLE_EXE, {"--threads", "2"}) {}

  /// Writes a single-channel float OpenEXR map.
  fs::path write_exr_map(const std::string& name, int width, int height,
                         const std::vector<float>& texels) {
    trs_test::write_float_exr(file(name), width, height, 1, texels);
    return file(name);
  }

  /// Writes an 8-bit PNG of `channels` channels.
  fs::path write_png(const std::string& name, int width, int height, int channels,
                     const std::vector<std::uint16_t>& samples) {
    return write_text(name, trs_test::png_file(width, height, channels, 8, samples));
  }

  /// A 4 x 4 map, `value` in the top row (row 0), zero elsewhere.
  fs::path write_top_row_map(const std::string& name, float value) {
    std::vector<float> texels(16, 0.0f);
    for (int x = 0; x < 4; ++x) texels[x] = value;
    return write_exr_map(name, 4, 4, texels);
  }

  fs::path write_constant_map(const std::string& name, float value) {
    return write_exr_map(name, 4, 4, std::vector<float>(16, value));
  }

  fs::path write_quad_gltf(const std::string& name) {
    write_file(file("quad.bin"), trs_test::quad_gltf_buffer());
    return write_text(name, quad_gltf_json(R"({"uri": "quad.bin", "byteLength": 92})"));
  }
};

nlohmann::json read_json(const fs::path& file) { return nlohmann::json::parse(read_file(file)); }

TEST_F(CliTest, WritesPlyAndStatsThatAgree) {
  const fs::path mesh = write_text("quad.obj", kQuadObj);
  const fs::path map = write_constant_map("map.exr", 100.0f);
  const RunResult result = run({mesh, map, "--count", "5e2", "--seed", "7", "--out", file("s.ply"),
                                "--stats", file("s.json")});
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_NE(result.out.find("quad.obj"), std::string::npos) << result.out;

  const nlohmann::json stats = read_json(file("s.json"));
  for (const char* key : {"expected_total", "sample_count", "candidates", "acceptance_rate",
                          "exhausted", "exact_draws", "method", "backend", "device", "threads", "seed",
                          "target_count", "scan", "triangles", "map", "mesh", "ms", "construction"}) {
    EXPECT_TRUE(stats.contains(key)) << key;
  }
  EXPECT_EQ(stats["construction"]["parts"], 2);  // a constant map: nothing to split
  EXPECT_GE(stats["construction"]["ms"].get<double>(), stats["construction"]["subdivision_ms"].get<double>());
  EXPECT_EQ(stats["mesh"], mesh.string());
  EXPECT_EQ(stats["map"]["file"], map.string());
  EXPECT_EQ(stats["map"]["width"], 4);
  EXPECT_EQ(stats["map"]["height"], 4);
  EXPECT_EQ(stats["triangles"], 2);
  EXPECT_EQ(stats["method"], "trs");
  EXPECT_EQ(stats["backend"], "cpu");
  EXPECT_EQ(stats["threads"], 2);
  EXPECT_EQ(stats["seed"], 7);
  EXPECT_EQ(stats["target_count"], 500.0);
  EXPECT_NEAR(stats["expected_total"].get<double>(), 100.0, 1e-3);
  EXPECT_EQ(stats["exhausted"], 0);
  EXPECT_TRUE(stats["ms"].contains("total"));
  EXPECT_GE(stats["ms"].size(), 2u);

  const auto count = stats["sample_count"].get<std::uint64_t>();
  EXPECT_GT(count, 400u);
  EXPECT_LT(count, 600u);
  const PlyFile ply = read_ply(file("s.ply"));
  EXPECT_EQ(ply.header, expected_ply_header(count, true));
  EXPECT_EQ(fs::file_size(file("s.ply")), ply.header.size() + 32 * count);
  ASSERT_EQ(ply.samples.size(), count);
  for (const PlySample& s : ply.samples) {
    ASSERT_LT(s.triangle, 2u);
    ASSERT_GE(s.b1, 0.0f);
    ASSERT_GE(s.b2, 0.0f);
    ASSERT_LE(s.b1 + s.b2, 1.0f + 1e-6f);
    ASSERT_NEAR(s.u, s.x, 1e-5f);  // the quad's UVs equal its positions, in the OBJ convention
    ASSERT_NEAR(s.v, s.y, 1e-5f);
  }
}

TEST_F(CliTest, WritesNothingWithoutOut) {
  const fs::path mesh = write_text("quad.obj", kQuadObj);
  const fs::path map = write_constant_map("map.exr", 100.0f);
  const std::set<std::string> before = listing();
  const RunResult result = run({mesh, map, "--count", "1e4"});
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(listing(), before);
  EXPECT_NE(result.out.find("samples"), std::string::npos) << result.out;
}

TEST_F(CliTest, RefinementIsAutomaticByDefault) {
  const fs::path mesh = write_quad_gltf("quad.gltf");
  const fs::path map = write_top_row_map("map.exr", 400.0f);
  for (const auto& [args, refine] : std::vector<std::pair<std::vector<std::string>, double>>{
           {{}, lightsampler::kAutoMinAcceptance}, {{"--refine", "auto"}, lightsampler::kAutoMinAcceptance},
           {{"--refine", "0"}, 0.0}, {{"--refine", "0.75"}, 0.75}}) {
    std::vector<std::string> command = {mesh.string(), map.string(), "--count", "1000", "--stats", file("s.json").string()};
    command.insert(command.end(), args.begin(), args.end());
    const RunResult result = run(command);
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_FLOAT_EQ(read_json(file("s.json"))["refine"].get<double>(), refine);
  }
}

TEST_F(CliTest, RejectionMethodAndOrderedScan) {
  const fs::path mesh = write_quad_gltf("quad.gltf");
  const fs::path map = write_top_row_map("map.exr", 400.0f);
  const RunResult result = run({mesh, map, "--method", "rs", "--scan", "ordered", "--count", "1000",
                                "--stats", file("s.json")});
  ASSERT_EQ(result.status, 0) << result.err;
  const nlohmann::json stats = read_json(file("s.json"));
  EXPECT_EQ(stats["method"], "rs");
  EXPECT_GT(stats["candidates"].get<std::uint64_t>(), stats["sample_count"].get<std::uint64_t>());
}

TEST_F(CliTest, NaiveAndFastRejectionSamplingOnBothBackends) {
  const fs::path mesh = write_quad_gltf("quad.gltf");
  const fs::path map = write_top_row_map("map.exr", 400.0f);
  for (const std::string backend : {"cpu", "vulkan"})
    for (const std::string method : {"naive", "frs"}) {
      SCOPED_TRACE(backend + " " + method);
      const RunResult result = run({mesh, map, "--method", method, "--backend", backend, "--count", "1000",
                                    "--stats", file("s.json")});
      if (result.status != 0 && backend == "vulkan") {
        const char* required = std::getenv("LIGHTSAMPLER_REQUIRE_VULKAN");
        if (required && std::string(required) == "1") FAIL() << "Vulkan is required here: " << result.err;
        GTEST_SKIP() << "no Vulkan device: " << result.err;
      }
      ASSERT_EQ(result.status, 0) << result.err;
      const nlohmann::json stats = read_json(file("s.json"));
      EXPECT_EQ(stats["method"], method);
      EXPECT_EQ(stats["backend"], backend);
      EXPECT_GT(stats["sample_count"].get<std::uint64_t>(), 900u);
      EXPECT_EQ(stats["setup_bytes"].get<std::uint64_t>() > 0, method == "frs");
    }
}

TEST_F(CliTest, OverlapFormulasAndTheLookbackScanOnTheCpu) {
  const fs::path mesh = write_quad_gltf("quad.gltf");
  const fs::path map = write_top_row_map("map.exr", 400.0f);
  for (const std::string overlap : {"closed-form", "clipping", "sdf"}) {
    const RunResult result = run({mesh, map, "--overlap", overlap, "--backend", "cpu", "--count", "1000",
                                  "--stats", file("s.json")});
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(read_json(file("s.json"))["overlap"], overlap);
  }
  EXPECT_EQ(run({mesh, map, "--overlap", "exact"}).status, 2);
  // Exact draws after every rejection: some slots of the top-row map are drawn exactly.
  const RunResult exact = run({mesh, map, "--exact-after", "1", "--refine", "0", "--backend", "cpu", "--count",
                               "1000", "--stats", file("s.json")});
  ASSERT_EQ(exact.status, 0) << exact.err;
  EXPECT_GT(read_json(file("s.json"))["exact_draws"].get<std::uint64_t>(), 0u);
  EXPECT_EQ(run({mesh, map, "--exact-after", "-1"}).status, 2);
  const RunResult lookback = run({mesh, map, "--scan", "lookback", "--backend", "cpu", "--count", "1000"});
  EXPECT_EQ(lookback.status, 1);
  EXPECT_NE(lookback.err.find("Vulkan backend only"), std::string::npos) << lookback.err;
}

// Density only in the top image row. OBJ puts v = 0 at the image's bottom, so the samples are at
// the quad's high-v end (v_obj near 1); glTF puts v = 0 at the top, so they are at low v.
TEST_F(CliTest, ObjAndGltfUvConventions) {
  const fs::path map = write_top_row_map("map.exr", 4000.0f);
  const fs::path obj = write_text("quad.obj", kQuadObj);
  ASSERT_EQ(run({obj, map, "--out", file("obj.ply")}).status, 0);
  const PlyFile from_obj = read_ply(file("obj.ply"));
  ASSERT_GT(from_obj.samples.size(), 500u);  // N-bar = 4000 * 1/4
  for (const PlySample& s : from_obj.samples) {
    ASSERT_GE(s.v, 0.75f - 1e-5f);
    ASSERT_GE(s.y, 0.75f - 1e-5f);
    ASSERT_NEAR(s.v, s.y, 1e-5f);
  }

  const fs::path gltf = write_quad_gltf("quad.gltf");
  ASSERT_EQ(run({gltf, map, "--out", file("gltf.ply")}).status, 0);
  const PlyFile from_gltf = read_ply(file("gltf.ply"));
  EXPECT_EQ(from_gltf.header, expected_ply_header(from_gltf.samples.size(), false));
  ASSERT_GT(from_gltf.samples.size(), 500u);
  for (const PlySample& s : from_gltf.samples) {
    ASSERT_LE(s.v, 0.25f + 1e-5f);
    ASSERT_LE(s.y, 0.25f + 1e-5f);
    ASSERT_NEAR(s.x, 10.0f + s.u, 1e-5f);  // the node's translation is applied
  }
}

TEST_F(CliTest, ReadsBinaryGltf) {
  const std::string json = quad_gltf_json(R"({"byteLength": 92})");
  write_file(file("quad.glb"), make_glb(json, trs_test::quad_gltf_buffer()));
  const fs::path map = write_constant_map("map.exr", 100.0f);
  const RunResult result = run({file("quad.glb"), map, "--stats", file("s.json")});
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(read_json(file("s.json"))["triangles"], 2);
}

// A U-shaped octagon of area 5: a fan from its first corner would cover area 7.
TEST_F(CliTest, TriangulatesConcavePolygons) {
  const fs::path mesh = write_text("u.obj",
                                   "v 0 0 0\nv 3 0 0\nv 3 2 0\nv 2 2 0\nv 2 1 0\nv 1 1 0\n"
                                   "v 1 2 0\nv 0 2 0\nvt 0.5 0.5\n"
                                   "f 1/1 2/1 3/1 4/1 5/1 6/1 7/1 8/1\n");
  const fs::path map = write_constant_map("map.exr", 100.0f);
  const RunResult result = run({mesh, map, "--stats", file("s.json")});
  ASSERT_EQ(result.status, 0) << result.err;
  const nlohmann::json stats = read_json(file("s.json"));
  EXPECT_EQ(stats["triangles"], 6);
  EXPECT_NEAR(stats["expected_total"].get<double>(), 500.0, 1e-3);
}

// 8-bit images are sRGB-encoded unless told otherwise; colour maps give their luminance.
TEST_F(CliTest, DecodesSrgbAndTakesLuminance) {
  const fs::path mesh = write_text("quad.obj", kQuadObj);
  const fs::path grey = write_png("grey.png", 1, 1, 1, {128});
  const fs::path red = write_png("red.png", 1, 1, 3, {255, 0, 0});
  auto expected_total = [&](const fs::path& map, const std::string& encoding) {
    const RunResult result = run({mesh, map, "--density-scale", "1000", "--map-encoding", encoding,
                                  "--stats", file("s.json")});
    EXPECT_EQ(result.status, 0) << result.err;
    return read_json(file("s.json"))["expected_total"].get<double>();
  };
  const double srgb_half = std::pow((128.0 / 255.0 + 0.055) / 1.055, 2.4);
  EXPECT_NEAR(expected_total(grey, "auto"), 1000 * srgb_half, 0.01);
  EXPECT_NEAR(expected_total(grey, "linear"), 1000 * 128.0 / 255.0, 0.01);
  EXPECT_NEAR(expected_total(red, "auto"), 212.6, 0.01);
}

TEST_F(CliTest, UsageErrorsExitWithTwo) {
  const fs::path mesh = write_text("quad.obj", kQuadObj);
  const fs::path map = write_constant_map("map.exr", 1.0f);
  EXPECT_EQ(run({mesh}).status, 2);
  EXPECT_EQ(run({mesh, map, "--count", "-5"}).status, 2);
  EXPECT_EQ(run({mesh, map, "--count", "nan"}).status, 2);
  EXPECT_EQ(run({mesh, map, "--method", "mcmc"}).status, 2);
  EXPECT_EQ(run({mesh, map, "--no-such-option"}).status, 2);
  EXPECT_EQ(run({mesh, map, "--backend", "opencl"}).status, 2);
  EXPECT_EQ(run({mesh, map, "--counting", "magic"}).status, 2);
  EXPECT_EQ(run({mesh, map, "--refine", "often"}).status, 2);
  EXPECT_EQ(run({mesh, map, "--refine", "1.5"}).status, 2);
  EXPECT_EQ(run({mesh, map, "--backend", "auto"}).status, 0);
}

TEST_F(CliTest, VulkanBackendNamesItsDevice) {
  const fs::path mesh = write_text("quad.obj", kQuadObj);
  const fs::path map = write_constant_map("map.exr", 1.0f);
  const RunResult missing = run({mesh, map, "--backend", "vulkan", "--device", "no-such-gpu"});
  EXPECT_EQ(missing.status, 1);
  EXPECT_NE(missing.err.find("no-such-gpu"), std::string::npos) << missing.err;

  for (const char* counting : {"raster", "compute"}) {
    const RunResult r = run({mesh, map, "--backend", "vulkan", "--counting", counting, "--count", "1000",
                             "--stats", file("v.json")});
    if (r.status != 0) {
      const char* required = std::getenv("LIGHTSAMPLER_REQUIRE_VULKAN");
      if (required && std::string(required) == "1") FAIL() << "Vulkan is required here: " << r.err;
      GTEST_SKIP() << "no Vulkan device: " << r.err;
    }
    const auto stats = read_json(file("v.json"));
    EXPECT_EQ(stats["backend"], "vulkan");
    EXPECT_FALSE(stats["device"].get<std::string>().empty());
    EXPECT_EQ(stats["counting"], counting);
    EXPECT_EQ(stats["sample_count"], 1000);
  }
}

TEST_F(CliTest, MissingInputs) {
  const fs::path mesh = write_text("quad.obj", kQuadObj);
  const fs::path map = write_constant_map("map.exr", 1.0f);
  expect_failure_naming({file("absent.obj"), map}, file("absent.obj"));
  expect_failure_naming({mesh, file("absent.exr")}, file("absent.exr"));
}

TEST_F(CliTest, BadObjFiles) {
  const fs::path map = write_constant_map("map.exr", 1.0f);
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n";
  const fs::path out_of_range = write_text("range.obj", vertices + "f 1/1 2/2 9/3\n");
  expect_failure_naming({out_of_range, map}, out_of_range);
  const fs::path truncated = write_text("truncated.obj", vertices + "f 1/1 2/2 3/");
  expect_failure_naming({truncated, map}, truncated);
  const fs::path cut_face = write_text("cut.obj", vertices + "f 1/1 2/2");
  expect_failure_naming({cut_face, map}, cut_face);
  const fs::path no_uvs = write_text("nouvs.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
  expect_failure_naming({no_uvs, map}, no_uvs);
  const fs::path no_faces = write_text("nofaces.obj", vertices);
  expect_failure_naming({no_faces, map}, no_faces);
}

// The OBJ parser reads a number it cannot parse as 0: each such field is refused, named by its
// element, index and line.
TEST_F(CliTest, NonFiniteObjNumbersAreRefused) {
  const fs::path map = write_constant_map("map.exr", 1.0f);
  const std::string face = "f 1/1 2/2 3/3\n";
  for (const auto& [text, where] : std::vector<std::pair<std::string, std::string>>{
           {"v nan 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n", "vertex 1 (line 1): 'nan'"},
           {"v 0 0 0\nv 1 -inf 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n", "vertex 2 (line 2): '-inf'"},
           {"v 0 0 0\nv 1 0 0\nv 1 1 1e999\nvt 0 0\nvt 1 0\nvt 1 1\n", "vertex 3 (line 3): '1e999'"},
           {"v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 NaN\nvt 1 1\n", "texture coordinate 2 (line 5): 'NaN'"},
           {"v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\n  vt\tx 1\n", "texture coordinate 3 (line 6): 'x'"}}) {
    const fs::path mesh = write_text("bad.obj", text + face);
    expect_failure_naming({mesh, map}, mesh);
    EXPECT_NE(run({mesh, map}).err.find(where), std::string::npos) << text;
  }
  const fs::path signed_numbers = write_text("signed.obj", "v +0 0 0\nv 1 0 0\nv 1 1 -0\nvt 0 0\nvt 1 0\nvt 1 1\n" + face);
  EXPECT_EQ(run({signed_numbers, map}).status, 0);
}

TEST_F(CliTest, BadGltfFiles) {
  const fs::path map = write_constant_map("map.exr", 1.0f);
  const fs::path malformed =
      write_text("malformed.gltf", R"({"asset": {"version": "2.0"}, "scenes": [)");
  expect_failure_naming({malformed, map}, malformed);

  const fs::path missing_bin =
      write_text("nobin.gltf", quad_gltf_json(R"({"uri": "absent.bin", "byteLength": 92})"));
  expect_failure_naming({missing_bin, map}, missing_bin);

  write_file(file("short.bin"), trs_test::quad_gltf_buffer().substr(0, 60));
  const fs::path short_bin =
      write_text("short.gltf", quad_gltf_json(R"({"uri": "short.bin", "byteLength": 60})"));
  expect_failure_naming({short_bin, map}, short_bin);

  std::string no_uv_json = quad_gltf_json(R"({"uri": "quad.bin", "byteLength": 92})");
  no_uv_json.replace(no_uv_json.find(R"(, "TEXCOORD_0": 1)"), std::strlen(R"(, "TEXCOORD_0": 1)"),
                     "");
  write_file(file("quad.bin"), trs_test::quad_gltf_buffer());
  const fs::path no_uvs = write_text("nouvs.gltf", no_uv_json);
  expect_failure_naming({no_uvs, map}, no_uvs);
}

TEST_F(CliTest, BadDensityMaps) {
  const fs::path mesh = write_text("quad.obj", kQuadObj);

  std::vector<std::uint16_t> gradient(64 * 64 * 3);
  for (std::size_t i = 0; i < gradient.size(); ++i) gradient[i] = std::uint16_t(i % 251);
  const fs::path png = write_png("truncated.png", 64, 64, 3, gradient);
  fs::resize_file(png, fs::file_size(png) / 2);
  expect_failure_naming({mesh, png}, png);

  std::vector<float> texels(16, 1.0f);
  texels[5] = std::numeric_limits<float>::quiet_NaN();
  const fs::path nan = write_exr_map("nan.exr", 4, 4, texels);
  expect_failure_naming({mesh, nan}, nan);

  texels[5] = -1.0f;
  const fs::path negative = write_exr_map("negative.exr", 4, 4, texels);
  expect_failure_naming({mesh, negative}, negative);

  // JPEG readers fill a truncated image with grey and only record the error.
  const std::vector<unsigned char> bytes(gradient.begin(), gradient.end());
  const std::string jpeg_bytes = trs_test::jpeg_file(64, 64, bytes, 90);
  const fs::path jpeg = write_text("truncated.jpg", jpeg_bytes.substr(0, jpeg_bytes.size() / 2));
  expect_failure_naming({mesh, jpeg}, jpeg);

  const fs::path not_an_image = write_text("garbage.png", "this is not an image");
  expect_failure_naming({mesh, not_an_image}, not_an_image);
}

// A header may claim any size: a map larger than 16384 x 16384 is refused before its pixels are
// allocated (a binary PPM header of 100000 x 100000 with no pixels after it).
TEST_F(CliTest, ImageHeadersClaimingHugeSizesAreRefused) {
  const fs::path mesh = write_text("quad.obj", kQuadObj);
  const fs::path huge = write_text("huge.ppm", "P6\n100000 100000\n255\n");
  expect_failure_naming({mesh, huge}, huge);
  EXPECT_NE(run({mesh, huge}).err.find("100000 x 100000 texels, more than the 16384 x 16384"), std::string::npos);
}

TEST_F(CliTest, FailedRunLeavesExistingOutputsUntouched) {
  const fs::path mesh = write_text("quad.obj", kQuadObj);
  std::vector<float> texels(16, 1.0f);
  texels[3] = -2.0f;
  const fs::path bad_map = write_exr_map("bad.exr", 4, 4, texels);
  const std::string old_ply = "previous samples\n", old_json = "{\"previous\": true}\n";
  write_file(file("out.ply"), old_ply);
  write_file(file("out.json"), old_json);
  expect_failure_naming({mesh, bad_map, "--out", file("out.ply"), "--stats", file("out.json")},
                        bad_map);
  EXPECT_EQ(read_file(file("out.ply")), old_ply);
  EXPECT_EQ(read_file(file("out.json")), old_json);
}

TEST_F(CliTest, UnwritableOutputIsNamed) {
  const fs::path mesh = write_text("quad.obj", kQuadObj);
  const fs::path map = write_constant_map("map.exr", 1.0f);
  const fs::path out = file("no-such-directory") / "s.ply";
  expect_failure_naming({mesh, map, "--out", out}, out);
}

}  // namespace
