// trs-imgdiff: compares a render with a reference, allowing for Monte Carlo noise.
//
// Always printed: the relative MSE of the test's luminance against the reference's (per-pixel
// squared error over reference^2 + a guard, averaged; scene_io/relmse.h) and that guard, then
// RMSE, relMSE and PSNR per channel and over all three. With the variance images trs-render
// writes (--variance) and both sample counts, it also runs a noise-aware test: the image is cut
// into tiles, and each tile's mean luminance difference is divided by its standard error (from
// the per-sample variances of both images). Averaging a tile first tames the heavy tails of path
// tracing noise. The test fails when any tile lies more than --sigmas standard errors away.
// --mask leaves out the pixels an emitter mask (trs-render --emitter-mask) marks: there the noise
// is the pixel footprint over an emitter, whatever the light strategy.
// Exit status: 0 pass, 1 fail or bad input, 2 bad command line.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <optional>
#include <string>

#include "scene_io/relmse.h"
#include "scene_io/atomic_file.h"
#include "scene_io/color.h"
#include "scene_io/file_error.h"
#include "scene_io/image_output.h"

namespace trs {
namespace {

struct Options {
  std::filesystem::path test, reference, test_variance, reference_variance, mask, json, heatmap;
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

/// Which pixels count: all, or those the emitter mask leaves at zero.
std::vector<bool> counted_pixels(const Options& o, const Image& reference) {
  const std::size_t pixels = std::size_t(reference.width) * reference.height;
  std::vector<bool> counted(pixels, true);
  if (o.mask.empty()) return counted;
  const Image mask = read_exr(o.mask);
  check_same_size(reference, mask, o.mask);
  for (std::size_t i = 0; i < pixels; ++i) counted[i] = mask.rgb[3 * i] == 0.0f;
  return counted;
}

struct Errors {
  double rmse = 0, relmse = 0, psnr = 0;
};

/// RMSE, relMSE and PSNR (against the reference's largest value in the counted pixels) of
/// channel `c` (0, 1, 2), or of all three (c = 3).
Errors channel_errors(const Image& test, const Image& reference, const std::vector<bool>& counted, int c) {
  double squared = 0, relative = 0, peak = 0;
  std::size_t values = 0;
  for (std::size_t i = 0; i < counted.size(); ++i) {
    if (!counted[i]) continue;
    for (int k = c == 3 ? 0 : c; k < (c == 3 ? 3 : c + 1); ++k) {
      const double x = test.rgb[3 * i + k], r = reference.rgb[3 * i + k];
      squared += (x - r) * (x - r);
      relative += relative_squared_error(x, r);
      peak = std::max(peak, r);
      ++values;
    }
  }
  if (values == 0) return {};
  const double mse = squared / double(values);
  return {std::sqrt(mse), relative / double(values),
          mse > 0 ? 10.0 * std::log10(peak * peak / mse) : std::numeric_limits<double>::infinity()};
}

double luminance_relmse(const Image& test, const Image& reference, const std::vector<bool>& counted) {
  double sum = 0.0;
  std::size_t pixels = 0;
  for (std::size_t i = 0; i < counted.size(); ++i) {
    if (!counted[i]) continue;
    sum += relative_squared_error(luminance(&test.rgb[3 * i]), luminance(&reference.rgb[3 * i]));
    ++pixels;
  }
  return pixels > 0 ? sum / double(pixels) : 0.0;
}

/// The largest |z| over tiles, where z is a tile's mean difference over its standard error.
double worst_tile(const Options& o, const Image& test, const Image& reference, const Image& test_var,
                  const Image& reference_var, const std::vector<bool>& counted) {
  double worst = 0.0;
  for (std::uint32_t ty = 0; ty < test.height; ty += o.tile) {
    for (std::uint32_t tx = 0; tx < test.width; tx += o.tile) {
      double difference = 0.0, variance = 0.0;
      std::size_t count = 0;
      for (std::uint32_t y = ty; y < std::min(test.height, ty + o.tile); ++y) {
        for (std::uint32_t x = tx; x < std::min(test.width, tx + o.tile); ++x) {
          const std::size_t i = std::size_t(y) * test.width + x;
          if (!counted[i]) continue;
          difference += luminance(&test.rgb[3 * i]) - luminance(&reference.rgb[3 * i]);
          variance += test_var.rgb[3 * i] / o.test_spp + reference_var.rgb[3 * i] / o.reference_spp;
          ++count;
        }
      }
      // A floor on the error: black tiles have no variance, and float rounding is not noise.
      const double error = std::sqrt(variance) + 1e-6 * double(count);
      if (count > 0) worst = std::max(worst, std::abs(difference) / error);
    }
  }
  return worst;
}

/// A false-colour error image: each pixel's relMSE over its channels on a log scale from 1e-4
/// (black) through red and orange to 10 and above (pale yellow); left-out pixels grey.
void write_heatmap(const std::filesystem::path& file, const Image& test, const Image& reference,
                   const std::vector<bool>& counted) {
  // Control points of a perceptually ordered dark-to-bright ramp (after matplotlib's inferno).
  constexpr std::array<std::array<float, 3>, 5> kRamp = {
      {{0, 0, 4}, {87, 16, 110}, {188, 55, 84}, {249, 142, 9}, {252, 255, 164}}};
  std::vector<unsigned char> rgb(3 * counted.size());
  for (std::size_t i = 0; i < counted.size(); ++i) {
    unsigned char* out = &rgb[3 * i];
    if (!counted[i]) {
      std::fill_n(out, 3, 128);
      continue;
    }
    double e = 0;
    for (int k = 0; k < 3; ++k) e += relative_squared_error(test.rgb[3 * i + k], reference.rgb[3 * i + k]) / 3;
    const double t = std::clamp((std::log10(std::max(e, 1e-30)) + 4.0) / 5.0, 0.0, 1.0);
    const double at = t * double(kRamp.size() - 1);
    const auto lo = std::min(std::size_t(at), kRamp.size() - 2);
    const double f = at - double(lo);
    for (int k = 0; k < 3; ++k)
      out[k] = static_cast<unsigned char>(std::lround((1 - f) * kRamp[lo][k] + f * kRamp[lo + 1][k]));
  }
  write_png(file, test.width, test.height, rgb.data());
}

nlohmann::json errors_json(const Errors& e) {
  // JSON has no infinity: an exact match has no PSNR.
  return {{"rmse", e.rmse}, {"relmse", e.relmse}, {"psnr", std::isfinite(e.psnr) ? nlohmann::json(e.psnr) : nlohmann::json()}};
}

int run(const Options& o) {
  const Image test = read_exr(o.test), reference = read_exr(o.reference);
  check_same_size(reference, test, o.test);
  const std::vector<bool> counted = counted_pixels(o, reference);
  if (!o.json.empty()) AtomicFile probe(o.json);  // fail before the work, not after it
  const double relmse = luminance_relmse(test, reference, counted);
  std::printf("relative MSE %.6g\n", relmse);
  std::printf("relMSE guard %g (squared errors over reference^2 + guard)\n", kRelmseGuard);
  const std::size_t pixels = std::size_t(std::count(counted.begin(), counted.end(), true));
  if (!o.mask.empty()) std::printf("pixels compared: %zu of %zu (the mask leaves out the rest)\n", pixels, counted.size());
  nlohmann::json json = {{"relative_mse_luminance", relmse},
                         {"relmse_guard", kRelmseGuard},
                         {"pixels", pixels},
                         {"pixels_left_out", counted.size() - pixels}};
  std::printf("%-8s %12s %12s %10s\n", "channel", "RMSE", "relMSE", "PSNR dB");
  const char* names[] = {"R", "G", "B", "overall"};
  for (int c = 0; c < 4; ++c) {
    const Errors e = channel_errors(test, reference, counted, c);
    std::printf("%-8s %12.6g %12.6g %10.2f\n", names[c], e.rmse, e.relmse, e.psnr);
    json[c == 3 ? "overall" : names[c]] = errors_json(e);
  }
  if (!o.heatmap.empty()) write_heatmap(o.heatmap, test, reference, counted);
  bool pass = o.max_relmse < 0.0 || relmse <= o.max_relmse;
  if (!o.test_variance.empty()) {
    const Image test_var = read_exr(o.test_variance), reference_var = read_exr(o.reference_variance);
    check_same_size(reference, test_var, o.test_variance);
    check_same_size(reference, reference_var, o.reference_variance);
    const double z = worst_tile(o, test, reference, test_var, reference_var, counted);
    std::printf("worst %u x %u tile: %.3g standard errors (limit %.3g)\n", o.tile, o.tile, z, o.sigmas);
    pass = pass && z <= o.sigmas;
    json["worst_tile_sigmas"] = z;
  }
  json["pass"] = pass;
  if (!o.json.empty()) {
    AtomicFile out(o.json);
    out.write(json.dump(2) + "\n");
    out.commit();
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
  app.add_option("--max-relmse", o.max_relmse, "fail above this relative MSE (of luminance)");
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
  app.add_option("--mask", o.mask,
                 "emitter mask (OpenEXR, trs-render --emitter-mask): pixels where it is not zero are "
                 "left out of every figure and of the tile test");
  app.add_option("--json", o.json, "the figures as JSON");
  app.add_option("--heatmap", o.heatmap, "false-colour PNG of each pixel's relative error (log scale, "
                                         "1e-4 to 10; left-out pixels grey)");
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
