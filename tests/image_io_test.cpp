// Image files in and out of scene_io through the build's image codec (OpenImageIO, or stb_image
// and OpenEXR: TRS_OPENIMAGEIO): its own EXR and PNG outputs read back (previews through
// OpenColorIO display transforms), and inputs written without it (support/image_files.h): PNG of
// every layout, EXR, JPEG, Radiance HDR, deep and truncated files, embedded bytes.

#include <OpenColorIO/OpenColorABI.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "scene_io/color.h"
#include "scene_io/density_io.h"
#include "scene_io/display.h"
#include "scene_io/image_output.h"
#include "support/image_files.h"
#include "support/ocio_config.h"
#include "support/scratch_dir.h"

namespace trs {

// For GoogleTest's messages.
void PrintTo(const DisplayTransform& t, std::ostream* out) {
  *out << "{config \"" << t.config << "\", colour space \"" << t.colorspace << "\", display \"" << t.display
       << "\", view \"" << t.view << "\"}";
}

}  // namespace trs

namespace {

namespace fs = std::filesystem;
using trs_test::expect_error;

constexpr bool kOpenImageIO = TRS_OPENIMAGEIO;

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

/// `values` scaled from [0, 1] back to 8-bit integers.
std::vector<int> to_bytes(const std::vector<float>& values) {
  std::vector<int> bytes(values.size());
  std::transform(values.begin(), values.end(), bytes.begin(),
                 [](float value) { return int(std::lround(value * 255.0f)); });
  return bytes;
}

class ImageIoTest : public trs_test::ScratchDirTest {
 protected:
  fs::path write_bytes(const std::string& name, const std::string& bytes) {
    std::ofstream(file(name), std::ios::binary) << bytes;
    return file(name);
  }

  /// A PNG of 8-bit samples.
  fs::path write_png8(const std::string& name, int width, int height, int channels,
                      const std::vector<std::uint16_t>& samples) {
    return write_bytes(name, trs_test::png_file(width, height, channels, 8, samples));
  }

  /// `file` cut to half its size.
  void truncate(const fs::path& file) { fs::resize_file(file, fs::file_size(file) / 2); }
};

TEST_F(ImageIoTest, PngWrittenByWritePngDecodesToItsBytes) {
  std::vector<unsigned char> bytes(3 * 5 * 3);
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>(i * 37);
  trs::write_png(file("out.png"), 5, 3, bytes.data());
  const trs::Image image = trs::read_image(file("out.png"));
  EXPECT_EQ(image.width, 5u);
  EXPECT_EQ(image.height, 3u);
  EXPECT_TRUE(image.integer);
  EXPECT_EQ(to_bytes(image.rgb), std::vector<int>(bytes.begin(), bytes.end()));
}

// Every float survives, NaN payloads and signed zeros included; the file is 32-bit float RGB,
// ZIP compressed. A grey EXR (one channel, Y) is repeated into R, G and B.
TEST_F(ImageIoTest, ExrRoundTripIsBitExact) {
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float tiny = std::numeric_limits<float>::denorm_min();
  const float huge = std::numeric_limits<float>::max();
  const std::vector<float> rgb = {0.0f, -0.0f, 1e-20f, -3.5f, 65504.0f, 1e30f, 0.1f, 1.0f / 3.0f,
                                  2.0f, 7.25f, tiny, huge, inf, -inf, nan};
  trs::write_exr(file("render.exr"), 5, 1, rgb.data());
  EXPECT_EQ(trs_test::exr_layout(file("render.exr")), "B:float G:float R:float, zip");
  const trs::Image image = trs::read_exr(file("render.exr"));
  EXPECT_EQ(image.width, 5u);
  EXPECT_EQ(image.height, 1u);
  EXPECT_FALSE(image.integer);
  ASSERT_EQ(image.rgb.size(), rgb.size());
  EXPECT_EQ(std::memcmp(image.rgb.data(), rgb.data(), rgb.size() * sizeof(float)), 0);

  trs_test::write_float_exr(file("grey.exr"), 2, 1, 1, {0.25f, 4.0f});
  EXPECT_EQ(trs::read_exr(file("grey.exr")).rgb,
            (std::vector<float>{0.25f, 0.25f, 0.25f, 4.0f, 4.0f, 4.0f}));
}

// Tiled files are read a row of tiles at a time; the last row and column of tiles are partial.
TEST_F(ImageIoTest, TiledExrReadsAsItsScanlines) {
  const int width = 37, height = 23;
  std::vector<float> rgb(std::size_t(width * height * 3));
  for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = float(i % 251) * 0.25f;
  trs_test::write_float_exr(file("tiled.exr"), width, height, 3, rgb, 16);
  const trs::Image image = trs::read_exr(file("tiled.exr"));
  EXPECT_EQ(image.width, std::uint32_t(width));
  EXPECT_EQ(image.height, std::uint32_t(height));
  EXPECT_EQ(image.rgb, rgb);
}

// The renders are linear Rec. 709: the EXR says so, for readers that honour its chromaticities.
TEST_F(ImageIoTest, ExrIsTaggedRec709WithD65) {
  const std::vector<float> rgb = {0.5f, 1.0f, 2.0f};
  trs::write_exr(file("render.exr"), 1, 1, rgb.data());
  EXPECT_EQ(trs_test::exr_chromaticities(file("render.exr")),
            (std::vector<float>{0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f}));
}

TEST_F(ImageIoTest, ReadExrRefusesOtherFormatsAndGarbage) {
  const std::vector<unsigned char> rgb(3, 0);
  trs::write_png(file("image.exr"), 1, 1, rgb.data());  // the name does not make it OpenEXR
  expect_error([&] { trs::read_exr(file("image.exr")); }, file("image.exr"),
               "is a png image, not OpenEXR");
  write_bytes("garbage.exr", "not an image");
  expect_error([&] { trs::read_exr(file("garbage.exr")); }, file("garbage.exr"),
               "cannot read image: ");
  expect_error([&] { trs::read_exr(file("absent.exr")); }, file("absent.exr"), "no such file");
}

TEST_F(ImageIoTest, PngPreviewIsSrgbEncodedAndClamped) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> rgb = {0.0f, 1.0f, 4.0f, -1.0f, nan, 0.18f, 0.5f, 0.0031308f, 0.25f};
  trs::write_png_preview(file("preview.png"), 3, 1, rgb.data());
  trs::write_png_preview(file("brighter.png"), 3, 1, rgb.data(), 1.0f);
  // The stored bytes, once the file's header says 8-bit RGB (IHDR's bit depth and colour type).
  auto stored = [](const fs::path& path) {
    const std::string png = read_bytes(path);
    EXPECT_EQ(png.substr(12, 4), "IHDR");
    EXPECT_EQ(png.substr(24, 2), std::string("\x08\x02", 2));
    return to_bytes(trs::read_image(path).rgb);
  };
  EXPECT_EQ(stored(file("preview.png")), (std::vector<int>{0, 255, 255, 0, 0, 118, 188, 10, 137}));
  EXPECT_EQ(stored(file("brighter.png"))[8], 188);  // 0.25 one stop up is 0.5
}

// Without a config, the encoder is the sRGB curve of the textures' decoding, inverted.
TEST_F(ImageIoTest, DisplayEncoderWithoutConfigIsTheSrgbCurve) {
  const std::vector<float> linear = {-0.5f, 0.0f, 0.001f, 0.0031308f, 0.18f, 0.5f, 1.0f, 3.0f, 100.0f};
  std::vector<float> curve = linear, encoded = linear;
  trs::linear_to_srgb(curve);
  trs::DisplayEncoder(trs::DisplayTransform{}).encode(encoded);
  EXPECT_EQ(encoded, curve);
  EXPECT_EQ(trs::DisplayEncoder().transform(), trs::DisplayTransform{});
}

/// A test with the OpenColorIO config of support/ocio_config.h, written to config.ocio.
class OcioPreviewTest : public ImageIoTest {
 protected:
  fs::path write_config(const std::string& linear, const std::string& aliases = "") {
    return write_bytes("config.ocio", trs_test::ocio_config(linear, aliases));
  }

  /// The preview's bytes through `display` of `rgb`, three pixels.
  std::vector<int> preview(const trs::DisplayEncoder& display, float exposure = 0.0f) {
    trs::write_png_preview(file("preview.png"), 3, 1, kRgb.data(), exposure, display);
    return to_bytes(trs::read_image(file("preview.png")).rgb);
  }

  /// The bytes of the view "Square root": 2^exposure v, its square root, clamped, NaN to 0.
  static std::vector<int> square_root_bytes(float exposure) {
    std::vector<int> bytes;
    for (const float v : kRgb) {
      const float root = std::sqrt(v * std::exp2(exposure));
      bytes.push_back(int(std::lround((root > 0.0f ? std::min(root, 1.0f) : 0.0f) * 255.0f)));
    }
    return bytes;
  }

  static inline const std::vector<float> kRgb = {
      0.0f, 0.01f, 0.18f, 0.25f, 0.7f, 4.0f, -1.0f, std::numeric_limits<float>::quiet_NaN(), 0.03f};
};

// The default colour space is the config's linear Rec. 709 (here found by its alias), not its
// scene_linear role (ACEScg); the default display and view are the config's first. Exposure
// applies before the view.
TEST_F(OcioPreviewTest, DefaultsAreLinearRec709AndTheDefaultDisplayAndView) {
  const fs::path config = write_config("Scene Linear", "lin_rec709");
  const trs::DisplayEncoder display({.config = config.string()});
  EXPECT_EQ(display.transform(), (trs::DisplayTransform{config.string(), "Scene Linear", "Gamma", "Square root"}));
  EXPECT_EQ(display.warning(), "");
  EXPECT_EQ(preview(display), square_root_bytes(0.0f));
  EXPECT_EQ(preview(display, 1.0f), square_root_bytes(1.0f));
  EXPECT_NE(square_root_bytes(0.0f), square_root_bytes(1.0f));
}

// Names given are checked and spelt as the config spells them (a role or alias resolved).
TEST_F(OcioPreviewTest, NamedDisplayViewAndColourSpace) {
  const fs::path config = write_config("Linear Rec.709 (sRGB)");
  std::vector<int> raw;  // the values as they are, clamped
  for (const float v : kRgb) raw.push_back(int(std::lround((v > 0.0f ? std::min(v, 1.0f) : 0.0f) * 255.0f)));
  const trs::DisplayEncoder linear({.config = config.string(), .display = "Linear"});
  EXPECT_EQ(linear.transform().view, "Raw");
  EXPECT_EQ(preview(linear), raw);
  const trs::DisplayEncoder gamma_raw({.config = config.string(), .display = "Gamma", .view = "Raw"});
  EXPECT_EQ(preview(gamma_raw), raw);
  const trs::DisplayEncoder acescg({.config = config.string(), .colorspace = "scene_linear", .view = "Raw"});
  EXPECT_EQ(acescg.transform().colorspace, "ACEScg");
  EXPECT_NE(preview(acescg), raw) << "ACEScg is not Rec. 709";
}

// A config without a linear Rec. 709 space: its scene_linear role, and a warning naming it.
TEST_F(OcioPreviewTest, WithoutLinearRec709TheSceneLinearRoleWithAWarning) {
  const fs::path config = write_config("reference");
  const trs::DisplayEncoder display({.config = config.string()});
  EXPECT_EQ(display.transform().colorspace, "ACEScg");
  EXPECT_NE(display.warning().find(config.string() + ": no colour space for linear Rec. 709"), std::string::npos)
      << display.warning();
  EXPECT_NE(display.warning().find("scene_linear role's, \"ACEScg\""), std::string::npos) << display.warning();
}

// Bad names are refused with the names the config has; the config is named.
TEST_F(OcioPreviewTest, BadNamesAndConfigsAreRefused) {
  const fs::path config = write_config("lin_rec709");
  const auto encoder = [&](trs::DisplayTransform transform) {
    return [transform] { trs::DisplayEncoder{transform}; };
  };
  trs_test::expect_error(encoder({.config = config.string(), .display = "sRGB"}), config,
                         "no display \"sRGB\" (its displays: \"Gamma\", \"Linear\")");
  trs_test::expect_error(encoder({.config = config.string(), .display = "Linear", .view = "Square root"}), config,
                         "no view \"Square root\" (its views: \"Raw\")");
  trs_test::expect_error(encoder({.config = config.string(), .colorspace = "ACES2065-1"}), config,
                         "no colour space \"ACES2065-1\" (its colour spaces: \"lin_rec709\", \"ACEScg\", \"gamma 2\")");
  trs_test::expect_error(encoder({.config = file("absent.ocio").string()}), file("absent.ocio"),
                         "cannot read the OpenColorIO config");
  write_bytes("garbage.ocio", "ocio_profile_version: [\n");
  trs_test::expect_error(encoder({.config = file("garbage.ocio").string()}), file("garbage.ocio"),
                         "cannot read the OpenColorIO config");
}

// OpenColorIO 2.2 reads its built-in configs by URI; older versions cannot, and say so.
TEST_F(OcioPreviewTest, BuiltInConfigs) {
  const trs::DisplayTransform builtin{.config = "ocio://default"};
  if (OCIO_VERSION_HEX >= 0x02020000) {
    const trs::DisplayEncoder display(builtin);
    EXPECT_EQ(display.transform().colorspace, "Linear Rec.709 (sRGB)");
    EXPECT_EQ(display.warning(), "");
  } else {
    trs_test::expect_error([&] { trs::DisplayEncoder{builtin}; }, "ocio://default",
                           "built-in configs need OpenColorIO 2.2 or later; this build has " OCIO_VERSION_STR);
  }
}

TEST_F(ImageIoTest, FailedWriteLeavesNoFile) {
  const std::vector<float> rgb(12, 0.5f);
  const fs::path nowhere = file("no-such-directory") / "render.exr";
  expect_error([&] { trs::write_exr(nowhere, 2, 2, rgb.data()); }, nowhere, "temporary");
  // PNG readers built on libpng refuse images over a million pixels wide, and so do the
  // encoders: this one fails after the temporary was created, and the previous file stays as it
  // was.
  std::ofstream(file("render.png")) << "previous";
  const std::vector<float> wide(3 * 1'000'001, 0.5f);
  expect_error([&] { trs::write_png_preview(file("render.png"), 1'000'001, 1, wide.data()); },
               file("render.png"), "cannot encode");
  expect_error([&] { trs::write_exr(file("empty.exr"), 0, 2, rgb.data()); }, file("empty.exr"),
               "without pixels");
  std::vector<fs::path> entries;
  for (const auto& entry : fs::directory_iterator(dir_)) entries.push_back(entry.path());
  EXPECT_EQ(entries, std::vector<fs::path>{file("render.png")});
  EXPECT_EQ(read_bytes(file("render.png")), "previous");
}

// Pixel data cut short is an error naming the file, for every reader, never a partly grey image.
TEST_F(ImageIoTest, TruncatedFilesAreRefused) {
  std::vector<unsigned char> noise(64 * 64 * 3);
  for (std::size_t i = 0; i < noise.size(); ++i)
    noise[i] = static_cast<unsigned char>((i * 2654435761u) >> 24);
  const std::string truncated = "cannot read pixels (truncated or corrupt file?): ";

  trs::write_png(file("cut.png"), 64, 64, noise.data());
  truncate(file("cut.png"));
  expect_error([&] { trs::read_image(file("cut.png")); }, file("cut.png"), truncated);
  expect_error([&] { trs::load_density_map(file("cut.png"), trs::MapEncoding::automatic); },
               file("cut.png"), truncated);

  const std::string jpeg = trs_test::jpeg_file(64, 64, noise, 90);
  write_bytes("cut.jpg", jpeg.substr(0, jpeg.size() / 2));
  expect_error([&] { trs::read_image(file("cut.jpg")); }, file("cut.jpg"), truncated);

  std::vector<float> floats(noise.begin(), noise.end());
  trs::write_exr(file("cut.exr"), 64, 64, floats.data());
  truncate(file("cut.exr"));
  expect_error([&] { trs::read_exr(file("cut.exr")); }, file("cut.exr"), truncated);
}

// 16 bits are kept (1 / 65535 is no 0), and a 16-bit file counts as display-encoded.
TEST_F(ImageIoTest, SixteenBitPngKeepsItsPrecision) {
  const std::vector<std::uint16_t> samples = {0, 1, 257, 65535, 32768, 65534};
  write_bytes("deep.png", trs_test::png_file(2, 1, 3, 16, samples));
  const trs::Image image = trs::read_image(file("deep.png"));
  EXPECT_TRUE(image.integer);
  ASSERT_EQ(image.rgb.size(), samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i)
    EXPECT_FLOAT_EQ(image.rgb[i], float(samples[i]) / 65535.0f) << i;
  EXPECT_TRUE(trs::load_density_map(file("deep.png"), trs::MapEncoding::automatic).srgb_decoded);
}

// Grey is repeated into R, G, B, and alpha is dropped; the colour stays as stored, not
// multiplied by the alpha (glTF's textures are unassociated), through either codec. A density
// map is the grey, or the luminance.
TEST_F(ImageIoTest, GreyGreyAlphaAndRgbaPngs) {
  const fs::path grey = write_png8("grey.png", 2, 1, 1, {0, 200});
  const fs::path grey_alpha = write_png8("grey-alpha.png", 2, 1, 2, {10, 255, 200, 0});
  const fs::path rgba = write_png8("rgba.png", 2, 1, 4, {10, 20, 30, 255, 50, 60, 70, 80});
  EXPECT_EQ(to_bytes(trs::read_image(grey).rgb), (std::vector<int>{0, 0, 0, 200, 200, 200}));
  EXPECT_EQ(to_bytes(trs::read_image(grey_alpha).rgb), (std::vector<int>{10, 10, 10, 200, 200, 200}));
  EXPECT_EQ(to_bytes(trs::read_image(rgba).rgb), (std::vector<int>{10, 20, 30, 50, 60, 70}));

  const trs::DensityMap grey_map = trs::load_density_map(grey_alpha, trs::MapEncoding::linear);
  ASSERT_EQ(grey_map.texels.size(), 2u);
  EXPECT_NEAR(grey_map.texels[0], 10 / 255.0f, 1e-7f);
  EXPECT_NEAR(grey_map.texels[1], 200 / 255.0f, 1e-7f);
  const trs::DensityMap rgba_map = trs::load_density_map(rgba, trs::MapEncoding::linear);
  ASSERT_EQ(rgba_map.texels.size(), 2u);
  EXPECT_NEAR(rgba_map.texels[0], (0.2126f * 10 + 0.7152f * 20 + 0.0722f * 30) / 255, 1e-6f);
}

// Images embedded in a glTF file (a buffer, a data URI) decode as their files do; problems name
// the glTF file and the image.
TEST_F(ImageIoTest, EmbeddedImagesDecodeLikeTheirFiles) {
  const fs::path gltf = file("scene.gltf");
  auto embedded = [&](const fs::path& image, std::size_t keep = SIZE_MAX) {
    const std::string bytes = read_bytes(image).substr(0, keep);
    const std::vector<unsigned char> buffer(bytes.begin(), bytes.end());
    return trs::read_image(buffer, image.extension().string().substr(1), gltf, "image 3");
  };
  write_png8("texture.png", 2, 2, 3, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12});
  EXPECT_EQ(embedded(file("texture.png")).rgb, trs::read_image(file("texture.png")).rgb);
  EXPECT_TRUE(embedded(file("texture.png")).integer);
  std::vector<float> rgb(32 * 32 * 3);  // enough for a cut to leave the header whole
  for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = std::sin(float(i));
  trs::write_exr(file("texture.exr"), 32, 32, rgb.data());
  EXPECT_EQ(embedded(file("texture.exr")).rgb, rgb);

  write_bytes("garbage.png", std::string(100, '\x07'));
  expect_error([&] { embedded(file("garbage.png")); }, gltf, "image 3: cannot decode image: ");
  for (const char* name : {"texture.png", "texture.exr"}) {
    const std::size_t half = fs::file_size(file(name)) / 2;
    expect_error([&] { embedded(file(name), half); }, gltf, "image 3: cannot read pixels");
  }
}

// JPEG decoders differ by a level or so; none strays further.
TEST_F(ImageIoTest, JpegDecodesToItsColour) {
  std::vector<unsigned char> rgb(16 * 16 * 3);
  for (std::size_t i = 0; i < rgb.size(); i += 3) {
    rgb[i] = 200;
    rgb[i + 1] = 100;
    rgb[i + 2] = 50;
  }
  write_bytes("flat.jpg", trs_test::jpeg_file(16, 16, rgb, 100));
  const trs::Image image = trs::read_image(file("flat.jpg"));
  EXPECT_TRUE(image.integer);
  ASSERT_EQ(image.rgb.size(), rgb.size());
  const std::vector<int> decoded = to_bytes(image.rgb);
  for (std::size_t i = 0; i < rgb.size(); ++i) EXPECT_NEAR(decoded[i], rgb[i], 3) << i;
}

// Radiance RGBE pixels (two, uncompressed: a scanline under 8 pixels is never run-length
// encoded) decode to floats, which a density map takes as linear.
TEST_F(ImageIoTest, RadianceHdrIsLinearFloat) {
  // (0.5, 1, 2): mantissas over 256 times 2^(exponent - 128); then (1, 1, 1).
  write_bytes("sky.hdr", std::string("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 2\n") +
                             std::string("\x20\x40\x80\x82\x80\x80\x80\x81", 8));
  const trs::Image image = trs::read_image(file("sky.hdr"));
  EXPECT_FALSE(image.integer);
  EXPECT_EQ(image.rgb, (std::vector<float>{0.5f, 1.0f, 2.0f, 1.0f, 1.0f, 1.0f}));
  EXPECT_FALSE(trs::load_density_map(file("sky.hdr"), trs::MapEncoding::automatic).srgb_decoded);
}

TEST_F(ImageIoTest, DeepExrIsRefused) {
  trs_test::write_deep_exr(file("deep.exr"));
  expect_error([&] { trs::read_exr(file("deep.exr")); }, file("deep.exr"),
               "deep images are not supported");
  expect_error([&] { trs::load_density_map(file("deep.exr"), trs::MapEncoding::automatic); },
               file("deep.exr"), "deep images are not supported");
}

// A header may claim any size; one over the limit is refused before anything is allocated.
TEST_F(ImageIoTest, HugeHeaderIsRefused) {
  write_bytes("huge.ppm", "P6\n100000 100000\n255\n");
  expect_error([&] { trs::read_image(file("huge.ppm")); }, file("huge.ppm"),
               "image is 100000 x 100000 texels, more than the 16384 x 16384");
  // Fewer texels than 16384 x 16384, but a row longer than the side an image may have.
  write_bytes("long.ppm", "P6\n16385 1\n255\n");
  expect_error([&] { trs::read_image(file("long.ppm")); }, file("long.ppm"),
               "image is 16385 x 1 texels, more than the 16384 x 16384");
}

/// The peak resident memory `action` adds, in MiB: measured in a child process, where nothing
/// else the tests did counts. -1 when the action returns instead of throwing.
long peak_growth_mib_of_refusal(const std::function<void()>& action) {
  const pid_t child = fork();
  if (child == 0) {
    long pages = 0, resident = 0;
    std::ifstream("/proc/self/statm") >> pages >> resident;
    const long before_kib = resident * (sysconf(_SC_PAGESIZE) / 1024);
    try {
      action();
      _exit(255);
    } catch (const std::exception&) {
    }
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    _exit(int(std::min(254L, std::max(0L, usage.ru_maxrss - before_kib) / 1024)));
  }
  int status = 0;
  waitpid(child, &status, 0);
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 255;
  return code == 255 ? -1 : code;
}

// A header within the limit may claim more rows than the file holds: the file is refused after the
// rows it has, before the memory its header claims (16384 x 16384 RGB floats: 3 GiB) is touched.
// The bound, 200 MiB, leaves room for AddressSanitizer's bookkeeping (about 70 MiB in its build).
TEST_F(ImageIoTest, HeaderClaimingMoreThanTheFileHoldsCostsOnlyWhatIsThere) {
  const fs::path pfm = write_bytes("claims.pfm", "PF\n16384 16384\n-1.0\n" + std::string(96, '\0'));
  const fs::path png = write_bytes(  // one row of 16-bit RGBA
      "claims.png", trs_test::png_file(16384, 16384, 4, 16, std::vector<std::uint16_t>(16384 * 4)));
  for (const fs::path& path : {pfm, png}) {
    const long growth = peak_growth_mib_of_refusal(
        [&] { trs::load_density_map(path, trs::MapEncoding::automatic); });
    EXPECT_GE(growth, 0) << path << " was accepted";
    EXPECT_LT(growth, 200) << path << " cost " << growth << " MiB before it was refused";
  }
}

// A 16-bit PNG whose gAMA chunk says gamma 1 holds linear values. OpenImageIO reads that and the
// map is not decoded from sRGB; stb_image reads no colour-space metadata, and it is.
TEST_F(ImageIoTest, ColourSpaceMetadataIsReadWithOpenImageIOOnly) {
  const std::string gamma_1 = std::string("\x00\x01\x86\xa0", 4);  // 100000: gamma 1.0
  write_bytes("linear.png", trs_test::png_file(2, 1, 1, 16, {1000, 60000}, {{"gAMA", gamma_1}}));
  const trs::DensityMap map =
      trs::load_density_map(file("linear.png"), trs::MapEncoding::automatic);
  EXPECT_EQ(map.srgb_decoded, !kOpenImageIO);
  EXPECT_FALSE(trs::load_density_map(file("linear.png"), trs::MapEncoding::linear).srgb_decoded);
}

}  // namespace
