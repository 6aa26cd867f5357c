#pragma once
// Two frames compared output by output, bit for bit.

#include <gtest/gtest.h>

#include "lightsampler/sampler.h"

namespace trs_test {

template <class T>
void expect_same_values(const lightsampler::Buffer<T>& got, const lightsampler::Buffer<T>& want, const char* what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t i = 0; i < want.size(); ++i) ASSERT_EQ(got[i], want[i]) << what << " " << i;
}

/// The counts, the CDF and the samples of `got` are those of `want`.
inline void expect_same_frames(const lightsampler::Frame& got, const lightsampler::Frame& want) {
  EXPECT_EQ(got.expected_total, want.expected_total);
  expect_same_values(got.expected_counts, want.expected_counts, "N-bar_T of triangle");
  expect_same_values(got.max_density, want.max_density, "D_T^max of triangle");
  expect_same_values(got.counts, want.counts, "N_T of triangle");
  expect_same_values(got.cdf, want.cdf, "CDF entry");
  ASSERT_EQ(got.samples.size(), want.samples.size());
  for (std::size_t i = 0; i < want.samples.size(); ++i) {
    const lightsampler::Sample &a = got.samples[i], &b = want.samples[i];
    ASSERT_TRUE(a.triangle == b.triangle && a.b1 == b.b1 && a.b2 == b.b2) << "sample " << i;
  }
}

}  // namespace trs_test
