// The candidate stream (core/candidate_stream.h): its segments cover the output once, its
// batched fill rule is the one-at-a-time rule, its vector candidates are the scalar ones, and the
// CPU passes give exactly the samples that the stream's definition, walked one candidate at a
// time, gives.

#include <random>

#include <gtest/gtest.h>

#include "core/area_pick.h"
#include "core/candidate_stream.h"
#include "core/piece_draw.h"
#include "cpu/candidates.h"
#include "cpu/passes.h"
#include "lightsampler/triangle_map.h"
#include "same_frame.h"
#include "sampler_fixtures.h"

using namespace lightsampler;
using trs_test::Map;
using trs_test::Mesh;

namespace {

/// Candidate j of segment s of triangle T, drawn as the definition says, one at a time.
struct ScalarCandidate {
  Barycentrics b;
  float accept;
  double pick;
};
ScalarCandidate scalar_candidate(std::uint32_t tri, std::uint64_t segment, std::uint64_t j, PhiloxKey key) {
  const PhiloxCounter u = philox4x32(core::candidate_counter(tri, segment, j), key);
  return {triangle_map(uniform_float(u[0]), uniform_float(u[1])), uniform_float(u[2]), uniform_double(u[3])};
}

/// Realization as the stream's definition states it: each triangle's segments in turn, each
/// walked one candidate at a time, the rest of a stopped segment drawn exactly.
cpu::RealizationResult reference_realize(std::span<const core::TexelTriangle> tris, const core::DensityMap& map,
                                         std::span<const float> max_density, std::span<const std::uint64_t> cdf,
                                         std::span<const std::uint32_t> inverse, cpu::RealizationKeys keys,
                                         core::TrsTries tries, std::vector<Sample>& out) {
  cpu::RealizationResult r;
  out.assign(cdf.empty() ? 0 : cdf.back(), Sample{});
  for (std::size_t p = 0; p < cdf.size(); ++p) {
    const std::uint32_t tri = inverse[p];
    const std::uint64_t start = p == 0 ? 0 : cdf[p - 1];
    for (std::uint64_t s = 0; start + s * core::kSegmentSlots < cdf[p]; ++s) {
      const std::uint64_t first = start + s * core::kSegmentSlots, slots = std::min(core::kSegmentSlots, cdf[p] - first);
      core::SegmentFill fill(slots, tries.rejection());
      for (std::uint64_t j = 0; !fill.done(); ++j) {
        const ScalarCandidate c = scalar_candidate(tri, s, j, keys.candidates);
        const auto [x, y] = core::texel_space_point(tris[tri], c.b.b1, c.b.b2);
        if (fill.take(c.accept * max_density[tri] < core::point_density(map, x, y)))
          out[first + fill.filled() - 1] = {tri, c.b.b1, c.b.b2};
      }
      r.candidates += fill.tries();
      r.exhausted += fill.exhausted();
      core::PieceStrata strata;
      strata.build(tris[tri], {&map, 1});
      for (std::uint64_t slot = fill.filled(); slot < slots; ++slot) {
        if (strata.pieces.empty()) {  // no piece to draw from: the slot gives up
          out[first + slot] = {tri, 1.0f / 3, 1.0f / 3};
          ++r.exhausted;
          continue;
        }
        const core::PieceDraw d = core::draw_from_pieces(strata, tri, tris[tri], s * core::kSegmentSlots + slot,
                                                         keys.exact, tries.max_tries);
        out[first + slot] = d.sample;
        r.candidates += d.attempts;
        r.exhausted += d.landed ? 0 : 1;
        ++r.exact;
      }
    }
  }
  return r;
}

std::vector<core::TexelTriangle> texel_triangles(const std::vector<core::TriangleRecord>& records,
                                                 const core::DensityMap& map) {
  std::vector<core::TexelTriangle> out;
  for (const core::TriangleRecord& r : records) out.push_back(core::make_texel_triangle(r, {&map, 1}));
  return out;
}

}  // namespace

TEST(CandidateStream, SegmentsStartingInDisjointRangesCoverEverySlotOnce) {
  // Counts with zeros, ones, and several segments' worth; ranges of every size cutting them.
  std::mt19937_64 rng(3);
  std::vector<std::uint64_t> counts(300), cdf;
  std::uint64_t total = 0;
  for (std::uint64_t& c : counts) {
    const int kind = int(rng() % 4);
    c = kind == 0 ? 0 : kind == 1 ? 1 + rng() % 3 : kind == 2 ? rng() % 300 : rng() % 2000;
    cdf.push_back(total += c);
  }
  for (std::uint64_t range : {1ull, 7ull, 256ull, 1000ull, 1ull << 20}) {
    std::vector<int> covered(total, 0);
    for (std::uint64_t lo = 0; lo < total; lo += range)
      core::for_each_segment(cdf, lo, std::min(lo + range, total), [&](const core::SegmentRun& run) {
        const std::uint64_t start = run.position == 0 ? 0 : cdf[run.position - 1];
        EXPECT_EQ(run.first, start + run.segment * core::kSegmentSlots);
        EXPECT_GE(run.first, lo);
        EXPECT_LT(run.first, lo + range);
        EXPECT_LE(run.first + run.slots, cdf[run.position]);
        for (std::uint64_t i = run.first; i < run.first + run.slots; ++i) ++covered[i];
      });
    for (std::uint64_t i = 0; i < total; ++i) ASSERT_EQ(covered[i], 1) << "slot " << i << ", range " << range;
  }
}

TEST(CandidateStream, BatchedFillIsTheOneAtATimeRule) {
  // Three fills of the same candidates: one at a time; a batch at a time; and a batch at a time
  // through take_open wherever the batch is open, as the CPU walk fills without branches.
  std::mt19937_64 rng(5);
  for (const bool stop : {false, true})
    for (std::uint32_t max_tries : {1u, 2u, 3u, 5u, 16u, 17u, 40u, 1u << 28})
      for (double acceptance : {0.0, 0.02, 0.3, 0.9, 1.0})
        for (std::uint64_t slots : {1ull, 5ull, 16ull, 40ull, 256ull}) {
          if (acceptance == 0.0 && max_tries > 40) continue;  // it would run 2^28 tries a slot
          const core::TryLimit limit{max_tries, stop};
          core::SegmentFill one(slots, limit), batched(slots, limit), open(slots, limit);
          std::vector<int> one_lanes, batched_lanes, open_lanes;
          int opened = 0;
          for (int batch = 0; !batched.done(); ++batch) {
            std::uint32_t mask = 0;
            for (int l = 0; l < cpu::kLanes; ++l)
              mask |= std::uint32_t(std::bernoulli_distribution(acceptance)(rng)) << l;
            for (int l = 0; l < cpu::kLanes && !one.done(); ++l)
              if (one.take(((mask >> l) & 1u) != 0)) one_lanes.push_back(batch * cpu::kLanes + l);
            batched.take(mask, cpu::kLanes, [&](int l, std::uint64_t slot) {
              EXPECT_EQ(slot, batched_lanes.size());
              batched_lanes.push_back(batch * cpu::kLanes + l);
            });
            if (open.done()) continue;
            if (open.open(cpu::kLanes)) {
              ++opened;
              for (int l = 0; l < cpu::kLanes; ++l)
                if ((mask >> l) & 1u) open_lanes.push_back(batch * cpu::kLanes + l);
              open.take_open(mask, cpu::kLanes);
            } else {
              open.take(mask, cpu::kLanes, [&](int l, std::uint64_t) { open_lanes.push_back(batch * cpu::kLanes + l); });
            }
          }
          SCOPED_TRACE(testing::Message() << "max_tries " << max_tries << ", acceptance " << acceptance
                                          << ", slots " << slots << (stop ? ", stops" : ""));
          EXPECT_TRUE(one.done());
          EXPECT_TRUE(open.done());
          EXPECT_EQ(batched_lanes, one_lanes);
          EXPECT_EQ(open_lanes, one_lanes);
          EXPECT_EQ(batched.tries(), one.tries());
          EXPECT_EQ(open.tries(), one.tries());
          EXPECT_EQ(batched.exhausted(), one.exhausted());
          EXPECT_EQ(open.exhausted(), one.exhausted());
          EXPECT_EQ(batched.stopped(), one.stopped());
          EXPECT_EQ(open.stopped(), one.stopped());
          // Large segments with a distant limit take most batches open.
          if (slots == 256 && max_tries > 40 && acceptance > 0.2) EXPECT_GT(opened, 0);
        }
}

TEST(CandidateStream, VectorCandidatesAreTheScalarOnes) {
  // Segments and candidate indices past 2^32 reach the counter's high words.
  const PhiloxKey key = stream_key(11, Stream::realization);
  for (std::uint64_t segment : {0ull, 1ull, 77ull, (1ull << 32) + 5, (1ull << 55) + 3})
    for (std::uint64_t first : {0ull, 16ull, (1ull << 32) - 8, (1ull << 39) + 32}) {
      cpu::CandidateBatch batch;
      cpu::draw_candidates(42, segment, first, key, batch);
      for (int l = 0; l < cpu::kLanes; ++l) {
        const ScalarCandidate c = scalar_candidate(42, segment, first + std::uint64_t(l), key);
        ASSERT_EQ(batch.b1[l], c.b.b1) << segment << " " << first << " " << l;
        ASSERT_EQ(batch.b2[l], c.b.b2);
        ASSERT_EQ(batch.accept[l], c.accept);
        ASSERT_EQ(batch.pick[l], c.pick);
      }
    }
}

TEST(CandidateStream, VectorAcceptanceIsTheScalarTest) {
  // Triangles inside the map, across its edges under each addressing, at negative coordinates,
  // and so far out (UVs near 2^24) that the lanes leave 32-bit range and take the 64-bit path.
  const PhiloxKey key = stream_key(12, Stream::realization);
  std::mt19937_64 rng(13);
  for (const Addressing addressing : {Addressing::wrap, Addressing::clamp, Addressing::mirror}) {
    Map m = trs_test::random_map(24, 20, 0.5, 14);
    m.addressing = addressing;
    m.scale = 0.7f;
    const core::DensityMap map{m.texels, m.width, m.height, m.addressing, m.scale};
    const core::TexelTriangle triangles[] = {
        {{2.5f, 3.25f}, {12.0f, 1.0f}, {3.0f, 9.5f}, 0},
        {{-6.0f, 15.0f}, {40.0f, 2.0f}, {5.0f, 14.0f}, 0},
        {{-30.5f, -41.0f}, {7.0f, -3.0f}, {-2.0f, 9.0f}, 0},
        {{0.5f, 0.5f}, {0.0f, 0.0f}, {0.0f, 0.0f}, 0},
        {{3.0e8f, -2.0e8f}, {1.0e3f, 0.0f}, {0.0f, 1.0e3f}, 0},
        {{1.07e9f, 5.0f}, {2.0e7f, 0.0f}, {0.0f, 3.0f}, 0},
    };
    for (const core::TexelTriangle& t : triangles)
      for (std::uint64_t first : {0ull, 16ull, 4096ull}) {
        cpu::CandidateBatch batch;
        cpu::draw_candidates(7, 3, first, key, batch);
        const float bound = std::uniform_real_distribution<float>(0.1f, 1.0f)(rng);
        const std::uint32_t got = cpu::accepted_on_triangle(t, map, bound, batch);
        for (int l = 0; l < cpu::kLanes; ++l) {
          const bool want =
              batch.accept[l] * bound < core::texel_triangle_density(t, {&map, 1}, batch.b1[l], batch.b2[l]);
          ASSERT_EQ(((got >> l) & 1u) != 0, want) << "origin " << t.origin[0] << ", lane " << l;
        }
      }
  }
}

TEST(CandidateStream, CountersOfDifferentCandidatesDiffer) {
  EXPECT_NE(core::candidate_counter(1, 0, 1ull << 32), core::candidate_counter(1, 1ull << 32, 0));
  EXPECT_NE(core::candidate_counter(1, 1ull << 32, 0), core::candidate_counter(1, 0, 0));
  EXPECT_NE(core::candidate_counter(1, 0, 1ull << 32), core::candidate_counter(1, 0, 0));
}

TEST(CandidateStream, RealizationIsTheStreamWalkedOneCandidateAtATime) {
  // A sparse map, so that acceptance is low and small max_tries exhaust slots; triangles of many
  // sizes, so that counts span zero to several segments.
  const Mesh mesh = trs_test::random_triangles(60, 0.0f, 1.0f, 31);
  const Map m = trs_test::random_map(24, 24, 0.7, 32);
  const DensityMapView view = m.view();
  Frame frame;
  make_cpu_sampler(mesh.view(), {&view, 1})->generate({.seed = 4, .target_count = 30000}, frame);
  const core::DensityMap map{m.texels, m.width, m.height, m.addressing, m.scale};
  const auto tris = texel_triangles(core::make_triangle_records(mesh.view(), 1), map);
  const cpu::RealizationKeys keys{stream_key(4, Stream::realization), stream_key(4, Stream::exact)};
  for (const core::TrsTries tries : {core::TrsTries{1, 0}, core::TrsTries{3, 0}, core::TrsTries{20, 0},
                                     core::TrsTries{1u << 28, 0}, core::TrsTries{1u << 28, 1},
                                     core::TrsTries{1u << 28, 5}, core::TrsTries{3, 40}, core::TrsTries{1u << 28, 256}}) {
    SCOPED_TRACE(testing::Message() << "max_tries " << tries.max_tries << ", exact_after " << tries.exact_after);
    Buffer<Sample> got;
    std::vector<Sample> want;
    const cpu::RealizationResult a = cpu::realize(tris, {&map, 1}, frame.max_density.span(), frame.cdf.span(),
                                                  frame.inverse_permutation.span(), keys, tries, got);
    const cpu::RealizationResult b = reference_realize(tris, map, frame.max_density.span(), frame.cdf.span(),
                                                       frame.inverse_permutation.span(), keys, tries, want);
    trs_test::expect_same_samples(got.span(), want);
    EXPECT_EQ(a.candidates, b.candidates);
    EXPECT_EQ(a.exhausted, b.exhausted);
    EXPECT_EQ(a.exact, b.exact);
    const core::TryLimit limit = tries.rejection();
    if (limit.max_tries < 20 && !limit.stop) EXPECT_GT(a.exhausted, 0u) << "the rule on tries is exercised";
    if (limit.max_tries < 20 && limit.stop) EXPECT_GT(a.exact, 0u) << "exact draws are exercised";
    if (tries.exact_after == 256) EXPECT_EQ(a.exact, 0u) << "an ordinary map never needs them";
  }
}

TEST(CandidateStream, RejectionSamplingIsTheStreamOverTheOutput) {
  const Mesh mesh = trs_test::random_triangles(40, 0.0f, 1.0f, 33);
  const Map m = trs_test::random_map(16, 16, 0.5, 34);
  const core::DensityMap map{m.texels, m.width, m.height, m.addressing, m.scale};
  const auto records = core::make_triangle_records(mesh.view(), 1);
  const auto tris = texel_triangles(records, map);
  Buffer<double> area_cdf;
  std::vector<std::uint32_t> area_guide;
  const float bound = cpu::rejection_distribution(records, {&map, 1}, area_cdf, area_guide);
  const PhiloxKey key = stream_key(6, Stream::rejection);
  const std::uint64_t n = 3000;
  Buffer<Sample> got;
  const cpu::RealizationResult a = cpu::rejection_sample(tris, {&map, 1}, area_cdf.span(), area_guide, bound, n, key, 4, got);
  // The definition: segment s holds samples [256 s, 256 s + 256); a candidate picks its
  // triangle by area with its fourth word.
  std::vector<Sample> want(n);
  std::uint64_t candidates = 0, exhausted = 0;
  for (std::uint64_t s = 0; s * core::kSegmentSlots < n; ++s) {
    core::SegmentFill fill(std::min(core::kSegmentSlots, n - s * core::kSegmentSlots), {4});
    for (std::uint64_t j = 0; !fill.done(); ++j) {
      const ScalarCandidate c = scalar_candidate(0, s, j, key);
      const auto tri = std::uint32_t(std::upper_bound(area_cdf.begin(), area_cdf.end(), c.pick * area_cdf[39]) -
                                     area_cdf.begin());
      const float d = core::texel_triangle_density(tris[tri], {&map, 1}, c.b.b1, c.b.b2);
      if (fill.take(c.accept * bound < d)) want[s * core::kSegmentSlots + fill.filled() - 1] = {tri, c.b.b1, c.b.b2};
    }
    candidates += fill.tries();
    exhausted += fill.exhausted();
  }
  trs_test::expect_same_samples(got.span(), want);
  EXPECT_EQ(a.candidates, candidates);
  EXPECT_EQ(a.exhausted, exhausted);
  EXPECT_GT(exhausted, 0u);
}

TEST(CandidateStream, AreaPickThroughCutpointsIsTheBinarySearch) {
  // Zero areas (flat runs of the CDF), areas over twelve orders of magnitude, and u at the
  // buckets' edges, at 0 and just below 1.
  std::mt19937_64 rng(9);
  for (std::size_t n : {1ul, 2ul, 7ul, 1000ul}) {
    std::vector<double> cdf;
    double sum = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const int kind = int(rng() % 4);
      sum += kind == 0 ? 0.0 : kind == 1 ? 1e-6 * double(rng() % 100) : kind == 2 ? 1e6 : double(rng() % 10);
      cdf.push_back(sum);
    }
    if (sum == 0.0) cdf.back() = sum = 1.0;
    const std::vector<std::uint32_t> guide = core::area_guide(cdf);
    std::vector<double> us = {0.0, 1.0 - 0x1p-32};
    for (std::size_t k = 0; k <= n; ++k)
      for (double d : {-0x1p-40, 0.0, 0x1p-40}) us.push_back(std::clamp(double(k) / double(n) + d, 0.0, 1.0 - 0x1p-32));
    for (int i = 0; i < 2000; ++i) us.push_back(uniform_double(std::uint32_t(rng())));
    for (double u : us) {
      const auto want = std::uint32_t(std::min<std::size_t>(
          std::upper_bound(cdf.begin(), cdf.end(), u * cdf.back()) - cdf.begin(), n - 1));
      ASSERT_EQ(core::pick_by_area(cdf, guide, u), want) << "n " << n << ", u " << u;
    }
  }
}
