// A sampler over the caller's mesh that samples its refinement (refinement.h) with another
// backend, and brings the results back to the caller's triangles.

#include <algorithm>
#include <chrono>
#include <optional>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/geometry.h"
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

/// The caller's mesh, kept to refine it again when a map changes.
struct OwnedMesh {
  std::vector<float> positions, uvs;
  std::vector<std::uint32_t> indices, triangle_maps;

  explicit OwnedMesh(const MeshView& m)
      : positions(m.positions.begin(), m.positions.end()),
        uvs(m.uvs.begin(), m.uvs.end()),
        indices(m.indices.begin(), m.indices.end()),
        triangle_maps(m.triangle_maps.begin(), m.triangle_maps.end()) {}
  MeshView view() const { return {positions, uvs, indices, triangle_maps}; }
};

class RefinedSampler final : public Sampler {
 public:
  RefinedSampler(const MeshView& mesh, std::span<const DensityMapView> maps, const Refinement& refinement,
                 SamplerFactory backend)
      : input_(mesh, maps), mesh_(mesh), refinement_(refinement), backend_(std::move(backend)) {
    refine(maps);
  }

  Backend backend() const override { return parts_->backend(); }
  std::string device() const override { return parts_->device(); }
  std::uint64_t triangle_count() const override { return input_.triangles().size(); }
  std::size_t map_count() const override { return input_.maps().size(); }
  SamplerSetup setup() const override { return {subdivision_ms_, parts_->triangle_count()}; }

  // The parts were split for the old map's pattern: on the CPU the next frame splits the mesh
  // again (milliseconds). A new Vulkan backend compiles its pipelines (a third of a second on
  // lavapipe), so there the parts stay as the first maps split them and take the new map in place.
  void update_map(std::size_t index, const DensityMapView& map) override {
    input_.update_map(index, map);
    if (parts_->backend() == Backend::cpu)
      stale_ = true;
    else
      parts_->update_map(index, map);
  }

  MapQueries maps() const override { return MapQueries(input_); }

  void generate(const FrameRequest& request, Frame& frame) override {
    double refine_ms = 0.0;
    if (stale_) {
      const auto start = std::chrono::steady_clock::now();
      refine_current_maps();
      refine_ms = ms_since(start);
    }
    parts_->generate(request, frame);
    if (!refined_) return add_refinement_pass(frame, refine_ms);
    const auto back = std::chrono::steady_clock::now();
    if (request.realize && request.vulkan.read_back) {
      std::span<Sample> samples = frame.samples.span();
      // A part's samples lie side by side: its triangle's texel margin is taken once for them.
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.size(), 1 << 14),
                        [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i < r.end();) {
                            const std::uint32_t part = samples[i].triangle;
                            const core::TexelTriangle& t = input_.texel_triangles()[refined_->parent(part)];
                            const float margin = core::texel_edge_margin(t);
                            for (; i < r.end() && samples[i].triangle == part; ++i)
                              samples[i] = on_its_texel(samples[i], t, margin);
                          }
                        });
    }
    const std::size_t n = input_.triangles().size();
    fold_to_parents(frame.expected_counts, *refined_, n, [](double a, double b) { return a + b; });
    fold_to_parents(frame.counts, *refined_, n, [](std::uint64_t a, std::uint64_t b) { return a + b; });
    fold_to_parents(frame.max_density, *refined_, n, [](float a, float b) { return std::max(a, b); });
    add_refinement_pass(frame, refine_ms + ms_since(back));
  }

 private:
  static double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }

  /// A part's sample as the same point of its triangle, on the texel the part read there. A
  /// point drawn on a texel's edge can round across it when its coordinates change, and would
  /// then read the density of a texel it was not drawn from (one without any, perhaps): it is
  /// moved back by a millionth of the triangle, along whichever barycentric axis crosses back.
  /// Most points lie well inside a texel: they are checked by arithmetic alone.
  /// `t` is the triangle's texel triangle, and `margin` its texel_edge_margin.
  Sample on_its_texel(const Sample& part_sample, const core::TexelTriangle& t, float margin) const {
    const Sample s = refined_->to_parent(part_sample);
    if (core::clear_of_texel_edges(t, margin, s.b1, s.b2)) return s;
    const std::optional<Texel> drawn = parts_->maps().texel(part_sample.triangle, part_sample.b1, part_sample.b2);
    const auto on_drawn = [&](const Sample& x) {
      const std::optional<Texel> t = input_.texel(x.triangle, x.b1, x.b2);
      return !drawn || (t && t->map == drawn->map && t->x == drawn->x && t->y == drawn->y);
    };
    if (on_drawn(s)) return s;
    constexpr float kStep = 0x1p-20f;
    for (const auto& [d1, d2] : {std::pair{kStep, 0.0f}, {-kStep, 0.0f}, {0.0f, kStep}, {0.0f, -kStep}}) {
      const Sample moved{s.triangle, s.b1 + d1, s.b2 + d2};
      if (moved.b1 >= 0.0f && moved.b2 >= 0.0f && moved.b1 + moved.b2 <= 1.0f && on_drawn(moved)) return moved;
    }
    return s;
  }

  /// Splits the mesh for `maps` and builds the backend over the parts, or over the mesh itself
  /// where nothing is worth splitting (then there is nothing to bring back).
  void refine(std::span<const DensityMapView> maps) {
    parts_.reset();  // the old backend's memory (a GPU's) before the new one's
    const auto start = std::chrono::steady_clock::now();
    RefinedMesh refined(mesh_.view(), maps, refinement_);
    subdivision_ms_ = ms_since(start);
    parts_ = backend_(refined.view(mesh_.view()), maps);
    // The subdivision measured every part it keeps (with no split, every triangle) as a count
    // would: the first frame need not count them again.
    if (!refined.expected_counts().empty()) parts_->use_counts(refined.expected_counts(), refined.max_density());
    if (refined.levels() == 0)
      refined_.reset();
    else
      refined_ = std::move(refined);
    stale_ = false;
  }

  void refine_current_maps() {
    std::vector<DensityMapView> maps;
    for (const core::DensityMap& m : input_.maps()) maps.push_back({m.texels, m.width, m.height, m.addressing, m.scale});
    refine(maps);
  }

  static void add_refinement_pass(Frame& frame, double ms) {
    if (ms <= 0.0) return;
    frame.passes.push_back({Pass::refinement, ms});
    frame.total_ms += ms;
  }

  core::HostScene input_;
  OwnedMesh mesh_;
  Refinement refinement_;
  SamplerFactory backend_;
  std::optional<RefinedMesh> refined_;  ///< none: the backend samples the mesh itself
  std::unique_ptr<Sampler> parts_;
  double subdivision_ms_ = 0.0;
  bool stale_ = false;
};

}  // namespace

std::unique_ptr<Sampler> make_refined_sampler(const MeshView& mesh,
                                              std::span<const DensityMapView> maps,
                                              const Refinement& refinement,
                                              SamplerFactory backend) {
  return std::make_unique<RefinedSampler>(mesh, maps, refinement, std::move(backend));
}

}  // namespace lightsampler
