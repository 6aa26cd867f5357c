#pragma once
// Command-line pieces the tools share: named choices and number checks for CLI11.

#include <CLI/CLI.hpp>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "lightsampler/backend.h"
#include "lightsampler/sampler.h"

namespace trs {

/// The names a table of EnumName lists (lightsampler/enum_names.h), for CLI::IsMember.
template <class Table>
std::vector<std::string> names(const Table& table) {
  std::vector<std::string> result;
  for (const auto& entry : table) result.push_back(entry.name);
  return result;
}

/// The value of a name that CLI::IsMember checked against names(table).
template <class Table>
lightsampler::NamedEnum<Table> named(const Table& table, const std::string& name) {
  return lightsampler::value_of(table, name).value();
}

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
