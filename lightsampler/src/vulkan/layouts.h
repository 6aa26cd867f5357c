#pragma once
// The shader-shared layouts (shaders/shared.h) as C++ sees them, checked against std430.

#include <cstddef>

#include "lightsampler/sample.h"
#include "shared.h"

namespace lightsampler::gpu {

static_assert(sizeof(TexelTriangle) == 32 && offsetof(TexelTriangle, area) == 24 && offsetof(TexelTriangle, map) == 28);
static_assert(sizeof(DensityMap) == 32 && offsetof(DensityMap, scale) == 16);
static_assert(sizeof(Sample) == kSampleBytes && sizeof(lightsampler::Sample) == kSampleBytes);
static_assert(sizeof(FrameTotals) == 64 && offsetof(FrameTotals, sample_count) == 8 &&
              offsetof(FrameTotals, scan_counter) == 16 && offsetof(FrameTotals, cells) == 40 &&
              offsetof(FrameTotals, realized) == 48 && offsetof(FrameTotals, exact) == 56);
static_assert(sizeof(WritePush) == 16);
static_assert(sizeof(PlanPush) == 56 && offsetof(PlanPush, target) == 24 && offsetof(PlanPush, max_workgroups) == 40 &&
              offsetof(PlanPush, key1) == 52);
static_assert(sizeof(CountingPush) == 96 && offsetof(CountingPush, stale_maps) == 64 &&
              offsetof(CountingPush, triangle_count) == 72 && offsetof(CountingPush, piece_cdf) == 88);
static_assert(sizeof(RasterPush) == 72 && offsetof(RasterPush, origin_x) == 48 && offsetof(RasterPush, map) == 64);
static_assert(sizeof(RoundingPush) == 48 && offsetof(RoundingPush, target) == 24 && offsetof(RoundingPush, key0) == 32);
static_assert(sizeof(ScanPush) == 56 && offsetof(ScanPush, sum_bits) == 48 && offsetof(ScanPush, polls) == 52);
static_assert(sizeof(RealizationPush) == 128 && offsetof(RealizationPush, stopped) == 120 && offsetof(RealizationPush, piece_cdf) == 40 &&
              offsetof(RealizationPush, guide) == 80 && offsetof(RealizationPush, key0) == 88 &&
              offsetof(RealizationPush, max_tries) == 100 && offsetof(RealizationPush, exact_after) == 112);
static_assert(sizeof(RejectionPush) == 80 && offsetof(RejectionPush, key0) == 56 && offsetof(RejectionPush, map) == 76);
static_assert(sizeof(FrsPush) == 96 && offsetof(FrsPush, key0) == 80 && offsetof(FrsPush, max_tries) == 92);
// Vulkan guarantees 128 bytes of push constants.
static_assert(sizeof(CountingPush) <= 128 && sizeof(RealizationPush) <= 128 && sizeof(RejectionPush) <= 128 &&
              sizeof(FrsPush) <= 128);

}  // namespace lightsampler::gpu
