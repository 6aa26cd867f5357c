// trs-imgdiff: compares a render with a reference, allowing for Monte Carlo noise.
//
// Always printed: the relative MSE of the test against the reference (per-pixel squared error of
// luminance over reference^2 + 0.01, averaged). With the variance images trs-render writes
// (--variance) and both sample counts, it also runs a noise-aware test: the image is cut into
// tiles, and each tile's mean luminance difference is divided by its standard error (from the
// per-sample variances of both images). Averaging a tile first tames the heavy tails of path
// tracing noise. The test fails when any tile lies more than --sigmas standard errors away.
// Exit status: 0 pass, 1 fail or bad input, 2 bad command line.

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>

#include "scene_io/color.h"
#include "scene_io/file_error.h"
#include "scene_io/image_output.h"

namespace trs {
namespace {

struct Options {
  std::filesystem::path test, reference, test_variance, reference_variance;
  unsigned test_spp = 0, reference_spp = 0, tile = 8;
  double sigmas = 6.0;
  double max_relmse = -1.0;
};

double luminance(const float* rgb) { return trs::luminance<double>(rgb[0], rgb[1], rgb[2]); }

void check_same_size(const Image& a, const Image& b, const std::filesystem::path& file) {
  if (a.width != b.width || a.height != b.height)
    throw FileError(file, std::to_string(b.width) + " x " + std::to_string(b.height) +
                              " pixels; expected " + std::to_string(a.width) + " x " +
                              std::to_string(a.height));
}

double relative_mse(const Image& test, const Image& reference) {
  const std::size_t pixels = std::size_t(test.width) * test.height;
  double sum = 0.0;
  for (std::size_t i = 0; i < pixels; ++i) {
    const double r = luminance(&reference.rgb[3 * i]);
    const double e = luminance(&test.rgb[3 * i]) - r;
    sum += e * e / (r * r + 0.01);
  }
  return sum / double(pixels);
}

/// The largest |z| over tiles, where z is a tile's mean difference over its standard error.
double worst_tile(const Options& o, const Image& test, const Image& reference,
                  const Image& test_var, const Image& reference_var) {
  double worst = 0.0;
  for (std::uint32_t ty = 0; ty < test.height; ty += o.tile) {
    for (std::uint32_t tx = 0; tx < test.width; tx += o.tile) {
      double difference = 0.0, variance = 0.0;
      std::size_t count = 0;
      for (std::uint32_t y = ty; y < std::min(test.height, ty + o.tile); ++y) {
        for (std::uint32_t x = tx; x < std::min(test.width, tx + o.tile); ++x) {
          const std::size_t i = std::size_t(y) * test.width + x;
          difference += luminance(&test.rgb[3 * i]) - luminance(&reference.rgb[3 * i]);
          variance += test_var.rgb[3 * i] / o.test_spp + reference_var.rgb[3 * i] / o.reference_spp;
          ++count;
        }
      }
      // A floor on the error: black tiles have no variance, and float rounding is not noise.
      const double error = std::sqrt(variance) + 1e-6 * count;
      worst = std::max(worst, std::abs(difference) / error);
    }
  }
  return worst;
}

int run(const Options& o) {
  const Image test = read_exr(o.test), reference = read_exr(o.reference);
  check_same_size(reference, test, o.test);
  const double relmse = relative_mse(test, reference);
  std::printf("relative MSE %.6g\n", relmse);
  bool pass = o.max_relmse < 0.0 || relmse <= o.max_relmse;
  if (!o.test_variance.empty()) {
    const Image test_var = read_exr(o.test_variance), reference_var = read_exr(o.reference_variance);
    check_same_size(reference, test_var, o.test_variance);
    check_same_size(reference, reference_var, o.reference_variance);
    const double z = worst_tile(o, test, reference, test_var, reference_var);
    std::printf("worst %u x %u tile: %.3g standard errors (limit %.3g)\n", o.tile, o.tile, z,
                o.sigmas);
    pass = pass && z <= o.sigmas;
  }
  std::printf("%s\n", pass ? "pass" : "FAIL");
  return pass ? 0 : 1;
}

}  // namespace
}  // namespace trs

int main(int argc, char** argv) {
  CLI::App app("Compares a render with a reference image, allowing for Monte Carlo noise.",
               "trs-imgdiff");
  trs::Options o;
  app.add_option("TEST", o.test, "the render (OpenEXR)")->required();
  app.add_option("REFERENCE", o.reference, "the reference (OpenEXR)")->required();
  app.add_option("--max-relmse", o.max_relmse, "fail above this relative MSE");
  auto* tv = app.add_option("--variance", o.test_variance, "per-sample variance of TEST");
  auto* rv = app.add_option("--reference-variance", o.reference_variance,
                            "per-sample variance of REFERENCE");
  auto* ts = app.add_option("--spp", o.test_spp, "samples per pixel of TEST")->check(CLI::PositiveNumber);
  auto* rs = app.add_option("--reference-spp", o.reference_spp, "samples per pixel of REFERENCE")
                 ->check(CLI::PositiveNumber);
  tv->needs(rv, ts, rs);
  rv->needs(tv);
  app.add_option("--tile", o.tile, "tile size, pixels")->check(CLI::PositiveNumber)->capture_default_str();
  app.add_option("--sigmas", o.sigmas, "most standard errors a tile may lie away")->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    return trs::run(o);
  } catch (const std::exception& e) {
    std::cerr << "trs-imgdiff: error: " << e.what() << "\n";
    return 1;
  }
}
