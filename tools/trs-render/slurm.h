#pragma once
// A sequence handed to Slurm as one job array (--submit slurm): a task per chunk of frames, each
// the command --plan prints with --resume, so that a task Slurm runs again (requeued, preempted)
// skips the frames already written.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "options.h"

namespace trs {

/// A submitted job array.
struct SlurmJob {
  std::string id;
  std::size_t tasks = 0;
  /// Each task's log: `log_pattern` with %A the job id and %a the task index (sbatch's --output).
  std::filesystem::path log_pattern;
};

/// What a --wait found: the frames of the failed tasks whose outputs are not all written.
struct SlurmOutcome {
  SlurmJob job;
  int sbatch_status = 0;  ///< sbatch --wait's: non-zero when a task failed
  std::vector<FrameRange> missing;  ///< per task, in task order
  std::vector<std::size_t> missing_tasks;
};

/// Submits options.frames (options.submit set) through the `sbatch` on the PATH, run without a
/// shell: its options and options.submit->sbatch's words as its arguments, a batch script that
/// holds the task commands alone, each run by `program` (an absolute path: the nodes run it).
/// Tells `progress` the job id and where its outputs and logs go as soon as Slurm has it; with
/// options.submit->wait, then waits for the array to end. Throws std::runtime_error when sbatch
/// fails or cannot be run, or the output folder cannot be a log pattern of Slurm's.
SlurmOutcome submit_to_slurm(const RenderOptions& options, const std::filesystem::path& program,
                             std::ostream& progress);

}  // namespace trs
