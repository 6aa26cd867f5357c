#include "support/image_files.h"

#include <ImfChannelList.h>
#include <ImfDeepFrameBuffer.h>
#include <ImfDeepScanLineOutputFile.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfPartType.h>
#include <ImfStandardAttributes.h>
#include <ImfTiledOutputFile.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <stdexcept>

namespace trs_test {
namespace {

void append_u32(std::string& out, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) out += char((value >> shift) & 0xff);
}

std::uint32_t crc32(const std::string& bytes) {
  std::uint32_t crc = 0xffffffff;
  for (const char byte : bytes) {
    crc ^= std::uint8_t(byte);
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xedb88320 & (0 - (crc & 1)));
  }
  return ~crc;
}

void append_chunk(std::string& out, const std::string& type, const std::string& data) {
  append_u32(out, std::uint32_t(data.size()));
  out += type + data;
  append_u32(out, crc32(type + data));
}

/// A zlib stream of `data` in stored (uncompressed) deflate blocks.
std::string zlib_stored(const std::string& data) {
  std::string out = "\x78\x01";
  std::size_t offset = 0;
  do {
    const std::size_t size = std::min<std::size_t>(data.size() - offset, 65535);
    const bool last = offset + size == data.size();
    out += char(last ? 1 : 0);
    out += char(size & 0xff);
    out += char(size >> 8);
    out += char(~size & 0xff);
    out += char((~size >> 8) & 0xff);
    out.append(data, offset, size);
    offset += size;
  } while (offset < data.size());
  std::uint32_t a = 1, b = 0;  // Adler-32
  for (const char byte : data) {
    a = (a + std::uint8_t(byte)) % 65521;
    b = (b + a) % 65521;
  }
  append_u32(out, (b << 16) | a);
  return out;
}

}  // namespace

std::string png_file(int width, int height, int channels, int bit_depth,
                     const std::vector<std::uint16_t>& samples,
                     const std::vector<PngChunk>& chunks) {
  static const char kColourType[] = {0, 0, 4, 2, 6};  // by channel count
  std::string header;
  append_u32(header, std::uint32_t(width));
  append_u32(header, std::uint32_t(height));
  header += {char(bit_depth), kColourType[channels], 0, 0, 0};

  std::string rows;  // each row: filter type 0 (none), then its samples, big-endian
  const std::size_t row_samples = std::size_t(width) * std::size_t(channels);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (i % row_samples == 0) rows += '\0';
    if (bit_depth == 16) rows += char(samples[i] >> 8);
    rows += char(samples[i] & 0xff);
  }

  std::string png = "\x89PNG\r\n\x1a\n";
  append_chunk(png, "IHDR", header);
  for (const auto& [type, data] : chunks) append_chunk(png, type, data);
  append_chunk(png, "IDAT", zlib_stored(rows));
  append_chunk(png, "IEND", "");
  return png;
}

void write_float_exr(const std::filesystem::path& file, int width, int height, int channels,
                     const std::vector<float>& values, int tile) {
  const std::vector<std::string> names =
      channels == 1 ? std::vector<std::string>{"Y"} : std::vector<std::string>{"R", "G", "B"};
  Imf::Header header(width, height);
  Imf::FrameBuffer frame;
  for (std::size_t c = 0; c < names.size(); ++c) {
    header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
    frame.insert(names[c],
                 Imf::Slice::Make(Imf::FLOAT, values.data() + c, header.dataWindow(),
                                  sizeof(float) * names.size(),
                                  sizeof(float) * names.size() * std::size_t(width)));
  }
  if (tile == 0) {
    Imf::OutputFile output(file.c_str(), header);
    output.setFrameBuffer(frame);
    output.writePixels(height);
    return;
  }
  header.setTileDescription(Imf::TileDescription(tile, tile, Imf::ONE_LEVEL));
  Imf::TiledOutputFile output(file.c_str(), header);
  output.setFrameBuffer(frame);
  output.writeTiles(0, output.numXTiles() - 1, 0, output.numYTiles() - 1);
}

std::string exr_layout(const std::filesystem::path& file) {
  const Imf::InputFile input(file.c_str());
  const Imf::Header& header = input.header();
  std::string layout;
  for (auto channel = header.channels().begin(); channel != header.channels().end(); ++channel) {
    const Imf::PixelType type = channel.channel().type;
    layout += std::string(layout.empty() ? "" : " ") + channel.name() + ":" +
              (type == Imf::FLOAT ? "float" : type == Imf::HALF ? "half" : "uint");
  }
  const bool zip = header.compression() == Imf::ZIP_COMPRESSION;
  return layout + ", " + (zip ? "zip" : "compression " + std::to_string(header.compression()));
}

std::vector<float> exr_chromaticities(const std::filesystem::path& file) {
  const Imf::InputFile input(file.c_str());
  if (!Imf::hasChromaticities(input.header())) return {};
  const Imf::Chromaticities& c = Imf::chromaticities(input.header());
  return {c.red.x, c.red.y, c.green.x, c.green.y, c.blue.x, c.blue.y, c.white.x, c.white.y};
}

void write_deep_exr(const std::filesystem::path& file) {
  Imf::Header header(1, 1);
  header.setType(Imf::DEEPSCANLINE);
  header.compression() = Imf::ZIPS_COMPRESSION;
  header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
  unsigned int count = 2;
  float depths[2] = {1.0f, 2.0f};
  float* pointer = depths;
  Imf::DeepFrameBuffer frame;
  frame.insertSampleCountSlice(
      Imf::Slice(Imf::UINT, reinterpret_cast<char*>(&count), sizeof count, sizeof count));
  frame.insert("Z", Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(&pointer),
                                   sizeof pointer, sizeof pointer, sizeof(float)));
  Imf::DeepScanLineOutputFile output(file.c_str(), header);
  output.setFrameBuffer(frame);
  output.writePixels(1);
}

std::string jpeg_file(int width, int height, const std::vector<unsigned char>& rgb, int quality) {
  std::string bytes;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), std::size_t(size));
  };
  if (!stbi_write_jpg_to_func(append, &bytes, width, height, 3, rgb.data(), quality))
    throw std::runtime_error("stb_image_write could not encode the JPEG");
  return bytes;
}

}  // namespace trs_test
