#pragma once
// Benchmark density maps generated in-process from fixed seeds, of the characters that matter to
// rejection sampling (after the paper's Figure 6): smooth (high acceptance), fractal (structure
// at every scale), strokes, dots, stripes and text (mostly zero: low acceptance for plain
// rejection sampling), high-frequency (per-texel variation: the per-triangle maximum is far above
// the mean), and the fractal thresholded to a chosen sparsity (the paper's Figure 10). A map may
// also come from a dataset file (dataset_file.h).

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "lightsampler/mesh.h"

namespace trs_bench {

enum class MapKind { smooth, sparse, hifreq, fractal, dots, stripes, text, threshold, file };

/// What to make, as written on the command line: "smooth", "threshold:1e-3", "file:lamp.trsd".
struct MapSpec {
  MapKind kind = MapKind::smooth;
  double fraction = 1;         ///< threshold: the fraction of texels kept lit
  std::filesystem::path file;  ///< file: the dataset file
};

/// Parses a map spec; throws std::invalid_argument naming the bad spec.
MapSpec parse_map_spec(std::string_view text);

/// The generated kinds' names, as --help lists them.
std::string map_kind_names();

struct DensityMap {
  std::string name;
  std::uint32_t width = 0, height = 0;  ///< texels
  std::vector<float> texels;            ///< row-major, row 0 at v = 0
  double coverage = 0;                  ///< fraction of texels with non-zero density

  lightsampler::DensityMapView view() const { return {texels, width, height}; }
};

/// A gradient times a low-frequency sinusoid, in [0.01, 1], non-zero everywhere.
DensityMap make_smooth_map(std::uint32_t size);

/// Thin strokes (~2 texels wide at 2048) of random length and brightness, added until about
/// 1.5% of texels are lit; zero elsewhere.
DensityMap make_sparse_map(std::uint32_t size);

/// A one-texel checker of 1 and 0.1 times per-texel noise in [0.5, 1].
DensityMap make_hifreq_map(std::uint32_t size);

/// Fractional Brownian motion of tileable value noise (8 octaves from 4 cells across), in
/// [0.02, 1], non-zero everywhere.
DensityMap make_fractal_map(std::uint32_t size);

/// The fractal map with all but its brightest `fraction` of texels set to zero, by rank (ties
/// broken by texel index), so that exactly max(1, round(fraction * texels)) stay lit: down to a
/// single texel.
DensityMap make_threshold_map(std::uint32_t size, double fraction);

/// Discs of 1-4 texels radius (at 2048) and random brightness until 1% of texels are lit.
DensityMap make_dots_map(std::uint32_t size);

/// Diagonal bars with hard edges in four columns of periods 64, 32, 16 and 8 texels (at 2048):
/// about a third lit at 1 (half at 4 texels), zero between.
DensityMap make_stripes_map(std::uint32_t size);

/// Lines of glyph-like clusters of short connected strokes (a neon sign's text), zero between.
DensityMap make_text_map(std::uint32_t size);

/// A generated map of `size` squared texels, or the map of a dataset file (its own size).
DensityMap make_map(const MapSpec& spec, std::uint32_t size);

}  // namespace trs_bench
