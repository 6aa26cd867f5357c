#pragma once
// Command-line pieces the tools share: named choices and number checks for CLI11.

#include <CLI/CLI.hpp>

#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "lightsampler/backend.h"
#include "lightsampler/sampler.h"

namespace trs {

/// The names of a choice map, for CLI::IsMember.
template <class T>
std::vector<std::string> names(const std::map<std::string, T>& choices) {
  std::vector<std::string> result;
  for (const auto& [name, value] : choices) result.push_back(name);
  return result;
}

inline const std::map<std::string, lightsampler::Backend> kBackends = {
    {"cpu", lightsampler::Backend::cpu},
    {"auto", lightsampler::Backend::automatic},
    {"vulkan", lightsampler::Backend::vulkan}};

inline const std::map<std::string, lightsampler::Method> kMethods = {
    {"trs", lightsampler::Method::trs},
    {"rs", lightsampler::Method::rejection},
    {"naive", lightsampler::Method::naive},
    {"frs", lightsampler::Method::frs}};

inline const std::map<std::string, lightsampler::Overlap> kOverlaps = {
    {"closed-form", lightsampler::Overlap::closed_form},
    {"clipping", lightsampler::Overlap::clipping},
    {"sdf", lightsampler::Overlap::sdf}};

inline const std::map<std::string, lightsampler::Counting> kCountings = {
    {"auto", lightsampler::Counting::automatic},
    {"raster", lightsampler::Counting::raster},
    {"compute", lightsampler::Counting::compute},
    {"per-triangle", lightsampler::Counting::per_triangle}};

/// Finite and non-negative; NaN fails every comparison, so it is rejected too.
inline const CLI::Validator kFiniteNonNegative(
    [](std::string& text) -> std::string {
      double value = 0;
      if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value) || value < 0) {
        return "must be a finite non-negative number: " + text;
      }
      return {};
    },
    "NUMBER >= 0");

/// --refine ACCEPTANCE|auto: the light sampler's adaptive subdivision (lightsampler/refinement.h);
/// `auto` is its cost model (lightsampler::auto_refinement), which the tool completes with the
/// samples of its frames. The default is what `refinement` holds.
inline CLI::Option* add_refine_option(CLI::App& app, lightsampler::Refinement& refinement) {
  const auto text = [](float value) {
    std::ostringstream out;
    out << value;
    return out.str();
  };
  const std::string current = refinement.cost_model ? "auto" : text(refinement.min_acceptance);
  return app
      .add_option_function<std::string>(
          "--refine",
          [&refinement](const std::string& value) {
            refinement = value == "auto" ? lightsampler::auto_refinement(refinement.frame_samples)
                                         : lightsampler::Refinement{.min_acceptance = std::stof(value)};
          },
          "split triangles (at most into 4^8 parts, not below " + text(refinement.min_texels) +
              " texels) where the sampler's expected acceptance on them is below this; auto: where the "
              "candidates a split saves on a frame's samples outweigh its parts' work each frame (below " +
              text(lightsampler::kAutoMinAcceptance) + "); 0: sample the mesh as it is")
      ->check(CLI::IsMember({"auto"}) | CLI::Range(0.0f, 1.0f))
      ->default_str(current);
}

}  // namespace trs
