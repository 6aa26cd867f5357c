#pragma once
// The shader-shared layouts (shaders/shared.h) as C++ sees them, checked against std430.

#include <cstddef>

#include "shared.h"

namespace lightsampler::gpu {

static_assert(sizeof(GpuTriangle) == 32 && offsetof(GpuTriangle, area) == 24 && offsetof(GpuTriangle, map) == 28);
static_assert(sizeof(GpuMap) == 32 && offsetof(GpuMap, scale) == 16);
static_assert(sizeof(GpuSample) == 12);
static_assert(sizeof(GpuTotals) == 48 && offsetof(GpuTotals, sample_count) == 8 &&
              offsetof(GpuTotals, scan_counter) == 16 && offsetof(GpuTotals, cells) == 40);
static_assert(sizeof(CountPush) == 72 && offsetof(CountPush, triangle_count) == 64);
static_assert(sizeof(RasterPush) == 72 && offsetof(RasterPush, origin_x) == 48 && offsetof(RasterPush, map) == 64);
static_assert(sizeof(RoundPush) == 48 && offsetof(RoundPush, target) == 24 && offsetof(RoundPush, key0) == 32);
static_assert(sizeof(ScanPush) == 56 && offsetof(ScanPush, sum_bits) == 48);
static_assert(sizeof(RealizePush) == 88 && offsetof(RealizePush, first) == 64 && offsetof(RealizePush, key0) == 72);
static_assert(sizeof(RejectionPush) == 88 && offsetof(RejectionPush, first) == 56 &&
              offsetof(RejectionPush, key0) == 64 && offsetof(RejectionPush, map) == 84);
// Vulkan guarantees 128 bytes of push constants.
static_assert(sizeof(RealizePush) <= 128 && sizeof(RejectionPush) <= 128);

}  // namespace lightsampler::gpu
