#include "lightsampler/refinement.h"

#include <algorithm>
#include <cmath>

#include "core/counting.h"
#include "core/host_scene.h"
#include "core/validate.h"

namespace lightsampler {

namespace {

using Part = RefinedMesh::Part;

/// The four parts of a part, split at its edge midpoints; each keeps its parent's winding.
void split(const Part& p, std::vector<Part>& out) {
  const auto mid = [&](int a, int b, float m[2]) {
    m[0] = 0.5f * (p.corners[a][0] + p.corners[b][0]);
    m[1] = 0.5f * (p.corners[a][1] + p.corners[b][1]);
  };
  float m01[2], m12[2], m20[2];
  mid(0, 1, m01);
  mid(1, 2, m12);
  mid(2, 0, m20);
  const float* c0 = p.corners[0];
  const float* c1 = p.corners[1];
  const float* c2 = p.corners[2];
  const float* children[4][3] = {{c0, m01, m20}, {m01, c1, m12}, {m20, m12, c2}, {m12, m20, m01}};
  for (const auto& child : children) {
    Part q{p.parent, {}};
    for (int k = 0; k < 3; ++k) std::copy_n(child[k], 2, q.corners[k]);
    out.push_back(q);
  }
}

/// Mean density over D_T^max: the probability that the rejection loop accepts a candidate.
/// 1 for a part with nothing to sample (no density or no area): nothing to gain by splitting it.
double acceptance(double expected, float max_density, double area) {
  const double bound = double(max_density) * area;
  return bound > 0.0 ? expected / bound : 1.0;
}

double texel_area(const core::TexelTriangle& t) {
  return 0.5 * std::abs(double(t.edge1[0]) * t.edge2[1] - double(t.edge1[1]) * t.edge2[0]);
}

}  // namespace

RefinedMesh::RefinedMesh(const MeshView& mesh, std::span<const DensityMapView> maps,
                         const Refinement& refinement) {
  core::validate_mesh(mesh, maps.size());
  for (std::size_t i = 0; i < maps.size(); ++i) core::validate_map(maps[i], i);
  std::vector<Part> open(mesh.indices.size() / 3), done, next;
  for (std::uint32_t t = 0; t < open.size(); ++t) open[t] = {t, {{0, 0}, {1, 0}, {0, 1}}};
  Buffer<double> expected;
  Buffer<float> max_density;
  for (std::uint32_t level = 0; !open.empty(); ++level) {
    if (level == refinement.max_levels || !(refinement.min_acceptance > 0.0f)) {
      done.insert(done.end(), open.begin(), open.end());
      break;
    }
    build(mesh, open);
    const core::HostScene scene(view(), maps);
    core::count(scene.triangles(), scene.texel_triangles(), scene.maps(), expected, max_density);
    next.clear();
    for (std::size_t i = 0; i < open.size(); ++i) {
      // Parts there would be if this one and those after it stayed whole.
      const std::uint64_t whole = done.size() + next.size() + (open.size() - i);
      const bool worth = acceptance(expected[i], max_density[i], scene.triangles()[i].area) <
                             refinement.min_acceptance &&
                         texel_area(scene.texel_triangles()[i]) > refinement.min_texels;
      if (worth && whole + 3 <= refinement.max_triangles)
        split(open[i], next);
      else
        done.push_back(open[i]);
    }
    if (!next.empty()) levels_ = level + 1;
    open.swap(next);
  }
  // Parts of one triangle side by side: the sampler walks them in order.
  std::stable_sort(done.begin(), done.end(),
                   [](const Part& a, const Part& b) { return a.parent < b.parent; });
  parts_ = std::move(done);
  build(mesh, parts_);
}

void RefinedMesh::build(const MeshView& mesh, const std::vector<Part>& parts) {
  positions_.clear();
  uvs_.clear();
  indices_.clear();
  triangle_maps_.clear();
  for (const Part& part : parts) {
    const std::uint32_t* v = &mesh.indices[3 * std::size_t(part.parent)];
    for (const float* b : part.corners) {
      const double w[3] = {1.0 - double(b[0]) - double(b[1]), b[0], b[1]};
      for (int axis = 0; axis < 3; ++axis) {
        double x = 0.0;
        for (int k = 0; k < 3; ++k) x += w[k] * mesh.positions[3 * std::size_t(v[k]) + axis];
        positions_.push_back(float(x));
      }
      for (int axis = 0; axis < 2; ++axis) {
        double x = 0.0;
        for (int k = 0; k < 3; ++k) x += w[k] * mesh.uvs[2 * std::size_t(v[k]) + axis];
        uvs_.push_back(float(x));
      }
      indices_.push_back(std::uint32_t(indices_.size()));
    }
    if (!mesh.triangle_maps.empty()) triangle_maps_.push_back(mesh.triangle_maps[part.parent]);
  }
}

}  // namespace lightsampler
