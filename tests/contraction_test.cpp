// The CPU backend reads texels at origin + b1 * edge1 + b2 * edge2 rounded operation by operation,
// as the GPU does (its shaders mark that arithmetic `precise`). A compiler that fused the
// multiply-add (-ffp-contract, on by default in some compilers and on targets with FMA) would
// move points that lie within an ulp of a texel edge into the next texel, and the backends'
// samples would differ. The library is built with -ffp-contract=off; this test finds points where
// a fused and an unfused evaluation fall in different texels, and checks that the library reads
// the unfused one.

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "lightsampler/sampler.h"
#include "sampler_fixtures.h"

using namespace lightsampler;

namespace {

struct Case {
  float origin, edge, b1;
  std::int64_t unfused_texel;
};

// Origins and edges on a 2^-10 grid (so that UVs on a 1024-texel map carry them exactly), and
// barycentrics whose product with the edge is inexact: where fma(b1, edge, origin) and
// origin + (b1 * edge) lie on either side of a texel edge.
std::vector<Case> cases_where_fusion_changes_the_texel(std::size_t wanted, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> origin_steps(0, 256 * 1024), edge_steps(1024, 256 * 1024);
  std::uniform_real_distribution<float> b(0.0f, 1.0f);
  std::vector<Case> found;
  while (found.size() < wanted) {
    const float origin = float(origin_steps(rng)) * 0x1p-10f, edge = float(edge_steps(rng)) * 0x1p-10f;
    const float b1 = b(rng);
    volatile float product = b1 * edge;  // rounded on its own
    const float unfused = origin + product;
    const float fused = std::fma(b1, edge, origin);
    if (std::floor(unfused) != std::floor(fused)) found.push_back({origin, edge, b1, std::int64_t(std::floor(unfused))});
  }
  return found;
}

TEST(Contraction, TexelLookupsRoundOperationByOperation) {
  constexpr std::uint32_t kWidth = 1024;
  const trs_test::Map map{std::vector<float>(kWidth, 1.0f), kWidth, 1};
  const DensityMapView view = map.view();
  for (const Case& c : cases_where_fusion_changes_the_texel(40, 1)) {
    // A triangle whose texel-space origin and first edge are exactly c.origin and c.edge along x.
    trs_test::Mesh mesh;
    const float p[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const float uv[3][2] = {{c.origin / kWidth, 0.25f}, {(c.origin + c.edge) / kWidth, 0.25f}, {c.origin / kWidth, 0.75f}};
    mesh.add_triangle(p, uv);
    const auto sampler = make_cpu_sampler(mesh.view(), {&view, 1});
    const std::optional<Texel> texel = sampler->maps().texel(0, c.b1, 0.0f);
    ASSERT_TRUE(texel.has_value());
    EXPECT_EQ(texel->x, std::uint32_t(c.unfused_texel))
        << "origin " << c.origin << " + " << c.b1 << " * edge " << c.edge << ": the library fused the multiply-add";
  }
}

}  // namespace
