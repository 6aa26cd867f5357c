#include "scene_io/ply.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <bit>
#include <cstring>
#include <future>
#include <memory>

namespace trs {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the PLY writer copies native floats into a little-endian file");

/// Samples per chunk: 64 MiB of output, large enough for big sequential writes, small enough
/// that two of them (one being converted, one being written) cost little memory.
constexpr std::size_t kChunkSamples = std::size_t(1) << 21;

struct PlyVertex {
  float x, y, z, u, v;
  std::uint32_t triangle;
  float b1, b2;
};
static_assert(sizeof(PlyVertex) == kPlyBytesPerSample);

void convert(const lightsampler::MeshView& view, UvOrigin uv_origin,
             std::span<const lightsampler::Sample> samples, PlyVertex* out) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        const lightsampler::Sample& s = samples[i];
                        const lightsampler::Float3 p = lightsampler::position(view, s);
                        const lightsampler::Float2 t =
                            to_file_uv(lightsampler::uv(view, s), uv_origin);
                        out[i] = {p.x, p.y, p.z, t.x, t.y, s.triangle, s.b1, s.b2};
                      }
                    });
}

}  // namespace

std::string ply_header(std::uint64_t count, UvOrigin uv_origin) {
  return "ply\n"
         "format binary_little_endian 1.0\n"
         "comment samples of trs-sample; uv: v = 0 at the image's " +
         std::string(uv_origin == UvOrigin::top ? "top row (glTF convention)"
                                                : "bottom row (OBJ convention)") +
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

void write_ply(AtomicFile& out, const MeshData& mesh,
               std::span<const lightsampler::Sample> samples) {
  out.write(ply_header(samples.size(), mesh.file_uv_origin));
  const lightsampler::MeshView view = mesh.view();
  const std::size_t chunk = std::min(kChunkSamples, samples.size());
  // Declared before the pending write, so that they outlive it when an exception unwinds.
  std::unique_ptr<PlyVertex[]> buffers[2] = {std::make_unique_for_overwrite<PlyVertex[]>(chunk),
                                             std::make_unique_for_overwrite<PlyVertex[]>(chunk)};
  std::future<void> pending;
  for (std::size_t begin = 0, k = 0; begin < samples.size(); begin += chunk, k ^= 1) {
    const std::size_t count = std::min(chunk, samples.size() - begin);
    convert(view, mesh.file_uv_origin, samples.subspan(begin, count), buffers[k].get());
    if (pending.valid()) pending.get();
    pending = std::async(std::launch::async, [&out, data = buffers[k].get(), count] {
      out.write(data, count * sizeof(PlyVertex));
    });
  }
  if (pending.valid()) pending.get();
}

}  // namespace trs
