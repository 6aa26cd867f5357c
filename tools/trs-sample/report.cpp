#include "report.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "lightsampler/refinement.h"

namespace trs {
namespace {

/// Accepted samples per candidate; undefined when nothing was tried.
std::optional<double> acceptance_rate(const lightsampler::Frame& frame) {
  if (frame.candidates == 0) return std::nullopt;
  return double(frame.sample_count) / double(frame.candidates);
}

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

// Worker threads of the CPU backend; none for the Vulkan backend.
unsigned threads(const RunReport& run) {
  return run.sampler.backend() == lightsampler::Backend::cpu ? lightsampler::worker_threads({run.options.threads}) : 0;
}

}  // namespace

nlohmann::ordered_json stats_json(const RunReport& run) {
  const lightsampler::Frame& frame = run.frame;
  nlohmann::ordered_json ms = nlohmann::ordered_json::object();
  for (const lightsampler::PassTime& pass : frame.passes) ms[lightsampler::to_string(pass.pass)] = pass.ms;
  ms["total"] = frame.total_ms;
  const auto rate = acceptance_rate(frame);

  nlohmann::ordered_json json;
  json["mesh"] = run.mesh.file.string();
  json["triangles"] = run.mesh.triangle_count();
  json["map"] = {{"file", run.map.file.string()},
                 {"width", run.map.width},
                 {"height", run.map.height},
                 {"encoding", run.map.srgb_decoded ? "srgb" : "linear"},
                 {"address", lightsampler::to_string(run.options.addressing)},
                 {"scale", run.options.density_scale}};
  json["method"] = lightsampler::to_string(frame.method);
  json["backend"] = lightsampler::to_string(run.sampler.backend());
  json["device"] = run.sampler.device();
  json["threads"] = threads(run);
  json["seed"] = run.options.seed;
  json["refine"] = run.options.refinement.min_acceptance;
  json["refine_rule"] = lightsampler::splits_by_cost(run.options.refinement) ? "cost" : "acceptance";
  json["target_count"] = run.options.target_count
                             ? nlohmann::ordered_json(*run.options.target_count)
                             : nlohmann::ordered_json(nullptr);
  json["scan"] = lightsampler::to_string(frame.scan_used);
  json["overlap"] = lightsampler::to_string(run.options.overlap);
  json["counting"] = frame.counting_used ? lightsampler::to_string(*frame.counting_used) : "";
  json["expected_total"] = std::isfinite(frame.expected_total)
                               ? nlohmann::ordered_json(frame.expected_total)
                               : nlohmann::ordered_json(nullptr);
  json["sample_count"] = frame.sample_count;
  json["candidates"] = frame.candidates;
  json["acceptance_rate"] = rate ? nlohmann::ordered_json(*rate) : nlohmann::ordered_json(nullptr);
  json["exhausted"] = frame.exhausted;
  json["exact_draws"] = frame.exact_draws;
  json["setup_bytes"] = frame.setup_bytes;
  const lightsampler::SamplerSetup setup = run.sampler.setup();
  json["construction"] = {{"ms", run.construction_ms}, {"subdivision_ms", setup.subdivision_ms}, {"parts", setup.parts}};
  json["ms"] = ms;
  json["out"] = run.options.out ? nlohmann::ordered_json(run.options.out->string())
                                : nlohmann::ordered_json(nullptr);
  return json;
}

void print_summary(std::ostream& out, const RunReport& run, std::optional<double> write_ms) {
  const lightsampler::Frame& frame = run.frame;
  out << "mesh         " << run.mesh.file.string() << ": " << run.mesh.triangle_count()
      << " triangles\n";
  out << "density map  " << run.map.file.string() << ": " << run.map.width << " x "
      << run.map.height << ", " << (run.map.srgb_decoded ? "sRGB" : "linear") << ", "
      << lightsampler::to_string(run.options.addressing) << ", scale " << run.options.density_scale << "\n";
  out << "sampler      " << lightsampler::to_string(frame.method) << " on " << lightsampler::to_string(run.sampler.backend())
      << " (" << run.sampler.device();
  if (threads(run) > 0) out << ", " << threads(run) << " threads";
  out << "), seed " << run.options.seed << ", scan " << lightsampler::to_string(frame.scan_used);
  if (frame.counting_used) out << ", counting " << lightsampler::to_string(*frame.counting_used);
  if (run.options.overlap != lightsampler::Overlap::closed_form)
    out << ", overlap " << lightsampler::to_string(run.options.overlap);
  out << "\n";
  out << "expected N̄   "
      << (std::isfinite(frame.expected_total) ? format("%.6g", frame.expected_total)
                                              : std::string("not computed"))
      << "\n";
  out << "samples N    " << frame.sample_count;
  if (run.options.target_count)
    out << " (target " << format("%.6g", *run.options.target_count) << ")";
  out << "\n";
  if (const auto rate = acceptance_rate(frame)) {
    out << "acceptance   " << format("%.2f", 100 * *rate) << " % (" << frame.candidates
        << " candidates)\n";
  }
  const lightsampler::SamplerSetup setup = run.sampler.setup();
  out << "construction " << format("%.3f", run.construction_ms) << " ms (subdivision "
      << format("%.3f", setup.subdivision_ms) << " ms, " << setup.parts << " parts)\n";
  out << "time         ";
  for (const lightsampler::PassTime& pass : frame.passes) {
    out << lightsampler::to_string(pass.pass) << " " << format("%.3f", pass.ms) << " ms, ";
  }
  out << "total " << format("%.3f", frame.total_ms) << " ms\n";
  if (frame.setup_bytes > 0)
    out << "set-up       " << format("%.3g", frame.setup_bytes / 1048576.0) << " MiB kept between frames\n";
  if (frame.total_ms > 0) {
    out << "rate         " << format("%.3g", frame.sample_count / (frame.total_ms * 1e-3))
        << " samples/s\n";
  }
  if (write_ms) {
    out << "output       " << run.options.out->string() << " (written in "
        << format("%.1f", *write_ms) << " ms)\n";
  }
}

}  // namespace trs
