#include "scene_io/color.h"
#include "report.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "scene_io/relmse.h"
#include "tracer/strategy_registry.h"
#include "lightsampler/backend.h"

namespace trs {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

namespace {

struct SamplerTimes {
  double mean_ms = 0.0;
  double median_ms = 0.0;
  double mean_lights = 0.0;
  double acceptance = 0.0;  ///< lights per candidate the rejection loops tried
  double records_ms = 0.0;  ///< mean time writing the light records
  std::uint64_t exhausted = 0;
  std::vector<lightsampler::PassTime> passes;  ///< mean per pass, in the sampler's order
};

void add_pass(std::vector<lightsampler::PassTime>& sums, const lightsampler::PassTime& pass) {
  const auto same = [&](const lightsampler::PassTime& p) { return p.pass == pass.pass; };
  if (auto it = std::find_if(sums.begin(), sums.end(), same); it != sums.end())
    it->ms += pass.ms;
  else
    sums.push_back(pass);
}

SamplerTimes sampler_times(const tracer::RenderResult& result) {
  SamplerTimes t;
  const auto& per_pass = result.light_passes;
  if (per_pass.empty()) return t;
  std::vector<double> ms;
  double lights = 0.0, candidates = 0.0;
  for (const tracer::LightPass& f : per_pass) {
    lights += double(f.lights);
    candidates += double(f.candidates);
    ms.push_back(f.sampler_ms);
    t.mean_ms += f.sampler_ms;
    t.records_ms += f.records_ms;
    t.exhausted += f.exhausted;
    for (const lightsampler::PassTime& p : f.passes) add_pass(t.passes, p);
  }
  for (lightsampler::PassTime& p : t.passes) p.ms /= double(per_pass.size());
  t.mean_ms /= double(per_pass.size());
  t.records_ms /= double(per_pass.size());
  t.acceptance = candidates > 0.0 ? lights / candidates : 0.0;
  t.mean_lights = lights / double(per_pass.size());
  std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
  t.median_ms = ms[ms.size() / 2];
  return t;
}

double per_second(double count, double seconds) { return seconds > 0.0 ? count / seconds : 0.0; }

/// restir's reuse per pass, milliseconds, mean; none for the other strategies.
std::optional<double> reuse_ms(const tracer::RenderResult& result) {
  if (result.reuse_ms.empty()) return std::nullopt;
  double sum = 0.0;
  for (double ms : result.reuse_ms) sum += ms;
  return sum / double(result.reuse_ms.size());
}

/// A pass's time, milliseconds, less its light sampler's, light records' and reuse's: tracing.
double tracing_ms(const tracer::RenderResult& result, const SamplerTimes& sampler) {
  if (result.passes == 0) return 0.0;
  return 1000.0 * result.render_seconds / result.passes - sampler.mean_ms - sampler.records_ms -
         reuse_ms(result).value_or(0.0);
}

/// The strategy's structure over the lights; null for strategies without one.
nlohmann::json light_structure(const tracer::StrategySetup& setup) {
  if (setup.bytes == 0) return nullptr;
  return {{"build_ms", setup.build_ms}, {"bytes", setup.bytes}};
}

/// The set-up's parts by name, in the order they run, milliseconds.
std::vector<std::pair<const char*, double>> setup_parts(const tracer::RenderResult& result) {
  const tracer::SetupTimes& t = result.setup;
  return {{"loading", t.loading_ms},
          {"texture_decoding", t.texture_decoding_ms},
          {"bvh", t.bvh_ms},
          {"emission", t.emission_ms},
          {"light_sampler", t.light_sampler_ms},
          {"subdivision", t.subdivision_ms},
          {"light_structure", t.light_structure_ms},
          {"pilot", t.pilot_ms},
          {"first_pass", 1000.0 * result.first_pass_seconds}};
}

/// What `auto` chose and why; null for a strategy named.
nlohmann::json strategy_choice_json(const tracer::StrategyOptions& asked, const tracer::StrategyChoice& choice) {
  if (asked.kind != tracer::kAutoStrategy) return nullptr;
  nlohmann::json pilot = nlohmann::json::array();
  for (const tracer::PilotMeasure& m : choice.pilot)
    pilot.push_back({{"strategy", m.strategy},
                     {"relative_variance", m.relative_variance},
                     {"relative_error", m.relative_error},
                     {"cost", m.cost},
                     {"efficiency", m.efficiency},
                     {"rays_per_path", m.rays_per_path},
                     {"light_samples_per_path", m.light_samples_per_path},
                     {"targets_per_path", m.targets_per_path},
                     {"sampler_tries_per_pass", m.sampler_tries_per_pass}});
  return {{"asked", asked.kind},
          {"used", choice.options.kind},
          {"texel_gain", choice.texel_gain},
          {"pilot", pilot},
          {"pilot_passes", choice.pilot_passes},
          {"pilot_pixels", choice.pilot_pixels},
          {"pilot_block_pixels", choice.pilot_block_pixels},
          {"most_efficient", choice.most_efficient},
          {"reason", choice.reason}};
}

nlohmann::json setup_json(const tracer::RenderResult& result) {
  nlohmann::json json = nlohmann::json::object();
  for (const auto& [name, ms] : setup_parts(result)) json[name] = ms;
  return json;
}

}  // namespace

ProgressBar::ProgressBar(bool enabled, std::optional<double> budget_seconds)
    : enabled_(enabled && isatty(STDERR_FILENO)), start_(std::chrono::steady_clock::now()), budget_(budget_seconds) {}

void ProgressBar::update(unsigned done, unsigned total) {
  if (!enabled_) return;
  constexpr int kWidth = 40;
  const double elapsed = seconds_since(start_);
  const double fraction = budget_ ? std::min(elapsed / *budget_, 1.0) : double(done) / total;
  const int filled = int(kWidth * fraction);
  const double remaining = budget_ ? std::max(*budget_ - elapsed, 0.0)
                                   : done > 0 ? elapsed * (total - done) / done : 0.0;
  const std::string passes = budget_ ? std::to_string(done) : std::to_string(done) + "/" + std::to_string(total);
  std::fprintf(stderr, "\r[%s%s] %s spp  %.1f s, %.1f s left ", std::string(std::size_t(filled), '#').c_str(),
               std::string(std::size_t(kWidth - filled), '.').c_str(), passes.c_str(), elapsed, remaining);
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressBar::finish() {
  if (drawn_) std::fputc('\n', stderr);
  drawn_ = false;
}

double relative_variance(const tracer::RenderResult& result) {
  const std::size_t pixels = result.luminance_variance.size();
  if (pixels == 0 || result.passes < 2) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < pixels; ++i) {
    const float* c = &result.rgb[3 * i];
    const double mean = trs::luminance<double>(c[0], c[1], c[2]);
    sum += result.luminance_variance[i] / (mean * mean + kRelmseGuard);
  }
  return sum / double(pixels);
}

namespace {

nlohmann::json update_json(const tracer::EmissionUpdate& u) {
  return {{"decode", u.decode_ms}, {"upload", u.upload_ms}, {"counting", u.counting_ms}, {"strategy", u.strategy_ms}};
}

/// A name of the preview's OpenColorIO transform as applied (defaults filled in); null without a
/// preview or without a config (the sRGB curve).
nlohmann::json display_setting(const std::optional<DisplayEncoder>& preview, std::string DisplayTransform::*name) {
  if (!preview || preview->transform().config.empty()) return nullptr;
  return preview->transform().*name;
}

/// This machine's name: the node a scheduler ran the render on.
std::string host_name() {
  char name[256] = {};
  return gethostname(name, sizeof name - 1) == 0 ? std::string(name) : std::string("unknown");
}

nlohmann::json current_stats_json(const RenderOptions& options, const tracer::RenderResult& result,
                                  double wall_seconds, const std::optional<SequenceFrame>& frame,
                                  const std::optional<DisplayEncoder>& preview) {
  const tracer::RenderSettings& r = options.render;
  const SamplerTimes sampler = sampler_times(result);
  nlohmann::json ms = nlohmann::json::array();
  for (const tracer::LightPass& f : result.light_passes) ms.push_back(f.sampler_ms);
  nlohmann::json stages = nlohmann::json::object();
  for (const lightsampler::PassTime& p : sampler.passes) stages[lightsampler::to_string(p.pass)] = p.ms;
  // The options that rendered: auto's choice, or the options as given.
  const tracer::StrategyOptions& used = result.strategy_choice.options;
  const bool tree = tracer::picks_by_tree(used);
  const bool ris = used.kind == "ris";
  return {
      {"settings",
       {{"scene", options.scene.string()},
        {"out", options.out.empty() ? nlohmann::json(nullptr)
                                    : nlohmann::json(output(options, options.out, frame ? frame->frame : 0).string())},
        {"frames", options.frames ? nlohmann::json(to_string(*options.frames)) : nlohmann::json()},
        {"fps", r.fps},
        {"width", r.width},
        {"height", r.height},
        // The most passes (null: none, a time budget alone) and the time budget (null: none).
        {"spp", options.time_seconds && r.spp == std::numeric_limits<unsigned>::max() ? nlohmann::json() : nlohmann::json(r.spp)},
        {"time", options.time_seconds ? nlohmann::json(*options.time_seconds) : nlohmann::json()},
        {"strategy", result.strategy},
        {"lights", r.strategy.lights},
        {"candidates", ris ? nlohmann::json(used.candidates) : nlohmann::json()},
        {"candidates_from", ris ? nlohmann::json(used.candidates_from) : nlohmann::json()},
        {"tree_importance", tree ? nlohmann::json(tracer::to_string(used.tree.importance)) : nlohmann::json()},
        {"tree_power", tree ? nlohmann::json(tracer::to_string(used.tree.power)) : nlohmann::json()},
        {"punctual", options.punctual},
        {"diffuse_materials", options.diffuse_materials},
        {"seed", r.seed},
        {"max_depth", r.max_depth},
        {"threads", r.threads},
        {"backend", lightsampler::to_string(r.sampler.backend)},
        {"refine", r.sampler.refinement.min_acceptance},
        {"refine_rule", r.sampler.refinement.cost_model ? "cost" : "acceptance"},
        {"ocio_config", display_setting(preview, &DisplayTransform::config)},
        {"ocio_colorspace", display_setting(preview, &DisplayTransform::colorspace)},
        {"display", display_setting(preview, &DisplayTransform::display)},
        {"view", display_setting(preview, &DisplayTransform::view)}}},
      {"passes", result.passes},
      {"strategy_choice", strategy_choice_json(r.strategy, result.strategy_choice)},
      {"interrupted", result.interrupted},
      {"frame", frame ? nlohmann::json(frame->frame) : nlohmann::json()},
      {"animation_seconds", frame ? nlohmann::json(frame->seconds) : nlohmann::json()},
      {"emission_update_ms", frame ? update_json(frame->update) : nlohmann::json()},
      {"light_sampler", result.light_device},
      {"host", {{"node", host_name()}, {"cpu", lightsampler::cpu_device()}}},
      {"light_structure", light_structure(result.light_structure)},
      {"wall_seconds", wall_seconds},
      {"setup_seconds", result.setup_seconds},
      {"setup_ms", setup_json(result)},
      {"light_sampler_parts", result.setup.sampler_parts},
      {"punctual_lights", result.punctual_lights},
      {"render_seconds", result.render_seconds},
      {"paths", result.paths},
      {"rays", result.rays},
      {"light_samples", result.light_samples},
      {"paths_per_second", per_second(double(result.paths), result.render_seconds)},
      {"rays_per_second", per_second(double(result.rays), result.render_seconds)},
      {"sampler_ms_per_pass", sampler.mean_ms},
      {"sampler_ms_median", sampler.median_ms},
      {"sampler_ms", ms},
      {"sampler_stages_ms", stages},
      {"light_records_ms_per_pass", sampler.records_ms},
      {"reuse_ms_per_pass", reuse_ms(result) ? nlohmann::json(*reuse_ms(result)) : nlohmann::json()},
      {"reuse_candidates", result.reuse_candidates},
      {"reuse_target_evaluations", result.reuse_targets},
      {"tracing_ms_per_pass", tracing_ms(result, sampler)},
      {"lights_per_pass", sampler.mean_lights},
      {"acceptance_rate", sampler.acceptance},
      {"exhausted_lights", sampler.exhausted},
      {"invalid_paths", result.invalid_paths},
      {"relative_variance", relative_variance(result)},
  };
}

/// Keys by which earlier versions, counting passes as "frames", wrote what is now a pass's: written
/// beside the new ones (the same values) for the scripts that read them.
constexpr std::pair<const char*, const char*> kEarlierKeys[] = {
    {"frames", "passes"},
    {"sampler_ms_per_frame", "sampler_ms_per_pass"},
    {"light_records_ms_per_frame", "light_records_ms_per_pass"},
    {"lights_per_frame", "lights_per_pass"},
    {"sampler_passes_ms", "sampler_stages_ms"},
};

nlohmann::json with_earlier_keys(nlohmann::json stats) {
  for (const auto& [earlier, key] : kEarlierKeys) stats[earlier] = stats[key];
  stats["setup_ms"]["first_frame"] = stats["setup_ms"]["first_pass"];
  return stats;
}

}  // namespace

nlohmann::json stats_json(const RenderOptions& options, const tracer::RenderResult& result,
                          double wall_seconds, const std::optional<SequenceFrame>& frame,
                          const std::optional<DisplayEncoder>& preview) {
  return with_earlier_keys(current_stats_json(options, result, wall_seconds, frame, preview));
}

void print_frame(std::ostream& out, const std::filesystem::path& image, const tracer::RenderResult& result,
                 const SequenceFrame& frame, double wall_seconds) {
  const tracer::EmissionUpdate& u = frame.update;
  char line[512];
  std::snprintf(line, sizeof line,
                "frame %lld: %s, %u spp, %.2f s; emission %.1f ms (decode %.1f, upload %.1f, counting %.1f, "
                "strategy %.1f), light sampler %.2f ms per spp\n",
                static_cast<long long>(frame.frame), image.string().c_str(), result.passes, wall_seconds,
                u.decode_ms + u.upload_ms + u.counting_ms + u.strategy_ms, u.decode_ms, u.upload_ms, u.counting_ms,
                u.strategy_ms, sampler_times(result).mean_ms);
  out << line;
}

void print_summary(std::ostream& out, const std::filesystem::path& image, const tracer::RenderResult& result,
                   double wall_seconds) {
  const SamplerTimes sampler = sampler_times(result);
  char line[256];
  std::snprintf(line, sizeof line, "%s: %u x %u, %u spp%s, strategy %s\n",
                image.string().c_str(), result.width, result.height, result.passes,
                result.interrupted ? " (interrupted)" : "", result.strategy.c_str());
  out << line;
  std::snprintf(line, sizeof line,
                "  %.2f s (set-up %.2f s, render %.2f s), %.3g paths/s, %.3g rays/s\n",
                wall_seconds, result.setup_seconds, result.render_seconds,
                per_second(double(result.paths), result.render_seconds),
                per_second(double(result.rays), result.render_seconds));
  out << line;
  const auto parts = setup_parts(result);
  const auto largest = std::max_element(parts.begin(), parts.end(),
                                        [](const auto& a, const auto& b) { return a.second < b.second; });
  std::snprintf(line, sizeof line, "  set-up's largest part: %s %.2f s\n", largest->first, largest->second / 1000.0);
  out << line;
  if (!result.strategy_choice.reason.empty()) out << "  strategy auto: " << result.strategy_choice.reason << "\n";
  if (result.punctual_lights > 0) out << "  punctual lights: " << result.punctual_lights << ", beside the emission\n";
  if (result.light_structure.bytes > 0) {
    std::snprintf(line, sizeof line, "  light structure: built in %.2f ms, %.3g MiB\n",
                  result.light_structure.build_ms, double(result.light_structure.bytes) / (1 << 20));
    out << line;
  }
  if (!result.light_device.empty()) {
    std::snprintf(line, sizeof line,
                  "  light sampler (%s): %.3g lights and %.2f ms per pass (median %.2f ms)\n",
                  result.light_device.c_str(), sampler.mean_lights, sampler.mean_ms,
                  sampler.median_ms);
    out << line;
    if (!sampler.passes.empty()) {
      out << "    per stage:";
      for (std::size_t i = 0; i < sampler.passes.size(); ++i) {
        std::snprintf(line, sizeof line, "%s %s %.2f ms", i ? "," : "",
                      lightsampler::to_string(sampler.passes[i].pass), sampler.passes[i].ms);
        out << line;
      }
      std::snprintf(line, sizeof line, "; %.3g of the candidates accepted\n", sampler.acceptance);
      out << line;
    }
    std::snprintf(line, sizeof line, "    light records: %.2f ms per pass\n", sampler.records_ms);
    out << line;
  }
  if (const std::optional<double> reuse = reuse_ms(result)) {
    std::snprintf(line, sizeof line, "  reuse (restir's reservoirs): %.2f ms per pass, tracing %.2f ms\n", *reuse,
                  tracing_ms(result, sampler));
    out << line;
  }
  std::snprintf(line, sizeof line,
                "  relative variance per sample: %.4g (a self-estimate: it underestimates heavy tails; "
                "measure noise against a reference)\n",
                relative_variance(result));
  out << line;
}

}  // namespace trs
