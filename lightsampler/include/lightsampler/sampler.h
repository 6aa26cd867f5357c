#pragma once
// The sampler: set up once with a mesh and its density maps, then generate a fresh sample set
// every frame (new seed, new target, updated maps).

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "lightsampler/buffer.h"
#include "lightsampler/enum_names.h"
#include "lightsampler/mesh.h"
#include "lightsampler/sample.h"
#include "lightsampler/texel_pieces.h"

namespace lightsampler {

/// Triangle Rejection Sampling (the paper's method); plain rejection sampling over the whole
/// mesh (its Algorithm 1, a baseline); naive triangle stratification (its Section 6 baseline:
/// each triangle walks its texels with a polygon clipper, counts by clipped area and draws texel
/// piece by texel piece); or fast rejection sampling after Šik and Křivánek (2013: the mesh
/// subdivided once until the density is nearly constant on each part, then rejection against
/// each part's bound, parts drawn from one CDF). Every method runs on both backends, with the same
/// samples; the Vulkan backend counts naive stratification by one invocation per triangle
/// (reported as Counting::per_triangle) and builds FRS's table on the host.
enum class Method { trs, rejection, naive, frs };

/// How the per-triangle counts are turned into a CDF. `unordered` is the paper's Algorithm 3
/// (one packed 64-bit atomic); `ordered` is a classic prefix sum. `automatic` takes the faster
/// of the two for the backend: ordered on the CPU (measured faster there, docs/benchmarks.md),
/// unordered on the GPU unless the triangle count and the total do not fit one 64-bit word.
/// `lookback` is a single-pass decoupled look-back scan (Merrill and Garland 2016), ordered like
/// `ordered`, with the same outputs; the Vulkan backend only, never chosen by `automatic` (an
/// experiment, Figure 13). It needs the device's vulkanMemoryModel and
/// vulkanMemoryModelDeviceScope (std::invalid_argument otherwise), and totals below 2^62
/// (std::overflow_error otherwise).
enum class ScanOrder { automatic, unordered, ordered, lookback };

/// How the counting pass measures a triangle's overlap with a texel (the paper's Figure 11).
/// `closed_form` is Eq. 5 (the sampler as designed); `clipping` clips the triangle to the texel
/// with a polygon clipper (exact, slower); `sdf` is Eq. 6, an approximation from the triangle's
/// signed distance at the texel's centre: cheaper but not exact, so its frames are biased
/// (Figure 12). For experiments; TRS only.
enum class Overlap { closed_form, clipping, sdf };

/// The backend that runs a sampler; `automatic` is a request only (backend.h).
enum class Backend { automatic, cpu, vulkan };

/// How the Vulkan backend enumerates (triangle, texel) pairs in the counting pass. `automatic`
/// counts each small triangle in one invocation and balances the cells of the large ones (the
/// per-triangle and compute paths, each where it is fastest, in the same passes). `raster`
/// rasterizes the mesh in UV space (the paper's method, conservative or dilated); `compute` runs
/// one thread per candidate cell after a prefix sum over the triangles' footprints, for GPUs
/// whose graphics units are a small part of the chip; `per_triangle` is the paper's naive
/// one-thread-per-triangle ablation, kept as the baseline `compute` is measured against. `cpu`
/// is the CPU backend's own path: reported in Frame::counting_used, never requested.
enum class Counting { automatic, raster, compute, per_triangle, cpu };

/// What a frame asks of the Vulkan backend only; the CPU backend ignores it.
struct VulkanFrameOptions {
  Counting counting = Counting::automatic;
  /// Copy the outputs into the Frame. False keeps them on the device (timing the sampler alone,
  /// or a consumer that reads the device buffers); the Frame's totals and times are still filled.
  bool read_back = true;
  /// Ablations of the paper's Figure 14, for experiments; the defaults are the sampler as
  /// designed. False: every invocation of the counting passes and of the unordered scan issues
  /// its own atomics instead of one per subgroup; N-bar_T changes only by float summation order.
  bool subgroup_reduction = true;
  /// True: realization finds the triangle of a slot through an inverse CDF (a guide table over
  /// the counts' CDF, built after the scan) before its binary search; the same samples.
  bool inverse_cdf = false;
};

struct FrameRequest {
  std::uint64_t seed = 0;
  /// N_target: the expected sample count. None: the count emerges from the maps (N-bar).
  std::optional<double> target_count;
  Method method = Method::trs;
  ScanOrder scan = ScanOrder::automatic;
  /// Changing it between frames counts again, as a replaced map does.
  Overlap overlap = Overlap::closed_form;
  /// False: stop after the counts and the CDF (no samples), e.g. to size buffers.
  bool realize = true;
  VulkanFrameOptions vulkan;
  /// Rejections in a row before a slot gives up: the last of them fills the slot anyway and is
  /// counted in Frame::exhausted; a non-zero count means a biased frame. Also bounds the
  /// attempts of an exact draw (naive stratification; TRS after exact_after).
  std::uint32_t max_tries = 1u << 28;
  /// TRS: rejections in a row after which the rest of the segment (up to 256 slots) is drawn
  /// exactly from the triangle's texel pieces, counted in Frame::exact_draws. Unbiased, and
  /// bounds the time of a triangle whose density is a sliver of it. 0: never (the paper's rule).
  std::uint32_t exact_after = 256;
};

/// The passes a frame times. `distribution` is plain rejection sampling's set-up (area CDF and
/// bound) or FRS's (its subdivision and CDF, when built), `readback` the Vulkan backend's copy to the host, `refinement` the adaptive
/// subdivision's mapping of samples back to the caller's triangles.
enum class Pass { counting, rounding, scan, realization, distribution, readback, refinement };

struct PassTime {
  Pass pass;
  double ms;
};

/// One frame's output. Reuse the same Frame across frames: buffers keep their capacity.
struct Frame {
  Buffer<Sample> samples;              ///< N samples
  Buffer<double> expected_counts;      ///< N-bar_T per triangle, before scaling to the target
  Buffer<std::uint64_t> counts;        ///< N_T per triangle, after scaling and stochastic rounding
  Buffer<float> max_density;           ///< D_T^max per triangle (scaled by the map's scale)
  Buffer<std::uint64_t> cdf;           ///< inclusive CDF of the counts, in processing order
  Buffer<std::uint32_t> inverse_permutation;  ///< processing index -> triangle index

  double expected_total = 0;      ///< N-bar, the integral of the density over the mesh (NaN: not computed)
  std::uint64_t sample_count = 0;   ///< N, the effective total
  std::uint64_t candidates = 0;     ///< candidates tried; sample_count / candidates = acceptance rate
  std::uint64_t exhausted = 0;      ///< slots filled after max_tries rejections in a row
  std::uint64_t exact_draws = 0;    ///< TRS: slots drawn exactly after exact_after rejections in a row
  /// Memory a method keeps between frames, bytes: FRS's micro-triangles and their CDF (built in
  /// the frame whose `distribution` pass is timed, the first or the first after update_map).
  std::uint64_t setup_bytes = 0;
  Method method = Method::trs;
  ScanOrder scan_used = ScanOrder::ordered;
  /// The counting path that ran; none when the counts of an earlier frame still held (no map
  /// replaced since) or the frame needed none.
  std::optional<Counting> counting_used;
  std::vector<PassTime> passes;     ///< time per pass, in order
  double total_ms = 0;
};

/// What building a sampler did, for reports.
struct SamplerSetup {
  double subdivision_ms = 0.0;  ///< splitting the mesh (refinement.h), within the construction
  std::uint64_t parts = 0;      ///< triangles the backend samples: the subdivision's parts, else the mesh's
};

namespace core {
class HostScene;
}

/// The density maps on the mesh as a sampler reads them. Every backend answers these on the
/// host, from the same maps it samples, so that a renderer's pdf, its emission lookups and its
/// exact draws read the very texels its samples were drawn from. Valid while its sampler lives.
class MapQueries {
 public:
  explicit MapQueries(const core::HostScene& scene) : scene_(&scene) {}

  /// Density (samples per world area) at a point of a triangle, read exactly as the sampler
  /// reads it (same texel, same addressing), so that a renderer's pdf agrees with the samples.
  float density(std::uint32_t triangle, float b1, float b2) const;

  /// The texel that density() reads at that point, after addressing; none for a triangle
  /// without a map. A renderer that reads its own per-texel data there (emitted radiance) stays
  /// texel for texel with the sampler.
  std::optional<Texel> texel(std::uint32_t triangle, float b1, float b2) const;

  /// The triangle's pieces of non-zero density, row by row of the lattice (texel_pieces.h), into
  /// `out` (cleared first): their densities times their areas integrate the density over the
  /// triangle exactly. A triangle without UV area is one piece.
  void texel_pieces(std::uint32_t triangle, std::vector<TexelPiece>& out) const;
  /// A uniform point of the piece of one lattice cell (TexelPiece::cell_x, cell_y), cut as
  /// texel_pieces cuts it, from three uniforms in [0, 1) as uniform_point takes them: a caller
  /// that keeps its pieces by cell draws in them without keeping their polygons. None where the
  /// triangle does not overlap that cell.
  std::optional<Barycentrics> texel_piece_point(std::uint32_t triangle, std::int64_t cell_x,
                                                std::int64_t cell_y, float u_fan, float u0, float u1) const;

 private:
  const core::HostScene* scene_;
};

/// A sampler bound to one mesh and its density maps. Implementations: the CPU backend
/// (make_cpu_sampler); the Vulkan backend.
class Sampler {
 public:
  virtual ~Sampler() = default;

  virtual Backend backend() const = 0;       ///< cpu or vulkan
  virtual std::string device() const = 0;    ///< the processor or GPU that runs it

  virtual std::uint64_t triangle_count() const = 0;
  virtual std::size_t map_count() const = 0;
  /// What its construction did (a subdivision's, its latest after a map changed).
  virtual SamplerSetup setup() const { return {0.0, triangle_count()}; }

  /// Replaces density map `index` (size, addressing and scale may change). Throws
  /// std::invalid_argument on a bad map, std::out_of_range on a bad index. N-bar_T and D_T^max
  /// are kept between frames; the next frame counts the triangles of this map again, and only
  /// those (Vulkan raster counting, which adds into its results: every triangle).
  virtual void update_map(std::size_t index, const DensityMapView& map) = 0;

  /// Generates one frame into `frame`.
  virtual void generate(const FrameRequest& request, Frame& frame) = 0;

  /// The density maps as this sampler reads them.
  virtual MapQueries maps() const = 0;
  /// Hands the sampler N-bar_T and D_T^max of its triangles, measured elsewhere exactly as its
  /// CPU counting pass measures them (the closed form, these maps), as the subdivision does: the
  /// next frame uses them rather than counting again. A backend that counts on a device ignores
  /// them; the CPU backend throws std::invalid_argument unless there is one of each per triangle.
  virtual void use_counts(std::span<const double> expected_counts, std::span<const float> max_density) {
    (void)expected_counts;
    (void)max_density;
  }
};

struct CpuOptions {
  unsigned threads = 0;  ///< worker threads; 0: every hardware thread
};

/// The worker threads a CPU sampler made with `options` runs.
unsigned worker_threads(const CpuOptions& options);

/// The native multi-threaded backend. Throws std::invalid_argument (bad mesh or map, with what
/// and where) or std::length_error (2^32 triangles or more).
std::unique_ptr<Sampler> make_cpu_sampler(const MeshView& mesh,
                                          std::span<const DensityMapView> maps,
                                          const CpuOptions& options = {});

/// The names of the enums' values, as the tools and the Python module take and print them.
inline constexpr EnumName<Method> kMethodNames[] = {
    {Method::trs, "trs"}, {Method::rejection, "rs"}, {Method::naive, "naive"}, {Method::frs, "frs"}};
inline constexpr EnumName<ScanOrder> kScanOrderNames[] = {{ScanOrder::automatic, "auto"},
                                                          {ScanOrder::unordered, "unordered"},
                                                          {ScanOrder::ordered, "ordered"},
                                                          {ScanOrder::lookback, "lookback"}};
inline constexpr EnumName<Overlap> kOverlapNames[] = {
    {Overlap::closed_form, "closed-form"}, {Overlap::clipping, "clipping"}, {Overlap::sdf, "sdf"}};
/// Counting::cpu, last, is reported and never requested: the choices a caller has are the others.
inline constexpr EnumName<Counting> kCountingNames[] = {{Counting::automatic, "auto"},
                                                        {Counting::raster, "raster"},
                                                        {Counting::compute, "compute"},
                                                        {Counting::per_triangle, "per-triangle"},
                                                        {Counting::cpu, "cpu"}};
inline constexpr std::span<const EnumName<Counting>> kRequestableCountings =
    std::span(kCountingNames).first(std::size(kCountingNames) - 1);
inline constexpr EnumName<Backend> kBackendNames[] = {
    {Backend::automatic, "auto"}, {Backend::cpu, "cpu"}, {Backend::vulkan, "vulkan"}};
inline constexpr EnumName<Pass> kPassNames[] = {
    {Pass::counting, "counting"},         {Pass::rounding, "rounding"}, {Pass::scan, "scan"},
    {Pass::realization, "realization"},   {Pass::distribution, "distribution"},
    {Pass::readback, "readback"},         {Pass::refinement, "refinement"}};
inline constexpr EnumName<Addressing> kAddressingNames[] = {
    {Addressing::wrap, "wrap"}, {Addressing::clamp, "clamp"}, {Addressing::mirror, "mirror"}};

inline const char* to_string(Method value) { return name_of(kMethodNames, value); }
inline const char* to_string(ScanOrder value) { return name_of(kScanOrderNames, value); }
inline const char* to_string(Overlap value) { return name_of(kOverlapNames, value); }
inline const char* to_string(Counting value) { return name_of(kCountingNames, value); }
inline const char* to_string(Backend value) { return name_of(kBackendNames, value); }
inline const char* to_string(Pass value) { return name_of(kPassNames, value); }
inline const char* to_string(Addressing value) { return name_of(kAddressingNames, value); }

}  // namespace lightsampler
