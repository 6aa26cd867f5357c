// The image codec through OpenImageIO (TRS_OPENIMAGEIO=ON): every format it has a plugin for,
// and the colour space its readers find in the metadata.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>

#include "image_codec.h"

namespace trs::image_codec {
namespace {

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

/// Whether the metadata declares linear values (or values that are data, not colour).
bool declared_linear(const OIIO::ImageSpec& spec) {
  const std::string space = lower(spec.get_string_attribute("oiio:ColorSpace"));
  if (space == "linear" || space == "scene_linear" || space.rfind("lin_", 0) == 0 ||
      space == "acescg" || space == "aces2065-1" || space == "raw" || space == "data" ||
      space == "non-color") {
    return true;
  }
  return spec.get_float_attribute("oiio:Gamma", 0.0f) == 1.0f;
}

bool integer_format(OIIO::TypeDesc format) {
  using B = OIIO::TypeDesc::BASETYPE;
  const auto base = B(format.basetype);
  return base == B::UINT8 || base == B::INT8 || base == B::UINT16 || base == B::INT16;
}

Header header_of(const OIIO::ImageInput& input) {
  const OIIO::ImageSpec& spec = input.spec();
  return {.format = input.format_name(),
          .width = spec.width,
          .height = spec.height,
          .channels = spec.nchannels,
          .alpha = (spec.nchannels == 2 || spec.nchannels == 4) && spec.alpha_channel == spec.nchannels - 1,
          .deep = spec.deep,
          .depth = spec.depth,
          .integer = integer_format(spec.format),
          .declared_linear = declared_linear(spec)};
}

/// OpenImageIO encodes into memory, for the caller to write the file atomically.
std::vector<unsigned char> encode(const char* format, const OIIO::ImageSpec& spec,
                                  const void* pixels) {
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  const auto encoder = OIIO::ImageOutput::create(format, &memory);
  if (!encoder) throw CodecError(std::string("no ") + format + " writer: " + OIIO::geterror());
  if (!encoder->open(std::string("memory.") + format, spec) ||
      !encoder->write_image(spec.format, pixels) || !encoder->close()) {
    throw CodecError(encoder->geterror());
  }
  return bytes;
}

/// What every reader is opened with: alpha as stored, the colour channels not multiplied by it
/// (OpenImageIO associates PNG's alpha by default; glTF's textures are not premultiplied).
const OIIO::ImageSpec& reader_config() {
  static const OIIO::ImageSpec config = [] {
    OIIO::ImageSpec spec;
    spec.attribute("oiio:UnassociatedAlpha", 1);
    return spec;
  }();
  return config;
}

}  // namespace

struct Decoder::State {
  std::unique_ptr<OIIO::Filesystem::IOMemReader> memory;  // embedded bytes; outlives `input`
  std::unique_ptr<OIIO::ImageInput> input;
};

Decoder::Decoder(const std::filesystem::path& file) : state_(std::make_unique<State>()) {
  state_->input = OIIO::ImageInput::open(file.string(), &reader_config());
  if (!state_->input) throw CodecError(OIIO::geterror());
  header_ = header_of(*state_->input);
}

Decoder::Decoder(std::span<const unsigned char> bytes, const std::string& format)
    : state_(std::make_unique<State>()) {
  state_->memory = std::make_unique<OIIO::Filesystem::IOMemReader>(bytes.data(), bytes.size());
  // The extension picks the first reader to try; OpenImageIO tries the others after it.
  // The proxy rides in the configuration: OpenImageIO 2.4 opens no proxy given beside one.
  OIIO::ImageSpec config = reader_config();
  void* proxy = state_->memory.get();
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  state_->input = OIIO::ImageInput::open("embedded." + format, &config);
  if (!state_->input) {
    const std::string error = OIIO::geterror();
    const auto reader = OIIO::ImageInput::create(format);
    if (reader && !reader->supports("ioproxy")) throw FileOnlyFormat(reader->format_name());
    throw CodecError(error);
  }
  header_ = header_of(*state_->input);
}

Decoder::Decoder(Decoder&&) noexcept = default;
Decoder::~Decoder() = default;

std::vector<float> Decoder::read(int channels) {
  OIIO::ImageInput& input = *state_->input;
  const OIIO::ImageSpec& spec = input.spec();
  const std::size_t row = std::size_t(spec.width) * std::size_t(channels);
  // A band of rows at a time, the buffer growing with them (doubling, up to the image's size): a
  // file whose header claims more rows than its data holds fails after the rows it has, not after
  // allocating what its header claims.
  const std::size_t total = row * std::size_t(spec.height);
  std::vector<float> pixels;
  const int band = spec.tile_width > 0 ? std::max(spec.tile_height, 1) : 256;
  for (int y = 0; y < spec.height; y += band) {
    const int rows = std::min(band, spec.height - y);
    const std::size_t end = pixels.size() + row * std::size_t(rows);
    if (end > pixels.capacity()) pixels.reserve(std::min(total, std::max(end, 2 * pixels.capacity())));
    pixels.resize(end);
    float* out = pixels.data() + row * std::size_t(y);
    const bool read =
        spec.tile_width > 0
            ? input.read_tiles(0, 0, spec.x, spec.x + spec.width, spec.y + y, spec.y + y + rows,
                               spec.z, spec.z + 1, 0, channels,
                               OIIO::TypeDesc::FLOAT, out)
            : input.read_scanlines(0, 0, spec.y + y, spec.y + y + rows, spec.z, 0, channels,
                                   OIIO::TypeDesc::FLOAT, out);
    // Some readers (JPEG) fill a truncated image with grey, report success and only record the
    // error.
    if (!read || input.has_error()) throw CodecError(input.geterror());
  }
  return pixels;
}

std::vector<unsigned char> encode_exr(std::uint32_t width, std::uint32_t height,
                                      const float* rgb) {
  OIIO::ImageSpec spec(int(width), int(height), 3, OIIO::TypeDesc::FLOAT);
  spec.attribute("compression", "zip");
  spec.attribute("oiio:ColorSpace", "Linear");
  spec.attribute("chromaticities", OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8),
                 kRec709Chromaticities.data());
  return encode("openexr", spec, rgb);
}

std::vector<unsigned char> encode_png(std::uint32_t width, std::uint32_t height,
                                      const unsigned char* rgb) {
  OIIO::ImageSpec spec(int(width), int(height), 3, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", "sRGB");
  return encode("png", spec, rgb);
}

}  // namespace trs::image_codec
