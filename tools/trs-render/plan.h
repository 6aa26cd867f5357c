#pragma once
// A sequence's frames as separate commands, a chunk of frames each: what --plan prints and what
// --submit hands to a scheduler.

#include <cstdint>
#include <string>
#include <vector>

#include "options.h"

namespace trs {

/// A shell word: as it is when it is safe, in single quotes otherwise.
std::string shell_quoted(const std::string& word);

/// One command of a plan: the frames it renders and its command line, quoted for a shell.
struct PlannedCommand {
  FrameRange frames;
  std::string command;
};

/// The command line once per `chunk` frames of options.frames, run by `program`, with that
/// chunk's --frames and without the options that plan or submit (--plan, --submit, --sbatch,
/// --wait, --chunk); `resume` adds --resume where the command line lacks it.
std::vector<PlannedCommand> plan_commands(const RenderOptions& options, const std::string& program,
                                          std::int64_t chunk, bool resume);

}  // namespace trs
