#include "plan.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string_view>

#include "shell_words.h"

namespace trs {
namespace {

/// The options a planned command leaves out, and whether each takes a value.
struct Dropped {
  std::string_view name;
  bool value;
};
constexpr std::array kDropped = {Dropped{"--plan", false}, Dropped{"--wait", false}, Dropped{"--chunk", true},
                                 Dropped{"--frames", true}, Dropped{"--submit", true}, Dropped{"--sbatch", true}};

}  // namespace

std::vector<PlannedCommand> plan_commands(const RenderOptions& options, const std::string& program,
                                          std::int64_t chunk, bool resume) {
  if (const std::optional<std::string> control = control_character(program))
    throw std::invalid_argument("the program's path " + printable(program) + " holds " + *control +
                                ", which a command line cannot hold safely");
  std::string kept;
  bool has_resume = false;
  for (std::size_t i = 1; i < options.arguments.size(); ++i) {
    const std::string& a = options.arguments[i];
    const auto dropped = std::find_if(kDropped.begin(), kDropped.end(), [&](const Dropped& d) {
      return a == d.name || (d.value && a.starts_with(std::string(d.name) + "="));
    });
    if (dropped != kDropped.end()) {
      if (dropped->value && a == dropped->name) ++i;  // and its value
      continue;
    }
    has_resume = has_resume || a == "--resume";
    kept.append(" ").append(shell_quoted(a));
  }
  if (resume && !has_resume) kept += " --resume";
  std::vector<PlannedCommand> commands;
  const FrameRange frames = *options.frames;
  for (std::int64_t first = frames.first; first <= frames.last; first += chunk) {
    const FrameRange part{first, std::min(frames.last, first + chunk - 1)};
    commands.push_back({part, shell_quoted(program) + kept + " --frames " + to_string(part)});
  }
  return commands;
}

}  // namespace trs
