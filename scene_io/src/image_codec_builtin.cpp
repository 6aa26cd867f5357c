// The image codec without OpenImageIO (TRS_OPENIMAGEIO=OFF), for programs that must run where
// OpenImageIO's dependencies are not installed: OpenEXR for EXR, stb_image and stb_image_write
// (Debian's libstb) for the rest. Neither reads colour-space metadata (a PNG's gAMA, sRGB or iCCP
// chunks): integer files count as sRGB, float files (EXR, HDR) as linear. A file's first bytes
// tell its format, whatever its name says.
#include <IexBaseExc.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputPart.h>
#include <ImfMultiPartInputFile.h>
#include <ImfOutputFile.h>
#include <ImfPartType.h>
#include <ImfStandardAttributes.h>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <optional>
#include <string_view>
#include <utility>

#include "image_codec.h"

namespace trs::image_codec {
namespace {

using Bytes = std::span<const unsigned char>;

// ---- Format -------------------------------------------------------------------------------------

struct Signature {
  std::string_view magic;
  const char* format;  // OpenImageIO's name, for messages that name a format
};

/// The formats that start with a signature. stb_image reads one more, Targa, which has none.
constexpr std::array kSignatures = {
    Signature{"\x76\x2f\x31\x01", "openexr"}, Signature{"\x89PNG\r\n\x1a\n", "png"},
    Signature{"\xff\xd8\xff", "jpeg"},        Signature{"BM", "bmp"},
    Signature{"#?", "hdr"},                   Signature{"P5", "pnm"},
    Signature{"P6", "pnm"},                   Signature{"GIF8", "gif"},
    Signature{"8BPS", "psd"},                 Signature{"\x53\x80\xf6\x34", "softimage"},
};

const char* format_of(Bytes bytes) {
  for (const Signature& signature : kSignatures) {
    if (bytes.size() >= signature.magic.size() &&
        std::memcmp(bytes.data(), signature.magic.data(), signature.magic.size()) == 0) {
      return signature.format;
    }
  }
  return "targa";
}

bool is_exr(Bytes bytes) { return format_of(bytes) == std::string_view("openexr"); }

// ---- OpenEXR ------------------------------------------------------------------------------------

/// OpenEXR's input from bytes in memory; reading past the end throws, as from a short file.
/// OpenEXR's messages call it `name`.
class MemoryInput final : public Imf::IStream {
 public:
  MemoryInput(const std::string& name, Bytes bytes) : Imf::IStream(name.c_str()), bytes_(bytes) {}

  bool read(char c[], int n) override {
    if (n < 0 || position_ > bytes_.size() || bytes_.size() - position_ < std::size_t(n))
      throw Iex::InputExc("unexpected end of file");
    std::memcpy(c, bytes_.data() + position_, std::size_t(n));
    position_ += std::size_t(n);
    return position_ < bytes_.size();
  }
  std::uint64_t tellg() override { return position_; }
  void seekg(std::uint64_t position) override { position_ = position; }

 private:
  Bytes bytes_;
  std::uint64_t position_ = 0;
};

/// OpenEXR's output into memory; it seeks back to fill in the offsets of the pixel data.
class MemoryOutput final : public Imf::OStream {
 public:
  explicit MemoryOutput(std::vector<unsigned char>& bytes)
      : Imf::OStream("memory"), bytes_(bytes) {}

  void write(const char c[], int n) override {
    const std::size_t end = position_ + std::size_t(n);
    if (end > bytes_.size()) bytes_.resize(end);
    std::memcpy(bytes_.data() + position_, c, std::size_t(n));
    position_ = end;
  }
  std::uint64_t tellp() override { return position_; }
  void seekp(std::uint64_t position) override { position_ = position; }

 private:
  std::vector<unsigned char>& bytes_;
  std::size_t position_ = 0;
};

/// The channels in the order read: R, G, B, A first when present (as OpenImageIO orders them),
/// then the others in the file's (alphabetical) order; a grey image's luminance Y leads.
std::vector<std::string> channel_order(const Imf::ChannelList& list) {
  const bool rgb = list.findChannel("R") && list.findChannel("G") && list.findChannel("B");
  const std::vector<std::string> leading =
      rgb ? std::vector<std::string>{"R", "G", "B", "A"} : std::vector<std::string>{"Y", "A"};
  std::vector<std::string> names;
  for (const std::string& name : leading) {
    if (list.findChannel(name)) names.push_back(name);
  }
  for (auto channel = list.begin(); channel != list.end(); ++channel) {
    if (std::find(names.begin(), names.end(), channel.name()) == names.end())
      names.emplace_back(channel.name());
  }
  return names;
}

/// Runs `action` with OpenEXR's exceptions turned into CodecError.
template <class Action>
auto with_exr_errors(Action action) -> decltype(action()) {
  try {
    return action();
  } catch (const std::exception& error) {
    throw CodecError(error.what());
  }
}

Header exr_header(const Imf::Header& header) {
  const Imath::Box2i window = header.dataWindow();
  const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
  const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
  if (width > INT_MAX || height > INT_MAX) throw CodecError("data window too large");
  int channels = 0;
  for (auto channel = header.channels().begin(); channel != header.channels().end(); ++channel)
    ++channels;
  // channel_order puts A right after R, G, B or after Y.
  const std::vector<std::string> names = channel_order(header.channels());
  return {.format = "openexr",
          .width = int(width),
          .height = int(height),
          .channels = channels,
          .alpha = (channels == 2 || channels == 4) && names[std::size_t(channels) - 1] == "A",
          .deep = header.hasType() && Imf::isDeepData(header.type())};
}

std::vector<float> read_exr(Imf::MultiPartInputFile& file, int channels) {
  Imf::InputPart part(file, 0);
  const Imath::Box2i window = part.header().dataWindow();
  const std::size_t width = std::size_t(window.max.x - window.min.x + 1);
  const std::size_t height = std::size_t(window.max.y - window.min.y + 1);
  std::vector<float> pixels(width * height * std::size_t(channels));
  const std::vector<std::string> names = channel_order(part.header().channels());
  Imf::FrameBuffer frame;
  for (int c = 0; c < channels; ++c) {
    frame.insert(names[std::size_t(c)],
                 Imf::Slice::Make(Imf::FLOAT, pixels.data() + c, window,
                                  sizeof(float) * std::size_t(channels),
                                  sizeof(float) * std::size_t(channels) * width));
  }
  part.setFrameBuffer(frame);
  part.readPixels(window.min.y, window.max.y);
  return pixels;
}

// ---- stb_image ----------------------------------------------------------------------------------

Header stb_header(Bytes bytes) {
  if (bytes.size() > std::size_t(INT_MAX)) throw CodecError("file larger than 2 GiB");  // an int
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels))
    throw CodecError(stbi_failure_reason());
  return {.format = format_of(bytes),
          .width = width,
          .height = height,
          .channels = channels,
          .alpha = channels == 2 || channels == 4,  // stb_image's grey-alpha and RGBA
          .integer = !stbi_is_hdr_from_memory(bytes.data(), int(bytes.size()))};
}

/// Samples as stb_image returns them (its conversion to `channels` keeps the first channel of
/// grey and alpha, and drops alpha from RGBA where 3 are asked for) as floats, divided by `one`: the sample for 1.
template <class Sample>
std::vector<float> to_floats(Sample* samples, int width, int height, const Header& header,
                             int channels, float one) {
  if (!samples) throw CodecError(stbi_failure_reason());
  const std::unique_ptr<Sample, void (*)(void*)> owner(samples, stbi_image_free);
  if (width != header.width || height != header.height)
    throw CodecError("the pixels' size differs from the header's");
  const std::size_t count = std::size_t(width) * std::size_t(height) * std::size_t(channels);
  std::vector<float> pixels(count);
  std::transform(samples, samples + count, pixels.begin(),
                 [one](Sample value) { return float(value) / one; });
  return pixels;
}

std::vector<float> read_stb(Bytes bytes, const Header& header, int channels) {
  const int size = int(bytes.size());
  int width = 0, height = 0, stored = 0;
  if (!header.integer) {
    float* samples = stbi_loadf_from_memory(bytes.data(), size, &width, &height, &stored, channels);
    return to_floats(samples, width, height, header, channels, 1.0f);
  }
  if (stbi_is_16_bit_from_memory(bytes.data(), size)) {
    stbi_us* samples =
        stbi_load_16_from_memory(bytes.data(), size, &width, &height, &stored, channels);
    return to_floats(samples, width, height, header, channels, 65535.0f);
  }
  stbi_uc* samples = stbi_load_from_memory(bytes.data(), size, &width, &height, &stored, channels);
  return to_floats(samples, width, height, header, channels, 255.0f);
}

/// The first `count` bytes of `file`, or all of them.
std::vector<unsigned char> read_bytes(const std::filesystem::path& file, std::size_t count) {
  std::ifstream in(file, std::ios::binary | std::ios::ate);
  const std::streamoff size = in ? std::streamoff(in.tellg()) : -1;
  if (size < 0) throw CodecError("cannot read the file");
  std::vector<unsigned char> bytes(std::min(count, static_cast<std::size_t>(size)));
  in.seekg(0);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size())))
    throw CodecError("read error");
  return bytes;
}

}  // namespace

struct Decoder::State {
  std::vector<unsigned char> file_bytes;  // a file's, for stb_image
  Bytes bytes;                            // what stb_image decodes: `file_bytes` or the caller's
  std::optional<MemoryInput> exr_memory;  // embedded OpenEXR
  std::unique_ptr<Imf::MultiPartInputFile> exr;  // null: stb_image decodes

  /// Opens OpenEXR from `source`: a file's name, or a stream.
  template <class Source>
  Header open_exr(Source&& source) {
    return with_exr_errors([&] {
      exr = std::make_unique<Imf::MultiPartInputFile>(std::forward<Source>(source));
      return exr_header(exr->header(0));
    });
  }

  Header open_stb(Bytes image) {
    bytes = image;
    return stb_header(bytes);
  }
};

// OpenEXR reads a file itself, as it goes; stb_image reads it from memory, whole.
Decoder::Decoder(const std::filesystem::path& file) : state_(std::make_unique<State>()) {
  constexpr std::size_t kLongestSignature = 8;
  if (is_exr(read_bytes(file, kLongestSignature))) {
    header_ = state_->open_exr(file.c_str());
  } else {
    state_->file_bytes = read_bytes(file, SIZE_MAX);
    header_ = state_->open_stb(state_->file_bytes);
  }
}

Decoder::Decoder(std::span<const unsigned char> bytes, const std::string& format)
    : state_(std::make_unique<State>()) {
  if (is_exr(bytes)) {
    header_ = state_->open_exr(state_->exr_memory.emplace("embedded." + format, bytes));
  } else {
    header_ = state_->open_stb(bytes);
  }
}

Decoder::Decoder(Decoder&&) noexcept = default;
Decoder::~Decoder() = default;

std::vector<float> Decoder::read(int channels) {
  if (!state_->exr) return read_stb(state_->bytes, header_, channels);
  return with_exr_errors([&] { return read_exr(*state_->exr, channels); });
}

// ---- Encoding -----------------------------------------------------------------------------------

std::vector<unsigned char> encode_exr(std::uint32_t width, std::uint32_t height,
                                      const float* rgb) {
  if (width > INT_MAX || height > INT_MAX) throw CodecError("image too large for OpenEXR");
  Imf::Header header(static_cast<int>(width), static_cast<int>(height));
  header.compression() = Imf::ZIP_COMPRESSION;
  const auto& c = kRec709Chromaticities;
  Imf::addChromaticities(header, Imf::Chromaticities({c[0], c[1]}, {c[2], c[3]}, {c[4], c[5]},
                                                     {c[6], c[7]}));
  Imf::FrameBuffer frame;
  const Imath::Box2i window = header.dataWindow();
  const char* const names[] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c) {
    header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
    frame.insert(names[c], Imf::Slice::Make(Imf::FLOAT, rgb + c, window, 3 * sizeof(float),
                                            3 * sizeof(float) * width));
  }
  std::vector<unsigned char> bytes;
  with_exr_errors([&] {
    MemoryOutput stream(bytes);
    Imf::OutputFile output(stream, header);
    output.setFrameBuffer(frame);
    output.writePixels(int(height));
  });
  return bytes;
}

std::vector<unsigned char> encode_png(std::uint32_t width, std::uint32_t height,
                                      const unsigned char* rgb) {
  // libpng, which most PNG readers use, refuses images over a million pixels wide or high by
  // default: such a file would be unreadable to them.
  constexpr std::uint32_t kLibpngLimit = 1'000'000;
  if (width > kLibpngLimit || height > kLibpngLimit) {
    throw CodecError("PNG images over " + std::to_string(kLibpngLimit) +
                     " pixels wide or high are refused by libpng's readers");
  }
  // stb_image_write counts the filtered rows' bytes in an int.
  if (std::uint64_t(height) * (3 * std::uint64_t(width) + 1) > std::uint64_t(INT_MAX))
    throw CodecError("image too large for the PNG encoder");
  std::vector<unsigned char> bytes;
  auto append = [](void* context, void* data, int size) {
    auto& out = *static_cast<std::vector<unsigned char>*>(context);
    const auto* first = static_cast<const unsigned char*>(data);
    out.insert(out.end(), first, first + size);
  };
  if (!stbi_write_png_to_func(append, &bytes, int(width), int(height), 3, rgb, int(3 * width)))
    throw CodecError("stb_image_write failed");
  return bytes;
}

}  // namespace trs::image_codec
