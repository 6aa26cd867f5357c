#pragma once
// Results as an aligned table on the terminal (a row as each case finishes) and as CSV, rewritten
// atomically after every case so that an interrupted run keeps what it measured.

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "measure.h"

namespace trs_bench {

struct CaseResult {
  /// "sampling" (time vs sample count), "floor" (writing samples alone) or "scan" (scan orders,
  /// no realization)
  std::string experiment;
  std::string mesh;
  std::uint64_t triangles = 0;
  std::string map;
  std::uint32_t map_width = 0, map_height = 0;
  double coverage = 0;  ///< the map's fraction of non-zero texels
  std::string method;  ///< "trs", "rs", "naive" or "frs" (lightsampler::to_string)
  std::string scan;    ///< the scan order used; "-" for plain rejection sampling
  std::string overlap;  ///< the overlap formula of TRS's counting; "-" for the other methods
  double target = 0;
  std::string backend;
  std::string engine;  ///< backend and counting path, e.g. "cpu", "vk/raster"
  std::string device;
  unsigned threads = 0;
  float refine = 0;  ///< the sampler's Refinement::min_acceptance (0: none)
  std::string variant;  ///< the ablation ("full", "no-subgroup-reduction", ...); empty outside them
  std::optional<Measurement> measured;  ///< empty: skipped
  double estimate_ms = 0;               ///< for a skipped case: its extrapolated frame time
  std::optional<double> floor_ms;       ///< the time to write as many samples on the backend
};

class Recorder {
 public:
  /// `csv` empty: no CSV.
  Recorder(std::ostream& table, std::filesystem::path csv);

  /// Prints a section title and the column header.
  void begin_section(const std::string& title);
  /// Prints the row and rewrites the CSV.
  void add(CaseResult result);

  const std::vector<CaseResult>& results() const { return results_; }

 private:
  void write_csv() const;

  std::ostream& table_;
  std::filesystem::path csv_;
  std::vector<CaseResult> results_;
};

/// TRS against plain rejection sampling for each (mesh, map, target) of the sampling experiment
/// where both ran or were estimated: the speed-up is rs / trs total time.
void print_speedups(std::ostream& out, const std::vector<CaseResult>& results);

}  // namespace trs_bench
