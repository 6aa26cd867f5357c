// Layouts shared by the GLSL passes and the C++ host code: buffer records, push constants and
// workgroup sizes. Scalars and 64-bit device addresses only, padded by hand, so that std430 and
// C++ agree; the host static_asserts sizes and offsets (lightsampler/src/vulkan/layouts.h).
#ifndef LIGHTSAMPLER_SHADERS_SHARED_H
#define LIGHTSAMPLER_SHADERS_SHARED_H

#ifdef __cplusplus
#include <cstdint>
namespace lightsampler::gpu {
using uint = std::uint32_t;
using uint64_t = std::uint64_t;
#define LS_CONST inline constexpr
#else
#define LS_CONST const
#endif

LS_CONST uint kWorkgroupSize = 256;
// Workgroups launched by grid-stride passes: each thread loops over its share of the work, so no
// dispatch exceeds the 65535-workgroup limit whatever the element count.
LS_CONST uint kMaxWorkgroups = 8192;
LS_CONST uint kNoMap = 0xffffffffu;
// lightsampler::Overlap, in its order: the counting passes' specialization constant kOverlap.
LS_CONST uint kOverlapClosedForm = 0u;
LS_CONST uint kOverlapClipping = 1u;
LS_CONST uint kOverlapSdf = 2u;
// Slots of a segment of the candidate stream (lightsampler/src/core/candidate_stream.h): part
// of the definition of the samples, the same on every backend.
LS_CONST uint kSegmentSlots = 256;
// Candidate cells per invocation of the compute counting path.
LS_CONST uint kCellsPerRun = 16;
LS_CONST uint kAddressWrap = 0u;
LS_CONST uint kAddressClamp = 1u;
LS_CONST uint kAddressMirror = 2u;

/// A triangle in its map's texel space, the twin of core::TexelTriangle: a point with
/// barycentrics (b1, b2) is at origin + b1 edge1 + b2 edge2; zero edges: UV-degenerate.
struct TexelTriangle {
  float origin_x, origin_y;
  float edge1_x, edge1_y;
  float edge2_x, edge2_y;
  float area;  // world units squared
  uint map;    // kNoMap: zero density
};

struct DensityMap {
  uint offset;  // first texel in the texel buffer
  uint width;
  uint height;
  uint addressing;
  float scale;
  uint pad0, pad1, pad2;
};

/// The twin of lightsampler::Sample, kSampleBytes apart in the sample buffer.
struct Sample {
  uint triangle;
  float b1;
  float b2;
};
LS_CONST uint kSampleBytes = 12;

/// Frame totals, written by the passes, read back by the host.
struct FrameTotals {
  float expected_total;  // N-bar (float atomic sum of N-bar_T)
  uint max_density_bits; // rejection sampling's global bound, as float bits
  uint64_t sample_count; // N
  uint64_t scan_counter; // Algorithm 3's packed (processing index, partial sum)
  uint64_t candidates;
  uint64_t exhausted;
  uint64_t cells;        // candidate cells of the compute counting path
  uint64_t realized;     // samples realization writes: N, or 0 when N exceeds the sample buffer
  uint64_t exact;        // TRS: slots drawn exactly after rejection stopped
};

/// Addresses of the resident and per-frame buffers; every pass takes the ones it needs.
struct CountingPush {
  uint64_t triangles;    // TexelTriangle[T]
  uint64_t maps;         // DensityMap[]
  uint64_t texels;       // float[]
  uint64_t expected;     // float[T], N-bar_T
  uint64_t max_density;  // uint[T], D_T^max as float bits
  uint64_t footprint;    // uint64[T], lattice cells of each triangle's bounding box
  uint64_t cell_cdf;     // uint64[T], inclusive prefix sum of the footprints
  uint64_t totals;       // FrameTotals
  uint64_t stale_maps;   // uint[maps]: non-zero for a map whose triangles to count; 0 (no buffer): all
  uint triangle_count;
  uint small_cells;      // setup pass: count triangles of at most this many cells itself (0: none)
  uint64_t piece_offsets;  // naive stratification: uint64[T + 1], the first cell of each
                           // triangle's lattice box (core::piece_cells) in piece_cdf
  uint64_t piece_cdf;      // double[cells]: per triangle, density times area of its texel pieces
                           // summed row by row up to each cell of its box
};

struct RasterPush {
  uint64_t triangles;
  uint64_t maps;
  uint64_t texels;
  uint64_t expected;
  uint64_t max_density;
  uint64_t footprint;        // zero: the setup pass already counted the triangle
  float origin_x, origin_y;  // texel-space coordinate of the viewport's corner
  float width, height;       // viewport size in texels
  uint map;                  // the map whose triangles this draw rasterizes
  float dilation;            // geometry-shader path: margin beyond half a texel, in texels, for
                             // vertex snapping and float rounding
};

struct RoundingPush {
  uint64_t expected;
  uint64_t counts;    // uint64[T], N_T
  uint64_t totals;
  double target;      // N_target; negative: none (the count emerges from the maps)
  uint key0, key1;    // Philox key of the rounding stream
  uint triangle_count;
  uint pad0;
};

struct ScanPush {
  uint64_t source;    // uint64[n]
  uint64_t result;    // uint64[n]: inclusive scan (ordered) or the CDF (unordered)
  uint64_t block_sums;  // ordered: the blocks' sums; lookback: a tile counter, then tile states
  uint64_t inverse;   // uint[n] (unordered scan)
  uint64_t totals;
  uint64_t count;     // n
  uint sum_bits;      // unordered: bits of the packed word holding the partial sum
  uint polls;         // lookback: reads of a predecessor's state before reducing its tile itself
};

// The lookback scan's tiles: kLookbackItems consecutive elements per invocation.
LS_CONST uint kLookbackItems = 4;
LS_CONST uint kLookbackTile = kWorkgroupSize * kLookbackItems;
// Reads of a predecessor tile's state before the waiting workgroup reduces that tile itself.
LS_CONST uint kLookbackPolls = 64;

struct RealizationPush {
  uint64_t triangles;
  uint64_t maps;
  uint64_t texels;
  uint64_t max_density;
  uint64_t piece_offsets;  // naive stratification: as in CountingPush
  uint64_t piece_cdf;
  uint64_t cdf;
  uint64_t inverse;
  uint64_t samples;
  uint64_t totals;
  uint64_t guide;     // uint[T + 1]: the inverse CDF (inverse_cdf.glsl); 0: none, a plain search
  uint key0, key1;
  uint triangle_count;
  uint max_tries;
  uint exact_key0, exact_key1;  // TRS: Philox key of the exact draws
  uint exact_after;   // TRS: rejections in a row that stop a segment's walk (0: never)
  uint exact_cells;   // TRS: the most lattice cells of a triangle drawn exactly (device limit)
  uint64_t stopped;   // TRS: the segments whose walk stopped (StoppedSegments); 0: none listed
};

// The segments whose rejection walk stopped, which the exact pass then draws: a header of eight
// uints (the count; the capacity in records; at kStoppedDispatch the exact pass's indirect
// workgroup counts x, y, z, x raised as records arrive, so that an empty list dispatches
// nothing; three unused) and records of four uints (processing index, slots filled, segment
// number's low and high words). The capacity holds every segment of a frame, so no record is
// ever dropped.
LS_CONST uint kStoppedHeaderUints = 8;
LS_CONST uint kStoppedDispatch = 2;
LS_CONST uint kStoppedRecordUints = 4;
// The exact pass's most workgroups, whose subgroups stride over the list: enough to keep a
// large GPU busy when slivers stop many segments.
LS_CONST uint kExactWorkgroups = 256;

LS_CONST uint kPlanTrs = 0u;        // N already in the totals: from the rounding pass, or (FRS) the host
LS_CONST uint kPlanRejection = 1u;  // N: the target (or N-bar) rounded, if anything can be drawn

// Realization's workgroups take chunks of kSegmentSlots samples, one per subgroup at a time:
// the plan launches one workgroup per this many chunks (subgroups of 32 lanes each take one),
// up to the device's limit, and the workgroups stride over the rest.
LS_CONST uint kChunksPerWorkgroup = 8;

struct PlanPush {
  uint64_t totals;
  uint64_t indirect;      // uint[3]: workgroup counts of the realization dispatch
  uint64_t capacity;      // samples the sample buffer holds
  double target;          // kPlanRejection: N_target; negative: N-bar
  double total_area;      // kPlanRejection: the mesh's world area
  uint max_workgroups;    // the device's maxComputeWorkGroupCount[0]
  uint method;            // kPlanTrs or kPlanRejection
  uint key0, key1;        // kPlanRejection: Philox key of the rounding stream
};

struct WritePush {
  uint64_t samples;
  uint64_t count;
};

struct RejectionPush {
  uint64_t triangles;
  uint64_t maps;
  uint64_t texels;
  uint64_t area_cdf;  // double[T], inclusive CDF of world areas
  uint64_t area_guide;  // uint[T + 1], its cutpoints (core/area_pick.h)
  uint64_t samples;
  uint64_t totals;
  uint key0, key1;
  uint triangle_count;
  uint max_tries;
  uint texel_count;   // texels of map `map` (the global-max pass runs once per map)
  uint map;
};

/// Fast rejection sampling over the micro-triangles of core::FrsTable (M of them).
struct FrsPush {
  uint64_t triangles;
  uint64_t maps;
  uint64_t texels;
  uint64_t cdf;       // double[M], inclusive CDF of world area times bound
  uint64_t guide;     // uint[M + 1], its cutpoints (core/area_pick.h)
  uint64_t parent;    // uint[M], the caller's triangle
  uint64_t corners;   // float[6 M], barycentrics (b1, b2) of the 3 corners in the parent
  uint64_t bound;     // float[M]
  uint64_t samples;
  uint64_t totals;
  uint key0, key1;
  uint micro_count;   // M
  uint max_tries;
};

#ifdef __cplusplus
}  // namespace lightsampler::gpu
#undef LS_CONST
#endif

#endif
