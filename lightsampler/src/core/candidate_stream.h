#pragma once
// The candidate stream: how realization turns random numbers into samples, on every backend
// (the GLSL twin is shaders/candidate_stream.glsl).
//
// A triangle's N_T slots are cut into segments of kSegmentSlots slots. Candidate j of segment s
// of triangle T is a pure function of (key, T, s, j); the segment's accepted candidates, in j
// order, fill its slots in order. A segment can thus be walked by one thread or by a whole
// subgroup, whose lanes draw consecutive candidates and assign slots by prefix counts, and the
// samples stay the same. Plain rejection sampling walks the same way over segments of the whole
// output (T = 0), its candidates spread over the mesh by area.
//
// The bound on tries: after max_tries rejected candidates in a row, either the last of them fills
// the slot anyway and is counted as exhausted, and the count of rejections starts again (the
// baselines, as the paper states them); or the walk stops there and the segment's remaining
// slots are drawn exactly (TRS: core/piece_draw.h), so that a sliver of density costs bounded
// time without bias.

#include <algorithm>
#include <bit>
#include <cstdint>
#include <span>

#include "lightsampler/random.h"
#include "shared.h"

namespace lightsampler::core {

inline constexpr std::uint64_t kSegmentSlots = gpu::kSegmentSlots;

/// Philox counter of candidate j of segment s of triangle T: (T, j, s) packed into 128 bits,
/// collision-free for s < 2^56 (2^64 slots) and j < 2^40 (kSegmentSlots times 2^32 tries).
inline PhiloxCounter candidate_counter(std::uint32_t triangle, std::uint64_t segment, std::uint64_t candidate) {
  return {triangle, std::uint32_t(candidate), std::uint32_t(segment),
          std::uint32_t(segment >> 32) ^ (std::uint32_t(candidate >> 32) << 24)};
}

/// A run of a triangle's slots that one walk fills: segment `segment` of processing index
/// `position`, whose first slot is sample `first` of the output.
struct SegmentRun {
  std::uint64_t position;
  std::uint64_t segment;
  std::uint64_t first;
  std::uint64_t slots;
};

/// Calls f(SegmentRun) for every segment that starts in samples [lo, hi), in output order.
/// `cdf` is the inclusive CDF over processing indices. Every segment starts in exactly one such
/// range, so disjoint ranges that cover the output split realization into independent work.
template <class F>
void for_each_segment(std::span<const std::uint64_t> cdf, std::uint64_t lo, std::uint64_t hi, F&& f) {
  // Triangle to triangle with slots by binary search, past those without (as the shader does).
  for (auto it = std::upper_bound(cdf.begin(), cdf.end(), lo); it != cdf.end();
       it = std::upper_bound(it + 1, cdf.end(), *it)) {
    const std::size_t p = std::size_t(it - cdf.begin());
    const std::uint64_t start = p == 0 ? 0 : cdf[p - 1], end = cdf[p];
    if (start >= hi) break;
    std::uint64_t s = start >= lo ? 0 : (lo - start + kSegmentSlots - 1) / kSegmentSlots;
    for (std::uint64_t first = start + s * kSegmentSlots; first < std::min(hi, end); first += kSegmentSlots, ++s)
      f(SegmentRun{p, s, first, std::min(kSegmentSlots, end - first)});
  }
}

/// What a walk does at the max_tries-th rejection in a row: fill the slot with that candidate
/// (`stop` false), or stop, leaving the rest of the segment to exact draws.
struct TryLimit {
  std::uint32_t max_tries;
  bool stop = false;
};

/// TRS's bounds on tries: max_tries a slot, as for every method, and exact_after, the rejections
/// in a row after which the rest of the segment is drawn exactly (0: never, the paper's rule).
struct TrsTries {
  std::uint32_t max_tries;
  std::uint32_t exact_after;

  TryLimit rejection() const {
    return exact_after == 0 ? TryLimit{max_tries, false} : TryLimit{std::min(max_tries, exact_after), true};
  }
};

/// The fill rule of one segment, fed candidates in j order: a candidate fills the next slot when
/// it is accepted, or when it is the max_tries-th rejection in a row and the limit does not stop.
class SegmentFill {
 public:
  SegmentFill(std::uint64_t slots, TryLimit limit) : slots_(slots), limit_(limit) {}

  /// Full, or stopped by the limit.
  bool done() const { return filled_ == slots_ || stopped_; }
  bool stopped() const { return stopped_; }
  std::uint64_t filled() const { return filled_; }
  std::uint64_t tries() const { return tries_; }
  std::uint64_t exhausted() const { return exhausted_; }

  /// Takes the next candidate; true when it fills slot filled() - 1.
  bool take(bool accepted) {
    ++tries_;
    rejections_ = accepted ? 0 : rejections_ + 1;
    if (!accepted && rejections_ < limit_.max_tries) return false;
    if (!accepted && limit_.stop) {
      stopped_ = true;
      return false;
    }
    if (!accepted) {
      ++exhausted_;
      rejections_ = 0;
    }
    ++filled_;
    return true;
  }

  /// Whether the next `lanes` candidates can neither reach the limit nor fill the segment before
  /// the last of them: then their accepted ones fill the next slots in lane order (take_open).
  bool open(int lanes) const {
    return slots_ - filled_ >= std::uint64_t(lanes) && limit_.max_tries - rejections_ > std::uint32_t(lanes);
  }

  /// take(accepted, lanes, ...) where open(lanes): the caller has put accepted lane l in slot
  /// filled() plus the accepted lanes before l.
  void take_open(std::uint32_t accepted, int lanes) {
    filled_ += std::uint64_t(std::popcount(accepted));
    count_rejections(accepted, lanes);
  }

  /// Takes the next `lanes` candidates (at most 32), bit l of `accepted` for candidate l, as
  /// take() on each in turn, until the segment is full; calls fill_slot(l, slot) for each one
  /// that fills a slot. Without a possible limit in these lanes, only the accepted bits are
  /// visited.
  template <class F>
  void take(std::uint32_t accepted, int lanes, F&& fill_slot) {
    if (limit_.max_tries - rejections_ <= std::uint32_t(lanes)) {
      for (int l = 0; l < lanes && !done(); ++l)
        if (take(((accepted >> l) & 1u) != 0)) fill_slot(l, filled_ - 1);
      return;
    }
    for (std::uint32_t left = accepted; left != 0; left &= left - 1) {
      const int l = std::countr_zero(left);
      fill_slot(l, filled_++);
      if (done()) {
        tries_ += std::uint64_t(l) + 1;
        return;
      }
    }
    count_rejections(accepted, lanes);
  }

 private:
  void count_rejections(std::uint32_t accepted, int lanes) {
    tries_ += std::uint64_t(lanes);
    rejections_ = accepted == 0 ? rejections_ + std::uint32_t(lanes) : std::uint32_t(std::countl_zero(accepted << (32 - lanes)));
  }

  std::uint64_t slots_;
  TryLimit limit_;
  std::uint64_t filled_ = 0, tries_ = 0, exhausted_ = 0;
  std::uint32_t rejections_ = 0;
  bool stopped_ = false;
};

}  // namespace lightsampler::core
