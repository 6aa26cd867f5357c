#include "slurm.h"

#include <fcntl.h>
#include <spawn.h>
#include <stdio.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <optional>
#include <stdexcept>

#include "plan.h"
#include "shell_words.h"

extern char** environ;

namespace trs {
namespace {

namespace fs = std::filesystem;

/// The batch script: the array's task index picks its command. It holds nothing else: sbatch's
/// options go on its command line, where no shell reads them.
std::string batch_script(const std::vector<PlannedCommand>& commands) {
  std::string script = "#!/bin/sh\ncase \"$SLURM_ARRAY_TASK_ID\" in\n";
  for (std::size_t i = 0; i < commands.size(); ++i)
    script += "  " + std::to_string(i) + ") exec " + commands[i].command + " ;;\n";
  script += "esac\necho \"trs-render: no task $SLURM_ARRAY_TASK_ID in this job array\" >&2\nexit 1\n";
  return script;
}

/// `path` as sbatch's --output pattern: Slurm reads % as a replacement symbol (%% is one %), and a
/// backslash anywhere as "no replacements", which would send every task's log to one file.
std::string output_pattern(const fs::path& folder, const std::string& name) {
  const std::string text = folder.string();
  if (text.find('\\') != std::string::npos)
    throw std::runtime_error("--out: the folder " + printable(text) +
                             " holds a backslash, which makes Slurm write every task's log to one file "
                             "(its --output patterns take none)");
  std::string escaped;
  for (const char c : text) escaped += c == '%' ? "%%" : std::string(1, c);
  return escaped + "/" + name;
}

/// sbatch's command line but the batch script: its own options, then the user's (--sbatch, which
/// come later and so win). Throws where the output folder cannot be a log pattern.
std::vector<std::string> sbatch_arguments(const RenderOptions::Submission& submission, std::size_t tasks,
                                          const fs::path& folder) {
  std::vector<std::string> words = {"sbatch", "--parsable"};
  if (submission.wait) words.push_back("--wait");
  words.push_back("--job-name=trs-render");
  words.push_back("--array=0-" + std::to_string(tasks - 1));
  words.push_back("--output=" + output_pattern(folder, "trs-render-%A_%a.log"));
  words.insert(words.end(), submission.sbatch.begin(), submission.sbatch.end());
  return words;
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

/// A program run from the PATH with `arguments` (the first its name), no shell between: its
/// standard output read line by line through a pipe, its standard error this process's.
class Program {
 public:
  explicit Program(const std::vector<std::string>& arguments) {
    int ends[2];
    if (pipe2(ends, O_CLOEXEC) != 0) throw std::runtime_error("cannot run " + arguments[0] + ": " + std::strerror(errno));
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, ends[1], STDOUT_FILENO);
    std::vector<char*> argv;
    for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const int spawned = posix_spawnp(&pid_, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    close(ends[1]);
    if (spawned != 0) {
      close(ends[0]);
      throw std::runtime_error("cannot run " + arguments[0] + ": " +
                               (spawned == ENOENT ? "no " + arguments[0] + " on the PATH, is Slurm installed?"
                                                  : std::string(std::strerror(spawned))));
    }
    output_ = fdopen(ends[0], "r");
    if (!output_) close(ends[0]);  // line() then reads nothing
  }
  ~Program() {
    if (pid_ > 0) wait();
  }
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  /// The next line, without its newline; none at the end.
  std::optional<std::string> line() {
    std::string text;
    for (int c; output_ && (c = fgetc(output_)) != EOF;) {
      if (c == '\n') return text;
      text.push_back(char(c));
    }
    return text.empty() ? std::nullopt : std::optional(text);
  }
  /// Waits for the program: its exit status, 128 + the signal that killed it.
  int wait() {
    if (output_) fclose(output_);
    output_ = nullptr;
    int status = 0;
    while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }

 private:
  pid_t pid_ = -1;
  FILE* output_ = nullptr;
};

}  // namespace

SlurmOutcome submit_to_slurm(const RenderOptions& options, const fs::path& program, std::ostream& progress) {
  const RenderOptions::Submission& submission = *options.submit;
  const std::vector<PlannedCommand> commands = plan_commands(options, program.string(), submission.chunk, true);
  const fs::path folder = fs::absolute(options.out).parent_path();
  SlurmOutcome outcome;
  outcome.job.tasks = commands.size();
  outcome.job.log_pattern = folder / "trs-render-%A_%a.log";
  std::vector<std::string> arguments = sbatch_arguments(submission, commands.size(), folder);
  fs::create_directories(folder);
  const TemporaryFile script(folder, batch_script(commands));
  arguments.push_back(script.path.string());
  Program sbatch(arguments);
  if (std::optional<std::string> line = sbatch.line()) {
    outcome.job.id = line->substr(0, line->find(';'));  // "id;cluster"
    progress << "trs-render: Slurm job " << outcome.job.id << ": frames " << to_string(*options.frames) << " in "
             << commands.size() << (commands.size() == 1 ? " task" : " tasks") << ", outputs " << options.out.string()
             << ", logs " << outcome.job.log_pattern.string() << std::endl;
  }
  while (sbatch.line()) {
  }
  outcome.sbatch_status = sbatch.wait();
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
