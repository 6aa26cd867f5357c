#pragma once
// Samples and frames compared output by output, bit for bit.

#include <span>

#include <gtest/gtest.h>

#include "lightsampler/sampler.h"

namespace trs_test {

template <class T>
void expect_same_values(const lightsampler::Buffer<T>& got, const lightsampler::Buffer<T>& want, const char* what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t i = 0; i < want.size(); ++i) ASSERT_EQ(got[i], want[i]) << what << " " << i;
}

/// The same samples, in the same order, bit for bit.
inline void expect_same_samples(std::span<const lightsampler::Sample> got, std::span<const lightsampler::Sample> want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    ASSERT_EQ(got[i].triangle, want[i].triangle) << "sample " << i;
    ASSERT_EQ(got[i].b1, want[i].b1) << "sample " << i;
    ASSERT_EQ(got[i].b2, want[i].b2) << "sample " << i;
  }
}

/// The counts, the CDF and the samples of `got` are those of `want`.
inline void expect_same_frames(const lightsampler::Frame& got, const lightsampler::Frame& want) {
  EXPECT_EQ(got.expected_total, want.expected_total);
  expect_same_values(got.expected_counts, want.expected_counts, "N-bar_T of triangle");
  expect_same_values(got.max_density, want.max_density, "D_T^max of triangle");
  expect_same_values(got.counts, want.counts, "N_T of triangle");
  expect_same_values(got.cdf, want.cdf, "CDF entry");
  expect_same_samples(got.samples.span(), want.samples.span());
}

}  // namespace trs_test
