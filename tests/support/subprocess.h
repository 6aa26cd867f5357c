#pragma once
// Running a command-line tool as a subprocess, for end-to-end tests: posix_spawn with stdout and
// stderr redirected to files, and a GoogleTest fixture that gives each test a fresh temporary
// directory (removed afterwards) for its inputs and outputs.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <utility>
#include <vector>

extern char** environ;

namespace trs_test {

namespace fs = std::filesystem;

struct RunResult {
  int status = -1;  ///< exit status, or -signal if the tool was killed by one
  std::string out;
  std::string err;
};

inline std::string read_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_file(const fs::path& file, const std::string& bytes) {
  std::ofstream out(file, std::ios::binary);
  out << bytes;
  ASSERT_TRUE(out.good()) << file;
}

/// Starts `argv` (argv[0] the executable's path) with stdout and stderr written to the given
/// files, and SIGINT, SIGTERM and SIGHUP at their default actions, unblocked, whatever the test
/// runner does with them (nohup ignores SIGHUP).
/// Returns the process id, or -1 (a test failure recorded) if it cannot be started.
inline pid_t spawn_process(const std::vector<std::string>& argv_strings, const fs::path& out_log,
                           const fs::path& err_log) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out_log.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_log.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t defaults, empty;
  sigemptyset(&defaults);
  for (const int signal : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&defaults, signal);
  sigemptyset(&empty);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setsigmask(&attributes, &empty);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);

  std::vector<std::string> strings = argv_strings;
  std::vector<char*> argv;
  for (auto& a : strings) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, argv[0], &actions, &attributes, argv.data(), environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  EXPECT_EQ(spawned, 0) << argv[0] << ": " << std::strerror(spawned);
  return spawned == 0 ? pid : -1;
}

/// Waits for a process started by spawn_process: its exit status, or -signal.
inline int wait_process(pid_t pid) {
  int status = 0;
  pid_t waited;
  do waited = ::waitpid(pid, &status, 0);
  while (waited < 0 && errno == EINTR);
  EXPECT_EQ(waited, pid) << std::strerror(errno);
  if (waited != pid) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

/// A test with a fresh temporary directory, and a tool to run in it.
class ToolTest : public ::testing::Test {
 protected:
  /// `common_args` follow the arguments of every run.
  explicit ToolTest(fs::path executable, std::vector<std::string> common_args = {})
      : executable_(std::move(executable)), common_args_(std::move(common_args)) {}

  void SetUp() override {
    char pattern[] = "/tmp/trs-cli-test-XXXXXX";
    ASSERT_NE(::mkdtemp(pattern), nullptr) << std::strerror(errno);
    root_ = pattern;
    fs::create_directory(work());
  }

  void TearDown() override {
    if (!root_.empty()) fs::remove_all(root_);
  }

  /// Where inputs and outputs live; the tool's stdout and stderr are captured outside it, so
  /// that a listing of it shows exactly what the tool left behind.
  fs::path work() const { return root_ / "work"; }
  fs::path file(const std::string& name) const { return work() / name; }

  fs::path write_text(const std::string& name, const std::string& text) {
    write_file(file(name), text);
    return file(name);
  }

  std::set<std::string> listing() const {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(work())) names.insert(entry.path().filename());
    return names;
  }

  /// Starts the tool on `args` without waiting; finish() waits and collects its output.
  pid_t start(const std::vector<std::string>& args) const {
    std::vector<std::string> argv = {executable_.string()};
    argv.insert(argv.end(), args.begin(), args.end());
    argv.insert(argv.end(), common_args_.begin(), common_args_.end());
    return spawn_process(argv, root_ / "stdout", root_ / "stderr");
  }

  RunResult finish(pid_t pid) const {
    RunResult result;
    if (pid < 0) return result;
    result.status = wait_process(pid);
    result.out = read_file(root_ / "stdout");
    result.err = read_file(root_ / "stderr");
    return result;
  }

  RunResult run(const std::vector<std::string>& args) const { return finish(start(args)); }

  /// A failed run: status 1, "TOOL: error: " and the offending file on stderr, nothing left
  /// behind in work().
  void expect_failure_naming(const std::vector<std::string>& args, const fs::path& culprit) {
    const std::set<std::string> before = listing();
    const RunResult result = run(args);
    EXPECT_EQ(result.status, 1) << result.err;
    EXPECT_NE(result.err.find(executable_.filename().string() + ": error: " + culprit.string()),
              std::string::npos)
        << result.err;
    EXPECT_EQ(listing(), before);
  }

  fs::path root_;

 private:
  fs::path executable_;
  std::vector<std::string> common_args_;
};

}  // namespace trs_test
