#include "lightsampler/refinement.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <numeric>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/counting.h"
#include "core/host_scene.h"

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

/// What the subdivision weighs about a part, from one counting pass over its parts.
struct Measure {
  double bound;       ///< D_T^max times world area: candidates per unit of expected samples, times them
  double acceptance;  ///< mean density over D_T^max; 1 with nothing to sample (no gain in splitting)
  double texels;      ///< area in texels
  double expected;    ///< the density's integral over the part
  float max_density;  ///< D_T^max
};

/// A part the subdivision keeps, with its measure: its count as a backend would make it.
struct MeasuredPart {
  Part part;
  Measure measure;
};

double texel_area(const core::TexelTriangle& t) {
  return 0.5 * std::abs(double(t.edge1[0]) * t.edge2[1] - double(t.edge1[1]) * t.edge2[0]);
}

double bound_of_four(const std::vector<Measure>& measured, std::size_t first) {
  double bound = 0.0;
  for (std::size_t c = first; c < first + 4; ++c) bound += measured[c].bound;
  return bound;
}

/// Whether each tried split pays (children: the four parts of each tried part, in order). A
/// part larger than gain_texels splits freely. A smaller one splits if its parts draw
/// min_split_gain times fewer candidates than the whole, or if two rounds of splits draw
/// min_split_gain squared times fewer (if a second round is allowed, look_ahead): a stroke that
/// crosses all four parts can leave most of their parts off it.
template <class Measurer>
std::vector<bool> splits_that_pay(const std::vector<std::size_t>& tried, const std::vector<Measure>& measured,
                                  const std::vector<Part>& children, const std::vector<Measure>& child_measured,
                                  const Refinement& refinement, bool look_ahead, const Measurer& measure) {
  std::vector<bool> pays(tried.size());
  std::vector<std::size_t> undecided;
  std::vector<Part> grandchildren;
  for (std::size_t k = 0; k < tried.size(); ++k) {
    const Measure& whole = measured[tried[k]];
    pays[k] = whole.texels > refinement.gain_texels ||
              bound_of_four(child_measured, 4 * k) * refinement.min_split_gain <= whole.bound;
    if (pays[k] || !look_ahead) continue;
    undecided.push_back(k);
    for (std::size_t c = 4 * k; c < 4 * k + 4; ++c) split(children[c], grandchildren);
  }
  if (undecided.empty()) return pays;
  const std::vector<Measure> grand_measured = measure(grandchildren);
  for (std::size_t j = 0; j < undecided.size(); ++j) {
    const std::size_t k = undecided[j];
    double bound = 0.0;
    for (std::size_t c = 0; c < 4; ++c) {
      // A part counts as split again only where the next round would try it and it pays.
      const Measure& child = child_measured[4 * k + c];
      const double parts = bound_of_four(grand_measured, 16 * j + 4 * c);
      const bool splits = child.acceptance < refinement.min_acceptance && child.texels > refinement.min_texels &&
                          parts * refinement.min_split_gain <= child.bound;
      bound += splits ? parts : child.bound;
    }
    pays[k] = bound * refinement.min_split_gain * refinement.min_split_gain <= measured[tried[k]].bound;
  }
  return pays;
}

/// A part the cost model explored, and where its four parts are, if it was split.
struct Node {
  Part part;
  Measure measure;
  std::uint32_t level;
  std::size_t first_child = std::numeric_limits<std::size_t>::max();
  bool explored() const { return first_child != std::numeric_limits<std::size_t>::max(); }
};

/// The parts of the cost model (Refinement::cost_model). Splits are explored round by round
/// where a part's wasted candidates (its bound less its integral, in candidates of a frame)
/// could pay for three more parts, the most wasteful first within the budget of parts; then
/// every explored split is kept or undone bottom-up, whichever leaves the part and what lies
/// below it cheaper per frame: candidates drawn plus part_cost per part. Those of a root side
/// by side, in root order. Raises `levels` to the deepest split kept; where none is, the parts
/// are the roots (and may not be returned).
template <class Measurer>
std::vector<MeasuredPart> split_by_cost(const std::vector<Part>& roots, const std::vector<Measure>& measured,
                                const Refinement& refinement, const Measurer& measure, std::uint32_t& levels) {
  const double total = std::accumulate(measured.begin(), measured.end(), 0.0,
                                       [](double sum, const Measure& m) { return sum + m.expected; });
  if (!(total > 0.0)) return {};
  const double candidates_per_bound = refinement.frame_samples / total;
  const double split_cost = 3.0 * double(refinement.part_cost);
  const auto wasted = [&](const Measure& m) { return candidates_per_bound * (m.bound - m.expected); };
  // A split is explored only where the candidates a frame could save on it pay for its three
  // more parts and for measuring its four: set-up then stays below what a frame repays.
  const auto worth_exploring = [&](const Measure& m) {
    const double measuring = 4.0 * refinement.measure_cost + refinement.measure_texel_cost * m.texels;
    return m.acceptance < refinement.min_acceptance && m.texels > refinement.min_texels &&
           wasted(m) > split_cost + measuring;
  };
  // Most triangles of a large mesh are not worth a split: where none is, the parts are the roots.
  if (std::none_of(measured.begin(), measured.end(), worth_exploring)) return {};
  const std::uint64_t room = refinement.max_triangles > roots.size() ? refinement.max_triangles - roots.size() : 0;
  std::uint64_t budget = std::min<std::uint64_t>(
      room, std::uint64_t(std::max(0.0, double(refinement.parts_per_sample) * refinement.frame_samples)));

  // A deque: the explored parts grow by levels into the millions, and a vector's growth would
  // copy and touch them again each time it doubles.
  std::deque<Node> nodes;
  for (std::size_t i = 0; i < roots.size(); ++i) nodes.push_back({roots[i], measured[i], 0});
  std::vector<std::size_t> frontier(nodes.size());
  std::iota(frontier.begin(), frontier.end(), std::size_t(0));
  std::vector<Part> children;
  for (std::uint32_t level = 0; level < refinement.max_levels && !frontier.empty(); ++level) {
    std::vector<std::size_t> tried;
    for (std::size_t i : frontier)
      if (worth_exploring(nodes[i].measure)) tried.push_back(i);
    if (tried.size() > budget / 3) {  // the most wasteful first; sorted only when the budget binds
      std::stable_sort(tried.begin(), tried.end(), [&](std::size_t a, std::size_t b) {
        return wasted(nodes[a].measure) > wasted(nodes[b].measure);
      });
      tried.resize(budget / 3);
    }
    if (tried.empty()) break;
    budget -= 3 * tried.size();
    children.clear();
    for (std::size_t i : tried) split(nodes[i].part, children);
    const std::vector<Measure> child_measured = measure(children);
    frontier.clear();
    for (std::size_t k = 0; k < tried.size(); ++k) {
      nodes[tried[k]].first_child = nodes.size();
      for (std::size_t c = 4 * k; c < 4 * k + 4; ++c) {
        frontier.push_back(nodes.size());
        nodes.push_back({children[c], child_measured[c], level + 1});
      }
    }
  }

  // Children come after their parent: one pass from the back settles every split.
  std::vector<double> cost(nodes.size());
  std::vector<bool> kept(nodes.size(), false);
  std::vector<std::size_t> leaves(nodes.size(), 1);  // the parts a node leaves, its split settled
  for (std::size_t i = nodes.size(); i-- > 0;) {
    const Node& n = nodes[i];
    const double whole = candidates_per_bound * n.measure.bound + refinement.part_cost;
    double parts = std::numeric_limits<double>::infinity();
    if (n.explored()) parts = cost[n.first_child] + cost[n.first_child + 1] + cost[n.first_child + 2] + cost[n.first_child + 3];
    kept[i] = parts < whole;
    cost[i] = std::min(whole, parts);
    if (kept[i])
      leaves[i] = leaves[n.first_child] + leaves[n.first_child + 1] + leaves[n.first_child + 2] + leaves[n.first_child + 3];
  }
  std::vector<MeasuredPart> parts;
  parts.reserve(std::accumulate(leaves.begin(), leaves.begin() + std::ptrdiff_t(roots.size()), std::size_t(0)));
  std::vector<std::size_t> stack;
  for (std::size_t root = 0; root < roots.size(); ++root) {
    stack.push_back(root);
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      if (!kept[i]) {
        parts.push_back({nodes[i].part, nodes[i].measure});
        continue;
      }
      levels = std::max(levels, nodes[i].level + 1);
      for (std::size_t c = 4; c-- > 0;) stack.push_back(nodes[i].first_child + c);
    }
  }
  return parts;
}

/// The parts, those of each triangle together in triangle order and in their order among
/// themselves: a counting sort, linear in the parts and the triangles.
std::vector<MeasuredPart> grouped_by_parent(const std::vector<MeasuredPart>& parts, std::size_t triangles) {
  std::vector<std::size_t> first(triangles + 1, 0);
  for (const MeasuredPart& p : parts) ++first[p.part.parent + 1];
  std::partial_sum(first.begin(), first.end(), first.begin());
  std::vector<MeasuredPart> grouped(parts.size());
  for (const MeasuredPart& p : parts) grouped[first[p.part.parent]++] = p;
  return grouped;
}

/// The parts of the acceptance rules: every part below min_acceptance is split, round by round,
/// and a small part's split is kept only where it pays (splits_that_pay). Those of a triangle
/// side by side, in triangle order.
template <class Measurer>
std::vector<MeasuredPart> split_by_acceptance(std::vector<Part> open, std::vector<Measure> measured,
                                              const Refinement& refinement, const Measurer& measure,
                                              std::uint32_t& levels) {
  const std::size_t triangles = open.size();
  std::vector<MeasuredPart> done;
  std::vector<Part> children, next;
  std::vector<Measure> child_measured, next_measured;
  std::uint64_t total = open.size();  // parts, counting every split kept so far
  for (std::uint32_t level = 0; level < refinement.max_levels && !open.empty(); ++level) {
    std::vector<std::size_t> tried;
    children.clear();
    for (std::size_t i = 0; i < open.size(); ++i)
      if (measured[i].acceptance < refinement.min_acceptance && measured[i].texels > refinement.min_texels) {
        tried.push_back(i);
        split(open[i], children);
      }
    if (tried.empty()) break;
    child_measured = measure(children);
    const bool look_ahead = level + 1 < refinement.max_levels;
    const std::vector<bool> pays =
        splits_that_pay(tried, measured, children, child_measured, refinement, look_ahead, measure);
    next.clear();
    next_measured.clear();
    std::vector<bool> kept(open.size(), false);
    for (std::size_t k = 0; k < tried.size(); ++k) {
      if (!pays[k] || total + 3 > refinement.max_triangles) continue;
      kept[tried[k]] = true;
      total += 3;
      next.insert(next.end(), children.begin() + std::ptrdiff_t(4 * k), children.begin() + std::ptrdiff_t(4 * k + 4));
      next_measured.insert(next_measured.end(), child_measured.begin() + std::ptrdiff_t(4 * k),
                           child_measured.begin() + std::ptrdiff_t(4 * k + 4));
    }
    for (std::size_t i = 0; i < open.size(); ++i)
      if (!kept[i]) done.push_back({open[i], measured[i]});
    if (!next.empty()) levels = level + 1;
    open.swap(next);
    measured.swap(next_measured);
  }
  for (std::size_t i = 0; i < open.size(); ++i) done.push_back({open[i], measured[i]});
  return grouped_by_parent(done, triangles);
}

}  // namespace

RefinedMesh::RefinedMesh(const MeshView& mesh, std::span<const DensityMapView> maps,
                         const Refinement& refinement) {
  // The mesh and maps checked, and the maps copied, once; each round counts only its parts.
  const std::vector<core::DensityMap> checked = core::checked_maps(mesh, maps);
  std::vector<Part> parts(mesh.indices.size() / 3);
  for (std::uint32_t t = 0; t < parts.size(); ++t) parts[t] = {t, {{0, 0}, {1, 0}, {0, 1}}};
  const auto measure = [&](const std::vector<Part>& tried) {
    std::vector<Measure> out(tried.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tried.size(), 256), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i < r.end(); ++i) {
        // The part's record as its backend will make it, from the same rounded corners.
        float positions[3][3], uvs[3][2];
        part_corners(mesh, tried[i], positions, uvs);
        const core::TriangleRecord record =
            core::make_triangle_record(positions, uvs, core::map_of_triangle(mesh, tried[i].parent, maps.size()));
        const core::TexelTriangle texels = core::make_texel_triangle(record, checked);
        const core::TriangleIntegral integral = core::integrate_triangle(record, texels, checked);
        const double bound = double(integral.max_density) * record.area;
        out[i] = {bound, bound > 0.0 ? integral.expected / bound : 1.0, texel_area(texels), integral.expected,
                  integral.max_density};
      }
    });
    return out;
  };
  if (refinement.min_acceptance > 0.0f && refinement.max_levels > 0) {
    const std::vector<Measure> measured = measure(parts);
    const std::vector<MeasuredPart> split =
        splits_by_cost(refinement) ? split_by_cost(parts, measured, refinement, measure, levels_)
                                   : split_by_acceptance(parts, measured, refinement, measure, levels_);
    expected_counts_.resize(levels_ > 0 ? split.size() : parts.size());
    max_density_.resize(expected_counts_.size());
    if (levels_ == 0) {  // nothing split: the parts are the triangles, as measured
      for (std::size_t i = 0; i < parts.size(); ++i) {
        expected_counts_[i] = measured[i].expected;
        max_density_[i] = measured[i].max_density;
      }
    } else {
      parts.resize(split.size());  // those of a triangle side by side: the sampler walks them in order
      for (std::size_t i = 0; i < split.size(); ++i) {
        parts[i] = split[i].part;
        expected_counts_[i] = split[i].measure.expected;
        max_density_[i] = split[i].measure.max_density;
      }
    }
  }
  parts_ = std::move(parts);
  if (levels_ > 0) build(mesh);  // with no split the caller's mesh is the refined one
}

void RefinedMesh::part_corners(const MeshView& mesh, const Part& part, float (&positions)[3][3], float (&uvs)[3][2]) {
  const std::uint32_t* v = &mesh.indices[3 * std::size_t(part.parent)];
  for (int corner = 0; corner < 3; ++corner) {
    const float* b = part.corners[corner];
    const double w[3] = {1.0 - double(b[0]) - double(b[1]), b[0], b[1]};
    for (int axis = 0; axis < 3; ++axis) {
      double x = 0.0;
      for (int k = 0; k < 3; ++k) x += w[k] * mesh.positions[3 * std::size_t(v[k]) + axis];
      positions[corner][axis] = float(x);
    }
    for (int axis = 0; axis < 2; ++axis) {
      double x = 0.0;
      for (int k = 0; k < 3; ++k) x += w[k] * mesh.uvs[2 * std::size_t(v[k]) + axis];
      uvs[corner][axis] = float(x);
    }
  }
}

void RefinedMesh::build(const MeshView& mesh) {
  const std::size_t n = parts_.size();
  positions_.resize(9 * n);
  uvs_.resize(6 * n);
  indices_.resize(3 * n);
  triangle_maps_.resize(mesh.triangle_maps.empty() ? 0 : n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      float positions[3][3], uvs[3][2];
      part_corners(mesh, parts_[i], positions, uvs);
      std::copy_n(&positions[0][0], 9, &positions_[9 * i]);
      std::copy_n(&uvs[0][0], 6, &uvs_[6 * i]);
      for (std::size_t k = 0; k < 3; ++k) indices_[3 * i + k] = std::uint32_t(3 * i + k);
      if (!triangle_maps_.empty()) triangle_maps_[i] = mesh.triangle_maps[parts_[i].parent];
    }
  });
}

}  // namespace lightsampler
