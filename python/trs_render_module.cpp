// `import trs_render`: the path tracer as a function. Keywords are trs-render's long options
// (max_depth=4 is --max-depth 4), parsed and checked by the command line's own parser, so that a
// render from Python is the one trs-render makes with the same settings, bit for bit.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "scene_io/relmse.h"
#include "lightsampler/backend.h"
#include "options.h"
#include "report.h"
#include "run.h"
#include "scene_io/file_error.h"
#include "slurm.h"
#include "scene_io/image_output.h"
#include "tracer/gltf_scene.h"
#include "tracer/renderer.h"
#include "tracer/strategy_registry.h"

namespace py = pybind11;

namespace {

using Clock = std::chrono::steady_clock;

/// trs-render's arguments for `scene` and keyword `options`: spp=16 is `--spp 16`, a flag given
/// True is the flag alone, False or None leaves the option out.
std::vector<std::string> arguments(const py::object& scene, const py::kwargs& options) {
  const py::object fspath = py::module_::import("os").attr("fspath");
  std::vector<std::string> args = {"trs-render", py::str(fspath(scene))};
  for (const auto& [key, value] : options) {
    std::string name = "--" + py::str(key).cast<std::string>();
    for (char& c : name) c = c == '_' ? '-' : c;
    if (value.is_none() || (py::isinstance<py::bool_>(value) && !value.cast<bool>())) continue;
    args.push_back(name);
    if (py::isinstance<py::bool_>(value)) continue;
    if (py::isinstance<py::float_>(value))
      args.push_back(py::repr(value));  // the shortest text that reads back as the same double
    else if (py::hasattr(value, "__fspath__"))
      args.push_back(py::str(fspath(value)));
    else
      args.push_back(py::str(value));
  }
  return args;
}

/// The options, or ValueError with the parser's message.
trs::RenderOptions parse(const py::object& scene, const py::kwargs& options) {
  auto parsed = trs::parse_render_arguments(arguments(scene, options), false);
  if (auto* o = std::get_if<trs::RenderOptions>(&parsed)) return std::move(*o);
  const trs::NoRender& stop = std::get<trs::NoRender>(parsed);
  throw py::value_error(stop.error.empty() ? "the options ask for nothing to render" : stop.error);
}

/// `values` (moved, not copied) as a numpy array of `shape`.
py::array_t<float> array_of(std::vector<float>&& values, std::vector<py::ssize_t> shape) {
  auto* owned = new std::vector<float>(std::move(values));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<float>*>(p); });
  return py::array_t<float>(shape, owned->data(), owner);
}

py::dict dict_of(const std::string& json) {
  return py::module_::import("json").attr("loads")(json);
}

/// A note of a run as a Python warning: a warning's sentence alone, what an interrupted run saved
/// as trs-render prints it.
void warn(const trs::RunNote& note) {
  const std::string text = note.kind == trs::RunNote::Kind::warning ? note.text : trs::note_line(note);
  PyErr_WarnEx(PyExc_RuntimeWarning, text.c_str(), 1);
}

/// Ctrl-C in Python while a render runs without the GIL: checked after each pass; the run then
/// stops as trs-render does on SIGINT, and KeyboardInterrupt is raised once it has saved.
class InterruptCheck {
 public:
  void operator()() {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) {
      error_.emplace();
      cancel_ = true;
    }
  }
  const std::atomic<bool>& cancel() const { return cancel_; }
  void raise_if_interrupted() {
    if (error_) throw std::move(*error_);
  }

 private:
  std::atomic<bool> cancel_{false};
  std::optional<py::error_already_set> error_;
};

struct Image {
  std::int64_t frame;
  tracer::RenderResult result;
  std::string stats;
};

py::tuple image_and_stats(Image& image) {
  tracer::RenderResult& r = image.result;
  return py::make_tuple(array_of(std::move(r.rgb), {py::ssize_t(r.height), py::ssize_t(r.width), 3}), dict_of(image.stats));
}

/// trs-render --submit slurm: the job id; with wait=True, RuntimeError naming the frames of the
/// tasks that failed. `program` is the trs-render the nodes run, by default the one on the PATH.
std::string submit(const py::object& scene, const py::kwargs& kwargs) {
  py::kwargs options;
  py::object program = py::none();
  for (const auto& [key, value] : kwargs) {
    if (py::str(key).cast<std::string>() == "program")
      program = py::reinterpret_borrow<py::object>(value);
    else
      options[key] = value;
  }
  if (!options.contains("submit")) options["submit"] = "slurm";
  if (program.is_none()) program = py::module_::import("shutil").attr("which")("trs-render");
  if (program.is_none())
    throw py::value_error("submit() needs trs-render for the nodes to run: put it on the PATH or give program=");
  const std::filesystem::path executable =
      std::filesystem::absolute(py::str(py::module_::import("os").attr("fspath")(program)).cast<std::string>());
  const trs::RenderOptions parsed = parse(scene, options);
  if (!parsed.submit) throw py::value_error("submit() hands an animation to a scheduler: give frames='A:B'");
  trs::SlurmOutcome outcome;
  {
    py::gil_scoped_release released;  // --wait blocks until the array ends
    outcome = trs::submit_to_slurm(parsed, executable, std::cerr);
  }
  if (!outcome.missing.empty()) {
    std::string frames;
    for (const trs::FrameRange& range : outcome.missing) frames += (frames.empty() ? "" : ", ") + trs::to_string(range);
    throw std::runtime_error("Slurm job " + outcome.job.id + " left frames " + frames + " unwritten (logs: " +
                             outcome.job.log_pattern.string() + ")");
  }
  return outcome.job.id;
}

py::object render(const py::object& scene, const py::kwargs& kwargs) {
  const auto start = Clock::now();
  const trs::RenderOptions options = parse(scene, kwargs);
  if (options.plan_chunk) throw py::value_error("--plan prints trs-render commands: run trs-render for it");
  if (options.submit) throw py::value_error("--submit hands the frames to a scheduler: call submit() for it");
  std::vector<Image> images;
  std::ostringstream out;
  std::vector<trs::RunNote> notes;  // kept until the GIL is back
  InterruptCheck interrupt;
  {
    py::gil_scoped_release release;
    trs::render(options, start,
                {interrupt.cancel(), out, [&](const trs::RunNote& note) { notes.push_back(note); },
                 [&](std::int64_t frame, const tracer::RenderResult& result, const nlohmann::json& stats) {
                   images.push_back({frame, result, stats.dump()});
                 },
                 std::ref(interrupt)});
  }
  for (const trs::RunNote& note : notes) warn(note);
  interrupt.raise_if_interrupted();
  if (!options.frames) return image_and_stats(images.at(0));
  py::list sequence;
  for (Image& image : images) sequence.append(image_and_stats(image));
  return sequence;
}

/// Keywords of the preview's display transform, which preview() takes too.
const char* const kDisplayOptions[] = {"ocio_config", "ocio_colorspace", "display", "view"};

/// Keywords that describe a run of trs-render rather than a renderer, besides kDisplayOptions.
const char* const kRunOptions[] = {"out", "stats", "preview", "variance", "emitter_mask", "frames",
                                   "resume", "save_partial", "plan", "chunk", "time", "exposure"};

/// A renderer driven a pass at a time, for notebooks that show the image converge.
class PyRenderer {
 public:
  PyRenderer(const py::object& scene, std::int64_t frame, const py::kwargs& kwargs)
      : options_(parse(scene, refuse_run_options(kwargs))), frame_(frame) {
    py::gil_scoped_release release;
    scene_ = std::make_unique<tracer::Scene>(trs::load_scene(options_));
    renderer_.emplace(trs::make_renderer(*scene_, options_, frame));
  }

  /// Renders `count` passes more (settings' spp by default) and returns the image so far.
  py::array_t<float> render_passes(std::optional<unsigned> count) {
    InterruptCheck interrupt;
    {
      py::gil_scoped_release release;
      last_ = renderer_->render_more(count.value_or(options_.render.spp),
                                     [&](unsigned, unsigned) { interrupt(); }, interrupt.cancel());
    }
    interrupt.raise_if_interrupted();
    return image();
  }

  void set_frame(std::int64_t frame) {
    py::gil_scoped_release release;
    renderer_->set_frame(frame);
    frame_ = frame;
    last_ = {};
  }

  py::array_t<float> image() const { return copy(last_.rgb, 3); }
  py::array_t<float> variance() const { return copy(last_.luminance_variance, 1); }
  py::array_t<float> emitter_fraction() const { return copy(last_.emitter_fraction, 1); }
  unsigned passes() const { return last_.passes; }
  std::int64_t frame() const { return frame_; }

  py::dict stats() const {
    trs::SequenceFrame sequence{frame_, tracer::animation_seconds(frame_, options_.render.fps), {}};
    return dict_of(trs::stats_json(options_, last_, last_.setup_seconds + last_.render_seconds, sequence).dump());
  }

 private:
  static const py::kwargs& refuse_run_options(const py::kwargs& kwargs) {
    for (const auto& names : {std::span<const char* const>(kRunOptions), std::span<const char* const>(kDisplayOptions)})
      for (const char* name : names)
        if (kwargs.contains(name))
          throw py::value_error(std::string(name) + " belongs to trs_render.render(); a Renderer renders a pass at a time");
    return kwargs;
  }

  /// Before the first pass: black, as an image of no samples is.
  py::array_t<float> copy(const std::vector<float>& values, py::ssize_t channels) const {
    const auto h = py::ssize_t(options_.render.height), w = py::ssize_t(options_.render.width);
    std::vector<float> data = values.empty() ? std::vector<float>(std::size_t(h * w * channels), 0.0f) : values;
    if (channels == 1) return array_of(std::move(data), {h, w});
    return array_of(std::move(data), {h, w, channels});
  }

  trs::RenderOptions options_;
  std::unique_ptr<tracer::Scene> scene_;
  std::optional<tracer::Renderer> renderer_;
  tracer::RenderResult last_;
  std::int64_t frame_;
};

py::array_t<float> emitter_mask(const py::object& scene, py::kwargs kwargs) {
  // Only the camera rays' first hits count: no light is sampled, no bounce traced.
  for (const auto& [key, value] : std::initializer_list<std::pair<const char*, py::object>>{
           {"strategy", py::str("uniform")}, {"max_depth", py::int_(0)}})
    if (!kwargs.contains(key)) kwargs[key] = value;
  PyRenderer renderer(scene, 0, kwargs);
  renderer.render_passes(std::nullopt);
  return renderer.emitter_fraction();
}

/// The display transform that kDisplayOptions keywords ask for, parsed and checked by
/// trs-render's parser ($OCIO included); its warning a Python warning.
trs::DisplayEncoder display_encoder(const py::kwargs& kwargs) {
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    if (std::find(std::begin(kDisplayOptions), std::end(kDisplayOptions), name) == std::end(kDisplayOptions))
      throw py::type_error("preview() got an unexpected keyword argument '" + name + "'");
  }
  const trs::RenderOptions options = parse(py::str("image"), kwargs);  // the parser wants a scene; none is read
  return trs::display_encoder(options, warn);
}

/// An image as trs-render's --preview shows it: 8-bit display values.
py::array_t<std::uint8_t> preview(const py::array_t<float, py::array::c_style | py::array::forcecast>& image,
                                  float exposure, const py::kwargs& kwargs) {
  if (image.ndim() != 3 || image.shape(2) != 3)
    throw py::value_error("image: expected shape (height, width, 3)");
  const trs::DisplayEncoder display = display_encoder(kwargs);
  std::vector<unsigned char> bytes;
  {
    py::gil_scoped_release release;
    bytes = trs::preview_rgb8(image.data(), std::size_t(image.size()), exposure, display);
  }
  py::array_t<std::uint8_t> result({image.shape(0), image.shape(1), py::ssize_t(3)});
  std::copy(bytes.begin(), bytes.end(), result.mutable_data());
  return result;
}

}  // namespace

PYBIND11_MODULE(trs_render, m) {
  m.doc() =
      "The trs-render path tracer as a function: glTF scenes lit by their emissive textures, "
      "images as numpy arrays. Keywords are trs-render's long options, with _ for -.";
  // The lightsampler module's class, so that `except lightsampler.VulkanUnavailable` catches a
  // render's too; held as long as the process runs.
  static const py::handle vulkan_unavailable =
      py::object(py::module_::import("lightsampler").attr("VulkanUnavailable")).release();
  m.attr("VulkanUnavailable") = vulkan_unavailable;
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const trs::FileError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const lightsampler::VulkanUnavailable& e) {
      PyErr_SetString(vulkan_unavailable.ptr(), e.what());
    }
  });

  py::list strategies;
  for (const std::string& name : tracer::strategy_names()) strategies.append(name);
  // The names --strategy (strategy=) takes, built in; render(plugin=...) adds a plugin's.
  m.attr("STRATEGIES") = py::tuple(strategies);
  m.attr("RELMSE_GUARD") = trs::kRelmseGuard;  // relMSE's guard, as trs-imgdiff prints it

  m.def("render", &render, py::arg("scene"),
        "render(scene, **options) -> (image, stats): image float32 (height, width, 3) linear radiance, "
        "stats the dict that --stats writes. With frames='A:B', a list of (image, stats), one per frame. "
        "Outputs named by out, preview, stats, variance or emitter_mask are written as trs-render writes them.");
  m.def("submit", &submit, py::arg("scene"),
        "submit(scene, frames='A:B', out=PATTERN, **options) -> job id: trs-render --submit slurm, the "
        "frames as one Slurm job array (chunk=, sbatch='ARGS', wait=True as trs-render's options: sbatch's "
        "words split by quotes and backslashes, nothing expanded or run); program= names the trs-render the "
        "nodes run (default: the one on the PATH). A bad option, sbatch= text or path is a ValueError.");
  m.def("emitter_mask", &emitter_mask, py::arg("scene"),
        "emitter_mask(scene, **options) -> float32 (height, width): each pixel's fraction of camera "
        "samples whose first hit is an emitter (spp of them, default 16).");

  m.def("preview", &preview, py::arg("image"), py::arg("exposure") = 0.0f,
        "preview(image, exposure=0, **options) -> uint8 (height, width, 3): linear RGB as --preview shows it "
        "(scaled by 2^exposure, the display transform, 8 bits); options: ocio_config, ocio_colorspace, "
        "display, view, as trs-render's.");

  py::class_<PyRenderer>(m, "Renderer", "A scene and settings, rendered a pass (one sample per pixel) at a time.")
      .def(py::init<const py::object&, std::int64_t, const py::kwargs&>(), py::arg("scene"), py::kw_only(),
           py::arg("frame") = 0,
           "Renderer(scene, frame=0, **options): trs-render's options, less those of a run (out, stats, "
           "preview, variance, emitter_mask, frames, resume, save_partial, plan, chunk, time, exposure, "
           "ocio_config, ocio_colorspace, display, view).")
      .def("render_pass", [](PyRenderer& r) { return r.render_passes(1); },
           "Renders one pass more; returns the mean image so far, float32 (height, width, 3).")
      .def("render_passes", &PyRenderer::render_passes, py::arg("count") = py::none(),
           "Renders `count` passes more (spp by default); returns the mean image so far.")
      // The names of earlier versions, kept for scripts written against them.
      .def("render_frame", [](PyRenderer& r) { return r.render_passes(1); }, "render_pass(), by its earlier name.")
      .def("render_frames", &PyRenderer::render_passes, py::arg("count") = py::none(),
           "render_passes(count), by its earlier name.")
      .def("set_frame", &PyRenderer::set_frame, py::arg("frame"),
           "Moves to animation frame `frame`; the next passes start its image afresh.")
      .def_property_readonly("image", &PyRenderer::image, "the mean image so far, float32 (height, width, 3)")
      .def_property_readonly("variance", &PyRenderer::variance,
                             "float32 (height, width): per-sample luminance variance of each pixel")
      .def_property_readonly("emitter_fraction", &PyRenderer::emitter_fraction,
                             "float32 (height, width): fraction of camera samples whose first hit is an emitter")
      .def_property_readonly("passes", &PyRenderer::passes, "passes (samples per pixel) so far")
      .def_property_readonly("frames", &PyRenderer::passes, "`passes`, by its earlier name")
      .def_property_readonly("frame", &PyRenderer::frame, "the animation frame")
      .def("stats", &PyRenderer::stats, "the stats JSON of the passes so far, as a dict");
}
