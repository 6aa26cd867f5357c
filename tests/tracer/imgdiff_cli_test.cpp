// The trs-imgdiff command line, run as a subprocess on small EXR images the tests write: its
// figures against values computed here from their definitions, the emitter mask, the JSON and
// the heatmap, and its exit statuses.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene_io/image_output.h"
#include "support/subprocess.h"

namespace {

namespace fs = std::filesystem;
using trs_test::RunResult;

class ImgdiffCliTest : public trs_test::ToolTest {
 protected:
  ImgdiffCliTest() : ToolTest(TRS_IMGDIFF_EXE) {}

  fs::path exr(const std::string& name, const std::vector<float>& rgb) {
    trs::write_exr(file(name), 2, 2, rgb.data());
    return file(name);
  }
};

// Four pixels; the last differs in red only, and is the one the mask leaves out.
const std::vector<float> kReference = {1, 1, 1, 0.5f, 0.25f, 0, 2, 2, 2, 0.1f, 0.2f, 0.3f};
const std::vector<float> kTest = {1.1f, 1, 0.9f, 0.5f, 0.25f, 0, 2, 2, 2.5f, 0.7f, 0.2f, 0.3f};

/// relMSE of the given values by its definition: mean of (x - r)^2 / (r^2 + 0.01).
double relmse(const std::vector<std::size_t>& values) {
  double sum = 0;
  for (std::size_t v : values) {
    const double e = double(kTest[v]) - double(kReference[v]);
    sum += e * e / (double(kReference[v]) * kReference[v] + 0.01);
  }
  return sum / double(values.size());
}

TEST_F(ImgdiffCliTest, FiguresPerChannelAndOverallFollowTheirDefinitions) {
  const fs::path test = exr("test.exr", kTest), reference = exr("ref.exr", kReference), json = file("d.json");
  const RunResult r = run({test.string(), reference.string(), "--json", json.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("relative MSE"), std::string::npos);
  EXPECT_NE(r.out.find("relMSE guard 0.01 "), std::string::npos) << r.out;
  const nlohmann::json d = nlohmann::json::parse(trs_test::read_file(json));
  EXPECT_EQ(d["relmse_guard"].get<double>(), 0.01);
  EXPECT_NEAR(d["R"]["relmse"].get<double>(), relmse({0, 3, 6, 9}), 1e-6);
  EXPECT_NEAR(d["B"]["relmse"].get<double>(), relmse({2, 5, 8, 11}), 1e-6);
  EXPECT_NEAR(d["overall"]["relmse"].get<double>(), relmse({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}), 1e-6);
  // Red: squared errors 0.01 and 0.36 over 4 values; the reference's red peaks at 2.
  const double mse = (0.01 + 0.36) / 4;
  EXPECT_NEAR(d["R"]["rmse"].get<double>(), std::sqrt(mse), 1e-6);
  EXPECT_NEAR(d["R"]["psnr"].get<double>(), 10 * std::log10(4 / mse), 1e-4);
  EXPECT_TRUE(d["G"]["psnr"].is_null()) << "green matches exactly: no PSNR";
  EXPECT_EQ(d["pixels"], 4);
  EXPECT_EQ(d["pass"], true);
}

TEST_F(ImgdiffCliTest, TheMaskLeavesPixelsOut) {
  const fs::path test = exr("test.exr", kTest), reference = exr("ref.exr", kReference), json = file("d.json");
  const fs::path mask = exr("mask.exr", {0, 0, 0, 0, 0, 0, 0, 0, 0, 0.25f, 0.25f, 0.25f});
  ASSERT_EQ(run({test.string(), reference.string(), "--mask", mask.string(), "--json", json.string()}).status, 0);
  const nlohmann::json d = nlohmann::json::parse(trs_test::read_file(json));
  EXPECT_EQ(d["pixels"], 3);
  EXPECT_EQ(d["pixels_left_out"], 1);
  EXPECT_NEAR(d["R"]["relmse"].get<double>(), relmse({0, 3, 6}), 1e-6);
  const fs::path small = file("small.exr");
  trs::write_exr(small, 1, 1, std::vector<float>(3, 0.0f).data());
  const RunResult wrong = run({test.string(), reference.string(), "--mask", small.string()});
  EXPECT_EQ(wrong.status, 1);
  EXPECT_NE(wrong.err.find("small.exr"), std::string::npos) << wrong.err;
}

TEST_F(ImgdiffCliTest, HeatmapIsAFalseColourPng) {
  const fs::path test = exr("test.exr", kTest), reference = exr("ref.exr", kReference), png = file("heat.png");
  ASSERT_EQ(run({test.string(), reference.string(), "--heatmap", png.string()}).status, 0);
  const trs::Image heat = trs::read_image(png);
  EXPECT_EQ(heat.width, 2u);
  EXPECT_EQ(heat.height, 2u);
  EXPECT_TRUE(heat.integer);
  // Pixel 1 matches exactly (darkest), pixel 3 is off by 0.6 in red (brighter).
  const auto brightness = [&](int p) { return heat.rgb[3 * p] + heat.rgb[3 * p + 1] + heat.rgb[3 * p + 2]; };
  EXPECT_LT(brightness(1), brightness(3));
}

TEST_F(ImgdiffCliTest, ExitStatusesAreKept) {
  const fs::path test = exr("test.exr", kTest), reference = exr("ref.exr", kReference);
  EXPECT_EQ(run({test.string(), reference.string(), "--max-relmse", "1e-6"}).status, 1);
  EXPECT_EQ(run({test.string(), reference.string(), "--max-relmse", "10"}).status, 0);
  EXPECT_EQ(run({test.string()}).status, 2);
  EXPECT_EQ(run({test.string(), reference.string(), "--variance", test.string()}).status, 2);
  EXPECT_EQ(run({test.string(), file("missing.exr").string()}).status, 1);
}

}  // namespace
