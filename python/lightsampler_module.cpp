// `import lightsampler`: the sampler for Python, numpy arrays in and out. A frame's outputs are
// read-only views of its own buffers (no copy); a view keeps its frame alive.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "lightsampler/lightsampler.h"

namespace py = pybind11;
namespace ls = lightsampler;

namespace {

/// `object` as a C-contiguous numpy array of T with `shape` (-1: any extent), or ValueError naming
/// `name` and what is wrong. Nothing is converted: a silent conversion would copy a large mesh, or
/// hide float64 positions that the sampler would round.
template <class T>
py::array require_array(const py::handle& object, const std::string& name, std::initializer_list<py::ssize_t> shape) {
  const auto shape_text = [](auto begin, auto end) {
    std::string text = "(";
    for (auto it = begin; it != end; ++it)
      text += (it == begin ? "" : ", ") + (*it < 0 ? std::string("any") : std::to_string(*it));
    return text + (end - begin == 1 ? ",)" : ")");
  };
  if (!py::isinstance<py::array>(object))
    throw py::value_error(name + ": expected a numpy array of " + std::string(py::str(py::dtype::of<T>())) + ", got " +
                          std::string(py::str(py::type::of(object).attr("__name__"))));
  const py::array a = py::reinterpret_borrow<py::array>(object);
  if (!py::array_t<T>::check_(a))
    throw py::value_error(name + ": expected dtype " + std::string(py::str(py::dtype::of<T>())) + ", got " +
                          std::string(py::str(a.dtype())) + " (convert with .astype(np." +
                          std::string(py::str(py::dtype::of<T>())) + "))");
  const std::vector<py::ssize_t> actual(a.shape(), a.shape() + a.ndim());
  bool fits = actual.size() == shape.size();
  for (std::size_t i = 0; fits && i < actual.size(); ++i) fits = shape.begin()[i] < 0 || shape.begin()[i] == actual[i];
  if (!fits)
    throw py::value_error(name + ": expected shape " + shape_text(shape.begin(), shape.end()) + ", got " +
                          shape_text(actual.begin(), actual.end()));
  if (!(a.flags() & py::array::c_style))
    throw py::value_error(name + ": the array is not C-contiguous (np.ascontiguousarray makes a copy that is)");
  return a;
}

/// The mesh as the sampler was given it, kept for positions(), uvs() and normals() of its frames:
/// a copy, so that changing the caller's arrays later cannot make a frame's points disagree with
/// its samples.
struct Mesh {
  std::vector<float> positions;
  std::vector<float> uvs;
  std::vector<std::uint32_t> indices;
  ls::MeshView view() const { return {positions, uvs, indices, {}}; }
};

/// Frames whose Python objects are gone, kept for the next generate(): a frame of 1e7 samples
/// is 120 MB, whose pages would otherwise be faulted in again every frame.
struct FramePool {
  static constexpr std::size_t kKept = 2;  // the frame in use and the one being generated
  std::mutex mutex;
  std::vector<std::unique_ptr<ls::Frame>> free;

  static std::shared_ptr<ls::Frame> take(const std::shared_ptr<FramePool>& pool) {
    std::unique_ptr<ls::Frame> frame;
    {
      std::lock_guard lock(pool->mutex);
      if (!pool->free.empty()) {
        frame = std::move(pool->free.back());
        pool->free.pop_back();
      }
    }
    if (!frame) frame = std::make_unique<ls::Frame>();
    std::weak_ptr<FramePool> owner = pool;
    return std::shared_ptr<ls::Frame>(frame.release(), [owner](ls::Frame* f) {
      std::unique_ptr<ls::Frame> done(f);
      if (const auto p = owner.lock()) {
        std::lock_guard lock(p->mutex);
        if (p->free.size() < kKept) p->free.push_back(std::move(done));
      }
    });
  }
};

struct PyFrame {
  std::shared_ptr<ls::Frame> frame;
  std::shared_ptr<const Mesh> mesh;
};

/// A read-only numpy view of `count` values of type T, `stride` bytes apart, owned by `owner`.
template <class T>
py::array view(const py::object& owner, const T* data, std::size_t count, std::size_t stride = sizeof(T)) {
  if (count == 0) return py::array_t<T>(0);
  py::array result(py::dtype::of<T>(), {py::ssize_t(count)}, {py::ssize_t(stride)}, data, owner);
  result.attr("setflags")(py::arg("write") = false);
  return result;
}

template <class T>
py::array buffer_view(const py::object& owner, const ls::Buffer<T>& buffer) {
  return view(owner, buffer.data(), buffer.size());
}

/// The value `table` (lightsampler/enum_names.h) names `name`.
template <class Table>
ls::NamedEnum<Table> choice(const Table& table, const std::string& name, const char* what) {
  if (const auto value = ls::value_of(table, name)) return *value;
  std::string known;
  for (const auto& entry : table) known += std::string(known.empty() ? "" : ", ") + entry.name;
  throw py::value_error(std::string(what) + ": unknown value '" + name + "' (one of " + known + ")");
}

ls::Addressing addressing(const std::string& name) { return choice(ls::kAddressingNames, name, "addressing"); }

ls::Backend backend(const std::string& name) { return choice(ls::kBackendNames, name, "backend"); }

/// refine: "auto" (the tools' default: the cost model for frames of `frame_samples` samples, the
/// acceptance rules below kAutoMinAcceptance without them), an acceptance in [0, 1], or 0 / None /
/// False for none.
ls::Refinement refinement(const py::object& refine, const py::object& frame_samples) {
  if (refine.is_none()) return {};
  if (py::isinstance<py::str>(refine)) {
    if (refine.cast<std::string>() != "auto")
      throw py::value_error("refine: 'auto', an acceptance in [0, 1], or None");
    const double samples = frame_samples.is_none() ? 0.0 : frame_samples.cast<double>();
    if (!(samples >= 0.0 && std::isfinite(samples)))
      throw py::value_error("frame_samples: a finite count >= 0, got " + std::to_string(samples));
    return ls::auto_refinement(samples);
  }
  if (!frame_samples.is_none()) throw py::value_error("frame_samples belongs to refine='auto'");
  const double value = refine.cast<double>();
  if (!(value >= 0.0 && value <= 1.0)) throw py::value_error("refine: an acceptance in [0, 1], got " + std::to_string(value));
  return {.min_acceptance = float(value)};
}

/// A density map from a float32 (H, W) array; the library copies its texels.
ls::DensityMapView density_map(const py::handle& array, const std::string& name, ls::Addressing address, float scale) {
  const py::array a = require_array<float>(array, name, {-1, -1});
  return {std::span<const float>(static_cast<const float*>(a.data()), std::size_t(a.size())),
          std::uint32_t(a.shape(1)), std::uint32_t(a.shape(0)), address, scale};
}

template <class T>
std::vector<T> copy_of(const py::array& a) {
  const T* data = static_cast<const T*>(a.data());
  return std::vector<T>(data, data + a.size());
}

class PySampler {
 public:
  PySampler(const py::handle& positions, const py::handle& uvs, const py::handle& indices, const py::list& maps,
            const py::object& triangle_maps, const std::string& address, const std::string& backend_name,
            const py::object& refine, const std::string& device, unsigned threads, const py::object& scales,
            const py::object& frame_samples)
      : addressing_(addressing(address)) {
    const py::array p = require_array<float>(positions, "positions", {-1, 3});
    const py::array t = require_array<float>(uvs, "uvs", {p.shape(0), 2});
    const py::array i = require_array<std::uint32_t>(indices, "indices", {-1, 3});
    auto mesh = std::make_shared<Mesh>(Mesh{copy_of<float>(p), copy_of<float>(t), copy_of<std::uint32_t>(i)});
    std::vector<std::uint32_t> per_triangle;
    if (!triangle_maps.is_none())
      per_triangle = copy_of<std::uint32_t>(require_array<std::uint32_t>(triangle_maps, "triangle_maps", {i.shape(0)}));
    std::vector<float> map_scales(maps.size(), 1.0f);
    if (!scales.is_none()) map_scales = scales.cast<std::vector<float>>();
    if (map_scales.size() != maps.size())
      throw py::value_error("scales: one per map (" + std::to_string(maps.size()) + "), got " + std::to_string(map_scales.size()));
    std::vector<ls::DensityMapView> views;
    for (std::size_t m = 0; m < maps.size(); ++m)
      views.push_back(density_map(maps[m], "maps[" + std::to_string(m) + "]", addressing_, map_scales[m]));

    ls::SamplerOptions options;
    options.backend = backend(backend_name);
    options.cpu.threads = threads;
    options.vulkan.device = device;
    options.refinement = refinement(refine, frame_samples);
    ls::MeshView view = mesh->view();
    view.triangle_maps = per_triangle;
    {
      py::gil_scoped_release release;
      sampler_ = ls::make_sampler(view, views, options);
    }
    mesh_ = std::move(mesh);
    scales_ = std::move(map_scales);
  }

  py::object generate(std::uint64_t seed, std::optional<double> target_count, const std::string& method,
                      const std::string& scan, const std::string& overlap, bool realize, std::uint32_t max_tries,
                      std::uint32_t exact_after, const std::string& counting, bool read_back, bool subgroup_reduction,
                      bool inverse_cdf) {
    ls::FrameRequest request;
    request.seed = seed;
    request.target_count = target_count;
    request.method = choice(ls::kMethodNames, method, "method");
    request.scan = choice(ls::kScanOrderNames, scan, "scan");
    request.overlap = choice(ls::kOverlapNames, overlap, "overlap");
    request.realize = realize;
    request.max_tries = max_tries;
    request.exact_after = exact_after;
    request.vulkan = {choice(ls::kRequestableCountings, counting, "counting"),
                      read_back, subgroup_reduction, inverse_cdf};
    PyFrame result{FramePool::take(pool_), mesh_};
    {
      // Other Python threads run meanwhile; calls into this sampler wait their turn.
      py::gil_scoped_release release;
      std::lock_guard lock(busy_);
      sampler_->generate(request, *result.frame);
    }
    return py::cast(std::move(result));
  }

  void update_map(std::size_t index, const py::handle& map) {
    if (index >= sampler_->map_count())
      throw py::index_error("update_map: map " + std::to_string(index) + " of " + std::to_string(sampler_->map_count()));
    const ls::DensityMapView view = density_map(map, "update_map", addressing_, scales_[index]);
    py::gil_scoped_release release;
    std::lock_guard lock(busy_);
    sampler_->update_map(index, view);
  }

  py::array density(const py::handle& triangles, const py::handle& b1, const py::handle& b2) const {
    const py::array t = require_array<std::uint32_t>(triangles, "triangles", {-1});
    const py::array x = require_array<float>(b1, "b1", {t.shape(0)});
    const py::array y = require_array<float>(b2, "b2", {t.shape(0)});
    const auto* tri = static_cast<const std::uint32_t*>(t.data());
    const auto* u = static_cast<const float*>(x.data());
    const auto* v = static_cast<const float*>(y.data());
    const std::uint64_t count = sampler_->triangle_count();
    for (py::ssize_t k = 0; k < t.shape(0); ++k)
      if (tri[k] >= count)
        throw py::value_error("triangles[" + std::to_string(k) + "] = " + std::to_string(tri[k]) + ": the mesh has " +
                              std::to_string(count) + " triangles");
    py::array_t<float> out(t.shape(0));
    float* d = out.mutable_data();
    py::gil_scoped_release release;
    std::lock_guard lock(busy_);
    for (py::ssize_t k = 0; k < t.shape(0); ++k) d[k] = sampler_->maps().density(tri[k], u[k], v[k]);
    return out;
  }

  const ls::Sampler& sampler() const { return *sampler_; }

 private:
  ls::Addressing addressing_;
  std::vector<float> scales_;
  std::shared_ptr<const Mesh> mesh_;
  std::unique_ptr<ls::Sampler> sampler_;
  std::shared_ptr<FramePool> pool_ = std::make_shared<FramePool>();
  mutable std::mutex busy_;  // one call into the sampler at a time
};

/// Per sample, the `components` values of `fn(mesh, sample)`, as an (N, components) float32 array.
template <int components, class Fn>
py::array per_sample(const PyFrame& f, Fn fn) {
  const ls::Buffer<ls::Sample>& samples = f.frame->samples;
  py::array_t<float> out({py::ssize_t(samples.size()), py::ssize_t(components)});
  float* o = out.mutable_data();
  const ls::MeshView mesh = f.mesh->view();
  py::gil_scoped_release release;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const auto value = fn(mesh, samples[i]);
    const float* v = &value.x;
    for (int c = 0; c < components; ++c) o[components * i + c] = v[c];
  }
  return out;
}

const PyFrame& frame_of(const py::object& self) { return self.cast<const PyFrame&>(); }

}  // namespace

PYBIND11_MODULE(lightsampler, m) {
  m.doc() =
      "Triangle Rejection Sampling: samples on a triangle mesh in proportion to density maps "
      "mapped onto it by UV, a fresh set every frame, on the CPU or a Vulkan GPU.";
  py::register_exception<ls::VulkanUnavailable>(m, "VulkanUnavailable", PyExc_RuntimeError);

  m.def("has_vulkan_backend", &ls::has_vulkan_backend, "Whether this build has the Vulkan backend.");
  m.def("vulkan_devices", &ls::vulkan_devices, "One line per Vulkan device: index, name, type, driver, what it lacks.");

  py::class_<PyFrame>(m, "Frame", "One frame's samples and per-triangle outputs; the arrays are read-only views of it.")
      .def_property_readonly("triangles", [](const py::object& self) {
        const auto& s = frame_of(self).frame->samples;
        return view(self, s.empty() ? nullptr : &s.data()->triangle, s.size(), sizeof(ls::Sample));
      }, "uint32 (N,): each sample's triangle")
      .def_property_readonly("b1", [](const py::object& self) {
        const auto& s = frame_of(self).frame->samples;
        return view(self, s.empty() ? nullptr : &s.data()->b1, s.size(), sizeof(ls::Sample));
      }, "float32 (N,): barycentric weight of the triangle's second vertex")
      .def_property_readonly("b2", [](const py::object& self) {
        const auto& s = frame_of(self).frame->samples;
        return view(self, s.empty() ? nullptr : &s.data()->b2, s.size(), sizeof(ls::Sample));
      }, "float32 (N,): barycentric weight of the third vertex")
      .def("positions", [](const PyFrame& f) { return per_sample<3>(f, ls::position); }, "float32 (N, 3) world positions")
      .def("uvs", [](const PyFrame& f) { return per_sample<2>(f, ls::uv); }, "float32 (N, 2) texture coordinates")
      .def("normals", [](const PyFrame& f) { return per_sample<3>(f, ls::geometric_normal); },
           "float32 (N, 3) unit geometric normals of the samples' triangles")
      .def_property_readonly("expected_counts", [](const py::object& self) { return buffer_view(self, frame_of(self).frame->expected_counts); },
                             "float64 per triangle: N-bar_T, the density's integral over it")
      .def_property_readonly("counts", [](const py::object& self) { return buffer_view(self, frame_of(self).frame->counts); },
                             "uint64 per triangle: N_T, samples drawn on it")
      .def_property_readonly("max_density", [](const py::object& self) { return buffer_view(self, frame_of(self).frame->max_density); },
                             "float32 per triangle: D_T^max")
      .def_property_readonly("cdf", [](const py::object& self) { return buffer_view(self, frame_of(self).frame->cdf); },
                             "uint64: inclusive CDF of the counts, in processing order")
      .def_property_readonly("inverse_permutation", [](const py::object& self) { return buffer_view(self, frame_of(self).frame->inverse_permutation); },
                             "uint32: processing index -> triangle")
      .def_property_readonly("sample_count", [](const PyFrame& f) { return f.frame->sample_count; })
      .def_property_readonly("expected_total", [](const PyFrame& f) { return f.frame->expected_total; },
                             "N-bar, the density's integral over the mesh")
      .def_property_readonly("candidates", [](const PyFrame& f) { return f.frame->candidates; })
      .def_property_readonly("acceptance", [](const PyFrame& f) {
        return f.frame->candidates > 0 ? double(f.frame->sample_count) / double(f.frame->candidates) : std::nan("");
      }, "samples per candidate tried")
      .def_property_readonly("exhausted", [](const PyFrame& f) { return f.frame->exhausted; },
                             "slots filled after max_tries rejections in a row (non-zero: a biased frame)")
      .def_property_readonly("exact_draws", [](const PyFrame& f) { return f.frame->exact_draws; })
      .def_property_readonly("setup_bytes", [](const PyFrame& f) { return f.frame->setup_bytes; })
      .def_property_readonly("method", [](const PyFrame& f) { return ls::to_string(f.frame->method); })
      .def_property_readonly("scan_used", [](const PyFrame& f) { return ls::to_string(f.frame->scan_used); })
      .def_property_readonly("counting_used", [](const PyFrame& f) -> py::object {
        if (!f.frame->counting_used) return py::none();
        return py::str(ls::to_string(*f.frame->counting_used));
      })
      .def_property_readonly("pass_ms", [](const PyFrame& f) {
        py::dict passes;
        for (const ls::PassTime& p : f.frame->passes) passes[ls::to_string(p.pass)] = p.ms;
        return passes;
      }, "milliseconds per pass, in the order they ran")
      .def_property_readonly("total_ms", [](const PyFrame& f) { return f.frame->total_ms; })
      .def("__len__", [](const PyFrame& f) { return f.frame->samples.size(); })
      .def("__repr__", [](const PyFrame& f) {
        return "<lightsampler.Frame " + std::to_string(f.frame->sample_count) + " samples, " +
               std::to_string(f.frame->total_ms) + " ms>";
      });

  py::class_<PySampler>(m, "Sampler",
                        "A sampler bound to one mesh and its density maps (samples per unit of world area, "
                        "row 0 at v = 0, nearest texel).")
      .def(py::init<const py::handle&, const py::handle&, const py::handle&, const py::list&, const py::object&,
                    const std::string&, const std::string&, const py::object&, const std::string&, unsigned,
                    const py::object&, const py::object&>(),
           py::arg("positions"), py::arg("uvs"), py::arg("indices"), py::arg("maps"), py::kw_only(),
           py::arg("triangle_maps") = py::none(), py::arg("addressing") = "wrap", py::arg("backend") = "auto",
           py::arg("refine") = "auto", py::arg("device") = "", py::arg("threads") = 0u,
           py::arg("scales") = py::none(), py::arg("frame_samples") = py::none(),
           "positions float32 (V, 3), uvs float32 (V, 2), indices uint32 (T, 3), maps a list of float32 (H, W); "
           "triangle_maps uint32 (T,) map per triangle (0xffffffff: none; None: all map 0); backend auto, cpu "
           "or vulkan; refine 'auto', an acceptance in [0, 1] or None; scales one factor per map; "
           "frame_samples, with refine 'auto', the samples a frame will draw, which its subdivision is "
           "weighed for (None: split below acceptance 0.85).")
      .def("generate", &PySampler::generate, py::kw_only(), py::arg("seed") = 0, py::arg("target_count") = py::none(),
           py::arg("method") = "trs", py::arg("scan") = "auto", py::arg("overlap") = "closed-form",
           py::arg("realize") = true, py::arg("max_tries") = ls::FrameRequest{}.max_tries,
           py::arg("exact_after") = ls::FrameRequest{}.exact_after, py::arg("counting") = "auto",
           py::arg("read_back") = true, py::arg("subgroup_reduction") = true, py::arg("inverse_cdf") = false,
           "Draws one frame (the GIL is released meanwhile). target_count None: N-bar samples.")
      .def("update_map", &PySampler::update_map, py::arg("index"), py::arg("density"),
           "Replaces density map `index`; the next frame samples it.")
      .def("density", &PySampler::density, py::arg("triangles"), py::arg("b1"), py::arg("b2"),
           "Density at points of the mesh, read exactly as the sampler reads it.")
      .def_property_readonly("backend", [](const PySampler& s) { return ls::to_string(s.sampler().backend()); })
      .def_property_readonly("device", [](const PySampler& s) { return s.sampler().device(); })
      .def_property_readonly("triangle_count", [](const PySampler& s) { return s.sampler().triangle_count(); })
      .def_property_readonly("map_count", [](const PySampler& s) { return s.sampler().map_count(); });
}
