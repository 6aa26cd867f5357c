#pragma once
// Benchmark density maps generated in-process from fixed seeds, one per regime that matters to
// rejection sampling: smooth (high acceptance), sparse (neon strokes, mostly zero: low acceptance
// for plain rejection sampling), high-frequency (per-texel variation: the per-triangle maximum is
// far above the mean).

#include <cstdint>
#include <string>
#include <vector>

#include "lightsampler/mesh.h"

namespace trs_bench {

enum class MapKind { smooth, sparse, hifreq };

/// "smooth", "sparse", "hifreq"; throws std::invalid_argument on another name.
MapKind parse_map_kind(const std::string& name);
const char* to_string(MapKind kind);

struct DensityMap {
  std::string name;
  std::uint32_t size = 0;  ///< width and height, texels
  std::vector<float> texels;

  lightsampler::DensityMapView view() const { return {texels, size, size}; }
};

/// A gradient times a low-frequency sinusoid, in [0.01, 1], non-zero everywhere.
DensityMap make_smooth_map(std::uint32_t size);

/// Thin strokes (~2 texels wide at 2048) of random length and brightness, added until about
/// 1.5% of texels are lit; zero elsewhere.
DensityMap make_sparse_map(std::uint32_t size);

/// A one-texel checker of 1 and 0.1 times per-texel noise in [0.5, 1].
DensityMap make_hifreq_map(std::uint32_t size);

DensityMap make_map(MapKind kind, std::uint32_t size);

/// Fraction of texels with non-zero density.
double coverage(const DensityMap& map);

}  // namespace trs_bench
