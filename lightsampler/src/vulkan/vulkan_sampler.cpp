// The Vulkan backend: the passes of shaders/, recorded in one submission per frame and sized on
// the device.

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/frame_policy.h"
#include "core/frs_table.h"
#include "core/validate.h"
#include "vulkan/gpu_scene.h"
#include "vulkan/passes.h"
#include "spirv/counting_raster_frag.h"
#include "spirv/counting_raster_geom.h"
#include "spirv/counting_raster_vert.h"

namespace lightsampler {

namespace {

using vk::Buffer;
using vk::Commands;

/// The pass a GPU timestamp was named after (stamps are named by to_string(Pass)).
Pass pass_named(const std::string& name) {
  for (Pass p : {Pass::counting, Pass::rounding, Pass::scan, Pass::realization, Pass::distribution})
    if (name == to_string(p)) return p;
  throw std::logic_error("a GPU timestamp named \"" + name + "\" that is no pass");
}
using vk::workgroups_for;

// Viewport tile of the raster counting path, in texels (within every device's limits).
constexpr std::int64_t kTile = 4096;

/// Mesa's llvmpipe (lavapipe) ends shader loops after about 65535 iterations (a counter shared
/// by the loops of a shader), and then lanes of the same SIMD group come out wrong.
bool is_llvmpipe(const std::string& device) { return device.find("llvmpipe") != std::string::npos; }

/// Tries per slot that realization may make on this device. A subgroup walks a chunk's segments
/// in rounds of one candidate per lane, so on llvmpipe a chunk stays within the loop limit while
/// its slots need fewer than about 65535 rounds in all; there a slot stops at 2^15 tries and, if
/// still rejected, is counted in Frame::exhausted like any slot reaching max_tries.
std::uint32_t device_max_tries(const std::string& device, std::uint32_t requested) {
  constexpr std::uint32_t kLlvmpipeMaxTries = 1u << 15;
  return is_llvmpipe(device) ? std::min(requested, kLlvmpipeMaxTries) : requested;
}

/// The most lattice cells of a triangle that TRS's exact draws walk on this device. On llvmpipe
/// a segment's exact draws walk the cells once per round of slots, so larger triangles would
/// pass the loop limit: they keep rejecting, up to max_tries, as with exact_after 0.
std::uint32_t device_exact_cells(const std::string& device) {
  constexpr std::uint32_t kLlvmpipeExactCells = 1024;
  return is_llvmpipe(device) ? kLlvmpipeExactCells : std::numeric_limits<std::uint32_t>::max();
}

/// How the per-triangle count buffers' N-bar_T and D_T^max were counted: TRS's path, whether its
/// atomics follow a subgroup reduction and its overlap formula, or naive stratification's
/// clipping (per triangle), which also leaves its pieces' weights.
struct CountingMode {
  Counting path;
  bool subgroup_reduction = true;
  Overlap overlap = Overlap::closed_form;
  bool naive = false;
  bool operator==(const CountingMode&) const = default;
};

constexpr CountingMode kNaiveCounting{Counting::per_triangle, true, Overlap::closed_form, true};

/// Per-triangle and per-frame device buffers, grown on demand and kept between frames.
struct FrameBuffers {
  Buffer expected, max_density, footprint, cell_cdf, counts, cdf, inverse, identity, totals, samples;
  Buffer guide;            ///< uint[T + 1]: realization's inverse CDF (inverse_cdf.glsl)
  Buffer piece_cdf;        ///< naive stratification: double per lattice cell (GpuScene::piece_cells)
  Buffer totals_readback;  ///< host-visible copy of `totals`: shader atomics stay in device memory
  Buffer dispatch_args;    ///< realization's indirect workgroup counts, written by the plan pass
  Buffer stopped;          ///< TRS: the segments whose walk stopped (gpu::kStoppedHeaderUints)
  Buffer stale_maps;       ///< uint per map: 1 where a partial count counts the map's triangles
};

/// FRS's table (core/frs_table.h) on the device, built on the host by the first FRS frame and
/// again after update_map.
struct FrsDevice {
  Buffer parent, corners, bound, cdf, guide;
  std::uint32_t size = 0;
  double expected_total = 0, total_area = 0;
  float max_bound = 0;
  std::uint64_t bytes = 0;
};

class VulkanSampler final : public Sampler {
 public:
  VulkanSampler(const MeshView& mesh, std::span<const DensityMapView> maps, const VulkanOptions& options)
      : context_(vk::Context::create({options.device, options.validation})),
        scene_(*context_, mesh, maps),
        pipelines_(*context_),
        reducing_(*context_, true),
        scan_(*context_),
        lookback_(*context_) {
    const std::uint64_t t = std::max<std::uint64_t>(scene_.triangle_count(), 1);
    buffers_.expected = context_->create_buffer(t * sizeof(float));
    buffers_.max_density = context_->create_buffer(t * sizeof(std::uint32_t));
    for (Buffer* b : {&buffers_.footprint, &buffers_.cell_cdf, &buffers_.counts, &buffers_.cdf})
      *b = context_->create_buffer(t * sizeof(std::uint64_t));
    buffers_.inverse = context_->create_buffer(t * sizeof(std::uint32_t));
    // The ordered scan keeps triangles in place: its inverse permutation is the identity.
    std::vector<std::uint32_t> identity(scene_.triangle_count());
    std::iota(identity.begin(), identity.end(), 0u);
    buffers_.identity = context_->create_buffer(t * sizeof(std::uint32_t));
    if (!identity.empty())
      context_->upload(buffers_.identity, 0, identity.data(), identity.size() * sizeof(std::uint32_t));
    buffers_.stale_maps = context_->create_buffer(std::max<std::size_t>(maps.size(), 1) * sizeof(std::uint32_t));
    stale_.assign(maps.size(), false);
    buffers_.totals = context_->create_buffer(sizeof(gpu::FrameTotals));
    buffers_.totals_readback = context_->create_buffer(sizeof(gpu::FrameTotals), /*host_visible=*/true);
  }

  Backend backend() const override { return Backend::vulkan; }
  std::string device() const override { return context_->device_name(); }
  std::uint64_t triangle_count() const override { return scene_.triangle_count(); }
  std::size_t map_count() const override { return scene_.host().maps().size(); }

  void update_map(std::size_t index, const DensityMapView& map) override {
    scene_.update_map(index, map);
    stale_[index] = true;
    frs_.reset();
  }

  MapQueries maps() const override { return MapQueries(scene_.host()); }

  void generate(const FrameRequest& request, Frame& frame) override {
    core::begin_frame(request, frame);
    const auto start = std::chrono::steady_clock::now();
    run_frame(request, frame);
    frame.total_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }

 private:
  /// A frame's commands, starting from zero totals.
  Commands begin_frame_commands() {
    counting_.reset();
    Commands c = context_->begin();
    c.fill(buffers_.totals, 0, sizeof(gpu::FrameTotals), 0);
    c.barrier();
    return c;
  }

  /// Runs `c`, whose passes end with a barrier, and returns the frame's totals after it.
  gpu::FrameTotals submit(Commands& c, Frame& frame) {
    c.copy(buffers_.totals, 0, buffers_.totals_readback, 0, sizeof(gpu::FrameTotals));
    add_passes(frame, context_->submit(c));
    if (counting_) {
      counted_ = counting_;
      std::fill(stale_.begin(), stale_.end(), false);
    }
    gpu::FrameTotals t;
    std::memcpy(&t, buffers_.totals_readback.mapped(), sizeof t);
    return t;
  }

  void add_passes(Frame& frame, const std::vector<std::pair<std::string, double>>& times) {
    for (const auto& [name, ms] : times) frame.passes.push_back({pass_named(name), ms});
  }

  /// `small_cells`: triangles of at most that many cells are counted by the setup pass.
  gpu::CountingPush count_push(std::uint32_t small_cells = 0) const {
    return {scene_.triangles(), scene_.map_records(), scene_.texels(), buffers_.expected.address(),
            buffers_.max_density.address(), buffers_.footprint.address(), buffers_.cell_cdf.address(),
            buffers_.totals.address(), 0, scene_.triangle_count(), small_cells};
  }

  /// TRS's compute counting passes with `overlap`, built on first use.
  const vk::CountingPipelines& counting_pipelines(Overlap overlap) {
    std::optional<vk::CountingPipelines>& pipelines = counting_pipelines_[std::size_t(overlap)];
    if (!pipelines) pipelines.emplace(*context_, overlap);
    return *pipelines;
  }

  /// The passes reducing over subgroups before their atomics, or, for the ablation, not.
  const vk::ReducingPipelines& reducing(bool subgroup_reduction) {
    if (subgroup_reduction) return reducing_;
    if (!unreduced_) unreduced_.emplace(*context_, false);
    return *unreduced_;
  }

  /// Counting (Algorithm 2, lines 1-8) and the total N-bar, recorded into `c`. N-bar_T and
  /// D_T^max stay in their buffers between frames: a frame counts the triangles of the maps
  /// replaced by update_map since, or every triangle when it asks for another counting mode
  /// (or raster, which adds into its results); otherwise it only sums the total.
  void record_counting(Commands& c, const FrameRequest& request, Frame& frame) {
    const Counting path = request.vulkan.counting;
    const CountingMode mode{path, request.vulkan.subgroup_reduction, request.overlap};
    if (path == Counting::cpu)
      throw std::invalid_argument("the Vulkan backend has no CPU counting path; ask for raster, compute or per-triangle");
    gpu::CountingPush push = count_push(path == Counting::automatic ? scene_.small_triangle_cells() : 0);
    const bool stale = any_stale();
    if (counted_ == mode && stale && path != Counting::raster) {
      c.fill(buffers_.stale_maps, 0, buffers_.stale_maps.size(), 0);
      for (std::size_t m = 0; m < stale_.size(); ++m)
        if (stale_[m]) c.fill(buffers_.stale_maps, m * sizeof(std::uint32_t), sizeof(std::uint32_t), 1);
      c.barrier();
      push.stale_maps = buffers_.stale_maps.address();
    }
    if (counted_ != mode || stale) record_triangle_counts(c, mode, push, frame);
    record_counting_total(c, push, mode.subgroup_reduction);
  }

  bool any_stale() const { return std::find(stale_.begin(), stale_.end(), true) != stale_.end(); }

  /// N-bar, the sum of the counts, ending the counting pass.
  void record_counting_total(Commands& c, const gpu::CountingPush& push, bool subgroup_reduction) {
    c.dispatch(reducing(subgroup_reduction).counting_total, &push, sizeof push, workgroups_for(scene_.triangle_count()));
    c.barrier();
    c.timestamp(to_string(Pass::counting));
  }

  /// Naive stratification's counting (paper, Section 3.2): one invocation per triangle walks its
  /// texels with the polygon clipper, writing the CDF of its pieces. Every triangle, when the
  /// buffers do not hold its counts yet or a map changed; reported as the per-triangle path.
  void record_naive_counting(Commands& c, Frame& frame) {
    const VkDeviceSize cdf_bytes = std::max<std::uint64_t>(scene_.piece_cells(), 1) * sizeof(double);
    if (!buffers_.piece_cdf || buffers_.piece_cdf.size() < cdf_bytes) {
      buffers_.piece_cdf = context_->create_buffer(cdf_bytes);
      counted_.reset();  // the CDF is lost with the old buffer
    }
    gpu::CountingPush push = count_push();
    push.piece_offsets = scene_.piece_offsets();
    push.piece_cdf = buffers_.piece_cdf.address();
    if (counted_ != kNaiveCounting || any_stale()) {
      c.dispatch(pipelines_.naive_counting, &push, sizeof push, workgroups_for(scene_.triangle_count()));
      c.barrier();
      counting_ = kNaiveCounting;
      frame.counting_used = Counting::per_triangle;
    }
    record_counting_total(c, push, true);
  }

  /// N-bar_T and D_T^max by `mode`, of every triangle or, with push.stale_maps, of the stale
  /// maps' triangles; counted_ once the commands have run.
  void record_triangle_counts(Commands& c, CountingMode mode, const gpu::CountingPush& push, Frame& frame) {
    const Counting path = mode.path;
    const std::uint32_t groups = workgroups_for(scene_.triangle_count());
    const vk::CountingPipelines& counting = counting_pipelines(mode.overlap);
    c.dispatch(counting.setup, &push, sizeof push, groups);
    c.barrier();
    if (path == Counting::raster) {
      record_raster_counting(c, mode);
      frame.counting_used = Counting::raster;
    } else if (path == Counting::per_triangle) {
      c.dispatch(counting.triangles, &push, sizeof push, groups);
      c.barrier();
      frame.counting_used = Counting::per_triangle;
    } else {
      // Automatic: the setup pass counted the small triangles; the cell pass takes the others.
      const std::uint64_t cells =
          path == Counting::automatic ? scene_.large_triangle_cells() : scene_.candidate_cells();
      if (cells > 0) {
        scan_.record(c, pipelines_, buffers_.footprint.address(), buffers_.cell_cdf.address(), scene_.triangle_count());
        // One invocation per run of kCellsPerRun candidates (counting_cells.comp).
        c.dispatch(counting.cells, &push, sizeof push,
                   workgroups_for((cells + gpu::kCellsPerRun - 1) / gpu::kCellsPerRun));
        c.barrier();
      }
      frame.counting_used = path == Counting::automatic ? Counting::automatic : Counting::compute;
    }
    counting_ = mode;
  }

  /// The paper's counting: every map's triangles rasterized in its texel space, one draw per
  /// viewport-sized tile of the lattice cells they touch.
  void record_raster_counting(Commands& c, CountingMode mode) {
    // Tile corners and vertices reach the rasterizer as floats, exact only within 2^24 texels.
    constexpr std::int64_t kExactFloat = std::int64_t(1) << 24;
    for (const vk::LatticeBox& box : scene_.map_boxes())
      if (!box.empty() && std::max({-box.x0, -box.y0, box.x1 + 1, box.y1 + 1}) > kExactFloat)
        throw std::invalid_argument("raster counting: the mesh reaches texel " + std::to_string(box.x0) + ", " +
                                    std::to_string(box.y0) + " to " + std::to_string(box.x1) + ", " +
                                    std::to_string(box.y1) +
                                    ", beyond the 2^24 texels a float rasterizer addresses exactly; use "
                                    "compute counting");
    const vk::RasterPipeline& pipeline = raster_pipeline(mode);
    const std::uint32_t vertices = 3 * scene_.triangle_count();
    // The geometry shader's margin: vertices snap to 2^-bits of a pixel, and texel coordinates
    // pass through NDC in float (about 1e-3 of a texel in a 4096-texel tile).
    const float dilation = std::ldexp(1.0f, -int(context_->capabilities().sub_pixel_bits)) + 0x1p-9f;
    for (std::uint32_t m = 0; m < scene_.map_boxes().size(); ++m) {
      const vk::LatticeBox box = scene_.map_boxes()[m];
      if (box.empty()) continue;
      for (std::int64_t y = box.y0; y <= box.y1; y += kTile)
        for (std::int64_t x = box.x0; x <= box.x1; x += kTile) {
          const auto width = std::uint32_t(std::min<std::int64_t>(kTile, box.x1 + 1 - x));
          const auto height = std::uint32_t(std::min<std::int64_t>(kTile, box.y1 + 1 - y));
          const gpu::RasterPush push{scene_.triangles(), scene_.map_records(), scene_.texels(),
                                     buffers_.expected.address(), buffers_.max_density.address(),
                                     buffers_.footprint.address(), float(x), float(y), float(width),
                                     float(height), m, dilation};
          c.draw(pipeline, &push, sizeof push, width, height, vertices);
        }
    }
    c.barrier();
  }

  /// Built on first use: conservative rasterization where the device has it, else the
  /// geometry shader dilates each triangle.
  const vk::RasterPipeline& raster_pipeline(CountingMode mode) {
    std::unique_ptr<vk::RasterPipeline>& raster = raster_[2 * std::size_t(mode.overlap) + mode.subgroup_reduction];
    if (!raster) {
      const bool conservative = context_->capabilities().conservative_rasterization;
      const std::uint32_t constants[] = {mode.subgroup_reduction, std::uint32_t(mode.overlap)};
      vk::RasterStages stages{spirv::counting_raster_vert, {}, spirv::counting_raster_frag, conservative, constants};
      if (!conservative) stages.geometry = spirv::counting_raster_geom;
      raster = std::make_unique<vk::RasterPipeline>(context_->create_raster(stages, sizeof(gpu::RasterPush)));
    }
    return *raster;
  }

  /// Grows the sample buffer to at least n samples; returns how many it holds.
  std::uint64_t ensure_samples(std::uint64_t n) {
    const VkDeviceSize bytes = std::max<std::uint64_t>(n, 1) * sizeof(gpu::Sample);
    if (!buffers_.samples || buffers_.samples.size() < bytes) {
      buffers_.samples = Buffer();  // free the old one first: samples can be most of the memory
      buffers_.samples = context_->create_buffer(bytes);
    }
    return buffers_.samples.size() / sizeof(gpu::Sample);
  }

  /// One submission per frame, sized on the device. The host chooses the sample buffer (and the
  /// scan) from a bound on N: the target plus one per triangle (stochastic rounding adds at most
  /// one to each), with room for the float total's rounding; without a target, the last such
  /// frame's N with room to spare. A frame whose N exceeds the bound (a first frame without a
  /// target, or a map made denser) realizes nothing and runs again with room: same seed, same
  /// samples.
  void run_frame(const FrameRequest& request, Frame& frame) {
    const std::uint32_t n_tri = scene_.triangle_count();
    const bool stratified = request.method == Method::trs || request.method == Method::naive;
    const bool frs = request.method == Method::frs;
    const bool counted = stratified || (request.method == Method::rejection && !request.target_count);
    std::uint64_t bound = request.target_count
                              ? std::uint64_t(std::ceil(*request.target_count * (1.0 + 0x1p-10))) + n_tri + 1
                              : last_count_ + last_count_ / 64 + 1024;
    // FRS's N is known on the host, from its table (as on the CPU backend): the bound is exact.
    const std::uint64_t frs_count = frs ? frs_sample_count(request, frs_table(frame)) : 0;
    if (frs) bound = frs_count;
    for (;;) {
      const std::uint64_t capacity = request.realize ? ensure_samples(bound) : 0;
      const std::uint64_t limit = request.realize ? capacity : bound;  // the N this run is valid for
      const gpu::FrameTotals totals = stratified ? run_stratified(request, frame, capacity, limit)
                                      : frs      ? run_frs(request, frame, frs_count, capacity)
                                                 : run_rejection(request, frame, capacity);
      frame.candidates = totals.candidates;
      frame.exhausted = totals.exhausted;
      frame.exact_draws = totals.exact;
      if (counted) {
        frame.expected_total = totals.expected_total;
        core::validate_expected_total(frame.expected_total);
      }
      frame.sample_count = totals.sample_count;
      if (frame.sample_count <= limit) break;
      bound = frame.sample_count + frame.sample_count / 64 + n_tri;
      frame.passes.clear();
    }
    if (frs) {
      frame.expected_total = frs_->expected_total;
      frame.setup_bytes = frs_->bytes;
    }
    if (!request.target_count) last_count_ = frame.sample_count;
    if (!stratified) frame.scan_used = ScanOrder::ordered;
    if (request.vulkan.read_back)
      read_back(frame, {.counted = counted, .inverse = stratified ? trs_inverse(frame) : nullptr}, request.realize);
  }

  const Buffer* trs_inverse(const Frame& frame) const {
    return frame.scan_used == ScanOrder::unordered ? &buffers_.inverse : &buffers_.identity;
  }

  /// Records and runs one frame with triangles as strata, TRS or naive stratification (counting
  /// by clipping, realization texel piece by texel piece; rounding and the scan are the same),
  /// its scan chosen for a total of at most `limit`, realizing N samples if N fits in `capacity`
  /// and none otherwise. Returns the frame's totals.
  gpu::FrameTotals run_stratified(const FrameRequest& request, Frame& frame, std::uint64_t capacity,
                                  std::uint64_t limit) {
    const std::uint32_t n_tri = scene_.triangle_count();
    const bool naive = request.method == Method::naive;
    // Automatic: unordered, one packed atomic per subgroup (Section 5).
    frame.scan_used = core::choose_scan(request.scan, ScanOrder::unordered, n_tri, limit);
    Commands c = begin_frame_commands();
    if (naive)
      record_naive_counting(c, frame);
    else
      record_counting(c, request, frame);
    const PhiloxKey rounding_key = stream_key(request.seed, Stream::rounding);
    const gpu::RoundingPush round{buffers_.expected.address(), buffers_.counts.address(), buffers_.totals.address(),
                                  request.target_count ? *request.target_count : -1.0, rounding_key[0],
                                  rounding_key[1], n_tri, 0};
    c.dispatch(pipelines_.rounding, &round, sizeof round, workgroups_for(n_tri));
    c.barrier();
    c.timestamp(to_string(Pass::rounding));
    if (frame.scan_used == ScanOrder::unordered && n_tri > 0) {
      const gpu::ScanPush scan{buffers_.counts.address(), buffers_.cdf.address(), 0, buffers_.inverse.address(),
                               buffers_.totals.address(), n_tri, std::uint32_t(64 - std::bit_width(std::uint64_t(n_tri))), 0};
      c.dispatch(reducing(request.vulkan.subgroup_reduction).scan_unordered, &scan, sizeof scan, workgroups_for(n_tri));
      c.barrier();
    } else if (frame.scan_used == ScanOrder::lookback) {
      lookback_.record(c, buffers_.counts.address(), buffers_.cdf.address(), n_tri);
    } else {
      scan_.record(c, pipelines_, buffers_.counts.address(), buffers_.cdf.address(), n_tri);
    }
    c.timestamp(to_string(Pass::scan));
    if (capacity > 0) {
      const PhiloxKey key = stream_key(request.seed, naive ? Stream::naive : Stream::realization);
      const PhiloxKey exact_key = stream_key(request.seed, Stream::exact);
      gpu::RealizationPush push{scene_.triangles(), scene_.map_records(), scene_.texels(),
                                buffers_.max_density.address(), scene_.piece_offsets(),
                                naive ? buffers_.piece_cdf.address() : 0, buffers_.cdf.address(),
                                trs_inverse(frame)->address(), buffers_.samples.address(),
                                buffers_.totals.address(), 0, key[0], key[1], n_tri,
                                device_max_tries(context_->device_name(), request.max_tries),
                                exact_key[0], exact_key[1], naive ? 0 : request.exact_after,
                                device_exact_cells(context_->device_name()), 0};
      if (request.vulkan.inverse_cdf && !naive && n_tri > 0) record_guide(c, push);
      if (push.exact_after > 0) push.stopped = record_stopped_list(c, capacity, n_tri);
      record_realization(c, naive ? pipelines_.naive_realization : pipelines_.realization, push,
                         {.method = gpu::kPlanTrs}, capacity);
      if (push.stopped != 0) {
        c.dispatch_indirect(pipelines_.realization_exact, &push, sizeof push, buffers_.stopped,
                            gpu::kStoppedDispatch * sizeof(std::uint32_t));
        c.barrier();
      }
      c.timestamp(to_string(Pass::realization));
    }
    return submit(c, frame);
  }

  /// FRS's table, built on the host and uploaded when the maps changed since the last one; the
  /// time that takes is the frame's `distribution` pass.
  const FrsDevice& frs_table(Frame& frame) {
    if (frs_) return *frs_;
    const auto start = std::chrono::steady_clock::now();
    const core::HostScene& host = scene_.host();
    const core::FrsTable table = core::frs_build(host.triangles(), host.texel_triangles(), host.maps());
    FrsDevice d;
    d.parent = upload(std::span(table.parent));
    d.corners = upload(std::span(table.corners));
    d.bound = upload(std::span(table.bound));
    d.cdf = upload(table.cdf.span());
    d.guide = upload(std::span(table.guide));
    d.size = std::uint32_t(table.size());
    d.expected_total = table.expected_total;
    d.total_area = table.total_area;
    d.max_bound = table.max_bound;
    d.bytes = table.bytes();
    frs_ = std::move(d);
    frame.passes.push_back(
        {Pass::distribution, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count()});
    return *frs_;
  }

  /// A new device buffer holding `data` (at least one element's room: no buffer is empty).
  template <class T>
  Buffer upload(std::span<const T> data) {
    Buffer b = context_->create_buffer(std::max(data.size_bytes(), sizeof(T)));
    if (!data.empty()) context_->upload(b, 0, data.data(), data.size_bytes());
    return b;
  }

  /// FRS's N: the target, or N-bar, rounded by the rounding stream (core::rejection_sample_count).
  static std::uint64_t frs_sample_count(const FrameRequest& request, const FrsDevice& table) {
    if (table.size == 0) return 0;
    return core::rejection_sample_count(request.target_count.value_or(table.expected_total), table.max_bound,
                                        table.total_area, request.seed);
  }

  /// Records and runs one FRS frame: its N samples, computed on the host, realized if they fit
  /// in `capacity`. Returns the frame's totals.
  gpu::FrameTotals run_frs(const FrameRequest& request, Frame& frame, std::uint64_t n, std::uint64_t capacity) {
    const FrsDevice& table = *frs_;
    Commands c = begin_frame_commands();
    // N into the totals, where the plan pass reads it (two words: a fill writes 32 bits).
    constexpr VkDeviceSize kCount = offsetof(gpu::FrameTotals, sample_count);
    c.fill(buffers_.totals, kCount, sizeof(std::uint32_t), std::uint32_t(n));
    c.fill(buffers_.totals, kCount + sizeof(std::uint32_t), sizeof(std::uint32_t), std::uint32_t(n >> 32));
    c.barrier();
    if (capacity > 0) {
      const PhiloxKey key = stream_key(request.seed, Stream::frs);
      const gpu::FrsPush push{scene_.triangles(), scene_.map_records(), scene_.texels(), table.cdf.address(),
                              table.guide.address(), table.parent.address(), table.corners.address(),
                              table.bound.address(), buffers_.samples.address(), buffers_.totals.address(),
                              key[0], key[1], table.size,
                              device_max_tries(context_->device_name(), request.max_tries)};
      record_realization(c, pipelines_.frs, push, {.method = gpu::kPlanTrs}, capacity);
      c.timestamp(to_string(Pass::realization));
    }
    return submit(c, frame);
  }

  /// Empties the list of stopped segments, grown to hold every segment of a frame of at most
  /// `capacity` samples over `triangles` triangles (each segment starts in its own chunk of
  /// kSegmentSlots samples or at a triangle's first slot), and returns its address.
  std::uint64_t record_stopped_list(Commands& c, std::uint64_t capacity, std::uint32_t triangles) {
    const std::uint64_t records = capacity / gpu::kSegmentSlots + triangles + 1;
    if (records > std::numeric_limits<std::uint32_t>::max())
      throw std::length_error("Vulkan backend: a frame of " + std::to_string(capacity) +
                              " samples has more segments than the exact pass can list");
    constexpr VkDeviceSize kUint = sizeof(std::uint32_t);
    const VkDeviceSize bytes = (gpu::kStoppedHeaderUints + records * gpu::kStoppedRecordUints) * kUint;
    if (!buffers_.stopped || buffers_.stopped.size() < bytes) buffers_.stopped = context_->create_buffer(bytes);
    // The count, the capacity, and the exact pass's workgroups: none until a walk stops.
    c.fill(buffers_.stopped, 0, kUint, 0);
    c.fill(buffers_.stopped, kUint, kUint, std::uint32_t(records));
    c.fill(buffers_.stopped, gpu::kStoppedDispatch * kUint, kUint, 0);
    c.fill(buffers_.stopped, (gpu::kStoppedDispatch + 1) * kUint, 2 * kUint, 1);
    c.barrier();
    return buffers_.stopped.address();
  }

  /// Builds realization's inverse CDF (the "Inverse CDF" ablation) and points `push` at it.
  void record_guide(Commands& c, gpu::RealizationPush& push) {
    const VkDeviceSize bytes = (VkDeviceSize(push.triangle_count) + 1) * sizeof(std::uint32_t);
    if (!buffers_.guide || buffers_.guide.size() < bytes) buffers_.guide = context_->create_buffer(bytes);
    push.guide = buffers_.guide.address();
    c.dispatch(pipelines_.realization_guide, &push, sizeof push, workgroups_for(push.triangle_count + std::uint64_t(1)));
    c.barrier();
  }

  /// Records and runs one frame of plain rejection sampling: the bound of every map (and N-bar
  /// without a target), then N and realization sized on the device. Returns the frame's totals.
  gpu::FrameTotals run_rejection(const FrameRequest& request, Frame& frame, std::uint64_t capacity) {
    const std::uint32_t n_tri = scene_.triangle_count();
    Commands c = begin_frame_commands();
    if (!request.target_count) record_counting(c, request, frame);  // Algorithm 1 needs N
    for (std::size_t m = 0; m < scene_.host().maps().size(); ++m) {
      const std::uint32_t texels = std::uint32_t(scene_.host().maps()[m].texels.size());
      const gpu::RejectionPush push{0, scene_.map_records(), scene_.texels(), 0, 0, 0, buffers_.totals.address(),
                                    0, 0, n_tri, 0, texels, std::uint32_t(m)};
      c.dispatch(pipelines_.rejection_distribution, &push, sizeof push, workgroups_for(texels));
    }
    c.barrier();
    c.timestamp(to_string(Pass::distribution));
    const PhiloxKey key = stream_key(request.seed, Stream::rejection);
    const PhiloxKey rounding_key = stream_key(request.seed, Stream::rounding);
    const gpu::RejectionPush push{scene_.triangles(), scene_.map_records(), scene_.texels(), scene_.area_cdf(),
                                  scene_.area_guide(), buffers_.samples.address(), buffers_.totals.address(), key[0], key[1], n_tri,
                                  device_max_tries(context_->device_name(), request.max_tries), 0, 0};
    const gpu::PlanPush plan{.target = request.target_count ? *request.target_count : -1.0,
                             .total_area = n_tri > 0 ? scene_.total_area() : 0.0,
                             .method = gpu::kPlanRejection,
                             .key0 = rounding_key[0],
                             .key1 = rounding_key[1]};
    record_realization(c, pipelines_.rejection, push, plan, capacity);
    if (capacity > 0) c.timestamp(to_string(Pass::realization));
    return submit(c, frame);
  }

  /// Realization sized on the device: the plan pass writes how many samples to realize (N, or
  /// none when N exceeds `capacity`) and the workgroup count of the one realization dispatch,
  /// whose subgroups then stride over the chunks of samples.
  template <class Push>
  void record_realization(Commands& c, const vk::ComputePipeline& pipeline, const Push& push, gpu::PlanPush plan,
                          std::uint64_t capacity) {
    constexpr VkDeviceSize kArgsBytes = 3 * sizeof(std::uint32_t);
    if (!buffers_.dispatch_args) buffers_.dispatch_args = context_->create_buffer(kArgsBytes);
    plan.totals = buffers_.totals.address();
    plan.indirect = buffers_.dispatch_args.address();
    plan.capacity = capacity;
    plan.max_workgroups = context_->capabilities().max_workgroup_count_x;
    c.dispatch(pipelines_.realization_plan, &plan, sizeof plan, 1);
    c.barrier();
    c.dispatch_indirect(pipeline, &push, sizeof push, buffers_.dispatch_args, 0);
    c.barrier();
  }

  /// What a frame computed on the device, to copy back.
  struct Outputs {
    bool counted = false;             ///< N-bar_T and D_T^max
    const Buffer* inverse = nullptr;  ///< N_T, the CDF and this inverse permutation (TRS)
  };

  /// Copies the frame's device outputs into `frame` (what was not computed is left empty, as by
  /// the CPU backend), timed as the "readback" pass on the host clock.
  void read_back(Frame& frame, Outputs outputs, bool with_samples) {
    const auto start = std::chrono::steady_clock::now();
    const std::size_t n = scene_.triangle_count();
    const std::size_t counted = outputs.counted ? n : 0, scanned = outputs.inverse ? n : 0;
    std::vector<float> expected(counted);
    if (counted > 0) context_->download(buffers_.expected, 0, expected.data(), n * sizeof(float));
    frame.expected_counts.resize(counted);
    for (std::size_t t = 0; t < counted; ++t) frame.expected_counts[t] = expected[t];
    frame.max_density.resize(counted);
    if (counted > 0) context_->download(buffers_.max_density, 0, frame.max_density.data(), n * sizeof(float));
    frame.counts.resize(scanned);
    frame.cdf.resize(scanned);
    frame.inverse_permutation.resize(scanned);
    if (scanned > 0) {
      context_->download(buffers_.counts, 0, frame.counts.data(), n * sizeof(std::uint64_t));
      context_->download(buffers_.cdf, 0, frame.cdf.data(), n * sizeof(std::uint64_t));
      context_->download(*outputs.inverse, 0, frame.inverse_permutation.data(), n * sizeof(std::uint32_t));
    }
    frame.samples.resize(with_samples ? frame.sample_count : 0);
    if (with_samples && frame.sample_count > 0)
      context_->download(buffers_.samples, 0, frame.samples.data(), frame.sample_count * sizeof(Sample));
    frame.passes.push_back(
        {Pass::readback, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count()});
  }

  std::unique_ptr<vk::Context> context_;
  vk::GpuScene scene_;
  vk::Pipelines pipelines_;
  vk::ReducingPipelines reducing_;                  ///< with subgroup reduction
  std::optional<vk::ReducingPipelines> unreduced_;  ///< without: the ablation, made on first use
  vk::OrderedScan scan_;
  vk::LookbackScan lookback_;
  FrameBuffers buffers_;
  std::array<std::optional<vk::CountingPipelines>, 3> counting_pipelines_;  ///< by overlap formula
  /// By overlap formula, then subgroup reduction (1: with).
  std::array<std::unique_ptr<vk::RasterPipeline>, 6> raster_;
  std::uint64_t last_count_ = 0;  ///< N of the last frame without a target: the next one's bound
  std::optional<CountingMode> counted_;   ///< the mode whose counts the buffers hold; none: to count
  std::optional<CountingMode> counting_;  ///< the mode the commands being recorded count by
  std::vector<bool> stale_;               ///< per map: replaced since the last count
  std::optional<FrsDevice> frs_;          ///< none: to build (first FRS frame, or a map replaced since)
};

}  // namespace

std::unique_ptr<Sampler> make_vulkan_sampler(const MeshView& mesh, std::span<const DensityMapView> maps,
                                             const VulkanOptions& options) {
  return std::make_unique<VulkanSampler>(mesh, maps, options);
}

}  // namespace lightsampler
