// A sampler over the caller's mesh that samples its refinement (refinement.h) with another
// backend, and brings the results back to the caller's triangles.

#include <algorithm>
#include <chrono>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/host_scene.h"
#include "lightsampler/refinement.h"

namespace lightsampler {

namespace {

/// Per-part values folded into per-triangle values, in place: parts are sorted by triangle and
/// every triangle has at least one, so triangle t is written only after part t has been read.
template <class T, class Fold>
void fold_to_parents(Buffer<T>& values, const RefinedMesh& refined, std::size_t triangles,
                     Fold fold) {
  if (values.size() != refined.triangle_count()) return;  // not filled this frame
  std::uint32_t last = ~0u;
  for (std::uint32_t part = 0; part < refined.triangle_count(); ++part) {
    const std::uint32_t t = refined.parent(part);
    values[t] = t == last ? fold(values[t], values[part]) : values[part];
    last = t;
  }
  values.resize(triangles);
}

class RefinedSampler final : public Sampler {
 public:
  RefinedSampler(const MeshView& mesh, std::span<const DensityMapView> maps, RefinedMesh refined,
                 const SamplerFactory& backend)
      : input_(mesh, maps), refined_(std::move(refined)), parts_(backend(refined_.view(), maps)) {}

  Backend backend() const override { return parts_->backend(); }
  std::string device() const override { return parts_->device(); }
  std::uint64_t triangle_count() const override { return input_.triangles().size(); }
  std::size_t map_count() const override { return input_.maps().size(); }

  void update_map(std::size_t index, const DensityMapView& map) override {
    parts_->update_map(index, map);
    input_.update_map(index, map);
  }

  float density(std::uint32_t triangle, float b1, float b2) const override {
    return input_.density(triangle, b1, b2);
  }
  std::optional<Texel> texel(std::uint32_t triangle, float b1, float b2) const override {
    return input_.texel(triangle, b1, b2);
  }
  void texel_pieces(std::uint32_t triangle, std::vector<TexelPiece>& out) const override {
    input_.texel_pieces(triangle, out);
  }
  std::optional<Barycentrics> texel_piece_point(std::uint32_t triangle, std::int64_t cell_x, std::int64_t cell_y,
                                                float u_fan, float u0, float u1) const override {
    return input_.texel_piece_point(triangle, cell_x, cell_y, u_fan, u0, u1);
  }

  void generate(const FrameRequest& request, Frame& frame) override {
    parts_->generate(request, frame);
    const auto start = std::chrono::steady_clock::now();
    if (request.realize && request.vulkan.read_back) {
      std::span<Sample> samples = frame.samples.span();
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.size(), 1 << 14),
                        [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i < r.end(); ++i)
                            samples[i] = refined_.to_parent(samples[i]);
                        });
    }
    const std::size_t n = input_.triangles().size();
    fold_to_parents(frame.expected_counts, refined_, n, [](double a, double b) { return a + b; });
    fold_to_parents(frame.counts, refined_, n, [](std::uint64_t a, std::uint64_t b) { return a + b; });
    fold_to_parents(frame.max_density, refined_, n, [](float a, float b) { return std::max(a, b); });
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    frame.passes.push_back({Pass::refinement, ms});
    frame.total_ms += ms;
  }

 private:
  core::HostScene input_;
  RefinedMesh refined_;
  std::unique_ptr<Sampler> parts_;
};

}  // namespace

std::unique_ptr<Sampler> make_refined_sampler(const MeshView& mesh,
                                              std::span<const DensityMapView> maps,
                                              const Refinement& refinement,
                                              const SamplerFactory& backend) {
  RefinedMesh refined(mesh, maps, refinement);
  // Nothing worth splitting: the backend over the mesh itself, with nothing to bring back.
  if (refined.levels() == 0) return backend(mesh, maps);
  return std::make_unique<RefinedSampler>(mesh, maps, std::move(refined), backend);
}

}  // namespace lightsampler
