#include "slurm.h"

#include <stdio.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <optional>
#include <stdexcept>

#include "plan.h"

namespace trs {
namespace {

namespace fs = std::filesystem;

/// The batch script: the array's task index picks its command.
std::string batch_script(const std::vector<PlannedCommand>& commands, const fs::path& log_pattern) {
  std::string script = "#!/bin/sh\n";
  script += "#SBATCH --job-name=trs-render\n";
  script += "#SBATCH --array=0-" + std::to_string(commands.size() - 1) + "\n";
  script += "#SBATCH --output=" + log_pattern.string() + "\n";
  script += "case \"$SLURM_ARRAY_TASK_ID\" in\n";
  for (std::size_t i = 0; i < commands.size(); ++i)
    script += "  " + std::to_string(i) + ") exec " + commands[i].command + " ;;\n";
  script += "esac\necho \"trs-render: no task $SLURM_ARRAY_TASK_ID in this job array\" >&2\nexit 1\n";
  return script;
}

/// A file that is removed when this goes out of scope.
struct TemporaryFile {
  fs::path path;
  explicit TemporaryFile(const fs::path& directory, const std::string& contents) {
    std::string name = (directory / ".trs-render-submit-XXXXXX").string();
    const int fd = mkstemp(name.data());
    if (fd < 0) throw std::runtime_error("cannot create a batch script in " + directory.string());
    close(fd);
    path = name;
    std::ofstream(path) << contents;
  }
  ~TemporaryFile() {
    std::error_code ignored;
    fs::remove(path, ignored);
  }
};

/// A command's standard output, line by line, through the shell.
class Pipe {
 public:
  explicit Pipe(const std::string& command) : file_(popen(command.c_str(), "r")) {
    if (!file_) throw std::runtime_error("cannot run " + command);
  }
  ~Pipe() {
    if (file_) pclose(file_);
  }
  Pipe(const Pipe&) = delete;
  Pipe& operator=(const Pipe&) = delete;

  /// The next line, without its newline; none at the end.
  std::optional<std::string> line() {
    std::string text;
    for (int c; (c = fgetc(file_)) != EOF;) {
      if (c == '\n') return text;
      text.push_back(char(c));
    }
    return text.empty() ? std::nullopt : std::optional(text);
  }
  /// Waits for the command: its exit status, 128 + the signal that killed it.
  int close() {
    const int status = pclose(file_);
    file_ = nullptr;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }

 private:
  FILE* file_;
};

/// Whether every output of animation frame `frame` is written.
bool frame_written(const RenderOptions& options, std::int64_t frame) {
  for (const fs::path& pattern : outputs(options))
    if (!fs::exists(output(options, pattern, frame))) return false;
  return true;
}

}  // namespace

SlurmOutcome submit_to_slurm(const RenderOptions& options, const fs::path& program, std::ostream& progress) {
  const RenderOptions::Submission& submission = *options.submit;
  const std::vector<PlannedCommand> commands = plan_commands(options, program.string(), submission.chunk, true);
  const fs::path folder = fs::absolute(options.out).parent_path();
  SlurmOutcome outcome;
  outcome.job.tasks = commands.size();
  outcome.job.log_pattern = folder / "trs-render-%A_%a.log";
  fs::create_directories(folder);
  const TemporaryFile script(folder, batch_script(commands, outcome.job.log_pattern));
  const std::string command = "sbatch --parsable" + std::string(submission.wait ? " --wait" : "") + " " +
                              submission.sbatch + " " + shell_quoted(script.path.string());
  Pipe sbatch(command);
  if (std::optional<std::string> line = sbatch.line()) {
    outcome.job.id = line->substr(0, line->find(';'));  // "id;cluster"
    progress << "trs-render: Slurm job " << outcome.job.id << ": frames " << to_string(*options.frames) << " in "
             << commands.size() << (commands.size() == 1 ? " task" : " tasks") << ", outputs " << options.out.string()
             << ", logs " << outcome.job.log_pattern.string() << std::endl;
  }
  while (sbatch.line()) {
  }
  outcome.sbatch_status = sbatch.close();
  if (outcome.job.id.empty()) {
    throw std::runtime_error("sbatch submitted nothing (status " + std::to_string(outcome.sbatch_status) +
                             (outcome.sbatch_status == 127 ? ": no sbatch on the PATH, is Slurm installed?" : "") + ")");
  }
  if (!submission.wait) return outcome;
  for (std::size_t task = 0; task < commands.size(); ++task) {
    const FrameRange& frames = commands[task].frames;
    for (std::int64_t f = frames.first; f <= frames.last; ++f) {
      if (frame_written(options, f)) continue;
      outcome.missing.push_back(frames);
      outcome.missing_tasks.push_back(task);
      break;
    }
  }
  return outcome;
}

}  // namespace trs
