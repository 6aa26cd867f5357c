#include "dataset_file.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

#include "scene_io/atomic_file.h"
#include "scene_io/file_error.h"

namespace trs_bench {

namespace {

static_assert(std::endian::native == std::endian::little, "dataset files are little-endian");

constexpr char kMagic[8] = {'T', 'R', 'S', 'D', 'S', 'E', 'T', '1'};

struct Header {
  char magic[8];
  std::uint64_t vertices, triangles;
  std::uint32_t width, height;
};
static_assert(sizeof(Header) == 32);

std::uint64_t body_bytes(const Header& h) {
  return 20 * h.vertices + 12 * h.triangles + 4 * std::uint64_t(h.width) * h.height;
}

/// An open dataset file whose header and size have been checked.
class Reader {
 public:
  explicit Reader(std::filesystem::path file) : file_(std::move(file)), in_(file_, std::ios::binary) {
    if (!in_) throw trs::FileError(file_, "cannot open");
    if (!in_.read(reinterpret_cast<char*>(&header_), sizeof header_) ||
        std::memcmp(header_.magic, kMagic, sizeof kMagic) != 0)
      throw trs::FileError(file_, "not a dataset file (no TRSDSET1 header)");
    // Limits far above any real input, so that the size arithmetic cannot overflow.
    if (header_.vertices > (1ull << 40) || header_.triangles > (1ull << 40))
      throw trs::FileError(file_, "implausible vertex or triangle count");
    const std::uint64_t expected = sizeof header_ + body_bytes(header_);
    const std::uint64_t actual = std::filesystem::file_size(file_);
    if (actual != expected)
      throw trs::FileError(file_, "is " + std::to_string(actual) + " bytes, the header says " +
                                      std::to_string(expected) +
                                      (actual < expected ? " (truncated)" : ""));
  }

  const Header& header() const { return header_; }
  [[noreturn]] void fail(const std::string& problem) const { throw trs::FileError(file_, problem); }
  std::string name() const { return file_.stem().string(); }

  template <class T>
  std::vector<T> read(std::uint64_t offset, std::uint64_t count) {
    std::vector<T> values(count);
    in_.seekg(std::streamoff(offset));
    if (!in_.read(reinterpret_cast<char*>(values.data()), std::streamsize(count * sizeof(T))))
      fail("read error");
    return values;
  }

 private:
  std::filesystem::path file_;
  std::ifstream in_;
  Header header_{};
};

bool all_finite(const std::vector<float>& values) {
  return std::all_of(values.begin(), values.end(), [](float x) { return std::isfinite(x); });
}

}  // namespace

Mesh read_dataset_mesh(const std::filesystem::path& file) {
  Reader reader(file);
  const Header& h = reader.header();
  if (h.triangles == 0) reader.fail("has no mesh (0 triangles)");
  if (h.vertices > 0xffffffffull) reader.fail("more than 2^32 vertices");
  Mesh mesh;
  mesh.name = reader.name();
  mesh.positions = reader.read<float>(sizeof(Header), 3 * h.vertices);
  mesh.uvs = reader.read<float>(sizeof(Header) + 12 * h.vertices, 2 * h.vertices);
  mesh.indices = reader.read<std::uint32_t>(sizeof(Header) + 20 * h.vertices, 3 * h.triangles);
  if (!all_finite(mesh.positions) || !all_finite(mesh.uvs))
    reader.fail("a vertex position or UV is NaN or infinite");
  const auto bad = std::find_if(mesh.indices.begin(), mesh.indices.end(),
                                [&](std::uint32_t i) { return i >= h.vertices; });
  if (bad != mesh.indices.end())
    reader.fail("index " + std::to_string(*bad) + " of triangle " +
                std::to_string((bad - mesh.indices.begin()) / 3) + " is past the " +
                std::to_string(h.vertices) + " vertices");
  return mesh;
}

DensityMap read_dataset_map(const std::filesystem::path& file) {
  Reader reader(file);
  const Header& h = reader.header();
  if (std::uint64_t(h.width) * h.height == 0) reader.fail("has no density map (0 texels)");
  DensityMap map;
  map.name = reader.name();
  map.width = h.width;
  map.height = h.height;
  map.texels = reader.read<float>(sizeof(Header) + 20 * h.vertices + 12 * h.triangles,
                                  std::uint64_t(h.width) * h.height);
  const auto bad = std::find_if(map.texels.begin(), map.texels.end(),
                                [](float t) { return !(std::isfinite(t) && t >= 0); });
  if (bad != map.texels.end())
    reader.fail("texel " + std::to_string(bad - map.texels.begin()) + " is " + std::to_string(*bad) +
                " (densities are finite and non-negative)");
  return map;
}

void write_dataset(const std::filesystem::path& file, const Mesh& mesh, const DensityMap& map) {
  Header header{};
  std::memcpy(header.magic, kMagic, sizeof kMagic);
  header.vertices = mesh.positions.size() / 3;
  header.triangles = mesh.triangle_count();
  header.width = map.texels.empty() ? 0 : map.width;
  header.height = map.texels.empty() ? 0 : map.height;
  trs::AtomicFile out(file);
  out.write(&header, sizeof header);
  out.write(mesh.positions.data(), mesh.positions.size() * sizeof(float));
  out.write(mesh.uvs.data(), mesh.uvs.size() * sizeof(float));
  out.write(mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t));
  out.write(map.texels.data(), map.texels.size() * sizeof(float));
  out.commit();
}

}  // namespace trs_bench
