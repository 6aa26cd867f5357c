#pragma once
// A sequence's frames as separate commands, a chunk of frames each: what --plan prints and what
// --submit hands to a scheduler.

#include <cstdint>
#include <string>
#include <vector>

#include "options.h"

namespace trs {

/// One command of a plan: the frames it renders and its command line, quoted for a shell.
struct PlannedCommand {
  FrameRange frames;
  std::string command;
};

/// The command line once per `chunk` frames of options.frames, run by `program`, with that
/// chunk's --frames and without the options that plan or submit (--plan, --submit, --sbatch,
/// --wait, --chunk); `resume` adds --resume where the command line lacks it. The options' words
/// hold no control character (the parser refuses them with --plan and --submit); a `program`
/// that does is a std::invalid_argument.
std::vector<PlannedCommand> plan_commands(const RenderOptions& options, const std::string& program,
                                          std::int64_t chunk, bool resume);

}  // namespace trs
