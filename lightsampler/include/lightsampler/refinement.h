#pragma once
// Adaptive subdivision of the mesh before sampling, the remedy the paper's Section 7 suggests
// for triangles whose density is very uneven. A triangle's rejection loop accepts a candidate
// with probability mean density / D_T^max; a large triangle under a sparse pattern (neon strokes,
// a fine mosaic) accepts few. Splitting it into four at its edge midpoints, where that is low,
// bounds each part by its own maximum. The samples are the same distribution (the parts are
// counted exactly, like any triangle); only the work per sample drops.
//
// The subdivision is decided once, from the maps it is built with. A map updated later keeps the
// same parts: still exact, only perhaps less efficient.

#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "lightsampler/mesh.h"
#include "lightsampler/sample.h"
#include "lightsampler/sampler.h"

namespace lightsampler {

/// The acceptance below which the tools' `--refine auto` considers splitting a triangle at all:
/// above it a split saves at most 15% of its candidates.
inline constexpr float kAutoMinAcceptance = 0.85f;

/// What a part costs every frame, in the work of one candidate of the rejection loop: its count
/// copied, rounded, scanned and folded back to its triangle (about 0.4 candidates on the CPU
/// backend), and the realization's set-up of a triangle that has samples (about 6), measured
/// and then tuned on the light sampler's frame time in trs-render (docs/benchmarks.md).
inline constexpr float kPartCost = 8.0f;

/// What measuring a part once costs at set-up (its integral and bound, as a count does), in the
/// work of one candidate: kMeasureCost for the part and kMeasureTexelCost more for each texel
/// it covers, measured on the CPU backend (docs/benchmarks.md).
inline constexpr float kMeasureCost = 28.0f;
inline constexpr float kMeasureTexelCost = 12.0f;

struct Refinement {
  /// Split a triangle while its expected acceptance (mean density over D_T^max) is below this.
  /// 0: no refinement.
  float min_acceptance = 0.0f;
  /// Never split a triangle that covers fewer texels than this. Parts of a sixteenth of a texel
  /// still pay on sparse maps, where they let a stroke's edge fall between them (the split gain
  /// rule keeps only such splits); below that they only add counting work.
  float min_texels = 0.0625f;
  /// Keep a split of a triangle of at most gain_texels texels only if its four parts draw at
  /// least this many times fewer candidates than the whole (the sum of D^max times area over
  /// the parts, against the whole's): near the texel scale a split that barely lowers the bound,
  /// as on texel noise, costs counting work every frame and saves little. It is also kept if
  /// two rounds draw min_split_gain squared times fewer (the parts' own splits counted where
  /// they pay): a thin stroke across all four parts may leave most of their parts off it.
  /// Larger triangles split freely, since a pattern finer than them may only pay off a few
  /// splits down.
  float min_split_gain = 1.25f;
  float gain_texels = 16.0f;
  /// Splits of one triangle at most (a triangle becomes at most 4^max_levels parts).
  std::uint32_t max_levels = 8;
  /// Parts in all at most; beyond it triangles stay as they are.
  std::uint64_t max_triangles = std::uint64_t(1) << 24;

  /// The cost model (the tools' `--refine auto`): a split is kept only where the candidates it
  /// saves on the samples of a frame outweigh the per-frame work of its three more parts, judged
  /// over all the rounds of splits below it (a pattern finer than a triangle may pay only a few
  /// splits down). Only triangles below min_acceptance, above min_texels, whose candidates could
  /// pay for a split even at full acceptance, are tried; min_split_gain and gain_texels are not
  /// used. Set-up and per-frame work then scale with the samples a frame draws, not with the
  /// texels under the mesh.
  bool cost_model = false;
  /// Cost model: the samples a frame draws (N_target). 0: not known; the rules above decide.
  double frame_samples = 0.0;
  /// Cost model: a part's work each frame, in candidates.
  float part_cost = kPartCost;
  /// Cost model: measuring a part at set-up, in candidates, and more per texel it covers. A split
  /// is explored only where the candidates one frame could save on it also repay measuring its
  /// four parts, so that the subdivision's set-up stays below what a frame repays.
  float measure_cost = kMeasureCost;
  float measure_texel_cost = kMeasureTexelCost;
  /// Cost model: parts added at most per sample a frame draws.
  float parts_per_sample = 0.5f;
};

/// The cost model's subdivision (the tools' `--refine auto`) for frames of `frame_samples` samples.
inline Refinement auto_refinement(double frame_samples) {
  return {.min_acceptance = kAutoMinAcceptance, .cost_model = true, .frame_samples = frame_samples};
}

/// Whether `refinement` splits by the cost model (it has the samples of a frame to weigh).
inline bool splits_by_cost(const Refinement& refinement) {
  return refinement.cost_model && refinement.frame_samples > 0.0;
}

/// The subdivided mesh: parts of the caller's triangles, each with its own vertices, and the
/// way back from a part to its triangle.
class RefinedMesh {
 public:
  /// Throws as the samplers do on a bad mesh or map.
  RefinedMesh(const MeshView& mesh, std::span<const DensityMapView> maps,
              const Refinement& refinement);

  /// The parts as a mesh; `mesh`, the one split, where nothing split (levels() == 0).
  MeshView view(const MeshView& mesh) const {
    return levels_ > 0 ? MeshView{positions_, uvs_, indices_, triangle_maps_} : mesh;
  }
  std::uint32_t triangle_count() const { return std::uint32_t(parts_.size()); }
  /// The caller's triangle that part `part` lies in.
  std::uint32_t parent(std::uint32_t part) const { return parts_[part].parent; }
  /// A sample of the refined mesh as the same point of the caller's mesh.
  Sample to_parent(const Sample& s) const;
  /// Splitting rounds that split at least one triangle.
  std::uint32_t levels() const { return levels_; }
  /// Each part's N-bar_T and D_T^max as the subdivision measured them, which is what a counting
  /// pass over view() gives with the closed form (Sampler::use_counts); empty without a
  /// refinement. With no split, the caller's triangles' counts.
  std::span<const double> expected_counts() const { return expected_counts_; }
  std::span<const float> max_density() const { return max_density_; }

  struct Part {
    std::uint32_t parent;
    float corners[3][2];  ///< the part's vertices as (b1, b2) of the parent triangle
  };

 private:
  /// A part's corners in the caller's mesh, rounded as the refined mesh stores them.
  static void part_corners(const MeshView& mesh, const Part& part, float (&positions)[3][3], float (&uvs)[3][2]);
  /// The refined mesh's vertices and triangles, from parts_.
  void build(const MeshView& mesh);

  std::vector<Part> parts_;
  std::vector<float> positions_;
  std::vector<float> uvs_;
  std::vector<std::uint32_t> indices_;
  std::vector<std::uint32_t> triangle_maps_;
  std::vector<double> expected_counts_;
  std::vector<float> max_density_;
  std::uint32_t levels_ = 0;
};

inline Sample RefinedMesh::to_parent(const Sample& s) const {
  const Part& p = parts_[s.triangle];
  float b[2];
  for (int axis = 0; axis < 2; ++axis)
    b[axis] = p.corners[0][axis] + s.b1 * (p.corners[1][axis] - p.corners[0][axis]) +
              s.b2 * (p.corners[2][axis] - p.corners[0][axis]);
  // Rounding can step an ulp outside the triangle.
  b[0] = std::clamp(b[0], 0.0f, 1.0f);
  b[1] = std::clamp(b[1], 0.0f, 1.0f - b[0]);
  return {p.parent, b[0], b[1]};
}

/// Builds the backend that samples the parts (e.g. make_cpu_sampler over the given mesh). The
/// refined sampler keeps it, to build the backend again when the parts change: it must own what
/// it captures.
using SamplerFactory =
    std::function<std::unique_ptr<Sampler>(const MeshView&, std::span<const DensityMapView>)>;

/// A sampler over the caller's mesh that samples a refined copy of it. Samples, density(),
/// texel(), and the Frame's per-triangle expected_counts, counts and max_density refer to the
/// caller's triangles; cdf and inverse_permutation to the parts, which are what is processed.
/// Samples are brought back to the caller's triangles on the host, so the Vulkan backend must
/// read them back (FrameRequest::vulkan.read_back). Where nothing is worth splitting the backend
/// samples the caller's mesh itself. After update_map, on the CPU backend, the next frame splits
/// the mesh again for the maps as they are (an animated texture's parts follow its pattern), and
/// its `refinement` pass includes that time; the Vulkan backend keeps the parts of the first maps.
std::unique_ptr<Sampler> make_refined_sampler(const MeshView& mesh,
                                              std::span<const DensityMapView> maps,
                                              const Refinement& refinement,
                                              SamplerFactory backend);

}  // namespace lightsampler
